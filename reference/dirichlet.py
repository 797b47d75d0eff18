"""The discrete Dirichlet problem and harmonic functions (section 3.2 of the notes), exact.

Given a Laplacian (a graph Laplacian, D3.1, or the cotan Laplacian of a
surface, Definition 3.2), a boundary set ``V0`` and values ``c`` on it, the
discrete Dirichlet boundary value problem (dDBVP) asks for f with
``(Lap f)(i) = 0`` for i not in V0 and ``f = c`` on V0.  :func:`solve_dirichlet`
solves it by exact Gaussian elimination over the entries (Fractions for
rational weights; Surds for cotan weights of a general surface).  Around it:

* T3.1 / R3.2: ``grad E = Lap f`` (:func:`energy_gradient`), checked against the
  exact derivative at t = 0 of the quadratic polynomial ``t -> E(f + t phi)``
  (:func:`directional_derivative`);
* T3.2 / C3.3: maximum principle and Liouville for positive weights
  (:func:`satisfies_maximum_principle`, :func:`strict_interior_extrema`,
  :func:`kernel_dimension`, :func:`is_constant_on_components`);
* C3.4 / T3.5: uniqueness and minimality, ``E(f + phi) - E(f) = E(phi) >= 0`` for
  phi vanishing on V0 (:func:`energy_increase`);
* P3.10: positive weights and harmonic at i => f(i) is a convex combination of
  its neighbours (:func:`neighbour_convex_combination`), and a separating
  direction as the exact certificate that a point is *not* in a hull
  (:func:`separates`), for the cotan counterexample (see :mod:`ddg_oracle.reference.minimal`).

Conventions: those of :mod:`ddg_oracle.reference.laplacian` (``Lap`` positive
semidefinite, ``E = 1/2 f^T Lap f = 1/2 sum_edges nu (f(i) - f(j))^2``).

Exactness guard: with Surd entries every elimination step multiplies and adds
square-root numbers and the number of terms grows; each operation is bounded
by ``ddg_oracle.reference.exact.settings.term_limit`` (default 4096) and raises
:class:`~ddg_oracle.reference.errors.TermLimitExceeded` beyond it.  ``solve_dirichlet``
takes ``term_limit=`` to raise the guard for one call.  Keep Surd systems small
(a handful of interior vertices); rational systems are cheap.

>>> from ddg_oracle.reference.laplacian import graph_laplacian
>>> L = graph_laplacian(3, [(0, 1, 1), (1, 2, 3)])
>>> solve_dirichlet(L, {0: 0, 2: 4})                   # f(1) = (1*0 + 3*4) / 4
[Fraction(0, 1), Fraction(3, 1), Fraction(4, 1)]
"""

from __future__ import annotations

from contextlib import nullcontext
from fractions import Fraction
from typing import Callable, Mapping, Sequence

from .errors import BadShape, InputError
from .exact import limits
from .laplacian import cotan_laplacian, dirichlet_energy
from .exact.surds import simplest
from .sparse import SparseMatrix, exact_number, rank

__all__ = ["SingularDirichletProblem", "as_laplacian", "solve_dirichlet", "matrix_components",
           "kernel_dimension", "is_harmonic_at", "energy_gradient", "directional_derivative",
           "energy_increase", "satisfies_maximum_principle", "strict_interior_extrema",
           "is_constant_on_components", "has_positive_weights", "neighbour_convex_combination",
           "separates"]

_ZERO = Fraction(0)


class SingularDirichletProblem(InputError):
    """The Dirichlet problem has no unique solution (the system is singular).

    ``component`` lists the vertices of a component without a boundary vertex
    when that is the reason, else the unknowns left without a pivot.
    """

    def __init__(self, message: str, component=()):
        super().__init__(message)
        self.component = tuple(component)


def as_laplacian(operator) -> SparseMatrix:
    """The Laplacian an operator argument names: a square :class:`SparseMatrix` as it is,
    a surface's cotan Laplacian (D3.2) otherwise."""
    if isinstance(operator, SparseMatrix):
        n, m = operator.shape
        if n != m:
            raise BadShape(f"a Laplacian is square, got {n} x {m}")
        return operator
    return cotan_laplacian(operator)         # a surface


