"""RK4 shooting of planar Kirchhoff rods (conventions: see :mod:`mechnum.rods`).

The shooting solvers wrap damped Newton (:func:`mechnum.newton.solve`, or ``solve_batch`` for a
batch of rods) around the RK4 sweeps of ``rods``'s rod module and their complex-step
Jacobians, from a start that lands on the intended equilibrium: the closed form of the growing
branch (``rods``'s growing module) by default. They return a :class:`Shooting`, a result
of the package's contract (:mod:`mechnum.results`).

**What shooting can resolve.** The tip depends on the clamp moment through the whole rod, and
``d m(L) / d m0`` grows quickly with the load (about ``1e4`` at ``lambda L = 10``, with
``lambda = sqrt(|n| / EI)``; without bound on a grid too coarse for RK4), so the rounding of
``m0`` reaches the tip multiplied by that factor. Newton stops when the residual is below
``tol`` or below that floor (:data:`ROUNDOFF_FACTOR` ulps of the start's unknowns, amplified
by the start's Jacobian), and refuses a rod whose floor exceeds :data:`MAX_FLOOR`: beyond it,
multiple shooting (:func:`shoot_pinned_multiple`), more nodes or the closed form is needed.

**Spurious rods.** RK4's error, amplified along a rod in tension by about ``exp(lambda L)``,
can move the tail of the discrete rod far from every equilibrium: Newton then converges, to a
solution of the discrete equations that is no rod (a cantilever at ``P L**2 / EI = 1e3`` on 41
nodes, whose tip is ``0.75 L`` from the true one). It happens where ``lambda L + 4 ln(lambda h)``
exceeds about 7 (``h`` the node spacing; measured from 21 to 161 nodes). Above
:data:`RISK` every solver compares its rod with the nearest equilibrium
(:func:`mechnum.rods.classify`; for a cantilever from its default start, with the closed
form) and raises :class:`UnresolvedRodError` rather than return a spurious rod.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, newton
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.results import Result
from mechnum.rods._growing import growing_rod
from mechnum.rods._pinned import RESOLVED, classify, pinned_start
from mechnum.rods._rod import MAX_NODES, Rod, as_vectors, integrate, rod_scales, tip_states

_EPS = np.finfo(float).eps
SHOOTING_TOL = 1e-12
"""The default residual tolerance of pinned shooting (:func:`shoot_pinned`, and the flexible
mechanisms built on it): well above the rounding floor of rods of a few hundred nodes."""
MAX_ITER = 10_000
"""Most Newton iterations any solver here accepts (a bound on the work)."""
ROUNDOFF_FACTOR = 64.0
"""Ulps of rounding allowed in the unknowns before amplification (a margin of some ten over the
``sqrt(nodes)`` ulps that a sweep of a few hundred steps accumulates)."""
MAX_FLOOR = 1e-6
"""Largest residual floor accepted: a rod whose rounding alone leaves a relative residual of
``1e-6`` (``d m(L) / d m0`` near ``1e8``, ``lambda L`` near 18) is beyond single shooting."""
BRACKET_DOUBLINGS = 12
"""Steps of the search for a sign change of ``m(L)`` from a start where damped Newton fails:
from an eighth of the moment scale ``max(|n| L, EI / L)`` up to 256 times it."""
BISECTIONS = 10
"""Halvings of that bracket before Newton takes over: a thousandth of its width, well inside
Newton's quadratic basin of a simple root."""
RISK = 0.0
"""Above this value of ``lambda L / segments + 4 ln(lambda h)`` a solver checks that its rod is
an equilibrium to RK4's error (the module's description); below, RK4's amplified error is
some ``exp(-7)`` of what makes a spurious rod."""
RESOLVE_LOG = 4.0
"""The value of ``lambda L + 4 ln(lambda h)`` at which :class:`UnresolvedRodError` suggests
a node count (a margin below the observed threshold, about 7)."""


class UnresolvedRodError(ConvergenceError):
    """Shooting converged to a solution of the discrete (RK4) equations that is no equilibrium
    of the rod (or, from a cantilever's default start, another one): more nodes, multiple
    shooting or the closed form is needed. ``result`` holds the :class:`Shooting` (None where
    Newton failed first on a load the nodes cannot resolve)."""


