"""Many paths of continuation in lockstep: the flood of the atlas (``atlas_of``).

:func:`mechnum.mechanisms._assembly.follow` follows solutions along their paths through
:func:`mechnum.continuation.solve_path`, one call per path or batch of paths, with the branch
tests that keep a path on its branch. :func:`track_paths` takes the same steps and tests for
all its paths at once, each step one damped Newton over every path still alive
(:func:`mechnum.newton.solve_batch`) on a system that gives its residual and Jacobian in one
call: the atlas's flood steps across every edge of a round so.
"""

from __future__ import annotations

import numpy as np

from mechnum import newton
from mechnum.mechanisms._assembly._checks import PATH_MAXITER, STATUS_DTYPE

HALVINGS = 4
"""Most halvings of a continuation step's Newton step (as in
:func:`mechnum.continuation.solve_path`): a step that needs more has lost its branch."""


def track_paths(system, domain, chart: int, params: np.ndarray, u0: np.ndarray, *,
                tol: float) -> tuple:
    """Each solution ``u0`` (n, m) followed along its own path of inputs ``params``
    (steps, n, k), all in lockstep, every path abandoned at its first failure.

    Step ``i`` corrects a secant prediction (from the last two accepted points, once a path has
    two) by damped Newton (:func:`mechnum.newton.solve_batch`, relative step ``tol``,
    ``PATH_MAXITER`` iterations, :data:`HALVINGS` halvings,
    the ``domain`` kept, if given) on all the paths' ``system(u (rows, m), inputs (rows, k))
    -> (G, D)`` at once: one call for the residual and the Jacobian of every path still alive.
    A converged point is on the branch of ``u0`` only if the sign of ``det D`` stayed that of
    the last accepted point's and of ``u0``'s (a fold, where it vanishes, lies between) and
    the signs of the ``t`` of the first ``chart`` unknowns, a chart ``(psi_i, t_i)``, that of
    ``u0``'s (the regular chart is discontinuous at ``t = 0``); the first point that fails a
    test, and every later one, is a "branch-jump": the tests of
    :func:`mechnum.continuation.solve_path` and :func:`mechnum.mechanisms._assembly.follow`, with
    their outcomes, and their numbers for the same ``system``.

    Returns
    -------
    status : ndarray of str, shape (steps, n)
    x : ndarray, shape (n, m)
        The last step's points (NaN where its status is not "converged").
    iterations : ndarray of int, shape (steps, n)
    calls : int
        Calls of ``system``.

    Examples
    --------
    The root of ``x**2 = p`` followed from ``p = 1`` to 4, and to -1: at the fold ``p = 0``
    the root is double, Newton converges only linearly, and the path ends there:

    >>> def system(x, p):
    ...     return x ** 2 - p, 2 * x[:, :, None]
    >>> params = np.linspace([[1.0], [1.0]], [[4.0], [-1.0]], 5)
    >>> status, x, _, _ = track_paths(system, None, 0, params, np.ones((2, 1)), tol=1e-12)
    >>> status[:, 1].tolist(), np.round(x[0], 12).tolist()
    (['converged', 'converged', 'maxiter', 'lost', 'lost'], [2.0])
    """
    steps, n = params.shape[:2]
    status = np.full((steps, n), "lost", dtype=STATUS_DTYPE)
    iterations = np.zeros((steps, n), dtype=int)
    det, converged = np.full((steps, n), np.nan), np.zeros((steps, n), dtype=bool)
    flips = np.zeros((steps, n), dtype=bool)      # a sign of the chart's t changed
    last, before = u0.copy(), u0.copy()
    last_p, before_p = params[0].copy(), params[0].copy()
    streak, sign, alive = np.zeros(n, dtype=int), np.zeros(n), np.ones(n, dtype=bool)
    reference = np.sign(np.linalg.det(system(u0, params[0])[1]))
    t_signs, calls, new = np.sign(u0[:, 1:chart:2]), 1, np.full(u0.shape, np.nan)
    for i in range(steps):
        rows = np.flatnonzero(alive)
        if not rows.size:
            break
        p = params[i]
        move = p - params[i - 1] if i else np.zeros_like(p)
        previous = last_p - before_p
        length = np.sum(previous ** 2, axis=1)
        scale = np.divide(np.sum(move * previous, axis=1), length, out=np.zeros(n),
                          where=(streak >= 2) & (length > 0))
        guess = (last + scale[:, None] * (last - before))[rows]
        if domain is not None:     # a prediction out of the domain falls back on the last point
            guess = np.where(domain(guess)[:, None], guess, last[rows])
        res = newton.solve_batch(lambda u, p=p[rows]: system(u, p), guess, True,
                                 tol=tol, maxiter=PATH_MAXITER, damping=True,
                                 domain=domain, raise_on_failure=False,
                                 halvings=HALVINGS)
        calls += res.nfev
        status[i, rows], iterations[i, rows] = res.status, res.iterations
        done = rows[res.converged]
        new = np.full(u0.shape, np.nan)
        new[done] = res.x[res.converged]
        if done.size:
            det[i, done] = np.linalg.det(system(new[done], p[done])[1])
            calls += 1
        ok = np.zeros(n, dtype=bool)
        ok[done] = True
        jump = ok & (sign * np.sign(det[i]) < 0)       # across a fold since the last point
        status[i, jump] = "branch-jump"
        ok &= ~jump
        converged[i] = ok
        flips[i] = ok & (np.sign(new[:, 1:chart:2]) != t_signs).any(axis=1)
        before = np.where(ok[:, None], last, before)
        before_p = np.where(ok[:, None], last_p, before_p)
        last, last_p = np.where(ok[:, None], new, last), np.where(ok[:, None], p, last_p)
        streak = np.where(ok, streak + 1, 0)
        sign = np.where(ok & (det[i] != 0), np.sign(det[i]), sign)
        alive &= ok
    # the sign of det D against u0's (or, where that is zero, against the first point's)
    first = np.sign(det[np.argmax(converged, axis=0), np.arange(n)])
    reference = np.where(np.isfinite(reference) & (reference != 0), reference, first)
    jump = (converged & (np.sign(det) != reference)) | (status == "branch-jump") | flips
    status = np.where(converged & (np.cumsum(jump, axis=0) > 0), "branch-jump", status)
    return status, np.where(converged[-1][:, None], new, np.nan), iterations, calls
