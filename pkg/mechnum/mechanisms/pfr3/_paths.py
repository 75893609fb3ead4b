"""Trajectories, Jacobians and singularities of the 3PFR (the study's 11.4.1, Ilustraciones 35
and 36).

With ``G = 0`` the nine equilibrium equations of :func:`~mechnum.mechanisms.pfr3.full_system`
in the rods' charts, the sliders ``lambda`` and the pose ``(x, y, phi)``:

* the **direct** problem solves ``G`` for ``(chart, pose)`` at given ``lambda``; where
  ``det dG/d(chart, pose) = 0`` (``det_fk``) the locked sliders no longer hold the platform;
* the **inverse** problem solves ``G`` for ``(chart, lambda)`` at a given pose; where
  ``det dG/d(chart, lambda) = 0`` (``det_ik``) the platform cannot move in some direction whatever
  the sliders do: the edge of the workspace.

These are the study's ``J_FK`` and ``J_IK`` (the Jacobians of its (110) in (112) and (111)),
whose zeros do not depend on how the rods are parametrised. Continuation follows one
equilibrium along a path (:func:`mechnum.mechanisms._assembly.follow`), by the closed form or by
shooting; a point reached on another branch (across a fold) is a "branch-jump", never a
converged point.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms._assembly import Path, State
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.mechanisms.pfr3 import _shooting as shooting
from mechnum.mechanisms.thesis import STUDY_NODES
from mechnum.rods import SHOOTING_TOL, ClampedRods, chart_from_clamps, in_chart

METHODS = ("elliptic", "shooting")


def _in_chart(u):
    """The continuation's unknowns ``(chart, ...)`` whose rods lie in the chart."""
    return in_chart(u[:, :6])


def jacobians(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
              modes: ArrayLike = (1, 1, 1)) -> assembly.Jacobians:
    """``det_fk``, ``det_ik`` and ``d pose / d lambda`` of closed-form equilibria.

    Parameters
    ----------
    lambdas : array_like, shape (..., 3)
    chart : array_like, shape (..., 6)
        Equilibria in the chart.

    Returns
    -------
    mechnum.mechanisms.Jacobians
        ``det_fk``, ``det_ik`` (...), and ``dpose_dinputs`` (..., 3, 3): how the pose moves
        with the sliders, the study's code's ``FK_Jacobian`` (its code's ``IK_Jacobian`` is
        the inverse matrix).

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> fk, ik, dpose = jacobians(model.TABLE8, model.TABLE8_LAMBDAS, z)
    >>> bool(fk > 0), dpose.shape
    (True, (3, 3))
    """
    assembly.check_type(mech, model.Mechanism)
    tip = model.rods(mech, lambdas, chart, modes, jacobian=False)[0]
    lambdas, z = np.asarray(lambdas, dtype=float), np.asarray(chart, dtype=float)
    D = model.full_system(mech, modes)(z, lambdas, model.pose_at(mech, tip))[1]
    return assembly.determinants(D, model.LAYOUT)


def _closed_form(mech, modes, trace, params, along):
    """The :class:`~mechnum.mechanisms.Path` of a closed-form trace: ``x = (chart,
    lambdas)`` along the pose, or ``(chart, pose)`` along the sliders."""
    return assembly.closed_form_path(model.full_system(mech, modes), model.LAYOUT, modes, trace,
                                     params, along)


