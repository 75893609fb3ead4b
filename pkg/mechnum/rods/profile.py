"""Shapes of clamped-pinned rods in any tension, from the complementary modulus.

A rod of the regular chart ``(psi, t)`` of :mod:`mechnum.rods.regular` has, along its length,
the amplitude ``phi(s) = am(F(phi1, k) + lambda s | k)`` of the study's (86), (87), (37) and
(42). In strong tension ``1 - k**2`` is far below the rounding of ``k**2`` (1e-34 for rods of
the 3PFR of Chapter 6, whose forces are ~100 times their buckling loads), and a routine that
receives the parameter ``m = k**2`` (scipy's ``ellipj``, which
:func:`mechnum.rods.regular.shape` uses) sees ``m = 1 - 1e-16`` instead: its error grows like
``1e-16 sinh(u)`` along the rod, up to ``1e-16 / k'``, and the shape of such a rod comes out
wrong by centimetres or by astronomical amounts. Here every quantity comes from the
complementary modulus ``k' = sqrt(1 - k**2)`` itself, which the chart gives to full precision:

* the amplitude by the arithmetic-geometric mean started from ``(1, k')`` (Abramowitz and Stegun
  16.4; DLMF 22.20.1), exact to rounding for any ``k' > 0``;
* ``E(phi, k)`` in Carlson's form with ``1 - k**2 sin(phi)**2 = cos(phi)**2 + k'**2 sin(phi)**2``,
  reduced by whole periods (``E(phi + n pi) = E(phi) + 2 n E(k)``);
* the tangent angle as ``psi - 2 atan2(dn, k sin(phi))`` with ``dn = sqrt(1 - k**2 sin(phi)**2)``,
  where ``arccos(k sin(phi))`` would lose half the digits as ``k sin(phi) -> 1``.
"""

import numpy as np
from scipy.special import elliprd, elliprf

from mechnum import _validate
from mechnum.rods import regular
from mechnum.rods.shooting import Rod

# The AGM's c_n falls quadratically once a_n ~ b_n; from b_0 = k' >= 1e-131 (the chart's least,
# q = 600) it needs at most ~log2(131 log2(10)) + 6 = 15 steps to reach round-off; it stops
# when every c_n / a_n is below AGM_TOL (the next step would change phi by ~AGM_TOL**2).
AGM_STEPS = 20
AGM_TOL = 1e-10


def amplitude(u, k, complement):
    """Jacobi's amplitude ``am(u | k)`` from ``k`` and its complement ``k' = sqrt(1 - k**2)``.

    The AGM ``a_{n+1} = (a_n + b_n) / 2``, ``b_{n+1} = sqrt(a_n b_n)``, ``c_{n+1} = (a_n - b_n) /
    2`` from ``(1, k', k)``, then ``phi_{n-1} = (phi_n + arcsin(c_n sin(phi_n) / a_n)) / 2`` from
    ``phi_N = 2**N a_N u``. Where the arcsine's argument ``x`` nears +-1 (``k -> 1`` and
    ``phi`` near an odd multiple of ``pi / 2``: a rod's straight part in tension) it is taken as
    ``atan2(|x|, sqrt((1 - |x|)(1 + |x|)))`` with ``1 - |x| = b_{n-1} / a_n + (c_n / a_n) 2
    sin(delta / 2)**2`` (``1 - c_n / a_n = b_{n-1} / a_n``, ``delta`` the distance of ``phi`` to
    the nearest odd multiple of ``pi / 2``): no cancellation, where ``arcsin`` would lose half
    the digits.

    Parameters
    ----------
    u, k, complement : array_like
        Broadcast together; ``0 <= |k| <= 1``, ``k' >= 0`` given to full precision.

    Examples
    --------
    >>> from scipy.special import ellipj
    >>> u = np.linspace(-3.0, 9.0, 7)
    >>> bool(np.allclose(amplitude(u, 0.8, 0.6), ellipj(u, 0.64)[3], rtol=0, atol=1e-14))
    True
    >>> phi = amplitude(30.0, 1.0, 1e-20)       # k' -> 0: am(u) -> gd(u), cos = sech(30)
    >>> bool(abs(np.cos(phi) * np.cosh(30.0) - 1) < 1e-3)
    True
    """
    u, k, kp = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (u, k, complement)))
    a, b = np.ones_like(u), kp.copy()
    steps = []                                   # (c_n / a_n, 1 - c_n / a_n)
    for _ in range(AGM_STEPS):
        a, b, c, previous_b = 0.5 * (a + b), np.sqrt(a * b), 0.5 * (a - b), b
        steps.append((c / a, previous_b / a))
        if np.all(c / a < AGM_TOL):
            break
    phi = 2.0 ** len(steps) * a * u
    for ratio, one_minus_ratio in steps[::-1]:
        delta = phi - (np.round(phi / np.pi - 0.5) + 0.5) * np.pi
        x = np.abs(ratio * np.sin(phi))
        one_minus_x = one_minus_ratio + 2.0 * ratio * np.sin(0.5 * delta) ** 2
        arcsin = np.sign(np.sin(phi)) * np.arctan2(x, np.sqrt(one_minus_x * (1.0 + x)))
        phi = 0.5 * (phi + arcsin)
    return phi


