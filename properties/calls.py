"""The checked implementation, watched: each protocol call marked as the implementation's
time, each answer checked to be of its method's kind (:mod:`ddg_oracle.protocol.answers`:
no string, complex number or 2.5 for an integer) and copied (a binding may overwrite the
storage it answered in on its next call), mapped from the conventions it declares
onto the reference's (:mod:`.conventions`) and, where it must be a finite number,
screened for NaN and infinity.

The runner hands every property the implementation wrapped in :class:`Watched`:

- a clock that stops a call (the task's budget, the time limit per example) stops the
  implementation, so it is the implementation's hang, reported with its input, not a
  search that merely ran out of time (:func:`~.budget.calling`);
- an answer of a method whose exact value is always a finite real number (``numbers``:
  angles, defects, areas, area gradients, Dirichlet solutions; ``edges``: mean
  curvatures; ``intrinsic triangulation``: squared lengths) that holds a NaN or an
  infinity fails the property being checked, at its first such element, before the
  property compares anything: a NaN compares false with every bound, so a check written
  ``abs(x - y) > bound`` would let it through.  Matrices are screened by
  :func:`~.harness.implementation_matrix`, which also knows the faces whose float area a
  correct implementation cannot resolve.
"""

from __future__ import annotations

import numpy as np

from .arithmetic import implementations_arithmetic
from ..protocol.answers import MalformedAnswer, read, short
from ..protocol.budget import BudgetExceeded, calling
from ..protocol.methods import (METHODS, OutsideDomain, at_least_machine_epsilon,
                                implementation_name, machine_epsilon)
from .registry import PropertyFailure

__all__ = ["Watched", "first_non_finite", "raised_by_implementation"]

#: what a call lets through unmarked: a declined input, the task's own clock, an interrupt
_NOT_THE_IMPLEMENTATIONS = (OutsideDomain, BudgetExceeded, KeyboardInterrupt, SystemExit)


class ImplementationRaised(RuntimeError):
    """What the implementation raised, when it was an exception that takes no mark."""

    _ddg_raised_by_implementation = True


def raised_by_implementation(e: BaseException) -> bool:
    """Whether ``e`` came out of a call of the checked implementation (marked by
    :class:`Watched`): a crash of the implementation.  Anything else a property raises
    that is not a failure, a decline or a limit of the exact reference is a bug of
    ddg-oracle (an ``internal error``), never blamed on the implementation."""
    return getattr(e, "_ddg_raised_by_implementation", False)

#: answers whose exact value is always finite, screened here (matrices: harness)
SCREENED = ("numbers", "edges", "intrinsic triangulation")


class Watched:
    """``impl`` as the properties of ``property_id`` see it: the same attributes and
    protocol methods, each call marked and its answer screened (module docstring)."""

    def __init__(self, impl, property_id: str):
        from .conventions import declared
        self.__dict__.update(_impl=impl, _pid=property_id, name=implementation_name(impl),
                             _conventions=declared(impl))

    def __getattr__(self, attr: str):
        value = getattr(self._impl, attr)
        if attr not in METHODS or not callable(value):
            return value

        def call(*args):
            on_mesh = METHODS[attr].arguments[:2] == ("V", "F")
            rounding = self._rounding(args) if on_mesh else None
            # the input as given, for the conventions' maps and the report: an
            # implementation may work in place (the course's loader rescales V in place),
            # and a map computed from the rescaled V (radius 1) left a correct answer
            # unscaled, a failure reported the rescaled mesh
            given = _given(args) if on_mesh else None
            try:
                with calling(f"{self.name}.{attr}"), implementations_arithmetic():
                    answer = value(*args)
            except _NOT_THE_IMPLEMENTATIONS:
                raise
            except BaseException as e:
                if rounding is not None and rounding[1] and isinstance(e, Exception):
                    raise _unresolved(attr, "raised " + type(e).__name__) from e
                _mark(e)
                raise
            try:
                answer = read(attr, answer)
            except MalformedAnswer as e:
                # not of its kind (a string, 2.5 for an integer, complex numbers): read as
                # it is, it could pass (int(2.5) == 2) or crash our reading of it
                raise PropertyFailure(self._pid, self._impl, str(e), mesh=_mesh(given),
                                      expected=f"the contract's {METHODS[attr].kind}",
                                      observed=short(answer)) from None
            # a copy of our own: a binding may answer in storage it overwrites on its next
            # call, and a property comparing two answers (T2.5: before and after a motion)
            # then compared the second with itself, moved: a correct implementation failed
            answer = _own_copy(answer)
            if self._conventions and on_mesh:
                # the conventions it declares, mapped onto the reference's (.conventions)
                from .conventions import to_reference
                answer = to_reference(self._conventions, attr, answer, *(given or args[:2]))
            if rounding is not None:
                # an input it rounds itself (a rescaling): the bounds count that rounding
                at_least_machine_epsilon(rounding[0])
            found = first_non_finite(attr, answer)
            if found is not None and rounding is not None and rounding[1]:
                raise _unresolved(attr, f"answered {found[1]!r}")
            if found is not None:
                where, x = found
                mesh = _mesh(given)
                raise PropertyFailure(self._pid, self._impl,
                                      f"{attr} answered {x!r} where the exact value is a "
                                      "finite number", mesh=mesh, element=where,
                                      expected="a finite number", observed=x)
            return answer
        return call

    def _rounding(self, args):
        """(the bounds' epsilon on this call's input, whether its rounding may collapse an
        edge) if the implementation declares rounding its input itself
        (:func:`.conventions.bound_epsilon`, :func:`.conventions.rescaling_collapses`),
        else None."""
        from .conventions import bound_epsilon, rescaling_collapses
        if not any(c.rounds_input for c in self._conventions):
            return None
        e = machine_epsilon(self._impl)
        return (bound_epsilon(self._conventions, e, args[0], args[1]),
                rescaling_collapses(self._conventions, e, args[0], args[1]))


