"""Every clamped-pinned equilibrium through a point, and what a rod found by shooting is.

Both questions are one equation in the regular chart ``(psi, t)`` of
``rods``'s regular module: ``tip(psi, t, mode) = point``, two equations in two unknowns,
solved by damped Newton with the chart's analytic Jacobian. The chart is smooth up to
``|t| = T_MAX`` (forces up to some ``1e5 EI / L**2``), where the study's chart ``(psi, k_rel)``
squeezes whole families of equilibria into ``1 - |k_rel| < 1e-7``: rods in tension that loop
once or more (a loop of width about ``1 / lambda`` absorbs the length that the chord does not
use). :func:`pinned_equilibria` samples the chart and polishes the candidates;
:func:`classify` names the equilibrium nearest to a rod found by RK4 shooting, or calls it
spurious: a solution of the discrete equations near which no equilibrium lies.
"""

import functools
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, newton
from mechnum.rods import _kernels as kernels
from mechnum.rods import _regular as regular
from mechnum.rods._elliptic import TWO_PI
from mechnum.rods._rod import Rod, as_modes, rod_scales

MAX_GRID = 100_000
"""Most grid cells per mode and sign of ``t`` (``n_psi * n_k``): a bound on the work and the
memory (the closed form on ``2e5`` points takes some 50 MB)."""
POLISH_MAXITER = 25
"""Newton's most steps from a candidate cell: one next to a root takes 3 to 6 (at the thesis's
point), the others wander until they stop."""
_EPS = np.finfo(float).eps
TIP_ACCEPT = 1e-10
"""A root is kept if its tip is within ``1e-10 L`` of the point."""
SAME = 1e-8
"""Two roots whose ``psi`` and ``t`` differ by less are one (the chart is well conditioned:
distinct equilibria lie far further apart)."""
RESOLVED = 1e-3
"""The largest relative gap between a rod found by shooting and its nearest equilibrium that
:func:`classify` accepts as RK4's error: a resolved rod is off by far less (``1e-6`` on the
thesis's 61 nodes), a spurious one by order one."""
START_TOL = 1e-9
"""Residual (tip distance over ``L``) at which the closed-form start of a pinned rod is good
enough: RK4 on the requested grid differs from the closed form by more."""
START_MAXITER = 60
"""Most iterations of that start's Newton (two to four on a transverse load, up to some seven
on loads within 45 degrees of transverse, from ``P L**2 / EI = 0.1`` to 15)."""
START_HALVINGS = 20
"""Most halvings of that Newton's step (as :func:`mechnum.newton.solve`'s damping by
default): a start whose step must be cut further has stopped short, and its best iterate is
the start."""
START_TABLE = np.linspace(0.0, 0.99, 67)
"""The chart's ``t`` at which the start's table of transversely loaded cantilevers is computed:
deflections up to ``0.97 L`` (``P L**2 / EI`` up to some 700; a point beyond starts from the
last)."""


def _polish(EI, L, point, mode, starts, tol, maxiter):
    """Damped Newton on ``tip(psi, t, mode) = point`` from ``starts`` (n, 2), each keeping the
    sign of its ``t``; returns the converged chart points whose tip is within
    :data:`TIP_ACCEPT` ``L``."""
    def fun(z):
        return (regular.closed_form(EI, L, z[:, 0], z[:, 1], mode, jacobian=False, check=False).tip
                - point) / L

    def jac(z):
        rod = regular.closed_form(EI, L, z[:, 0], z[:, 1], mode, check=False)
        return rod.jacobian[:, :2, :] / L

    roots = [np.empty((0, 2))]
    for sign in (-1.0, 1.0):
        rows = starts[np.sign(starts[:, 1]) == sign]
        if len(rows):
            res = newton.solve_batch(
                fun, rows, jac, tol=tol, maxiter=maxiter, criterion="residual", damping=True,
                raise_on_failure=False, independent=True,
                domain=lambda z, sign=sign: ((z[:, 0] > 0) & (z[:, 0] < TWO_PI) & (
                    sign * z[:, 1] > 0) & (np.abs(z[:, 1]) <= regular.T_MAX)))
            ok = res.x[res.converged]
            roots.append(ok[np.abs(fun(ok)).max(axis=1, initial=0.0) <= TIP_ACCEPT])
    return np.concatenate(roots)


