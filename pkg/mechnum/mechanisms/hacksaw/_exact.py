"""The kinematics without iteration: the closed form, its two assembly modes, the rate stages as
linear solves, and the singular points.

:func:`~mechnum.mechanisms.hacksaw.closed_form` is the study's list of formulas, corrected;
:func:`~mechnum.mechanisms.hacksaw.forward` gives both assembly modes at once;
:func:`~mechnum.mechanisms.hacksaw.solve_rates` solves the velocity and acceleration stages,
which are linear in their unknowns, as two linear solves; and
:func:`~mechnum.mechanisms.hacksaw.singular_points` gives the crank angles where the
mechanism is singular.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum.mechanisms.hacksaw import _kernels as kernels
from mechnum.mechanisms.hacksaw._model import (
    ALPHA_MAX,
    Geometry,
    checked,
    checked_motor,
    finite,
    motor,
)
from mechnum.results import Assemblies, Result

# Positions that close the position constraints to 1e-8 of the mechanism's size are a
# configuration (a Newton solution stopped at the study's step of 1e-6 closes them to about
# 1e-12); rates computed at positions that miss by more would be the rates of no configuration.
POSITION_RTOL = 1e-8


def closed_form(mech: Geometry, t: ArrayLike | None = None, *,
                motor_state: tuple | None = None, alpha_max: float = ALPHA_MAX) -> np.ndarray:
    """The exact kinematics in the study's assembly mode at times ``t`` (or at motor states).

    The study's list of formulas, corrected (its ``r1`` and ``omega3`` are wrong), with
    ``theta1 = acot(x / r1y)`` computed by ``arctan2`` (accurate for a tiny ``r1y``) and the
    rates of ``r1`` solved without ``tan(theta1)`` (no removable 0/0 at ``theta1 = pi/2``).
    Mode 0 of :func:`forward`.

    Parameters
    ----------
    mech : Geometry
    t : array_like, optional
        Times in seconds; the motor state comes from :func:`motor`.
    motor_state : tuple of array_like, optional
        ``(theta2, omega2, alpha2)`` instead of ``t``.
    alpha_max : float, optional
        The motor's largest acceleration, used with ``t``.

    Returns
    -------
    ndarray, shape ``np.shape(t) + (9,)`` (or the broadcast shape of ``motor_state``)

    Raises
    ------
    ValueError
        If neither or both of ``t`` and ``motor_state`` are given, an input is not finite, or
        the result overflows.
    UnreachablePoseError
        If ``|r1y - r2 sin(theta2)| > r3``: the coupler cannot reach the guide.
    SingularJacobianError
        At a dead point, ``|cos(theta3)| < DEAD_POINT_COS``: the rates are undefined.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> np.round(closed_form(STUDY, 0.0)[:3], 6)
    array([-0.099672, -0.468422,  2.873694])
    """
    if (t is None) == (motor_state is None):
        raise ValueError("give either t or motor_state")
    checked(mech)
    th2, w2, a2 = motor(t, alpha_max) if motor_state is None else checked_motor(motor_state)
    with np.errstate(over="ignore", invalid="ignore"):
        x = kernels.closed_form(mech, th2, w2, a2)
    return finite(x, "the closed-form kinematics")


def forward(mech: Geometry, motor_state: tuple) -> Assemblies:
    """Every assembly mode of the saw at the motor states: the forward problem, in closed form.

    For a crank angle the coupler meets the guide at two points: mode 0, the study's, with
    the coupler pointing back (``cos(theta3) < 0``, the slider left of the crank pin), and
    mode 1, pointing forward. Both exist, or neither (``|r1y - r2 sin(theta2)| > r3``); they
    meet at the dead points (:func:`singular_points`).

    Parameters
    ----------
    mech : Geometry
    motor_state : tuple of array_like
        ``(theta2, omega2, alpha2)``, arrays that broadcast.

    Returns
    -------
    mechnum.results.Assemblies
        ``x``, of shape (the broadcast shape) ``+ (2, 9)``: the nine unknowns of mode 0 and of
        mode 1; ``inputs``, of that shape ``+ (3,)``: the motor states.

    Raises
    ------
    ValueError, UnreachablePoseError, SingularJacobianError
        As :func:`closed_form`.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> both = forward(STUDY, (0.0, 0.0, 0.0))
    >>> np.round(both.x[:, :3], 4).tolist()    # r1, theta1, theta3 of each mode
    [[-0.0997, -0.4684, 2.8737], [0.2431, 0.1862, 0.2679]]
    """
    checked(mech)
    th2, w2, a2 = checked_motor(motor_state)
    with np.errstate(over="ignore", invalid="ignore"):
        x = np.stack([kernels.closed_form(mech, th2, w2, a2, mode) for mode in kernels.MODES],
                     axis=-2)
    return Assemblies.of(finite(x, "the closed-form kinematics"),
                         np.stack(np.broadcast_arrays(th2, w2, a2), axis=-1),
                         int(np.prod(x.shape[:-2])), len(kernels.MODES))


def solve_rates(mech: Geometry, q: ArrayLike,
                motor_state: tuple) -> tuple[np.ndarray, np.ndarray]:
    """Velocities and accelerations at the positions ``q``: two linear solves, no iteration.

    The velocity and acceleration constraints are linear in their unknowns, with the matrix
    :func:`rate_jacobian` (rows permuted: :func:`position_jacobian`), so each stage is one
    linear solve; Newton would take one exact step from any seed, then a confirming step. The
    matrix's structure solves it without pivoting: two of its rows differ in the column of
    ``theta3`` only, which gives ``omega3`` (``alpha3``) at once, and the two others are then a
    rotation by ``theta1``.

    Parameters
    ----------
    mech : Geometry
    q : array_like, shape (..., 3)
        Positions ``(r1, theta1, theta3)`` that satisfy the position constraints (to
        :data:`POSITION_RTOL` of the largest link).
    motor_state : tuple of array_like
        ``(theta2, omega2, alpha2)``, broadcasting against ``q.shape[:-1]``.

    Returns
    -------
    v, a : ndarray, shape: the broadcast batch shape ``+ (3,)``
        ``(Vr, omega1, omega3)`` and ``(Ar, alpha1, alpha3)``.

    Raises
    ------
    ValueError
        If an input is ill-shaped or not finite, or ``q`` misses the position constraints.
    SingularJacobianError
        At a dead point, ``|cos(theta3)| < DEAD_POINT_COS``.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> x = closed_form(STUDY, 1.0)
    >>> v, a = solve_rates(STUDY, x[:3], motor(1.0))
    >>> bool(np.allclose(np.concatenate([v, a]), x[3:], rtol=1e-13, atol=1e-13))
    True
    """
    th2, w2, a2 = checked_motor(motor_state)
    q, th2, w2, a2 = checked(mech, [("q", q, 3)], [("theta2", th2), ("omega2", w2),
                                                   ("alpha2", a2)])
    with np.errstate(over="ignore", invalid="ignore"):
        miss = np.abs(kernels.loop(mech, q, kernels.crank(th2))).max(initial=0.0)
        size = max(mech.r1y, mech.r2, mech.r3)
        if not miss <= POSITION_RTOL * size:
            raise ValueError(f"q must satisfy the position constraints at theta2 (to "
                             f"{POSITION_RTOL:g} of {size:g} m), they miss by {miss:.3g} m")
        v, a = kernels.linear_rates(mech, q, th2, w2, a2)
    return finite(v, "the velocities"), finite(a, "the accelerations")


@dataclass(frozen=True, kw_only=True)
class SingularPoints(Result):
    """The crank angles where the saw is singular (radians in ``[0, 2 pi)``, increasing).

    Attributes
    ----------
    x : ndarray, shape (k,)
        The dead points: the coupler perpendicular to the guide (``cos(theta3) = 0``), where
        the two assembly modes meet and the rate equations are singular (the forward problem's
        singularity). They exist only for a short coupler, ``r3 <= r1y + r2``; there the crank
        cannot turn round.
    status, message, iterations, nfev, njev
        ``"converged"``, and no work: a closed form.
    limits : ndarray, shape (2, k)
        For each assembly mode, the limit positions: the crank and the coupler aligned, where
        the slider stops and turns back (the inverse problem's singularity, the ends of the
        stroke), extended (``|OB| = r2 + r3``) and folded (``|OB| = |r3 - r2|``) where each
        exists.
    """

    limits: np.ndarray


def singular_points(mech: Geometry) -> SingularPoints:
    """The crank angles of the dead points and of the limit positions, in closed form.

    A dead point has ``r1y - r2 sin(theta2) = +-r3``. At a limit position the slider pin ``B``
    lies on the line of the crank, at ``|OB| = r2 + r3`` or ``|r3 - r2|`` from the crank's
    pivot and at height ``r1y``: ``B = (+-sqrt(|OB|^2 - r1y^2), r1y)``, the crank along ``OB``
    (extended, or folded with ``r3 < r2``) or against it (folded, ``r3 > r2``); the sign of
    ``B``'s abscissa against the crank pin's gives the mode.

    Parameters
    ----------
    mech : Geometry

    Returns
    -------
    SingularPoints

    Raises
    ------
    ValueError
        If ``mech`` is not a Geometry.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> points = singular_points(STUDY)
    >>> points.x.size, np.degrees(points.limits).round(2).tolist()
    (0, [[169.42, 331.73], [10.58, 208.27]])
    """
    g = mech
    checked(g)
    dead = []
    for side in (1.0, -1.0):  # r1y - r2 sin(theta2) = side r3
        s = (g.r1y - side * g.r3) / g.r2
        if abs(s) <= 1:
            dead += [np.arcsin(s), np.pi - np.arcsin(s)]
    limits = [[], []]
    for reach, folded in ((g.r2 + g.r3, False), (abs(g.r3 - g.r2), True)):
        if reach < g.r1y:
            continue
        for right, x_b in enumerate((-np.sqrt(reach ** 2 - g.r1y ** 2),
                                     np.sqrt(reach ** 2 - g.r1y ** 2))):
            along = np.arctan2(g.r1y, x_b)  # the direction of B from the crank's pivot
            turned = folded and g.r3 < g.r2  # the coupler points back along OB (theta3 + pi)
            theta2 = along + np.pi if folded and g.r3 > g.r2 else along
            limits[1 - right if turned else right].append(theta2)  # mode 1: cos(theta3) > 0
    limits = np.array([_angles(m) for m in limits]).reshape(2, -1)
    dead = np.unique(_angles(dead))
    return SingularPoints(x=dead, status="converged", iterations=0, nfev=0, njev=0,
                          message=f"{dead.size} dead points, {limits.shape[1]} limit positions "
                                  "per mode, in closed form", limits=limits)


def _angles(values):
    """Angles in ``[0, 2 pi)``, sorted."""
    return np.sort(np.mod(np.asarray(values, dtype=float), 2 * np.pi))
