"""The growing branch of a cantilever in closed form: a chart that holds every digit.

(The module of the cantilever's chart; it is not called ``cantilever`` because
:func:`mechnum.rods.cantilever` is the function that a reader calls.)

A cantilever clamped along +x under a tip force ``n = R (cos psi, sin psi)`` has, among its
equilibria, the one that grows continuously from the unloaded rod (mode 1, bending towards the
force): the **growing branch**. This module evaluates it in Carlson's symmetric integrals, in a
variable ``zeta`` in which every quantity is smooth and free of cancellation, from loads of
``1e-200`` (linear beam theory to rounding) to ``P L**2 / EI`` near ``1e5``; the study's formulas
(:func:`mechnum.rods.clamped_pinned`) lose the small loads and the large ones. It serves
:func:`mechnum.rods.cantilever`, the default starts of the shooting solvers
(:func:`growing_rod`, the pinned rod's start), :func:`mechnum.rods.k_rel_for_force`
(:func:`growing_branch`) and the shapes of nearly unloaded rods (:func:`branch_shape`).
"""

import math

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import elliprd, elliprf

from mechnum import _validate
from mechnum.errors import ConvergenceError
from mechnum.rods._rod import MAX_NODES, Rod

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
SERIES = 5e-3
"""Below this relative spread of its arguments, :func:`_rf_excess` uses its series (error near
``4e-17`` of the excess at ``5e-3``); beyond, the difference loses at most ``eps / 5e-3`` of
it."""
_STRAIGHT = 0.25  # _Branch.tip: a deviation from the straight rod where |excess| is below
_SMALL_STEP = 1e-8  # a Newton step below 1e-8 t1 leaves an error near 1e-16 t1 (quadratic rate)
CLOSED_FORM_TOL = 1e-14  # relative residual of lambda L at which the cantilever's modulus is kept
CLOSED_FORM_MAXITER = 100  # Newton-bisection steps for it: bisection alone needs some 60


def _folded(psi):
    """``(a, b)`` of the force direction ``psi`` (any real): ``b = |sin(psi/2)|`` (at least
    :data:`_B_MIN`) and ``a = cos(psi/2)`` signed as ``sin(psi)`` (as ``n_y``)."""
    half = 0.5 * math.remainder(psi, math.tau)          # psi / 2 in [-pi/2, pi/2]
    sign = 1.0 if half >= 0 else -1.0
    return sign * math.cos(half), max(abs(math.sin(half)), _B_MIN)


def growing_branch(a: float, b: float, Lam: float, mode: int = 1, *,
                   tol: float = CLOSED_FORM_TOL,
                   maxiter: int = CLOSED_FORM_MAXITER) -> tuple[float, float, float]:
    """``(v, s, |k|)`` of the growing branch at ``lambda L = Lam``.

    ``a = cos(psi/2)`` and ``b = sin(psi/2) > 0`` of the force direction; ``v = tanh(zeta)``
    and ``s = sech(zeta)``, so that ``k cos(phi1) = sign(a) b v`` and ``1 - k**2 = (b s)**2``
    (the module's comments). ``Lam`` must exceed the branch's least value, ``2 (mode - 1)
    K(|a|)`` (the caller checks). Raises :class:`~mechnum.errors.ConvergenceError` if
    ``maxiter`` Newton-bisection steps do not reach ``tol``, and ValueError beyond the range
    of double precision.

    Examples
    --------
    >>> v, s, k = growing_branch(np.sqrt(0.5), np.sqrt(0.5), 1.0)   # transverse, P L^2/EI = 1
    >>> round(k, 6), bool(abs(v * v + s * s - 1) < 1e-15)
    (0.850047, True)
    """
    a, b, Lam = _validate.numbers(dict(a=a, b=b, Lam=Lam), positive=("b",), nonnegative=("Lam",))
    return _branch(a, b, _zeta(a, b, Lam, mode, tol, maxiter))