def _shooting_path(mech, trace, params, unknown, nodes, rigid_end):
    """The :class:`~mechnum.mechanisms.Path` of a shooting trace ``x`` (..., 12) along
    ``params`` (..., 3): the pose or the sliders, the study's two Jacobians, and the rods'
    charts from their clamp states (NaN with a rigid end: its rods are no clamped-pinned
    elasticas). With a rigid end the modes are 0 (unknown)."""
    split = shooting.shooting_system(mech, nodes, unknown, rigid_end)[1]
    direct = shooting.shooting_system(mech, nodes, "pose", rigid_end)[0]
    inverse = shooting.shooting_system(mech, nodes, "inputs", rigid_end)[0]

    def evaluate(x, known):
        m0, n, lam, P = split(x, known)
        per_rod = np.concatenate((m0[..., None], n), axis=-1)
        X_fk = np.concatenate((per_rod.reshape(-1, 9), P), axis=-1)
        X_ik = np.concatenate((per_rod, lam[..., None]), axis=-1).reshape(-1, 12)
        A, B = direct(X_fk, lam)[1], inverse(X_ik, P)[1]
        z, modes = chart_from_clamps(mech.EI, mech.L, mech.clamp_angles, m0, n)
        if rigid_end:
            z, modes = np.full_like(z, np.nan), np.zeros_like(modes)
        return (lam, P, z, modes) + assembly.jacobians(A, B, B[:, :, [3, 7, 11]], slice(9, 12))

    return assembly.path_of(trace, params, model.LAYOUT, evaluate)


def _path_inputs(mech, modes, method, nodes, rigid_end):
    assembly.check_type(mech, model.Mechanism)
    _validate.choice(method, METHODS, "method")
    return (assembly.check_modes(modes, 3),
            _validate.maxiter(nodes, "nodes", minimum=2, maximum=assembly.MAX_NODES),
            shooting.check_rigid_end(mech, rigid_end))


def _inverse_trace(mech, modes, method, nodes, rigid_end, resume):
    """``trace(poses, u0)`` of the inverse problem by ``method``, and ``u0(lambdas, chart)``."""
    if method == "shooting":
        fun = shooting.shooting_system(mech, nodes, "inputs", rigid_end)[0]
        return ((lambda p, u: assembly.follow(fun, u, p, tol=SHOOTING_TOL, resume=resume)),
                lambda lam, z: shooting.shooting_guess(mech, lam, z, modes, unknown="inputs"))
    fun = assembly.continuation_system(model.full_system(mech, modes), model.LAYOUT, "pose")
    return ((lambda p, u: assembly.follow(
        fun, u, p, tol=assembly.PATH_TOL, maxiter=assembly.PATH_MAXITER, resume=resume,
        domain=_in_chart, chart=6)),
        lambda lam, z: np.concatenate((z, lam)))


def inverse_path(mech: model.Mechanism, poses: ArrayLike, lambdas: ArrayLike, chart: ArrayLike,
                 modes: ArrayLike = (1, 1, 1), *, method: str = "elliptic",
                 nodes: int = STUDY_NODES, rigid_end: float = 0.0) -> Path:
    """Follow an equilibrium while the platform moves through ``poses``: the inverse problem by
    continuation (the study's 11.4.1.1).

    Parameters
    ----------
    mech, modes
        As in :func:`~mechnum.mechanisms.pfr3.forward`.
    poses : array_like, shape (n, 3)
        Platform poses ``(x, y, phi)``, close to each other (``n`` may be 0; at most
        ``MAX_POINTS = 1_000_000``).
    lambdas, chart : array_like, shapes (3,) and (6,)
        An equilibrium at (or near) ``poses[0]``: its sliders and rods.
    method : {"elliptic", "shooting"}, optional
        The closed form (fixed modes), or RK4 shooting in the study's unknowns (111) as the
        study does (modes free: a rod whose clamp moment passes through zero changes mode).
    nodes, rigid_end : optional
        RK4 nodes per rod (at most ``MAX_NODES = 100_000``) and the rigid
        segment at each pin, ``0 <= rigid_end < L`` (shooting only).

    Returns
    -------
    mechnum.mechanisms.Path
        Closed form: the modes are fixed; shooting finds them, and the determinants are the
        study's 12 x 12 Jacobians of (109) in (112) and (111), scaled; with a rigid end the
        rods have no chart (NaN).

    Raises
    ------
    UnreachablePoseError
        If a pin of some pose is farther than ``L`` from its guide.

    Examples
    --------
    >>> eq_z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> pose0 = shooting.shooting_guess(model.TABLE8, model.TABLE8_LAMBDAS, eq_z)[9:]
    >>> line = pose0 + np.linspace(0.0, 0.05, 11)[:, None] * [1.0, 0.0, 0.0]
    >>> fast = inverse_path(model.TABLE8, line, model.TABLE8_LAMBDAS, eq_z)
    >>> study = inverse_path(model.TABLE8, line, model.TABLE8_LAMBDAS, eq_z, method="shooting")
    >>> bool(fast.converged.all()), bool(np.abs(study.inputs - fast.inputs).max() < 1e-5)
    (True, True)
    """
    modes, nodes, rigid_end = _path_inputs(mech, modes, method, nodes, rigid_end)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    z0 = model.check_chart(_validate.array(chart, "chart", shape=(6,)))
    poses = assembly.points(poses, "poses", 3)
    model.check_reach(mech, poses)
    trace, start = _inverse_trace(mech, modes, method, nodes, rigid_end, True)
    result = trace(poses, start(lambdas, z0))
    if method == "shooting":
        return _shooting_path(mech, result, poses, "inputs", nodes, rigid_end)
    return _closed_form(mech, modes, result, poses, "pose")


