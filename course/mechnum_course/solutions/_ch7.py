"""Chapter 7: the reference solutions and the typical mistakes."""

from types import SimpleNamespace

import numpy as np

from mechnum_course.solutions._solution import Solution


def velocity_coefficients(theta2, theta4, a, l, b):
    """The exact velocity coefficients ``k2`` and ``k4`` (rad/m).

    Parameters
    ----------
    theta2, theta4 : float
        The angles of the barrel and of the rocker (rad), at a closed loop.
    a, l, b : float
        The stroke, the rod beyond it and the crank ``O4 A`` (m).

    Returns
    -------
    k2, k4 : float
        ``d theta2 / da`` and ``d theta4 / da`` (rad/m).
    """
    delta = theta2 - theta4
    s, c = np.sin(delta), np.cos(delta)
    return c / ((a + l) * s), 1 / (b * s)


def force_by_virtual_power(kin, mech, g):
    """The actuator's force ``Q`` (N) at one instant, by virtual power.

    Parameters
    ----------
    kin : object
        The kinematics at the instant, as ``actuator.kinematics`` gives
        them: ``a, a_dot, a_ddot, theta2, theta4, k2, k4, omega2, omega4,
        eps2, eps4`` (SI units, angles in rad).
    mech : object
        The mechanism, as ``actuator.study.ANNEX``: ``m2, m3, m4, g2,
        g3, g4`` and ``inertias`` (``I_G2, I_G3, I_G4``), in SI units.
    g : float
        Gravity (m/s^2).
    """
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    r3, w2, w4 = kin.a + mech.g3, kin.omega2, kin.omega4
    eps, k = (kin.eps2, kin.eps2, kin.eps4), (kin.k2, kin.k2, kin.k4)
    coriolis = 2 * w2 * kin.a_dot  # the rod's centre slides on the barrel
    a_G = [mech.g2 * (1j * eps[0] - w2 ** 2) * e2,  # of G2, G3, G4
           (kin.a_ddot - r3 * w2 ** 2 + 1j * (r3 * eps[1] + coriolis)) * e2,
           mech.g4 * (1j * eps[2] - w4 ** 2) * e4]
    J = [1j * mech.g2 * k[0] * e2, (1 + 1j * r3 * k[1]) * e2,
         1j * mech.g4 * k[2] * e4]
    Q = 0.0
    for i, mass in enumerate((mech.m2, mech.m3, mech.m4)):
        Q += mass * (a_G[i] * np.conj(J[i])).real  # inertia force . J
        Q += mech.inertias[i] * eps[i] * k[i]  # inertia couple * k
        Q += mass * g * J[i].imag  # weight . J, sign reversed
    return Q


# Typical mistakes of 7.1
def _sheet(theta2, theta4, a, l, b):
    delta = theta2 - theta4
    return np.sin(delta) * np.cos(delta) / (a + l), np.sin(delta) / b


def _reversed_delta(theta2, theta4, a, l, b):
    return velocity_coefficients(theta4, theta2, a, l, b)


def _stroke_only(theta2, theta4, a, l, b):
    return velocity_coefficients(theta2, theta4, a, 0.0, b)



# Typical mistakes of 7.2
def _no_coriolis(kin, mech, g):
    # the Coriolis acceleration 2 omega2 a_dot (i e2) of the rod's centre, dotted with J3
    r3 = kin.a + mech.g3
    coriolis = mech.m3 * 2 * kin.omega2 * kin.a_dot * r3 * kin.k2
    return force_by_virtual_power(kin, mech, g) - coriolis


def _gravity_sign(kin, mech, g):
    return force_by_virtual_power(kin, mech, -g)


def _no_couples(kin, mech, g):
    return force_by_virtual_power(kin, SimpleNamespace(**{**vars(mech), "inertias": (0, 0, 0)}), g)


SOLUTIONS = {
    "7.1": Solution(velocity_coefficients, {"the sheet's coefficients": _sheet,
                                            "delta = theta4 - theta2": _reversed_delta,
                                            "the stroke for the distance O2 A": _stroke_only},
                    forbidden=("mechnum.mechanisms.actuator.kinematics",)),
    "7.2": Solution(force_by_virtual_power, {"the Coriolis term left out": _no_coriolis,
                                             "a sign of gravity": _gravity_sign,
                                             "the inertia couples left out": _no_couples},
                    forbidden=("mechnum.mechanisms.actuator.virtual_power_force",)),
}
