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
from scipy.special import ellipeinc, ellipj, elliprd, elliprf

from mechnum import _validate
from mechnum.rods.shooting import Rod

TWO_PI = 2.0 * np.pi
# Largest q = t**2 / (1 - t**2): 1 - k**2 = b**2 exp(-q) must stay a normal double (exp(-708)
# underflows), and at q = 600 the force is already (q / 2)**2 ~ 1e5 times EI / L**2.
Q_MAX = 600.0
T_MAX = float(np.sqrt(Q_MAX / (1.0 + Q_MAX)))
"""The largest ``|t|`` the chart accepts (``q = Q_MAX``)."""


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


def _check(psi, t):
    psi, t = _validate.array(psi, "psi"), _validate.array(t, "t")
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError("psi must lie in the open interval (0, 2 pi), "
                         f"got {_validate._shown(psi)}")
    if np.any((t == 0) | (np.abs(t) > T_MAX)):
        raise ValueError(f"t must satisfy 0 < |t| <= {T_MAX:.6f}, got {_validate._shown(t)}")
    return psi, t


def _q(t):
    """``q = t**2 / (1 - t**2)`` without cancellation near ``|t| = 1``."""
    return t * t / ((1.0 - t) * (1.0 + t))


def k_rel_from_t(psi, t, *, complement=False):
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
    a, b = np.abs(np.cos(0.5 * psi)), np.sin(0.5 * psi)
    q = _q(t)
    k = np.sqrt(a * a - np.expm1(-q) * b * b)
    one_minus_kmin = b * b / (1.0 + a)
    if complement:     # (1 - |k|) / (1 - k_min), with 1 - |k| = (1 - k**2) / (1 + |k|)
        return b * b * np.exp(-q) / (1.0 + k) / one_minus_kmin
    # |k| - k_min = (k**2 - k_min**2) / (|k| + k_min), without cancellation
    return np.sign(t) * (-np.expm1(-q) * b * b / (k + a)) / one_minus_kmin


def t_from_k_rel(psi, k_rel):
    """The chart's ``t`` of the study's rod ``(psi, k_rel)``, ``0 < |k_rel| < 1``.

    Examples
    --------
    >>> float(np.round(t_from_k_rel(np.pi, [0.5, -1 + 1e-9]), 6)[1])
    -0.975935
    """
    psi, k_rel = _validate.array(psi, "psi"), _validate.array(k_rel, "k_rel")
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError("psi must lie in the open interval (0, 2 pi), "
                         f"got {_validate._shown(psi)}")
    if np.any((k_rel == 0) | (np.abs(k_rel) >= 1)):
        raise ValueError(f"k_rel must satisfy 0 < |k_rel| < 1, got {_validate._shown(k_rel)}")
    a, b = np.abs(np.cos(0.5 * psi)), np.sin(0.5 * psi)
    one_minus_kmin = b * b / (1.0 + a)
    k = a + one_minus_kmin * np.abs(k_rel)
    # 1 - v**2 and v**2 = (k - k_min)(k + k_min) / b**2, each without cancellation
    one_minus_v2 = one_minus_kmin * (1.0 - np.abs(k_rel)) * (1.0 + k) / (b * b)
    v2 = one_minus_kmin * np.abs(k_rel) * (k + a) / (b * b)
    q = np.where(v2 < 0.5, -np.log1p(-np.minimum(v2, 0.5)), -np.log(one_minus_v2))
    return np.sign(k_rel) * np.sqrt(q / (1.0 + q))


def clamped_pinned_regular(EI, L, psi, t, mode=1, *, jacobian=True):
    """Tip, tip force and clamp moment of clamped-pinned rods, with their analytic Jacobian.

    Vectorised: ``EI``, ``L``, ``psi``, ``t`` and ``mode`` broadcast together (one call for all
    the rods of a mechanism, or for all the starts of a search).

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m), positive.
    psi : array_like
        Direction of the tip force from the clamped tangent, in ``(0, 2 pi)`` (rad).
    t : array_like
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
        If an input is outside its range or not finite.

    Examples
    --------
    The rods of the study's Table 7 (its solution 2, mode 1):

    >>> psi, k_rel = np.array([1.962541, 4.811041]), np.array([-0.004391, 0.943413])
    >>> rod = clamped_pinned_regular(0.0522, 1.0, psi, t_from_k_rel(psi, k_rel))
    >>> np.round(rod.tip, 6).tolist(), rod.jacobian.shape
    ([[0.235039, -0.642051], [-0.298731, -0.164104]], (2, 5, 2))
    """
    EI, L = _validate.positive(EI, "EI"), _validate.positive(L, "L")
    psi, t = _check(psi, t)
    mode = _validate.array(mode, "mode")
    if np.any(mode < 1) or np.any(mode != np.round(mode)):
        raise ValueError(f"mode must be an integer >= 1, got {_validate._shown(mode)}")
    return _closed_form(EI, L, psi, t, mode, jacobian)


