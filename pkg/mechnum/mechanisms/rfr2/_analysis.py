"""What an equilibrium is like: its stability, its crossings, its strain, an independent check.

:func:`~mechnum.mechanisms.rfr2.stability` counts the negative eigenvalues of the second
variation under the constraint ``tip1 = tip2`` (:mod:`mechnum.rods.stability`) at two
resolutions, :func:`~mechnum.mechanisms.rfr2.index` at one, and
:func:`~mechnum.mechanisms.rfr2.eigenvalues` gives them; :func:`~mechnum.mechanisms.rfr2.crossings`
counts where the rods cross (:mod:`mechnum.rods.crossing`), :func:`~mechnum.mechanisms.rfr2.strain`
gives the rods' largest bending strain, and :func:`~mechnum.mechanisms.rfr2.verify` integrates
each rod from its clamp with scipy, independently of the closed form.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

from mechnum import _validate
from mechnum.mechanisms._assembly import (
    MAX_DENSE_SEGMENTS,
    MAX_SEGMENTS,
    check_equilibrium,
    check_modes,
    check_segments,
)
from mechnum.mechanisms.rfr2._drawing import shapes
from mechnum.mechanisms.rfr2._model import Mechanism, broadcast, rods
from mechnum.rods import (
    constrained_eigenvalues,
    constrained_index,
    mutual_crossings,
    peak_moment,
    rod_block,
    self_crossings,
)
from mechnum.rods import shape as rod_shapes

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
IVP_RTOL_RANGE = (100 * np.finfo(float).eps, 1e-3)
"""The tolerances :func:`verify` accepts: DOP853's floor (scipy raises smaller ones to it), and
a loose one beyond which the check checks nothing."""
# The stability tests refuse a chart whose dimensionless residual (positions over L, forces
# over EI / L**2) exceeds this: the study's printed digits leave ~4e-4, a point that is no
# equilibrium has residuals of order one.
EQUILIBRIUM_TOL = 1e-2


def _angles(mech, theta, z, modes, segments):
    """The rods' tangent angles at the midpoints of ``segments`` segments, ``(n, 2, segments)``
    for each resolution, and their tip forces ``(n, 2, 2)``, of equilibria ``z`` (n, 4) at
    ``theta`` (n, 2), checked to be equilibria. The shapes are sampled once, at the finest
    resolution, when every other one divides it: a coarser resolution's midpoints are nodes of
    the finest's, computed from the same ``s``, so they are the same numbers."""
    modes = check_modes(modes, 2)
    tip, force = rods(mech, theta, z, modes, jacobian=False)[:2]
    for i in range(len(z)):
        check_equilibrium(np.concatenate(((tip[i, 0] - tip[i, 1]) / mech.L, (
            force[i].sum(axis=0) - mech.force) * mech.L ** 2 / mech.EI)), EQUILIBRIUM_TOL)
    finest = max(segments)
    samples = {}
    for n in ([finest] if all(finest % n == 0 for n in segments) else sorted(set(segments))):
        rod = rod_shapes(mech.EI, mech.L, z[:, 0::2], z[:, 1::2], modes, nodes=2 * n + 1)
        samples[n] = rod.theta + theta[..., None]
    return [samples[finest][..., finest // n::2 * finest // n] if n not in samples
            else samples[n][..., 1::2] for n in segments], force


def _blocks(angles, force, mech):
    """The two rods' discretised second variations (angles (2, N)), and the constraint
    ``tip1 = tip2``."""
    blocks = [rod_block(mech.EI, mech.L, angles[i], force[i]) for i in range(2)]
    return blocks, np.concatenate((blocks[0].tip_gradient, -blocks[1].tip_gradient), axis=1)


def _one(mech, theta, chart, modes, segments):
    """The blocks of one equilibrium at ``segments`` segments per rod."""
    theta, z = broadcast(theta, chart)
    if z.shape != (4,):
        raise ValueError(f"chart must be one equilibrium, shape (4,), got {z.shape}")
    angles, force = _angles(mech, theta[None], z[None], modes, (segments,))
    return _blocks(angles[0][0], force[0], mech)


def index(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1), *,
          segments: int = SEGMENTS[0]) -> int:
    """The index of one equilibrium at one resolution: negative eigenvalues of its second
    variation with ``segments`` segments per rod (``<= MAX_SEGMENTS``).

    Motors locked, dead load ``F`` on ``P``: the Hessian of the Lagrangian
    ``U1 + U2 - F . P + mu . (tip1 - tip2)`` on the tangent space of ``tip1 = tip2``
    (:mod:`mechnum.rods.stability`; the multiplier ``mu`` is the force ``n2``), counted by
    :func:`mechnum.rods.stability.constrained_index`.

    Raises
    ------
    ValueError
        If ``chart`` is no equilibrium (dimensionless residual above ``EQUILIBRIUM_TOL``).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> index(TABLE7, TABLE7_THETA, chart_from_thesis([5.304574, 0.969830, 1.825456,
    ...                                                -0.992135]))
    0
    """
    segments = _validate.maxiter(segments, "segments", minimum=2, maximum=MAX_SEGMENTS)
    return int(constrained_index(*_one(mech, theta, chart, modes, segments)))


