"""Polynomial homotopy continuation: every isolated solution of a polynomial system.

Newton's method finds the root whose basin holds its start; a homotopy finds them all. To solve
``F(x) = 0``, ``n`` polynomial equations of degrees ``d_i`` in ``n`` complex unknowns:

1. take the *start system* ``G_i(x) = x_i^{d_i} - 1``, whose ``d_1 ... d_n`` solutions (Bezout's
   number, :func:`mechnum.polynomials.bezout_bound`) are all the tuples of roots of unity;
2. deform it into ``F`` along ``H(x, s) = (1 - s) gamma G(x) + s F(x)``, ``s`` from 0 to 1, with a
   random complex ``gamma``: with probability one no path meets a singular point for
   ``s < 1`` (the "gamma trick": the bad ``gamma`` form a set of measure zero);
3. follow each solution ``x(s)`` by :func:`track` (a predictor-corrector path tracker): a
   Runge-Kutta step along ``dx/ds = -H_x^{-1} H_s``, then Newton on ``H(., s + h) = 0``, the
   step ``h`` halved on failure and doubled after successes.

Every isolated solution of ``F`` is the end of some path. Paths whose solution escapes to
infinity (``F`` has fewer finite solutions than Bezout's number, as mechanisms usually do)
are tracked in projective space: the unknowns become ``(x0, x1, ..., xn)`` with every equation
made homogeneous by powers of ``x0``, plus one random linear equation ``h . X = 1`` (a random
affine chart) that keeps every path bounded; a path ending with ``x0 = 0`` went to infinity,
the others give ``x = (x1, ..., xn) / x0``, polished by Newton on ``F``.

A path that ends at a *singular* solution (a double root: two paths meet there) cannot be
tracked to ``s = 1`` exactly, since the Jacobian is singular at its end. A path the tracker
follows to within :data:`ENDGAME` of ``s = 1`` is finished by Newton's method on ``F`` itself,
which converges linearly to a multiple root (to about the square root of round-off for a double
root); the paths that end at one solution are counted as its ``multiplicity``.

This is the method of Sommese and Wampler's *The Numerical Solution of Systems of Polynomials*
(2005), kept small for teaching: that simple endgame instead of a Cauchy or power-series one,
and one path after the other.

Examples
--------
>>> F = PolynomialSystem.from_dicts([{(2,): 1, (0,): -2}])     # x^2 = 2
>>> sorted(solve(F, rng=0).real().ravel().round(12).tolist())
[-1.414213562373, 1.414213562373]
"""

from collections.abc import Callable
from dataclasses import dataclass
from itertools import product

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError
from mechnum.polynomials import PolynomialSystem, bezout_bound
from mechnum.results import Result, status_counts

__all__ = ["ENDS", "solve", "track"]

# Newton's corrector may take this many steps at each s: more means the predictor went too far.
_CORRECTOR_STEPS = 3
# The step h doubles after this many successes in a row, and never exceeds _MAX_STEP (a step
# of a tenth of the path keeps the predictor from jumping between neighbouring paths).
_SUCCESSES_TO_GROW = 3
_MAX_STEP = 0.1
# A step below this fraction of the path means the path is lost (it met a near-singular point).
_MIN_STEP = 1e-12
# An endpoint whose x0 is below this (relative to |X|) lies at infinity: a finite solution of
# a problem scaled to unit size has |x0| of order 1 on a random chart.
_AT_INFINITY = 1e-6
# Newton steps polishing a finite endpoint on F itself (linear convergence to a multiple root
# needs tens), and the residual it must reach (relative to the equations' coefficients):
# round-off of unit-sized terms.
_POLISH_STEPS = 60
_POLISH_TOL = 1e-10
# A solution whose Jacobian has a condition number above this is singular (a multiple root):
# its digits are those of sqrt(eps), and it is grouped with others within sqrt(same).
_SINGULAR_COND = 1e8
TOL = 1e-9
"""Default corrector tolerance of :func:`track` (relative): the paths need not be followed more
accurately than to keep them apart; the endpoints are polished on the system itself."""
SAME = 1e-6
"""Default distance below which two polished endpoints are one solution: far above the round-off
of a simple root, far below the distance of two roots of a system scaled to unit size."""
IMAG_TOL = 1e-8
"""Default of :meth:`HomotopyResult.real`: a solution whose imaginary parts are below this is
real. The polished solutions of a problem scaled to unit size carry round-off of 1e-15; the
margin keeps a real root of condition up to 1e7 real."""
ENDGAME = 1e-3
"""A path lost at ``s >= 1 - ENDGAME`` has reached the neighbourhood of a singular end (a
multiple root, or a root at infinity): its endpoint is finished by Newton on the system."""
MAX_STEPS_LIMIT = 10_000_000
"""The most steps :func:`track` accepts for one path."""
PATHS_LIMIT = 100_000
"""The most paths (Bezout's number) :func:`solve` follows: each path takes milliseconds to
seconds, so a hundred thousand is hours."""
ENDS = ("finite", "at-infinity", "lost")
"""Where a path of :func:`solve` ends (its :attr:`HomotopyResult.ends`): at a finite solution, at
infinity, or nowhere known (the tracker lost it)."""


