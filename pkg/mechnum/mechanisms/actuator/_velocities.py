"""The actuator's velocity coefficients, the kinematics of a motion, and Kane's partial velocities.

Every angular velocity is a velocity coefficient times the stroke rate: ``omega_j = k_j a_dot``,
``k_j = d theta_j / d a`` (:func:`stroke_kinematics`, :func:`kinematics`), and the velocity
coefficients of the centres of mass are Kane's partial velocities (:func:`partial_velocities`).
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import SingularJacobianError
from mechnum.mechanisms.actuator._loop import triangle
from mechnum.mechanisms.actuator._model import Actuator, checked

MODELS = ("exact", "annex")
"""The velocity coefficients: the loop's own, or the annex's approximations."""
# A dead point: |sin(theta2 - theta4)| below sqrt(eps), or the stroke within 64 eps (d + b) of
# a dead stroke (a + l = d +- b, where the round-off of the law of cosines, amplified by d / b,
# leaves sin(delta) itself no correct digit, and 1/sin(delta) with it).
_DEAD_POINT, _DEAD_STROKE = np.sqrt(np.finfo(float).eps), 64 * np.finfo(float).eps


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


def checked_kinematics(kin: object) -> Kinematics:
    """``kin`` if it is a :class:`Kinematics`; else :class:`ValueError` naming it."""
    if not isinstance(kin, Kinematics):
        raise ValueError(f"kin must be the Kinematics of kinematics(), got {kin!r:.80}")
    return kin


def stroke_kinematics(mech: Actuator, a: ArrayLike, a_dot: ArrayLike = 0.0,
                      a_ddot: ArrayLike = 0.0, model: str = "exact") -> "Kinematics":
    """Positions, velocity coefficients and their derivatives at given strokes and rates.

    The annex's assembly mode (mode 0 of :func:`forward`).

    Parameters
    ----------
    mech : Actuator
    a, a_dot, a_ddot : array_like
        Stroke (m), rate (m/s) and acceleration (m/s**2); finite, real, broadcast together.
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
        If ``model="exact"`` and some stroke is a dead point (``|sin delta| < sqrt(eps)``,
        or ``a + l`` within round-off of ``d +- b``).

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> kin = stroke_kinematics(ANNEX, 0.6, a_dot=0.1)
    >>> round(float(kin.k4), 6), round(float(kin.omega4), 6)
    (4.0, 0.4)
    """
    model = _validate.choice(model, MODELS, "model")
    mech = checked(mech)
    a, a_dot, a_ddot = (_validate.array(a, "a"), _validate.array(a_dot, "a_dot"),
                        _validate.array(a_ddot, "a_ddot"))
    try:
        a, a_dot, a_ddot = np.broadcast_arrays(a, a_dot, a_ddot)
    except ValueError as error:
        raise ValueError(f"a, a_dot and a_ddot must broadcast together: {error}") from None
    return kinematics_at(mech, a, a_dot, a_ddot, model)


def kinematics_at(mech: Actuator, a: np.ndarray, a_dot: np.ndarray, a_ddot: np.ndarray,
                  model: str) -> "Kinematics":
    """:func:`stroke_kinematics` of checked input (the forward dynamics' kernel)."""
    th2, th4 = triangle(mech, a)
    L, b = a + mech.l, mech.b
    s, c = np.sin(th2 - th4), np.cos(th2 - th4)
    if model == "exact":
        L_dead = np.abs(np.subtract.outer(L, [mech.d + b, abs(mech.d - b)])).min(axis=-1)
        if np.any(np.abs(s) < _DEAD_POINT) or np.any(L_dead <= _DEAD_STROKE * (mech.d + b)):
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


def kinematics(mech: Actuator, t: ArrayLike, model: str = "exact") -> "Kinematics":
    """Positions, velocity coefficients and their derivatives at the instants ``t``.

    The stroke, its rate and acceleration follow :meth:`Actuator.stroke`; the rest is
    :func:`stroke_kinematics`.

    Parameters
    ----------
    mech : Actuator
    t : array_like
        Times (s); must be finite and real. An empty array is valid.
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
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> kin = kinematics(ANNEX, 0.0)
    >>> round(float(kin.omega2), 6) + 0.0, round(float(kin.omega4), 6)
    (0.0, 0.502655)
    """
    model = _validate.choice(model, MODELS, "model")
    return kinematics_at(mech, *checked(mech).stroke(t), model)


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


def partial_velocities(kin: Kinematics) -> PartialVelocities:
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
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> pv = partial_velocities(kinematics(ANNEX, 0.0))
    >>> (np.round(pv.v, 6) + 0.0).tolist()   # G2 at rest; G3 up the cylinder; G4 up, g4 k4
    [0j, 1j, 2.4j]
    """
    kin = checked_kinematics(kin)
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    r3 = kin.a + m.g3
    turn2, turn4 = 1j * kin.dk2 - kin.k2**2, 1j * kin.dk4 - kin.k4**2
    v = np.array([1j * m.g2 * kin.k2 * e2, (1 + 1j * r3 * kin.k2) * e2, 1j * m.g4 * kin.k4 * e4])
    dv = np.array([m.g2 * turn2 * e2, (2j * kin.k2 + r3 * turn2) * e2, m.g4 * turn4 * e4])
    return PartialVelocities(v, np.array([kin.k2, kin.k2, kin.k4]), dv,
                             np.array([kin.dk2, kin.dk2, kin.dk4]))


def centres_of_mass(kin: Kinematics) -> np.ndarray:
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
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> (np.round(centres_of_mass(kinematics(ANNEX, 0.0)), 6) + 0.0).tolist()
    [0.3j, 0.8j, (0.35+1j)]
    """
    kin = checked_kinematics(kin)
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    return np.array([m.g2 * e2, (kin.a + m.g3) * e2, complex(-m.o2, m.o4) + m.g4 * e4])
