"""RK4 shooting, as the study solves its mechanism: its (98) in the unknowns (99) and (102).

:func:`~mechnum.mechanisms.rfr2.forward_shooting` (the direct problem, unknowns (102)) and
:func:`~mechnum.mechanisms.rfr2.inverse_shooting` (the inverse problem, unknowns (99)) drive the
tip moments to zero, both tips to ``P`` and ``n1 + n2`` to ``F`` by damped Newton with
complex-step Jacobians (:func:`mechnum.rods.tip_jacobian`);
:func:`~mechnum.mechanisms.rfr2.shooting_guess` gives their unknowns from a closed-form
equilibrium, and :func:`shooting_system` is the residual and Jacobian they solve.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.rfr2._model import Mechanism, rods
from mechnum.mechanisms.thesis import STUDY_NODES
from mechnum.rods import SHOOTING_TOL, ShotRods

UNKNOWNS = ("pose", "inputs")
"""The two sets of shooting unknowns: the study's (102), with the end effector (the pose), and
its (99), with the motor angles (the inputs)."""


def _shoot(shot, mech, m0, force, theta):
    """Tip states (batch, 2, 4) of both rods and their derivatives (batch, 2, 4, 4) with
    respect to ``(m0, n_x, n_y, theta0)``: complex step for the first three, and for the clamp
    angle the rotation identity ``d/dtheta0 = J (tip - O) - d/dn . (J n)`` (turning clamp
    and force together turns the rod), with ``J`` the rotation by a right angle."""
    tip, J = shot(m0, force, theta, mech.origins)
    turned = np.stack((-force[..., 1], force[..., 0]), axis=-1)           # J n
    d_theta = -np.einsum("...ij,...j->...i", J[..., 1:], turned)
    d_theta[..., 0] -= tip[..., 1] - mech.origins[:, 1]
    d_theta[..., 1] += tip[..., 0] - mech.origins[:, 0]
    return tip, np.concatenate((J, d_theta[..., None]), axis=-1)


def shooting_system(mech: Mechanism, nodes: int, unknown: str) -> tuple[Callable, Callable]:
    """Residual (98) and its Jacobian for a batch of unknowns ``X`` (batch, 8).

    Parameters
    ----------
    mech : Mechanism
    nodes : int
        RK4 nodes per rod (at most ``MAX_NODES = 100_000``).
    unknown : {"pose", "inputs"}
        The study's (102), ``X = (m0_1, n1, m0_2, n2, P)`` with ``known`` the motor angles
        (batch, 2), or its (99), ``X = (m0_1, n1, theta1, m0_2, n2, theta2)`` with ``known`` the
        end effector.

    Returns
    -------
    fun, split : callable
        ``fun(X, known) -> (f, J)``: the residual (batch, 8) (scaled: moments by ``EI / L``,
        positions by ``L``, forces by ``EI / L**2``) and its Jacobian (batch, 8, 8), from one
        RK4 sweep (complex step), as :func:`mechnum.newton.solve` takes them with
        ``jac=True``; ``split(X, known) -> (m0, n, theta, P)``. Neither checks its input.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> fun, _ = shooting_system(TABLE7, 801, "pose")
    >>> X = shooting_guess(TABLE7, TABLE7_THETA, eq.x)
    >>> f, J = fun(X, np.broadcast_to(TABLE7_THETA, (3, 2)))
    >>> bool(np.abs(f).max() < 1e-8), J.shape      # RK4's error
    (True, (3, 8, 8))
    """
    assembly.check_type(mech, Mechanism)
    shot = ShotRods(mech.EI, mech.L, _validate.maxiter(nodes, "nodes", minimum=2,
                                                        maximum=assembly.MAX_NODES))
    _validate.choice(unknown, UNKNOWNS, "unknown")
    moment, length, force = mech.EI / mech.L, mech.L, mech.EI / mech.L ** 2
    row_scale = np.array([moment, length, length] * 2 + [force, force])
    width = 3 if unknown == "pose" else 4           # (m0, n_x, n_y[, theta0]) of each rod

    def split(X, known):
        """``(m0, n, theta, P)`` of the unknowns, the known ones filled in."""
        if unknown == "inputs":
            return X[:, [0, 4]], X[:, [1, 2, 5, 6]].reshape(-1, 2, 2), X[:, [3, 7]], known
        return X[:, [0, 3]], X[:, [1, 2, 4, 5]].reshape(-1, 2, 2), known, X[:, 6:8]

    def fun(X, known):
        m0, n, theta, P = split(X, known)
        tip, D = _shoot(shot, mech, m0, n, theta)
        rows = [tip[:, 0, 3:], tip[:, 0, :2] - P, tip[:, 1, 3:], tip[:, 1, :2] - P,
                n.sum(axis=1) - mech.force]
        D = D[:, :, [3, 0, 1], :]                     # rows m(L), x(L), y(L)
        J = np.zeros((len(X), 8, 8))
        for r in range(2):
            c = width * r
            J[:, 3 * r:3 * r + 3, c:c + width] = D[:, r, :, :width]
            J[:, 6:8, c + 1:c + 3] = np.eye(2)
        if unknown == "pose":
            J[:, [1, 4], 6] = J[:, [2, 5], 7] = -1.0
        return np.concatenate(rows, axis=-1) / row_scale, J / row_scale[:, None]

    return fun, split


def _shooting(mech, unknown, known, seed, nodes, tol, maxiter):
    fun, split = shooting_system(mech, nodes, unknown)
    res, known = assembly.shoot(fun, seed, known, width=8, tol=tol, maxiter=maxiter)
    m0, n, theta, P = split(res.x, known)
    return assembly.shooting_result(res, theta, P, m0, n, fun(res.x, known)[1])


def forward_shooting(mech: Mechanism, theta: ArrayLike, seed: ArrayLike, *,
                     nodes: int = STUDY_NODES, tol: float = SHOOTING_TOL,
                     maxiter: int = 50) -> assembly.ShotEquilibria:
    """The direct problem by RK4 shooting: the study's (98) in its unknowns (102).

    ``X = (m0_1, n1_x, n1_y, m0_2, n2_x, n2_y, x_P, y_P)``; Newton (damped) drives the tip
    moments to zero, both tips to ``P`` and ``n1 + n2`` to ``F``, with the complex-step
    Jacobian of :func:`mechnum.rods.tip_jacobian` (the study differentiates by forward
    differences with a step of ``1e-11``). The seed picks the equilibrium.

    Parameters
    ----------
    mech : Mechanism
    theta : array_like, shape (2,) or (batch, 2)
        Motor angles (rad): one, or one per seed.
    seed : array_like, shape (8,) or (batch, 8)
        Initial ``X`` (:func:`shooting_guess` gives it from a closed-form equilibrium).
    nodes : int, optional
        RK4 nodes per rod (the study's 41 by default; the RK4 error falls as ``nodes**-4``),
        at most ``MAX_NODES = 100_000``.
    tol, maxiter : optional
        Newton's tolerance on the scaled residual (``criterion="residual"``), most iterations
        (at most 10,000).

    Returns
    -------
    mechnum.mechanisms.ShotEquilibria
        ``x`` the unknowns, ``inputs`` the motor angles and ``pose`` the end effector (batch,
        2); ``jacobian`` (batch, 8, 8) is the Jacobian of (98) in the unknowns at the last
        iterate (scaled: moments by ``EI / L``, positions by ``L``, forces by ``EI / L**2``),
        the study's ``J_FK``. ``status`` per system; a system that did not converge is not
        an equilibrium.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> sol = forward_shooting(TABLE7, TABLE7_THETA, shooting_guess(TABLE7, TABLE7_THETA, z),
    ...                        nodes=801)
    >>> np.round(sol.pose, 6).tolist(), sol.status.tolist()
    ([[-0.081103, -0.245872]], ['converged'])
    """
    theta = _validate.array(theta, "theta", ndim=(1, 2))
    if theta.shape[-1] != 2:
        raise ValueError(f"theta must have shape (2,) or (batch, 2), got {theta.shape}")
    return _shooting(mech, "pose", theta, seed, nodes, tol, maxiter)


def inverse_shooting(mech: Mechanism, pose: ArrayLike, seed: ArrayLike, *,
                     nodes: int = STUDY_NODES, tol: float = SHOOTING_TOL,
                     maxiter: int = 50) -> assembly.ShotEquilibria:
    """The inverse problem by RK4 shooting: the study's (98) in its unknowns (99).

    ``X = (m0_1, n1_x, n1_y, theta1, m0_2, n2_x, n2_y, theta2)`` for a given end effector
    ``pose`` (shape (2,) or (batch, 2)); otherwise as :func:`forward_shooting` (its
    ``jacobian`` the study's ``J_IK``).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> X = shooting_guess(TABLE7, TABLE7_THETA, z, unknown="inputs")
    >>> sol = inverse_shooting(TABLE7, [-0.081103, -0.245872], X, nodes=801)
    >>> np.round(np.degrees(sol.inputs), 3).tolist()
    [[40.0, 60.0]]
    """
    pose = _validate.array(pose, "pose", ndim=(1, 2))
    if pose.shape[-1] != 2:
        raise ValueError(f"pose must have shape (2,) or (batch, 2), got {pose.shape}")
    return _shooting(mech, "inputs", pose, seed, nodes, tol, maxiter)


def shooting_guess(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1),
                   *, unknown: str = "pose") -> np.ndarray:
    """The study's shooting unknowns of closed-form equilibria: (102), or (99) with
    ``unknown="inputs"``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> X = shooting_guess(TABLE7, TABLE7_THETA, chart_from_thesis(
    ...     [5.304574, 0.969830, 1.825456, -0.992135]))
    >>> np.round(X, 4).tolist()
    [0.2541, 1.39, -0.4004, -0.3825, -1.09, 0.3004, -0.0811, -0.2459]
    """
    _validate.choice(unknown, UNKNOWNS, "unknown")
    assembly.check_type(mech, Mechanism)
    tip, force, moment, _, _ = rods(mech, theta, chart, modes, jacobian=False)
    theta = np.broadcast_to(np.asarray(theta, dtype=float), moment.shape)
    if unknown == "pose":
        return np.concatenate((moment[..., :1], force[..., 0, :], moment[..., 1:],
                               force[..., 1, :], tip[..., 0, :]), axis=-1)
    return np.concatenate((moment[..., :1], force[..., 0, :], theta[..., :1], moment[..., 1:],
                           force[..., 1, :], theta[..., 1:]), axis=-1)
