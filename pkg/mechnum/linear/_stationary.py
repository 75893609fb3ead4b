"""Jacobi, Gauss-Seidel and SOR: the solvers, when they stop, and a sweep over ``omega``.

Each solver sweeps a :class:`Splitting` until its
:class:`~mechnum.results.StoppingRule` is met. The criterion is explicit, because iteration counts
depend on it:

* ``criterion="step"``: stop when ``||x_{k+1} - x_k|| / omega <= tol ||x_{k+1}||`` (``<= tol``
  with ``relative=False``). The step of SOR is ``omega`` times the Gauss-Seidel-like correction
  ``(D - omega L)^{-1} r_k``; dividing by ``omega`` tests that correction, a preconditioned
  residual, and not a step made small by a small ``omega``. For Jacobi and Gauss-Seidel this is
  the rule of Burden and Faires' algorithms 7.1 and 7.2;
* ``criterion="residual"``: stop when ``||b - A x_k|| <= tol ||b||`` (``<= tol`` with
  ``relative=False``).

Both tests are relative by default: an absolute test stops a system whose solution is small
(``A`` scaled by ``1e12``) after one sweep, far from its solution, and never stops one whose
solution is large. A relative test also stops once the residual is at the subnormal floor
(``SUBNORMAL_FLOOR``, two units of the smallest subnormal), below which nothing is representable.

An iteration whose residual grows beyond :data:`DIVERGENCE_GROWTH` times its start, or
overflows, is reported as diverging (:class:`~mechnum.errors.DivergenceError`). The compiled
loop runs :data:`CHUNK` sweeps per call and records the norm of every step and residual.
"""

import dataclasses
from dataclasses import dataclass

import numba
import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError, DivergenceError
from mechnum.linear._checks import SUBNORMAL_FLOOR, _check_system, _relaxation_factors
from mechnum.linear._spectra import iteration_matrix, sor_spectral_radii, spectral_radius
from mechnum.linear._sweeps import _sweep, splitting
from mechnum.results import Result, StoppingRule

#: Default tolerance of the stationary solvers, relative: ten digits of the solution, well above
#: the round-off floor of a sweep (``eps`` times the condition number, for ``cond(A) < 1e5``).
TOL = 1e-10
#: The most sweeps (or steps) of one solve: a convergent stationary method with a spectral
#: radius of ``1 - 1e-5`` gains ten digits in ``2.3e6`` sweeps; more is a typing slip.
MAXITER_LIMIT = 10_000_000
#: A residual this many times larger than at the start (or than ``||b||``) means divergence: a
#: convergent iteration can grow transiently, but not by eight orders of magnitude.
DIVERGENCE_GROWTH = 1e8
#: Sweeps run per call of the compiled loop: the Python overhead is paid once per chunk, and the
#: norms of a chunk (two arrays of this length) cost nothing next to the sweeps.
CHUNK = 4096
#: Error messages of the stationary solvers quote rho(M) for matrices up to this order, where
#: the dense eigenvalue problem costs milliseconds.
DIAGNOSTIC_ORDER = 200

_NORM_CODES = {np.inf: 0, 1: 1, 2: 2}
_RUNNING, _CONVERGED, _DIVERGED = 0, 1, 2


@dataclass(frozen=True, kw_only=True)
class IterationResult(Result):
    """The outcome of an iterative linear solver.

    Attributes
    ----------
    x : ndarray, shape (n,)
        The last iterate.
    status : str
        ``"converged"``, ``"maxiter"``, ``"diverged"`` (the residual grew beyond
        :data:`DIVERGENCE_GROWTH` times its start) or ``"non-finite"`` (it overflowed); or, for
        refinement, ``"stagnated"``. A result that is not converged reaches the caller only
        inside the error raised.
    message : str
        The outcome in a sentence.
    iterations : int
        Sweeps (or steps, or refinement steps) taken.
    nfev : int
        Products with ``A`` (one per sweep or step, for its residual, plus the first).
    njev : int
        Zero: a linear solver evaluates no Jacobian.
    history : ndarray, shape (iterations + 1, n), or None
        Every iterate, the initial guess first (None when it was not kept).
    residual_norms : ndarray, shape (iterations + 1,)
        ``||b - A x_k||`` for every iterate, in the norm of the criterion.
    step_norms : ndarray, shape (iterations,)
        ``||x_{k+1} - x_k||`` of every sweep (of every correction, for refinement).
    """

    history: np.ndarray | None
    residual_norms: np.ndarray
    step_norms: np.ndarray


