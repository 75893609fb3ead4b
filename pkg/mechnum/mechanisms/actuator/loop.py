"""Positions and velocity coefficients of the actuator mechanism.

The loop ``(a + l) e^{i theta2} = O4 + b e^{i theta4}`` closes in the triangle ``O2 O4 A``
(:func:`positions`), or by Newton's method (:func:`solve_loop`). Every angular velocity is a
velocity coefficient times the stroke rate (:func:`kinematics`), and the velocity coefficients of
the centres of mass are Kane's partial velocities (:func:`partial_velocities`).
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.errors import SingularJacobianError, UnreachablePoseError
from mechnum.mechanisms.actuator.model import ANNEX, Actuator, _mechanism
from mechnum.newton import solve

_MODELS = ("exact", "annex")
# A dead point: |sin(theta2 - theta4)| below sqrt(eps). There delta comes from an arccos of an
# argument within eps of +-1, which leaves it no correct digit, and 1/sin(delta) with it.
_DEAD_POINT = np.sqrt(np.finfo(float).eps)


@dataclass(frozen=True)
class Kinematics:
    """Positions and velocity coefficients of links 2 (and 3) and 4 at a set of instants.

    Attributes
    ----------
    mech : Actuator
        The mechanism.
    model : {"exact", "annex"}
        Which velocity coefficients: the loop's, or the annex's approximations.
    a, a_dot, a_ddot : ndarray
        Stroke, rate and acceleration.
    theta2, theta4 : ndarray
        Link angles (rad) from the x axis.
    k2, k4 : ndarray
        Velocity coefficients ``d theta / d a`` (rad/m).
    dk2, dk4 : ndarray
        Their derivatives along the motion, ``d k / d a`` (rad/m**2).
    """

    mech: Actuator
    model: str
    a: np.ndarray
    a_dot: np.ndarray
    a_ddot: np.ndarray
    theta2: np.ndarray
    theta4: np.ndarray
    k2: np.ndarray
    k4: np.ndarray
    dk2: np.ndarray
    dk4: np.ndarray

    @property
    def omega2(self):
        """Angular velocity of links 2 and 3 (rad/s)."""
        return self.k2 * self.a_dot

    @property
    def omega4(self):
        """Angular velocity of link 4 (rad/s)."""
        return self.k4 * self.a_dot

    @property
    def eps2(self):
        """Angular acceleration of links 2 and 3 (rad/s**2)."""
        return self.k2 * self.a_ddot + self.dk2 * self.a_dot**2

    @property
    def eps4(self):
        """Angular acceleration of link 4 (rad/s**2)."""
        return self.k4 * self.a_ddot + self.dk4 * self.a_dot**2


def _kinematics(kin):
    if not isinstance(kin, Kinematics):
        raise ValueError(f"kin must be the Kinematics of kinematics(), "
                         f"got {_validate._shown(kin)}")
    return kin


def _pairs(x):
    """``(theta2, theta4)`` from an array of shape (..., 2), checked."""
    x = _validate.array(x, "x", ndim=range(1, 33))
    if x.shape[-1] != 2:
        raise ValueError(f"x must have shape (..., 2): pairs (theta2, theta4), "
                         f"got shape {x.shape}")
    return x[..., 0], x[..., 1]


def positions(a, mech=ANNEX):
    """Link angles from the triangle of the pivots, as the annex computes them.

    ``phi`` (at ``O4``) and ``psi`` (at ``O2``) follow from the law of cosines in the triangle
    of sides ``d``, ``b`` and ``a + l``; then ``theta4 = phi - beta`` and
    ``theta2 = pi - beta - psi`` with ``beta = atan(o4 / o2)``.

    Parameters
    ----------
    a : array_like
        Strokes (m); must be finite and real. An empty array is valid.
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    theta2, theta4 : ndarray
        Angles (rad) of the cylinder and of the rocker, of ``a``'s shape.

    Raises
    ------
    ValueError
        If ``a`` is not finite and real, or ``mech`` is not an :class:`Actuator`.
    UnreachablePoseError
        If ``a + l`` is outside ``[|d - b|, d + b]``: the loop cannot close.

    Examples
    --------
    >>> th2, th4 = positions(0.6)
    >>> round(float(th2), 6), round(float(th4), 6)
    (1.570796, 0.0)
    """
    return _positions(_validate.array(a, "a"), _mechanism(mech))


def _positions(a, mech):
    """:func:`positions` of checked input."""
    L = a + mech.l
    d, b = mech.d, mech.b
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_phi = (d**2 + b**2 - L**2) / (2 * d * b)
        cos_psi = (d**2 + L**2 - b**2) / (2 * d * L)
    bad = ~(np.abs(cos_phi) <= 1) | ~(np.abs(cos_psi) <= 1) | (L <= 0)
    if np.any(bad):
        first = np.flatnonzero(np.ravel(bad))[0]
        raise UnreachablePoseError(
            f"the loop cannot close: a + l = {np.ravel(L)[first]:.6g} m is outside "
            f"[|d - b|, d + b] = [{abs(d - b):.6g}, {d + b:.6g}] m")
    beta = np.arctan2(mech.o4, mech.o2)
    return np.pi - beta - np.arccos(cos_psi), np.arccos(cos_phi) - beta


def loop_residual(x, a, mech=ANNEX):
    """The two loop equations ``(a + l) e^{i theta2} - O4 - b e^{i theta4} = 0``.

    Parameters
    ----------
    x : array_like, shape (..., 2)
        ``(theta2, theta4)`` in radians, or a batch of such pairs.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    ndarray, shape (..., 2)
        The x and y components of the loop's closure error (m).

    Raises
    ------
    ValueError
        If ``x`` is not finite and real with a last axis of length 2, ``a`` not a finite real
        number, or ``mech`` not an :class:`Actuator`.

    Examples
    --------
    >>> np.round(loop_residual([np.pi / 2, 0.0], 0.6), 12) + 0.0
    array([0., 0.])
    """
    th2, th4 = _pairs(x)
    mech = _mechanism(mech)
    L = _validate.scalar(a, "a") + mech.l
    return np.stack([L * np.cos(th2) + mech.o2 - mech.b * np.cos(th4),
                     L * np.sin(th2) - mech.o4 - mech.b * np.sin(th4)], axis=-1)


def loop_jacobian(x, a, mech=ANNEX):
    """Jacobian of :func:`loop_residual` with respect to ``(theta2, theta4)``.

    Its determinant is ``(a + l) b sin(theta2 - theta4)``: it vanishes at the dead points,
    where the cylinder and the crank are aligned, and at every guess with ``theta2 = theta4``.

    Parameters
    ----------
    x : array_like, shape (..., 2)
        ``(theta2, theta4)`` in radians, or a batch of such pairs.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    ndarray, shape (..., 2, 2)

    Raises
    ------
    ValueError
        As :func:`loop_residual`.

    Examples
    --------
    >>> round(float(np.linalg.det(loop_jacobian([np.pi / 2, 0.0], 0.6))), 12)
    0.25
    """
    th2, th4 = _pairs(x)
    mech = _mechanism(mech)
    L = _validate.scalar(a, "a") + mech.l
    rows = [np.stack([-L * np.sin(th2), mech.b * np.sin(th4)], axis=-1),
            np.stack([L * np.cos(th2), -mech.b * np.cos(th4)], axis=-1)]
    return np.stack(rows, axis=-2)


def solve_loop(a, mech=ANNEX, x0=(np.pi / 2, 0.0), **options):
    """Solve the loop equations for one stroke by Newton-Raphson.

    Parameters
    ----------
    a : float
        Stroke (m); must be finite and real.
    mech : Actuator, optional
        The mechanism.
    x0 : array_like, shape (2,), optional
        Initial guess ``(theta2, theta4)``; its branch is the one found.
    **options
        Passed to :func:`mechnum.newton.solve` (``tol``, ``maxiter``, ``criterion``, ``norm``,
        ``damping``).

    Returns
    -------
    mechnum.newton.NewtonResult
        ``x`` is ``(theta2, theta4)``.

    Raises
    ------
    ValueError
        If ``a`` or ``x0`` are not finite and real, or an option is invalid.
    SingularJacobianError, ConvergenceError
        From :func:`mechnum.newton.solve`: a guess with ``theta2 = theta4`` (singular Jacobian
        at the start), a pose out of reach (no convergence).

    Examples
    --------
    >>> res = solve_loop(0.62, x0=(1.5, 0.0))
    >>> np.round(res.x, 9).tolist() == np.round(positions(0.62), 9).tolist()
    True
    """
    a = _validate.scalar(a, "a")
    mech = _mechanism(mech)
    x0 = _validate.array(x0, "x0", shape=(2,))
    return solve(lambda x: loop_residual(x, a, mech), x0,
                 lambda x: loop_jacobian(x, a, mech), **options)


def stroke_kinematics(a, a_dot=0.0, a_ddot=0.0, mech=ANNEX, model="exact"):
    """Positions, velocity coefficients and their derivatives at given strokes and rates.

    Parameters
    ----------
    a, a_dot, a_ddot : array_like
        Stroke (m), rate (m/s) and acceleration (m/s**2); finite, real, broadcast together.
    mech : Actuator, optional
        The mechanism.
    model : {"exact", "annex"}, optional
        ``"exact"``: ``k4 = 1/(b sin delta)``, ``k2 = cos delta / ((a+l) sin delta)``;
        ``"annex"``: the annex's ``k4 = sin delta / b``, ``k2 = sin delta cos delta / (a+l)``.
        In both, ``dk/da`` is the derivative of the chosen ``k`` with
        ``d delta / d a = k2 - k4`` of the same model (the annex's accelerations follow its
        own velocities, so its model is consistent, though not the mechanism's).

    Returns
    -------
    Kinematics

    Raises
    ------
    ValueError
        If an input is not finite and real, the shapes do not broadcast, or ``model`` is
        unknown.
    UnreachablePoseError
        If the loop cannot close at some stroke.
    SingularJacobianError
        If ``model="exact"`` and some stroke is a dead point (``|sin delta| < sqrt(eps)``).

    Examples
    --------
    >>> kin = stroke_kinematics(0.6, a_dot=0.1)
    >>> round(float(kin.k4), 6), round(float(kin.omega4), 6)
    (4.0, 0.4)
    """
    model = _validate.choice(model, _MODELS, "model")
    mech = _mechanism(mech)
    a, a_dot, a_ddot = (_validate.array(a, "a"), _validate.array(a_dot, "a_dot"),
                        _validate.array(a_ddot, "a_ddot"))
    try:
        a, a_dot, a_ddot = np.broadcast_arrays(a, a_dot, a_ddot)
    except ValueError as error:
        raise ValueError(f"a, a_dot and a_ddot must broadcast together: {error}") from None
    return _stroke_kinematics(a, a_dot, a_ddot, mech, model)


def _stroke_kinematics(a, a_dot, a_ddot, mech, model):
    """:func:`stroke_kinematics` of checked input."""
    th2, th4 = _positions(a, mech)
    L, b = a + mech.l, mech.b
    s, c = np.sin(th2 - th4), np.cos(th2 - th4)
    if model == "exact":
        if np.any(np.abs(s) < _DEAD_POINT):
            raise SingularJacobianError(
                f"dead point: |sin(theta2 - theta4)| = {np.min(np.abs(s)):.3g}, the cylinder "
                "and the crank are aligned and the velocity coefficients are infinite")
        k2, k4 = c / (L * s), 1 / (b * s)
        ddelta = k2 - k4
        dk2, dk4 = -k2 / L - ddelta / (L * s**2), -c * ddelta / (b * s**2)
    else:
        k2, k4 = s * c / L, s / b
        ddelta = k2 - k4
        dk2, dk4 = -k2 / L + (c**2 - s**2) * ddelta / L, c * ddelta / b
    return Kinematics(mech, model, a, a_dot, a_ddot, th2, th4, k2, k4, dk2, dk4)


def kinematics(t, mech=ANNEX, model="exact"):
    """Positions, velocity coefficients and their derivatives at the instants ``t``.

    The stroke, its rate and acceleration follow :meth:`Actuator.stroke`; the rest is
    :func:`stroke_kinematics`.

    Parameters
    ----------
    t : array_like
        Times (s); must be finite and real. An empty array is valid.
    mech : Actuator, optional
        The mechanism.
    model : {"exact", "annex"}, optional
        As in :func:`stroke_kinematics`.

    Returns
    -------
    Kinematics

    Raises
    ------
    ValueError, UnreachablePoseError, SingularJacobianError
        As :func:`stroke_kinematics`.

    Examples
    --------
    >>> kin = kinematics(0.0)
    >>> round(float(kin.omega2), 6) + 0.0, round(float(kin.omega4), 6)
    (0.0, 0.502655)
    """
    model = _validate.choice(model, _MODELS, "model")
    return _stroke_kinematics(*_mechanism(mech).stroke(t), mech, model)


@dataclass(frozen=True)
class PartialVelocities:
    """Kane's partial velocities of the three links for the generalised speed ``a_dot``.

    Plane vectors are complex numbers ``x + i y``; the first axis runs over links 2, 3, 4.

    Attributes
    ----------
    v : ndarray of complex, shape (3,) + kin.a.shape
        ``d v_G / d a_dot``: the velocity coefficient of each centre of mass (m/s per m/s).
    omega : ndarray, shape (3,) + kin.a.shape
        ``d omega / d a_dot``: ``k2, k2, k4`` (rad/m).
    dv : ndarray of complex, shape (3,) + kin.a.shape
        ``d v / d a`` (1/m): the acceleration of ``G`` is ``v a_ddot + dv a_dot**2``.
    domega : ndarray, shape (3,) + kin.a.shape
        ``d omega / d a``: ``k2', k2', k4'`` (rad/m**2).
    """

    v: np.ndarray
    omega: np.ndarray
    dv: np.ndarray
    domega: np.ndarray


def partial_velocities(kin):
    """Kane's partial velocities: the velocity coefficients of the centres of mass.

    With the stroke rate as generalised speed, every velocity is linear in it, ``v_G = J a_dot``
    and ``omega = k a_dot``; ``J`` and ``k`` are the partial velocities:

    * ``J2 = i g2 k2 e2``, ``J3 = e2 + i (a + g3) k2 e2``, ``J4 = i g4 k4 e4``, with
      ``e_j = exp(i theta_j)``;
    * their derivatives along the motion, ``dJ/da``, e.g. ``dJ2/da = g2 (i k2' - k2**2) e2``.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.

    Returns
    -------
    PartialVelocities

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`.

    Examples
    --------
    >>> pv = partial_velocities(kinematics(0.0))
    >>> (np.round(pv.v, 6) + 0.0).tolist()   # G2 at rest; G3 up the cylinder; G4 up, g4 k4
    [0j, 1j, 2.4j]
    """
    kin = _kinematics(kin)
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    r3 = kin.a + m.g3
    turn2, turn4 = 1j * kin.dk2 - kin.k2**2, 1j * kin.dk4 - kin.k4**2
    v = np.array([1j * m.g2 * kin.k2 * e2, (1 + 1j * r3 * kin.k2) * e2, 1j * m.g4 * kin.k4 * e4])
    dv = np.array([m.g2 * turn2 * e2, (2j * kin.k2 + r3 * turn2) * e2, m.g4 * turn4 * e4])
    return PartialVelocities(v, np.array([kin.k2, kin.k2, kin.k4]), dv,
                             np.array([kin.dk2, kin.dk2, kin.dk4]))


def centres_of_mass(kin):
    """Centres of mass of links 2, 3, 4 at the strokes of ``kin``.

    ``G2 = g2 e2``, ``G3 = (a + g3) e2`` and ``G4 = O4 + g4 e4``, with ``e_j = exp(i theta_j)``.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.

    Returns
    -------
    ndarray of complex, shape (3,) + kin.a.shape
        The centres as complex numbers ``x + i y`` (m).

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`.

    Examples
    --------
    >>> (np.round(centres_of_mass(kinematics(0.0)), 6) + 0.0).tolist()
    [0.3j, 0.8j, (0.35+1j)]
    """
    kin = _kinematics(kin)
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    return np.array([m.g2 * e2, (kin.a + m.g3) * e2, complex(-m.o2, m.o4) + m.g4 * e4])
