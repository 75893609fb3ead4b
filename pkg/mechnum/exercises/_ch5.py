"""Chapter 5, the flexible 2RFR: the elliptic tip of one rod (5.1), the pin's equilibrium
(5.2), and a Krawczyk test in one dimension (5.3)."""

import numpy as np

from mechnum.exercises._harness import Case, Exercise, Mistake, close


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
    from scipy.special import ellipeinc, ellipkinc

    k_min = abs(np.cos(psi / 2))
    k = np.sign(k_rel) * k_min + (1 - k_min) * k_rel  # the study's (91)
    phi1 = np.arcsin(np.cos(psi / 2) / k)  # the clamp, (41)
    phi2 = (mode - 0.5) * np.pi  # the pinned tip, (43)
    m = k ** 2  # scipy takes the parameter m = k^2
    dF = ellipkinc(phi2, m) - ellipkinc(phi1, m)
    dE = ellipeinc(phi2, m) - ellipeinc(phi1, m)
    lam = dF / L  # (40): lambda L = F(phi2, k) - F(phi1, k)
    dC = np.cos(phi2) - np.cos(phi1)  # then x by (45), y by (46)
    x = -(np.cos(psi) * (2 * dE - dF) + 2 * k * np.sin(psi) * dC) / lam
    y = -(np.sin(psi) * (2 * dE - dF) - 2 * k * np.cos(psi) * dC) / lam
    return np.array([x, y])


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


# Typical mistakes of 5.1: the closed form with one thing changed
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


def _tip_cases():
    return [Case("EI = L = 1, psi = 1 rad, k_rel = 0.5, mode 1", (1.0, 1.0, 1.0, 0.5, 1)),
            Case("EI = 0.16, L = 1 m, psi = 2.5 rad, k_rel = -0.3, mode 1",
                 (0.16, 1.0, 2.5, -0.3, 1)),
            Case("EI = 0.16, L = 1 m, psi = 3.49 rad, k_rel = -0.32, mode 2",
                 (0.16, 1.0, 3.49, -0.32, 2)),
            Case("EI = 2, L = 0.7 m, psi = 4 rad, k_rel = 0.8, mode 3", (2.0, 0.7, 4.0, 0.8, 3))]


ELLIPTIC = Exercise(
    number="5.1", label="ch5-ex-elliptic-tip", title="the elliptic tip of one rod",
    statement=(
        "**Implement it yourself.** Write `elliptic_tip(EI, L, psi, k_rel, mode)`, the tip of "
        "one clamped-pinned rod in its clamp's frame from the thesis's closed form: $k$ from "
        "$k_{rel}$ by (91), $\\phi_1$ by (41), $\\phi_2 = (\\text{mode} - \\tfrac12)\\pi$, "
        "$\\lambda L = F(\\phi_2, k) - F(\\phi_1, k)$, and the tip by (45) and (46). "
        "`scipy.special.ellipkinc(phi, m)` and `ellipeinc(phi, m)` take the parameter "
        "$m = k^2$. Compare with `rods.clamped_pinned(EI, L, psi, k_rel, mode).tip`."),
    reference=elliptic_tip, cases=_tip_cases,
    compare=lambda expected, got: close(expected, got, rtol=1e-9, atol=1e-12, what="the tip"),
    mistakes=(Mistake("the modulus for the parameter", "scipy's ellipkinc(phi, m) and "
                      "ellipeinc(phi, m) take m = k^2, not k.", _tip_variant(lambda k: k)),
              Mistake("phi2 = mode pi", "a pinned tip carries no moment: cos(phi2) = 0, "
                      "phi2 = (mode - 1/2) pi.", _tip_variant(phi2_turns=0.0)),
              Mistake("a sign in y", "y = -(sin psi (2 dE - dF) - 2 k cos psi dC) / lambda.",
                      _tip_variant(y_sign=1))),
    hint="a nearly straight rod in pure compression (psi = pi, k_rel = 1e-6, mode 1) carries "
         "Euler's load pi^2 EI / (4 L^2), with its tip near (L, 0).")


# Typical mistakes of 5.2
def _plus_load(tips, forces, origins, theta, load):
    return pin_residual(tips, forces, origins, theta, -np.asarray(load))


def _inverse_rotation(tips, forces, origins, theta, load):
    return pin_residual(tips, forces, origins, -np.asarray(theta), load)


def _no_origins(tips, forces, origins, theta, load):
    return pin_residual(tips, forces, np.zeros((2, 2)), theta, load)