@dataclass(frozen=True, kw_only=True)
class SorSweep(Result):
    """The outcome of :func:`sor_sweep`: one SOR run per relaxation factor, a batch.

    Attributes
    ----------
    x : ndarray, shape (k, n)
        The last iterate of each run.
    status : ndarray of str, shape (k,)
        ``"converged"``, ``"maxiter"``, ``"diverged"`` or ``"non-finite"``, per run.
    message : str
        How many runs converged.
    iterations : ndarray of int, shape (k,)
        Sweeps taken by each run.
    nfev, njev : int
        Products with ``A`` over all the runs; zero.
    omegas : ndarray, shape (k,)
        The relaxation factors.
    spectral_radii : ndarray, shape (k,), or None
        ``rho(M_SOR(omega))`` (None for a sparse matrix, whose iteration matrix is not formed).
    """

    omegas: np.ndarray
    spectral_radii: np.ndarray | None


def _initial_guess(seed, b):
    """The checked initial guess, a new array (zero by default)."""
    return np.zeros(b.size) if seed is None else _validate.array(seed, "seed", shape=b.shape)


def _keeps_history(A, keep_history):
    """Whether to keep every iterate: as asked, else for a dense ``A`` only."""
    return not sp.issparse(A) if keep_history is None else _validate.flag(keep_history,
                                                                           "keep_history")


@numba.njit(cache=True)
def _norm(v, p):
    """The inf- (p = 0), 1- or 2-norm of a vector, in plain loops (a BLAS call would pay its
    threads' overhead at every sweep)."""
    total = 0.0
    for value in v:
        if p == 0:
            total = max(total, abs(value))
        elif p == 1:
            total += abs(value)
        else:
            total += value * value
    return np.sqrt(total) if p == 2 else total


@numba.njit(cache=True)
def _run(csr, diagonal, b, x, omega, jacobi, rule, residuals, steps, history):
    """Up to ``steps.size`` sweeps in place; fills the norms (and ``history`` if it has rows).

    ``rule = (norm code, stop on step, relative, tol, residual limit, divergence limit,
    residual floor)``.
    Returns ``(sweeps taken, state)``, the state being running, converged or diverged.
    """
    indptr, indices, data = csr
    p, by_step, relative, tol, limit, blow_up, floor = rule
    n = b.size
    old, work = np.empty(n), np.empty(n)
    for k in range(steps.size):
        old[:] = x
        _sweep(indptr, indices, data, diagonal, b, x, omega, jacobi, work)
        steps[k] = _norm(x - old, p)
        for i in range(n):  # the residual b - A x
            work[i] = b[i]
            for m in range(indptr[i], indptr[i + 1]):
                work[i] -= data[m] * x[indices[m]]
        residuals[k] = _norm(work, p)
        if history.shape[0]:
            history[k] = x
        if by_step:
            done = steps[k] / omega <= tol * (_norm(x, p) if relative else 1.0)
        else:
            done = residuals[k] <= limit
        # a relative test met at the subnormal floor: nothing smaller is representable
        done = done or residuals[k] <= floor
        if done:
            return k + 1, 1
        if not residuals[k] <= blow_up:  # growth, overflow or NaN
            return k + 1, 2
    return steps.size, 0


def _vector_norm(v, norm):
    return float(np.linalg.norm(v, norm)) if v.size else 0.0


