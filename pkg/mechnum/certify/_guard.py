"""Balls that stay balls: what a residual is handed, and the checks of what it hands back.

A proof by interval arithmetic holds only if the residual computes, from the balls it is
given, balls that contain every value of ``f`` over them. A residual that leaves ball
arithmetic (takes ``float(X[0].mid())`` and calls :func:`math.sin` on it, or branches on
``X[0] > 0`` where the answer is uncertain) returns a ball that may miss values of ``f``, and
the search then proves nothing. :func:`~mechnum.certify.roots` and
:func:`~mechnum.certify.verify` therefore hand the residual, the Jacobian and the
exclusion test :class:`Ball`\\ s (:func:`mechnum.certify.balls.guarded`): Arb balls
(``flint.arb``) whose arithmetic and methods return :class:`Ball`\\ s again, and which refuse,
with a :class:`BallArithmeticError` naming the operation,

* conversion to a number: ``float``, ``int``, ``complex``, ``operator.index`` (so also
  ``np.float64(x)``, ``math.sin(x)``, ``range(x)``, indexing), ``bool`` (``if x:``), and the
  methods that return a point or an integer of the ball (``man_exp``, ``mid_rad_10exp``,
  ``unique_fmpz``, ``fmpz``, ``fmpq``);
* an ordering or equality comparison whose answer is not the same for every point of the balls
  (``x > 0`` is True when every point of ``x`` is positive, False when none is, and an error
  otherwise).

``x.mid()``, ``x.lower()``, ``x.upper()`` and ``x.rad()`` are Balls too (exact points), and
so are the ends of the box a ball was made from (:func:`interval`): none of them converts to a
float, and a pickled or copied Ball (``__getstate__``, ``__reduce_ex__``) is refused, so no
method of a Ball hands out a float of its points (the predicates kept give bools, bit counts and
text). Comparisons with them are certain (they are points) and
therefore allowed: a residual can still learn where its box lies, by comparisons alone (a
bisection on ``x.mid() > c`` recovers the midpoint bit by bit, and one on ``x > c`` the
ball's ends); see below.

What comes back is checked (:func:`values`, :func:`matrix`, :func:`decision`): a sequence of
exactly ``n`` balls (``flint.arb``; Python ``int`` is accepted as exact, a ``float`` is not: it
was computed outside ball arithmetic or is a constant written as one), a matrix of ``n`` rows of
``n``, an exclusion test's plain ``bool``; and the residual must be finite at the points where
it is evaluated (a function with no finite value at a point of the box is not continuous
there). Each failure is a :class:`ResidualError` that names the function and the problem.

**What remains the caller's responsibility.** The guard catches the common ways out of ball
arithmetic, not all of them. The caller must still make sure that

* ``residual`` and ``jacobian`` enclose a function and its derivative, continuously
  differentiable on every searched box (a wrong formula is a wrong proof, whatever the balls);
* nothing reaches a number by a route the guard cannot see: an explicit ``flint.arb(x)`` (the
  sanctioned exit, used by the package's own audited enclosures of the rods,
  ``mechnum.rods._balls``),
  ``flint.acb`` or ``flint.arb_mat`` built from the balls (their results are plain flint
  objects), static functions such as ``arb.atan2``, the text of ``str(x)``, or state kept
  between calls;
* the answers of certain comparisons and of the predicates of a ball (``x > 0``,
  ``x.mid() > c``, ``x.contains(0)``, ``x.is_finite()``, ``x.rad()`` compared with a number)
  are used only to choose between formulas that each enclose ``f`` on that ball, never to
  compute a value: the guard cannot tell a branch from a bisection that recovers a point of
  the box as a float by comparisons alone;
* nothing reads a Ball's private attributes (``x._box``) or calls base-class methods on it
  (``arb.mid(x)``), which are plain ``flint.arb``'s.

Examples
--------
>>> import math
>>> from mechnum.certify.balls import guarded
>>> x = guarded([[3.0, 3.3]])[0]                    # holds pi, where sin is 0
>>> type(x.sin()).__name__, bool(x.sin().contains(0))
('Ball', True)
>>> lo, hi = interval(x)                            # the box's exact ends, as Balls
>>> type(hi).__name__, hi.is_exact(), bool(hi == 3.3)
('Ball', True, True)
>>> bool(x.mid() > 3.1)              # certain (a point): allowed, and it tells where x lies
True
>>> math.sin(sum(interval(x)) / 2)
Traceback (most recent call last):
...
mechnum.certify.BallArithmeticError: float() of a ball [3.15000000000000 +/- 8.91e-17]: \
a residual must stay in ball arithmetic (use the ball's own methods, such as x.sin())
>>> math.sin(float(x.mid()))
Traceback (most recent call last):
...
mechnum.certify.BallArithmeticError: float() of a ball [3.15000000000000 +/- 8.91e-17]: \
a residual must stay in ball arithmetic (use the ball's own methods, such as x.sin())
>>> x > 3.1
Traceback (most recent call last):
...
mechnum.certify.BallArithmeticError: x > y is not certain for x = [3e+0 +/- 0.301], \
y = 3.1: a residual cannot branch on it
"""

