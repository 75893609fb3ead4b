"""Every clamped-pinned equilibrium that reaches a point, proven (Chapter 3's pinned rod).

:func:`~mechnum.rods.certify_pinned` searches the regular chart ``(psi, t)`` of ``rods``'s
regular module of each mode with :func:`~mechnum.certify.roots`, the closed form enclosed over boxes
(``rods._balls``). The searched boxes are the chart's whole closed domain, one per branch:
``0 <= psi <= 2 pi`` and ``0 <= t <= T_MAX`` or ``-T_MAX <= t <= 0``.

**Beyond the chart** (``|t| > T_MAX``, ``q > Q_MAX = 600``) the rods are excluded analytically.
On every branch ``Lambda = lambda L >= I`` (the partial wave; the complete ``K >= I``), and
``I = (v / k) R_F(w a**2 / k**2, 1, w) >= v R_F(w, 1, w) = v arccosh(w**-1/2) / (1 - w)**1/2
>= v q / 2`` (``R_F`` decreases in each argument, ``k <= 1``; DLMF 19.2.17), so a rod with
``q >= Q_MAX`` has ``Lambda >= TAIL_LAMBDA``. Its tip is ``L Rot(psi) (1 - 2 D / Lambda,
-2 v b / Lambda)`` with ``|D| <= mode pi`` (``D`` is a sum of ``2 mode`` quarter-wave
E-integrals, each at most ``pi / 2``) and ``v b <= 1``: it lies within
``tail_reach(mode, Lambda) = (2 pi mode + 2) / Lambda`` times ``L`` of ``L (cos psi, sin psi)``,
farther than ``L (1 - tail_reach)`` from the clamp; a target nearer than that is reached by no
rod of the tail. The a-priori bound of a-priori bound of the pinned rod (``Lambda <= c_j L /
(L - d)``, the same reach with ``|D| <= mode pi`` and ``v b <= 1`` used the other way round)
is tighter wherever it confines the rods inside the chart (:func:`chart_t_bound`
below ``T_MAX``: 34 for Chapter 3's target in mode 1, 98 in mode 3): the tail is then excluded
by it.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from flint import arb
from numpy.typing import ArrayLike

from mechnum import _validate, certify
from mechnum.certify.balls import interval
from mechnum.rods import _balls as balls
from mechnum.rods import _regular as regular
from mechnum.rods._apriori import chart_t_bound, pair_bound, pinned_bound
from mechnum.rods._cocertificate import verify as verify_corefined
from mechnum.rods._leaves import ChartRod
from mechnum.rods._tuples import Assembly

# The pinned rod's system, and what the rod mechanisms' certified modules build theirs from
# (certify_pinned is rods'; Certified, the result, is documented with the functions that return
# it): the rods' charts cut to the a-priori bound and their assembly, which the co-refinement
# (rods.corefine) searches, and the re-check of its certificate.
__all__ = ["MAX_LIVE", "TAIL_LAMBDA", "Assembly", "ChartRod", "around_boxes", "around_note",
           "branch_boxes", "chart_t_bound", "combine", "enclosed", "forces_exclude",
           "forces_split", "memoised", "pair_bound", "pinned_system", "placed", "stiffness",
           "tail_reach", "verdict", "verify_corefined"]

TWO_PI = 2.0 * np.pi
CHART_BOX = ((0.0, TWO_PI), (0.0, regular.T_MAX))
"""The chart's closed domain on the branch ``t > 0`` (mirrored for ``t < 0``)."""
TAIL_LAMBDA = 0.5 * regular.Q_MAX * float(np.sqrt(-np.expm1(-regular.Q_MAX))) * (1 - 1e-12)
"""A lower bound of ``Lambda = lambda L`` of every rod beyond the chart (``q > Q_MAX``), with a
margin for rounding: ``v q / 2`` at ``q = Q_MAX`` (see the module)."""


def tail_reach(mode: int, lam: float = TAIL_LAMBDA) -> float:
    """``(2 pi mode + 2) / Lambda``: how far (over ``L``) the tip of a rod of that ``mode`` with
    ``lambda L >= Lambda`` may lie from ``L (cos psi, sin psi)``."""
    return (2.0 * np.pi * mode + 2.0) / lam


