"""The fault suite (issue 45, item 7): ``python -m benchmarks faults [--quick] --no-write``.

Re-runs the hostile cases the tests hold (tests/test_containment.py, test_interruptions.py,
test_faults.py, test_codec.py, test_hostile.py, test_cluster.py, tests/hostile.py,
tests/misbehaving.py) and a few more of the same kinds, as one standalone report: per area
(containment, signals, safe formats and --resume, bounded readers, error paths and exit
codes, the example database) how many cases, how many handled, how many badly.

Every case is a real subprocess (``ddg-oracle ...``, else the reproducing snippet or pytest
with the plugin) in a session of its own, with the environment variable ``DDG_FAULT_MARKER``
set to a value of its own, and a verdict rule:

- the exit code the case expects (2 for bad usage or input, 128 + N after signal N, ...);
- an expected exit 2 is one line on stderr, ``ddg-oracle: error: ...`` naming the problem
  (besides the progress lines ``[k/n ...]`` of the tasks that ran);
- the words the case expects on stdout / stderr;
- no traceback, no "internal error", no warning of multiprocessing's resource tracker;
- done within the case's seconds (killed at twice that, at least 5 s more: a hang);
- no stray process: none left in the run's session, none anywhere with its marker
  (waited for up to 3 s after the run ended; strays are then killed);
- for a file that must not be read: the peak RSS of the run (``_PEAK`` of
  tests/test_hostile.py), and the case's own check (a marker file a crafted pickle would
  create does not exist, a report is complete, ...).

``run(mode)`` runs every case (``--quick``: the cases marked quick), prints the table and
writes docs/faults.md; :func:`run_cases` runs a list of cases and returns their outcomes
(tests/test_benchmarks_faults.py).
"""

from __future__ import annotations

import base64
import json
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import uuid
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from ddg_oracle.application.containment import alive

from .common import ROOT, Mode, machine, say

DOC = ROOT / "docs" / "faults.md"
MARKER_ENV = "DDG_FAULT_MARKER"
VECTORS = ROOT / "vectors"
MISBEHAVING_DRIVER = ROOT / "tests" / "misbehaving_driver.py"     # one misbehaviour per MODE
PROGRESS = re.compile(r"\s*\[\d+/\d+ ")      # "[2/4 0 s] X1.4 reference: passed", on stderr
AREAS = ("containment", "signals", "safe formats, --resume", "bounded readers",
         "error paths, exit codes", "example database")


# --- cases and outcomes --------------------------------------------------------------------------

@dataclass
class Ctx:
    """What a case's callables see: its own directory, the shared kit, its marker."""
    dir: Path
    kit: Path
    marker: str
    state: dict = field(default_factory=dict)
    closers: list = field(default_factory=list)

    def ddg(self, *args) -> list[str]:
        return [ddg_exe(), *map(str, args)]


@dataclass
class Case:
    area: str
    name: str
    argv: Callable[[Ctx], list[str]]
    rc: int | tuple[int, ...] | None = 2
    err: tuple[str, ...] = ()
    out: tuple[str, ...] = ()
    one_line: bool | None = None              # default: when the expected exit is 2
    seconds: float = 10.0
    env: Callable[[Ctx], dict] | None = None
    setup: Callable[[Ctx], None] | None = None
    during: Callable[[subprocess.Popen, Ctx], None] | None = None
    check: Callable[[Ctx, "Outcome"], str | None] | None = None
    peak_mb: float | None = None              # run under the peak wrapper: at most this
    traceback_ok: bool = False                # a Python API call's expected exception
    quick: bool = False
    needs: tuple[str, ...] = ()               # modules ("distributed") or "unshare"


@dataclass
class Outcome:
    case: Case
    command: str
    rc: int | None = None
    out: str = ""
    err: str = ""
    seconds: float = 0.0
    strays: list = field(default_factory=list)
    peak_mb: float | None = None
    problems: list = field(default_factory=list)
    skipped: str | None = None

    @property
    def handled(self) -> bool:
        return self.skipped is None and not self.problems


def ddg_exe() -> str:
    exe = Path(sys.executable).with_name("ddg-oracle")
    return str(exe) if exe.exists() else shutil.which("ddg-oracle") or "ddg-oracle"


# --- the kit: implementations, drivers and files shared by the cases ----------------------------

HELPER = "ddg-fault-helper"        # in the command line of every helper a library starts

SPAWNING = f"""\
import subprocess, sys, time
from ddg_oracle.oracles.exact_reference import ReferenceImplementation
SLEEP = [sys.executable, "-c", "import time; time.sleep(300)", "{HELPER}"]
class Spawns(ReferenceImplementation):
    name = "spawns"
    def euler_characteristic(self, V, F):
        subprocess.Popen(SLEEP)                        # a helper process per call
        return super().euler_characteristic(V, F)
class SpawnsAndFails(Spawns):
    name = "spawns-and-fails"
    def euler_characteristic(self, V, F):
        return super().euler_characteristic(V, F) + 1
class SpawnsSlowly(Spawns):
    name = "spawns-slowly"
    def cotan_laplacian(self, V, F):                   # a helper and a second per Laplacian
        subprocess.Popen(SLEEP)
        time.sleep(1.0)
        return super().cotan_laplacian(V, F)
"""

DRIVER = f"""\
import json, subprocess, sys, time
child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)", "{HELPER}"])
for line in sys.stdin:
    r = json.loads(line)
    if r["method"] == "hello":
        print(json.dumps({{"methods": ["euler_characteristic"]}}), flush=True)
    else:
        time.sleep(300)                                 # hangs on the first request
"""

