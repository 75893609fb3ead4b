"""The closed form in elliptic integrals of a clamped-pinned rod (conventions: mechnum.rods).

scipy's ``ellipkinc(phi, m)`` and ``ellipeinc(phi, m)`` are ``F(phi, k)`` and ``E(phi, k)`` with
the parameter ``m = k**2``; ``ellipj`` gives the amplitude ``phi = am(u | m)``.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import ellipeinc, ellipj, ellipkinc, elliprd, elliprf, expit

from mechnum import _validate, newton
from mechnum.errors import ConvergenceError, MechnumError
from mechnum.rods.shooting import Rod, _vectors

TWO_PI = 2.0 * np.pi


class NoEquilibriumError(MechnumError):
    """A rod has no equilibrium on the requested branch (a load below a mode's range)."""


@dataclass(frozen=True)
class EllipticRod:
    """The closed-form clamped-pinned rod of :func:`clamped_pinned` (local frame).

    Attributes
    ----------
    k, k_min, phi1, phi2 : ndarray
        Elliptic modulus, its least admissible magnitude, and the amplitudes at clamp and tip.
    R : ndarray
        Magnitude of the tip force (N); ``force = R (cos psi, sin psi)``.
    force, tip : ndarray, shape (..., 2)
        Tip force (N) and tip position (m).
    tip_angle, clamp_moment : ndarray
        ``theta(L)`` (rad) and ``m(0)`` (N m).
    rod : Rod or None
        The shape at ``nodes`` equally spaced points, when asked for.
    """

    k: np.ndarray
    k_min: np.ndarray
    phi1: np.ndarray
    phi2: np.ndarray
    R: np.ndarray
    force: np.ndarray
    tip: np.ndarray
    tip_angle: np.ndarray
    clamp_moment: np.ndarray
    rod: Rod = None


def elliptic_k(psi, k_rel):
    """The modulus ``k`` and its least magnitude ``k_min`` from ``(psi, k_rel)``.

    ``k_min = |cos(psi/2)|`` and ``k = sign(k_rel) k_min + (1 - k_min) k_rel`` (the study's
    (91)), so ``k_rel`` in ``(-1, 0) U (0, 1)`` maps onto the admissible
    ``k_min < |k| < 1``.

    Parameters
    ----------
    psi : array_like
        Direction of the tip force in the local frame, in ``(0, 2 pi)`` (rad).
    k_rel : array_like
        Relative modulus, ``0 < |k_rel| < 1``.

    Returns
    -------
    k, k_min : ndarray

    Raises
    ------
    ValueError
        If ``psi`` or ``k_rel`` is outside its open range (or not finite).

    Examples
    --------
    >>> k, kmin = elliptic_k(2 * np.pi / 3, [-0.5, 0.5])
    >>> np.round(k, 12).tolist(), round(float(kmin), 12)
    ([-0.75, 0.75], 0.5)
    """
    psi, k_rel = _angles(psi), _validate.array(k_rel, "k_rel")
    if np.any((k_rel == 0) | (np.abs(k_rel) >= 1)):
        raise ValueError(f"k_rel must satisfy 0 < |k_rel| < 1, got {k_rel!r}")
    k_min = np.abs(np.cos(0.5 * psi))
    return np.sign(k_rel) * k_min + _one_minus_k_min(psi) * k_rel, k_min


def _one_minus_k_min(psi):
    """``1 - |cos(psi/2)|`` without cancellation (``sin(psi/2)**2 / (1 + |cos(psi/2)|)``)."""
    return np.sin(0.5 * psi) ** 2 / (1.0 + np.abs(np.cos(0.5 * psi)))


def _angles(psi):
    """``psi`` as a float array, checked to lie in the open interval ``(0, 2 pi)``."""
    psi = _validate.array(psi, "psi")
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError(f"psi must lie in the open interval (0, 2 pi), got {psi!r}")
    return psi


def _mode(mode):
    mode = _validate.array(mode, "mode")
    if np.any(mode < 1) or np.any(mode != np.round(mode)):
        raise ValueError(f"mode must be an integer >= 1, got {mode!r}")
    return mode


def _shape(phi, psi, k, phi1, F1, E1, lam, EI):
    """``(x, y, theta, m)`` at amplitude ``phi`` (the study's (86), (87), (37) and (42))."""
    m = k * k
    dF, dE = ellipkinc(phi, m) - F1, ellipeinc(phi, m) - E1
    dC = np.cos(phi) - np.cos(phi1)
    x = -(np.cos(psi) * (2 * dE - dF) + 2 * k * np.sin(psi) * dC) / lam
    y = -(np.sin(psi) * (2 * dE - dF) - 2 * k * np.cos(psi) * dC) / lam
    theta = psi - 2 * np.arccos(np.clip(k * np.sin(phi), -1.0, 1.0))
    return x, y, theta, 2 * EI * k * lam * np.cos(phi)


def clamped_pinned(EI, L, psi, k_rel, mode=1, *, nodes=None):
    """The clamped-pinned (or end-loaded cantilever) rod in closed form.

    With ``lambda = sqrt(R / EI)``: ``lambda L = F(phi2, k) - F(phi1, k)`` gives ``R``; along the
    rod ``F(phi, k) = F(phi1, k) + lambda s``, ``cos((psi - theta)/2) = k sin(phi)`` and::

        x = -(cos psi (2 dE - dF) + 2 k sin psi dC) / lambda
        y = -(sin psi (2 dE - dF) - 2 k cos psi dC) / lambda

    where ``dE = E(phi, k) - E(phi1, k)``, ``dF`` likewise and ``dC = cos(phi) - cos(phi1)``;
    ``m = 2 EI k lambda cos(phi)``. Conventions and ranges: see the module docstring.

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m).
    psi, k_rel : array_like
        Force direction (rad, in ``(0, 2 pi)``) and relative modulus (``0 < |k_rel| < 1``),
        broadcast together.
    mode : int or array_like of int, optional
        Buckling mode, ``>= 1``.
    nodes : int, optional
        If given (``>= 2``), also sample the shape at this many equally spaced nodes.

    Returns
    -------
    EllipticRod

    Raises
    ------
    ValueError
        If an input is outside its range.

    Examples
    --------
    >>> rod = clamped_pinned(1.0, 1.0, np.pi, 1e-6)   # compression at the Euler load
    >>> round(float(rod.R / (np.pi ** 2 / 4)), 9)
    1.0
    """
    EI, L = _validate.positive(EI, "EI"), _validate.positive(L, "L")
    k, k_min = elliptic_k(psi, k_rel)
    psi = np.asarray(psi, dtype=float)
    # phi1 = arcsin(cos(psi/2) / k), the study's (89), written as an arctan2 of
    # sin(phi1) |k| and cos(phi1) |k| = sqrt((|k| - k_min)(|k| + k_min)), with
    # |k| - k_min = (1 - k_min) |k_rel| exactly: arcsin near 1 would lose half the digits.
    phi1 = np.arctan2(np.cos(0.5 * psi) * np.sign(k),
                      np.sqrt(_one_minus_k_min(psi) * np.abs(k_rel) * (np.abs(k) + k_min)))
    phi2 = (_mode(mode) - 0.5) * np.pi
    m = k * k
    F1, E1 = ellipkinc(phi1, m), ellipeinc(phi1, m)
    lam = (ellipkinc(phi2, m) - F1) / L
    R = EI * lam ** 2

    x2, y2, theta2, _ = _shape(phi2, psi, k, phi1, F1, E1, lam, EI)
    force = np.stack(np.broadcast_arrays(R * np.cos(psi), R * np.sin(psi)), axis=-1)
    rod = None
    if nodes is not None:
        s = np.linspace(0.0, 1.0, _validate.maxiter(nodes, "nodes", minimum=2)) * L[..., None]
        phi = ellipj(F1[..., None] + lam[..., None] * s, m[..., None])[3]
        xs, ys, ts, ms = _shape(phi, *(np.asarray(a)[..., None]
                                       for a in (psi, k, phi1, F1, E1, lam, EI)))
        rod = Rod(np.broadcast_to(s, xs.shape), xs, ys, ts, ms, force)
    return EllipticRod(k, k_min, phi1, phi2, R, force, np.stack((x2, y2), axis=-1), theta2,
                       2 * EI * k * lam * np.cos(phi1), rod)


# The growing branch in Carlson's symmetric form (the cantilever and k_rel_for_force).
#
# With a = cos(psi/2), b = sin(psi/2) and zeta >= 0, the branch that grows from the straight rod
# has k cos(phi1) = sign(a) b tanh(zeta) and 1 - k**2 = (b sech(zeta))**2. Every quantity of
# the rod is then a smooth function of zeta, computed without cancellation at any load, where
# the study's formulas lose the small loads (differences of nearly equal integrals, divided by
# lambda) and the large ones (scipy's ellipkinc(phi, m) receives m = k**2 already rounded).
# With t = pi/2 - phi (from t1 at the clamp to 0 at the tip), eta = |k| sin(t) / b and
# s = sech(zeta), DLMF 19.25.5 and 19.25.7 (scaled by b**2) give the arc length and the integral
# that the position needs:
#
#   lambda (L - s_t) = I(t) = (eta / |k|) R_F(s**2 cos(t)**2, s**2 + eta**2, s**2)
#   G(t) = int_0^t sin(t)**2 dt / Delta(t) = (b**2 eta**3 s**2 / (3 |k|**3)) R_D(same arguments)
#
# with lambda L = I(t1) + 2 (mode - 1) K(k), eta(t1) = tanh(zeta) and cos(t1) = |a| / |k|.
_ZETA_MAX = 350.0  # beyond, 1 - k**2 = (b sech zeta)**2 underflows (lambda L > 350 or so)
_EPS = np.finfo(float).eps
_TINY = np.finfo(float).tiny  # keeps R_D finite where a = cos(psi/2) is 0 (its factor a**2 is)
_TAN_LIMIT = 1.5  # the start's beam-column law arctan(...) is used below the Euler plateau pi/2
_TANH_LIMIT = 0.999  # and kept away from zeta = infinity
_B_MIN = 1e-150  # below, sin(psi/2)**2 underflows; the rod deflects by less than b L: none
_SMALL_STEP = 1e-8  # a Newton step below 1e-8 t1 leaves an error near 1e-16 t1 (quadratic rate)
CLOSED_FORM_TOL = 1e-14  # relative residual of lambda L at which the cantilever's modulus is kept
CLOSED_FORM_MAXITER = 100  # Newton-bisection steps for it: bisection alone needs some 60
# pinned_equilibria: |k_rel| = logistic(z), clipped where it is within 1e-11 of 0 or 1 (the chart
# is flat beyond); Newton's most steps from a grid cell; a root is kept if its tip is within
# 1e-10 L of the point; two roots equal to 9 digits are one
_LOGIT_CLIP, _POLISH_MAXITER, _TIP_ACCEPT, _SAME_DIGITS = 25.0, 60, 1e-10, 9


def _branch(a, b, zeta):
    """``(tanh(zeta), sech(zeta), |k|)`` of the growing branch, for scalars."""
    v = math.tanh(zeta)
    return v, 1.0 / math.cosh(zeta), math.sqrt(a * a + (b * v) ** 2)


def _lambda_L(a, b, zeta, mode, slope=True):
    """``lambda L`` of the growing branch and (or 0) its derivative in ``zeta``, for scalars."""
    v, s, k = _branch(a, b, zeta)
    X, Z = max((s * a / k) ** 2, _TINY), s * s
    rf = float(elliprf(X, 1.0, Z))
    value = v / k * rf
    if slope:
        slope = (Z * a * a / k ** 3 * rf + v * v * Z / (3.0 * k) *
                 (a * a * float(elliprd(1.0, Z, X)) / k ** 4 + float(elliprd(X, 1.0, Z))))
    if mode > 1:   # the whole half-waves, 2 (mode - 1) K(k) with K = R_F(0, 1 - k**2, 1)
        kc2 = (b * s) ** 2
        value += 2.0 * (mode - 1) * float(elliprf(0.0, kc2, 1.0))
        slope += 2.0 * (mode - 1) * kc2 * v * float(elliprd(0.0, 1.0, kc2)) / 3.0
    return value, slope


def _zeta(a, b, target, mode, tol, maxiter):
    """Solve ``lambda L(zeta) = target`` on the growing branch, for one ``(a, b, target)``.

    ``lambda L`` grows with ``zeta`` from its value at 0 (below ``target``: the caller checks),
    like ``zeta / |a|`` for small loads and like ``zeta + ln(2 / b)`` for large ones, and never
    falls below ``zeta``: ``[0, target]`` brackets the root. Newton's steps are kept inside the
    bracket (bisection otherwise); the iteration stops when the residual is below ``tol`` or
    at the rounding floor of ``zeta`` itself (``2 eps zeta`` times the slope), or after a
    Newton step so small (``|g| / slope <= 1e-8 zeta``) that the quadratic rate leaves an
    error of its square.
    """
    lo, hi = 0.0, target
    if hi > _ZETA_MAX:
        if _lambda_L(a, b, _ZETA_MAX, mode)[0] < target:
            raise ValueError(f"lambda L = L sqrt(R / EI) = {target:.6g} is beyond the loads that "
                             f"the closed form represents in double precision (1 - k**2 "
                             f"underflows): use shooting")
        hi = _ZETA_MAX
    # start: the beam-column law lambda L = arctan(tanh(zeta) / |a|) of small loads, or the
    # large-load asymptote lambda L = zeta + ln(2 / b), whichever is larger
    zeta = max(math.atanh(min(abs(a) * math.tan(min(target, _TAN_LIMIT)), _TANH_LIMIT)),
               target - math.log(2.0 / b))
    if not lo < zeta < hi:
        zeta = 0.5 * hi
    for _ in range(maxiter):
        value, slope = _lambda_L(a, b, zeta, mode)
        g = value - target
        if abs(g) <= tol * target + 2.0 * _EPS * zeta * slope:
            return zeta
        lo, hi = (zeta, hi) if g < 0 else (lo, zeta)
        step = g / slope
        if lo < zeta - step < hi:
            if abs(step) <= _SMALL_STEP * zeta:
                return zeta - step
            zeta -= step
        else:
            zeta = 0.5 * (lo + hi)
    raise ConvergenceError(f"no modulus for lambda L = {target!r} in {maxiter} iterations "
                           f"(psi = {2.0 * math.atan2(b, a)!r}, mode {mode})")


def _arcs(b, s, k, eta, cos_t):
    """``I(t)`` and ``G(t)`` of the growing branch (see above), for arrays of ``t``.

    The arguments of R_F and R_D are divided by ``s**2 + eta**2`` (they are homogeneous, of
    degrees -1/2 and -3/2), so that a large load's tiny ``s`` neither underflows nor overflows.
    """
    Y = s * s + eta * eta
    X, Z, r = (s * cos_t) ** 2 / Y, s * s / Y, eta / np.sqrt(Y)
    return r / k * elliprf(X, 1.0, Z), b * b * r ** 3 * s * s / (3.0 * k ** 3) * elliprd(X, 1.0, Z)


def _amplitudes(b, v, s, k, t1, targets, maxiter):
    """Solve ``I(t) = target`` for ``t`` in ``[0, t1]``, one per target: safeguarded Newton."""
    lo, hi = np.zeros_like(targets), np.full_like(targets, t1)
    # start: I(t) = asinh(eta / s) / |k| where cos(t) = 1
    eta = np.minimum(s * np.sinh(np.minimum(k * targets, _ZETA_MAX)), v)
    t = np.minimum(np.arcsin(np.minimum(b * eta / k, 1.0)), t1)
    active = np.ones(targets.shape, dtype=bool)
    for _ in range(maxiter):
        eta = k * np.sin(t) / b
        g = _arcs(b, s, k, eta, np.cos(t))[0] - targets
        step = g * b * np.sqrt(s * s + eta * eta)        # g / (dI/dt), dI/dt = 1 / Delta(t)
        lo, hi = np.where(g < 0, t, lo), np.where(g < 0, hi, t)
        newton = (t - step >= lo) & (t - step <= hi)
        t = np.where(active, np.where(newton, t - step, 0.5 * (lo + hi)), t)
        # a Newton step this small leaves an error of its square: done
        active &= ~(newton & (np.abs(step) <= _SMALL_STEP * t1))
        if not active.any():
            return t
    raise ConvergenceError(f"the shape of the closed-form cantilever did not converge in "
                           f"{maxiter} iterations")


def _cantilever(EI, L, force, nodes, tol, maxiter):
    """The growing-branch (mode 1) cantilever under a tip force, in closed form: a Rod.

    ``EI``, ``L`` positive floats, ``force`` a finite 2-vector with ``force[1] != 0``,
    ``nodes >= 2``; the formulas are those of the comment above, in the force's frame. The
    clamp and the tip are computed on floats, the nodes between them on arrays.
    """
    nx, ny = float(force[0]), float(force[1])
    R = math.hypot(nx, ny)
    half = 0.5 * math.atan2(ny, nx)     # psi / 2, folded into (-pi/2, pi/2]
    sign = 1.0 if half >= 0 else -1.0   # sign(k) = sign(a) = sign(n_y)
    a, b = sign * math.cos(half), abs(math.sin(half))
    if b < _B_MIN:  # a force this close to pure tension leaves the rod straight to rounding
        return Rod(np.linspace(0.0, L, nodes), np.linspace(0.0, L, nodes), np.zeros(nodes),
                   np.zeros(nodes), np.zeros(nodes), np.array([nx, ny]))
    psi = 2.0 * half if half >= 0 else 2.0 * half + TWO_PI
    c, d = nx / R, ny / R               # cos(psi), sin(psi)
    Lam = L * math.sqrt(R / EI)
    v, s, k = _branch(a, b, _zeta(a, b, Lam, 1, tol, maxiter))
    G1 = _clamp_G(a, b, v, s, k)
    straight = c + 2.0 * (b * v) ** 2   # 2 k**2 - 1: the projection's rate along the force

    def state(sigma, eta, cos_t, G):    # (x, y, theta, m) where t has sin(t) = b eta / |k|
        along = L * (straight * sigma - 2.0 * k * k * (G1 - G) / Lam)
        across = -2.0 * sign * b * L / Lam * (v - eta)
        theta = psi - 2.0 * np.arctan2(b * np.sqrt(s * s + eta * eta), sign * k * cos_t)
        return (along * c - across * d, along * d + across * c, theta,
                2.0 * EI * Lam / L * sign * b * eta)

    ends = np.array([[0.0, 0.0, 0.0, 2.0 * EI * Lam / L * sign * b * v],
                     state(1.0, 0.0, 1.0, 0.0)])
    ends[1, 3] = 0.0
    if nodes > 2:
        sigma = np.linspace(0.0, 1.0, nodes)[1:-1]
        t = _amplitudes(b, v, s, k, math.atan2(b * v, abs(a)), Lam * (1.0 - sigma), maxiter)
        eta, cos_t = np.minimum(k * np.sin(t) / b, v), np.cos(t)
        inner = np.column_stack(state(sigma, eta, cos_t, _arcs(b, s, k, eta, cos_t)[1]))
        ends = np.concatenate((ends[:1], inner, ends[1:]))
    return Rod(np.linspace(0.0, L, nodes), *ends.T, np.array([nx, ny]))


def _clamp_G(a, b, v, s, k):
    """``G(t1)``, the integral from the tip to the clamp (scalars)."""
    return b * b * v ** 3 * s * s / (3.0 * k ** 3) * float(elliprd((s * a / k) ** 2, 1.0, s * s))


def _growing_tip(psi, Lam):
    """The growing branch at the force direction ``psi`` (any real) and ``lambda L = Lam``
    (taken as ``|Lam|``, at most the closed form's range): ``(x(L) / L, y(L) / L, m(0) L / EI)``.
    The chart of the default start of :func:`mechnum.rods.shoot_pinned`."""
    half = 0.5 * math.remainder(psi, TWO_PI)          # psi / 2 in [-pi/2, pi/2]
    sign = 1.0 if half >= 0 else -1.0
    a, b = sign * math.cos(half), max(abs(math.sin(half)), _B_MIN)
    Lam = min(max(abs(Lam), _TINY), _ZETA_MAX)
    v, s, k = _branch(a, b, _zeta(a, b, Lam, 1, CLOSED_FORM_TOL, CLOSED_FORM_MAXITER))
    c, d = math.cos(psi), math.sin(psi)
    along = c + 2.0 * (b * v) ** 2 - 2.0 * k * k * _clamp_G(a, b, v, s, k) / Lam
    across = -2.0 * sign * b * v / Lam
    return along * c - across * d, along * d + across * c, 2.0 * Lam * sign * b * v


def k_rel_for_force(EI, L, psi, R, mode=1, *, tol=1e-14, maxiter=100):
    """The relative modulus whose clamped-pinned rod carries the tip force ``R`` at ``psi``.

    For a given ``psi`` and ``mode``, ``R`` grows strictly with ``|k|`` on the half of
    ``k_rel`` whose sign is that of ``cos(psi/2)`` (the branch that grows from the straight rod:
    bending towards the force), from ``R_0 = EI (2 (mode - 1) K(k_min) / L)**2`` to infinity.
    This function solves ``lambda L = F(phi2, k) - F(phi1, k)`` on that half (for ``psi = pi``,
    ``k_rel > 0``) by Newton's method safeguarded with bisection, in a variable ``zeta`` in
    which the equation is smooth and well conditioned at every load (``k cos(phi1) =
    sin(psi/2) tanh(zeta)``, ``1 - k**2 = (sin(psi/2) sech(zeta))**2``; see the module's
    comments), and checks its residual. On the other half ``R`` is not monotone and one force
    has several ``k_rel`` (the study's Ilustracion 10).

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m).
    psi : array_like
        Force direction in the local frame, in ``(0, 2 pi)`` (rad).
    R : array_like
        Force magnitude (N), positive.
    mode : int or array_like of int, optional
        Buckling mode.
    tol, maxiter
        Relative tolerance on ``lambda L = L sqrt(R / EI)`` (or the rounding floor of the
        solution, if larger) and most iterations per element.

    Returns
    -------
    ndarray
        ``k_rel``, broadcast shape of the inputs.

    Raises
    ------
    ValueError
        If an input is out of range, or ``R`` is so large (or so small) that ``k_rel`` rounds
        to ``+-1`` (or underflows): the chart ``k_rel`` cannot hold that rod in double
        precision (:func:`mechnum.rods.cantilever` can).
    NoEquilibriumError
        If ``R <= R_0`` (a mode above the first needs a least load).
    ConvergenceError
        If ``maxiter`` iterations do not reach ``tol``.

    Examples
    --------
    >>> kr = k_rel_for_force(1.0, 1.0, np.pi / 2, 1.0)    # a transverse unit force
    >>> rod = clamped_pinned(1.0, 1.0, np.pi / 2, kr)
    >>> round(float(rod.R), 12), np.round(rod.tip, 5).tolist()
    (1.0, [0.94357, 0.30172])
    """
    EI, L, R = (_validate.positive(v, name) for v, name in ((EI, "EI"), (L, "L"), (R, "R")))
    psi, mode = _angles(psi), _mode(mode)
    tol, maxiter = _validate.tolerance(tol), _validate.maxiter(maxiter)
    EI, L, R, psi, mode = np.broadcast_arrays(EI, L, R, psi, mode)
    k_rel = np.empty(psi.shape)
    for i in np.ndindex(psi.shape):
        a, b = math.cos(0.5 * psi[i]), math.sin(0.5 * psi[i])
        target = L[i] * math.sqrt(R[i] / EI[i])
        # lambda L at zeta = 0: the whole half-waves, and the Euler load in pure compression
        low = 2.0 * (mode[i] - 1) * float(elliprf(0.0, b * b, 1.0)) + (0.5 * math.pi if a == 0
                                                                      else 0.0)
        if target <= low:
            raise NoEquilibriumError(
                f"mode {mode[i]:.0f} needs R > {EI[i] * (low / L[i]) ** 2:.6g} N at "
                f"psi = {psi[i]:.6g}, got R = {R[i]:.6g}")
        v, _, k = _branch(a, b, _zeta(a, b, target, int(mode[i]), tol, maxiter))
        k_rel[i] = (1.0 if a >= 0 else -1.0) * v * v * (1.0 + abs(a)) / (k + abs(a))
        if not _TINY <= abs(k_rel[i]) < 1.0:
            raise ValueError(
                f"R L^2/EI = {target ** 2:.6g} at psi = {psi[i]:.6g}: k_rel = {k_rel[i]:.17g} "
                f"is not representable in double precision (it rounds to +-1 or underflows); "
                f"use rods.cantilever or rods.shoot_cantilever for this rod")
    return k_rel


def elliptic_parameters(EI, L, clamp_moment, force):
    """``(psi, k_rel, mode)`` of a clamped-pinned rod known by its clamp moment and tip force.

    The inverse of :func:`clamped_pinned`, for identifying a rod found by shooting (local
    frame, ``theta(0) = 0``): ``psi`` is the direction of ``force`` in ``[0, 2 pi)``,
    ``k sin(phi1) = cos(psi/2)`` and ``k cos(phi1) = m(0) / (2 EI lambda)`` (the study's (37)
    and (42) at ``s = 0``), and the mode is fixed by the tip amplitude
    ``phi2 = am(F(phi1, k) + lambda L)``, an odd multiple of ``pi/2``.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    clamp_moment : array_like
        ``m(0)`` (N m).
    force : array_like, shape (..., 2)
        The tip force (N), not zero.

    Returns
    -------
    psi, k_rel, mode, phi2 : ndarray
        ``phi2`` unrounded: ``(mode - 1/2) pi`` up to the accuracy of the inputs.

    Examples
    --------
    >>> rod = clamped_pinned(1.0, 1.0, 2.0, -0.4, mode=2)
    >>> psi, k_rel, mode, _ = elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)
    >>> round(float(psi), 12), round(float(k_rel), 12), int(mode)
    (2.0, -0.4, 2)
    """
    EI, L = _validate.positive(EI, "EI"), _validate.positive(L, "L")
    force, m0 = _vectors(force, "force", 2), _validate.array(clamp_moment, "clamp_moment")
    R = np.hypot(force[..., 0], force[..., 1])
    if np.any(R == 0):
        raise ValueError("the tip force must not be zero: an unloaded rod has no k")
    psi = np.mod(np.arctan2(force[..., 1], force[..., 0]), TWO_PI)
    if np.any(psi == 0):
        raise ValueError("a tip force along the clamped tangent (psi = 0, pure tension) has "
                         "no elliptic parameters: its rod is straight")
    lam = np.sqrt(R / EI)
    a, b = np.cos(0.5 * psi), m0 / (2.0 * EI * lam)
    k = np.where(b < 0, -1.0, 1.0) * np.hypot(a, b)
    k_min = np.abs(a)
    phi1 = np.arctan2(a * np.sign(k), np.abs(b))
    phi2 = ellipj(ellipkinc(phi1, k * k) + lam * L, k * k)[3]
    mode = np.round(phi2 / np.pi + 0.5)
    return psi, np.sign(k) * (np.abs(k) - k_min) / _one_minus_k_min(psi), mode, phi2


def pinned_equilibria(EI, L, tip, modes=(1, 2, 3), *, n_psi=120, n_k=80, tol=1e-13):
    """Every clamped-pinned equilibrium whose tip is at ``tip``, by the closed form.

    As the study does for its mechanisms, the admissible rectangle ``0 < psi < 2 pi``,
    ``0 < |k_rel| < 1`` of each mode is sampled on a grid (finer near ``k_rel = 0, +-1``); the
    local minima of the tip distance seed Newton's method (:func:`mechnum.newton.solve`) on
    ``tip(psi, k_rel) = target``, in variables that keep ``k_rel`` in its half-interval. A
    grid can miss a solution in a cell smaller than its spacing; refine it to check.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    tip : array_like, shape (2,)
        The pinned point in the local frame (m), within ``L`` of the clamp.
    modes : iterable of int, optional
        Buckling modes searched.
    n_psi, n_k : int, optional
        Grid size per mode (``n_k`` values of ``|k_rel|`` on each sign).
    tol : float, optional
        Newton step tolerance.

    Returns
    -------
    ndarray, shape (n, 3)
        Rows ``(psi, k_rel, mode)``, sorted by mode then ``R``; ``n >= 0``.

    Examples
    --------
    >>> sols = pinned_equilibria(1.0, 1.0, [0.8, 0.1], modes=(1, 2))   # none in mode 1
    >>> sols.shape, np.round(sols[:, :2], 4).tolist()
    ((2, 3), [[3.4872, -0.3223], [3.0352, 0.4212]])
    """
    EI, L = _validate.scalar(EI, "EI", positive=True), _validate.scalar(L, "L", positive=True)
    tip = _validate.array(tip, "tip", shape=(2,))
    if np.hypot(*tip) >= L:
        raise ValueError(f"tip must be one point closer than L = {L} to the clamp, got {tip!r}")
    modes = [int(m) for m in _mode(list(modes)).ravel()]
    n_psi, n_k = _validate.maxiter(n_psi, "n_psi"), _validate.maxiter(n_k, "n_k")
    tol = _validate.tolerance(tol)
    u = (np.arange(n_k) + 0.5) / n_k
    half = 0.5 * (1 - np.cos(np.pi * u))
    k_grid = np.concatenate((-half[::-1], half))
    psi_grid = (np.arange(n_psi) + 0.5) / n_psi * TWO_PI
    found = []
    for mode in modes:
        P, K = np.meshgrid(psi_grid, k_grid, indexing="ij")
        dist = np.linalg.norm(clamped_pinned(EI, L, P, K, mode).tip - tip, axis=-1)
        padded = np.pad(dist, 1, constant_values=np.inf)
        neighbours = np.stack([padded[1 + i:1 + i + n_psi, 1 + j:1 + j + 2 * n_k]
                               for i in (-1, 0, 1) for j in (-1, 0, 1) if i or j])
        for i, j in zip(*np.nonzero(dist <= neighbours.min(axis=0))):
            sign = np.sign(K[i, j])

            def unpack(z, sign=sign):   # psi free (wrapped), |k_rel| = logistic(z[1])
                return np.mod(z[0], TWO_PI), sign * expit(np.clip(z[1], -_LOGIT_CLIP,
                                                                  _LOGIT_CLIP))

            def fun(z, mode=mode, unpack=unpack):
                return clamped_pinned(EI, L, *unpack(z), mode).tip - tip

            z0 = [P[i, j], np.log(abs(K[i, j]) / (1 - abs(K[i, j])))]
            try:
                z = newton.solve(fun, z0, tol=tol, maxiter=_POLISH_MAXITER).x
            except (MechnumError, ValueError):
                continue
            if np.linalg.norm(fun(z)) < _TIP_ACCEPT * L:
                found.append((*unpack(z), mode))
    if not found:
        return np.empty((0, 3))
    found = np.array(found, dtype=float)   # the same root from two cells: keep one, unrounded
    sols = found[np.unique(np.round(found, _SAME_DIGITS), axis=0, return_index=True)[1]]
    R = clamped_pinned(EI, L, sols[:, 0], sols[:, 1], sols[:, 2]).R
    return sols[np.lexsort((R, sols[:, 2]))]
