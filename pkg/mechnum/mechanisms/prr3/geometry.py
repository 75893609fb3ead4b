"""The 3PRR's geometry: its dimensions, its vertices, its loop equations and their Jacobians.

Everything here is a function of a pose ``(x, y, psi)`` and of the inputs ``lambdas``, vectorised
over any leading axes; the inverse and direct problems are built on it.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.errors import GeometryError

_ROOT3 = np.sqrt(3.0)

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
    """Dimensions of the 3PRR mechanism, in metres.

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


def vectors(value, name):
    """``value`` as a finite float array of shape ``(..., 3)`` (a pose or an input), checked."""
    out = _validate.array(value, name)
    if out.ndim == 0 or out.shape[-1] != 3:
        raise ValueError(f"{name} must have shape (..., 3), got shape {out.shape}")
    return out


def vertices(poses, geometry):
    """The platform vertices ``P1, P2, P3`` of poses ``(x, y, psi)``.

    Parameters
    ----------
    poses : array_like, shape (..., 3)
        ``(x, y, psi)`` in metres and radians.
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 3, 2)
        ``[..., i, :]`` is vertex ``P_{i+1}``.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> vertices([0.6, 0.4, 0.0], g).round(4).tolist()
    [[0.6, 0.4], [1.6, 0.4], [1.1, 1.266]]
    """
    return _vertices(vectors(poses, "poses"), geometry)


def _vertices(poses, geometry):
    x, y = poses[..., 0], poses[..., 1]
    c, s = geometry.a * np.cos(poses[..., 2]), geometry.a * np.sin(poses[..., 2])
    out = np.empty(poses.shape[:-1] + (3, 2))
    out[..., 0, 0], out[..., 0, 1] = x, y
    out[..., 1, 0], out[..., 1, 1] = x + c, y + s
    # (cos, sin)(psi + pi/3) by the rotation formulas: no second pair of trigonometric calls
    out[..., 2, 0], out[..., 2, 1] = x + (c - _ROOT3 * s) / 2, y + (s + _ROOT3 * c) / 2
    return out


def sliders(lambdas, geometry):
    """The slider points ``C1, C2, C3`` of inputs ``lambdas``.

    Parameters
    ----------
    lambdas : array_like, shape (..., 3)
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 3, 2)
        ``(lambda1, 0)``, ``(B2 - lambda2, 0)``, ``(B3, H3 - lambda3)``.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> sliders([1.0, 0.5, 0.25], g).tolist()
    [[1.0, 0.0], [2.5, 0.0], [1.5, 1.75]]
    """
    return _sliders(vectors(lambdas, "lambdas"), geometry)


def _sliders(lam, geometry):
    out = np.zeros(lam.shape[:-1] + (3, 2))
    out[..., 0, 0] = lam[..., 0]
    out[..., 1, 0] = geometry.B2 - lam[..., 1]
    out[..., 2, 0], out[..., 2, 1] = geometry.B3, geometry.H3 - lam[..., 2]
    return out


def radicands(poses, geometry):
    """The radicands of the inverse problem, one per leg (equations 62 to 64 of the study).

    Leg ``i`` can be assembled when its radicand is ``>= 0``; it is tangent to its guide (an
    inverse singularity: the two values of ``lambda_i`` merge) when it is zero.

    Parameters
    ----------
    poses : array_like, shape (..., 3)
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 3)
        ``L^2 - y_P^2``, ``L^2 - y_P2^2``, ``L^2 - (B3 - x_P3)^2`` in m^2 (``-inf`` for a pose
        so far away that the square overflows: it is unreachable).

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> radicands([0.6, 0.4, 0.0], g).round(4).tolist()
    [0.84, 0.84, 0.84]
    """
    v = _vertices(vectors(poses, "poses"), geometry)
    distance = np.stack([v[..., 0, 1], v[..., 1, 1], geometry.B3 - v[..., 2, 0]], axis=-1)
    with np.errstate(over="ignore"):
        return (geometry.L - distance) * (geometry.L + distance)


def bars(poses, lambdas, geometry):
    """The bar vectors ``P_i - C_i``, shape ``(..., 3, 2)``; poses and inputs broadcast.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> bars([0.6, 0.4, 0.0], [1.0, 0.5, 0.25], g)[0].tolist()
    [-0.4, 0.4]
    """
    return _bars(vectors(poses, "poses"), vectors(lambdas, "lambdas"), geometry)


def _bars(poses, lambdas, geometry):
    return _vertices(poses, geometry) - _sliders(lambdas, geometry)


def loop_residuals(poses, lambdas, geometry):
    """The loop-closure equations ``|P_i - C_i|^2 - L^2``, zero when the mechanism is assembled.

    Parameters
    ----------
    poses : array_like, shape (..., 3)
        ``(x, y, psi)``.
    lambdas : array_like, shape (..., 3)
        The inputs; broadcast against ``poses``.
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 3)
        In m^2.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> loop_residuals([0.6, 0.4, 0.0], [0.6, 0.5, 0.25], g).round(4).tolist()
    [-0.84, -0.03, -0.6058]
    """
    return _loop_residuals(vectors(poses, "poses"), vectors(lambdas, "lambdas"), geometry)


def _loop_residuals(poses, lambdas, geometry):
    with np.errstate(over="ignore", invalid="ignore"):
        return np.sum(_bars(poses, lambdas, geometry) ** 2, axis=-1) - geometry.L ** 2


