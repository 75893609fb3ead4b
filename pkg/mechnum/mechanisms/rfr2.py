"""The flexible 2RFR mechanism of the flexible-mechanisms study (001: 11.3, 13.2, Annex II 3).

Two motors on the ground, at ``O1`` and ``O2``, turn the clamped ends of two flexible rods to the
angles ``theta = (theta1, theta2)``; the rods' other ends are pinned together at the end effector
``P``, which carries an external force ``F``. Each rod is a clamped-pinned elastica
(:mod:`mechnum.rods`), and the mechanism is in equilibrium when

* both tips are at ``P``: ``tip1 = tip2 = P``;
* the forces that the rods receive at their tips carry the load: ``n1 + n2 = F`` (the study's
  (92) and (98), and its code; its (104) prints ``+ F`` on the other side, the wrong sign).

Three formulations, as in the study, and what this module adds to them:

* **Closed form** (the study's 11.3.2): each rod is its force direction ``psi_i`` in the rod's
  clamp frame and a shape parameter, in the regular chart ``t_i`` of :mod:`mechnum.rods.regular`
  (the study's ``k_rel`` is singular at both ends of its range). The four unknowns
  ``(psi1, t1, psi2, t2)`` satisfy four equations, ``tip1 = tip2`` and ``n1 + n2 = F``, with an
  analytic Jacobian. :func:`forward_elliptic` finds every equilibrium of given buckling modes
  (:func:`mechnum.newton.solve_all`) with the evidence that there are no more, its stability
  (:mod:`mechnum.rods.stability`) and whether the rods cross (:mod:`mechnum.rods.crossing`).
* **RK4 shooting** (the study's 11.3.1): :func:`forward_shooting` and :func:`inverse_shooting`,
  the study's unknowns (its (99) and (102)) and equations (98), with complex-step Jacobians.
* **Continuation**: :func:`inverse_path` and :func:`forward_path` follow one equilibrium along
  a path of end-effector positions or of motor angles (the study's trajectories, :func:`path`),
  and :func:`forward_map` over a grid of motor angles; :func:`jacobians` gives the determinants
  whose zeros are the singularities.

The residual is dimensionless: positions over ``L``, forces over ``EI / L**2``.
"""

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from mechnum import _validate, newton, rods
from mechnum.errors import GeometryError, MechnumError, UnreachablePoseError
from mechnum.rods import crossing, regular
from mechnum.rods.stability import constrained_eigenvalues, constrained_index, rod_block

LENGTH = 1.0                                   # m, both rods (Annex II 3.4)
YOUNG = 210e9                                  # Pa
DIAMETER = 1.5e-3                              # m
EI = YOUNG * 0.25 * np.pi * (0.5 * DIAMETER) ** 4   # N m^2 (I = pi r^4 / 4)
STUDY_NODES = 41                               # RK4 nodes of the study's shooting programs
# Shooting converges when the dimensionless residual (98) is below this: round-off of the
# O(1) positions and forces is ~1e-15; 1e-12 leaves a margin of a thousand.
SHOOTING_TOL = 1e-12
# Starts of the all-solutions search are drawn with |t| <= 0.985 (forces up to ~(q/2)**2 =
# 1000 EI / L**2, far beyond what the study's mechanism can balance); iterates may go on to T_MAX.
START_T = 0.985
# The index of the second variation is counted with 200 and 400 segments per rod (O(N) work):
# eigenvalues move by O(h**2) between them, so an index settled by both is the continuous one
# unless an eigenvalue lies within ~1e-3 of zero (see mechnum.rods.stability).
SEGMENTS = (200, 400)
# Segments for the eigenvalues themselves (a dense eigenproblem): enough for 2 digits.
EIGEN_SEGMENTS = 64
# Relative tolerance of the independent check by solve_ivp (DOP853 accepts down to 2.2e-14):
# integrating a rod in tension from its clamp amplifies errors by ~cosh(L sqrt(R / EI)), so
# the near-tension equilibria need the tightest tolerance to show their tips within 1e-11 m.
IVP_RTOL = 3e-14
# Nodes of the rods' polylines for the crossing test and the drawings: a chord of L / 200 is
# within ~1e-5 L of the rods of this chapter (curvatures below ~10 / L).
SHAPE_NODES = 201


