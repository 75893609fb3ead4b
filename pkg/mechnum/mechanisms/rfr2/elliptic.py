"""Every equilibrium in closed form: of given motor angles (direct), or of a given end effector
(inverse).

:func:`~mechnum.mechanisms.rfr2.forward_system` is the study's four equations (its 11.3.2: both
tips at one point, ``n1 + n2 = F``) in the chart, with their analytic Jacobian;
:func:`~mechnum.mechanisms.rfr2.residual` the same residual in metres and newtons.
:func:`~mechnum.mechanisms.rfr2.forward_elliptic` (the protocol's
:func:`~mechnum.mechanisms.rfr2.forward`) finds every equilibrium by Newton from many starts
(:func:`mechnum.rods.assembly.search`), with the evidence that there are no more, and classifies
each (:mod:`~mechnum.mechanisms.rfr2.analysis`). :func:`~mechnum.mechanisms.rfr2.inverse` does
the same for a given end effector, on :func:`inverse_system`: each motor angle is the one that
turns its rod's tip onto ``P``, so that the unknowns are the four chart coordinates again.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.rfr2.analysis import crossings, stability, strain
from mechnum.mechanisms.rfr2.drawing import draw
from mechnum.mechanisms.rfr2.model import Mechanism, Names, in_chart, rods, thesis_from_chart
from mechnum.rods import assembly, regular

# Starts of the all-solutions search are drawn with |t| <= 0.985 (forces up to ~(q/2)**2 =
# 1000 EI / L**2, far beyond what the study's mechanism can balance); iterates may go on to T_MAX.
START_T = 0.985
# Newton's step tolerance in the (dimensionless) chart, and its most iterations from a start.
SEARCH_TOL = 1e-12
SEARCH_MAXITER = 40


def _scales(mech):
    """Scales of the residual rows: positions by ``L``, forces by ``EI / L**2``."""
    return np.array([mech.L, mech.L, mech.EI / mech.L ** 2, mech.EI / mech.L ** 2])


def forward_system(mech: Mechanism, theta: ArrayLike, modes: ArrayLike = (1, 1)):
    """The direct problem in closed form: the residual and its Jacobian, batched.

    The study's four equations (its 11.3.2: both tips at one point, ``n1 + n2 = F``) in the
    four unknowns ``z = (psi1, t1, psi2, t2)``, dimensionless (positions over ``L``, forces
    over ``EI / L**2``), with the analytic Jacobian of :mod:`mechnum.rods.regular`.

    Returns
    -------
    fun, jac : callable
        ``fun(z) -> (batch, 4)`` and ``jac(z) -> (batch, 4, 4)`` for ``z`` of shape
        ``(batch, 4)`` in the chart.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> fun, jac = forward_system(TABLE7, TABLE7_THETA)
    >>> z = chart_from_thesis([[5.304574, 0.969830, 1.825456, -0.992135]])
    >>> fun(z).shape, jac(z).shape, bool(np.abs(fun(z)).max() < 3e-4)
    ((1, 4), (1, 4, 4), True)
    """
    assembly.check_type(mech, Mechanism)
    theta = _validate.array(theta, "theta", shape=(2,))
    modes, scale = assembly.check_modes(modes, 2), _scales(mech)

    def fun(z):
        tip, force = rods(mech, theta, z, modes, jacobian=False)[:2]
        return np.concatenate((tip[..., 0, :] - tip[..., 1, :], force.sum(axis=-2)
                               - mech.force), axis=-1) / scale

    def jac(z):
        d = rods(mech, theta, z, modes)[3]
        J = np.concatenate((np.concatenate((d[:, 0, :2], -d[:, 1, :2]), axis=-1),
                            np.concatenate((d[:, 0, 2:], d[:, 1, 2:]), axis=-1)), axis=1)
        return J / scale[:, None]

    return fun, jac


def residual(mech: Mechanism, theta: ArrayLike, chart: ArrayLike,
             modes: ArrayLike = (1, 1)) -> np.ndarray:
    """The closed-form equilibrium residual ``(tip1 - tip2, n1 + n2 - F)`` (m, m, N, N).

    Parameters
    ----------
    theta : array_like, shape (..., 2)
        Motor angles (rad), broadcast with ``chart``.
    chart : array_like, shape (..., 4)
        Equilibria ``(psi1, t1, psi2, t2)``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> r = residual(TABLE7, TABLE7_THETA, chart_from_thesis([5.304574, 0.969830, 1.825456,
    ...                                                       -0.992135]))
    >>> bool(np.abs(r).max() < 2e-5)        # the printed digits leave ~1e-5
    True
    """
    assembly.check_type(mech, Mechanism)
    tip, force = rods(mech, theta, chart, modes, jacobian=False)[:2]
    return np.concatenate((tip[..., 0, :] - tip[..., 1, :], force.sum(axis=-2) - mech.force),
                          axis=-1)


def inverse_system(mech: Mechanism, P: ArrayLike, modes: ArrayLike = (1, 1)):
    """The inverse problem in closed form, reduced to the rods: residual and Jacobian, batched.

    Rod ``i`` of chart ``(psi_i, t_i)`` has its tip at ``l_i`` in its clamp's frame; the motor
    angle that turns it onto ``P`` is ``theta_i = atan2(P - O_i) - atan2(l_i)``
    (:func:`motor_angles`), so that four equations remain: ``|l_i| = |P - O_i|`` and
    ``n1 + n2 = F`` (the forces turned by ``theta_i``), dimensionless.

    Returns
    -------
    fun, jac : callable
        ``fun(z) -> (batch, 4)`` and ``jac(z) -> (batch, 4, 4)``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, forward_elliptic
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> fun, jac = inverse_system(TABLE7, eq.P[0])
    >>> bool(np.abs(fun(eq.chart[:1])).max() < 1e-12), jac(eq.chart[:1]).shape
    (True, (1, 4, 4))
    """
    assembly.check_type(mech, Mechanism)
    P = _validate.array(P, "P", shape=(2,))
    modes, f = assembly.check_modes(modes, 2), mech.EI / mech.L ** 2
    reach = np.hypot(*(P - mech.origins).T)

    def parts(z, jacobian):
        rod = regular._closed_form(mech.EI, mech.L, z[:, 0::2], z[:, 1::2], modes, jacobian)
        length = np.hypot(rod.tip[..., 0], rod.tip[..., 1])
        theta = motor_angles(mech, P, rod.tip)
        c, s = np.cos(theta), np.sin(theta)
        n = np.stack((c * rod.force[..., 0] - s * rod.force[..., 1],
                      s * rod.force[..., 0] + c * rod.force[..., 1]), axis=-1)
        G = np.concatenate(((length - reach) / mech.L, (n.sum(axis=1) - mech.force) / f), -1)
        return G, (rod, length, c, s, n)

    def fun(z):
        return parts(z, False)[0]

    def jac(z):
        rod, length, c, s, n = parts(z, True)[1]
        J_tip, J_force = rod.jacobian[..., 0:2, :], rod.jacobian[..., 2:4, :]   # (b, r, 2, 2)
        tip = rod.tip[..., None]
        d_length = np.sum(tip * J_tip, axis=-2) / length[..., None]            # (b, r, 2)
        d_theta = -(tip[..., 0, :] * J_tip[..., 1, :] - tip[..., 1, :] * J_tip[..., 0, :]) \
            / length[..., None] ** 2
        c, s = c[..., None], s[..., None]
        d_n = np.stack((c * J_force[..., 0, :] - s * J_force[..., 1, :],
                        s * J_force[..., 0, :] + c * J_force[..., 1, :]), axis=-2)
        d_n += np.stack((-n[..., 1], n[..., 0]), axis=-1)[..., None] * d_theta[..., None, :]
        J = np.zeros((len(z), 4, 4))
        for r in range(2):
            J[:, r, 2 * r:2 * r + 2] = d_length[:, r] / mech.L
            J[:, 2:4, 2 * r:2 * r + 2] = d_n[:, r] / f
        return J

    return fun, jac


def motor_angles(mech: Mechanism, P: ArrayLike, tip: ArrayLike) -> np.ndarray:
    """The motor angles ``(..., 2)`` that turn rods whose tips are ``tip`` (..., 2, 2) in their
    clamps' frames onto the end effector ``P``, in ``(-pi, pi]``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7
    >>> np.degrees(motor_angles(TABLE7, [0.0, 0.5], np.array([[0.5, 0.0], [0.5, 0.0]]))).round(
    ...     3).tolist()
    [59.036, 120.964]
    """
    assembly.check_type(mech, Mechanism)
    to_P = _validate.array(P, "P", shape=(2,)) - mech.origins
    tip = _validate.array(tip, "tip")
    if tip.shape[-2:] != (2, 2):
        raise ValueError(f"tip must have shape (..., 2, 2), got shape {tip.shape}")
    turn = np.arctan2(to_P[:, 1], to_P[:, 0]) - np.arctan2(tip[..., 1], tip[..., 0])
    return np.angle(np.exp(1j * turn))


@dataclass(frozen=True, kw_only=True)
class Equilibria(assembly.Equilibria, Names):
    """Every equilibrium that :func:`forward_elliptic` (or :func:`inverse`) found.

    The fields of :class:`mechnum.rods.assembly.Equilibria`, with the 2RFR's names too:
    ``theta`` (the inputs, motor angles, rad) and ``P`` (the pose, the end effector, m).
    ``rods_cross`` has shape (n,), ``self_cross`` (n, 2); ``solutions`` is the study's
    ``(psi1, k_rel1, psi2, k_rel2)`` (its Table 7).
    """

    drawer = staticmethod(draw)


def sample(rng: np.random.Generator | int | None, m: int) -> np.ndarray:
    """Random starts: force directions uniform in (0, 2 pi), ``t`` uniform in
    ``(-START_T, START_T)`` (every sign branch of both rods).

    Examples
    --------
    >>> z = sample(np.random.default_rng(0), 3)
    >>> z.shape, bool(in_chart(z).all())
    ((3, 4), True)
    """
    m = _validate.maxiter(m, "m", minimum=0, maximum=assembly.MAX_STARTS * assembly.MAX_CHECK)
    rng = _validate.rng(rng)
    psi = rng.uniform(0.0, regular.TWO_PI, (m, 2))
    t = rng.uniform(-START_T, START_T, (m, 2))
    return np.stack((psi[:, 0], t[:, 0], psi[:, 1], t[:, 1]), axis=-1)


def _equilibria(mech, theta, P, modes, found, nfev, njev, inputs, pose):
    """Classify the roots (chart) of a search at motor angles ``theta`` (n, 2)."""
    z = found.x
    n = len(z)
    _, force, moment, _, _ = rods(mech, theta, z, modes, jacobian=False)
    index, cross, own = np.zeros((0, 2), int), np.zeros(0, int), np.zeros((0, 2), int)
    if n:
        index = np.array([stability(mech, theta[i], z[i], modes) for i in range(n)])
        cross, own = crossings(mech, theta, z, modes)
    return Equilibria(x=z, status=np.full(n, "converged"), iterations=njev, nfev=nfev,
                      njev=njev, message=assembly.equilibria_message(n, found),
                      inputs=inputs, pose=pose, modes=tuple(int(m) for m in modes),
                      solutions=thesis_from_chart(z), chart=z, forces=force,
                      clamp_moments=moment, index=index, rods_cross=cross, self_cross=own,
                      strain=strain(mech, theta, z, modes), strain_limit=mech.strain_limit,
                      search=found)


def forward_elliptic(mech: Mechanism, theta: ArrayLike, modes: ArrayLike = (1, 1), *,
                     n_starts: int = 200, check: int = 10,
                     rng: np.random.Generator | int | None = None):
    """Every equilibrium of the mechanism at the motor angles ``theta`` with the given modes.

    Damped Newton on the closed form (analytic Jacobian) from ``n_starts`` random starts, then
    ``check`` times as many new starts (:func:`mechnum.newton.solve_all`). The starts cover
    the four sign branches of ``(t1, t2)`` (the study's signs of ``k_rel``); an iterate may
    step across ``t = 0`` into another branch, where the residual jumps: Newton then simply
    goes on from there, and every root it reports satisfies the equations. Each equilibrium
    is then classified: stability (:func:`stability`), crossings of the rods
    (:func:`crossings`) and bending strain (:func:`strain`). Rods under forces beyond the
    chart's range (``T_MAX`` of :mod:`mechnum.rods.regular`, ``~(300 mode)**2 EI / L**2``) are
    not sought.

    Parameters
    ----------
    mech : Mechanism
    theta : array_like, shape (2,)
        Motor angles (rad).
    modes : (int, int), optional
        Buckling modes of rod 1 and rod 2 (inflections on ``0 < s <= L``).
    n_starts : int, optional
        Starts of the search, at most :data:`~mechnum.rods.assembly.checks.MAX_STARTS`.
    check : int, optional
        Size of the completeness check, in multiples of ``n_starts`` (0: none; at most
        :data:`~mechnum.rods.assembly.checks.MAX_CHECK`).
    rng : numpy.random.Generator or int, optional
        Random generator or seed (a non-negative integer) of the starts.

    Returns
    -------
    Equilibria
        ``n >= 0`` equilibria, sorted by ``psi1``; an empty result when none is found.

    Raises
    ------
    ValueError
        If ``mech`` is no :class:`Mechanism`, ``theta`` not two finite angles, ``modes`` not
        two integers ``>= 1``, or a size or ``rng`` invalid.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> np.round(eq.solutions, 6).tolist()[0], eq.stable.tolist(), eq.search.complete
    ([1.962541, -0.004391, 4.811041, 0.943413], [True, True, True], True)
    """
    fun, jac = forward_system(mech, theta, modes)
    theta, modes = np.asarray(theta, dtype=float), assembly.check_modes(modes, 2)
    found, nfev, njev = assembly.search(fun, jac, sample, domain=in_chart, n_starts=n_starts,
                                        check=check, rng=rng, tol=SEARCH_TOL,
                                        maxiter=SEARCH_MAXITER)
    P = rods(mech, theta, found.x, modes, jacobian=False)[0][:, 0]
    return _equilibria(mech, np.broadcast_to(theta, (len(P), 2)), P, modes, found, nfev,
                       njev, theta, P)


forward = forward_elliptic
"""The protocol's name of :func:`forward_elliptic`: every equilibrium at given inputs."""


def inverse(mech: Mechanism, P: ArrayLike, modes: ArrayLike = (1, 1), *, n_starts: int = 200,
            check: int = 10, rng: np.random.Generator | int | None = None):
    """Every equilibrium of the mechanism with its end effector at ``P``, with the given modes.

    The inverse problem: the motor angles and the rods that hold ``P`` against the load, found
    as :func:`forward_elliptic` finds the direct problem's, on :func:`inverse_system`.

    Parameters
    ----------
    mech, modes, n_starts, check, rng
        As in :func:`forward_elliptic`.
    P : array_like, shape (2,)
        The end effector (m).

    Returns
    -------
    Equilibria
        ``theta`` of shape (n, 2), one per equilibrium, in ``(-pi, pi]``; ``P`` as given.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, forward_elliptic
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> back = inverse(TABLE7, eq.P[2], rng=0)
    >>> bool(np.abs(back.theta - TABLE7_THETA).max(axis=1).min() < 1e-10)
    True
    """
    fun, jac = inverse_system(mech, P, modes)
    P, modes = np.asarray(P, dtype=float), assembly.check_modes(modes, 2)
    found, nfev, njev = assembly.search(fun, jac, sample, domain=in_chart, n_starts=n_starts,
                                        check=check, rng=rng, tol=SEARCH_TOL,
                                        maxiter=SEARCH_MAXITER)
    z = found.x
    tip = regular._closed_form(mech.EI, mech.L, z[:, 0::2], z[:, 1::2], modes, False).tip
    theta = motor_angles(mech, P, tip)
    return _equilibria(mech, theta, P, modes, found, nfev, njev, theta, P)