def direct_jacobian(poses, lambdas, geometry):
    """Jacobian of :func:`loop_residuals` with respect to the pose ``(x, y, psi)``.

    It is singular at the direct (type II) singularities, where the platform gains a degree of
    freedom with the inputs locked: the three bars' lines are concurrent or parallel.

    Parameters
    ----------
    poses, lambdas : array_like, shape (..., 3)
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.newton import fd_jacobian
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> pose, lam = np.array([0.6, 0.4, 0.3]), np.array([1.5, 0.5, 0.2])
    >>> J = direct_jacobian(pose, lam, g)
    >>> bool(np.allclose(J, fd_jacobian(lambda p: loop_residuals(p, lam, g), pose), atol=1e-6))
    True
    """
    return _direct_jacobian(vectors(poses, "poses"), vectors(lambdas, "lambdas"), geometry)


def _direct_jacobian(poses, lambdas, geometry):
    u = _bars(poses, lambdas, geometry)
    v = _vertices(poses, geometry)
    lever = v - v[..., :1, :]  # P_i - P: its derivative with respect to psi is its normal
    dpsi = np.sum(u * np.stack([-lever[..., 1], lever[..., 0]], axis=-1), axis=-1)
    return 2 * np.concatenate([u, dpsi[..., None]], axis=-1)


def inverse_jacobian(poses, lambdas, geometry):
    """Jacobian of :func:`loop_residuals` with respect to the inputs: diagonal.

    Input ``i`` moves only slider ``i``, so ``dF_i/dlambda_i`` is twice the bar's component along
    its guide (with the guide's sign). It vanishes where the bar is perpendicular to its guide,
    the leg tangent: an inverse (type I) singularity, on the workspace boundary.

    Parameters
    ----------
    poses, lambdas : array_like, shape (..., 3)
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.newton import fd_jacobian
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> pose, lam = np.array([0.6, 0.4, 0.3]), np.array([1.5, 0.5, 0.2])
    >>> J = inverse_jacobian(pose, lam, g)
    >>> bool(np.allclose(J, fd_jacobian(lambda l: loop_residuals(pose, l, g), lam), atol=1e-6))
    True
    """
    u = _bars(vectors(poses, "poses"), vectors(lambdas, "lambdas"), geometry)
    along = np.stack([-u[..., 0, 0], u[..., 1, 0], u[..., 2, 1]], axis=-1)
    return 2 * along[..., None] * np.eye(3)


def jacobian_dets(poses, lambdas, geometry):
    """Dimensionless determinants of the inverse and the direct Jacobian.

    Each bar vector is divided by ``L`` and the column of ``psi`` by ``a``, so the entries are
    of order 1 and a determinant near 0 (below :data:`SINGULAR_DET`) means a singularity
    whatever the mechanism's size: inverse (a leg tangent to its guide), direct (the bars'
    lines concurrent or parallel), or combined (both at once).

    Parameters
    ----------
    poses, lambdas : array_like, shape (..., 3)
    geometry : Geometry

    Returns
    -------
    inverse_det, direct_det : ndarray, shape (...)

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> [round(float(d), 4) for d in jacobian_dets([0.6, 0.4, 0.0], [1.516515, 0.483485,
    ...                                           -0.182541], g)]
    [0.7699, -0.4]
    """
    return _jacobian_dets(vectors(poses, "poses"), vectors(lambdas, "lambdas"), geometry)


def _jacobian_dets(poses, lambdas, geometry):
    scale = 2 * geometry.L
    u = _bars(poses, lambdas, geometry)
    inverse = -u[..., 0, 0] * u[..., 1, 0] * u[..., 2, 1] / geometry.L ** 3
    direct = _direct_jacobian(poses, lambdas, geometry) / scale
    direct[..., 2] /= geometry.a
    return inverse, np.linalg.det(direct)


def draw(ax, pose, lambdas, geometry, *, color="tab:blue", alpha=1.0, guides=True):
    """Draw one configuration: the guides, the bars ``C_i P_i``, the sliders and the platform.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    pose, lambdas : array_like, shape (3,)
        The platform's pose and the inputs that assemble it.
    geometry : Geometry
    color : str, optional
        Colour of the bars and sliders.
    alpha : float, optional
        Opacity (to overlay several assembly modes).
    guides : bool, optional
        Whether to draw the fixed guides and the motors' origins.

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> len(draw(ax, [0.6, 0.4, 0.0], [1.516515, 0.483485, -0.182541], g)) > 0
    True
    >>> plt.close(fig)
    """
    v, c = vertices(pose, geometry), sliders(lambdas, geometry)
    if v.shape != (3, 2) or c.shape != (3, 2):
        raise ValueError("draw takes one pose and one input, each of shape (3,)")
    artists = []
    if guides:
        artists += [ax.axhline(0.0, color="0.75", lw=1), ax.axvline(geometry.B3, color="0.75",
                                                                    lw=1)]
        artists += ax.plot([0, geometry.B2, geometry.B3], [0, 0, geometry.H3], "k^", ms=5)
    artists += ax.fill(v[:, 0], v[:, 1], color="tab:orange", alpha=0.6 * alpha)
    for ci, pi in zip(c, v):
        artists += ax.plot([ci[0], pi[0]], [ci[1], pi[1]], "-", color=color, lw=2, alpha=alpha)
    artists += ax.plot(c[:, 0], c[:, 1], "s", color=color, ms=6, alpha=alpha)
    ax.set_aspect("equal")
    return artists
