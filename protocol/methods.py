"""The implementation protocol: what a checked implementation may provide.

An implementation is any object with some of the methods below.  Each takes
``V`` (float64 array, n x 3) and ``F`` (int array, m x 3) and answers in the
reference's conventions (docs/reference.md, "Conventions").  Adapters in ``oracles/``
translate libraries into these conventions; properties call only these names,
so they never mention a library.

An implementation declares what it has simply by defining the method; a
property that needs a method the implementation lacks is "not applicable".  Optional
attributes: ``name`` (reports), ``machine_epsilon`` (float32: 2**-23; the bounds scale
with it) and ``conventions`` (a library convention it follows instead of the
reference's: :func:`declared_conventions`).
"""

from __future__ import annotations

import contextlib
import contextvars
import math
import numbers
from dataclasses import dataclass


@dataclass(frozen=True)
class Method:
    """A protocol method: its one-line contract (what it answers, in the reference's
    conventions), its arguments, and the shape of its answer -- ``kind``: ``"integer"``,
    ``"boolean"``, ``"loops"`` (boundary cycles), ``"numbers"`` (a float array with one
    value per ``element``: ``"corner"`` (m, 3), ``"vertex"`` (n,), ``"vertex coordinate"``
    (n, 3), or the ``"total"``), ``"edges"`` ({(i, j): value}), ``"matrix"`` (n x n
    sparse), ``"flags"`` ((m, 3) bool, column c the edge opposite corner c),
    ``"intrinsic triangulation"`` ((F2, l2)) or ``"planar triangulation"`` ((m, 3)
    faces).  The executable protocol (encoding, schema) and the comparisons of
    ``compare`` and the test vectors read the shape from here; how closely an answer
    must match is declared beside the properties (``properties.registry.quantity``)."""

    contract: str
    kind: str
    element: str = ""
    arguments: tuple = ("V", "F")

    def __str__(self) -> str:
        return self.contract


KINDS = ("integer", "boolean", "loops", "numbers", "edges", "matrix", "flags",
         "intrinsic triangulation", "planar triangulation")
ELEMENTS = ("corner", "vertex", "vertex coordinate", "total")
#: where an element of a "numbers" answer is, by its ``element`` and its index (reports)
WHERE = {"corner": lambda k: f"face {k[0]}, corner {k[1]}",
         "vertex": lambda k: f"vertex {k[0]}",
         "vertex coordinate": lambda k: f"vertex {k[0]}, coordinate {k[1]}",
         "total": lambda k: "total"}

