"""The input checks that every public entry point of :mod:`mechnum` shares.

Each check returns the value it checked, converted (a float array, a float, an int), or raises
:class:`ValueError` with a message that names the argument and shows the offending value. A
numerical method is only as trustworthy as its input: NaN, infinity, a complex number where the
method is real, a wrong shape or a tolerance of ``-1`` must fail loudly at the door, not turn into
a silent wrong answer deep inside an iteration.

Examples
--------
>>> array([[1, 2]], "x0", ndim=2).dtype
dtype('float64')
>>> tolerance(1e-10), maxiter(50), choice("qr", ("qr", "normal"), "method")
(1e-10, 50, 'qr')
>>> array([1.0, float("nan")], "x0")
Traceback (most recent call last):
...
ValueError: x0 must be finite, got [ 1. nan]
"""

import operator

import numpy as np
from numpy.typing import ArrayLike


def shown(value: object) -> str:
    """A short text of ``value`` for an error message.

    Examples
    --------
    >>> shown(np.arange(100.0))
    '[ 0.  1. ... 98. 99.]'
    """
    if isinstance(value, np.ndarray):
        return np.array2string(value, threshold=8, edgeitems=2, precision=6)
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."




def array(value: ArrayLike, name: str, *, ndim: int | tuple | None = None,
          shape: tuple | None = None, finite: bool = True) -> np.ndarray:
    """``value`` as a real float array, checked.

    Parameters
    ----------
    value : array_like
        The input.
    name : str
        Its name, for the error message.
    ndim : int or tuple of int, optional
        The allowed numbers of dimensions.
    shape : tuple, optional
        The required shape; ``None`` in it stands for any length of that axis (so
        ``(None, 3)`` is a batch of 3-vectors, possibly empty).
    finite : bool, optional
        Whether NaN and infinities are refused.

    Returns
    -------
    ndarray of float

    Raises
    ------
    ValueError
        If ``value`` is not numeric, is complex, has the wrong shape, or is not finite.

    Examples
    --------
    >>> array([[0.0, 1.0, 2.0]], "poses", shape=(None, 3)).shape
    (1, 3)
    >>> array(np.empty((0, 3)), "poses", shape=(None, 3)).shape   # an empty batch is valid
    (0, 3)
    >>> array([1j], "x0")
    Traceback (most recent call last):
    ...
    ValueError: x0 must be real, got [0.+1.j]
    """
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError) as error:  # ragged nested lists, for example
        raise ValueError(f"{name} must be a numeric array, got {shown(value)}: {error}") from None
    if np.iscomplexobj(raw):
        raise ValueError(f"{name} must be real, got {shown(raw)}")
    if raw.dtype.kind not in "biuf":
        raise ValueError(f"{name} must be numeric, got {shown(value)} (dtype {raw.dtype})")
    out = raw.astype(float)
    if ndim is not None and out.ndim not in ((ndim,) if isinstance(ndim, int) else ndim):
        raise ValueError(f"{name} must have {ndim} dimension(s), got shape {out.shape}")
    if shape is not None and (out.ndim != len(shape) or any(
            want is not None and got != want for got, want in zip(out.shape, shape))):
        wanted = "(" + ", ".join("n" if s is None else str(s) for s in shape) + \
                 ("," if len(shape) == 1 else "") + ")"
        raise ValueError(f"{name} must have shape {wanted}, got shape {out.shape}")
    if finite and not np.isfinite(out).all():   # the method: some microseconds cheaper
        raise ValueError(f"{name} must be finite, got {shown(out)}")
    return out


def scalar(value: ArrayLike, name: str, *, positive: bool = False,
           nonnegative: bool = False) -> float:
    """``value`` as a finite real float, checked (optionally ``> 0`` or ``>= 0``).

    Examples
    --------
    >>> scalar(2, "EI", positive=True)
    2.0
    >>> scalar(-1.0, "L", positive=True)
    Traceback (most recent call last):
    ...
    ValueError: L must be positive, got -1.0
    """
    out = array(value, name, ndim=0)
    out = float(out)
    if positive and not out > 0:
        raise ValueError(f"{name} must be positive, got {out!r}")
    if nonnegative and not out >= 0:
        raise ValueError(f"{name} must be non-negative, got {out!r}")
    return out