def _second_kind(phi, m, p, complete):
    """``E(phi, k)`` for any real ``phi``, from ``m = k**2`` and ``p = 1 - k**2``."""
    turns = np.round(phi / np.pi)
    r = phi - np.pi * turns
    s, c = np.sin(r), np.cos(r)
    delta2 = c * c + p * s * s
    return (2.0 * turns * complete + s * elliprf(c * c, delta2, 1.0)
            - m / 3.0 * s ** 3 * elliprd(c * c, delta2, 1.0))


def shape(EI, L, psi, t, mode=1, *, nodes=201):
    """Clamped-pinned rods of the regular chart sampled at ``nodes`` equally spaced points,
    accurate in any tension (local frame: clamp at the origin, tangent along +x).

    Same arguments and result as :func:`mechnum.rods.regular.shape`.

    Returns
    -------
    Rod
        Arrays of shape ``batch + (nodes,)``.

    Examples
    --------
    A rod with ``1 - k**2 ~ 1e-26``, its tip force 60 N (EI = 0.0522 N m^2): the profile ends
    at the closed form's tip with no moment.

    >>> rod = shape(0.0522, 1.0, 6.0288, 0.9912, nodes=401)
    >>> tip = regular.clamped_pinned_regular(0.0522, 1.0, 6.0288, 0.9912).tip
    >>> bool(np.abs(rod.tip - tip).max() < 1e-12), bool(abs(rod.m[-1]) < 1e-12)
    (True, True)
    """
    EI, L = _validate.positive(EI, "EI"), _validate.positive(L, "L")
    psi, t = regular._check(psi, t)
    mode = _validate.array(mode, "mode")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    end = regular._closed_form(EI, L, psi, t, mode, False)
    psi, t, EI, L, mode = np.broadcast_arrays(psi, t, EI, L, mode)
    a, b, sign = np.cos(0.5 * psi), np.sin(0.5 * psi), np.sign(t)
    q = regular._q(t)
    v2, p = -np.expm1(-q), b * b * np.exp(-q)                  # v**2 and 1 - k**2
    m = a * a + v2 * b * b
    k = sign * np.sqrt(m)
    s1, c1 = sign * a / np.abs(k), np.sqrt(v2) * b / np.abs(k)  # sin, cos of phi1
    F1 = s1 * elliprf(c1 * c1, b * b, 1.0)
    E1 = F1 - m / 3.0 * s1 ** 3 * elliprd(c1 * c1, b * b, 1.0)
    K = elliprf(0.0, p, 1.0)
    Ek = K - m / 3.0 * elliprd(0.0, p, 1.0)
    lam = np.sqrt(np.hypot(*np.moveaxis(end.force, -1, 0)) / EI)
    s = np.linspace(0.0, 1.0, nodes) * L[..., None]
    psi_, k_, m_, p_, E1_, c1_, lam_, Ek_, EI_ = (np.asarray(x)[..., None] for x in (
        psi, k, m, p, E1, c1, lam, Ek, EI))
    phi = amplitude(F1[..., None] + lam_ * s, k_, np.sqrt(p_))
    dE = _second_kind(phi, m_, p_, Ek_) - E1_
    dC = np.cos(phi) - c1_
    x = -(np.cos(psi_) * (2 * dE - lam_ * s) + 2 * k_ * np.sin(psi_) * dC) / lam_
    y = -(np.sin(psi_) * (2 * dE - lam_ * s) - 2 * k_ * np.cos(psi_) * dC) / lam_
    sin_phi = np.sin(phi)
    dn = np.sqrt(np.cos(phi) ** 2 + p_ * sin_phi ** 2)
    theta = psi_ - 2 * np.arctan2(dn, k_ * sin_phi)
    moment = 2 * EI_ * k_ * lam_ * np.cos(phi)
    return Rod(np.broadcast_to(s, x.shape), x, y, theta, moment, end.force)
