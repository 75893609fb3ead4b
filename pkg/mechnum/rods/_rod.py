"""The planar Kirchhoff rod: its state, its equations, and RK4 sweeps from the clamp.

Conventions: see :mod:`mechnum.rods`. A rod is integrated from its clamp by RK4 in the arc
fraction ``sigma = s / L`` on the state ``(x / L, y / L, theta, m)``; :func:`integrate` returns
the whole rod, :func:`tip_jacobian` its tip and the derivatives of the tip with respect to
``(m0, n_x, n_y)`` by the complex step.

**One sweep, any arithmetic.** :func:`sweep` is the RK4 loop written with arithmetic and two
trigonometric functions only, so that the same lines integrate one rod on Python floats
(``trig=math``; a numpy call costs about a microsecond whatever its size, a rod has four
states, and floats are an order of magnitude faster: ``bench/bench_rods.py``), one rod on
complex numbers (``trig=cmath``: the complex-step derivative) and a batch of rods on numpy
arrays, real or complex (``trig=numpy``). As ``x`` and ``y`` do not enter the right-hand
side, their RK4 stages need only the stages of ``theta``.
"""

import cmath
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from types import ModuleType

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import DivergenceError

STEP = 1e-30
"""The complex step: ``f(x + i h) = f(x) + i h f'(x) + O(h**2)``, with no cancellation."""
ANGLE_MAX = 1e12
"""Largest tangent angle (rad) a sweep may reach: beyond it the angle's rounding (``1e-4`` rad)
leaves its cosine with fewer than four digits, and the rod is noise (a force far too large for
the step)."""
SCALES = (1e-100, 1e100)
"""The range of ``EI`` (N m^2) and ``L`` (m) that the rods' formulas hold (their squares and
cubes finite), far beyond any physical rod."""
MAX_MODE = 10_000
"""The largest buckling mode accepted (its force, ``(mode pi)**2 EI / L**2``, stays finite and
its ``2 mode K`` half-waves keep their digits)."""
MAX_NODES = 100_000
"""Most nodes of a rod (a bound on the work: RK4's error on ``1e5`` nodes is below rounding for
every load that single shooting resolves)."""


@dataclass(frozen=True)
class Rod:
    """A deformed rod sampled at ``N`` nodes (leading batch axes first).

    Attributes
    ----------
    s, x, y, theta, m : ndarray, shape (..., N)
        Arc length from the clamp and the state there.
    force : ndarray, shape (..., 2)
        The internal force ``n`` (the force on the rod at its tip), N.
    """

    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    m: np.ndarray
    force: np.ndarray

    @property
    def tip(self) -> np.ndarray:
        """Tip position ``(x(L), y(L))``, shape (..., 2)."""
        return np.stack((self.x[..., -1], self.y[..., -1]), axis=-1)

    @property
    def tip_angle(self) -> np.ndarray:
        """Tangent angle at the tip, ``theta(L)`` (rad)."""
        return self.theta[..., -1]

    @property
    def clamp_moment(self) -> np.ndarray:
        """Bending moment at the clamp, ``m(0)`` (N m)."""
        return self.m[..., 0]


def as_vectors(value: ArrayLike, name: str, size: int) -> np.ndarray:
    """``value`` as a finite real float array whose last axis has length ``size``.

    Examples
    --------
    >>> as_vectors([[0.0, 1.0]], "force", 2).shape
    (1, 2)
    >>> as_vectors([0.0, 1.0, 2.0], "force", 2)
    Traceback (most recent call last):
    ...
    ValueError: force must have a last axis of length 2, got shape (3,)
    """
    out = _validate.array(value, name)
    if out.ndim == 0 or out.shape[-1] != size:
        raise ValueError(f"{name} must have a last axis of length {size}, got shape {out.shape}")
    return out


def rod_scales(EI: ArrayLike, L: ArrayLike, *, scalar: bool = False) -> tuple:
    """``EI`` and ``L`` checked: finite, positive and within :data:`SCALES`, where their squares
    and cubes stay finite (floats with ``scalar``, else float arrays).

    Examples
    --------
    >>> rod_scales(2.0, 0.5, scalar=True)
    (2.0, 0.5)
    >>> rod_scales(1.0, 1e300)
    Traceback (most recent call last):
    ...
    ValueError: L must lie within [1e-100, 1e+100], got 1.e+300
    """
    check = _validate.scalar if scalar else _validate.array
    out = []
    for value, name in ((EI, "EI"), (L, "L")):
        value = check(value, name)
        if not np.all(value > 0):
            raise ValueError(f"{name} must be positive, got {_validate.shown(value)}")
        if not np.all((value >= SCALES[0]) & (value <= SCALES[1])):
            raise ValueError(f"{name} must lie within [{SCALES[0]:g}, {SCALES[1]:g}], got "
                             f"{_validate.shown(value)}")
        out.append(value)
    return tuple(out)


