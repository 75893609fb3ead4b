"""Tests of mechnum.ode: classical RK4 and multiple shooting."""

import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from mechnum.errors import ConvergenceError, MechnumError, NonFiniteError, SingularJacobianError
from mechnum.ode import multiple_shooting, rk4

EXAMPLES = settings(max_examples=200, deadline=None)


def harmonic(_, y):
    return np.stack((y[..., 1], -y[..., 0]), axis=-1)


def pendulum(_, y):
    """A coupled nonlinear system (the rod's theta'' = -sin(theta) with unit load)."""
    return np.stack((y[..., 1], -np.sin(y[..., 0])), axis=-1)


def observed_orders(f, y0, length, steps, exact):
    errors = [np.abs(rk4(f, y0, np.linspace(0.0, length, n + 1))[-1] - exact).max()
              for n in steps]
    return -np.diff(np.log(errors)) / np.log(np.diff(steps) / steps[:-1] + 1)


def test_fourth_order_on_a_linear_system():
    orders = observed_orders(harmonic, [1.0, 0.0], 2.0, np.array([10, 20, 40, 80]),
                             [np.cos(2.0), -np.sin(2.0)])
    # the observed order is 4 up to terms of relative size O(h) at these steps; 0.1 tells 4 from 3
    # or 5 with room for them
    assert_allclose(orders, 4.0, atol=0.1, rtol=0)


def test_fourth_order_on_a_coupled_nonlinear_system():
    # reference: the same RK4 on a grid 64 times finer (its error is 64**4 times smaller)
    exact = rk4(pendulum, [2.0, 0.0], np.linspace(0.0, 3.0, 2561))[-1]
    orders = observed_orders(pendulum, [2.0, 0.0], 3.0, np.array([40, 80, 160]), exact)
    # as above: 0.1 tells order 4 from 3 or 5
    assert_allclose(orders, 4.0, atol=0.1, rtol=0)


def test_exact_for_cubic_polynomials():
    # RK4 integrates y' = 3 s^2 (a quadrature, Simpson's rule) exactly
    y = rk4(lambda s, y: np.full_like(y, 3.0 * s ** 2), [0.0], np.array([0.0, 0.3, 1.0, 2.0]))
    # exact in exact arithmetic (Simpson's rule integrates cubics exactly): round-off of values up
    # to 8 is a few ulps, eps 8 = 1.8e-15
    assert_allclose(y[:, 0], [0.0, 0.027, 1.0, 8.0], rtol=0, atol=1e-14)


def test_batch_equals_separate_runs_and_backward_grid():
    s = np.linspace(0.0, 1.5, 31)
    batch = rk4(harmonic, [[1.0, 0.0], [0.0, 2.0]], s)
    for i, y0 in enumerate(([1.0, 0.0], [0.0, 2.0])):
        assert np.array_equal(batch[:, i], rk4(harmonic, y0, s))
    back = rk4(harmonic, batch[-1, 0], s[::-1])
    # RK4's global error at h = 0.05 over 1.5 there and back is about 7e-9 here (h^4 = 6e-6 times a
    # small constant): 1e-6 is a margin of a hundred
    assert_allclose(back[-1], [1.0, 0.0], rtol=0, atol=1e-6)


def test_complex_states_give_complex_step_derivatives():
    h = 1e-30
    y = rk4(pendulum, [2.0 + 1j * h, 0.0], np.linspace(0.0, 1.0, 21))[-1]
    up, down = (rk4(pendulum, [2.0 + d, 0.0], np.linspace(0.0, 1.0, 21))[-1]
                for d in (1e-6, -1e-6))
    # the complex step is exact to round-off; the central difference errs by d^2 |y'''| ~ 1e-12 and
    # by round-off eps / d ~ 2e-10, relative: 1e-8 covers both
    assert_allclose(y.imag / h, (up - down).real / 2e-6, rtol=1e-8)


@EXAMPLES
@given(st.floats(-20, 20), st.floats(1e-3, 10.0), st.integers(1, 60))
def test_linear_decay_matches_the_rk4_amplification_factor(a, length, steps):
    # for y' = a y, one RK4 step multiplies by 1 + z + z^2/2 + z^3/6 + z^4/24, z = a h
    z = a * length / steps
    y = rk4(lambda s, y: a * y, [1.0], np.linspace(0.0, length, steps + 1))
    growth = 1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24
    # each step rounds the product by a few ulps (eps = 2.2e-16); over n steps the relative error
    # grows at most linearly: 1e-12 n is a margin of over a thousand
    assert_allclose(y[-1, 0], growth ** steps, rtol=1e-12 * steps)