MODULES = {
    "spawning.py": SPAWNING,
    "driver.py": DRIVER,
    "aborts_at_import.py": "import os\nos.abort()\n",
    "hangs_at_import.py": "import time\ntime.sleep(300)\n",
    # python ulimit_v.py BYTES PROGRAM ARGS: PROGRAM under an address-space limit (ulimit -v)
    "ulimit_v.py": "import os, resource, sys\nn = int(sys.argv[1])\n"
                   "resource.setrlimit(resource.RLIMIT_AS, (n, n))\n"
                   "os.execv(sys.argv[2], sys.argv[2:])\n",
    # tests/test_faults.py sets cluster.SCHEDULER_TIMEOUT to 2 s; the same in a subprocess
    "short_scheduler_timeout.py": "import sys\nfrom ddg_oracle.application import cluster\n"
                                  "cluster.SCHEDULER_TIMEOUT = 2.0\n"
                                  "from ddg_oracle.application.cli import main\nsys.exit(main(sys.argv[1:]))\n",
    "raises_at_init.py": "class Impl:\n    def __init__(self):\n"
                         "        raise RuntimeError('no licence for this machine')\n",
}


def make_kit(directory) -> Path:
    """Write the kit (implementations, a driver, an icosahedron) into ``directory``."""
    from ddg_oracle.application.meshfiles import write_obj
    from ddg_oracle.reference import surfaces
    kit = Path(directory)
    kit.mkdir(parents=True, exist_ok=True)
    for name, text in MODULES.items():
        (kit / name).write_text(text)
    write_obj(kit / "ico.obj", *surfaces.icosahedron().to_arrays())
    (kit / "cases").mkdir(exist_ok=True)
    return kit


# --- processes -------------------------------------------------------------------------------


def marked(marker: str) -> list[int]:
    """Live processes whose environment holds ``DDG_FAULT_MARKER=marker``."""
    needle = f"{MARKER_ENV}={marker}".encode() + b"\0"
    out = []
    for entry in os.listdir("/proc"):
        if entry.isdigit() and int(entry) != os.getpid():
            try:
                with open(f"/proc/{entry}/environ", "rb") as fh:
                    if needle in fh.read() + b"\0" and alive(int(entry)):
                        out.append(int(entry))
            except OSError:
                continue
    return out


def _helpers(marker: str) -> list[int]:
    """The marked processes that are a library's or a driver's helpers."""
    out = []
    for pid in marked(marker):
        try:
            if HELPER.encode() in Path(f"/proc/{pid}/cmdline").read_bytes():
                out.append(pid)
        except OSError:
            continue
    return out


def strays(marker: str, session: int) -> list[int]:
    """Processes a run left: alive in its session (tests/test_interruptions.py's ``_group``:
    the run started a session, so its group is its session's first group) or carrying its
    marker."""
    from tests.test_interruptions import _group
    return sorted(set(_group(session)) | set(marked(marker)))


def _kill(pids) -> None:
    """SIGKILL each of ``pids`` (a run's strays), then wait up to 2 s for them to be gone."""
    for pid in pids:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    _wait_for(lambda: not any(alive(p) for p in pids), None, 2.0)


