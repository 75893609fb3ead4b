"""The constraint equations of the saw and their Jacobians, for one state or a batch.

Position ``(c, x, y)`` in ``q = (r1, theta1, theta3)``
(:func:`~mechnum.mechanisms.hacksaw.position_residual`, in the loop or the eliminated form),
velocity ``(x', y', c')`` (:func:`~mechnum.mechanisms.hacksaw.velocity_residual`) and
acceleration ``(c'', x'', y'')`` (:func:`~mechnum.mechanisms.hacksaw.acceleration_residual`),
and all nine at once (:func:`~mechnum.mechanisms.hacksaw.residual`). The rate equations are
linear in their unknowns, with the position Jacobian as their matrix, rows permuted
(:func:`~mechnum.mechanisms.hacksaw.rate_jacobian`); the 9x9 Jacobian
(:func:`~mechnum.mechanisms.hacksaw.jacobian`) is block lower triangular. Where
``|cos(theta3)|`` falls below ``DEAD_POINT_COS`` (a dead point) the rate equations are
singular. Each evaluator takes the mechanism first, checks its input and calls its kernel
(``hacksaw``'s kernels module), which the solvers call directly.
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum.mechanisms.hacksaw import _kernels as kernels
from mechnum.mechanisms.hacksaw._kernels import DEAD_POINT_COS, RATE_ROWS
from mechnum.mechanisms.hacksaw._model import Geometry, evaluator

__all__ = ["DEAD_POINT_COS", "position_residual", "position_jacobian", "rate_jacobian",
           "velocity_residual", "acceleration_residual", "residual", "jacobian"]


@evaluator(("q", 3), motor=("theta2",))
def position_residual(mech: Geometry, q: ArrayLike, theta2: ArrayLike,
                      form: str = "loop") -> np.ndarray:
    """Position constraints ``(c, x, y)`` at ``q = (r1, theta1, theta3)``.

    ``form="loop"`` is the loop equation as written; ``form="eliminated"`` replaces ``r1`` by
    ``r1y / sin(theta1)`` in the ``x`` and ``y`` rows, as the study's single-point code does.

    Parameters
    ----------
    mech : Geometry
    q : array_like, shape (..., 3)
    theta2 : array_like
        Crank angles, broadcasting against the batch shape ``q.shape[:-1]``.
    form : {"loop", "eliminated"}, optional

    Returns
    -------
    ndarray, shape: the broadcast batch shape ``+ (3,)``

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> q = closed_form(STUDY, 0.0)[:3]
    >>> bool(np.allclose(position_residual(STUDY, q, 0.0), 0, atol=1e-14))
    True
    """
    return kernels.loop(mech, q, kernels.crank(theta2), form)


@evaluator(("q", 3))
def position_jacobian(mech: Geometry, q: ArrayLike, form: str = "loop") -> np.ndarray:
    """Jacobian of :func:`position_residual` with respect to ``(r1, theta1, theta3)``.

    Its determinant, in the loop form, is ``-r1 r3 cos(theta3)``.

    Returns
    -------
    ndarray, shape ``q.shape[:-1] + (3, 3)``

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> J = position_jacobian(STUDY, np.array([-0.1, -0.5, 3.0]))
    >>> bool(np.isclose(np.linalg.det(J), 0.1 * 0.17 * np.cos(3.0)))
    True
    """
    return kernels.loop_jacobian(mech, q, form)


def rate_jacobian(mech: Geometry, q: ArrayLike) -> np.ndarray:
    """Jacobian of the velocity constraints ``(x', y', c')`` in ``(Vr, omega1, omega3)``.

    The acceleration constraints ``(c'', x'', y'')`` have the same matrix in
    ``(Ar, alpha1, alpha3)`` with its rows in their order: :func:`position_jacobian`.

    Returns
    -------
    ndarray, shape ``q.shape[:-1] + (3, 3)``

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> q = closed_form(STUDY, 0.0)[:3]
    >>> bool(np.allclose(rate_jacobian(STUDY, q)[2], position_jacobian(STUDY, q)[0]))
    True
    """
    return position_jacobian(mech, q)[..., RATE_ROWS, :]


@evaluator(("v", 3), ("q", 3), motor=("theta2", "omega2"))
def velocity_residual(mech: Geometry, v: ArrayLike, q: ArrayLike, theta2: ArrayLike,
                      omega2: ArrayLike) -> np.ndarray:
    """Velocity constraints ``(x', y', c')`` at ``v = (Vr, omega1, omega3)``, given ``q``.

    Returns
    -------
    ndarray, shape: the broadcast batch shape of the inputs ``+ (3,)``

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form, motor
    >>> x = closed_form(STUDY, 0.5)
    >>> th2, w2, _ = motor(0.5)
    >>> bool(np.abs(velocity_residual(STUDY, x[3:6], x[:3], th2, w2)).max() < 1e-15)
    True
    """
    return kernels.velocity(mech, v, q, kernels.crank(theta2), omega2)


@evaluator(("a", 3), ("v", 3), ("q", 3), motor=("theta2", "omega2", "alpha2"))
def acceleration_residual(mech: Geometry, a: ArrayLike, v: ArrayLike, q: ArrayLike,
                          theta2: ArrayLike, omega2: ArrayLike, alpha2: ArrayLike) -> np.ndarray:
    """Acceleration constraints ``(c'', x'', y'')`` at ``a = (Ar, alpha1, alpha3)``.

    Returns
    -------
    ndarray, shape: the broadcast batch shape of the inputs ``+ (3,)``

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form, motor
    >>> x = closed_form(STUDY, 0.5)
    >>> bool(np.abs(acceleration_residual(STUDY, x[6:], x[3:6], x[:3], *motor(0.5))).max()
    ...      < 1e-13)
    True
    """
    return kernels.acceleration(mech, a, v, q, kernels.crank(theta2), omega2, alpha2)


@evaluator(("x", 9), motor=("theta2", "omega2", "alpha2"))
def residual(mech: Geometry, x: ArrayLike, theta2: ArrayLike, omega2: ArrayLike,
             alpha2: ArrayLike) -> np.ndarray:
    """All nine constraints (position, velocity, acceleration) at the states ``x``.

    Parameters
    ----------
    mech : Geometry
    x : array_like, shape (..., 9)
    theta2, omega2, alpha2 : array_like
        The motor state, broadcasting against the batch shape ``x.shape[:-1]``.

    Returns
    -------
    ndarray, shape: the broadcast batch shape ``+ (9,)``

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form, motor
    >>> x = closed_form(STUDY, 1.0)
    >>> bool(np.abs(residual(STUDY, x, *motor(1.0))).max() < 1e-14)
    True
    """
    return kernels.residual(mech, x, kernels.crank(theta2), omega2, alpha2)


@evaluator(("x", 9))
def jacobian(mech: Geometry, x: ArrayLike) -> np.ndarray:
    """Jacobian of :func:`residual` in the nine unknowns; shape ``x.shape[:-1] + (9, 9)``.

    Block lower triangular: position rows depend on ``q`` only, velocity rows on ``q`` and
    ``v``; the diagonal blocks are the position Jacobian (rows permuted for the velocity).

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> x = closed_form(STUDY, 0.5)
    >>> J = jacobian(STUDY, x)
    >>> bool(np.allclose(J[3:6, 3:6], rate_jacobian(STUDY, x[:3])) and not J[0:3, 3:].any())
    True
    """
    return kernels.jacobian(mech, x)
