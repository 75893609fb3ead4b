"""A-priori bounds: how hard a clamped-pinned rod can pull, given where its tip must be.

**The reach of a loaded rod.** A rod of ``mode`` ``j`` in the regular chart
(``rods._regular``), clamped at the origin along +x, has (that module's formulas)::

    tip = L Rot(psi) (1 - 2 D / Lambda, -2 v b / Lambda),   force = R e,   R = EI Lambda**2 / L**2

with ``e = (cos psi, sin psi)`` the force's direction, ``Lambda = lambda L`` and
``D = E(phi2, k) - E(phi1, k) = int_{phi1}^{phi2} (1 - k**2 sin(x)**2)**(1/2) dx``. The integrand
lies in ``(0, 1]`` and ``-pi/2 <= phi1 <= pi/2``, ``phi2 = (j - 1/2) pi``, so ``0 <= D <= j pi``;
and ``|v b| = |k cos(phi1)| <= 1``. Hence::

    |tip - L e| = (2 L / Lambda) (D**2 + (v b)**2)**(1/2) <= c_j L / Lambda,
    c_j = 2 ((j pi)**2 + 1)**(1/2)                                      (:func:`reach`)

(6.594 for mode 1): a rod pulled hard has its tip near ``L e``, at the full length from the clamp,
in the direction of its force. The constant is nearly sharp: rods near the straight one at the
Euler load (``psi = pi``, ``t -> 0-``) come within 5 % of it for mode 1 (``D -> pi``).

**The chart's range.** On every branch ``Lambda >= I`` (the partial wave), and
``I = (v / k) R_F(w a**2 / k**2, 1, w) >= v R_F(w, 1, w) = arccosh(w**(-1/2))`` (``R_F``
decreases in each argument, ``k <= 1``, DLMF 19.2.19), ``w = exp(-q)``, ``q = t**2 / (1 - t**2)``.
So ``Lambda <= Lambda_max`` confines the chart to ``q <= 2 log cosh(Lambda_max)``
(:func:`chart_t_bound`).

**One pinned rod** (Chapter 3): a tip at distance ``d < L`` from the clamp has
``|tip - L e| >= L - d``, so ``Lambda <= c_j L / (L - d)`` (:func:`pinned_bound`; 34 for mode 1
and Chapter 3's target, 98 for mode 3).

**Two rods meeting at a point** (the 2RFR, motors ``g`` apart, load ``F``; :func:`pair_bound`):
write ``f = |F| L**2 / EI``. From ``n1 + n2 = F``, ``|R1 - R2| <= |F|``, so
``R1 (e1 + e2) = F + (R1 - R2) e2`` gives ``|e1 + e2| <= 2 f / Lambda1**2`` and
``Lambda2**2 >= Lambda1**2 - f``. Both tips at one point: ``L (e1 - e2) = O2 - O1 + d2 - d1``
with ``|d_i| <= c_i L / Lambda_i``, and ``|e1 - e2| >= 2 - |e1 + e2|``; so an equilibrium needs::

    2 - g / L <= h(Lambda1) = 2 f / Lambda1**2 + c1 / Lambda1 + c2 / (Lambda1**2 - f)**(1/2).

``h`` decreases for ``Lambda1 > f**(1/2)`` and tends to 0: above its crossing with ``2 - g / L``
there is no equilibrium. The crossing is found by bisection in floats, and the bound returned is
checked in ball arithmetic (Arb): ``h(Lambda*) < 2 - g / L`` proven, so ``Lambda1 < Lambda*``
for every equilibrium (the same with the rods' roles swapped). Table 7, modes ``(1, 1)``:
``Lambda_i < 10.4``.

Examples
--------
>>> round(reach(1), 4), round(pinned_bound(1, 0.806, 1.0), 1)
(6.5938, 34.0)
"""

import math

import numpy as np
from flint import arb

from mechnum import _validate
from mechnum.rods import _regular as regular

BISECTIONS = 80
"""Bisection steps of :func:`pair_bound` (the crossing to the last bits of a double)."""
MAX_MODE = 10
"""The highest mode accepted (as :func:`mechnum.rods.certified.certify_pinned`)."""


def _mode(mode, name="mode"):
    """``mode`` checked: an integer in ``[1, MAX_MODE]``."""
    if isinstance(mode, bool) or not isinstance(mode, (int, np.integer)) or not (
            1 <= mode <= MAX_MODE):
        raise ValueError(f"{name} must be an integer in [1, {MAX_MODE}], got "
                         f"{_validate.shown(mode)}")
    return int(mode)


def _up(x):
    """A float ``>= `` the ball ``x`` (its upper end, rounded up)."""
    return math.nextafter(float(x.upper()), math.inf)


def _reach_ball(mode):
    return 2 * ((mode * arb.pi()) ** 2 + 1).sqrt()


def reach(mode: int) -> float:
    """``c_j = 2 ((j pi)**2 + 1)**(1/2)``, rounded up: the tip of a rod of mode ``j`` lies
    within ``c_j L / Lambda`` of ``L e`` (see the module).

    Examples
    --------
    >>> [round(reach(j), 3) for j in (1, 2, 3)]
    [6.594, 12.725, 18.955]
    """
    return _up(_reach_ball(_mode(mode)))


