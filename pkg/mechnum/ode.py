"""Ordinary differential equations: fixed-step RK4, and two-point boundary value problems.

:func:`rk4` is the classical fourth-order Runge-Kutta method on a given grid of nodes, the
integrator of the flexible-rod study (its equations (81) to (85)). It is vectorised: the state
may carry any leading batch shape, so many initial-value problems (many rods, many Newton
perturbations) advance together in one sweep over the grid.

:func:`multiple_shooting` solves a two-point boundary value problem ``y' = fun(s, y)``,
``bc(y(s_0), y(s_N)) = 0``. Plain shooting guesses the missing initial values, integrates to the
far end and corrects the guess by Newton's method; its residual depends on the guess through the
whole interval, so it is as nonlinear as the problem (a small change at the start can move the
far end a long way: the rod's tip, or another buckling mode). Multiple shooting cuts the grid
into segments, takes the state at the start of every segment as unknowns, and adds the
continuity of the state between segments to the equations: each segment is short, hence
nearly linear, and a guess of the whole solution (a shape, not only its start) steers Newton.
"""

from collections.abc import Callable
from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, newton
from mechnum.errors import NonFiniteError
from mechnum.results import Result

__all__ = ["multiple_shooting", "rk4"]

_STEP = 1e-30  # complex step: f(x + i h) = f(x) + i h f'(x) + O(h^2), with no cancellation
OUTPUT_LIMIT = 100_000_000
"""The most numbers :func:`rk4` returns (nodes times the size of the state): 800 MB."""
MAXITER_LIMIT = 1000
"""The most Newton iterations of :func:`multiple_shooting`: damped Newton on a boundary value
problem that converges at all does so in tens."""


def _rk4(fun, y, s):
    """The RK4 sweep of :func:`rk4`, without its checks of ``y0`` and ``s`` (``s`` a list of
    floats); a stage of the wrong shape raises, and a complex stage makes the states complex."""
    out = np.empty((len(s),) + y.shape, dtype=y.dtype)
    out[0] = y
    shape = y.shape

    def stage(si, yi):
        k = np.asarray(fun(si, yi))
        if k.shape != shape:
            raise ValueError(f"fun returned shape {k.shape} at s = {si!r}, expected {shape}")
        return k

    k1 = stage(s[0], y)
    for i in range(len(s) - 1):
        h = s[i + 1] - s[i]
        half = 0.5 * h
        k2 = stage(s[i] + half, y + half * k1)
        k3 = stage(s[i] + half, y + half * k2)
        k4 = stage(s[i + 1], y + h * k3)
        y = y + (h / 6.0) * (k1 + 2.0 * (k2 + k3) + k4)
        if y.dtype != out.dtype:  # fun returned complex values for a real state
            out = out.astype(np.result_type(out.dtype, y.dtype))
        out[i + 1] = y
        if i + 2 < len(s):
            k1 = stage(s[i + 1], y)
    return out


def _nodes(s):
    """The nodes ``s`` checked: finite, 1-D, at least two, strictly monotone; a list of floats."""
    s = _validate.array(s, "s", ndim=1)
    if s.size < 2:
        raise ValueError(f"s must have at least 2 nodes, got {s.size}")
    h = np.diff(s)
    if not (np.all(h > 0) or np.all(h < 0)):
        raise ValueError("the nodes s must be strictly increasing or strictly decreasing")
    return s.tolist()  # Python floats: cheaper than numpy scalars in the loop


