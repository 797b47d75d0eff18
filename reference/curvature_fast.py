"""Exact angle sums and the exact Gauss-Bonnet decision, fast: integer arithmetic, same answers.

:mod:`ddg_oracle.reference.curvature` defines the angle sums, angle defects (D2.2) and the
Gauss-Bonnet decision (T2.6, R2.4) from the metric: Fraction squared lengths,
Surd areas and cotangents, one exact :class:`~ddg_oracle.reference.exact.Angle` per
corner.  This module gives the *same* results (``==`` on every Angle, the same
bool; tested with Hypothesis and on the 1,280-face float icosphere) from the
integers of :func:`ddg_oracle.reference.cotangents.face_data`: per face ``G`` and per
corner ``N`` with ``cot = N / sqrt(G)``.  :func:`ddg_oracle.reference.curvature.angle_sums`
(hence ``angle_defects`` and ``turning_angles``) and
:func:`ddg_oracle.reference.curvature.gauss_bonnet_holds` dispatch here whenever
:func:`applies`.

Angle sums.  The angle at a corner is ``arccot(N / sqrt(G))``; the definition
stores it as ``pi / 24`` multiples when it is one (right angles, 60 degrees,
...) and as the primitive ``arccot(cot)`` otherwise
(:func:`ddg_oracle.reference.exact.corner_angle`).  Such a multiple has a cotangent whose
radicand is 1, 2, 3 or 6, i.e. ``k G`` is a square for one of ``k = 1, 2, 3,
6``, i.e. the odd part of ``G`` is a square or 3 times one; residues exclude
that for almost every face of a float mesh (:func:`ddg_oracle.reference.cotangents._maybe_square`),
and those corners get a
:class:`~ddg_oracle.reference.cotangents.CotanSum` cotangent (canonical form on demand;
its hash, enclosures and sign come from the integers).  The other faces take
the definition's route: canonical cotangent, then ``corner_angle``.  A vertex all of
whose corners are of the first kind gets a :class:`CornerSum`: its corners as
integers, the dict of those CotanSums built only when something needs it (sign,
``float()`` and ``2 pi`` minus it do not).

Gauss-Bonnet.  The total curvature minus ``2 pi chi`` regroups face by face as
``sum_f (pi - angle sum of f) + (2 |V_int| + |V_bd| - F - 2 chi) pi`` (see
:func:`ddg_oracle.reference.curvature.gauss_bonnet_holds`).  A face's angles sum to pi
exactly when ``w = (c_0 + i)(c_1 + i)(c_2 + i)`` is a negative real: each
``arccot(c_k) = arg(c_k + i)`` lies in (0, pi), so the sum lies in (0, 3 pi)
and ``arg w`` is the sum modulo 2 pi.  With ``c_k = N_k / sqrt(G)``,

    Im w = 0  <=>  N_0 N_1 + N_1 N_2 + N_2 N_0 = G,
    Re w < 0  <=>  N_0 N_1 N_2 < G (N_0 + N_1 + N_2),

integer tests (the first is the identity ``cot a cot b + cot b cot c +
cot c cot a = 1`` of a triangle).  When every face passes, the decision is
the integer test; should one fail (impossible for a Euclidean triangle; it
would be a bug), :func:`gauss_bonnet_holds_fast` returns None and the
definition decides.  No float is used anywhere.
"""

from __future__ import annotations

from fractions import Fraction

from .cotangents import maybe_square, applies, face_data
from .exact import Angle, corner_angle
from .exact.angles import arccot_bounds

__all__ = ["applies", "angle_sums_fast", "corner_angles_fast", "gauss_bonnet_holds_fast",
           "CornerSum"]

_ZERO = Fraction(0)


def angle_sums_fast(surface) -> list[Angle]:
    """The sum of the corner angles at each vertex (the cone angle; 2 pi minus it is
    the angle defect of D2.2, pi minus it the turning angle of R2.4), exact Angles
    equal (``==``) to :func:`ddg_oracle.reference.curvature.angle_sums_from_corners` (see the
    module docstring).

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.curvature import angle_sums_from_corners
    >>> angle_sums_fast(surfaces.torus(5, 3)) == angle_sums_from_corners(surfaces.torus(5, 3))
    True
    """
    return _angle_sums(surface)


