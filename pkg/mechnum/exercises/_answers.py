"""What a student's answer must be, and how it is read: exact conversions into plain numbers.

A check never compares the object a student's function returns: it first converts it, by the
exercise's :class:`Spec`, into plain values (``float``, ``int``, ``str``, float arrays), and a
value that is not exactly of the documented kind is a wrong answer, said in words. An integer
must be an integer (``2.7`` and ``2.0`` are not), a real must not be complex, a verdict must be
one of its documented words, and an object that pretends to be a number (one that compares
equal to everything, say) is not one.

Answers cross from the process that ran the student's function as a pickle, read by
:func:`loads`, which rebuilds nothing but Python's containers and numbers and numpy's arrays and
scalars: an object of any other class never reaches the check.
"""

import io
import pickle

import numpy as np


class Raises:
    """The expected outcome of a case on which the statement asks for an exception: its class's
    name (``Raises("RuntimeError")``)."""

    def __init__(self, name):
        self.name = name

    def __eq__(self, other):
        return isinstance(other, Raises) and other.name == self.name

    def __repr__(self):
        return f"Raises({self.name!r})"


class WrongForm(Exception):
    """An answer that is not of the documented kind; its message says what it is instead."""


def _describe(value):
    kind = type(value).__name__
    if isinstance(value, np.ndarray):
        return f"an array of dtype {value.dtype}"
    return f"a {kind}"


def _number(value, what):
    """A real number (int, float or a numpy real scalar or 0-d array), as a ``float``."""
    if type(value) is np.ndarray and value.ndim == 0:
        value = value[()]
    if type(value) in (int, float) or isinstance(value, (np.integer, np.floating)):
        return float(value)
    if type(value) is complex or isinstance(value, np.complexfloating):
        raise WrongForm(f"{what} is complex ({value}); it must be real")
    raise WrongForm(f"{what} is {_describe(value)}, not a real number")


class Real:
    """A real number (a Python or numpy integer or float; not a bool, not complex)."""

    def convert(self, value, what):
        return _number(value, what)


class Integer:
    """An integer (``int`` or a numpy integer): ``2.7`` and ``2.0`` are not integers."""

    def convert(self, value, what):
        if type(value) is np.ndarray and value.ndim == 0:
            value = value[()]
        if type(value) is int or isinstance(value, np.integer):
            return int(value)
        if type(value) is float or isinstance(value, np.floating):
            raise WrongForm(f"{what} is {value!r}, a float; it must be an integer (an int)")
        raise WrongForm(f"{what} is {_describe(value)}, not an integer")


class Array:
    """An array of real numbers (an ndarray, or nested lists or tuples of real numbers), read as
    float64; ``shape`` (optional) is checked by the comparison, which knows the expected one."""

    def convert(self, value, what):
        if isinstance(value, (str, bytes, bool, dict, set)) or value is None:
            raise WrongForm(f"{what} is {_describe(value)}, not an array of real numbers")
        if type(value) in (list, tuple):
            flat = list(value)
            while flat:
                item = flat.pop()
                if type(item) in (list, tuple):
                    flat.extend(item)
                elif type(item) is np.ndarray:
                    flat.extend(self.convert(item, what).ravel().tolist())
                else:
                    _number(item, f"an entry of {what}")
            try:
                value = np.array(value, dtype=float) if value else np.zeros(0)
            except ValueError:  # entries of different shapes
                raise WrongForm(f"{what} is a {type(value).__name__} of {len(value)} items of "
                                "different shapes, not an array") from None
        if type(value) is not np.ndarray:
            return np.array(_number(value, what))
        if value.dtype.kind == "c":
            raise WrongForm(f"{what} is complex (dtype {value.dtype}); it must be real")
        if value.dtype.kind not in "iuf":
            raise WrongForm(f"{what} is {_describe(value)}, not an array of real numbers")
        return np.array(value, dtype=float)


