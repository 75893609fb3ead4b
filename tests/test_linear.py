"""Tests of mechnum.linear: textbook systems, every public function's bad input, and
properties checked by hypothesis (200 examples each) over the valid domain and its edges."""

import warnings
from fractions import Fraction

import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from mechnum import linear
from mechnum.errors import (
    ConvergenceError,
    DivergenceError,
    RelaxationFactorError,
    SingularJacobianError,
)
from mechnum.linear import _spectra, _stationary
from mechnum.linear._checks import check_matrix
from mechnum.linear._krylov import POISSON3D_LIMIT
from mechnum.linear._spectra import OMEGA_GRID
from mechnum.linear._stationary import CHUNK, MAXITER_LIMIT
from mechnum.linear._sweeps import METHODS, splitting
from mechnum.results import CRITERIA, NORMS, Result, StoppingRule

# Burden and Faires, Numerical Analysis, Examples 7.3.1 and 7.3.3: solution (1, 2, -1, 1).
BF_A = np.array([[10.0, -1, 2, 0], [-1, 11, -1, 3], [2, -1, 10, -1], [0, 3, -1, 8]])
BF_B = np.array([6.0, 25, -11, 15])
# Burden and Faires, Example 7.4.3 (SOR): tridiagonal SPD, solution (3, 4, -5).
TRI_A = np.array([[4.0, 3, 0], [3, 4, -1], [0, -1, 4]])
TRI_B = np.array([24.0, 30, -24])
A2, B2 = np.array([[4.0, 1.0], [1.0, 3.0]]), np.array([1.0, 2.0])
X2 = np.linalg.solve(A2, B2)
HYPOTHESIS = settings(max_examples=200, deadline=None)


# --- strategies --------------------------------------------------------------------------------

def _matrix(draw, n, low=-1.0, high=1.0):
    values = draw(st.lists(st.floats(low, high), min_size=n * n, max_size=n * n))
    return np.array(values).reshape(n, n)


@st.composite
def spd_systems(draw, max_n=5):
    """A symmetric positive definite A (eigenvalues >= 0.5) and a right-hand side."""
    n = draw(st.integers(1, max_n))
    B = _matrix(draw, n)
    b = np.array(draw(st.lists(st.floats(-10, 10), min_size=n, max_size=n)))
    return B @ B.T + 0.5 * np.eye(n), b


@st.composite
def dominant_systems(draw, max_n=5):
    """A strictly diagonally dominant A (Jacobi and Gauss-Seidel converge) and b."""
    n = draw(st.integers(1, max_n))
    A = _matrix(draw, n)
    signs = np.where(np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n))), 1, -1)
    A[np.diag_indices(n)] = signs * (np.abs(A).sum(axis=1) + 0.5)
    b = np.array(draw(st.lists(st.floats(-10, 10), min_size=n, max_size=n)))
    return A, b


@st.composite
def tridiagonal_spd(draw):
    n = draw(st.integers(2, 6))
    off = np.array(draw(st.lists(st.floats(-1, 1), min_size=n - 1, max_size=n - 1)))
    diag = np.array(draw(st.lists(st.floats(2.05, 4), min_size=n, max_size=n)))
    return np.diag(diag) + np.diag(off, 1) + np.diag(off, -1)  # dominant, so SPD


omegas = st.floats(0.05, 1.95)


# --- textbook numbers --------------------------------------------------------------------------

@pytest.mark.parametrize("method, iterations, last", [
    ("jacobi", 10, [1.0001, 1.9998, -0.9998, 0.9998]),
    ("gauss_seidel", 5, [1.0001, 2.0000, -1.0000, 1.0000])])
def test_burden_faires_iteration_counts(method, iterations, last):
    # The book's tables stop at k = 10 (Jacobi) and k = 5 (Gauss-Seidel), where the step
    # ||x_k - x_{k-1}||_inf first falls below 1e-3 (an absolute test), and print these
    # iterates to 4 decimals.
    res = getattr(linear, method)(BF_A, BF_B, tol=1e-3, criterion="step", relative=False)
    assert res.iterations == iterations
    assert res.x.round(4).tolist() == last
    assert res.step_norms.shape == (iterations,)
    # the criterion itself: the last step is the first below tol = 1e-3
    assert res.step_norms[-1] < 1e-3 <= res.step_norms[-2]


def test_sor_textbook_solution_and_speed_up():
    # Burden and Faires, Example 7.4.3: 7 decimals, an absolute test
    sor = linear.sor(TRI_A, TRI_B, 1.25, seed=np.ones(3), tol=1e-7, relative=False)
    gs = _stationary.gauss_seidel(TRI_A, TRI_B, seed=np.ones(3), tol=1e-7, relative=False)
    # the absolute step test with tol 1e-7 stops with an error of about rho / (1 - rho) times the
    # step (rho = omega - 1 = 0.25): 1e-6 bounds it
    assert_allclose(sor.x, [3, 4, -5], atol=1e-6, rtol=0)
    assert sor.iterations < gs.iterations / 2


def test_optimal_omega_young_textbook_value():
    best = linear.optimal_omega(TRI_A)
    # rho_J^2 = 0.625 for this matrix, so omega* = 2 / (1 + sqrt(0.375)) = 1.2404...
    assert best.how == "young"
    # Young's formula evaluated from the computed rho_J: round-off of O(1) numbers
    assert best.x == pytest.approx(2 / (1 + np.sqrt(0.375)), rel=1e-12)
    # the SOR iteration matrix's radius at Young's omega is omega - 1 exactly; computed from its
    # eigenvalues, to round-off (a defective eigenvalue there would cost digits, but rel 1e-12 holds
    # for this 3 x 3)
    assert best.spectral_radius == pytest.approx(best.x - 1, rel=1e-12)
    fine = np.linspace(1.0, 1.5, 5001)
    radii = linear.sor_spectral_radii(TRI_A, fine)
    # the grid's spacing is 1e-4: its minimiser lies within two spacings of the optimum
    assert fine[np.argmin(radii)] == pytest.approx(best.x, abs=2e-4)


def test_optimal_omega_numerical_is_a_minimum():
    A = BF_A @ BF_A.T  # dense SPD: Young's formula does not apply
    best = linear.optimal_omega(A)
    assert best.how == "numerical"
    grid = np.linspace(0.01, 1.99, 199)
    # the optimum found numerically is at least as good as any point of the grid, up to round-off of
    # the radii
    assert best.spectral_radius <= linear.sor_spectral_radii(A, grid).min() + 1e-12
    # as above: the radius at the returned omega, recomputed, to round-off
    assert best.spectral_radius == pytest.approx(
        _spectra.spectral_radius(_spectra.iteration_matrix(A, "sor", best.x)), rel=1e-12)


