"""A small exact sparse matrix: rows of exact entries (``Fraction`` or ``Surd``).

Chapter 3's operators (graph Laplacians D3.1, the cotan Laplacian (3.3)) are
sparse and their entries are exact numbers; this is the container they are
returned in.  It stores a dict of rows, each a dict ``column -> value`` holding
only the nonzero entries (zero is decided exactly, so an entry that cancels to
0 disappears).  Arithmetic stays exact; :meth:`SparseMatrix.to_scipy` and
:meth:`SparseMatrix.to_dense_floats` hand out *float views*, every entry
correctly rounded (``float()`` of a ``Fraction`` or a ``Surd`` is).

>>> from fractions import Fraction
>>> L = SparseMatrix.from_entries((2, 2), [(0, 0, 1), (0, 1, -1), (1, 0, -1), (1, 1, 1)])
>>> L[0, 1], L.shape, L.is_symmetric()
(Fraction(-1, 1), (2, 2), True)
>>> L.matvec([3, 5])
[Fraction(-2, 1), Fraction(2, 1)]
>>> L.quadratic_form([3, 5])       # f^T L f
Fraction(4, 1)
"""

from __future__ import annotations

from fractions import Fraction
from typing import Iterable, Sequence

from .errors import BadShape, DDGError, IndexOutOfRange, InputError
from .exact.rationals import rational
from .exact.surds import Surd, exact_sum, simplest

__all__ = ["SparseMatrix", "exact_number", "negative_direction", "rank",
           "is_positive_semidefinite"]

_ZERO = Fraction(0)


def exact_number(x, where: str = ""):
    """``x`` as an exact entry: a Surd stays a Surd, anything else becomes a Fraction.

    Floats are taken exactly (dyadic rationals); NaN and infinities are rejected.

    >>> exact_number(0.5), exact_number(3)
    (Fraction(1, 2), Fraction(3, 1))
    """
    if isinstance(x, Surd):
        return simplest(x)
    return rational(x, where)