class Choice:
    """One of the documented words (a ``str``), or a ``bool`` where ``True``/``False`` are
    among the choices."""

    def __init__(self, *choices):
        self.choices = choices

    def convert(self, value, what):
        if type(value) is bool or isinstance(value, np.bool_):
            if bool(value) in [c for c in self.choices if type(c) is bool]:
                return bool(value)
        elif isinstance(value, str) and str(value) in self.choices:
            return str(value)
        words = ", ".join(repr(c) for c in self.choices)
        shown = repr(value) if isinstance(value, (str, bool, np.bool_)) else _describe(value)
        raise WrongForm(f"{what} is {shown}; it must be one of {words}")


class Tuple:
    """A fixed number of values (a tuple or a list), each of its own kind."""

    def __init__(self, *specs, names=()):
        self.specs, self.names = specs, names

    def convert(self, value, what):
        if type(value) not in (tuple, list) or len(value) != len(self.specs):
            shown = (f"{len(value)} values" if type(value) in (tuple, list)
                     else _describe(value))
            raise WrongForm(f"{what} is {shown}; it must be {len(self.specs)} values, "
                            + ", ".join(self.names or ["..."] * len(self.specs)))
        names = self.names or [f"{what}[{k}]" for k in range(len(self.specs))]
        return tuple(spec.convert(item, name)
                     for spec, item, name in zip(self.specs, value, names))


_ALLOWED = {
    ("builtins", "complex"), ("builtins", "slice"), ("builtins", "frozenset"),
    ("builtins", "set"), ("numpy", "ndarray"), ("numpy", "dtype"),
    *((module, name) for module in ("numpy.core.multiarray", "numpy._core.multiarray")
      for name in ("_reconstruct", "scalar")),
    *((module, "_frombuffer") for module in ("numpy.core.numeric", "numpy._core.numeric")),
    *(("numpy.dtypes", name) for name in ("Float64DType", "Float32DType", "Int64DType",
                                          "Int32DType", "BoolDType", "Complex128DType",
                                          "StrDType", "UInt64DType", "Float16DType")),
}


class _Unpickler(pickle.Unpickler):
    def find_class(self, module, name):
        if (module, name) in _ALLOWED:
            return super().find_class(module, name)
        raise WrongForm(f"the answer holds an object of class {module}.{name}, not numbers")


def loads(data):
    """Read an answer pickled by the process that ran the student's function, rebuilding only
    containers, numbers, strings and numpy arrays and scalars.

    Examples
    --------
    >>> import pickle
    >>> from fractions import Fraction
    >>> loads(pickle.dumps((np.arange(3.0), 2)))
    (array([0., 1., 2.]), 2)
    >>> loads(pickle.dumps(Fraction(1, 3)))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechnum.exercises._answers.WrongForm: the answer holds an object of class fractions...
    """
    return _Unpickler(io.BytesIO(data)).load()


def differ(got, expected):
    """``got`` and ``expected`` with the digits that tell them apart, and their difference.

    Examples
    --------
    >>> differ(1.24586371, 1.24586123)
    '1.245864, expected 1.245861 (off by 2.5e-06)'
    >>> differ(2.0, 3.0)
    '2, expected 3 (off by 1)'
    """
    digits = 6
    while digits < 17 and f"{got:.{digits}g}" == f"{expected:.{digits}g}":
        digits += 1
    return (f"{got:.{digits}g}, expected {expected:.{digits}g} "
            f"(off by {abs(got - expected):.2g})")


def close(expected, got, *, rtol, atol, what):
    """``None`` when the float arrays agree within ``atol + rtol |expected|``, else the largest
    difference in words, with the digits that tell the two values apart; ``got`` is converted
    first (:class:`Array`), so NaN, complex values or objects that are not numbers never
    agree."""
    expected = np.asarray(expected, dtype=float)
    got = Array().convert(got, what)
    if got.shape != expected.shape:  # the answer's form: a message about it, and no hint
        raise WrongForm(f"{what} has shape {got.shape}; it must have shape {expected.shape}")
    if not np.all(np.isfinite(got)):
        return f"{what} is not finite: {np.array2string(got, precision=4)}"
    error = np.abs(got - expected)
    if np.all(error <= atol + rtol * np.abs(expected)):
        return None
    worst = np.unravel_index(np.argmax(error - rtol * np.abs(expected)), error.shape)
    at = f" at index {tuple(int(i) for i in worst)}" if expected.ndim else ""
    return f"{what}{at} is " + differ(float(got[worst]), float(expected[worst]))