def _integrals(a, b, v, w, whole=True):
    """``(k**2, p, I, G, p I + k**2 G, K, E(k))`` of :func:`_waves` (``K, E(k)`` None unless
    ``whole``)."""
    m, p = a * a + b * b * v * v, b * b * w
    k = m ** 0.5
    X = w * a * a / m
    I = v / k * elliprf(X, 1.0, w)
    G = p * v ** 3 / (3.0 * k ** 3) * elliprd(X, 1.0, w)
    K = Ek = None
    if whole:
        K = elliprf(0.0, p, 1.0)
        Ek = K - m / 3.0 * elliprd(0.0, p, 1.0)
    return m, p, I, G, p * I + m * G, K, Ek


def _waves(a, b, v, w, j, sgn, rates=True):
    """The elliptic integrals of clamped-pinned rods, and their rates: the one core.

    For ``a = cos(psi/2)`` (signed), ``b = sin(psi/2) > 0``, ``v = |v|``, ``w = 1 - v**2``
    (given, not computed from ``v``: it may be tiny), ``j = 2 mode - 1`` and ``sgn = +1`` on
    the growing branch (``sign(t) = sign(a)``, with ``a = 0`` taken as positive) or ``-1``:
    ``Lambda = lambda L = j K - F(phi1)`` and ``D = j E(k) - E(phi1)``. They are built from
    the complete integrals ``K``, ``E(k)`` and the **partial wave** from ``|phi1|`` to
    ``pi/2`` (``t = pi/2 - phi`` from 0 to ``t1``, ``cos(t1) = |a| / k``; DLMF 19.25.5, 19.25.7
    with ``sin(t)`` for ``sin(phi)``)::

        I = int_0^t1 dt / Delta = (v / k) R_F(X, 1, w),    X = w a**2 / k**2
        G = int_0^t1 sin(t)**2 dt / Delta = b**2 w v**3 / (3 k**3) R_D(X, 1, w)

    whose E-integral is ``p I + k**2 G`` (``p = 1 - k**2 = b**2 w``), so that
    ``F(phi1) = sgn (K - I)`` and ``Lambda = (j - sgn) K + sgn I``: no difference of nearly
    equal integrals near the straight rod, and no ``m = k**2`` rounded near 1 (``p`` is exact).

    With ``rates``, also their derivatives in ``|v|`` at fixed ``psi`` and in ``psi`` at fixed
    ``v`` (``d/dm`` and ``d/dphi`` of DLMF 19.4.1 to 19.4.4 for the partial wave; the factors
    ``1/p`` cancel analytically)::

        dI/dv = (v G + |a| / k**2) / w
        dI/dpsi = sign(a) (b**2 v / k**2 - |a| G) / (2 b)

    and likewise for ``K``, ``E(k)`` and ``p I + k**2 G``. Returns ``(Lambda, D)`` and, with
    ``rates``, ``((Lambda_v, Lambda_psi), (D_v, D_psi))``. Arrays or Python floats: only
    arithmetic and scipy's ufuncs, so the same lines serve a batch of rods and one rod
    given as Python floats. Where ``j == sgn`` everywhere (mode 1 on its growing
    branch) the complete integrals are not needed and not computed.
    """
    m, p, I, G, Dp, K, Ek = _integrals(a, b, v, w, np.any(np.not_equal(j, sgn)))
    if K is None:
        Lam, D = I, Dp
    else:
        Lam, D = (j - sgn) * K + sgn * I, (j - sgn) * Ek + sgn * Dp
    if not rates:
        return Lam, D
    sa, aa = np.where(a < 0, -1.0, 1.0), abs(a)   # sign(a) (+1 at a = 0) and |a|
    Lam_d = [(v * G + aa / m) / w, sa * (b * b * v / m - aa * G) / (2.0 * b)]
    D_d = [(v * p * (Dp - I) / w + aa * b * b) / m, sa * b * (v - aa * w * (Dp - I)) / (2.0 * m)]
    if K is not None:
        K_d = (v * (Ek - p * K) / (m * w), -a * (Ek - p * K) / (2.0 * m * b))
        Ek_d = (v * b * b * (Ek - K) / m, -a * b * w * (Ek - K) / (2.0 * m))
        for i in range(2):
            Lam_d[i] = (j - sgn) * K_d[i] + sgn * Lam_d[i]
            D_d[i] = (j - sgn) * Ek_d[i] + sgn * D_d[i]
    return Lam, D, tuple(Lam_d), tuple(D_d)


