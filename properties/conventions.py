"""The conventions this field uses, as data: each one a name, the protocol methods it changes,
and the exact map of an answer in that convention onto the reference's.

Libraries and course code differ from the notes in a few well-known ways: libigl's
``cotmatrix`` is -L; CGAL and OpenMesh weigh an edge cot a + cot b, twice the notes'
1/2 (cot a + cot b); VTK's Gaussian curvature is the angle defect per a third of the
incident area; libigl, trimesh and VTK give 2 pi - angle sum at boundary vertices where the
notes' turning angle is pi - angle sum; trimesh's dihedral angles are unsigned; the DDG
course adds 1e-8 to the Laplacian's diagonal and rescales its input to unit radius; LaPy
answers for the referenced vertices only; mouette's vertex mass is the whole incident area.  An implementation that follows such a
convention declares it, in one line::

    class Mine:
        conventions = {"laplacian": "negative"}          # or a preset: conventions = "libigl"

and every property, ``compare`` and the test vectors then map its answers onto the
reference's convention (:func:`to_reference`, applied by
:class:`~ddg_oracle.properties.calls.Watched` to every call) before comparing.  A map
adds at most two roundings (a sign and a factor 2 none), far inside the derived bounds,
whose constants leave a margin of about 2 over the counted roundings (:mod:`.bounds`).
A pointwise curvature is multiplied back by a float vertex area (:attr:`Convention.divides_by`):
the library's own area and this one each carry an honest float error, within the vertex-area
bound of L3.7 and relative to the area unbounded on a needle; the angle defects' bounds add
both for such an implementation (:func:`.harness.widened`: the curvature properties, ``compare`` and
``verify --impl``).  Once they did not, and PyGEL3D failed D2.2 at 1.38 x the bound on a
needle tetrahedron where its curvature times its own mixed area is accurate.
Where an implementation declares nothing and fails, :func:`explaining` names the
conventions under which its answer agrees with the exact one: the report then says
"your cotan_laplacian is -L: declare conventions = {'laplacian': 'negative'}".

The older declaration ``{"follows": {...}, "counterpart": spec}``
(:func:`~.protocol.declared_conventions`, for ``--expect-conventions``) is another thing:
it names a finding and another implementation, not a map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["Convention", "VOCABULARY", "PRESETS", "declared", "to_reference", "explaining",
           "declaration_text", "pointwise_area", "bound_epsilon", "bounds_epsilon_of",
           "rescaling_collapses"]


@dataclass(frozen=True)
class Convention:
    """One value of one convention key: the methods it changes and the map of such an
    answer onto the reference's convention (``to_reference(method, answer, V, F)``)."""

    key: str
    value: object
    methods: tuple
    about: str
    to_reference: Callable = None
    #: a pointwise curvature: the vertex area (a protocol method's name) the map multiplies
    #: the answer back by, whose float error the angle defects' bounds must then add
    divides_by: str | None = None
    #: the implementation rounds its own input before computing (a rescaling): every
    #: bound on its answers counts that rounding (:func:`bound_epsilon`)
    rounds_input: bool = False

    @property
    def name(self) -> str:
        return f"{self.key}={self.value}"

    def applies(self, method: str) -> bool:
        return method in self.methods


# --- what the maps need from a mesh ------------------------------------------------------------


def _arrays(V, F):
    return np.asarray(V, dtype=np.float64), np.asarray(F, dtype=np.int64).reshape(-1, 3)


def boundary_vertices(F, n: int) -> np.ndarray:
    """(n,) bool: the vertices of edges of one face (whatever the faces' orientation)."""
    F = np.asarray(F, dtype=np.int64).reshape(-1, 3)
    e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    keys, counts = np.unique(e, axis=0, return_counts=True)
    out = np.zeros(n, dtype=bool)
    out[keys[counts == 1].ravel()] = True
    return out


def _face_areas(V, F):
    X = V[F]
    return 0.5 * np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)


def barycentric_areas(V, F) -> np.ndarray:
    V, F = _arrays(V, F)
    out = np.zeros(len(V))
    np.add.at(out, F.ravel(), np.repeat(_face_areas(V, F) / 3, 3))
    return out