def test_condition_number_of_the_ill_conditioned_example():
    delta = 1e-2
    A = [[1.0, -2.0], [1.0, -(2 + delta)]]
    # cond_inf of a 2 x 2 matrix, computed from its explicit inverse: pytest's default rel 1e-6 is
    # far above the round-off (delta = 1e-2 costs two digits of sixteen)
    assert linear.condition_number(A, np.inf) == pytest.approx((3 + delta) * (4 + delta) / delta)
    for p in (1, 2, "fro"):
        # the same norms numpy computes, by other means: its default rel 1e-6 is far above round-off
        assert linear.condition_number(A, p) == pytest.approx(np.linalg.cond(A, p))
    assert linear.condition_number([[1.0, 2.0], [2.0, 4.0]], 1) == np.inf
    assert linear.condition_number([[1.0, 2.0], [2.0, 4.0]], 2) > 1 / np.finfo(float).eps


def test_rectangular_condition_number_squares_in_normal_equations():
    A = np.vander(np.linspace(0, 1, 12), 4)
    # cond(A^T A) = cond(A)^2 for the 2-norm in exact arithmetic; forming A^T A rounds at about
    # eps cond(A)^2 = 2e-12 relative for this Vandermonde (cond(A) = 102): rel 1e-8 is generous
    assert linear.condition_number(A.T @ A) == pytest.approx(linear.condition_number(A) ** 2,
                                                              rel=1e-8)


# --- the step criterion, divergence, histories ---------------------------------------------------

def test_a_small_omega_does_not_fake_convergence():
    # The step of SOR is omega times a correction of the size of the residual: with
    # omega = 1e-12 it is 1e-12 after one sweep, while the residual is still 2.
    with pytest.raises(ConvergenceError, match="did not converge") as info:
        linear.sor(A2, B2, 1e-12, maxiter=50)
    # the residual after 50 sweeps of omega = 1e-12 is still 2 to within 50e-12 relative
    assert info.value.result.residual_norms[-1] == pytest.approx(2.0, rel=1e-9)
    sweep = linear.sor_sweep(A2, B2, [1e-12, 1.0], maxiter=50)
    assert sweep.converged.tolist() == [False, True]


def test_divergence_is_detected_not_looped_on():
    A = np.array([[1.0, 2.0], [2.0, 1.0]])  # rho(M_J) = 2
    with pytest.raises(DivergenceError, match="diverges.*spectral radius.*2") as info:
        linear.jacobi(A, [1.0, 1.0], maxiter=10_000)
    assert 20 < info.value.result.iterations < 100  # 2^27 > 1e8: about 27 sweeps


def test_no_convergence_keeps_history():
    with pytest.raises(ConvergenceError, match="did not converge in 5 sweeps") as info:
        linear.sor(TRI_A, TRI_B, 0.1, maxiter=5)
    result = info.value.result
    assert result.history.shape == (6, 3) and result.residual_norms.shape == (6,)
    assert result.step_norms.shape == (5,) and not result.converged
    # the step norms are the max-norms of the differences the history records, recomputed: round-off
    # of O(1) numbers
    assert_allclose(np.abs(np.diff(result.history, axis=0)).max(axis=1), result.step_norms,
                    rtol=1e-14)


def test_history_of_a_sparse_solve_is_not_kept_unless_asked():
    A = linear.poisson2d(4)
    b = np.ones(16)
    assert _stationary.gauss_seidel(A, b).history is None
    kept = _stationary.gauss_seidel(A, b, keep_history=True)
    assert kept.history.shape == (kept.iterations + 1, 16)
    # the kept history is the iteration itself: from x0 to x, its steps and residuals recorded
    assert not kept.history[0].any() and np.array_equal(kept.history[-1], kept.x)
    # as above, in the sparse route: round-off of O(1) numbers
    assert_allclose(np.abs(np.diff(kept.history, axis=0)).max(axis=1), kept.step_norms,
                    rtol=1e-12)
    # the residuals recomputed from the history: round-off of b's size, and atol where the residual
    # is itself near round-off
    assert_allclose(np.abs(b - kept.history @ A.T).max(axis=1), kept.residual_norms,
                    rtol=1e-9, atol=1e-15)
    with pytest.raises(ValueError, match="keep_history must be True or False"):
        _stationary.gauss_seidel(A, b, keep_history="yes")


def test_residual_criterion():
    res = _stationary.gauss_seidel(TRI_A, TRI_B, tol=1e-9, criterion="residual", relative=False)
    # the criterion itself: the first residual below tol = 1e-9 (absolute)
    assert res.residual_norms[-1] < 1e-9 <= res.residual_norms[-2]
    relative = _stationary.gauss_seidel(TRI_A, TRI_B, tol=1e-9, criterion="residual", relative=True,
                                   norm=2)
    # the criterion itself, relative: tol ||b||_2
    assert relative.residual_norms[-1] <= 1e-9 * np.linalg.norm(TRI_B)
    # the recorded residual is the 2-norm of b - A x recomputed: round-off
    assert_allclose(relative.residual_norms[-1], np.linalg.norm(TRI_B - TRI_A @ relative.x),
                    rtol=1e-12)


def test_long_runs_cross_the_compiled_chunks():
    # More sweeps than one compiled chunk: the history is stitched without gaps.
    res = linear.sor(TRI_A, TRI_B, 0.01, tol=1e-12, maxiter=CHUNK * 3)
    assert res.iterations > CHUNK
    assert res.history.shape == (res.iterations + 1, 3)
    # the residuals recomputed from the history across chunk boundaries: round-off of b's size (atol
    # for the last, near 1e-12)
    assert_allclose(res.residual_norms, np.abs(TRI_B - res.history @ TRI_A.T).max(axis=1),
                    rtol=1e-9, atol=1e-12)


def test_zero_right_hand_side_converges_at_once():
    for relative in (False, True):
        res = _stationary.gauss_seidel(TRI_A, np.zeros(3), relative=relative)
        assert res.iterations == 1 and res.converged and not res.x.any()


# --- sparse matrices and the sweep ---------------------------------------------------------------

