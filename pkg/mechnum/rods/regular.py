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


def _closed_form(EI, L, psi, t, mode, jacobian):
    """:func:`clamped_pinned_regular` on checked float arrays (for solvers that keep their
    iterates in the chart's domain, and call it thousands of times)."""
    j = 2.0 * mode - 1.0                      # F(phi2, k) = j K(k), E(phi2, k) = j E(k)
    a, b = np.cos(0.5 * psi), np.sin(0.5 * psi)
    sign, q = np.sign(t), _q(t)
    w = np.exp(-q)                            # 1 - v**2
    v2 = -np.expm1(-q)
    v = sign * np.sqrt(v2)
    p = b * b * w                             # 1 - k**2
    m = a * a + v2 * b * b                    # k**2
    s1 = sign * a / np.sqrt(m)                # sin(phi1)
    c2 = v2 * b * b / m                       # cos(phi1)**2
    rf1, rd1 = elliprf(c2, b * b, 1.0), elliprd(c2, b * b, 1.0)
    K = elliprf(0.0, p, 1.0)
    Ek = K - m / 3.0 * elliprd(0.0, p, 1.0)
    F1 = s1 * rf1
    E1 = F1 - m / 3.0 * s1 ** 3 * rd1
    Lam, D = j * K - F1, j * Ek - E1
    u, w2 = 1.0 - 2.0 * D / Lam, 2.0 * v * b / Lam
    cos, sin = np.cos(psi), np.sin(psi)
    L = np.asarray(L)
    tip = L[..., None] * np.stack((u * cos + w2 * sin, u * sin - w2 * cos), axis=-1)
    R = EI * Lam ** 2 / L ** 2
    force = R[..., None] * np.stack((cos, sin), axis=-1)
    moment = 2.0 * EI * v * b * Lam / L
    if not jacobian:
        return RegularRod(tip, force, moment)

    # Derivatives of m = k**2, phi1 and v b with respect to psi (first) and t (second).
    # dm/dt = p q', so the terms 1/p of dF/dm, dK/dm cancel analytically.
    q_t = 2.0 * t / ((1.0 - t) * (1.0 + t)) ** 2
    v2_t = w * q_t
    abs_v_t = np.divide(v2_t, 2.0 * np.abs(v), out=np.ones_like(t), where=v != 0)
    c1 = np.sqrt(c2)
    phi1_d = (-v / (2.0 * m), -sign * a * b * abs_v_t / m)
    vb_d = (0.5 * v * a, sign * abs_v_t * b)
    # d/dm of F(phi1), E(phi1), K, E(k), multiplied by dm/dpsi = -a b w and dm/dt = p q_t
    F1_m = (-0.5 * a * (E1 / (m * b) - F1 * b * w / m - s1 * c1 / (b * b)),
            0.5 * q_t * (E1 / m - F1 * p / m - s1 * c1 / b))
    E1_m = tuple(0.5 * (E1 - F1) / m * dm for dm in (-a * b * w, p * q_t))
    K_m = (-0.5 * a * (Ek - p * K) / (m * b), 0.5 * q_t * (Ek - p * K) / m)
    Ek_m = tuple(0.5 * (Ek - K) / m * dm for dm in (-a * b * w, p * q_t))
    J = np.empty(np.broadcast_shapes(psi.shape, t.shape, np.shape(EI), L.shape, np.shape(mode))
                 + (5, 2))
    for i in range(2):
        Lam_d = j * K_m[i] - (phi1_d[i] / b + F1_m[i])       # dF/dphi = 1/Delta, Delta = b
        D_d = j * Ek_m[i] - (phi1_d[i] * b + E1_m[i])        # dE/dphi = Delta
        u_d = -2.0 * (D_d * Lam - D * Lam_d) / Lam ** 2
        w2_d = 2.0 * (vb_d[i] * Lam - v * b * Lam_d) / Lam ** 2
        if i == 0:   # the rotation Rot(psi) and the direction of the force depend on psi too
            du, dw = u_d + w2, w2_d - u
            J[..., 0:2, 0] = L[..., None] * np.stack((du * cos + dw * sin, du * sin - dw * cos), -1)
            dR = 2.0 * EI * Lam * Lam_d / L ** 2
            J[..., 2:4, 0] = np.stack((dR * cos - R * sin, dR * sin + R * cos), -1)
        else:
            J[..., 0:2, 1] = L[..., None] * np.stack((u_d * cos + w2_d * sin,
                                                      u_d * sin - w2_d * cos), -1)
            dR = 2.0 * EI * Lam * Lam_d / L ** 2
            J[..., 2:4, 1] = dR[..., None] * np.stack((cos, sin), -1)
        J[..., 4, i] = 2.0 * EI * (vb_d[i] * Lam + v * b * Lam_d) / L
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
    a, b, sign = np.cos(0.5 * psi), np.sin(0.5 * psi), np.sign(t)
    v2 = -np.expm1(-_q(t))
    m = a * a + v2 * b * b
    k = sign * np.sqrt(m)
    s1, c1 = sign * a / np.abs(k), np.sqrt(v2) * b / np.abs(k)
    F1 = s1 * elliprf(c1 * c1, b * b, 1.0)
    E1 = F1 - m / 3.0 * s1 ** 3 * elliprd(c1 * c1, b * b, 1.0)
    lam = np.sqrt(np.hypot(*np.moveaxis(end.force, -1, 0)) / EI)
    s = np.linspace(0.0, 1.0, nodes) * L[..., None]
    ex = [np.asarray(x)[..., None] for x in (psi, k, m, F1, E1, lam, c1, EI)]
    psi_, k_, m_, F1_, E1_, lam_, c1_, EI_ = ex
    # reduce u = F1 + lambda s by whole periods 2 K (from the accurate 1 - k**2) before
    # scipy's am and E, which see m = k**2 rounded and, at m = 1, an infinite period
    p = b * b * np.exp(-_q(t))
    K = elliprf(0.0, p, 1.0)
    Ek = K - m / 3.0 * elliprd(0.0, p, 1.0)
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