def _chart(psi, t, mode):
    """``(a, b, |v|, w, j, sgn, sign(t))`` of chart points, and ``d|v|/dt``."""
    a, b = np.cos(0.5 * psi), np.sin(0.5 * psi)
    sign, q = np.sign(t), _q(t)
    v, w = np.sqrt(-np.expm1(-q)), np.exp(-q)
    q_t = 2.0 * t / ((1.0 - t) * (1.0 + t)) ** 2
    # d|v|/dt = w q_t / (2 |v|), which tends to sign(t) where |v| ~ |t| underflows
    v_t = np.divide(w * q_t, 2.0 * v, out=np.array(sign * np.ones_like(v)), where=v != 0)
    return a, b, v, w, 2.0 * mode - 1.0, sign * np.where(a < 0, -1.0, 1.0), sign, v_t


def _closed_form(EI, L, psi, t, mode, jacobian):
    """:func:`clamped_pinned_regular` on checked float arrays (for solvers that keep their
    iterates in the chart's domain, and call it thousands of times)."""
    a, b, v, w, j, sgn, sign, v_t = _chart(psi, t, mode)
    waves = _waves(a, b, v, w, j, sgn, jacobian)
    Lam, D = waves[:2]
    vb = sign * v * b                          # k cos(phi1), signed
    u, w2 = 1.0 - 2.0 * D / Lam, 2.0 * vb / Lam
    cos, sin = np.cos(psi), np.sin(psi)
    L = np.asarray(L)
    tip = L[..., None] * np.stack((u * cos + w2 * sin, u * sin - w2 * cos), axis=-1)
    R = EI * Lam ** 2 / L ** 2
    force = R[..., None] * np.stack((cos, sin), axis=-1)
    moment = 2.0 * EI * vb * Lam / L
    if not jacobian:
        return RegularRod(tip, force, moment)

    # derivatives in psi (column 0, at fixed t) and t (column 1): d/dt = v_t d/d|v|
    (Lam_v, Lam_psi), (D_v, D_psi) = waves[2:]
    Lam_d, D_d = (Lam_psi, Lam_v * v_t), (D_psi, D_v * v_t)
    vb_d = (0.5 * sign * v * a, sign * b * v_t)
    J = np.empty(np.broadcast_shapes(psi.shape, t.shape, np.shape(EI), L.shape, np.shape(mode))
                 + (5, 2))
    for i in range(2):
        u_d = -2.0 * (D_d[i] * Lam - D * Lam_d[i]) / Lam ** 2
        w2_d = 2.0 * (vb_d[i] * Lam - vb * Lam_d[i]) / Lam ** 2
        dR = 2.0 * EI * Lam * Lam_d[i] / L ** 2
        if i == 0:   # the rotation Rot(psi) and the direction of the force depend on psi too
            u_d, w2_d = u_d + w2, w2_d - u
            J[..., 2:4, 0] = np.stack((dR * cos - R * sin, dR * sin + R * cos), -1)
        else:
            J[..., 2:4, 1] = dR[..., None] * np.stack((cos, sin), -1)
        J[..., 0:2, i] = L[..., None] * np.stack((u_d * cos + w2_d * sin,
                                                  u_d * sin - w2_d * cos), -1)
        J[..., 4, i] = 2.0 * EI * (vb_d[i] * Lam + vb * Lam_d[i]) / L
    return RegularRod(tip, force, moment, J)


def place(rod, origin, angle):
    """A local-frame :class:`RegularRod` clamped at ``origin`` with its tangent at ``angle``.

    Returns the global tip and force, and their derivatives: with respect to the chart
    ``(psi, t)``, shape ``(..., 4, 2)`` (rows ``tip_x, tip_y, force_x, force_y``), and with
    respect to the clamp ``angle``, shape ``(..., 4)``. The clamp moment does not change.

    Examples
    --------
    >>> rod = clamped_pinned_regular(1.0, 1.0, 2.0, 0.5)
    >>> tip, force, d_chart, d_angle = place(rod, [1.0, 0.0], np.pi / 2)
    >>> np.allclose(tip, [1.0 - rod.tip[1], rod.tip[0]]), d_chart.shape, d_angle.shape
    (True, (4, 2), (4,))
    """
    origin, angle = _validate.array(origin, "origin"), _validate.array(angle, "angle")
    c, s = np.cos(angle), np.sin(angle)
    rot = np.stack((np.stack((c, -s), -1), np.stack((s, c), -1)), -2)   # (..., 2, 2)
    tip, force = (rot @ rod.tip[..., None])[..., 0], (rot @ rod.force[..., None])[..., 0]
    d_angle = np.concatenate((np.stack((-tip[..., 1], tip[..., 0]), -1),
                              np.stack((-force[..., 1], force[..., 0]), -1)), axis=-1)
    d_chart = None
    if rod.jacobian is not None:
        d_chart = np.concatenate((rot @ rod.jacobian[..., 0:2, :],
                                  rot @ rod.jacobian[..., 2:4, :]), axis=-2)
    return tip + origin, force, d_chart, d_angle