@pytest.mark.parametrize("method", METHODS)
def test_sparse_and_dense_give_the_same_iterates(method):
    A = linear.poisson2d(5)
    b = np.arange(25.0)
    dense = getattr(linear, method)(A.toarray(), b, **({"omega": 1.5} if method == "sor" else {}))
    sparse = getattr(linear, method)(A, b, **({"omega": 1.5} if method == "sor" else {}))
    assert sparse.iterations == dense.iterations
    # the same sweeps on a dense and a sparse matrix (other summation orders): round-off of the
    # solution's size
    assert_allclose(sparse.x, dense.x, rtol=0, atol=1e-12)
    assert_allclose(A @ sparse.x, b, atol=1e-9 * np.abs(b).max(), rtol=0)  # a relative stop


def test_poisson_sor_at_young_omega():
    m = 30
    A = linear.poisson2d(m)
    omega = linear.young_omega(np.cos(np.pi / (m + 1)))
    b = np.ones(m * m)
    sor = linear.sor(A, b, omega, tol=1e-8, criterion="residual")
    gs = _stationary.gauss_seidel(A, b, tol=1e-8, criterion="residual")
    assert sor.iterations * 10 < gs.iterations  # O(m) sweeps against O(m^2)
    cg = linear.conjugate_gradient(A, b, tol=1e-10)
    assert cg.iterations < sor.iterations
    # both stop on their residual tests (1e-8 relative for SOR, 1e-10 for CG); Poisson's matrix
    # (cond 389 at m = 30, solution up to 71) turns SOR's into an error of 8.3e-8 measured here, so
    # 1e-7 is a bound with little margin: it checks the two agree to SOR's own test, no better
    assert_allclose(sor.x, cg.x, atol=1e-7, rtol=0)


def test_poisson2d_structure():
    A = linear.poisson2d(7)
    assert A.shape == (49, 49) and A.nnz == 5 * 49 - 4 * 7
    assert abs(A - A.T).max() == 0
    rho_j = _spectra.spectral_radius(_spectra.iteration_matrix(A.toarray(), "jacobi"))
    # an eigenvalue of a symmetric 49 x 49 matrix: a few ulps, relative to its size (about 1)
    assert rho_j == pytest.approx(np.cos(np.pi / 8), rel=1e-12)


def test_poisson3d_structure_and_jacobi_radius():
    m = 4
    A = linear.poisson3d(m)
    n = m ** 3
    assert A.shape == (n, n) and A.nnz == 7 * n - 6 * m * m and abs(A - A.T).max() == 0
    dense = A.toarray()
    assert set(np.diag(dense)) == {6.0}
    # node (i, j, k) = i + m j + m^2 k: its neighbours are 1, m and m^2 away (not across edges)
    assert dense[0, [1, m, m * m]].tolist() == [-1.0, -1.0, -1.0] and dense[m - 1, m] == 0
    eig = np.linalg.eigvalsh(dense)
    assert eig.min() > 0
    # eigvalsh of a symmetric matrix: errors of eps times its norm (12), a few ulps relative to the
    # largest eigenvalue
    assert eig.max() / 6 - 1 == pytest.approx(np.cos(np.pi / (m + 1)), rel=1e-12)
    rho_j = _spectra.spectral_radius(_spectra.iteration_matrix(dense, "jacobi"))
    # as above: the Jacobi radius, an eigenvalue of I - D^-1 A
    assert rho_j == pytest.approx(np.cos(np.pi / (m + 1)), rel=1e-12)
    assert linear.poisson3d(1).toarray().tolist() == [[6.0]]


def test_a_sparse_matrix_is_never_made_dense(monkeypatch):
    A = linear.poisson2d(3)
    monkeypatch.setattr(sp.csr_array, "toarray", lambda self, *a, **k: pytest.fail("dense"))
    monkeypatch.setattr(sp.csr_array, "todense", lambda self, *a, **k: pytest.fail("dense"))
    for call in (lambda: linear.sor(A, np.ones(9), 1.3), lambda: linear.jacobi(A, np.ones(9)),
                 lambda: linear.sor_sweep(A, np.ones(9), [0.5, 1.5]),
                 lambda: linear.conjugate_gradient(A, np.ones(9)),
                 lambda: splitting(A, "sor", 1.2).sweep(np.zeros(9), np.ones(9))):
        call()
    with pytest.raises(ValueError, match="dense"):
        _spectra.iteration_matrix(A, "jacobi")


@HYPOTHESIS
@given(dominant_systems(), omegas, st.sampled_from(METHODS))
def test_compiled_sweep_is_the_textbook_sweep(system, omega, method):
    A, b = system
    x = np.linspace(-1, 1, b.size)
    split = splitting(A, method, omega)
    if method == "jacobi":
        expected = (b - (A - np.diag(np.diag(A))) @ x) / np.diag(A)
    else:
        expected = linear.sweep_by_components(A, b, x, split.omega)
    # one sweep written two ways (vectorised and by components): round-off of O(1) numbers
    assert_allclose(split.sweep(x, b), expected, rtol=1e-12, atol=1e-12)
    # ... and the matrix form x <- M x + c, with c the sweep of x = 0
    M = _spectra.iteration_matrix(A, method, omega)
    # the sweep and its matrix form M x + c (M from an inverse of D - L): round-off amplified by
    # that inverse, for the drawn systems at most a few hundred ulps: 1e-10
    assert_allclose(split.sweep(x, b), M @ x + split.sweep(np.zeros(b.size), b),
                    rtol=1e-10, atol=1e-10)


def test_sweep_by_components_by_hand():
    # One Gauss-Seidel sweep from 0 on [[4, 1], [1, 3]] x = [1, 2]: x1 = 1/4, x2 = (2 - 1/4)/3.
    assert_allclose(linear.sweep_by_components(A2, B2, [0.0, 0.0]), [0.25, 1.75 / 3],
                    rtol=1e-15)
    # x1 = 1/4 and x2 = 1.75/3 computed in a few operations: a few ulps (1e-15 relative is about 4
    # eps)
    assert_allclose(linear.sweep_by_components(A2, B2, [0.0, 0.0], 0.5), [0.125, 1.875 / 6],
                    rtol=1e-15)


# --- bad input -----------------------------------------------------------------------------------

BAD_SYSTEMS = [
    ([[1.0, 2.0, 3.0]], [1.0], ValueError, "square"),
    ([[1.0, np.nan], [0.0, 1.0]], [1.0, 1.0], ValueError, "finite"),
    ([[1.0, 1j], [0.0, 1.0]], [1.0, 1.0], ValueError, "real"),
    ([["a", "b"], ["c", "d"]], [1.0, 1.0], ValueError, "numeric"),
    (np.zeros((0, 0)), [], ValueError, "non-empty"),
    ([[1.0, 0.0], [0.0, 1.0]], [1.0, np.inf], ValueError, "b must be finite"),
    ([[1.0, 0.0], [0.0, 1.0]], [1.0, 2.0, 3.0], ValueError, "b must have shape"),
    ([[0.0, 1.0], [1.0, 0.0]], [1.0, 1.0], SingularJacobianError, "zero diagonal"),
    ([[1.0, 2.0], [2.0, 4.0]], [1.0, 2.0], SingularJacobianError, "singular"),
    (sp.csr_array([[1.0, np.nan], [0.0, 1.0]]), [1.0, 1.0], ValueError, "finite"),
    (sp.csr_array([[1.0, 0.0], [1.0, 0.0]]), [1.0, 1.0], SingularJacobianError, "diagonal"),
]


