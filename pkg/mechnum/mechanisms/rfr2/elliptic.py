"""The direct problem in closed form: every equilibrium of given motor angles and modes.

:func:`~mechnum.mechanisms.rfr2.forward_system` is the study's four equations (its 11.3.2: both
tips at one point, ``n1 + n2 = F``) in the chart, with their analytic Jacobian;
:func:`~mechnum.mechanisms.rfr2.residual` the same residual in metres and newtons.
:func:`~mechnum.mechanisms.rfr2.forward_elliptic` finds every equilibrium by Newton from many
starts (:func:`mechnum.newton.solve_all`), with the evidence that there are no more, and
classifies each (:mod:`~mechnum.mechanisms.rfr2.analysis`).
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate, newton
from mechnum.mechanisms.rfr2.analysis import crossings, stability
from mechnum.mechanisms.rfr2.model import _in_chart, _modes, _rods, _theta
from mechnum.rods import regular
from mechnum.rods.stability import TwoResolutions

# Starts of the all-solutions search are drawn with |t| <= 0.985 (forces up to ~(q/2)**2 =
# 1000 EI / L**2, far beyond what the study's mechanism can balance); iterates may go on to T_MAX.
START_T = 0.985


def _scales(mech):
    """Scales of the residual rows: positions by ``L``, forces by ``EI / L**2``."""
    return np.array([mech.L, mech.L, mech.EI / mech.L ** 2, mech.EI / mech.L ** 2])


def forward_system(mech, theta, modes=(1, 1)):
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
    theta, modes = _theta(theta), _modes(modes)
    scale = _scales(mech)

    def fun(z):
        return _residual(mech, modes, z, theta) / scale

    def jac(z):
        d = _rods(mech, modes, z, theta)[3]
        J = np.concatenate((np.concatenate((d[:, 0, :2], -d[:, 1, :2]), axis=-1),
                            np.concatenate((d[:, 0, 2:], d[:, 1, 2:]), axis=-1)), axis=1)
        return J / scale[:, None]

    return fun, jac


def residual(mech, theta, chart, modes=(1, 1)):
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
    z = _validate.array(chart, "chart")
    theta = _validate.array(theta, "theta")
    if z.shape[-1:] != (4,) or theta.shape[-1:] != (2,):
        raise ValueError(f"chart must be (..., 4) and theta (..., 2), got {z.shape} and "
                         f"{theta.shape}")
    shape = np.broadcast_shapes(z.shape[:-1], theta.shape[:-1])
    z, theta = np.broadcast_to(z, shape + (4,)), np.broadcast_to(theta, shape + (2,))
    return _residual(mech, _modes(modes), z, theta)


def _residual(mech, modes, z, theta):
    """The kernel of :func:`residual` (and, scaled, of :func:`forward_system`)."""
    tip, force = _rods(mech, modes, z, theta)[:2]
    return np.concatenate((tip[..., 0, :] - tip[..., 1, :], force.sum(axis=-2) - mech.force),
                          axis=-1)


@dataclass(frozen=True)
class Equilibria(TwoResolutions):
    """Every equilibrium that :func:`forward_elliptic` found, and how well it looked.

    Attributes
    ----------
    theta : ndarray, shape (2,)
        The motor angles (rad).
    modes : tuple of int
        The buckling modes of rod 1 and rod 2.
    solutions : ndarray, shape (n, 4)
        ``(psi1, k_rel1, psi2, k_rel2)``, the study's convention (its Table 7).
    chart : ndarray, shape (n, 4)
        ``(psi1, t1, psi2, t2)``, the solver's regular coordinates.
    P : ndarray, shape (n, 2)
        End-effector positions (m).
    forces : ndarray, shape (n, 2, 2)
        Force on each rod at its tip (N); ``forces.sum(axis=1)`` is the external force.
    clamp_moments : ndarray, shape (n, 2)
        Moments at the clamps (N m): what the motors hold.
    index : ndarray of int, shape (n, 2)
        Negative eigenvalues of the second variation with ``SEGMENTS`` segments per rod
        (coarse, fine): 0 is stable.
    rods_cross : ndarray of int, shape (n,)
        How many times the two rods cross each other.
    self_cross : ndarray of int, shape (n, 2)
        How many times each rod crosses itself.
    search : mechnum.newton.RootSet
        The search and its completeness evidence: ``roots`` (chart), ``hits``, ``n_starts``,
        ``n_check``, ``new_in_check``, ``complete``.
    """

    theta: np.ndarray
    modes: tuple
    solutions: np.ndarray
    chart: np.ndarray
    P: np.ndarray
    forces: np.ndarray
    clamp_moments: np.ndarray
    index: np.ndarray
    rods_cross: np.ndarray
    self_cross: np.ndarray
    search: newton.RootSet

    @property
    def buildable(self):
        """ndarray of bool, shape (n,): stable, and no rod crosses itself or the other."""
        return self.stable & (self.rods_cross == 0) & (self.self_cross.sum(axis=1) == 0)


def _sample(rng, m):
    """Random starts: force directions uniform in (0, 2 pi), ``t`` uniform in
    ``(-START_T, START_T)`` (every sign branch of both rods)."""
    psi = rng.uniform(0.0, regular.TWO_PI, (m, 2))
    t = rng.uniform(-START_T, START_T, (m, 2))
    return np.stack((psi[:, 0], t[:, 0], psi[:, 1], t[:, 1]), axis=-1)


def forward_elliptic(mech, theta, modes=(1, 1), *, n_starts=200, check=10, rng=None):
    """Every equilibrium of the mechanism at the motor angles ``theta`` with the given modes.

    Damped Newton on the closed form (analytic Jacobian) from ``n_starts`` random starts, then
    ``check`` times as many new starts (:func:`mechnum.newton.solve_all`). The starts cover
    the four sign branches of ``(t1, t2)`` (the study's signs of ``k_rel``); an iterate may
    step across ``t = 0`` into another branch, where the residual jumps: Newton then simply
    goes on from there, and every root it reports satisfies the equations. Each equilibrium
    is then classified: stability (:func:`stability`) and crossings of the rods
    (:func:`crossings`). Rods under forces beyond the chart's range (``T_MAX`` of
    :mod:`mechnum.rods.regular`, ``~(300 mode)**2 EI / L**2``) are not sought.

    Parameters
    ----------
    mech : Mechanism
    theta : array_like, shape (2,)
        Motor angles (rad).
    modes : (int, int), optional
        Buckling modes of rod 1 and rod 2 (inflections on ``0 < s <= L``).
    n_starts : int, optional
        Starts of the search (``check`` times as many again for the completeness check).
    check : int, optional
        Size of the completeness check, in multiples of ``n_starts`` (0: none).
    rng : numpy.random.Generator or int, optional
        Random generator or seed of the starts.

    Returns
    -------
    Equilibria
        ``n >= 0`` equilibria, sorted by ``psi1``; an empty result when none is found.

    Raises
    ------
    ValueError
        If ``theta`` is not two finite angles or ``modes`` not two integers ``>= 1``.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> np.round(eq.solutions, 6).tolist()[0], eq.stable.tolist(), eq.search.complete
    ([1.962541, -0.004391, 4.811041, 0.943413], [True, True, True], True)
    """
    theta, modes = _theta(theta), _modes(modes)
    fun, jac = forward_system(mech, theta, modes)
    found = newton.solve_all(fun, _sample, jac, n_starts=n_starts, check=check, rng=rng,
                             domain=_in_chart, tol=1e-12, maxiter=40)
    z = found.roots
    tip, force, moment = _rods(mech, modes, z, theta)[:3]
    index, cross, self_cross = np.zeros((0, 2), int), np.zeros(0, int), np.zeros((0, 2), int)
    if len(z):
        index = np.array([stability(mech, theta, zi, modes) for zi in z])
        cross, self_cross = crossings(mech, theta, z, modes)
    k_rel = regular.k_rel_from_t(z[:, 0::2], z[:, 1::2]) if len(z) else np.zeros((0, 2))
    solutions = np.stack((z[:, 0], k_rel[:, 0], z[:, 2], k_rel[:, 1]), axis=-1)
    return Equilibria(theta, tuple(int(m) for m in modes), solutions, z, tip[:, 0], force,
                      moment, index, cross, self_cross, found)