@dataclass(frozen=True, kw_only=True)
class Shooting(Result):
    """A rod found by shooting, with the Newton iteration that found it.

    Attributes
    ----------
    x : ndarray, shape (...) or (..., 3)
        The unknowns at the solution: ``m0`` for a cantilever, ``(m0, n_x, n_y)`` for a pinned
        rod (one per rod of a batch).
    status, message, iterations, nfev, njev
        As in :class:`mechnum.results.Result` (one status and iteration count per rod of a
        batch; ``nfev`` and ``njev`` count RK4 sweeps of the residual and of the Jacobian).
    rod : Rod
        The rod at the solution.
    newton : NewtonResult or BatchNewtonResult
        The iteration on the requested grid.
    start : ndarray, shape (...) or (..., 3)
        The unknowns that iteration started from.
    """

    rod: Rod
    newton: object
    start: np.ndarray


class _Tips:
    """The tips of rods clamped at the origin at ``theta0`` as a function of the unknowns
    ``p`` (batch, k), which ``split(p)`` maps to ``(m0, force)``; ``columns`` says which of
    ``(m0, n_x, n_y)`` they are. Newton asks for the residual and then the Jacobian at the same
    point: a memo of the last sweep serves both (until :func:`mechnum.newton.solve` takes a
    function that returns both)."""

    def __init__(self, EI, L, theta0, nodes, split, columns):
        self.args, self.split, self.columns = (EI, L), split, columns
        self.theta0, self.nodes = theta0, nodes
        self.key, self.value, self.nfev, self.njev = None, None, 0, 0

    def __call__(self, p, jac=False):
        self.nfev, self.njev = self.nfev + (not jac), self.njev + jac
        key = p.tobytes()
        if key != self.key or (jac and self.value[1] is None):
            self.value = tip_states(*self.args, *self.split(p), self.theta0, self.nodes,
                                    self.columns if jac else ())
            self.key = key
        return self.value


def _floor(J, scale_in, scale_out, p):
    """The rounding floor of a residual: ``ROUNDOFF_FACTOR`` ulps of the unknowns, amplified."""
    J = np.abs(J) * scale_in[..., None, :] / scale_out[..., :, None]
    size = np.maximum(np.abs(p / scale_in).max(axis=-1), 1.0)
    return float(np.max(J.max(axis=(-2, -1)) * size, initial=0.0)) * ROUNDOFF_FACTOR * _EPS


def _solve(fun, jac, x0, tol, floor, maxiter, what, damping=True):
    """Damped Newton from ``x0`` (batch, k): one system by ``solve``, a batch by
    ``solve_batch``; the tolerance is raised to the rounding floor ``floor``."""
    if floor > MAX_FLOOR:
        raise ConvergenceError(
            f"{what}: rounding in the unknowns reaches the tip amplified by "
            f"{floor / _EPS / ROUNDOFF_FACTOR:.3g} (d tip / d unknowns): single shooting cannot "
            f"resolve this rod (use more nodes, multiple shooting or the closed form)")
    tol = max(tol, floor)
    if len(x0) == 1:
        k = x0.shape[1]
        res = newton.solve(lambda p: fun(p.reshape(-1, k)).reshape(p.shape), x0[0],
                           lambda p: jac(p[None])[0], tol=tol, maxiter=maxiter,
                           criterion="residual", damping=damping)
        return res, res.x[None], tol
    res = newton.solve_batch(fun, x0, jac, tol=tol, maxiter=maxiter, criterion="residual",
                             damping=damping)
    return res, res.x, tol


def _reshaped(rod, batch):
    """``rod`` with its leading axis reshaped to ``batch`` (``()`` for one rod)."""
    return Rod(*(getattr(rod, name).reshape(batch + getattr(rod, name).shape[1:])
                 for name in ("s", "x", "y", "theta", "m", "force")))