@dataclass(frozen=True)
class Mechanism:
    """A 2RFR mechanism: two motors, two rods, one external force on the end effector.

    Attributes
    ----------
    origins : ndarray, shape (2, 2)
        Motor (clamp) positions ``O1``, ``O2`` (m).
    force : ndarray, shape (2,)
        External force on the end effector (N).
    L : float
        Length of each rod (m).
    EI : float
        Bending stiffness of each rod (N m^2).

    Raises
    ------
    ValueError
        If an attribute is not finite or has the wrong shape.
    GeometryError
        If ``L`` or ``EI`` is not positive, or the motors are ``2 L`` or more apart (the rods
        cannot meet).

    Examples
    --------
    >>> TABLE7.origins.tolist(), TABLE7.force.tolist(), round(TABLE7.EI, 7)
    ([[-0.3, 0.0], [0.3, 0.0]], [0.3, -0.1], 0.052186)
    """

    origins: np.ndarray
    force: np.ndarray = field(default_factory=lambda: np.zeros(2))
    L: float = LENGTH
    EI: float = EI

    def __post_init__(self):
        object.__setattr__(self, "origins", _validate.array(self.origins, "origins",
                                                            shape=(2, 2)))
        object.__setattr__(self, "force", _validate.array(self.force, "force", shape=(2,)))
        for name in ("L", "EI"):
            value = _validate.scalar(getattr(self, name), name)
            if value <= 0:
                raise GeometryError(f"{name} must be positive, got {value!r}")
            object.__setattr__(self, name, value)
        gap = float(np.hypot(*(self.origins[1] - self.origins[0])))
        if gap >= 2 * self.L:
            raise GeometryError(f"the motors are {gap:g} m apart: rods of length {self.L:g} m "
                                f"cannot meet")


TABLE7 = Mechanism(origins=[[-0.3, 0.0], [0.3, 0.0]], force=[0.3, -0.1])
"""The study's example of its Table 7 (13.2.1, Annex II 3.4): motor 2 at ``(0.3, 0)``, where its
code puts it and where the published solutions belong (the text says ``(0, 0.3)``)."""
TABLE7_THETA = np.radians([40.0, 60.0])
"""The motor angles of Table 7 (rad)."""


def _modes(modes):
    modes = _validate.array(modes, "modes", shape=(2,))
    if np.any(modes < 1) or np.any(modes != np.round(modes)):
        raise ValueError(f"modes must be two integers >= 1, got {modes.tolist()}")
    return modes


def _theta(theta, shape=(2,)):
    return _validate.array(theta, "theta", shape=shape)


# --- the closed form ------------------------------------------------------------------------

def _rods(mech, modes, z, theta):
    """Both rods of the chart points ``z`` (..., 4) at motor angles ``theta`` (..., 2), global:
    tips and forces (..., 2 rods, 2), clamp moments (..., 2), and the derivatives of
    ``(tip, force)`` in the chart (..., 2, 4, 2) and in the motor angle (..., 2, 4)."""
    z = np.asarray(z, dtype=float)
    if not np.all(_in_chart(z.reshape(-1, 4))):
        raise ValueError("chart points (psi1, t1, psi2, t2) need 0 < psi < 2 pi and "
                         f"0 < |t| <= {regular.T_MAX:.6f}, got {_validate._shown(z)}")
    rod = regular._closed_form(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], modes, True)
    tip, force, d_chart, d_angle = regular.place(rod, mech.origins, theta)
    return tip, force, rod.clamp_moment, d_chart, d_angle


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
    >>> fun, jac = forward_system(TABLE7, TABLE7_THETA)
    >>> z = chart_from_thesis([[5.304574, 0.969830, 1.825456, -0.992135]])
    >>> fun(z).shape, jac(z).shape, bool(np.abs(fun(z)).max() < 3e-4)
    ((1, 4), (1, 4, 4), True)
    """
    theta, modes = _theta(theta), _modes(modes)
    scale = _scales(mech)

    def fun(z):
        tip, force = _rods(mech, modes, z, theta)[:2]
        return np.concatenate((tip[:, 0] - tip[:, 1], force.sum(axis=1) - mech.force),
                              axis=-1) / scale

    def jac(z):
        d = _rods(mech, modes, z, theta)[3]
        J = np.concatenate((np.concatenate((d[:, 0, :2], -d[:, 1, :2]), axis=-1),
                            np.concatenate((d[:, 0, 2:], d[:, 1, 2:]), axis=-1)), axis=1)
        return J / scale[:, None]

    return fun, jac


def _in_chart(z):
    """Whether chart points ``(psi1, t1, psi2, t2)`` lie where the chart is defined."""
    psi, t = z[:, 0::2], z[:, 1::2]
    return np.all((psi > 0) & (psi < regular.TWO_PI) & (t != 0)
                  & (np.abs(t) <= regular.T_MAX), axis=1)


@dataclass(frozen=True)
class Equilibria:
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
    def stable(self):
        """ndarray of bool, shape (n,): stable at both resolutions."""
        return (self.index == 0).all(axis=1)

    @property
    def settled(self):
        """ndarray of bool, shape (n,): both resolutions give the same index."""
        return self.index[:, 0] == self.index[:, 1]

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


def chart_from_thesis(solutions):
    """The chart ``(psi1, t1, psi2, t2)`` of the study's ``(psi1, k_rel1, psi2, k_rel2)``.

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> np.round(z, 6).tolist()
    [5.304574, 0.880277, 1.825456, -0.906868]
    """
    s = _validate.array(solutions, "solutions")
    if s.shape[-1] != 4:
        raise ValueError(f"solutions must have a last axis of 4, got shape {s.shape}")
    t = regular.t_from_k_rel(s[..., 0::2], s[..., 1::2])
    return np.stack((s[..., 0], t[..., 0], s[..., 2], t[..., 1]), axis=-1)


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
    tip, force = _rods(mech, _modes(modes), z, theta)[:2]
    return np.concatenate((tip[..., 0, :] - tip[..., 1, :], force.sum(axis=-2) - mech.force),
                          axis=-1)


# --- stability, crossings, shapes ------------------------------------------------------------

def _clamp_states(mech, theta, chart, modes):
    tip, force, moment = _rods(mech, _modes(modes), np.asarray(chart, float), _theta(theta))[:3]
    return tip, force, moment


def _angles(mech, theta, chart, modes, nodes):
    """Both rods of equilibria sampled at ``nodes`` equally spaced points (closed form,
    :func:`mechnum.rods.regular.shape`, local frames) and their global tangent angles,
    shape (..., 2, nodes)."""
    z = np.asarray(chart, dtype=float)
    rod = regular.shape(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], _modes(modes),
                        nodes=nodes)
    return rod, rod.theta + _validate.array(theta, "theta")[..., None]


def _blocks(mech, theta, chart, modes, segments):
    """The two rods' discretised second variations, and the constraint ``tip1 = tip2``."""
    force = _clamp_states(mech, theta, _validate.array(chart, "chart", shape=(4,)), modes)[1]
    angles = _angles(mech, theta, chart, modes, 2 * segments + 1)[1][:, 1::2]
    blocks = [rod_block(mech.EI, mech.L, angles[i], force[i]) for i in range(2)]
    return blocks, np.concatenate((blocks[0].tip_gradient, -blocks[1].tip_gradient), axis=1)