MAX_BOXES = 200_000
MAX_LIVE = 2_000_000
"""Default bound on the co-refinement's live tuples after a round (memory: 8 r bytes each, and
their tests): beyond it the rounds stop, and the result is not complete."""


@dataclass(frozen=True, kw_only=True)
class Certified(certify.Roots):
    """A certified search of an application, with the solutions in the package's coordinates.

    Attributes
    ----------
    solutions : ndarray
        The midpoints of the root enclosures, in the coordinates of the corresponding sampled
        solver (``pinned_equilibria``: rows ``(psi, k_rel, mode)``; ``forward``:
        ``(psi_i, k_rel_i)`` per rod).
    stable : list of (bool or None)
        Per solution: True (proven stable), False (proven unstable), None (not decided).
    parts : tuple of mechnum.certify.Roots
        The searches (one per mode, or one for a mechanism), each with its certificate.
    """

    solutions: np.ndarray
    stable: list
    parts: tuple

    def certificate(self, inputs: dict | None = None) -> certify.Certificate:
        """The certificate of the one search (a certificate is made per search: for several,
        ``parts[i].certificate()``)."""
        if len(self.parts) != 1:
            raise ValueError(f"{len(self.parts)} searches (one per mode) make "
                             f"{len(self.parts)} certificates: use parts[i].certificate()")
        return self.parts[0].certificate(inputs)


def combine(parts: Sequence, solutions: np.ndarray, stable: list,
            extra: str = "") -> Certified:
    """One :class:`~mechnum.rods.certified.Certified` of several searches (counts, work added)."""
    n = parts[0].roots.shape[1] if parts else 2
    roots = np.concatenate([p.roots for p in parts] + [np.zeros((0, n, 2))])
    undecided = np.concatenate([p.undecided for p in parts] + [np.zeros((0, n, 2))])
    searched = np.concatenate([p.searched for p in parts] + [np.zeros((0, n, 2))])
    scopes = {p.scope for p in parts} or {"all"}
    if len(scopes) != 1:
        raise ValueError(f"the searches to combine must have one scope, got {sorted(scopes)}")
    complete = all(p.complete for p in parts) and not extra
    count = sum(p.count for p in parts)
    message = "; ".join(p.message for p in parts) + extra
    scope = scopes.pop()
    decided = complete or (scope == "existence" and all(p.status == "converged" for p in parts))
    return Certified(x=roots.mean(axis=2), status="converged" if decided else "undecided",
                     message=message, iterations=sum(p.iterations for p in parts),
                     nfev=sum(p.nfev for p in parts), njev=sum(p.njev for p in parts),
                     roots=roots, excluded=sum(p.excluded for p in parts),
                     undecided=undecided, scope=scope, complete=complete, count=count,
                     boxes=sum(p.boxes for p in parts), seconds=sum(p.seconds for p in parts),
                     searched=searched,
                     leaves=sum((p.leaves for p in parts), ()), solutions=solutions,
                     stable=list(stable), parts=tuple(parts))


def branch_boxes(n_rods: int) -> np.ndarray:
    """The chart's domain for ``n_rods`` rods: one box per sign pattern of the ``t_i``."""
    out = []
    for signs in np.ndindex(*(2,) * n_rods):
        box = []
        for s in signs:
            box += [CHART_BOX[0], CHART_BOX[1] if s == 0 else (-CHART_BOX[1][1], 0.0)]
        out.append(box)
    return np.array(out)


AROUND = 1e-6
"""Half-width of the boxes searched around given chart points, relative to the chart's
ranges (``2 pi`` for ``psi``, ``T_MAX`` for ``t``)."""


