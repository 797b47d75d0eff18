"""What an answer of a protocol method must be made of, before anything reads it.

Each method's contract names its answer's kind (:class:`~.methods.Method`): an integer,
a bool, boundary loops of vertex indices, real numbers (arrays, a total, edge values),
a matrix, flags, triangulations.  :func:`problem` says, in one line, why an answer is
not of its kind (None when it is): a string, a complex number, an array of objects that
are not numbers, 2.5 for an integer, ``"True"`` for a bool.  Every answer of a checked
implementation passes through it first (``properties.calls.Watched``, ``compare``, ``verify``
and the executable protocol's decoder, ``oracles.executable.decode_value``), so
that reading it can neither let a wrong value through (``int(2.5) == 2``, ``bool("False")``,
``float("0.5")``, ``np.asarray(complex, float)`` dropping the imaginary part) nor crash
ddg-oracle's own code (``int(np.array([2, 7]))``): such an answer is the
implementation's failure, said as such.

Only the kind of each element is checked here, not the shape (the checks and ``compare``
say which shape was expected); numbers may be any real numbers: Python and numpy ints
and floats of any width, ``Fraction``.  An integer may come as an integral float
(``2.0``), a bool as 0 or 1, a single number as an array of one element;
:func:`normalized` gives them as Python's ``int``, ``bool`` and number.

>>> problem("euler_characteristic", 2), problem("euler_characteristic", 2.0)
(None, None)
>>> problem("euler_characteristic", 2.5)
'euler_characteristic answered 2.5 (float), not an integer'
>>> problem("is_orientable", "False")
"is_orientable answered 'False' (str), not a bool"
>>> problem("angle_defects", [0.5, 1j])
'angle_defects answered complex numbers, not real numbers'
>>> problem("boundary_loops", [[0, 1, 2]]), problem("boundary_loops", [["0", "1", "2"]])
(None, "boundary_loops answered a loop holding '0' (str), not a vertex index")
"""

from __future__ import annotations

import numbers

import numpy as np

from .methods import METHODS

__all__ = ["MalformedAnswer", "indices_problem", "normalized", "problem", "read",
           "reals_problem", "short"]


class MalformedAnswer(ValueError):
    """An answer not of its method's kind (the message: :func:`problem`'s line)."""


def short(x) -> str:
    """``repr(x)`` in at most 60 characters (an answer's own ``__repr__`` may raise)."""
    try:
        text = repr(x)
    except Exception:  # noqa: BLE001  (an answer's own __repr__ that raises)
        text = f"<{type(x).__name__}>"
    return text if len(text) <= 60 else text[:57] + "..."


def _what(x) -> str:
    return f"{short(x)} ({type(x).__name__})"


def _is_real(x) -> bool:
    """A real number, not a bool (True is an int to Python, never an answer's number): a
    ``numbers.Real`` (ints, floats, Fractions, numpy's, gmpy2's, SymPy's), or another
    number type that converts itself with ``__float__`` (Decimal, mpmath's mpf); never a
    complex number (numpy's would drop its imaginary part) nor a string."""
    if isinstance(x, (bool, np.bool_, str, bytes, complex, np.complexfloating, np.ndarray)):
        return False
    return isinstance(x, numbers.Real) or hasattr(type(x), "__float__")


def _integral(x) -> bool:
    if isinstance(x, numbers.Integral):
        return not isinstance(x, (bool, np.bool_))
    try:
        return _is_real(x) and float(x).is_integer()
    except (OverflowError, ValueError):
        return False


def _scalar(x):
    """A 0-dimensional or one-element numpy array as its element (``np.sum`` of a shape-(1,)
    array, a library's ``array(2)``), as is any array numpy reads (``__array__``: a torch
    or JAX tensor of one element); anything else unchanged."""
    if not isinstance(x, (np.ndarray, numbers.Number, str, bytes)) and hasattr(x, "__array__"):
        try:
            x = np.asarray(x)
        except Exception:  # noqa: BLE001  (not readable as an array: judged as it is)
            return x
    if isinstance(x, np.ndarray) and x.size == 1:
        return x.reshape(()).item() if x.dtype.kind != "O" else x.reshape(())[()]
    return x


