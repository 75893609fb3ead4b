"""Chapter 7, the hydraulic actuator: the exact velocity coefficients (7.1), and the force at
one instant by virtual power (7.2)."""

import dataclasses
from types import SimpleNamespace

from mechnum.exercises._answers import Real, Tuple, close
from mechnum.exercises._harness import Case, Exercise, Mistake
from mechnum.mechanisms import actuator
from mechnum.mechanisms.actuator.study import ANNEX

COEFFICIENTS_STARTER = '''\
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
    ...
'''

FORCE_STARTER = '''\
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
    ...
'''

STATE = ("theta2", "theta4", "k2", "k4", "omega2", "omega4", "eps2", "eps4", "a", "a_dot",
         "a_ddot")
"""The kinematics an answer of 7.2 reads, as ``actuator.kinematics`` gives them."""


def state(mech, t):
    """The kinematics of ``mech`` (an ``actuator.Actuator``) at ``t`` as plain numbers."""
    kin = actuator.kinematics(mech, t)
    return SimpleNamespace(**{name: float(getattr(kin, name)) for name in STATE})


OTHER = dataclasses.replace(ANNEX, o2=0.1, b=0.35, l=0.5)
"""A second mechanism, with another barrel pivot, crank and rod."""


def _coefficient_cases():
    cases = []
    for mech, t, label in [(ANNEX, t, f"the chapter's mechanism at t = {t} s")
                           for t in (0.0, 0.1, 0.6)] + [
            (OTHER, 0.3, "a mechanism with b = 0.35 m, l = 0.5 m at t = 0.3 s")]:
        s = state(mech, t)
        cases.append(Case(label, (s.theta2, s.theta4, s.a, mech.l, mech.b)))
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
    starter=COEFFICIENTS_STARTER, cases=_coefficient_cases,
    returns=Tuple(Real(), Real(), names=("k2", "k4")),
    compare=lambda expected, got: close(expected, got, rtol=1e-12, atol=1e-14,
                                        what="(k2, k4)"),
    mistakes=(Mistake("the sheet's coefficients", "the loop divides by sin(delta); the sheet "
                      "multiplies by it (they agree only where delta = pi/2, as at t = 0)."),
              Mistake("delta = theta4 - theta2", "delta = theta2 - theta4: with it reversed "
                      "both coefficients change sign."),
              Mistake("the stroke for the distance O2 A", "A is a + l from O2, not a.")),
    hint="the imaginary part of the differentiated loop gives a_dot = b omega4 sin(delta).")


def _force_cases():
    other = dataclasses.replace(OTHER, m4=3.0)
    return [Case(f"the chapter's mechanism at t = {t} s, g = 9.81 m/s^2",
                 (state(ANNEX, t), ANNEX, 9.81)) for t in (0.1, 0.25, 0.7)] + [
        Case("a mechanism with b = 0.35 m, l = 0.5 m, m4 = 3 kg at t = 0.4 s, g = 9.80665",
             (state(other, 0.4), other, 9.80665))]


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
    starter=FORCE_STARTER, cases=_force_cases, returns=Real(),
    compare=lambda expected, got: close(expected, got, rtol=1e-10, atol=1e-10, what="Q (N)"),
    mistakes=(Mistake("the Coriolis term left out", "the rod's centre slides along the turning "
                      "barrel: its acceleration has i 2 omega2 a_dot e2."),
              Mistake("a sign of gravity", "the weight's virtual power is -m g J_y; moved to "
                      "the side of Q it is + m g J_y."),
              Mistake("the inertia couples left out", "each link adds I_G epsilon k.")),
    hint="with g = 0 and the actuator at rest (a_dot = a_ddot = 0) Q must be 0.")