def stability(mech, theta, chart, modes=(1, 1), *, segments=SEGMENTS):
    """Index of one equilibrium: the negative eigenvalues of its second variation.

    Motors locked, dead load ``F`` on ``P``: the Hessian of the Lagrangian
    ``U1 + U2 - F . P + mu . (tip1 - tip2)`` on the tangent space of ``tip1 = tip2``
    (:mod:`mechnum.rods.stability`; the multiplier ``mu`` is the force ``n2``), counted by
    :func:`mechnum.rods.stability.constrained_index` at each resolution.

    Parameters
    ----------
    mech, theta, modes
        As in :func:`forward_elliptic`.
    chart : array_like, shape (4,)
        The equilibrium, ``(psi1, t1, psi2, t2)``.
    segments : tuple of int, optional
        Resolutions (segments per rod).

    Returns
    -------
    tuple of int
        The index at each resolution (0: stable).

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> stability(TABLE7, TABLE7_THETA, z)
    (0, 0)
    """
    theta = _theta(theta)
    index = []
    for n in segments:
        blocks, constraints = _blocks(mech, theta, chart, modes, n)
        index.append(constrained_index(blocks, constraints))
    return tuple(index)


def eigenvalues(mech, theta, chart, modes=(1, 1), *, segments=EIGEN_SEGMENTS):
    """The eigenvalues of an equilibrium's second variation, ascending, dimensionless.

    Dense (:func:`mechnum.rods.stability.constrained_eigenvalues`), divided by
    ``h EI / L**2``: they approximate those of the continuous second variation, to about
    ``(segments / 64)**-2`` percent of the larger ones.

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> np.round(eigenvalues(TABLE7, TABLE7_THETA, z)[:2], 0).tolist()
    [7.0, 28.0]
    """
    theta = _theta(theta)
    blocks, constraints = _blocks(mech, theta, chart, modes, segments)
    hessian = np.zeros((2 * segments, 2 * segments))
    hessian[:segments, :segments] = blocks[0].hessian
    hessian[segments:, segments:] = blocks[1].hessian
    return constrained_eigenvalues(hessian, constraints) / (blocks[0].h * mech.EI / mech.L ** 2)


