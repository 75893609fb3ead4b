"""Every equilibrium of the 3PFR for given slider inputs, its stability and its crossings.

:func:`forward_elliptic` solves the reduced closed-form system of
:func:`~mechnum.mechanisms.pfr3.model.forward_system` from many starts at once
(:func:`mechnum.newton.solve_all`). A uniform sample of the six chart coordinates rarely lands
near the equilibria in which the rods are in strong tension (nearly straight along their chords,
forces tens of times the buckling loads): their basins are narrow in ``psi``, since the force
must point along the chord. The starts therefore come from two physical families, each built
from a random platform pose (centre in the clamps' bounding box, any angle):

* **pulling** rods: each force along its chord, from the clamp to the pin, with a large force
  (``q = t**2 / (1 - t**2)`` log-uniform in ``PULL_Q``);
* **pushing** rods: each force along the chord from the pin to the clamp, with a small to
  moderate force (``q`` log-uniform in ``PUSH_Q``), as in compressed and bent rods;

with random signs of ``t`` (the study's branches of ``k_rel``). On the study's examples every
equilibrium gets at least ~30 hits per 10,000 starts, against none to a few with uniform starts.
"""

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from mechnum import _validate, newton
from mechnum.mechanisms.pfr3 import model
from mechnum.mechanisms.rfr2.analysis import SHAPE_NODES
from mechnum.rods import crossing, profile, regular
from mechnum.rods.bodies import constrained_index_with_body
from mechnum.rods.stability import TwoResolutions, rod_block

# q ranges of the starts (q ~ 2 sqrt(R L**2 / EI) for large forces R): pulling rods from about
# the buckling load to ~2e4 EI / L**2 (q = 300), pushing ones from a straight rod (q = 1e-8,
# t = 1e-4) to about twice the buckling load (q = 3).
PULL_Q = (1.0, 300.0)
PUSH_Q = (1e-8, 3.0)
# Newton's step tolerance in the (dimensionless) chart, and its most iterations from a start.
SEARCH_TOL = 1e-12
SEARCH_MAXITER = 40
# Roots closer than this (largest chart coordinate) are one.
SAME = 1e-8
# The second variation is discretised with N and 2 N segments per rod (the index must agree):
# at least 200, and 10 per decay length 1 / lambda = sqrt(EI / R) of the most tensioned rod, so
# that its boundary layers (loops) are resolved (lambda h <= 0.1): the discretisation error
# of the eigenvalues, ~(lambda h)**2 lambda**2 EI, then stays well below the lowest of them.
SEGMENTS = 200
SEGMENTS_PER_DECAY = 10
# A rod is checked by one integration from its clamp when lambda L <= SINGLE_SHOT: the
# rounding of its clamp data (1e-16) grows like exp(lambda L) along it (6e-12 at 11); a rod in
# stronger tension is integrated from both ends to its middle (growth exp(lambda L / 2)).
SINGLE_SHOT = 9.0
# Relative tolerance of the check by solve_ivp (DOP853 accepts down to 2.2e-14): its error
# norm is a root mean square over the pieces integrated together, up to 28 components here.
IVP_RTOL = 3e-14
# Inflections are counted on the integrated moment where |m| exceeds this fraction of its
# largest value: along a rod in strong tension the moment is exponentially small (1e-17 of
# its peak for the rods of Table 8), below the integration's noise, whose sign changes there
# are no inflections (a true one has |m| clearly positive on one side, negative on the other).
INFLECTION_FLOOR = 1e-9
# Default starts: the narrowest basin of the study's examples holds ~4e-3 of them, so 1000
# starts hit every equilibrium ~4 times (and the check of 10,000 ~40 times).
N_STARTS = 1000


