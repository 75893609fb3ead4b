"""Intervals as Arb balls: conversions, and elementary functions enclosed tightly over wide balls.

Arb (through ``python-flint``) rounds every operation outward, so the ball it returns contains
the exact result for every point of the input balls. Its elementary and elliptic functions are
built for narrow balls, though: ``cos`` of ``[0.9, 1.1]`` comes back as ``[-0.62, 0.62]`` and
Carlson's ``R_F`` of a ball of radius 0.05 as ``[-2.2, 2.2]``. Over the wide boxes of a
branch-and-prune search this module evaluates instead at the **endpoints** of intervals where the
function is monotone (:func:`monotone`), and handles the extrema of ``cos`` and ``sin``
explicitly: the enclosures are then as tight as the interval itself allows.

An interval ``[lo, hi]`` of floats is the ball :func:`ball` returns; :func:`bounds` turns a ball
back into floats ``lo <= x <= hi`` (rounded outward by one unit in the last place, so that the
floats always enclose the ball).

Examples
--------
>>> x = ball(0.9, 1.1)
>>> lo, hi = bounds(cos(x))
>>> bool(lo <= np.cos(1.1) < np.cos(0.9) <= hi), round(hi - lo, 6)
(True, 0.168014)
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence

import numpy as np
from flint import acb, arb
from numpy.typing import ArrayLike

from mechnum._validate import shown
from mechnum.certify import _guard as guard
from mechnum.certify._guard import interval

# What the rods' and the mechanisms' enclosures use (the rest serves certify's own modules).
__all__ = ["PI", "ball", "bounds", "cos", "ends", "guarded", "interval", "meet", "monotone",
           "mul", "sin", "span", "sqrt"]

PI = arb.pi()


def _accepts_balls(function):
    """Let ``function`` take the guarded balls a residual is handed
    (:class:`mechnum.certify.Ball`): it computes on plain balls (it is audited: its
    comparisons and bounds are of enclosures), and a result from guarded balls is guarded."""
    @functools.wraps(function)
    def call(*args):
        if not any(isinstance(a, guard.Ball) for a in args):
            return function(*args)
        return guard.Ball(function(*(arb(a) if isinstance(a, arb) else a for a in args)))
    return call


def ball(lo: object, hi: object = None) -> arb:
    """The ball that contains the interval ``[lo, hi]`` of floats (a point if ``hi`` is None).

    Examples
    --------
    >>> b = ball(1.0, 2.0)
    >>> b.contains(arb(1.0)), b.contains(arb(2.0)), b.contains(arb(2.01))
    (True, True, False)
    """
    try:
        if np.iscomplexobj(lo) or np.iscomplexobj(hi):
            raise TypeError
        lo = float(lo)
        hi = lo if hi is None else float(hi)
    except (TypeError, ValueError):
        raise ValueError(f"an interval needs two real numbers lo <= hi, got lo={shown(lo)}, "
                         f"hi={shown(hi)}") from None
    if not lo <= hi:
        raise ValueError(f"an interval needs lo <= hi, got [{lo!r}, {hi!r}]")
    if lo == hi:
        return arb(lo)
    mid = 0.5 * lo + 0.5 * hi
    rad = math.nextafter(max(hi - mid, mid - lo), math.inf)
    return arb(mid, rad)


def guarded(box: ArrayLike) -> list:
    """The :class:`~mechnum.certify.Ball`\\ s of a float box ``[[lo, hi], ...]``, each
    knowing its ends: what a residual is handed.

    Examples
    --------
    >>> from mechnum.certify._guard import interval
    >>> [interval(x) for x in guarded([[0.0, 1.0], [2.0, 2.0]])]
    [(0, 1.00000000000000), (2.00000000000000, 2.00000000000000)]
    """
    return [guard.Ball(ball(lo, hi), box=(float(lo), float(hi))) for lo, hi in box]


def bounds(x: object) -> tuple[float, float]:
    """Floats ``(lo, hi)`` with ``lo <= x <= hi`` for every point of the ball ``x``
    (``-inf, inf`` where ``x`` is not finite)."""
    if isinstance(x, guard.Ball):
        raise guard.BallArithmeticError(f"bounds() of a ball {arb.str(x)}: floats are not "
                                        f"ball arithmetic")
    if not x.is_finite():
        return -math.inf, math.inf
    return (math.nextafter(float(x.lower()), -math.inf),
            math.nextafter(float(x.upper()), math.inf))


def ends(x: object) -> tuple[arb, arb]:
    """The endpoints of the ball ``x`` as exact balls (points)."""
    return x.lower(), x.upper()


def monotone(f: Callable, *args: object) -> arb:
    """Enclosure of ``f`` over balls on which it is monotone in each argument.

    ``args`` are ``(ball, direction)`` pairs (or ``((lo, hi), direction)`` with the endpoints
    as exact balls, see :func:`span`), ``direction`` +1 where ``f`` increases with that
    argument and -1 where it decreases; ``f`` is evaluated at the two corners where it is
    least and greatest, each as a ball, and the union of the two is returned (a NaN ball,
    which holds every number, where a corner's value is not finite).

    Examples
    --------
    >>> r = monotone(lambda x, z: x - z, (ball(1, 2), 1), (ball(0, 1), -1))
    >>> bounds(r)[0] < 0.0 < 2.0 < bounds(r)[1] < 2.0 + 1e-8
    True
    """
    spans = [x if isinstance(x, tuple) else ends(x) for x, _ in args]
    low = [s[0] if d > 0 else s[1] for s, (_, d) in zip(spans, args)]
    high = [s[1] if d > 0 else s[0] for s, (_, d) in zip(spans, args)]
    a = f(*low)
    if all(s[0] == s[1] for s in spans):
        return a
    b = f(*high)
    if not (a.is_finite() and b.is_finite()):
        return arb("nan")
    return a.union(b)


def span(x: object, lo: object = None, hi: object = None) -> arb:
    """The endpoints of the ball ``x`` as exact balls, cut to ``[lo, hi]`` (floats or balls):
    the interval of a quantity known to lie there, whose ball's rounding pokes beyond (a
    ball from 0 to 0.3 has the centre 0.15 and a radius rounded up, below 0)."""
    a, b = ends(x)
    if lo is not None and bool(a < lo):
        a = arb(lo)
    if hi is not None and bool(b > hi):
        b = arb(hi)
    if bool(a > b):
        a = b
    return a, b


def _extrema_between(lo, hi, period, phase):
    """Whether some ``phase + k period`` may lie in ``[lo, hi]`` (lo, hi, phase, period balls)."""
    k = math.ceil(float(((lo - phase) / period).lower()))
    return not bool(phase + k * period > hi)


@_accepts_balls
def cos(x: object) -> arb:
    """``cos`` over the ball ``x``: the endpoints' values and, where they fall inside, the
    extrema ``+1`` (at ``2 k pi``) and ``-1`` (at ``pi + 2 k pi``)."""
    if x.rad() == 0 or x.rad() < 1e-8:
        return x.cos()
    lo, hi = ends(x)
    if bool(hi - lo >= 2 * PI):
        return arb(0, 1)
    out = lo.cos().union(hi.cos())
    if _extrema_between(lo, hi, 2 * PI, arb(0)):
        out = out.union(arb(1))
    if _extrema_between(lo, hi, 2 * PI, PI):
        out = out.union(arb(-1))
    return out


@_accepts_balls
def sin(x: object) -> arb:
    """``sin`` over the ball ``x`` (as :func:`cos` of ``x - pi / 2``)."""
    if x.rad() == 0 or x.rad() < 1e-8:
        return x.sin()
    return cos(x - PI / 2)


@_accepts_balls
def exp(x: object) -> arb:
    return monotone(lambda y: y.exp(), (x, 1))


@_accepts_balls
def expm1(x: object) -> arb:
    return monotone(lambda y: y.expm1(), (x, 1))


@_accepts_balls
def sqrt(x: object) -> arb:
    """``sqrt`` over the ball ``x``, whose negative part (rounding of a square) is cut at 0."""
    return monotone(lambda y: y.sqrt(), (span(x, 0), 1))


@_accepts_balls
def nonnegative(x: object) -> arb:
    """``x`` with its negative part removed (for quantities known to be ``>= 0``)."""
    lo, hi = ends(x)
    return arb(0).union(hi) if bool(lo < 0) else x


def _carlson(f, direction, args):
    """A Carlson function over balls of non-negative arguments, monotone in each (their
    negative rounding cut at 0)."""
    return monotone(lambda *p: f(*(acb(x) for x in p)).real,
                    *((span(x, 0), direction) for x in args))


@_accepts_balls
def rf(x: object, y: object, z: object) -> arb:
    """Carlson's ``R_F(x, y, z)`` over balls of non-negative arguments: it decreases in each
    (DLMF 19.16.1), so two evaluations enclose it."""
    return _carlson(acb.elliptic_rf, -1, (x, y, z))


@_accepts_balls
def rd(x: object, y: object, z: object) -> arb:
    """Carlson's ``R_D(x, y, z) = R_J(x, y, z, z)``, decreasing in each argument."""
    return _carlson(lambda a, b, c: acb.elliptic_rj(a, b, c, c), -1, (x, y, z))


