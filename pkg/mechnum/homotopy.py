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

This is the method of Sommese and Wampler's *The Numerical Solution of Systems of Polynomials*
(2005), kept small for teaching: no endgame (a path ending at a singular solution is only
accurate to about the square root of the tracking tolerance), and one path after the other.
"""

from dataclasses import dataclass
from itertools import product

import numpy as np

from mechnum import _validate
from mechnum.polynomials import PolynomialSystem

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
# Newton steps polishing a finite endpoint on F itself, and the residual it must reach
# (relative to the equations' coefficients): round-off of unit-sized terms.
_POLISH_STEPS = 8
_POLISH_TOL = 1e-10
STATUSES = ("finite", "at-infinity", "lost")
"""What becomes of a path: it ends at a finite solution, at infinity, or the tracker lost it."""


@dataclass(frozen=True)
class TrackResult:
    """One tracked path: its end ``x``, the ``s`` it reached, steps taken and rejected."""

    x: np.ndarray
    s: float
    steps: int
    rejected: int


def track(homotopy, x0, *, tol=1e-9, h0=0.01, max_steps=20000):
    """Follow a solution of ``H(x, s) = 0`` from ``s = 0`` to ``s = 1``.

    Parameters
    ----------
    homotopy : callable
        ``homotopy(x, s) -> (H, H_x, H_s)``: the value (shape ``(m,)``), its Jacobian in ``x``
        (``(m, m)``) and its derivative in ``s`` (``(m,)``), complex.
    x0 : array_like, shape (m,)
        A solution at ``s = 0``.
    tol : float, optional
        Newton's corrector accepts a step when its last update is below ``tol * (1 + |x|)``.
    h0 : float, optional
        The first step in ``s``.
    max_steps : int, optional
        Steps (accepted and rejected) before the path is declared lost.

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
    >>> end.s, np.round(end.x.real, 12).tolist()
    (1.0, [2.0])
    """
    tol = _validate.tolerance(tol)
    max_steps = _validate.maxiter(max_steps, "max_steps")
    x, s, h = np.asarray(x0, dtype=complex), 0.0, _validate.tolerance(h0, "h0")
    steps = rejected = successes = 0

    def velocity(x, s):
        _, Hx, Hs = homotopy(x, s)
        return -np.linalg.solve(Hx, Hs)

    while s < 1.0 and steps + rejected < max_steps and h >= _MIN_STEP:
        h = min(h, 1.0 - s)
        try:  # predictor: one classical Runge-Kutta step along the path's tangent
            k1 = velocity(x, s)
            k2 = velocity(x + h / 2 * k1, s + h / 2)
            k3 = velocity(x + h / 2 * k2, s + h / 2)
            k4 = velocity(x + h * k3, s + h)
            y = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            for _ in range(_CORRECTOR_STEPS):  # corrector: Newton at the new s
                value, Hx, _ = homotopy(y, s + h)
                dy = np.linalg.solve(Hx, -value)
                y = y + dy
                if np.linalg.norm(dy) <= tol * (1 + np.linalg.norm(y)):
                    break
            else:
                raise np.linalg.LinAlgError("corrector did not converge")
        except np.linalg.LinAlgError:  # a singular Jacobian or a failed corrector: shorten
            h, successes, rejected = h / 2, 0, rejected + 1
            continue
        x, s, steps, successes = y, (1.0 if s + h >= 1.0 else s + h), steps + 1, successes + 1
        if successes >= _SUCCESSES_TO_GROW:
            h, successes = min(2 * h, _MAX_STEP), 0
    return TrackResult(x, s, steps, rejected)


@dataclass(frozen=True)
class HomotopyResult:
    """The outcome of :func:`solve`.

    Attributes
    ----------
    solutions : ndarray of complex, shape (k, n)
        The distinct finite solutions, polished by Newton on the system itself.
    status : ndarray of str, shape (paths,)
        What became of each path (:data:`STATUSES`).
    endpoints : ndarray of complex, shape (paths, n + 1)
        Where each path ended, in projective coordinates ``(x0, x1, ..., xn)``.
    steps : ndarray of int, shape (paths,)
        Accepted steps of each path.
    """

    solutions: np.ndarray
    status: np.ndarray
    endpoints: np.ndarray
    steps: np.ndarray

    def real(self, imag_tol=1e-8):
        """The solutions whose imaginary parts are all below ``imag_tol``, as real arrays."""
        imag_tol = _validate.tolerance(imag_tol, "imag_tol")
        keep = np.all(np.abs(self.solutions.imag) <= imag_tol, axis=1)
        return self.solutions[keep].real


def _start_points(degrees, chart):
    """The start system's solutions (tuples of roots of unity) on the chart ``chart . X = 1``."""
    for powers in product(*(range(d) for d in degrees)):
        v = np.r_[1.0, [np.exp(2j * np.pi * k / d) for k, d in zip(powers, degrees)]]
        yield v / (chart @ v)