def stability(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1), *,
              segments: tuple = SEGMENTS) -> tuple:
    """The index of one equilibrium at two resolutions (:func:`index`): ``(0, 0)`` is stable.

    Parameters
    ----------
    mech, theta, modes
        As in :func:`~mechnum.mechanisms.rfr2.forward`.
    chart : array_like, shape (4,)
        The equilibrium, ``(psi1, t1, psi2, t2)``.
    segments : (int, int), optional
        The resolutions, segments per rod (coarse, fine), each at most
        :data:`~mechnum.mechanisms._assembly.MAX_SEGMENTS`.

    Returns
    -------
    tuple of int
        The index at each resolution.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> stability(TABLE7, TABLE7_THETA, z)
    (0, 0)
    """
    theta, z = broadcast(theta, chart)
    if z.shape != (4,):
        raise ValueError(f"chart must be one equilibrium, shape (4,), got {z.shape}")
    return tuple(stabilities(mech, theta[None], z[None], modes, segments=segments)[0].tolist())


def stabilities(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1),
                *, segments: tuple = SEGMENTS) -> np.ndarray:
    """:func:`stability` of many equilibria at once: their indices, ``(n, len(segments))``.

    The rods of all of them are sampled in one evaluation of the closed form (once, at the
    finest resolution, when the others divide it), then each index is counted as
    :func:`stability` counts it.

    Parameters
    ----------
    mech, modes, segments
        As in :func:`stability`.
    theta, chart : array_like, shapes (n, 2) and (n, 4)
        The equilibria (an empty batch is valid).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> stabilities(TABLE7, eq.inputs[None].repeat(3, axis=0), eq.x).tolist()
    [[0, 0], [0, 0], [0, 0]]
    """
    segments = check_segments(segments)
    theta, z = broadcast(theta, chart)
    if z.ndim != 2:
        raise ValueError(f"chart must be a batch of equilibria, shape (n, 4), got {z.shape}")
    if not len(z):
        return np.zeros((0, len(segments)), dtype=int)
    angles, force = _angles(mech, theta, z, modes, segments)
    return np.array([[constrained_index(*_blocks(a[i], force[i], mech)) for a in angles]
                     for i in range(len(z))], dtype=int)


def eigenvalues(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1), *,
                segments: int = EIGEN_SEGMENTS) -> np.ndarray:
    """The eigenvalues of an equilibrium's second variation, ascending, dimensionless.

    Dense (:func:`mechnum.rods.stability.constrained_eigenvalues`, at most
    :data:`~mechnum.mechanisms._assembly.MAX_DENSE_SEGMENTS` segments per rod), divided by
    ``h EI / L**2``: they approximate those of the continuous second variation, to about
    ``(segments / 64)**-2`` percent of the larger ones.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> np.round(eigenvalues(TABLE7, TABLE7_THETA, z)[:2], 0).tolist()
    [7.0, 28.0]
    """
    segments = _validate.maxiter(segments, "segments", minimum=2, maximum=MAX_DENSE_SEGMENTS)
    blocks, constraints = _one(mech, theta, chart, modes, segments)
    hessian = np.zeros((2 * segments, 2 * segments))
    hessian[:segments, :segments] = blocks[0].hessian
    hessian[segments:, segments:] = blocks[1].hessian
    return constrained_eigenvalues(hessian, constraints) / (blocks[0].h * mech.EI / mech.L ** 2)


