"""The 3PRR's geometry: its dimensions, its vertices, its loop equations and their Jacobians.

Everything here is a function of the mechanism (:class:`Geometry`, first), of poses
``(x, y, psi)`` and of inputs ``lambdas``, vectorised over any leading axes; the inverse and
direct problems are built on it. Each function checks its input, then calls its kernel
(``prr3``'s kernels module).
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError
from mechnum.mechanisms.prr3 import _kernels as kernels

# Lengths are squared (radicands and loop residuals are in m^2) and the direct problem's
# polynomial has degree 8 in them: outside 1e-100 to 1e100 m these overflow or underflow
# double precision (range 1e-308 to 1e308), so such a geometry is refused with its name.
LENGTH_LIMITS = (1e-100, 1e100)
# The polynomial's terms scale as L^2 a^6 against a^8: past a ratio of 1e6 between L and a the
# smaller length's terms fall below 1e-12 of the others, and double precision (16 digits)
# cannot resolve the poses any more.
MAX_ASPECT = 1e6
# |det| below this (on the dimensionless Jacobians of :func:`jacobian_dets`, whose entries
# are of order 1) counts as a singularity: two assembly modes, or two working modes, meet.
SINGULAR_DET = 1e-6


@dataclass(frozen=True)
class Geometry:
    """The 3PRR mechanism: its dimensions, in metres (the first argument of every function).

    Attributes
    ----------
    L : float
        Length of the three bars (> 0).
    a : float
        Side of the equilateral platform (> 0).
    B2 : float
        Origin of guide 2 on the x axis (``lambda2`` is measured from it towards -x).
    B3, H3 : float
        Origin of the vertical guide 3 (``lambda3`` is measured from it towards -y).

    Raises
    ------
    ValueError
        If a dimension is not a finite real number.
    GeometryError
        If ``L`` or ``a`` is not positive, a length lies outside :data:`LENGTH_LIMITS`, or
        ``L`` and ``a`` differ by a factor above :data:`MAX_ASPECT`.

    Examples
    --------
    >>> Geometry(L=1, a=1, B2=3, B3=1.5, H3=2).a
    1.0
    >>> Geometry(L=1, a=0, B2=3, B3=1.5, H3=2)
    Traceback (most recent call last):
    ...
    mechnum.errors.GeometryError: geometry a must be positive, got 0.0
    """

    L: float
    a: float
    B2: float
    B3: float
    H3: float

    def __post_init__(self):
        for name in ("L", "a", "B2", "B3", "H3"):
            object.__setattr__(self, name, _validate.scalar(getattr(self, name),
                                                            f"geometry {name}"))
        low, high = LENGTH_LIMITS
        for name in ("L", "a"):
            value = getattr(self, name)
            if not value > 0:
                raise GeometryError(f"geometry {name} must be positive, got {value!r}")
            if not low <= value <= high:
                raise GeometryError(f"geometry {name} = {value!r} m lies outside the lengths "
                                    f"this module resolves, {low:g} to {high:g} m")
        for name in ("B2", "B3", "H3"):
            if abs(getattr(self, name)) > high:
                raise GeometryError(f"geometry {name} = {getattr(self, name)!r} m lies outside "
                                    f"the lengths this module resolves, |{name}| <= {high:g} m")
        if max(self.L, self.a) > MAX_ASPECT * min(self.L, self.a):
            raise GeometryError(f"geometry L = {self.L!r} and a = {self.a!r} differ by more "
                                f"than a factor {MAX_ASPECT:g}: the poses cannot be resolved")


def check(mech: object) -> "Geometry":
    """``mech`` if it is a :class:`Geometry`; else :class:`ValueError` naming it.

    Examples
    --------
    >>> check("prr3")
    Traceback (most recent call last):
    ValueError: mech must be a prr3.Geometry, got 'prr3'
    """
    return _validate.instance(mech, Geometry, "mech", "a prr3.Geometry")


def vectors(value: ArrayLike, name: str) -> np.ndarray:
    """``value`` as a finite float array of shape ``(..., 3)`` (a pose or an input), checked."""
    out = _validate.array(value, name)
    if out.ndim == 0 or out.shape[-1] != 3:
        raise ValueError(f"{name} must have shape (..., 3), got shape {out.shape}")
    return out


def resolved(values: np.ndarray, name: str) -> np.ndarray:
    """``values`` (checked poses or inputs) if their positions lie within ``1e100`` m, the
    lengths this module resolves; else a ValueError naming them. Beyond, the squares of the loop
    equations overflow (1e300 gave inf and then NaN), and no answer of the functions that
    compute those squares would carry a digit. (The workspace and :func:`inverse` take any
    finite pose: so far away nothing is reachable.)

    Examples
    --------
    >>> resolved(np.array([1e300, 0.0, 0.0]), "poses")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: poses must lie within 1e+100 m of the origin ..., got [1.e+300 0.e+000 0.e+000]
    """
    if values.size and np.abs(values).max() > LENGTH_LIMITS[1]:
        raise ValueError(f"{name} must lie within {LENGTH_LIMITS[1]:g} m of the origin (the "
                         f"lengths this module resolves: their squares would overflow), got "
                         f"{_validate.shown(values)}")
    return values


def pairs(poses: ArrayLike, lambdas: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Poses and inputs of shape ``(..., 3)`` whose batch shapes broadcast, checked."""
    poses, lambdas = vectors(poses, "poses"), vectors(lambdas, "lambdas")
    try:
        np.broadcast_shapes(poses.shape, lambdas.shape)
    except ValueError:
        raise ValueError(f"poses and lambdas must broadcast together, got shapes {poses.shape} "
                         f"and {lambdas.shape}") from None
    return poses, lambdas


