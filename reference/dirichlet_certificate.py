"""A certified enclosure of the Dirichlet solution at any size (C3.4 / T3.5), exact.

:func:`~ddg_oracle.reference.dirichlet.solve_dirichlet` eliminates exactly.  Rational
weights keep that cheap, but with the irrational cotan weights of a float mesh every
elimination step multiplies square-root numbers, and a solution in ``Q(sqrt p_1, ...,
sqrt p_k)`` can need ``2^k`` terms: exact solving stays limited to a handful of unknowns.
This module answers at any size in another form: given a *candidate* ``z`` (any numbers:
a float solve, an implementation's answer) it proves, with integer arithmetic only, that
the exact solution ``u*`` satisfies ``|u*(i) - z(i)| <= t v(i)`` at every vertex.

The certificate.  Let ``I`` be the unknowns (the vertices off V0), ``A = L_II`` and
``r = (L z)_I`` the candidate's residual (``z = c`` on V0).  If

1. ``A`` is a Z-matrix: ``L_ij <= 0`` for ``i != j`` in ``I`` (the weights between
   unknowns are nonnegative; decided exactly), and
2. a given vector ``v > 0`` on ``I`` has ``(A v)_i > 0`` at every ``i`` in ``I``
   (decided on enclosures),

then ``A`` is a nonsingular M-matrix with ``A^-1 >= 0`` entrywise (a Z-matrix with a
positive vector mapped to a positive vector: Berman and Plemmons, *Nonnegative Matrices in
the Mathematical Sciences*, ch. 6, Theorem 2.3, condition I27), so ``u*`` exists and is
unique, and with ``e = u*_I - z_I``: ``A e = -r``, ``|r| <= t A v`` for
``t = max_i |r_i| / (A v)_i``, hence ``|e| <= A^-1 |r| <= t A^-1 A v = t v``.  A good
``v`` is the solution of ``A v = 1`` (any float solve of it: the certificate checks it).

Condition 1 holds for a Delaunay triangulation (every cotan weight >= 0, D4.8 / L4.11),
so always for the intrinsic Delaunay Laplacian, and for any graph Laplacian with
nonnegative weights; elsewhere :class:`CertificateFailed` names the edge.

Exactness.  Every entry ``L_ij``, candidate value and ``v(j)`` is enclosed by integers at
the scale ``2^-bits`` (:func:`~ddg_oracle.reference.exact.intervals.scaled_bounds`;
square roots by ``isqrt``), products and sums of those enclose ``r_i`` and ``(A v)_i`` at
the scale ``2^-2 bits``; ``t`` and the radii are exact Fractions.  No float is used; when
the enclosures at ``bits`` do not show ``(A v)_i > 0`` the precision is doubled up to
``max_bits``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Mapping, Sequence

from .dirichlet import as_laplacian
from .errors import BadShape, DDGError, InputError
from .exact import sign
from .exact.intervals import scaled_bounds
from .sparse import exact_number

__all__ = ["CertificateFailed", "DirichletEnclosure", "certify_dirichlet"]


class CertificateFailed(DDGError):
    """The certificate does not apply or the given vector does not prove it; ``where``
    holds the vertices concerned (an edge ``(i, j)`` or a row ``(i,)``)."""

    def __init__(self, message: str, where=()):
        super().__init__(message)
        self.where = tuple(where)


@dataclass(frozen=True)
class DirichletEnclosure:
    """``|u*(i) - center[i]| <= radius[i]`` for the exact Dirichlet solution ``u*``.

    ``center``: the boundary values on V0 and the candidate elsewhere (exact numbers);
    ``radius``: 0 on V0, ``scale * v(i)`` elsewhere (Fractions); ``scale``: the ``t`` of the
    certificate (for the exact solution as candidate, the enclosures' width alone: 0 when
    every entry and value is a multiple of ``2^-bits``); ``bits``: the precision of the
    enclosures that proved it."""

    center: list
    radius: list
    scale: Fraction
    bits: int

    def interval(self, i: int) -> tuple:
        """``(lo, hi)``, exact, with ``lo <= u*(i) <= hi``."""
        return self.center[i] - self.radius[i], self.center[i] + self.radius[i]

    def contains(self, i: int, x) -> bool:
        """Whether ``x`` (taken exactly) is within ``radius[i]`` of ``center[i]``."""
        return abs(exact_number(x, f"vertex {i}") - self.center[i]) <= self.radius[i]


def certify_dirichlet(operator, boundary_values: Mapping, candidate: Sequence,
                      positive: Sequence, *, bits: int = 96, max_bits: int = 1536
                      ) -> DirichletEnclosure:
    """C3.4 / T3.5: a proven enclosure of the exact solution of ``Lap f = 0`` off V0,
    ``f = c`` on V0 around ``candidate`` (module docstring), at any size.

    ``operator``: a Laplacian (:class:`~ddg_oracle.reference.sparse.SparseMatrix`) or a
    surface (its cotan Laplacian).  ``boundary_values``: ``{vertex: number}`` (V0 and c);
    ``candidate``, ``positive``: n numbers each (floats taken exactly; ``candidate`` is
    read off V0 only, ``positive`` must be > 0 there).  Raises :class:`CertificateFailed`
    when a weight between two unknowns is negative, or when ``(L_II v)_i > 0`` is not
    shown at ``max_bits`` (then no enclosure is claimed).

    >>> from ddg_oracle.reference.laplacian import graph_laplacian
    >>> L = graph_laplacian(3, [(0, 1, 1), (1, 2, 3)])     # f(1) = (0 + 3 * 4) / 4 = 3
    >>> e = certify_dirichlet(L, {0: 0, 2: 4}, [0, 3.25, 4], [0, 1, 0])
    >>> e.scale, e.interval(1)                # |L f(1)| = 4 * 0.25 = 1, (L v)(1) = 4
    (Fraction(1, 4), (Fraction(3, 1), Fraction(7, 2)))
    """
    L = as_laplacian(operator)
    n = L.shape[0]
    if len(candidate) != n or len(positive) != n:
        raise BadShape(f"candidate and positive need {n} values each, got {len(candidate)} "
                       f"and {len(positive)}")
    if not boundary_values:
        raise InputError("V0 is empty: the Dirichlet problem needs at least one boundary vertex")
    c = {}
    for v, x in boundary_values.items():
        if not (isinstance(v, int) and 0 <= v < n):
            raise InputError(f"boundary vertex {v!r} is not a vertex 0..{n - 1}")
        c[v] = exact_number(x, f"boundary value at {v}")
    unknowns = [i for i in range(n) if i not in c]
    z = [c[i] if i in c else exact_number(candidate[i], f"candidate at vertex {i}")
         for i in range(n)]
    v = {i: exact_number(positive[i], f"positive vector at vertex {i}") for i in unknowns}
    for i in unknowns:
        if v[i] <= 0:
            raise InputError(f"the positive vector is {v[i]} at vertex {i}: it must be > 0 "
                             "at every vertex off V0")
        for j, x in L.row(i).items():
            if j != i and j not in c and sign(x) > 0:
                raise CertificateFailed(
                    f"L[{i}, {j}] = {float(x):.6g} > 0: the weight between the unknowns {i} "
                    f"and {j} is negative, so L restricted to the unknowns is no M-matrix and "
                    "this certificate does not apply (the intrinsic Delaunay Laplacian has "
                    "nonnegative weights, L4.11; solve_dirichlet solves a few unknowns "
                    "exactly)", (i, j))
    k = bits
    while True:
        t = _certify(L, c, unknowns, z, v, k)
        if isinstance(t, Fraction):
            break
        if 2 * k > max_bits:
            raise CertificateFailed(
                f"(L v)(i) > 0 is not shown at vertex {t} with enclosures of 2^-{k} (tried "
                f"{bits} up to {k} bits): give a vector v > 0 with L v > 0 off V0, e.g. a "
                "solution of L_II v = 1; no such v exists when a component of the unknowns "
                "has no edge to V0", (t,))
        k *= 2
    radius = [Fraction(0) if i in c else t * v[i] for i in range(n)]
    return DirichletEnclosure(z, radius, t, k)


def _entry_bounds(row, k):
    """``[(j, lo, hi)]``: each entry of the row enclosed at the scale ``2^-k``."""
    return [(j, *scaled_bounds(a, k)) for j, a in row.items()]


def _dot_bounds(entries, values, skip=()):
    """Integers enclosing ``sum_j L_ij x_j * 2^(2k)`` (``entries`` from :func:`_entry_bounds`,
    ``values[j]`` the bounds of ``x_j``; columns in ``skip`` left out): interval products
    summed."""
    lo = hi = 0
    for j, alo, ahi in entries:
        if j in skip:
            continue
        xlo, xhi = values[j]
        if xlo == xhi:
            p, q = alo * xlo, ahi * xlo
            if p > q:
                p, q = q, p
        else:
            ps = (alo * xlo, alo * xhi, ahi * xlo, ahi * xhi)
            p, q = min(ps), max(ps)
        lo += p
        hi += q
    return lo, hi


def _certify(L, c, unknowns, z, v, k):
    """``t`` (a Fraction) when the enclosures at scale ``2^-k`` show ``(A v)_i > 0`` at every
    unknown, else the first unknown where they do not (an int)."""
    zb = [scaled_bounds(x, k) for x in z]
    vb = {i: scaled_bounds(x, k) for i, x in v.items()}
    r_max, w_at = 0, 1                            # the largest |r_i| / (A v)_i so far
    for i in unknowns:
        entries = _entry_bounds(L.row(i), k)
        wlo, _ = _dot_bounds(entries, vb, skip=c)
        if wlo <= 0:
            return i
        rlo, rhi = _dot_bounds(entries, zb)
        r = max(-rlo, rhi, 0)
        if r * w_at > r_max * wlo:
            r_max, w_at = r, wlo
    return Fraction(r_max, w_at)
