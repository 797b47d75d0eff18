"""Run a checked implementation in a worker process with a time and memory limit.

A segfault, an abort or a hang of third-party code must not stop a check run.
:class:`Isolated` wraps an implementation spec (``"libigl"`` or
``"module:object"``) as a proxy with the same protocol methods; each call is
sent to a persistent worker process and waited for at most ``timeout``
seconds.  If the worker dies or overruns, it is killed, restarted for the next
call, and the call raises :class:`ImplementationCrashed` saying how (signal,
exit code, time limit, memory limit).  Hypothesis treats that exception like
any failure, so the input that crashes the library is shrunk before it is
reported.

Memory: the worker's address space is capped with ``RLIMIT_AS`` (``memory``
bytes; default ``DDG_MEMORY_LIMIT`` from the environment, e.g. ``4G``,
``512M`` or ``none``, else 8 GiB).  An allocation beyond it fails inside the
worker (``MemoryError``, or a crash of a library that does not check its
allocations) and is reported as a crash naming the limit; the worker is
restarted, and the run goes on.
"""

from __future__ import annotations

import os
import resource
import tempfile
import time
import traceback

from .containment import worker_context
from ..protocol.processes import (ROWS_PER_TIMEOUT, NotSent, SelfDescribed, call_limit,
                                  exit_text, rows_of, stderr_tail)
from ..protocol.budget import Hang, check_time_left, cut_short, time_left
from ..protocol.methods import (METHODS, NotAnImplementation, OutsideDomain,
                                           declared_conventions, machine_epsilon, near_misses,
                                           require_protocol)


class ImplementationCrashed(SelfDescribed, RuntimeError):
    """The implementation's process died or exceeded its time limit on this call."""

    def __init__(self, implementation: str, method: str, how: str):
        self.implementation, self.method, self.how = implementation, method, how
        super().__init__(f"{implementation}.{method} {how}")


class CallTimedOut(Hang, ImplementationCrashed):
    """An isolated call killed at its own time limit: a crash of that call, and a hang."""


class ImplementationError(SelfDescribed, RuntimeError):
    """The implementation raised a Python exception (its traceback is in the message)."""


MEMORY_ENV = "DDG_MEMORY_LIMIT"
DEFAULT_MEMORY = 8 << 30
_UNITS = {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}


def memory_limit(spec: str | None = None) -> int | None:
    """Bytes of address space for a worker: ``spec`` (or ``$DDG_MEMORY_LIMIT``) such as
    ``"4G"``, ``"512M"``, ``"1073741824"``, or ``"none"``; 8 GiB when unset.

    >>> memory_limit("4G"), memory_limit("none"), memory_limit("")
    (4294967296, None, 8589934592)
    """
    raw = (os.environ.get(MEMORY_ENV, "") if spec is None else spec).strip().upper()
    if not raw:
        return DEFAULT_MEMORY
    if raw == "NONE":
        return None
    unit = raw[-1] if raw[-1] in _UNITS else ""
    try:
        n = float(raw[:-1] if unit else raw) * _UNITS[unit]
    except ValueError:
        n = -1
    if not n > 0:
        from ..reference.errors import InputError
        raise InputError(f"memory limit {raw!r}: use a positive size such as 4G, 512M or "
                         f"1073741824 bytes, or none (from {MEMORY_ENV} or Isolated(memory=...))")
    return int(n)


def _size(n: int) -> str:
    return f"{n / (1 << 30):g} GiB" if n >= 1 << 30 else f"{n / (1 << 20):g} MiB"