@pytest.mark.parametrize("y0, s, match", [
    ([np.nan], [0.0, 1.0], "y0 must be finite"),
    (["a"], [0.0, 1.0], "real or complex numeric"),
    ([1.0], [0.0], "at least 2 nodes"),
    ([1.0], [0.0, 1.0, 0.5], "strictly"),
    ([1.0], [0.0, np.inf], "s must be finite"),
    ([1.0], [[0.0, 1.0]], "s must have 1 dimension"),
    ([1.0], [0.0, 1.0j], "s must be real"),
])
def test_bad_input(y0, s, match):
    with pytest.raises(ValueError, match=match):
        rk4(lambda s, y: y, y0, s)


def test_wrong_shape_from_f():
    with pytest.raises(ValueError, match="shape"):
        rk4(lambda s, y: np.zeros(3), [1.0, 2.0], [0.0, 1.0])


def sine_bvp(c, a, b):
    """y'' = -c y, y(0) = a, y(1) = b: f, bc and the exact solution."""
    w = np.sqrt(c)

    def f(_, y):
        return np.stack((y[..., 1], -c * y[..., 0]), axis=-1)

    def bc(ya, yb):
        return np.array([ya[0] - a, yb[0] - b])

    def exact(s):
        return a * np.cos(w * s) + (b - a * np.cos(w)) / np.sin(w) * np.sin(w * s)

    return f, bc, exact


@pytest.mark.parametrize("segments", [1, 2, 5, 40])
def test_multiple_shooting_solves_a_linear_bvp_in_one_step(segments):
    f, bc, exact = sine_bvp(4.0, 0.5, -1.0)
    s = np.linspace(0.0, 1.0, 41)
    sol = multiple_shooting(f, bc, s, np.zeros((41, 2)), segments=segments)
    assert sol.newton.iterations == 1 and sol.segment_starts.size == segments
    assert_allclose(sol.x[:, 0], exact(s), rtol=0, atol=1e-7)   # RK4 at h = 1/40
    # the grid is handed back as given or rebuilt from the segments' ends: round-off of O(1) numbers
    assert_allclose(sol.s, s, rtol=1e-12)


@EXAMPLES
@given(st.floats(0.01, 9.0), st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.integers(1, 8))
@example(1.0, 7.060005362754902e-11, 0.0, 1)
def test_multiple_shooting_solves_the_discrete_rk4_problem(c, a, b, segments):
    # the RK4 propagator M over [0, 1] (from the identity) gives the discrete BVP's answer:
    # y(1) = M00 a + M01 y'(0) = b; every number of segments must find that same solution.
    # The guess is far from it (a zero guess would already meet the absolute tolerance 1e-10
    # when |a|, |b| are below it, and be returned as it is: a = 7e-11, b = 0).
    f, bc, _ = sine_bvp(c, a, b)
    s = np.linspace(0.0, 1.0, 33)
    M = rk4(f, np.eye(2), s)[-1].T
    discrete = rk4(f, [a, (b - M[0, 0] * a) / M[0, 1]], s)
    sol = multiple_shooting(f, bc, s, np.ones((33, 2)), segments=segments)
    scale = max(np.abs(discrete).max(), 1.0) / abs(M[0, 1])       # M01 ~ sin(sqrt(c))
    # the discrete (RK4) solution of a linear BVP, solved in one Newton step: round-off amplified by
    # the condition 1/|M01| of the shooting matrix (scale)
    assert_allclose(sol.x, discrete, rtol=0, atol=1e-12 * scale)
    # the boundary residual after that step: round-off of the same size; 1e-10 leaves the room of
    # Newton's stopping test on the residual
    assert_allclose(bc(sol.x[0], sol.x[-1]), 0.0, rtol=0, atol=1e-10 * scale)


