"""One system: Newton-Raphson (:func:`solve`) and Broyden's method (:func:`broyden`).

Both take Newton's step, ``J dx = -f`` (with the test of a singular ``J``), with the
Jacobian itself (Newton) or a rank-one update of it (Broyden), and stop by the
:class:`~mechnum.results.StoppingRule`. Newton may be damped (a backtracking line search)
and its steps bounded (``max_step``); every iterate is kept in the result's ``history``.

Examples
--------
>>> import numpy as np
>>> solve(lambda x: x ** 2 - 4.0, [1.0], lambda x: np.diag(2 * x)).x.tolist()
[2.0]
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError, DivergenceError, SingularJacobianError
from mechnum.newton._core import (
    HALVINGS_LIMIT,
    MAX_HALVINGS,
    MAXITER_LIMIT,
    TOL,
    Equations,
    bounded,
    describe,
    line_search,
    newton_step,
    norms,
)
from mechnum.results import Result, StoppingRule


@dataclass(frozen=True, kw_only=True)
class NewtonResult(Result):
    """The outcome of :func:`solve` and :func:`broyden`.

    Attributes
    ----------
    x : ndarray, shape (n,)
        The last iterate.
    status : str
        ``"converged"``, or what stopped it (:data:`~mechnum.results.STATUSES`; a result that
        is not converged reaches the caller only inside the error raised).
    message, iterations, nfev, njev
        As in :class:`~mechnum.results.Result`; ``iterations`` counts the steps.
    history : ndarray, shape (iterations + 1, n)
        Every iterate, the initial guess first.
    residual_norms : ndarray, shape (iterations + 1,)
        ``||f(x_k)||`` for every iterate in ``history``.
    step_norms : ndarray, shape (iterations,)
        ``||x_{k+1} - x_k||``, the step taken (shortened by ``max_step`` or damping).
    full_step_norms : ndarray, shape (iterations,)
        ``||dx_k||`` of the full Newton step, the quantity the step criterion tests.
    """

    history: np.ndarray
    residual_norms: np.ndarray
    step_norms: np.ndarray
    full_step_norms: np.ndarray


def solve(fun: Callable, seed: ArrayLike, jac: Callable | bool | None = None, *, tol: float = TOL,
          maxiter: int = 50, criterion: str = "step", norm: float = 2,
          damping: bool = False, max_step: float | None = None, relative: bool | None = None,
          halvings: int = MAX_HALVINGS) -> NewtonResult:
    """Solve ``fun(x) = 0`` by Newton-Raphson.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (n,)``, the residual (real); with ``jac=True``,
        ``fun(x) -> (f, J)``.
    seed : array_like, shape (n,)
        The initial guess; must be finite and real.
    jac : callable, True or None, optional
        ``jac(x) -> ndarray (n, n)``, the Jacobian; ``True`` if ``fun`` returns it with the
        residual (as scipy's ``root(jac=True)``: work the two share is done once, and the
        Jacobian of a point the line search accepts is not computed again). Default:
        forward differences (:func:`~mechnum.newton.fd_jacobian`).
    tol : float, optional
        Tolerance of the stopping criterion (positive); default ``1e-10`` (relative: the
        accepted iterate is at round-off if Newton's constant is below ``1e5``, while a
        Jacobian of condition ``1e6`` can still meet it).
    maxiter : int, optional
        Most Newton steps, at most :data:`~mechnum.newton.MAXITER_LIMIT`.
    criterion : {"step", "residual"}, optional
        Stop after the first full Newton step ``dx`` with ``||dx|| <= tol ||x_{k+1}||`` (the
        step before ``max_step`` or damping shortens it; the accepted ``x`` is the one after
        that step), or as soon as ``||f(x_k)|| <= tol``.
    norm : {2, 1, inf}, optional
        Vector norm of the criterion.
    damping : bool, optional
        Backtrack along each step until ``||f||`` decreases by Armijo's rule (see
        :mod:`mechnum.newton`); raise :class:`~mechnum.errors.ConvergenceError` if no step
        length of at least ``2**-halvings`` of Newton's does.
    max_step : float, optional
        Shorten every Newton step to at most this size (largest component) before anything
        else: a start far from the root then moves towards it in bounded strides, where a full
        step could leap across a periodic or unbounded variable to a far, wrong basin. The
        criterion still tests the full step, so a ``max_step`` below ``tol`` cannot fake
        convergence.
    relative : bool, optional
        Whether the test is relative: by default it is for the step (``tol ||x_{k+1}||``) and
        not for the residual (``tol``; with ``True``, ``tol ||f(x_0)||``). ``False`` with the
        step criterion is the absolute rule of most course codes, the hacksaw study's included:
        use it for a root at the origin, which a relative test reaches only once the iterates
        underflow.
    halvings : int, optional
        With damping, the most halvings of a step (at most 52: ``2**-52`` of a step moves
        ``x`` by round-off).

    Returns
    -------
    NewtonResult

    Raises
    ------
    ValueError
        If ``seed`` is not a finite real vector, an option is invalid, or ``fun``/``jac`` return
        the wrong shape or complex values.
    SingularJacobianError
        If the Jacobian is singular at an iterate; ``result`` holds the partial result.
    DivergenceError
        If a residual, a Jacobian or an iterate stops being finite.
    ConvergenceError
        If ``maxiter`` steps do not meet the criterion, or (with damping) the line search
        stagnates; its ``result`` attribute holds the partial :class:`NewtonResult`.

    Examples
    --------
    >>> import numpy as np
    >>> res = solve(lambda x: np.array([x[0] ** 2 - 2.0]), [1.0], lambda x: np.array([[2 * x[0]]]))
    >>> res.converged, res.iterations, round(float(res.x[0]), 12)
    (True, 5, 1.414213562373)

    The residual and its Jacobian from one function:

    >>> res = solve(lambda x: (x ** 2 - 2.0, np.diag(2 * x)), [1.0], jac=True)
    >>> res.nfev, res.njev, res.status
    (6, 6, 'converged')

    Plain Newton on ``arctan(x) = 0`` from the seed ``1.5`` overshoots further at every step and
    diverges; damped, it converges:

    >>> res = solve(lambda x: np.arctan(x), [1.5], lambda x: np.diag(1 / (1 + x**2)), damping=True)
    >>> res.converged, abs(float(res.x[0])) < 1e-12
    (True, True)
    """
    damping = _validate.flag(damping, "damping")
    halvings = _validate.maxiter(halvings, "halvings", maximum=HALVINGS_LIMIT)

    def matrix(eqs, x, fx, J, previous):
        return eqs.jacobian(x, fx, J)

    return _iterate(Equations(fun, jac), seed, matrix,
                    StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                         maxiter_limit=MAXITER_LIMIT),
                    damping, max_step, halvings, "Newton", "Jacobian")


def broyden(fun: Callable, seed: ArrayLike, jac: Callable | bool | None = None, *, tol: float = TOL,
            maxiter: int = 100, criterion: str = "step", norm: float = 2,
            relative: bool | None = None) -> NewtonResult:
    """Solve ``fun(x) = 0`` by Broyden's method: Newton's step with an updated Jacobian.

    The Jacobian is evaluated once, at the seed (``B_0 = J(seed)``); after every step
    ``s = x_{k+1} - x_k``, with ``y = f(x_{k+1}) - f(x_k)``, it is replaced by the closest
    matrix (in the Frobenius norm) that maps ``s`` to ``y`` (the secant condition
    ``B_{k+1} s = y``), a rank-one update::

        B_{k+1} = B_k + (y - B_k s) s^T / (s^T s)

    (Broyden's "good" update). Each iteration costs one evaluation of ``fun`` and no Jacobian;
    the convergence is superlinear instead of quadratic, so it takes more iterations than
    Newton: worth it when the Jacobian is expensive. Step, criteria and errors as in
    :func:`solve` (no damping).

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (n,)``, the residual (real); with ``jac=True``,
        ``fun(x) -> (f, J)`` (only the first ``J`` is used).
    seed : array_like, shape (n,)
        The initial guess; must be finite and real.
    jac : callable, True or None, optional
        ``jac(x) -> ndarray (n, n)``, evaluated at the seed only. Default: forward differences.
    tol, maxiter, criterion, norm, relative
        As in :func:`solve`.

    Returns
    -------
    NewtonResult
        ``iterations`` is the number of Broyden steps (each one call of ``fun``).

    Raises
    ------
    ValueError, SingularJacobianError, DivergenceError, ConvergenceError
        As :func:`solve` (a singular update is a :class:`~mechnum.errors.SingularJacobianError`).

    Examples
    --------
    >>> import numpy as np
    >>> fun = lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0, x[0] - x[1]])
    >>> jac = lambda x: np.array([[2 * x[0], 2 * x[1]], [1.0, -1.0]])
    >>> res = broyden(fun, [1.0, 0.5], jac, tol=1e-12)
    >>> res.iterations, solve(fun, [1.0, 0.5], jac, tol=1e-12).iterations
    (7, 6)
    >>> np.round(res.x, 12).tolist()
    [0.707106781187, 0.707106781187]
    """
    def matrix(eqs, x, fx, J, previous):
        if previous is None:
            return eqs.jacobian(x, fx, J)
        B, x_old, f_old = previous
        s, y = x - x_old, fx - f_old
        # the rank-one update (y - B s) s^T / (s^T s) with s scaled to a unit vector: s^T s
        # underflows for a step below 1e-162, which would leave B unchanged (a chord method)
        size = norms(s, 2)
        if not size > 0:
            return B
        return B + np.outer((y - B @ s) / size, s / size)

    return _iterate(Equations(fun, jac), seed, matrix,
                    StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                         maxiter_limit=MAXITER_LIMIT),
                    False, None, MAX_HALVINGS, "Broyden's method", "Broyden matrix")


def _iterate(eqs, seed, matrix, rule, damping, max_step, halvings, method, what):
    """The iteration of :func:`solve` and :func:`broyden`: step ``dx`` solves
    ``B dx = -f`` with ``B = matrix(eqs, x, f, J, previous)``, the Jacobian (Newton) or its
    update from ``previous = (B, x, f)`` of the last step (Broyden), the ``what`` of the
    messages."""
    x = _validate.array(seed, "seed", ndim=1)
    if x.size == 0:
        raise ValueError("seed must have shape (n,) with n >= 1, got shape (0,)")
    if max_step is not None:
        max_step = _validate.tolerance(max_step, "max_step")
    history, residuals, steps, full = [x], [], [], []
    status, previous, detail = None, None, ""
    fx, J = eqs.value(x)
    limit = rule.tol * norms(fx, rule.norm) if rule.relative else rule.tol
    while True:
        residuals.append(norms(fx, rule.norm))
        if not np.isfinite(residuals[-1]):
            status, detail = "non-finite", "the residual is not finite"
            break
        if rule.criterion == "step" and full and np.isfinite(full[-1]) and full[-1] <= (
                rule.tol * (norms(x, rule.norm) if rule.relative else 1.0)):
            status = "converged"
            break
        if rule.criterion == "residual" and residuals[-1] <= limit:
            status = "converged"
            break
        if len(steps) == rule.maxiter:
            status = "maxiter"
            break
        B = matrix(eqs, x, fx, J, previous)
        if not np.all(np.isfinite(B)):
            status, detail = "non-finite", f"the {what} is not finite"
            break
        dx, singular, cond = newton_step(B, fx)
        if singular:
            status = "singular"
            break
        previous = (B, x, fx)
        full.append(norms(dx, rule.norm))
        dx, shrink = bounded(dx, max_step)
        if damping:  # the batched line search, on a batch of this one system
            sure = rule.criterion == "step" and full[-1] <= rule.tol * (
                norms(x + dx, rule.norm) if rule.relative else 1.0)
            trial, failed, _ = line_search(
                lambda z, _: _one(eqs.value(z[0])), x[None], fx[None],
                None if J is None else J[None], dx[None], np.ones(1, bool),
                residuals[-1:], np.array([sure]), rule.norm, None, shrink=shrink[None],
                halvings=halvings)
            if failed[0]:
                status = "stagnated"
                break
            x_new, fx, J = trial.x[0], trial.f[0], None if trial.J is None else trial.J[0]
        else:
            x_new = x + dx
            fx, J = eqs.value(x_new)
        steps.append(norms(x_new - x, rule.norm))
        x = x_new
        history.append(x)
    k = len(steps)
    messages = {
        "converged": f"{method} converged in {k} iterations ({describe(rule)})",
        "non-finite": f"{method} stopped at iteration {k}: {detail}",
        "singular": f"singular {what} at iteration {k}: condition number >= "
                    f"{cond if status == 'singular' else 0:.3g}, residual norm "
                    f"{residuals[-1]:.3g}",
        "stagnated": f"the line search stagnated at iteration {k}: no step of at least "
                     f"2**-{halvings} of {method}'s decreases the residual norm "
                     f"{residuals[-1]:.3g} (a local minimum of ||f|| that is no root?)",
        "maxiter": f"{method} did not converge in {k} iterations: last full step norm "
                   f"{full[-1] if full else float('nan'):.3g}, residual norm "
                   f"{residuals[-1]:.3g} ({describe(rule)})",
    }
    result = NewtonResult(x=x, status=status, message=messages[status], iterations=k,
                          nfev=eqs.nfev, njev=eqs.njev, history=np.array(history),
                          residual_norms=np.array(residuals), step_norms=np.array(steps),
                          full_step_norms=np.array(full))
    error = {"singular": SingularJacobianError, "non-finite": DivergenceError}.get(
        status, ConvergenceError)
    if status != "converged":
        raise error(result.message, result)
    return result


def _one(value):
    """``(f, J)`` of one system as a batch of one."""
    f, J = value
    return f[None], None if J is None else J[None]