def shapes(mech, theta, chart, modes=(1, 1), *, nodes=SHAPE_NODES):
    """The two rods of equilibria as polylines (closed form, :func:`mechnum.rods.regular.shape`).

    Parameters
    ----------
    mech, modes
        As in :func:`forward_elliptic`.
    theta : array_like, shape (..., 2)
        Motor angles (rad), broadcast with ``chart``.
    chart : array_like, shape (..., 4)
        Equilibria ``(psi1, t1, psi2, t2)``.
    nodes : int, optional
        Points per rod.

    Returns
    -------
    x, y : ndarray, shape (..., 2, nodes)
        Coordinates of the rods (m), from the clamp to the tip.

    Examples
    --------
    >>> x, y = shapes(TABLE7, TABLE7_THETA, chart_from_thesis([5.304574, 0.969830,
    ...                                                        1.825456, -0.992135]))
    >>> gap = np.hypot(x[0, -1] - x[1, -1], y[0, -1] - y[1, -1])   # the printed digits
    >>> x.shape, np.round([x[0, 0], y[0, 0]], 12).tolist(), bool(gap < 1e-5)
    ((2, 201), [-0.3, 0.0], True)
    """
    rod = _angles(mech, theta, chart, modes, nodes)[0]
    theta = _validate.array(theta, "theta")[..., None]
    c, s = np.cos(theta), np.sin(theta)
    return (mech.origins[:, 0, None] + c * rod.x - s * rod.y,
            mech.origins[:, 1, None] + s * rod.x + c * rod.y)


def crossings(mech, theta, chart, modes=(1, 1)):
    """Crossings of the rods of equilibria: of each other, and of each with itself.

    Returns
    -------
    rods_cross : ndarray of int, shape (n,)
    self_cross : ndarray of int, shape (n, 2)

    Examples
    --------
    >>> z = chart_from_thesis([[5.304574, 0.969830, 1.825456, -0.992135],
    ...                        [1.962541, -0.004391, 4.811041, 0.943413]])
    >>> [a.tolist() for a in crossings(TABLE7, TABLE7_THETA, z)]
    [[0, 1], [[0, 0], [0, 0]]]
    """
    z = np.atleast_2d(_validate.array(chart, "chart"))
    x, y = shapes(mech, theta, z, modes)
    mutual = np.array([crossing.mutual_crossings(x[i, 0], y[i, 0], x[i, 1], y[i, 1],
                                                 shared_tip=True) for i in range(len(z))])
    own = np.array([[crossing.self_crossings(x[i, r], y[i, r]) for r in range(2)]
                    for i in range(len(z))])
    return mutual, own.reshape(len(z), 2)


def verify(mech, theta, chart, modes=(1, 1), *, rtol=IVP_RTOL):
    """Check equilibria independently: integrate each rod from its clamp with scipy.

    Each rod is integrated by ``solve_ivp`` (DOP853, relative tolerance ``rtol``) from its
    clamp, with the clamp moment and the tip force of the closed form, and compared with the
    closed form's end effector.

    Returns
    -------
    tip_error : ndarray, shape (n, 2)
        Distance from each integrated tip to ``P`` (m).
    tip_moment : ndarray, shape (n, 2)
        Moment at each integrated tip (N m); zero at a pin.
    inflections : ndarray of int, shape (n, 2)
        Zeros of the moment on ``0 < s <= L`` (sign changes on a fine grid, the tip's
        included): the mode.

    Examples
    --------
    >>> err, moment, inflections = verify(TABLE7, TABLE7_THETA, forward_elliptic(
    ...     TABLE7, TABLE7_THETA, rng=0).chart)
    >>> bool(err.max() < 1e-10), bool(np.abs(moment).max() < 1e-10), inflections.tolist()
    (True, True, [[1, 1], [1, 1], [1, 1]])
    """
    z = np.atleast_2d(_validate.array(chart, "chart"))
    theta = _theta(theta)
    tip, force, moment = _clamp_states(mech, theta, z, modes)
    err, tip_m, infl = (np.zeros((len(z), 2)), np.zeros((len(z), 2)),
                        np.zeros((len(z), 2), int))
    s = np.linspace(0.0, mech.L, 4001)
    for i in range(len(z)):
        for r in range(2):
            n = force[i, r]

            def rhs(_, y, n=n):
                return [np.cos(y[2]), np.sin(y[2]), y[3] / mech.EI,
                        n[0] * np.sin(y[2]) - n[1] * np.cos(y[2])]

            sol = solve_ivp(rhs, (0.0, mech.L), [*mech.origins[r], theta[r], moment[i, r]],
                            method="DOP853", rtol=rtol, atol=rtol * mech.L, dense_output=True)
            end = sol.y[:, -1]
            err[i, r] = np.hypot(*(end[:2] - tip[i, 0]))
            tip_m[i, r] = end[3]
            m = sol.sol(s)[3][:-1]         # the tip's zero is counted apart
            infl[i, r] = int(np.sum(np.sign(m[1:]) != np.sign(m[:-1]))) + 1
    return err, tip_m, infl