def _array(method: str, answer):
    """(``answer`` as a numpy array, None), or (None, why numpy cannot read it)."""
    try:
        return np.asarray(answer), None
    except (TypeError, ValueError) as e:
        return None, f"{method} answered something numpy cannot read as an array ({e})"


def _first(a: np.ndarray, ok):
    """The first element of ``a`` (an object array) that is not ``ok``, or None."""
    return next((x for x in a.reshape(-1) if not ok(x)), None)


def reals_problem(method: str, answer, what: str = "real numbers") -> str | None:
    """Why ``answer`` (an array or nested sequences) is not made of real numbers, or None."""
    a, why = _array(method, answer)
    if why:
        return why
    kind = a.dtype.kind
    if kind == "c":
        return f"{method} answered complex numbers, not {what}"
    if kind in "US":
        return f"{method} answered strings, not {what}"
    if kind == "b":
        return f"{method} answered bools, not {what}"
    if kind == "O":
        bad = _first(a, _is_real)
        if bad is not None:
            return f"{method} answered an array holding {_what(bad)}, not {what}"
    elif kind not in "iuf":
        return f"{method} answered an array of {a.dtype}, not {what}"
    return None


def indices_problem(method: str, answer, what: str = "a vertex index") -> str | None:
    """Why ``answer`` (an array of indices) is not made of integers, or None."""
    a, why = _array(method, answer)
    if why or a.dtype.kind in "iu":
        return why
    if a.dtype.kind == "O":
        bad = _first(a, _integral)
        return None if bad is None else f"{method} answered {_what(bad)}, not {what}"
    if a.dtype.kind == "f":
        # integral floats, as numpy reads [[0, 1, 2.0]] (an empty list reads as float64)
        bad = a[~(np.isfinite(a) & (a == np.round(a)))]
        return None if not bad.size else \
            f"{method} answered {float(bad[0])!r} in an array of {a.dtype}, not {what}"
    return f"{method} answered an array of {a.dtype}, not of {what}s"


def problem(method: str, answer) -> str | None:
    """Why ``answer`` is not of the kind of ``method``'s answer (one line), or None.  An
    answer whose own code raises while it is read (its ``__len__``, ``__iter__``,
    ``__array__``...) is not of its kind either."""
    try:
        return _problem(method, answer)
    except Exception as e:  # noqa: BLE001  (the implementation's object raised)
        return f"{method} answered a {type(answer).__name__} that raised {type(e).__name__} " \
               f"when read: {short(str(e))}"


def _problem(method: str, answer) -> str | None:
    spec = METHODS[method]
    kind = spec.kind
    if kind == "integer":
        x = _scalar(answer)
        return None if _integral(x) else f"{method} answered {_what(x)}, not an integer"
    if kind == "boolean":
        x = _scalar(answer)
        if isinstance(x, (bool, np.bool_)) or (isinstance(x, numbers.Integral) and x in (0, 1)):
            return None
        return f"{method} answered {_what(x)}, not a bool"
    if kind == "numbers" and spec.element == "total":
        x = _scalar(answer)
        return None if _is_real(x) else f"{method} answered {_what(x)}, not a real number"
    if kind == "numbers":
        return reals_problem(method, answer)
    if kind == "loops":
        if isinstance(answer, (str, bytes)) or not _iterable(answer):
            return f"{method} answered {_what(answer)}, not a list of loops"
        for loop in answer:
            if isinstance(loop, (str, bytes)) or not _iterable(loop):
                return f"{method} answered a loop {_what(loop)}, not a list of vertex indices"
            for v in loop:
                if not _integral(v):        # 3 or 3.0 (a float array's list), not 3.4
                    return f"{method} answered a loop holding {_what(v)}, not a vertex index"
        return None
    if kind == "edges":
        if not hasattr(answer, "items"):
            return f"{method} answered {_what(answer)}, not a dict {{(i, j): value}}"
        if _plain_edges(answer):
            return None
        for key, value in answer.items():
            if not (isinstance(key, tuple) and len(key) == 2 and all(_integral(i) for i in key)):
                return f"{method} answered the key {_what(key)}, not a pair of vertex indices"
            if not _is_real(_scalar(value)):
                return f"{method} answered {_what(value)} at edge {key}, not a real number"
        return None
    if kind == "matrix":
        import scipy.sparse as sp
        if sp.issparse(answer):
            return None if answer.dtype.kind in "iuf" else \
                f"{method} answered a sparse matrix of {answer.dtype}, not of real numbers"
        return reals_problem(method, answer)
    if kind == "flags":
        a, why = _array(method, answer)
        if why:
            return why
        if a.dtype.kind == "b" or (a.dtype.kind in "iu" and np.all((a == 0) | (a == 1))):
            return None
        return f"{method} answered an array of {a.dtype}, not of bools"
    if kind == "intrinsic triangulation":
        if isinstance(answer, (str, bytes)) or not _iterable(answer) or len(answer) != 2:
            return f"{method} answered {_what(answer)}, not a pair (F2, l2)"
        F2, l2 = answer
        return indices_problem(method, F2, "a vertex index") or reals_problem(method, l2)
    return indices_problem(method, answer, "a vertex index")          # a planar triangulation


