"""What an equilibrium of the 3PFR is like: its stability, its crossings, its strain, and an
independent check.

:func:`stability` counts the negative eigenvalues of the second
variation (:func:`second_variation`: the rods and the platform under the constraints that pin
them together) at two resolutions chosen by :func:`resolutions`, :func:`index` at one;
:func:`crossings` counts where the rods cross each other, themselves
and the platform; :func:`strain` gives the rods' largest bending strain;
:func:`verify` integrates each rod with scipy, independently of the
closed form.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

from mechnum import _validate
from mechnum.mechanisms._assembly import (
    MAX_SEGMENTS,
    check_equilibrium,
    check_modes,
    check_segments,
    check_type,
)
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.mechanisms.pfr3._drawing import shapes
from mechnum.rods import (
    constrained_index_with_body,
    mutual_crossings,
    peak_moment,
    rod_block,
    self_crossings,
)
from mechnum.rods import shape as rod_shapes

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
IVP_RTOL_RANGE = (100 * np.finfo(float).eps, 1e-3)
"""The tolerances :func:`verify` accepts: DOP853's floor, and a loose one beyond which the check
checks nothing."""
# Inflections are counted on the integrated moment where |m| exceeds this fraction of its
# largest value: along a rod in strong tension the moment is exponentially small (1e-17 of
# its peak for the rods of Table 8), below the integration's noise, whose sign changes there
# are no inflections (a true one has |m| clearly positive on one side, negative on the other).
INFLECTION_FLOOR = 1e-9
# The stability tests refuse a chart whose dimensionless residual (forward_system) exceeds
# this: the study's printed 4 decimals leave ~2e-3, a point that is no equilibrium ~1.
EQUILIBRIUM_TOL = 1e-2


def second_variation(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
                     modes: ArrayLike = (1, 1, 1), *, segments: tuple = SEGMENTS):
    """The second variation of one equilibrium, discretised with ``segments`` per rod.

    Returns
    -------
    blocks : list
        The rods' discretised second variations (:func:`mechnum.rods.rod_block`).
    dense : ndarray, shape (3, 3)
        The platform's Hessian in its pose ``(x, y, phi)``.
    constraints : ndarray, shape (6, 3 segments + 3)
        ``tip_i - P - Rot(phi) b_i = 0`` differentiated in the rods' angles and the pose.

    Raises
    ------
    ValueError
        If ``chart`` is no equilibrium (dimensionless residual above ``EQUILIBRIUM_TOL``).

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> blocks, dense, G = second_variation(model.TABLE8, model.TABLE8_LAMBDAS, z, segments=4)
    >>> len(blocks), dense.shape, G.shape
    (3, (3, 3), (6, 15))
    """
    check_type(mech, model.Mechanism)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    z, modes = _validate.array(chart, "chart", shape=(6,)), check_modes(modes, 3)
    segments = _validate.maxiter(segments, "segments", minimum=2, maximum=MAX_SEGMENTS)
    check_equilibrium(model.forward_system(mech, lambdas, modes)(z[None])[0], EQUILIBRIUM_TOL)
    tip, force, _, _ = model.rods(mech, lambdas, z, modes, jacobian=False)
    r = tip - tip.mean(axis=0)                            # B_i - P
    rod = rod_shapes(mech.EI, mech.L, z[0::2], z[1::2], modes, nodes=2 * segments + 1)
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


def resolutions(mech: model.Mechanism, forces: ArrayLike):
    """Segments per rod ``(N, 2 N)`` for the second variation of an equilibrium whose rods
    carry ``forces`` (3, 2): ``N >= SEGMENTS`` and ``lambda h <= 1 / SEGMENTS_PER_DECAY``.

    Examples
    --------
    >>> resolutions(model.TABLE8, [[0.0, 0.1], [0.2, 0.0], [60.0, 0.0]])
    (340, 680)
    """
    check_type(mech, model.Mechanism)
    forces = _validate.array(forces, "forces", shape=(3, 2))
    lam_L = np.sqrt(np.max(np.linalg.norm(forces, axis=-1)) / mech.EI) * mech.L
    n = max(SEGMENTS, int(np.ceil(SEGMENTS_PER_DECAY * lam_L)))
    return n, 2 * n


def stability(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
              modes: ArrayLike = (1, 1, 1), *, segments: ArrayLike | None = None):
    """Index of one equilibrium: negative eigenvalues of its second variation.

    Sliders locked, dead load ``(F, M)`` on the platform: the Hessian of the Lagrangian
    ``sum U_i - F . P - M phi - sum n_i . (tip_i - P - Rot(phi) b_i)`` in the rods' angles and
    the pose, on the tangent space of the constraints, counted by
    :func:`mechnum.rods.constrained_index_with_body` at each resolution.

    Parameters
    ----------
    mech, lambdas, modes
        As in :func:`~mechnum.mechanisms.pfr3.forward`.
    chart : array_like, shape (6,)
        The equilibrium in the chart.
    segments : (int, int), optional
        Resolutions (segments per rod, coarse and fine, each at most
        ``MAX_SEGMENTS = 20_000``); default :func:`resolutions`.

    Returns
    -------
    tuple of int

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> stability(model.TABLE8, model.TABLE8_LAMBDAS, z)
    (0, 0)
    """
    z = _validate.array(chart, "chart", shape=(6,))
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    if segments is None:
        segments = resolutions(mech, model.rods(mech, lambdas, z, modes, jacobian=False)[1])
    return tuple(int(constrained_index_with_body(*second_variation(
        mech, lambdas, z, modes, segments=n))) for n in check_segments(segments))


def index(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
          modes: ArrayLike = (1, 1, 1), *,
          segments: ArrayLike | None = None) -> int:
    """The index of one equilibrium at one resolution (``segments`` per rod, at most
    ``MAX_SEGMENTS = 20_000``; default the coarse one of
    :func:`resolutions`): negative eigenvalues of its second variation.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> index(model.TABLE8, model.TABLE8_LAMBDAS, z, segments=100)
    0
    """
    if segments is None:
        segments = resolutions(mech, model.rods(mech, lambdas, chart, modes,
                                                jacobian=False)[1])[0]
    return int(constrained_index_with_body(*second_variation(mech, lambdas, chart, modes,
                                                             segments=segments)))


def crossings(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
              modes: ArrayLike = (1, 1, 1)):
    """Crossings of the rods of equilibria: of each other, of themselves, of the platform.

    Returns
    -------
    rods_cross : ndarray of int, shape (n, 3)
        Pairs (1, 2), (2, 3), (3, 1).
    self_cross : ndarray of int, shape (n, 3)
    body_cross : ndarray of int, shape (n,)
        Crossings of the rods with the platform's three edges.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> [a.tolist() for a in crossings(model.TABLE8, model.TABLE8_LAMBDAS, z)]
    [[[0, 0, 0]], [[0, 0, 0]], [0]]
    """
    z = np.atleast_2d(model.check_chart(chart)).reshape(-1, 6)
    x, y = shapes(mech, lambdas, z, modes)
    pairs = ((0, 1), (1, 2), (2, 0))
    mutual = np.array([[mutual_crossings(x[k, i], y[k, i], x[k, j], y[k, j])
                        for i, j in pairs] for k in range(len(z))], dtype=int)
    own = np.array([[self_crossings(x[k, i], y[k, i]) for i in range(3)]
                    for k in range(len(z))], dtype=int)
    loop = [0, 1, 2, 0]                          # the platform's edges, from pin to pin
    edges = np.array([sum(mutual_crossings(x[k, i], y[k, i], x[k, loop, -1],
                                                    y[k, loop, -1]) for i in range(3))
                      for k in range(len(z))], dtype=int)
    return mutual.reshape(-1, 3), own.reshape(-1, 3), edges.reshape(-1)


def verify(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
           modes: ArrayLike = (1, 1, 1),
           *, rtol: float = IVP_RTOL) -> tuple:
    """Check equilibria independently: integrate each rod with scipy (``solve_ivp``, DOP853).

    Each rod is integrated from its clamp, with the clamp moment and tip force of the closed
    form, to its tip, which must be at the pin ``B_i`` with no moment. In strong tension this
    cannot check anything: the rounding of the clamp data (1e-16) grows like ``exp(lambda L)``
    along the rod (``lambda = sqrt(R / EI)``). A rod with ``lambda L > SINGLE_SHOT`` is
    therefore integrated in ``ceil(lambda L / SINGLE_SHOT)`` equal pieces, each from the closed
    form's state at its start (:func:`mechnum.rods.shape`), and each piece must end at
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
    >>> from mechnum.mechanisms.pfr3 import forward
    >>> eq = forward(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> err, moment, inflections, pieces = verify(model.TABLE8, model.TABLE8_LAMBDAS, eq.x)
    >>> bool(err.max() < 1e-10), int(inflections.max()), int(pieces.max())
    (True, 1, 4)
    """
    rtol = _validate.tolerance(rtol, "rtol")
    if not IVP_RTOL_RANGE[0] <= rtol <= IVP_RTOL_RANGE[1]:
        raise ValueError(f"rtol must lie in [{IVP_RTOL_RANGE[0]:.3g}, {IVP_RTOL_RANGE[1]:g}] "
                         f"(DOP853's floor, and a check that checks), got {rtol!r}")
    z = np.atleast_2d(model.check_chart(chart)).reshape(-1, 6)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    modes = check_modes(modes, 3)
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
    spaced points, global (closed form, :func:`mechnum.rods.shape`)."""
    rod = rod_shapes(mech.EI, mech.L, z[2 * i], z[2 * i + 1], modes[i], nodes=count + 1)
    c = model.clamps(mech, lambdas)[i]
    cos, sin = np.cos(mech.clamp_angles[i]), np.sin(mech.clamp_angles[i])
    return np.column_stack((c[0] + cos * rod.x - sin * rod.y, c[1] + sin * rod.x + cos * rod.y,
                            rod.theta + mech.clamp_angles[i], rod.m))


def strain(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
           modes: ArrayLike = (1, 1, 1)) -> np.ndarray:
    """The largest bending strain ``(d / 2) max |kappa|`` of each rod of equilibria, exactly
    (:func:`mechnum.rods.peak_moment`; ``kappa = m / EI``).

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> np.round(100 * strain(model.TABLE8, model.TABLE8_LAMBDAS, z), 2).tolist()   # per cent
    [0.09, 0.18, 0.11]
    """
    modes = check_modes(modes, 3)
    _, force, moment, _ = model.rods(mech, lambdas, chart, modes, jacobian=False)
    return 0.5 * mech.diameter * peak_moment(mech.EI, moment, force, mech.clamp_angles,
                                             modes) / mech.EI
