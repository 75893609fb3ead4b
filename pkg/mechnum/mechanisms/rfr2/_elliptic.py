"""Every equilibrium in closed form: of given motor angles (direct), or of a given end effector
(inverse).

:func:`~mechnum.mechanisms.rfr2.forward_system` is the study's four equations (its 11.3.2: both
tips at one point, ``n1 + n2 = F``) in the chart, with their analytic Jacobian;
:func:`~mechnum.mechanisms.rfr2.residual` the same residual in metres and newtons.
:func:`~mechnum.mechanisms.rfr2.forward` finds every equilibrium by Newton from many starts
(:func:`mechnum.newton.solve_all`), with the evidence that there are no more, and classifies
each. :func:`~mechnum.mechanisms.rfr2.inverse` does the same for a given end effector, on
:func:`inverse_system`: each motor angle is the one that turns its rod's tip onto the end
effector, so that the unknowns are the four chart coordinates again. The systems check their
input once, when they are made; the searches' iterates go through unchecked kernels.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.rfr2._analysis import crossings, stabilities, strain
from mechnum.mechanisms.rfr2._model import Mechanism, rods, rods_at, thesis_from_chart
from mechnum.rods import T_MAX, ClampedRods, MeetingRods, in_chart

# Starts of the all-solutions search are drawn with |t| <= 0.985 (forces up to ~(q/2)**2 =
# 1000 EI / L**2, far beyond what the study's mechanism can balance); iterates may go on to T_MAX.
START_T = 0.985
# Newton's step tolerance in the (dimensionless) chart, and its most iterations from a start.
SEARCH_TOL = 1e-12
SEARCH_MAXITER = 40
# Starts of the search, and of its completeness check in multiples of them (the defaults).
N_STARTS, CHECK = 200, 10


def _scales(mech):
    """Scales of the residual rows: positions by ``L``, forces by ``EI / L**2``."""
    return np.array([mech.L, mech.L, mech.EI / mech.L ** 2, mech.EI / mech.L ** 2])


def forward_system(mech: Mechanism, theta: ArrayLike,
                   modes: ArrayLike = (1, 1)) -> Callable[[np.ndarray], tuple]:
    """The direct problem in closed form: the residual and its Jacobian, batched.

    The study's four equations (its 11.3.2: both tips at one point, ``n1 + n2 = F``) in the
    four unknowns ``z = (psi1, t1, psi2, t2)``, dimensionless (positions over ``L``, forces
    over ``EI / L**2``), with the analytic Jacobian of the closed form.

    Returns
    -------
    callable
        ``system(z) -> (f, J)``, ``f`` of shape ``(batch, 4)`` and ``J`` ``(batch, 4, 4)``
        for ``z`` of shape ``(batch, 4)`` in the chart: both from one evaluation of the rods,
        as :func:`mechnum.newton.solve` takes them with ``jac=True``. Its input is not
        checked (the solvers' iterates).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> system = forward_system(TABLE7, TABLE7_THETA)
    >>> f, J = system(chart_from_thesis([[5.304574, 0.969830, 1.825456, -0.992135]]))
    >>> f.shape, J.shape, bool(np.abs(f).max() < 3e-4)
    ((1, 4), (1, 4, 4), True)
    """
    assembly.check_type(mech, Mechanism)
    theta = _validate.array(theta, "theta", shape=(2,))
    family = ClampedRods(mech.EI, mech.L, assembly.check_modes(modes, 2))
    scale = _scales(mech)

    def system(z):
        tip, force, _, d, _ = rods_at(family, mech, theta, z)
        f = np.concatenate((tip[..., 0, :] - tip[..., 1, :], force.sum(axis=-2)
                            - mech.force), axis=-1) / scale
        J = np.concatenate((np.concatenate((d[:, 0, :2], -d[:, 1, :2]), axis=-1),
                            np.concatenate((d[:, 0, 2:], d[:, 1, 2:]), axis=-1)), axis=1)
        return f, J / scale[:, None]

    return system


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
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> r = residual(TABLE7, TABLE7_THETA, chart_from_thesis([5.304574, 0.969830, 1.825456,
    ...                                                       -0.992135]))
    >>> bool(np.abs(r).max() < 2e-5)        # the printed digits leave ~1e-5
    True
    """
    assembly.check_type(mech, Mechanism)
    tip, force = rods(mech, theta, chart, modes, jacobian=False)[:2]
    return np.concatenate((tip[..., 0, :] - tip[..., 1, :], force.sum(axis=-2) - mech.force),
                          axis=-1)


def inverse_system(mech: Mechanism, pose: ArrayLike,
                   modes: ArrayLike = (1, 1)) -> Callable[[np.ndarray], tuple]:
    """The inverse problem in closed form, reduced to the rods: residual and Jacobian, batched.

    Rod ``i`` of chart ``(psi_i, t_i)`` has its tip at ``l_i`` in its clamp's frame; the motor
    angle that turns it onto the end effector ``pose`` is ``theta_i = atan2(pose - O_i) -
    atan2(l_i)``, so that four equations remain: ``|l_i| = |pose - O_i|`` and ``n1 + n2 = F``
    (the forces turned by ``theta_i``), dimensionless.

    Returns
    -------
    callable
        ``system(z) -> (f, J)``, shapes ``(batch, 4)`` and ``(batch, 4, 4)`` (unchecked, as
        :func:`forward_system`'s).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> f, J = inverse_system(TABLE7, eq.pose[0])(eq.x[:1])
    >>> bool(np.abs(f).max() < 1e-12), J.shape
    (True, (1, 4, 4))
    """
    assembly.check_type(mech, Mechanism)
    pose = _validate.array(pose, "pose", shape=(2,))
    family = ClampedRods(mech.EI, mech.L, assembly.check_modes(modes, 2))
    f_scale = mech.EI / mech.L ** 2
    reach = np.hypot(*(pose - mech.origins).T)
    local = np.zeros(2)

    def system(z):
        tip, force, _, d_chart, _ = family(z, local, local)       # in the clamps' frames
        length = np.hypot(tip[..., 0], tip[..., 1])
        theta = motor_angles(mech, pose, tip)
        c, s = np.cos(theta), np.sin(theta)
        n = np.stack((c * force[..., 0] - s * force[..., 1],
                      s * force[..., 0] + c * force[..., 1]), axis=-1)
        G = np.concatenate(((length - reach) / mech.L, (n.sum(axis=1) - mech.force) / f_scale),
                           -1)
        J_tip, J_force = d_chart[..., 0:2, :], d_chart[..., 2:4, :]          # (b, r, 2, 2)
        tip = tip[..., None]
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
            J[:, 2:4, 2 * r:2 * r + 2] = d_n[:, r] / f_scale
        return G, J

    return system


def motor_angles(mech: Mechanism, pose: np.ndarray, tip: np.ndarray) -> np.ndarray:
    """The motor angles ``(..., 2)`` that turn rods whose tips are ``tip`` (..., 2, 2) in their
    clamps' frames onto the end effector ``pose`` (2,), in ``(-pi, pi]`` (unchecked: a
    kernel of :func:`inverse_system` and :func:`inverse`).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7
    >>> turn = motor_angles(TABLE7, np.array([0.0, 0.5]), np.array([[0.5, 0.0], [0.5, 0.0]]))
    >>> np.degrees(turn).round(3).tolist()
    [59.036, 120.964]
    """
    to_pose = pose - mech.origins
    turn = np.arctan2(to_pose[:, 1], to_pose[:, 0]) - np.arctan2(tip[..., 1], tip[..., 0])
    return np.angle(np.exp(1j * turn))


def sample(rng: np.random.Generator, m: int) -> np.ndarray:
    """Random starts: force directions uniform in (0, 2 pi), ``t`` uniform in
    ``(-START_T, START_T)`` (every sign branch of both rods); the search checks ``rng`` and
    ``m``.

    Examples
    --------
    >>> z = sample(np.random.default_rng(0), 3)
    >>> z.shape, bool(in_chart(z).all())
    ((3, 4), True)
    """
    psi = rng.uniform(0.0, 2.0 * np.pi, (m, 2))
    t = rng.uniform(-START_T, START_T, (m, 2))
    return np.stack((psi[:, 0], t[:, 0], psi[:, 1], t[:, 1]), axis=-1)


def _equilibria(mech, theta, pose, modes, found, nfev, njev, inputs, given_pose):
    """Classify the roots (chart) of a search at motor angles ``theta`` (n, 2)."""
    z = found.x
    n = len(z)
    _, force, moment, _, _ = rods(mech, theta, z, modes, jacobian=False)
    index, cross, own = np.zeros((0, 2), int), np.zeros(0, int), np.zeros((0, 2), int)
    if n:
        index = stabilities(mech, theta, z, modes)
        cross, own = crossings(mech, theta, z, modes)
    return assembly.Equilibria(
        x=z, status=np.full(n, "converged"), iterations=njev, nfev=nfev, njev=njev,
        message=assembly.equilibria_message(n, found), inputs=inputs, pose=given_pose,
        modes=tuple(int(m) for m in modes), solutions=thesis_from_chart(z), forces=force,
        clamp_moments=moment, index=index, rods_cross=cross, self_cross=own,
        body_cross=np.zeros(n, dtype=int), strain=strain(mech, theta, z, modes),
        strain_limit=mech.strain_limit, search=found)


def in_chart_rows(z: np.ndarray) -> np.ndarray:
    """:func:`~mechnum.rods.in_chart` unchecked, for a solver's iterates (finite rows of four).

    Examples
    --------
    >>> in_chart_rows(np.array([[1.0, 0.5, 2.0, -0.5], [1.0, 0.0, 2.0, 0.5]])).tolist()
    [True, False]
    """
    psi, t = z[:, 0::2], z[:, 1::2]
    return ((psi > 0) & (psi < 2.0 * np.pi) & (t != 0) & (np.abs(t) <= T_MAX)).all(axis=1)


def search_roots(mech: Mechanism, theta: np.ndarray, modes: ArrayLike, n_starts: int,
                 check: int, rng: np.random.Generator | int | None) -> tuple:
    """The search of :func:`forward` alone, its roots unclassified: ``(found, nfev, njev)``.
    Every start of it and of its check in one damped Newton over all of them
    (:func:`mechnum.newton.solve_all`), on the compiled closed form
    (:class:`mechnum.rods.MeetingRods`: residual and Jacobian in one call).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> found, nfev, njev = search_roots(TABLE7, TABLE7_THETA, (1, 1), 200, 10, 0)
    >>> len(found.x), found.complete
    (3, True)
    """
    assembly.check_type(mech, Mechanism)
    theta = _validate.array(theta, "theta", shape=(2,))
    rods = MeetingRods(mech.EI, mech.L, mech.origins, assembly.check_modes(modes, 2), mech.force)

    def both(z):
        return rods.meeting(theta, z)

    return assembly.search(both, sample, domain=in_chart_rows, n_starts=n_starts, check=check,
                           rng=rng, tol=SEARCH_TOL, maxiter=SEARCH_MAXITER)


def forward(mech: Mechanism, theta: ArrayLike, *, modes: ArrayLike = (1, 1),
            n_starts: int = N_STARTS, check: int = CHECK,
            rng: np.random.Generator | int | None = None) -> assembly.Equilibria:
    """Every equilibrium of the mechanism at the motor angles ``theta`` with the given modes.

    Damped Newton on the closed form (analytic Jacobian) from ``n_starts`` random starts, then
    ``check`` times as many new starts (:func:`mechnum.newton.solve_all`). The starts cover
    the four sign branches of ``(t1, t2)`` (the study's signs of ``k_rel``); an iterate may
    step across ``t = 0`` into another branch, where the residual jumps: Newton then simply
    goes on from there, and every root it reports satisfies the equations. Each equilibrium
    is then classified: its stability (the index of its second variation at two
    resolutions), the crossings of the rods and their bending strain. Rods under forces beyond
    the chart's range (``T_MAX`` of :mod:`mechnum.rods`, ``~(300 mode)**2 EI / L**2``) are not
    sought.

    Parameters
    ----------
    mech : Mechanism
    theta : array_like, shape (2,)
        Motor angles (rad).
    modes : (int, int), optional
        Buckling modes of rod 1 and rod 2 (inflections on ``0 < s <= L``).
    n_starts : int, optional
        Starts of the search, at most 100,000.
    check : int, optional
        Size of the completeness check, in multiples of ``n_starts`` (0: none; at most 100).
    rng : numpy.random.Generator or int, optional
        Random generator or seed (a non-negative integer) of the starts.

    Returns
    -------
    mechnum.mechanisms.Equilibria
        ``n >= 0`` equilibria, sorted by ``psi1``, their chart ``x``; the ``inputs`` are
        ``theta``, each ``pose`` the end effector; an empty result when none is found.

    Raises
    ------
    ValueError
        If ``mech`` is no :class:`Mechanism`, ``theta`` not two finite angles, ``modes`` not
        two integers ``>= 1``, or a size or ``rng`` invalid.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> np.round(eq.solutions, 6).tolist()[0], eq.stable.tolist(), eq.search.complete
    ([1.962541, -0.004391, 4.811041, 0.943413], [True, True, True], True)
    """
    found, nfev, njev = search_roots(mech, theta, modes, n_starts, check, rng)
    theta, modes = np.asarray(theta, dtype=float), assembly.check_modes(modes, 2)
    pose = rods(mech, theta, found.x, modes, jacobian=False)[0][:, 0]
    return _equilibria(mech, np.broadcast_to(theta, (len(pose), 2)), pose, modes, found, nfev,
                       njev, theta, pose)


def inverse(mech: Mechanism, pose: ArrayLike, *, modes: ArrayLike = (1, 1),
            n_starts: int = 200, check: int = 10,
            rng: np.random.Generator | int | None = None) -> assembly.Equilibria:
    """Every equilibrium of the mechanism with its end effector at ``pose``, with the given
    modes.

    The inverse problem: the motor angles and the rods that hold the end effector against the
    load, found as :func:`forward` finds the direct problem's, on :func:`inverse_system`.

    Parameters
    ----------
    mech, modes, n_starts, check, rng
        As in :func:`forward`.
    pose : array_like, shape (2,)
        The end effector (m).

    Returns
    -------
    mechnum.mechanisms.Equilibria
        ``inputs`` of shape (n, 2), the motor angles of each equilibrium, in ``(-pi, pi]``;
        ``pose`` as given.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> back = inverse(TABLE7, eq.pose[2], rng=0)
    >>> bool(np.abs(back.inputs - TABLE7_THETA).max(axis=1).min() < 1e-10)
    True
    """
    system = inverse_system(mech, pose, modes)
    pose, modes = np.asarray(pose, dtype=float), assembly.check_modes(modes, 2)
    found, nfev, njev = assembly.search(system, sample, domain=in_chart, n_starts=n_starts,
                                        check=check, rng=rng, tol=SEARCH_TOL,
                                        maxiter=SEARCH_MAXITER)
    tip = ClampedRods(mech.EI, mech.L, modes)(found.x, np.zeros(2), np.zeros(2),
                                               jacobian=False)[0]
    theta = motor_angles(mech, pose, tip)
    return _equilibria(mech, theta, pose, modes, found, nfev, njev, theta, pose)