def _wait_for(what: Callable[[], object], proc, seconds: float):
    """Poll ``what()`` until truthy (returned) or ``seconds`` pass or ``proc`` ends (None)."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        got = what()
        if got:
            return got
        if proc is not None and proc.poll() is not None:
            return None
        time.sleep(0.05)
    return None


# --- running a case -------------------------------------------------------------------------------

def _have(need: str) -> str | None:
    """None if ``need`` is there, else why not."""
    if need == "unshare":
        if shutil.which("unshare") is None:
            return "no unshare(1)"
        ok = subprocess.run(["unshare", "-rm", "true"], capture_output=True).returncode == 0
        return None if ok else "unshare -rm is not permitted here"
    import importlib.util
    return None if importlib.util.find_spec(need) else f"{need} is not installed"


def _display(argv, ctx: Ctx) -> str:
    """The command as one shell line: the case's directory DIR, the kit's KIT."""
    words = [("ddg-oracle" if a == ddg_exe() else "python" if a == sys.executable else a)
             for a in argv]
    return shlex.join(words).replace(str(ctx.dir), "DIR").replace(str(ctx.kit), "KIT")


def run_case(case: Case, kit: Path) -> Outcome:
    """Run one case in a fresh directory under ``kit``; its outcome with the verdict."""
    slug = re.sub(r"[^a-z0-9]+", "-", f"{case.area} {case.name}".lower()).strip("-")[:60]
    ctx = Ctx(Path(tempfile.mkdtemp(prefix=slug + "-", dir=kit / "cases")), kit,
              f"{uuid.uuid4().hex[:16]}")
    o = Outcome(case, "")
    for need in case.needs:
        why = _have(need)
        if why:
            o.skipped = why
            return o
    try:
        if case.setup is not None:
            case.setup(ctx)
        argv = case.argv(ctx)
        o.command = _display(argv, ctx)
        if case.peak_mb is not None:
            from tests.test_hostile import _PEAK
            argv = [sys.executable, "-c", _PEAK, *argv]
        env = {**os.environ, "PYTHONPATH": str(ROOT), MARKER_ENV: ctx.marker}
        env.pop("COLUMNS", None)
        if case.env is not None:
            env.update(case.env(ctx))
        _execute(case, ctx, argv, env, o)
    except Exception as e:  # noqa: BLE001  (the harness's own failure is one badly handled case)
        o.problems.append(f"the fault suite failed to run it: {type(e).__name__}: {e}")
    finally:
        for close in ctx.closers:
            close()
        shutil.rmtree(ctx.dir, ignore_errors=True)
    return o


def _execute(case: Case, ctx: Ctx, argv, env, o: Outcome) -> None:
    out_path, err_path = ctx.dir / ".stdout", ctx.dir / ".stderr"
    limit = max(2 * case.seconds, case.seconds + 5)
    with open(out_path, "w+") as out_fh, open(err_path, "w+") as err_fh:
        t0 = time.monotonic()
        p = subprocess.Popen(argv, cwd=ctx.kit, env=env, stdin=subprocess.DEVNULL,
                             stdout=out_fh, stderr=err_fh, start_new_session=True)
        try:
            if case.during is not None:
                case.during(p, ctx)
        except Exception as e:  # noqa: BLE001
            o.problems.append(f"the fault suite's step during the run failed: "
                              f"{type(e).__name__}: {e}")
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGKILL)
        try:
            p.wait(timeout=max(1.0, limit - (time.monotonic() - t0)))
        except subprocess.TimeoutExpired:
            o.problems.append(f"still running after {limit:.0f} s (killed): a hang")
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
        o.seconds = time.monotonic() - t0
    o.rc = p.returncode
    o.out = out_path.read_text(errors="replace")
    o.err = err_path.read_text(errors="replace")
    if case.peak_mb is not None:                  # the wrapper printed "EXIT PEAK_KIB"
        try:
            o.rc, kib = map(int, o.out.split())
            o.peak_mb = kib / 1024
        except ValueError:
            o.problems.append(f"the peak wrapper printed {o.out[:80]!r}")
    left = _wait_for(lambda: not strays(ctx.marker, p.pid), None, 3.0)
    if left is None:
        o.strays = strays(ctx.marker, p.pid)
        _kill(o.strays)
    _verdict(case, ctx, o)


def _verdict(case: Case, ctx: Ctx, o: Outcome) -> None:
    bad = o.problems
    expected = case.rc if isinstance(case.rc, tuple) else (case.rc,)
    if case.rc is not None and o.rc not in expected:
        bad.append(f"exit {o.rc}, expected {' or '.join(map(str, expected))}")
    text = o.out + o.err
    if not case.traceback_ok and "Traceback (most recent call last)" in text:
        bad.append("a traceback")
    if "internal error" in o.err:
        bad.append("an internal error (exit 3)")
    if "resource_tracker" in o.err:
        bad.append("multiprocessing's resource tracker warned (leaked semaphores: an "
                   "unclean shutdown)")
    lines = [x for x in o.err.splitlines() if x.strip() and not PROGRESS.match(x)]
    one_line = case.one_line if case.one_line is not None else expected == (2,)
    if one_line and not (len(lines) == 1 and lines[0].startswith("ddg-oracle: error:")):
        bad.append(f"stderr is {len(lines)} lines, not one 'ddg-oracle: error:' line")
    for w in case.err:
        if w not in o.err:
            bad.append(f"stderr lacks {w!r}")
    for w in case.out:
        if w not in o.out:
            bad.append(f"stdout lacks {w!r}")
    if o.seconds > case.seconds and not any("a hang" in b for b in bad):
        bad.append(f"took {o.seconds:.1f} s (limit {case.seconds:g} s)")
    if case.peak_mb is not None and o.peak_mb is not None and o.peak_mb > case.peak_mb:
        bad.append(f"peak RSS {o.peak_mb:.0f} MB (limit {case.peak_mb:g} MB)")
    if o.strays:
        bad.append(f"{len(o.strays)} stray process(es) left after the run")
    if case.check is not None:
        why = case.check(ctx, o)
        if why:
            bad.append(why)


def run_cases(cases, kit=None, echo: bool = False) -> list[Outcome]:
    """Run ``cases`` in order (a kit in a temporary directory unless given)."""
    own = kit is None
    kit = Path(tempfile.mkdtemp(prefix="ddg-faults-")) if own else Path(kit)
    make_kit(kit)
    outcomes = []
    try:
        for case in cases:
            o = run_case(case, kit)
            outcomes.append(o)
            if echo:
                verdict = ("skipped: " + o.skipped if o.skipped else
                           "handled" if o.handled else "BADLY: " + "; ".join(o.problems))
                say(f"  {case.area:24} {case.name[:58]:58} {o.seconds:5.1f} s  {verdict}")
    finally:
        if own:
            shutil.rmtree(kit, ignore_errors=True)
    return outcomes


# --- the cases ---------------------------------------------------------------------------------

def _spawning(ctx: Ctx, cls: str) -> str:
    return f"spawning:{cls}"


def _report(ctx: Ctx) -> tuple:
    """``--report DIR/report``: a failing run's counterexamples there, not in /tmp."""
    return ("--report", str(ctx.dir / "report"))


def _driver(ctx: Ctx) -> str:
    return f"exec:{sys.executable} {ctx.kit / 'driver.py'}"


def _report_run(ctx: Ctx, report: Path, *args, impl="reference", only=("D1.6", "X1.4")):
    """A finished ``check --report`` run (setup of the resume cases)."""
    p = subprocess.run([ddg_exe(), "check", "--impl", impl, "--only", *only, "--workers", "1",
                        "--report", str(report), *args], cwd=ctx.kit, capture_output=True,
                       text=True, timeout=300, env={**os.environ, "PYTHONPATH": str(ROOT)})
    if not (report / "results.jsonl").is_file():
        raise RuntimeError(f"setup run wrote no report: {p.stderr[-300:]}")
    return p


def _crafted_pickle(marker_file: Path) -> bytes:
    """A pickle that creates ``marker_file`` when loaded (tests/test_codec.py's _Touch)."""
    import pickle

    from tests.test_codec import _Touch
    return pickle.dumps([_Touch(str(marker_file))])


def _no_file(name: str):
    def check(ctx, o):
        return f"{name} was created: the crafted pickle ran" if (ctx.dir / name).exists() else None
    return check


# signals ---------------------------------------------------------------------------------------

def _signal_when_helpers_run(sig, then=None, pause=0.0):
    """Send ``sig`` to the run once a helper of the checked library is alive."""
    def during(p, ctx):
        if not _wait_for(lambda: _helpers(ctx.marker), p, 60):
            raise RuntimeError("the implementation never started a helper")
        time.sleep(pause)
        p.send_signal(sig)
        if then is not None:
            time.sleep(0.3)
            if p.poll() is None:
                p.send_signal(then)
    return during


def _interrupted_report(ctx, o):
    """A partial report marked interrupted, and no task blamed on the implementation."""
    try:
        doc = json.loads((ctx.dir / "report" / "results.json").read_text())
    except (OSError, ValueError) as e:
        return f"no partial report: {e}"
    if doc.get("interrupted") is not True:
        return "results.json not marked interrupted"
    return _not_blamed(ctx, o)


