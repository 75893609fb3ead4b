"""The actuator's loop: its assembly modes (forward), the stroke of a rocker angle (inverse), its
dead points, and the loop equations that Newton's method solves.

The loop ``(a + l) e^{i theta2} = O4 + b e^{i theta4}`` closes in the triangle ``O2 O4 A``
(:func:`forward`: both assembly modes, the triangle and its mirror image across ``O2 O4``), or
by Newton's method (:func:`solve_loop`) from a seed. Its Jacobian in ``(theta2, theta4)`` has the
determinant ``(a + l) b sin(theta2 - theta4)``: the dead points, where the cylinder and the
crank are aligned, are :func:`singular_points`.
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import UnreachablePoseError
from mechnum.mechanisms.actuator._model import Actuator, checked
from mechnum.newton import solve
from mechnum.results import Assemblies

# The law of cosines at a dead point (a + l = d +- b) rounds to a cosine a few units of
# round-off of its terms beyond +-1 (d^2 + b^2 + L^2 over 2 d b, for phi): within 8 eps of them,
# the triangle is flat, not impossible.
_ROUNDING = 8 * np.finfo(float).eps
# A rocker pin within 1e-12 of the pivots' distance from O2 lies on it, to round-off of the
# sum O4 + b e^{i theta4}: the cylinder's direction is then undefined.
_ON_PIVOT = 1e-12
MODES = (0, 1)
"""The two assembly modes: 0, the annex's (the rocker pin ``A`` on the side of ``O2 O4`` where
``theta4 = phi - beta``), and 1, its mirror image across the line ``O2 O4``."""


def triangle(mech: Actuator, a: np.ndarray, mode: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """``(theta2, theta4)`` of assembly mode ``mode`` at checked strokes ``a`` (the kernel of
    :func:`forward`).

    ``phi`` (at ``O4``) and ``psi`` (at ``O2``) follow from the law of cosines in the triangle of
    sides ``d``, ``b`` and ``a + l``; with ``beta = atan(o4 / o2)``, mode 0 is
    ``theta2 = pi - beta - psi``, ``theta4 = phi - beta``, and mode 1 its mirror image,
    ``theta2 = pi - beta + psi``, ``theta4 = -phi - beta``.

    Raises
    ------
    UnreachablePoseError
        If ``a + l`` is outside ``[|d - b|, d + b]``: the loop cannot close.
    """
    L = a + mech.l
    d, b = mech.d, mech.b
    with np.errstate(divide="ignore", invalid="ignore"):
        squares = d**2 + b**2 + L**2  # the round-off of each cosine: _ROUNDING of it
        cos_phi = (d**2 + b**2 - L**2) / (2 * d * b)
        cos_psi = (d**2 + L**2 - b**2) / (2 * d * L)
        bad = ~(np.abs(cos_phi) <= 1 + _ROUNDING * squares / (2 * d * b))
        bad |= ~(np.abs(cos_psi) <= 1 + _ROUNDING * squares / (2 * d * L)) | (L <= 0)
    if np.any(bad):
        first = np.flatnonzero(np.ravel(bad))[0]
        raise UnreachablePoseError(
            f"the loop cannot close: a + l = {np.ravel(L)[first]:.6g} m is outside "
            f"[|d - b|, d + b] = [{abs(d - b):.6g}, {d + b:.6g}] m")
    beta = np.arctan2(mech.o4, mech.o2)
    side = 1 - 2 * mode
    cos_psi, cos_phi = np.clip(cos_psi, -1.0, 1.0), np.clip(cos_phi, -1.0, 1.0)
    return np.pi - beta - side * np.arccos(cos_psi), side * np.arccos(cos_phi) - beta


def forward(mech: Actuator, a: ArrayLike) -> Assemblies:
    """Both assembly modes of the loop at the strokes ``a``: the forward problem, in closed form.

    Parameters
    ----------
    mech : Actuator
    a : array_like
        Strokes (m); finite and real. An empty array is valid.

    Returns
    -------
    mechnum.results.Assemblies
        ``x``, shape ``np.shape(a) + (2, 2)``: ``x[..., mode, :]`` is ``(theta2, theta4)``
        (rad) of mode 0 (the annex's) and mode 1 (its mirror image across ``O2 O4``);
        ``inputs``: the strokes.

    Raises
    ------
    ValueError
        If ``a`` is not finite and real, or ``mech`` is not an :class:`Actuator`.
    UnreachablePoseError
        If ``a + l`` is outside ``[|d - b|, d + b]``: the loop cannot close.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> np.degrees(forward(ANNEX, 0.6).x).round(4).tolist()   # the annex's mode first
    [[90.0, 0.0], [118.0725, -151.9275]]
    """
    mech, a = checked(mech), _validate.array(a, "a")
    x = np.stack([np.stack(triangle(mech, a, mode), axis=-1) for mode in MODES], axis=-2)
    return Assemblies.of(x, a, a.size, len(MODES))


def inverse(mech: Actuator, theta4: ArrayLike) -> np.ndarray:
    """The strokes that put the rocker at the angles ``theta4``: the inverse problem.

    The rocker places its pin ``A = O4 + b e^{i theta4}``; the cylinder points from ``O2`` at
    it, so ``a = |A| - l``, one stroke per angle (in the mode that the angle's side of
    ``O2 O4`` gives).

    Parameters
    ----------
    mech : Actuator
    theta4 : array_like
        Rocker angles (rad), finite and real.

    Returns
    -------
    ndarray
        Strokes (m), of ``theta4``'s shape.

    Raises
    ------
    ValueError
        If ``theta4`` is not finite and real, or ``mech`` is not an :class:`Actuator`.
    UnreachablePoseError
        If the pin ``A`` falls on ``O2`` (``b = d``): the cylinder has no direction.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> a = inverse(ANNEX, [0.0, 0.3])
    >>> a.round(6).tolist(), bool(np.allclose(forward(ANNEX, a).x[:, 0, 1], [0.0, 0.3]))
    ([0.6, 0.673938], True)
    """
    mech, theta4 = checked(mech), _validate.array(theta4, "theta4")
    pin = complex(-mech.o2, mech.o4) + mech.b * np.exp(1j * theta4)
    if np.any(np.abs(pin) <= _ON_PIVOT * mech.d):
        raise UnreachablePoseError("the rocker's pin A falls on the cylinder's pivot O2: the "
                                   "cylinder has no direction")
    return np.abs(pin) - mech.l


def singular_points(mech: Actuator) -> np.ndarray:
    """The strokes of the dead points: the cylinder and the crank aligned.

    There ``sin(theta2 - theta4) = 0``, the loop's Jacobian (determinant
    ``(a + l) b sin(theta2 - theta4)``) is singular, and the two assembly modes meet: ``A`` on
    the line ``O2 O4``, at ``a + l = d + b`` (extended) or ``|d - b|`` (folded). The velocity
    coefficients are infinite there (:func:`stroke_kinematics` refuses them).

    Parameters
    ----------
    mech : Actuator

    Returns
    -------
    ndarray, shape (2,)
        The two strokes (m), increasing (either may be negative: the stroke law decides
        whether the mechanism reaches them).

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> singular_points(ANNEX).round(6).tolist()
    [0.380776, 0.880776]
    """
    mech = checked(mech)
    return np.array([abs(mech.d - mech.b), mech.d + mech.b]) - mech.l


def _loop_inputs(mech, x, a):
    """The checked inputs of the loop equations: ``mech``, ``theta2`` and ``theta4`` from ``x`` of
    shape (..., 2), and the length ``a + l`` of the cylinder."""
    x = _validate.array(x, "x", ndim=range(1, 33))
    if x.shape[-1] != 2:
        raise ValueError(f"x must have shape (..., 2): pairs (theta2, theta4), "
                         f"got shape {x.shape}")
    mech = checked(mech)
    return mech, x[..., 0], x[..., 1], _validate.scalar(a, "a") + mech.l


def loop_residual(mech: Actuator, x: ArrayLike, a: float) -> np.ndarray:
    """The two loop equations ``(a + l) e^{i theta2} - O4 - b e^{i theta4} = 0``.

    Parameters
    ----------
    mech : Actuator
    x : array_like, shape (..., 2)
        ``(theta2, theta4)`` in radians, or a batch of such pairs.
    a : float
        Stroke (m).

    Returns
    -------
    ndarray, shape (..., 2)
        The x and y components of the loop's closure error (m).

    Raises
    ------
    ValueError
        If ``x`` is not finite and real with a last axis of length 2, ``a`` not a finite real
        number, or ``mech`` not an :class:`Actuator`.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> np.round(loop_residual(ANNEX, [np.pi / 2, 0.0], 0.6), 12) + 0.0
    array([0., 0.])
    """
    mech, th2, th4, L = _loop_inputs(mech, x, a)
    return np.stack([L * np.cos(th2) + mech.o2 - mech.b * np.cos(th4),
                     L * np.sin(th2) - mech.o4 - mech.b * np.sin(th4)], axis=-1)


def loop_jacobian(mech: Actuator, x: ArrayLike, a: float) -> np.ndarray:
    """Jacobian of :func:`loop_residual` with respect to ``(theta2, theta4)``.

    Its determinant is ``(a + l) b sin(theta2 - theta4)``: it vanishes at the dead points,
    where the cylinder and the crank are aligned, and at every guess with ``theta2 = theta4``.

    Parameters
    ----------
    mech, x, a
        As :func:`loop_residual`.

    Returns
    -------
    ndarray, shape (..., 2, 2)

    Raises
    ------
    ValueError
        As :func:`loop_residual`.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> round(float(np.linalg.det(loop_jacobian(ANNEX, [np.pi / 2, 0.0], 0.6))), 12)
    0.25
    """
    mech, th2, th4, L = _loop_inputs(mech, x, a)
    rows = [np.stack([-L * np.sin(th2), mech.b * np.sin(th4)], axis=-1),
            np.stack([L * np.cos(th2), -mech.b * np.cos(th4)], axis=-1)]
    return np.stack(rows, axis=-2)


def solve_loop(mech: Actuator, a: float, *, seed: ArrayLike = (np.pi / 2, 0.0),
               **options: object) -> object:
    """Solve the loop equations for one stroke by Newton-Raphson.

    Parameters
    ----------
    mech : Actuator
    a : float
        Stroke (m); must be finite and real.
    seed : array_like, shape (2,), optional
        Initial guess ``(theta2, theta4)``; its branch is the one found.
    **options
        Passed to :func:`mechnum.newton.solve` (``tol``, ``maxiter`` with its bound,
        ``criterion``, ``norm``, ``damping``).

    Returns
    -------
    mechnum.newton.NewtonResult
        ``x`` is ``(theta2, theta4)``.

    Raises
    ------
    ValueError
        If ``a`` or ``seed`` are not finite and real, or an option is invalid.
    SingularJacobianError, ConvergenceError
        From :func:`mechnum.newton.solve`: a guess with ``theta2 = theta4`` (singular Jacobian
        at the start), a pose out of reach (no convergence).

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> res = solve_loop(ANNEX, 0.62, seed=(1.5, 0.0))
    >>> np.round(res.x, 9).tolist() == np.round(forward(ANNEX, 0.62).x[0], 9).tolist()
    True
    """
    a = _validate.scalar(a, "a")
    mech = checked(mech)
    seed = _validate.array(seed, "seed", shape=(2,))
    return solve(lambda x: loop_residual(mech, x, a), seed,
                 lambda x: loop_jacobian(mech, x, a), **options)
