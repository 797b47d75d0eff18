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
Two things of the implementation do reach a computation: the format its inputs
are rounded to (:func:`~.precision.input_format`: a moved copy of the example
is rounded to float32 for a float32 implementation) and the machine epsilon its
bounds are derived for (:func:`~.protocol.eps`).  Every key therefore carries
both (:func:`context`): a value computed for a float32 implementation is never
handed to a float64 one checked after it in the same worker, where the float32
rounding of its input was once reported as the float64 implementation's error
(T2.5, the moved copy of the example).
The table holds at most :data:`LIMIT` entries (a few examples' worth of every
property), so memory stays bounded on long runs.

A second table, :data:`DRAWN`, keeps what strategies build from their drawn
choices (exact surfaces, step by step): every implementation's task draws the
same choices, and building the exact surface (Fractions) costs more than
checking a float implementation on it.  It is separate so that drawing many
shrink candidates does not evict the reference values of the examples.
"""

from __future__ import annotations

import weakref
from collections import OrderedDict

from .precision import input_format
from ..protocol.methods import eps


def context() -> tuple:
    """What a computation may read of the implementation being checked: its input format
    and machine epsilon (part of every key here).

    >>> from ddg_oracle.properties.precision import inputs_at
    >>> with inputs_at(2.0 ** -23):
    ...     context()
    ('float32', 2.220446049250313e-16)
    """
    return input_format().name, eps()


class Table:
    """A least-recently-used table of at most ``limit`` entries."""

    def __init__(self, limit: int):
        self.limit, self._entries = limit, OrderedDict()

    def shared(self, key, compute):
        """``compute()``, or what it returned for an equal ``key`` before (see module doc).

        ``key`` must be hashable and determine the value completely together with
        :func:`context` (e.g. a name and the exact content of the example it is computed
        from).

        >>> calls, table = [], Table(2)
        >>> table.shared(("demo", 1), lambda: calls.append(1) or "value")
        'value'
        >>> table.shared(("demo", 1), lambda: calls.append(1) or "other"), len(calls)
        ('value', 1)
        """
        entries, key = self._entries, (context(), key)
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

    def get(self, key, default=None):
        """The value kept for ``key`` (marked recently used), else ``default``; adds nothing."""
        key = (context(), key)
        try:
            self._entries.move_to_end(key)
        except KeyError:
            return default
        return self._entries[key]

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


def of(fn, obj):
    """``fn(obj)``, computed once per *object* ``obj`` while it lives: for the exact values
    of one surface (or metric) that several callers ask for, e.g. a property's reference
    values and the reference adapter's answer on a mesh file, whose surfaces are one object
    (:data:`DRAWN`).  The values are kept beside a weak reference to ``obj`` and dropped
    with it, so they never outlive what they are computed from; ``fn`` must be a
    module-level function (its name is the key).

    Unlike :func:`shared`, not once per :func:`context`: ``fn`` must depend on ``obj``
    alone (an exact value, its correctly rounded float view; never a bound, which depends
    on the epsilon), and a float32 reading is another object.  With the context in the key,
    the float32 reading of a CGAL mesh flipped to Delaunay twice (its float64 views, then
    its float32 bounds): cheese.off, 24 s instead of 15.

    >>> class Mesh(list): pass
    >>> calls, xs = [], Mesh([1, 2])
    >>> def double(xs): calls.append(1); return [2 * x for x in xs]
    >>> of(double, xs), of(double, xs), len(calls)
    ([2, 4], [2, 4], 1)
    >>> k = id(xs); del xs; k in _OF
    False
    """
    values, name = _values_of(obj), (fn.__module__, fn.__qualname__)
    if name not in values:
        values[name] = fn(obj)
    return values[name]


def given(fn, obj, value) -> None:
    """Keep ``value`` as :func:`of`'s ``fn(obj)``: for a caller that has it already (a mesh
    file's float coordinates are its surface's positions as floats), without computing it."""
    _values_of(obj)[(fn.__module__, fn.__qualname__)] = value


def _values_of(obj) -> dict:
    k = id(obj)
    entry = _OF.get(k)
    if entry is None or entry[0]() is not obj:
        def drop(ref, k=k, table=_OF):      # the table bound: module globals go at exit
            if table.get(k, (None,))[0] is ref:
                del table[k]
        entry = _OF[k] = (weakref.ref(obj, drop), {})
    return entry[1]


#: id(object) -> (weak reference to it, {function name: value}) (see :func:`of`)
_OF: dict = {}


def clear() -> None:
    """Forget every kept value and drawn example (tests that measure a computation call
    this first)."""
    VALUES.clear()
    DRAWN.clear()
    _OF.clear()