def _distinct(z):
    """The rows of ``z`` that differ from every earlier kept row by more than :data:`SAME`."""
    kept = []
    for row in z[np.lexsort(z.T[::-1])]:
        if not any(np.abs(row - other).max() <= SAME for other in kept):
            kept.append(row)
    return np.array(kept).reshape(-1, 2)


def _candidates(tips, point):
    """Cells ``(i, j)`` of a grid of tips (n_psi, n_k, 2) that may hold a root.

    A cell whose distance to the point is a local minimum, or at most the largest change of the
    tip to a neighbour: within a cell the tip moves (to first order) by at most half of that,
    so a root in the cell needs no more (a factor two of margin).
    """
    n, m = tips.shape[:2]
    padded = np.pad(tips, ((1, 1), (1, 1), (0, 0)), constant_values=np.nan)
    dist = np.linalg.norm(tips - point, axis=-1)
    change, nearest = np.zeros((n, m)), np.full((n, m), np.inf)
    for i in (-1, 0, 1):
        for j in (-1, 0, 1):
            if i or j:
                other = padded[1 + i:1 + i + n, 1 + j:1 + j + m]
                gap = np.linalg.norm(other - tips, axis=-1)
                change = np.fmax(change, gap)
                nearest = np.fmin(nearest, np.linalg.norm(other - point, axis=-1))
    return np.nonzero((dist <= change) | (dist <= nearest))


def pinned_equilibria(EI: float, L: float, tip: ArrayLike, modes: Iterable[int] = (1, 2, 3), *,
                      n_psi: int = 120, n_k: int = 60, tol: float = 1e-13,
                      chart: str = "k_rel") -> np.ndarray:
    """Every clamped-pinned equilibrium of the given modes whose tip is at ``tip``.

    For each mode the regular chart ``(psi, t)`` (``rods``'s regular module) is sampled on a
    grid of ``n_psi`` directions ``psi`` in ``(0, 2 pi)`` by ``n_k`` values of ``|t|`` in
    ``(0, T_MAX)`` on each side of ``t = 0``; every cell that may hold a root (its distance to
    the point is a local minimum, or no larger than the change of the tip to a neighbour)
    seeds damped Newton (:func:`mechnum.newton.solve_batch`) with the chart's analytic
    Jacobian, and a root is kept if its tip is within :data:`TIP_ACCEPT` ``L`` of the point.
    This reaches the rods that loop in tension, whose ``1 - |k_rel|`` is below ``1e-7``.
    Sampling is evidence, not proof: a root in a cell much smaller than the grid's could be
    missed (refine the grid to check; at the thesis's point a grid a quarter of the default
    finds the same roots).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    tip : array_like, shape (2,)
        The pinned point in the local frame (m), closer than ``L`` to the clamp.
    modes : iterable of int, optional
        Buckling modes searched.
    n_psi, n_k : int, optional
        Grid size per mode: ``n_psi`` directions by ``n_k`` values of ``|t|`` on each sign,
        ``n_psi * n_k <=`` :data:`MAX_GRID`.
    tol : float, optional
        Newton's tolerance on the tip's distance from the point, relative to ``L``.
    chart : {"k_rel", "t"}, optional
        The second column of the result: the study's ``k_rel`` or the chart's ``t``.

    Returns
    -------
    ndarray, shape (n, 3)
        Rows ``(psi, k_rel, mode)`` (or ``(psi, t, mode)``), sorted by mode then force;
        ``n >= 0``.

    Raises
    ------
    ValueError
        If an input is malformed or out of range, or (``chart="k_rel"``) an equilibrium's
        ``k_rel`` is within rounding of ``+-1``, which that chart cannot hold (``chart="t"``
        can).

    Examples
    --------
    The thesis's point: one mode-1 rod (a loop in tension) and four of mode 2, two of them
    looped.

    >>> sols = pinned_equilibria(1.0, 1.0, [0.8, 0.1], modes=(1, 2))
    >>> sols[:, 2].tolist(), np.round(sols[1:3, :2], 4).tolist()
    ([1.0, 2.0, 2.0, 2.0, 2.0], [[3.4872, -0.3223], [3.0352, 0.4212]])
    """
    EI, L = rod_scales(EI, L, scalar=True)
    tip = _validate.array(tip, "tip", shape=(2,))
    if np.hypot(*tip) >= L:
        raise ValueError(f"tip must be one point closer than L = {L} to the clamp, got {tip!r}")
    modes = [int(m) for m in as_modes(_validate.modes(modes)).ravel()]
    n_psi = _validate.maxiter(n_psi, "n_psi", maximum=MAX_GRID)
    n_k = _validate.maxiter(n_k, "n_k", maximum=MAX_GRID)
    if n_psi * n_k > MAX_GRID:
        raise ValueError(f"n_psi * n_k must be at most {MAX_GRID} (a bound on the work), got "
                         f"{n_psi} * {n_k}")
    tol = _validate.tolerance(tol)
    chart = _validate.choice(chart, ("k_rel", "t"), "chart")
    psi = (np.arange(n_psi) + 0.5) / n_psi * TWO_PI
    t = (np.arange(n_k) + 0.5) / n_k * regular.T_MAX
    rows = []
    for mode in modes:
        starts = []
        for sign in (-1.0, 1.0):
            P, T = np.meshgrid(psi, sign * t, indexing="ij")
            tips = regular.closed_form(EI, L, P, T, mode, jacobian=False, check=False).tip
            cells = _candidates(tips, tip)
            starts.append(np.column_stack((P[cells], T[cells])))
        z = _distinct(_polish(EI, L, tip, mode, np.concatenate(starts), tol, POLISH_MAXITER))
        rows += [(p, s, mode) for p, s in z]
    if not rows:
        return np.empty((0, 3))
    sols = np.array(rows)
    R = np.hypot(*regular.closed_form(EI, L, sols[:, 0], sols[:, 1], sols[:, 2],
                                      jacobian=False).force.T)
    sols = sols[np.lexsort((R, sols[:, 2]))]
    if chart == "k_rel":
        k_rel = regular.k_rel_from_t(sols[:, 0], sols[:, 1])
        if np.any(np.abs(k_rel) >= 1):
            raise ValueError(f"an equilibrium's k_rel rounds to +-1 ({_validate.shown(k_rel)})"
                             f": ask for chart='t', which holds it")
        sols[:, 1] = k_rel
    return sols