@_accepts_balls
def rg(x: object, y: object, z: object) -> arb:
    """Carlson's ``R_G(x, y, z)``, increasing in each argument (DLMF 19.16.3)."""
    return _carlson(acb.elliptic_rg, 1, (x, y, z))


@_accepts_balls
def mul(x: object, y: object) -> arb:
    """``x * y`` from the four products of the endpoints: Arb's midpoint-radius product adds
    ``|mid(x)| rad(y) + |mid(y)| rad(x)`` to the radius, which for wide balls (a force from 10
    to 1e5 N times a direction cosine from 0.96 to 1) loses the sign of the product."""
    (a, b), (c, d) = ends(x), ends(y)
    if not (x.is_finite() and y.is_finite()):
        return x * y
    return hull([a * c, a * d, b * c, b * d])


@_accepts_balls
def meet(x: object, y: object) -> arb:
    """The intersection of two balls known to hold the same number (each an enclosure of it);
    a NaN ball where they are disjoint (which a correct pair never is)."""
    if not x.is_finite():
        return y
    if not y.is_finite():
        return x
    (a, b), (c, d) = ends(x), ends(y)
    lo, hi = (a if bool(a > c) else c), (b if bool(b < d) else d)
    return arb("nan") if bool(lo > hi) else lo.union(hi)


def hull(values: Sequence) -> arb:
    """The union of balls."""
    out = values[0]
    for v in values[1:]:
        out = out.union(v)
    return out


def as_array(box: Sequence) -> np.ndarray:
    """A box ``(n, 2)`` of floats, checked: finite, ``lo <= hi``."""
    box = np.asarray(box, dtype=float)
    if box.ndim != 2 or box.shape[1] != 2 or not np.all(np.isfinite(box)):
        raise ValueError(f"a box must be an (n, 2) array of finite [lo, hi] rows, got {box!r}")
    if np.any(box[:, 0] > box[:, 1]):
        raise ValueError(f"a box needs lo <= hi in every row, got {box.tolist()}")
    return box


def balls(box: ArrayLike) -> list:
    """A box ``(n, 2)`` of floats as a list of ``n`` balls."""
    return [ball(lo, hi) for lo, hi in box]
