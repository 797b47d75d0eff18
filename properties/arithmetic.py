"""numpy's floating-point error state: the properties' own arithmetic and the checked
implementation's.

A degenerate answer of an implementation (a zero angle, a zero area) makes a property's
float arithmetic divide by zero or overflow.  numpy reports that as a ``RuntimeWarning``,
which a project's ``filterwarnings = error`` (or ``python -W error``) turns into an
exception of ddg-oracle's: an internal error where the verdict is the implementation's
failure.  So a property computes under :func:`own_arithmetic` (numpy's warnings off), and
every call of the implementation under :func:`implementations_arithmetic` (the error state
it was called with: its own warnings follow the project's filters, as without ddg-oracle).
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np

__all__ = ["implementations_arithmetic", "own_arithmetic"]

#: numpy's error state outside ddg-oracle's own arithmetic (innermost last)
_OUTSIDE: list[dict] = []


@contextmanager
def own_arithmetic():
    """numpy's floating-point warnings off, until :func:`implementations_arithmetic`."""
    _OUTSIDE.append(np.geterr())
    try:
        with np.errstate(all="ignore"):
            yield
    finally:
        _OUTSIDE.pop()


def implementations_arithmetic():
    """The error state the properties were entered with (a context manager)."""
    return np.errstate(**(_OUTSIDE[-1] if _OUTSIDE else np.geterr()))