from __future__ import annotations

from collections.abc import Callable

from flint import arb

from mechnum._validate import shown
from mechnum.errors import MechnumError

__all__ = ["BallArithmeticError", "ResidualError", "decision", "interval", "matrix",
           "values"]


class BallArithmeticError(MechnumError):
    """A residual tried to leave ball arithmetic: a ball converted to a number, or an ordering
    comparison of balls whose answer is not certain."""


class ResidualError(MechnumError, ValueError):
    """A residual, Jacobian or exclusion test returned what a proof cannot use: the wrong
    length, ``None``, a float, a non-ball, or no finite value at a point."""


# the methods of arb that give back a number (not a ball) of the ball's points
REFUSED = ("man_exp", "mid_rad_10exp", "unique_fmpz", "fmpz", "fmpq")
# the methods of arb that say something about the ball itself (a bool, an int, a text)
KEPT = ("contains", "contains_interior", "contains_integer", "overlaps", "is_zero",
        "is_finite", "is_nan", "is_exact", "is_integer", "rel_accuracy_bits",
        "rel_one_accuracy_bits", "bits", "repr", "str")


def _as_ball(value):
    """``value`` as a :class:`Ball` where it is a plain ``arb`` (tuples element-wise)."""
    if type(value) is arb:
        return Ball(value)
    if isinstance(value, tuple):
        return tuple(_as_ball(v) for v in value)
    return value


def _left(what, x):
    raise BallArithmeticError(f"{what} of a ball {arb.str(x)}: a residual must stay in ball "
                              f"arithmetic (use the ball's own methods, such as x.sin())")


def _shown(y):
    return arb.str(y) if isinstance(y, arb) else repr(y)


def _certain(name, symbol, holds, fails):
    """A comparison of balls that answers only when every point agrees (``holds`` and
    ``fails``: arb's own comparisons, True only where certain)."""
    def compare(self, other):
        yes = holds(self, other)
        if yes is NotImplemented:
            return NotImplemented
        if yes:
            return True
        if fails(self, other):
            return False
        raise BallArithmeticError(f"x {symbol} y is not certain for x = {arb.str(self)}, "
                                  f"y = {_shown(other)}: a residual cannot branch on it")
    compare.__name__ = name
    return compare


class Ball(arb):
    """An Arb ball that refuses to leave ball arithmetic (see the module).

    Arithmetic with numbers, ``flint.arb`` and other Balls, and arb's methods (``sin``,
    ``sqrt``, ``mid``, ...), return Balls. ``interval(ball)`` gives the exact ends of the box it
    was made from (:func:`mechnum.certify.balls.guarded`), as Balls, or None.

    Examples
    --------
    >>> x = Ball(arb(2, 0.5))
    >>> type(x * x + 1).__name__, bool(x > 1), 0 in x
    ('Ball', True, False)
    >>> int(x)
    Traceback (most recent call last):
    ...
    mechnum.certify.BallArithmeticError: int() of a ball [2e+0 +/- 0.501]: a residual \
must stay in ball arithmetic (use the ball's own methods, such as x.sin())
    """

    __slots__ = ("_box",)

    def __init__(self, value=0, *, box=None):
        if type(value) not in (int, float) and not isinstance(value, arb):
            raise ValueError(f"a Ball is made from a ball (flint.arb) or a number, got "
                             f"{shown(value)}")
        super().__init__(value)
        self._box = None if box is None else (float(box[0]), float(box[1]))

    def __float__(self):
        _left("float()", self)

    def __int__(self):
        _left("int()", self)

    def __index__(self):
        _left("operator.index()", self)

    def __complex__(self):
        _left("complex()", self)

    def __bool__(self):
        _left("bool()", self)

    def __round__(self, ndigits=None):
        _left("round()", self)

    def __trunc__(self):
        _left("math.trunc()", self)

    def __getstate__(self):
        _left("pickling (__getstate__)", self)

    def __reduce_ex__(self, protocol):
        _left("pickling or copying (__reduce_ex__)", self)

    __lt__ = _certain("__lt__", "<", arb.__lt__, arb.__ge__)
    __le__ = _certain("__le__", "<=", arb.__le__, arb.__gt__)
    __gt__ = _certain("__gt__", ">", arb.__gt__, arb.__le__)
    __ge__ = _certain("__ge__", ">=", arb.__ge__, arb.__lt__)
    __eq__ = _certain("__eq__", "==", arb.__eq__, arb.__ne__)
    __ne__ = _certain("__ne__", "!=", arb.__ne__, arb.__eq__)
    __hash__ = None

    @property
    def real(self):
        return self

    @property
    def imag(self):
        return Ball(0)


