"""Chapter 5, the flexible 2RFR: the elliptic tip of one rod (5.1), the pin's equilibrium
(5.2), and a Krawczyk test in one dimension (5.3)."""

import numpy as np

from mechnum.exercises._answers import Array, Choice, Tuple, close
from mechnum.exercises._harness import Case, Exercise, Mistake

TIP_STARTER = '''\
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
    ...
'''

PIN_STARTER = '''\
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
    ...
'''

KRAWCZYK_STARTER = '''\
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
    ...
'''


def _tip_cases():
    return [Case("EI = L = 1, psi = 1 rad, k_rel = 0.5, mode 1", (1.0, 1.0, 1.0, 0.5, 1)),
            Case("EI = 0.16, L = 1 m, psi = 2.5 rad, k_rel = -0.3, mode 1",
                 (0.16, 1.0, 2.5, -0.3, 1)),
            Case("EI = 0.16, L = 1 m, psi = 3.49 rad, k_rel = -0.32, mode 2",
                 (0.16, 1.0, 3.49, -0.32, 2)),
            Case("EI = 2, L = 0.7 m, psi = 4 rad, k_rel = 0.8, mode 3", (2.0, 0.7, 4.0, 0.8, 3)),
            Case("a small load: EI = L = 1, psi = 2 rad, k_rel = 1e-14, mode 1",
                 (1.0, 1.0, 2.0, 1e-14, 1))]


ELLIPTIC = Exercise(
    number="5.1", label="ch5-ex-elliptic-tip", title="the elliptic tip of one rod",
    statement=(
        "**Implement it yourself.** Write `elliptic_tip(EI, L, psi, k_rel, mode)`, the tip of "
        "one clamped-pinned rod in its clamp's frame from the thesis's closed form: $k$ from "
        "$k_{rel}$ by (91), $\\phi_1$ by (41), $\\phi_2 = (\\text{mode} - \\tfrac12)\\pi$, "
        "$\\lambda L = F(\\phi_2, k) - F(\\phi_1, k)$, and the tip by (45) and (46), "
        "accurate at small loads ($k_{rel} = 10^{-14}$), where Chapter 3's `printed_tip` is not: "
        "take $\\phi_2 - \\phi_1$ by `arctan2` and integrate over $[\\phi_1, \\phi_2]$ "
        "itself (`scipy.integrate.quad`). Compare with "
        "`rods.clamped_pinned(EI, L, psi, k_rel, mode).tip`."),
    starter=TIP_STARTER, cases=_tip_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=1e-9, atol=1e-12, what="the tip"),
    mistakes=(Mistake("the printed formulas", "differences of integrals from 0, divided by a "
                      "small lambda, amplify rounding: integrate over [phi1, phi2] itself."),
              Mistake("the modulus for the parameter", "scipy's ellipkinc(phi, m) and "
                      "ellipeinc(phi, m) take m = k^2, not k."),
              Mistake("phi2 = mode pi", "a pinned tip carries no moment: cos(phi2) = 0, "
                      "phi2 = (mode - 1/2) pi."),
              Mistake("a sign in y", "y = -(sin psi (2 dE - dF) - 2 k cos psi dC) / lambda.")),
    hint="a nearly straight rod in pure compression (psi = pi, k_rel = 1e-6, mode 1) carries "
         "Euler's load pi^2 EI / (4 L^2), with its tip near (L, 0).")


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
    starter=PIN_STARTER, cases=_pin_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=1e-12, atol=1e-14,
                                        what="the residual"),
    mistakes=(Mistake("the study's sign of F", "n is the force on each rod, so the pin "
                      "balances n1 + n2 - F = 0; the study's (104) prints + F, an erratum."),
              Mistake("the inverse rotation", "Rot(theta) = [[cos, -sin], [sin, cos]] turns the "
                      "clamp's frame into the fixed one; you used its transpose."),
              Mistake("the motors left out", "p_i = O_i + Rot(theta_i) p_i,loc: add the "
                      "motor's position.")),
    hint="with theta = 0 and both motors at the origin the residual is (tip1 - tip2, "
         "n1 + n2 - F).")


