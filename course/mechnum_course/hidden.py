"""The hidden cases of the self-checked exercises: inputs that a grade adds to the public ones.

A student's self-check runs the public cases only; ``make grade`` and the nbgrader course run
these too, so that an answer written to pass the public cases (or one that reads their stored
answers) does not pass. This module holds inputs only, never an answer: the grader's sandboxed
process that runs a student's function loads it on its own (it imports nothing of the
instructors' package), and the expected answers are computed outside that process by the
reference solutions.

``HIDDEN[number]()`` is the list of the hidden :class:`~mechnum.exercises._harness.Case` of an
exercise.
"""

import dataclasses
from types import SimpleNamespace

import numpy as np

from mechnum.exercises._ch2 import FINGER, freudenstein
from mechnum.exercises._ch3 import rod
from mechnum.exercises._ch5 import Polynomial
from mechnum.exercises._ch6 import column, platform
from mechnum.exercises._ch7 import OTHER, state
from mechnum.exercises._harness import Case
from mechnum.mechanisms import hacksaw
from mechnum.mechanisms.actuator.study import ANNEX


def _loop():
    rng = np.random.default_rng(101)
    cases = [Case("the study's saw near its dead point, theta2 = 3.1 rad",
                  (np.array([0.2, 0.3, 2.6]), 3.1, 0.045, 0.075, 0.17))]
    for k in range(2):
        q = rng.uniform([-0.5, -np.pi, -np.pi], [0.5, np.pi, np.pi])
        cases.append(Case(f"a hidden random state {k + 1}",
                          (q, float(rng.uniform(-np.pi, np.pi)), *rng.uniform(0.02, 0.3, 3))))
    return cases


def _newton():
    def saw(theta2, geometry):
        mech = hacksaw.Geometry(*geometry)
        return (lambda q: hacksaw.position_residual(mech, q, theta2),
                lambda q: hacksaw.position_jacobian(mech, q))
    three = (lambda x: np.array([x[0] + x[1] ** 2 - 2.0, np.sin(x[1]) + x[2] - 1.0,
                                 x[0] * x[2] - 0.5]),
             lambda x: np.array([[1.0, 2 * x[1], 0.0], [0.0, np.cos(x[1]), 1.0],
                                 [x[2], 0.0, x[0]]]))  # a root near (1.48, 0.72, 0.34)
    return [Case("the hacksaw at theta2 = 4 rad, tol = 1e-12",
                 (*saw(4.0, (0.045, 0.075, 0.17)), np.array([-0.1, -0.5, 3.0]), 1e-12, 50)),
            Case("a 3 x 3 system from (1.2, 0.9, 0.4), tol = 1e-11",
                 (*three, np.array([1.2, 0.9, 0.4]), 1e-11, 30))]


def _update():
    rng = np.random.default_rng(131)
    B = rng.normal(size=(5, 5)) + 5 * np.eye(5)
    scaled = np.diag([100.0, 1.0, 0.01]) + 0.001 * rng.normal(size=(3, 3))
    return [Case("a random 5 x 5 matrix, step and change",
                 (np.linalg.inv(B), rng.normal(size=5), rng.normal(size=5))),
            Case("a 3 x 3 matrix of rows of sizes 100, 1 and 0.01",
                 (np.linalg.inv(scaled), rng.normal(size=3), rng.normal(size=3)))]


def _sweep():
    rng = np.random.default_rng(121)
    M = rng.normal(size=(7, 7))
    D = rng.normal(size=(4, 4)) + 6 * np.eye(4)
    return [Case("a random 7 x 7 symmetric positive definite system, omega = 0.8",
                 (M @ M.T + 7 * np.eye(7), rng.normal(size=7), rng.normal(size=7), 0.8)),
            Case("a non-symmetric diagonally dominant 4 x 4 system, omega = 1.1",
                 (D, rng.normal(size=4), rng.normal(size=4), 1.1)),
            Case("a 1 x 1 system, omega = 1.5",
                 (np.array([[3.0]]), np.array([2.0]), np.array([5.0]), 1.5))]


def _lstsq():
    rng = np.random.default_rng(122)
    A, b = freudenstein(np.linspace(5.2, 5.3, 9), FINGER)
    return [Case("a random 20 x 5 matrix", (rng.normal(size=(20, 5)), rng.normal(size=20))),
            Case("Freudenstein's 9 x 3 matrix over 0.1 rad", (A, b)),
            Case("a square 4 x 4 system", (rng.normal(size=(4, 4)) + 3 * np.eye(4),
                                           rng.normal(size=4)))]


def _step():
    return [Case("y' = -y^3 + s at s = 0.3, h = 0.2",
                 (lambda s, y: -y ** 3 + s, 0.3, np.array([1.2, -0.4]), 0.2)),
            Case("a rod (EI = 0.5, n = (1, -1) N) at s = 0.2, h = 0.2",
                 (rod(0.5, (1.0, -1.0)), 0.2, np.array([0.1, 0.0, 0.3, 0.4]), 0.2)),
            Case("y' = cos(s) y backwards, h = -0.1",
                 (lambda s, y: np.cos(s) * y, 1.0, np.array([0.5]), -0.1))]