def chart_tip(a: np.ndarray, b: np.ndarray, v: np.ndarray, w: np.ndarray) -> tuple:
    """The tip of growing-branch rods of mode 1 in the regular chart, and its rates, without
    cancellation or underflow as the load tends to zero (arrays: ``b``, ``w > 0``, ``v >= 0``).

    In ``rods``'s regular module's notation (``a = cos(psi/2)``, ``b = sin(psi/2)``,
    ``v = |v|``, ``w = 1 - v**2``, ``m = k**2``, ``p = 1 - k**2``) this branch has ``Lambda = I``
    and ``D = p I + m G``, so the tip ``L Rot(psi) (u, -w2)`` has ``u = 1 - 2 p - 2 m G / I``
    and ``w2 = 2 sign(a) b v / I``. With ``X = w a**2 / m``, ``R_F = R_F(X, 1, w)`` and ``R_D =
    R_D(X, 1, w)``: ``v / I = k / R_F``, ``G / I = p v**2 R_D / (3 m R_F)`` and ``G / I**2 = p v
    R_D / (3 k R_F**2)``, none of which loses digits (or underflows) where ``v`` and ``I``
    vanish together. Nor does the tip, written as the straight rod plus the deviations
    ``du = u - cos(psi) = 2 b**2 v**2 (1 - w R_D / (3 R_F))`` and ``dw = w2 - sin(psi) =
    -2 sign(a) b (v / I) e`` (``e = |a| R_F / k - 1`` from :func:`_rf_excess`): ``tip = L (1 +
    du cos(psi) + dw sin(psi), du sin(psi) - dw cos(psi))``. Nor do the rates, which the quotient
    rule would find as differences of nearly equal terms divided by ``I**2``, written here with
    those terms cancelled::

        du/dv = 2 (v p + m v (G/I)**2 + |a| G / I**2) / w
        du/dpsi = -sign(a) (b (v/I) (1 - G/I) + |a| b w + m |a| (G/I)**2 / b)
        d(v/I)/dv = b**2 v / (k R_F) + k (R_D(1, w, X) X_v - 2 v R_D) / (6 R_F**2)
        d(v/I)/dpsi = -(v/I)**2 sign(a) (b**2 / m - |a| (G/I) / (v/I)) / (2 b)

    (Carlson's ``dR_F/dz = -R_D / 6``, DLMF 19.18.1; ``X_v = -2 a**2 v (m + b**2 w) / m**2``.)

    Returns
    -------
    du, dw, u_v, u_psi, w2_v, w2_psi : ndarray
        The deviations, and the rates of ``u`` and of ``w2 / sign(a)``.

    Examples
    --------
    Near the unloaded rod ``du = (4/3) b**2 v**2`` and ``du/dv = (8/3) b**2 v`` (to ``v**2``):

    >>> a, b, v = np.cos(1.0), np.sin(1.0), 1e-150
    >>> du, dw, u_v = chart_tip(a, b, v, 1.0)[:3]
    >>> round(float(du / (b * b * v * v)), 12), round(float(u_v / (b * b * v)), 12)
    (1.333333333333, 2.666666666667)
    """
    # unchecked: a kernel of the closed form's inner loop (its callers checked the chart)
    a, b, v, w = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (a, b, v, w)))
    X = w * a * a / (a * a + b * b * v * v)
    return tip_deviations(a, b, v, w, elliprf(X, 1.0, w), elliprd(X, 1.0, w))


def tip_deviations(a, b, v, w, RF, RD, rates=True) -> tuple:
    """:func:`chart_tip` from the partial wave's ``R_F = R_F(X, 1, w)`` and ``R_D = R_D(X, 1,
    w)`` (the closed form has them), unchecked as it is: arrays of one shape. Its Carlson
    integrals: ``R_D(1, w, X)`` with the ``rates`` (which it returns only then: else ``(du,
    dw)``), and :func:`_rf_excess`'s where its series does not serve.

    Examples
    --------
    >>> a, b, v, w = (np.array([x]) for x in (np.cos(1.0), np.sin(1.0), 0.3, 0.91))
    >>> X = w * a * a / (a * a + b * b * v * v)
    >>> fast = tip_deviations(a, b, v, w, elliprf(X, 1.0, w), elliprd(X, 1.0, w))
    >>> bool(np.allclose(fast, chart_tip(a, b, v, w), rtol=0, atol=0))
    True
    """
    aa, sa = np.abs(a), np.where(a < 0, -1.0, 1.0)
    m, p = a * a + b * b * v * v, b * b * w
    k = np.sqrt(m)
    vI = k / RF
    du = 2.0 * b * b * v * v * (1.0 - w * RD / (3.0 * RF))
    dw = -2.0 * sa * b * vI * _rf_excess(a, b, v, w)
    if not rates:
        return du, dw
    X = w * a * a / m
    g1, g2 = p * v * v * RD / (3.0 * m * RF), p * v * RD / (3.0 * k * RF * RF)
    u_v = 2.0 * (v * p + m * v * g1 * g1 + aa * g2) / w
    u_psi = -sa * (b * vI * (1.0 - g1) + aa * b * w + m * aa * g1 * g1 / b)
    X_v = -2.0 * a * a * v * (m + b * b * w) / (m * m)
    vI_v = b * b * v / (k * RF) + k * (elliprd(1.0, w, X) * X_v - 2.0 * v * RD) / (6.0 * RF * RF)
    vI_psi = -vI * vI * sa * (b * b / m - aa * g1 / vI) / (2.0 * b)
    return du, dw, u_v, u_psi, 2.0 * b * vI_v, a * vI + 2.0 * b * vI_psi


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


