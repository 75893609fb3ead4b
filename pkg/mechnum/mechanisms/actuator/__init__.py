"""The hydraulic-actuator mechanism of the study's Annex 3.2: the force the cylinder must exert.

The annex (a Mathcad sheet) drives a three-link mechanism with a hydraulic cylinder. The barrel
(link 2) turns about the ground pivot ``O2``; the rod (link 3) slides in it and turns with it; the
rod's end ``A`` is pinned to the rocker (link 4), which turns about ``O4``. With ``O2`` at the
origin and ``O4 = (-o2, o4)``, the pivots are ``d = sqrt(o2**2 + o4**2)`` apart and the loop closes
when

.. math:: (a + l)\\,e^{i\\theta_2} = O_4 + b\\,e^{i\\theta_4},

where ``a(t) = 0.6 + 0.02 sin(2 pi t)`` m is the cylinder's stroke, the one degree of freedom. The
annex solves the loop from the triangle ``O2 O4 A`` (:func:`forward`, both assembly modes, the
annex's first); :func:`solve_loop` solves the same two equations by
:func:`mechnum.newton.solve`. :func:`inverse` gives the stroke of a rocker angle, and
:func:`singular_points` the strokes of the dead points.

Every angular velocity is proportional to the stroke rate: ``omega_j = k_j(a) a_dot``, where
``k_j = d theta_j / d a`` is a *velocity coefficient*, and ``eps_j = k_j a_ddot + k_j' a_dot**2``.
With ``delta = theta_2 - theta_4`` the loop gives exactly

    ``k4 = 1 / (b sin delta)``,  ``k2 = cos delta / ((a + l) sin delta)``;

the annex uses instead ``k4 = sin delta / b`` and ``k2 = sin delta cos delta / (a + l)``, which
agree with the exact ones only where ``delta = pi/2`` (``model="annex"`` in :func:`kinematics`).
The velocity coefficients of the centres of mass are Kane's *partial velocities*
(:func:`partial_velocities`).

The force ``Q`` along the cylinder is *inverse dynamics* (the force from a prescribed motion), by
three routes that share the velocity coefficients and nothing else:

* virtual power (:func:`virtual_power_force`, the annex's ``Q_di``): the accelerations of the
  centres of mass by the relative-motion formulas (centripetal, tangential, Coriolis), their
  power over the virtual motion ``delta a = 1``;
* Kane's equations (:func:`kane_force`): the accelerations by differentiating ``v = J a_dot``;
* Lagrange's equation (:func:`lagrange_force`, the annex's ``Q_dd``):
  ``Q = M(a) a_ddot + M'(a) a_dot**2 / 2 + V'(a)`` (:func:`lagrange_terms`).

With consistent velocity coefficients (exact, or the annex's with their own derivatives) the
three agree to round-off. The annex's printed Lagrange formula does not: its rod gravity term has
``cos(2 delta) / (a + l)`` where ``k2`` belongs, which is the whole of the 0.0132088 N it reports
as the routes' numerical error (``annex_slip=True`` in :func:`lagrange_force` reproduces it).
*Forward* dynamics, the motion that a given force produces, integrates Lagrange's equation by
RK4 (:func:`forward_dynamics`); :func:`energy` gives ``T + V`` for the energy balance.

The parameters are those the annex prints (``ANNEX``,
in :mod:`mechnum.mechanisms.actuator.study` with the annex's numbers recomputed), suspicious
ones included: the rocker's centroidal inertia ``I_G4 = g4**2 m2 / 3`` uses the barrel's mass
``m2`` (printed ``I_O4 = 0.96`` confirms it), and its centre of mass lies ``g4 = 0.6`` m from
``O4`` though the crank ``b`` is 0.25 m long. Gravity is Mathcad's built-in ``g = 9.80665``
m/s**2, the only value that reproduces the printed ``Q(0) = 43.14926`` N.

Every function takes the mechanism, an :class:`Actuator`, first (``f(mech, inputs, ...)``);
the stroke ``a`` (or the time ``t``) is the input, and a state, what :func:`draw` draws, is the
pair ``(a, (theta2, theta4))``.

Examples
--------
>>> import numpy as np
>>> from mechnum.mechanisms import actuator
>>> np.degrees(actuator.forward(actuator.Actuator(), 0.6).x[0]).round(4).tolist()
[90.0, 0.0]
"""

import importlib

from mechnum.mechanisms.actuator._drawing import draw

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.mechanisms.actuator._dynamics import Energy as Energy
from mechnum.mechanisms.actuator._dynamics import ForwardDynamics as ForwardDynamics
from mechnum.mechanisms.actuator._dynamics import LagrangeTerms as LagrangeTerms
from mechnum.mechanisms.actuator._dynamics import (
    energy,
    forward_dynamics,
    kane_force,
    lagrange_force,
    lagrange_terms,
    virtual_power_force,
)
from mechnum.mechanisms.actuator._loop import (
    forward,
    inverse,
    loop_jacobian,
    loop_residual,
    singular_points,
    solve_loop,
)
from mechnum.mechanisms.actuator._model import Actuator
from mechnum.mechanisms.actuator._velocities import Kinematics as Kinematics
from mechnum.mechanisms.actuator._velocities import PartialVelocities as PartialVelocities
from mechnum.mechanisms.actuator._velocities import (
    kinematics,
    partial_velocities,
    stroke_kinematics,
)

__all__ = ["Actuator", "draw", "energy", "forward", "forward_dynamics", "inverse", "kane_force",
           "kinematics", "lagrange_force", "lagrange_terms", "loop_jacobian", "loop_residual",
           "partial_velocities", "singular_points", "solve_loop", "stroke_kinematics",
           "virtual_power_force"]


def __getattr__(name: str) -> object:
    """The :mod:`~mechnum.mechanisms.actuator.study` module, imported on first use."""
    if name == "study":
        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