def matrix_components(L: SparseMatrix) -> list[list[int]]:
    """Connected components of the graph of nonzero off-diagonal entries (sorted lists).

    For a graph Laplacian these are the components of the graph of edges with
    nonzero total weight; an isolated vertex is its own component.
    """
    n = L.shape[0]
    comp = [-1] * n
    out = []
    for s in range(n):
        if comp[s] >= 0:
            continue
        comp[s] = len(out)
        stack, members = [s], [s]
        while stack:
            i = stack.pop()
            for j in L.row(i):
                if comp[j] < 0:
                    comp[j] = comp[s]
                    stack.append(j)
                    members.append(j)
        out.append(sorted(members))
    return out


# --- exact elimination ------------------------------------------------------------------


def _eliminate(rows: dict[int, dict[int, object]], rhs: dict[int, list] | None):
    """In-place Gaussian elimination; returns the pivots [(row, col, inverse)] in order.

    Pivot choice: a nonzero diagonal entry if any remains (symmetric pivoting),
    else any nonzero entry of a remaining row and column; among those the
    Markowitz cost (row length - 1) * (column length - 1) decides (fill-in),
    then the number of square-root terms of the pivot (Surd growth).
    Zero is decided exactly.  Rows that end up empty are left out of the pivots.
    """
    remaining = set(rows)
    cols_left = set()
    for r in rows.values():
        cols_left.update(r)
    # column -> rows holding it (kept up to date for the rows still remaining)
    where: dict[int, set] = {}
    for i, r in rows.items():
        for j in r:
            where.setdefault(j, set()).add(i)
    pivots = []
    while remaining:
        # Markowitz: the pivot (i, c) minimising (row length - 1) * (column length - 1),
        # diagonal pivots first, then the fewest square-root terms (Surd growth).
        best, best_key = None, None
        for i in remaining:
            r = rows[i]
            for c in (i,) if i in r and i in cols_left else ():
                key = (0, (len(r) - 1) * (len(where[c]) - 1), _terms(r[c]))
                if best_key is None or key < best_key:
                    best, best_key = (i, c), key
        if best is None:
            for i in remaining:
                r = rows[i]
                for c in r:
                    if c in cols_left:
                        key = (1, (len(r) - 1) * (len(where[c]) - 1), _terms(r[c]))
                        if best_key is None or key < best_key:
                            best, best_key = (i, c), key
        if best is None:
            break
        p, c = best
        prow = rows[p]
        inv = 1 / prow[c]
        remaining.discard(p)
        cols_left.discard(c)
        for i in list(where.get(c, ())):
            if i == p or i not in remaining:
                continue
            r = rows[i]
            factor = r[c] * inv
            for j, v in prow.items():
                if j == c:
                    continue
                new = r[j] - factor * v if j in r else -factor * v
                if new:
                    r[j] = new
                    where.setdefault(j, set()).add(i)
                elif j in r:
                    del r[j]
                    where[j].discard(i)
            del r[c]
            where[c].discard(i)
            if rhs is not None:
                rhs[i] = [a - factor * b if b else a for a, b in zip(rhs[i], rhs[p])]
        pivots.append((p, c, inv))
    return pivots


def _terms(x) -> int:
    return x.n_terms if hasattr(x, "n_terms") else 1



def kernel_dimension(L: SparseMatrix) -> int:
    """``n - rank(L)``, the rank found by exact (division-free) elimination (C3.3 / R3.3).

    For nonnegative weights (and for cotan weights, R3.3) the kernel of a
    Laplacian is exactly the locally constant functions: its dimension is the
    number of components of the graph (Liouville, C3.3).

    >>> from ddg_oracle.reference.laplacian import graph_laplacian
    >>> kernel_dimension(graph_laplacian(4, [(0, 1, 1), (2, 3, 5)]))
    2
    """
    return L.shape[0] - rank({i: L.row(i) for i in range(L.shape[0])})


