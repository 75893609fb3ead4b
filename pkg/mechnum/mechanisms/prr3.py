"""The rigid 3PRR planar parallel mechanism of seed 001 (thesis section 11.1, Annexes I and II).

Three legs carry a triangular platform of side ``a``. Each leg is a slider ``C_i`` on a fixed
guide (the prismatic input ``lambda_i``) and a bar of length ``L`` from ``C_i`` to a vertex
``P_i`` of the platform:

* leg 1: ``C1 = (lambda1, 0)``, bar to ``P1 = P = (x, y)``;
* leg 2: ``C2 = (B2 - lambda2, 0)``, bar to ``P2 = P + a (cos psi, sin psi)``;
* leg 3: ``C3 = (B3, H3 - lambda3)`` on the vertical guide ``x = B3``, bar to
  ``P3 = P + a (cos(psi + pi/3), sin(psi + pi/3))``.

The loop-closure equations, with the bar angles eliminated, are ``|P_i - C_i|^2 = L^2``
(:func:`loop_residuals`).

* Inverse problem (pose -> inputs): each leg is a line-circle intersection, two values or one
  (tangency: an inverse singularity) or none; up to 8 combinations (:func:`inverse`).
* Direct problem (inputs -> poses): subtracting the circle of leg 1 from the other two leaves
  two equations linear in ``(x, y)`` (the radical axes); solving them and substituting into leg 1
  gives, with ``t = tan(psi/2)``, the study's polynomial of degree 8 (:func:`polynomial`). It
  always has the factor ``1 + t^2``, so at most 6 real roots remain (:func:`solve_direct`,
  :func:`direct`).
* Workspace: the poses for which every leg's radicand is non-negative (:func:`workspace`).
"""

from dataclasses import dataclass
from itertools import product

import numpy as np

from mechnum.errors import GeometryError
from mechnum.newton import solve_batch

_ROOT3 = np.sqrt(3.0)


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
        If a dimension is not a finite number.
    GeometryError
        If ``L`` or ``a`` is not positive.

    Examples
    --------
    >>> Geometry(L=1, a=1, B2=3, B3=1.5, H3=2).a
    1.0
    """

    L: float
    a: float
    B2: float
    B3: float
    H3: float

    def __post_init__(self):
        for name in ("L", "a", "B2", "B3", "H3"):
            value = getattr(self, name)
            if np.ndim(value) != 0 or not np.isfinite(float(value)):
                raise ValueError(f"geometry {name} must be a finite number, got {value!r}")
            object.__setattr__(self, name, float(value))
        for name in ("L", "a"):
            if getattr(self, name) <= 0:
                raise GeometryError(f"geometry {name} must be positive, got {getattr(self, name)}")


def _triples(values, what):
    """``values`` as a float array of shape ``(..., 3)``, or ValueError."""
    arr = np.asarray(values, dtype=float)
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise ValueError(f"{what} must have shape (..., 3), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{what} must be finite, got {values!r}")
    return arr


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
    x, y, psi = np.moveaxis(_triples(poses, "poses"), -1, 0)
    angles = np.stack([psi, psi + np.pi / 3], axis=-1)
    offsets = geometry.a * np.stack([np.cos(angles), np.sin(angles)], axis=-1)
    p = np.stack([x, y], axis=-1)[..., None, :]
    return np.concatenate([p, p + offsets], axis=-2)


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
        ``L^2 - y_P^2``, ``L^2 - y_P2^2``, ``L^2 - (B3 - x_P3)^2``.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> radicands([0.6, 0.4, 0.0], g).round(4).tolist()
    [0.84, 0.84, 0.84]
    """
    v = vertices(poses, geometry)
    distance = np.stack([v[..., 0, 1], v[..., 1, 1], geometry.B3 - v[..., 2, 0]], axis=-1)
    return geometry.L ** 2 - distance ** 2