@dataclass(frozen=True)
class Equilibria(TwoResolutions):
    """Every equilibrium that :func:`forward_elliptic` found, and how well it looked.

    Attributes
    ----------
    lambdas : ndarray, shape (3,)
        The slider inputs (m).
    modes : tuple of int
        The buckling modes of the three rods.
    solutions : ndarray, shape (n, 6)
        ``(psi1, k_rel1, psi2, k_rel2, psi3, k_rel3)``, the study's convention (Tabla 8).
    chart : ndarray, shape (n, 6)
        ``(psi1, t1, psi2, t2, psi3, t3)``, the solver's regular coordinates.
    pose : ndarray, shape (n, 3)
        The platform's centre ``(x, y)`` (m) and angle ``phi`` (rad, in ``(-pi, pi]``).
    forces : ndarray, shape (n, 3, 2)
        Force on each rod at its tip (N).
    clamp_moments : ndarray, shape (n, 3)
        Moments at the clamps (N m).
    index : ndarray of int, shape (n, 2)
        Negative eigenvalues of the second variation at two resolutions
        (:func:`resolutions`): 0 is stable.
    rods_cross : ndarray of int, shape (n, 3)
        Crossings of the rod pairs (1, 2), (2, 3) and (3, 1).
    self_cross : ndarray of int, shape (n, 3)
        Self-crossings of each rod (a loop).
    platform_cross : ndarray of int, shape (n,)
        Crossings of the rods with the platform's edges.
    search : mechnum.newton.RootSet
        The search and its completeness evidence (``roots`` in the chart, ``hits``,
        ``n_starts``, ``n_check``, ``new_in_check``, ``complete``).
    """

    lambdas: np.ndarray
    modes: tuple
    solutions: np.ndarray
    chart: np.ndarray
    pose: np.ndarray
    forces: np.ndarray
    clamp_moments: np.ndarray
    index: np.ndarray
    rods_cross: np.ndarray
    self_cross: np.ndarray
    platform_cross: np.ndarray
    search: newton.RootSet

    @property
    def crossing_free(self):
        """ndarray of bool, shape (n,): no rod crosses another, itself or the platform."""
        return ((self.rods_cross.sum(axis=1) == 0) & (self.self_cross.sum(axis=1) == 0)
                & (self.platform_cross == 0))

    @property
    def buildable(self):
        """ndarray of bool, shape (n,): stable and crossing-free."""
        return self.stable & self.crossing_free