@dataclass(frozen=True)
class Classification:
    """What :func:`classify` makes of a rod.

    Attributes
    ----------
    kind : str
        ``"elastica"`` (a clamped-pinned equilibrium to RK4's error), ``"straight"`` (the
        straight rod under an axial force) or ``"spurious"`` (no equilibrium near it).
    psi, k_rel, mode : float
        The equilibrium's closed form (NaN unless an elastica).
    R : float
        The rod's force magnitude (N).
    lambda_h : float
        ``sqrt(R / EI)`` times the rod's node spacing: RK4 resolves ``lambda h`` well below 1.
    gap : float
        The relative gap between the rod and the equilibrium (NaN if there is none).
    reason : str
        Why, in words.
    """

    kind: str
    psi: float
    k_rel: float
    mode: float
    R: float
    lambda_h: float
    gap: float
    reason: str

    def __str__(self) -> str:
        if self.kind == "elastica":
            return f"mode {self.mode:.0f}, k_rel {self.k_rel:+.3f}, R {self.R:6.3f} N"
        if self.kind == "straight":
            return f"the straight rod, R {self.R:6.3f} N"
        return (f"no elastica (R {self.R:.0f} N, lambda h {self.lambda_h:.1f}): a spurious "
                f"solution of the discrete equations")


