"""What an equilibrium is like: its stability, its shape, its crossings, an independent check.

:func:`~mechnum.mechanisms.rfr2.stability` counts the negative eigenvalues of the second
variation under the constraint ``tip1 = tip2`` (:mod:`mechnum.rods.stability`) and
:func:`~mechnum.mechanisms.rfr2.eigenvalues` gives them; :func:`~mechnum.mechanisms.rfr2.shapes`
samples both rods, :func:`~mechnum.mechanisms.rfr2.crossings` counts where they cross
(:mod:`mechnum.rods.crossing`), and :func:`~mechnum.mechanisms.rfr2.verify` integrates each rod
from its clamp with scipy, independently of the closed form.
"""

import numpy as np
from scipy.integrate import solve_ivp

from mechnum import _validate
from mechnum.mechanisms.rfr2.model import _clamp_states, _modes, _theta
from mechnum.rods import crossing, regular
from mechnum.rods.stability import constrained_eigenvalues, constrained_index, rod_block

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
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
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
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
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
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
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
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
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
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, forward_elliptic
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