def outwards(values):
    """The floats around the exact results of correctly rounded operations."""
    return np.nextafter(min(values), -np.inf), np.nextafter(max(values), np.inf)


class Polynomial:
    """A polynomial with its enclosures on floats (Horner, each operation rounded outwards)."""

    def __init__(self, coefficients):
        self.c = [float(v) for v in coefficients]  # ascending powers

    @staticmethod
    def _horner(c, lo, hi):
        value = (c[-1], c[-1])
        for a in reversed(c[:-1]):
            product = outwards([v * x for v in value for x in (lo, hi)])
            value = outwards([product[0] + a])[0], outwards([product[1] + a])[1]
        return value

    def at(self, x):
        """An enclosure of the polynomial at the float ``x``."""
        return self._horner(self.c, x, x)

    def slope(self, lo, hi):
        """An enclosure of the derivative over ``[lo, hi]``."""
        return self._horner([k * a for k, a in enumerate(self.c)][1:], lo, hi)


def _krawczyk_cases():
    def case(label, coefficients, lo, hi):
        p = Polynomial(coefficients)
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


SLACK = 64
"""Units in the last place by which an answer's K(X) may be wider than the tightest enclosure
of the exact set at each end (outward rounding at every operation widens it by a few)."""


def _krawczyk_compare(expected, got):
    """The expected K(X) is the tightest floating-point enclosure of the exact one: an answer's
    must contain it, and be wider by at most SLACK units in the last place at each end."""
    verdict, K = got
    if verdict != expected[0]:
        return f"the verdict is {verdict!r}, expected {expected[0]!r}"
    (low, high), (lo, hi) = (float(v) for v in expected[1]), (float(v) for v in K)
    if not lo <= hi:
        return f"K(X) = [{lo!r}, {hi!r}] is no interval"
    if lo > low or hi < high:
        end = (f"its lower end {lo!r} lies above {low!r}" if lo > low
               else f"its upper end {hi!r} lies below {high!r}")
        point = ", a single point," if lo == hi else ""
        return (f"K(X) = [{lo!r}, {hi!r}]{point} does not enclose the exact K(X): {end}. "
                "Round every lower end down and every upper end up")
    if lo < low - SLACK * abs(np.spacing(low)) or hi > high + SLACK * abs(np.spacing(high)):
        return (f"K(X) = [{lo!r}, {hi!r}] is wider than the computation needs (the exact set "
                f"is within [{low!r}, {high!r}])")
    return None


def _krawczyk_agree(mistaken, got):
    """Whether an answer is a mistake's: the same verdict, and K(X) within SLACK units in the
    last place at each end (the two may round differently)."""
    return got[0] == mistaken[0] and all(
        abs(float(a) - float(b)) <= SLACK * abs(np.spacing(float(b)))
        for a, b in zip(got[1], mistaken[1]))


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
    starter=KRAWCZYK_STARTER, cases=_krawczyk_cases, compare=_krawczyk_compare,
    agree=_krawczyk_agree,
    returns=Tuple(Choice("unique", "none", "undecided"), Array(), names=("the verdict", "K")),
    mistakes=(Mistake("the Newton point without its enclosure", "K(X) adds (1 - y f'(X))(X - "
                      "m) to the Newton point: without it nothing is proved, and two roots look "
                      "like one."),
              Mistake("no outward rounding", "round every lower end down and every upper end "
                      "up (np.nextafter): rounded to nearest, K(X) can miss part of the exact "
                      "set, and then nothing is proved."),
              Mistake("'unique' on the closed X", "uniqueness needs K(X) in the interior of X: "
                      "lo < K_lo and K_hi < hi, strictly; a K(X) that touches an end proves "
                      "nothing."),
              Mistake("a sign", "K(X) = m - y f(m) + ..., with the minus of Newton's step."),
              Mistake("X instead of X - m", "the last factor is X - m, centred on m."),
              Mistake("'none' for an undecided box", "no root is proved only when K(X) misses "
                      "X; an overlap proves nothing.")),
    hint="every root of f in X lies in K(X): check that K(X) contains sqrt(2) on [1.3, 1.5].")