@dataclass(frozen=True, kw_only=True)
class TrackResult(Result):
    """One tracked path (:func:`track`).

    Attributes
    ----------
    x : ndarray of complex
        Where the path ended.
    status : str
        ``"converged"`` if it reached ``s = 1``; ``"lost"`` if the step fell below
        ``1e-12`` or ``max_steps`` ran out; ``"non-finite"`` if ``x`` overflowed.
    message, nfev, njev
        As in :class:`~mechnum.results.Result` (calls of ``fun``, which gives both).
    iterations : int
        Steps tried, accepted and rejected.
    s : float
        How far it got.
    steps, rejected : int
        Steps accepted, and rejected (the step halved).
    """

    s: float
    steps: int
    rejected: int


def _checked(fun, x, s):
    """``fun(x, s)`` checked: ``H`` and ``H_s`` of shape ``(m,)``, ``H_x`` ``(m, m)``."""
    H, Hx, Hs = (np.asarray(v) for v in fun(x, s))
    m = x.shape[0]
    if H.shape != (m,) or Hx.shape != (m, m) or Hs.shape != (m,):
        raise ValueError(f"fun must return H ({m},), H_x ({m}, {m}) and H_s ({m},) for x "
                         f"of shape ({m},), got {H.shape}, {Hx.shape}, {Hs.shape}")
    return H, Hx, Hs


