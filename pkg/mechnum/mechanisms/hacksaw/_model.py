"""The saw and its motor: the unknowns, the links, the motor's profile, and the input checks.

The nine unknowns are ``NAMES``, in that order;
:class:`~mechnum.mechanisms.hacksaw.Geometry` holds the link lengths (``STUDY``: the study's),
and :func:`~mechnum.mechanisms.hacksaw.motor` gives the study's jerk-limited start of the motor.
The study's seeds and tolerance are here too, and the input checks that every public function
of the package shares (:func:`checked`, :func:`checked_motor`, :func:`finite`, and the decorator
:func:`evaluator` of the equations), so that the solvers can call the unchecked kernels
(``hacksaw``'s kernels module) inside Newton's loop.
"""

import functools
import inspect
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError

NAMES = ("r1", "theta1", "theta3", "Vr", "omega1", "omega3", "Ar", "alpha1", "alpha3")
ALPHA_MAX = 5.0  # rad/s^2, the study's maximum motor acceleration
TOL = 1e-6  # the study's tolerance on the Euclidean norm of the Newton step
#: The initial guess of the study's MATLAB code (``Pi``).
STUDY_SEED = np.array([-0.1, -0.5, 3.0, -0.5, 0.0, 0.5, -0.5, 0.0, 0.5])
#: The initial guess that the report prints: the MATLAB's with the six rates' signs flipped.
REPORT_SEED = np.array([-0.1, -0.5, 3.0, 0.5, 0.0, -0.5, 0.5, 0.0, -0.5])
#: The seed of the first trajectory point in the study's code: the rounded solution at rest.
TRAJECTORY_SEED = np.array([-0.0997, -0.4684, 2.8737, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
FORMS = ("loop", "eliminated")


@dataclass(frozen=True)
class Geometry:
    """The saw: its link lengths, in metres (defaults: the study's); the mechanism, the first
    argument of every function of the package.

    Raises
    ------
    GeometryError
        If a length is not a finite positive real number.

    Examples
    --------
    >>> Geometry(r3=0.2).r3
    0.2
    >>> Geometry(r2=-1.0)
    Traceback (most recent call last):
    ...
    mechnum.errors.GeometryError: r2 must be positive, got -1.0
    """

    r1y: float = 0.045
    r2: float = 0.075
    r3: float = 0.170

    def __post_init__(self):
        for name in ("r1y", "r2", "r3"):
            try:
                value = _validate.scalar(getattr(self, name), name, positive=True)
            except ValueError as error:
                raise GeometryError(str(error)) from None
            object.__setattr__(self, name, value)


STUDY = Geometry()


def checked(mech: object, states=(), motor=()) -> list:
    """Check the mechanism, states ``(name, value, width)`` of shape ``(..., width)`` and motor
    quantities ``(name, value)``; return the arrays, once their batch shapes are known to
    broadcast together.

    Examples
    --------
    >>> checked(None)
    Traceback (most recent call last):
    ...
    ValueError: mech must be a hacksaw.Geometry, got None
    """
    _validate.instance(mech, Geometry, "mech", "a hacksaw.Geometry")
    arrays, batches = [], []
    for name, value, width in states:
        a = _validate.array(value, name)
        if a.ndim == 0 or a.shape[-1] != width:
            raise ValueError(f"{name} must have shape (..., {width}), got shape {a.shape}")
        arrays.append(a)
        batches.append((name, a.shape[:-1]))
    for name, value in motor:
        arrays.append(_validate.array(value, name))
        batches.append((name, arrays[-1].shape))
    try:
        batch = np.broadcast_shapes(*(shape for _, shape in batches))
    except ValueError:
        shown = ", ".join(f"{name} {shape}" for name, shape in batches)
        raise ValueError(f"the batch shapes do not broadcast together: {shown}") from None
    return [np.array(np.broadcast_to(a, batch + a.shape[len(s):]))
            for a, (_, s) in zip(arrays, batches)]


def finite(out: np.ndarray, what: str) -> np.ndarray:
    """``out``, if finite; inputs that are finite may still overflow the formulas."""
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{what} is not finite for these inputs: they are too large "
                         f"(overflow) or the form is singular there")
    return out


def checked_motor(motor_state: object) -> list:
    """``(theta2, omega2, alpha2)``, checked: three finite real arrays that broadcast."""
    try:
        th2, w2, a2 = motor_state
    except (TypeError, ValueError):
        raise ValueError(f"motor_state must be (theta2, omega2, alpha2), "
                         f"got {motor_state!r:.80}") from None
    return checked(STUDY, motor=(("theta2", th2), ("omega2", w2), ("alpha2", a2)))


def first_revolution_time(alpha_max: float = ALPHA_MAX) -> float:
    """Time ``T`` of the motor's first revolution, from ``theta2(T) = alpha_max T**2 / 3 = 2 pi``.

    Raises
    ------
    ValueError
        If ``alpha_max`` is not a finite positive number, or so small that ``T`` overflows.

    Examples
    --------
    >>> round(first_revolution_time(), 6)
    1.941626
    """
    alpha_max = _validate.scalar(alpha_max, "alpha_max", positive=True)
    T = float(np.sqrt(6.0 * np.pi / alpha_max))
    if not np.isfinite(T):
        raise ValueError(f"alpha_max = {alpha_max!r} is too small: the first revolution "
                         f"time overflows")
    return T


def _motor(t, alpha_max):
    """The motor profile at checked times ``t`` (the kernel of :func:`motor`)."""
    T, A = first_revolution_time(alpha_max), alpha_max
    phase = np.minimum(np.floor(3.0 * t / T), 3.0).astype(int)  # 0, 1, 2 ramps; 3 cruise
    theta = np.choose(phase, [
        A * t**3 / (2 * T),
        A * T**2 / 54 - A * t * (T - 3 * t) / 6,
        A * T**2 / 6 - 5 * A * T * t / 6 + 3 * A * t**2 / 2 - A * t**3 / (2 * T),
        2 * A * T / 3 * (t - T / 2)])  # not 2 A T t / 3: its 2 A T t overflows first
    omega = np.choose(phase, [
        3 * A * t**2 / (2 * T),
        A * t - A * T / 6,
        3 * A * t - 5 * A * T / 6 - 3 * A * t**2 / (2 * T),
        np.full_like(t, 2 * A * T / 3)])
    alpha = np.choose(phase, [3 * A * t / T, np.full_like(t, A), 3 * A - 3 * A * t / T,
                              np.zeros_like(t)])
    return theta, omega, alpha


def motor(t: ArrayLike, alpha_max: float = ALPHA_MAX) -> tuple[np.ndarray, ...]:
    """Angle, speed and acceleration of the motor at times ``t`` (the study's profile).

    Parameters
    ----------
    t : array_like
        Times in seconds, ``t >= 0``.
    alpha_max : float, optional
        Largest angular acceleration, rad/s^2.

    Returns
    -------
    theta2, omega2, alpha2 : ndarray
        Each of the shape of ``t``, in rad, rad/s and rad/s^2.

    Raises
    ------
    ValueError
        If some ``t`` is negative or not finite, ``alpha_max`` is not finite and positive, or
        ``t`` is so large that the crank angle overflows.

    Examples
    --------
    >>> T = first_revolution_time()
    >>> [round(float(v), 6) for v in motor(T)]
    [6.283185, 6.472086, 0.0]
    """
    t = _validate.array(t, "t")
    if np.any(t < 0):
        raise ValueError(f"t must be non-negative, got a smallest t of {float(t.min())!r}")
    with np.errstate(over="ignore", invalid="ignore"):
        out = _motor(t, alpha_max)
    if not np.all(np.isfinite(out[0])):
        raise ValueError(f"t is too large: the crank angle overflows at t = {float(t.max())!r} s")
    return out


def evaluator(*states, motor=()) -> Callable[[Callable], Callable]:
    """Check the input and output of a public evaluator of the equations: the mechanism, the
    ``form`` if there is one, the ``states`` (``(name, width)``: arrays of shape
    ``(..., width)``) and the ``motor`` quantities (names), that their batch shapes broadcast,
    and that the result is finite. (The solvers call the kernels directly: inside Newton's
    loop the checks would only cost time.)"""
    def decorate(function):
        signature = inspect.signature(function)

        @functools.wraps(function)
        def public(*args, **kwargs):
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            given = bound.arguments
            values = checked(given["mech"], [(n, given[n], w) for n, w in states],
                             [(n, given[n]) for n in motor])
            given.update(zip([n for n, _ in states] + list(motor), values))
            if "form" in given:
                _validate.choice(given["form"], FORMS, "form")
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                out = function(*bound.args, **bound.kwargs)
            return finite(out, f"the {function.__name__.replace('_', ' ')}")

        return public
    return decorate
