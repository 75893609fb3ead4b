"""Chapter 5: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum.exercises._ch5 import outwards as _out
from mechnum_course.solutions._solution import Solution


def elliptic_tip(EI, L, psi, k_rel, mode):
    """The tip of a clamped-pinned rod from the thesis's closed form.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    psi, k_rel, mode : float, float, int
        The tip force's direction from the clamped tangent,
        ``0 < psi < 2 pi``; the relative modulus, ``0 < |k_rel| < 1``; the
        buckling mode, ``>= 1``.

    Returns
    -------
    ndarray, shape (2,)
        The tip ``(x, y)`` in the clamp's frame (m).
    """
    from scipy.integrate import quad

    k_min = abs(np.cos(psi / 2))
    k = np.sign(k_rel) * k_min + (1 - k_min) * k_rel  # the study's (91)
    q = (1 - k_min) * (1 - abs(k_rel)) * (1 + abs(k))  # 1 - k^2
    kc = np.sqrt((1 - k_min) * abs(k_rel) * (abs(k) + k_min))
    w = (mode - 1) * np.pi + np.arctan2(kc, np.cos(psi / 2) / np.sign(k))
    dF, chord = (quad(f, 0, w, epsabs=1e-15, epsrel=1e-12)[0] for f in (
        lambda u: 1 / np.sqrt(q + k**2 * np.sin(u) ** 2),  # u = phi2 - phi
        lambda u: (2 * q - 1 + 2 * k**2 * np.sin(u) ** 2)
        / np.sqrt(q + k**2 * np.sin(u) ** 2)))  # 2 dE - dF
    side = -2 * np.sign(k) * kc  # 2 k (cos(phi2) - cos(phi1))
    return -np.array([np.cos(psi) * chord + np.sin(psi) * side,  # (45) (46)
                      np.sin(psi) * chord - np.cos(psi) * side]) * L / dF


def pin_residual(tips, forces, origins, theta, load):
    """The 2RFR's pin: the tips at one point, the forces balancing the load.

    Parameters
    ----------
    tips, forces : ndarray, shape (2, 2)
        Row ``i``: the tip of rod ``i`` (m) and the force on it at its tip
        (N), in the frame of its clamp.
    origins : ndarray, shape (2, 2)
        Row ``i``: the motor ``O_i`` (m).
    theta : ndarray, shape (2,)
        The motor angles (rad).
    load : ndarray, shape (2,)
        The external force ``F`` on the pin (N).

    Returns
    -------
    ndarray, shape (4,)
        ``(p_1 - p_2, n_1 + n_2 - F)``, in the fixed frame.
    """
    c, s = np.cos(theta), np.sin(theta)
    rotations = np.array([[[ci, -si], [si, ci]] for ci, si in zip(c, s)])
    p = origins + np.einsum("ijk,ik->ij", rotations, tips)  # (103)
    n = np.einsum("ijk,ik->ij", rotations, forces)
    return np.concatenate((p[0] - p[1], n[0] + n[1] - load))


def krawczyk_1d(f, df, lo, hi):
    """Krawczyk's test for a root of ``f`` in the interval ``[lo, hi]``.

    Parameters
    ----------
    f : callable
        ``f(x)`` -> ``(f_lo, f_hi)``: an enclosure of ``f`` at the float
        ``x``.
    df : callable
        ``df(lo, hi)`` -> ``(d_lo, d_hi)``: an enclosure of ``f'`` over
        ``[lo, hi]``.
    lo, hi : float
        The interval ``X``, ``lo < hi``.

    Returns
    -------
    verdict : str
        ``"unique"`` if ``K(X)`` lies in the interior of ``X`` (exactly
        one root in ``X``), ``"none"`` if ``K(X)`` and ``X`` are disjoint
        (no root in ``X``), else ``"undecided"``.
    K : tuple of float
        ``K(X) = m - y f(m) + (1 - y f'(X)) (X - m)``, ``m`` the midpoint
        of ``X``, ``y = 2 / (d_lo + d_hi)``, rounded outwards.
    """
    def down(v):  # below v, so below the exact value v was rounded from
        return np.nextafter(v, -np.inf)

    def up(v):
        return np.nextafter(v, np.inf)

    def times(a, b):
        products = [a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1]]
        return down(min(products)), up(max(products))

    m = lo + (hi - lo) / 2
    d_lo, d_hi = df(lo, hi)
    y = 2 / (d_lo + d_hi)  # near 1 / f'(m); any y != 0 is valid
    yf = times((y, y), f(m))
    newton = down(m - yf[1]), up(m - yf[0])
    yd = times((y, y), (d_lo, d_hi))
    slope = down(1 - yd[1]), up(1 - yd[0])
    spread = times(slope, (down(lo - m), up(hi - m)))
    K = down(newton[0] + spread[0]), up(newton[1] + spread[1])
    if lo < K[0] and K[1] < hi:
        return "unique", K
    if K[1] < lo or K[0] > hi:
        return "none", K
    return "undecided", K


# Typical mistakes of 5.1
def _tip_variant(parameter=lambda k: k ** 2, phi2_turns=0.5, y_sign=-1):
    def tip(EI, L, psi, k_rel, mode):
        from scipy.special import ellipeinc, ellipkinc

        k_min = abs(np.cos(psi / 2))
        k = np.sign(k_rel) * k_min + (1 - k_min) * k_rel
        phi1, phi2, m = np.arcsin(np.cos(psi / 2) / k), (mode - phi2_turns) * np.pi, parameter(k)
        dF = ellipkinc(phi2, m) - ellipkinc(phi1, m)
        dE = ellipeinc(phi2, m) - ellipeinc(phi1, m)
        dC, lam = np.cos(phi2) - np.cos(phi1), dF / L
        return -np.array([np.cos(psi) * (2 * dE - dF) + 2 * k * np.sin(psi) * dC,
                          np.sin(psi) * (2 * dE - dF) + y_sign * 2 * k * np.cos(psi) * dC]) / lam
    return tip



# Typical mistakes of 5.2
def _plus_load(tips, forces, origins, theta, load):
    return pin_residual(tips, forces, origins, theta, -np.asarray(load))


def _inverse_rotation(tips, forces, origins, theta, load):
    return pin_residual(tips, forces, origins, -np.asarray(theta), load)


def _no_origins(tips, forces, origins, theta, load):
    return pin_residual(tips, forces, np.zeros((2, 2)), theta, load)



def exact_krawczyk(f, df, lo, hi):
    """The verdict and the tightest floating-point enclosure of the exact ``K(X)`` of the
    statement (``m`` and ``y`` the statement's floats), by rational arithmetic: the expected
    answer, which any correct outward rounding encloses."""
    from fractions import Fraction

    def times(a, b):
        products = [u * v for u in a for v in b]
        return min(products), max(products)
    m = lo + (hi - lo) / 2
    d_lo, d_hi = df(lo, hi)
    y = 2 / (d_lo + d_hi)
    F, Y, M = [Fraction(v) for v in f(m)], Fraction(y), Fraction(m)
    yf = times((Y, Y), F)
    yd = times((Y, Y), (Fraction(d_lo), Fraction(d_hi)))
    spread = times((1 - yd[1], 1 - yd[0]), (Fraction(lo) - M, Fraction(hi) - M))
    K = (M - yf[1] + spread[0], M - yf[0] + spread[1])
    out = [float(K[0]), float(K[1])]  # rounded to nearest, then outwards if need be
    out[0] = float(np.nextafter(out[0], -np.inf)) if Fraction(out[0]) > K[0] else out[0]
    out[1] = float(np.nextafter(out[1], np.inf)) if Fraction(out[1]) < K[1] else out[1]
    if lo < K[0] and K[1] < hi:
        return "unique", tuple(out)
    return ("none" if K[1] < lo or K[0] > hi else "undecided"), tuple(out)


# Typical mistakes of 5.3
def _krawczyk_variant(sign=-1, centred=True, enclosed=True, overlap="undecided",
                      outward=True, closed=False):
    out = _out if outward else (lambda values: (min(values), max(values)))

    def test(f, df, lo, hi):
        m = lo + (hi - lo) / 2
        d_lo, d_hi = df(lo, hi)
        y = 2 / (d_lo + d_hi)
        yf = out([y * v for v in f(m)])
        newton = out([m + sign * v for v in yf])
        slope = out([1 - y * d for d in (d_lo, d_hi)])
        X = out([lo - m, hi - m]) if centred else (lo, hi)
        spread = out([a * b for a in slope for b in X]) if enclosed else (0.0, 0.0)
        K = out([newton[0] + spread[0]])[0], out([newton[1] + spread[1]])[1]
        if (lo <= K[0] and K[1] <= hi) if closed else (lo < K[0] and K[1] < hi):
            return "unique", K
        return ("none" if K[1] < lo or K[0] > hi else overlap), K
    return test


SOLUTIONS = {
    "5.1": Solution(elliptic_tip, {"the printed formulas": _tip_variant(),
                                   "the modulus for the parameter": _tip_variant(lambda k: k),
                                   "phi2 = mode pi": _tip_variant(phi2_turns=0.0),
                                   "a sign in y": _tip_variant(y_sign=1)},
                    forbidden=("mechnum.rods.clamped_pinned",)),
    "5.2": Solution(pin_residual, {"the study's sign of F": _plus_load,
                                   "the inverse rotation": _inverse_rotation,
                                   "the motors left out": _no_origins},
                    forbidden=()),
    "5.3": Solution(krawczyk_1d, {
        "the Newton point without its enclosure": _krawczyk_variant(enclosed=False),
        "no outward rounding": _krawczyk_variant(outward=False),
        "'unique' on the closed X": _krawczyk_variant(outward=False, closed=True),
        "a sign": _krawczyk_variant(sign=1),
        "X instead of X - m": _krawczyk_variant(centred=False),
        "'none' for an undecided box": _krawczyk_variant(overlap="none")},
        forbidden=(), expected=exact_krawczyk),
}