def _not_blamed(ctx, o):
    """The interrupted task is not reported as the implementation's crash."""
    crashed = []
    try:
        crashed = [r for r in json.loads((ctx.dir / "report" / "results.json").read_text())
                   ["results"] if r.get("status") == "crashed"]
    except (OSError, ValueError, KeyError):
        pass
    if crashed or "crashed" in o.out:
        return (f"the interrupted task is reported as the implementation's crash "
                f"({len(crashed)} 'crashed' in results.json; stdout: "
                f"{next((x.strip() for x in o.out.splitlines() if 'crashed' in x), '')!r})")
    return None


def _stop_a_pool_worker(sig):
    """Send ``sig`` to a pool worker as soon as the first result is in the report (as
    tests/test_interruptions.py does); a worker that ended meanwhile: the next one."""
    def during(p, ctx):
        from tests.test_interruptions import _lines, _pool_workers
        if not _wait_for(lambda: _pool_workers(p.pid), p, 60):
            raise RuntimeError("no pool worker started")
        _wait_for(lambda: _lines(ctx.dir / "report") >= 1, p, 120)
        while p.poll() is None:
            for worker in _pool_workers(p.pid):
                try:
                    os.kill(worker, sig)
                    return
                except ProcessLookupError:
                    continue
            time.sleep(0.02)
        raise RuntimeError("the run ended before a worker could be signalled")
    return during


def _interruption_only() -> list[str]:
    from tests.test_interruptions import ONLY
    return list(ONLY)


def _complete_report(ctx, o):
    from tests.test_interruptions import ONLY
    try:
        doc = json.loads((ctx.dir / "report" / "results.json").read_text())
    except (OSError, ValueError) as e:
        return f"no report: {e}"
    n = len(doc["results"])
    return None if n == len(ONLY) and not doc.get("interrupted") else \
        f"the report holds {n} of {len(ONLY)} results (interrupted={doc.get('interrupted')})"


# the resume cases ------------------------------------------------------------------------------

def _crafted_report(ctx):
    report = ctx.dir / "report"
    _report_run(ctx, report)
    lines = (report / "results.jsonl").read_text().splitlines()
    entry = json.loads(lines[0])
    entry["pickled"] = base64.b64encode(_crafted_pickle(ctx.dir / "ran")).decode()
    entry["resume"] = [{"r": "Example", "v": {"d": [["positions", {"t": []}]]}}]
    (report / "results.jsonl").write_text(json.dumps(entry) + "\n" + "\n".join(lines[1:]) + "\n")


def _crafted_snippet(ctx):
    report = ctx.dir / "report"
    _report_run(ctx, report, "--seed", "7", impl="tests.planted_bugs:ChiIgnoresBoundary",
                only=("D1.6",))
    snippets = sorted(report.rglob("reproduce.py"))
    if not snippets:
        raise RuntimeError("the failing run wrote no reproduce.py")
    crafted = "ddg1:" + base64.b64encode(zlib.compress(_crafted_pickle(ctx.dir / "ran"))).decode()
    text, n = re.subn(r"replay\(('[^']*'), impl, \(.*?\)\)",
                      lambda m: f"replay({m.group(1)}, impl, {crafted!r})",
                      snippets[0].read_text(), flags=re.S)
    if n != 1:
        raise RuntimeError("no replay string found in reproduce.py")
    (ctx.dir / "reproduce.py").write_text(text)


def _damaged_run_json(run):
    def setup(ctx):
        (ctx.dir / "run.json").write_text(json.dumps(run))
        (ctx.dir / "results.jsonl").write_text("")
    return setup


def _moved_report(ctx):
    first = ctx.dir / "first"
    _report_run(ctx, first)
    lines = (first / "results.jsonl").read_text().splitlines()
    (first / "results.jsonl").write_text(lines[0] + "\n")        # as if interrupted
    first.rename(ctx.dir / "moved")


def _moved_check(ctx, o):
    if (ctx.dir / "first").exists():
        return "the old path was written again"
    n = len((ctx.dir / "moved" / "results.jsonl").read_text().splitlines())
    return None if n == 2 else f"results.jsonl has {n} lines, expected 2"


def _report_with(name, make):
    """A finished report whose file ``name`` is replaced by ``make(path)``."""
    def setup(ctx):
        report = ctx.dir / "report"
        _report_run(ctx, report)
        (report / name).unlink()
        make(report / name)
    return setup


def _damaged_middle_line(path):
    path.write_text('{"task": ["reference", "D1.6", null], "resume": []}\nnot json\n{}\n')