@pytest.mark.parametrize("solver", ["sor", "gauss_seidel", "jacobi", "sor_sweep"])
@pytest.mark.parametrize("A, b, error, message", BAD_SYSTEMS)
def test_bad_systems(solver, A, b, error, message):
    with pytest.raises(error, match=message):
        if solver == "sor":
            linear.sor(A, b, 1.0)
        elif solver == "sor_sweep":
            linear.sor_sweep(A, b, [1.0])
        else:
            getattr(linear, solver)(A, b)


@pytest.mark.parametrize("omega", [0.0, 2.0, -0.5, 2.5, np.nan, np.inf, None, "1.2", 1j, [1.0]])
def test_omega_outside_open_interval(omega):
    for call in (lambda: linear.sor(TRI_A, TRI_B, omega),
                 lambda: _spectra.iteration_matrix(TRI_A, "sor", omega),
                 lambda: splitting(TRI_A, "sor", omega),
                 lambda: linear.sor_spectral_radii(TRI_A, [1.0, omega]),
                 lambda: linear.sor_sweep(TRI_A, TRI_B, [omega]),
                 lambda: linear.sweep_by_components(TRI_A, TRI_B, np.zeros(3), omega)):
        with pytest.raises(RelaxationFactorError, match="omega"):
            call()


@pytest.mark.parametrize("kwargs, message", [
    (dict(tol=0.0), "tol"), (dict(tol=-1.0), "tol"), (dict(tol=np.nan), "tol"),
    (dict(maxiter=0), "maxiter"), (dict(maxiter=np.inf), "maxiter"),
    (dict(maxiter=2.5), "maxiter"), (dict(criterion="size"), "criterion"),
    (dict(norm=3), "norm"), (dict(norm="fro"), "norm"), (dict(relative="yes"), "relative"),
    (dict(seed=[1.0, 2.0]), "seed"), (dict(seed=[1, np.nan, 0]), "seed")])
def test_bad_controls(kwargs, message):
    for solver in (_stationary.gauss_seidel, linear.jacobi,
                   lambda A, b, **k: linear.sor(A, b, 1.2, **k),
                   lambda A, b, **k: linear.sor_sweep(A, b, [1.2], **k)):
        with pytest.raises(ValueError, match=message):
            solver(TRI_A, TRI_B, **kwargs)


