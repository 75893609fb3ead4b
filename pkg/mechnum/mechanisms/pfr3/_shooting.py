"""The 3PFR by RK4 shooting: the study's (109) with its unknowns (111) and (112) (11.4.1).

Each rod is integrated from its clamp by RK4 (:func:`mechnum.rods.tip_jacobian`,
complex-step derivatives in the same sweep). The twelve equations are the study's (109): at
each pin a moment-free tip at ``B_i``, and the platform's balance of forces and of moments
about the origin, ``sum_i p_i x n_i - P x F - M = 0`` (its (110) prints rod 1 three times in
``f12``). The unknowns are the clamp moments and forces with the sliders,
``X = (m0_i, n_i, lambda_i)`` (its (111), the inverse problem at a given pose), or with the pose,
``X = (m0_i, n_i; x, y, phi)`` (its (112), the direct problem at given sliders).

The study's shooting programs (Annex II 4.1 to 4.3) end each rod with a rigid segment of length
``d = 0.1`` m along the tip's tangent, pinned at its far end: ``rigid_end`` reproduces it
(``pin = p(L) + d t(L)``, ``m_pin = m(L) - d t(L) x n``); the study's text and its elliptic
program have none (``rigid_end = 0``, the default).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.mechanisms.thesis import STUDY_NODES
from mechnum.rods import SHOOTING_TOL, ShotRods

UNKNOWNS = ("pose", "inputs")
"""The two sets of shooting unknowns: the study's (112) with the pose, (111) with the sliders
(the inputs)."""
STUDY_RIGID_END = 0.10
"""The rigid segment at the pinned end of the study's shooting programs (``d``, m)."""


def _pins(shot, mech, m0, force, lambdas, rigid_end):
    """States ``(x, y, theta, m)`` at the pins (batch, 3, 4) and their derivatives with respect
    to ``(m0, n_x, n_y)`` (batch, 3, 4, 3)."""
    tip, D = shot(m0, force, mech.clamp_angles, model.clamps_at(mech, lambdas))
    if rigid_end:
        c, s = np.cos(tip[..., 2]), np.sin(tip[..., 2])
        dn = np.zeros(D.shape[:-2] + (2, 3))
        dn[..., 0, 1] = dn[..., 1, 2] = 1.0
        t_cross_n = c * force[..., 1] - s * force[..., 0]
        d_theta = D[..., 2, :]
        tip = tip.copy()
        tip[..., 0] += rigid_end * c
        tip[..., 1] += rigid_end * s
        tip[..., 3] -= rigid_end * t_cross_n
        D = D.copy()
        D[..., 0, :] -= rigid_end * s[..., None] * d_theta
        D[..., 1, :] += rigid_end * c[..., None] * d_theta
        D[..., 3, :] -= rigid_end * ((-s * force[..., 1] - c * force[..., 0])[..., None]
                                     * d_theta + c[..., None] * dn[..., 1, :]
                                     - s[..., None] * dn[..., 0, :])
    return tip, D


def check_rigid_end(mech: model.Mechanism, rigid_end: float) -> float:
    """The rigid segment at each pin, checked: ``0 <= rigid_end < L`` (m).

    Examples
    --------
    >>> check_rigid_end(model.TABLE8, -0.1)
    Traceback (most recent call last):
    ...
    ValueError: rigid_end must lie in [0, L) = [0, 1) m, got -0.1
    """
    value = _validate.scalar(rigid_end, "rigid_end")
    if not 0.0 <= value < mech.L:
        raise ValueError(f"rigid_end must lie in [0, L) = [0, {mech.L:g}) m, got {value!r}")
    return value