def _shape(rod, EI, L, nodes, maxiter):
    """``(x, y, theta, m)`` of a :class:`_Branch` at ``nodes`` equally spaced nodes, shape
    ``(nodes, 4)``: the clamp and the tip on floats, the nodes between them on arrays."""
    ends = np.array([[0.0, 0.0, 0.0, EI / L * rod.moment(rod.v)],
                     [*(L * rod.tip()), rod.angle(0.0, 1.0), 0.0]])
    if nodes > 2:
        sigma = np.linspace(0.0, 1.0, nodes)[1:-1]
        a, b, v, s, k = rod.a, rod.b, rod.v, rod.s, rod.k
        t = _amplitudes(b, v, s, k, math.atan2(b * v, abs(a)), rod.Lam * (1.0 - sigma), maxiter)
        eta, cos_t = np.minimum(k * np.sin(t) / b, v), np.cos(t)
        x, y = rod.position(sigma, eta, _arcs(b, s, k, eta, cos_t)[1])
        inner = np.column_stack((L * x, L * y, rod.angle(eta, cos_t), EI / L * rod.moment(eta)))
        ends = np.concatenate((ends[:1], inner, ends[1:]))
    return ends


def growing_rod(EI: float, L: float, force: ArrayLike, nodes: int = 2, *,
                tol: float = CLOSED_FORM_TOL, maxiter: int = CLOSED_FORM_MAXITER) -> Rod:
    """The growing-branch (mode 1) cantilever under a tip force, in closed form.

    The fast path of :func:`mechnum.rods.cantilever` (``EI``, ``L`` > 0, ``force`` a 2-vector,
    ``2 <= nodes <= MAX_NODES``), by the formulas of the module's comments and :class:`_Branch`.

    Examples
    --------
    >>> rod = growing_rod(1.0, 1.0, [0.0, 1.0])     # Bisshopp and Drucker, P L^2 / EI = 1
    >>> np.round(rod.tip, 5).tolist(), round(float(rod.clamp_moment), 5)
    ([0.94357, 0.30172], 0.94357)
    """
    EI, L = _validate.numbers(dict(EI=EI, L=L), positive=("EI", "L"))
    nx, ny = _validate.array(force, "force", shape=(2,)).tolist()
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    R = math.hypot(nx, ny)
    half = 0.5 * math.atan2(ny, nx)     # psi / 2, folded into (-pi/2, pi/2]
    sign = 1.0 if half >= 0 else -1.0   # sign(k) = sign(a) = sign(n_y)
    a, b = sign * math.cos(half), abs(math.sin(half))
    if b < _B_MIN:  # a force this close to pure tension leaves the rod straight to rounding
        return Rod(np.linspace(0.0, L, nodes), np.linspace(0.0, L, nodes), np.zeros(nodes),
                   np.zeros(nodes), np.zeros(nodes), np.array([nx, ny]))
    rod = _Branch.solved(a, b, L * math.sqrt(R / EI), nx / R, ny / R, tol, maxiter)
    return Rod(np.linspace(0.0, L, nodes), *_shape(rod, EI, L, nodes, maxiter).T,
               np.array([nx, ny]))