def rk4(fun: Callable, y0: ArrayLike, s: ArrayLike) -> np.ndarray:
    """Integrate ``dy/ds = fun(s, y)`` from ``y(s[0]) = y0`` by classical RK4 on the nodes ``s``.

    One step from ``s_i`` to ``s_{i+1}`` with ``h = s_{i+1} - s_i`` is::

        k1 = fun(s_i, y_i)
        k2 = fun(s_i + h/2, y_i + h/2 k1)
        k3 = fun(s_i + h/2, y_i + h/2 k2)
        k4 = fun(s_i + h, y_i + h k3)
        y_{i+1} = y_i + h/6 (k1 + 2 k2 + 2 k3 + k4)

    and the global error is ``O(h**4)`` for a smooth ``fun``.

    Parameters
    ----------
    fun : callable
        ``fun(s, y) -> ndarray`` of ``y``'s shape; ``s`` is a float, ``y`` has shape
        ``y0.shape`` (for example ``(batch, n)``: the last axis is the state, the leading
        ones a batch of independent problems). If it returns complex values for a real
        ``y0``, the states are complex from there on.
    y0 : array_like
        The initial state (or batch of states), real or complex; must be finite.
    s : array_like, shape (N,)
        The nodes, ``N >= 2``, strictly monotone (increasing or decreasing); the grid may be
        non-uniform. ``N`` times the size of ``y0`` is at most :data:`OUTPUT_LIMIT`.

    Returns
    -------
    ndarray, shape (N,) + y0.shape
        The state at every node; ``[0]`` is ``y0``.

    Raises
    ------
    ValueError
        If ``y0`` is not numeric or not finite, ``s`` has fewer than two nodes or is not
        strictly monotone, the output would be too large, or ``fun`` returns the wrong shape.
    NonFiniteError
        If a state is not finite: ``fun`` returned NaN or infinity, or a step overflowed (a
        step far too large for ``fun``); the message names the first node.

    Examples
    --------
    >>> import numpy as np
    >>> y = rk4(lambda s, y: -y, [1.0, 2.0], np.linspace(0.0, 1.0, 11))
    >>> y.shape, np.round(y[-1] / np.exp(-1.0), 6).tolist()    # exact: [1, 2]
    ((11, 2), [1.000001, 2.000002])
    >>> np.round(rk4(lambda s, y: 1j * y, [1.0], [0.0, 0.1])[-1], 6)    # exp(0.1 i)
    array([0.995004+0.099833j])
    """
    _validate.function(fun, "fun")
    y = np.asarray(y0)
    if y.dtype.kind not in "biufc":
        raise ValueError(f"y0 must be a real or complex numeric array, got dtype {y.dtype}")
    y = y.astype(np.result_type(y.dtype, float))
    if not np.all(np.isfinite(y)):
        raise ValueError(f"y0 must be finite, got {y0!r}")
    s = _nodes(s)
    if len(s) * max(y.size, 1) > OUTPUT_LIMIT:
        raise ValueError(f"rk4 would return {len(s)} x {y.size} numbers, more than "
                         f"{OUTPUT_LIMIT} (a bound on the memory)")
    with np.errstate(over="ignore", invalid="ignore"):
        out = _rk4(fun, y, s)
    finite = np.isfinite(out.reshape(len(s), -1)).all(axis=1)
    if not finite.all():
        i = int(np.argmin(finite))
        raise NonFiniteError(f"the state is not finite at node {i} (s = {s[i]!r}), after a step "
                             f"of h = {s[i] - s[i - 1]:.3g} from a finite one: fun returned NaN "
                             f"or infinity there, or the step overflowed")
    return out


@dataclass(frozen=True, kw_only=True)
class BVPSolution(Result):
    """The outcome of :func:`multiple_shooting`.

    Attributes
    ----------
    x : ndarray, shape (N, n)
        The solution ``y`` at every node.
    status, message, iterations, nfev, njev
        Those of the Newton iteration on the segments' initial states (``"converged"``: a
        failure raises).
    s : ndarray, shape (N,)
        The nodes.
    segment_starts : ndarray of int, shape (segments,)
        Index in ``s`` of each segment's first node.
    newton : NewtonResult
        The Newton iteration on the segments' initial states.
    """

    s: np.ndarray
    segment_starts: np.ndarray
    newton: newton.NewtonResult


BVP_TOL = 1e-10
"""Default residual tolerance of :func:`multiple_shooting` (absolute: the boundary conditions and
the states are the caller's to scale to order one)."""