def shooting_system(mech: model.Mechanism, nodes: int, unknown: str,
                    rigid_end: float = 0.0) -> tuple[Callable, Callable]:
    """Residual (109) and its Jacobian for a batch of unknowns ``X`` (batch, 12).

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    nodes : int
        RK4 nodes per rod (at most ``MAX_NODES = 100_000``).
    unknown : {"pose", "inputs"}
        The study's (112), ``known`` the sliders (batch, 3), or its (111), ``known`` the pose.
    rigid_end : float, optional
        The rigid segment at each pin (m), ``0 <= rigid_end < L``.

    Returns
    -------
    fun, split : callable
        ``fun(X, known) -> (f, J)``: the residual (batch, 12) (scaled) and its Jacobian (batch,
        12, 12), from one RK4 sweep, as :func:`mechnum.newton.solve` takes them with
        ``jac=True``; ``split(X, known) -> (m0, n, lambdas, pose)``. Neither checks its input.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> fun, _ = shooting_system(model.TABLE8, 801, "pose")
    >>> X = shooting_guess(model.TABLE8, model.TABLE8_LAMBDAS, z)[None]
    >>> bool(np.abs(fun(X, model.TABLE8_LAMBDAS[None])[0]).max() < 2e-3)   # 4 printed decimals
    True
    """
    assembly.check_type(mech, model.Mechanism)
    shot = ShotRods(mech.EI, mech.L, _validate.maxiter(nodes, "nodes", minimum=2,
                                                        maximum=assembly.MAX_NODES))
    _validate.choice(unknown, UNKNOWNS, "unknown")
    rigid_end = check_rigid_end(mech, rigid_end)
    moment, length, force = mech.EI / mech.L, mech.L, mech.EI / mech.L ** 2
    scale = np.array([moment, length, length] * 3 + [force, force, moment])
    guide = np.stack((np.cos(mech.guide_angles), np.sin(mech.guide_angles)), -1)

    def split(X, known):
        """``(m0, n, lambdas, pose)`` of the unknowns, the known ones filled in."""
        if unknown == "inputs":
            per_rod = X.reshape(-1, 3, 4)
            return per_rod[..., 0], per_rod[..., 1:3], per_rod[..., 3], known
        per_rod = X[:, :9].reshape(-1, 3, 3)
        return per_rod[..., 0], per_rod[..., 1:], known, X[:, 9:]

    def fun(X, known):
        m0, n, lambdas, pose = split(X, known)
        pin, D = _pins(shot, mech, m0, n, lambdas, rigid_end)
        B = model.pins_at(mech, pose)
        rows = np.concatenate((pin[..., 3:], pin[..., :2] - B), axis=-1).reshape(-1, 9)
        P, F = pose[:, :2], mech.force
        torque = (model.cross(pin[..., :2], n).sum(axis=1) - model.cross(P, F) - mech.moment)
        f = np.concatenate((rows, n.sum(axis=1) - F, torque[:, None]), axis=-1) / scale
        width = 4 if unknown == "inputs" else 3
        J = np.zeros((len(X), 12, 12))
        for i in range(3):
            rows, cols = slice(3 * i, 3 * i + 3), slice(width * i, width * i + 3)
            J[:, rows, cols] = D[:, i][:, [3, 0, 1], :]
            J[:, 9:11, width * i + 1:width * i + 3] = np.eye(2)
            dp = D[:, i, :2, :]                                   # d pin / d (m0, n)
            J[:, 11, cols] = dp[:, 0] * n[:, i, 1, None] - dp[:, 1] * n[:, i, 0, None]
            J[:, 11, width * i + 1] -= pin[:, i, 1]
            J[:, 11, width * i + 2] += pin[:, i, 0]
            if unknown == "inputs":
                J[:, 3 * i + 1:3 * i + 3, 4 * i + 3] = guide[i]
                J[:, 11, 4 * i + 3] = guide[i, 0] * n[:, i, 1] - guide[i, 1] * n[:, i, 0]
            else:
                r = B[:, i] - pose[:, :2]
                J[:, 3 * i + 1:3 * i + 3, 9:11] = -np.eye(2)
                J[:, 3 * i + 1, 11], J[:, 3 * i + 2, 11] = r[:, 1], -r[:, 0]
        if unknown == "pose":
            J[:, 11, 9], J[:, 11, 10] = -mech.force[1], mech.force[0]
        return f, J / scale[:, None]

    return fun, split


def _shooting(mech, unknown, known, seed, nodes, tol, maxiter, rigid_end):
    known = _validate.array(known, "lambdas" if unknown == "pose" else "pose", ndim=(1, 2))
    if known.shape[-1] != 3:
        raise ValueError(f"{'lambdas' if unknown == 'pose' else 'pose'} must have shape (3,) or "
                         f"(batch, 3), got {known.shape}")
    fun, split = shooting_system(mech, nodes, unknown, rigid_end)
    res, known = assembly.shoot(fun, seed, known, width=12, tol=tol, maxiter=maxiter)
    m0, n, lambdas, pose = split(res.x, known)
    return assembly.shooting_result(res, lambdas, pose, m0, n, fun(res.x, known)[1])