class SparseMatrix:
    """An exact sparse matrix: ``rows[i] = {j: value}`` with nonzero exact values.

    Build with :meth:`from_entries` (duplicates are summed, exact zeros dropped)
    or :meth:`from_rows`.  Entries are ``Fraction`` or ``Surd`` (a rational Surd
    is stored as its Fraction); reading an absent entry gives ``Fraction(0)``.  Immutable by convention: operations
    return new matrices or lists.
    """

    __slots__ = ("_shape", "_rows")

    def __init__(self, shape: tuple[int, int], rows: dict | None = None):
        n, m = shape
        if n < 0 or m < 0:
            raise BadShape(f"negative matrix shape {shape}")
        self._shape = (int(n), int(m))
        self._rows: dict[int, dict[int, object]] = {}
        for i, row in (rows or {}).items():
            clean = {j: simplest(v) for j, v in row.items() if v}
            if clean:
                self._rows[i] = clean

    @classmethod
    def from_entries(cls, shape: tuple[int, int], entries: Iterable) -> "SparseMatrix":
        """From ``(i, j, value)`` triples; values at the same position are added exactly."""
        n, m = shape
        rows: dict[int, dict[int, object]] = {}
        for i, j, v in entries:
            if not (0 <= i < n and 0 <= j < m):
                raise IndexOutOfRange(f"entry ({i}, {j}) outside a {n} x {m} matrix")
            v = exact_number(v, f"entry ({i}, {j})")
            row = rows.setdefault(i, {})
            row[j] = row[j] + v if j in row else v
        return cls((n, m), rows)

    @classmethod
    def _trusted(cls, shape: tuple[int, int], rows: dict) -> "SparseMatrix":
        """Internal: from rows of nonzero entries, rational ones already Fractions."""
        self = object.__new__(cls)
        self._shape = shape
        self._rows = rows
        return self

    @classmethod
    def from_rows(cls, shape: tuple[int, int], rows: dict) -> "SparseMatrix":
        """From ``{i: {j: value}}`` (values already exact)."""
        return cls(shape, rows)

    @classmethod
    def diagonal(cls, values: Sequence) -> "SparseMatrix":
        """The diagonal matrix with the given exact values (e.g. a lumped mass matrix)."""
        n = len(values)
        return cls((n, n), {i: {i: exact_number(v)} for i, v in enumerate(values)})

    # --- inspection -----------------------------------------------------------

    @property
    def shape(self) -> tuple[int, int]:
        return self._shape

    def __getitem__(self, ij):
        i, j = ij
        n, m = self._shape
        if not (0 <= i < n and 0 <= j < m):
            raise IndexOutOfRange(f"entry ({i}, {j}) outside a {n} x {m} matrix")
        return self._rows.get(i, {}).get(j, _ZERO)

    def row(self, i: int) -> dict:
        """Copy of the nonzero entries ``{j: value}`` of row ``i``."""
        return dict(self._rows.get(i, {}))

    def entries(self) -> list[tuple[int, int, object]]:
        """The nonzero entries as sorted ``(i, j, value)`` triples."""
        return [(i, j, v) for i in sorted(self._rows) for j, v in sorted(self._rows[i].items())]

    @property
    def nnz(self) -> int:
        """Number of stored (nonzero) entries."""
        return sum(len(r) for r in self._rows.values())

    def is_symmetric(self) -> bool:
        """Exact symmetry: square and ``A[i, j] == A[j, i]`` for every stored entry."""
        n, m = self._shape
        if n != m:
            return False
        for i, row in self._rows.items():
            for j, v in row.items():
                if self._rows.get(j, {}).get(i, _ZERO) != v:
                    return False
        return True

    def __eq__(self, other):
        if not isinstance(other, SparseMatrix):
            return NotImplemented
        return self._shape == other._shape and self.entries() == other.entries()

    __hash__ = None

    def __repr__(self) -> str:
        n, m = self._shape
        return f"SparseMatrix({n} x {m}, {self.nnz} nonzeros)"

    # --- exact products ----------------------------------------------------------

    def matvec(self, x: Sequence) -> list:
        """``A x`` exactly (a list; entries Fraction or Surd)."""
        n, m = self._shape
        if len(x) != m:
            raise BadShape(f"vector of length {len(x)} for a {n} x {m} matrix")
        return [exact_sum(v * x[j] for j, v in self._rows.get(i, {}).items() if x[j])
                for i in range(n)]

    def quadratic_form(self, f: Sequence, g: Sequence | None = None):
        """``f^T A f`` (or ``f^T A g``) exactly."""
        g = f if g is None else g
        n, m = self._shape
        if len(f) != n or len(g) != m:
            raise BadShape(f"vectors of lengths {len(f)}, {len(g)} for a {n} x {m} matrix")
        terms = []
        for i, row in self._rows.items():
            fi = f[i]
            if not fi:
                continue
            s = exact_sum(v * g[j] for j, v in row.items() if g[j])
            if s:
                terms.append(fi * s)
        return exact_sum(terms)

    def submatrix(self, rows: Sequence[int], cols: Sequence[int]) -> "SparseMatrix":
        """The matrix restricted to ``rows`` x ``cols`` (renumbered in the given order)."""
        ci = {c: k for k, c in enumerate(cols)}
        out = {}
        for a, i in enumerate(rows):
            r = {ci[j]: v for j, v in self._rows.get(i, {}).items() if j in ci}
            if r:
                out[a] = r
        return SparseMatrix((len(rows), len(cols)), out)

    # --- float views -----------------------------------------------------------------

    def to_dense_floats(self) -> list[list[float]]:
        """Nested lists of floats, each entry correctly rounded."""
        n, m = self._shape
        out = [[0.0] * m for _ in range(n)]
        for i, row in self._rows.items():
            for j, v in row.items():
                out[i][j] = float(v)
        return out

    def to_scipy(self):
        """A ``scipy.sparse.csr_matrix`` of floats, each entry correctly rounded.

        The exact matrix stays the reference; this is only a float view for
        numerical code.  Structural nonzeros whose float is 0.0 (underflow) are
        kept as explicit entries.
        """
        # export adapter: the only non-stdlib import, used only to hand out a float view
        import scipy.sparse
        rows, cols, vals = [], [], []
        for i, j, v in self.entries():
            rows.append(i)
            cols.append(j)
            vals.append(float(v))
        return scipy.sparse.csr_matrix((vals, (rows, cols)), shape=self._shape, dtype=float)


# --- positive semidefiniteness, decided exactly ---------------------------------------