def shooting_result(what: str, res: object, p: np.ndarray, start: np.ndarray, rod: Rod,
                    batch: tuple, tol: float, counts: object) -> Shooting:
    """The :class:`Shooting` of a converged Newton ``res`` (one system or a batch), for the
    solvers built on shooting: ``p`` and ``start`` of shape ``(n,)`` or ``(n, k)``, ``rod``
    with a leading axis of ``n`` rods, reshaped to ``batch``; ``counts`` has ``nfev`` and
    ``njev``.

    Examples
    --------
    >>> res = shoot_cantilever(1.0, 1.0, [[0.0, 1.0], [0.0, 2.0]])
    >>> again = shooting_result("again", res.newton, res.x, res.start, res.rod, (2,), 1e-13,
    ...                         res)
    >>> again.status.tolist(), again.x.shape
    (['converged', 'converged'], (2,))
    """
    status, iterations = getattr(res, "status", "converged"), np.reshape(res.iterations, batch)
    most = int(np.max(iterations, initial=0))
    if batch == ():         # one rod: a word and an int, as scipy's results have
        status, iterations = str(np.reshape(status, -1)[0]), most
    else:
        status = np.reshape(status, batch)
    return Shooting(x=p.reshape(batch + p.shape[1:]), status=status,
                    message=f"{what}: converged, residual below {tol:.3g} in at most {most} "
                            f"Newton iterations",
                    iterations=iterations, nfev=counts.nfev, njev=counts.njev,
                    rod=_reshaped(rod, batch), newton=res,
                    start=start.reshape(batch + start.shape[1:]))


def _risk(EI, L, force, h, segments=1):
    """``lambda L / segments + 4 ln(lambda h)`` of each rod (see :data:`RISK`)."""
    lam = np.sqrt(np.hypot(force[..., 0], force[..., 1]) / EI)
    with np.errstate(divide="ignore"):
        return lam * L / segments + 4.0 * np.log(lam * h)


def _advice(lam_L, what="multiple shooting or the closed form"):
    """What resolves a rod of ``lambda L`` (per segment): the nodes at which ``lambda L +
    4 ln(lambda h) = RESOLVE_LOG``, if single shooting's rounding floor allows it."""
    if ROUNDOFF_FACTOR * _EPS * math.exp(lam_L) > MAX_FLOOR:
        return f"it is beyond single shooting at any node count: use {what}"
    nodes = math.ceil(1.0 + lam_L * math.exp((lam_L - RESOLVE_LOG) / 4.0))
    return f"use more nodes (about {nodes}) or {what}"


def _unresolvable(EI, L, force, nodes, error):
    """Raise :class:`UnresolvedRodError` from Newton's ``error`` if RK4 on ``nodes`` cannot
    resolve a rod under ``force`` (``lambda L + 4 ln(lambda h)`` above :data:`RESOLVE_LOG`):
    the failure is then the grid's, and more nodes is the remedy to name."""
    lam_L = math.sqrt(math.hypot(*force) / EI) * L
    if float(_risk(EI, L, np.asarray(force), L / (nodes - 1))) > RESOLVE_LOG:
        raise UnresolvedRodError(
            f"shoot_cantilever: RK4 on {nodes} nodes cannot resolve the rod under the force "
            f"{np.asarray(force).tolist()} (P L^2/EI = {lam_L ** 2:.4g}, lambda h = "
            f"{lam_L / (nodes - 1):.3g}), and Newton failed ({error}); "
            f"{_advice(lam_L, 'rods.cantilever')}", None) from error


def check_resolved(EI: float, L: float, result: Shooting, segments: int = 1) -> None:
    """Raise :class:`UnresolvedRodError` if a rod of ``result`` at risk (:data:`RISK`, with
    ``lambda L`` per segment) is no equilibrium to RK4's error
    (:func:`mechnum.rods.classify`): the check of every solver built on shooting.

    Examples
    --------
    >>> check_resolved(1.0, 1.0, shoot_pinned(1.0, 1.0, [0.8, 0.1], [4.0, -20.0, 2.0]))
    """
    nodes = result.rod.s.shape[-1]
    rods = Rod(*(np.reshape(getattr(result.rod, name), (-1, nodes))
                 for name in ("s", "x", "y", "theta", "m")), result.rod.force.reshape(-1, 2))
    for i in np.flatnonzero(_risk(EI, L, rods.force, L / (nodes - 1), segments) > RISK):
        one = Rod(*(getattr(rods, name)[i] for name in ("s", "x", "y", "theta", "m", "force")))
        verdict = classify(EI, L, one)
        if verdict.kind == "spurious":
            lam_L = math.sqrt(verdict.R / EI) * L
            raise UnresolvedRodError(
                f"rod {i}: RK4 on {nodes} nodes cannot resolve it (lambda h = "
                f"{verdict.lambda_h:.3g}, lambda L = {lam_L:.3g}): {verdict.reason}; "
                f"{_advice(lam_L / segments)}", result)


