"""The shape of a clamped-pinned rod of the regular chart: :func:`shape`, its profile sampled
along its length from the closed form's elliptic integrals (``rods._regular``)."""

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import elliprd, elliprf

from mechnum import _validate
from mechnum.rods._growing import branch_shape
from mechnum.rods._jacobi import amplitude
from mechnum.rods._regular import SMALL_LOAD, _chart, _inputs, closed_form
from mechnum.rods._rod import MAX_NODES, Rod


def _second_kind(phi, m, p, complete):
    """``E(phi, k)`` for any real ``phi``, from ``m = k**2`` and ``p = 1 - k**2``, reduced by
    whole periods (``E(phi + n pi) = E(phi) + 2 n E(k)``, ``complete = E(k)``)."""
    turns = np.round(phi / np.pi)
    r = phi - np.pi * turns
    s, c = np.sin(r), np.cos(r)
    delta2 = c * c + p * s * s
    return (2.0 * turns * complete + s * elliprf(c * c, delta2, 1.0)
            - m / 3.0 * s ** 3 * elliprd(c * c, delta2, 1.0))


def shape(EI: ArrayLike, L: ArrayLike, psi: ArrayLike, t: ArrayLike, mode: ArrayLike = 1, *,
          nodes: int = 201) -> Rod:
    """Clamped-pinned rods of the chart sampled at ``nodes`` equally spaced points, accurate in
    any tension and at any load (local frame: clamp at the origin, tangent along +x).

    Along the rod ``F(phi, k) = F(phi1, k) + lambda s`` gives the amplitude ``phi``, and the
    study's (86), (87), (37) and (42) the position, tangent angle and moment. Every quantity
    comes from the complementary modulus ``k' = sqrt(1 - k**2)``, which the chart gives to full
    precision: the amplitude from ``amplitude``, ``E(phi, k)`` in
    Carlson's form with ``1 - k**2 sin(phi)**2 = cos(phi)**2 + k'**2 sin(phi)**2`` and the
    tangent angle as ``psi - 2 atan2(dn, k sin(phi))`` with ``dn = sqrt(1 - k**2 sin(phi)**2)``
    (where ``arccos(k sin(phi))`` would lose half the digits as ``k sin(phi) -> 1``). The
    rods of the growing branch of mode 1 under a load ``lambda L <`` :data:`SMALL_LOAD`,
    whose positions the study's formulas find as differences of nearly equal integrals divided
    by ``lambda`` (all digits lost as the load tends to zero), are drawn in the cantilever's
    chart instead (``branch_shape``). The clamp is at the origin
    and the last node at :func:`clamped_pinned_regular`'s tip, exactly.

    Parameters
    ----------
    EI, L, psi, t, mode
        As in :func:`clamped_pinned_regular`.
    nodes : int, optional
        Points per rod, clamp and tip included, ``2 <= nodes <=``
        ``MAX_NODES = 100_000``.

    Returns
    -------
    Rod
        Arrays of shape ``batch + (nodes,)``.

    Examples
    --------
    A rod with ``1 - k**2 ~ 1e-26``, its tip force 60 N (EI = 0.0522 N m^2): the profile ends
    at the closed form's tip with no moment.

    >>> from mechnum.rods import clamped_pinned_regular
    >>> rod = shape(0.0522, 1.0, 6.0288, 0.9912, nodes=401)
    >>> tip = clamped_pinned_regular(0.0522, 1.0, 6.0288, 0.9912).tip
    >>> bool(np.abs(rod.tip - tip).max() < 1e-12), bool(abs(rod.m[-1]) < 1e-12)
    (True, True)
    """
    EI, L, psi, t, mode = _inputs(EI, L, psi, t, mode)
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    end = closed_form(EI, L, psi, t, mode, jacobian=False, check=False)
    psi, t, EI, L, mode = np.broadcast_arrays(psi, t, EI, L, mode)
    a, b, v, w, j, sgn, sign, _ = _chart(psi, t, mode)
    p, m = b * b * w, a * a + v * v * b * b                    # 1 - k**2 and k**2
    k = sign * np.sqrt(m)
    s1, c1 = sign * a / np.abs(k), v * b / np.abs(k)            # sin, cos of phi1
    F1 = s1 * elliprf(c1 * c1, b * b, 1.0)
    E1 = F1 - m / 3.0 * s1 ** 3 * elliprd(c1 * c1, b * b, 1.0)
    K = elliprf(0.0, p, 1.0)
    Ek = K - m / 3.0 * elliprd(0.0, p, 1.0)
    lam = np.sqrt(np.hypot(end.force[..., 0], end.force[..., 1]) / EI)
    s = np.linspace(0.0, 1.0, nodes) * L[..., None]
    psi_, k_, m_, p_, E1_, c1_, lam_, Ek_, EI_ = (np.asarray(x)[..., None] for x in (
        psi, k, m, p, E1, c1, lam, Ek, EI))
    phi = amplitude(F1[..., None] + lam_ * s, k_, np.sqrt(p_))
    dE = _second_kind(phi, m_, p_, Ek_) - E1_
    dC = np.cos(phi) - c1_
    with np.errstate(divide="ignore", invalid="ignore"):   # replaced below where lam is 0
        x = -(np.cos(psi_) * (2 * dE - lam_ * s) + 2 * k_ * np.sin(psi_) * dC) / lam_
        y = -(np.sin(psi_) * (2 * dE - lam_ * s) - 2 * k_ * np.cos(psi_) * dC) / lam_
    sin_phi = np.sin(phi)
    dn = np.sqrt(np.cos(phi) ** 2 + p_ * sin_phi ** 2)
    theta = psi_ - 2 * np.arctan2(dn, k_ * sin_phi)
    moment = 2 * EI_ * k_ * lam_ * np.cos(phi)
    small = (j == sgn) & (lam * L < SMALL_LOAD)
    for i in np.ndindex(small.shape):
        if not small[i]:
            continue
        x[i], y[i], theta[i], moment[i] = branch_shape(
            float(EI[i]), float(L[i]), float(psi[i]), float(v[i]), float(w[i]),
            float(lam[i] * L[i]), nodes).T
    x[..., 0] = y[..., 0] = theta[..., 0] = 0.0
    x[..., -1], y[..., -1] = end.tip[..., 0], end.tip[..., 1]
    return Rod(np.broadcast_to(s, x.shape), x, y, theta, moment, end.force)