def _polish(system, x):
    """Newton on ``system`` from ``x``; the last iterate and whether its residual is tiny."""
    scale = max(np.abs(c).max() for _, c in system.terms)
    for _ in range(_POLISH_STEPS):
        try:
            x = x - np.linalg.solve(system.jacobian(x), system(x))
        except np.linalg.LinAlgError:
            break
    return x, np.abs(system(x)).max() <= _POLISH_TOL * scale * (1 + np.abs(x).max()) ** \
        max(system.degrees)


def solve(system, *, rng=None, tol=1e-9, same=1e-6):
    """Every isolated finite solution of a square polynomial system, by a total-degree homotopy.

    Parameters
    ----------
    system : PolynomialSystem
        ``n`` equations in ``n`` unknowns. Scale it so its solutions are of order 1.
    rng : numpy.random.Generator or int, optional
        Draws ``gamma`` and the projective chart: no hidden randomness.
    tol : float, optional
        The path tracker's corrector tolerance (:func:`track`).
    same : float, optional
        Two finite endpoints closer than this are one solution (the paths of a multiple root).

    Returns
    -------
    HomotopyResult
        ``bezout_bound(system)`` paths.

    Raises
    ------
    ValueError
        If the system is not square, or ``tol`` or ``same`` is not a positive number.

    Examples
    --------
    ``x y = 1`` and ``x^2 = 4``: Bezout says 4 paths; two solutions are finite.

    >>> import numpy as np
    >>> F = PolynomialSystem.from_dicts([{(1, 1): 1, (0, 0): -1}, {(2, 0): 1, (0, 0): -4}])
    >>> result = solve(F, rng=1)
    >>> result.status.tolist().count("at-infinity"), np.round(result.real(), 10).tolist()
    (2, [[-2.0, -0.5], [2.0, 0.5]])
    """
    if not isinstance(system, PolynomialSystem):
        raise ValueError(f"system must be a PolynomialSystem, got {type(system).__name__}")
    n = system.n
    if len(system.terms) != n:
        raise ValueError(f"the system must be square: {len(system.terms)} equations in {n} "
                         "unknowns")
    tol, same = _validate.tolerance(tol), _validate.tolerance(same, "same")
    rng = np.random.default_rng(rng)
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

    ends, status, steps = [], [], []
    for X0 in _start_points(degrees, chart):
        path = track(homotopy, X0, tol=tol)
        X = path.x
        if abs(X[0]) <= _AT_INFINITY * np.linalg.norm(X):
            status.append("at-infinity" if path.s > 1 - 1e-3 else "lost")
        else:
            status.append("finite" if path.s == 1.0 else "lost")
        ends.append(X)
        steps.append(path.steps)
    ends, status = np.array(ends), np.array(status)
    found = []
    for X in ends[status == "finite"]:
        x, ok = _polish(system, X[1:] / X[0])
        if ok and not any(np.abs(x - y).max() <= same for y in found):
            found.append(x)
    solutions = np.array(found).reshape(-1, n)
    order = np.lexsort(solutions.real.T[::-1]) if len(found) else np.arange(0)
    return HomotopyResult(solutions[order], status, ends, np.array(steps))