def forward_path(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
                 modes: ArrayLike = (1, 1, 1), *, method: str = "elliptic",
                 nodes: int = STUDY_NODES, rigid_end: float = 0.0, resume: bool = True) -> Path:
    """Follow an equilibrium while the sliders move through ``lambdas``: the direct problem by
    continuation (the study's 11.4.1.2).

    Parameters
    ----------
    lambdas : array_like, shape (n, 3) or, closed form only, (n, batch, 3)
        Slider inputs (m), close to each other; with a batch axis, ``batch`` paths at once
        (``n`` may be 0; at most ``MAX_POINTS = 1_000_000`` points in all).
    chart : array_like, shape (6,) or (batch, 6)
        Equilibria at ``lambdas[0]``.
    method, nodes, rigid_end
        As in :func:`inverse_path`.
    resume : bool, optional
        After a failure, go on from the last converged point, or abandon the path.

    Returns
    -------
    mechnum.mechanisms.Path

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> sliders = np.linspace(0.0, 0.1, 11)[:, None] * [1.0, 0.0, 0.0]
    >>> path = forward_path(model.TABLE8, sliders, z)
    >>> bool(path.converged.all()), np.round(path.pose[-1], 3).tolist()
    (True, [0.077, 0.035, 1.48])
    """
    modes, nodes, rigid_end = _path_inputs(mech, modes, method, nodes, rigid_end)
    resume = _validate.flag(resume, "resume")
    lambdas = assembly.points(lambdas, "lambdas", 3, batch=method == "elliptic")
    z0 = model.check_chart(_validate.array(chart, "chart", shape=(6,) if lambdas.ndim == 2 else
                                           (lambdas.shape[1], 6)))
    width = 12 if method == "shooting" else 9
    if not len(lambdas):                    # an empty path: nothing to follow
        empty = assembly.follow(None, np.zeros(z0.shape[:-1] + (width,)), lambdas,
                                tol=assembly.PATH_TOL)
        return (_shooting_path(mech, empty, lambdas, "pose", nodes, rigid_end)
                if method == "shooting" else _closed_form(mech, modes, empty, lambdas, "inputs"))
    if method == "shooting":
        fun = shooting.shooting_system(mech, nodes, "pose", rigid_end)[0]
        X0 = shooting.shooting_guess(mech, lambdas[0], z0, modes)
        result = assembly.follow(fun, X0, lambdas, tol=SHOOTING_TOL, resume=resume)
        return _shooting_path(mech, result, lambdas, "pose", nodes, rigid_end)
    tip = model.rods(mech, lambdas[0], z0, modes, jacobian=False)[0]
    u0 = np.concatenate((z0, model.pose_at(mech, tip)), axis=-1)
    result = forward_trace(mech, modes, resume)(lambdas, u0)
    return _closed_form(mech, modes, result, lambdas, "inputs")