def multiple_shooting(fun: Callable, bc: Callable, s: ArrayLike, seed: ArrayLike, *,
                      segments: int = 4,
                      tol: float = BVP_TOL, maxiter: int = 50) -> "BVPSolution":
    """Solve ``y' = fun(s, y)``, ``bc(y(s[0]), y(s[-1])) = 0`` by multiple shooting with RK4.

    The nodes are cut into ``segments`` runs of (nearly) equal numbers of steps. The unknowns
    are the states ``Y_j`` at the first node of every segment; the equations are the boundary
    conditions ``bc(Y_0, phi_last(Y_last)) = 0`` and the continuity ``phi_j(Y_j) - Y_{j+1} = 0``,
    where ``phi_j`` is the RK4 sweep over segment ``j``. Damped Newton
    (:func:`mechnum.newton.solve`) solves them, with the exact Jacobian of the discrete
    sweeps (complex step: ``fun`` and ``bc`` must accept complex states, as a formula of
    numpy's functions does). With ``segments=1`` this is plain shooting.

    Parameters
    ----------
    fun : callable
        ``fun(s, y) -> ndarray`` for ``y`` of shape ``(..., n)`` (a batch), as in :func:`rk4`.
    bc : callable
        ``bc(ya, yb) -> ndarray (n,)``, the ``n`` boundary conditions.
    s : array_like, shape (N,)
        The RK4 nodes, strictly monotone.
    seed : array_like, shape (N, n)
        The initial guess of the solution at every node (only the segments' first nodes are
        used).
    segments : int, optional
        Number of segments, ``1 <= segments <= N - 1``.
    tol, maxiter
        Newton stops when the residual norm is below ``tol``; most iterations (at most
        :data:`MAXITER_LIMIT`).

    Returns
    -------
    BVPSolution

    Raises
    ------
    ValueError
        If an input is malformed (shapes, non-finite values, ``segments`` out of range).
    ConvergenceError, SingularJacobianError
        If Newton fails (:func:`mechnum.newton.solve`); ``result`` holds its partial result.

    Examples
    --------
    ``y'' = -y`` with ``y(0) = 0`` and ``y(pi/2) = 1`` is ``sin(s)``; from a zero guess:

    >>> s = np.linspace(0.0, np.pi / 2, 41)
    >>> sol = multiple_shooting(lambda s, y: np.stack((y[..., 1], -y[..., 0]), -1),
    ...                         lambda ya, yb: np.array([ya[0], yb[0] - 1.0]),
    ...                         s, np.zeros((41, 2)), segments=4)
    >>> bool(np.abs(sol.x[:, 0] - np.sin(s)).max() < 1e-7), sol.iterations
    (True, 1)
    """
    _validate.function(fun, "fun"), _validate.function(bc, "bc")
    nodes = _nodes(s)
    guess = _validate.array(seed, "seed", shape=(len(nodes), None))
    n = guess.shape[1]
    segments = _validate.maxiter(segments, "segments")
    if segments > len(nodes) - 1:
        raise ValueError(f"segments must be at most the number of steps, {len(nodes) - 1}, "
                         f"got {segments}")
    tol = _validate.tolerance(tol)
    maxiter = _validate.maxiter(maxiter, maximum=MAXITER_LIMIT)
    starts = np.linspace(0, len(nodes) - 1, segments + 1).round().astype(int)
    grids = [nodes[i:j + 1] for i, j in pairwise(starts)]

    def sweeps(Y):
        """Every segment from its start, with ``n`` complex-step copies of its state."""
        copies = Y.reshape(segments, n)[:, None, :] + 1j * _STEP * np.eye(n)
        with np.errstate(over="ignore", invalid="ignore"):      # Newton reads non-finite
            return [_rk4(fun, c, g) for c, g in zip(copies, grids)]

    def bc_value(ya, yb):
        out = np.asarray(bc(ya, yb))
        if out.shape != (n,):
            raise ValueError(f"bc returned shape {out.shape}, expected ({n},)")
        return out

    def system(Y):
        """The defects and their Jacobian, from one sweep of the complex-step copies (Newton's
        ``jac=True``: the sweep is shared, and no cache is needed)."""
        ends = sweeps(Y)
        last = [e[-1, 0].real for e in ends]                            # phi_j(Y_j)
        Phi = [e[-1].imag.T / _STEP for e in ends]                      # d phi_j / d Y_j
        Z = Y.reshape(segments, n)
        defects = [bc_value(Z[0], last[-1]).real] + [last[j] - Z[j + 1]
                                                     for j in range(segments - 1)]
        step = 1j * _STEP * np.eye(n)
        Ba = np.column_stack([bc_value(Z[0] + e, last[-1]).imag for e in step]) / _STEP
        Bb = np.column_stack([bc_value(Z[0], last[-1] + e).imag for e in step]) / _STEP
        J = np.zeros((segments * n, segments * n))
        J[:n, :n] += Ba
        J[:n, -n:] += Bb @ Phi[-1]
        for j in range(segments - 1):
            J[(j + 1) * n:(j + 2) * n, j * n:(j + 1) * n] = Phi[j]
            J[(j + 1) * n:(j + 2) * n, (j + 1) * n:(j + 2) * n] -= np.eye(n)
        return np.concatenate(defects), J

    result = newton.solve(system, guess[starts[:-1]].ravel(), jac=True, tol=tol,
                          maxiter=maxiter, criterion="residual", damping=True)
    ends = sweeps(result.x)
    y = np.concatenate([ends[0][:, 0].real] + [e[1:, 0].real for e in ends[1:]])
    return BVPSolution(x=y, status=result.status, message=result.message,
                       iterations=result.iterations, nfev=result.nfev, njev=result.njev,
                       s=np.array(nodes), segment_starts=starts[:-1], newton=result)
