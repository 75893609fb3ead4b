"""Whether a stationary method converges, and how fast: iteration matrices, spectral radii.

The iteration ``x <- M x + c`` converges from every start if and only if the spectral radius
``rho(M) < 1``, and its error falls like ``rho(M)^k``. :func:`~mechnum.linear.iteration_matrix`
forms ``M`` of Jacobi, Gauss-Seidel or SOR (dense); :func:`~mechnum.linear.sor_spectral_radii`
gives ``rho(M_SOR(omega))`` for a whole sweep of relaxation factors at once, and
:func:`~mechnum.linear.optimal_omega` the factor that minimises it: Young's formula
(:func:`~mechnum.linear.young_omega`) where it is exact, a minimisation otherwise.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from mechnum import _validate
from mechnum.linear._checks import _dense, _relaxation_factors, _unit_scaled
from mechnum.linear._sweeps import splitting
from mechnum.results import Result

#: optimal_omega scans rho(M_SOR) on this grid of (0, 2) (spacing 0.005, fine enough to land in
#: the basin of the minimum), then minimises between the neighbours of the best grid point ...
OMEGA_GRID = np.linspace(0.005, 1.995, 399)
#: ... down to this width of the bracket: rho has a cusp at the optimum, where a bracketing
#: method needs no derivative.
OMEGA_XTOL = 1e-10
#: sor_spectral_radii forms its iteration matrices in blocks of at most this many entries
#: (16 MB of float64 per array), so that thousands of omegas cost one batched call per block.
BLOCK_ENTRIES = 2 ** 21


@dataclass(frozen=True, kw_only=True)
class OptimalOmega(Result):
    """The outcome of :func:`optimal_omega`.

    Attributes
    ----------
    x : float
        The relaxation factor ``omega`` minimising the spectral radius of the SOR iteration
        matrix.
    status : str
        ``"converged"``: Young's formula, or the minimisation met its tolerance on ``omega``.
    message : str
        How it was found.
    iterations, nfev, njev : int
        The minimisation's iterations and spectral radii computed (zero for Young's formula).
    spectral_radius : float
        That minimal spectral radius.
    how : str
        ``"young"`` (the formula ``2 / (1 + sqrt(1 - rho_J^2))``) or ``"numerical"`` (a
        minimisation of ``rho(M_SOR(omega))`` over ``(0, 2)``).
    """

    spectral_radius: float
    how: str


def iteration_matrix(A: ArrayLike, method: str, omega: float = 1.0) -> np.ndarray:
    """The iteration matrix ``M = P^{-1} N`` of Jacobi, Gauss-Seidel or SOR (dense ``A``).

    Parameters
    ----------
    A : array_like, shape (n, n)
        The system matrix; finite, with a non-zero diagonal.
    method : {"jacobi", "gauss_seidel", "sor"}
    omega : float, optional
        The SOR relaxation factor, in ``(0, 2)`` (ignored by the other methods).

    Returns
    -------
    ndarray, shape (n, n)

    Raises
    ------
    ValueError, RelaxationFactorError, SingularJacobianError
        As :func:`splitting`; ValueError also for a sparse ``A``.

    Examples
    --------
    >>> iteration_matrix([[2.0, -1.0], [-1.0, 2.0]], "jacobi")
    array([[0. , 0.5],
           [0.5, 0. ]])
    """
    A = _unit_scaled(_dense(A, "iteration_matrix"))
    split = splitting(A, method, omega)
    if method == "jacobi":
        return np.eye(len(A)) - A / split.diagonal[:, None]
    return _sor_matrices(A, np.array([split.omega]))[0]


def _sor_matrices(A, omegas):
    """``M_SOR(omega) = (D - omega L)^{-1} ((1 - omega) D + omega U)`` for each omega."""
    D = np.diag(np.diag(A))
    L, U = -np.tril(A, -1), -np.triu(A, 1)
    w = omegas[:, None, None]
    return np.linalg.solve(D - w * L, (1 - w) * D + w * U)


def spectral_radius(M: ArrayLike) -> float:
    """The largest modulus of the eigenvalues of a square matrix.

    Parameters
    ----------
    M : array_like, shape (n, n)

    Returns
    -------
    float

    Examples
    --------
    >>> round(spectral_radius([[0.0, 2.0], [-0.5, 0.0]]), 12)   # eigenvalues +-i
    1.0
    """
    return float(np.max(np.abs(np.linalg.eigvals(_dense(M, "spectral_radius")))))


def sor_spectral_radii(A: ArrayLike, omegas: ArrayLike) -> np.ndarray:
    """``rho(M_SOR(omega))`` for every ``omega`` of a sweep, in batched dense algebra.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Dense, finite, with a non-zero diagonal.
    omegas : array_like, shape (k,)
        Relaxation factors in ``(0, 2)``; an empty sweep gives an empty result.

    Returns
    -------
    ndarray, shape (k,)

    Examples
    --------
    >>> sor_spectral_radii([[2.0, -1.0], [-1.0, 2.0]], [1.0]).round(6).tolist()
    [0.25]
    """
    A = _unit_scaled(_dense(A, "sor_spectral_radii"))
    splitting(A, "gauss_seidel")  # checks the diagonal
    omegas = _relaxation_factors(omegas)
    radii = np.empty(omegas.size)
    block = max(1, BLOCK_ENTRIES // A.size)
    for start in range(0, omegas.size, block):
        M = _sor_matrices(A, omegas[start:start + block])
        radii[start:start + block] = np.abs(np.linalg.eigvals(M)).max(axis=-1)
    return radii


def young_omega(rho_jacobi: float) -> float:
    """Young's optimal SOR factor ``2 / (1 + sqrt(1 - rho_J^2))`` from Jacobi's spectral radius.

    It is the optimum for consistently ordered matrices whose Jacobi eigenvalues are real
    (tridiagonal SPD matrices, the 5-point Laplacian in natural order), where the optimal
    spectral radius is ``omega* - 1``.

    Examples
    --------
    >>> round(young_omega(np.cos(np.pi / 51)), 6)   # 2-D Poisson, 50 x 50 interior nodes
    1.884018
    """
    rho = _validate.scalar(rho_jacobi, "rho_jacobi", nonnegative=True)
    if not rho < 1:
        raise ValueError(f"Young's formula needs rho_jacobi < 1 (Jacobi convergent), got {rho!r}")
    return float(2.0 / (1.0 + np.sqrt(1.0 - rho ** 2)))


def _young_applies(A):
    """Young's formula holds for consistently ordered matrices; here: tridiagonal SPD ones."""
    tridiagonal = np.array_equal(A, np.triu(np.tril(A, 1), -1))
    if not (tridiagonal and np.allclose(A, A.T)):
        return False
    return bool(np.all(np.linalg.eigvalsh(A) > 0))


