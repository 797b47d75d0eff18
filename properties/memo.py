"""Values a property derives from an example alone, computed once per example content.

Every implementation of a property sees the same examples (one stream per
property, see :func:`~.runner.run_property`), and a check worker runs the
property's tasks for several implementations one after the other.  The exact
reference values and float bounds of an example depend on the example only,
so :func:`shared` keeps them in a small least-recently-used table of this
process, keyed by the example's *content* (its exact positions, faces,
isolated vertices: never by object identity): a worker computes them once per
example instead of once per implementation.

What is kept never depends on an implementation, so a result can only be the
one the property would compute again; callers must not mutate what they get.
The table holds at most :data:`LIMIT` entries (a few examples' worth of every
property), so memory stays bounded on long runs.

A second table, :data:`DRAWN`, keeps what strategies build from their drawn
choices (exact surfaces, step by step): every implementation's task draws the
same choices, and building the exact surface (Fractions) costs more than
checking a float implementation on it.  It is separate so that drawing many
shrink candidates does not evict the reference values of the examples.
"""

from __future__ import annotations

from collections import OrderedDict


class Table:
    """A least-recently-used table of at most ``limit`` entries."""

    def __init__(self, limit: int):
        self.limit, self._entries = limit, OrderedDict()

    def shared(self, key, compute):
        """``compute()``, or what it returned for an equal ``key`` before (see module doc).

        ``key`` must be hashable and determine the value completely (e.g. a name and the
        exact content of the example it is computed from).

        >>> calls, table = [], Table(2)
        >>> table.shared(("demo", 1), lambda: calls.append(1) or "value")
        'value'
        >>> table.shared(("demo", 1), lambda: calls.append(1) or "other"), len(calls)
        ('value', 1)
        """
        entries = self._entries
        try:
            entries.move_to_end(key)
            return entries[key]
        except KeyError:
            pass
        value = compute()
        entries[key] = value
        if len(entries) > self.limit:
            entries.popitem(last=False)
        return value

    def clear(self) -> None:
        self._entries.clear()

    def __len__(self) -> int:
        return len(self._entries)


#: entries kept of the reference values (least recently used dropped first)
LIMIT = 512
#: entries kept of drawn examples' building steps
DRAWN_LIMIT = 1024

VALUES = Table(LIMIT)
DRAWN = Table(DRAWN_LIMIT)
shared = VALUES.shared


def clear() -> None:
    """Forget every kept value and drawn example (tests that measure a computation call
    this first)."""
    VALUES.clear()
    DRAWN.clear()