def around_boxes(points: ArrayLike, n_rods: int) -> np.ndarray:
    """Boxes of half-width ``AROUND`` (relative) around chart points ``(k, 2 n_rods)``, cut to
    the chart and to each point's branch (the side of ``t = 0`` it lies on).

    Examples
    --------
    >>> around_boxes([[0.0, -0.5]], 1).tolist()
    [[[0.0, 6.283185307179586e-06], [-0.5000009991677069, -0.4999990008322931]]]
    """
    points = _validate.array(points, "around", ndim=2)
    if points.shape[1] != 2 * n_rods:
        raise ValueError(f"around must be (k, {2 * n_rods}) chart points, got {points.shape}")
    psi, t = points[:, 0::2], points[:, 1::2]
    if np.any((psi < 0) | (psi > TWO_PI) | (np.abs(t) > regular.T_MAX) | (t == 0)):
        raise ValueError(f"around must be points of the chart (0 <= psi <= 2 pi, "
                         f"0 < |t| <= T_MAX), got {points.tolist()}")
    scale = np.tile([TWO_PI, regular.T_MAX], n_rods) * AROUND
    lo, hi = points - scale, points + scale
    lo[:, 0::2], hi[:, 0::2] = np.maximum(lo[:, 0::2], 0.0), np.minimum(hi[:, 0::2], TWO_PI)
    lo[:, 1::2] = np.where(t > 0, np.maximum(lo[:, 1::2], 0.0),
                           np.maximum(lo[:, 1::2], -regular.T_MAX))
    hi[:, 1::2] = np.where(t > 0, np.minimum(hi[:, 1::2], regular.T_MAX),
                           np.minimum(hi[:, 1::2], 0.0))
    return np.stack((lo, hi), axis=-1)


def around_note(around: object) -> str:
    """The message of a search around given points (its count is a lower bound)."""
    return "" if around is None else (
        f"; searched around {len(around)} given points only: the count is a lower bound")


def _ends(x: arb) -> tuple:
    """The float interval a ball stands for: the exact box of a ball from
    :func:`mechnum.certify.balls.guarded` (what the search hands a residual), else the ball's
    own bounds (rounded outward)."""
    box = interval(x)
    if box is None:
        return certify.balls.bounds(arb(x))
    return float(arb(box[0])), float(arb(box[1]))          # exact points: exact floats


def branch_of(X: list, i: int) -> int:
    """The sign of ``t`` of rod ``i`` on the box of balls ``X``: the side of ``t = 0`` that the
    box lies on, decided on the box's own float interval (:func:`_ends`), not on its ball,
    whose radius is rounded outward past ``t = 0`` when the box ends there.

    Raises
    ------
    ValueError
        If the box leaves the chart (``0 <= psi <= 2 pi``, ``|t| <= T_MAX``) or holds points of
        both branches (``t`` on both sides of 0, or the edge ``t = 0`` alone).
    """
    (p0, p1), (t0, t1) = _ends(X[2 * i]), _ends(X[2 * i + 1])
    if p0 < 0.0 or p1 > TWO_PI or t0 < -regular.T_MAX or t1 > regular.T_MAX:
        raise ValueError(f"rod {i}'s box psi in [{p0!r}, {p1!r}], t in [{t0!r}, {t1!r}] "
                         f"leaves the chart [0, 2 pi] x [-T_MAX, T_MAX]")
    if t0 < 0.0 < t1 or t0 == t1 == 0.0:
        raise ValueError(f"rod {i}'s box t in [{t0!r}, {t1!r}] holds points of both branches "
                         f"(which do not meet at t = 0): search t <= 0 and t >= 0 as separate "
                         f"boxes (branch_boxes)")
    return 1 if t1 > 0.0 else -1


