"""Tests of mechnum.continuation: pseudo-arclength continuation through folds."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from mechnum.continuation import pseudo_arclength
from mechnum.errors import ConvergenceError


def cubic(u):      # x**3 - 3 x = p: folds at (1, -2) and (-1, 2)
    return np.array([u[0] ** 3 - 3.0 * u[0] - u[1]])


def cubic_jac(u):
    return np.array([[3.0 * u[0] ** 2 - 3.0, -1.0]])


def test_the_s_curve_is_traced_through_both_folds():
    branch = pseudo_arclength(cubic, cubic_jac, [-2.5, -8.125], direction=[1.0, 0.0],
                              step=0.05, steps=400, stop=lambda u: u[0] > 2.5)
    assert branch.complete and branch.u[-1, 0] > 2.5
    assert_allclose([cubic(u)[0] for u in branch.u], 0.0, atol=1e-9)
    assert branch.folds.size == 2
    assert_allclose(branch.fold_points, [[-1.0, 2.0], [1.0, -2.0]], atol=1e-9)
    # the folds are where the parameter turns back, and x grows all the way
    p = branch.u[:, 1]
    for i, j in zip(branch.folds, np.append(branch.folds[1:], len(p) - 1)):
        assert np.all(np.sign(np.diff(p[i + 1:j + 1])) == np.sign(np.diff(p[i + 1:i + 3]))[0])
    assert np.all(np.diff(branch.u[:, 0]) > 0)
    assert_allclose(np.linalg.norm(branch.tangent, axis=1), 1.0)


def test_the_arclength_step_is_the_distance_along_the_tangent():
    circle = (lambda u: np.array([u[0] ** 2 + u[1] ** 2 - 1.0]),
              lambda u: np.array([[2.0 * u[0], 2.0 * u[1]]]))
    branch = pseudo_arclength(*circle, [1.0, 0.0], step=0.1, max_step=0.1, steps=10)
    assert len(branch.u) == 11 and branch.folds.size == 0
    angles = np.arctan2(branch.u[:, 1], branch.u[:, 0])
    assert_allclose(np.sin(np.diff(angles)), 0.1, rtol=1e-9)   # 0.1 along the tangent


def test_a_start_off_the_curve_is_refused():
    with pytest.raises(ValueError, match="not on the curve"):
        pseudo_arclength(cubic, cubic_jac, [0.0, 1.0])


def test_a_curve_that_ends_is_reported():
    def fun(u):      # sqrt(x) = p, which Newton cannot continue below x = 0
        return np.array([np.sqrt(u[0]) - u[1]]) if u[0] >= 0 else np.array([np.nan])

    def jac(u):
        return np.array([[0.5 / np.sqrt(abs(u[0])), -1.0]])

    branch = pseudo_arclength(fun, jac, [1.0, 1.0], direction=[-1.0, 0.0], step=0.1,
                              steps=200, min_step=1e-6)
    assert not branch.complete and branch.u[-1, 0] < 1e-3
    with pytest.raises(ConvergenceError):
        pseudo_arclength(fun, jac, [1.0, 1.0], step=10.0, min_step=1.0, maxiter=1)
