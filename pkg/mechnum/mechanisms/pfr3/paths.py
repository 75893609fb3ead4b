"""Trajectories, Jacobians and singularities of the 3PFR (the study's 11.4.1, Ilustraciones 35
and 36).

With ``G = 0`` the nine equilibrium equations of :func:`~mechnum.mechanisms.pfr3.model.full_system`
in the rods' charts ``z``, the sliders ``lambda`` and the pose ``(x, y, phi)``:

* the **direct** problem solves ``G`` for ``(z, pose)`` at given ``lambda``; where
  ``det dG/d(z, pose) = 0`` (``det_fk``) the locked sliders no longer hold the platform;
* the **inverse** problem solves ``G`` for ``(z, lambda)`` at a given pose; where
  ``det dG/d(z, lambda) = 0`` (``det_ik``) the platform cannot move in some direction whatever
  the sliders do: the edge of the workspace.

These are the study's ``J_FK`` and ``J_IK`` (the Jacobians of its (110) in (112) and (111)),
whose zeros do not depend on how the rods are parametrised. Continuation follows one
equilibrium along a path (:func:`mechnum.newton.solve_path`), by the closed form or by shooting.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate, newton
from mechnum.errors import ConvergenceError
from mechnum.mechanisms.pfr3 import model, shooting
from mechnum.mechanisms.rfr2.shooting import STUDY_NODES, _memoised

_Z, _LAMBDA, _POSE = list(range(6)), [6, 7, 8], [9, 10, 11]
_FK, _IK = _Z + _POSE, _Z + _LAMBDA
# Newton's tolerance and most iterations per step of closed-form continuation: from a good
# prediction a few iterations reach round-off; more means the branch is lost.
PATH_TOL = 1e-12
PATH_MAXITER = 10


@dataclass(frozen=True)
class Path:
    """One equilibrium followed along a path; NaN where continuation failed.

    Attributes
    ----------
    lambdas, pose : ndarray, shape (..., 3)
        Slider inputs (m) and platform pose ``(x, y, phi)`` at every point.
    chart : ndarray, shape (..., 6)
        The rods ``(psi_i, t_i)``.
    converged : ndarray of bool
    det_fk, det_ik : ndarray
        Determinants of the direct and inverse problems (dimensionless, closed form; with
        shooting, the study's 12 x 12 Jacobians of (109) in (112) and (111), scaled).
    """

    lambdas: np.ndarray
    pose: np.ndarray
    chart: np.ndarray
    converged: np.ndarray
    det_fk: np.ndarray
    det_ik: np.ndarray


def jacobians(mech, lambdas, z, modes=(1, 1, 1)):
    """``det_fk``, ``det_ik`` and ``d pose / d lambda`` of closed-form equilibria.

    Parameters
    ----------
    lambdas : array_like, shape (..., 3)
    z : array_like, shape (..., 6)
        Equilibria in the chart.

    Returns
    -------
    det_fk, det_ik : ndarray, shape (...)
    dpose_dlambda : ndarray, shape (..., 3, 3)
        How the pose moves with the sliders: the study's code's ``FK_Jacobian``; its code's
        ``IK_Jacobian`` is the inverse matrix.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> fk, ik, dpose = jacobians(model.TABLE8, model.TABLE8_LAMBDAS, z)
    >>> bool(fk > 0), dpose.shape
    (True, (3, 3))
    """
    lambdas, z = _validate.array(lambdas, "lambdas"), _validate.array(z, "z")
    tip = model.rods(mech, lambdas, z, modes, jacobian=False)[0]
    D = model.full_system(mech, modes)(z, lambdas, model.pose_of_tips(mech, tip))[1]
    A, B = D[..., _FK], D[..., _IK]
    dpose = -np.linalg.solve(A, D[..., _LAMBDA])[..., 6:, :]
    return np.linalg.det(A), np.linalg.det(B), dpose


def _finish(mech, modes, z, lambdas, pose, converged):
    ok = converged[..., None]
    z, lambdas, pose = (np.where(ok, a, np.nan) for a in (z, lambdas, pose))
    nan = np.where(converged, 1.0, np.nan)
    if converged.any():
        fk, ik, _ = jacobians(mech, np.where(ok, lambdas, 0.0), np.where(
            ok, z, [1.0, 0.5] * 3), modes)
    else:
        fk = ik = np.zeros(converged.shape)
    return Path(lambdas, pose, z, converged, fk * nan, ik * nan)


def _closed_form(mech, modes, unknown):
    """``fun(u, p)``, ``jac(u, p)`` of the closed form for continuation: ``u = (z, lambda)`` at
    a given pose ``p`` (inverse), or ``u = (z, pose)`` at given sliders ``p`` (direct)."""
    full = model.full_system(mech, modes)
    cols = _IK if unknown == "lambdas" else _FK

    @_memoised
    def system(u, p):
        return full(u[:, :6], u[:, 6:], p) if unknown == "lambdas" else full(u[:, :6], p,
                                                                            u[:, 6:])

    return (lambda u, p: system(u, p)[0]), (lambda u, p: system(u, p)[1][..., cols])


def _shooting_path(mech, x, converged, known, unknown, nodes, rigid_end):
    """A :class:`Path` from shooting solutions ``x`` (..., 12) along ``known`` (..., 3): the
    pose or the sliders, the study's two Jacobians, and the rods' charts from their clamp
    states (NaN with a rigid end: its rods are no clamped-pinned elasticas)."""
    shape, ok = converged.shape, converged.ravel()
    x, known = x.reshape(-1, 12), np.broadcast_to(known, shape + (3,)).reshape(-1, 3)
    _, fk_jac, fk_split = shooting._system(mech, nodes, "pose", rigid_end)
    _, ik_jac, ik_split = shooting._system(mech, nodes, "lambdas", rigid_end)
    X = np.where(ok[:, None], x, 0.0)
    m0, n, lambdas, pose = (fk_split if unknown == "pose" else ik_split)(X, known)
    per_rod = np.concatenate((m0[..., None], n), axis=-1)
    X_fk = np.concatenate((per_rod.reshape(-1, 9), pose), axis=-1)
    X_ik = np.concatenate((per_rod, lambdas[..., None]), axis=-1).reshape(-1, 12)
    nan = np.where(ok, 1.0, np.nan)
    det_fk = np.linalg.det(fk_jac(X_fk, lambdas)) * nan
    det_ik = np.linalg.det(ik_jac(X_ik, pose)) * nan
    chart = np.full((len(ok), 6), np.nan)
    if ok.any() and not rigid_end:
        chart[ok] = shooting.chart_from_clamps(mech, m0[ok], n[ok])[0]
    return Path((lambdas * nan[:, None]).reshape(shape + (3,)),
                (pose * nan[:, None]).reshape(shape + (3,)), chart.reshape(shape + (6,)),
                converged, det_fk.reshape(shape), det_ik.reshape(shape))


def inverse_path(mech, poses, lambdas, z, modes=(1, 1, 1), *, method="elliptic",
                 nodes=STUDY_NODES, rigid_end=0.0):
    """Follow an equilibrium while the platform moves through ``poses``: the inverse problem by
    continuation (the study's 11.4.1.1).

    Parameters
    ----------
    mech, modes
        As in :func:`~mechnum.mechanisms.pfr3.equilibria.forward_elliptic`.
    poses : array_like, shape (n, 3)
        Platform poses ``(x, y, phi)``, close to each other.
    lambdas, z : array_like, shapes (3,) and (6,)
        An equilibrium at (or near) ``poses[0]``: its sliders and rods.
    method : {"elliptic", "shooting"}, optional
        The closed form (fixed modes), or RK4 shooting in the study's unknowns (111) as the
        study does (modes free: a rod whose clamp moment passes through zero changes mode).
    nodes, rigid_end : optional
        RK4 nodes per rod and the rigid segment at each pin (shooting only).

    Returns
    -------
    Path

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
    >>> bool(fast.converged.all()), bool(np.abs(study.lambdas - fast.lambdas).max() < 1e-5)
    (True, True)
    """
    _validate.choice(method, ("elliptic", "shooting"), "method")
    modes, lambdas = model._modes(modes), model._lambdas(lambdas)
    z0 = _validate.array(z, "z", shape=(6,))
    poses = _validate.array(poses, "poses", shape=(None, 3))
    model.check_reach(mech, poses)
    if method == "shooting":
        fun, jac, _ = shooting._system(mech, _validate.maxiter(nodes, "nodes", minimum=2),
                                       "lambdas", rigid_end)
        X0 = shooting.shooting_guess(mech, lambdas, z0, modes, unknown="lambdas")
        res = newton.solve_path(fun, poses, X0, jac, tol=shooting.SHOOTING_TOL)
        return _shooting_path(mech, res.x, res.converged, poses, "lambdas", nodes, rigid_end)
    fun, jac = _closed_form(mech, modes, "lambdas")
    res = newton.solve_path(fun, poses, np.concatenate((z0, lambdas)), jac, tol=PATH_TOL,
                            maxiter=PATH_MAXITER, domain=lambda u: model.in_chart(u[:, :6]))
    converged = _on_branch(z0, res.x[:, :6], res.converged)
    return _finish(mech, modes, res.x[:, :6], res.x[:, 6:], poses, converged)


def forward_path(mech, lambdas, z, modes=(1, 1, 1), *, method="elliptic", nodes=STUDY_NODES,
                 rigid_end=0.0, resume=True):
    """Follow an equilibrium while the sliders move through ``lambdas``: the direct problem by
    continuation (the study's 11.4.1.2).

    Parameters
    ----------
    lambdas : array_like, shape (n, 3) or, closed form only, (n, batch, 3)
        Slider inputs (m), close to each other; with a batch axis, ``batch`` paths at once.
    z : array_like, shape (6,) or (batch, 6)
        Equilibria at ``lambdas[0]``.
    method, nodes, rigid_end
        As in :func:`inverse_path`.
    resume : bool, optional
        After a failure, go on from the last converged point, or abandon the path.

    Returns
    -------
    Path

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> sliders = np.linspace(0.0, 0.1, 11)[:, None] * [1.0, 0.0, 0.0]
    >>> path = forward_path(model.TABLE8, sliders, z)
    >>> bool(path.converged.all()), np.round(path.pose[-1], 3).tolist()
    (True, [0.077, 0.035, 1.48])
    """
    _validate.choice(method, ("elliptic", "shooting"), "method")
    modes = model._modes(modes)
    z0 = _validate.array(z, "z")
    lambdas = _validate.array(lambdas, "lambdas")
    if method == "shooting":
        lambdas = _validate.array(lambdas, "lambdas", shape=(None, 3))
        fun, jac, _ = shooting._system(mech, _validate.maxiter(nodes, "nodes", minimum=2),
                                       "pose", rigid_end)
        X0 = shooting.shooting_guess(mech, lambdas[0], _validate.array(z, "z", shape=(6,)),
                                     modes)
        res = newton.solve_path(fun, lambdas, X0, jac, tol=shooting.SHOOTING_TOL, resume=resume)
        return _shooting_path(mech, res.x, res.converged, lambdas, "pose", nodes, rigid_end)
    fun, jac = _closed_form(mech, modes, "pose")
    tip = model.rods(mech, lambdas[0], z0, modes, jacobian=False)[0]
    u0 = np.concatenate((z0, model.pose_of_tips(mech, tip)), axis=-1)
    res = newton.solve_path(fun, lambdas, u0, jac, tol=PATH_TOL, maxiter=PATH_MAXITER,
                            domain=lambda u: model.in_chart(u[:, :6]), resume=resume)
    converged = _on_branch(z0, res.x[..., :6], res.converged)
    return _finish(mech, modes, res.x[..., :6], lambdas, res.x[..., 6:], converged)


def _on_branch(z0, z, converged):
    """``converged``, but False from the first point where a rod's ``t`` changed sign (the
    chart is discontinuous at ``t = 0``: Newton has jumped to another branch)."""
    same = np.all(np.sign(z[..., 1::2]) == np.sign(np.asarray(z0)[..., 1::2]), axis=-1)
    return converged & (np.cumsum(converged & ~same, axis=0) == 0)


def _outwards(n, start):
    """The indices from ``start`` to the end and back to 0, as two paths of one length (the
    shorter padded with its last index: a step of length zero, solved at once), and their
    lengths."""
    up, down = np.arange(start, n), np.arange(start, -1, -1)
    steps = max(len(up), len(down))
    padded = [np.pad(i, (0, steps - len(i)), mode="edge") for i in (up, down)]
    return np.stack(padded, axis=1), (len(up), len(down))


def _both_ways(fun, jac, params, u0, keep, controls):
    """Continuation from ``u0`` (batch, m) along ``params`` (steps, 2, batch, 3), both ways at
    once; the solutions (steps, 2, batch, m), NaN where continuation stopped."""
    steps, _, batch, _ = params.shape
    u0 = np.concatenate((u0, u0))
    res = newton.solve_path(fun, params.reshape(steps, 2 * batch, 3), u0, jac, resume=False,
                            **controls)
    ok = keep(u0, res.x, res.converged)
    return np.where(ok[..., None], res.x, np.nan).reshape(steps, 2, batch, -1)


def inverse_map(mech, x, y, phi, pose, lambdas, z, modes=(1, 1, 1), *, method="elliptic",
                nodes=STUDY_NODES):
    """An equilibrium followed over the grid ``x`` by ``y`` of platform centres at the angle
    ``phi``: the inverse problem over the plane (the study's Ilustraciones 35 and 36).

    The equilibrium (at ``pose``, with sliders ``lambdas`` and rods ``z``) is first moved to
    the grid point nearest to it at the angle ``phi``, then followed along ``y`` both ways, then
    every ``y`` at once along ``x`` both ways. Continuation stops (the map has NaN) where the
    branch folds back (``det_ik`` through zero: the edge of its workspace), and, with the closed
    form, where it leaves the chart: a rod whose clamp moment vanishes (its mode changes) or
    whose force turns through its clamped tangent (``psi`` through 0). Shooting (the study's
    unknowns (111)) has no chart, and stops at folds only.

    Parameters
    ----------
    method : {"elliptic", "shooting"}, optional
        The closed form, or RK4 shooting with ``nodes`` nodes per rod.

    Returns
    -------
    Path
        Arrays of shape ``(len(x), len(y), ...)``.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> grid = inverse_map(model.TABLE8, [0.0, 0.02, 0.04], [0.0, 0.02], 1.2,
    ...                    [0.0165, 0.0206, 1.2027], model.TABLE8_LAMBDAS, z)
    >>> grid.lambdas.shape, bool(grid.converged.all())
    ((3, 2, 3), True)
    """
    _validate.choice(method, ("elliptic", "shooting"), "method")
    modes = model._modes(modes)
    x, y = _validate.array(x, "x", ndim=1), _validate.array(y, "y", ndim=1)
    pose = _validate.array(pose, "pose", shape=(3,))
    phi = _validate.scalar(phi, "phi")
    i0, j0 = np.argmin(np.abs(x - pose[0])), np.argmin(np.abs(y - pose[1]))
    start = inverse_path(mech, np.linspace(pose, [x[i0], y[j0], phi], 9), lambdas, z, modes)
    if not start.converged[-1]:
        raise ConvergenceError(f"the equilibrium could not be moved from the pose "
                               f"{pose.tolist()} to the grid at phi = {phi:g}", start)
    grid = np.stack(np.meshgrid(x, y, indexing="ij") + (np.full((len(x), len(y)), phi),), -1)
    if method == "elliptic":
        fun, jac = _closed_form(mech, modes, "lambdas")
        u0 = np.concatenate((start.chart[-1], start.lambdas[-1]))
        controls = dict(tol=PATH_TOL, maxiter=PATH_MAXITER,
                        domain=lambda u: model.in_chart(u[:, :6]))

        def keep(u0, u, ok):
            return _on_branch(u0[..., :6], u[..., :6], ok)
    else:
        nodes = _validate.maxiter(nodes, "nodes", minimum=2)
        fun, jac, _ = shooting._system(mech, nodes, "lambdas", 0.0)
        u0 = shooting.shooting_guess(mech, start.lambdas[-1], start.chart[-1], modes,
                                     unknown="lambdas")
        controls = dict(tol=shooting.SHOOTING_TOL)

        def keep(u0, u, ok):
            return ok
    column = np.full((len(y), len(u0)), np.nan)
    js, lengths = _outwards(len(y), j0)
    both = _both_ways(fun, jac, grid[i0, js][:, :, None], u0[None], keep, controls)
    for way, n in enumerate(lengths):
        column[js[:n, way]] = both[:n, way, 0]
    alive = np.flatnonzero(~np.isnan(column[:, 0]))
    u = np.full(grid.shape[:2] + (len(u0),), np.nan)
    i_s, lengths = _outwards(len(x), i0)
    both = _both_ways(fun, jac, grid[i_s][:, :, alive], column[alive], keep, controls)
    for way, n in enumerate(lengths):
        u[i_s[:n, way, None], alive] = both[:n, way]
    converged = ~np.isnan(u[..., 0])
    if method == "shooting":
        return _shooting_path(mech, u, converged, grid, "lambdas", nodes, 0.0)
    return _finish(mech, modes, u[..., :6], u[..., 6:], grid, converged)


def workspace_edge(mech, pose, lambdas, z, modes=(1, 1, 1), *, directions=24, step=0.04,
                   reach=1.0, levels=6, nodes=STUDY_NODES):
    """Where the inverse problem's branch ends on rays from the platform's centre, at its fixed
    angle: the edge of the workspace that the equilibrium reaches (by shooting, modes free).

    All rays are followed at once (:func:`mechnum.newton.solve_path`), from the equilibrium
    at ``pose`` (sliders ``lambdas``, rods ``z``), in steps of ``step`` up to ``reach`` from
    the centre; from each ray's last solution on, the ray is followed again in steps four
    times shorter, ``levels`` times, so the edge is located to ``step / 4**levels`` (a step
    fails near a fold when the solution changes too fast for it). Where the branch folds
    (``det_ik`` through zero) the last points approach the fold, and their ``det_ik`` falls
    towards zero; a ray may also end at ``reach``.

    Parameters
    ----------
    mech, modes
        As in :func:`~mechnum.mechanisms.pfr3.equilibria.forward_elliptic`.
    pose : array_like, shape (3,)
        The centre and the platform's (fixed) angle.
    lambdas, z : array_like, shapes (3,) and (6,)
        An equilibrium at ``pose``.
    directions, step, reach, levels, nodes : optional
        Rays at equal angles, the first step (m), the largest distance (m), refinements and
        RK4 nodes per rod.

    Returns
    -------
    Path
        Shape ``(directions,)``: the last equilibrium of each ray (its ``pose`` is the edge).

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> pose = shooting.shooting_guess(model.TABLE8, model.TABLE8_LAMBDAS, z)[9:]
    >>> edge = workspace_edge(model.TABLE8, pose, model.TABLE8_LAMBDAS, z, directions=4,
    ...                       step=0.05, reach=0.1, levels=1)
    >>> edge.pose.shape, bool(edge.converged.all())
    ((4, 3), True)
    """
    pose = _validate.array(pose, "pose", shape=(3,))
    directions = _validate.maxiter(directions, "directions", minimum=1)
    levels = _validate.maxiter(levels, "levels", minimum=0)
    step, reach = _validate.positive(step, "step"), _validate.positive(reach, "reach")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    angle = 2.0 * np.pi * np.arange(directions) / directions
    ray = np.column_stack((np.cos(angle), np.sin(angle)))
    fun, jac, _ = shooting._system(mech, nodes, "lambdas", 0.0)
    u = np.tile(shooting.shooting_guess(mech, lambdas, z, modes, unknown="lambdas"),
                (directions, 1))
    r, h = np.zeros(directions), step
    for level in range(levels + 1):
        # each level starts at its rays' last solutions (the centre first), and goes on for
        # three steps of the level before (a step of the secant prediction needs two)
        steps = np.arange(int(np.ceil(reach / h)) + 1) if level == 0 else np.arange(13)
        radii = np.minimum(r + h * steps[:, None], reach)                     # (steps, rays)
        known = np.concatenate((pose[:2] + radii[..., None] * ray,
                                np.full(radii.shape + (1,), pose[2])), axis=-1)
        res = newton.solve_path(fun, known, u, jac, tol=shooting.SHOOTING_TOL, resume=False)
        done = res.converged.sum(axis=0)                 # steps before the first failure
        moved = np.flatnonzero(done > 0)
        u[moved] = res.x[done[moved] - 1, moved]
        r[moved] = radii[done[moved] - 1, moved]
        if level == 0:
            converged = done > 0                         # the centre's equilibrium solved
        h /= 4.0
    edge = np.column_stack((pose[:2] + r[:, None] * ray, np.full(directions, pose[2])))
    return _shooting_path(mech, u, converged, edge, "lambdas", nodes, 0.0)


def singular_points(x, y, values):
    """Where a map over the grid ``x`` by ``y`` changes sign: points on its zero curve.

    Each grid edge whose ends have opposite signs gives one point, by linear interpolation
    (edges touching NaN give none): the singularity curves ``det = 0`` of a map of
    :func:`inverse_map`, to the grid's resolution.

    Returns
    -------
    ndarray, shape (k, 2)

    Examples
    --------
    >>> g = np.linspace(-1.0, 1.0, 21)
    >>> X, Y = np.meshgrid(g, g, indexing="ij")
    >>> pts = singular_points(g, g, X ** 2 + Y ** 2 - 0.25)
    >>> bool(np.allclose(np.hypot(*pts.T), 0.5, atol=0.02)), len(pts)
    (True, 32)
    """
    x, y = _validate.array(x, "x", ndim=1), _validate.array(y, "y", ndim=1)
    v = _validate.array(values, "values", shape=(len(x), len(y)), finite=False)
    X, Y = np.meshgrid(x, y, indexing="ij")
    points = []
    for a, b, Pa, Pb in ((v[:-1], v[1:], (X[:-1], Y[:-1]), (X[1:], Y[1:])),
                         (v[:, :-1], v[:, 1:], (X[:, :-1], Y[:, :-1]), (X[:, 1:], Y[:, 1:]))):
        cut = (a * b < 0) & np.isfinite(a) & np.isfinite(b)
        w = a[cut] / (a[cut] - b[cut])
        points.append(np.column_stack([p[cut] + w * (q[cut] - p[cut]) for p, q in zip(Pa, Pb)]))
    return np.concatenate(points)