# --- RK4 shooting: the study's (98) with its unknowns (99) and (102) ---------------------------

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


# --- the full system: Jacobians, singularities, continuation ------------------------------

def _full(mech, modes, z, theta, P):
    """``G = ((tip1 - P) / L, (tip2 - P) / L, (n1 + n2 - F) L**2 / EI)`` (..., 6) and its
    Jacobian (..., 6, 8) with respect to ``(psi1, t1, psi2, t2, theta1, theta2, x_P, y_P)``."""
    tip, force, _, d_chart, d_angle = _rods(mech, modes, z, theta)
    L, f = mech.L, mech.EI / mech.L ** 2
    G = np.concatenate(((tip[..., 0, :] - P) / L, (tip[..., 1, :] - P) / L,
                        (force.sum(axis=-2) - mech.force) / f), axis=-1)
    D = np.zeros(G.shape + (8,))
    for r in range(2):
        rows = slice(2 * r, 2 * r + 2)
        D[..., rows, 2 * r:2 * r + 2] = d_chart[..., r, :2, :] / L
        D[..., 4:6, 2 * r:2 * r + 2] = d_chart[..., r, 2:, :] / f
        D[..., rows, 4 + r] = d_angle[..., r, :2] / L
        D[..., 4:6, 4 + r] = d_angle[..., r, 2:] / f
        D[..., rows, 6:8] = -np.eye(2) / L
    return G, D


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


_FK = [0, 1, 2, 3, 6, 7]       # unknowns of the direct problem: the chart and P
_IK = [0, 1, 2, 3, 4, 5]       # of the inverse problem: the chart and theta


@dataclass(frozen=True)
class Jacobians:
    """The Jacobians of equilibria (:func:`jacobians`).

    Attributes
    ----------
    det_fk : ndarray
        ``det dG / d(chart, P)``: zero where the direct problem is singular (the motors
        locked, ``P`` can still move: the mechanism gains a freedom).
    det_ik : ndarray
        ``det dG / d(chart, theta)``: zero where the inverse problem is singular (``P`` cannot
        move in some direction, whatever the motors do: the edge of the workspace).
    dP_dtheta : ndarray, shape (..., 2, 2)
        How ``P`` moves with the motors (m/rad): the study's code's ``FK_Jacobian``. Its
        determinant is ``L**2 det_ik / det_fk``, and the code's ``IK_Jacobian`` is its inverse.
    """

    det_fk: np.ndarray
    det_ik: np.ndarray
    dP_dtheta: np.ndarray


def jacobians(mech, theta, chart, modes=(1, 1)):
    """Determinants of the direct and inverse problems of equilibria, and ``dP / dtheta``.

    ``G`` is the dimensionless residual (tips to ``P`` over ``L``, forces over
    ``EI / L**2``); the determinants are those of its Jacobian with respect to the unknowns
    of each problem (the chart of the rods and ``P``, or the chart and ``theta``), whose
    zeros do not depend on how the rods are parametrised (the study's 8 x 8 shooting
    Jacobians of (98) vanish at the same places).

    Examples
    --------
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> J = jacobians(TABLE7, TABLE7_THETA, eq.chart)
    >>> ratio = np.linalg.det(J.dP_dtheta) * J.det_fk / (TABLE7.L ** 2 * J.det_ik)
    >>> bool(np.allclose(ratio, 1.0)), np.sign(J.det_fk).tolist()
    (True, [-1.0, 1.0, -1.0])
    """
    z = _validate.array(chart, "chart")
    theta = _validate.array(theta, "theta")
    tip = _rods(mech, _modes(modes), z, theta)[0]
    _, D = _full(mech, _modes(modes), z, theta, tip[..., 0, :])
    A, B = D[..., _FK], D[..., _IK]
    dP = -np.linalg.solve(A, D[..., 4:6])[..., 4:6, :]
    return Jacobians(np.linalg.det(A), np.linalg.det(B), dP * mech.L)


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
    psi, k_rel, modes, _ = rods.elliptic_parameters(mech.EI, mech.L, m0, local)
    chart = np.stack((psi[:, 0], regular.t_from_k_rel(psi, k_rel)[:, 0], psi[:, 1],
                      regular.t_from_k_rel(psi, k_rel)[:, 1]), axis=-1)
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
    system = _memoised(lambda u, p: _full(mech, modes, u[:, :4], u[:, 4:], p))

    def fun(u, p):
        return system(u, p)[0]

    def jac(u, p):
        return system(u, p)[1][..., _IK]

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
    system = _memoised(lambda u, p: _full(mech, modes, u[:, :4], p, u[:, 4:]))

    def fun(u, p):
        return system(u, p)[0]

    def jac(u, p):
        return system(u, p)[1][..., _FK]

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