def track(fun: Callable, seed: ArrayLike, *, tol: float = TOL, h0: float = 0.01,
          max_steps: int = 20000) -> TrackResult:
    """Follow a solution of ``H(x, s) = 0`` from ``s = 0`` to ``s = 1``.

    Parameters
    ----------
    fun : callable
        The homotopy, ``fun(x, s) -> (H, H_x, H_s)``: the value (shape ``(m,)``), its
        Jacobian in ``x`` (``(m, m)``) and its derivative in ``s`` (``(m,)``), complex.
    seed : array_like, shape (m,)
        A solution at ``s = 0``, finite: where the path starts.
    tol : float, optional
        Newton's corrector accepts a step when its last update is below ``tol * (1 + |x|)``.
    h0 : float, optional
        The first step in ``s``: it doubles after three accepted steps in a row (up to
        ``0.1``) and halves after a rejected one.
    max_steps : int, optional
        Steps (accepted and rejected) before the path is declared lost, at most
        :data:`MAX_STEPS_LIMIT`.

    Returns
    -------
    TrackResult
        ``s == 1`` if the path was followed to its end.

    Examples
    --------
    The root of ``x^2 - (1 + 3 s)`` that starts at 1 ends at 2:

    >>> import numpy as np
    >>> H = lambda x, s: (x**2 - (1 + 3 * s), np.diag(2 * x), np.array([-3.0 + 0j]))
    >>> end = track(H, [1.0 + 0j])
    >>> end.s, np.round(end.x.real, 12).tolist(), end.status
    (1.0, [2.0], 'converged')
    """
    _validate.function(fun, "fun")
    tol = _validate.tolerance(tol)
    max_steps = _validate.maxiter(max_steps, "max_steps", maximum=MAX_STEPS_LIMIT)
    h = _validate.tolerance(h0, "h0")
    x = np.asarray(seed)
    if x.dtype.kind not in "biufc" or x.ndim != 1 or x.size == 0:
        raise ValueError(f"seed must be a non-empty 1-D numeric array, got "
                         f"{_validate.shown(seed)}")
    x = x.astype(complex)
    if not np.all(np.isfinite(x)):
        raise ValueError(f"seed must be finite, got {_validate.shown(x)}")
    s, steps, rejected, successes, calls = 0.0, 0, 0, 0, 0

    def velocity(x, s):
        _, Hx, Hs = _checked(fun, x, s)
        return -np.linalg.solve(Hx, Hs)

    while s < 1.0 and steps + rejected < max_steps and h >= _MIN_STEP:
        last = h >= 1.0 - s  # this step ends the path
        h = min(h, 1.0 - s)
        try:  # predictor: one classical Runge-Kutta step along the path's tangent
            with np.errstate(all="ignore"):  # a non-finite stage is a rejected step
                k1 = velocity(x, s)
                k2 = velocity(x + h / 2 * k1, s + h / 2)
                k3 = velocity(x + h / 2 * k2, s + h / 2)
                k4 = velocity(x + h * k3, s + h)
                calls += 4
                y = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
                for _ in range(_CORRECTOR_STEPS):  # corrector: Newton at the new s
                    value, Hx, _ = _checked(fun, y, s + h)
                    calls += 1
                    dy = np.linalg.solve(Hx, -value)
                    y = y + dy
                    if np.linalg.norm(dy) <= tol * (1 + np.linalg.norm(y)):
                        break
                else:
                    raise np.linalg.LinAlgError("corrector did not converge")
            if not np.all(np.isfinite(y)):
                raise np.linalg.LinAlgError("the corrector overflowed")
        except np.linalg.LinAlgError:  # a singular Jacobian or a failed corrector: shorten
            h, successes, rejected = h / 2, 0, rejected + 1
            continue
        x, s, steps, successes = y, (1.0 if last else s + h), steps + 1, successes + 1
        if successes >= _SUCCESSES_TO_GROW:
            h, successes = min(2 * h, _MAX_STEP), 0
    status = "converged" if s == 1.0 else "lost"
    why = ("reached s = 1" if status == "converged" else
           f"lost at s = {s:.12g}: " + ("max_steps ran out" if h >= _MIN_STEP
                                        else f"the step fell below {_MIN_STEP:g}"))
    return TrackResult(x=x, status=status, message=f"{why} after {steps} steps ({rejected} "
                       f"rejected)", iterations=steps + rejected, nfev=calls, njev=calls, s=s,
                       steps=steps, rejected=rejected)


@dataclass(frozen=True, kw_only=True)
class HomotopyResult(Result):
    """The outcome of :func:`solve`.

    Attributes
    ----------
    x : ndarray of complex, shape (k, n)
        The distinct finite solutions, polished by Newton on the system itself.
    status : ndarray of str, shape (paths,)
        What became of each path, in the shared vocabulary (:data:`~mechnum.results.STATUSES`):
        ``"converged"`` (followed to ``s = 1``), ``"singular"`` (to a singular end, finished by
        the endgame: a multiple root or one at infinity) or ``"lost"``.
    message : str
        The counts of the ends and of the solutions.
    iterations : ndarray of int, shape (paths,)
        Accepted steps of each path.
    nfev, njev : int
        Evaluations of the homotopy (each gives the values and the Jacobian).
    ends : ndarray of str, shape (paths,)
        Where each path ended (:data:`ENDS`): ``"finite"``, ``"at-infinity"`` or ``"lost"``.
    endpoints : ndarray of complex, shape (paths, n + 1)
        Where each path ended, in projective coordinates ``(x0, x1, ..., xn)``.
    multiplicity : ndarray of int, shape (k,)
        How many paths end at each solution: 1 for a simple root, 2 for a double one.
    """

    ends: np.ndarray
    endpoints: np.ndarray
    multiplicity: np.ndarray

    def real(self, imag_tol: float = IMAG_TOL) -> np.ndarray:
        """The solutions whose imaginary parts are all below ``imag_tol``, as real arrays;
        below ``imag_tol ** (1 / m)`` for a root of multiplicity ``m``, which round-off
        blurs by the ``m``-th root of its size (a double root carries half the digits).

        Examples
        --------
        >>> F = PolynomialSystem.from_dicts([{(2,): 1, (1,): -2, (0,): 1}])    # (x - 1)^2
        >>> solve(F, rng=0).real().round(6).tolist()
        [[1.0]]
        """
        imag_tol = _validate.tolerance(imag_tol, "imag_tol")
        limit = imag_tol ** (1.0 / np.maximum(self.multiplicity, 1))
        keep = np.all(np.abs(self.x.imag) <= limit[:, None], axis=1)
        return self.x[keep].real