def classify(EI: float, L: float, rod: Rod, *, tol: float = RESOLVED) -> Classification:
    """The clamped-pinned equilibrium that a rod (found by shooting) approximates, if any.

    A rod with no moment at its tip is pinned there. Its clamp moment and force give a first
    guess of the equilibrium (its chart point, as :func:`mechnum.rods.elliptic_parameters`
    finds it, in the rod's clamp frame; its mode, one more than the sign changes of its moment
    before the tip); Gauss-Newton in the regular chart then finds the equilibrium of that mode
    nearest to the rod (its tip, force and clamp moment together, relative to ``L``, ``max(R, EI /
    L**2)`` and ``max(|m0|, R L, EI / L)``), and the rod is that equilibrium if they agree to
    ``tol``. Otherwise it is a spurious solution of the discrete (RK4) equations: at a step
    ``h`` with ``lambda h`` near 1 or beyond, or in tension strong enough that RK4's error,
    amplified along the rod, moves its tail (a rod whose moment never vanishes, ``|k| >= 1``,
    is spurious unless RK4's error put it there, just across the edge of the family from a
    looped equilibrium).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m) of the rod.
    rod : Rod
        One rod (any clamp pose), with ``m(L)`` zero to its solver's tolerance.
    tol : float, optional
        The largest relative gap accepted as RK4's error.

    Returns
    -------
    Classification

    Examples
    --------
    >>> from mechnum import rods
    >>> shot = rods.shoot_pinned(1.0, 1.0, [0.8, 0.1], [4.0, -20.0, 2.0], nodes=61).rod
    >>> print(classify(1.0, 1.0, shot))
    mode 2, k_rel +0.421, R 23.691 N
    """
    EI, L = rod_scales(EI, L, scalar=True)
    tol = _validate.tolerance(tol)
    if not isinstance(rod, Rod) or np.ndim(rod.x) != 1 or len(rod.x) < 2:
        raise ValueError(f"rod must be one Rod of at least 2 nodes, got {type(rod).__name__}")
    c, s = np.cos(rod.theta[0]), np.sin(rod.theta[0])
    rot = np.array([[c, s], [-s, c]])                    # into the clamp's frame
    force = rot @ rod.force
    point = rot @ (rod.tip - [rod.x[0], rod.y[0]])
    m0, R = float(rod.m[0]), float(np.hypot(*force))
    lambda_h = float(np.sqrt(R / EI) * (rod.s[1] - rod.s[0]))
    M, F = max(abs(m0), R * L, EI / L), max(R, EI / L ** 2)

    def outcome(kind, reason, psi=np.nan, k_rel=np.nan, mode=np.nan, gap=np.nan):
        return Classification(kind, float(psi), float(k_rel), float(mode), R, lambda_h,
                              float(gap), reason)

    if abs(m0) <= tol * M and abs(force[1]) <= tol * F and abs(point[1]) <= tol * L:
        return outcome("straight", "no moment at the clamp and an axial force")
    psi = float(np.mod(np.arctan2(force[1], force[0]), TWO_PI))
    if psi == 0.0:
        return outcome("spurious", "a moment at the clamp and a force along the clamped tangent")
    # the start: psi, and t from v = k cos(phi1) / sin(psi/2) (elliptic_parameters' v, taken
    # just inside the family where RK4's error put the rod across its edge, |k| >= 1); the
    # mode: one more than the moment's sign changes before the tip
    v = abs(m0) / (2.0 * EI * np.sqrt(R / EI) * np.sin(0.5 * psi))
    q = min(-np.log(max((1.0 - min(v, 1.0)) * (1.0 + min(v, 1.0)), _EPS)), regular.Q_MAX)
    t0 = np.copysign(max(np.sqrt(q / (1.0 + q)), 1e-8), m0 if m0 else 1.0)
    m = rod.m[:-1][np.abs(rod.m[:-1]) > _EPS * M]
    mode = 1.0 + np.count_nonzero(np.diff(np.sign(m)))
    scales = np.array([L, L, F, F, M])
    target = np.array([*point, *force, m0])

    def gaps(z):              # the rod against the equilibrium z: tip, force, clamp moment
        near = regular.closed_form(EI, L, z[0], z[1], mode)
        value = np.array([*near.tip, *near.force, float(near.clamp_moment)])
        return (value - target) / scales, near.jacobian / scales[:, None]

    z = _nearest(gaps, np.array([psi, t0]))
    gap = float(np.abs(gaps(z)[0]).max())
    if gap > tol:
        edge = "; its moment never vanishes (|k| >= 1)" if v >= 1 else ""
        return outcome("spurious", f"the nearest equilibrium of mode {mode:.0f} is {gap:.2g} "
                                   f"away (relative){edge}", gap=gap)
    return outcome("elastica", "an equilibrium to RK4's error", z[0],
                   regular.k_rel_from_t(z[0], z[1]), mode, gap)


