"""Library conventions an adapter may select instead of the reference's.

An adapter option such as ``boundary="library"`` makes the adapter return the
library's own value where it follows another convention than the notes (each
documented in docs/findings.md and docs/conventions.md).  Each adapter lists its
options next to its code (e.g. ``oracles/libigl.py``, ``LIBRARY_CONVENTIONS``) and
declares the chosen ones with :func:`declare`, through the same ``conventions``
attribute any implementation may have (``protocol.methods.declared_conventions``);
``ddg-oracle check --expect-conventions`` reports a failure of such an option as
"convention" when the same adapter with reference conventions passes the same example.
"""

from __future__ import annotations

#: The values of an adapter's convention option: the reference's or the library's own.
CONVENTIONS = ("reference", "library")


def convention_name(base: str, **options: str) -> str:
    """Display name of an adapter with convention options (each one of CONVENTIONS):
    ``base`` if all are "reference", else the non-default ones in parentheses.

    >>> convention_name("gpytoolbox", boundary="library", dihedral="reference")
    "gpytoolbox(boundary='library')"
    >>> convention_name("gpytoolbox", boundary="lib")
    Traceback (most recent call last):
    ...
    ValueError: boundary must be one of ('reference', 'library'), got 'lib'
    """
    for key, value in options.items():
        if value not in CONVENTIONS:
            raise ValueError(f"{key} must be one of {CONVENTIONS}, got {value!r}")
    chosen = [f"{k}={v!r}" for k, v in options.items() if v != "reference"]
    return f"{base}({', '.join(chosen)})" if chosen else base


def declare(base: str, documented: dict[str, tuple[str, str]], **options: str) -> tuple[str, dict]:
    """(display name, ``conventions`` declaration) of the adapter ``base`` with these
    convention options; ``documented`` maps each option to (finding id, what differs).

    >>> declare("libigl", {"boundary": ("F-libigl-2", "2 pi - angle sum at boundary vertices")},
    ...         boundary="library")
    ("libigl(boundary='library')", {'follows': {'F-libigl-2': '2 pi - angle sum at boundary vertices'}, 'counterpart': 'libigl'})
    >>> declare("libigl", {"boundary": ("F-libigl-2", "...")}, boundary="reference")
    ('libigl', {})
    """
    name = convention_name(base, **options)
    follows = dict(documented[k] for k, v in options.items() if v == "library")
    return name, ({"follows": follows, "counterpart": base} if follows else {})