def numbers(values: dict, *, positive: tuple = (), nonnegative: tuple = (),
            scalars: bool = True) -> list:
    """The named ``values``, checked: finite real floats (with ``scalars=False``, float arrays
    that broadcast together); those named in ``positive`` ``> 0``, in ``nonnegative`` ``>= 0``.

    The one line of checks of a function whose arguments are plain numbers (the inner
    functions of :mod:`mechnum.rods`, called from the outside too).

    Examples
    --------
    >>> numbers({"EI": 2, "psi": -1.0}, positive=("EI",))
    [2.0, -1.0]
    >>> numbers({"a": [1.0, 2.0], "w": [0.5, -0.5]}, positive=("w",), scalars=False)
    Traceback (most recent call last):
    ...
    ValueError: w must be positive, got [ 0.5 -0.5]
    """
    out = []
    for name, value in values.items():
        x = array(value, name, ndim=0 if scalars else None)
        for names, ok, word in ((positive, x > 0, "positive"), (nonnegative, x >= 0,
                                                                "non-negative")):
            if name in names and not np.all(ok):
                got = shown(x) if x.ndim else repr(float(x))
                raise ValueError(f"{name} must be {word}, got {got}")
        out.append(float(x) if scalars else x)
    if not scalars:
        broadcast(**dict(zip(values, out)))
    return out


def positive(value: ArrayLike, name: str) -> np.ndarray:
    """``value`` as a float array whose every entry is finite and positive.

    Examples
    --------
    >>> positive([1.0, 2.0], "lengths").tolist()
    [1.0, 2.0]
    """
    out = array(value, name)
    if not np.all(out > 0):
        raise ValueError(f"{name} must be positive, got {shown(out)}")
    return out


def tolerance(value: ArrayLike, name: str = "tol") -> float:
    """A tolerance: a finite positive float.

    Examples
    --------
    >>> tolerance(-1)
    Traceback (most recent call last):
    ...
    ValueError: tol must be positive, got -1.0
    """
    return scalar(value, name, positive=True)


def maxiter(value: object, name: str = "maxiter", minimum: int = 1,
            maximum: int | None = None) -> int:
    """An iteration (or node, or start) count: an integer ``>= minimum`` (and ``<= maximum``).

    Floats with an integer value are accepted; ``inf``, NaN, fractions, booleans are not. Every
    argument that sets an amount of work has a documented ``maximum``, so that a typing slip
    (``nodes=1e6``) fails at once instead of running for hours or exhausting memory.

    Examples
    --------
    >>> maxiter(10.0)
    10
    >>> maxiter(float("inf"))
    Traceback (most recent call last):
    ...
    ValueError: maxiter must be an integer >= 1, got inf
    >>> maxiter(10**6, "nodes", minimum=2, maximum=100_000)
    Traceback (most recent call last):
    ...
    ValueError: nodes must be an integer <= 100000 (a bound on the work), got 1000000
    """
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    try:
        out = operator.index(value)
    except TypeError:
        as_float = float(value) if isinstance(value, (float, np.floating)) else None
        if as_float is None or not np.isfinite(as_float) or as_float != int(as_float):
            raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}") from None
        out = int(as_float)
    if out < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if maximum is not None and out > maximum:
        raise ValueError(f"{name} must be an integer <= {maximum} (a bound on the work), "
                         f"got {value!r}")
    return out


