"""Tests of mechnum.continuation: natural-parameter paths and their branch jumps,
pseudo-arclength continuation through folds."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from mechnum import newton
from mechnum.continuation import PathResult, pseudo_arclength, solve_path
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.results import STATUSES, Result


def cubic(u):      # x**3 - 3 x = p: folds at (1, -2) and (-1, 2)
    return np.array([u[0] ** 3 - 3.0 * u[0] - u[1]])


def cubic_jac(u):
    return np.array([[3.0 * u[0] ** 2 - 3.0, -1.0]])


def test_the_s_curve_is_traced_through_both_folds():
    branch = pseudo_arclength(cubic, [-2.5, -8.125], cubic_jac, direction=[1.0, 0.0],
                              step=0.05, steps=400, stop=lambda u: u[0] > 2.5)
    assert branch.complete and branch.x[-1, 0] > 2.5
    # the corrector stops at CORRECTOR_TOL = 1e-10 on the step (relative): the residual of x^3 - 3x
    # - p at points of size <= 8 is then far below 1e-9
    assert_allclose([cubic(u)[0] for u in branch.x], 0.0, atol=1e-9)
    assert branch.folds.size == 2
    # a fold is located by the sign change of the tangent's p-component and refined by the corrector
    # (tol 1e-10): 1e-9 allows for it
    assert_allclose(branch.fold_points, [[-1.0, 2.0], [1.0, -2.0]], atol=1e-9, rtol=0)
    # the folds are where the parameter turns back, and x grows all the way
    p = branch.x[:, 1]
    for i, j in zip(branch.folds, np.append(branch.folds[1:], len(p) - 1)):
        assert np.all(np.sign(np.diff(p[i + 1:j + 1])) == np.sign(np.diff(p[i + 1:i + 3]))[0])
    assert np.all(np.diff(branch.x[:, 0]) > 0)
    # unit tangents: normalised in floating point, a few ulps
    assert_allclose(np.linalg.norm(branch.tangent, axis=1), 1.0, rtol=1e-12)


def test_the_arclength_step_is_the_distance_along_the_tangent():
    circle = (lambda u: np.array([u[0] ** 2 + u[1] ** 2 - 1.0]),
              lambda u: np.array([[2.0 * u[0], 2.0 * u[1]]]))
    branch = pseudo_arclength(circle[0], [1.0, 0.0], circle[1], step=0.1, max_step=0.1,
                              steps=10)
    assert len(branch.x) == 11 and branch.folds.size == 0
    angles = np.arctan2(branch.x[:, 1], branch.x[:, 0])
    assert_allclose(np.sin(np.diff(angles)), 0.1, rtol=1e-9)   # 0.1 along the tangent


def test_a_start_off_the_curve_is_refused():
    with pytest.raises(ValueError, match="not on the curve"):
        pseudo_arclength(cubic, [0.0, 1.0], cubic_jac)


def test_a_curve_that_ends_is_reported():
    def fun(u):      # sqrt(x) = p, which Newton cannot continue below x = 0
        return np.array([np.sqrt(u[0]) - u[1]]) if u[0] >= 0 else np.array([np.nan])

    def jac(u):
        return np.array([[0.5 / np.sqrt(abs(u[0])), -1.0]])

    branch = pseudo_arclength(fun, [1.0, 1.0], jac, direction=[-1.0, 0.0], step=0.1,
                              steps=200, min_step=1e-6)
    # the branch ends at x = 0, where the Jacobian blows up: 1e-3 asks only that it got there
    assert not branch.complete and branch.x[-1, 0] < 1e-3 and branch.status == "stagnated"
    # the same curve the other way does not end: traced to its 20 points, complete
    onward = pseudo_arclength(fun, [1.0, 1.0], jac, direction=[1.0, 0.0], step=0.1, steps=20)
    assert onward.complete and onward.status == "converged" and len(onward.x) == 21
    with pytest.raises(ConvergenceError):
        pseudo_arclength(fun, [1.0, 1.0], jac, step=10.0, min_step=1.0, maxiter=1)


def test_a_bifurcation_point_has_no_tangent():
    # x^2 = p^2: the lines x = p and x = -p cross at the origin, where F' = 0
    cross = (lambda u: np.array([u[0] ** 2 - u[1] ** 2]),
             lambda u: np.array([[2 * u[0], -2 * u[1]]]))
    with pytest.raises(SingularJacobianError, match="bifurcation"):
        pseudo_arclength(cross[0], [0.0, 0.0], cross[1])
    branch = pseudo_arclength(cross[0], [1.0, 1.0], cross[1], steps=5)   # away from it, a line
    # points on the line x = p, corrected to CORRECTOR_TOL = 1e-10 relative and with a quadratic
    # last step: round-off
    assert_allclose(branch.x[:, 0], branch.x[:, 1], rtol=1e-12)


@pytest.mark.parametrize("kwargs, error, match", [
    ({"direction": [0.0, 0.0]}, ValueError, "direction must be a non-zero"),
    ({"direction": [np.nan, 1.0]}, ValueError, "direction must be finite"),
    ({"fun": lambda u: np.zeros(2)}, ValueError, r"fun must return a real array of shape \(1,\)"),
    ({"jac": lambda u: np.zeros((2, 2))}, ValueError, r"jac must return .* shape \(1, 2\)"),
    ({"steps": 10 ** 7}, ValueError, "bound on the work"),
    ({"seed": [1.0]}, ValueError, "seed must hold the unknowns and the parameter"),
])
def test_pseudo_arclength_refuses_bad_input(kwargs, error, match):
    args = {"fun": cubic, "jac": cubic_jac, "seed": [-2.5, -8.125]} | kwargs
    with pytest.raises(error, match=match):
        pseudo_arclength(args.pop("fun"), args.pop("seed"), args.pop("jac"), **args)


def test_branch_follows_the_result_contract():
    branch = pseudo_arclength(cubic, [-2.5, -8.125], cubic_jac, direction=[1.0, 0.0],
                              step=0.05, steps=30)
    assert isinstance(branch, Result) and branch.converged
    assert branch.nfev > 30 and branch.njev > 30 and branch.iterations >= 30


# --- natural-parameter paths ---------------------------------------------------------------------

def square(x, c):
    return x ** 2 - c[:, None]


def square_jac(x, c):
    return 2 * x[:, :, None]


def test_solve_path_follows_a_branch_and_reports_failures():
    # x**2 = p on p from 1 down to -1: the positive root exists until p = 0
    p = np.linspace(1.0, -1.0, 21)
    path = solve_path(square, [1.0], p, square_jac)
    ok = p > 0
    assert np.array_equal(path.converged, ok)
    # the path's Newton stops at ||f|| <= PATH_TOL = 1e-12, reached by a quadratic last step that
    # leaves an error far below it: round-off of sqrt(p)
    assert_allclose(path.x[ok, 0], np.sqrt(p[ok]), rtol=1e-12)
    assert np.isnan(path.x[~ok]).all() and set(path.status[~ok]) <= set(STATUSES) - {"converged"}
    # two paths at once, with their own parameters; a failed path may be abandoned
    both = solve_path(square, [[1.0], [-np.sqrt(3.0)]], np.stack([p, p + 2], axis=1),
                      square_jac, resume=False)
    assert both.converged[:, 1].all() and both.converged[:, 0].sum() == ok.sum()
    assert (both.status[~ok, 0][1:] == "lost").all()      # abandoned after its first failure
    # as above: the negative root to round-off
    assert_allclose(both.x[:, 1, 0], -np.sqrt(p + 2), rtol=1e-12)
    with pytest.raises(ValueError, match="params"):
        solve_path(square, [[1.0], [2.0]], p, square_jac)


def arm(q, P):
    """A two-link arm of unit links reaching the points P: the loop equations in its angles."""
    a, b = q[:, 0], q[:, 0] + q[:, 1]
    return np.stack([np.cos(a) + np.cos(b) - P[:, 0], np.sin(a) + np.sin(b) - P[:, 1]], axis=-1)


def arm_jac(q, P):
    a, b = q[:, 0], q[:, 0] + q[:, 1]
    return np.stack([np.stack([-np.sin(a) - np.sin(b), -np.sin(b)], -1),
                     np.stack([np.cos(a) + np.cos(b), np.cos(b)], -1)], axis=1)


def reach(n):
    """Points that pass within 0.001 of the arm's reach of 2, and the elbow-up start."""
    phi = np.linspace(0.0, 1.0, n)
    r = 1.999 - 0.6 * np.abs(phi - 0.5)
    elbow = np.arccos(r[0] ** 2 / 2 - 1)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi)]), [-elbow / 2, elbow]