def workspace(x, y, psi, geometry, *, tol=1e-12):
    """Reachability of every pose of a grid: can the inverse problem be solved there?

    Parameters
    ----------
    x, y, psi : array_like
        Coordinates (m) and orientation (rad) of the poses; broadcast against each other (use
        :func:`numpy.meshgrid` with ``indexing="ij"`` for a full grid).
    geometry : Geometry
    tol : float, optional
        A radicand down to ``-tol * L**2`` counts as zero (a tangent leg is reachable).

    Returns
    -------
    ndarray of bool
        True where all three legs can be assembled; the broadcast shape of the inputs.

    Examples
    --------
    >>> import numpy as np
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> workspace(np.array([0.6, 0.6]), np.array([0.4, 1.2]), 0.0, g).tolist()
    [True, False]
    """
    poses = np.stack(np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, psi))),
                     axis=-1)
    return np.all(radicands(poses, geometry) >= -tol * geometry.L ** 2, axis=-1)


def inverse(pose, geometry, *, tol=1e-12):
    """All the inputs ``(lambda1, lambda2, lambda3)`` that assemble the mechanism in ``pose``.

    Each leg gives two values of its input (line-circle intersection, equations 53, 57, 61 of the
    study), one when the leg is tangent to its guide (``|radicand| <= tol * L**2``: an inverse
    singularity, reported by :func:`radicands`), none when the pose is out of its reach. The
    solutions are all the combinations, in the order of the study's tables: ``lambda1`` with
    ``+`` first, ``lambda2`` and ``lambda3`` with ``-`` first.

    Parameters
    ----------
    pose : array_like, shape (3,)
        ``(x, y, psi)`` in metres and radians.
    geometry : Geometry
    tol : float, optional
        Relative tolerance of tangency.

    Returns
    -------
    ndarray, shape (n, 3)
        ``n = 8`` in general, 4, 2 or 1 with tangent legs, 0 for an unreachable pose.

    Raises
    ------
    ValueError
        If ``pose`` is not three finite numbers.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> inverse([0.6, 0.4, 0.0], g)[:2].round(5).tolist()
    [[1.51652, 0.48348, -0.18254], [1.51652, 0.48348, 1.65049]]
    >>> inverse([0.6, 1.4, 0.0], g).shape
    (0, 3)
    """
    pose = _triples(pose, "pose")
    if pose.shape != (3,):
        raise ValueError(f"pose must have shape (3,), got {pose.shape}")
    rad = radicands(pose, geometry)
    if np.any(rad < -tol * geometry.L ** 2):
        return np.empty((0, 3))
    first = branch_inputs(pose, geometry, (1, -1, -1), tol=tol)
    second = branch_inputs(pose, geometry, (-1, 1, 1), tol=tol)
    tangent = np.abs(rad) <= tol * geometry.L ** 2
    return np.array(list(product(*([f, s][:1 if t else 2]
                                    for f, s, t in zip(first, second, tangent)))))