def as_modes(mode: ArrayLike) -> np.ndarray:
    """``mode`` as a float array of integers ``>= 1`` (buckling modes), checked.

    Examples
    --------
    >>> as_modes([1, 2.0]).tolist()
    [1.0, 2.0]
    >>> as_modes(1.5)
    Traceback (most recent call last):
    ...
    ValueError: mode must be an integer >= 1, got 1.5
    """
    mode = _validate.array(mode, "mode")
    if np.any(mode < 1) or np.any(mode != np.round(mode)):
        raise ValueError(f"mode must be an integer >= 1, got {_validate.shown(mode)}")
    if np.any(mode > MAX_MODE):
        raise ValueError(f"mode must be at most {MAX_MODE}, got {_validate.shown(mode)}")
    return mode


def batch_shape(**shapes: tuple) -> tuple:
    """The one batch shape that the named shapes broadcast to, or a ValueError naming them.

    Examples
    --------
    >>> batch_shape(psi=(3,), t=(1,))
    (3,)
    >>> batch_shape(m0=(3,), force=(2,))
    Traceback (most recent call last):
    ...
    ValueError: the batch shapes of m0 (3,) and force (2,) do not broadcast to one shape
    """
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:
        named = " and ".join(f"{name} {shape}" for name, shape in shapes.items())
        raise ValueError(f"the batch shapes of {named} do not broadcast to one shape") from None


def equations(EI: ArrayLike, force: ArrayLike) -> Callable[[float, np.ndarray], np.ndarray]:
    """The rod's equations (the study's (78)) as ``f(s, state)``, for any ODE or BVP solver.

    ``state = (x, y, theta, m)`` along the **first** axis (shape ``(4,)`` for one point,
    ``(4, k)`` for ``k`` points, as :func:`scipy.integrate.solve_ivp` and
    :func:`scipy.integrate.solve_bvp` pass it); ``f`` returns ``(cos theta, sin theta,
    m / EI, n_x sin theta - n_y cos theta)`` of the same shape. :func:`sweep` integrates the
    same equations, in ``s / L``.

    Parameters
    ----------
    EI : float or array_like
        Bending stiffness (N m^2), positive.
    force : array_like, shape (2,)
        The force on the rod at its tip (N); it may be an unknown of a boundary value problem.

    Returns
    -------
    callable

    Raises
    ------
    ValueError
        If ``EI`` is not positive and finite, or ``force`` is not a finite 2-vector.

    Examples
    --------
    >>> f = equations(2.0, [0.0, 1.0])
    >>> f(0.0, np.array([0.0, 0.0, 0.0, 1.0])).tolist()
    [1.0, 0.0, 0.5, -1.0]
    """
    EI = rod_scales(EI, 1.0)[0]
    nx, ny = _validate.array(force, "force", shape=(2,))

    def f(s, state):
        theta, m = np.asarray(state)[2:]
        c, sn = np.cos(theta), np.sin(theta)
        return np.stack((c, sn, m / EI, nx * sn - ny * c))

    return f