def _worker(spec: str, memory_bytes: int | None, conn, stderr_path: str | None = None) -> None:
    if stderr_path:
        # what the library prints before it dies (an assertion, an abort message) is kept
        # for the report; the parent reads the tail of this file
        fd = os.open(stderr_path, os.O_WRONLY | os.O_APPEND)
        os.dup2(fd, 2)
        os.close(fd)
    if memory_bytes:
        resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    from .implementations import ImplementationNotFound, load_implementation
    from ..properties.conventions import declared
    try:
        impl = load_implementation(spec)
        methods = sorted(require_protocol(impl))
        declared_conventions(impl)               # a malformed declaration: refused here
        declared(impl)
        conventions = getattr(impl, "conventions", None) or {}
        conn.send(("ready", methods, (getattr(impl, "name", spec), machine_epsilon(impl),
                                      conventions if isinstance(conventions, str)
                                      else dict(conventions), near_misses(impl))))
    except NotAnImplementation as e:
        conn.send(("not-an-implementation", str(e), None))
        return
    except ImplementationNotFound as e:
        conn.send(("error", str(e), None))
        return
    except BaseException as e:  # noqa: BLE001  (report any other failure to the parent)
        conn.send(("error", f"{spec}: {type(e).__name__}: {e}", None))
        return
    while True:
        try:
            method, args = conn.recv()
        except EOFError:
            return
        try:
            conn.send(("ok", getattr(impl, method)(*args), None))
        except OutsideDomain as e:        # an answer, not a crash: re-raised as such
            conn.send(("outside", str(e), None))
        except NotSent as e:              # a program never saw it: re-raised as such
            conn.send(("not sent", str(e), None))
        except MemoryError as e:
            conn.send(("memory", "".join(traceback.format_exception_only(type(e), e)).strip(),
                       None))
        except BaseException as e:  # noqa: BLE001
            conn.send(("raised", "".join(traceback.format_exception_only(type(e), e)).strip(),
                       None))