def shape(EI, L, psi, t, mode=1, *, nodes=201):
    """The shape of clamped-pinned rods of the chart, sampled at ``nodes`` equally spaced points.

    Along the rod ``F(phi, k) = F(phi1, k) + lambda s`` gives the amplitude ``phi = am(.)``
    (scipy's ``ellipj``), and the study's (86), (87), (37) and (42) the position, tangent
    angle and moment (local frame). Unlike an RK4 integration from the clamp, which amplifies
    its errors by ``cosh(lambda L)``, this stays accurate for rods in any tension (scipy's
    parameter ``m = k**2`` is rounded, an error of order ``1 - k**2 + 1e-16``, far below what
    a drawing or a second variation needs).

    Parameters
    ----------
    EI, L, psi, t, mode
        As in :func:`clamped_pinned_regular`.
    nodes : int, optional
        Points per rod, clamp and tip included.

    Returns
    -------
    Rod
        Arrays of shape ``batch + (nodes,)``.

    Examples
    --------
    >>> rod = shape(1.0, 1.0, 2.0, -0.6, 2, nodes=101)
    >>> tip = clamped_pinned_regular(1.0, 1.0, 2.0, -0.6, 2).tip
    >>> bool(np.abs(rod.tip - tip).max() < 1e-12), float(rod.theta[0]), bool(abs(rod.m[-1]) < 1e-12)
    (True, 0.0, True)
    """
    EI, L = _validate.positive(EI, "EI"), _validate.positive(L, "L")
    psi, t = _check(psi, t)
    mode = _validate.array(mode, "mode")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    end = _closed_form(EI, L, psi, t, mode, False)
    psi, t, EI, L, mode = np.broadcast_arrays(psi, t, EI, L, mode)
    a, b, v, w, _, sgn, sign, _ = _chart(psi, t, mode)
    m, p, I, _, Dp, K, Ek = _integrals(a, b, v, w)
    F1, E1 = sgn * (K - I), sgn * (Ek - Dp)      # F(phi1, k), E(phi1, k)
    k, c1 = sign * np.sqrt(m), v * b / np.sqrt(m)
    lam = np.sqrt(np.hypot(*np.moveaxis(end.force, -1, 0)) / EI)
    s = np.linspace(0.0, 1.0, nodes) * L[..., None]
    ex = [np.asarray(x)[..., None] for x in (psi, k, m, F1, E1, lam, c1, EI)]
    psi_, k_, m_, F1_, E1_, lam_, c1_, EI_ = ex
    # reduce u = F1 + lambda s by whole periods 2 K (from the accurate 1 - k**2) before
    # scipy's am and E, which see m = k**2 rounded and, at m = 1, an infinite period
    u = F1_ + lam_ * s
    turns = np.round(u / (2 * K[..., None]))
    phi_r = ellipj(u - 2 * turns * K[..., None], np.minimum(m_, 1.0))[3]
    phi = phi_r + np.pi * turns
    dE = 2 * turns * Ek[..., None] + ellipeinc(phi_r, np.minimum(m_, 1.0)) - E1_
    dC = np.cos(phi) - c1_
    x = -(np.cos(psi_) * (2 * dE - lam_ * s) + 2 * k_ * np.sin(psi_) * dC) / lam_
    y = -(np.sin(psi_) * (2 * dE - lam_ * s) - 2 * k_ * np.cos(psi_) * dC) / lam_
    theta = psi_ - 2 * np.arccos(np.clip(k_ * np.sin(phi), -1.0, 1.0))
    moment = 2 * EI_ * k_ * lam_ * np.cos(phi)
    # the ends exactly: the clamp and the closed-form tip (the profile is continuous)
    x[..., 0] = y[..., 0] = theta[..., 0] = 0.0
    x[..., -1], y[..., -1] = end.tip[..., 0], end.tip[..., 1]
    return Rod(np.broadcast_to(s, x.shape), x, y, theta, moment, end.force)