def sweep(EI, L, m0, nx, ny, theta0, nodes: int, *, trig: ModuleType = math,
          keep: bool = True) -> tuple[list, list, list, list]:
    """The RK4 sweep of rods clamped at the origin, unchecked: lists of ``x, y, theta, m``.

    The stages are those of :func:`mechnum.ode.rk4` for ``(x / L, y / L, theta, m)`` in
    ``sigma = s / L``. The arguments are Python floats (``trig=math``), complex numbers
    (``trig=cmath``) or numpy arrays that broadcast together (``trig=numpy``); the result is
    four lists with the values at every node (with ``keep``) or at the tip only.

    Examples
    --------
    >>> x, y, theta, m = sweep(1.0, 1.0, 0.5, 0.0, 0.0, 0.0, 41, keep=False)
    >>> round(theta[0], 12), bool(abs(y[0] - (1 - math.cos(0.5)) / 0.5) < 1e-8)
    (0.5, True)
    """
    cos, sin = trig.cos, trig.sin
    c_EI, nx, ny, h = L / EI, nx * L, ny * L, 1.0 / (nodes - 1)
    half, sixth = 0.5 * h, h / 6.0
    x, y, t, m = 0.0, 0.0, theta0, m0
    xs, ys, ts, ms = [x], [y], [t], [m]
    for _ in range(nodes - 1):
        c1, s1 = cos(t), sin(t)
        t2, m2 = t + half * c_EI * m, m + half * (nx * s1 - ny * c1)
        c2, s2 = cos(t2), sin(t2)
        t3, m3 = t + half * c_EI * m2, m + half * (nx * s2 - ny * c2)
        c3, s3 = cos(t3), sin(t3)
        t4, m4 = t + h * c_EI * m3, m + h * (nx * s3 - ny * c3)
        c4, s4 = cos(t4), sin(t4)
        cc, ss = c1 + 2.0 * (c2 + c3) + c4, s1 + 2.0 * (s2 + s3) + s4
        x, y = x + sixth * cc, y + sixth * ss
        t, m = t + sixth * c_EI * (m + 2.0 * (m2 + m3) + m4), m + sixth * (nx * ss - ny * cc)
        if keep:
            xs.append(x), ys.append(y), ts.append(t), ms.append(m)
    if not keep:
        xs, ys, ts, ms = [x], [y], [t], [m]
    return [v * L for v in xs], [v * L for v in ys], ts, ms


def tip_states(EI: float, L: float, m0: np.ndarray, force: np.ndarray, theta0: float, nodes: int,
               columns: Sequence[int] = (0, 1, 2)) -> tuple[np.ndarray, np.ndarray | None]:
    """Tip states and their complex-step derivatives, unchecked (for shooting's Newton).

    ``EI``, ``L``, ``theta0`` are floats, ``m0`` of shape ``(batch,)`` and ``force`` of shape
    ``(batch, 2)``; ``columns`` picks among ``(m0, n_x, n_y)`` the unknowns to differentiate
    by (none: no Jacobian). One rod takes the float sweep (one complex sweep per column), a
    batch one numpy sweep of ``batch x len(columns)`` complex copies. Non-finite states (an
    overflowing sweep) come back as NaN.

    Returns
    -------
    tip : ndarray, shape (batch, 4)
        ``(x, y, theta, m)`` at ``s = L``.
    jacobian : ndarray, shape (batch, 4, len(columns)), or None without columns
        Derivatives exact to rounding (no subtraction).

    Examples
    --------
    >>> tip, J = tip_states(2.0, 1.0, np.zeros(1), np.array([[0.0, 1e-9]]), 0.0, 41, (0,))
    >>> round(float(J[0, 1, 0]), 8)     # dy(L)/dm0 = L**2 / (2 EI), linear beam theory
    0.25
    """
    columns = list(columns)
    if len(m0) == 1:
        args = [EI, L, float(m0[0]), float(force[0, 0]), float(force[0, 1]), theta0, nodes]
        try:
            J = np.empty((1, 4, len(columns)))
            for j, column in enumerate(columns):          # one complex sweep per unknown
                moved = list(args)
                moved[2 + column] += 1j * STEP
                end = sweep(*moved, trig=cmath, keep=False)
                J[0, :, j] = [v[0].imag / STEP for v in end]
            if not columns:
                end = sweep(*args, keep=False)
            tip = np.array([[v[0].real for v in end]])
        except (OverflowError, ValueError):      # math's and cmath's words for infinity
            tip, J = np.full((1, 4), np.nan), np.full((1, 4, len(columns)), np.nan)
    else:
        E = 1j * STEP * np.eye(3)[columns]                 # (k, 3): one copy per unknown
        m, n = m0[:, None] + E[:, 0], force[:, None, :] + E[:, 1:]
        if not columns:
            m, n = m0[:, None], force[:, None, :]
        with np.errstate(over="ignore", invalid="ignore"):     # Newton reads non-finite
            end = np.stack([v[0] for v in sweep(EI, L, m, n[..., 0], n[..., 1], theta0, nodes,
                                                trig=np, keep=False)], axis=-1)   # (b, k, 4)
        tip, J = end[:, 0, :].real, np.swapaxes(end.imag, 1, 2) / STEP
        tip = np.where(np.isfinite(tip), tip, np.nan)
    return tip, (J if columns else None)


