"""Vectors of R^2 and R^3 as coordinate tuples, exact: the differences, inner products,
cross products and determinants the chapters compute with.

The entries are whatever exact numbers the caller holds (ints, Fractions, Surds: a
PolyhedralSurface's positions are Fractions, an unfolding's coordinates may be Surds);
nothing is rounded and nothing is converted, so integer input stays integer arithmetic.

>>> u, v = sub((1, 0, 0), (0, 0, 0)), sub((0, 2, 0), (0, 0, 0))
>>> dot(u, v), cross(u, v), det3(u, v, (0, 0, 3)), cross2((1, 0), (0, 2))
(0, (0, 0, 2), 6, 2)
"""

from __future__ import annotations

__all__ = ["sub", "dot", "cross", "det3", "cross2"]


def sub(p, q) -> tuple:
    """``p - q``, any dimension."""
    return tuple(x - y for x, y in zip(p, q))


def dot(u, v):
    """``<u, v>``, any dimension >= 1 (no zero is added first: an int stays an int, a
    Surd is not added to 0)."""
    pairs = zip(u, v)
    x, y = next(pairs)
    acc = x * y
    for x, y in pairs:
        acc = acc + x * y
    return acc


def cross(a, b) -> tuple:
    """``a x b`` in R^3."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def det3(a, b, c):
    """``det(a, b, c) = <a, b x c>`` in R^3."""
    return dot(a, cross(b, c))


def cross2(p, q):
    """``p x q = det(p, q)`` in R^2: twice the signed area of the triangle 0 p q."""
    return p[0] * q[1] - p[1] * q[0]
