"""The power-hacksaw mechanism of the hacksaw study (report and slides; Chapter 1).

An offset crank-slider: the motor turns the crank ``r2`` (angle ``theta2``); the coupler ``r3``
(angle ``theta3``) drives the saw frame, whose pin slides on a guide at height ``r1y`` above the
crank pivot. The vector ``r1 = r2 + r3`` from the crank pivot to the slider pin has length ``r1``
and angle ``theta1``, with ``r1 sin(theta1) = r1y``. The study follows the branch with the coupler
pointing back (``theta3`` near ``pi``) and writes ``r1`` with a negative length, ``theta1`` in
``(-pi/2, 0)``; this module keeps that convention.

The nine unknowns, always in this order (SI units, radians)::

    r1, theta1, theta3, Vr, omega1, omega3, Ar, alpha1, alpha3

The constraint equations, in the study's row order:

* position ``(c, x, y)``: ``r1 sin(theta1) - r1y``, ``-r1 cos(theta1) + r2 cos(theta2) +
  r3 cos(theta3)``, ``r1 sin(theta1) - r2 sin(theta2) - r3 sin(theta3)``; the study's
  single-point code first eliminates ``r1 = r1y / sin(theta1)`` from the ``x`` and ``y`` rows
  (``form="eliminated"``), its trajectory code does not (``form="loop"``);
* velocity ``(x', y', c')`` and acceleration ``(c'', x'', y'')``: their first and second time
  derivatives, linear in the unknown rates with the matrix ``J`` of the loop form, whose
  determinant is ``-r1 r3 cos(theta3)``. Where ``cos(theta3) = 0`` (the coupler perpendicular to
  the guide) the rates are undefined: a *dead point*, which the solvers refuse
  (:class:`~mechnum.errors.SingularJacobianError`).

The motor starts from rest with a jerk-limited profile: the angular acceleration rises linearly to
``alpha_max`` over ``T/3``, holds for ``T/3`` and falls back to zero over ``T/3``, where ``T`` is
the time of the first revolution; the speed is constant afterwards.

Every function takes the mechanism, a :class:`Geometry`, first (``f(mech, inputs, ...)``);
the motor's state ``(theta2, omega2, alpha2)`` (or the time ``t``) is its input, and a state,
what :func:`draw` draws, is the pair ``(theta2, x)``. Every public function checks its input
(finite real arrays of the right shapes, a :class:`Geometry`, known options) and raises
:class:`ValueError` naming the argument; the solvers work on the unchecked kernels
(:mod:`~mechnum.mechanisms.hacksaw.kernels`), so the checks cost nothing inside Newton's loop.
The argument orders of version 0.1, with the geometry last, are deprecated (CHANGELOG.md).

The package's modules:

* :mod:`~mechnum.mechanisms.hacksaw.model`: the unknowns (``NAMES``), the links
  (:class:`Geometry`), the motor's profile (:func:`motor`, :func:`first_revolution_time`), the
  study's seeds and tolerance, and the input checks;
* :mod:`~mechnum.mechanisms.hacksaw.equations`: the constraints and their Jacobians
  (:func:`position_residual`, :func:`position_jacobian`, :func:`rate_jacobian`,
  :func:`velocity_residual`, :func:`acceleration_residual`, :func:`residual`,
  :func:`jacobian`);
* :mod:`~mechnum.mechanisms.hacksaw.kernels`: their formulas on checked input;
* :mod:`~mechnum.mechanisms.hacksaw.exact`: the kinematics without iteration, in closed form
  (:func:`closed_form`, both assembly modes: :func:`forward`), the rates by linear solves
  (:func:`solve_rates`) and the singular points (:func:`singular_points`);
* :mod:`~mechnum.mechanisms.hacksaw.solvers`: Newton as the study applies it, to one point in
  stages (:func:`solve_consecutive`) or at once (:func:`solve_simultaneous`), and along a
  trajectory (:func:`sweep`);
* :mod:`~mechnum.mechanisms.hacksaw.drawing`: :func:`joints` and :func:`draw`;
* :mod:`~mechnum.mechanisms.hacksaw.study`: :func:`reproduce`, the study's numbers.
"""

from mechnum.mechanisms.hacksaw.drawing import DRAW_PAD, draw, joints
from mechnum.mechanisms.hacksaw.equations import (
                                                  DEAD_POINT_COS,
                                                  acceleration_residual,
                                                  jacobian,
                                                  position_jacobian,
                                                  position_residual,
                                                  rate_jacobian,
                                                  residual,
                                                  velocity_residual,
)
from mechnum.mechanisms.hacksaw.exact import (
                                                  POSITION_RTOL,
                                                  SingularPoints,
                                                  closed_form,
                                                  forward,
                                                  singular_points,
                                                  solve_rates,
)
from mechnum.mechanisms.hacksaw.kernels import MODES
from mechnum.mechanisms.hacksaw.model import (
                                                  ALPHA_MAX,
                                                  FORMS,
                                                  NAMES,
                                                  REPORT_SEED,
                                                  STUDY,
                                                  STUDY_SEED,
                                                  TOL,
                                                  TRAJECTORY_SEED,
                                                  Geometry,
                                                  first_revolution_time,
                                                  motor,
)
from mechnum.mechanisms.hacksaw.solvers import (
                                                  MAX_POINTS,
                                                  METHODS,
                                                  PREDICTORS,
                                                  SweepResult,
                                                  solve_consecutive,
                                                  solve_simultaneous,
                                                  sweep,
)
from mechnum.mechanisms.hacksaw.study import reproduce

__all__ = [
    # model
    "NAMES", "ALPHA_MAX", "TOL", "STUDY_SEED", "REPORT_SEED", "TRAJECTORY_SEED", "FORMS",
    "Geometry", "STUDY", "first_revolution_time", "motor",
    # equations
    "DEAD_POINT_COS", "position_residual", "position_jacobian", "rate_jacobian",
    "velocity_residual", "acceleration_residual", "residual", "jacobian",
    # exact
    "MODES", "POSITION_RTOL", "closed_form", "forward", "solve_rates", "SingularPoints",
    "singular_points",
    # solvers
    "METHODS", "PREDICTORS", "MAX_POINTS", "solve_consecutive", "solve_simultaneous",
    "SweepResult", "sweep",
    # drawing
    "DRAW_PAD", "joints", "draw",
    # study
    "reproduce",
]
