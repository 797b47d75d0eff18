"""Helpers for drawing inside strategies: one of a few values (:func:`spread`), a branch of
an enclosing ``one_of`` (:func:`grouped`), and strategies built once per arguments
(:func:`once`), so that drawing from them inside a draw costs no new validation."""

from __future__ import annotations

import functools

from hypothesis import strategies as st


def once(factory):
    """``factory`` (a strategy's constructor) giving one strategy object per arguments.

    A strategy built inside a draw is a new object at every draw, and Hypothesis validates
    every new object over its whole tree (emptiness, reusable values, cacheability) the
    first time it is drawn from: three small ones built afresh made a trivial example 1.3
    to 1.8 times as costly (a micro-benchmark, 300 examples).  Hypothesis itself caches
    ``integers``, ``lists``, ``tuples`` and ``booleans`` of equal arguments, not
    ``sampled_from``, ``one_of``, ``filter``, ``map`` or composites.  Arguments that
    cannot be hashed (a list) build a new strategy, as without this."""
    memo = functools.lru_cache(maxsize=512)(factory)

    @functools.wraps(factory)
    def strategy(*args, **kwargs):
        try:
            hash((args, tuple(kwargs.items())))
        except TypeError:
            return factory(*args, **kwargs)
        return memo(*args, **kwargs)
    return strategy


def spread(values):
    """One of ``values``, each about equally often, shrinking towards the first (list them
    simplest first).  ``st.integers(a, b)`` draws ``a`` in about half of the examples (and
    ``st.integers(0, 3) == 3`` holds in one of seven, not four); where a bug shows only
    in part of a range (an exponent past a threshold), that part must be drawn."""
    return _sampled(tuple(values))


@once
def _sampled(values: tuple):
    return st.sampled_from(values)


def grouped(*strategies):
    """``st.one_of(*strategies)`` as one branch of an enclosing ``one_of``: Hypothesis
    flattens nested ``one_of`` (through ``map`` too), so ``one_of(one_of(a, b, c), d)``
    draws d one time in four, not two."""
    inner = st.one_of(*strategies)
    return st.composite(lambda draw: draw(inner))()