def branch_inputs(poses, geometry, signs=(1, -1, -1), *, tol=1e-12):
    """The inputs of one working mode (one branch of each leg), vectorised over poses.

    ``lambda1 = x_P + s1 r1``, ``lambda2 = B2 - x_P2 + s2 r2``, ``lambda3 = H3 - y_P3 + s3 r3``
    with ``r_i`` the square roots of :func:`radicands` (zero for a tangent leg): equations 53,
    57 and 61 of the study, whose first solution is ``signs = (1, -1, -1)``. A working mode is
    a continuous function of the pose inside the workspace, as a path or a singularity map needs.

    Parameters
    ----------
    poses : array_like, shape (..., 3)
    geometry : Geometry
    signs : array_like of +-1, shape (3,)
        The branch of each leg.
    tol : float, optional
        A radicand down to ``-tol * L**2`` counts as zero.

    Returns
    -------
    ndarray, shape (..., 3)
        NaN for the legs that cannot reach their guide.

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> branch_inputs([[0.6, 0.4, 0.0], [0.6, 1.4, 0.0]], g).round(4).tolist()
    [[1.5165, 0.4835, -0.1825], [nan, nan, -1.1825]]
    """
    rad = radicands(poses, geometry)
    tol = tol * geometry.L ** 2
    root = np.where(np.abs(rad) <= tol, 0.0, np.where(rad < -tol, np.nan, np.sqrt(np.abs(rad))))
    v = vertices(poses, geometry)
    centre = np.stack([v[..., 0, 0], geometry.B2 - v[..., 1, 0], geometry.H3 - v[..., 2, 1]], -1)
    return centre + np.asarray(signs, dtype=float) * root


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

    Examples
    --------
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> lam = inverse([0.6, 0.4, 0.0], g)
    >>> bool(abs(loop_residuals([0.6, 0.4, 0.0], lam, g)).max() < 1e-14)
    True
    """
    return np.sum(_bars(poses, lambdas, geometry) ** 2, axis=-1) - geometry.L ** 2


def _bars(poses, lambdas, geometry):
    """The bar vectors ``P_i - C_i``, shape ``(..., 3, 2)``."""
    lam = _triples(lambdas, "lambdas")
    zero = np.zeros_like(lam[..., 0])
    sliders = np.stack([np.stack([lam[..., 0], zero], -1),
                        np.stack([geometry.B2 - lam[..., 1], zero], -1),
                        np.stack([geometry.B3 + zero, geometry.H3 - lam[..., 2]], -1)], axis=-2)
    return vertices(poses, geometry) - sliders


def direct_jacobian(poses, lambdas, geometry):
    """Jacobian of :func:`loop_residuals` with respect to the pose ``(x, y, psi)``.

    It is singular at the direct (type II) singularities, where the platform gains a degree of
    freedom with the inputs locked: the three bars are concurrent or parallel.

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
    bars = _bars(poses, lambdas, geometry)
    v = vertices(poses, geometry)
    lever = v - v[..., :1, :]  # P_i - P: its derivative with respect to psi is its normal
    dpsi = np.sum(bars * np.stack([-lever[..., 1], lever[..., 0]], axis=-1), axis=-1)
    return 2 * np.concatenate([bars, dpsi[..., None]], axis=-1)


def _poly_mul(p, q):
    """Product of polynomials with ascending coefficients along the last axis."""
    out = np.zeros(np.broadcast_shapes(p.shape[:-1], q.shape[:-1])
                   + (p.shape[-1] + q.shape[-1] - 1,))
    for i in range(p.shape[-1]):
        out[..., i:i + q.shape[-1]] += p[..., i, None] * q
    return out


def _f_and_g(lam, geometry):
    """``(1 + t^2)`` times the study's ``f1, f2, f3, g1, g2, g3`` (eq. 126-145), quadratics in t.

    ``(1 + t^2)`` times ``sin psi``, ``cos psi`` and ``1`` are ``2 t``, ``1 - t^2``, ``1 + t^2``.
    """
    l1, l2, l3 = np.moveaxis(lam, -1, 0)
    a, B2, B3, H3 = geometry.a, geometry.B2, geometry.B3, geometry.H3
    K = [2 * a, 2 * l1 + 2 * (l2 - B2), 2 * a, 2 * a * (l2 - B2),
         -l1 ** 2 + a ** 2 + (l2 - B2) ** 2]
    Q = [-a * _ROOT3, a, 2 * (l1 - B3), a, a * _ROOT3, 2 * (l3 - H3),
         a * (l3 - H3) + a * _ROOT3 * B3, a * _ROOT3 * (l3 - H3) - a * B3,
         -l1 ** 2 + B3 ** 2 + a ** 2 + (l3 - H3) ** 2]

    def times(k_sin, k_cos, k_one):
        return sum(np.asarray(k, dtype=float)[..., None] * np.array(basis) for k, basis in
                   ((k_sin, [0.0, 2, 0]), (k_cos, [1.0, 0, -1]), (k_one, [1.0, 0, 1])))

    return (times(0, K[0], K[1]), times(K[2], 0, 0), times(0, K[3], K[4]),
            times(Q[0], Q[1], Q[2]), times(Q[3], Q[4], Q[5]), times(Q[6], Q[7], Q[8]))


