"""The actuator force by three routes (inverse dynamics), the energy, and forward dynamics.

Virtual power (:func:`virtual_power_force`), Kane's equations (:func:`kane_force`) and
Lagrange's equation (:func:`lagrange_force`) share the velocity coefficients and nothing else;
:func:`energy` gives ``T + V`` for the energy balance, and :func:`forward_dynamics` integrates
Lagrange's equation by RK4: the motion that a given force produces.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.actuator._model import G_MATHCAD, Actuator, checked
from mechnum.mechanisms.actuator._velocities import (  # kinematics: for the examples
    MODELS,
    Kinematics,
    centres_of_mass,
    checked_kinematics,
    kinematics,  # noqa: F401
    kinematics_at,
    partial_velocities,
    stroke_kinematics,  # noqa: F401
)
from mechnum.ode import rk4
from mechnum.results import Result


def _masses(kin):
    """The three links' masses and inertias about their centres, shaped to broadcast against
    arrays of shape ``(3,) + kin.a.shape``."""
    shape, m = (3,) + (1,) * kin.a.ndim, kin.mech
    return np.reshape([m.m2, m.m3, m.m4], shape), np.reshape(m.inertias, shape)


def kane_force(kin: Kinematics, g: float = G_MATHCAD) -> np.ndarray:
    """Actuator force by Kane's equations.

    Kane's equation for the generalised speed ``a_dot`` is ``F + F* = 0``: the generalised active
    force ``F = Q - g sum_i m_i Im(J_i)`` (the cylinder's pair of forces contributes ``Q``, since
    the rod's partial velocity relative to the barrel is the unit axis) and the generalised
    inertia force ``F* = -sum_i m_i a_Gi . J_i + I_Gi eps_i k_i``, with the accelerations from
    differentiating ``v_G = J a_dot``: ``a_G = J a_ddot + (dJ/da) a_dot**2``
    (:func:`partial_velocities`).

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics` or ``g`` is not finite and real.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> round(float(kane_force(kinematics(ANNEX, 0.0))), 5)
    43.14926
    """
    kin, g = checked_kinematics(kin), _validate.scalar(g, "g")
    pv, (mass, inertia) = partial_velocities(kin), _masses(kin)
    acc = pv.v * kin.a_ddot + pv.dv * kin.a_dot**2
    alpha = pv.omega * kin.a_ddot + pv.domega * kin.a_dot**2
    dot = acc.real * pv.v.real + acc.imag * pv.v.imag  # a_G . J
    inertia_force = mass * dot + inertia * alpha * pv.omega
    return np.sum(inertia_force + mass * g * pv.v.imag, axis=0)


def virtual_power_force(kin: Kinematics, g: float = G_MATHCAD,
                        divide_by_rate: bool = False) -> np.ndarray:
    """Actuator force by virtual power, the annex's ``Q_di``.

    The accelerations of the centres of mass follow the relative-motion formulas, as the annex
    writes them: ``a_G2 = g2 (i eps2 - omega2**2) e2``, ``a_G4 = g4 (i eps4 - omega4**2) e4``,
    and for the rod's centre, sliding at ``r3 = a + g3`` along the turning barrel,
    ``a_G3 = (a_ddot - r3 omega2**2 + i (r3 eps2 + 2 omega2 a_dot)) e2`` (the last term is
    Coriolis's). The power of the actuator, of the inertia forces and couples and of gravity
    vanishes for every virtual motion the mechanism allows; for the virtual motion ``delta a = 1``
    the virtual velocities are the velocity coefficients, and::

        Q = sum_i  m_i (a_Gi . J_i) + I_Gi eps_i k_i + m_i g J_iy.

    The annex takes the actual motion instead and divides its power by ``a_dot``, which is 0/0
    where the actuator is at rest (``divide_by_rate=True``).

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    divide_by_rate : bool, optional
        Evaluate the annex's form literally: the power along the actual motion divided by the
        stroke rate. The result is NaN where the rate is exactly zero.

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`, ``g`` is not finite and real, or
        ``divide_by_rate`` is not a bool.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> round(float(virtual_power_force(kinematics(ANNEX, 0.0))), 5)
    43.14926
    >>> kin = kinematics(ANNEX, 0.25)                 # at rest: Mathcad's cos(pi/2) is not 0 either
    >>> float(kin.a_dot) != 0, round(float(virtual_power_force(kin, divide_by_rate=True)), 5)
    (True, 29.35295)
    """
    kin, g = checked_kinematics(kin), _validate.scalar(g, "g")
    divide_by_rate = _validate.flag(divide_by_rate, "divide_by_rate")
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    w2, w4, eps2, eps4, r3 = kin.omega2, kin.omega4, kin.eps2, kin.eps4, kin.a + m.g3
    acc = np.array([m.g2 * (1j * eps2 - w2**2) * e2,
                    (kin.a_ddot - r3 * w2**2 + 1j * (r3 * eps2 + 2 * w2 * kin.a_dot)) * e2,
                    m.g4 * (1j * eps4 - w4**2) * e4])
    alpha = np.array([eps2, eps2, eps4])
    if divide_by_rate:  # the actual velocities, whose power is divided by a_dot
        rate, w, rod = kin.a_dot, np.array([w2, w2, w4]), kin.a_dot
    else:  # the virtual motion delta a = 1: the velocity coefficients
        rate, w, rod = 1.0, np.array([kin.k2, kin.k2, kin.k4]), 1.0
    v = np.array([1j * m.g2 * w[0] * e2, (rod + 1j * r3 * w[1]) * e2, 1j * m.g4 * w[2] * e4])
    mass, inertia = _masses(kin)
    power = np.sum(mass * (acc.real * v.real + acc.imag * v.imag) + inertia * alpha * w
                   + mass * g * v.imag, axis=0)
    with np.errstate(invalid="ignore"):
        return power / rate


@dataclass(frozen=True)
class LagrangeTerms:
    """The terms of Lagrange's equation ``Q = M a_ddot + M' a_dot**2 / 2 + V'``.

    Attributes
    ----------
    mass : ndarray
        The generalised mass ``M(a)`` (kg).
    mass_slope : ndarray
        ``M'(a) = dM/da`` (kg/m).
    potential_slope : ndarray
        ``V'(a) = dV/da`` (N): the generalised force of gravity, with its sign reversed.
    """

    mass: np.ndarray
    mass_slope: np.ndarray
    potential_slope: np.ndarray


def lagrange_terms(kin: Kinematics, g: float = G_MATHCAD,
                   annex_slip: bool = False) -> "LagrangeTerms":
    """Generalised mass, its slope, and the slope of the potential, at the strokes of ``kin``.

    With the stroke ``a`` as generalised coordinate, ``T = M(a) a_dot**2 / 2``, where::

        M  = (I_O2 + J3) k2**2 + m3 + I_O4 k4**2,        J3 = m3 (a + g3)**2 + I_G3,
        M' = 2 (I_O2 + J3) k2 k2' + 2 m3 (a + g3) k2**2 + 2 I_O4 k4 k4',
        V' = g [m2 g2 cos(theta2) k2 + m3 (sin(theta2) + (a + g3) cos(theta2) k2)
                + m4 g4 cos(theta4) k4].

    None depends on the rates ``kin.a_dot``, ``kin.a_ddot``.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics` or :func:`stroke_kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    annex_slip : bool, optional
        Reproduce the annex's slip in the rod's gravity term, which has
        ``cos(2 delta) / (a + l)`` where ``k2`` belongs.

    Returns
    -------
    LagrangeTerms

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`, ``g`` is not finite and real, or
        ``annex_slip`` is not a bool.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> terms = lagrange_terms(stroke_kinematics(ANNEX, 0.6))      # rocker crank at right angles
    >>> round(float(terms.mass), 6), round(float(terms.potential_slope / G_MATHCAD), 6)
    (17.36, 4.4)
    """
    kin, g = checked_kinematics(kin), _validate.scalar(g, "g")
    return _lagrange_terms(kin, g, _validate.flag(annex_slip, "annex_slip"))


def _lagrange_terms(kin, g, annex_slip=False):
    """:func:`lagrange_terms` of checked input."""
    m = kin.mech
    r3 = kin.a + m.g3
    rot2 = m.Io2 + m.m3 * r3**2 + m.inertias[1]
    mass = rot2 * kin.k2**2 + m.m3 + m.Io4 * kin.k4**2
    slope = 2 * (rot2 * kin.k2 * kin.dk2 + m.m3 * r3 * kin.k2**2 + m.Io4 * kin.k4 * kin.dk4)
    k_rod = np.cos(2 * (kin.theta2 - kin.theta4)) / (kin.a + m.l) if annex_slip else kin.k2
    potential = g * (m.m2 * m.g2 * np.cos(kin.theta2) * kin.k2
                     + m.m3 * (np.sin(kin.theta2) + r3 * np.cos(kin.theta2) * k_rod)
                     + m.m4 * m.g4 * np.cos(kin.theta4) * kin.k4)
    return LagrangeTerms(mass, slope, potential)


def lagrange_force(kin: Kinematics, g: float = G_MATHCAD,
                   annex_slip: bool = False) -> np.ndarray:
    """Actuator force by Lagrange's equation, the annex's ``Q_dd``.

    ``Q = d/dt dT/da_dot - dT/da + dV/da = M a_ddot + M' a_dot**2 / 2 + V'``, with the terms of
    :func:`lagrange_terms`. The annex files this route under "Dinámica directa" (direct
    dynamics), but like ``Q_di`` it is inverse dynamics: the force from a prescribed motion.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    annex_slip : bool, optional
        Reproduce the annex's slip in the rod's gravity term (see :func:`lagrange_terms`).

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Raises
    ------
    ValueError
        As :func:`lagrange_terms`.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> kin = kinematics(ANNEX, [0.0, 0.25])
    >>> np.round(lagrange_force(kin), 5).tolist()
    [43.14926, 29.35295]
    """
    terms = lagrange_terms(kin, g, annex_slip)
    return terms.mass * kin.a_ddot + 0.5 * terms.mass_slope * kin.a_dot**2 + terms.potential_slope


@dataclass(frozen=True)
class Energy:
    """Kinetic and potential energy of the mechanism (J).

    Attributes
    ----------
    kinetic, potential : ndarray
        ``T`` and ``V`` (zero with every centre of mass at ``y = 0``).
    """

    kinetic: np.ndarray
    potential: np.ndarray

    @property
    def total(self):
        """``T + V`` (J)."""
        return self.kinetic + self.potential


def energy(kin: Kinematics, g: float = G_MATHCAD) -> "Energy":
    """Kinetic and potential energy, from the partial velocities and the positions.

    ``T = sum_i (m_i |J_i|**2 + I_Gi k_i**2) a_dot**2 / 2`` and ``V = g sum_i m_i y_Gi``.
    Only ``T`` uses the velocity coefficients: along a motion, the work of ``Q`` equals the
    change of ``T + V`` if, and only if, they are the derivatives of the positions.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.

    Returns
    -------
    Energy

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics` or ``g`` is not finite and real.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> e = energy(kinematics(ANNEX, 0.0))
    >>> round(float(e.kinetic), 6), round(float(e.potential), 5)
    (0.137069, 40.20726)
    """
    kin, g = checked_kinematics(kin), _validate.scalar(g, "g")
    pv, (mass, inertia) = partial_velocities(kin), _masses(kin)
    kinetic = 0.5 * np.sum(mass * np.abs(pv.v) ** 2 + inertia * pv.omega**2, axis=0) * kin.a_dot**2
    return Energy(kinetic, g * np.sum(mass * centres_of_mass(kin).imag, axis=0))


@dataclass(frozen=True, kw_only=True)
class ForwardDynamics(Result):
    """The motion that :func:`forward_dynamics` computes.

    The fields of ``mechnum.results.Result`` (``x``: the state ``(a, a_dot)`` at every node,
    shape ``(N, 2)``; ``status``: ``"converged"``, RK4 having taken every step;
    ``iterations``: its steps; ``nfev``: the force's calls), and:

    Attributes
    ----------
    t : ndarray, shape (N,)
        The nodes (s).
    """

    t: np.ndarray

    @property
    def a(self) -> np.ndarray:
        """ndarray, shape (N,): the stroke (m) at every node, ``x[:, 0]``."""
        return self.x[:, 0]

    @property
    def a_dot(self) -> np.ndarray:
        """ndarray, shape (N,): the rate (m/s) at every node, ``x[:, 1]``."""
        return self.x[:, 1]


def forward_dynamics(mech: Actuator, force: Callable, t: ArrayLike, a0: float, v0: float,
                     model: str = "exact", g: float = G_MATHCAD) -> ForwardDynamics:
    """The motion that a given actuator force produces, by RK4 (forward dynamics).

    Lagrange's equation solved for the acceleration,
    ``M(a) a_ddot = Q(t) - M'(a) a_dot**2 / 2 - V'(a)`` (:func:`lagrange_terms`), is integrated as
    the first-order system ``y = (a, a_dot)`` by :func:`mechnum.ode.rk4` on the nodes ``t``.

    Parameters
    ----------
    mech : Actuator
    force : callable
        ``force(t) -> float``: the actuator force ``Q`` (N) at time ``t`` (s); it is called at
        the nodes and halfway between them.
    t : array_like, shape (N,)
        The nodes (s), ``N >= 2``, strictly monotone.
    a0, v0 : float
        Stroke (m) and rate (m/s) at ``t[0]``.
    model : {"exact", "annex"}, optional
        The velocity coefficients of ``M`` and ``V'`` (:func:`stroke_kinematics`).
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.

    Returns
    -------
    ForwardDynamics

    Raises
    ------
    ValueError
        If an input is not finite and real, ``t`` has fewer than two nodes or is not monotone,
        ``force`` is not callable or returns something other than one finite real number.
    UnreachablePoseError, SingularJacobianError
        If the motion leaves the mechanism's range or reaches a dead point.

    Examples
    --------
    The force of the prescribed stroke, applied to the mechanism, gives that stroke back:

    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> a0, v0, _ = ANNEX.stroke(0.0)
    >>> motion = forward_dynamics(ANNEX, lambda s: lagrange_force(kinematics(ANNEX, s)), t, a0, v0)
    >>> bool(np.max(np.abs(motion.a - ANNEX.stroke(t)[0])) < 1e-8)
    True
    """
    if not callable(force):
        raise ValueError(f"force must be a callable force(t), got {force!r:.80}")
    t = _validate.array(t, "t", ndim=1)
    y0 = np.array([_validate.scalar(a0, "a0"), _validate.scalar(v0, "v0")])
    mech, g = checked(mech), _validate.scalar(g, "g")
    model = _validate.choice(model, MODELS, "model")

    def rate(time, y):
        q = _validate.scalar(force(time), "force(t)")
        terms = _lagrange_terms(kinematics_at(mech, y[0], y[1], 0.0, model), g)
        acc = (q - 0.5 * terms.mass_slope * y[1] ** 2 - terms.potential_slope) / terms.mass
        return np.array([y[1], acc])

    y = rk4(rate, y0, t)
    steps = len(t) - 1
    return ForwardDynamics(x=y, status="converged", message=f"{steps} RK4 steps",
                           iterations=steps, nfev=4 * steps, njev=0, t=t)