def optimal_omega(A: ArrayLike) -> "OptimalOmega":
    """The SOR relaxation factor of smallest spectral radius, and how it was found.

    For a symmetric positive definite tridiagonal matrix (consistently ordered, Jacobi
    eigenvalues real and below 1) Young's formula (:func:`young_omega`) is exact. Otherwise
    ``rho(M_SOR(omega))`` is scanned on ``OMEGA_GRID`` and
    minimised between the neighbours of the best grid point.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Dense.

    Returns
    -------
    OptimalOmega

    Examples
    --------
    >>> A = [[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]]
    >>> best = optimal_omega(A)
    >>> round(best.x, 6), round(best.spectral_radius, 6), best.how
    (1.171573, 0.171573, 'young')
    """
    A = _unit_scaled(_dense(A, "optimal_omega"))
    if _young_applies(A):
        omega = young_omega(spectral_radius(iteration_matrix(A, "jacobi")))
        return OptimalOmega(x=omega, status="converged", iterations=0, nfev=0, njev=0,
                            message=f"Young's formula: omega = {omega:.6g}",
                            spectral_radius=omega - 1.0, how="young")
    rho = sor_spectral_radii(A, OMEGA_GRID)
    i = int(np.argmin(rho))
    lo, hi = OMEGA_GRID[max(i - 1, 0)], OMEGA_GRID[min(i + 1, OMEGA_GRID.size - 1)]
    best = minimize_scalar(lambda w: sor_spectral_radii(A, [w])[0], bounds=(lo, hi),
                           method="bounded", options={"xatol": OMEGA_XTOL})
    omega, value = (best.x, best.fun) if best.fun <= rho[i] else (OMEGA_GRID[i], rho[i])
    return OptimalOmega(x=float(omega), status="converged", iterations=int(best.nit),
                        nfev=int(best.nfev) + OMEGA_GRID.size, njev=0,
                        message=f"minimised over (0, 2): omega = {omega:.6g}",
                        spectral_radius=float(value), how="numerical")
