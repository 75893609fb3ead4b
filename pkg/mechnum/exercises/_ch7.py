"""Chapter 7, the hydraulic actuator: the exact velocity coefficients (7.1), and the force at
one instant by virtual power (7.2)."""

from types import SimpleNamespace

import numpy as np

from mechnum.exercises._harness import Case, Exercise, Mistake, close


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


ANNEX = SimpleNamespace(o2=0.25, o4=1.0, b=0.25, l=0.4, m2=5.0, m3=2.0, m4=1.0, g2=0.3, g3=0.2,
                        g4=0.6, inertias=(0.15, 2 * 0.4 ** 2 / 12, 0.6))
"""The parameters of the chapter's mechanism (the study's annex), as plain numbers."""


def _state(t, mech=ANNEX):
    """The exact kinematics at ``t`` for the stroke ``0.6 + 0.02 sin(2 pi t)``, from the
    triangle (the chapter's model section)."""
    w = 2 * np.pi
    a, a_dot, a_ddot = 0.6 + 0.02 * np.sin(w * t), 0.02 * w * np.cos(w * t), \
        -0.02 * w ** 2 * np.sin(w * t)
    d, beta, r = np.hypot(mech.o2, mech.o4), np.arctan2(mech.o4, mech.o2), a + mech.l
    theta4 = np.arccos((d ** 2 + mech.b ** 2 - r ** 2) / (2 * d * mech.b)) - beta
    theta2 = np.pi - beta - np.arccos((d ** 2 + r ** 2 - mech.b ** 2) / (2 * d * r))
    k2, k4 = velocity_coefficients(theta2, theta4, a, mech.l, mech.b)
    delta, d_delta = theta2 - theta4, k2 - k4
    dk2 = -d_delta / (r * np.sin(delta) ** 2) - np.cos(delta) / (r ** 2 * np.sin(delta))
    dk4 = -np.cos(delta) * d_delta / (mech.b * np.sin(delta) ** 2)
    return SimpleNamespace(theta2=theta2, theta4=theta4, k2=k2, k4=k4, omega2=k2 * a_dot,
                           omega4=k4 * a_dot, eps2=k2 * a_ddot + dk2 * a_dot ** 2,
                           eps4=k4 * a_ddot + dk4 * a_dot ** 2, a=a, a_dot=a_dot, a_ddot=a_ddot)


def _coefficient_cases():
    cases = []
    for t in (0.0, 0.1, 0.6):
        s = _state(t)
        cases.append(Case(f"the chapter's mechanism at t = {t} s",
                          (s.theta2, s.theta4, s.a, ANNEX.l, ANNEX.b)))
    other = SimpleNamespace(**{**vars(ANNEX), "o2": 0.1, "b": 0.35, "l": 0.5})
    s = _state(0.3, other)
    cases.append(Case("a mechanism with b = 0.35 m, l = 0.5 m at t = 0.3 s",
                      (s.theta2, s.theta4, s.a, other.l, other.b)))
    return cases


COEFFICIENTS = Exercise(
    number="7.1", label="ch7-ex-velocity-coefficients", title="the exact velocity coefficients",
    statement=(
        "**Implement it yourself.** Write `velocity_coefficients(theta2, theta4, a, l, b)`: "
        "differentiate the loop $(a + l)\\,\\mathbf e_2 = O_4 + b\\,\\mathbf e_4$ with respect "
        "to $a$, multiply by $\\mathbf e_2^{-1}$, and solve the real and imaginary parts for "
        "$k_2 = \\mathrm d\\theta_2/\\mathrm da$ and $k_4 = \\mathrm d\\theta_4/\\mathrm da$. "
        "Check them against central differences of the triangle's positions in $a$. Where do "
        "they differ from the sheet's, and by what factor?"),
    reference=velocity_coefficients, cases=_coefficient_cases,
    compare=lambda expected, got: close(expected, np.asarray(got, dtype=float), rtol=1e-12,
                                        atol=1e-14, what="(k2, k4)"),
    mistakes=(Mistake("the sheet's coefficients", "the loop divides by sin(delta); the sheet "
                      "multiplies by it (they agree only where delta = pi/2, as at t = 0).",
                      _sheet),
              Mistake("delta = theta4 - theta2", "delta = theta2 - theta4: with it reversed "
                      "both coefficients change sign.", _reversed_delta),
              Mistake("the stroke for the distance O2 A", "A is a + l from O2, not a.",
                      _stroke_only)),
    hint="the imaginary part of the differentiated loop gives a_dot = b omega4 sin(delta).")


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


def _force_cases():
    other = SimpleNamespace(**{**vars(ANNEX), "o2": 0.1, "b": 0.35, "l": 0.5, "m4": 3.0})
    return [Case(f"the chapter's mechanism at t = {t} s, g = 9.81 m/s^2",
                 (_state(t), ANNEX, 9.81)) for t in (0.1, 0.25, 0.7)] + [
        Case("a mechanism with b = 0.35 m, l = 0.5 m, m4 = 3 kg at t = 0.4 s, g = 9.80665",
             (_state(0.4, other), other, 9.80665))]


FORCE = Exercise(
    number="7.2", label="ch7-ex-virtual-power", title="the force at one instant by virtual power",
    statement=(
        "**Implement it yourself.** Write `force_by_virtual_power(kin, mech, g)`, the actuator's "
        "force $Q$ at one instant by virtual power: for the virtual motion $\\delta a = 1$, "
        "$Q = \\sum_i m_i\\,\\mathbf a_{G_i}\\cdot\\mathbf J_i + I_{G_i}\\varepsilon_i k_i "
        "+ m_i g J_{i,y}$, with the accelerations of the centres of mass by the relative-motion "
        "formulas of the chapter (the rod's centre has a Coriolis term $2\\omega_2\\dot a$). "
        "Compare with the package's `virtual_power_force` on `kinematics(ANNEX, t)`, and at "
        "$t = 0.25$ s, where the actuator stops, with the sheet's power divided by $\\dot a$."),
    reference=force_by_virtual_power, cases=_force_cases,
    compare=lambda expected, got: close(expected, float(got), rtol=1e-10, atol=1e-10,
                                        what="Q (N)"),
    mistakes=(Mistake("the Coriolis term left out", "the rod's centre slides along the turning "
                      "barrel: its acceleration has i 2 omega2 a_dot e2.", _no_coriolis),
              Mistake("a sign of gravity", "the weight's virtual power is -m g J_y; moved to "
                      "the side of Q it is + m g J_y.", _gravity_sign),
              Mistake("the inertia couples left out", "each link adds I_G epsilon k.",
                      _no_couples)),
    hint="with g = 0 and the actuator at rest (a_dot = a_ddot = 0) Q must be 0.")