def polynomial(lambdas, geometry):
    """Coefficients ``C0 ... C8`` of the study's degree-8 polynomial in ``t = tan(psi/2)``.

    It is equation 148 of the study, ``(N_x - lambda1 D)^2 + N_y^2 - L^2 D^2 = 0``, with
    ``x_P = N_x / D`` and ``y_P = N_y / D`` the radical-axis solution (equations 146-147)
    multiplied through by ``(1 + t^2)^4``. It is computed here by multiplying the quadratics
    ``(1 + t^2) f_i`` and ``(1 + t^2) g_i``, not from the printed expansion of Annex I.

    Parameters
    ----------
    lambdas : array_like, shape (..., 3)
    geometry : Geometry

    Returns
    -------
    ndarray, shape (..., 9)
        ``C0, C1, ..., C8`` (ascending powers of ``t``).

    Examples
    --------
    >>> import numpy as np
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> C = polynomial([0.4, 0.1, 0.6], g)
    >>> C.round(2).tolist()
    [-4.12, 19.2, 257.57, 409.42, 3157.17, 1836.44, 10133.14, 1446.22, 7237.66]
    >>> bool(abs(np.polynomial.polynomial.polyval(1j, C)) < 1e-14 * abs(C).sum())
    True
    """
    lam = _triples(lambdas, "lambdas")
    f1, f2, f3, g1, g2, g3 = _f_and_g(lam, geometry)
    nx = _poly_mul(f3, g2) - _poly_mul(f2, g3)  # x_P = N_x / D, y_P = N_y / D (eq. 146-147)
    ny = _poly_mul(f1, g3) - _poly_mul(f3, g1)
    d = _poly_mul(f2, g1) - _poly_mul(f1, g2)
    e = nx - lam[..., 0, None] * d
    return _poly_mul(e, e) + _poly_mul(ny, ny) - geometry.L ** 2 * _poly_mul(d, d)


def _deflate(c):
    """Divide ``c`` (ascending, degree 8) by ``1 + t^2``: the sextic quotient, ascending."""
    q = np.zeros(7)
    rest = c.astype(float).copy()
    for k in range(8, 1, -1):
        q[k - 2] = rest[k]
        rest[k - 2] -= rest[k]
    return q


def _sextic_angles(c):
    """The six roots of the sextic ``c`` as complex angles ``psi``, and whether each came from
    the reversed polynomial in ``u = cot(psi/2) = 1/t`` (the roots with ``|t| > 1``)."""
    forward = np.roots(c[::-1])  # np.roots drops zero leading coefficients: fewer roots
    forward = forward[np.abs(forward) <= 1]
    backward = np.roots(c)  # in u: a zero leading coefficient of c gives a root u = 0
    backward = backward[np.argsort(np.abs(backward))][:6 - forward.size]
    psi = np.concatenate([2 * np.arctan(forward), np.pi - 2 * np.arctan(backward)])
    return psi, np.arange(psi.size) >= forward.size


@dataclass(frozen=True)
class DirectSolution:
    """The direct problem's solutions with what :func:`solve_direct` found about each.

    Attributes
    ----------
    poses : ndarray, shape (n, 3)
        ``(x, y, psi)``, ``psi`` in ``[0, 2 pi)``, sorted by ``psi``.
    coefficients : ndarray, shape (9,)
        The study's polynomial ``C0 ... C8`` (:func:`polynomial`).
    from_reversed : ndarray of bool, shape (n,)
        The root was found in ``u = cot(psi/2)``: where ``t = tan(psi/2)`` is large or infinite
        (``psi`` near ``pi``, the blind spot of the study's substitution).
    elimination_det : ndarray, shape (n,)
        Dimensionless determinant of the two radical-axis equations at the pose's ``psi``,
        proportional to the study's denominator ``D`` (equation 76). Where it vanishes the
        elimination, not the mechanism, is singular: the pose then comes from intersecting two of
        the legs' circles instead of from ``x = N_x / D``.
    jacobian_det : ndarray, shape (n,)
        Determinant of the dimensionless direct Jacobian (rows ``(u_i / L, u_i . n_i / (L a))``):
        zero at a direct (type II) singularity.
    residuals : ndarray, shape (n,)
        ``max |loop_residuals| / L**2`` of each pose.
    """

    poses: np.ndarray
    coefficients: np.ndarray
    from_reversed: np.ndarray
    elimination_det: np.ndarray
    jacobian_det: np.ndarray
    residuals: np.ndarray

    @property
    def singular(self):
        """Poses at a direct singularity of the mechanism (``|jacobian_det| < 1e-6``)."""
        return np.abs(self.jacobian_det) < 1e-6

    @property
    def elimination_singular(self):
        """Poses where the study's back-substitution fails (``|elimination_det| < 1e-6``)."""
        return np.abs(self.elimination_det) < 1e-6