@pytest.mark.parametrize("call, error, message", [
    (lambda: _spectra.iteration_matrix(TRI_A, "richardson"), ValueError, "method"),
    (lambda: splitting(TRI_A, "sor_sweep"), ValueError, "method"),
    (lambda: linear.condition_number(TRI_A, 3), ValueError, "p must be"),
    (lambda: linear.condition_number([[1.0, 2.0]], 1), ValueError, "square"),
    (lambda: linear.condition_number(linear.poisson2d(2)), ValueError, "dense"),
    (lambda: _spectra.spectral_radius([[1.0, 2.0]]), ValueError, "square"),
    (lambda: _spectra.spectral_radius([[np.inf]]), ValueError, "finite"),
    (lambda: linear.sor_spectral_radii(TRI_A, [[1.0]]), ValueError, "dimension"),
    (lambda: linear.sor_spectral_radii(np.ones((2, 2)) - np.eye(2), [1.0]),
     SingularJacobianError, "diagonal"),
    (lambda: linear.young_omega(1.0), ValueError, "rho_jacobi < 1"),
    (lambda: linear.young_omega(-0.1), ValueError, "non-negative"),
    (lambda: linear.young_omega(np.nan), ValueError, "finite"),
    (lambda: linear.optimal_omega([[1.0, 2.0]]), ValueError, "square"),
    (lambda: linear.optimal_omega(linear.poisson2d(2)), ValueError, "dense"),
    (lambda: check_matrix([1.0, 2.0]), ValueError, "dimension"),
    (lambda: check_matrix(sp.csr_array(np.eye(2) * 1j)), ValueError, "real"),
    (lambda: splitting(TRI_A).sweep([0.0, 0.0], TRI_B), ValueError, "x must have"),
    (lambda: splitting(TRI_A).sweep(np.zeros(3), [1, 2, np.nan]), ValueError, "finite"),
    (lambda: linear.sweep_by_components(linear.poisson2d(2), np.ones(4), np.zeros(4)),
     ValueError, "dense"),
    (lambda: linear.sweep_by_components(TRI_A, TRI_B, [0.0]), ValueError, "x must have"),
    (lambda: linear.poisson2d(0), ValueError, "m must be"),
    (lambda: linear.poisson2d(2.5), ValueError, "m must be"),
    (lambda: StoppingRule.checked(1e-8, True, maxiter_limit=MAXITER_LIMIT), ValueError,
     "maxiter"),
])
def test_bad_input_of_the_other_functions(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_empty_omega_sweeps_are_valid():
    assert linear.sor_spectral_radii(TRI_A, []).shape == (0,)
    empty = linear.sor_sweep(TRI_A, TRI_B, [])
    assert empty.iterations.shape == (0,) and empty.spectral_radii.shape == (0,)


# --- conjugate gradients -------------------------------------------------------------------------

@pytest.mark.parametrize("A, error, message", [
    ([[1.0, 2.0], [0.0, 1.0]], ValueError, "symmetric"),
    ([[1.0, 0.0], [0.0, -1.0]], SingularJacobianError, "positive definite"),
    ([[1.0, np.nan], [np.nan, 1.0]], ValueError, "finite")])
def test_conjugate_gradient_bad_matrices(A, error, message):
    with pytest.raises(error, match=message):
        linear.conjugate_gradient(A, [1.0, 1.0])


def test_conjugate_gradient_maxiter():
    with pytest.raises(ConvergenceError, match="did not converge in 1 steps") as info:
        linear.conjugate_gradient(TRI_A @ TRI_A.T, TRI_B, maxiter=1)
    assert info.value.result.iterations == 1
    with pytest.raises(ValueError, match="maxiter"):
        linear.conjugate_gradient(A2, B2, maxiter=0)


@HYPOTHESIS
@given(spd_systems(max_n=6))
def test_conjugate_gradient_solves_spd_systems(system):
    A, b = system
    res = linear.conjugate_gradient(A, b, tol=1e-12)
    assert res.converged and res.iterations <= 3 * b.size
    # CG with tol 1e-12 on its relative residual stops with ||A x - b|| <= 1e-12 ||b||; 1e-9 allows
    # for the recomputed residual's round-off (eps cond(A) ||b||, cond up to about 1e3 for these
    # systems)
    assert np.linalg.norm(A @ res.x - b) <= 1e-9 * max(np.linalg.norm(b), 1e-300) + 1e-300
    assert res.step_norms.shape == (res.iterations,)


# --- least squares -------------------------------------------------------------------------------

@st.composite
def full_rank_least_squares(draw):
    n = draw(st.integers(1, 3))
    m = draw(st.integers(n, 8))
    t = np.array(draw(st.lists(st.floats(-1, 1), min_size=m, max_size=m, unique=True)))
    A = np.vander(t, n)
    b = np.array(draw(st.lists(st.floats(-5, 5), min_size=m, max_size=m)))
    return A, b


@HYPOTHESIS
@given(full_rank_least_squares())
def test_least_squares_methods_meet_the_normal_equations(problem):
    A, b = problem
    s = np.linalg.svd(A, compute_uv=False)
    if s[-1] < 1e-3 * s[0]:  # keep kappa^2 eps small enough for the normal equations
        return
    qr = linear.least_squares(A, b)
    # optimality: the residual is orthogonal to the columns of A
    assert np.abs(A.T @ (A @ qr.x - b)).max() <= 1e-10 * (1 + np.abs(b).max())
    # the stored residuals are A x - b recomputed: round-off of b's size (a few ulps)
    assert_allclose(qr.residuals, A @ qr.x - b, rtol=0, atol=1e-14 * (1 + np.abs(b).max()))
    for method in ("svd", "cholesky", "lu"):
        other = linear.least_squares(A, b, method)
        # the normal equations square the condition number: their solutions differ from QR's by
        # about eps kappa^2 (kappa <= 1e3 here, by the return above): 1e-6 relative
        assert_allclose(other.x, qr.x, rtol=1e-6, atol=1e-6 * (1 + np.abs(b).max()))
    assert qr.rank == A.shape[1]


@pytest.mark.parametrize("method, options", [
    ("sor", dict(omega=1.3, tol=1e-13, maxiter=100_000)), ("gauss_seidel", dict(tol=1e-13)),
    ("cg", dict(tol=1e-14))])
def test_least_squares_iterative_methods(method, options):
    A = np.vander(np.linspace(0, 1, 9), 3)
    b = np.exp(np.linspace(0, 1, 9))
    fit = linear.least_squares(A, b, method, **options)
    # both iterative methods stop at their tolerances (1e-12, 1e-14) on the normal equations of a
    # Vandermonde of condition about 1e2: their answers agree with QR's to about 1e-10 relative,
    # 1e-9 a margin of ten
    assert_allclose(fit.x, linear.least_squares(A, b).x, rtol=1e-9)
    assert fit.solver is not None and fit.solver.converged


def test_least_squares_rank_deficiency():
    A = np.column_stack([np.ones(5), np.arange(5.0), 2 * np.arange(5.0)])  # rank 2
    b = np.arange(5.0) ** 2
    for method in ("qr", "cholesky", "lu", "sor", "jacobi", "gauss_seidel", "cg"):
        with pytest.raises(SingularJacobianError, match="rank 2 < 3"):
            linear.least_squares(A, b, method, **({"omega": 1.0} if method == "sor" else {}))
    fit = linear.least_squares(A, b, "svd")
    assert fit.rank == 2
    # the minimum-norm solution: no component along the null vector (0, 2, -1)
    assert abs(fit.x @ [0.0, 2.0, -1.0]) < 1e-12
    # the minimum-norm solution: its component along the null vector is round-off of O(1) numbers
    assert np.abs(A.T @ fit.residuals).max() < 1e-10
# the residual of the least-squares fit is orthogonal to the columns, to round-off of b's size times
# the condition (about 10)


@pytest.mark.parametrize("call, error, message", [
    (lambda: linear.least_squares(np.ones((2, 3)), np.ones(2)), ValueError, "rows"),
    (lambda: linear.least_squares(np.eye(3), np.ones(2)), ValueError, "b must have"),
    (lambda: linear.least_squares(np.eye(3), np.ones(3), "lsqr"), ValueError, "method"),
    (lambda: linear.least_squares(np.eye(3), np.ones(3), "qr", 1.2), ValueError, "omega"),
    (lambda: linear.least_squares(np.eye(3), np.ones(3), "qr", tol=1), ValueError, "direct"),
    (lambda: linear.least_squares(np.eye(3), np.ones(3), "sor"), RelaxationFactorError, "omega"),
    (lambda: linear.least_squares(np.zeros((3, 2)), np.ones(3)), SingularJacobianError, "rank 0"),
    (lambda: linear.least_squares(sp.eye_array(3), np.ones(3)), ValueError, "dense"),
])
def test_least_squares_bad_input(call, error, message):
    with pytest.raises(error, match=message):
        call()


# --- iterative refinement ------------------------------------------------------------------------

def _hilbert(n):
    return 1.0 / (np.arange(n)[:, None] + np.arange(n) + 1)


def test_iterative_refinement_recovers_double_precision():
    n = 5
    res = linear.iterative_refinement(_hilbert(n), _hilbert(n) @ np.ones(n))
    assert np.max(np.abs(res.history[0] - 1)) > 1e-4  # a float32 solve alone is poor
    # iterative refinement reaches about eps cond(H5) = 2.2e-16 * 4.8e5 = 1e-10 in x: 1e-9 is a
    # margin of ten
    assert np.max(np.abs(res.x - 1)) < 1e-9
    assert res.converged and res.iterations >= 2
    assert res.step_norms.shape == (res.iterations,)


def test_iterative_refinement_stalls_on_too_ill_conditioned():
    n = 9
    with pytest.raises(ConvergenceError, match="stalled") as info:
        linear.iterative_refinement(_hilbert(n), _hilbert(n) @ np.ones(n))
    assert not info.value.result.converged


def test_iterative_refinement_reaches_maxiter():
    with pytest.raises(ConvergenceError, match="after 1 steps"):
        linear.iterative_refinement(_hilbert(5), _hilbert(5) @ np.ones(5), maxiter=1)


@pytest.mark.parametrize("scale", [1e-50, 1e-300, 1e30, 1e300])
def test_iterative_refinement_is_scale_invariant(scale):
    # float32 holds neither 1e-50 nor 1e300: the right-hand side is scaled before the solve.
    res = linear.iterative_refinement(A2, scale * B2)
    # the scaled system is solved as the unscaled one, by powers of two: the same digits, round-off
    # only
    assert_allclose(res.x, scale * X2, rtol=1e-12)
    res = linear.iterative_refinement(scale * A2, B2)
    # as above
    assert_allclose(res.x, X2 / scale, rtol=1e-12)


def test_iterative_refinement_bad_input():
    for kwargs, message in ((dict(maxiter=0), "maxiter"), (dict(tol=-1), "tol"),
                            (dict(factor_dtype=np.int32), "factor_dtype")):
        with pytest.raises(ValueError, match=message):
            linear.iterative_refinement(A2, B2, **kwargs)
    with pytest.raises(SingularJacobianError):
        linear.iterative_refinement([[1.0, 2.0], [2.0, 4.0]], B2)
    assert not linear.iterative_refinement(A2, [0.0, 0.0]).x.any()


@HYPOTHESIS
@given(dominant_systems(), st.floats(-300, 300))
@example(system=(np.array([[-1.4375]]), np.array([2.22507386e-313])), exponent=1.0)
@example(system=(np.array([[-1.25]]), np.array([6.73643596e-167])), exponent=-152.0)
def test_iterative_refinement_accuracy(system, exponent):
    A, b = system
    b = b * 10.0 ** exponent
    res = linear.iterative_refinement(A, b, tol=1e-13)
    exact = _exact_solution(A, b)
    error = max(abs(Fraction(float(x)) - e) for x, e in zip(res.x, exact))
    # Relative accuracy holds down to the normal range; a subnormal solution carries fewer than
    # 53 bits, so its floor is a couple of units of the smallest subnormal (b = 2.2e-312 gives
    # x = -1.5e-312, one subnormal unit = 3e-12 of x). The reference is the exact rational
    # solution: numpy's own solve can be several subnormal units off there.
    floor = 2 * Fraction(float(np.finfo(float).smallest_subnormal))
    assert error <= Fraction(1, 10**12) * max(abs(e) for e in exact) + floor


def _exact_solution(A, b):
    """The exact solution of ``A x = b`` for the floats given, in rationals (Gauss-Jordan with
    partial pivoting on :class:`fractions.Fraction`)."""
    n = len(b)
    M = [[Fraction(float(v)) for v in row] + [Fraction(float(bi))] for row, bi in zip(A, b)]
    for k in range(n):
        pivot = max(range(k, n), key=lambda i: abs(M[i][k]))
        M[k], M[pivot] = M[pivot], M[k]
        for i in range(n):
            if i != k:
                factor = M[i][k] / M[k][k]
                M[i] = [a - factor * c for a, c in zip(M[i], M[k])]
    return [M[i][n] / M[i][i] for i in range(n)]


# --- properties of the stationary solvers --------------------------------------------------------

@HYPOTHESIS
@given(spd_systems(), omegas)
@example(system=(np.array([[0.5]]), np.array([5e-324])), omega=1.5)  # a subnormal solution
def test_sor_converges_on_spd_for_every_omega(system, omega):
    A, b = system
    assert _spectra.spectral_radius(_spectra.iteration_matrix(A, "sor", omega)) < 1
    res = linear.sor(A, b, omega, tol=1e-12, maxiter=200_000)
    expected = np.linalg.solve(A, b)
    # SOR stops on its relative step (1e-12); a contraction's error is then about the step times rho
    # / (1 - rho), and the answer itself is only determined to eps cond(A): 1e-8 cond(A) bounds both
    # for the drawn systems
    assert np.abs(res.x - expected).max() <= 1e-8 * linear.condition_number(A) * max(
        1.0, np.abs(expected).max())


@HYPOTHESIS
@given(dominant_systems(), st.sampled_from(["jacobi", "gauss_seidel"]),
       st.sampled_from(NORMS), st.booleans())
def test_jacobi_and_gauss_seidel_converge_on_dominant_systems(system, method, norm, relative):
    A, b = system
    res = getattr(linear, method)(A, b, tol=1e-11, norm=norm, relative=relative,
                                  criterion="residual")
    assert res.converged
    limit = 1e-11 * (np.linalg.norm(b, norm) if relative else 1.0)
    # the criterion itself, recomputed: the residual it measured, up to a few ulps of rounding in
    # the recomputation
    assert np.linalg.norm(b - A @ res.x, norm) <= limit * (1 + 1e-9) + 1e-300


@HYPOTHESIS
@given(spd_systems(max_n=4), st.lists(omegas, min_size=1, max_size=4))
def test_sweep_matches_single_runs(system, ws):
    A, b = system
    sweep = linear.sor_sweep(A, b, ws, tol=1e-9, criterion="residual", maxiter=50_000)
    single = [linear.sor(A, b, w, tol=1e-9, criterion="residual", maxiter=50_000).iterations
              for w in ws]
    assert sweep.iterations.tolist() == single and sweep.converged.all()
    # the same radii by the same formula, vectorised over omega: round-off
    assert_allclose(sweep.spectral_radii, linear.sor_spectral_radii(A, ws), rtol=1e-12)


# --- properties of the other functions -----------------------------------------------------------

@HYPOTHESIS
@given(dominant_systems(), st.booleans())
def test_check_matrix_keeps_values(system, sparse):
    A, _ = system
    checked = check_matrix(sp.csr_array(A) if sparse else A.tolist())
    assert_allclose(checked.toarray() if sparse else checked, A, rtol=0, atol=0)


@HYPOTHESIS
@given(dominant_systems(), omegas, st.sampled_from(METHODS))
def test_iteration_matrix_is_p_inverse_n(system, omega, method):
    A, _ = system
    D, L = np.diag(np.diag(A)), np.tril(A, -1)
    P = {"jacobi": D, "gauss_seidel": D + L, "sor": D / omega + L}[method]
    M = _spectra.iteration_matrix(A, method, omega)
    # P M = P - A holds exactly; computed, M carries round-off of P^-1 (diagonal dominance keeps P's
    # condition modest): 1e-9
    assert_allclose(P @ M, P - A, rtol=1e-9, atol=1e-9 * np.abs(A).max())


@HYPOTHESIS
@given(st.integers(1, 5).flatmap(lambda n: st.lists(st.floats(-1e3, 1e3), min_size=n * n,
                                                     max_size=n * n)), st.floats(-10, 10))
def test_spectral_radius_is_homogeneous_and_below_the_norm(values, c):
    n = int(round(np.sqrt(len(values))))
    M = np.array(values).reshape(n, n)
    rho = _spectra.spectral_radius(M)
    # rho <= ||M||_2, with a few ulps of rounding in both (1e-300: M = 0)
    assert 0 <= rho <= np.linalg.norm(M, 2) * (1 + 1e-9) + 1e-300
    # the eigenvalues of c M are c times those of M; a defective eigenvalue (drawn matrices may
    # have one) is only determined to about sqrt(eps) = 1.5e-8 of the norm: 1e-6
    assert _spectra.spectral_radius(c * M) == pytest.approx(abs(c) * rho, rel=1e-6, abs=1e-9)


@HYPOTHESIS
@given(spd_systems(max_n=4), st.lists(omegas, min_size=0, max_size=5))
def test_sor_spectral_radii_match_the_iteration_matrices(system, ws):
    A, _ = system
    radii = linear.sor_spectral_radii(A, ws)
    expected = [_spectra.spectral_radius(_spectra.iteration_matrix(A, "sor", w)) for w in ws]
    # two ways of computing the same eigenvalue moduli (the batched closed form, and eigenvalues of
    # the matrix): round-off, with atol for radii near 0
    assert_allclose(radii, expected, rtol=1e-10, atol=1e-12)
    assert np.all(radii < 1)  # Ostrowski-Reich: SPD, omega in (0, 2)


@HYPOTHESIS
@given(tridiagonal_spd())
def test_young_omega_is_the_optimum_of_tridiagonal_spd(T):
    rho_j = _spectra.spectral_radius(_spectra.iteration_matrix(T, "jacobi"))
    omega = linear.young_omega(rho_j)
    best = linear.optimal_omega(T)
    assert best.how == "young" and best.x == omega
    rho = linear.sor_spectral_radii(T, [omega, max(omega - 0.01, 0.01), min(omega + 0.01, 1.99)])
    # rho(omega*) = omega* - 1 (eigenvalues of modulus omega* - 1, so up to sqrt(eps) digits)
    assert rho[0] == pytest.approx(omega - 1, abs=1e-6)
    assert rho[0] <= rho[1:].min() + 1e-6


@HYPOTHESIS
@given(st.floats(0, 0.999))
def test_young_omega_gives_rho_omega_minus_one(rho):
    # [[1, rho], [rho, 1]] is consistently ordered with rho_J = rho: at Young's omega* the SOR
    # iteration matrix has spectral radius omega* - 1, the smallest over omega
    A = np.array([[1.0, rho], [rho, 1.0]])
    omega = linear.young_omega(rho)
    assert 1 <= omega < 2
    radii = linear.sor_spectral_radii(A, [omega, omega * 0.99, min(omega * 1.01, 1.999)])
    # a double eigenvalue at omega*: its computed modulus is accurate to about sqrt(eps)
    assert radii[0] == pytest.approx(omega - 1, abs=1e-6)
    assert radii[0] <= radii[1:].min() + 1e-6


@HYPOTHESIS
@given(spd_systems(max_n=4))
def test_optimal_omega_beats_the_grid(system):
    A, _ = system
    if A.shape[0] > 1 and np.any(np.abs(np.diag(A)) < 1e-3):
        return
    best = linear.optimal_omega(A)
    assert 0 < best.x < 2
    grid = linear.sor_spectral_radii(A, OMEGA_GRID)
    # the optimum found (a refinement of the grid's best point) is at least as good as every grid
    # point, up to round-off of the radii
    assert best.spectral_radius <= grid.min() + 1e-12


@HYPOTHESIS
@given(dominant_systems(), st.sampled_from([1, 2, np.inf, "fro"]))
def test_condition_number_matches_numpy(system, p):
    A, _ = system
    cond = linear.condition_number(A, p)
    # cond >= 1 for an induced norm, up to round-off (the Frobenius one is not induced)
    assert cond >= 1 - 1e-12 or p == "fro"
    # the same norms numpy computes, through another factorisation: round-off amplified by cond
    # (the drawn matrices are diagonally dominant, modestly conditioned): 1e-8
    assert cond == pytest.approx(np.linalg.cond(A, p), rel=1e-8)


@HYPOTHESIS
@given(st.integers(1, 12))
def test_poisson2d_is_spd_with_known_jacobi_radius(m):
    A = linear.poisson2d(m)
    assert A.shape == (m * m, m * m) and abs(A - A.T).max() == 0
    # row sums of integers: exact; rtol only for the form
    assert_allclose(A.sum(axis=1)[[0, -1]], [2.0, 2.0] if m > 1 else [4.0, 4.0], rtol=1e-12)
    if m <= 6:
        eig = np.linalg.eigvalsh(A.toarray())
        assert eig.min() > 0
        # eigvalsh of a symmetric matrix: errors of eps times its norm (8), a few ulps relative to
        # the largest eigenvalue
        assert eig.max() / 4 - 1 == pytest.approx(np.cos(np.pi / (m + 1)), rel=1e-12)


@HYPOTHESIS
@given(st.floats(1e-300, 1e300), st.integers(1, 10**7), st.sampled_from(CRITERIA),
       st.sampled_from(NORMS), st.booleans())
def test_stopping_rule_accepts_its_domain(tol, maxiter, criterion, norm, relative):
    rule = StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                maxiter_limit=MAXITER_LIMIT)
    assert (rule.tol, rule.maxiter) == (tol, maxiter)
    with pytest.raises(ValueError, match="tol"):
        StoppingRule.checked(-tol, maxiter, maxiter_limit=MAXITER_LIMIT)