def pinned_system(EI: float, L: float, target: ArrayLike, mode: int) -> tuple:
    """``residual, jacobian`` of ``tip(psi, t) - target`` (over ``L``) for :mod:`mechnum.certify`.

    Examples
    --------
    >>> from mechnum.certify.balls import ball
    >>> f, J = pinned_system(1.0, 1.0, [0.8, 0.1], 2)
    >>> [bool(v.contains(0)) for v in f([ball(3.0, 3.1), ball(0.3, 0.5)])]
    [True, True]
    """
    tx, ty = arb(float(target[0])), arb(float(target[1]))
    inv_L = 1 / arb(float(L))

    def residual(X):
        rod = balls.clamped_pinned(EI, L, X[0], X[1], mode, branch_of(X, 0))
        return [(rod.tip[0] - tx) * inv_L, (rod.tip[1] - ty) * inv_L]

    def jacobian(X):
        rod = balls.clamped_pinned(EI, L, X[0], X[1], mode, branch_of(X, 0), jacobian=True)
        return [[rod.jacobian[i][j] * inv_L for j in range(2)] for i in range(2)]

    return residual, jacobian


def certify_pinned(EI: float, L: float, target: ArrayLike, modes: Sequence = (1, 2, 3), *,
                   max_boxes: int = MAX_BOXES) -> Certified:
    """Every clamped-pinned equilibrium whose tip is at ``target``, proven by interval arithmetic.

    The certified counterpart of :func:`~mechnum.rods.pinned_equilibria` (same inputs, same
    coordinates of the solutions): a branch-and-prune search of the regular chart of each mode
    (see the module). When the result is ``complete``, the count is a theorem: there are
    exactly ``count`` equilibria of these modes with ``|t| <= T_MAX``, each in its enclosure,
    and none beyond (the tail bound of the module).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    target : array_like, shape (2,)
        The pinned point in the rod's local frame (m), nearer than ``L`` to the clamp.
    modes : iterable of int, optional
        Buckling modes (``1 <= mode <= 10``).
    max_boxes : int, optional
        Boxes tested per mode, at most ``mechnum.certify.MAX_BOXES_LIMIT``.

    Returns
    -------
    Certified
        ``solutions``: rows ``(psi, k_rel, mode)`` (the midpoints of the enclosures, sorted
        by mode); ``stable``: None for each (the stability of a pinned rod is not certified
        here); ``parts``: one search per mode, each with its ``certificate()``.

    Examples
    --------
    Chapter 3's target in mode 1: one equilibrium, a looped rod in strong tension (``k_rel``
    within ``1e-8`` of -1) that a grid in ``k_rel`` cannot reach:

    >>> r = certify_pinned(1.0, 1.0, [0.8, 0.1], modes=(1,))
    >>> r.count, r.complete, np.round(r.solutions[0, [0, 2]], 4).tolist()
    (1, True, [0.1173, 1.0])
    """
    EI = _validate.scalar(EI, "EI", positive=True)
    L = _validate.scalar(L, "L", positive=True)
    target = _validate.array(target, "target", shape=(2,))
    if np.hypot(*target) >= L:
        raise ValueError(f"target must be nearer than L = {L} to the clamp, got "
                         f"{target.tolist()}")
    modes = _validate.modes(modes, maximum=10)
    parts, rows = [], []
    for mode in modes:
        f, J = pinned_system(EI, L, target, mode)
        part = certify.roots(f, J, branch_boxes(1), max_boxes=max_boxes, scope="all")
        parts.append(part)
        for psi, t in part.x:
            rows.append((psi, float(regular.k_rel_from_t(psi, t)), mode))
    reach = 1.0 - tail_reach(max(modes, default=1))
    bounded = all(chart_t_bound(pinned_bound(mode, float(np.hypot(*target)), L))
                  < regular.T_MAX for mode in modes)
    extra = "" if np.hypot(*target) < reach * L or bounded else (
        f"; the target is farther than {reach:.3f} L: rods beyond the chart are not excluded")
    solutions = np.array(rows, dtype=float).reshape(-1, 3)
    return combine(parts, solutions, [None] * len(rows), extra)


def placed(EI: float, L: float, X: Sequence, i: int, mode: int, origin: ArrayLike,
           angle: float, jacobian: bool) -> tuple:
    """Rod ``i`` of a box of balls ``X = (psi_1, t_1, psi_2, t_2, ...)``, placed at its clamp
    (``rods._balls.place``)."""
    rod = balls.clamped_pinned(EI, L, X[2 * i], X[2 * i + 1], mode, branch_of(X, i),
                               jacobian=jacobian)
    return balls.place(rod, origin, angle)