def _centres(psi, lambdas, geometry):
    """Centres, in the plane of ``P``, of the three circles of radius ``L`` that ``P`` lies on."""
    l1, l2, l3 = lambdas
    a = geometry.a
    return np.stack([np.broadcast_to([l1, 0.0], psi.shape + (2,)),
                     np.stack([geometry.B2 - l2 - a * np.cos(psi), -a * np.sin(psi)], -1),
                     np.stack([geometry.B3 - a * np.cos(psi + np.pi / 3),
                               geometry.H3 - l3 - a * np.sin(psi + np.pi / 3)], -1)], axis=-2)


def _elimination(centres, L):
    """The radical-axis equations ``A P = b`` of the circles, and ``det A`` made dimensionless."""
    A = centres[:, 1:] - centres[:, :1]
    b = (np.sum(centres[:, 1:] ** 2, -1) - np.sum(centres[:, :1] ** 2, -1)) / 2
    det = A[:, 0, 0] * A[:, 1, 1] - A[:, 0, 1] * A[:, 1, 0]
    return A, b, det / np.maximum(np.abs(A).max(axis=(1, 2)), L) ** 2


def _candidates(psi, lambdas, geometry):
    """Candidate positions of ``P`` for each root ``psi``, shape ``(m, 3, 2)``.

    Candidate 0 solves the two radical-axis equations (the study's equations 146-147), unless
    their dimensionless determinant vanishes (then it is NaN); candidates 1 and 2 are the
    intersections of the two circles whose centres are farthest apart, a back-substitution
    that still works where the radical axes are parallel. The caller keeps those that satisfy all
    three loop equations.
    """
    c = _centres(psi, lambdas, geometry)
    A, b, det = _elimination(c, geometry.L)
    raw_det = A[:, 0, 0] * A[:, 1, 1] - A[:, 0, 1] * A[:, 1, 0]
    linear = np.stack([b[:, 0] * A[:, 1, 1] - b[:, 1] * A[:, 0, 1],  # Cramer's rule
                       A[:, 0, 0] * b[:, 1] - A[:, 1, 0] * b[:, 0]], -1)
    linear /= np.where(np.abs(det) <= 1e-9, np.nan, raw_det)[:, None]
    pairs = np.array([[0, 1], [0, 2], [1, 2]])
    gaps = c[:, pairs[:, 1]] - c[:, pairs[:, 0]]
    best = np.argmax(np.sum(gaps ** 2, -1), axis=1)
    rows = np.arange(len(psi))
    d, start = gaps[rows, best], c[rows, pairs[best, 0]]
    half = np.linalg.norm(d, axis=-1) / 2
    h = np.sqrt(np.maximum(geometry.L ** 2 - half ** 2, 0.0)) / np.maximum(2 * half, 1e-300)
    normal = np.stack([-d[:, 1], d[:, 0]], -1) * h[:, None]
    mid = start + d / 2
    return np.stack([linear, mid + normal, mid - normal], axis=1)


def _wrap(psi):
    """Angles in ``[0, 2 pi)``; those within ``1e-12`` below ``2 pi`` become 0."""
    psi = np.mod(psi, 2 * np.pi)
    return np.where(psi >= 2 * np.pi - 1e-12, 0.0, psi)


