"""Typed errors for bad input and for guards of the exact arithmetic.

Every error names the problem and where it is (face index, vertex indices,
value), so a user reading one line knows what to fix.  All derive from
``ValueError`` (bad input) except :class:`ExactArithmeticLimit`, which is an
``ArithmeticError``: the input was fine, but the computation outgrew a guard.
"""

from __future__ import annotations


class DDGError(Exception):
    """Base class of every error raised on purpose by ddg-oracle."""


class InputError(DDGError, ValueError):
    """Bad input: the message says what and where."""


# --- numbers -----------------------------------------------------------------


class NonFiniteValue(InputError):
    """A NaN or an infinity where an exact number is required."""


class NotANumber(InputError, TypeError):
    """A value that is not an int, Fraction or float (e.g. a string or None)."""


# --- face lists (chapter 1) --------------------------------------------------


class EmptyMesh(InputError):
    """No faces (or no vertices) at all."""


class BadShape(InputError):
    """Faces are not rows of three indices, or positions are not rows of n >= 2."""


class NonIntegerIndex(InputError, TypeError):
    """A face entry is not an integer (a float, a bool, a NaN, a string)."""


class NegativeIndex(InputError, IndexError):
    """A face entry is negative."""


class IndexOutOfRange(InputError, IndexError):
    """A face entry is >= the number of vertices."""


class RepeatedVertexInFace(InputError):
    """A face lists the same vertex twice."""


class NonManifoldEdge(InputError):
    """Three or more faces share an edge (vertex pair)."""


class NonManifoldVertex(InputError):
    """The faces around a vertex form more than one fan."""


class UnreferencedVertex(InputError):
    """A vertex index below the vertex count that no face uses."""


class NotConnected(InputError):
    """An operation that needs a connected surface got several components."""


class NotFlippable(InputError):
    """An edge flip that is impossible (boundary edge, or both sides one face)."""


# --- geometry (chapters 2-4) -------------------------------------------------


class DegenerateFace(InputError):
    """A face of zero area where a quantity needs a positive one."""


class TriangleInequalityViolated(InputError):
    """Edge lengths of a face violate the strict triangle inequality."""


class ClockwiseFace(InputError):
    """A face of a planar triangulation that should run counterclockwise runs clockwise."""


# --- planar point sets and quadrilaterals (chapter 4) ---------------------------


class PointSetError(InputError):
    """A planar point set that has no triangulation with all its points as vertices."""


class TooFewPoints(PointSetError):
    """Fewer than three points: no triangle at all."""


class RepeatedPoint(PointSetError):
    """Two input points coincide (the message names both indices)."""


class CollinearPoints(PointSetError):
    """All points lie on one line: the convex hull has no interior."""


class BadQuadrilateral(InputError):
    """Four points that do not form the quadrilateral a statement needs (the
    message names the condition: convex, counterclockwise, or P2 and P4 on
    opposite sides of the diagonal P1 P3)."""


class BadInversion(InputError):
    """An inversion whose centre is one of the points, or whose squared radius is not positive."""


# --- guards of the exact arithmetic ------------------------------------------


class ExactArithmeticLimit(DDGError, ArithmeticError):
    """An exact computation outgrew a configured guard (term count, precision).

    The message says which limit and how to raise it.
    """


class TermLimitExceeded(ExactArithmeticLimit):
    """A square-root number would have more terms than ``exact.term_limit``."""


class TimeLimitExceeded(ExactArithmeticLimit):
    """One property example ran longer than its time limit.

    Raised by the guard of ``ddg_oracle.properties.profiles.example_time_limit`` (the
    reference itself never reads a clock); the message names the property and
    the setting to change (``DDG_EXAMPLE_TIME_LIMIT``).
    """


class BeyondFloatRange(ExactArithmeticLimit):
    """An exact value that a float view or bound needs lies beyond the float range (the
    cotangent of a needle's corner, say): it has no float to compare an answer with, so
    nothing is decided there.  Raised by the checks (``float()`` of an exact number raises
    ``OverflowError`` there, as ``float(Fraction)`` does)."""


class Undecidable(ExactArithmeticLimit):
    """An angle comparison that exact arithmetic cannot settle and enclosures
    did not separate up to the precision limit."""