def _nearest(gaps, z):
    """Gauss-Newton from ``z`` on ``gaps(z) -> (residual, Jacobian)`` in the chart, each step
    halved until it decreases the residual and keeps ``psi`` and ``t`` in the chart (``t`` of
    its start's sign): the chart point nearest to a rod in the least-squares sense. Both the
    tip and the force enter it, so it is well posed where either alone is not (the force of a
    nearly straight rod is ill-determined by its tip)."""
    def inside(z):
        return 0 < z[0] < TWO_PI and 0 < z[1] * sign <= regular.T_MAX

    sign = np.sign(z[1])
    r, J = gaps(z)
    for _ in range(POLISH_MAXITER):
        step = np.linalg.lstsq(J, -r, rcond=None)[0]
        for _ in range(30):
            if inside(z + step) and np.linalg.norm(gaps(z + step)[0]) < np.linalg.norm(r):
                break
            step = 0.5 * step
        else:
            return z
        z = z + step
        r, J = gaps(z)
        if np.abs(step).max() <= 1e-14 * (1.0 + np.abs(z).max()):
            return z
    return z


@functools.cache
def _transverse_table():
    """``(y(L) / L, P L**2 / EI)`` of cantilevers under a transverse tip load ``P`` (the growing
    branch of mode 1 at ``psi = pi / 2``) at ``t`` in :data:`START_TABLE` (computed once)."""
    rod = regular.closed_form(1.0, 1.0, 0.5 * np.pi, START_TABLE[1:], 1, jacobian=False)
    return (np.concatenate(([0.0], rod.tip[:, 1])),
            np.concatenate(([0.0], np.hypot(rod.force[:, 0], rod.force[:, 1]))))


def pinned_start(EI: float, L: float, points: np.ndarray, theta0: float) -> np.ndarray:
    """The closed-form cantilevers through points: the default start of
    :func:`mechnum.rods.shoot_pinned`, ``(m0, n_x, n_y)`` of shape (batch, 3).

    A pinned tip carries no moment, so a pinned rod of mode 1 is the cantilever (growing
    branch) under its tip force. Damped Newton drives the closed form's tip to the point in
    the force's components ``n L**2 / EI`` in the clamp's frame (in which the tip of a nearly
    straight rod is nearly linear: its deflection follows ``n_y``, its shortening ``n_x``
    weakly), with the analytic Jacobian of the regular chart (compiled,
    ``rods``'s kernels module, ``pinned_starts``), from the transverse load whose cantilever
    deflects as far as the point does: interpolated in a table of the closed form
    (:func:`_transverse_table`; linear beam theory, ``3 EI Y / L**3`` for the point's offset
    ``Y`` from the clamp line, at small loads). If Newton stops short (no mode-1 rod reaches
    the point, or a nearly straight rod leaves its axial force ill-determined), its last
    iterate, the best, is the start.

    Examples
    --------
    >>> from mechnum.rods._growing import growing_rod
    >>> tip = growing_rod(1.0, 1.0, [0.0, 1.0]).tip              # P L^2/EI = 1
    >>> (np.round(pinned_start(1.0, 1.0, tip[None], 0.0), 6) + 0.0).tolist()
    [[0.943567, 0.0, 1.0]]
    """
    EI, L, theta0 = _validate.numbers(dict(EI=EI, L=L, theta0=theta0), positive=("EI", "L"))
    points = _validate.array(points, "points", shape=(None, 2))
    deflections, loads = _transverse_table()
    c, s = np.cos(theta0), np.sin(theta0)
    X, Y = (c * points[:, 0] + s * points[:, 1]) / L, (c * points[:, 1] - s * points[:, 0]) / L
    n_y = np.copysign(np.interp(np.abs(Y), deflections, loads), Y)
    n_y = np.where(n_y == 0.0, np.copysign(3.0 * _EPS, Y), n_y)   # on the clamp line
    start = kernels.pinned_starts(np.column_stack((X, Y)), np.column_stack((0.0 * Y, n_y)),
                                  tol=START_TOL, maxiter=START_MAXITER,
                                  halvings=START_HALVINGS)
    n = start[:, 1:] * EI / L ** 2
    return np.column_stack((start[:, 0] * EI / L, c * n[:, 0] - s * n[:, 1],
                            s * n[:, 0] + c * n[:, 1]))