def _shooting():
    return [Case("a rod with EI = 0.5, L = 2 m, 41 nodes",
                 (np.array([0.3, -0.5, 0.8]), 0.5, 2.0, np.array([1.2, 0.9]), 41)),
            Case("one RK4 step (2 nodes)",
                 (np.array([0.2, 0.1, -0.1]), 1.0, 0.3, np.array([0.3, 0.0]), 2))]


def _companion():
    return [Case("a line, 2 t - 3", (np.array([-3.0, 2.0]),)),
            Case("(t - 0.5)^2 (t + 1) times 3", (3 * np.poly([0.5, 0.5, -1.0])[::-1],)),
            Case("a degree-5 polynomial with roots 1, 1.1, 1.2, -5, 0.01 times -0.5",
                 (-0.5 * np.poly([1.0, 1.1, 1.2, -5.0, 0.01])[::-1],))]


def _prr3_step():
    g = SimpleNamespace(a=0.4, L=0.9, B2=2.2, B3=1.4, H3=1.8)
    return [Case("a mechanism with a = 0.4, L = 0.9 m from the pose (0.7, 0.6, 1.0)",
                 (np.array([0.7, 0.6, 1.0]), np.array([0.4, 0.8, 0.6]), g)),
            Case("the same mechanism from the pose (0.2, 0.9, -1.3)",
                 (np.array([0.2, 0.9, -1.3]), np.array([0.1, 1.2, 0.3]), g))]


def _tip():
    return [Case("EI = 0.3, L = 1.5 m, psi = 2 rad, k_rel = -0.7, mode 1",
                 (0.3, 1.5, 2.0, -0.7, 1)),
            Case("EI = 1, L = 0.4 m, psi = 5 rad, k_rel = 0.1, mode 2", (1.0, 0.4, 5.0, 0.1, 2))]


def _pin():
    rng = np.random.default_rng(152)
    return [Case(f"hidden random mechanism {k + 1}",
                 (rng.normal(size=(2, 2)), rng.normal(size=(2, 2)), rng.normal(size=(2, 2)),
                  rng.uniform(-np.pi, np.pi, 2), rng.normal(size=2))) for k in range(2)]


def _krawczyk():
    def case(label, coefficients, lo, hi):
        p = Polynomial(coefficients)
        return Case(label, (p.at, p.slope, lo, hi))
    return [case("x^2 - 3 on [1.6, 1.9] (one root)", (-3, 0, 1), 1.6, 1.9),
            case("(x - 2)(x + 1) on [3, 4] (no root)", (-2, -1, 1), 3.0, 4.0),
            case("x^2 - 0.25 on [-1, 1.2] (two roots)", (-0.25, 0, 1), -1.0, 1.2)]


def _index():
    rng = np.random.default_rng(161)
    M = rng.normal(size=(8, 8))
    return [Case("a column pinned at its tip (30 segments), P L^2/EI = 25", (*column(25.0, 30),)),
            Case("a random symmetric 8 x 8 H with three constraints",
                 (M + M.T, rng.normal(size=(3, 8)))),
            Case("H = diag(-1, -2, 3) with the constraint v_1 = 0",
                 (np.diag([-1.0, -2.0, 3.0]), np.array([[1.0, 0.0, 0.0]])))]


def _rigid():
    rng = np.random.default_rng(162)
    return [Case("a platform of side 0.5 m turned by 2.5 rad", (platform((-0.3, 0.4), 2.5, 0.5),
                                                             0.5)),
            Case("the mirror image of a platform of side 0.3 m",
                 (platform((0.2, 0.2), -1.0, 0.3, mirror=True), 0.3)),
            Case("three hidden random points, a = 1 m", (rng.normal(size=(3, 2)), 1.0))]


def _coefficients():
    third = dataclasses.replace(OTHER, o2=0.2, b=0.3, l=0.45)
    cases = []
    for mech, t, label in ((ANNEX, 0.35, "the chapter's mechanism at t = 0.35 s"),
                           (ANNEX, 0.85, "the chapter's mechanism at t = 0.85 s"),
                           (third, 0.55, "a mechanism with b = 0.3 m, l = 0.45 m at t = 0.55 s")):
        s = state(mech, t)
        cases.append(Case(label, (s.theta2, s.theta4, s.a, mech.l, mech.b)))
    return cases


def _force():
    heavy = dataclasses.replace(ANNEX, m2=4.0, g3=0.25)
    return [Case("the chapter's mechanism at t = 0.45 s, g = 9.81 m/s^2",
                 (state(ANNEX, 0.45), ANNEX, 9.81)),
            Case("a mechanism with m2 = 4 kg, g3 = 0.25 m at t = 0.9 s, g = 1.62 m/s^2",
                 (state(heavy, 0.9), heavy, 1.62))]


HIDDEN = {"1.1": _loop, "1.2": _newton, "1.3": _update, "2.1": _sweep, "2.2": _lstsq, "3.1": _step,
          "3.2": _shooting, "4.1": _companion, "4.2": _prr3_step, "5.1": _tip, "5.2": _pin,
          "5.3": _krawczyk, "6.1": _index, "6.2": _rigid, "7.1": _coefficients, "7.2": _force}
"""The hidden cases of each self-checked exercise, by its number (functions that build them)."""