def _iterate(split, b, x, rule, keep_history):
    """Sweep ``split`` from ``x`` until ``rule`` stops it; ``(IterationResult, state)``."""
    A, n = split.A, b.size
    residual0, b_norm = _vector_norm(b - A @ x, rule.norm), _vector_norm(b, rule.norm)
    limit = max(rule.tol * b_norm, SUBNORMAL_FLOOR) if rule.relative else rule.tol
    blow_up = DIVERGENCE_GROWTH * max(residual0, b_norm, np.finfo(float).tiny)
    compiled_rule = (_NORM_CODES[rule.norm], rule.criterion == "step", bool(rule.relative),
                     rule.tol, limit, blow_up, SUBNORMAL_FLOOR if rule.relative else 0.0)
    x = x.copy()
    residuals, steps, history = [np.array([residual0])], [], [x[None].copy()]
    done, state = 0, _RUNNING
    with np.errstate(over="ignore", invalid="ignore"):
        while state == _RUNNING and done < rule.maxiter:
            count = min(CHUNK, rule.maxiter - done)
            chunk = np.empty(count), np.empty(count), np.empty((count * keep_history, n))
            taken, state = _run(split.rows, split.diagonal, b, x,
                                split.omega, split.method == "jacobi", compiled_rule, *chunk)
            residuals.append(chunk[0][:taken])
            steps.append(chunk[1][:taken])
            history.append(chunk[2][:taken])
            done += taken
    residuals = np.concatenate(residuals)
    if state == _CONVERGED:
        status, message = "converged", f"converged in {done} sweeps ({_described(rule)})"
    elif state == _DIVERGED:
        status = "diverged" if np.isfinite(residuals[-1]) else "non-finite"
        message = f"diverges: residual norm {residuals[-1]:.3g} after {done} sweeps, from " \
                  f"{residuals[0]:.3g}"
    else:
        status, message = "maxiter", (f"did not converge in {rule.maxiter} sweeps: residual "
                                      f"norm {residuals[-1]:.3g} ({_described(rule)})")
    result = IterationResult(x=x, status=status, message=message, iterations=done,
                             nfev=done + 1, njev=0,
                             history=np.concatenate(history) if keep_history else None,
                             residual_norms=residuals,
                             step_norms=np.concatenate(steps or [np.empty(0)]))
    return result, state


def _described(rule):
    """The stopping test in words."""
    if rule.criterion == "step":
        return f"step / omega <= {rule.tol:g}" + (" ||x||" if rule.relative else "")
    return f"residual <= {rule.tol:g}" + (" ||b||" if rule.relative else "")


def _solve(A, b, method, omega, seed, rule, keep_history):
    A, b = _check_system(A, b)
    split = splitting(A, method, omega)
    x, keep = _initial_guess(seed, b), _keeps_history(A, keep_history)
    result, state = _iterate(split, b, x, rule, keep)
    if state == _CONVERGED:
        return result
    name = method if method != "sor" else f"SOR (omega={split.omega:g})"
    rho = ""
    if not sp.issparse(A) and b.size <= DIAGNOSTIC_ORDER:
        rho = f"; spectral radius of the iteration matrix " \
              f"{spectral_radius(iteration_matrix(A, method, split.omega)):.4g}"
    error = DivergenceError if state == _DIVERGED else ConvergenceError
    raise error(f"{name} {result.message}{rho}", result)


def sor(A: ArrayLike | sp.sparray, b: ArrayLike, omega: float, seed: ArrayLike | None = None, *,
        tol: float = TOL, maxiter: int = 10_000, criterion: str = "step",
        norm: float = np.inf, relative: bool = True,
        keep_history: bool | None = None) -> IterationResult:
    """Solve ``A x = b`` by successive over-relaxation.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix, shape (n, n)
        Finite, non-singular, with a non-zero diagonal. A sparse matrix is swept over its
        non-zeros and never made dense.
    b : array_like, shape (n,)
    omega : float
        Relaxation factor in ``(0, 2)``: under-relaxation below 1, over-relaxation above.
    seed : array_like, shape (n,), optional
        The initial guess (default zero).
    tol, maxiter, criterion, norm, relative
        The stopping rule (:class:`~mechnum.results.StoppingRule`): by default the step
        divided by ``omega`` is below ``1e-10 ||x||`` (ten digits, well above the round-off
        floor ``eps cond(A)`` for ``cond(A) < 1e5``), within at most ``maxiter`` sweeps (at
        most ten million: a spectral radius of ``1 - 1e-5`` gains ten digits in ``2.3e6``).
    keep_history : bool, optional
        Keep every iterate in ``history`` (default: for a dense ``A`` only).

    Returns
    -------
    IterationResult

    Raises
    ------
    ValueError
        Ill-shaped or non-finite input, an unknown option.
    SingularJacobianError
        A dense ``A`` singular to working precision, or a zero diagonal entry.
    RelaxationFactorError
        ``omega`` missing or outside ``(0, 2)``.
    DivergenceError
        The residual grows beyond ``DIVERGENCE_GROWTH`` (``1e8``)
        times its start, or overflows.
    ConvergenceError
        ``maxiter`` sweeps without meeting the criterion; ``result`` holds the history.

    Examples
    --------
    >>> res = sor([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], omega=1.1, tol=1e-12)
    >>> res.x.round(10).tolist(), res.converged
    ([0.0909090909, 0.6363636364], True)
    """
    rule = StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                maxiter_limit=MAXITER_LIMIT)
    return _solve(A, b, "sor", omega, seed, rule, keep_history)


