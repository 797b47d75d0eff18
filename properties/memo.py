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
"""

from __future__ import annotations

from collections import OrderedDict

#: entries kept (least recently used dropped first)
LIMIT = 512

_table: OrderedDict = OrderedDict()


def shared(key, compute):
    """``compute()``, or what it returned for an equal ``key`` before (see module doc).

    ``key`` must be hashable and determine the value completely (e.g. a name and the
    exact content of the example it is computed from).

    >>> calls = []
    >>> shared(("demo", 1), lambda: calls.append(1) or "value")
    'value'
    >>> shared(("demo", 1), lambda: calls.append(1) or "other"), len(calls)
    ('value', 1)
    """
    try:
        _table.move_to_end(key)
        return _table[key]
    except KeyError:
        pass
    value = compute()
    _table[key] = value
    if len(_table) > LIMIT:
        _table.popitem(last=False)
    return value


def clear() -> None:
    """Forget every kept value (tests that measure a computation call this first)."""
    _table.clear()
