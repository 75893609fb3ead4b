"""One equilibrium followed along a path, by continuation: the study's trajectories, maps and the
workspace.

:func:`~mechnum.mechanisms.rfr2.inverse_path` follows it while the end effector moves (the
study's 11.3.1.1), :func:`~mechnum.mechanisms.rfr2.forward_path` while the motors turn
(11.3.1.2), by RK4 shooting as the study does or in closed form;
:func:`~mechnum.mechanisms.rfr2.forward_map` follows it over a grid of motor angles, and
:func:`~mechnum.mechanisms.rfr2.workspace` along rays of the end effector to where its branch
ends. Each returns a :class:`mechnum.mechanisms.Path`, with the determinants of
:func:`~mechnum.mechanisms.rfr2.jacobians` at every point; a point reached on another branch
(across a fold) is a "branch-jump", never a converged point (the shared continuation of the
mechanisms built of rods).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms._assembly import Path, State
from mechnum.mechanisms.rfr2._model import LAYOUT, Mechanism, broadcast, full_system, rods
from mechnum.mechanisms.rfr2._shooting import shooting_guess, shooting_system
from mechnum.mechanisms.thesis import STUDY_NODES
from mechnum.rods import SHOOTING_TOL, chart_from_clamps, in_chart

METHODS = ("shooting", "elliptic")


def _in_chart(u):
    """The continuation's unknowns ``(chart, ...)`` whose rods lie in the chart."""
    return in_chart(u[:, :4])


def _closed_form(mech, modes, trace, params, along):
    """The :class:`~mechnum.mechanisms.Path` of a closed-form trace: ``x = (chart, theta)``
    along the pose, or ``(chart, pose)`` along the inputs."""
    return assembly.closed_form_path(full_system(mech, modes), LAYOUT, modes, trace, params,
                                     along)


def _shooting(mech, nodes, trace, params, unknown):
    """The :class:`~mechnum.mechanisms.Path` of a shooting trace ``x`` (..., 8) along
    ``params`` (the motor angles when ``unknown == "pose"``, the end effector when
    ``"inputs"``)."""
    split = shooting_system(mech, nodes, unknown)[1]
    direct, inverse = shooting_system(mech, nodes, "pose")[0], shooting_system(
        mech, nodes, "inputs")[0]

    def evaluate(x, known):
        m0, n, theta, P = split(x, known)
        X_fk = np.concatenate((m0[:, :1], n[:, 0], m0[:, 1:], n[:, 1], P), axis=-1)
        X_ik = np.concatenate((m0[:, :1], n[:, 0], theta[:, :1], m0[:, 1:], n[:, 1],
                               theta[:, 1:]), axis=-1)
        A, B = direct(X_fk, theta)[1], inverse(X_ik, P)[1]
        chart, modes = chart_from_clamps(mech.EI, mech.L, theta, m0, n)
        return (theta, P, chart, modes) + assembly.jacobians(A, B, B[:, :, [3, 7]],
                                                             slice(6, 8))

    return assembly.path_of(trace, params, LAYOUT, evaluate)


def _path_inputs(mech, modes, method, nodes):
    assembly.check_type(mech, Mechanism)
    _validate.choice(method, METHODS, "method")
    return (assembly.check_modes(modes, 2),
            _validate.maxiter(nodes, "nodes", minimum=2, maximum=assembly.MAX_NODES))