def forward_shooting(mech: model.Mechanism, lambdas: ArrayLike, seed: ArrayLike, *,
                     nodes: int = STUDY_NODES, tol: float = SHOOTING_TOL, maxiter: int = 50,
                     rigid_end: float = 0.0) -> assembly.ShotEquilibria:
    """The direct problem by RK4 shooting: the study's (109) in its unknowns (112).

    ``X = (m0_1, n1_x, n1_y, m0_2, n2_x, n2_y, m0_3, n3_x, n3_y, x, y, phi)``: damped Newton
    (complex-step Jacobian; the study differentiates by forward differences with a step of
    ``1e-11``) drives the pins' moments to zero, the tips to the platform and its loads to
    balance. The seed picks the equilibrium.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    lambdas : array_like, shape (3,) or (batch, 3)
        Slider inputs (m).
    seed : array_like, shape (12,) or (batch, 12)
        Initial ``X`` (:func:`shooting_guess` gives it from a closed-form equilibrium).
    nodes : int, optional
        RK4 nodes per rod (the study's 41; the error falls as ``nodes**-4``), at most
        ``MAX_NODES = 100_000``.
    tol, maxiter : optional
        Newton's tolerance on the scaled residual, most iterations (at most 10,000).
    rigid_end : float, optional
        Length of a rigid segment at each pinned end (m), ``0 <= rigid_end < L``: the study's
        programs have 0.1.

    Returns
    -------
    mechnum.mechanisms.ShotEquilibria
        ``inputs`` the sliders (m), ``pose`` the platform ``(x, y, phi)``, both (batch, 3);
        ``jacobian`` (batch, 12, 12) is the scaled Jacobian of (109) in the unknowns: the
        study's ``J_FK`` (in (112); ``J_IK`` in (111) for :func:`inverse_shooting`).

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> X = shooting_guess(model.TABLE8, model.TABLE8_LAMBDAS, z)
    >>> sol = forward_shooting(model.TABLE8, model.TABLE8_LAMBDAS, X, nodes=801)
    >>> np.round(sol.pose, 4).tolist(), sol.status.tolist()
    ([[0.0165, 0.0206, 1.2027]], ['converged'])
    """
    return _shooting(mech, "pose", lambdas, seed, nodes, tol, maxiter, rigid_end)


def inverse_shooting(mech: model.Mechanism, pose: ArrayLike, seed: ArrayLike, *,
                     nodes: int = STUDY_NODES, tol: float = SHOOTING_TOL, maxiter: int = 50,
                     rigid_end: float = 0.0) -> assembly.ShotEquilibria:
    """The inverse problem by RK4 shooting: the study's (109) in its unknowns (111).

    ``X = (m0_1, n1_x, n1_y, lambda_1, ..., m0_3, n3_x, n3_y, lambda_3)`` for a given pose
    ``(x, y, phi)``; otherwise as :func:`forward_shooting`. A pose with a pin farther than
    ``L`` from its guide raises :class:`~mechnum.errors.UnreachablePoseError`.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> X = shooting_guess(model.TABLE8, model.TABLE8_LAMBDAS, z, unknown="inputs")
    >>> sol = inverse_shooting(model.TABLE8, [0.0165, 0.0206, 1.2027], X, nodes=801)
    >>> np.round(sol.inputs, 3).tolist()          # the printed pose has 4 decimals
    [[0.0, -0.0, -0.0]]
    """
    model.check_reach(mech, pose)
    return _shooting(mech, "inputs", pose, seed, nodes, tol, maxiter, rigid_end)


def shooting_guess(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
                   modes: ArrayLike = (1, 1, 1), *, unknown: str = "pose") -> np.ndarray:
    """The study's shooting unknowns of closed-form equilibria: (112), or (111) with
    ``unknown="inputs"``.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> np.round(shooting_guess(model.TABLE8, model.TABLE8_LAMBDAS, z)[9:], 4).tolist()
    [0.0165, 0.0206, 1.2028]
    """
    _validate.choice(unknown, UNKNOWNS, "unknown")
    assembly.check_type(mech, model.Mechanism)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    tip, force, moment, _ = model.rods(mech, lambdas, chart, modes, jacobian=False)
    per_rod = np.concatenate((moment[..., None], force), axis=-1)       # (..., 3, 3)
    if unknown == "inputs":
        per_rod = np.concatenate((per_rod, np.broadcast_to(lambdas, moment.shape)[..., None]),
                                 axis=-1)
        return per_rod.reshape(per_rod.shape[:-2] + (12,))
    return np.concatenate((per_rod.reshape(per_rod.shape[:-2] + (9,)),
                           model.pose_at(mech, tip)), axis=-1)