def _residual_norms(poses, lambdas, geometry):
    """``max_i |F_i| / L**2`` of each pose."""
    residuals = np.abs(loop_residuals(poses, lambdas, geometry))
    return residuals.max(axis=-1, initial=0) / geometry.L ** 2


# A candidate pose whose loop residual (relative to L**2) lies between these is polished by
# Newton: above _EXACT (a few units of round-off) it may lie residual / sigma_min(J) from the
# root, 1e-9 near a direct singularity; above _CANDIDATE it is no root at all.
_EXACT, _CANDIDATE = 16 * np.finfo(float).eps, 1e-2


def _polish(poses, lambdas, geometry):
    """A few Newton steps on the loop equations from each pose; a pose that moves by more than
    ``1e-2`` (relative), or meets a numerically singular Jacobian, is returned unchanged."""
    result = solve_batch(lambda p: loop_residuals(p, lambdas, geometry), poses,
                         lambda p: direct_jacobian(p, lambdas, geometry), tol=1e-14, maxiter=6,
                         raise_on_failure=False)
    moved = np.hypot(*(result.x - poses)[:, :2].T) / geometry.L + np.abs(result.x - poses)[:, 2]
    keep = (moved <= 1e-2) & ~result.singular  # a singular pose is returned unchanged
    return np.where(keep[:, None], result.x, poses)


def _distinct(poses, order, L, tol=1e-4):
    """Indices of the distinct poses among ``poses[order]`` (the first of each group of poses
    within ``tol``, position relative to ``L``, angle modulo ``2 pi``), sorted by ``psi``."""
    kept = []
    for k in order:
        delta = poses[kept] - poses[k]
        gap = (np.hypot(delta[:, 0], delta[:, 1]) / L
               + np.abs(np.mod(delta[:, 2] + np.pi, 2 * np.pi) - np.pi))
        if not np.any(gap <= tol):
            kept.append(k)
    return np.array(sorted(kept, key=lambda k: poses[k, 2]), dtype=int)


def solve_direct(lambdas, geometry, *, imag_tol=1e-4, residual_tol=1e-6):
    """Solve the direct problem by the study's polynomial, robustly, and report on each solution.

    1. The degree-8 polynomial of :func:`polynomial` is divided by its factor ``1 + t^2`` (its
       roots ``t = +-i`` are spurious for every input).
    2. The sextic's roots with ``|t| <= 1`` come from it, the others from the reversed polynomial
       in ``u = 1/t = cot(psi/2)``, so a root at or near ``psi = pi`` (``t`` infinite: the
       substitution's blind spot, where the leading coefficient vanishes) is found accurately.
    3. A root is real when ``|Im psi| <= imag_tol``. Each real ``psi`` gives candidate points
       ``(x, y)``: the solution of the two radical-axis equations (146-147), unless their
       determinant ``D`` vanishes (equation 76: the study's "singular position"), and the two
       intersections of the pair of the legs' circles whose centres are farthest apart.
    4. The candidates that satisfy the three loop equations to ``residual_tol * L**2`` are the
       solutions; poses closer than ``1e-4`` (relative to ``L`` and in radians) count as one
       (a double root finds the same pose twice). Candidates that miss by ``4e-15`` to ``1e-2``
       get a few Newton steps first (a multiple root, as ``D = 0`` creates, is blurred by
       round-off to about ``eps**(1/m)``); Newton cannot sharpen a pose at a direct singularity
       (two assembly modes meeting), accurate to about ``1e-8`` only.

    Parameters
    ----------
    lambdas : array_like, shape (3,)
        The inputs ``(lambda1, lambda2, lambda3)``, metres.
    geometry : Geometry
    imag_tol : float, optional
        Largest ``|Im psi|`` (radians) of a root taken as real.
    residual_tol : float, optional
        Relative tolerance of the loop residual of an accepted pose.

    Returns
    -------
    DirectSolution

    Raises
    ------
    ValueError
        If ``lambdas`` is not three finite numbers.

    Examples
    --------
    >>> import numpy as np
    >>> g = Geometry(L=1, a=1, B2=3, B3=2.5, H3=2.8)
    >>> sol = solve_direct([2, 0.5, 0.2], g)
    >>> sol.poses[:, 2].round(4).tolist(), sol.singular.tolist()
    ([0.1251, 6.0322], [False, False])
    """
    lam = _three(lambdas)
    poses, coefficients, from_reversed, residuals = _direct(lam, geometry, imag_tol, residual_tol)
    jac = direct_jacobian(poses, lam, geometry) / (2 * geometry.L)
    jac[..., 2] /= geometry.a
    elimination = _elimination(_centres(poses[:, 2], lam, geometry), geometry.L)[2]
    return DirectSolution(poses, coefficients, from_reversed, elimination, np.linalg.det(jac),
                          residuals)