def test_multiple_shooting_tames_an_unstable_shooting_problem():
    # y'' = 400 y: a start error grows like exp(20) over [0, 1]; 20 segments cut it to e
    s = np.linspace(0.0, 1.0, 401)

    def f(_, y):
        return np.stack((y[..., 1], 400.0 * y[..., 0]), axis=-1)

    def bc(ya, yb):
        return np.array([ya[0] - 1.0, yb[0] - 1.0])

    sol = multiple_shooting(f, bc, s, np.zeros((401, 2)), segments=20)
    exact = np.cosh(20.0 * (s - 0.5)) / np.cosh(10.0)
    # RK4 at h = 1/400 on cosh(20 (s - 1/2)): relative error 5e-7 here ((20 h)^4 = 6e-6 times a
    # small constant); 1e-6 bounds it, atol 1e-12 covers the smallest values
    assert_allclose(sol.x[:, 0], exact, rtol=1e-6, atol=1e-12)


def test_multiple_shooting_reports_a_bvp_with_no_solution():
    # y'' = -pi^2 y, y(0) = 0, y(1) = 1 has no solution: the Jacobian is singular
    f, _, _ = sine_bvp(np.pi ** 2, 0.0, 1.0)
    with pytest.raises(MechnumError) as error:
        multiple_shooting(f, lambda ya, yb: np.array([ya[0], yb[0] - 1.0]),
                          np.linspace(0.0, 1.0, 201), np.zeros((201, 2)), segments=4)
    assert isinstance(error.value, (SingularJacobianError, ConvergenceError))


@pytest.mark.parametrize("kwargs, match", [
    (dict(segments=0), "segments must be an integer >= 1"),
    (dict(segments=41), "segments must be at most"),
    (dict(seed=np.zeros((40, 2))), "seed must have shape"),
    (dict(seed=np.full((41, 2), np.nan)), "seed must be finite"),
    (dict(tol=-1.0), "tol must be positive"),
    (dict(bc=lambda ya, yb: np.zeros(3)), "bc returned shape"),
])
def test_multiple_shooting_bad_input(kwargs, match):
    f, bc, _ = sine_bvp(1.0, 0.0, 1.0)
    args = dict(fun=f, bc=bc, s=np.linspace(0.0, 1.0, 41), seed=np.zeros((41, 2)))
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        multiple_shooting(args.pop("fun"), args.pop("bc"), args.pop("s"), args.pop("seed"),
                          **args)


# --- issue 23: complex stages, non-finite states, changing shapes, bounds -----------------------

def test_a_complex_f_makes_the_states_complex():
    # D10: y' = i y from the real y(0) = 1 is exp(i s); the imaginary part used to be dropped
    # with a ComplexWarning
    s = np.linspace(0.0, 1.0, 101)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        y = rk4(lambda _, y: 1j * y, [1.0], s)
    assert np.iscomplexobj(y)
    # RK4 at h = 0.01 on exp(i s): relative error about h^4 / 120 = 8e-11 (measured 8.3e-11); 1e-9
    # is a margin of ten
    assert_allclose(y[:, 0], np.exp(1j * s), rtol=1e-9)
    # complex from a later stage on (f real at s = 0)
    late = rk4(lambda t, y: (1j if t > 0 else 1.0) * y, [1.0], [0.0, 0.5, 1.0])
    assert np.iscomplexobj(late) and late[1, 0].imag != 0


@pytest.mark.parametrize("f, s, match", [
    (lambda t, y: np.full_like(y, np.nan), [0.0, 1.0], "not finite at node 1"),
    (lambda t, y: y if t < 0.5 else np.full_like(y, np.inf), [0.0, 0.25, 0.5, 1.0],
     "not finite at node 2"),
    (lambda t, y: -y ** 3, [0.0, 1e300], r"h = 1e\+300"),
])
def test_a_state_that_is_not_finite_is_a_named_error(f, s, match):
    # D13: NaN from f, or an overflowing step, used to be returned silently
    with pytest.raises(NonFiniteError, match=match):
        rk4(f, [1.0, 2.0], s)


def test_f_that_changes_shape_is_a_value_error():
    # R4: f of the right shape at s[0] and of another later
    with pytest.raises(ValueError, match=r"fun returned shape \(3,\) at s = 0.5"):
        rk4(lambda t, y: y if t < 0.5 else np.zeros(3), [1.0, 2.0], [0.0, 0.5, 1.0])


def test_the_output_is_bounded():
    with pytest.raises(ValueError, match="bound on the memory"):
        rk4(lambda t, y: y, np.zeros((1000, 1000)), np.linspace(0.0, 1.0, 200))
    f, bc, _ = sine_bvp(1.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="bound on the work"):
        multiple_shooting(f, bc, np.linspace(0.0, 1.0, 41), np.zeros((41, 2)), maxiter=10 ** 6)