def stiffness(rod: object) -> list:
    """The tip stiffness ``d force / d tip = J_force J_tip^-1`` of a placed rod (2 x 2 balls,
    symmetrised): the Hessian of the rod's energy as a function of its pinned tip, along its
    branch of equilibria."""
    (a, b), (c, d) = rod.jacobian[0], rod.jacobian[1]
    det = a * d - b * c
    inv = [[d / det, -b / det], [-c / det, a / det]]
    F = rod.jacobian[2:4]
    K = [[F[r][0] * inv[0][col] + F[r][1] * inv[1][col] for col in range(2)] for r in range(2)]
    off = K[0][1].union(K[1][0])
    return [[K[0][0], off], [off, K[1][1]]]


MEMORY = 4
"""Boxes whose rods :func:`memoised` remembers (a box's residual, exclusion test, Jacobian,
midpoint and cut interleave)."""


def memoised(rods: Callable) -> Callable:
    """``rods(X, jacobian)`` remembering its last ``MEMORY`` answers: the residual, the
    exclusion test, the cut and the Jacobian of one box share one evaluation of the rods (a
    Jacobian's evaluation also serves the residual). The key is the balls exactly, and the
    box each stands for."""
    memory = {}

    def cached(X, jacobian):
        key = tuple((interval(x) is not None and _ends(x), arb.mid(x).man_exp(),
                     arb.rad(x).man_exp()) for x in X)
        known = memory.get(key)
        if known is not None and (known[0] or not jacobian):
            return known[1]
        out = rods(X, jacobian)
        memory.pop(key, None)
        memory[key] = (jacobian, out)
        if len(memory) > MEMORY:
            del memory[next(iter(memory))]
        return out

    return cached


def enclosed(root: np.ndarray) -> list:
    """The balls of a root's enclosure ``(n, 2)`` (knowing their float box)."""
    return certify.balls.guarded(root)


def verdict(reduced: Sequence) -> bool | None:
    """Stability from the reduced Hessian (balls) of an equilibrium: False where it is proven
    to have a negative eigenvalue (the equilibrium is then unstable, whatever the rods' own
    pinned-tip index: the index is the sum of the rods' pinned-tip indices and the reduced
    Hessian's, by Haynsworth's inertia additivity), None otherwise (a positive definite
    reduced Hessian proves stability only with every rod stable with its tip pinned, which is
    not enclosed here)."""
    return False if certify.definite(reduced) is False else None


def _box(values):
    """Float bounds ``[(lo, hi), ...]`` of balls."""
    return [certify.balls.bounds(v) for v in values]


def _norm_range(box):
    """``(min, max)`` of ``|x|`` over a float box ``[(lo, hi), (lo, hi)]`` (arb, outward)."""
    near = [0.0 if lo <= 0.0 <= hi else min(abs(lo), abs(hi)) for lo, hi in box]
    far = [max(abs(lo), abs(hi)) for lo, hi in box]
    low = (arb(near[0]) ** 2 + arb(near[1]) ** 2).sqrt()
    high = (arb(far[0]) ** 2 + arb(far[1]) ** 2).sqrt()
    return low.lower(), high.upper()


def _arc(box):
    """The directions ``(lo, hi)`` (arb points, ``hi - lo < pi``) of a float box that excludes
    the origin, or None."""
    (x0, x1), (y0, y1) = box
    if x0 <= 0.0 <= x1 and y0 <= 0.0 <= y1:
        return None
    centre = arb.atan2(arb(0.5 * (y0 + y1)), arb(0.5 * (x0 + x1)))
    rel = []
    for x in (x0, x1):
        for y in (y0, y1):
            d = arb.atan2(arb(y), arb(x)) - centre
            d = d - 2 * balls.B.PI if bool(d > balls.B.PI) else d
            d = d + 2 * balls.B.PI if bool(d < -balls.B.PI) else d
            rel.append(d)
    lo = min((d.lower() for d in rel), key=float)
    hi = max((d.upper() for d in rel), key=float)
    return (centre + lo).lower(), (centre + hi).upper()


