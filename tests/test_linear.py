"""Tests of mechnum.linear: textbook systems, bad input, and properties."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum import linear
from mechnum.errors import (ConvergenceError, DivergenceError, RelaxationFactorError,
                            SingularJacobianError)

# Burden and Faires, Numerical Analysis, Examples 7.3.1 and 7.3.3: solution (1, 2, -1, 1).
BF_A = np.array([[10.0, -1, 2, 0], [-1, 11, -1, 3], [2, -1, 10, -1], [0, 3, -1, 8]])
BF_B = np.array([6.0, 25, -11, 15])
# Burden and Faires, Example 7.4.3 (SOR): tridiagonal SPD, solution (3, 4, -5).
TRI_A = np.array([[4.0, 3, 0], [3, 4, -1], [0, -1, 4]])
TRI_B = np.array([24.0, 30, -24])


@pytest.mark.parametrize("method, iterations, last", [
    ("jacobi", 10, [1.0001, 1.9998, -0.9998, 0.9998]),
    ("gauss_seidel", 5, [1.0001, 2.0000, -1.0000, 1.0000])])
def test_burden_faires_iteration_counts(method, iterations, last):
    # The book's tables stop at k = 10 (Jacobi) and k = 5 (Gauss-Seidel), where the step
    # ||x_k - x_{k-1}||_inf first falls below 1e-3, and print these iterates to 4 decimals.
    res = getattr(linear, method)(BF_A, BF_B, tol=1e-3, criterion="step")
    assert res.iterations == iterations
    assert res.x.round(4).tolist() == last


def test_sor_textbook_solution_and_speed_up():
    sor = linear.sor(TRI_A, TRI_B, 1.25, x0=np.ones(3), tol=1e-7)
    gs = linear.gauss_seidel(TRI_A, TRI_B, x0=np.ones(3), tol=1e-7)
    assert np.allclose(sor.x, [3, 4, -5], atol=1e-6)
    assert sor.iterations < gs.iterations / 2


def test_optimal_omega_young_textbook_value():
    best = linear.optimal_omega(TRI_A)
    # rho_J^2 = 0.625 for this matrix, so omega* = 2 / (1 + sqrt(0.375)) = 1.2404...
    assert best.how == "young"
    assert best.omega == pytest.approx(2 / (1 + np.sqrt(0.375)), rel=1e-12)
    assert best.spectral_radius == pytest.approx(best.omega - 1, rel=1e-12)
    fine = np.linspace(1.0, 1.5, 5001)
    assert fine[np.argmin(linear.sor_spectral_radii(TRI_A, fine))] == pytest.approx(best.omega,
                                                                                      abs=2e-3)


def test_optimal_omega_numerical_is_a_minimum():
    A = BF_A @ BF_A.T  # dense SPD: Young's formula does not apply
    best = linear.optimal_omega(A)
    assert best.how == "numerical"
    grid = np.linspace(0.01, 1.99, 199)
    assert best.spectral_radius <= linear.sor_spectral_radii(A, grid).min() + 1e-12
    assert best.spectral_radius == pytest.approx(
        linear.spectral_radius(linear.iteration_matrix(A, "sor", best.omega)))


def test_condition_number_of_the_ill_conditioned_example():
    delta = 1e-2
    A = [[1.0, -2.0], [1.0, -(2 + delta)]]
    assert linear.condition_number(A, np.inf) == pytest.approx((3 + delta) * (4 + delta) / delta)
    for p in (1, 2, "fro"):
        assert linear.condition_number(A, p) == pytest.approx(np.linalg.cond(A, p))
    assert linear.condition_number([[1.0, 2.0], [2.0, 4.0]], 1) == np.inf


def test_rectangular_condition_number_squares_in_normal_equations():
    A = np.vander(np.linspace(0, 1, 12), 4)
    assert linear.condition_number(A.T @ A) == pytest.approx(linear.condition_number(A) ** 2,
                                                              rel=1e-8)


def test_iterative_refinement_recovers_double_precision():
    n = 5
    hilbert = 1.0 / (np.arange(n)[:, None] + np.arange(n) + 1)
    b = hilbert @ np.ones(n)
    res = linear.iterative_refinement(hilbert, b)
    single = res.history[0]
    assert np.max(np.abs(single - 1)) > 1e-4  # a float32 solve alone is poor
    assert np.max(np.abs(res.x - 1)) < 1e-9
    assert res.converged and res.iterations >= 2


def test_iterative_refinement_stalls_on_too_ill_conditioned():
    n = 9
    hilbert = 1.0 / (np.arange(n)[:, None] + np.arange(n) + 1)
    with pytest.raises(ConvergenceError, match="stalled"):
        linear.iterative_refinement(hilbert, hilbert @ np.ones(n))


@pytest.mark.parametrize("A, b, error", [
    ([[1.0, 2.0, 3.0]], [1.0], ValueError),
    ([[1.0, np.nan], [0.0, 1.0]], [1.0, 1.0], ValueError),
    ([[1.0, 0.0], [0.0, 1.0]], [1.0, np.inf], ValueError),
    ([[1.0, 0.0], [0.0, 1.0]], [1.0, 2.0, 3.0], ValueError),
    ([[0.0, 1.0], [1.0, 0.0]], [1.0, 1.0], SingularJacobianError),
    ([[1.0, 2.0], [2.0, 4.0]], [1.0, 2.0], SingularJacobianError),
])
def test_bad_systems(A, b, error):
    with pytest.raises(error):
        linear.sor(A, b, 1.0)


@pytest.mark.parametrize("omega", [0.0, 2.0, -0.5, 2.5, np.nan])
def test_omega_outside_open_interval(omega):
    with pytest.raises(RelaxationFactorError, match="omega"):
        linear.sor(TRI_A, TRI_B, omega)
    with pytest.raises(RelaxationFactorError):
        linear.iteration_matrix(TRI_A, "sor", omega)


def test_divergence_is_detected_not_looped_on():
    A = np.array([[1.0, 2.0], [2.0, 1.0]])  # rho(M_J) = 2
    with pytest.raises(DivergenceError, match="diverges") as info:
        linear.jacobi(A, [1.0, 1.0], maxiter=10_000)
    assert info.value.result.iterations < 100


def test_no_convergence_keeps_history():
    with pytest.raises(ConvergenceError, match="did not converge") as info:
        linear.sor(TRI_A, TRI_B, 0.1, maxiter=5)
    assert info.value.result.history.shape == (6, 3)
    assert not info.value.result.converged


@pytest.mark.parametrize("kwargs", [dict(tol=0.0), dict(maxiter=0), dict(criterion="size"),
                                    dict(x0=[1.0, 2.0])])
def test_bad_controls(kwargs):
    with pytest.raises(ValueError):
        linear.gauss_seidel(TRI_A, TRI_B, **kwargs)


def test_bad_method_and_norm():
    with pytest.raises(ValueError, match="method"):
        linear.iteration_matrix(TRI_A, "richardson")
    with pytest.raises(ValueError, match="p must be"):
        linear.condition_number(TRI_A, 3)


def test_residual_criterion():
    res = linear.gauss_seidel(TRI_A, TRI_B, tol=1e-9, criterion="residual")
    assert res.residual_norms[-1] < 1e-9 <= res.residual_norms[-2]


@st.composite
def spd_systems(draw):
    n = draw(st.integers(2, 5))
    B = np.array(draw(st.lists(st.floats(-1, 1), min_size=n * n, max_size=n * n))).reshape(n, n)
    b = np.array(draw(st.lists(st.floats(-10, 10), min_size=n, max_size=n)))
    return B @ B.T + 0.5 * np.eye(n), b


@settings(max_examples=40, deadline=None)
@given(spd_systems(), st.floats(0.05, 1.95))
def test_sor_converges_on_spd_for_every_omega(system, omega):
    A, b = system
    assert linear.spectral_radius(linear.iteration_matrix(A, "sor", omega)) < 1
    res = linear.sor(A, b, omega, tol=1e-12, maxiter=200_000)
    expected = np.linalg.solve(A, b)
    assert np.allclose(res.x, expected, atol=1e-8 * linear.condition_number(A) *
                       max(1.0, np.abs(expected).max()))


def test_sweep_matches_single_runs():
    omegas = [0.3, 1.0, 1.24, 1.8]
    sweep = linear.sor_sweep(TRI_A, TRI_B, omegas, tol=1e-9, criterion="residual")
    single = [linear.sor(TRI_A, TRI_B, w, tol=1e-9, criterion="residual").iterations
              for w in omegas]
    assert sweep.iterations.tolist() == single
    assert np.allclose(sweep.spectral_radii, linear.sor_spectral_radii(TRI_A, omegas))
    assert linear.sor_sweep(TRI_A, TRI_B, [0.01], maxiter=20).converged.tolist() == [False]