def mixed_areas(V, F) -> np.ndarray:
    """Meyer et al.'s mixed Voronoi areas (the obtuse-triangle rule), in floats."""
    V, F = _arrays(V, F)
    out = np.zeros(len(V))
    area = _face_areas(V, F)
    X = V[F]
    for c in range(3):
        a, b = X[:, (c + 1) % 3] - X[:, c], X[:, (c + 2) % 3] - X[:, c]
        dot = (a * b).sum(axis=1)
        obtuse_here = dot < 0
        # the other corners: obtuse when their own dot is negative
        others = np.zeros(len(F), dtype=bool)
        for d in ((c + 1) % 3, (c + 2) % 3):
            p, q = X[:, (d + 1) % 3] - X[:, d], X[:, (d + 2) % 3] - X[:, d]
            others |= (p * q).sum(axis=1) < 0
        la2, lb2 = (a * a).sum(axis=1), (b * b).sum(axis=1)
        # Voronoi part: (|a|^2 cot(at b's far corner) + |b|^2 cot(...)) / 8
        cot_b = np.empty(len(F))
        cot_a = np.empty(len(F))
        for k, (d, w) in enumerate((((c + 2) % 3, a), ((c + 1) % 3, b))):
            p, q = X[:, (d + 1) % 3] - X[:, d], X[:, (d + 2) % 3] - X[:, d]
            cot = (p * q).sum(axis=1) / (2 * area)
            (cot_a if k == 0 else cot_b)[:] = cot
        voronoi = (la2 * cot_a + lb2 * cot_b) / 8
        part = np.where(obtuse_here, area / 2, np.where(others, area / 4, voronoi))
        np.add.at(out, F[:, c], part)
    return out


def _expand_used(answer, V, F, isolated_value):
    """An answer indexed by the referenced vertices only (LaPy's), put back on every vertex
    of V, with the protocol's value at the others; one with a row for every vertex of V
    already (a solution of the Dirichlet problem, whose values at a boundary vertex of no
    face only the call's arguments know) as it is."""
    V, F = _arrays(V, F)
    used = np.unique(F)
    import scipy.sparse as sp
    if sp.issparse(answer):
        A = sp.coo_matrix(answer)
        if A.shape == (len(V), len(V)):
            return answer
        return sp.csr_matrix((A.data, (used[A.row], used[A.col])), shape=(len(V), len(V)))
    a = np.asarray(answer, dtype=np.float64)
    if len(a) == len(V):
        return a
    out = np.full((len(V),) + a.shape[1:], isolated_value, dtype=np.float64)
    out[used] = a
    return out


def _renumbered_faces(answer, F):
    """A triangulation (F2, l2) whose faces number the used vertices of F in order, put
    back on the numbering of V (an index past them is left as it is: the property then
    reports it)."""
    F2, l2 = answer
    used = np.unique(np.asarray(F, dtype=np.int64))
    F2 = np.asarray(F2, dtype=np.int64)
    inside = (F2 >= 0) & (F2 < len(used))
    return np.where(inside, used[np.where(inside, F2, 0)], F2), l2


def _scale(V) -> float:
    """The factor the DDG course's loader scales a mesh by: centred at the mean of its
    positions, its farthest vertex at distance 1."""
    V = np.asarray(V, dtype=np.float64)
    r = float(np.max(np.linalg.norm(V - V.mean(axis=0), axis=1))) if len(V) else 1.0
    return 1.0 / r if r > 0 else 1.0


def _by_method(**maps):
    """A to_reference from {method: (answer, V, F) -> answer}."""
    def to_reference(method, answer, V, F):
        return maps[method](answer, V, F)
    return to_reference


_MATRICES = ("cotan_laplacian", "intrinsic_delaunay_laplacian")
_PER_VERTEX = ("angle_defects", "vertex_areas_barycentric", "vertex_areas_voronoi",
               "area_gradient", "solve_dirichlet")


def _shift(eps):
    import scipy.sparse as sp

    def unshift(A, V, F):
        A = sp.csr_matrix(A, dtype=np.float64)
        return A - eps * sp.identity(A.shape[0], format="csr")
    return unshift