def _inputs(EI, L, m0, force, theta0, origin, nodes):
    """Check the inputs of a sweep and broadcast them to one batch shape."""
    EI, L = rod_scales(EI, L)
    m0, theta0 = _validate.array(m0, "m0"), _validate.array(theta0, "theta0")
    force, origin = as_vectors(force, "force", 2), as_vectors(origin, "origin", 2)
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    shape = batch_shape(EI=EI.shape, L=L.shape, m0=m0.shape, theta0=theta0.shape,
                        force=force.shape[:-1], origin=origin.shape[:-1])
    EI, L, m0, theta0 = (np.broadcast_to(a, shape) for a in (EI, L, m0, theta0))
    force, origin = (np.broadcast_to(a, shape + (2,)) for a in (force, origin))
    return EI, L, m0, force, theta0, origin, nodes


def _finite(states, EI, L, force, nodes):
    """``states`` (last axis ``x, y, theta, m``), or a DivergenceError if the sweep overflowed
    or lost its angles' digits (a load far beyond RK4's step)."""
    if not np.isfinite(states).all() or np.abs(states[..., 2]).max(initial=0.0) > ANGLE_MAX:
        lam_h = np.sqrt(np.hypot(force[..., 0], force[..., 1]) / EI) * L / (nodes - 1)
        raise DivergenceError(f"the RK4 sweep overflowed: the force is too large for {nodes} "
                              f"nodes (lambda h = sqrt(|n| / EI) L / (nodes - 1) up to "
                              f"{np.max(lam_h):.3g}; RK4 resolves lambda h well below 1)")
    return states


def integrate(EI: ArrayLike, L: ArrayLike, m0: ArrayLike, force: ArrayLike, *,
              theta0: ArrayLike = 0.0, origin: ArrayLike = (0.0, 0.0), nodes: int = 41) -> Rod:
    """Integrate rods from their clamps by RK4, given the clamp moment and the force.

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m), positive.
    m0 : float or array_like
        Bending moment at the clamp, ``m(0)`` (N m).
    force : array_like, shape (..., 2)
        The internal force ``n``, the force on the rod at its tip (N).
    theta0 : float or array_like, optional
        Clamp angle (rad).
    origin : array_like, shape (..., 2), optional
        Clamp position (m).
    nodes : int, optional
        Number of equally spaced nodes, ends included (``nodes - 1`` RK4 steps),
        ``2 <= nodes <=`` :data:`MAX_NODES`.

    Returns
    -------
    Rod
        Arrays of shape ``batch + (nodes,)``, ``batch`` the broadcast of the inputs' shapes
        (possibly empty).

    Raises
    ------
    ValueError
        If an input is not finite, ``EI`` or ``L`` is not positive, the shapes do not
        broadcast, or ``nodes`` is out of range.
    DivergenceError
        If the sweep overflows or its angle passes :data:`ANGLE_MAX` (a force far too large
        for the step).

    Examples
    --------
    >>> rod = integrate(1.0, 1.0, 0.5, [0.0, 0.0], nodes=41)   # pure moment: a circular arc
    >>> bool(abs(rod.tip[1] - (1 - np.cos(0.5)) / 0.5) < 1e-8), round(float(rod.tip_angle), 12)
    (True, 0.5)
    """
    EI, L, m0, force, theta0, origin, nodes = _inputs(EI, L, m0, force, theta0, origin, nodes)
    if m0.size == 1:
        args = (float(v.flat[0]) for v in (EI, L, m0, force[..., 0], force[..., 1], theta0))
        try:
            Y = np.column_stack(sweep(*args, nodes)).reshape(m0.shape + (nodes, 4))
        except (OverflowError, ValueError):      # math's words for infinity
            Y = np.full(m0.shape + (nodes, 4), np.inf)
    else:
        with np.errstate(over="ignore", invalid="ignore"):
            Y = np.stack([np.stack(v, axis=-1) for v in sweep(
                EI, L, m0, force[..., 0], force[..., 1], theta0, nodes, trig=np)], axis=-1)
    Y = _finite(Y, EI, L, force, nodes)
    Y[..., 0] += origin[..., 0, None]
    Y[..., 1] += origin[..., 1, None]
    s = np.linspace(0.0, 1.0, nodes) * L[..., None]
    return Rod(s, Y[..., 0], Y[..., 1], Y[..., 2], Y[..., 3], np.array(force))