def crossings(mech: Mechanism, theta: ArrayLike, chart: ArrayLike,
              modes: ArrayLike = (1, 1)) -> tuple[np.ndarray, np.ndarray]:
    """Crossings of the rods of equilibria: of each other, and of each with itself.

    Returns
    -------
    rods_cross : ndarray of int, shape (n,)
    self_cross : ndarray of int, shape (n, 2)

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([[5.304574, 0.969830, 1.825456, -0.992135],
    ...                        [1.962541, -0.004391, 4.811041, 0.943413]])
    >>> [a.tolist() for a in crossings(TABLE7, TABLE7_THETA, z)]
    [[0, 1], [[0, 0], [0, 0]]]
    """
    theta, z = broadcast(theta, np.atleast_2d(_validate.array(chart, "chart", finite=False)))
    x, y = shapes(mech, theta.reshape(-1, 2), z.reshape(-1, 4), modes)
    mutual = np.array([mutual_crossings(x[i, 0], y[i, 0], x[i, 1], y[i, 1],
                                                 shared_tip=True) for i in range(len(x))],
                      dtype=int)
    own = np.array([[self_crossings(x[i, r], y[i, r]) for r in range(2)]
                    for i in range(len(x))], dtype=int)
    return mutual.reshape(-1), own.reshape(-1, 2)


def strain(mech: Mechanism, theta: ArrayLike, chart: ArrayLike,
           modes: ArrayLike = (1, 1)) -> np.ndarray:
    """The largest bending strain ``(d / 2) max |kappa|`` of each rod of equilibria, exactly
    (:func:`mechnum.rods.peak_moment`; ``kappa = m / EI``).

    Returns
    -------
    ndarray, shape (..., 2)

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> np.round(100 * strain(TABLE7, TABLE7_THETA, z), 2).tolist()      # per cent
    [0.79, 0.7]
    >>> round(100 * TABLE7.strain_limit, 2)      # music wire: Table 7's solution 1 yields
    0.77
    """
    theta, z = broadcast(theta, chart)
    modes = check_modes(modes, 2)
    _, force, moment, _, _ = rods(mech, theta, z, modes, jacobian=False)
    return 0.5 * mech.diameter * peak_moment(mech.EI, moment, force, theta, modes) / mech.EI


def verify(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1), *,
           rtol: float = IVP_RTOL) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Check equilibria independently: integrate each rod from its clamp with scipy.

    Each rod is integrated by ``solve_ivp`` (DOP853, relative tolerance ``rtol`` in
    :data:`IVP_RTOL_RANGE`) from its clamp, with the clamp moment and the tip force of the
    closed form, and compared with the closed form's end effector.

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
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> err, moment, inflections = verify(TABLE7, TABLE7_THETA, forward(
    ...     TABLE7, TABLE7_THETA, rng=0).x)
    >>> bool(err.max() < 1e-10), bool(np.abs(moment).max() < 1e-10), inflections.tolist()
    (True, True, [[1, 1], [1, 1], [1, 1]])
    """
    rtol = _validate.tolerance(rtol, "rtol")
    if not IVP_RTOL_RANGE[0] <= rtol <= IVP_RTOL_RANGE[1]:
        raise ValueError(f"rtol must lie in [{IVP_RTOL_RANGE[0]:.3g}, {IVP_RTOL_RANGE[1]:g}] "
                         f"(DOP853's floor, and a check that checks), got {rtol!r}")
    theta, z = broadcast(theta, np.atleast_2d(_validate.array(chart, "chart", finite=False)))
    theta, z = theta.reshape(-1, 2), z.reshape(-1, 4)
    tip, force, moment, _, _ = rods(mech, theta, z, modes, jacobian=False)
    err, tip_m, infl = np.zeros((3, len(z), 2))
    s = np.linspace(0.0, mech.L, 4001)
    for i in range(len(z)):
        for r in range(2):
            n = force[i, r]

            def rhs(_, y, n=n):
                return [np.cos(y[2]), np.sin(y[2]), y[3] / mech.EI,
                        n[0] * np.sin(y[2]) - n[1] * np.cos(y[2])]

            sol = solve_ivp(rhs, (0.0, mech.L), [*mech.origins[r], theta[i, r], moment[i, r]],
                            method="DOP853", rtol=rtol, atol=rtol * mech.L, dense_output=True)
            end = sol.y[:, -1]
            err[i, r] = np.hypot(*(end[:2] - tip[i, 0]))
            tip_m[i, r] = end[3]
            m = sol.sol(s)[3][:-1]         # the tip's zero is counted apart
            infl[i, r] = int(np.sum(np.sign(m[1:]) != np.sign(m[:-1]))) + 1
    return err, tip_m, infl.astype(int)