# --- issue 23: relative stopping tests, the result contract, bounds ------------------------------

def test_the_default_test_is_relative():
    # D4: scaled by 1e12, the solution is [9.1e-14, 6.4e-13]; an absolute step test of 1e-10
    # stops after one sweep at [3.0e-13, 6.8e-13], 200 % off
    A = A2 * 1e12
    res = linear.sor(A, B2, 1.2)
    # SOR stops on its relative step (default 1e-10): for this 2 x 2 contraction the error is of the
    # same size; 1e-9 a margin of ten
    assert_allclose(res.x, X2 / 1e12, rtol=1e-9)
    for method in ("jacobi", "gauss_seidel"):
        assert_allclose(getattr(linear, method)(A, B2).x, X2 / 1e12, rtol=1e-9)
        # as above, for Jacobi and Gauss-Seidel
        assert_allclose(getattr(linear, method)(sp.csr_array(A), B2).x, X2 / 1e12, rtol=1e-9)
    absolute = linear.sor(A, B2, 1.2, relative=False)
    assert absolute.iterations == 1 and np.abs(absolute.x / (X2 / 1e12) - 1).max() > 1


@HYPOTHESIS
@given(dominant_systems(), st.integers(-40, 40), st.sampled_from(METHODS),
       st.sampled_from(CRITERIA))