def forward_trace(mech: model.Mechanism, modes: np.ndarray, resume: bool = False, *,
                  tol: float = assembly.PATH_TOL, criterion: str = "residual") -> Callable:
    """``trace(lambdas, u0)``: the closed form followed along the sliders
    (:func:`mechnum.mechanisms._assembly.follow`, with ``resume``, ``tol`` and ``criterion``),
    ``u = (chart, pose)``: the continuation of :func:`forward_path` and of the atlas (which
    abandons a path at its first failure)."""
    fun = assembly.continuation_system(model.full_system(mech, modes), model.LAYOUT, "inputs")

    def trace(lambdas, u0):
        return assembly.follow(fun, u0, lambdas, tol=tol, maxiter=assembly.PATH_MAXITER,
                               resume=resume, chart=6, criterion=criterion, domain=_in_chart)

    return trace


def inverse_map(mech: model.Mechanism, x: ArrayLike, y: ArrayLike, phi: float, pose: ArrayLike,
                lambdas: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1, 1), *,
                method: str = "elliptic", nodes: int = STUDY_NODES) -> Path:
    """An equilibrium followed over the grid ``x`` by ``y`` of platform centres at the angle
    ``phi``: the inverse problem over the plane (the study's Ilustraciones 35 and 36).

    The equilibrium (at ``pose``, with sliders ``lambdas`` and rods ``chart``) is first moved to
    the grid point nearest to it at the angle ``phi``, then followed along ``y`` both ways, then
    every ``y`` at once along ``x`` both ways (``follow_grid``).
    Continuation stops (the map has NaN) where the branch folds back (``det_ik`` through zero:
    the edge of its workspace), and, with the closed form, where it leaves the chart: a rod
    whose clamp moment vanishes (its mode changes) or whose force turns through its clamped
    tangent (``psi`` through 0). Shooting (the study's unknowns (111)) has no chart, and stops
    at folds only.

    Parameters
    ----------
    x, y : array_like, shapes (nx,) and (ny,)
        The grid of centres (m), ``nx ny`` at most ``MAX_POINTS = 1_000_000``.
    method : {"elliptic", "shooting"}, optional
        The closed form, or RK4 shooting with ``nodes`` nodes per rod.

    Returns
    -------
    mechnum.mechanisms.Path
        Arrays of shape ``(nx, ny, ...)``; ``params`` the grid's poses.

    Raises
    ------
    ConvergenceError
        If the equilibrium cannot be moved to the grid.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> grid = inverse_map(model.TABLE8, [0.0, 0.02, 0.04], [0.0, 0.02], 1.2,
    ...                    [0.0165, 0.0206, 1.2027], model.TABLE8_LAMBDAS, z)
    >>> grid.inputs.shape, bool(grid.converged.all())
    ((3, 2, 3), True)
    """
    modes, nodes, _ = _path_inputs(mech, modes, method, nodes, 0.0)
    x, y = assembly.grid_axes(x, y)
    pose = _validate.array(pose, "pose", shape=(3,))
    phi = _validate.scalar(phi, "phi")
    grid = np.stack(np.meshgrid(x, y, indexing="ij") + (np.full((len(x), len(y)), phi),), -1)
    trace, start = _inverse_trace(mech, modes, method, nodes, 0.0, False)
    if not grid.size:
        empty = assembly.follow_grid(trace, grid, (0, 0), np.zeros(12 if method == "shooting"
                                                                   else 9))
        return (_shooting_path(mech, empty, grid, "inputs", nodes, 0.0) if method ==
                "shooting" else _closed_form(mech, modes, empty, grid, "pose"))
    first = (int(np.argmin(np.abs(x - pose[0]))), int(np.argmin(np.abs(y - pose[1]))))
    move = inverse_path(mech, np.linspace(pose, grid[first], 9), lambdas, chart, modes)
    if not move.converged[-1]:
        raise ConvergenceError(f"the equilibrium could not be moved from the pose "
                               f"{pose.tolist()} to the grid at phi = {phi:g}", move)
    result = assembly.follow_grid(trace, grid, first, start(move.inputs[-1], move.chart[-1]))
    if method == "shooting":
        return _shooting_path(mech, result, grid, "inputs", nodes, 0.0)
    return _closed_form(mech, modes, result, grid, "pose")