def _three(lambdas):
    lam = _triples(lambdas, "lambdas")
    if lam.shape != (3,):
        raise ValueError(f"lambdas must have shape (3,), got {lam.shape}")
    return lam


def _direct(lam, geometry, imag_tol=1e-4, residual_tol=1e-6):
    """The work of :func:`solve_direct`: poses, coefficients, from_reversed, residuals."""
    coefficients = polynomial(lam, geometry)
    psi, from_reversed = _sextic_angles(_deflate(coefficients))
    real = np.abs(psi.imag) <= imag_tol
    psi, from_reversed = _wrap(psi[real].real), from_reversed[real]
    points = _candidates(psi, lam, geometry)
    poses = np.concatenate([points, np.broadcast_to(psi[:, None, None], points.shape[:2] + (1,))],
                           axis=-1).reshape(-1, 3)
    finite = np.all(np.isfinite(poses), axis=1)
    poses = poses[finite]
    from_reversed = np.repeat(from_reversed, 3)[finite]
    residuals = _residual_norms(poses, lam, geometry)
    near = (residuals > _EXACT) & (residuals < _CANDIDATE)
    if near.any():  # roots blurred by a multiple root: polish them on the loop equations
        poses[near] = _polish(poses[near], lam, geometry)
        poses[:, 2] = _wrap(poses[:, 2])
        residuals[near] = _residual_norms(poses[near], lam, geometry)
    best_first = np.argsort(residuals)
    accepted = _distinct(poses, best_first[residuals[best_first] <= residual_tol], geometry.L)
    return poses[accepted], coefficients, from_reversed[accepted], residuals[accepted]


def direct(lambdas, geometry):
    """All the poses ``(x, y, psi)`` of the mechanism for inputs ``lambdas``.

    The poses of :func:`solve_direct` (see it for the method and for the report on each).

    Parameters
    ----------
    lambdas : array_like, shape (3,)
    geometry : Geometry

    Returns
    -------
    ndarray, shape (n, 3)
        ``n`` from 0 to 6, ``psi`` in ``[0, 2 pi)``.

    Examples
    --------
    >>> import numpy as np
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> sol = direct([0.4, 0.1, 0.6], g)
    >>> np.column_stack([sol[:, :2].round(5), np.degrees(sol[:, 2]).round(4)]).tolist()
    [[1.23123, 0.55593, 9.9967], [1.05352, 0.7569, 341.5164]]
    """
    lam = _three(lambdas)
    return _direct(lam, geometry)[0]