def branch_shape(EI: float, L: float, psi: float, v: float, w: float, Lam: float,
                 nodes: int) -> np.ndarray:
    """``(x, y, theta, m)`` at ``nodes`` nodes of the growing-branch rod ``(psi, v)``: shape
    ``(nodes, 4)``, local frame (``2 <= nodes <= MAX_NODES``).

    The rod of the regular chart (``rods``'s regular module) of mode 1 with ``sign(t) =
    sign(cos(psi/2))``, given by ``v`` (``tanh(zeta)`` here), ``w = 1 - v**2`` (given, as it
    may be tiny) and ``Lam = lambda L``; accurate as the load tends to zero, where the
    study's position formulas divide differences of nearly equal integrals by ``lambda``.

    Examples
    --------
    >>> from mechnum.rods import _regular as regular
    >>> end = regular.closed_form(1.0, 1.0, 2.0, 1e-12)          # EI = L = 1
    >>> Lam = float(np.sqrt(np.hypot(*end.force)))
    >>> xy = branch_shape(1.0, 1.0, 2.0, 1e-12, 1.0, Lam, 3)[:, :2]
    >>> bool(np.abs(xy[-1] - end.tip).max() < 1e-15), bool(abs(xy[1, 0] - 0.5) < 1e-15)
    (True, True)
    """
    EI, L, psi, v, w, Lam = _validate.numbers(dict(EI=EI, L=L, psi=psi, v=v, w=w, Lam=Lam),
                                              positive=("EI", "L", "w"), nonnegative=("v", "Lam"))
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    a, b = _folded(psi)
    rod = _Branch(a, b, v, math.sqrt(w), Lam, math.cos(psi), math.sin(psi))
    return _shape(rod, EI, L, nodes, CLOSED_FORM_MAXITER)


def _clamp_G(a, b, v, s, k):
    """``G(t1)``, the integral from the tip to the clamp (scalars)."""
    return b * b * v ** 3 * s * s / (3.0 * k ** 3) * float(elliprd((s * a / k) ** 2, 1.0, s * s))


def _rf_excess(a, b, v, w):
    """``|a| lambda L / v - 1`` of the growing branch (floats or arrays), accurate as the load
    tends to 0.

    ``lambda L / v = R_F(w a**2, k**2, w k**2)`` (R_F is homogeneous) and ``1 / |a| =
    R_F(a**2, a**2, a**2)``: for small loads the excess is a difference of nearly equal values.
    The three arguments exceed ``a**2`` by ``delta = v**2 (-a**2, b**2, b**2 w - a**2)``,
    computed without cancellation; where they differ from their mean ``A`` by less than
    ``SERIES A``, Carlson's series of R_F about ``A`` (DLMF 19.36.1, with an error of the
    eighth order in the deviations) gives the excess from the ``delta`` alone. Beyond, the
    plain difference loses at most ``eps / SERIES`` of the excess.
    """
    deltas = (-(v * a) ** 2, (v * b) ** 2, v * v * (b * b * w - a * a))
    mean = sum(deltas) / 3.0
    A = a * a + mean
    if np.ndim(a) == np.ndim(v) == np.ndim(w) == 0:    # one rod on floats: the hot path
        if a == 0.0:
            return -1.0
        X, Y = ((mean - delta) / A for delta in deltas[:2])
        if max(abs(X), abs(Y), abs(X + Y)) > SERIES:
            return _rf_far(a, b, v, w)
        return _rf_near(abs(a), mean, A, X, Y)
    with np.errstate(divide="ignore", invalid="ignore"):       # a = 0 is answered below
        X, Y = ((mean - delta) / A for delta in deltas[:2])
        far = np.maximum(np.maximum(np.abs(X), np.abs(Y)), np.abs(X + Y)) > SERIES
        if not far.any():
            out = _rf_near(np.abs(a), mean, A, X, Y)
        elif far.all():
            out = _rf_far(a, b, v, w)
        else:      # each formula on its own rows (the far one costs an integral)
            a, b, v, w, mean, A, X, Y = np.broadcast_arrays(a, b, v, w, mean, A, X, Y)
            out = np.empty(far.shape)
            out[far] = _rf_far(a[far], b[far], v[far], w[far])
            near = ~far
            out[near] = _rf_near(np.abs(a[near]), mean[near], A[near], X[near], Y[near])
    return np.where(a == 0, -1.0, out)


def _rf_far(a, b, v, w):
    """The excess of :func:`_rf_excess` as a plain difference."""
    k2 = a * a + (b * v) ** 2
    return np.abs(a) * elliprf(w * a * a, k2, w * k2) - 1.0