def _mark(e: BaseException) -> None:
    try:
        e._ddg_raised_by_implementation = True
    except AttributeError:         # an exception type without attributes
        raise ImplementationRaised(f"{type(e).__name__}: {e}") from e


def _unresolved(method: str, what: str) -> OutsideDomain:
    """A declined input: the implementation rounds its input itself (a declared rescaling)
    and that rounding may collapse an edge of this mesh (an edge below 2^-49 of the radius
    in float64: :func:`.conventions.rescaling_collapses`), so whatever it answers or raises
    judges nothing."""
    return OutsideDomain(f"{method} {what} on a mesh its own declared rescaling "
                         "(input_scale) cannot resolve: not judged")


def first_non_finite(method: str, answer):
    """(where, value) of the first NaN or infinity in ``answer`` of ``method`` (an index,
    an edge, or None for a single number), or None; None too for an answer of the wrong
    shape or type, which the property reports as such.

    >>> first_non_finite("angle_defects", [0.5, float("nan")])
    ((1,), nan)
    >>> first_non_finite("edge_mean_curvature", {(0, 1): 0.25, (1, 2): float("inf")})
    ((1, 2), inf)
    >>> first_non_finite("euler_characteristic", 2) is None
    True
    """
    kind = METHODS[method].kind
    if kind not in SCREENED:
        return None
    try:
        if kind == "edges":
            for edge, h in dict(answer).items():
                if not np.isfinite(float(h)):
                    return edge, float(h)
            return None
        if kind == "intrinsic triangulation":
            answer = answer[1]
        a = np.asarray(answer, dtype=np.float64)
    except (TypeError, ValueError, IndexError, KeyError):
        return None
    bad = np.argwhere(~np.isfinite(a))
    if not len(bad):
        return None
    where = tuple(int(i) for i in bad[0])
    return (where or None), float(a[where])


def _own_copy(answer):
    """``answer`` with nothing the implementation still holds: arrays, sparse matrices,
    dicts, lists and tuples copied (a dict of 170,000 edge values in 0.09 s, where a
    deep copy took 0.4 s); a number as it is."""
    if isinstance(answer, (int, float, bool, str, type(None))):
        return answer
    if isinstance(answer, np.ndarray) or hasattr(answer, "tocsr"):
        # a scipy sparse matrix's own copy copies its arrays (copy.copy shares them); before
        # the dict case: a dok_matrix is a dict too (and was copied into a plain one)
        return answer.copy()
    if isinstance(answer, dict):
        return {k: v if isinstance(v, (int, float)) else _own_copy(v) for k, v in answer.items()}
    if isinstance(answer, (list, tuple)):
        return type(answer)(_own_copy(x) for x in answer) if type(answer) in (list, tuple) \
            else list(map(_own_copy, answer))
    import copy
    try:
        return copy.deepcopy(answer)
    except Exception:  # noqa: BLE001  (an object that cannot be copied: read as it is)
        return answer


def _given(args):
    """A copy of the (V, F) of a call, as float and integer arrays (None if they are not)."""
    try:
        return np.array(args[0], dtype=np.float64), np.array(args[1], dtype=np.int64)
    except (TypeError, ValueError):
        return None


def _mesh(given):
    return None if given is None else (given[0].tolist(), given[1].tolist())