def _pin_cases():
    rng = np.random.default_rng(52)
    cases = [Case("the study's motors (-0.3, 0) and (0.3, 0) m at 40 and 60 degrees, load "
                  "(0.3, -0.1) N, random tips and forces",
                  (rng.normal(size=(2, 2)), rng.normal(size=(2, 2)),
                   np.array([[-0.3, 0.0], [0.3, 0.0]]), np.radians([40.0, 60.0]),
                   np.array([0.3, -0.1])))]
    for k in range(2):
        cases.append(Case(f"random mechanism {k + 1}", (rng.normal(size=(2, 2)),
                          rng.normal(size=(2, 2)), rng.normal(size=(2, 2)),
                          rng.uniform(-np.pi, np.pi, 2), rng.normal(size=2))))
    return cases


PIN = Exercise(
    number="5.2", label="ch5-ex-pin-residual", title="the pin's equilibrium",
    statement=(
        "**Implement it yourself.** Write `pin_residual(tips, forces, origins, theta, load)`: "
        "place each rod's tip and tip force, given in its clamp's frame, by its motor, "
        "$\\mathbf p_i = O_i + \\mathrm{Rot}(\\theta_i)\\,\\mathbf p_{i,\\mathrm{loc}}$ (the "
        "study's (103)) and $\\mathbf n_i = \\mathrm{Rot}(\\theta_i)\\,\\mathbf n_{i,"
        "\\mathrm{loc}}$, and return the four equations of the pin, "
        "$(\\mathbf p_1 - \\mathbf p_2,\\ \\mathbf n_1 + \\mathbf n_2 - F)$. Evaluate it at your "
        "`elliptic_tip` rods of Table 7's solutions."),
    reference=pin_residual, cases=_pin_cases,
    compare=lambda expected, got: close(expected, got, rtol=1e-12, atol=1e-14,
                                        what="the residual"),
    mistakes=(Mistake("the study's sign of F", "n is the force on each rod, so the pin "
                      "balances n1 + n2 - F = 0; the study's (104) prints + F, an erratum.",
                      _plus_load),
              Mistake("the inverse rotation", "Rot(theta) = [[cos, -sin], [sin, cos]] turns the "
                      "clamp's frame into the fixed one; you used its transpose.",
                      _inverse_rotation),
              Mistake("the motors left out", "p_i = O_i + Rot(theta_i) p_i,loc: add the "
                      "motor's position.", _no_origins)),
    hint="with theta = 0 and both motors at the origin the residual is (tip1 - tip2, "
         "n1 + n2 - F).")


def _out(values):
    """The floats around the exact results of correctly rounded operations."""
    return np.nextafter(min(values), -np.inf), np.nextafter(max(values), np.inf)


class _Polynomial:
    """A polynomial with its enclosures on floats (Horner, each operation rounded outwards)."""

    def __init__(self, coefficients):
        self.c = [float(v) for v in coefficients]  # ascending powers

    @staticmethod
    def _horner(c, lo, hi):
        value = (c[-1], c[-1])
        for a in reversed(c[:-1]):
            product = _out([v * x for v in value for x in (lo, hi)])
            value = _out([product[0] + a])[0], _out([product[1] + a])[1]
        return value

    def at(self, x):
        return self._horner(self.c, x, x)

    def slope(self, lo, hi):
        return self._horner([k * a for k, a in enumerate(self.c)][1:], lo, hi)


def _krawczyk_cases():
    def case(label, coefficients, lo, hi):
        p = _Polynomial(coefficients)
        return Case(label, (p.at, p.slope, lo, hi))

    def line(x):  # f(x) = x - 1.75 at a float of [1, 2]: exact
        return x - 1.75, x - 1.75

    def loose(lo, hi):  # a valid but loose enclosure of f' = 1
        return 0.5, 1.5
    return [case("x^2 - 2 on [1.3, 1.5] (one root)", (-2, 0, 1), 1.3, 1.5),
            case("x^2 - 2 on [1.5, 2] (no root)", (-2, 0, 1), 1.5, 2.0),
            case("(x - 1)(x - 2)(x - 3) on [1.8, 2.25] (one root)", (-6, 11, -6, 1), 1.8, 2.25),
            case("(x - 1)^2 on [0.9, 1.15] (a double root)", (1, -2, 1), 0.9, 1.15),
            case("x^2 - 2 on [-1.6, 1.7] (two roots)", (-2, 0, 1), -1.6, 1.7),
            case("x^3 - x on [-0.3, 0.35] (one root)", (0, -1, 0, 1), -0.3, 0.35),
            case("x^2 - 2 on [1.4, 1.44], where K(X) rounded to nearest misses the exact set "
                 "at both ends", (-2, 0, 1), 1.4, 1.44),
            Case("f(x) = x - 1.75 on [1, 2], f' enclosed in [0.5, 1.5]: K(X) = [1.5, 2] "
                 "exactly, touching the edge of X", (line, loose, 1.0, 2.0))]


