"""Tests of the guard: residuals that leave ball arithmetic, or return what a proof cannot use,
are stopped with a named error, in the search and in the verifier.

Each leaky residual below, handed plain ``flint.arb`` balls, makes the search report
"complete, 0 roots" on ``[3.0, 3.3]``, which holds pi (``test_without_the_guard_...`` shows
it, so that these tests fail if the guard is taken away).
"""

import copy
import math
import operator
import pickle

import numpy as np
import pytest
from flint import arb

from mechnum import certify
from mechnum.certify import Ball, BallArithmeticError, ResidualError
from mechnum.certify import _krawczyk as kr
from mechnum.certify import balls as B

BOX = [[3.0, 3.3]]                   # holds pi, the root of sin
J_SIN = lambda X: [[X[0].cos()]]     # noqa: E731

LEAKS = {
    "float of the midpoint": lambda X: [arb(math.sin(float(X[0].mid())))],
    "np.float64": lambda X: [arb(float(np.sin(np.float64(X[0]))))],
    "math.sin": lambda X: [arb(math.sin(X[0]))],
    "an uncertain branch": lambda X: [X[0].sin() if X[0] < 3.14 else arb(1)],
    "bool": lambda X: [X[0].sin() if not X[0] else arb(1)],
    "operator.index": lambda X: [arb([0.5, 0.7][operator.index(X[0])])],
    "int": lambda X: [arb(int(X[0])) - 3 + arb("0.5")],
    "a float of a ball's bound": lambda X: [arb(math.sin(float(X[0].upper())))],
    "the exponent of a ball": lambda X: [arb(X[0].man_exp()[1])],
    "floats from bounds": lambda X: [arb(math.sin(certify.balls.bounds(X[0])[0]))],
    "the box's ends": lambda X: [X[0] * 0 + math.sin(sum(B.interval(X[0])) / 2)],
    "the ball's state": lambda X: [X[0] * 0 + math.sin(_state(X[0]))],
    "a copy": lambda X: [X[0] * 0 + math.sin(copy.copy(X[0]))],
}


def _state(x):
    """A float the ball's pickled state holds, if any (None: it holds none)."""
    state = x.__getstate__()
    floats = [v for value in (state[1] or {}).values() for v in (value or ())]
    return floats[0] if floats else None


@pytest.mark.parametrize("name", LEAKS)
def test_a_residual_that_leaves_ball_arithmetic_is_stopped(name):
    with pytest.raises(BallArithmeticError, match="of a ball|is not certain"):
        certify.roots(LEAKS[name], J_SIN, BOX)


@pytest.mark.parametrize("name", ["float of the midpoint", "an uncertain branch"])
def test_without_the_guard_the_leaks_prove_a_falsehood(monkeypatch, name):
    """What the guard prevents: with plain balls the search calls ``[3.0, 3.3]`` free of
    roots (the sine's root pi is in it)."""
    monkeypatch.setattr(kr, "guarded", lambda box: [B.ball(lo, hi) for lo, hi in box])
    result = certify.roots(LEAKS[name], J_SIN, BOX)
    assert result.complete and result.count == 0


def test_the_verifier_hands_guarded_balls_too():
    f, J = (lambda X: [X[0].sin()]), J_SIN
    cert = certify.roots(f, J, BOX).certificate()
    assert certify.verify(cert, f, J, domain=BOX).count == 1
    with pytest.raises(BallArithmeticError, match="float"):
        certify.verify(cert, LEAKS["float of the midpoint"], J, domain=BOX)