def workspace(mech: model.Mechanism, state: State, *, directions: int = 24, step: float = 0.04,
              reach: float = 1.0, levels: int = 6, nodes: int = STUDY_NODES) -> Path:
    """Where the inverse problem's branch ends on rays from the platform's centre, at its fixed
    angle: the edge of the workspace that the equilibrium reaches (by shooting, modes free).

    All rays are followed at once (``workspace_edge``), from the
    equilibrium ``state``, in steps of ``step`` up to ``reach`` from the centre; from each
    ray's last solution on, the ray is followed again in steps four times shorter, ``levels``
    times, so the edge is located to ``step / 4**levels`` (a step fails near a fold when the
    solution changes too fast for it). Where the branch folds (``det_ik`` through zero) the
    last points approach the fold, and their ``det_ik`` falls towards zero; a ray may also
    end at ``reach``.

    Parameters
    ----------
    mech : Mechanism
    state : mechnum.mechanisms.State
        An equilibrium: its sliders, rods and modes (``forward(...).state(i)``).
    directions, step, reach, levels : optional
        As in ``workspace_edge`` (rays, first step and largest
        distance in m, refinements), each bounded there.
    nodes : int, optional
        RK4 nodes per rod, at most ``MAX_NODES = 100_000``.

    Returns
    -------
    mechnum.mechanisms.Path
        Shape ``(directions,)``: the last equilibrium of each ray (its ``pose`` is the edge).

    Examples
    --------
    >>> from mechnum.mechanisms.pfr3 import forward
    >>> eq = forward(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> edge = workspace(model.TABLE8, eq.state(0), directions=4, step=0.05, reach=0.1,
    ...                  levels=1)
    >>> edge.pose.shape, bool(edge.converged.all())
    ((4, 3), True)
    """
    state = assembly.check_state(state, 3)
    modes, nodes, _ = _path_inputs(mech, state.modes, "shooting", nodes, 0.0)
    lambdas = _validate.array(state.inputs, "state.inputs", shape=(3,))
    z0 = model.check_chart(state.chart)
    tip = model.rods_at(ClampedRods(mech.EI, mech.L, modes), mech, lambdas, z0,
                        jacobian=False)[0]
    trace, start = _inverse_trace(mech, modes, "shooting", nodes, 0.0, False)
    edge, u, status, nfev, njev = assembly.workspace_edge(
        trace, model.pose_at(mech, tip), start(lambdas, z0), directions=directions, step=step,
        reach=reach, levels=levels)
    last = assembly.trace_of(u, status, np.zeros(len(u), dtype=int), nfev, njev)
    return _shooting_path(mech, last, edge, "inputs", nodes, 0.0)


def singular_points(mech: model.Mechanism, grid: Path, *, which: str = "det_ik") -> np.ndarray:
    """Points where ``det_ik`` (or ``det_fk``) of a map of :func:`inverse_map` changes sign: on
    the singularity curves, in the platform's centre ``(x, y)`` (m), to the grid's resolution
    (``zero_crossings``).

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> x = np.linspace(-0.6, 0.6, 13)
    >>> grid = inverse_map(model.TABLE8, x, x, 1.2027, [0.0165, 0.0206, 1.2027],
    ...                    model.TABLE8_LAMBDAS, z)
    >>> singular_points(model.TABLE8, grid).shape[1]
    2
    """
    assembly.check_type(mech, model.Mechanism)
    return assembly.singular_points(grid, which)
