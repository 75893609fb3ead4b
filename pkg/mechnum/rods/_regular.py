"""The clamped-pinned closed form in a chart that is regular where the study's is not.

The study parametrises a clamped-pinned rod of a given ``mode`` by ``(psi, k_rel)`` (its
(89) to (91); conventions: :mod:`mechnum.rods`). That chart is singular at both ends of its
range: ``phi1 = arcsin(cos(psi/2) / k)`` has ``d phi1 / d k_rel ~ 1 / sqrt|k_rel|`` as
``k_rel -> 0``, and the tip moves like ``1 / log(1 - |k_rel|)`` as ``k_rel -> +-1`` (the force
grows without bound and the rod straightens). Real equilibria sit at both ends (a 2RFR rod
of the study's own example has ``k_rel = -0.0044``; others have ``|k_rel|`` within ``1e-7``
of 1), where Newton in ``(psi, k_rel)`` is slow or lost. This module uses ``(psi, t)``:

* ``v = k cos(phi1) / sin(psi/2)``, in ``(-1, 1)`` with the sign of ``k_rel``. With
  ``a = cos(psi/2)`` and ``b = sin(psi/2)``: ``k sin(phi1) = a`` and ``k cos(phi1) = v b``, so
  ``k**2 = a**2 + v**2 b**2``, ``1 - k**2 = b**2 (1 - v**2)`` and every quantity below is
  explicit, with no ``arcsin``.
* ``1 - v**2 = exp(-t**2 / (1 - t**2))``, ``t`` in ``(-1, 1)`` with the sign of ``v``:
  ``v ~ t`` near 0, and as ``t -> +-1`` the force grows like ``1 / (1 - t**2)`` and the tip
  is a smooth function of ``t`` (it depends smoothly on ``1 / lambda``, up to terms
  ``exp(-lambda L)`` whose every derivative vanishes there).

The elliptic integrals are evaluated in Carlson's symmetric form (DLMF 19.25.5 and 19.25.7),
``F(phi, k) = sin(phi) R_F(cos(phi)**2, 1 - k**2 sin(phi)**2, 1)`` and
``E(phi, k) = F(phi, k) - k**2 sin(phi)**3 R_D(cos(phi)**2, 1 - k**2 sin(phi)**2, 1) / 3``,
from the complementary parameter ``1 - k**2`` itself, so that no digit is lost as
``|k| -> 1`` (scipy's ``ellipkinc(phi, m)`` would receive ``m = k**2`` already rounded). With
``Lambda = lambda L = F(phi2, k) - F(phi1, k)`` and ``D = E(phi2, k) - E(phi1, k)``, the
study's (86) to (88) at the tip become::

    tip = L Rot(psi) (1 - 2 D / Lambda, -2 v b / Lambda)
    force = R (cos psi, sin psi),  R = EI Lambda**2 / L**2
    m(0) = 2 EI v b Lambda / L

and their derivatives with respect to ``(psi, t)`` follow in closed form (DLMF 19.4.1 to
19.4.4 for the derivatives of ``F`` and ``E`` in ``phi`` and ``k``), written so that the
factors ``1 / (1 - k**2)`` cancel analytically.

The sign of ``t`` selects the branch (the study's sign of ``k_rel``); ``t = 0`` is the edge
between them, where the two branches do not meet (the clamp moment vanishes on one side, the
force on the other). Also singular, as in the study's chart: ``psi = 0`` (force along the
clamped tangent: the straight rod in tension, whose tip does not depend on the force), and
``k = 0`` (``psi = pi`` and ``t = 0``: the straight rod at the Euler load).
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import elliprd, elliprf

from mechnum import _validate
from mechnum.rods._growing import tip_deviations
from mechnum.rods._rod import as_modes, as_vectors, batch_shape, rod_scales

TWO_PI = 2.0 * np.pi
# Largest q = t**2 / (1 - t**2): 1 - k**2 = b**2 exp(-q) must stay a normal double (exp(-708)
# underflows), and at q = 600 the force is already (q / 2)**2 ~ 1e5 times EI / L**2.
Q_MAX = 600.0
T_MAX = float(np.sqrt(Q_MAX / (1.0 + Q_MAX)))
"""The largest ``|t|`` the chart accepts (``q = Q_MAX``)."""
SMALL_LOAD = 1.0
"""Below this ``lambda L``, :func:`shape` draws the growing branch of mode 1 in the
cantilever's chart, which holds every digit as the load tends to zero (the study's formulas
lose about ``eps / (lambda L)`` of ``L``)."""


@dataclass(frozen=True)
class RegularRod:
    """A clamped-pinned rod from :func:`clamped_pinned_regular` (local frame).

    Attributes
    ----------
    tip, force : ndarray, shape (..., 2)
        Tip position (m) and the force on the rod at its tip (N).
    clamp_moment : ndarray, shape (...)
        ``m(0)`` (N m).
    jacobian : ndarray, shape (..., 5, 2) or None
        ``d (tip_x, tip_y, force_x, force_y, clamp_moment) / d (psi, t)``.
    """

    tip: np.ndarray
    force: np.ndarray
    clamp_moment: np.ndarray
    jacobian: np.ndarray = None


def _check(psi, t, name="t", bound=f"<= {T_MAX:.6f}"):
    """``psi`` and ``t`` (or ``k_rel``, ``bound="< 1"``), checked."""
    psi, t = _validate.array(psi, "psi"), _validate.array(t, name)
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError("psi must lie in the open interval (0, 2 pi), "
                         f"got {_validate.shown(psi)}")
    if np.any((t == 0) | ((np.abs(t) > T_MAX) if name == "t" else (np.abs(t) >= 1))):
        raise ValueError(f"{name} must satisfy 0 < |{name}| {bound}, got {_validate.shown(t)}")
    return psi, t


def _inputs(EI, L, psi, t, mode):
    """The checked inputs of :func:`clamped_pinned_regular` and :func:`shape`."""
    EI, L = rod_scales(EI, L)
    psi, t = _check(psi, t)
    mode = as_modes(mode)
    batch_shape(EI=EI.shape, L=L.shape, psi=psi.shape, t=t.shape, mode=mode.shape)
    return EI, L, psi, t, mode


def _q(t):
    """``q = t**2 / (1 - t**2)`` without cancellation near ``|t| = 1``."""
    return t * t / ((1.0 - t) * (1.0 + t))


def k_rel_from_t(psi: ArrayLike, t: ArrayLike, *, complement: bool = False) -> np.ndarray:
    """The study's ``k_rel`` of the rod ``(psi, t)``, or ``1 - |k_rel|``.

    Parameters
    ----------
    psi, t : array_like
        The rod in the chart.
    complement : bool, optional
        Return ``1 - |k_rel|`` instead, computed without cancellation (a rod in near-straight
        tension has ``|k_rel|`` too close to 1 for a double to tell it from 1).

    Examples
    --------
    >>> round(float(k_rel_from_t(2.0, t_from_k_rel(2.0, -0.004391))), 12)
    -0.004391
    >>> float(k_rel_from_t(5.3, -0.99, complement=True)) < 1e-20
    True
    """
    psi, t = _check(psi, t)
    complement = _validate.flag(complement, "complement")
    a, b = np.abs(np.cos(0.5 * psi)), np.sin(0.5 * psi)
    q = _q(t)
    k = np.sqrt(a * a - np.expm1(-q) * b * b)
    one_minus_kmin = b * b / (1.0 + a)
    if complement:     # (1 - |k|) / (1 - k_min), with 1 - |k| = (1 - k**2) / (1 + |k|)
        return b * b * np.exp(-q) / (1.0 + k) / one_minus_kmin
    # |k| - k_min = (k**2 - k_min**2) / (|k| + k_min), without cancellation
    return np.sign(t) * (-np.expm1(-q) * b * b / (k + a)) / one_minus_kmin


def t_from_k_rel(psi: ArrayLike, k_rel: ArrayLike) -> np.ndarray:
    """The chart's ``t`` of the study's rod ``(psi, k_rel)``, ``0 < |k_rel| < 1``.

    Examples
    --------
    >>> float(np.round(t_from_k_rel(np.pi, [0.5, -1 + 1e-9]), 6)[1])
    -0.975935
    """
    psi, k_rel = _check(psi, k_rel, "k_rel", "< 1")
    _validate.broadcast(psi=psi, k_rel=k_rel)
    a, b = np.abs(np.cos(0.5 * psi)), np.sin(0.5 * psi)
    one_minus_kmin = b * b / (1.0 + a)
    k = a + one_minus_kmin * np.abs(k_rel)
    # 1 - v**2 and v**2 = (k - k_min)(k + k_min) / b**2, each without cancellation
    one_minus_v2 = one_minus_kmin * (1.0 - np.abs(k_rel)) * (1.0 + k) / (b * b)
    v2 = one_minus_kmin * np.abs(k_rel) * (k + a) / (b * b)
    q = np.where(v2 < 0.5, -np.log1p(-np.minimum(v2, 0.5)), -np.log(one_minus_v2))
    return np.sign(k_rel) * np.sqrt(q / (1.0 + q))


def clamped_pinned_regular(EI: ArrayLike, L: ArrayLike, psi: ArrayLike, t: ArrayLike,
                           mode: ArrayLike = 1, *, jacobian: bool = True) -> RegularRod:
    """Tip, tip force and clamp moment of clamped-pinned rods, with their analytic Jacobian.

    Vectorised: ``EI``, ``L``, ``psi``, ``t`` and ``mode`` broadcast together (one call for all
    the rods of a mechanism, or for all the starts of a search).

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m), positive.
    psi : array_like, shape (...)
        Direction of the tip force from the clamped tangent, in ``(0, 2 pi)`` (rad).
    t : array_like, shape (...)
        The chart's coordinate, ``0 < |t| <= T_MAX`` (its sign is the study's sign of
        ``k_rel``; see :func:`t_from_k_rel`).
    mode : int or array_like of int, optional
        Buckling mode, ``>= 1`` (inflections of the rod on ``0 < s <= L``).
    jacobian : bool, optional
        Also return the derivatives with respect to ``(psi, t)``.

    Returns
    -------
    RegularRod

    Raises
    ------
    ValueError
        If an input is outside its range or not finite, or the shapes do not broadcast.

    Examples
    --------
    The rods of the study's Table 7 (its solution 2, mode 1):

    >>> psi, k_rel = np.array([1.962541, 4.811041]), np.array([-0.004391, 0.943413])
    >>> rod = clamped_pinned_regular(0.0522, 1.0, psi, t_from_k_rel(psi, k_rel))
    >>> np.round(rod.tip, 6).tolist(), rod.jacobian.shape
    ([[0.235039, -0.642051], [-0.298731, -0.164104]], (2, 5, 2))
    """
    return closed_form(EI, L, psi, t, mode, jacobian=jacobian)


def _rows(mask):
    """An index of the rows ``mask`` holds: the whole array if all, None if none."""
    return slice(None) if mask.all() else np.flatnonzero(mask) if mask.any() else None


def _waves(a, b, v, w, j, sgn, rates=True):
    """The elliptic integrals of clamped-pinned rods, and their rates: the one core.

    For rows (1-D arrays) of ``a = cos(psi/2)`` (signed), ``b = sin(psi/2) > 0``, ``v = |v|``,
    ``w = 1 - v**2`` (given, not computed from ``v``: it may be tiny), ``j = 2 mode - 1`` and
    ``sgn = +1`` on the growing branch (``sign(t) = sign(a)``, with ``a = 0`` taken as
    positive) or ``-1``: ``Lambda = lambda L = j K - F(phi1)`` and ``D = j E(k) - E(phi1)``.
    They are built from the complete integrals ``K``, ``E(k)`` and the **partial wave** from
    ``|phi1|`` to ``pi/2`` (``t = pi/2 - phi`` from 0 to ``t1``, ``cos(t1) = |a| / k``; DLMF
    19.25.5, 19.25.7 with ``sin(t)`` for ``sin(phi)``)::

        I = int_0^t1 dt / Delta = (v / k) R_F(X, 1, w),    X = w a**2 / k**2
        G = int_0^t1 sin(t)**2 dt / Delta = b**2 w v**3 / (3 k**3) R_D(X, 1, w)

    whose E-integral is ``p I + k**2 G`` (``p = 1 - k**2 = b**2 w``), so that
    ``F(phi1) = sgn (K - I)`` and ``Lambda = (j - sgn) K + sgn I``: no difference of nearly
    equal integrals near the straight rod, and no ``m = k**2`` rounded near 1 (``p`` is exact).

    With ``rates``, their derivatives in ``|v|`` at fixed ``psi`` and in ``psi`` at fixed ``v``
    (DLMF 19.4.1 to 19.4.4, the factors ``1/p`` cancelled analytically), as ``dI/dv = (v G +
    |a| / k**2) / w`` and ``dI/dpsi = sign(a) (b**2 v / k**2 - |a| G) / (2 b)``.

    Each integral is computed once, on the rows that need it: the partial wave's ``R_F`` and
    ``R_D`` on every row (returned: the growing branch's tip reuses them), ``K``, ``E(k)`` and
    ``D`` only where ``j != sgn`` (mode 1 on its growing branch has ``Lambda = I``, and its tip
    needs no ``D``). Returns ``(Lambda, D, R_F, R_D)`` and, with ``rates``, ``((Lambda_v,
    Lambda_psi), (D_v, D_psi))`` (``D`` and its rates NaN on the growing rows).
    """
    m, p = a * a + b * b * v * v, b * b * w
    k = m ** 0.5
    X = w * a * a / m
    RF, RD = elliprf(X, 1.0, w), elliprd(X, 1.0, w)
    Iw = v / k * RF
    G = p * v ** 3 / (3.0 * k ** 3) * RD
    Dp = p * Iw + m * G
    sa, aa = np.where(a < 0, -1.0, 1.0), abs(a)   # sign(a) (+1 at a = 0) and |a|
    Lam, D = Iw.copy(), np.full(Iw.shape, np.nan)
    Lam_d = [(v * G + aa / m) / w, sa * (b * b * v / m - aa * G) / (2.0 * b)]
    D_d = [np.full(Iw.shape, np.nan), np.full(Iw.shape, np.nan)]
    rows = _rows(j != sgn)
    if rows is not None:          # the rows past the partial wave: K, E(k), D and rates
        a, b, v, w, m, p, aa, sa, G, Iw, Dp, sgn = (x[rows] for x in (
            a, b, v, w, m, p, aa, sa, G, Iw, Dp, sgn))
        n = j[rows] - sgn
        K = elliprf(0.0, p, 1.0)
        Ek = K - m / 3.0 * elliprd(0.0, p, 1.0)
        Lam[rows], D[rows] = n * K + sgn * Iw, n * Ek + sgn * Dp
        if rates:
            K_d = (v * (Ek - p * K) / (m * w), -a * (Ek - p * K) / (2.0 * m * b))
            Ek_d = (v * b * b * (Ek - K) / m, -a * b * w * (Ek - K) / (2.0 * m))
            own = ((v * p * (Dp - Iw) / w + aa * b * b) / m,
                   sa * b * (v - aa * w * (Dp - Iw)) / (2.0 * m))
            for i in range(2):
                Lam_d[i][rows] = n * K_d[i] + sgn * Lam_d[i][rows]
                D_d[i][rows] = n * Ek_d[i] + sgn * own[i]
    return (Lam, D, RF, RD) + ((tuple(Lam_d), tuple(D_d)) if rates else ())


def _chart(psi, t, mode):
    """``(a, b, |v|, w, j, sgn, sign(t))`` of chart points, and ``d|v|/dt``."""
    a, b = np.cos(0.5 * psi), np.sin(0.5 * psi)
    sign, q = np.sign(t), _q(t)
    # v = sqrt(1 - exp(-q)) = |t| sqrt((1 - exp(-q)) / q / (1 - t**2)): no underflow of v ~ |t|
    # where t**2 does (t = 1e-300 is in the chart: a rod under a load of 1e-600)
    ratio = np.divide(-np.expm1(-q), q, out=np.ones_like(q), where=q > 0)
    v, w = np.abs(t) * np.sqrt(ratio / ((1.0 - t) * (1.0 + t))), np.exp(-q)
    q_t = 2.0 * t / ((1.0 - t) * (1.0 + t)) ** 2
    # d|v|/dt = w q_t / (2 |v|), which tends to sign(t) where |v| ~ |t| underflows
    v_t = np.divide(w * q_t, 2.0 * v, out=np.array(sign * np.ones_like(v)), where=v != 0)
    return a, b, v, w, 2.0 * mode - 1.0, sign * np.where(a < 0, -1.0, 1.0), sign, v_t


def closed_form(EI: ArrayLike, L: ArrayLike, psi: ArrayLike, t: ArrayLike, mode: ArrayLike = 1,
                *, jacobian: bool = True, check: bool = True) -> RegularRod:
    """:func:`clamped_pinned_regular`, whose checks ``check=False`` skips: the solvers' fast path.

    A solver that keeps its iterates inside the chart's domain (``0 < psi < 2 pi``,
    ``0 < |t| <= T_MAX``, integer ``mode >= 1``, positive ``EI`` and ``L``, shapes that
    broadcast) and calls the closed form thousands of times saves the checks, about a third
    of the time of a small batch. Outside that domain the unchecked result is meaningless (NaN
    or finite garbage): check once, then call this with ``check=False``.

    Parameters
    ----------
    EI, L, jacobian
        As in :func:`clamped_pinned_regular`.
    psi, t, mode : array_like, shape (...)
        As in :func:`clamped_pinned_regular` (float arrays, or floats, when unchecked).
    check : bool, optional
        Check the inputs first (a :class:`ValueError` names one outside the domain).

    Returns
    -------
    RegularRod

    Examples
    --------
    >>> psi, t = np.array([2.0, 4.0]), np.array([0.5, -0.3])
    >>> fast = closed_form(1.0, 1.0, psi, t, np.array([1.0, 2.0]))
    >>> checked = clamped_pinned_regular(1.0, 1.0, psi, t, [1, 2])
    >>> bool(np.array_equal(fast.tip, checked.tip)), fast.jacobian.shape
    (True, (2, 5, 2))
    """
    if check:                 # the door's call; the kernel's (check=False) checks nothing
        EI, L, psi, t, mode = _inputs(EI, L, psi, t, mode)
        jacobian = _validate.flag(jacobian, "jacobian")
    shape = np.broadcast_shapes(np.shape(psi), np.shape(t), np.shape(mode))
    psi, t, mode = (np.broadcast_to(np.asarray(x, dtype=float), shape).ravel()
                    for x in (psi, t, mode))
    a, b, v, w, j, sgn, sign, v_t = _chart(psi, t, mode)
    waves = _waves(a, b, v, w, j, sgn, jacobian)
    Lam, D, RF, RD = waves[:4]
    vb = sign * v * b                          # k cos(phi1), signed
    cos, sin = np.cos(psi), np.sin(psi)
    # mode 1 bending towards the force, where Lambda -> 0 with the load and the quotients below
    # would lose every digit: there the tip is the straight rod plus its deviations
    grow, other = _rows(j == sgn), _rows(j != sgn)
    x, y, u, w2 = (np.empty(psi.shape) for _ in range(4))
    if other is not None:
        with np.errstate(divide="ignore", invalid="ignore", under="ignore"):
            u[other] = 1.0 - 2.0 * D[other] / Lam[other]
            w2[other] = 2.0 * vb[other] / Lam[other]
        x[other] = u[other] * cos[other] + w2[other] * sin[other]
        y[other] = u[other] * sin[other] - w2[other] * cos[other]
    if grow is not None:
        small = tip_deviations(a[grow], b[grow], v[grow], w[grow], RF[grow], RD[grow],
                               jacobian)
        du, dw, c, s = small[0], small[1], cos[grow], sin[grow]
        u[grow], w2[grow] = c + du, s + dw
        x[grow], y[grow] = 1.0 + (du * c + dw * s), du * s - dw * c
    L = np.asarray(L)
    x, y, Lam, vb, cos, sin = (z.reshape(shape) for z in (x, y, Lam, vb, cos, sin))
    tip = L[..., None] * np.stack((x, y), axis=-1)
    R = EI * Lam ** 2 / L ** 2
    force = R[..., None] * np.stack((cos, sin), axis=-1)
    moment = 2.0 * EI * vb * Lam / L
    if not jacobian:
        return RegularRod(tip, force, moment)

    # derivatives in psi (row 0, at fixed t) and t (row 1): d/dt = v_t d/d|v|
    (Lam_v, Lam_psi), (D_v, D_psi) = waves[4:]
    Lam_d, vb_d = np.stack((Lam_psi, Lam_v * v_t)), np.stack((0.5 * sign * v * a, sign * b * v_t))
    u_d, w2_d = np.empty((2, psi.size)), np.empty((2, psi.size))
    if other is not None:
        lam, lam_d = Lam.ravel()[other], Lam_d[:, other]
        D_d = np.stack((D_psi, D_v * v_t))[:, other]
        with np.errstate(divide="ignore", invalid="ignore", under="ignore", over="ignore"):
            u_d[:, other] = -2.0 * (D_d * lam - D[other] * lam_d) / lam ** 2
            w2_d[:, other] = 2.0 * (vb_d[:, other] * lam - vb.ravel()[other] * lam_d) / lam ** 2
    if grow is not None:
        scale = np.stack((np.ones(len(v_t[grow])), v_t[grow]))
        u_d[:, grow] = np.stack((small[3], small[2])) * scale
        w2_d[:, grow] = sign[grow] * np.stack((small[5], small[4])) * scale
    # the rotation Rot(psi) and the direction of the force depend on psi too
    u_d[0], w2_d[0] = u_d[0] + w2, w2_d[0] - u
    u_d, w2_d, Lam_d, vb_d = (z.reshape((2,) + shape) for z in (u_d, w2_d, Lam_d, vb_d))
    J = np.empty(np.broadcast_shapes(shape, np.shape(EI), L.shape) + (5, 2))
    dR = [2.0 * EI * Lam * Lam_d[i] / L ** 2 for i in range(2)]
    J[..., 2:4, 0] = np.stack((dR[0] * cos - R * sin, dR[0] * sin + R * cos), -1)
    J[..., 2:4, 1] = dR[1][..., None] * np.stack((cos, sin), -1)
    for i in range(2):
        J[..., 0:2, i] = L[..., None] * np.stack((u_d[i] * cos + w2_d[i] * sin,
                                                  u_d[i] * sin - w2_d[i] * cos), -1)
        J[..., 4, i] = 2.0 * EI * (vb_d[i] * Lam + vb * Lam_d[i]) / L
    return RegularRod(tip, force, moment, J)


def place(rod: RegularRod, origin: ArrayLike,
          angle: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray]:
    """A local-frame :class:`RegularRod` clamped at ``origin`` with its tangent at ``angle``.

    Returns the global tip and force, and their derivatives: with respect to the chart
    ``(psi, t)``, shape ``(..., 4, 2)`` (rows ``tip_x, tip_y, force_x, force_y``; None if the
    rod has no Jacobian), and with respect to the clamp ``angle``, shape ``(..., 4)``. The
    clamp moment does not change.

    Raises
    ------
    ValueError
        If ``rod`` is not a :class:`RegularRod`, ``origin`` has no last axis of length 2, an
        input is not finite, or the shapes do not broadcast.

    Examples
    --------
    >>> rod = clamped_pinned_regular(1.0, 1.0, 2.0, 0.5)
    >>> tip, force, d_chart, d_angle = place(rod, [1.0, 0.0], np.pi / 2)
    >>> np.allclose(tip, [1.0 - rod.tip[1], rod.tip[0]]), d_chart.shape, d_angle.shape
    (True, (4, 2), (4,))
    """
    if not isinstance(rod, RegularRod):
        raise ValueError(f"rod must be a RegularRod, got {type(rod).__name__}")
    origin, angle = as_vectors(origin, "origin", 2), _validate.array(angle, "angle")
    batch_shape(rod=rod.tip.shape[:-1], origin=origin.shape[:-1], angle=angle.shape)
    return place_at(rod, origin, angle)


def place_at(rod: RegularRod, origin: np.ndarray, angle: np.ndarray) -> tuple:
    """:func:`place` on checked input (the kernel of :class:`ClampedRods`)."""
    c, s = np.cos(angle), np.sin(angle)
    tip, force = (np.stack((c * x[..., 0] - s * x[..., 1], s * x[..., 0] + c * x[..., 1]), -1)
                  for x in (rod.tip, rod.force))
    d_angle = np.stack((-tip[..., 1], tip[..., 0], -force[..., 1], force[..., 0]), -1)
    d_chart, J, c, s = None, rod.jacobian, c[..., None], s[..., None]
    if J is not None:       # the rows (tip_x, tip_y) and (force_x, force_y) turned alike
        d_chart = np.stack([f(J[..., i, :], J[..., i + 1, :]) for i in (0, 2) for f in (
            lambda x, y: c * x - s * y, lambda x, y: s * x + c * y)], -2)
    return tip + origin, force, d_chart, d_angle


def in_chart(chart: ArrayLike) -> np.ndarray:
    """Whether chart points ``(psi_1, t_1, ..., psi_r, t_r)`` lie where the regular chart is
    defined: ``0 < psi_i < 2 pi`` and ``0 < |t_i| <= T_MAX`` for every rod (NaN does not).

    A predicate on any array of shape ``(..., 2 r)``, cheap enough for the ``domain`` of a
    solver's iterates (:func:`mechnum.newton.solve_batch`).

    Examples
    --------
    >>> in_chart(np.array([[1.0, 0.5, 2.0, -0.5], [1.0, 0.0, 2.0, 0.5]])).tolist()
    [True, False]
    """
    if not (isinstance(chart, np.ndarray) and chart.dtype == float):   # a solver's iterates are
        chart = _validate.array(chart, "chart", finite=False)         # float arrays already
    if chart.ndim < 1 or chart.shape[-1] % 2:
        raise ValueError(f"chart must have a last axis of 2 r numbers (psi_i, t_i), got shape "
                         f"{chart.shape}")
    psi, t = chart[..., 0::2], chart[..., 1::2]
    with np.errstate(invalid="ignore"):
        return np.all((psi > 0) & (psi < TWO_PI) & (t != 0) & (np.abs(t) <= T_MAX), axis=-1)


class ClampedRods:
    """Clamped-pinned rods of one stiffness, one length and given modes, in the regular chart:
    checked once here, then evaluated many times without checks, as a solver's inner loop needs.

    A mechanism built of ``r`` such rods makes one when its equations are built (at the door of
    its solver, where its input is checked) and calls it at every iterate: the closed form of
    :func:`clamped_pinned_regular` and the placement of each rod at its clamp, with no input
    check on the way (the iterates stay in the chart's domain, which the caller keeps).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m) of every rod, positive.
    modes : sequence of int
        The rods' buckling modes, ``r`` of them, each ``>= 1``.

    Examples
    --------
    >>> pair = ClampedRods(1.0, 1.0, (1, 2))
    >>> tip, force, moment, d_chart, d_angle = pair(np.array([2.0, 0.5, 4.0, -0.3]),
    ...                                             np.zeros((2, 2)), np.zeros(2))
    >>> alone = clamped_pinned_regular(1.0, 1.0, 4.0, -0.3, 2)
    >>> bool(np.array_equal(tip[1], alone.tip)), d_chart.shape, d_angle.shape
    (True, (2, 4, 2), (2, 4))
    """

    def __init__(self, EI: float, L: float, modes: ArrayLike) -> None:
        self.EI, self.L = rod_scales(EI, L, scalar=True)
        self.modes = as_modes(modes)
        if self.modes.ndim != 1 or not self.modes.size:
            raise ValueError(f"modes must be one mode per rod, got {modes!r:.60}")

    def __call__(self, chart: np.ndarray, origin: np.ndarray, angle: np.ndarray, *,
                 jacobian: bool = True) -> tuple:
        """The rods at chart points ``chart`` (..., 2 r), clamped at ``origin`` (..., r, 2)
        with tangents at ``angle`` (..., r): ``tip``, ``force`` (..., r, 2), ``clamp_moment``
        (..., r), ``d_chart`` (..., r, 4, 2) (None without ``jacobian``) and ``d_angle``
        (..., r, 4), as :func:`place` gives them."""
        rod = closed_form(self.EI, self.L, chart[..., 0::2], chart[..., 1::2], self.modes,
                          jacobian=jacobian, check=False)
        tip, force, d_chart, d_angle = place_at(rod, origin, angle)
        return tip, force, rod.clamp_moment, d_chart, d_angle