# --- the study's trajectories (Annex II 3.1 and 3.2) -----------------------------------------

def straight_path(length, angle, divisions):
    """Increments along a straight line from the origin (the study's ``StraightPath``, whose
    code is not listed: ``divisions + 1`` equally spaced points).

    Examples
    --------
    >>> straight_path(0.5, np.pi, 100).shape
    (101, 2)
    """
    s = np.linspace(0.0, _validate.scalar(length, "length"),
                    _validate.maxiter(divisions, "divisions") + 1)
    return s[:, None] * [np.cos(angle), np.sin(angle)]


def circles(diameter, count, divisions):
    """Increments on concentric circles (the study's ``Workspace_Circles``, not listed):
    the centre, then ``count`` circles of diameters ``diameter k / count``, each from angle 0
    in ``divisions`` points.

    Examples
    --------
    >>> pts = circles(0.2, 5, 8)
    >>> pts.shape, round(float(2 * np.abs(pts).max()), 6)
    ((41, 2), 0.2)
    """
    count = _validate.maxiter(count, "count")
    divisions = _validate.maxiter(divisions, "divisions")
    radius = 0.5 * _validate.scalar(diameter, "diameter") * np.arange(1, count + 1) / count
    angle = 2 * np.pi * np.arange(divisions) / divisions
    ring = radius[:, None, None] * np.stack((np.cos(angle), np.sin(angle)), -1)
    return np.concatenate((np.zeros((1, 2)), ring.reshape(-1, 2)))


