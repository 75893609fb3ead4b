"""The clamped-pinned closed form of the regular chart, enclosed over boxes (ball arithmetic).

``rods``'s regular module evaluates a rod ``(psi, t)`` of the regular chart in floats; this
module encloses the same closed form, tip, force, clamp moment and their derivatives in
``(psi, t)``, over a whole **box** of the chart, with Arb's balls (:mod:`mechnum.certify.balls`),
for the proofs of :mod:`mechnum.certify`. The formulas are those of ``regular``'s module
docstring (with ``a = cos(psi/2)``, ``b = sin(psi/2)``, ``1 - v**2 = w = exp(-q)``,
``q = t**2 / (1 - t**2)``, the partial wave ``I = (v/k) R_F(X, 1, w)``,
``G = b**2 w v**3 / (3 k**3) R_D(X, 1, w)``, ``X = w a**2 / k**2``, and the complete integrals
``K = R_F(0, p, 1)``, ``E = 2 R_G(0, p, 1)``, ``p = b**2 w``), rewritten where a box reaches an
edge of the chart so that every enclosure stays finite:

* Carlson's ``R_F``, ``R_D``, ``R_G`` are monotone in each argument, and are evaluated at the
  two extreme corners of a box (tight where Arb's own enclosure of a wide ball is not);
* ``a**2 / k**2`` and ``v / k`` are evaluated as monotone functions of ``|a|`` and ``b v``
  (bounded as ``k -> 0``), and the tip uses ``D / Lambda`` and ``v b / Lambda`` only, through
  ``1 / K`` (which tends to 0 where ``K`` is infinite, at ``psi = 0, 2 pi``) and, for mode 1 on
  its growing branch, the cancelled forms ``D / Lambda = p (1 + v**2 R_D / (3 R_F))`` and
  ``v b / Lambda = b k / R_F`` (bounded as ``t -> 0``, the unloaded rod), with ``w R_D`` as
  one function (finite as ``w -> 0``);
* the sign of ``a`` selects the formula (``regular._waves``'s ``sgn``): a box across
  ``psi = pi`` is enclosed by the union of both formulas over ``|a|`` in its range, each valid
  on its side, and the closed form is continuous there.

A box must lie on one side of ``t = 0`` (the branches do not meet there): its ``sign`` is given,
and ``t`` is taken as ``|t|`` in the box (``t = 0`` itself: the limit of the branch). What is
enclosed is the closed form as written; that it is the elastica is the study's derivation
(its (86) to (91), checked against RK4 shooting by the package's tests).

Examples
--------
>>> from mechnum.certify.balls import ball, bounds
>>> from mechnum.rods import _regular as regular
>>> rod = clamped_pinned(1.0, 1.0, ball(2.0, 2.001), ball(0.5, 0.501), 1, 1)
>>> exact = regular.clamped_pinned_regular(1.0, 1.0, 2.0005, 0.5005).tip
>>> [bool(bounds(x)[0] < e < bounds(x)[1]) for x, e in zip(rod.tip, exact)]
[True, True]
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from flint import acb, arb
from numpy.typing import ArrayLike

from mechnum.certify import balls as B
from mechnum.rods import _regular as regular

__all__ = ["TWO_PI", "RodBall", "clamped_pinned", "place"]

TWO_PI = 2 * B.PI


@dataclass(frozen=True)
class RodBall:
    """A box of clamped-pinned rods of the chart, enclosed (local frame).

    Attributes
    ----------
    tip, force : list of 2 arb
        Tip (m) and force on the rod at its tip (N).
    moment : arb
        Clamp moment ``m(0)`` (N m).
    jacobian : list of 5 lists of 2 arb, or None
        ``d (tip_x, tip_y, force_x, force_y, moment) / d (psi, t)``.
    R : arb or None
        The force's magnitude (N).
    direction : arb or None
        The force's direction (rad): ``psi`` in the local frame, ``psi + angle`` when placed.
    """

    tip: list
    force: list
    moment: arb
    jacobian: list = None
    R: arb = None
    direction: arb = None


def _quotient(num, den):
    """``x**2 / (x**2 + y**2)`` over spans of ``x = |a| >= 0``, ``y = b v >= 0`` (in [0, 1];
    at ``x = y = 0``, where it has no limit, all of [0, 1])."""
    def ratio(x, y):
        if x == 0 and y == 0:
            return arb(0.5, 0.5)
        return x * x / (x * x + y * y)
    return B.monotone(ratio, (num, 1), (den, -1))


def _w(tau):
    """``w = exp(-q)``, ``q = tau**2 / (1 - tau**2)``, at a point ``tau``."""
    return (-(tau * tau / ((1 - tau) * (1 + tau)))).exp()


def _rf(x, y, z):
    return acb.elliptic_rf(acb(x), acb(y), acb(z)).real


def _rd(x, y, z):
    return acb.elliptic_rj(acb(x), acb(y), acb(z), acb(z)).real


def _rg(x, y, z):
    return acb.elliptic_rg(acb(x), acb(y), acb(z)).real


def _partial(f, tau, r):
    """``f(w, r)`` over ``tau`` and ``r = a**2 / k**2`` for ``f`` increasing in ``tau``
    (decreasing in ``w``) and decreasing in ``r``: ``R_F(w r, 1, w)`` (decreasing in each
    argument) and ``w R_D(w r, 1, w) = 3/2 int_0^inf ds / ((s + r)**(1/2) (w s + 1)**(1/2)
    (s + 1)**(3/2))`` (``t = w s`` in DLMF 19.16.5), which is finite as ``w -> 0`` where
    ``R_D`` alone is not: a product ``w * R_D`` of two balls would not be. Evaluated at two
    corners, each ``w`` a narrow ball (a ball of ``w`` over the box, from ``exp(-600)`` to
    ``exp(-2)`` say, would lose its lower end to rounding)."""
    return B.monotone(lambda x, y: f(_w(x), y), (tau, 1), (r, -1))


def _rf_wave(w, r):
    return _rf(w * r, arb(1), w)


def _rd_wave(w, r):
    return w * _rd(w * r, arb(1), w)


def _complete(tau, b):
    """``K = R_F(0, p, 1)``, ``E = 2 R_G(0, p, 1)`` and ``1 / K`` over ``tau`` and ``b``
    (``p = b**2 w`` decreases with ``tau`` and increases with ``b``; ``K`` decreases with
    ``p``, ``E`` increases; ``K`` is infinite at ``p = 0``, where ``1 / K = 0``)."""
    (t_lo, t_hi), (b_lo, b_hi) = tau, b
    p_lo, p_hi = b_lo * b_lo * _w(t_hi), b_hi * b_hi * _w(t_lo)
    K_hi, K_lo = (_rf(arb(0), x, arb(1)) if x != 0 else arb("nan") for x in (p_lo, p_hi))
    inv = [arb(0) if not K.is_finite() else 1 / K for K in (K_hi, K_lo)]
    E = (2 * _rg(arb(0), p_lo, arb(1))).union(2 * _rg(arb(0), p_hi, arb(1)))
    K = K_lo.union(K_hi) if K_hi.is_finite() and K_lo.is_finite() else arb("nan")
    return K, E, inv[0].union(inv[1])


def _chart(psi, t, sign):
    """Over the box (``sign``: the branch): ``psi`` and the balls ``a, b, w, v``, the spans
    (exact endpoints) of ``tau = |t|``, ``b`` and ``v``, and ``(dv/dtau) / w``."""
    p_span = B.span(psi, 0, TWO_PI)
    psi = p_span[0].union(p_span[1])
    tau = B.span(t if sign > 0 else -t, 0, regular.T_MAX)
    a, b = B.cos(psi / 2), B.sin(psi / 2)
    b_span = B.span(b, 0)
    q = B.span(B.monotone(lambda x: x * x / ((1 - x) * (1 + x)), (tau, 1)), 0)
    w = B.monotone(lambda x: (-x).exp(), (q, -1))
    v_span = B.span(B.monotone(lambda x: (-(-x).expm1()).sqrt(), (q, 1)), 0, 1)
    g = B.monotone(lambda x: arb(1) if x == 0 else -(-x).expm1() / x, (q, -1))
    t_ball = tau[0].union(tau[1])
    dv_w = 1 / ((1 - t_ball * t_ball) * (1 - t_ball * t_ball).sqrt() * g.sqrt())
    return psi, a, b, w, v_span[0].union(v_span[1]), dv_w, (tau, b_span, v_span)


def clamped_pinned(EI: float, L: float, psi: object, t: object, mode: int, sign: int, *,
                   jacobian: bool = False) -> object:
    """Tip, force and clamp moment of the rods of a chart box, enclosed, with their Jacobian.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    psi, t : flint.arb
        The box: ``psi`` in ``[0, 2 pi]``, ``t`` on the branch ``sign`` (``0 <= sign * t <=
        T_MAX``; the parts of the balls beyond are cut off).
    mode : int
        Buckling mode, ``>= 1``.
    sign : {1, -1}
        The branch: the sign of ``t`` (the study's sign of ``k_rel``).
    jacobian : bool, optional
        Also enclose ``d (tip, force, moment) / d (psi, t)``.

    Returns
    -------
    RodBall
    """
    if sign not in (1, -1) or int(mode) != mode or mode < 1:
        raise ValueError(f"sign must be 1 or -1 and mode an integer >= 1, got {sign!r}, "
                         f"{mode!r}")
    EI, L = arb(float(EI)), arb(float(L))
    # plain balls from here on: this module's enclosures use ball predicates and bounds on
    # purpose, and are tested against the closed form (mechnum.certify._guard)
    psi, t = arb(psi), arb(t)
    psi, a, b, w, v, dv_w, spans = _chart(psi, t, sign)
    a_lo, a_hi = B.ends(a)
    sides = [s for s, possible in ((1, not bool(a_hi < 0)), (-1, not bool(a_lo > 0)))
             if possible]
    cos, sin = B.cos(psi), B.sin(psi)
    parts = [_side(EI, L, (a, b, w, v, dv_w, spans), cos, sin, 2 * int(mode) - 1, sign, sa,
                   jacobian) for sa in sides]
    if len(parts) == 1:
        return replace(parts[0], direction=psi)
    first, second = parts
    join = [x.union(y) for x, y in zip(_flat(first), _flat(second))]
    return replace(_unflat(join, jacobian), R=first.R.union(second.R), direction=psi)


def _flat(rod):
    out = rod.tip + rod.force + [rod.moment]
    if rod.jacobian is not None:
        out += [x for row in rod.jacobian for x in row]
    return out


def _unflat(values, jacobian):
    J = [values[5 + 2 * i:7 + 2 * i] for i in range(5)] if jacobian else None
    return RodBall(values[0:2], values[2:4], values[4], J)


def _side(EI, L, chart, cos, sin, j, sign, sa, jacobian):
    """The closed form on one side of ``psi = pi`` (``sa``: the sign of ``a``)."""
    a, b, w, v, dv_w, (tau, b_span, v_span) = chart
    aa_span = B.span(a if sa > 0 else -a, 0, 1)
    aa = aa_span[0].union(aa_span[1])
    sgn = sign * sa
    bv = b * v
    m = aa * aa + bv * bv
    p = b * b * w
    r = B.span(_quotient(aa_span, B.span(bv, 0)), 0, 1)       # a**2 / k**2
    r_ball = r[0].union(r[1])
    vk = B.sqrt(1 - r_ball) / b if bool(b > 0.5) else v / B.sqrt(m)
    RF, wRD = _partial(_rf_wave, tau, r), _partial(_rd_wave, tau, r)
    I = vk * RF
    G = b * b * vk * vk * vk / 3 * wRD
    Dp = p * I + m * G
    if j == sgn:                                           # mode 1, growing branch: Lambda = I
        Lam, D = I, Dp
        D_over = p + v * v * b * b * wRD / (3 * RF)
        vb_over = b * B.sqrt(m) / RF
        inv_lam = 1 / I
    else:
        K, Ek, inv_k = _complete(tau, b_span)
        Lam = (j - sgn) * K + sgn * I
        D = (j - sgn) * Ek + sgn * Dp
        share = B.span(I * inv_k, 0, 1)                     # I / K: a part of the wave
        inv_lam = inv_k / ((j - sgn) + sgn * share[0].union(share[1]))
        D_over, vb_over = D * inv_lam, bv * inv_lam
    u, w2 = 1 - 2 * D_over, 2 * sign * vb_over
    mul = B.mul
    tip = [L * (mul(u, cos) + mul(w2, sin)), L * (mul(u, sin) - mul(w2, cos))]
    # every tangent angle lies within 2 arcsin(k) of psi - pi (theta = psi - 2 arccos(k sin
    # phi)), so the tip is within 2 k L of -L (cos psi, sin psi): tight where k -> 0
    spread = arb(0, 1) * (2 * B.sqrt(m)).upper() * L
    tip = [B.meet(tip[0], -L * cos + spread), B.meet(tip[1], -L * sin + spread)]
    lam_span = B.span(Lam, 0)                    # Lambda >= 0: its square from the ends
    R = EI * B.monotone(lambda x: x * x, (lam_span, 1)) / (L * L)
    force = [mul(R, cos), mul(R, sin)]
    vb = sign * bv
    moment = 2 * EI * vb * Lam / L
    if not jacobian:
        return RodBall(tip, force, moment, R=R)

    # the rates of regular._waves, then of regular._closed_form (column 0: psi, 1: t); the
    # rates in |v| are multiplied by dv/dt = sign w (dv/dtau / w) with the 1 / w cancelled
    v_t = sign * dv_w
    Lam_t = (v * G + aa / m) * v_t
    Lam_psi = sa * (b * b * v / m - aa * G) / (2 * b)
    D_t = (v * b * b * (Dp - I) + aa * b * b) / m * w * v_t
    D_psi = sa * b * (v - aa * w * (Dp - I)) / (2 * m)
    if j != sgn:
        EK = Ek - p * K
        K_t, K_psi = v * EK / m * v_t, -sa * aa * EK / (2 * m * b)
        E_t, E_psi = v * b * b * (Ek - K) / m * w * v_t, -sa * aa * b * w * (Ek - K) / (2 * m)
        Lam_t, Lam_psi = (j - sgn) * K_t + sgn * Lam_t, (j - sgn) * K_psi + sgn * Lam_psi
        D_t, D_psi = (j - sgn) * E_t + sgn * D_t, (j - sgn) * E_psi + sgn * D_psi
    Lam_d, D_d = (Lam_psi, Lam_t), (D_psi, D_t)
    vb_d = (sign * v * sa * aa / 2, sign * b * w * v_t)
    J = [[None, None] for _ in range(5)]
    for i in range(2):
        u_d = -2 * inv_lam * (D_d[i] - D_over * Lam_d[i])
        w2_d = 2 * inv_lam * (vb_d[i] - sign * vb_over * Lam_d[i])
        dR = 2 * EI * Lam * Lam_d[i] / (L * L)
        if i == 0:
            u_d, w2_d = u_d + w2, w2_d - u
            J[2][0], J[3][0] = dR * cos - R * sin, dR * sin + R * cos
        else:
            J[2][1], J[3][1] = dR * cos, dR * sin
        J[0][i] = L * (u_d * cos + w2_d * sin)
        J[1][i] = L * (u_d * sin - w2_d * cos)
        J[4][i] = 2 * EI * (vb_d[i] * Lam + vb * Lam_d[i]) / L
    return RodBall(tip, force, moment, J, R)


def place(rod: object, origin: ArrayLike, angle: object) -> tuple:
    """A local-frame :class:`RodBall` clamped at ``origin`` (2 floats) at ``angle`` (rad):
    the global tip, force and their Jacobian rows (4 rows of 2: tip_x, tip_y, force_x,
    force_y). The clamp moment does not change."""
    c, s = arb(float(angle)).cos(), arb(float(angle)).sin()
    x0, y0 = arb(float(origin[0])), arb(float(origin[1]))

    def rot(u, w):
        return c * u - s * w, s * u + c * w

    tx, ty = rot(*rod.tip)
    fx, fy = rot(*rod.force)
    J = None
    if rod.jacobian is not None:
        tip_cols = [rot(rod.jacobian[0][i], rod.jacobian[1][i]) for i in range(2)]
        force_cols = [rot(rod.jacobian[2][i], rod.jacobian[3][i]) for i in range(2)]
        J = [[col[row] for col in cols] for cols in (tip_cols, force_cols) for row in (0, 1)]
    return RodBall([x0 + tx, y0 + ty], [fx, fy], rod.moment, J, rod.R,
                   rod.direction + arb(float(angle)))