def _vocabulary() -> dict:
    two = lambda a, V, F: a / 2                                  # noqa: E731  (exact)
    neg = lambda a, V, F: -a                                     # noqa: E731  (exact)
    from ..protocol.methods import ISOLATED_VERTEX, OutsideDomain

    def unused(method):
        return lambda a, V, F: _expand_used(a, V, F, ISOLATED_VERTEX.get(method, 0.0))

    def at_boundary(delta):
        def f(K, V, F):
            K = np.asarray(K, dtype=np.float64).copy()
            K[boundary_vertices(F, len(K))] += delta
            return K
        return f

    def per(areas):
        def f(K, V, F):
            A = areas(V, F)
            used = np.zeros(len(A), dtype=bool)
            used[np.asarray(F, dtype=np.int64).ravel()] = True
            flat = np.flatnonzero(used & (A == 0))
            if len(flat):
                # K / 0 carries no angle defect back: no value on this mesh, not a failure
                raise OutsideDomain(f"pointwise curvature at vertex {int(flat[0])}, whose faces "
                                    "have no area: the angle defect cannot be recovered")
            with np.errstate(invalid="ignore"):    # inf * 0 at unused vertices: replaced
                out = np.asarray(K, dtype=np.float64) * A
            out[~used] = ISOLATED_VERTEX["angle_defects"]   # no faces: no pointwise value
            return out
        return f

    def scaled(power):
        return lambda a, V, F: np.asarray(a, dtype=np.float64) / _scale(V) ** power \
            if not hasattr(a, "tocsr") else a / _scale(V) ** power
    def per_edge(H, V):
        s = _scale(V)               # once per answer: per edge it made the map O(E V)
        return {e: h / s for e, h in dict(H).items()}
    entries = [
        Convention("laplacian", "negative", _MATRICES,
                   "the matrix is -L, negative semidefinite (libigl's cotmatrix; gpytoolbox's "
                   "cotangent_laplacian is positive, as the reference)",
                   _by_method(cotan_laplacian=neg, intrinsic_delaunay_laplacian=neg)),
        Convention("weights", "full", _MATRICES + ("area_gradient",),
                   "an edge weighs cot a + cot b, twice the notes' 1/2 (cot a + cot b) "
                   "(CGAL, OpenMesh)",
                   _by_method(cotan_laplacian=two, intrinsic_delaunay_laplacian=two,
                              area_gradient=two)),
        Convention("boundary_defect", "two_pi", ("angle_defects",),
                   "2 pi - angle sum at boundary vertices too, where the notes' turning angle "
                   "is pi - angle sum (libigl, trimesh, VTK)",
                   _by_method(angle_defects=at_boundary(-np.pi))),
        Convention("curvature", "per_barycentric_area", ("angle_defects",),
                   "pointwise: the angle defect divided by the vertex's barycentric area "
                   "(a third of the incident faces' area; VTK's Gaussian curvature)",
                   _by_method(angle_defects=per(barycentric_areas)),
                   divides_by="vertex_areas_barycentric"),
        Convention("curvature", "per_mixed_area", ("angle_defects",),
                   "pointwise: the angle defect divided by the vertex's mixed Voronoi area "
                   "(Meyer et al.; PyGEL3D's and many papers' Gaussian curvature)",
                   _by_method(angle_defects=per(mixed_areas)),
                   divides_by="vertex_areas_voronoi"),
        Convention("dihedral", "negative", ("edge_mean_curvature",),
                   "theta > 0 where concave (the normals compared the other way round)",
                   lambda method, H, V, F: {e: -h for e, h in dict(H).items()}),
        Convention("input_scale", "unit_radius", ("area", "vertex_areas_barycentric",
                                                   "vertex_areas_voronoi", "area_gradient",
                                                   "edge_mean_curvature"),
                   "the input is first centred and scaled to unit radius (the DDG course's "
                   "loader): areas come out times s^2, lengths times s",
                   lambda method, a, V, F: (
                       per_edge(a, V) if method == "edge_mean_curvature" else
                       scaled(1 if method == "area_gradient" else 2)(a, V, F)),
                   rounds_input=True),
        Convention("unused_vertices", "dropped", _MATRICES + _PER_VERTEX
                   + ("euler_characteristic", "intrinsic_delaunay_triangulation"),
                   "answers only for the vertices some face uses, renumbered in order; "
                   "chi counts those only (LaPy's TriaMesh)",
                   lambda method, a, V, F: (
                       int(a) + len(_arrays(V, F)[0]) - len(np.unique(_arrays(V, F)[1]))
                       if method == "euler_characteristic" else
                       _renumbered_faces(a, F) if method == "intrinsic_delaunay_triangulation"
                       else unused(method)(a, V, F))),
        Convention("mass", "whole_area", ("vertex_areas_barycentric",),
                   "a vertex gets the whole area of each incident face, three times the "
                   "barycentric area (mouette's area_weight_matrix)",
                   lambda method, a, V, F: np.asarray(a, dtype=np.float64) / 3),
    ]
    out: dict = {}
    for c in entries:
        out.setdefault(c.key, {})[c.value] = c
    return out