def _interrupt_then_resume(ctx):
    report = ctx.dir / "report"
    only = ["D1.6", "R1.5", "X1.4", "CS", "D2.2"]
    ctx.state["n"] = len(only)
    p = subprocess.Popen([ddg_exe(), "check", "--impl", "reference", "--only", *only,
                          "--profile", "ci", "--workers", "2", "--report", str(report)],
                         cwd=ctx.kit, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    try:
        def lines():
            try:
                return len((report / "results.jsonl").read_text().splitlines()) >= 1
            except OSError:
                return False
        _wait_for(lines, p, 120)
        p.send_signal(signal.SIGINT)
        p.wait(timeout=60)
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


def _resumed_complete(ctx, o):
    doc = json.loads((ctx.dir / "report" / "results.json").read_text())
    n = len(doc["results"])
    if doc.get("interrupted") or n != ctx.state["n"]:
        return f"resumed report: interrupted={doc.get('interrupted')}, {n} results"
    return None


# readers ---------------------------------------------------------------------------------------

def _hostile(what):
    def argv_of(command):
        def argv(ctx):
            from tests.hostile import hostile_paths
            path, words = hostile_paths(ctx.dir)[what]
            ctx.state["words"] = words
            if command == "check":
                return ctx.ddg("check", "--mesh", path, "--impl", "reference", "--workers", "1")
            return ctx.ddg("compare", path, "--impl", "reference")
        return argv
    return argv_of


def _words_of_path(ctx, o):
    w = ctx.state.get("words")
    return None if not w or w in o.err else f"stderr lacks {w!r}"


def _fifo(path):
    os.mkfifo(path)


def _zero(path):
    os.symlink("/dev/zero", path)


def _vectors_with(name, make):
    def setup(ctx):
        shutil.copytree(VECTORS, ctx.dir / "vectors")
        (ctx.dir / "vectors" / name).unlink()
        make(ctx.dir / "vectors" / name)
    return setup


# error paths -------------------------------------------------------------------------------

def _in_tmpfs(options: str, *args):
    """``ddg-oracle ARGS`` in a mount namespace of its own with a tmpfs (``options``: size=4k,
    ro) at DIR/mnt: a full or read-only file system without root."""
    def argv(ctx):
        (ctx.dir / "mnt").mkdir()
        return ["unshare", "-rm", "sh", "-c", 'mount -t tmpfs -o "$0" tmpfs "$1" && shift && '
                'exec "$@"', options, str(ctx.dir / "mnt"),
                *ctx.ddg(*[a.replace("MNT", str(ctx.dir / "mnt")) for a in args])]
    return argv


def _remove_report_when_it_starts(p, ctx):
    report = ctx.dir / "report"
    if _wait_for(lambda: (report / "results.jsonl").is_file()
                 and (report / "results.jsonl").stat().st_size > 0, p, 60):
        shutil.rmtree(report, ignore_errors=True)


def _silent_port(ctx):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen(5)                       # accepts, never speaks
    ctx.state["address"] = f"tcp://127.0.0.1:{s.getsockname()[1]}"
    ctx.closers.append(s.close)


def _main_with_short_scheduler_timeout(ctx):
    return [sys.executable, str(ctx.kit / "short_scheduler_timeout.py"), "check", "--impl",
            "reference", "--only", "D1.6", "--scheduler", ctx.state["address"]]


def _unchanged(ctx, o):
    return None if (ctx.dir / "taken").read_text() == "mine" else "the existing file was changed"


# database -----------------------------------------------------------------------------------

def _db_has_files(ctx, o):
    return None if any(p.is_file() for p in (ctx.dir / "db").rglob("*")) else \
        "nothing saved in the example database"


REDIS = "redis://127.0.0.1:1"
#: the reference as a user's class: run isolated, under --timeout, like any library
REFERENCE_CLASS = "ddg_oracle.oracles.exact_reference:ReferenceImplementation"


def _plugin(ctx):
    return [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q", "--ddg-impl",
            "reference", "--ddg-only", "D1.6", str(ctx.dir)]


def cases() -> list[Case]:
    """Every case of the suite, by area."""
    C, S, F, B, E, D = AREAS
    ddg = Ctx.ddg
    sigint, sigterm, sighup = signal.SIGINT, signal.SIGTERM, signal.SIGHUP
    out = [
        # containment: no process a run starts outlives it
        Case(C, "Python library starting a helper per call, 1 worker", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "Spawns"), "--only", "D1.6", "X1.4",
            "--workers", "1"), rc=0, seconds=30, quick=True),
        Case(C, "Python library starting a helper per call, 2 workers", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "Spawns"), "--only", "D1.6", "X1.4",
            "--workers", "2"), rc=0, seconds=30),
        Case(C, "failing Python library starting helpers", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "SpawnsAndFails"), "--only", "D1.6", "X1.4",
            "--workers", "1", *_report(c)), rc=1, seconds=30),
        Case(C, "hanging exec driver with a child", lambda c: ddg(
            c, "check", "--impl", _driver(c), "--only", "D1.6", "--budget", "3", "--workers",
            "1", *_report(c)), rc=1, out=("hang",), seconds=30),
        Case(C, "compare: Python library starting helpers", lambda c: ddg(
            c, "compare", c.kit / "ico.obj", "--impl", _spawning(c, "Spawns")), rc=0,
            seconds=30),
        Case(C, "verify --impl: Python library starting helpers", lambda c: ddg(
            c, "verify", VECTORS, "--impl", _spawning(c, "Spawns")), rc=0, seconds=60),
        Case(C, "dask local:2: Python library starting helpers", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "Spawns"), "--only", "D1.6", "--scheduler",
            "local:2"), rc=0, seconds=60, needs=("distributed",)),
        Case(C, "library segfaulting on meshes with boundary", lambda c: ddg(
            c, "check", "--impl", "tests.misbehaving:SegfaultsOnBoundary", "--only", "D1.6",
            "--workers", "1", *_report(c)), rc=1, out=("SIGSEGV",), seconds=30),
        Case(C, "library call hanging (--timeout 1)", lambda c: ddg(
            c, "check", "--impl", "tests.misbehaving:HangsOnBoundary", "--only", "D1.6",
            "--timeout", "1", "--budget", "5", "--workers", "1", *_report(c)), rc=1,
            out=("hang",), seconds=30),
        *[Case(C, f"misbehaving exec driver: {mode}", lambda c, m=mode: ddg(
            c, "check", "--impl", f"exec:{sys.executable} {MISBEHAVING_DRIVER} {m}", "--only",
            "D3.1", "--workers", "1", "--timeout", "2", "--budget", "10", *_report(c)), rc=1,
            out=words, peak_mb=peak, seconds=30, quick=mode == "segfault")
          for mode, words, peak in [("segfault", ("SIGSEGV",), None),
                                    ("garbage", ("not JSON",), None),
                                    ("dies", ("exited with code 3",), None),
                                    ("half-line", (), None), ("hangs-later", (), None),
                                    ("huge-line", (), 1000)]],

        # signals: handled from start to end, every interrupted run says how to resume
        *[Case(S, f"{sig.name} mid-run (library with helpers, --report)", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "Spawns"), "--only", "D1.6", "R1.5", "CS",
            "--profile", "ci", "--report", c.dir / "report"), rc=128 + sig,
            err=(f"interrupted by {sig.name}", "--resume"), seconds=60,
            during=_signal_when_helpers_run(sig), check=_interrupted_report,
            quick=sig == sigint) for sig in (sigint, sigterm, sighup)],
        Case(S, "SIGINT twice (an impatient Ctrl-C)", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "Spawns"), "--only", "D1.6", "R1.5", "CS",
            "--profile", "ci", "--report", c.dir / "report"), rc=130,
            err=("interrupted by SIGINT",), seconds=60,
            during=_signal_when_helpers_run(sigint, then=sigint)),
        *[Case(S, f"SIGINT while an exec driver hangs, {w} worker(s)", lambda c, w=w: ddg(
            c, "check", "--impl", _driver(c), "--only", "D1.6", "--workers", w, *_report(c)),
            rc=130, err=("interrupted by SIGINT", "--resume"), seconds=60,
            during=_signal_when_helpers_run(sigint, pause=1.0), check=_interrupted_report)
          for w in ("1", "2")],
        Case(S, "SIGTERM to compare (library with helpers)", lambda c: ddg(
            c, "compare", c.kit / "ico.obj", "--impl", _spawning(c, "SpawnsSlowly")), rc=143,
            seconds=60, during=_signal_when_helpers_run(sigterm), quick=True),
        Case(S, "SIGINT to compare (library with helpers)", lambda c: ddg(
            c, "compare", c.kit / "ico.obj", "--impl", _spawning(c, "SpawnsSlowly")), rc=130,
            seconds=60, during=_signal_when_helpers_run(sigint)),
        Case(S, "SIGTERM to verify --impl (library with helpers)", lambda c: ddg(
            c, "verify", VECTORS, "--impl", _spawning(c, "SpawnsSlowly")), rc=143,
            seconds=60, during=_signal_when_helpers_run(sigterm, pause=1.0)),
        *[Case(S, f"{sig.name} to a pool worker", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", *_interruption_only(), "--profile", "ci",
            "--workers", "2", "--report", c.dir / "report"), rc=0, seconds=120,
            during=_stop_a_pool_worker(sig), check=_complete_report)
          for sig in (signal.SIGSTOP, signal.SIGKILL)],

        # safe formats: data, never code; --resume where the directory is
        Case(F, "crafted report directory (a pickle) on --resume", lambda c: ddg(
            c, "check", "--resume", c.dir / "report"), err=("is not a result ddg-oracle wrote",),
            setup=_crafted_report, check=_no_file("ran"), seconds=15, quick=True),
        Case(F, "crafted replay string (a pickle) in reproduce.py",
             lambda c: [sys.executable, str(c.dir / "reproduce.py")], rc=1, one_line=False,
             err=("pickle",), traceback_ok=True, setup=_crafted_snippet, check=_no_file("ran"),
             seconds=15),
        *[Case(F, f"damaged run.json {json.dumps(run)[:40]}", lambda c: ddg(
            c, "check", "--resume", c.dir), err=("--resume",), setup=_damaged_run_json(run),
            quick=k == 0)
          for k, run in enumerate([{"argv": "check", "seed": 1},
                                   {"argv": ["--only", "D1.6"], "seed": "zero"}, []])],
        Case(F, "moved report directory resumes where it is", lambda c: ddg(
            c, "check", "--resume", c.dir / "moved"), rc=0, setup=_moved_report,
            check=_moved_check, seconds=20),
        Case(F, "interrupted (SIGINT), then --resume", lambda c: ddg(
            c, "check", "--resume", c.dir / "report"), rc=0, setup=_interrupt_then_resume,
            check=_resumed_complete, seconds=60),
        Case(F, "--resume: results.jsonl is a FIFO", lambda c: ddg(
            c, "check", "--resume", c.dir / "report"), err=("FIFO",),
            setup=_report_with("results.jsonl", _fifo), seconds=5),
        Case(F, "--resume: results.jsonl is /dev/zero", lambda c: ddg(
            c, "check", "--resume", c.dir / "report"), err=("a device",),
            setup=_report_with("results.jsonl", _zero), seconds=5),
        Case(F, "--resume: run.json is /dev/zero", lambda c: ddg(
            c, "check", "--resume", c.dir / "report"), err=("run.json",),
            setup=_report_with("run.json", _zero), seconds=5),
        Case(F, "--resume: results.jsonl damaged mid-file", lambda c: ddg(
            c, "check", "--resume", c.dir / "report"), err=("line 2 is not",),
            setup=_report_with("results.jsonl", _damaged_middle_line), seconds=10),
        Case(F, "--resume of a directory without run.json", lambda c: ddg(
            c, "check", "--resume", c.dir), err=("no run.json",)),

        # bounded readers: refused before reading, within seconds, in little memory
        *[Case(B, f"{command} {what}", _hostile(what)(command), check=_words_of_path,
               peak_mb=500, seconds=5, quick=command == "compare")
          for command in ("compare", "check --mesh")
          for what in ("/dev/urandom", "a FIFO", "/dev/zero named x.obj", "a directory",
                       "empty PLY elements with a body",
                       "a PLY element with rows and no property",
                       "a duplicated (opposite) face")],
        Case(B, "verify: answers /dev/zero", lambda c: ddg(c, "verify", VECTORS, "/dev/zero"),
             err=("it is a device",), peak_mb=500, seconds=5, quick=True),
        Case(B, "verify: answers a FIFO", lambda c: ddg(c, "verify", VECTORS, c.dir / "fifo"),
             err=("it is a FIFO",), setup=lambda c: os.mkfifo(c.dir / "fifo"), seconds=5,
             quick=True),
        Case(B, "verify: an empty answers file", lambda c: ddg(
            c, "verify", VECTORS, c.dir / "empty.jsonl"), err=("no answer in it",),
            setup=lambda c: (c.dir / "empty.jsonl").write_text(""), seconds=5, quick=True),
        Case(B, "verify: a corpus file is /dev/zero", lambda c: ddg(
            c, "verify", c.dir / "vectors", "/dev/null"), err=("a device",),
            setup=_vectors_with("area.json", _zero), peak_mb=500, seconds=5),
        Case(B, "verify: a corpus file is a FIFO", lambda c: ddg(
            c, "verify", c.dir / "vectors", "/dev/null"), err=("FIFO",),
            setup=_vectors_with("area.json", _fifo), seconds=5),
        Case(B, "verify: the corpus manifest is /dev/zero", lambda c: ddg(
            c, "verify", c.dir / "vectors", "/dev/null"), err=("a device",),
            setup=_vectors_with("manifest.json", _zero), peak_mb=500, seconds=5),
        Case(B, "a mesh over DDG_MESH_SIZE_LIMIT", lambda c: ddg(
            c, "compare", c.kit / "ico.obj", "--impl", "reference"),
            err=("over the limit", "DDG_MESH_SIZE_LIMIT"),
            env=lambda c: {"DDG_MESH_SIZE_LIMIT": "100"}, seconds=5),
        Case(B, "a 20-face OBJ under ulimit -v 1.5 GiB (address space)", lambda c: [
            sys.executable, str(c.kit / "ulimit_v.py"), str(1536 << 20), *ddg(
                c, "compare", c.kit / "ico.obj", "--impl", "reference")], rc=0, seconds=20,
             quick=True),
        Case(B, "an exec manifest that is a FIFO", lambda c: ddg(
            c, "check", "--impl", f"exec:{c.dir / 'driver.json'}", "--only", "D1.6"),
            setup=lambda c: os.mkfifo(c.dir / "driver.json"), seconds=5),

        # error paths: one line, exit 2, before any work; never exit 3
        *[Case(E, f"check {' '.join(args)!s}", lambda c, a=args: ddg(
            c, "check", "--impl", "reference", *a), err=(words,), quick=args[0] == "--only")
          for args, words in [(["--timeout", "0"], "--timeout must be a positive"),
                              (["--timeout", "-1"], "--timeout"),
                              (["--width", "0"], "--width must be at least"),
                              (["--only", ""], "no catalog ID given"),
                              (["--workers", "0"], "--workers must be >= 1"),
                              (["--only", "ZZZ9"], "ZZZ9")]],
        *[Case(E, f"{var}={value}", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6"), err=(var,),
            env=lambda c, v=var, x=value: {v: x}, quick=var == "DDG_EXAMPLE_TIME_LIMIT")
          for var, value in [("DDG_EXAMPLE_TIME_LIMIT", "soon"), ("DDG_MEMORY_LIMIT", "lots"),
                             ("DDG_MESH_SIZE_LIMIT", "big")]],
        Case(E, "vectors --out onto an existing file", lambda c: ddg(
            c, "vectors", "--out", c.dir / "taken"), err=("is an existing file",),
            setup=lambda c: (c.dir / "taken").write_text("mine"), check=_unchanged),
        Case(E, "--report where nothing can be written (/proc)", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6", "--report",
            "/proc/ddg-oracle-cannot/report"), err=("--report",)),
        Case(E, "--report on a read-only file system", _in_tmpfs(
            "ro", "check", "--impl", "reference", "--only", "D1.6", "--workers", "1",
            "--report", "MNT/report"), err=("--report",), needs=("unshare",)),
        Case(E, "--report on a full file system (4 KiB)", _in_tmpfs(
            "size=4k", "check", "--impl", "reference", "--only", "D1.6", "--workers", "1",
            "--report", "MNT/report"), err=("--report",), needs=("unshare",), seconds=20,
            quick=True),
        Case(E, "--report filling up during the run (12 KiB)", _in_tmpfs(
            "size=12k", "check", "--impl", "reference", "--only", "D1.6", "X1.4", "CS", "R1.5",
            "--workers", "1", "--report", "MNT/report"), err=("--report", "could not write"),
            needs=("unshare",), seconds=30),
        Case(E, "--report directory removed during the run", lambda c: ddg(
            c, "check", "--impl", _spawning(c, "Spawns"), "--only", "D1.6", "R1.5", "CS",
            "X1.4", "--workers", "1", "--report", c.dir / "report"), rc=(0, 2),
            during=_remove_report_when_it_starts, seconds=60),
        Case(E, "implementation aborting at import", lambda c: ddg(
            c, "check", "--impl", "aborts_at_import:Impl", "--only", "D1.6"),
            err=("cannot load aborts_at_import:Impl", "SIGABRT"), seconds=20, quick=True),
        Case(E, "implementation hanging at import (--timeout 3)", lambda c: ddg(
            c, "check", "--impl", "hangs_at_import:Impl", "--only", "D1.6", "--timeout", "3"),
            err=("did not load within",), seconds=45),
        Case(E, "implementation raising in its constructor", lambda c: ddg(
            c, "check", "--impl", "raises_at_init:Impl", "--only", "D1.6"),
            err=("no licence",), seconds=20),
        Case(E, "unknown implementation module", lambda c: ddg(
            c, "check", "--impl", "nowhere_at_all:Nothing", "--only", "D1.6"),
            err=("nowhere_at_all",)),
        Case(E, "exec: a program that does not exist", lambda c: ddg(
            c, "check", "--impl", "exec:/nonexistent/driver", "--only", "D1.6"),
            err=("/nonexistent/driver",)),
        Case(E, "--scheduler nonsense", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6", "--scheduler", "nonsense"),
            err=("cannot reach a dask scheduler",), seconds=30, needs=("distributed",)),
        Case(E, "--scheduler local:zero", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6", "--scheduler", "local:zero"),
            err=("local:N",)),
        Case(E, "--scheduler: a port that never answers (2 s timeout)",
             _main_with_short_scheduler_timeout, err=("no dask scheduler answered within 2 s",),
             setup=_silent_port, seconds=20, needs=("distributed",)),
        Case(E, "compare --timeout -1", lambda c: ddg(
            c, "compare", c.kit / "ico.obj", "--impl", REFERENCE_CLASS, "--timeout", "-1"),
            err=("--timeout",), seconds=20),
        Case(E, "verify --impl --timeout 0", lambda c: ddg(
            c, "verify", VECTORS, "--impl", REFERENCE_CLASS, "--timeout", "0"),
            err=("--timeout",), seconds=5),
        Case(E, "compare: unknown mesh format", lambda c: ddg(
            c, "compare", c.dir / "mesh.xyz", "--impl", "reference"),
            err=("unknown mesh format",),
            setup=lambda c: (c.dir / "mesh.xyz").write_text("1 2 3\n")),

        # the example database
        Case(D, "DDG_HYPOTHESIS_DATABASE=DIR saves a failure of check", lambda c: ddg(
            c, "check", "--impl", "tests.planted_bugs:ChiIgnoresBoundary", "--only", "D1.6",
            "--workers", "1", "--seed", "7", "--report", c.dir / "report"), rc=1,
            env=lambda c: {"DDG_HYPOTHESIS_DATABASE": str(c.dir / "db")}, check=_db_has_files,
            seconds=20, quick=True),
        Case(D, "unreachable Redis, 1 worker: a warning, the run goes on", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6", "--workers", "1"), rc=0,
            out=("passed",), err=("the run goes on",),
            env=lambda c: {"DDG_HYPOTHESIS_DATABASE": REDIS}, seconds=30, needs=("redis",)),
        Case(D, "unreachable Redis, 2 workers: a warning, the run goes on", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6", "--workers", "2"), rc=0,
            out=("passed",), err=("the run goes on",),
            env=lambda c: {"DDG_HYPOTHESIS_DATABASE": REDIS}, seconds=30, needs=("redis",)),
        Case(D, "unreachable Redis through the pytest plugin", _plugin, rc=0, one_line=False,
             out=("1 passed",), env=lambda c: {"DDG_HYPOTHESIS_DATABASE": REDIS}, seconds=40,
             needs=("redis",)),
        Case(D, "DDG_HYPOTHESIS_DATABASE names a regular file: failure unsaved", lambda c: ddg(
            c, "check", "--impl", "tests.planted_bugs:ChiIgnoresBoundary", "--only", "D1.6",
            "--workers", "1", "--seed", "7", "--report", c.dir / "report"), rc=1,
            err=("example database",),
            setup=lambda c: (c.dir / "dbfile").write_text("not a directory\n"),
            env=lambda c: {"DDG_HYPOTHESIS_DATABASE": str(c.dir / "dbfile")}, seconds=20),
        Case(D, "DDG_HYPOTHESIS_DATABASE=none", lambda c: ddg(
            c, "check", "--impl", "reference", "--only", "D1.6", "--workers", "1"), rc=0,
            out=("passed",), env=lambda c: {"DDG_HYPOTHESIS_DATABASE": "none"}),
    ]
    return out


