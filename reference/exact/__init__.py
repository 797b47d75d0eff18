"""Exact numbers: rationals, square-root numbers (:class:`Surd`), angles (:class:`Angle`).

>>> from ddg_oracle.reference.exact import sqrt, pi
>>> sqrt(8) == 2 * sqrt(2)
True
"""

from .angles import Angle, corner_angle, direction_angle, pi
from .rationals import float_view, rational
from .surds import (Quotient, Surd, exact_sum, limits, rounded_sum, settings, sign, simplest,
                    sqrt)

__all__ = ["Angle", "Quotient", "Surd", "corner_angle", "direction_angle", "exact_sum", "float_view", "limits",
           "pi", "rational", "rounded_sum", "settings", "sign", "simplest", "sqrt"]