@example(system=(np.array([[-0.5]]), np.array([2.22507386e-308])), power=-3, method="sor",
         criterion="step")  # steps below the normal range: not compared, the answers checked
def test_stationary_solvers_are_indifferent_to_scale(system, power, method, criterion):
    # A scaled by a power of two scales every iterate exactly: a relative test stops at the
    # same sweep, wherever the solution's size
    A, b = system
    omega = {"omega": 1.1} if method == "sor" else {}
    try:
        one = getattr(linear, method)(A, b, criterion=criterion, **omega)
    except ConvergenceError as error:   # SOR at 1.1 need not converge on these
        assert error.result.status in ("maxiter", "diverged", "non-finite")
        return
    scaled = getattr(linear, method)(A * 2.0 ** power, b, criterion=criterion, **omega)
    # ... as long as the steps and residuals the test compares are normal numbers: a subnormal
    # one keeps fewer bits, and the two runs round it differently (make explore found b = 2e-308)
    tested = 1e-10 * min(np.abs(one.x).max(), np.abs(scaled.x).max(), np.abs(b).max())
    if tested >= np.finfo(float).tiny:
        assert scaled.iterations == one.iterations
        # the same iteration in a scale shifted by a power of two: the same digits exactly, rtol
        # only for the form
        assert_allclose(scaled.x * 2.0 ** power, one.x, rtol=1e-12, atol=1e-300)
    exact = np.linalg.solve(A, b)
    if criterion == "residual":   # the documented tolerance, recomputed
        assert np.abs(b - A @ one.x).max() <= 1e-10 * np.abs(b).max() * (1 + 1e-6) + 1e-300
    else:                         # a step below 1e-10 |x|: a contraction's error is not far off
        assert np.abs(one.x - exact).max() <= 1e-6 * max(np.abs(exact).max(), 1e-300)


