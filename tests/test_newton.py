"""Tests of mechnum.newton: textbook systems, criteria, batches, and every failure mode."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.newton import fd_jacobian, solve, solve_batch


def circle_line(x):
    """Unit circle meets the line y = x: roots +-(1, 1)/sqrt(2)."""
    return np.array([x[0] ** 2 + x[1] ** 2 - 1.0, x[0] - x[1]])


def circle_line_jac(x):
    return np.array([[2 * x[0], 2 * x[1]], [1.0, -1.0]])


def test_textbook_system_converges_quadratically():
    res = solve(circle_line, [1.0, 0.5], circle_line_jac, tol=1e-14)
    assert res.converged
    np.testing.assert_allclose(res.x, [2 ** -0.5, 2 ** -0.5], rtol=0, atol=1e-15)
    assert res.history.shape == (res.iterations + 1, 2)
    assert res.residual_norms.shape == (res.iterations + 1,)
    assert res.step_norms.shape == (res.iterations,)
    e = res.step_norms
    # quadratic: once close, each step is at most a modest constant times the square of the last
    assert np.all(e[2:-1] <= 2.0 * e[1:-2] ** 2)


def test_result_is_frozen():
    res = solve(circle_line, [1.0, 0.5], circle_line_jac)
    with pytest.raises(AttributeError):
        res.x = None


def test_step_criterion_counts_the_confirming_step():
    # A linear system: the first step is exact, the second (of size ~0) confirms it.
    A, b = np.array([[3.0, 1.0], [1.0, 2.0]]), np.array([1.0, 1.0])
    step = solve(lambda x: A @ x - b, [5.0, -5.0], lambda x: A, tol=1e-8)
    residual = solve(lambda x: A @ x - b, [5.0, -5.0], lambda x: A, tol=1e-8,
                     criterion="residual")
    assert (step.iterations, residual.iterations) == (2, 1)
    np.testing.assert_allclose(step.x, np.linalg.solve(A, b), atol=1e-14)


def test_norm_choice_changes_the_test_not_the_iterates():
    a = solve(circle_line, [1.0, 0.5], circle_line_jac, norm=np.inf)
    b = solve(circle_line, [1.0, 0.5], circle_line_jac, norm=1)
    np.testing.assert_allclose(a.history[:2], b.history[:2])


def test_finite_difference_jacobian_is_the_default():
    res = solve(circle_line, [1.0, 0.5], tol=1e-12)
    np.testing.assert_allclose(res.x, [2 ** -0.5, 2 ** -0.5], atol=1e-12)
    J = fd_jacobian(circle_line, np.array([0.3, -0.7]))
    np.testing.assert_allclose(J, circle_line_jac([0.3, -0.7]), atol=1e-7)


def test_fd_jacobian_of_a_batch():
    x = np.array([[0.3, -0.7], [1.0, 2.0]])
    J = fd_jacobian(lambda z: np.stack([z[:, 0] ** 2, z[:, 0] * z[:, 1]], axis=-1), x)
    np.testing.assert_allclose(J[1], [[2.0, 0.0], [2.0, 1.0]], atol=1e-6)


@pytest.mark.parametrize("x0", [[np.nan, 1.0], [np.inf, 0.0], [[1.0, 2.0]], [], 3.0])
def test_bad_initial_guess_is_a_value_error(x0):
    with pytest.raises(ValueError, match="x0 must"):
        solve(circle_line, x0, circle_line_jac)


@pytest.mark.parametrize("kwargs, match", [({"criterion": "size"}, "criterion"),
                                           ({"tol": 0.0}, "tol"), ({"tol": np.nan}, "tol"),
                                           ({"maxiter": 0}, "maxiter"), ({"maxiter": 2.5}, "maxiter")])
def test_bad_options_are_value_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve(circle_line, [1.0, 0.5], circle_line_jac, **kwargs)


def test_wrong_shapes_from_the_callables_are_value_errors():
    with pytest.raises(ValueError, match="fun returned shape"):
        solve(lambda x: np.zeros(3), [1.0, 0.5], circle_line_jac)
    with pytest.raises(ValueError, match="jac returned shape"):
        solve(circle_line, [1.0, 0.5], lambda x: np.eye(3))


def test_singular_jacobian_is_named_with_its_iteration():
    parallel = lambda x: np.array([x[0] + x[1] - 1.0, 2 * x[0] + 2 * x[1] - 3.0])  # noqa: E731
    with pytest.raises(SingularJacobianError, match="iteration 0") as info:
        solve(parallel, [0.0, 0.0], lambda x: np.array([[1.0, 1.0], [2.0, 2.0]]))
    assert info.value.result.iterations == 0


def test_numerically_singular_jacobian_is_refused():
    J = np.array([[1.0, 1.0], [1.0, 1.0 + 1e-17]])  # rounds to exactly singular or nearly so
    with pytest.raises(SingularJacobianError, match="condition number"):
        solve(lambda x: J @ x - np.array([1.0, 2.0]), [0.0, 0.0], lambda x: J)


def atan_system(x):
    """Newton on arctan(x) = 0 diverges from |x0| > 1.39 (the iterates alternate and grow)."""
    return np.arctan(x)


def atan_jac(x):
    return np.diag(1.0 / (1.0 + x ** 2))


def test_maxiter_exceeded_raises_with_the_partial_result():
    with pytest.raises(ConvergenceError, match="did not converge in 4 iterations") as info:
        solve(atan_system, [2.0], atan_jac, maxiter=4)
    assert info.value.result.iterations == 4
    assert not info.value.result.converged
    assert np.all(np.abs(info.value.result.history[1:, 0]) > 2.0)


def test_non_finite_iterate_is_not_convergence():
    with pytest.raises(ConvergenceError):
        solve(lambda x: np.exp(x) * 0 + np.where(x > 10, np.nan, x - 20), [0.0],
              lambda x: np.eye(1))


def test_batch_has_per_system_convergence():
    c = np.array([2.0, 3.0, 400.0])
    res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((3, 1)), lambda x: 2 * x[:, :, None])
    np.testing.assert_allclose(res.x[:, 0], np.sqrt(c), rtol=1e-14)
    singles = [solve(lambda x: x ** 2 - ci, [1.0], lambda x: np.diag(2 * x)).iterations
               for ci in c]
    assert res.iterations.tolist() == singles
    assert res.iterations[2] > res.iterations[0]
    assert res.converged.all() and not res.singular.any()


def test_batch_with_fd_jacobian():
    c = np.array([2.0, 5.0])
    res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((2, 1)), tol=1e-12)
    np.testing.assert_allclose(res.x[:, 0], np.sqrt(c), rtol=1e-12)


def test_batch_singular_system_does_not_stop_the_others():
    target = np.array([[4.0], [-1.0]])
    with pytest.raises(SingularJacobianError, match="1 of 3|2 of 3") as info:
        solve_batch(lambda x: x ** 2 - np.vstack([target, [[9.0]]]),
                    np.array([[1.0], [0.0], [1.0]]), lambda x: 2 * x[:, :, None])
    res = info.value.result
    assert res.singular[1] and not res.singular[0]
    np.testing.assert_allclose(res.x[[0, 2], 0], [2.0, 3.0])
    assert res.converged[[0, 2]].all()


def test_batch_non_convergence_names_the_systems():
    fun = lambda x: np.stack([x[0] ** 2 - 4.0, np.arctan(x[1])])  # noqa: E731
    jac = lambda x: np.stack([np.diag(2 * x[0]), atan_jac(x[1])])  # noqa: E731
    with pytest.raises(ConvergenceError, match=r"1 of 2 systems .*\[1\]") as info:
        solve_batch(fun, np.array([[1.0], [2.0]]), jac, maxiter=6)
    assert info.value.result.converged.tolist() == [True, False]


@pytest.mark.parametrize("x0", [np.ones(3), np.ones((2, 2, 2)), np.full((2, 1), np.nan)])
def test_batch_bad_initial_guess(x0):
    with pytest.raises(ValueError, match="x0 must"):
        solve_batch(lambda x: x, x0)


def test_batch_wrong_jacobian_shape():
    with pytest.raises(ValueError, match="jac returned shape"):
        solve_batch(lambda x: x, np.ones((2, 2)), lambda x: np.ones((2, 2)))


@settings(max_examples=60, deadline=None)
@given(a=st.floats(1e-3, 1e3), start=st.floats(0.5, 2.0))
def test_cube_root_from_anywhere_near(a, start):
    x0 = start * np.cbrt(a)
    res = solve(lambda x: x ** 3 - a, [x0], lambda x: np.diag(3 * x ** 2), tol=1e-13)
    assert abs(res.x[0] - np.cbrt(a)) <= 1e-12 * np.cbrt(a)