# name -> Method; the single source of the protocol's method names, contracts and shapes.
METHODS: dict[str, Method] = {
    # chapter 1: topology
    "euler_characteristic": Method("int: V - E + F of the surface (D1.6)", "integer"),
    "boundary_loops": Method(
        "list of boundary cycles, each a list of vertex indices in order",
        "loops"),
    "is_orientable": Method("bool: whether the surface is orientable", "boolean"),
    "genus": Method(
        "int: g of an orientable surface (chi = 2 - 2g - k); of a non-orientable one its "
        "number of crosscaps h (chi = 2 - h - k)",
        "integer"),
    # chapter 2: curvature (integrated values, never divided by an area)
    "corner_angles": Method(
        "(m, 3) float array: angle at corner c of face f, in (0, pi)",
        "numbers", element="corner"),
    "angle_defects": Method(
        "(n,) float array: 2 pi - angle sum at interior vertices, pi - angle sum (turning "
        "angle) at boundary vertices (D2.2, R2.4)",
        "numbers", element="vertex"),
    "edge_mean_curvature": Method(
        "dict {(i, j) with i < j: H(e) = 1/2 theta(e) l(e)} over interior edges, theta > "
        "0 where convex (D2.3); a regular mesh has one edge per pair",
        "edges"),
    "area": Method("float: total area", "numbers", element="total"),
    # chapter 3: Laplacians and mass matrices
    "cotan_laplacian": Method(
        "(n, n) scipy.sparse: (L f)(i) = sum_j nu(ij) (f(i) - f(j)), nu = 1/2 (cot a + "
        "cot b), boundary 1/2 cot a; positive semidefinite",
        "matrix"),
    "area_gradient": Method(
        "(n, 3) float array: the gradient of the total area with respect to each vertex "
        "position, grad_v A = (L V)(v) with L as cotan_laplacian (T3.9, L3.8): the "
        "integrated mean curvature normal, pointing where the area grows (outward at a "
        "convex vertex); zero at a vertex used by no face",
        "numbers", element="vertex coordinate"),
    "solve_dirichlet": Method(
        "solve_dirichlet(V, F, boundary, values): (n,) float array u with u[boundary] = "
        "values ((k,) int and (k,) float arrays; the indices distinct) and (L u)(i) = 0 at "
        "every other vertex, "
        "L as cotan_laplacian: the discrete Dirichlet problem (C3.4 / T3.5); every "
        "component of the mesh meets the boundary set",
        "numbers", element="vertex", arguments=("V", "F", "boundary", "values")),
    "vertex_areas_barycentric": Method(
        "(n,) float array: one third of the area of each incident face",
        "numbers", element="vertex"),
    "vertex_areas_voronoi": Method(
        "(n,) float array: mixed Voronoi areas (Meyer et al. 2003, obtuse-triangle rule)",
        "numbers", element="vertex"),
    # chapter 4: intrinsic Delaunay (per-face layouts: column c is the edge opposite corner c)
    "is_locally_delaunay": Method(
        "(m, 3) bool array: the edge opposite corner c of face f is Delaunay in the "
        "mesh's own metric, cot a + cot b >= 0; boundary edges True (D4.4)",
        "flags"),
    "intrinsic_delaunay_laplacian": Method(
        "(n, n) scipy.sparse: the cotan Laplacian (sign as cotan_laplacian) of an "
        "intrinsic Delaunay triangulation of the mesh's metric, same vertices: "
        "Laplace-Beltrami (D4.8)",
        "matrix"),
    "intrinsic_delaunay_triangulation": Method(
        "(F2, l2): (m, 3) int faces on the same vertices and (m, 3) float squared "
        "lengths, l2[f, c] the edge opposite corner c, of an intrinsic Delaunay "
        "triangulation of the same metric (A4.13); F2 may have loops and multi-edges",
        "intrinsic triangulation"),
    "planar_flip_to_delaunay": Method(
        "(m, 3) int faces: the straight-line triangulation F of the planar points V "
        "(every z = 0, faces counterclockwise) after flipping interior edges until all "
        "are Delaunay (A4.13, P4.4); same vertices, same boundary edges",
        "planar triangulation"),
    "planar_delaunay": Method(
        "planar_delaunay(P): (m, 3) int array, a Delaunay triangulation of the planar "
        "points P ((n, 2) float64), every point a vertex (T4.1, D4.1)",
        "planar triangulation", arguments=("P",)),
}


#: what a per-vertex method answers at a vertex used by no face (an "isolated" vertex, as in
#: an OBJ file with leftover vertices): the empty angle sum gives angle defect 2 pi (and
#: sum K = 2 pi chi keeps holding with chi = V - E + F counting the point), no face gives
#: it area, no edge gives it a Laplacian entry (its row and column of L are zero)
ISOLATED_VERTEX: dict[str, float] = {
    "angle_defects": math.tau,
    "vertex_areas_barycentric": 0.0,
    "vertex_areas_voronoi": 0.0,
    "area_gradient": 0.0,
}


FLOAT64_EPSILON = 2.0 ** -52
_epsilon = contextvars.ContextVar("ddg_machine_epsilon", default=FLOAT64_EPSILON)
_in_block = contextvars.ContextVar("ddg_in_epsilon_block", default=False)


def machine_epsilon(impl) -> float:
    """The implementation's declared ``machine_epsilon`` (float32: 2**-23), default float64;
    :class:`BadDeclaration` for a declaration :func:`checked_epsilon` refuses.

    Tolerances are derived from it: a library computing in float32 is held to
    float32 bounds, not float64 ones.
    """
    return checked_epsilon(getattr(impl, "machine_epsilon", FLOAT64_EPSILON),
                           implementation_name(impl))


#: the coarsest machine epsilon an implementation may declare: bfloat16's, the coarsest
#: binary floating-point format computed in; the bounds scale with it, and with 1.0 an
#: angle defect off by 3 radians passed D2.2
COARSEST_EPSILON = 2.0 ** -7


def checked_epsilon(value, who: str) -> float:
    """``value`` as a declared machine epsilon: a real number with 0 <= eps <= 2**-7 (0: an
    exact implementation), else :class:`BadDeclaration` naming ``who`` and the value.

    >>> checked_epsilon(2 ** -23, "f32") == 2 ** -23
    True
    >>> checked_epsilon(1.0, "mine")
    Traceback (most recent call last):
    ...
    ddg_oracle.protocol.methods.BadDeclaration: mine declares machine_epsilon 1.0: it must be a number from 0 (exact) to 2**-7 (bfloat16; float16 2**-10, float32 2**-23, float64 2**-52)
    """
    ok = isinstance(value, numbers.Real) and not isinstance(value, bool)
    e = float(value) if ok else math.nan
    if not 0 <= e <= COARSEST_EPSILON:
        raise BadDeclaration(f"{who} declares machine_epsilon {value!r}: it must be a number "
                             "from 0 (exact) to 2**-7 (bfloat16; float16 2**-10, float32 "
                             "2**-23, float64 2**-52)")
    return e