def _start_points(degrees, chart):
    """The start system's solutions (tuples of roots of unity) on the chart ``chart . X = 1``."""
    for powers in product(*(range(d) for d in degrees)):
        v = np.r_[1.0, [np.exp(2j * np.pi * k / d) for k, d in zip(powers, degrees)]]
        yield v / (chart @ v)


def _polish(system, x):
    """Newton on ``system`` from ``x`` (least squares where the Jacobian is singular): the
    last iterate, whether its residual is tiny, and whether its Jacobian is singular."""
    scale = max(np.abs(c).max() for _, c in system.terms)
    floor = _POLISH_TOL * scale
    with np.errstate(all="ignore"):
        last = np.inf
        for _ in range(_POLISH_STEPS):
            residual = np.abs(system(x)).max()
            # stop once at round-off: below the floor and no longer falling by half (a simple
            # root falls quadratically to its floor, a double one by a quarter per step)
            if not np.isfinite(residual) or (residual <= floor and residual > 0.5 * last):
                break
            last = residual
            x = x + np.linalg.lstsq(system.jacobian(x), -system(x), rcond=None)[0]
        residual = np.abs(system(x)).max()
        cond = np.linalg.cond(system.jacobian(x))
    ok = bool(residual <= floor * (1 + np.abs(x).max()) ** max(system.degrees))
    return x, ok, not cond < _SINGULAR_COND