def inverse_path(mech: Mechanism, poses: ArrayLike, theta: ArrayLike, chart: ArrayLike,
                 modes: ArrayLike = (1, 1), *, method: str = "shooting",
                 nodes: int = STUDY_NODES) -> Path:
    """Follow an equilibrium while the end effector moves through ``poses``: the inverse
    problem by continuation (the study's 11.3.1.1).

    Parameters
    ----------
    mech, modes
        As in :func:`~mechnum.mechanisms.rfr2.forward`.
    poses : array_like, shape (n, 2)
        End-effector positions (m), close to each other (``n`` may be 0; at most
        ``MAX_POINTS = 1_000_000``).
    theta, chart : array_like, shapes (2,) and (4,)
        An equilibrium at (or near) ``poses[0]``: its motor angles and rods.
    method : {"shooting", "elliptic"}, optional
        RK4 shooting in the study's unknowns (99), as the study does: a rod may change mode
        on the way (when its clamp moment passes through zero); or the closed form, faster,
        whose modes are fixed, so that the path stops where a rod's clamp moment vanishes.
    nodes : int, optional
        RK4 nodes per rod (shooting), at most ``MAX_NODES = 100_000``.

    Returns
    -------
    mechnum.mechanisms.Path
        ``status`` per point: "converged" on the branch of the start only. Closed form: the
        modes are fixed; shooting finds them (a rod whose clamp moment passes through zero
        changes mode), and the determinants are the study's 8 x 8 of (98), in (102) and (99).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> line = eq.pose[2] + np.outer(np.linspace(0.0, 0.1, 11), [-1.0, 0.0])  # 0.1 m left
    >>> fast = inverse_path(TABLE7, line, TABLE7_THETA, eq.x[2], method="elliptic")
    >>> bool(fast.converged.all()), np.round(np.degrees(fast.inputs[-1]), 3).tolist()
    (True, [29.576, 22.131])
    >>> study = inverse_path(TABLE7, line, TABLE7_THETA, eq.x[2])    # 41 RK4 nodes
    >>> bool(np.abs(study.inputs - fast.inputs).max() < 1e-4)
    True
    """
    modes, nodes = _path_inputs(mech, modes, method, nodes)
    theta, z0 = broadcast(_validate.array(theta, "theta", shape=(2,)),
                          _validate.array(chart, "chart", shape=(4,)))
    poses = assembly.points(poses, "poses", 2)
    if method == "shooting":
        fun = shooting_system(mech, nodes, "inputs")[0]
        X0 = shooting_guess(mech, theta, z0, modes, unknown="inputs")
        trace = assembly.follow(fun, X0, poses, tol=SHOOTING_TOL)
        return _shooting(mech, nodes, trace, poses, "inputs")
    fun = assembly.continuation_system(full_system(mech, modes), LAYOUT, "pose")
    trace = assembly.follow(fun, np.concatenate((z0, theta)), poses, tol=assembly.PATH_TOL,
                            maxiter=assembly.PATH_MAXITER, domain=_in_chart, chart=4)
    return _closed_form(mech, modes, trace, poses, "pose")


def forward_path(mech: Mechanism, thetas: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1),
                 *, method: str = "shooting", nodes: int = STUDY_NODES,
                 resume: bool = True) -> Path:
    """Follow an equilibrium while the motors turn through ``thetas``: the direct problem by
    continuation (the study's 11.3.1.2).

    Parameters
    ----------
    thetas : array_like, shape (n, 2) or, with ``method="elliptic"``, (n, batch, 2)
        Motor angles (rad), close to each other; with a batch axis, ``batch`` paths at once
        (``n`` may be 0; at most ``MAX_POINTS = 1_000_000`` points in all).
    chart : array_like, shape (4,) or (batch, 4)
        Equilibria at ``thetas[0]``.
    method, nodes
        As in :func:`inverse_path`.
    resume : bool, optional
        After a failure, go on from the last converged point (the study's way), or abandon
        the path.

    Returns
    -------
    mechnum.mechanisms.Path

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> thetas = TABLE7_THETA + np.linspace(0.0, 0.1, 11)[:, None] * [1.0, 0.0]
    >>> path = forward_path(TABLE7, thetas, eq.x[2], method="elliptic")
    >>> bool(path.converged.all()), np.round(path.pose[-1], 4).tolist()
    (True, [-0.0763, -0.2585])
    """
    modes, nodes = _path_inputs(mech, modes, method, nodes)
    resume = _validate.flag(resume, "resume")
    thetas = assembly.points(thetas, "thetas", 2, batch=method == "elliptic")
    z0 = _validate.array(chart, "chart", shape=(4,) if thetas.ndim == 2 else (None, 4))
    if thetas.ndim == 3 and len(z0) != thetas.shape[1]:
        raise ValueError(f"chart must have one row per path, {thetas.shape[1]}, got {len(z0)}")
    if not len(thetas):                     # an empty path: nothing to follow
        empty = assembly.follow(None, np.zeros(z0.shape[:-1] + (
            8 if method == "shooting" else 6,)), thetas, tol=assembly.PATH_TOL)
        return (_shooting(mech, nodes, empty, thetas, "pose") if method == "shooting"
                else _closed_form(mech, modes, empty, thetas, "inputs"))
    theta0, z0 = broadcast(thetas[0], z0)
    if method == "shooting":
        fun = shooting_system(mech, nodes, "pose")[0]
        X0 = shooting_guess(mech, theta0, z0, modes)
        trace = assembly.follow(fun, X0, thetas, tol=SHOOTING_TOL, resume=resume)
        return _shooting(mech, nodes, trace, thetas, "pose")
    fun = assembly.continuation_system(full_system(mech, modes), LAYOUT, "inputs")
    P0 = rods(mech, theta0, z0, modes, jacobian=False)[0][..., 0, :]
    trace = assembly.follow(fun, np.concatenate((z0, P0), axis=-1), thetas,
                            tol=assembly.PATH_TOL, maxiter=assembly.PATH_MAXITER,
                            domain=_in_chart, resume=resume, chart=4)
    return _closed_form(mech, modes, trace, thetas, "inputs")


