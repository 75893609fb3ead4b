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
:class:`ValueError` naming the argument; the solvers work on the unchecked kernels, so the
checks cost nothing inside Newton's loop.

What the package holds:

* the unknowns (:data:`NAMES`), the links (:class:`Geometry`) and the motor's profile
  (:func:`motor`, :func:`first_revolution_time`);
* the constraints and their Jacobians (:func:`position_residual`, :func:`position_jacobian`,
  :func:`rate_jacobian`, :func:`velocity_residual`, :func:`acceleration_residual`,
  :func:`residual`, :func:`jacobian`);
* the kinematics without iteration: in closed form (:func:`closed_form`, the study's mode;
  :func:`forward`, both assembly modes), the rates by linear solves (:func:`solve_rates`) and
  the singular points (:func:`singular_points`);
* Newton as the study applies it, to one point in stages (:func:`solve_consecutive`) or at
  once (:func:`solve_simultaneous`), and along a trajectory (:func:`sweep`);
* :func:`joints` and :func:`draw`.

The study's data (its saw, seeds and tolerance) and its reproduction are in
:mod:`mechnum.mechanisms.hacksaw.study`.

Examples
--------
>>> from mechnum.mechanisms import hacksaw
>>> saw = hacksaw.Geometry()                     # the study's link lengths
>>> hacksaw.forward(saw, (0.0, 0.0, 0.0)).x[0, :3].round(4).tolist()   # r1, theta1, theta3
[-0.0997, -0.4684, 2.8737]
"""

import importlib

from mechnum.mechanisms.hacksaw._drawing import draw, joints
from mechnum.mechanisms.hacksaw._equations import (
    jacobian,
    position_jacobian,
    position_residual,
    residual,
)

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.mechanisms.hacksaw._exact import SingularPoints as SingularPoints
from mechnum.mechanisms.hacksaw._exact import (
    closed_form,
    forward,
    singular_points,
)
from mechnum.mechanisms.hacksaw._model import NAMES, Geometry, first_revolution_time, motor
from mechnum.mechanisms.hacksaw._solvers import Stages as Stages
from mechnum.mechanisms.hacksaw._solvers import SweepResult as SweepResult
from mechnum.mechanisms.hacksaw._solvers import (
    solve_consecutive,
    solve_simultaneous,
    sweep,
)

__all__ = ["NAMES", "Geometry", "closed_form", "draw", "first_revolution_time", "forward",
           "jacobian", "joints", "motor", "position_jacobian", "position_residual", "residual",
           "singular_points", "solve_consecutive", "solve_simultaneous", "sweep"]


def __getattr__(name: str) -> object:
    """The :mod:`~mechnum.mechanisms.hacksaw.study` module, imported on first use."""
    if name == "study":
        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
