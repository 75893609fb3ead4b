"""Pseudo-arclength continuation: :func:`pseudo_arclength` traces a curve through its folds.

The step grows by half after every easy correction: along the line ``x = p``, the points lie at
arclength 0.1, 0.25 and 0.475 from the start.

Examples
--------
>>> import numpy as np
>>> branch = pseudo_arclength(lambda u: u[:1] - u[1:], [0.0, 0.0],
...                           lambda u: np.array([[1.0, -1.0]]), steps=3)
>>> np.linalg.norm(branch.x, axis=1).round(12).tolist(), branch.complete
([0.0, 0.1, 0.25, 0.475], True)
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, newton
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.results import Result

CORRECTOR_TOL = 1e-10
"""Default tolerance of :func:`pseudo_arclength`'s corrector: Newton's relative step test
(the default of :func:`mechnum.newton.solve`)."""
STEPS_LIMIT = 1_000_000
"""The most points :func:`pseudo_arclength` traces in one call."""
# The step grows by this factor after a step whose corrector needed at most _EASY iterations.
_GROWTH, _EASY = 1.5, 3
# Secant steps that locate a fold on its interval (each one a corrector), and the tolerance on
# the parameter's tangent component (relative to the tangent's unit length).
_FOLD_STEPS, _FOLD_TOL = 30, 1e-12
_MAX_COND = 1.0 / np.finfo(float).eps  # a condition number past which no digit is left
@dataclass(frozen=True, kw_only=True)
class Branch(Result):
    """A curve traced by :func:`pseudo_arclength`.

    Attributes
    ----------
    x : ndarray, shape (m, n + 1)
        The points (the parameter last), in the order traced.
    status : str
        ``"converged"`` if the curve was traced to ``steps`` points or to ``stop``;
        ``"stagnated"`` if the step fell below ``min_step`` first.
    message, nfev, njev
        As in :class:`~mechnum.results.Result`.
    iterations : int
        Newton iterations of all the correctors.
    tangent : ndarray, shape (m, n + 1)
        The unit tangents at the points.
    folds : ndarray of int, shape (f,)
        ``i`` where a fold lies between ``x[i]`` and ``x[i + 1]``.
    fold_points : ndarray, shape (f, n + 1)
        The folds themselves (where the tangent's last component vanishes).
    rejected : int
        Steps halved because Newton failed.
    """

    tangent: np.ndarray
    folds: np.ndarray
    fold_points: np.ndarray
    rejected: int

    @property
    def complete(self) -> bool:
        """bool: False if the step fell below ``min_step`` before ``steps`` points or
        ``stop``."""
        return self.status == "converged"


class _Curve:
    """``fun`` and ``jac`` of :func:`pseudo_arclength`, checked and counted, and the corrector."""

    def __init__(self, fun, jac, size, tol, maxiter):
        self.fun, self.jac, self.n, self.tol, self.maxiter = fun, jac, size - 1, tol, maxiter
        self.nfev = self.njev = self.iterations = 0

    def value(self, u):
        out = np.asarray(self.fun(u))
        if out.shape != (self.n,) or out.dtype.kind not in "biuf":
            raise ValueError(f"fun must return a real array of shape ({self.n},) for u of "
                             f"shape ({self.n + 1},), got {out.dtype} of shape {out.shape}")
        self.nfev += 1
        return out.astype(float)

    def jacobian(self, u):
        out = np.asarray(self.jac(u))
        if out.ndim == 1 and self.n == 1:
            out = out[None]
        if out.shape != (self.n, self.n + 1) or out.dtype.kind not in "biuf":
            raise ValueError(f"jac must return a real array of shape ({self.n}, {self.n + 1}),"
                             f" got {out.dtype} of shape {out.shape}")
        self.njev += 1
        return out.astype(float)

    def correct(self, u, t, h):
        """Newton (:func:`mechnum.newton.solve`) on ``F(v) = 0``, ``t . (v - u) = h`` from
        ``u + h t``: ``(v, F'(v), iterations)``, or None if it fails."""
        try:
            res = newton.solve(lambda v: np.append(self.value(v), t @ (v - u) - h), u + h * t,
                               lambda v: np.vstack((self.jacobian(v), t)), tol=self.tol,
                               maxiter=self.maxiter)
        except (ConvergenceError, SingularJacobianError) as error:
            self.iterations += error.result.iterations
            return None
        self.iterations += res.iterations
        return res.x, self.jacobian(res.x), res.iterations


def _tangent(J, previous):
    """The unit null vector of ``J`` (shape ``(n, n + 1)``) on the side of ``previous``, or
    None where ``[J; previous]`` is singular (``J`` of rank below ``n``)."""
    border = np.vstack((J, previous))
    rhs = np.zeros(len(border))
    rhs[-1] = 1.0
    try:
        t = np.linalg.solve(border, rhs)
    except np.linalg.LinAlgError:
        return None
    # singular to working precision: max|B_ij| ||t||_1 / ||rhs||_1, a lower bound of the
    # condition number ||B||_1 ||B^-1||_1, beyond 1/eps (the test of Newton's step)
    if not np.abs(border).max() * np.abs(t).sum() <= _MAX_COND:
        return None
    return t / np.linalg.norm(t)


def _fold(curve, u, t, h, v, t_h):
    """The fold between ``u`` (tangent ``t``) and ``v``, the point at step ``h`` (tangent
    ``t_h``): the secant method
    on the step ``s`` for the last component of the tangent there (the last point reached, if
    a corrector fails on the way)."""
    def g(s):
        corrected = curve.correct(u, t, s)
        if corrected is None:
            return None
        tangent = _tangent(corrected[1], t)
        return None if tangent is None else (tangent[-1], corrected[0])

    (x0, g0), (x1, g1) = (0.0, t[-1]), (h, t_h[-1])
    for _ in range(_FOLD_STEPS):
        if abs(g1) <= _FOLD_TOL or g1 == g0:
            break
        x0, g0, x1 = x1, g1, x1 - g1 * (x1 - x0) / (g1 - g0)
        found = g(x1)
        if found is None:
            break
        g1, v = found
    return v


def pseudo_arclength(fun: Callable, seed: ArrayLike, jac: Callable, *,
                     direction: ArrayLike | None = None, step: float = 0.1,
                     max_step: float | None = None, min_step: float = 1e-8,
                     steps: int = 200, tol: float = CORRECTOR_TOL, maxiter: int = 8,
                     stop: Callable | None = None) -> Branch:
    """Trace the curve ``F(u) = 0`` through the ``seed`` by pseudo-arclength continuation.

    Parameters
    ----------
    fun : callable
        ``fun(u) -> (n,)``, for ``u`` of shape ``(n + 1,)`` (the parameter last).
    seed : array_like, shape (n + 1,)
        A point on the curve (to ``tol``), where ``F'`` has full rank ``n``.
    jac : callable
        ``jac(u) -> (n, n + 1)``, the Jacobian of ``fun``.
    direction : array_like, shape (n + 1,), optional
        The way to go, non-zero: the first tangent is taken on its side. Default: increasing
        parameter.
    step, max_step, min_step : float, optional
        First arclength step, largest step (default ``10 step``), and the step below which
        the curve is declared lost.
    steps : int, optional
        Most points traced after the seed, at most :data:`STEPS_LIMIT`.
    tol, maxiter : optional
        Newton's corrector (:func:`mechnum.newton.solve`) stops when its step is below
        ``tol |v|`` (:data:`CORRECTOR_TOL`), and fails after ``maxiter`` iterations.
    stop : callable, optional
        ``stop(u) -> bool``: the point for which it is true is kept, and the tracing ends.

    Returns
    -------
    Branch

    Raises
    ------
    ValueError
        If the seed is not on the curve (``|F(seed)| > 1e3 tol (1 + |seed|)``), ``fun`` or ``jac``
        return the wrong shape, or an input is out of range.
    SingularJacobianError
        If ``F'(seed)`` has rank below ``n`` (a bifurcation point, where no single tangent
        exists), or is orthogonal to ``direction``.
    ConvergenceError
        If no point after the seed could be computed.

    Examples
    --------
    The circle ``x**2 + p**2 = 1`` folds at ``p = +-1``; from ``(1, 0)`` upwards:

    >>> fun = lambda u: np.array([u[0] ** 2 + u[1] ** 2 - 1.0])
    >>> jac = lambda u: np.array([[2.0 * u[0], 2.0 * u[1]]])
    >>> branch = pseudo_arclength(fun, [1.0, 0.0], jac, step=0.1, steps=40)
    >>> len(branch.folds), (np.round(branch.fold_points, 10) + 0.0).tolist()
    (2, [[0.0, 1.0], [0.0, -1.0]])
    """
    _validate.function(fun, "fun"), _validate.function(jac, "jac")
    u = _validate.array(seed, "seed", ndim=1)
    if u.size < 2:
        raise ValueError(f"seed must hold the unknowns and the parameter, got shape {u.shape}")
    tol = _validate.tolerance(tol)
    maxiter = _validate.maxiter(maxiter, maximum=newton.MAXITER_LIMIT)
    steps = _validate.maxiter(steps, "steps", maximum=STEPS_LIMIT)
    h = _validate.scalar(step, "step", positive=True)
    max_step = 10.0 * h if max_step is None else _validate.scalar(max_step, "max_step",
                                                                    positive=True)
    min_step = _validate.scalar(min_step, "min_step", positive=True)
    curve = _Curve(fun, jac, u.size, tol, maxiter)
    gap = np.linalg.norm(curve.value(u))
    if gap > 1e3 * tol * (1.0 + np.linalg.norm(u)):
        raise ValueError(f"seed = {u!r} is not on the curve: |F(seed)| = {gap:.3g}")
    if direction is None:
        direction = np.zeros(u.size)
        direction[-1] = 1.0
    direction = _validate.array(direction, "direction", shape=u.shape)
    if not direction.any():
        raise ValueError("direction must be a non-zero vector")
    t = _tangent(curve.jacobian(u), direction)
    if t is None:
        raise SingularJacobianError(
            f"no tangent at the seed {u!r}: F'(seed) has rank below {u.size - 1} (a bifurcation "
            f"point, where branches cross), or its null space is orthogonal to direction")
    points, tangents, folds, fold_points, rejected = [u], [t], [], [], 0
    status = "converged"
    while len(points) <= steps:
        corrected = curve.correct(u, t, h)
        t_new = None if corrected is None else _tangent(corrected[1], t)
        if t_new is None:
            h, rejected = 0.5 * h, rejected + 1
            if h < min_step:
                status = "stagnated"
                break
            continue
        v, _, iterations = corrected
        if np.sign(t_new[-1]) != np.sign(t[-1]) and t[-1] != 0:
            folds.append(len(points) - 1)
            fold_points.append(_fold(curve, u, t, h, v, t_new))
        u, t = v, t_new
        points.append(u)
        tangents.append(t)
        if iterations <= _EASY:
            h = min(_GROWTH * h, max_step)
        if stop is not None and stop(u):
            break
    if len(points) == 1:
        raise ConvergenceError(f"no point of the curve beyond the seed (the step fell below "
                               f"{min_step:g})")
    message = (f"{len(points)} points, {len(folds)} folds, {rejected} steps halved" +
               ("" if status == "converged" else f"; the step fell below {min_step:g}"))
    return Branch(x=np.array(points), status=status, message=message,
                  iterations=curve.iterations, nfev=curve.nfev, njev=curve.njev,
                  tangent=np.array(tangents), folds=np.array(folds, dtype=int),
                  fold_points=np.array(fold_points).reshape(len(fold_points), u.size),
                  rejected=rejected)