def grid_trace(mech: Mechanism, modes: np.ndarray, *, tol: float = assembly.PATH_TOL,
               criterion: str = "residual") -> Callable:
    """``trace(params, u0)``: the closed form followed along the motor angles, every path
    abandoned at its first failure (:func:`mechnum.mechanisms._assembly.follow`, ``resume=False``,
    with ``tol`` and ``criterion``), ``u = (chart, P)``: the continuation of the maps
    (:func:`forward_map`, the atlas)."""
    fun = assembly.continuation_system(full_system(mech, modes), LAYOUT, "inputs")

    def trace(params, u0):
        return assembly.follow(fun, u0, params, tol=tol, maxiter=assembly.PATH_MAXITER,
                               resume=False, chart=4, domain=_in_chart, criterion=criterion)

    return trace


def forward_map(mech: Mechanism, theta1: ArrayLike, theta2: ArrayLike, theta: ArrayLike,
                chart: ArrayLike, modes: ArrayLike = (1, 1)) -> Path:
    """An equilibrium followed over the grid ``theta1 x theta2`` of motor angles (rad).

    The equilibrium ``(theta, chart)`` is first moved to the nearest grid point, then followed
    along ``theta2`` both ways, then every ``theta2`` at once along ``theta1`` both ways
    (``follow_grid``), in closed form. Where the branch folds back
    (``det_fk`` through zero: the motors can no longer hold it) continuation stops, and the
    map has NaN: other equilibria take over there.

    Parameters
    ----------
    theta1, theta2 : array_like, shape (nx,) and (ny,)
        The grid (rad), ``nx ny`` at most ``MAX_POINTS = 1_000_000``.
    theta, chart : array_like, shapes (2,) and (4,)
        An equilibrium.

    Returns
    -------
    mechnum.mechanisms.Path
        Arrays of shape ``(nx, ny, ...)``; ``params`` the grid.

    Raises
    ------
    ConvergenceError
        If the equilibrium cannot be moved to the grid.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> grid = forward_map(TABLE7, np.radians([36, 38, 40, 42]), np.radians([58, 60, 62]),
    ...                    TABLE7_THETA, eq.x[2])
    >>> grid.pose.shape, bool(grid.converged.all())
    ((4, 3, 2), True)
    """
    modes = _path_inputs(mech, modes, "elliptic", STUDY_NODES)[0]
    theta1, theta2 = assembly.grid_axes(theta1, theta2, ("theta1", "theta2"))
    grid = np.stack(np.meshgrid(theta1, theta2, indexing="ij"), axis=-1)
    theta, z0 = broadcast(_validate.array(theta, "theta", shape=(2,)),
                          _validate.array(chart, "chart", shape=(4,)))
    trace = grid_trace(mech, modes)
    if not grid.size:
        return _closed_form(mech, modes, assembly.follow_grid(trace, grid, (0, 0), np.zeros(6)),
                            grid, "inputs")
    start = np.unravel_index(np.argmin(np.abs(grid - theta).max(axis=-1)), grid.shape[:2])
    move = forward_path(mech, np.linspace(theta, grid[start], 5), z0, modes, method="elliptic")
    if not move.converged[-1]:
        raise ConvergenceError(f"the equilibrium could not be moved from theta = "
                               f"{theta.tolist()} to the grid point {grid[start].tolist()}",
                               move)
    return _closed_form(mech, modes, assembly.follow_grid(trace, grid, start, move.x[-1]),
                        grid, "inputs")