def solve(system: PolynomialSystem, *, rng: np.random.Generator | int | None = None,
          tol: float = TOL, same: float = SAME, raise_on_failure: bool = True) -> HomotopyResult:
    """Every isolated finite solution of a square polynomial system, by a total-degree homotopy.

    Parameters
    ----------
    system : PolynomialSystem
        ``n`` equations in ``n`` unknowns, Bezout's number at most :data:`PATHS_LIMIT`. Scale
        it so its solutions are of order 1.
    rng : numpy.random.Generator or int, optional
        Draws ``gamma`` and the projective chart: no hidden randomness.
    tol : float, optional
        The path tracker's corrector tolerance (:func:`track`).
    same : float, optional
        Two polished endpoints closer than this are one solution (the paths of a multiple
        root); ``sqrt(same)`` where the solution is singular (its digits are those of the
        square root of round-off).
    raise_on_failure : bool, optional
        Raise if a path is lost (then some solution may be missing); with False, return the
        result and let the caller read ``status``.

    Returns
    -------
    HomotopyResult
        ``bezout_bound(system)`` paths.

    Raises
    ------
    ValueError
        If the system is not square, has too many paths, or an option is invalid.
    ConvergenceError
        If a path is lost (and ``raise_on_failure``): the solutions may be incomplete; the
        error's ``result`` holds the :class:`HomotopyResult`.

    Examples
    --------
    ``x y = 1`` and ``x^2 = 4``: Bezout says 4 paths; two solutions are finite.

    >>> import numpy as np
    >>> F = PolynomialSystem.from_dicts([{(1, 1): 1, (0, 0): -1}, {(2, 0): 1, (0, 0): -4}])
    >>> result = solve(F, rng=1)
    >>> result.ends.tolist().count("at-infinity"), np.round(result.real(), 10).tolist()
    (2, [[-2.0, -0.5], [2.0, 0.5]])

    ``(x - 1)^2 = 0`` and ``y = 1``: both paths end at the double root ``(1, 1)``:

    >>> F = PolynomialSystem.from_dicts([{(2, 0): 1, (1, 0): -2, (0, 0): 1},
    ...                                  {(0, 1): 1, (0, 0): -1}])
    >>> result = solve(F, rng=0)
    >>> np.round(result.real(), 6).tolist(), result.multiplicity.tolist()
    ([[1.0, 1.0]], [2])
    """
    if not isinstance(system, PolynomialSystem):
        raise ValueError(f"system must be a PolynomialSystem, got {type(system).__name__}")
    n = system.n
    if len(system.terms) != n:
        raise ValueError(f"the system must be square: {len(system.terms)} equations in {n} "
                         "unknowns")
    if bezout_bound(system) > PATHS_LIMIT:
        raise ValueError(f"Bezout's number {bezout_bound(system)} is more paths than "
                         f"{PATHS_LIMIT} (a bound on the work)")
    tol, same = _validate.tolerance(tol), _validate.tolerance(same, "same")
    raise_on_failure = _validate.flag(raise_on_failure, "raise_on_failure")
    rng = _validate.rng(rng)
    gamma = np.exp(2j * np.pi * rng.uniform())
    chart = rng.standard_normal(n + 1) + 1j * rng.standard_normal(n + 1)
    target = system.homogenized()
    degrees = system.degrees
    start = PolynomialSystem(tuple(  # G_i = x_i^d_i - x0^d_i, homogeneous of degree d_i
        (np.array([np.eye(n + 1, dtype=int)[i + 1] * d, np.eye(n + 1, dtype=int)[0] * d]),
         np.array([1.0 + 0j, -1.0])) for i, d in enumerate(degrees)))

    def homotopy(X, s):
        G, F = start(X), target(X)
        H = np.r_[(1 - s) * gamma * G + s * F, chart @ X - 1]
        Hx = np.vstack([(1 - s) * gamma * start.jacobian(X) + s * target.jacobian(X), chart])
        return H, Hx, np.r_[F - gamma * G, 0.0]

    paths = [track(homotopy, X0, tol=tol) for X0 in _start_points(degrees, chart)]
    ends, status, found, multiplicity, singular = [], [], [], [], []
    for path in paths:
        X = path.x
        near_end = path.s == 1.0 or path.s >= 1.0 - ENDGAME
        end = "lost"
        if near_end and abs(X[0]) <= _AT_INFINITY * np.linalg.norm(X):
            end = "at-infinity"
        elif near_end:
            x, ok, flat = _polish(system, X[1:] / X[0])
            if ok:
                end = "finite"
                _group(found, multiplicity, singular, x, flat, same)
        ends.append(end)
        status.append("lost" if end == "lost" else "converged" if path.s == 1.0 else "singular")
    ends, status = np.array(ends), np.array(status)
    solutions = np.array(found).reshape(-1, n)
    # ordered by their real parts, rounded: the digits round-off leaves to a multiple root
    # (1e-8) must not decide the order
    order = np.lexsort(np.round(solutions.real, 6).T[::-1]) if len(found) else np.arange(0)
    counts = {e: int(np.sum(ends == e)) for e in ENDS}
    result = HomotopyResult(
        x=solutions[order], status=status, iterations=np.array([p.steps for p in paths]),
        message=f"{len(paths)} paths: {counts}; {len(found)} distinct finite solutions "
                f"({status_counts(status)['singular']} paths to a singular end)",
        nfev=sum(p.nfev for p in paths), njev=sum(p.njev for p in paths), ends=ends,
        endpoints=np.array([p.x for p in paths]),
        multiplicity=np.array(multiplicity, dtype=int)[order])
    if raise_on_failure and counts["lost"]:
        raise ConvergenceError(f"{counts['lost']} of {len(paths)} paths were lost: solutions "
                               f"may be missing ({result.message})", result)
    return result


def _group(found, multiplicity, singular, x, flat, same):
    """Add the polished endpoint ``x`` to the solution it coincides with (within ``same``, or
    ``sqrt(same)`` if either is singular), or as a new one."""
    for i, y in enumerate(found):
        if np.abs(x - y).max() <= (np.sqrt(same) if flat or singular[i] else same):
            multiplicity[i] += 1
            return
    found.append(x)
    multiplicity.append(1)
    singular.append(flat)