def sampler(mech, lambdas):
    """The starts of :func:`forward_elliptic`: ``sample(rng, m) -> (m, 6)`` chart points, half
    of pulling rods and half of pushing ones (see the module).

    Examples
    --------
    >>> z = sampler(model.TABLE8, model.TABLE8_LAMBDAS)(np.random.default_rng(0), 4)
    >>> z.shape, bool(model.in_chart(z).all())
    ((4, 6), True)
    """
    c = model.clamps(mech, lambdas)
    low, high = c.min(axis=0), c.max(axis=0)

    def family(rng, m, q_range, pull):
        pose = np.column_stack((rng.uniform(low, high, (m, 2)), rng.uniform(-np.pi, np.pi, m)))
        chord = model.pins(mech, pose) - c
        if not pull:
            chord = -chord
        psi = np.mod(np.arctan2(chord[..., 1], chord[..., 0]) - mech.clamp_angles,
                     regular.TWO_PI)
        q = np.exp(rng.uniform(*np.log(q_range), (m, 3)))
        t = rng.choice([-1.0, 1.0], (m, 3)) * np.sqrt(q / (1.0 + q))
        z = np.empty((m, 6))
        z[:, 0::2] = np.clip(psi, 1e-6, regular.TWO_PI - 1e-6)
        z[:, 1::2] = np.clip(t, -regular.T_MAX, regular.T_MAX)
        return z

    def sample(rng, m):
        return np.concatenate((family(rng, m // 2, PULL_Q, True),
                               family(rng, m - m // 2, PUSH_Q, False)))

    return sample


def forward_elliptic(mech, lambdas, modes=(1, 1, 1), *, n_starts=N_STARTS, check=10, rng=None):
    """Every equilibrium of the mechanism at the slider inputs ``lambdas``, with given modes.

    Damped Newton on the reduced closed form (analytic Jacobian, only real assemblies of the
    platform) from ``n_starts`` starts of :func:`sampler`, then ``check`` times as many new
    starts (:func:`mechnum.newton.solve_all`). Each equilibrium is classified: stability
    (:func:`stability`) and crossings (:func:`crossings`). Rods under forces beyond the chart's
    range (``T_MAX`` of :mod:`mechnum.rods.regular`, about ``(300 mode)**2 EI / L**2``) are not
    sought.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.model.Mechanism
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    modes : (int, int, int), optional
        Buckling modes of the rods (inflections on ``0 < s <= L``).
    n_starts : int, optional
        Starts of the search (``check`` times as many again for the completeness check).
    check : int, optional
        Size of the completeness check, in multiples of ``n_starts`` (0: none).
    rng : numpy.random.Generator or int, optional
        Random generator or seed of the starts.

    Returns
    -------
    ~mechnum.mechanisms.pfr3.equilibria.Equilibria
        ``n >= 0`` equilibria, sorted by ``psi1``.

    Raises
    ------
    ValueError
        If ``lambdas`` is not three finite numbers or ``modes`` not three integers ``>= 1``.
    GeometryError
        If no platform of side ``a`` can close between the clamps (:func:`check_closure`).

    Examples
    --------
    >>> eq = forward_elliptic(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> len(eq.pose), eq.search.complete, np.round(eq.solutions[0], 4).tolist()
    (9, True, [5.1834, -0.7267, 5.006, -0.9287, 2.6908, -0.0953])
    """
    lambdas, modes = model._lambdas(lambdas), model._modes(modes)
    model.check_closure(mech, lambdas)
    fun, jac = model.forward_system(mech, lambdas, modes)
    found = newton.solve_all(fun, sampler(mech, lambdas), jac, n_starts=n_starts,
                             check=check, rng=rng, domain=model.in_chart, tol=SEARCH_TOL,
                             maxiter=SEARCH_MAXITER, same=SAME)
    z = found.roots
    tip, force, moment, _ = model.rods(mech, lambdas, z, modes, jacobian=False)
    pose = model.pose_of_tips(mech, tip)
    n = len(z)
    index = np.array([stability(mech, lambdas, zi, modes) for zi in z]).reshape(n, 2)
    cross = crossings(mech, lambdas, z, modes)
    return Equilibria(lambdas, tuple(int(m) for m in modes), model.thesis_from_chart(z), z,
                      pose, force, moment, index, *cross, found)


def shapes(mech, lambdas, z, modes=(1, 1, 1), *, nodes=SHAPE_NODES):
    """The three rods of equilibria as polylines (closed form, :func:`mechnum.rods.profile.shape`).

    Returns
    -------
    x, y : ndarray, shape (..., 3, nodes)
        Coordinates (m), from each clamp to its tip.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> x, y = shapes(model.TABLE8, model.TABLE8_LAMBDAS, z)
    >>> x.shape, round(float(x[0, 0]), 4), round(float(y[0, 0]), 4)
    ((3, 201), -0.866, -0.5)
    """
    z = np.asarray(z, dtype=float)
    rod = profile.shape(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], model._modes(modes),
                        nodes=nodes)
    c = model.clamps(mech, model._lambdas(lambdas))
    cos, sin = np.cos(mech.clamp_angles)[:, None], np.sin(mech.clamp_angles)[:, None]
    return (c[:, 0, None] + cos * rod.x - sin * rod.y,
            c[:, 1, None] + sin * rod.x + cos * rod.y)


def _blocks(mech, lambdas, z, modes, segments):
    """The rods' discretised second variations, the platform's Hessian and the constraints
    ``tip_i - P - Rot(phi) b_i = 0`` in the rods' angles and the pose ``(x, y, phi)``."""
    tip, force, _, _ = model.rods(mech, lambdas, z, modes, jacobian=False)
    r = tip - tip.mean(axis=0)                            # B_i - P
    rod = profile.shape(mech.EI, mech.L, z[0::2], z[1::2], modes, nodes=2 * segments + 1)
    angles = rod.theta[:, 1::2] + mech.clamp_angles[:, None]
    blocks = [rod_block(mech.EI, mech.L, angles[i], force[i]) for i in range(3)]
    G = np.zeros((6, 3 * segments + 3))
    for i, block in enumerate(blocks):
        G[2 * i:2 * i + 2, i * segments:(i + 1) * segments] = block.tip_gradient
        G[2 * i:2 * i + 2, -3:-1] = -np.eye(2)
        G[2 * i:2 * i + 2, -1] = r[i, 1], -r[i, 0]
    # the work of the pins' forces as the platform turns: d2/dphi2 sum n_i . Rot(phi) b_i
    dense = np.zeros((3, 3))
    dense[2, 2] = -np.sum(r * force)
    return blocks, dense, G


def resolutions(mech, forces):
    """Segments per rod ``(N, 2 N)`` for the second variation of an equilibrium whose rods
    carry ``forces`` (3, 2): ``N >= SEGMENTS`` and ``lambda h <= 1 / SEGMENTS_PER_DECAY``.

    Examples
    --------
    >>> resolutions(model.TABLE8, [[0.0, 0.1], [0.2, 0.0], [60.0, 0.0]])
    (340, 680)
    """
    lam_L = np.sqrt(np.max(np.linalg.norm(forces, axis=-1)) / mech.EI) * mech.L
    n = max(SEGMENTS, int(np.ceil(SEGMENTS_PER_DECAY * lam_L)))
    return n, 2 * n


def stability(mech, lambdas, z, modes=(1, 1, 1), *, segments=None):
    """Index of one equilibrium: negative eigenvalues of its second variation.

    Sliders locked, dead load ``(F, M)`` on the platform: the Hessian of the Lagrangian
    ``sum U_i - F . P - M phi - sum n_i . (tip_i - P - Rot(phi) b_i)`` in the rods' angles and
    the pose, on the tangent space of the constraints, counted by
    :func:`mechnum.rods.bodies.constrained_index_with_body` at each resolution.

    Parameters
    ----------
    mech, lambdas, modes
        As in :func:`forward_elliptic`.
    z : array_like, shape (6,)
        The equilibrium in the chart.
    segments : tuple of int, optional
        Resolutions (segments per rod); default :func:`resolutions`.

    Returns
    -------
    tuple of int

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> stability(model.TABLE8, model.TABLE8_LAMBDAS, z)
    (0, 0)
    """
    z = _validate.array(z, "z", shape=(6,))
    lambdas, modes = model._lambdas(lambdas), model._modes(modes)
    if segments is None:
        segments = resolutions(mech, model.rods(mech, lambdas, z, modes, jacobian=False)[1])
    return tuple(constrained_index_with_body(*_blocks(mech, lambdas, z, modes, n))
                 for n in segments)


def crossings(mech, lambdas, z, modes=(1, 1, 1)):
    """Crossings of the rods of equilibria: of each other, of themselves, of the platform.

    Returns
    -------
    rods_cross : ndarray of int, shape (n, 3)
        Pairs (1, 2), (2, 3), (3, 1).
    self_cross : ndarray of int, shape (n, 3)
    platform_cross : ndarray of int, shape (n,)
        Crossings of the rods with the platform's three edges.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> [a.tolist() for a in crossings(model.TABLE8, model.TABLE8_LAMBDAS, z)]
    [[[0, 0, 0]], [[0, 0, 0]], [0]]
    """
    z = np.atleast_2d(_validate.array(z, "z"))
    x, y = shapes(mech, lambdas, z, modes)
    pairs = ((0, 1), (1, 2), (2, 0))
    mutual = np.array([[crossing.mutual_crossings(x[k, i], y[k, i], x[k, j], y[k, j])
                        for i, j in pairs] for k in range(len(z))], dtype=int)
    own = np.array([[crossing.self_crossings(x[k, i], y[k, i]) for i in range(3)]
                    for k in range(len(z))], dtype=int)
    loop = [0, 1, 2, 0]                          # the platform's edges, from pin to pin
    edges = np.array([sum(crossing.mutual_crossings(x[k, i], y[k, i], x[k, loop, -1],
                                                    y[k, loop, -1]) for i in range(3))
                      for k in range(len(z))], dtype=int)
    return mutual.reshape(-1, 3), own.reshape(-1, 3), edges.reshape(-1)


def verify(mech, lambdas, z, modes=(1, 1, 1), *, rtol=IVP_RTOL):
    """Check equilibria independently: integrate each rod with scipy (``solve_ivp``, DOP853).

    Each rod is integrated from its clamp, with the clamp moment and tip force of the closed
    form, to its tip, which must be at the pin ``B_i`` with no moment. In strong tension this
    cannot check anything: the rounding of the clamp data (1e-16) grows like ``exp(lambda L)``
    along the rod (``lambda = sqrt(R / EI)``). A rod with ``lambda L > SINGLE_SHOT`` is
    therefore integrated in ``ceil(lambda L / SINGLE_SHOT)`` equal pieces, each from the closed
    form's state at its start (:func:`mechnum.rods.profile.shape`), and each piece must end at
    the state where the next begins (multiple shooting). The pieces of a rod are integrated
    together, as one system in the fraction of their length.

    Returns
    -------
    error : ndarray, shape (n, 3)
        Largest distance between an integrated piece's end and the closed form's point there
        (the pin at the tip) (m).
    moment : ndarray, shape (n, 3)
        Largest difference of the moments there (the tip's moment itself at the tip) (N m).
    inflections : ndarray of int, shape (n, 3)
        Sign changes of the integrated moment on ``0 < s <= L`` (where ``|m|`` exceeds
        ``INFLECTION_FLOOR`` of its largest value), plus the tip's zero: the mode.
    pieces : ndarray of int, shape (n, 3)
        Pieces of each rod's integration.

    Examples
    --------
    >>> eq = forward_elliptic(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> err, moment, inflections, pieces = verify(model.TABLE8, model.TABLE8_LAMBDAS, eq.chart)
    >>> bool(err.max() < 1e-10), int(inflections.max()), int(pieces.max())
    (True, 1, 4)
    """
    z = np.atleast_2d(_validate.array(z, "z"))
    lambdas, modes = model._lambdas(lambdas), model._modes(modes)
    tip, force, _, _ = model.rods(mech, lambdas, z, modes, jacobian=False)
    B = model.pins(mech, model.pose_of_tips(mech, tip))
    lam_L = np.sqrt(np.linalg.norm(force, axis=-1) / mech.EI) * mech.L
    pieces = np.maximum(1, np.ceil(lam_L / SINGLE_SHOT)).astype(int)
    err, gap_m, infl = np.zeros((3, len(z), 3))
    for k in range(len(z)):
        for i in range(3):
            n, count = force[k, i], pieces[k, i]
            states = _states(mech, lambdas, z[k], modes, i, count)     # (count + 1, 4)
            states[-1, :2], states[-1, 3] = B[k, i], 0.0               # the pin, no moment
            h = mech.L / count

            def rhs(_, u, n=n, h=h):                  # all pieces, in sigma = (s - s_j) / h
                u = u.reshape(-1, 4)
                c, s = np.cos(u[:, 2]), np.sin(u[:, 2])
                return h * np.column_stack((c, s, u[:, 3] / mech.EI,
                                            n[0] * s - n[1] * c)).ravel()

            sol = solve_ivp(rhs, (0.0, 1.0), states[:-1].ravel(), method="DOP853", rtol=rtol,
                            atol=rtol * mech.L)
            path = sol.y.reshape(count, 4, -1)
            err[k, i] = np.hypot(*(path[:, :2, -1] - states[1:, :2]).T).max()
            gap_m[k, i] = np.abs(path[:, 3, -1] - states[1:, 3]).max()
            m = np.concatenate(path[:, 3, :-1])              # the tip's zero is counted apart
            m = m[np.abs(m) > INFLECTION_FLOOR * np.abs(m).max()]
            infl[k, i] = np.sum(np.sign(m[1:]) != np.sign(m[:-1])) + 1
    return err, gap_m, infl.astype(int), pieces


def _states(mech, lambdas, z, modes, i, count):
    """``(x, y, theta, m)`` of rod ``i`` of the equilibrium ``z`` at ``count + 1`` equally
    spaced points, global (closed form, :func:`mechnum.rods.profile.shape`)."""
    rod = profile.shape(mech.EI, mech.L, z[2 * i], z[2 * i + 1], modes[i], nodes=count + 1)
    c = model.clamps(mech, lambdas)[i]
    cos, sin = np.cos(mech.clamp_angles[i]), np.sin(mech.clamp_angles[i])
    return np.column_stack((c[0] + cos * rod.x - sin * rod.y, c[1] + sin * rod.x + cos * rod.y,
                            rod.theta + mech.clamp_angles[i], rod.m))
