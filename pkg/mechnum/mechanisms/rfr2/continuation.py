"""One equilibrium followed along a path, by continuation: the study's trajectories.

:func:`~mechnum.mechanisms.rfr2.inverse_path` follows it while the end effector moves (the
study's 11.3.1.1), :func:`~mechnum.mechanisms.rfr2.forward_path` while the motors turn
(11.3.1.2), by RK4 shooting as the study does or in closed form;
:func:`~mechnum.mechanisms.rfr2.forward_map` follows it over a grid of motor angles. Each
returns a :class:`~mechnum.mechanisms.rfr2.Path`, with the determinants of
:func:`~mechnum.mechanisms.rfr2.jacobians` at every point.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate, newton, rods
from mechnum.mechanisms.rfr2.model import (TABLE7, TABLE7_THETA, _chart, _in_chart, _modes, _rods,
                                           _theta)
from mechnum.mechanisms.rfr2.shooting import (SHOOTING_TOL, STUDY_NODES, _memoised,
                                              _shooting_system, shooting_guess)
from mechnum.mechanisms.rfr2.singularities import _FK, _IK, Jacobians, _full, jacobians


@dataclass(frozen=True)
class Path:
    """One equilibrium followed along a path (:func:`inverse_path`, :func:`forward_path`,
    :func:`forward_map`); NaN where continuation failed.

    Attributes
    ----------
    theta, P : ndarray, shape (..., 2)
        Motor angles (rad) and end effector (m) at every point.
    chart : ndarray, shape (..., 4)
        The rods, ``(psi1, t1, psi2, t2)``.
    modes : ndarray, shape (..., 2)
        The rods' buckling modes (fixed in closed form; shooting finds them, and a rod whose
        clamp moment passes through zero changes mode).
    converged : ndarray of bool
        Where Newton converged.
    jacobians : Jacobians
        At every point: of the closed form (6 x 6, dimensionless), or with shooting the
        study's 8 x 8 of (98), with respect to (102) and to (99).
    """

    theta: np.ndarray
    P: np.ndarray
    chart: np.ndarray
    modes: np.ndarray
    converged: np.ndarray
    jacobians: Jacobians


def _full_system(mech, modes, unknown):
    """The closed form's residual ``G`` and its Jacobian, ``fun(u, p)`` and ``jac(u, p)``, for
    continuation: in the end effector ``p`` with ``u = (chart, theta)`` when
    ``unknown == "theta"``, in the motor angles ``p`` with ``u = (chart, P)`` when
    ``unknown == "P"``. Both come from one evaluation of the rods, remembered between the
    two calls."""
    if unknown == "theta":
        system, columns = _memoised(lambda u, p: _full(mech, modes, u[:, :4], u[:, 4:], p)), _IK
    else:
        system, columns = _memoised(lambda u, p: _full(mech, modes, u[:, :4], p, u[:, 4:])), _FK

    def fun(u, p):
        return system(u, p)[0]

    def jac(u, p):
        return system(u, p)[1][..., columns]

    return fun, jac


def _on_branch(z0, chart, converged):
    """``converged``, but False from the first point where a rod's ``t`` changed sign: the
    chart is discontinuous at ``t = 0`` (the rod's clamp moment or force vanishes there), so
    Newton has jumped to another branch."""
    same = np.all(np.sign(chart[..., 1::2]) == np.sign(np.asarray(z0)[..., 1::2]), axis=-1)
    return converged & (np.cumsum(converged & ~same, axis=0) == 0)


def _finish(mech, modes, chart, theta, P, converged):
    ok = converged[..., None]
    chart, theta, P = (np.where(ok, a, np.nan) for a in (chart, theta, P))
    J = jacobians(mech, np.where(ok, theta, TABLE7_THETA), np.where(
        ok, chart, [1.0, 0.5, 1.0, 0.5]), modes)
    nan = np.where(converged, 1.0, np.nan)
    return Path(theta, P, chart, np.broadcast_to(modes, P.shape).astype(int), converged,
                Jacobians(J.det_fk * nan, J.det_ik * nan, J.dP_dtheta * nan[..., None, None]))


def _shooting_path(mech, nodes, x, converged, known, unknown):
    """A :class:`Path` from shooting solutions ``x`` (steps, 8) along ``known``."""
    ok = converged
    fk, fk_jac, fk_split = _shooting_system(mech, nodes, "P")
    ik, ik_jac, ik_split = _shooting_system(mech, nodes, "theta")
    X = np.where(ok[:, None], x, shooting_guess(TABLE7, TABLE7_THETA, [1.0, 0.5, 1.0, 0.5],
                                                unknown=unknown))
    m0, n, theta, P = (fk_split if unknown == "P" else ik_split)(X, known)
    X_fk = np.concatenate((m0[:, :1], n[:, 0], m0[:, 1:], n[:, 1], P), axis=-1)
    X_ik = np.concatenate((m0[:, :1], n[:, 0], theta[:, :1], m0[:, 1:], n[:, 1], theta[:, 1:]),
                          axis=-1)
    A, B = fk_jac(X_fk, theta), ik_jac(X_ik, P)
    dP = -np.linalg.solve(A, B[:, :, [3, 7]])[:, 6:8]
    c, s = np.cos(theta)[..., None], np.sin(theta)[..., None]
    local = np.stack((c[..., 0] * n[..., 0] + s[..., 0] * n[..., 1],
                      -s[..., 0] * n[..., 0] + c[..., 0] * n[..., 1]), axis=-1)
    psi, k_rel, modes, _ = rods.elliptic_parameters(mech.EI, mech.L, m0, local, outside="nan")
    chart = _chart(psi, k_rel)
    nan = np.where(ok, 1.0, np.nan)
    return Path(theta * nan[:, None], P * nan[:, None], chart * nan[:, None],
                np.where(ok[:, None], modes, 0).astype(int), ok,
                Jacobians(np.linalg.det(A) * nan, np.linalg.det(B) * nan,
                          dP * nan[:, None, None]))


def inverse_path(mech, points, theta, chart, modes=(1, 1), *, method="shooting",
                 nodes=STUDY_NODES):
    """Follow an equilibrium while the end effector moves through ``points``: the inverse
    problem by continuation (the study's 11.3.1.1).

    Parameters
    ----------
    mech, modes
        As in :func:`forward_elliptic`.
    points : array_like, shape (n, 2)
        End-effector positions (m), close to each other.
    theta, chart : array_like, shapes (2,) and (4,)
        An equilibrium at (or near) ``points[0]``: its motor angles and rods.
    method : {"shooting", "elliptic"}, optional
        RK4 shooting in the study's unknowns (99), as the study does: a rod may change mode
        on the way (when its clamp moment passes through zero); or the closed form, faster,
        whose modes are fixed, so that the path stops where a rod's clamp moment vanishes.
    nodes : int, optional
        RK4 nodes per rod (shooting).

    Returns
    -------
    Path

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward_elliptic, straight_path
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> line = eq.P[2] + straight_path(0.1, np.pi, 10)
    >>> fast = inverse_path(TABLE7, line, TABLE7_THETA, eq.chart[2], method="elliptic")
    >>> bool(fast.converged.all()), np.round(np.degrees(fast.theta[-1]), 3).tolist()
    (True, [29.576, 22.131])
    >>> study = inverse_path(TABLE7, line, TABLE7_THETA, eq.chart[2])    # 41 RK4 nodes
    >>> bool(np.abs(study.theta - fast.theta).max() < 1e-4)
    True
    """
    _validate.choice(method, ("shooting", "elliptic"), "method")
    modes, z0 = _modes(modes), _validate.array(chart, "chart", shape=(4,))
    points = _validate.array(points, "points", shape=(None, 2))
    if method == "shooting":
        fun, jac, _ = _shooting_system(mech, _validate.maxiter(nodes, "nodes", minimum=2),
                                       "theta")
        X0 = shooting_guess(mech, theta, z0, modes, unknown="theta")
        res = newton.solve_path(fun, points, X0, jac, tol=SHOOTING_TOL)
        return _shooting_path(mech, nodes, res.x, res.converged, points, "theta")
    fun, jac = _full_system(mech, modes, "theta")
    u0 = np.concatenate((z0, _theta(theta)))
    res = newton.solve_path(fun, points, u0, jac, tol=1e-12,
                            domain=lambda u: _in_chart(u[:, :4]))
    return _finish(mech, modes, res.x[:, :4], res.x[:, 4:], points,
                   _on_branch(z0, res.x[:, :4], res.converged))


def forward_path(mech, thetas, chart, modes=(1, 1), *, method="shooting", nodes=STUDY_NODES,
                 resume=True):
    """Follow an equilibrium while the motors turn through ``thetas``: the direct problem by
    continuation (the study's 11.3.1.2).

    Parameters
    ----------
    thetas : array_like, shape (n, 2) or, with ``method="elliptic"``, (n, batch, 2)
        Motor angles (rad), close to each other; with a batch axis, ``batch`` paths at once.
    chart : array_like, shape (4,) or (batch, 4)
        Equilibria at ``thetas[0]``.
    method, nodes
        As in :func:`inverse_path`.
    resume : bool, optional
        After a failure, go on from the last converged point (the study's way), or abandon
        the path.

    Returns
    -------
    Path

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward_elliptic
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> thetas = TABLE7_THETA + np.linspace(0.0, 0.1, 11)[:, None] * [1.0, 0.0]
    >>> path = forward_path(TABLE7, thetas, eq.chart[2], method="elliptic")
    >>> bool(path.converged.all()), np.round(path.P[-1], 4).tolist()
    (True, [-0.0763, -0.2585])
    """
    _validate.choice(method, ("shooting", "elliptic"), "method")
    modes = _modes(modes)
    z0 = _validate.array(chart, "chart")
    thetas = _validate.array(thetas, "thetas")
    if method == "shooting":
        fun, jac, _ = _shooting_system(mech, _validate.maxiter(nodes, "nodes", minimum=2),
                                       "P")
        X0 = shooting_guess(mech, thetas[0], _validate.array(chart, "chart", shape=(4,)),
                            modes)
        res = newton.solve_path(fun, _validate.array(thetas, "thetas", shape=(None, 2)), X0,
                                jac, tol=SHOOTING_TOL, resume=resume)
        return _shooting_path(mech, nodes, res.x, res.converged, thetas, "P")
    fun, jac = _full_system(mech, modes, "P")
    P0 = _rods(mech, modes, z0, thetas[0])[0][..., 0, :]
    res = newton.solve_path(fun, thetas, np.concatenate((z0, P0), axis=-1), jac, tol=1e-12,
                            domain=lambda u: _in_chart(u[:, :4]), resume=resume)
    return _finish(mech, modes, res.x[..., :4], thetas, res.x[..., 4:],
                   _on_branch(z0, res.x[..., :4], res.converged))


def _outwards(n, start):
    """The indices ``start, start+1, ..., n-1`` and ``start, start-1, ..., 0``."""
    return np.arange(start, n), np.arange(start, -1, -1)


def forward_map(mech, theta1, theta2, theta, chart, modes=(1, 1)):
    """An equilibrium followed over the grid ``theta1 x theta2`` of motor angles (rad).

    The equilibrium ``(theta, chart)`` is first moved to the nearest grid point, then followed
    along ``theta2`` both ways, then every ``theta2`` at once along ``theta1`` both ways
    (:func:`mechnum.newton.solve_path`). Where the branch folds back (``det_fk`` through
    zero: the motors can no longer hold it) continuation stops, and the map has NaN: other
    equilibria take over there.

    Returns
    -------
    Path
        Arrays of shape ``(len(theta1), len(theta2), ...)``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward_elliptic
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> grid = forward_map(TABLE7, np.radians([36, 38, 40, 42]), np.radians([58, 60, 62]),
    ...                    TABLE7_THETA, eq.chart[2])
    >>> grid.P.shape, bool(grid.converged.all())
    ((4, 3, 2), True)
    """
    modes = _modes(modes)
    theta1 = _validate.array(theta1, "theta1", ndim=1)
    theta2 = _validate.array(theta2, "theta2", ndim=1)
    theta = _theta(theta)
    i0, j0 = np.argmin(np.abs(theta1 - theta[0])), np.argmin(np.abs(theta2 - theta[1]))
    move = np.linspace(theta, [theta1[i0], theta2[j0]], 5)
    start = forward_path(mech, move, chart, modes, method="elliptic")
    grid = np.stack(np.meshgrid(theta1, theta2, indexing="ij"), axis=-1)
    column = np.full((len(theta2), 4), np.nan)
    for js in _outwards(len(theta2), j0):
        column[js] = forward_path(mech, grid[i0, js], start.chart[-1], modes,
                                  method="elliptic", resume=False).chart
    alive = ~np.isnan(column[:, 0])
    charts = np.full(grid.shape[:2] + (4,), np.nan)
    for i_s in _outwards(len(theta1), i0):
        charts[i_s[:, None], alive] = forward_path(
            mech, grid[i_s][:, alive], column[alive], modes, method="elliptic",
            resume=False).chart
    converged = ~np.isnan(charts[..., 0])
    P = _rods(mech, modes, np.where(converged[..., None], charts, [1.0, 0.5, 1.0, 0.5]),
              grid)[0][..., 0, :]
    return _finish(mech, modes, charts, grid, P, converged)