def _cantilever_start(EI, L, forces, theta0):
    """Clamp moments and tips (batch, 2) of the closed-form cantilevers (mode 1, growing
    branch) under ``forces`` (batch, 2), clamped at ``theta0``; a straight rod where the force
    is axial."""
    c, s = math.cos(theta0), math.sin(theta0)
    m0, tips = np.zeros(len(forces)), np.tile([c * L, s * L], (len(forces), 1))
    for i, (nx, ny) in enumerate(forces.tolist()):
        local = (c * nx + s * ny, c * ny - s * nx)
        if local[1] != 0:
            rod = growing_rod(EI, L, local)
            m0[i], (x, y) = rod.m[0], rod.tip
            tips[i] = c * x - s * y, s * x + c * y
    return m0, tips


def _bracket(g, x, width):
    """A start for Newton on the scalar ``g`` where it changes sign nearest ``x``.

    Points ``x +- width 2**j / 8`` are tried on both sides, outwards, until ``g`` changes sign
    between neighbours; that bracket is halved :data:`BISECTIONS` times and its midpoint
    returned, shape (1, 1). Raises :class:`ConvergenceError` if no sign change is found.
    """
    last = {-1.0: (x, g(x)), 1.0: (x, g(x))}
    for step in width / 8 * 2.0 ** np.arange(BRACKET_DOUBLINGS):
        for direction in (-1.0, 1.0):
            (near, g_near), far = last[direction], x + direction * step
            g_far = g(far)
            if g_near * g_far <= 0:
                for _ in range(BISECTIONS):
                    mid = 0.5 * (near + far)
                    near, far = (mid, far) if g(mid) * g_far > 0 else (near, mid)
                return np.array([[0.5 * (near + far)]])
            last[direction] = far, g_far
    raise ConvergenceError(f"shoot_cantilever: m(L) changes sign nowhere within "
                           f"{step:.3g} N m of the start {x!r}")


def _controls(EI, L, theta0, nodes, tol, maxiter, damping):
    """The checked common arguments of the single-shooting solvers."""
    EI, L = rod_scales(EI, L, scalar=True)
    return (EI, L, _validate.scalar(theta0, "theta0"),
            _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES),
            _validate.tolerance(tol), _validate.maxiter(maxiter, maximum=MAX_ITER),
            _validate.flag(damping, "damping"))


def _batch(value, name, size):
    """``value`` with a last axis of ``size``, of shape ``(size,)`` or ``(batch, size)``."""
    value = as_vectors(value, name, size)
    if value.ndim > 2:
        raise ValueError(f"{name} must have shape ({size},) or (batch, {size}), got shape "
                         f"{value.shape}")
    return value