def _special(residue: int) -> bool:
    """Whether a face's corners may be multiples of pi / 24 (k G a square for k = 1, 2, 3
    or 6: odd part 1 or 3; see the module docstring): they take the definition's route."""
    return maybe_square(residue) or maybe_square(3 * residue)


def corner_angles_fast(surface) -> list[tuple[Angle, Angle, Angle]]:
    """The three corner angles of every face, equal (``==``) to
    :func:`ddg_oracle.reference.curvature.corner_angles` (D2.6): ``arccot`` of the lazy
    cotangent, or the definition's angle on a face whose corners may be multiples of
    pi / 24 (see the module docstring).

    >>> from ddg_oracle.reference import surfaces
    >>> from ddg_oracle.reference.exact import pi
    >>> corner_angles_fast(surfaces.cube())[0] == (pi / 4, pi / 2, pi / 4)
    True
    """
    fd = face_data(surface)
    N, residue, lazy, value = fd.N, fd.residue, fd.lazy, fd.value
    out = []
    for f in range(len(fd.G)):
        special = _special(residue[f])
        k = 3 * f  # inline halfedge(f, c): hot
        # corners 0, 1, 2 are opposite the halfedges 3f + 1, 3f + 2, 3f
        out.append(tuple(corner_angle(value((f, n))) if special or not n
                         else Angle._raw({lazy((f, n)): 1}, _ZERO)
                         for n in (2 * N[k + 1], 2 * N[k + 2], 2 * N[k])))
    return out


def _angle_sums(surface) -> list[Angle]:
    t = surface.triangulation
    fd = face_data(surface)
    N, residue = fd.N, fd.residue
    # per vertex the corners (f, n) with cot = n / (2 sqrt(G_f)), flat; the corners of faces
    # that may hold multiples of pi / 24 go the definition's way, into that vertex's dict
    raws: list[list] = [[] for _ in range(t.n_vertices)]
    defined: dict[int, dict] = {}
    pis = [_ZERO] * t.n_vertices
    for f, face in enumerate(t.faces):
        special = _special(residue[f])
        k = 3 * f  # inline halfedge(f, c): hot
        # corners 0, 1, 2 with the halfedges opposite them, 3f + 1, 3f + 2, 3f
        # (opposite_halfedge(f, c), written out: this loop runs over every corner)
        for v, h in zip(face, (k + 1, k + 2, k)):
            n = 2 * N[h]
            if special or not n:                    # maybe a multiple of pi / 24: as defined
                a = corner_angle(fd.value((f, n)))
                acc = defined.setdefault(v, {})
                for cot, m in a.parts.items():
                    acc[cot] = acc.get(cot, 0) + m
                pis[v] += a.pi_coefficient
            else:
                raws[v] += (f, n)
    out = []
    for v, (raw, q) in enumerate(zip(raws, pis)):
        if v not in defined:
            # the common case: parts left to the first use that needs them (one object per
            # vertex instead of one per corner, see CornerSum)
            out.append(CornerSum._of(fd, tuple(raw), 1, q))
            continue
        acc = defined[v]
        for i in range(0, len(raw), 2):
            cot = fd.lazy_slice(raw, i, i + 2)
            acc[cot] = acc.get(cot, 0) + 1
        out.append(Angle._raw({c: m for c, m in acc.items() if m}, q))
    return out