def _arcs_meet(a, b):
    """Whether two arcs ``(lo, hi)`` (arb points, each narrower than ``2 pi``, at any number of
    turns) may meet modulo ``2 pi``: whether an integer ``k`` has ``a_lo + 2 pi k <= b_hi``
    and ``a_hi + 2 pi k >= b_lo``, that is ``k`` in ``[(b_lo - a_hi) / 2 pi,
    (b_hi - a_lo) / 2 pi]``. The ends of that range are enclosed by Arb and rounded outward
    to integers, so the test is sound for angles of any size (a huge angle gives a wide
    range: the arcs may meet).

    Examples
    --------
    >>> turns = 2 * balls.B.PI * 10**6
    >>> _arcs_meet((arb(0.1) + turns, arb(0.2) + turns), (arb(0.15), arb(0.3)))
    True
    >>> _arcs_meet((arb(0.1) + turns, arb(0.2) + turns), (arb(0.25), arb(0.3)))
    False
    """
    two_pi = 2 * balls.B.PI
    first = ((b[0] - a[1]) / two_pi).lower().ceil()
    last = ((b[1] - a[0]) / two_pi).upper().floor()
    return not bool(last < first)


def _allowed(rods, load, i):
    """The box ``load - sum_{j != i} n_j`` that rod ``i``'s force must lie in (floats), or
    None where it is not finite."""
    c = [arb(float(load[k])) - sum((r.force[k] for j, r in enumerate(rods) if j != i), arb(0))
         for k in range(2)]
    return _box(c) if all(v.is_finite() for v in c) else None


def forces_exclude(rods: Callable, load: ArrayLike) -> Callable:
    """Whether ``sum of the rods' forces = load`` is impossible over a box, in polar form.

    For each rod ``i`` the others' forces give the box ``c = load - sum_{j != i} n_j`` that
    ``n_i`` must lie in; ``n_i`` is an annular sector (its magnitude ``R_i`` and direction
    enclosed), so the equation fails when ``R_i`` misses the range of ``|c|`` or its direction
    misses the directions of ``c``. Much stronger than the Cartesian enclosure of
    ``R (cos, sin)`` when ``R`` spans decades.
    """
    for i, rod in enumerate(rods):
        box = _allowed(rods, load, i)
        if box is None or rod.R is None:
            continue
        low, high = _norm_range(box)
        if rod.R.is_finite() and (bool(rod.R < low) or bool(rod.R > high)):
            return True
        arc = _arc(box)
        if arc is not None and rod.direction.is_finite() and rod.direction.rad() < 3:
            if not _arcs_meet(balls.B.ends(rod.direction), arc):
                return True
    return False


def forces_split(rods: Callable, load: ArrayLike, X: Sequence) -> object:
    """Where to cut the box ``X`` of chart coordinates ``(psi_1, t_1, ...)``: at an edge of the
    directions that the force balance leaves rod ``i`` (see :func:`forces_exclude`), when that
    edge lies inside ``psi_i``'s range; the half beyond it is then excluded at once. The rod
    whose allowed arc is the smallest share of its ``psi`` range is cut; None if none."""
    best = None
    for i, rod in enumerate(rods):
        box = _allowed(rods, load, i)
        arc = _arc(box) if box is not None else None
        if arc is None or rod.direction.rad() >= 3:
            continue
        lo, hi = (float(x) for x in balls.B.ends(rod.direction))
        offset = lo - _ends(X[2 * i])[0]                      # direction = psi + angle
        a0, a1 = float(arc[0]), float(arc[1])
        k = np.round((0.5 * (lo + hi) - 0.5 * (a0 + a1)) / TWO_PI)
        a0, a1 = a0 + k * TWO_PI, a1 + k * TWO_PI
        share = (min(hi, a1) - max(lo, a0)) / max(hi - lo, 1e-300)
        for edge in (a0, a1):
            if lo < edge < hi and (best is None or share < best[0]):
                best = (share, 2 * i, edge - offset)
    return None if best is None else best[1:]