def solve_dirichlet(operator, boundary_values: Mapping, *, term_limit: int | None = None) -> list:
    """C3.4 / T3.5: the unique f with ``Lap f = 0`` off V0 and ``f = c`` on V0, exact.

    ``operator``: a Laplacian (:class:`SparseMatrix`) or a surface (its cotan
    Laplacian is used).  ``boundary_values``: ``{vertex: value}`` for the
    vertices of V0; a value is a number (Fraction, int, float taken exactly,
    Surd) or a tuple of numbers (an R^N-valued problem, solved coordinate-wise
    with one elimination).  Returns the list of values at all vertices
    (numbers or tuples), Fractions where rational.

    Raises :class:`SingularDirichletProblem` when the solution is not unique:
    a component of the graph without a boundary vertex (named in the message),
    or, for weights of mixed sign, a singular system.  ``term_limit`` raises the
    Surd term guard for this call (see the module docstring).
    """
    L = as_laplacian(operator)
    n = L.shape[0]
    if not boundary_values:
        raise SingularDirichletProblem("V0 is empty: the Dirichlet problem needs at least one "
                                       "boundary vertex (otherwise every constant solves it)",
                                       range(n))
    vector = None
    values: dict[int, list] = {}
    for v, c in boundary_values.items():
        if not (isinstance(v, int) and 0 <= v < n):
            raise InputError(f"boundary vertex {v!r} is not a vertex 0..{n - 1}")
        is_vec = isinstance(c, (tuple, list))
        if vector is None:
            vector = is_vec
            dim = len(c) if is_vec else 1
        if is_vec != vector or (is_vec and len(c) != dim):
            raise BadShape("boundary values must be all numbers or all tuples of one length")
        values[v] = [exact_number(x, f"boundary value at {v}") for x in (c if is_vec else (c,))]
    interior = [i for i in range(n) if i not in values]
    for comp in matrix_components(L):
        if not any(v in values for v in comp):
            raise SingularDirichletProblem(
                f"the component with vertices {comp} has no boundary vertex: Lap f = 0 there "
                "determines f only up to a constant (add a vertex of it to V0)", comp)
    guard = limits(term_limit=term_limit) if term_limit is not None else nullcontext()
    with guard:
        rows, rhs = {}, {}
        for i in interior:
            r, b = {}, [_ZERO] * dim
            for j, v in L.row(i).items():
                if j in values:
                    b = [a - v * c for a, c in zip(b, values[j])]
                else:
                    r[j] = v
            rows[i], rhs[i] = r, b
        pivots = _eliminate(rows, rhs)
        if len(pivots) < len(interior):
            left = sorted(set(interior) - {c for _, c, _ in pivots})
            raise SingularDirichletProblem(
                f"the Dirichlet system is singular (weights of mixed sign?): no pivot for the "
                f"unknowns at vertices {left}", left)
        sol: dict[int, list] = {}
        for p, c, inv in reversed(pivots):
            b = rhs[p]
            for j, v in rows[p].items():
                if j != c:
                    b = [a - v * x for a, x in zip(b, sol[j])]
            sol[c] = [simplest(a * inv) for a in b]
    out = []
    for i in range(n):
        x = values[i] if i in values else sol[i]
        out.append(tuple(x) if vector else x[0])
    return out


# --- T3.1 / R3.2: harmonicity and the gradient of the energy ------------------------------------


def is_harmonic_at(operator, f: Sequence, i: int) -> bool:
    """``(Lap f)(i) == 0`` with ``(Lap f)(i) = sum_j nu(ij) (f(i) - f(j))``, exactly."""
    L = as_laplacian(operator)
    acc = _ZERO
    for j, v in L.row(i).items():
        acc = acc + v * f[j]
    return not acc


def energy_gradient(operator, f: Sequence) -> list:
    """R3.2: ``grad E(f) = Lap f``, i.e. ``dE/df(i) = (Lap f)(i)``, exact.

    With ``(Lap f)(i) = sum_j nu(ij) (f(i) - f(j))`` and
    ``E = 1/2 sum_edges nu (f(i) - f(j))^2`` there is no factor 2 (T3.1).
    """
    return as_laplacian(operator).matvec(list(f))


def directional_derivative(energy: Callable, f: Sequence, phi: Sequence):
    """``d/dt E(f + t phi)`` at t = 0, exactly, for a quadratic energy E.

    ``t -> E(f + t phi)`` is a polynomial of degree at most 2 (T3.1's proof:
    ``E(f) + t sum phi (Lap f) + t^2 E(phi)``), so its derivative at 0 is the
    central difference ``(E(f + phi) - E(f - phi)) / 2`` -- no limit is taken.
    ``energy`` is any callable giving an exact value (a graph energy, the
    piecewise linear energy of T3.6, ...).  T3.1 says this equals
    ``sum_i phi(i) (Lap f)(i)``.
    """
    if len(f) != len(phi):
        raise BadShape(f"f and phi have lengths {len(f)} and {len(phi)}")
    plus = [a + b for a, b in zip(f, phi)]
    minus = [a - b for a, b in zip(f, phi)]
    return simplest((energy(plus) - energy(minus)) / 2)