def _rf_near(aa, mean, A, X, Y):
    """The excess of :func:`_rf_excess` from Carlson's series about ``A``."""
    Z = -X - Y
    E2, E3 = X * Y - Z * Z, X * Y * Z
    series = (-E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0
              - 5.0 * E2 ** 3 / 208.0 + 3.0 * E3 * E3 / 104.0 + E2 * E2 * E3 / 16.0)
    root = np.sqrt(A)
    return (aa * series - mean / (aa + root)) / root   # |a| A**-1/2 (1 + series) - 1


class _Branch:
    """One rod of the growing branch (mode 1) in the clamp's frame, for the cantilever and its
    shape: the force direction's ``a`` (signed as ``n_y``) and ``b``, ``v``,
    ``s = sqrt(1 - v**2)``, ``Lam = lambda L`` and ``(c, d) = (cos psi, sin psi)``.

    In the force's frame, the point at arc fraction ``sigma`` lies ``L (sigma c + along)``
    along the force and ``-2 sign(a) b L (v - eta) / Lam`` across it, with ``along = 2 (b
    v)**2 sigma - 2 k**2 (G1 - G) / Lam``; :meth:`position` rotates it into the clamp's frame.
    At the tip of a nearly straight rod that rotation would subtract terms of order ``L`` to
    find a small ``y`` (all digits were lost at loads near 1e-14), so :meth:`tip` writes the
    tip as the straight rod ``(L, 0)`` plus a deviation computed from small terms only: across
    the force, ``L across`` beyond ``-L d``, with ``across = 2 sign(a) b (|a| - v / Lam)`` from
    :func:`_rf_excess`; rotated back with ``c**2 + d**2 = 1``, ``x = L (1 + along c - across
    d)`` and ``y = L (along d + across c)``.
    """

    def __init__(self, a, b, v, s, Lam, c, d):
        self.a, self.b, self.v, self.s, self.Lam, self.c, self.d = a, b, v, s, Lam, c, d
        self.sign = 1.0 if a >= 0 else -1.0
        self.k = math.sqrt(a * a + (b * v) ** 2)
        self.G1 = _clamp_G(a, b, v, s, self.k)

    @classmethod
    def solved(cls, a, b, Lam, c, d, tol, maxiter):
        """The rod of the branch that carries ``lambda L = Lam``."""
        v, s, _ = _branch(a, b, _zeta(a, b, Lam, 1, tol, maxiter))
        return cls(a, b, v, s, Lam, c, d)

    def _along(self, sigma, G):
        return 2.0 * (self.b * self.v) ** 2 * sigma - 2.0 * self.k ** 2 * (self.G1 - G) / self.Lam

    def position(self, sigma, eta, G):
        """``(x / L, y / L)`` at arc fraction ``sigma``, where ``sin(t) = b eta / |k|``."""
        along = sigma * self.c + self._along(sigma, G)
        across = -2.0 * self.sign * self.b * (self.v - eta) / self.Lam
        return along * self.c - across * self.d, along * self.d + across * self.c

    def tip(self):
        """``(x(L) / L, y(L) / L)``: as a deviation from the straight rod where the rod is nearly
        straight (``|excess| <= _STRAIGHT``), as :meth:`position` where it is not."""
        excess = _rf_excess(self.a, self.b, self.v, self.s ** 2)
        if abs(excess) > _STRAIGHT:
            return np.array(self.position(1.0, 0.0, 0.0))
        along = self._along(1.0, 0.0)
        across = 2.0 * self.sign * self.b * excess * self.v / self.Lam
        return np.array((1.0 + (along * self.c - across * self.d),
                         along * self.d + across * self.c))

    def angle(self, eta, cos_t):
        """``theta`` where ``sin(t) = b eta / |k|``.

        ``theta = psi - 2 beta``, ``beta`` the angle of ``(sign(a) k cos t, b q)`` with ``q =
        sqrt(s**2 + eta**2)``, written as one arctan of the difference of ``psi / 2`` and
        ``beta``, whose sine has the factor ``|k| cos t - |a| q = (v**2 - eta**2) / (|k| cos t
        + |a| q)``: zero at the clamp, and accurate at small loads.
        """
        a, b, v, kc = abs(self.a), self.b, self.v, self.k * cos_t
        q = np.sqrt(self.s ** 2 + eta * eta)
        return 2.0 * self.sign * np.arctan2(b * (v - eta) * (v + eta),
                                            (kc + a * q) * (a * kc + b * b * q))

    def moment(self, eta):
        """``m L / EI`` where ``sin(t) = b eta / |k|``."""
        return 2.0 * self.Lam * self.sign * self.b * eta
