"""The exact rank of reference/sparse.py: both routes (reduced Fractions for rational
matrices, division-free elimination for Surd entries) against matrices built with a known
rank, and the rational route's size growth (issue 46: the division-free route took over
700 s on the 30 x 36 rigidity matrix of the rational icosahedron)."""

import random
import time
from fractions import Fraction

import pytest

from ddg_oracle.reference import rigidity, surfaces
from ddg_oracle.reference.exact.surds import Surd
from ddg_oracle.reference.sparse import rank


def _matrix_of_rank(k, n_rows, n_cols, rng):
    """``n_rows x n_cols`` of rank exactly ``k``: k rows with distinct pivot columns (a 1 in
    their pivot column, 0 in the others' pivots: independent), the other rows integer and
    fractional combinations of them; rows and columns shuffled."""
    pivots = rng.sample(range(n_cols), k)
    base = []
    for i, c in enumerate(pivots):
        row = {j: Fraction(rng.randint(-9, 9), rng.randint(1, 4))
               for j in range(n_cols) if j not in pivots}
        row[c] = Fraction(1)
        base.append(row)
    rows = list(base)
    for _ in range(n_rows - k):
        coef = [Fraction(rng.randint(-3, 3), rng.randint(1, 3)) for _ in range(k)]
        combo = {}
        for a, r in zip(coef, base):
            for j, v in r.items():
                combo[j] = combo.get(j, 0) + a * v
        rows.append(combo)
    rng.shuffle(rows)
    perm = list(range(n_cols))
    rng.shuffle(perm)
    return {i: {perm[j]: v for j, v in r.items() if v} for i, r in enumerate(rows)}


@pytest.mark.parametrize("seed", range(12))
def test_rank_is_the_built_rank_by_both_routes(seed):
    rng = random.Random(seed)
    k = rng.randint(0, 6)
    n_rows, n_cols = k + rng.randint(0, 5), k + rng.randint(0, 5)
    m = _matrix_of_rank(k, n_rows, n_cols, rng)
    assert rank(m) == k
    # the same matrix with Surd entries takes the division-free route
    assert rank({i: {j: Surd(v) for j, v in r.items()} for i, r in m.items()}) == k


def test_the_rational_route_keeps_the_rigidity_rank_fast():
    """Dehn: the icosahedron (rational coordinates) is infinitesimally rigid; its 30 x 36
    rigidity matrix has rank 30.  Reduced fractions keep the entries the size of the minors
    (about 0.01 s here); the generous limit only catches exponential growth coming back."""
    start = time.process_time()
    assert rank(rigidity.rigidity_matrix(surfaces.icosahedron())) == 30
    assert time.process_time() - start < 10