def workspace(mech: Mechanism, state: State, *, directions: int = 24, step: float = 0.04,
              reach: float = 1.0, levels: int = 6, nodes: int = STUDY_NODES) -> Path:
    """Where the inverse problem's branch of an equilibrium ends on rays from its end effector:
    the edge of the workspace it reaches (by shooting, modes free).

    All rays are followed at once (``workspace_edge``), in steps of
    ``step`` up to ``reach`` from the equilibrium's end effector, then again from each ray's
    last solution in steps four times shorter, ``levels`` times, so that the edge is located
    to ``step / 4**levels``. Where the branch folds (``det_ik`` through zero) the last points
    approach the fold and their ``det_ik`` falls towards zero; a ray may also end at
    ``reach``.

    Parameters
    ----------
    mech : Mechanism
    state : mechnum.mechanisms.State
        An equilibrium: its motor angles, rods and modes (``forward(...).state(i)``).
    directions, step, reach, levels, nodes : optional
        The rays, the first step and the largest distance (m) and the refinements of
        ``workspace_edge`` (bounded there); the RK4 nodes per rod
        (at most ``MAX_NODES = 100_000``).

    Returns
    -------
    mechnum.mechanisms.Path
        One point per ray, the last equilibrium on it: ``pose`` is the edge.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> edge = workspace(TABLE7, eq.state(2), directions=4, step=0.05, reach=0.1, levels=1)
    >>> edge.pose.shape, bool(edge.converged.all())
    ((4, 2), True)
    """
    state = assembly.check_state(state, 2)
    modes, nodes = _path_inputs(mech, state.modes, "shooting", nodes)
    theta, z0 = broadcast(state.inputs, state.chart)
    fun = shooting_system(mech, nodes, "inputs")[0]
    P = rods(mech, theta, z0, modes, jacobian=False)[0][0]

    def trace(known, u):
        return assembly.follow(fun, u, known, tol=SHOOTING_TOL, resume=False)

    edge, u, status, nfev, njev = assembly.workspace_edge(
        trace, P, shooting_guess(mech, theta, z0, modes, unknown="inputs"),
        directions=directions, step=step, reach=reach, levels=levels)
    last = assembly.trace_of(u, status, np.zeros(len(u), dtype=int), nfev, njev)
    return _shooting(mech, nodes, last, edge, "inputs")


def singular_points(mech: Mechanism, grid: Path, *, which: str = "det_ik") -> np.ndarray:
    """Points where ``det_ik`` (or ``det_fk``) of a map of :func:`forward_map` changes sign:
    on the singularity curves, in motor angles (rad), to the grid's resolution
    (``zero_crossings``).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> g = np.radians(np.linspace(0.0, 180.0, 19))
    >>> grid = forward_map(TABLE7, g, g, TABLE7_THETA, eq.x[0])
    >>> singular_points(TABLE7, grid).shape, singular_points(TABLE7, grid, which="det_fk").shape
    ((22, 2), (0, 2))
    """
    assembly.check_type(mech, Mechanism)
    return assembly.singular_points(grid, which)