def energy_increase(operator, f: Sequence, phi: Sequence):
    """``E(f + phi) - E(f)``, exact (T3.5: equals E(phi) >= 0 when f solves the
    Dirichlet problem and phi vanishes on V0)."""
    L = as_laplacian(operator)
    g = [a + b for a, b in zip(f, phi)]
    return simplest(dirichlet_energy(L, g) - dirichlet_energy(L, f))


# --- T3.2, C3.3: maximum principle and Liouville -------------------------------------------------


def has_positive_weights(operator) -> bool:
    """Every off-diagonal entry is <= 0 (every edge weight >= 0), decided exactly.

    An edge of weight exactly 0 is no edge for the matrix; the theorems then
    apply to the graph of the remaining edges (:func:`matrix_components`).
    """
    L = as_laplacian(operator)
    return all(v < 0 for i, j, v in L.entries() if i != j)


def strict_interior_extrema(operator, f: Sequence, boundary) -> list[int]:
    """Vertices i not in V0 where f has a non-trivial local maximum or minimum.

    i qualifies when ``f(i) >= f(j)`` for every neighbour j with strict
    inequality for one (or the reverse).  T3.2's proof: with positive weights
    ``(Lap f)(i) > 0`` there (``< 0`` at a minimum), so f is not harmonic at i.
    """
    L = as_laplacian(operator)
    V0 = set(boundary)
    out = []
    for i in range(L.shape[0]):
        if i in V0:
            continue
        nb = [f[j] for j in L.row(i) if j != i]
        if not nb:
            continue
        if all(f[i] >= y for y in nb) and any(f[i] > y for y in nb):
            out.append(i)
        elif all(f[i] <= y for y in nb) and any(f[i] < y for y in nb):
            out.append(i)
    return out


def satisfies_maximum_principle(operator, f: Sequence, boundary) -> bool:
    """T3.2: on every component, max and min of f are attained on V0 (exact).

    A component without a vertex of V0 must carry a constant f (C3.3).  The
    premise of the theorem (positive weights, f harmonic off V0) is *not*
    checked here: this is the conclusion, to test against.
    """
    L = as_laplacian(operator)
    V0 = set(boundary)
    for comp in matrix_components(L):
        vals = [f[i] for i in comp]
        on_b = [f[i] for i in comp if i in V0]
        if not on_b:
            if any(v != vals[0] for v in vals):
                return False
            continue
        if max(vals) != max(on_b) or min(vals) != min(on_b):
            return False
    return True


def is_constant_on_components(operator, f: Sequence) -> bool:
    """C3.3: f is constant on every component of the graph (exact)."""
    L = as_laplacian(operator)
    return all(all(f[i] == f[comp[0]] for i in comp) for comp in matrix_components(L))


# --- P3.10: convex hull of the neighbours ----------------------------------------------------------


def neighbour_convex_combination(operator, i: int) -> dict[int, object]:
    """P3.10: ``{j: lambda_j}`` with ``lambda_j = nu(ij) / C``, ``C = sum_j nu(ij)``.

    If f is harmonic at i then ``f(i) = sum_j lambda_j f(j)`` (any dimension);
    with positive weights every lambda_j > 0 and they sum to 1, so f(i) lies in
    the convex hull of its neighbours.  The lambdas are exact; whether they are
    positive is for the caller to check (they are not for negative cotan weights).
    """
    L = as_laplacian(operator)
    row = L.row(i)
    C = row.get(i, _ZERO)
    if not C:
        raise InputError(f"vertex {i}: the weights at it sum to 0, no convex combination")
    return {j: simplest(-v / C) for j, v in row.items() if j != i}


def separates(direction: Sequence, point: Sequence, points: Sequence[Sequence]) -> bool:
    """``<d, point> > max_q <d, q>``: an exact certificate that point is NOT in conv(points)."""
    def dot(x):
        acc = _ZERO
        for a, b in zip(direction, x):
            acc = acc + a * b
        return acc
    top = max((dot(q) for q in points), default=None)
    return top is not None and dot(point) > top