@pytest.mark.parametrize("n", [5, 9, 21])
def test_a_leap_across_the_fold_is_a_branch_jump(n):
    # near full reach the elbow angle q[1] is 0.063 and the Jacobian nearly singular; the
    # secant prediction crosses q[1] = 0 and Newton converges with the elbow bent the other way
    # (det J = sin q[1] < 0): the other assembly, which no continuous motion of this path reaches
    points, q0 = reach(n)
    path = solve_path(arm, q0, points, arm_jac)
    jump = np.flatnonzero(path.status == "branch-jump")
    assert jump.tolist() == [n // 2 + 1]
    assert np.isnan(path.x[jump]).all() and np.isnan(path.det[jump]).all()
    ok = path.converged
    assert ok.sum() == n - 1 and np.all(path.det[ok] > 0) and np.all(path.x[ok, 1] > 0)
    # the determinant is computed from the same converged x as sin(x_1): round-off
    assert_allclose(path.det[ok], np.sin(path.x[ok, 1]), rtol=1e-12)
    # the same steps, solved one by one from the last point: Newton does land on the other
    # assembly, with the elbow angle of the opposite sign
    before = path.x[jump[0] - 1]
    other = newton.solve(lambda q: arm(q[None], points[jump])[0],
                         before + (before - path.x[jump[0] - 2]), tol=1e-12)
    assert other.x[1] < 0


def test_a_point_that_moves_too_fast_is_a_branch_jump():
    # x = 10 tanh(100 (p - 0.5)) changes by 10 over a step of 0.1 where the steps before it
    # moved x by 4e-8 at most: the point cannot be trusted to be on the branch followed
    def fun(x, c):
        return x - 10 * np.tanh(100 * (c[:, None] - 0.5))

    p = np.linspace(0.0, 1.0, 11)
    path = solve_path(fun, [-10.0], p, lambda x, c: np.ones((len(x), 1, 1)))
    assert path.status[5:].tolist().count("branch-jump") >= 1
    assert path.converged[:5].all()
    free = solve_path(fun, [-10.0], p, lambda x, c: np.ones((len(x), 1, 1)), max_jump=None)
    assert free.converged.all()
    # as above, with atol for the points near the origin (tanh of about 0)
    assert_allclose(free.x[:, 0], 10 * np.tanh(100 * (p - 0.5)), rtol=1e-12, atol=1e-12)


def test_solve_path_with_the_jacobian_from_fun():
    p = np.linspace(1.0, 4.0, 7)
    path = solve_path(lambda x, c: (square(x, c), square_jac(x, c)), [1.0], p, jac=True)
    assert path.converged.all() and path.nfev == path.njev
    # as above: ||f|| <= PATH_TOL = 1e-12 after a quadratic last step
    assert_allclose(path.x[:, 0], np.sqrt(p), rtol=1e-12)
    assert isinstance(path, PathResult) and isinstance(path, Result)


def test_solve_path_of_no_steps_is_empty():
    path = solve_path(square, [1.0], [], square_jac)
    assert path.x.shape == (0, 1) and path.status.shape == (0,)
    batch = solve_path(square, [[1.0], [2.0]], np.empty((0, 2)), square_jac)
    assert batch.x.shape == (0, 2, 1) and batch.converged.shape == (0, 2)


@pytest.mark.parametrize("kwargs, match", [
    ({"params": 2.0}, "one parameter set per step"),
    ({"params": [1.0, np.nan]}, "params must be finite"),
    ({"params": [1.0, np.inf]}, "params must be finite"),
    ({"params": [1.0, 2.0 + 1j]}, "params must be real"),
    ({"resume": "yes"}, "resume must be True or False"),
    ({"max_jump": 0.0}, "max_jump must be positive"),
    ({"maxiter": 10 ** 9}, "bound on the work"),
    ({"domain": lambda x: np.ones(5, bool)}, "domain returned shape"),
])
def test_solve_path_refuses_bad_input(kwargs, match):
    args = {"params": [1.0, 2.0]} | kwargs
    with warnings.catch_warnings():
        warnings.simplefilter("error")      # no ComplexWarning on the way
        with pytest.raises(ValueError, match=match):
            solve_path(square, [1.0], args.pop("params"), square_jac, **args)


# --- property tests: the documented tolerance, or a reported failure -----------------------------

@settings(max_examples=100, deadline=None)
@given(a=st.floats(0.1, 10.0), b=st.floats(-10.0, 10.0), steps=st.integers(2, 40),
       span=st.floats(0.1, 5.0))
def test_solve_path_points_meet_the_residual_tolerance(a, b, steps, span):
    # the real root of x^3 + a x = p + b (monotone in x: one branch, no fold) along p
    p = np.linspace(0.0, span, steps)
    fun = lambda x, c: x ** 3 + a * x - (c[:, None] + b)  # noqa: E731
    path = solve_path(fun, [0.0], p, lambda x, c: (3 * x ** 2 + a)[:, :, None], tol=1e-10)
    ok = path.converged
    residual = np.abs(path.x[ok, 0] ** 3 + a * path.x[ok, 0] - p[ok] - b)
    # the criterion itself: the call's tolerance 1e-10 on the residual
    assert np.all(residual <= 1e-10)
    assert set(path.status[~ok]) <= set(STATUSES) and np.isnan(path.x[~ok]).all()
    assert "branch-jump" not in path.status    # one branch, no fold: nothing to jump to


@settings(max_examples=50, deadline=None)
@given(rx=st.floats(0.2, 5.0), ry=st.floats(0.2, 5.0), step=st.floats(0.01, 0.3))
def test_pseudo_arclength_points_lie_on_the_curve(rx, ry, step):
    # the ellipse (x / rx)^2 + (p / ry)^2 = 1 from (rx, 0): two folds on every lap
    fun = lambda u: np.array([(u[0] / rx) ** 2 + (u[1] / ry) ** 2 - 1.0])  # noqa: E731
    jac = lambda u: np.array([[2 * u[0] / rx ** 2, 2 * u[1] / ry ** 2]])  # noqa: E731
    try:
        branch = pseudo_arclength(fun, [rx, 0.0], jac, step=step * min(rx, ry), steps=60)
    except ConvergenceError as error:     # a failure is named
        assert "no point" in str(error)
        return
    gaps = np.abs([fun(u)[0] for u in branch.x])
    # the corrector stops on its relative step (1e-10) after a quadratic last step; the residual of
    # an equation of order one is then round-off, and 1e-8 leaves room for the worst ellipses (axes
    # ratio 25, whose condition multiplies it)
    assert np.all(gaps <= 1e-8)
    # unit tangents: normalised in floating point, a few ulps
    assert_allclose(np.linalg.norm(branch.tangent, axis=1), 1.0, rtol=1e-12)