#: {key: {value: Convention}}: the vocabulary (the reference's own values are absent)
VOCABULARY = _vocabulary()
#: {key: what the reference does}, for messages
REFERENCE = {"laplacian": "positive (L positive semidefinite)",
             "weights": "half (1/2 (cot a + cot b))",
             "boundary_defect": "turning (pi - angle sum at boundary vertices)",
             "curvature": "integrated (the angle defect itself)",
             "dihedral": "signed (theta > 0 where convex)",
             "input_scale": "none (the input as given)",
             "unused_vertices": "kept (a value for every row of V; chi counts every vertex)",
             "mass": "barycentric (a third of each incident face's area)",
             "regularization": "none (no diagonal shift)"}

#: the conventions of libraries and courses, by name (each documented in docs/conventions.md)
PRESETS = {
    "libigl": {"laplacian": "negative", "boundary_defect": "two_pi"},
    "cgal": {"weights": "full"},
    "openmesh": {"weights": "full"},
    "trimesh": {"boundary_defect": "two_pi"},
    "vtk": {"boundary_defect": "two_pi", "curvature": "per_barycentric_area"},
    "lapy": {"unused_vertices": "dropped"},
    "mouette": {"mass": "whole_area"},
    "meshlib": {"weights": "full", "boundary_defect": "two_pi"},
    "ddg-course": {"regularization": 1e-8},
}


def _regularization(eps) -> Convention:
    return Convention("regularization", eps, _MATRICES,
                      f"{eps:g} added to every diagonal entry (the DDG course's shift, which "
                      "makes L invertible)",
                      _by_method(cotan_laplacian=_shift(eps),
                                 intrinsic_delaunay_laplacian=_shift(eps)))


def parse(declaration) -> tuple[Convention, ...]:
    """The conventions of a declaration: a preset's name, or {key: value} (``"preset"``:
    a preset to start from); ValueError naming what is wrong.

    >>> [c.name for c in parse("libigl")]
    ['laplacian=negative', 'boundary_defect=two_pi']
    >>> [c.name for c in parse({"preset": "ddg-course", "input_scale": "unit_radius"})]
    ['regularization=1e-08', 'input_scale=unit_radius']
    """
    if isinstance(declaration, str):
        if declaration not in PRESETS:
            raise ValueError(f"conventions: no preset {declaration!r}; presets: "
                             f"{', '.join(PRESETS)}")
        declaration = dict(PRESETS[declaration])
    if not isinstance(declaration, dict):
        raise ValueError(f"conventions must be a preset name or {{key: value}}, got "
                         f"{declaration!r}")
    d = dict(declaration)
    preset = d.pop("preset", None)
    if preset is not None:
        if not isinstance(preset, str):
            raise ValueError(f"conventions: preset must be a preset's name, got {preset!r}")
        d = {**parse_dict(preset), **d}
    out = []
    for key, value in d.items():
        if key == "regularization":
            if not isinstance(value, (int, float)) or isinstance(value, bool) or \
                    not 0 < value < 1:
                raise ValueError(f"conventions: regularization must be a small positive "
                                 f"number (the diagonal shift), got {value!r}")
            out.append(_regularization(float(value)))
            continue
        if not isinstance(key, str) or key not in VOCABULARY:
            raise ValueError(f"conventions: no convention {key!r}; the keys: "
                             f"{', '.join(list(VOCABULARY) + ['regularization'])}")
        if not isinstance(value, str) or value not in VOCABULARY[key]:      # ["x"]: no name
            raise ValueError(f"conventions: {key} is one of {', '.join(map(str, VOCABULARY[key]))} "
                             f"(the reference's: {REFERENCE[key]}), got {value!r}")
        out.append(VOCABULARY[key][value])
    return tuple(out)


def parse_dict(preset: str) -> dict:
    if preset not in PRESETS:
        raise ValueError(f"conventions: no preset {preset!r}; presets: {', '.join(PRESETS)}")
    return dict(PRESETS[preset])