class CornerSum(Angle):
    """An :class:`~ddg_oracle.reference.exact.Angle` known as ``s sum_k arccot(n_k / (2
    sqrt(G_k))) + r pi`` (``s = 1`` or ``-1``): an angle sum of :func:`angle_sums_fast`, or
    ``2 pi`` or ``pi`` minus one (a defect, D2.2, or turning angle, R2.4), exact.

    ``_corners = (f1, n1, f2, n2, ...)`` are corners of a :class:`~ddg_oracle.reference.
    cotangents.FaceData` (``G_k = G[f_k]``, ``n_k != 0``).  It *is* an Angle: everything an
    Angle does works.  Its parts (``{cotangent: multiplicity}``, one
    :class:`~ddg_oracle.reference.cotangents.CotanSum` per distinct corner cotangent,
    equal ones merged: the definition's dict) are built on first use (``__getattr__``:
    the slot stays unset until then); the sign when no enclosure is needed, enclosures,
    ``float()``, ``hash()``, negation and adding a multiple of pi are computed from the
    integers without them.  Why: one object per vertex instead of one per corner, which
    the garbage collector would visit over and over on a large mesh.
    """

    __slots__ = ("_src", "_corners", "_s")

    @classmethod
    def _of(cls, src, corners: tuple, s: int, r) -> "CornerSum":
        a = object.__new__(cls)
        a._src, a._corners, a._s, a._pi, a._hash, a._enc = src, corners, s, r, None, None
        return a

    @staticmethod
    def _raw(parts, r):
        # what Angle's arithmetic builds from a CornerSum's parts is a plain Angle
        return Angle._raw(parts, r)

    def __getattr__(self, name):
        if name != "_parts":
            raise AttributeError(f"'CornerSum' object has no attribute {name!r}")
        lazy, raw, s = self._src.lazy_slice, self._corners, self._s
        parts: dict = {}
        for i in range(0, len(raw), 2):
            c = lazy(raw, i, i + 2)
            parts[c] = parts.get(c, 0) + s
        self._parts = parts
        return parts

    def __reduce__(self):
        # pickled as the plain Angle it equals (not with the whole mesh's FaceData)
        return (Angle._raw, (self._parts, self._pi))

    def _weight(self) -> int:
        return len(self._corners) >> 1

    def _one_signed(self) -> int:
        return self._s

    def _arccots_scaled(self, bits: int) -> tuple[int, int]:
        # the corner's CotanSum lives only for its bounds
        lazy, raw = self._src.lazy_slice, self._corners
        lo = hi = 0
        for i in range(0, len(raw), 2):
            a, b = arccot_bounds(lazy(raw, i, i + 2), bits)
            lo += a
            hi += b
        return (lo, hi) if self._s > 0 else (-hi, -lo)

    def __neg__(self):
        return CornerSum._of(self._src, self._corners, -self._s, -self._pi)

    def __add__(self, other):
        # a rational multiple of pi (or the number 0) keeps the form; an angle with parts
        # adds them (ArccotSum.__add__)
        o = self._coerce(other)
        if type(o) is Angle and not o._parts:
            if not o._pi:
                return self
            return CornerSum._of(self._src, self._corners, self._s, self._pi + o._pi)
        return Angle.__add__(self, other)

    __radd__ = __add__


def gauss_bonnet_holds_fast(surface) -> bool | None:
    """T2.6 / R2.4: whether ``total_curvature(surface) == 2 pi chi``, decided with
    integers (see the module docstring); None if a face's angle sum could not be
    shown to be pi this way (never for a Euclidean triangle; the caller then
    decides with the definition).  Equal to
    :func:`ddg_oracle.reference.curvature.gauss_bonnet_holds`.

    >>> from ddg_oracle.reference import surfaces
    >>> gauss_bonnet_holds_fast(surfaces.genus_surface(2))
    True
    """
    t = surface.triangulation
    fd = face_data(surface)
    N = fd.N
    # N[3f], N[3f + 1], N[3f + 2] are face f's N_2, N_0, N_1
    for G, n2, n0, n1 in zip(fd.G, N[0::3], N[1::3], N[2::3]):
        if n0 * n1 + n1 * n2 + n2 * n0 != G or n0 * n1 * n2 >= G * (n0 + n1 + n2):
            return None
    boundary = len(t.boundary_vertices())
    interior = t.n_vertices - boundary
    return 2 * interior + boundary - t.n_faces - 2 * t.euler_characteristic() == 0