def _exact_krawczyk(f, df, lo, hi):
    """The verdict and the tightest floating-point enclosure of the exact ``K(X)`` of the
    statement (``m`` and ``y`` the statement's floats), by rational arithmetic: the answer
    that any correct outward rounding encloses."""
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


SLACK = 64
"""Units in the last place by which an answer's K(X) may be wider than the tightest enclosure
of the exact set at each end (outward rounding at every operation widens it by a few)."""


def _krawczyk_compare(expected, got):
    verdict, K = got
    if verdict != expected[0]:
        return f"the verdict is {verdict!r}, expected {expected[0]!r}"
    (low, high), (lo, hi) = (float(v) for v in expected[1]), (float(v) for v in K)
    if not lo <= hi:
        return f"K(X) = [{lo!r}, {hi!r}] is no interval"
    if lo > low or hi < high:
        end = (f"its lower end {lo!r} lies above {low!r}" if lo > low
               else f"its upper end {hi!r} lies below {high!r}")
        point = ", a single point" if lo == hi else ""
        return (f"K(X) = [{lo!r}, {hi!r}]{point} does not enclose the exact K(X): {end}. "
                "Round every lower end down and every upper end up")
    if lo < low - SLACK * abs(np.spacing(low)) or hi > high + SLACK * abs(np.spacing(high)):
        return (f"K(X) = [{lo!r}, {hi!r}] is wider than the computation needs (the exact set "
                f"is within [{low!r}, {high!r}])")
    return None


def _krawczyk_agree(mistaken, got):
    """Whether an answer is a mistake's: the same verdict, and K(X) within SLACK units in the
    last place at each end (the two may round differently)."""
    if got[0] != mistaken[0]:
        return False
    return all(abs(float(a) - float(b)) <= SLACK * abs(np.spacing(float(b)))
               for a, b in zip(got[1], mistaken[1]))


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


KRAWCZYK = Exercise(
    number="5.3", label="ch5-ex-krawczyk", title="a Krawczyk test in one dimension",
    statement=(
        "**Implement it yourself.** Write `krawczyk_1d(f, df, lo, hi)`, the test of "
        "{ref}`ch3-count` in one dimension. With $X = [lo, hi]$, $m = lo + (hi - lo)/2$ and "
        "$y = 2/(d_{lo} + d_{hi})$ from the enclosure $f'(X) \\subseteq [d_{lo}, d_{hi}]$ that "
        "`df(lo, hi)` returns, compute Krawczyk's "
        "$K(X) = m - y f(m) + (1 - y f'(X))(X - m)$ in interval arithmetic (`f(m)` returns an "
        "enclosure of $f(m)$), every lower end rounded down and every upper end up "
        "(`np.nextafter(v, -np.inf)`, `np.nextafter(v, np.inf)`): the check asks that your "
        "$K(X)$ contain the exact one. Return `\"unique\"` if $K(X)$ lies in the interior of "
        "$X$, `\"none\"` if $K(X) \\cap X = \\emptyset$, else `\"undecided\"`, with $K(X)$. "
        "Rounding outwards by one unit in the last place encloses the exact result because "
        "$+, -, \\times, /$ are correctly rounded in IEEE arithmetic. Why can a double root "
        "never be proved unique?"),
    reference=krawczyk_1d, cases=_krawczyk_cases, compare=_krawczyk_compare,
    expected=_exact_krawczyk, agree=_krawczyk_agree,
    mistakes=(Mistake("the Newton point without its enclosure", "K(X) adds (1 - y f'(X))(X - "
                      "m) to the Newton point: without it nothing is proved, and two roots look "
                      "like one.", _krawczyk_variant(enclosed=False)),
              Mistake("no outward rounding", "round every lower end down and every upper end "
                      "up (np.nextafter): rounded to nearest, K(X) can miss part of the exact "
                      "set, and then nothing is proved.", _krawczyk_variant(outward=False)),
              Mistake("'unique' on the closed X", "uniqueness needs K(X) in the interior of X: "
                      "lo < K_lo and K_hi < hi, strictly; a K(X) that touches an end proves "
                      "nothing.", _krawczyk_variant(outward=False, closed=True)),
              Mistake("a sign", "K(X) = m - y f(m) + ..., with the minus of Newton's step.",
                      _krawczyk_variant(sign=1)),
              Mistake("X instead of X - m", "the last factor is X - m, centred on m.",
                      _krawczyk_variant(centred=False)),
              Mistake("'none' for an undecided box", "no root is proved only when K(X) misses "
                      "X; an overlap proves nothing.", _krawczyk_variant(overlap="none"))),
    hint="every root of f in X lies in K(X): check that K(X) contains sqrt(2) on [1.3, 1.5].")