def read(method: str, answer):
    """``answer`` as :func:`normalized` gives it, or :class:`MalformedAnswer` saying why it
    is not of its method's kind.

    >>> read("genus", np.int64(1))
    1
    >>> read("genus", "1")
    Traceback (most recent call last):
    ...
    ddg_oracle.protocol.answers.MalformedAnswer: genus answered '1' (str), not an integer
    """
    why = problem(method, answer)
    if why is not None:
        raise MalformedAnswer(why)
    return normalized(method, answer)


def normalized(method: str, answer):
    """An answer without a :func:`problem`, in the forms the checks read: a single value as
    Python's ``int`` (integer kinds), ``bool`` (boolean kinds) or number (a total); arrays
    (numbers, flags, faces; a matrix not sparse) as numpy arrays, their dtype kept (a list
    of Fractions stays exact); loops as lists of Python ints; edge values as numbers (an
    array of one element is its element).  A declared convention's map negates, halves or
    scales these (``-answer`` of a list raised inside ddg-oracle).

    >>> normalized("euler_characteristic", np.float64(2.0)), normalized("is_orientable", 1)
    (2, True)
    >>> normalized("angle_defects", [0.5, 1.0]), normalized("boundary_loops", [(0, 1.0, 2)])
    (array([0.5, 1. ]), [[0, 1, 2]])
    >>> normalized("edge_mean_curvature", {(0, 1): np.array([0.5])})
    {(0, 1): 0.5}
    """
    spec = METHODS[method]
    kind = spec.kind
    if kind == "integer":
        return int(_scalar(answer))
    if kind == "boolean":
        return bool(_scalar(answer))
    if kind == "numbers" and spec.element == "total":
        return _scalar(answer)
    if kind in ("numbers", "flags", "planar triangulation") or (
            kind == "matrix" and not hasattr(answer, "tocsr")):
        return np.asarray(answer)
    if kind == "loops":
        return [[int(v) for v in loop] for loop in answer]
    if kind == "edges":
        if _plain_edges(answer, {int}):
            return dict(answer)
        return {(int(i), int(j)): _scalar(h) for (i, j), h in answer.items()}
    if kind == "intrinsic triangulation":
        F2, l2 = answer
        return np.asarray(F2), np.asarray(l2)
    return answer


def _plain_edges(answer, index_types=None) -> bool:
    """Whether a dict answer of kind "edges" is what the per-item checks accept, decided by
    the types present (at C speed: 1.35 million edges in a fraction of the loop's 2.5 s):
    every key a tuple of two integers of ``index_types`` (default: any integer but a bool),
    every value a real number that :func:`_scalar` leaves as it is.  False decides nothing
    (the loop then looks at each item)."""
    if type(answer) is not dict or not answer:
        return False
    keys = answer.keys()
    if {type(k) for k in keys} != {tuple} or {len(k) for k in keys} != {2}:
        return False
    index = {type(i) for k in keys for i in k}
    value = {type(v) for v in answer.values()}
    integral = (index <= index_types if index_types is not None else all(
        issubclass(t, numbers.Integral) and not issubclass(t, (bool, np.bool_)) for t in index))
    return integral and all(issubclass(t, numbers.Real) and not issubclass(t, (bool, np.bool_))
                            for t in value)


def _iterable(x) -> bool:
    try:
        iter(x)
    except TypeError:
        return False
    return hasattr(x, "__len__")