def tip_jacobian(EI: ArrayLike, L: ArrayLike, m0: ArrayLike, force: ArrayLike, *,
                 theta0: ArrayLike = 0.0, origin: ArrayLike = (0.0, 0.0),
                 nodes: int = 41) -> tuple[np.ndarray, np.ndarray]:
    """Tip state and its derivatives with respect to ``(m0, n_x, n_y)``, in one RK4 sweep.

    The derivatives are complex-step derivatives: each rod is integrated, in the same sweep, as
    three complex copies with ``m0``, ``n_x`` or ``n_y`` moved by ``i h`` (``h =``
    :data:`STEP`); the imaginary part of the tip over ``h`` is the derivative of the discrete
    RK4 map, exact to rounding (no subtraction, so no cancellation). This is the Jacobian a
    shooting Newton needs, for one rod or a batch; it equals the integral of the variational
    equations.

    Parameters
    ----------
    EI, L, m0, force, theta0, origin, nodes
        As in :func:`integrate`.

    Returns
    -------
    tip : ndarray, shape (..., 4)
        ``(x, y, theta, m)`` at ``s = L``.
    jacobian : ndarray, shape (..., 4, 3)
        ``d tip / d (m0, n_x, n_y)``.

    Raises
    ------
    ValueError, DivergenceError
        As :func:`integrate`.

    Examples
    --------
    Near the straight rod (linear beam theory, at fixed ``m0``): ``dy(L)/dm0 = L^2 / (2 EI)``
    and ``dy(L)/dn_y = -L^3 / (6 EI)``.

    >>> tip, J = tip_jacobian(2.0, 1.0, 0.0, [0.0, 1e-9])
    >>> round(float(J[1, 0]), 8), round(float(J[1, 2]), 8), round(float(J[3, 0]), 8)
    (0.25, -0.08333333, 1.0)
    """
    EI, L, m0, force, theta0, origin, nodes = _inputs(EI, L, m0, force, theta0, origin, nodes)
    return _tip_jacobian(EI, L, m0, force, theta0, origin, nodes)


def _tip_jacobian(EI, L, m0, force, theta0, origin, nodes):
    """:func:`tip_jacobian` on checked, broadcast input."""
    E = 1j * STEP * np.eye(3)
    with np.errstate(over="ignore", invalid="ignore"):
        end = np.stack([v[0] for v in sweep(
            EI[..., None], L[..., None], m0[..., None] + E[:, 0],
            force[..., None, 0] + E[:, 1], force[..., None, 1] + E[:, 2], theta0[..., None],
            nodes, trig=np, keep=False)], axis=-1)                         # (..., 3, 4)
    tip = _finite(end[..., 0, :].real, EI, L, force, nodes)
    tip[..., :2] += origin
    J = np.swapaxes(end.imag, -1, -2) / STEP
    if not np.isfinite(J).all():
        _finite(np.full(4, np.nan), EI, L, force, nodes)
    return tip, J


class ShotRods:
    """Rods of one stiffness and length shot by RK4 in a solver's loop: :func:`tip_jacobian`,
    its ``EI``, ``L`` and ``nodes`` checked once, when made, and its calls unchecked.

    Calling it with clamp moments ``m0`` (..., r), forces ``force`` (..., r, 2), clamp angles
    ``theta0`` and clamp positions ``origin`` (..., r, 2), all broadcast together, gives
    :func:`tip_jacobian`'s ``(tip, jacobian)``.

    Examples
    --------
    >>> tip, J = ShotRods(2.0, 1.0, 41)(np.zeros(1), np.array([[0.0, 1e-9]]), np.zeros(1),
    ...                                  np.zeros((1, 2)))
    >>> round(float(J[0, 1, 0]), 8)     # dy(L)/dm0 = L**2 / (2 EI), linear beam theory
    0.25
    """

    def __init__(self, EI: float, L: float, nodes: int = 41):
        self.EI, self.L = rod_scales(EI, L, scalar=True)
        self.nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)

    def __call__(self, m0: np.ndarray, force: np.ndarray, theta0: np.ndarray,
                 origin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        shape = np.broadcast_shapes(m0.shape, force.shape[:-1], np.shape(theta0),
                                    np.shape(origin)[:-1])
        EI, L = np.full(shape, self.EI), np.full(shape, self.L)
        return _tip_jacobian(EI, L, np.broadcast_to(m0, shape),
                             np.broadcast_to(force, shape + (2,)), np.broadcast_to(theta0, shape),
                             np.broadcast_to(origin, shape + (2,)), self.nodes)