def shoot_cantilever(EI: float, L: float, force: ArrayLike, *, m0: ArrayLike | None = None,
                     theta0: float = 0.0, nodes: int = 41, tol: float = 1e-13,
                     maxiter: int = 50, damping: bool = True) -> Shooting:
    """A cantilever under a given tip force, by shooting on the clamp moment.

    Damped Newton (:func:`mechnum.newton.solve`) adjusts ``m0`` until ``m(L) = 0``, with the
    exact Jacobian of the RK4 sweep. The equilibrium found depends on the start: the default
    is the clamp moment of the closed form (:func:`mechnum.rods.cantilever`), the equilibrium
    that grows continuously from the unloaded rod (mode 1, bending towards the force), which
    RK4 on ``nodes`` nodes then reproduces to its discretisation error in one or two Newton
    steps; from that start the rod returned is that equilibrium, its tip within
    ``RESOLVED = 1e-3`` ``L`` of the closed form's, or the solver raises. A
    start of your own may lead elsewhere (above the Euler load, to the rod bent the other way).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    force : array_like, shape (2,) or (batch, 2)
        Tip force (N), one or a batch (possibly empty).
    m0 : float or array_like, optional
        Start of the clamp moment (N m), one or one per force.
    theta0 : float, optional
        Clamp angle (rad); the clamp is at the origin.
    nodes : int, optional
        RK4 nodes, ``2 <= nodes <=`` ``MAX_NODES = 100_000``.
    tol, maxiter
        Newton stops when ``|m(L)| < tol * max(|n| L, EI / L)`` (a residual relative to the
        moments of the problem), or below the rounding floor of the module's description if
        that is larger; most iterations (at most :data:`MAX_ITER`).
    damping : bool, optional
        Backtrack along Newton's steps (Armijo); for one rod, if damped Newton still fails,
        restart from the sign change of ``m(L)`` nearest the start. ``False`` is plain Newton.

    Returns
    -------
    Shooting

    Raises
    ------
    ValueError
        If an input is not finite, of the wrong shape, or out of range.
    ConvergenceError, SingularJacobianError
        If Newton fails, or the rod is beyond what single shooting resolves.
    UnresolvedRodError
        If the rod found is no equilibrium to RK4's error (or, from the default start, another
        equilibrium than the closed form's): the load needs more nodes.

    Examples
    --------
    >>> res = shoot_cantilever(1.0, 1.0, [0.0, 1.0])      # Bisshopp-Drucker, P L^2 / EI = 1
    >>> np.round(res.rod.tip, 4).tolist(), res.iterations, res.status
    ([0.9436, 0.3017], 1, 'converged')
    """
    EI, L, theta0, nodes, tol, maxiter, damping = _controls(EI, L, theta0, nodes, tol, maxiter,
                                                            damping)
    force = _batch(force, "force", 2)
    batch = force.reshape(-1, 2)
    exact = None
    if m0 is None:
        start, exact = _cantilever_start(EI, L, batch, theta0)
    else:
        m0 = _validate.array(m0, "m0")
        if m0.size not in (1, len(batch)):
            raise ValueError(f"m0 must be one start or one per force ({len(batch)}), got shape "
                             f"{m0.shape}: the shapes do not broadcast")
        start = np.broadcast_to(m0.reshape(-1), batch.shape[:1]).copy()
    tips = _Tips(EI, L, theta0, nodes, lambda p: (p[:, 0], batch), (0,))
    scale = max(float(np.abs(batch).max(initial=0.0)) * L, EI / L)

    def fun(p):
        return tips(p)[0][:, 3:] / scale

    def jac(p):
        return tips(p, jac=True)[1][:, 3:, :] / scale

    x0 = start[:, None]
    floor = _floor(jac(x0), np.ones(1), np.ones(1), x0 / scale)
    try:
        res, p, tol = _solve(fun, jac, x0, tol, floor, maxiter, "shoot_cantilever", damping)
    except (ConvergenceError, SingularJacobianError):
        if len(batch) != 1 or not damping:
            raise
        # a start beyond a hump of m(L): restart from the sign change of m(L) nearest it
        try:
            x0 = _bracket(lambda m0: float(fun(np.array([[m0]]))[0, 0]), float(x0[0, 0]), scale)
            res, p, tol = _solve(fun, jac, x0, tol, floor, maxiter, "shoot_cantilever")
        except ConvergenceError as error:
            _unresolvable(EI, L, batch[0], nodes, error)
            raise
    rod = integrate(EI, L, p[:, 0], batch, theta0=theta0, nodes=nodes)
    result = shooting_result("shoot_cantilever", res, p[:, 0], start, rod, force.shape[:-1],
                             tol, tips)
    if exact is None:
        check_resolved(EI, L, result)
        return result
    off = np.abs(rod.tip - exact).max(axis=-1, initial=0.0) / L
    if np.any(off > RESOLVED):
        i = int(np.argmax(off))
        lam_L = math.sqrt(math.hypot(*batch[i]) / EI) * L
        raise UnresolvedRodError(
            f"shoot_cantilever: RK4 on {nodes} nodes cannot resolve the rod under the force "
            f"{batch[i].tolist()} (P L^2/EI = {lam_L ** 2:.4g}, lambda h = "
            f"{lam_L / (nodes - 1):.3g}): Newton from the closed form's clamp moment ended on "
            f"a rod whose tip is {off[i]:.2g} L from the closed form's; "
            f"{_advice(lam_L, 'rods.cantilever')}", result)
    return result