def declared(impl) -> tuple[Convention, ...]:
    """The conventions ``impl`` declares in its ``conventions`` attribute (none: ()); the
    older ``{"follows", "counterpart"}`` form declares none of these."""
    value = getattr(impl, "conventions", None)
    if not value or (isinstance(value, dict) and "follows" in value):
        return ()
    return parse(value)


def pointwise_area(conventions) -> str | None:
    """The vertex area (protocol method name) a declared pointwise curvature is multiplied
    back by, or None for an integrated one.

    >>> pointwise_area(parse("vtk")), pointwise_area(parse("libigl"))
    ('vertex_areas_barycentric', None)
    """
    return next((c.divides_by for c in conventions if c.divides_by), None)


#: how much wider than the rounding it counts :func:`bound_epsilon` makes the bounds
ROUNDING_MARGIN = 2.0


def bound_epsilon(conventions, e: float, V, F) -> float:
    """The machine epsilon the bounds use for an implementation of machine epsilon ``e``
    declaring ``conventions``, called on (V, F): ``e``, unless a declared convention rounds
    the input before the implementation computes (:attr:`Convention.rounds_input`).

    The DDG course's loader (``input_scale = unit_radius``) centres the points at their
    mean and divides them by the largest distance r from it: two roundings of every
    coordinate, which move a vertex by delta <= e |x - c~| (relative to the exact point
    after an exact rescaling; c~ the float centre).  With c~ any point of the input's hull
    (the mean, a bounding box's centre) off by the float mean's error (<= gamma_n max |x|
    per coordinate), |x - c~| <= rho = 2 r + sqrt(3) n e max |x|, r taken over every row
    of V (the loader sees the unused vertices too).  Each edge vector of a face then
    carries a further relative error 2 delta / l_min (l_min: the shortest edge of any
    face): far more than the bounds' own count where a point far from a small mesh sets
    the radius (a 4e-9 edge with a point at distance 1 failed at 3e4 x the float64
    bound).  Every bound of :mod:`.bounds` is derived for edge vectors (or side lengths)
    with relative errors of a few units u = e / 2 and grows linearly with that count, so
    4 rho / l_min units more, with a margin of :data:`ROUNDING_MARGIN`, cover the
    rounding.  The radius itself is off by eta <= 3 e + sqrt(3) n e max |x| / r, which
    scales an area by 1 + 2 eta, a length by 1 + eta; every bound on a quantity that
    scales has a term of at least e' |value| (the area gradient's; the areas' are 16 e'
    |value|), so e' >= eta covers it, and twice that keeps the margin.  Together:

        e' = e (1 + ROUNDING_MARGIN 4 rho / l_min) + ROUNDING_MARGIN eta

    Where e' exceeds 2^-7 (the coarsest machine epsilon there is) or an edge has no
    length: infinite (the bounds then judge nothing, and the runner says so).  An exact
    implementation (e = 0) rescales exactly.  The scale must be the declared one (the
    radius about the mean): a centre anywhere in the hull is covered only in the rounding
    it causes.  One epsilon per mesh: the shortest edge anywhere sets it for every
    element, so on a real scan (bunny10k: 3.1e4 x float64's) the bounds of an
    implementation declaring a rescaling are far wider than its rounding of most faces.

    >>> V, F = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]
    >>> bound_epsilon(parse("libigl"), 2.0 ** -52, V, F) == 2.0 ** -52
    True
    >>> small = bound_epsilon(parse({"input_scale": "unit_radius"}), 2.0 ** -52, V, F)
    >>> far = bound_epsilon(parse({"input_scale": "unit_radius"}), 2.0 ** -52, V + [[1e3, 0, 0]], F)
    >>> 2.0 ** -52 < small < 50 * 2.0 ** -52 < 1e4 * 2.0 ** -52 < far
    True
    """
    if e == 0 or not any(c.rounds_input for c in conventions):
        return e
    rho, eta, l_min = _rescaling(e, V, F)
    from ..protocol.methods import COARSEST_EPSILON
    with np.errstate(all="ignore"):
        wider = e * (1 + ROUNDING_MARGIN * 4 * rho / l_min) + ROUNDING_MARGIN * eta \
            if l_min > 0 else math.inf
    return wider if math.isfinite(wider) and wider <= COARSEST_EPSILON else math.inf