def negative_direction(A: SparseMatrix) -> list | None:
    """A vector ``x`` with ``x^T A x < 0``, or ``None`` if the symmetric ``A`` is
    positive semidefinite; decided exactly (T4.21 uses it for ``L_T - L_Delaunay``).

    Symmetric elimination (``A = L D L^T`` with diagonal pivots): at every step,
    on the current Schur complement ``S``,

    * a negative diagonal entry ``S_ii < 0`` gives the witness ``e_i``;
    * a zero diagonal entry with a nonzero ``S_ij`` gives ``t e_i + e_j`` with
      ``t = -(S_jj + 1) / (2 S_ij)``, whose value ``2 t S_ij + S_jj`` is ``-1``;
    * otherwise a positive diagonal entry is the pivot (the Schur complement of
      a positive pivot of a semidefinite matrix is semidefinite, and conversely);
      when only zero rows remain, ``A`` is semidefinite.

    A witness ``y`` on the indices still active is lifted through the pivots in
    reverse (``x_p = -(row_p . x) / S_pp`` gives ``x^T S x = y^T S' y``), and
    checked: ``x^T A x < 0`` exactly.  Entries may be Fractions or Surds (signs
    are exact).  ``A`` must be square and symmetric (:class:`BadShape`,
    :class:`InputError`).

    >>> A = SparseMatrix.from_entries((2, 2), [(0, 0, 1), (0, 1, 2), (1, 0, 2), (1, 1, 1)])
    >>> x = negative_direction(A); A.quadratic_form(x) < 0
    True
    >>> negative_direction(SparseMatrix.from_entries((2, 2), [(0, 0, 1), (0, 1, 1),
    ...                                                      (1, 0, 1), (1, 1, 1)])) is None
    True
    """
    n, m = A.shape
    if n != m:
        raise BadShape(f"a semidefiniteness test needs a square matrix, got {n} x {m}")
    if not A.is_symmetric():
        raise InputError("a semidefiniteness test needs a symmetric matrix")
    rows = {i: A.row(i) for i in range(n)}
    active = set(range(n))
    pivots = []                       # (p, {j: S_pj} over the indices active after p, S_pp)

    def lift(y: dict) -> list:
        x = dict(y)
        for p, prow, app in reversed(pivots):
            s = exact_sum(v * x[j] for j, v in prow.items() if x.get(j))
            x[p] = simplest(-s / app)
        out = [x.get(i, _ZERO) for i in range(n)]
        if not A.quadratic_form(out) < 0:          # a bug here, never an input problem
            raise DDGError("negative_direction: the lifted witness is not negative")
        return out

    while active:
        best = None
        for i in sorted(active):
            r = rows[i]
            d = r.get(i, _ZERO)
            if d < 0:
                return lift({i: Fraction(1)})
            if not d:
                for j in sorted(r):
                    if j != i:
                        t = -(rows[j].get(j, _ZERO) + 1) / (2 * r[j])
                        return lift({i: simplest(t), j: Fraction(1)})
                continue
            key = (len(r), getattr(d, "n_terms", 1))
            if best is None or key < best[0]:
                best = (key, i)
        if best is None:                # only zero rows remain
            return None
        p = best[1]
        prow = rows.pop(p)
        app = prow.pop(p)
        active.discard(p)
        pivots.append((p, prow, app))
        for i, a in prow.items():
            r = rows[i]
            del r[p]
            f = a / app
            for j, v in prow.items():
                x = r.get(j, _ZERO) - f * v
                if x:
                    r[j] = simplest(x)
                else:
                    r.pop(j, None)
    return None


def is_positive_semidefinite(A: SparseMatrix) -> bool:
    """True iff the symmetric matrix ``A`` is positive semidefinite, decided exactly
    (see :func:`negative_direction`, which also gives a witness when it is not).

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.laplacian import cotan_laplacian
    >>> is_positive_semidefinite(cotan_laplacian(surfaces.grid(2, 2)))
    True
    """
    return negative_direction(A) is None


def rank(rows: dict[int, dict[int, object]]) -> int:
    """The exact rank of a matrix given by its nonzero entries ``{row: {column: value}}``
    (Fractions, ints or Surds), by division-free elimination: ``row_i <- p row_i - a_ic row_p``.

    No inverse of a Surd is ever formed, so Surd entries never go through conjugate
    inversion (the costly step); a term count grows at most to the number of
    products of the radicands involved.  A matrix of ints and Fractions is eliminated
    with the reduced Fraction ``a_ic / p`` instead: division-free elimination doubles
    the entries' bit size at every step (the 30 x 36 rigidity matrix of a rational
    icosahedron took over 700 s), reduced fractions stay the size of the minors.
    Pivots: diagonal first, short rows, few terms.

    >>> rank({0: {0: 1, 1: 2}, 1: {0: 2, 1: 4}, 2: {2: Fraction(1, 3)}})
    2
    """
    rows = {i: dict(r) for i, r in rows.items()}
    all_rational = all(isinstance(v, (int, Fraction)) for r in rows.values() for v in r.values())
    remaining, cols_left, found = set(rows), set(), 0
    for r in rows.values():
        cols_left.update(r)
    while remaining:
        best = None
        for i in remaining:
            for c, v in rows[i].items():
                if c in cols_left:
                    key = (c != i, len(rows[i]), getattr(v, "n_terms", 1))
                    if best is None or key < best[0]:
                        best = (key, i, c)
        if best is None:
            break
        _, p, c = best
        prow, pv = rows[p], rows[p][c]
        remaining.discard(p)
        cols_left.discard(c)
        found += 1
        for i in remaining:
            r = rows[i]
            a = r.get(c)
            if a is None:
                continue
            new = {}
            f = Fraction(a, pv) if all_rational else None
            for j in set(r) | set(prow):
                if j != c:
                    x = (r.get(j, _ZERO) - f * prow.get(j, _ZERO) if all_rational
                         else r.get(j, _ZERO) * pv - a * prow.get(j, _ZERO))
                    if x:
                        new[j] = x
            rows[i] = new
    return found
