"""Pseudo-arclength continuation: a curve of solutions traced through its folds.

Natural-parameter continuation (:func:`mechnum.newton.solve_path`) fixes the parameter and
corrects the state: it stops at a *fold*, where the curve turns back in the parameter and the
Jacobian in the state is singular. Keller's pseudo-arclength continuation treats the ``n``
equations ``F(u) = 0`` in the ``n + 1`` unknowns ``u = (state, parameter)`` alike, and steps
along the curve by its arclength ``h``:

1. the **tangent** ``t`` at a point ``u`` spans the null space of ``F'(u)`` (shape
   ``(n, n + 1)``); it is the solution of ``[F'(u); t_prev^T] t = [0; 1]``, normalised, so
   that it keeps the orientation of the previous tangent;
2. the **predictor** ``u + h t`` is corrected by Newton's method on the bordered system
   ``F(v) = 0``, ``t . (v - u) = h`` (the new point lies on the hyperplane at distance ``h``
   along the tangent), whose Jacobian ``[F'(v); t^T]`` stays regular at a fold;
3. the step ``h`` is halved when Newton fails, and grows after an easy step.

A fold is where the parameter's component of the tangent changes sign; :func:`pseudo_arclength`
reports the intervals where it does and locates each fold on the curve by the secant method on
that component. Reference: H. B. Keller, *Numerical solution of bifurcation and nonlinear
eigenvalue problems* (1977); E. L. Allgower and K. Georg, *Introduction to Numerical
Continuation Methods* (2003), chapter 2.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.errors import ConvergenceError

# The step grows by this factor after a step whose corrector needed at most _EASY iterations.
_GROWTH, _EASY = 1.5, 3
# Secant steps that locate a fold on its interval (each one a corrector), and the tolerance on
# the parameter's tangent component (relative to the tangent's unit length).
_FOLD_STEPS, _FOLD_TOL = 30, 1e-12


@dataclass(frozen=True)
class Branch:
    """A curve traced by :func:`pseudo_arclength`.

    Attributes
    ----------
    u, tangent : ndarray, shape (m, n + 1)
        The points (the parameter last) and the unit tangents there, in the order traced.
    folds : ndarray of int, shape (f,)
        ``i`` where a fold lies between ``u[i]`` and ``u[i + 1]``.
    fold_points : ndarray, shape (f, n + 1)
        The folds themselves (where the tangent's last component vanishes).
    rejected : int
        Steps halved because Newton failed.
    complete : bool
        False if the step fell below ``min_step`` before ``steps`` points or ``stop``.
    """

    u: np.ndarray
    tangent: np.ndarray
    folds: np.ndarray
    fold_points: np.ndarray
    rejected: int
    complete: bool


def _tangent(J, previous):
    """The unit null vector of ``J`` (shape ``(n, n + 1)``) on the side of ``previous``."""
    border = np.vstack((J, previous))
    rhs = np.zeros(len(border))
    rhs[-1] = 1.0
    t = np.linalg.solve(border, rhs)
    return t / np.linalg.norm(t)


def _correct(fun, jac, u, t, h, tol, maxiter):
    """Newton on ``F(v) = 0``, ``t . (v - u) = h`` from ``u + h t``: ``(v, J(v), iterations)``,
    or None if it does not converge (or meets a singular matrix)."""
    v = u + h * t
    for iteration in range(1, maxiter + 1):
        J = np.atleast_2d(jac(v))
        r = np.append(fun(v), t @ (v - u) - h)
        try:
            dv = np.linalg.solve(np.vstack((J, t)), -r)
        except np.linalg.LinAlgError:
            return None
        v = v + dv
        if not np.all(np.isfinite(v)):
            return None
        if np.linalg.norm(dv) <= tol * (1.0 + np.linalg.norm(v)):
            return v, np.atleast_2d(jac(v)), iteration
    return None


def _fold(fun, jac, u, t, h, tol, maxiter):
    """The fold between ``u`` (tangent ``t``) and the point at step ``h``: the secant method
    on the step ``x`` for the last component of the tangent at ``x``."""
    def g(x):
        v, J, _ = _correct(fun, jac, u, t, x, tol, maxiter)
        return _tangent(J, t)[-1], v

    (x0, g0), (x1, (g1, v)) = (0.0, t[-1]), (h, g(h))
    for _ in range(_FOLD_STEPS):
        if abs(g1) <= _FOLD_TOL:
            break
        x0, g0, x1 = x1, g1, x1 - g1 * (x1 - x0) / (g1 - g0)
        g1, v = g(x1)
    return v


def pseudo_arclength(fun, jac, u0, *, direction=None, step=0.1, max_step=None, min_step=1e-8,
                     steps=200, tol=1e-10, maxiter=8, stop=None):
    """Trace the curve ``F(u) = 0`` through ``u0`` by pseudo-arclength continuation.

    Parameters
    ----------
    fun : callable
        ``fun(u) -> (n,)``, for ``u`` of shape ``(n + 1,)`` (the parameter last).
    jac : callable
        ``jac(u) -> (n, n + 1)``, the Jacobian of ``fun``.
    u0 : array_like, shape (n + 1,)
        A point on the curve (to ``tol``).
    direction : array_like, shape (n + 1,), optional
        The way to go: the first tangent is taken on its side. Default: increasing parameter.
    step, max_step, min_step : float, optional
        First arclength step, largest step (default ``10 step``), and the step below which
        the curve is declared lost.
    steps : int, optional
        Most points traced after ``u0``.
    tol, maxiter : optional
        Newton's corrector stops when its step is below ``tol (1 + |v|)``, and fails after
        ``maxiter`` iterations.
    stop : callable, optional
        ``stop(u) -> bool``: the point for which it is true is kept, and the tracing ends.

    Returns
    -------
    Branch

    Raises
    ------
    ValueError
        If ``u0`` is not on the curve (``|F(u0)| > 1e3 tol (1 + |u0|)``), or an input is
        out of range.
    ConvergenceError
        If no point after ``u0`` could be computed.

    Examples
    --------
    The circle ``x**2 + p**2 = 1`` folds at ``p = +-1``; from ``(1, 0)`` upwards:

    >>> fun = lambda u: np.array([u[0] ** 2 + u[1] ** 2 - 1.0])
    >>> jac = lambda u: np.array([[2.0 * u[0], 2.0 * u[1]]])
    >>> branch = pseudo_arclength(fun, jac, [1.0, 0.0], step=0.1, steps=40)
    >>> len(branch.folds), (np.round(branch.fold_points, 10) + 0.0).tolist()
    (2, [[0.0, 1.0], [0.0, -1.0]])
    """
    u = _validate.array(u0, "u0", ndim=1)
    tol, maxiter = _validate.tolerance(tol), _validate.maxiter(maxiter)
    steps = _validate.maxiter(steps, "steps")
    h = _validate.scalar(step, "step", positive=True)
    max_step = 10.0 * h if max_step is None else _validate.scalar(max_step, "max_step",
                                                                    positive=True)
    min_step = _validate.scalar(min_step, "min_step", positive=True)
    if np.linalg.norm(fun(u)) > 1e3 * tol * (1.0 + np.linalg.norm(u)):
        raise ValueError(f"u0 = {u!r} is not on the curve: |F(u0)| = "
                         f"{np.linalg.norm(fun(u)):.3g}")
    if direction is None:
        direction = np.zeros(u.size)
        direction[-1] = 1.0
    direction = _validate.array(direction, "direction", shape=u.shape)
    t = _tangent(np.atleast_2d(jac(u)), direction)
    points, tangents, folds, fold_points, rejected = [u], [t], [], [], 0
    complete = True
    while len(points) <= steps:
        corrected = _correct(fun, jac, u, t, h, tol, maxiter)
        if corrected is None:
            h, rejected = 0.5 * h, rejected + 1
            if h < min_step:
                complete = False
                break
            continue
        v, J, iterations = corrected
        t_new = _tangent(J, t)
        if np.sign(t_new[-1]) != np.sign(t[-1]) and t[-1] != 0:
            folds.append(len(points) - 1)
            fold_points.append(_fold(fun, jac, u, t, h, tol, maxiter))
        u, t = v, t_new
        points.append(u)
        tangents.append(t)
        if iterations <= _EASY:
            h = min(_GROWTH * h, max_step)
        if stop is not None and stop(u):
            break
    if len(points) == 1:
        raise ConvergenceError(f"no point of the curve beyond u0 (the step fell below "
                               f"{min_step:g})")
    return Branch(np.array(points), np.array(tangents), np.array(folds, dtype=int),
                  np.array(fold_points).reshape(len(fold_points), u.size), rejected, complete)