def eps() -> float:
    """Machine epsilon of the implementation whose property is being checked now."""
    return _epsilon.get()


@contextlib.contextmanager
def at_machine_epsilon(e: float):
    """Derive bounds for an implementation of machine epsilon ``e`` inside this block
    (:func:`eps`; the runner sets it per implementation, ``compare`` and the test vectors
    with this)."""
    token, inside = _epsilon.set(float(e)), _in_block.set(True)
    try:
        yield
    finally:
        _in_block.reset(inside)
        _epsilon.reset(token)


def at_least_machine_epsilon(e: float) -> None:
    """From now on, until the innermost :func:`at_machine_epsilon` block ends, derive bounds
    at ``e`` if it is coarser than the current epsilon (an implementation that rounds its
    own input: :func:`ddg_oracle.properties.conventions.bound_epsilon`).  Outside such a
    block nothing changes: the process's default stays float64's (a call outside a check
    once left every later bound of the process infinite)."""
    if _in_block.get() and not e <= _epsilon.get():
        _epsilon.set(float(e))


def declared_conventions(impl) -> tuple[str, str] | None:
    """(counterpart spec, what differs) if ``impl`` declares that it follows a library's
    convention instead of the reference's, else None.

    The declaration is the attribute ``conventions = {"follows": {id: what differs},
    "counterpart": spec}``: ``id`` names the documented difference (a finding of
    docs/findings.md, or the library's own reference), ``spec`` is what
    ``load_implementation`` loads for the same library on the reference's conventions
    (``"libigl"``, ``"mypkg.mod:MyLib"``, ``"exec:./driver"``).  ``ddg-oracle check
    --expect-conventions`` then reports a failure that the counterpart does not have on
    the same example as ``convention``.  An empty ``follows`` (or no attribute) declares
    nothing; a malformed declaration is :class:`NotAnImplementation`.

    >>> class Igl:
    ...     conventions = {"follows": {"F-libigl-2": "2 pi - angle sum at the boundary"},
    ...                    "counterpart": "libigl"}
    >>> declared_conventions(Igl())
    ('libigl', 'F-libigl-2 (2 pi - angle sum at the boundary)')
    >>> declared_conventions(object()) is None
    True
    """
    declared = getattr(impl, "conventions", None) or {}
    if isinstance(declared, str) or (isinstance(declared, dict) and "follows" not in declared):
        return None                    # a map of the vocabulary (properties.conventions)
    follows = declared.get("follows") if isinstance(declared, dict) else None
    if isinstance(declared, dict) and not follows:
        return None
    counterpart = declared.get("counterpart") if isinstance(declared, dict) else None
    if not (isinstance(follows, dict) and all(isinstance(k, str) and isinstance(v, str)
                                              for k, v in follows.items())
            and isinstance(counterpart, str) and counterpart.strip()):
        raise NotAnImplementation(
            f"{implementation_name(impl)}: conventions must be {{'follows': {{id: what "
            f"differs}}, 'counterpart': spec on the reference's conventions}}, got {declared!r}")
    return counterpart, "; ".join(f"{k} ({v})" for k, v in follows.items())


class OutsideDomain(ValueError):
    """Raised by an implementation for an input on which it has no value in the reference's
    convention (``RobustLaplacian()`` on a mesh with boundary: the library computes another
    operator there, and no mapping recovers the notes' one).  The runner does not check
    that example; if no example is inside the domain the property is "not applicable"."""


def capabilities(impl) -> frozenset[str]:
    """The protocol methods ``impl`` defines."""
    return frozenset(m for m in METHODS if callable(getattr(impl, m, None)))


def implementation_name(impl) -> str:
    """A display name: ``impl.name`` if set, else the class name."""
    return str(getattr(impl, "name", None) or type(impl).__name__)


#: Names other libraries give to protocol methods (libigl, gpytoolbox, trimesh, ...),
#: so that a near miss is answered with the protocol's name.
KNOWN_ALIASES: dict[str, str] = {
    "cotmatrix": "cotan_laplacian", "cotangent_laplacian": "cotan_laplacian",
    "laplacian": "cotan_laplacian", "massmatrix": "vertex_areas_voronoi",
    "mass_matrix": "vertex_areas_voronoi", "gaussian_curvature": "angle_defects",
    "angle_defect": "angle_defects", "vertex_defects": "angle_defects",
    "internal_angles": "corner_angles", "tip_angles": "corner_angles",
    "doublearea": "area", "boundary_loop": "boundary_loops", "boundary_loop_all": "boundary_loops",
    "euler": "euler_characteristic", "euler_number": "euler_characteristic",
    "intrinsic_delaunay_cotmatrix": "intrinsic_delaunay_laplacian",
    "delaunay": "planar_delaunay", "mean_curvature": "edge_mean_curvature",
    "mean_curvature_normal": "area_gradient", "area_grad": "area_gradient",
    "harmonic": "solve_dirichlet", "min_quad_with_fixed": "solve_dirichlet",
    "dirichlet": "solve_dirichlet",
}


