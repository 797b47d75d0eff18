"""Input arrays as adapters hand them to libraries: checked first, because some
libraries segfault on a bad index instead of raising."""

from __future__ import annotations

import numpy as np


def checked_arrays(V, F) -> tuple[np.ndarray, np.ndarray]:
    """(V float64 C-contiguous n x 3, F int64 C-contiguous m x 3), or a ValueError saying why."""
    V = np.ascontiguousarray(V, dtype=np.float64)
    F = np.ascontiguousarray(F, dtype=np.int64)
    if V.ndim != 2 or V.shape[1] != 3:
        raise ValueError(f"V must be n x 3, got shape {V.shape}")
    if F.ndim != 2 or F.shape[1] != 3:
        raise ValueError(f"F must be m x 3, got shape {F.shape}")
    if F.shape[0] == 0:
        raise ValueError("F has no faces")
    if F.min() < 0 or F.max() >= V.shape[0]:
        raise ValueError(f"face indices must lie in [0, {V.shape[0]}), got [{F.min()}, {F.max()}]")
    return V, F