def direct_by_newton(lambdas, geometry, starts, *, tol=1e-12):
    """The distinct poses that Newton-Raphson reaches from many starting poses.

    Each start is iterated on the loop equations (:func:`loop_residuals`, with the analytic
    :func:`direct_jacobian`) by :func:`mechnum.newton.solve_batch`; the starts that do not
    converge in 50 steps, or meet a singular Jacobian, are ignored. It finds only the solutions whose basins the starts hit:
    a check on :func:`direct`, not a replacement.

    Parameters
    ----------
    lambdas : array_like, shape (3,)
    geometry : Geometry
    starts : array_like, shape (m, 3)
        Starting poses ``(x, y, psi)``.
    tol : float, optional
        Newton's step tolerance.

    Returns
    -------
    ndarray, shape (n, 3)
        The distinct converged poses, ``psi`` in ``[0, 2 pi)``, sorted by ``psi``.

    Raises
    ------
    ValueError
        If ``lambdas`` or ``starts`` are ill-shaped or not finite.

    Examples
    --------
    >>> import numpy as np
    >>> g = Geometry(L=1, a=1, B2=3, B3=2.5, H3=2.8)
    >>> starts = [[2.0, 1.0, 6.0], [1.5, 1.0, 0.2]]
    >>> direct_by_newton([2, 0.5, 0.2], g, starts)[:, 2].round(4).tolist()
    [0.1251, 6.0322]
    """
    lam, starts = _three(lambdas), _triples(starts, "starts")
    if starts.ndim != 2:
        raise ValueError(f"starts must have shape (m, 3), got {starts.shape}")
    result = solve_batch(lambda p: loop_residuals(p, lam, geometry), starts,
                         lambda p: direct_jacobian(p, lam, geometry), tol=tol,
                         raise_on_failure=False)
    poses = result.x[result.converged]
    poses[:, 2] = _wrap(poses[:, 2])
    return poses[_distinct(poses, np.arange(len(poses)), geometry.L)]


#: The study's worked examples (Tables 3 to 6 of seed 001): geometry and input of each.
EXAMPLES = {
    "Tabla 3": (Geometry(L=1, a=1, B2=3, B3=1.5, H3=2), (0.6, 0.4, 0.0)),
    "Tabla 4": (Geometry(L=1, a=0.3, B2=3, B3=3, H3=3), (3.0, 0.3, np.pi / 4)),
    "Tabla 5": (Geometry(L=1, a=1, B2=3, B3=2.5, H3=2.8), (2.0, 0.5, 0.2)),
    "Tabla 6": (Geometry(L=1, a=1, B2=3, B3=2, H3=3), (0.4, 0.1, 0.6)),
}


def reproduce():
    """Every number of the registry rows of chapter ``04_rigid_3prr``, computed by this module.

    Tables 3 and 4 (inverse problem): the two values of each input (``+``: the branch adding the
    square root in equations 53, 57 and 61, the larger value), and the number of solutions.
    Tables 5 and 6 (direct problem): the two poses (``psi`` in degrees; solution 1 is the one
    with ``psi > 180``, listed first by the study) and their number.
    The count of roots of the degree-8 polynomial that can be real (Table 6's inputs): the roots
    other than ``t = +-i``.

    Returns
    -------
    dict of str to float

    Examples
    --------
    >>> values = reproduce()
    >>> values["Tabla 3 number of solutions"], round(values["Tabla 5 solution 2 x"], 4)
    (8.0, 1.5162)
    """
    values = {}
    for table in ("Tabla 3", "Tabla 4"):
        geometry, pose = EXAMPLES[table]
        lam = inverse(pose, geometry)
        values[f"{table} number of solutions"] = float(len(lam))
        for i in range(3):  # the + branch (adding the square root) gives the larger value
            values[f"{table} lambda{i + 1} (+)"] = float(lam[:, i].max())
            values[f"{table} lambda{i + 1} (-)"] = float(lam[:, i].min())
    for table in ("Tabla 5", "Tabla 6"):
        geometry, lam = EXAMPLES[table]
        poses = direct(lam, geometry)
        values[f"{table} number of solutions"] = float(len(poses))
        study_order = (poses[poses[:, 2] > np.pi][0], poses[poses[:, 2] < np.pi][0])
        for number, pose in enumerate(study_order, start=1):
            for name, value in zip(("x", "y", "psi"), (pose[0], pose[1], np.degrees(pose[2]))):
                values[f"{table} solution {number} {name}"] = float(value)
    geometry, lam = EXAMPLES["Tabla 6"]
    roots = np.roots(polynomial(lam, geometry)[::-1])
    values["Anexo I roots that can be real"] = float(np.sum(np.abs(np.abs(roots.imag) - 1)
                                                        + np.abs(roots.real) > 1e-6))
    return values
