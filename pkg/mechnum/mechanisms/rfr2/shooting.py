"""RK4 shooting, as the study solves its mechanism: its (98) in the unknowns (99) and (102).

:func:`~mechnum.mechanisms.rfr2.forward_shooting` (the direct problem, unknowns (102)) and
:func:`~mechnum.mechanisms.rfr2.inverse_shooting` (the inverse problem, unknowns (99)) drive the
tip moments to zero, both tips to ``P`` and ``n1 + n2`` to ``F`` by damped Newton with
complex-step Jacobians (:func:`mechnum.rods.shooting.tip_jacobian`);
:func:`~mechnum.mechanisms.rfr2.shooting_guess` gives their unknowns from a closed-form
equilibrium.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate, newton, rods
from mechnum.mechanisms.rfr2.model import _clamp_states

STUDY_NODES = 41                               # RK4 nodes of the study's shooting programs
# Shooting converges when the dimensionless residual (98) is below this: round-off of the
# O(1) positions and forces is ~1e-15; 1e-12 leaves a margin of a thousand.
SHOOTING_TOL = 1e-12


def _memoised(compute):
    """``compute(u, p)`` that remembers its last call: Newton asks for the residual and then
    for the Jacobian at the same point, and both come from one evaluation of the rods."""
    last = {}

    def call(u, p):
        key = (u.tobytes(), np.asarray(p).tobytes())
        if last.get("key") != key:
            last["key"], last["value"] = key, compute(u, p)
        return last["value"]

    return call


@dataclass(frozen=True)
class Shooting:
    """Equilibria found by RK4 shooting (:func:`forward_shooting`, :func:`inverse_shooting`).

    Attributes
    ----------
    theta, P : ndarray, shape (batch, 2)
        Motor angles (rad) and end effector (m).
    clamp_moments : ndarray, shape (batch, 2)
        ``m(0)`` of each rod (N m).
    forces : ndarray, shape (batch, 2, 2)
        Force on each rod at its tip (N).
    jacobian : ndarray, shape (batch, 8, 8)
        The Jacobian of (98) with respect to the unknowns, at the last iterate (scaled: moments
        by ``EI / L``, positions by ``L``, forces by ``EI / L**2``): the study's ``J_FK`` (with
        respect to its (102)) or ``J_IK`` (its (99)).
    newton : mechnum.newton.BatchNewtonResult
        The iteration; read ``newton.status`` for the systems that did not converge.
    """

    theta: np.ndarray
    P: np.ndarray
    clamp_moments: np.ndarray
    forces: np.ndarray
    jacobian: np.ndarray
    newton: newton.BatchNewtonResult


def _shoot(mech, m0, force, theta, nodes):
    """Tip states (batch, 2, 4) of both rods and their derivatives (batch, 2, 4, 4) with
    respect to ``(m0, n_x, n_y, theta0)``: complex step for the first three, and for the clamp
    angle the rotation identity ``d/dtheta0 = J (tip - O) - d/dn . (J n)`` (turning clamp
    and force together turns the rod), with ``J`` the rotation by a right angle."""
    tip, J = rods.tip_jacobian(mech.EI, mech.L, m0, force, theta0=theta, origin=mech.origins,
                               nodes=nodes)
    turned = np.stack((-force[..., 1], force[..., 0]), axis=-1)           # J n
    d_theta = -np.einsum("...ij,...j->...i", J[..., 1:], turned)
    d_theta[..., 0] -= tip[..., 1] - mech.origins[:, 1]
    d_theta[..., 1] += tip[..., 0] - mech.origins[:, 0]
    return tip, np.concatenate((J, d_theta[..., None]), axis=-1)


def _shooting_system(mech, nodes, unknown):
    """Residual (98) and its Jacobian, ``fun(X, known)`` and ``jac(X, known)``, for a batch of
    unknowns ``X`` (batch, 8): the study's (102) when ``unknown == "P"`` (``known`` the motor
    angles, (batch, 2)), (99) when ``unknown == "theta"`` (``known`` the end effector). Both
    come from one RK4 sweep (complex step), remembered between the two calls."""
    moment, length, force = mech.EI / mech.L, mech.L, mech.EI / mech.L ** 2
    row_scale = np.array([moment, length, length] * 2 + [force, force])

    def split(X, known):
        """``(m0, n, theta, P)`` of the unknowns, the known ones filled in."""
        if unknown == "theta":
            return X[:, [0, 4]], X[:, [1, 2, 5, 6]].reshape(-1, 2, 2), X[:, [3, 7]], known
        return X[:, [0, 3]], X[:, [1, 2, 4, 5]].reshape(-1, 2, 2), known, X[:, 6:8]

    def sweep(X, known):
        m0, n, theta, P = split(X, known)
        return _shoot(mech, m0, n, theta, nodes), n, P

    sweep = _memoised(sweep)

    def fun(X, known):
        (tip, _), n, P = sweep(X, known)
        rows = [tip[:, 0, 3:], tip[:, 0, :2] - P, tip[:, 1, 3:], tip[:, 1, :2] - P,
                n.sum(axis=1) - mech.force]
        return np.concatenate(rows, axis=-1) / row_scale

    def jac(X, known):
        D = sweep(X, known)[0][1][:, :, [3, 0, 1], :]   # rows m(L), x(L), y(L)
        width = 3 if unknown == "P" else 4           # (m0, n_x, n_y[, theta0]) of each rod
        J = np.zeros((len(X), 8, 8))
        for r in range(2):
            c = width * r
            J[:, 3 * r:3 * r + 3, c:c + width] = D[:, r, :, :width]
            J[:, 6:8, c + 1:c + 3] = np.eye(2)
        if unknown == "P":
            J[:, [1, 4], 6] = J[:, [2, 5], 7] = -1.0
        return J / row_scale[:, None]

    return fun, jac, split


def _shooting(mech, unknown, known, guess, nodes, tol, maxiter):
    guess = _validate.array(guess, "guess")
    X0 = np.atleast_2d(guess)
    if X0.shape[1] != 8:
        raise ValueError(f"guess must have a last axis of 8 (the study's unknowns), "
                         f"got shape {guess.shape}")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    known = np.broadcast_to(known, (len(X0), 2))
    fun, jac, split = _shooting_system(mech, nodes, unknown)
    res = newton.solve_batch(lambda X: fun(X, known), X0, lambda X: jac(X, known), tol=tol,
                             maxiter=maxiter, criterion="residual", damping=True,
                             raise_on_failure=False)
    m0, n, theta, P = split(res.x, known)
    return Shooting(np.array(theta), np.array(P), m0, n, jac(res.x, known), res)


def forward_shooting(mech, theta, guess, *, nodes=STUDY_NODES, tol=SHOOTING_TOL, maxiter=50):
    """The direct problem by RK4 shooting: the study's (98) in its unknowns (102).

    ``X = (m0_1, n1_x, n1_y, m0_2, n2_x, n2_y, x_P, y_P)``; Newton (damped) drives the tip
    moments to zero, both tips to ``P`` and ``n1 + n2`` to ``F``, with the complex-step
    Jacobian of :func:`mechnum.rods.shooting.tip_jacobian` (the study differentiates by forward
    differences with a step of ``1e-11``). The guess picks the equilibrium.

    Parameters
    ----------
    mech : Mechanism
    theta : array_like, shape (2,) or (batch, 2)
        Motor angles (rad).
    guess : array_like, shape (8,) or (batch, 8)
        Initial ``X`` (:func:`shooting_guess` gives it from a closed-form equilibrium).
    nodes : int, optional
        RK4 nodes per rod (the study's 41 by default; the RK4 error falls as ``nodes**-4``).
    tol, maxiter : optional
        Newton's tolerance on the scaled residual (``criterion="residual"``), most iterations.

    Returns
    -------
    Shooting

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> sol = forward_shooting(TABLE7, TABLE7_THETA, shooting_guess(TABLE7, TABLE7_THETA, z),
    ...                        nodes=801)
    >>> np.round(sol.P, 6).tolist(), sol.newton.status.tolist()
    ([[-0.081103, -0.245872]], ['converged'])
    """
    return _shooting(mech, "P", _validate.array(theta, "theta"), guess, nodes, tol, maxiter)


def inverse_shooting(mech, P, guess, *, nodes=STUDY_NODES, tol=SHOOTING_TOL, maxiter=50):
    """The inverse problem by RK4 shooting: the study's (98) in its unknowns (99).

    ``X = (m0_1, n1_x, n1_y, theta1, m0_2, n2_x, n2_y, theta2)`` for a given end effector
    ``P``; otherwise as :func:`forward_shooting`.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> X = shooting_guess(TABLE7, TABLE7_THETA, z, unknown="theta")
    >>> sol = inverse_shooting(TABLE7, [-0.081103, -0.245872], X, nodes=801)
    >>> np.round(np.degrees(sol.theta), 3).tolist()
    [[40.0, 60.0]]
    """
    return _shooting(mech, "theta", _validate.array(P, "P"), guess, nodes, tol, maxiter)


def shooting_guess(mech, theta, chart, modes=(1, 1), *, unknown="P"):
    """The study's shooting unknowns of closed-form equilibria: (102), or (99) with
    ``unknown="theta"``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> X = shooting_guess(TABLE7, TABLE7_THETA, chart_from_thesis(
    ...     [5.304574, 0.969830, 1.825456, -0.992135]))
    >>> np.round(X, 4).tolist()
    [0.2541, 1.39, -0.4004, -0.3825, -1.09, 0.3004, -0.0811, -0.2459]
    """
    _validate.choice(unknown, ("P", "theta"), "unknown")
    tip, force, moment = _clamp_states(mech, theta, chart, modes)
    theta = np.broadcast_to(_validate.array(theta, "theta"), moment.shape)
    if unknown == "P":
        return np.concatenate((moment[..., :1], force[..., 0, :], moment[..., 1:],
                               force[..., 1, :], tip[..., 0, :]), axis=-1)
    return np.concatenate((moment[..., :1], force[..., 0, :], theta[..., :1], moment[..., 1:],
                           force[..., 1, :], theta[..., 1:]), axis=-1)