class NotAnImplementation(TypeError):
    """An object given as an implementation that defines none of the protocol's methods:
    checking it would pass every property vacuously."""


class BadDeclaration(NotAnImplementation):
    """An implementation declaring what cannot be checked against (a machine epsilon of 1.0,
    NaN or -1): its bounds would let any answer pass, or none."""


def near_misses(impl) -> list[tuple[str, str]]:
    """(name ``impl`` has, protocol method it probably means), for its public callables
    that are not protocol methods but look like one.

    >>> class Typo:
    ...     def angle_defect(self, V, F): ...
    ...     def cotmatrix(self, V, F): ...
    >>> near_misses(Typo())
    [('angle_defect', 'angle_defects'), ('cotmatrix', 'cotan_laplacian')]
    """
    import difflib

    known = getattr(impl, "near_misses", None)
    if isinstance(known, (list, tuple)):          # found where the object lives (Isolated)
        return [tuple(x) for x in known]
    out = []
    for name in sorted(dir(impl)):
        if name.startswith("_") or name in METHODS or not _callable_attribute(impl, name):
            continue
        guess = KNOWN_ALIASES.get(name.lower()) or next(
            iter(difflib.get_close_matches(name.lower(), METHODS, n=1, cutoff=0.75)), None)
        if guess is not None and guess not in capabilities(impl):
            out.append((name, guess))
    return out


def _callable_attribute(impl, name: str) -> bool:
    """Whether ``impl.name`` is callable; False when reading it raises (a property of the
    user's that computes something: a hint must never stop a check)."""
    try:
        return callable(getattr(impl, name, None))
    except Exception:  # noqa: BLE001
        return False


def near_miss_warning(impl) -> str | None:
    """A one-line warning naming the public methods of ``impl`` that look like protocol
    methods it does not define (``cotmatrix`` beside ``angle_defects``): the properties
    that need them are not applicable, although the user meant them to run.  None if
    there are none.

    >>> class Half:
    ...     def angle_defects(self, V, F): ...
    ...     def cotmatrix(self, V, F): ...
    >>> near_miss_warning(Half())
    'Half: `cotmatrix` is not a protocol method (did you mean `cotan_laplacian`?); the properties that need it are not applicable'
    """
    misses = near_misses(impl)
    if not misses:
        return None
    names = ", ".join(f"`{n}` is not a protocol method (did you mean `{g}`?)" for n, g in misses)
    return (f"{implementation_name(impl)}: {names}; the properties that need "
            f"{'it' if len(misses) == 1 else 'them'} are not applicable")


def require_protocol(impl) -> frozenset[str]:
    """The protocol methods ``impl`` defines; :class:`NotAnImplementation` if none, naming
    the protocol's methods and the nearest names ``impl`` has.

    >>> class Typo:
    ...     def angle_defect(self, V, F): ...
    >>> require_protocol(Typo())
    Traceback (most recent call last):
    ...
    ddg_oracle.protocol.methods.NotAnImplementation: Typo defines none of the protocol's methods (did you mean `angle_defects` for `angle_defect`?); the methods are: euler_characteristic, boundary_loops, is_orientable, genus, corner_angles, angle_defects, edge_mean_curvature, area, cotan_laplacian, area_gradient, solve_dirichlet, vertex_areas_barycentric, vertex_areas_voronoi, is_locally_delaunay, intrinsic_delaunay_laplacian, intrinsic_delaunay_triangulation, planar_flip_to_delaunay, planar_delaunay (ddg_oracle.protocol.methods.METHODS)
    """
    caps = capabilities(impl)
    if caps:
        machine_epsilon(impl)               # BadDeclaration for one that cannot be checked
        return caps
    misses = near_misses(impl)
    hint = ""
    if misses:
        hint = " (did you mean " + ", ".join(f"`{g}` for `{n}`" for n, g in misses) + "?)"
    raise NotAnImplementation(
        f"{implementation_name(impl)} defines none of the protocol's methods{hint}; the "
        f"methods are: {', '.join(METHODS)} (ddg_oracle.protocol.methods.METHODS)")
