"""What a child process that ran an implementation left behind: how it ended, what it said.

Shared by the isolated Python workers (:mod:`ddg_oracle.application.isolation`), the programs of the
executable protocol (:mod:`ddg_oracle.oracles.executable`) and the pool of check workers
(:mod:`ddg_oracle.application.jobs`), so that every report words a death the same way.
"""

from __future__ import annotations

import signal


class SelfDescribed:
    """Marks an exception about a checked implementation whose message says it all (the
    implementation, its method, what happened): a report shows the message alone, not our
    wrapper's class path before it."""


class NotSent(ValueError):
    """An input no protocol request can carry (a NaN coordinate, an index out of range: the
    request's JSON would not be read as the same arrays): the program never saw it, so
    nothing about the program follows from it (raised by the executable protocol, passed
    on as such by an isolated worker)."""


def exit_text(code: int | None) -> str:
    """How a process ended, from its exit code (negative: the signal that killed it).

    >>> exit_text(-11), exit_text(3), exit_text(None)
    ('signal SIGSEGV', 'exit code 3', 'no exit code (still running)')
    """
    if code is None:
        return "no exit code (still running)"
    if code < 0:
        try:
            return f"signal {signal.Signals(-code).name}"
        except ValueError:
            return f"signal {-code}"
    return f"exit code {code}"


def stderr_tail(path, lines: int = 3, chars: int = 400) -> str:
    """The last ``lines`` non-empty lines of the file a process's stderr went to, joined
    with ' | ' and cut to ``chars`` (a library's own message before it died), or ''."""
    try:
        with open(path, "rb") as fh:
            fh.seek(0, 2)
            fh.seek(max(0, fh.tell() - 4 * chars))
            text = fh.read().decode("utf-8", "replace")
    except OSError:
        return ""
    tail = [x.strip() for x in text.strip().splitlines() if x.strip()][-lines:]
    return " | ".join(tail)[-chars:]


#: The per-call limit grows with the input: ``timeout`` seconds per this many rows of the
#: largest argument (faces or vertices), never less than ``timeout``.
ROWS_PER_TIMEOUT = 10_000


def call_limit(timeout: float, rows: int) -> float:
    """Seconds one call on an input of ``rows`` faces (or vertices) may take: ``timeout``
    per ROWS_PER_TIMEOUT rows, never less than ``timeout``.

    >>> round(call_limit(60, 56_172), 3), call_limit(60, 12)
    (337.032, 60)
    """
    return timeout * max(1, rows / ROWS_PER_TIMEOUT)


def rows_of(args) -> int:
    """The length of the longest argument (V or F of a protocol call), 0 if none has one."""
    return max((len(a) for a in args if hasattr(a, "__len__") and not isinstance(a, (str, bytes))),
               default=0)