def rectangles(base, height, count, divisions):
    """Increments on concentric rectangles (the study's ``Workspace_Rectangles``, not listed):
    the centre, then ``count`` rectangles scaled by ``k / count``, each side in ``divisions``
    steps, anticlockwise from the middle of the right side.

    Examples
    --------
    >>> rectangles(0.2, 0.2, 4, 4).shape
    (65, 2)
    """
    count = _validate.maxiter(count, "count")
    n = _validate.maxiter(divisions, "divisions")
    b, h = _validate.scalar(base, "base") / 2, _validate.scalar(height, "height") / 2
    u = np.linspace(-1.0, 1.0, n + 1)[:-1]
    unit = np.concatenate((np.column_stack((np.ones(n), -u))[::-1][n // 2:],   # right, upwards
                           np.column_stack((-u, np.ones(n))),                   # top
                           np.column_stack((-np.ones(n), -u)),                  # left
                           np.column_stack((u, -np.ones(n))),                   # bottom
                           np.column_stack((np.ones(n), u))[:n // 2]))           # right, to start
    scales = np.arange(1, count + 1) / count
    ring = scales[:, None, None] * unit * [b, h]
    return np.concatenate((np.zeros((1, 2)), ring.reshape(-1, 2)))


STUDY_PATHS = {
    "inverse line": (straight_path, (0.5, np.pi, 100)),
    "inverse circles": (circles, (0.2, 5, 8)),
    "inverse rectangles": (rectangles, (0.2, 0.2, 4, 4)),
    "direct line": (straight_path, (1.0, 0.0, 100)),
    "direct circles": (circles, (0.2, 5, 8)),
    "direct rectangles": (rectangles, (0.2, 0.2, 4, 4)),
}
"""The trajectories of Annex II 3.1 (inverse: increments of ``P``, m) and 3.2 (direct:
increments of ``theta``, rad): generator and the study's parameters."""


def path(kind):
    """The increments of one of the study's trajectories (:data:`STUDY_PATHS`).

    Examples
    --------
    >>> path("inverse circles").shape
    (41, 2)
    """
    generator, args = STUDY_PATHS[_validate.choice(kind, tuple(STUDY_PATHS), "kind")]
    return generator(*args)


# --- drawing ----------------------------------------------------------------------------------

def draw(ax, mech, theta, chart, modes=(1, 1), *, force_scale=0.3, colors=("C0", "C3"),
         label=None):
    """Draw one equilibrium: motors, clamped tangents, both rods, the end effector and the load.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech, modes
        As in :func:`forward_elliptic`.
    theta, chart : array_like, shapes (2,) and (4,)
        The equilibrium.
    force_scale : float, optional
        Length of the load's arrow per newton (m/N).
    colors : (str, str), optional
        Colours of rod 1 and rod 2.
    label : str, optional
        Legend label of rod 1 (rod 2 gets ``label`` too, with " (rod 2)").

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> len(draw(ax, TABLE7, TABLE7_THETA, z)) > 4
    True
    >>> plt.close(fig)
    """
    theta = _theta(theta)
    x, y = shapes(mech, theta, _validate.array(chart, "chart", shape=(4,)), modes)
    artists = []
    for r in range(2):
        artists += ax.plot(x[r], y[r], color=colors[r], lw=2,
                           label=None if label is None else f"{label}, rod {r + 1}")
        O = mech.origins[r]
        artists += ax.plot(*np.column_stack((O, O + 0.15 * mech.L * np.array(
            [np.cos(theta[r]), np.sin(theta[r])]))), "k--", lw=0.8)
        artists += ax.plot(*O, marker="^", color="k", ms=9)
    tip = (x[0, -1], y[0, -1])
    artists += ax.plot(*tip, "ko", ms=5)
    if np.any(mech.force):
        artists.append(ax.annotate("", xy=tip + force_scale * mech.force, xytext=tip,
                                   arrowprops=dict(arrowstyle="->", color="C2", lw=1.5)))
    return artists


# --- the study's published numbers -------------------------------------------------------------

TABLE7_PUBLISHED = np.array([[5.304574, 0.969830, 1.825456, -0.992135],
                             [1.962541, -0.004391, 4.811041, 0.943413]])
"""Table 7 as printed, ``(psi1, k_rel1, psi2, k_rel2)`` of its solutions 1 and 2: input data of
:func:`recover_inputs` (the reproduction computes them, see :func:`reproduce`)."""


def recover_inputs(solutions, free="EI"):
    """The example's inputs that the printed solutions of Table 7 determine, by least squares.

    Each printed solution ``(psi1, k_rel1, psi2, k_rel2)`` fixes both rods' shapes and
    forces in their clamp frames; the mechanism must close (``tip1 = tip2``) and carry its
    load (``n1 + n2 = F``): four equations per solution, eight for two. With motor 1 at
    ``(-0.3, 0)`` (the origin of the study's frame) and the printed load ``F`` (which fixes the
    orientation), they determine the two motor angles, motor 2's position and one of the
    rods' stiffness ``EI`` (with ``L`` = 1 m) or their length ``L`` (with the code's ``EI``):
    ``L`` and ``EI`` enter the forces only as ``EI / L**2``. The printed digits (6 decimals)
    leave a residual of about ``1e-5``.

    Parameters
    ----------
    solutions : array_like, shape (m, 4)
        Printed solutions (mode 1), ``m >= 2``.
    free : {"EI", "L"}, optional
        The rod property to fit with the angles and motor 2.

    Returns
    -------
    dict
        ``theta`` (rad), ``motor2`` (m), ``EI`` (N m^2) or ``L`` (m), and ``residual``, the
        largest residual of the fit (m or N).

    Examples
    --------
    >>> fit = recover_inputs(TABLE7_PUBLISHED)
    >>> np.round(np.degrees(fit["theta"]), 3).tolist(), np.round(fit["motor2"], 4).tolist()
    ([40.0, 60.0], [0.3, 0.0])
    """
    from scipy.optimize import least_squares

    _validate.choice(free, ("EI", "L"), "free")
    s = _validate.array(solutions, "solutions", shape=(None, 4))
    if len(s) < 2:
        raise ValueError("at least two solutions are needed to fix the inputs")
    z = chart_from_thesis(s)
    rod = regular.clamped_pinned_regular(1.0, 1.0, z[:, 0::2], z[:, 1::2])   # EI = L = 1

    def residuals(q):
        theta, motor2 = q[:2], q[2:4]
        EI_, L = (q[4], LENGTH) if free == "EI" else (EI, q[4])
        tip, n, _, _ = regular.place(rod, np.stack((TABLE7.origins[0], motor2)) / L, theta)
        return np.concatenate(((tip[:, 0] - tip[:, 1]).ravel() * L,
                               (n.sum(axis=1) * EI_ / L ** 2 - TABLE7.force).ravel()))

    fit = least_squares(residuals, [0.5, 1.0, 0.0, 0.0, 0.05 if free == "EI" else 1.2],
                        xtol=1e-15, ftol=1e-15, gtol=1e-15)
    return {"theta": fit.x[:2], "motor2": fit.x[2:4], free: float(fit.x[4]),
            "residual": float(np.abs(residuals(fit.x)).max())}


def _path_sizes():
    """The sizes of the study's trajectories, measured on :func:`path`'s points."""
    out = {}
    for kind in STUDY_PATHS:
        p, unit = path(kind), " (m)" if kind.startswith("inverse") else " (rad)"
        name = kind.replace(" ", " path: ", 1)
        if kind.endswith("line"):
            out[f"{name} length{unit}"] = float(np.hypot(*(p[-1] - p[0])))
            out[f"{name} direction (deg)"] = float(np.degrees(np.arctan2(*(p[-1] - p[0])[::-1])))
            out[f"{name} divisions"] = float(len(p) - 1)
        elif kind.endswith("circles"):
            radii = np.unique(np.round(np.hypot(*p.T), 12))
            outer = np.isclose(np.hypot(*p.T), radii[-1])
            out[f"{name} outer diameter{unit}"] = float(2 * radii[-1])
            out[f"{name} number"] = float(np.count_nonzero(radii))
            out[f"{name} divisions"] = float(outer.sum())
        else:
            b, h = 2 * np.abs(p[:, 0]).max(), 2 * np.abs(p[:, 1]).max()
            scale = np.round(np.maximum(np.abs(p[:, 0]) / b, np.abs(p[:, 1]) / h), 12)
            out[f"{name} outer base{unit}"], out[f"{name} outer height{unit}"] = b, h
            out[f"{name} number"] = float(np.count_nonzero(np.unique(scale)))
            out[f"{name} divisions per side"] = float(np.sum(scale == scale.max()) / 4)
    return out


def reproduce():
    """The chapter's registry values, computed (see ``book/published_values.csv``).

    Table 7 from the equilibria that :func:`forward_elliptic` finds (each printed solution
    matched with the nearest one), the example's inputs from :func:`recover_inputs`, the
    number of mode-1 equilibria, and the residual of the study's force balance (104) as
    printed at its own solution 1.

    Examples
    --------
    >>> values = reproduce()
    >>> len(values) > 10 and all(isinstance(v, float) for v in values.values())
    True
    """
    eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    values = {}
    for i, printed in enumerate(TABLE7_PUBLISHED, start=1):
        found = eq.solutions[np.argmin(np.abs(eq.solutions - printed).max(axis=1))]
        for name, value in zip(("psi1", "k_rel1", "psi2", "k_rel2"), found):
            values[f"Table 7 solution {i} {name}"] = float(value)
    fit = recover_inputs(TABLE7_PUBLISHED)
    printed = chart_from_thesis(TABLE7_PUBLISHED[0])
    load = _rods(TABLE7, np.ones(2), printed, TABLE7_THETA)[1].sum(axis=0)
    values.update({"motor angle theta1 (fitted to Table 7)": float(np.degrees(fit["theta"][0])),
                   "motor angle theta2 (fitted to Table 7)": float(np.degrees(fit["theta"][1])),
                   "motor 2 x (text: (0, 0.3); fitted to Table 7)": float(fit["motor2"][0]),
                   "motor 2 y (text: (0, 0.3); fitted to Table 7)": float(fit["motor2"][1]),
                   "rod length L (fitted to Table 7)": recover_inputs(TABLE7_PUBLISHED,
                                                                      "L")["L"],
                   "rod diameter (fitted to Table 7, E = 210 GPa)": float(
                       1e3 * (64 * fit["EI"] / (np.pi * YOUNG)) ** 0.25),
                   "load F_x (n1 + n2 at the printed solution 1)": float(load[0]),
                   "load F_y (n1 + n2 at the printed solution 1)": float(load[1])})
    values["mode-1 equilibria for the Table 7 inputs"] = float(len(eq.P))
    # the listing of EmpArt_xyR returns tips relative to their clamps: at the printed
    # solution 1 its residual Res_x, Res_y is the distance between the motors
    relative = _rods(TABLE7, np.ones(2), printed, TABLE7_THETA)[0] - TABLE7.origins
    values["tip gap at the printed solution 1 with EmpArt_xyR as listed (m)"] = float(
        np.hypot(*(relative[0] - relative[1])))
    X = shooting_guess(TABLE7, TABLE7_THETA, eq.chart)
    shot = forward_shooting(TABLE7, TABLE7_THETA, X, nodes=STUDY_NODES)
    scale = np.array([TABLE7.EI / TABLE7.L, TABLE7.L, TABLE7.L] * 2 + [TABLE7.EI] * 2)
    values["shooting residual at convergence, N = 41 (N m, m, N)"] = float(np.max(np.abs(
        _shooting_system(TABLE7, STUDY_NODES, "P")[0](shot.newton.x, shot.theta) * scale)))
    values["elliptic residual (105) at convergence (m, N)"] = float(np.abs(residual(
        TABLE7, TABLE7_THETA, eq.chart)).max())
    values.update(_path_sizes())
    sol1 = eq.forces[np.argmin(np.abs(eq.solutions - TABLE7_PUBLISHED[0]).max(axis=1))]
    values["force balance (104) as printed, at solution 1 (N)"] = float(
        np.hypot(*(sol1.sum(axis=0) + TABLE7.force)))
    return values