def vertices(mech: Geometry, poses: ArrayLike) -> np.ndarray:
    """The platform vertices ``P1, P2, P3`` of poses ``(x, y, psi)``.

    Parameters
    ----------
    mech : Geometry
    poses : array_like, shape (..., 3)
        ``(x, y, psi)`` in metres and radians.

    Returns
    -------
    ndarray, shape (..., 3, 2)
        ``[..., i, :]`` is vertex ``P_{i+1}``.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> vertices(g, [0.6, 0.4, 0.0]).round(4).tolist()
    [[0.6, 0.4], [1.6, 0.4], [1.1, 1.266]]
    """
    return kernels.vertices(check(mech), vectors(poses, "poses"))


def sliders(mech: Geometry, lambdas: ArrayLike) -> np.ndarray:
    """The slider points ``C1, C2, C3`` of inputs ``lambdas``.

    Parameters
    ----------
    mech : Geometry
    lambdas : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 2)
        ``(lambda1, 0)``, ``(B2 - lambda2, 0)``, ``(B3, H3 - lambda3)``.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> sliders(g, [1.0, 0.5, 0.25]).tolist()
    [[1.0, 0.0], [2.5, 0.0], [1.5, 1.75]]
    """
    return kernels.sliders(check(mech), vectors(lambdas, "lambdas"))


def radicands(mech: Geometry, poses: ArrayLike) -> np.ndarray:
    """The radicands of the inverse problem, one per leg (equations 62 to 64 of the study).

    Leg ``i`` can be assembled when its radicand is ``>= 0``; it is tangent to its guide (an
    inverse singularity: the two values of ``lambda_i`` merge) when it is zero.

    Parameters
    ----------
    mech : Geometry
    poses : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3)
        ``L^2 - y_P^2``, ``L^2 - y_P2^2``, ``L^2 - (B3 - x_P3)^2`` in m^2.

    Raises
    ------
    ValueError
        If ``poses`` is ill-shaped, not finite, or beyond ``1e100`` m (:func:`resolved`).

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> radicands(g, [0.6, 0.4, 0.0]).round(4).tolist()
    [0.84, 0.84, 0.84]
    """
    return kernels.radicands(check(mech), resolved(vectors(poses, "poses"), "poses"))


def bars(mech: Geometry, poses: ArrayLike, lambdas: ArrayLike) -> np.ndarray:
    """The bar vectors ``P_i - C_i``, shape ``(..., 3, 2)``; poses and inputs broadcast.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> bars(g, [0.6, 0.4, 0.0], [1.0, 0.5, 0.25])[0].tolist()
    [-0.4, 0.4]
    """
    return kernels.bars(check(mech), *pairs(poses, lambdas))