def broadcast(**arrays: np.ndarray) -> tuple:
    """The shape that ``arrays`` (checked arrays, by name) broadcast to.

    Examples
    --------
    >>> broadcast(psi=np.zeros(2), k_rel=np.zeros((4, 1)))
    (4, 2)
    >>> broadcast(psi=np.zeros(2), k_rel=np.zeros(3))
    Traceback (most recent call last):
    ...
    ValueError: the shapes of psi (2,) and k_rel (3,) do not broadcast to one shape
    """
    try:
        return np.broadcast_shapes(*(np.shape(a) for a in arrays.values()))
    except ValueError:
        shapes = " and ".join(f"{name} {np.shape(a)}" for name, a in arrays.items())
        raise ValueError(f"the shapes of {shapes} do not broadcast to one shape") from None


def modes(value: object, name: str = "modes", maximum: int | None = None) -> list:
    """Distinct buckling modes (or other counts >= 1), from any iterable of integers.

    Examples
    --------
    >>> modes((1, 2.0))
    [1, 2]
    >>> modes(None)
    Traceback (most recent call last):
    ...
    ValueError: modes must be an iterable of distinct integers >= 1, got None
    """
    try:
        out = [maxiter(m, "mode", maximum=maximum) for m in value]
    except TypeError:
        out = None
    if out is None or len(set(out)) != len(out):
        raise ValueError(f"{name} must be an iterable of distinct integers >= 1, "
                         f"got {shown(value)}")
    return out


def flag(value: object, name: str) -> bool:
    """A yes/no option: a ``bool`` (or numpy's), nothing that is merely truthy.

    Examples
    --------
    >>> flag(True, "damping")
    True
    >>> flag("yes", "damping")
    Traceback (most recent call last):
    ...
    ValueError: damping must be True or False, got 'yes'
    """
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False, got {shown(value)}")
    return bool(value)


def function(value: object, name: str, *, optional: bool = False) -> object:
    """``value`` if it is callable (or None, when ``optional``): a residual, a Jacobian, ...

    Examples
    --------
    >>> function(abs, "fun") is abs
    True
    >>> function("x**2", "fun")
    Traceback (most recent call last):
    ...
    ValueError: fun must be a function (callable), got 'x**2'
    """
    if not (callable(value) or optional and value is None):
        raise ValueError(f"{name} must be a function (callable){' or None' if optional else ''}"
                         f", got {shown(value)}")
    return value


def rng(value: object, name: str = "rng") -> np.random.Generator:
    """A random generator: ``None``, a non-negative integer seed, or a ``numpy.random.Generator``.

    Examples
    --------
    >>> int(rng(0).integers(10)) == int(rng(0).integers(10))
    True
    >>> rng(-1)
    Traceback (most recent call last):
    ...
    ValueError: rng must be None, a non-negative integer seed or a numpy.random.Generator, got -1
    """
    if value is None or isinstance(value, np.random.Generator):
        return np.random.default_rng(value)
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)) \
            and value >= 0:
        return np.random.default_rng(value)
    raise ValueError(f"{name} must be None, a non-negative integer seed or a "
                     f"numpy.random.Generator, got {shown(value)}")


def choice(value: object, options: tuple, name: str) -> object:
    """``value`` if it is one of ``options``.

    Examples
    --------
    >>> choice("lu", ("qr", "normal"), "method")
    Traceback (most recent call last):
    ...
    ValueError: method must be one of ('qr', 'normal'), got 'lu'
    """
    try:
        known = value in options
    except (TypeError, ValueError):  # an array or an unhashable value
        known = False
    if not known:
        raise ValueError(f"{name} must be one of {tuple(options)}, got {value!r}")
    return value


def instance(value: object, kind: type, name: str, label: str) -> object:
    """``value`` if it is an instance of ``kind``; else :class:`ValueError` naming ``label``.

    Every mechanism checks its ``mech`` argument with this at its entry points.

    Examples
    --------
    >>> instance(2.5, float, "x", "a float")
    2.5
    >>> instance(None, float, "mech", "a finger.Linkage")
    Traceback (most recent call last):
    ...
    ValueError: mech must be a finger.Linkage, got None
    """
    if not isinstance(value, kind):
        raise ValueError(f"{name} must be {label}, got {value!r:.80}")
    return value