def chart_t_bound(lam_max: float) -> float:
    """The largest ``|t|`` of a rod with ``Lambda <= lam_max`` (rounded up, at most
    the chart's ``T_MAX``): ``q <= 2 log cosh(lam_max)``.

    Examples
    --------
    >>> round(chart_t_bound(10.39), 4), chart_t_bound(1e4) == regular.T_MAX
    (0.9752, True)
    """
    lam_max = _validate.scalar(lam_max, "lam_max", positive=True)
    lam = arb(lam_max)
    q = 2 * (lam - arb(2).log() + (1 + (-2 * lam).exp()).log())     # 2 log cosh, no overflow
    if not _up(q) <= _up(lam * lam):         # log cosh x <= x**2 / 2: tiny loads, no cancelling
        q = lam * lam
    if q >= regular.Q_MAX:
        return regular.T_MAX
    return min(_up((q / (1 + q)).sqrt()), regular.T_MAX)


def pinned_bound(mode: int, distance: float, L: float) -> float:
    """``c_j L / (L - d)``, rounded up: the largest ``Lambda`` of a rod of ``mode`` whose tip is
    ``distance`` from its clamp.

    Raises
    ------
    ValueError
        If ``distance`` is not in ``[0, L)``.

    Examples
    --------
    >>> round(pinned_bound(3, 0.806, 1.0), 1)
    97.7
    """
    mode = _mode(mode)
    L = _validate.scalar(L, "L", positive=True)
    distance = _validate.scalar(distance, "distance")
    if not 0.0 <= distance < L:
        raise ValueError(f"distance must lie in [0, L) = [0, {L!r}), got {distance!r}")
    return _up(_reach_ball(mode) * arb(L) / (arb(L) - arb(distance)))


def _excess(lam, c_own, c_other, f, room):
    """``h(Lambda) - (2 - g / L)`` in balls (see the module); NaN where ``Lambda**2 <= f``."""
    lam = arb(lam)
    inner = lam * lam - f
    if not bool(inner > 0):
        return arb("nan")
    return 2 * f / (lam * lam) + c_own / lam + c_other / inner.sqrt() - room


def pair_bound(modes, gap: float, force: float, EI: float, L: float) -> tuple:
    """The largest ``Lambda`` of each rod of two that meet at a point (the 2RFR).

    Parameters
    ----------
    modes : (int, int)
        The rods' modes.
    gap : float
        Distance between the clamps (m), ``0 <= gap < 2 L``.
    force : float
        ``|F|``, the load at the meeting point (N).
    EI, L : float
        Bending stiffness (N m^2) and length (m) of each rod.

    Returns
    -------
    (float, float)
        ``Lambda*`` per rod: every equilibrium has ``Lambda_i < Lambda*_i`` (proven in ball
        arithmetic, see the module).

    Examples
    --------
    Table 7 (motors 0.6 m apart, ``|F| = 0.316 N``):

    >>> from mechnum.mechanisms.rfr2.study import TABLE7
    >>> [round(x, 2) for x in pair_bound((1, 1), 0.6, float(np.hypot(*TABLE7.force)),
    ...                                  TABLE7.EI, TABLE7.L)]
    [10.39, 10.39]
    """
    if not isinstance(modes, (tuple, list, np.ndarray)) or len(modes) != 2:
        raise ValueError(f"modes must be two modes, got {_validate.shown(modes)}")
    modes = [_mode(j, "modes") for j in modes]
    EI = _validate.scalar(EI, "EI", positive=True)
    L = _validate.scalar(L, "L", positive=True)
    gap, force = _validate.scalar(gap, "gap"), _validate.scalar(force, "force")
    if not 0.0 <= gap < 2.0 * L:
        raise ValueError(f"gap must lie in [0, 2 L) = [0, {2 * L!r}), got {gap!r}")
    if force < 0.0:
        raise ValueError(f"force is a magnitude |F| >= 0, got {force!r}")
    f = arb(force) * arb(L) ** 2 / arb(EI)
    room = 2 - arb(gap) / arb(L)
    c = [_reach_ball(j) for j in modes]
    return tuple(_crossing(c[i], c[1 - i], f, room) for i in range(2))


def _crossing(c_own, c_other, f, room):
    """The bound of :func:`pair_bound` for one rod: bisection, then the proof."""
    def excess(lam):
        value = _excess(lam, c_own, c_other, f, room)
        return float(value.mid()) if value.is_finite() else math.inf

    lo = math.nextafter(float(f.sqrt().upper()), math.inf)
    hi = max(2.0 * lo, 1.0)
    while excess(hi) >= 0.0:
        lo, hi = hi, 2.0 * hi
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if excess(mid) >= 0.0 else (lo, mid)
    bound = hi
    while not bool(_excess(bound, c_own, c_other, f, room) < 0):   # proven, or a little up
        bound = math.nextafter(bound * (1.0 + 1e-12), math.inf)
    return bound