@HYPOTHESIS
@given(spd_systems(), st.integers(-40, 40))
@example(system=(np.array([[0.5]]), np.array([6.78643142e-162])), power=-3)  # b . b subnormal
def test_conjugate_gradient_meets_its_tolerance(system, power):
    A, b = system
    A = A * 2.0 ** power
    res = linear.conjugate_gradient(A, b, tol=1e-10)
    # CG with tol 1e-10 on its relative residual; 1e-9 allows for the recomputed residual's
    # round-off
    assert np.linalg.norm(b - A @ res.x) <= 1e-9 * np.linalg.norm(b) + 1e-300


def test_results_follow_the_contract():
    res = _stationary.gauss_seidel(TRI_A, TRI_B)
    assert isinstance(res, Result) and res.status == "converged" and res.converged
    assert res.nfev == res.iterations + 1 and res.njev == 0 and "converged" in res.message
    with pytest.raises(ConvergenceError) as info:
        linear.sor(TRI_A, TRI_B, 0.1, maxiter=5)
    assert info.value.result.status == "maxiter" and not info.value.result.converged
    with pytest.raises(DivergenceError) as info:
        linear.jacobi([[1.0, 2.0], [2.0, 1.0]], [1.0, 1.0])
    assert info.value.result.status == "diverged"
    cg = linear.conjugate_gradient(TRI_A, TRI_B)
    assert cg.status == "converged" and cg.nfev == cg.iterations + 1
    refined = linear.iterative_refinement(TRI_A, TRI_B)
    assert refined.status == "converged" and isinstance(refined, Result)


@pytest.mark.parametrize("call, message", [
    (lambda: _stationary.gauss_seidel(TRI_A, TRI_B, maxiter=10 ** 8), "bound on the work"),
    (lambda: linear.sor_sweep(TRI_A, TRI_B, np.full(10_001, 1.2)), "bound on the work"),
    (lambda: linear.sor_spectral_radii(TRI_A, np.full(10_001, 1.2)), "bound on the work"),
    (lambda: linear.conjugate_gradient(TRI_A, TRI_B, maxiter=10 ** 8), "bound on the work"),
    (lambda: linear.iterative_refinement(TRI_A, TRI_B, maxiter=1000), "bound on the work"),
    (lambda: linear.poisson2d(10 ** 5), "bound on the work"),
    (lambda: linear.poisson3d(POISSON3D_LIMIT + 1), "bound on the work"),
    (lambda: linear.sor(TRI_A, TRI_B, 1.2, relative=1), "relative must be True or False"),
])
def test_every_amount_of_work_is_bounded(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_a_sparse_matrix_of_float16_is_accepted():
    # R7: scipy converts a COO or DIA matrix holding float16 (which it does not support) only
    # element by element; check_matrix converts it first
    for fmt in (sp.coo_array, sp.dia_array, sp.csr_array):
        A = fmt(TRI_A)
        A.data = A.data.astype(np.float16)
        checked = check_matrix(A)
        assert checked.dtype == np.float64
        assert_allclose(checked.toarray(), TRI_A, rtol=0, atol=0)


@pytest.mark.parametrize("scale", [2.0 ** -1040, 1e-300, 1e300])
def test_scale_invariant_quantities_ignore_the_scale(scale):
    # cond(c A) = cond(A) and SOR's iteration matrix of c A is that of A: with subnormal (2^-1040)
    # or huge entries the inverse and D^-1 overflowed (cond came out inf, optimal_omega raised
    # numpy's LinAlgError). A power of two keeps every digit; 1e-300 and 1e300 round each entry
    # once, so the results agree to a few ulps (rtol 1e-14).
    A = np.array([[4.0, 1.0, 0.0], [1.0, 4.0, 1.0], [0.0, 1.0, 4.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        for p in (1, 2, np.inf, "fro"):
            # a few ulps, as above
            assert linear.condition_number(scale * A, p) == pytest.approx(
                linear.condition_number(A, p), rel=1e-14)
        assert_allclose(linear.sor_spectral_radii(scale * A, [1.0, 1.2]),
                        linear.sor_spectral_radii(A, [1.0, 1.2]), rtol=1e-14)  # as above
        assert linear.optimal_omega(scale * A).x == pytest.approx(  # as above
            linear.optimal_omega(A).x, rel=1e-14)