# --- the report ---------------------------------------------------------------------------------

def summary(outcomes) -> list[dict]:
    rows = []
    for area in AREAS:
        mine = [o for o in outcomes if o.case.area == area]
        rows.append({"area": area, "cases": len(mine),
                     "handled": sum(o.handled for o in mine),
                     "badly": sum(1 for o in mine if o.skipped is None and not o.handled),
                     "skipped": sum(1 for o in mine if o.skipped is not None),
                     "seconds": sum(o.seconds for o in mine)})
    return rows


def table(outcomes) -> str:
    rows = summary(outcomes)
    lines = ["| area | cases | handled | badly | skipped | seconds |",
             "|---|---:|---:|---:|---:|---:|"]
    for r in rows + [{"area": "**all**", **{k: sum(r[k] for r in rows) for k in
                                           ("cases", "handled", "badly", "skipped", "seconds")}}]:
        lines.append(f"| {r['area']} | {r['cases']} | {r['handled']} | {r['badly']} | "
                     f"{r['skipped']} | {r['seconds']:.0f} |")
    return "\n".join(lines)


def _first_lines(text: str, n: int = 3) -> str:
    lines = [x.strip() for x in text.splitlines() if x.strip()]
    return " / ".join(lines[-n:])[:400]


def badly(outcomes) -> str:
    out = []
    for o in outcomes:
        if o.skipped is None and not o.handled:
            out.append(f"- **{o.case.area}: {o.case.name}**: {'; '.join(o.problems)}.  \n"
                       f"  `{o.command}` (exit {o.rc}, {o.seconds:.1f} s)"
                       + (f"; stderr: `{_first_lines(o.err)}`" if o.err.strip() else ""))
    return "\n".join(out) or "None."


