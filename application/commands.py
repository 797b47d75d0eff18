"""What the commands share: the usage error (exit 2), the options every command checks
the same way, notes and warnings on stderr, and starting the implementations to check.

A layer below :mod:`ddg_oracle.application.cli` and the commands' own modules (:mod:`.report`,
:mod:`.survey`): they raise and use these without importing the command line.
"""

from __future__ import annotations

import concurrent.futures as cf
import os
import sys

from ..reference.errors import InputError

#: pool workers of check, compare and survey by default (fewer on a one-core machine)
DEFAULT_WORKERS = 2


class UsageError(InputError):
    """A command line that cannot be run as given (exit 2)."""


def default_workers() -> int:
    return max(1, min(DEFAULT_WORKERS, os.cpu_count() or 1))


def refuse_used_report_dir(path: str) -> None:
    """--report DIR must be a new or empty directory: refused before any work is done."""
    if os.path.lexists(path) and not (os.path.isdir(path) and not os.listdir(path)):
        what = "a directory that is not empty" if os.path.isdir(path) else "an existing file"
        raise UsageError(f"--report {path}: is {what}; name a new or empty directory")


def warn(message: str) -> None:
    print(f"ddg-oracle: note: {message}", file=sys.stderr)


def warn_near_misses(impls) -> None:
    """A warning per implementation with a method that looks like a protocol method it
    lacks (a misnamed ``cotmatrix``): its properties would be silently not applicable."""
    from ..protocol.methods import near_miss_warning
    for impl in impls:
        said = near_miss_warning(impl)
        if said:
            print(f"ddg-oracle: warning: {said}", file=sys.stderr)


def start_implementations(specs, timeout):
    """{spec: implementation}: the reference in this process, the others isolated, started
    in parallel; an unloadable spec raises ImplementationNotFound (exit 2)."""
    from .implementations import load_implementation
    from .isolation import Isolated

    def one(spec):
        return load_implementation(spec) if spec == "reference" else Isolated(spec, timeout=timeout)

    with cf.ThreadPoolExecutor(max_workers=max(1, len(specs))) as pool:
        futures = {s: pool.submit(one, s) for s in specs}
    started, error = {}, None
    for s, f in futures.items():
        try:
            started[s] = f.result()
        except Exception as e:  # noqa: BLE001  (re-raised below after closing the others)
            error = error or e
    if error is not None:
        for impl in started.values():
            getattr(impl, "close", lambda: None)()
        from .isolation import ImplementationCrashed
        if isinstance(error, ImplementationCrashed):   # it died or hung while loading
            raise UsageError(f"cannot load {error.implementation}: it {error.how}") from None
        raise error
    return started


def check_timeout(args) -> None:
    """--timeout of check, compare and verify: a bad value is a usage error, never a result
    blamed on a library (-1: every call 'did not return'; 0: a worker restarted per call)."""
    if not args.timeout > 0 or args.timeout == float("inf"):
        raise UsageError(f"--timeout must be a positive number of seconds per call, got "
                         f"{args.timeout}")
