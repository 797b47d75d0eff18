"""Shared counterexamples: Hypothesis's Redis example database against a real redis-server.

The server is started by the fixture on a free loopback port with an
append-only file fsynced on every write, in a temporary directory; it is
killed (SIGKILL) and restarted in the middle of a run, and nothing saved is
lost.  .ci/run installs redis-server; without the binary these tests skip,
except under CI (``CI`` set), where they fail.
"""

import os
import shutil
import signal
import socket
import subprocess
import sys
import time

import pytest
import redis
from hypothesis import HealthCheck, Phase, settings
from hypothesis.extra.redis import RedisExampleDatabase

from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.profiles import DATABASE_ENV, database_from, profile, use_database
from ddg_oracle.properties.runner import FAILED, run_property
from tests.planted_bugs import ChiIgnoresBoundary

REDIS_SERVER = shutil.which("redis-server")
MISSING = "redis-server is not installed (.ci/run installs it: apt-get install redis-server)"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class RedisServer:
    """A redis-server child process with persistence in ``directory``."""

    def __init__(self, directory):
        self.directory = directory
        self.port = _free_port()
        self.url = f"redis://127.0.0.1:{self.port}/0"
        self.proc = None

    def start(self) -> None:
        self.proc = subprocess.Popen(
            [REDIS_SERVER, "--port", str(self.port), "--bind", "127.0.0.1", "--dir",
             str(self.directory), "--appendonly", "yes", "--appendfsync", "always",
             "--save", "", "--logfile", str(self.directory / "redis.log")],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        client = redis.Redis(host="127.0.0.1", port=self.port, socket_connect_timeout=1)
        deadline = time.monotonic() + 20
        while True:
            try:
                if client.ping():
                    break
            except redis.ConnectionError:
                if self.proc.poll() is not None or time.monotonic() > deadline:
                    log = (self.directory / "redis.log").read_text(errors="replace")[-2000:]
                    raise RuntimeError(f"redis-server did not start on port {self.port}:\n{log}")
                time.sleep(0.05)
        client.close()

    def kill(self) -> None:
        """SIGKILL: no shutdown save, only what the append-only file already holds survives."""
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait(10)

    def restart(self) -> None:
        self.kill()
        self.start()

    def keys(self) -> list[bytes]:
        client = redis.Redis(host="127.0.0.1", port=self.port)
        try:
            return client.keys(b"hypothesis-example:*")
        finally:
            client.close()


@pytest.fixture
def redis_server(tmp_path):
    if REDIS_SERVER is None:
        if os.environ.get("CI"):        # CI must run these: .ci/run installs the server
            pytest.fail(MISSING)
        pytest.skip(MISSING)
    server = RedisServer(tmp_path)
    server.start()
    yield server
    if server.proc.poll() is None:
        server.proc.terminate()
        server.proc.wait(10)


class RecordingChiBug(ChiIgnoresBoundary):
    """The planted chi bug, recording each face list it is asked about;
    optionally restarting the Redis server at its ``restart_at``-th call."""

    def __init__(self, server=None, restart_at=None):
        self.seen, self.server, self.restart_at = [], server, restart_at

    def euler_characteristic(self, V, F):
        self.seen.append([list(map(int, f)) for f in F])
        if self.server is not None and len(self.seen) == self.restart_at:
            self.server.restart()        # mid-run, inside a test call
        return super().euler_characteristic(V, F)


def _settings(db, **kw):
    return settings(max_examples=40, deadline=None, derandomize=False, database=db,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large], **kw)


def test_failure_survives_a_server_restart_mid_run_and_is_replayed_first(redis_server):
    db = database_from(redis_server.url)       # the DDG_HYPOTHESIS_DATABASE path
    assert isinstance(db.inner, RedisExampleDatabase)   # inside the tolerant wrapper
    prop = PROPERTIES["D1.6"]

    # The server is killed and restarted during the first call: Hypothesis has
    # read the database but found nothing to save yet, so every save of the
    # failure (found, then shrunk) goes through the reconnecting client.
    impl = RecordingChiBug(redis_server, restart_at=1)
    first = run_property(prop, impl, _settings(db))
    assert first.status == FAILED and len(impl.seen) > 1
    failing = impl.seen[-1]                                     # Hypothesis replays the shrunk one last
    assert first.example.triangulation.n_faces == len(failing)
    assert redis_server.keys(), "nothing was saved in Redis"

    redis_server.restart()                     # again, between runs, with the same client

    # reuse phase only: whatever fails now can only come from the database
    replay = RecordingChiBug()
    second = run_property(prop, replay, _settings(db, phases=[Phase.reuse]))
    assert second.status == FAILED
    assert replay.seen[0] == failing                            # replayed first
    # a full run also starts with it
    again = RecordingChiBug()
    assert run_property(prop, again, _settings(db)).status == FAILED
    assert again.seen[0] == failing


def test_use_database_switches_every_profile_and_ci_trades_derandomize_for_it(redis_server):
    try:
        db = use_database(redis_server.url)
        assert isinstance(db.inner, RedisExampleDatabase)
        for name in ("default", "ci", "thorough"):
            assert profile(name).database == db
        assert not profile("ci").derandomize
        use_database("none")
        assert profile("default").database is None
        assert profile("ci").derandomize
    finally:
        use_database(os.environ.get(DATABASE_ENV))     # as this session started


def test_environment_variable_selects_redis_in_a_fresh_process(redis_server):
    code = ("from ddg_oracle.properties.profiles import profile\n"
            "p = profile('ci')\n"
            "print(type(profile('default').database.inner).__name__, p.derandomize)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, DATABASE_ENV: redis_server.url}, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["RedisExampleDatabase", "False"]