def every_case(outcomes) -> str:
    lines = ["| area | case | exit | seconds | verdict |", "|---|---|---:|---:|---|"]
    for o in outcomes:
        verdict = ("skipped (" + o.skipped + ")" if o.skipped else "handled" if o.handled
                   else "**badly**")
        lines.append(f"| {o.case.area} | {o.case.name} | {o.rc} | {o.seconds:.1f} | {verdict} |")
    return "\n".join(lines)


def replace_section(name: str, body: str) -> None:
    """Put ``body`` between ``<!-- begin NAME -->`` and ``<!-- end NAME -->`` in docs/faults.md."""
    text = DOC.read_text()
    begin, end = f"<!-- begin {name} -->", f"<!-- end {name} -->"
    i, j = text.find(begin), text.find(end)
    if i < 0 or j < i:
        raise RuntimeError(f"{DOC}: no {begin} ... {end} section")
    DOC.write_text(text[:i + len(begin)] + "\n" + body.rstrip("\n") + "\n" + text[j:])


def _load() -> str:
    try:
        out = subprocess.run(["uptime"], capture_output=True, text=True, timeout=5).stdout
        return out.rsplit("load average:", 1)[1].strip()
    except (OSError, IndexError, subprocess.SubprocessError):
        return "-"


def run(mode: Mode) -> dict:
    chosen = [c for c in cases() if c.quick or not mode.quick]
    load_before = _load()
    t0 = time.monotonic()
    outcomes = run_cases(chosen, echo=True)
    wall = time.monotonic() - t0
    m = machine()
    command = "python -m benchmarks faults" + (" --quick" if mode.quick else "") + " --no-write"
    print(table(outcomes))
    print("\nhandled badly:\n" + badly(outcomes))
    body = (f"`{command}`: commit {m['commit']}, {m['date']}, {wall:.0f} s, load "
            f"{load_before} (uptime, at the start), {m['cpus']} CPUs, Python {m['python']}.\n\n"
            + table(outcomes) + "\n\n### Handled badly\n\n" + badly(outcomes)
            + "\n\n### Every case\n\n" + every_case(outcomes) + "\n")
    replace_section("faults", body)
    say(f"wrote {DOC.relative_to(ROOT)}")
    return {"rows": summary(outcomes), "wall": wall, "command": command,
            "badly": [{"area": o.case.area, "case": o.case.name, "command": o.command,
                       "exit": o.rc, "problems": o.problems} for o in outcomes
                      if o.skipped is None and not o.handled]}