def test_ball_arithmetic_stays_guarded_and_answers_certain_questions():
    x = B.guarded([[3.0, 3.3]])[0]
    lo, hi = B.interval(x)
    assert type(lo) is Ball and lo == 3.0 and hi == 3.3 and B.interval(x + 0) is None
    assert not hasattr(x, "interval")
    for leave in (pickle.dumps, copy.copy, copy.deepcopy):
        with pytest.raises(BallArithmeticError, match="pickling"):
            leave(x)
    for value in (x + 1, 1 + x, x * x, 2 / x, x ** 2, -x, abs(x), x.sin(), x.mid(),
                  x.lower(), x.rad(), x.sin_cos()[1], arb(2) * x, B.sin(x), B.sqrt(x)):
        assert type(value) is Ball
    assert x > 2.9 and not x > 3.4 and x < arb(4) and arb(4) > x and x != 5 and 3.1 in x
    assert B.sin(x).contains(0) and not B.sin(x - 1).contains(0)
    with pytest.raises(BallArithmeticError, match="x >= y is not certain"):
        assert x >= 3.1
    with pytest.raises(BallArithmeticError, match="x == y is not certain"):
        assert x == x
    for leave in (float, int, complex, bool, round, math.floor, math.trunc, operator.index,
                  np.float64, lambda v: np.asarray([v], dtype=float), lambda v: v.fmpz()):
        with pytest.raises(BallArithmeticError):
            leave(x)


def test_a_guarded_ball_encloses_what_the_plain_one_does():
    x, plain = B.guarded([[0.2, 0.9]])[0], B.ball(0.2, 0.9)
    for f in (lambda v: (v * v - 1).exp() / (v + 2), lambda v: v.atan() + v.sqrt()):
        assert arb(f(x)).str() == f(plain).str()


BAD = {
    "None": (lambda X: None, "must return a sequence of 1, got NoneType"),
    "a number": (lambda X: X[0], "must return a sequence of 1, got Ball"),
    "too long": (lambda X: [X[0] - 1, X[0]], "must return a sequence of 1, got 2"),
    "empty": (lambda X: [], "must return a sequence of 1, got 0"),
    "a None component": (lambda X: [None], "returned None .* component 0"),
    "a float component": (lambda X: [0.5], "a float was computed outside ball arithmetic"),
    "a string": (lambda X: ["0"], "returned str"),
    "NaN": (lambda X: [arb("nan")], "not finite at the point"),
    "NaN from a ball": (lambda X: [X[0] * arb("nan")], "not finite at the point"),
    "infinite": (lambda X: [X[0] / 0], "not finite at the point"),
}


@pytest.mark.parametrize("name", BAD)
def test_a_residual_that_returns_the_wrong_thing_is_stopped_at_once(name):
    residual, match = BAD[name]
    calls = []

    def counted(X):
        calls.append(1)
        return residual(X)

    with pytest.raises(ResidualError, match=match):
        certify.roots(counted, lambda X: [[arb(1)]], [[-1.0, 1.0]])
    assert len(calls) <= 2                      # the box, then its midpoint: at once


def test_ints_are_exact_and_accepted():
    result = certify.roots(lambda X: [2 * X[0] - 1], lambda X: [[2]], [[-1.0, 1.0]])
    assert result.count == 1 and result.complete


@pytest.mark.parametrize("jacobian, match", [
    (lambda X: [[1], [1]], "jacobian must return a sequence of rows of 1, got 2"),
    (lambda X: [1], "must return a row 0 of 1, got int"),
    (lambda X: [[1.5]], "float was computed"),
    (lambda X: None, "got NoneType")])
def test_a_jacobian_of_the_wrong_shape_is_stopped(jacobian, match):
    with pytest.raises(ResidualError, match=match):
        certify.roots(lambda X: [X[0] - arb("0.1")], jacobian, [[-1.0, 1.0]])


def test_exclude_and_split_are_checked():
    f, J = (lambda X: [X[0] * X[0] - 2]), (lambda X: [[2 * X[0]]])
    with pytest.raises(ResidualError, match="exclude must return a bool, got Ball"):
        certify.roots(f, J, [[-3.0, 3.0]], exclude=lambda X: X[0] * 0)
    with pytest.raises(BallArithmeticError, match="not certain"):
        certify.roots(f, J, [[-3.0, 3.0]], exclude=lambda X: X[0] > 0)
    with pytest.raises(ResidualError, match="split must return None or"):
        certify.roots(f, J, [[-3.0, 3.0]], split=lambda X: "middle")
    with pytest.raises(ResidualError, match="coordinate 3"):
        certify.roots(f, J, [[-3.0, 3.0]], split=lambda X: (3, 0.0))
    good = certify.roots(f, J, [[-3.0, 3.0]], exclude=lambda X: X[0].lower() > 2.5,
                         split=lambda X: (0, 0.1))
    assert good.count == 2 and good.complete