class Isolated:
    """Proxy of an implementation living in a worker process.

    ``timeout`` is per call, in seconds, for inputs of up to ROWS_PER_TIMEOUT faces (and as
    much again per as many more: :func:`call_limit`); ``memory`` caps the worker's address
    space in bytes (None: no cap; default :func:`memory_limit`, i.e.
    ``$DDG_MEMORY_LIMIT`` or 8 GiB).  Use as a context manager or call
    :meth:`close`.
    """

    def __init__(self, spec: str, timeout: float = 60.0, memory: int | None | str = "env"):
        if memory == "env":
            memory = memory_limit()
        self.spec, self.timeout, self.memory = spec, timeout, memory
        self._ctx = worker_context()
        self._proc = None
        self._conn = None
        fd, self._stderr = tempfile.mkstemp(prefix="ddg-oracle-worker-", suffix=".stderr")
        os.close(fd)
        self._start()

    def _start(self) -> None:
        if self._conn is not None:
            self._conn.close()
        parent, child = self._ctx.Pipe()
        with open(self._stderr, "w"):
            pass                                # a fresh worker: a fresh stderr
        self._proc = self._ctx.Process(target=_worker,
                                       args=(self.spec, self.memory, child, self._stderr),
                                       daemon=True)
        self._proc.start()
        child.close()
        self._conn = parent
        # loading (importing a library, building the object) gets the time of a call
        wait = max(self.timeout, 30.0)
        try:
            loaded = parent.poll(wait)
            message = parent.recv() if loaded else None
        except EOFError:
            raise ImplementationCrashed(self.spec, "load", self._how_it_died()) from None
        except BaseException:
            # interrupted while the worker loads (the task budget's alarm, Ctrl-C, after a
            # worker was replaced mid-task): its "ready" would be read as the next call's
            # answer, and every answer after it as the call before's (a false FAILED)
            self._abandon()
            raise
        if not loaded:
            self._kill()
            raise ImplementationCrashed(self.spec, "load", f"did not load within {wait:g} s "
                                                           "(killed)")
        status, payload, name = message
        if status == "not-an-implementation":
            self._kill()
            raise NotAnImplementation(payload)
        if status != "ready":
            from .implementations import ImplementationNotFound
            self._kill()
            raise ImplementationNotFound(payload)
        self.methods = frozenset(payload)
        self.name, self.machine_epsilon, self.conventions, self.near_misses = name

    def _abandon(self) -> None:
        """Interrupted (Ctrl-C, the time limit of a property example) while a request or its
        answer is in the pipe: the worker owes an answer the next call would read as its
        own, so it is killed, and the next call starts a fresh one."""
        self._kill()
        self._proc = None

    def _kill(self) -> None:
        if self._proc is not None and self._proc.is_alive():
            self._proc.kill()
        if self._proc is not None:
            self._proc.join(5)

    def _how_it_died(self) -> str:
        self._proc.join(5)
        code = self._proc.exitcode
        how = (f"crashed with {exit_text(code)}" if code is not None and code < 0
               else f"exited with code {code}")
        said = self.stderr_tail()
        return f"{how}; it printed: {said}" if said else how

    def stderr_tail(self) -> str:
        """The last lines the worker wrote to stderr (its library's own message), or ''."""
        return stderr_tail(self._stderr)

    def call(self, method: str, *args):
        # inside a check task, wait at most what its budget has left (protocol.budget)
        check_time_left(f"{self.name}.{method}")
        left = time_left()
        limit = call_limit(self.timeout, rows_of(args))
        wait = limit if left is None else min(limit, left)
        if self._proc is None or not self._proc.is_alive():
            self._start()
        started = time.monotonic()
        try:
            self._conn.send((method, args))
        except (BrokenPipeError, OSError):
            how = self._how_it_died()
            self._abandon()                 # the next call starts a fresh worker
            raise ImplementationCrashed(self.name, method, how) from None
        except BaseException:
            self._abandon()                 # interrupted mid-request: see _abandon
            raise
        try:
            done = self._conn.poll(wait)
        except BaseException:
            self._abandon()
            raise
        if not done:
            self._abandon()                 # a fresh worker for the next call, if one comes
            if wait < limit:                # the task's budget ran out: a hang, or a late call
                raise cut_short(f"{self.name}.{method}", started)
            scaled = "" if limit == self.timeout else \
                f" ({self.timeout:g} s per {ROWS_PER_TIMEOUT:,} faces)"
            raise CallTimedOut(self.name, method,
                               f"did not return within {limit:g} s{scaled} (killed); raise "
                               "the limit with Isolated(timeout=...) or ddg-oracle check "
                               "--timeout SECONDS")
        try:
            status, payload, _ = self._conn.recv()
        except EOFError:
            # the crash is this call's result now; the fresh worker is the next call's to
            # start (inside this task's budget, an alarm during its start would replace the
            # crash by "budget ran out")
            how = self._how_it_died()
            self._abandon()
            raise ImplementationCrashed(self.name, method, how) from None
        except BaseException:
            # a signal between poll and the end of the answer (the task budget's alarm):
            # the answer, or its rest, would be read as the next call's
            self._abandon()
            raise
        if status == "memory":
            # a failed allocation may leave a library's state half-built: a fresh worker
            # for the next call
            self._abandon()
            raise ImplementationCrashed(
                self.name, method,
                f"ran out of memory under the limit of {_size(self.memory)} address space "
                f"({payload}); raise it with {MEMORY_ENV}=SIZE or Isolated(memory=...)"
                if self.memory else f"ran out of memory ({payload})")
        if status == "outside":
            raise OutsideDomain(payload)
        if status == "not sent":
            raise NotSent(payload)
        if status == "raised":
            raise ImplementationError(f"{self.name}.{method} raised {payload}")
        if status != "ok":                  # never an answer out of turn, whatever happened
            self._abandon()
            raise RuntimeError(f"isolation: {self.name}.{method} got a {status!r} message "
                               "as its answer")
        return payload

    def __getattr__(self, method: str):
        # only protocol methods the worker's implementation has are exposed
        if method in METHODS and method in self.__dict__.get("methods", ()):
            return lambda *args: self.call(method, *args)
        raise AttributeError(method)

    def close(self) -> None:
        if self._conn is not None:
            self._conn.close()
        self._kill()
        try:
            os.unlink(self._stderr)
        except OSError:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