def loop_residuals(mech: Geometry, poses: ArrayLike, lambdas: ArrayLike) -> np.ndarray:
    """The loop-closure equations ``|P_i - C_i|^2 - L^2``, zero when the mechanism is assembled.

    Parameters
    ----------
    mech : Geometry
    poses : array_like, shape (..., 3)
        ``(x, y, psi)``.
    lambdas : array_like, shape (..., 3)
        The inputs; broadcast against ``poses``.

    Returns
    -------
    ndarray, shape (..., 3)
        In m^2.

    Raises
    ------
    ValueError
        If an argument is not finite, beyond ``1e100`` m (:func:`resolved`), has no last axis
        of 3, or the two do not broadcast.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> loop_residuals(g, [0.6, 0.4, 0.0], [0.6, 0.5, 0.25]).round(4).tolist()
    [-0.84, -0.03, -0.6058]
    """
    poses, lambdas = pairs(poses, lambdas)
    return kernels.loop_residuals(check(mech), resolved(poses, "poses"),
                                  resolved(lambdas, "lambdas"))


def direct_jacobian(mech: Geometry, poses: ArrayLike, lambdas: ArrayLike) -> np.ndarray:
    """Jacobian of :func:`loop_residuals` with respect to the pose ``(x, y, psi)``.

    It is singular at the direct (type II) singularities, where the platform gains a degree of
    freedom with the inputs locked: the three bars' lines are concurrent or parallel.

    Parameters
    ----------
    mech : Geometry
    poses, lambdas : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.newton import fd_jacobian
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> pose, lam = np.array([0.6, 0.4, 0.3]), np.array([1.5, 0.5, 0.2])
    >>> J = direct_jacobian(g, pose, lam)
    >>> bool(np.allclose(J, fd_jacobian(lambda p: loop_residuals(g, p, lam), pose), atol=1e-6))
    True
    """
    return kernels.direct_jacobian(check(mech), *pairs(poses, lambdas))


def inverse_jacobian(mech: Geometry, poses: ArrayLike, lambdas: ArrayLike) -> np.ndarray:
    """Jacobian of :func:`loop_residuals` with respect to the inputs: diagonal.

    Input ``i`` moves only slider ``i``, so ``dF_i/dlambda_i`` is twice the bar's component along
    its guide (with the guide's sign). It vanishes where the bar is perpendicular to its guide,
    the leg tangent: an inverse (type I) singularity, on the workspace boundary.

    Parameters
    ----------
    mech : Geometry
    poses, lambdas : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> J = inverse_jacobian(g, [0.6, 0.4, 0.0], [0.6, 0.5, 0.25])  # bar 1 normal to guide 1
    >>> bool(np.all(J == np.diag(np.diag(J)))), (np.diag(J).round(4) + 0.0).tolist()
    (True, [0.0, -1.8, -0.9679])
    """
    u = kernels.bars(check(mech), *pairs(poses, lambdas))
    along = np.stack([-u[..., 0, 0], u[..., 1, 0], u[..., 2, 1]], axis=-1)
    return 2 * along[..., None] * np.eye(3)


def jacobian_dets(mech: Geometry, poses: ArrayLike,
                  lambdas: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Dimensionless determinants of the inverse and the direct Jacobian.

    Each bar vector is divided by ``L`` and the column of ``psi`` by ``a``, so the entries are
    of order 1 and a determinant near 0 (below :data:`SINGULAR_DET`) means a singularity
    whatever the mechanism's size: inverse (a leg tangent to its guide), direct (the bars'
    lines concurrent or parallel), or combined (both at once).

    Parameters
    ----------
    mech : Geometry
    poses, lambdas : array_like, shape (..., 3)

    Returns
    -------
    inverse_det, direct_det : ndarray, shape (...)

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> [round(float(d), 4) for d in jacobian_dets(g, [0.6, 0.4, 0.0], [1.516515, 0.483485,
    ...                                            -0.182541])]
    [0.7699, -0.4]
    """
    poses, lambdas = pairs(poses, lambdas)
    return kernels.jacobian_dets(check(mech), resolved(poses, "poses"),
                                 resolved(lambdas, "lambdas"))