def gauss_seidel(A: ArrayLike | sp.sparray, b: ArrayLike, seed: ArrayLike | None = None, *,
                 tol: float = TOL, maxiter: int = 10_000, criterion: str = "step",
                 norm: float = np.inf, relative: bool = True,
                 keep_history: bool | None = None) -> IterationResult:
    """Solve ``A x = b`` by Gauss-Seidel (SOR with ``omega = 1``); arguments as :func:`sor`.

    Examples
    --------
    >>> res = gauss_seidel([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], tol=1e-12)
    >>> res.x.round(10).tolist()
    [0.0909090909, 0.6363636364]
    """
    rule = StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                maxiter_limit=MAXITER_LIMIT)
    return _solve(A, b, "gauss_seidel", 1.0, seed, rule, keep_history)


def jacobi(A: ArrayLike | sp.sparray, b: ArrayLike, seed: ArrayLike | None = None, *,
           tol: float = TOL, maxiter: int = 10_000, criterion: str = "step",
           norm: float = np.inf, relative: bool = True,
           keep_history: bool | None = None) -> IterationResult:
    """Solve ``A x = b`` by Jacobi's method; arguments as :func:`sor`.

    Examples
    --------
    >>> res = jacobi([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], tol=1e-12)
    >>> res.x.round(10).tolist()
    [0.0909090909, 0.6363636364]
    """
    rule = StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                maxiter_limit=MAXITER_LIMIT)
    return _solve(A, b, "jacobi", 1.0, seed, rule, keep_history)


def sor_sweep(A: ArrayLike | sp.sparray, b: ArrayLike, omegas: ArrayLike,
              seed: ArrayLike | None = None, *, tol: float = TOL, maxiter: int = 100_000,
              criterion: str = "step", norm: float = np.inf,
              relative: bool = True) -> "SorSweep":
    """Run SOR for many relaxation factors: spectral radius and iteration count of each.

    Each ``omega`` runs its own iteration with the options of :func:`sor`; nothing is raised
    for one that does not converge, its ``converged`` entry is ``False``.

    Parameters
    ----------
    A, b, seed, tol, maxiter, criterion, norm, relative
        As in :func:`sor`.
    omegas : array_like, shape (k,)
        Relaxation factors, each in ``(0, 2)``; at most
        ``OMEGAS_LIMIT`` (10,000) of them.

    Returns
    -------
    SorSweep

    Examples
    --------
    >>> A = [[4.0, 3.0, 0.0], [3.0, 4.0, -1.0], [0.0, -1.0, 4.0]]
    >>> sweep = sor_sweep(A, [24.0, 30.0, -24.0], [1.0, 1.24, 1.9], tol=1e-8)
    >>> sweep.iterations.tolist(), sweep.converged.tolist()
    ([37, 16, 179], [True, True, True])
    """
    A, b = _check_system(A, b)
    rule = StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                maxiter_limit=MAXITER_LIMIT)
    omegas = _relaxation_factors(omegas)
    x = _initial_guess(seed, b)
    split = splitting(A, "gauss_seidel")
    runs = [_iterate(dataclasses.replace(split, method="sor", omega=float(omega)), b, x, rule,
                     False)[0] for omega in omegas]
    status = np.array([r.status for r in runs], dtype="<U10")
    radii = None if sp.issparse(A) else sor_spectral_radii(A, omegas)
    return SorSweep(x=np.array([r.x for r in runs]).reshape(len(runs), b.size), status=status,
                    message=f"{int(np.sum(status == 'converged'))} of {len(runs)} relaxation "
                            f"factors converged ({_described(rule)})",
                    iterations=np.array([r.iterations for r in runs], dtype=int),
                    nfev=sum(r.nfev for r in runs), njev=0, omegas=omegas,
                    spectral_radii=radii)