def _method(name):
    base = getattr(arb, name)

    def method(self, *args, **kwargs):
        return _as_ball(base(self, *args, **kwargs))
    method.__name__ = name
    method.__doc__ = base.__doc__
    return method


def _refused(name):
    def method(self, *args, **kwargs):
        _left(f"{name}()", self)
    method.__name__ = name
    return method


_OPERATORS = ("__add__", "__radd__", "__sub__", "__rsub__", "__mul__", "__rmul__",
              "__truediv__", "__rtruediv__", "__floordiv__", "__rfloordiv__", "__pow__",
              "__rpow__", "__neg__", "__pos__", "__abs__")
for _name in _OPERATORS:
    setattr(Ball, _name, _method(_name))
for _name, _value in vars(arb).items():
    if _name.startswith("_") or isinstance(_value, staticmethod) or not callable(_value):
        continue
    if _name in REFUSED:
        setattr(Ball, _name, _refused(_name))
    elif _name not in KEPT:
        setattr(Ball, _name, _method(_name))


def interval(x: arb) -> tuple | None:
    """The exact ends ``(lo, hi)`` of the float box a :class:`~mechnum.certify.Ball` was made
    from (:func:`mechnum.certify.balls.guarded`), as Balls (exact points, so comparisons with
    them are certain), or None (a plain ball, or a Ball computed from others).

    Examples
    --------
    >>> lo, hi = interval(Ball(arb(1), box=(1.0, 1.0)))
    >>> type(lo).__name__, bool(lo == 1), interval(arb(1))
    ('Ball', True, None)
    """
    box = x._box if isinstance(x, Ball) else None
    return None if box is None else (Ball(box[0]), Ball(box[1]))


def _component(value, name, where):
    if isinstance(value, arb):
        return arb(value)
    if type(value) is int:
        return arb(value)
    kind = "None" if value is None else type(value).__name__
    hint = (": a float was computed outside ball arithmetic (or is a constant written as one: "
            "use flint.arb or an int)" if isinstance(value, float) else "")
    raise ResidualError(f"{name} returned {kind} ({value!r}) at {where}, not a ball{hint}")


def _sequence(out, n, name, what):
    try:
        length = len(out)
    except TypeError:
        raise ResidualError(f"{name} must return {what} of {n}, got "
                            f"{type(out).__name__} ({out!r})") from None
    if length != n:
        raise ResidualError(f"{name} must return {what} of {n}, got {length}")
    return list(out)


def values(residual: Callable, X: list, n: int, *, point: bool = False) -> list:
    """``residual(X)`` checked: ``n`` balls (plain ``arb``), finite if ``point``.

    Examples
    --------
    >>> values(lambda X: [X[0] - 1, 2], [Ball(arb(3))], 2)
    [2.00000000000000, 2.00000000000000]
    >>> values(lambda X: [X[0] - 1], [Ball(arb(3))], 2)
    Traceback (most recent call last):
    ...
    mechnum.certify.ResidualError: the residual must return a sequence of 2, got 1

    Raises
    ------
    ResidualError
        If it returns another length, None or something that is not a ball, or (at a point)
        a ball that is not finite.
    """
    out = [_component(v, "the residual", f"component {i}")
           for i, v in enumerate(_sequence(residual(X), n, "the residual", "a sequence"))]
    if point and not all(v.is_finite() for v in out):
        raise ResidualError(f"the residual is not finite at the point "
                            f"{[arb.str(x) for x in X]}: {[v.str() for v in out]} (f must be "
                            f"finite and continuously differentiable on the searched box)")
    return out


def matrix(jacobian: Callable, X: list, n: int) -> list:
    """``jacobian(X)`` checked: ``n`` rows of ``n`` balls (plain ``arb``).

    Examples
    --------
    >>> matrix(lambda X: [[2 * X[0]]], [Ball(arb(3))], 1)
    [[6.00000000000000]]
    """
    rows = _sequence(jacobian(X), n, "the jacobian", "a sequence of rows")
    return [[_component(v, "the jacobian", f"entry ({i}, {j})")
             for j, v in enumerate(_sequence(row, n, "the jacobian", f"a row {i}"))]
            for i, row in enumerate(rows)]


def decision(exclude: Callable, X: list) -> bool:
    """``exclude(X)`` checked: a plain ``bool`` (numpy's ``bool_`` too).

    Examples
    --------
    >>> decision(lambda X: X[0] > 2, [Ball(arb(3))])
    True
    """
    out = exclude(X)
    if type(out) is bool or type(out).__name__ == "bool_":
        return bool(out)
    raise ResidualError(f"exclude must return a bool, got {type(out).__name__} ({out!r})")