def bounds_epsilon_of(impl, mesh) -> float:
    """The epsilon of ``impl``'s bounds on ``mesh`` ((V, F), or a function giving it, called
    only if needed): its declared machine epsilon, coarser where it declares rounding its
    own input (:func:`bound_epsilon`)."""
    from ..protocol.methods import machine_epsilon
    e, conventions = machine_epsilon(impl), declared(impl)
    if not any(c.rounds_input for c in conventions):
        return e
    return bound_epsilon(conventions, e, *(mesh() if callable(mesh) else mesh))


def rescaling_collapses(conventions, e: float, V, F) -> bool:
    """Whether a declared rescaling (:func:`bound_epsilon`) may collapse an edge of (V, F):
    it moves each vertex by up to e rho, so an edge of length l_min <= 4 e rho may come out
    of zero length or reversed (a 1e-17 tetrahedron beside a point at distance 1, in
    float64).  There whatever the implementation answers or raises judges nothing: the
    example is declined.  Short of that the rescaled mesh keeps some bits of every edge,
    and a crash or a NaN is the implementation's (float32: edges down to 2^-20 of the
    radius; the decline once began at 2^-12, where a crash was hidden as "not applicable").

    >>> tiny = [[0, 0, 0], [1e-17, 0, 0], [0, 1e-17, 0], [1, 1, 1]]
    >>> ur = parse({"input_scale": "unit_radius"})
    >>> rescaling_collapses(ur, 2.0 ** -52, tiny, [[0, 1, 2]]), rescaling_collapses(ur, 2.0 ** -23, [[0, 0, 0], [1e-4, 0, 0], [0, 1e-4, 0], [1, 1, 1]], [[0, 1, 2]])
    (True, False)
    """
    if e == 0 or not any(c.rounds_input for c in conventions):
        return False
    rho, _, l_min = _rescaling(e, V, F)
    return not l_min > 4 * e * rho


def _rescaling(e: float, V, F) -> tuple[float, float, float]:
    """(rho, eta, l_min) of :func:`bound_epsilon` on (V, F) (l_min infinite without faces)."""
    V, F = _arrays(V, F)
    if not len(F) or not len(V):
        return 0.0, 0.0, math.inf
    with np.errstate(all="ignore"):
        r = float(np.max(np.linalg.norm(V - V.mean(axis=0), axis=1)))
        off = math.sqrt(3) * len(V) * e * float(np.max(np.abs(V)))   # the float mean's error
        eta = 3 * e + off / r if r > 0 else math.inf
        X = V[F]
        l_min = float(min(np.linalg.norm(X[:, (c + 1) % 3] - X[:, c], axis=1).min()
                          for c in range(3)))
    return 2 * r + off, eta, l_min


def to_reference(conventions, method: str, answer, V, F):
    """``answer`` of ``method`` mapped onto the reference's convention through every
    declared convention that changes it (in the order declared)."""
    for c in conventions:
        if c.applies(method):
            answer = c.to_reference(method, answer, V, F)
    return answer


def candidates(method: str, declared_ones=()) -> list[Convention]:
    """The conventions of the vocabulary (and a 1e-8 shift) that change ``method`` and are
    not declared already: what :func:`explaining` tries."""
    keys = {c.key for c in declared_ones}
    out = [c for values in VOCABULARY.values() for c in values.values()
           if c.applies(method) and c.key not in keys]
    if method in _MATRICES and "regularization" not in keys:
        out.append(_regularization(1e-8))
    return out


def explaining(method: str, answer, V, F, agrees, declared_ones=()) -> list[Convention]:
    """The conventions under which ``answer`` agrees with the exact one (``agrees(mapped)``
    says whether a mapped answer does), one at a time."""
    out = []
    for c in candidates(method, declared_ones):
        try:
            mapped = to_reference((c,), method, answer, V, F)
        except Exception:  # noqa: BLE001  (a map that does not fit this answer: not it)
            continue
        try:
            if agrees(mapped):
                out.append(c)
        except Exception:  # noqa: BLE001
            continue
    return out


def declaration_text(conventions) -> str:
    """How to declare these conventions, as Python: always the explicit {key: value} (a
    preset may declare more than the one convention seen at work)."""
    return f"conventions = { {c.key: c.value for c in conventions}!r}"