def _pinned(EI, L, points, x0, theta0, nodes, tol, maxiter, damping):
    """Damped Newton on the pinned-tip residual from ``x0`` (batch, 3): (result, unknowns,
    tolerance, memo)."""
    tips = _Tips(EI, L, theta0, nodes, lambda p: (p[:, 0], p[:, 1:]), (0, 1, 2))
    scale_in = np.array([EI / L, EI / L ** 2, EI / L ** 2])      # m0, n_x, n_y
    scale_out = np.array([L, L, EI / L])                          # x, y, m at the tip

    def fun(p):
        end = tips(p)[0]
        return np.column_stack((end[:, :2] - points, end[:, 3])) / scale_out

    def jac(p):
        return tips(p, jac=True)[1][:, [0, 1, 3], :] / scale_out[:, None]

    floor = _floor(jac(x0) * scale_out[:, None], scale_in, scale_out, x0)
    return *_solve(fun, jac, x0, tol, floor, maxiter, "shoot_pinned", damping), tips


def shoot_pinned(EI: float, L: float, tip: ArrayLike, seed: ArrayLike | None = None, *,
                 theta0: float = 0.0, nodes: int = 41, tol: float = SHOOTING_TOL,
                 maxiter: int = 50, damping: bool = True) -> Shooting:
    """A rod clamped at the origin whose tip is pinned at a given point, by shooting.

    The unknowns are ``p = (m0, n_x, n_y)``; damped Newton drives the residual
    ``((x(L) - x_t) / L, (y(L) - y_t) / L, m(L) L / EI)`` to zero with the exact Jacobian of
    :func:`mechnum.rods.tip_jacobian`. A pinned point has many equilibria (buckling modes, both
    senses of bending, loops in tension: :func:`mechnum.rods.pinned_equilibria`): the start
    selects one. The default start is the closed-form cantilever (mode 1, the growing branch)
    whose tip is at the point (``pinned_start``): it leads to the
    mode-1 rod where the point admits one and Newton reaches it (a point near the reach ``L``
    in near tension may defeat it: the force of a nearly straight rod is ill-determined by its
    tip).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    tip : array_like, shape (2,) or (batch, 2)
        The pinned point(s) (m); each within ``L`` of the clamp.
    seed : array_like, shape (3,) or (batch, 3), optional
        Start ``(m0, n_x, n_y)`` (N m, N, N).
    theta0, nodes, tol, maxiter, damping
        As in :func:`shoot_cantilever` (``tol`` on the residual above; ``damping=False`` is
        plain Newton).

    Returns
    -------
    Shooting

    Raises
    ------
    ValueError
        If a point is farther than ``L`` from the clamp (an inextensible rod cannot reach it),
        or another input is malformed.
    ConvergenceError, SingularJacobianError
        If Newton fails.
    UnresolvedRodError
        If the rod found is no equilibrium to RK4's error (a spurious solution of the discrete
        equations).

    Examples
    --------
    >>> res = shoot_pinned(1.0, 1.0, [0.8, 0.1], [4.0, -20.0, 2.0])
    >>> np.round(res.rod.tip, 12).tolist(), abs(float(res.rod.m[-1])) < 1e-12
    ([0.8, 0.1], True)
    """
    EI, L, theta0, nodes, tol, maxiter, damping = _controls(EI, L, theta0, nodes, tol, maxiter,
                                                            damping)
    tip = _batch(tip, "tip", 2)
    if np.any(np.hypot(tip[..., 0], tip[..., 1]) > L):
        raise ValueError(f"a pinned point {tip!r} is farther than L = {L} from the clamp")
    points = tip.reshape(-1, 2)
    if seed is None:
        start = pinned_start(EI, L, points, theta0)
    else:
        seed = _batch(seed, "seed", 3)
        if seed.ndim == 2 and len(seed) not in (1, len(points)):
            raise ValueError(f"seed must be one start or one per point ({len(points)}), got "
                             f"shape {seed.shape}: the shapes do not broadcast")
        start = np.broadcast_to(seed.reshape(-1, 3), points.shape[:1] + (3,)).copy()
    res, p, tol, tips = _pinned(EI, L, points, start, theta0, nodes, tol, maxiter, damping)
    rod = integrate(EI, L, p[:, 0], p[:, 1:], theta0=theta0, nodes=nodes)
    result = shooting_result("shoot_pinned", res, p, start, rod, tip.shape[:-1], tol, tips)
    check_resolved(EI, L, result)
    return result
