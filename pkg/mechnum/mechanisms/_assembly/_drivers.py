"""The drivers every mechanism built of rods shares: its searches, its paths, its maps.

:func:`search` (every equilibrium from many starts, with the completeness check), :func:`shoot`
(damped Newton on a shooting residual), :func:`continuation_system` and :func:`follow`
(continuation that never reports a point of another branch as converged), :func:`follow_grid`
(a map over a grid, from a neighbour), :func:`workspace_edge` (where a branch ends on rays),
and :func:`zero_crossings` and :func:`singular_points` (where a determinant changes sign on a
map). Every system here gives its residual and its Jacobian together, ``fun(u) -> (f, J)``
(Newton's ``jac=True``): they share one evaluation of the rods, and nothing is cached.
"""

from __future__ import annotations

import numpy as np

from mechnum import _validate, continuation, newton
from mechnum.mechanisms._assembly._checks import (
    MAX_CHECK,
    MAX_DIRECTIONS,
    MAX_LEVELS,
    MAX_RAY_STEPS,
    MAX_STARTS,
    STATUS_DTYPE,
    check_type,
)
from mechnum.mechanisms._assembly._results import Layout, Path, Trace, trace_of


def continuation_system(system, layout: Layout, along: str):
    """``fun(u, p) -> (f, J)`` of a full system ``system(chart, inputs, pose) -> (G, D)`` for
    continuation: along the pose (``u = (chart, inputs)``, the inverse problem) or along the
    inputs (``u = (chart, pose)``, the direct problem); ``J`` is ``D`` in the columns of
    ``u``.

    Examples
    --------
    One rod, one input ``a`` and a pose ``b``: three equations ``(z1 - a, z2 - b, a - b**2)``.

    >>> def system(z, a, b):
    ...     G = np.concatenate((z[:, :1] - a, z[:, 1:] - b, a - b ** 2), axis=-1)
    ...     D = np.zeros((len(z), 3, 4))
    ...     D[:, 0, [0, 2]], D[:, 1, [1, 3]] = [1.0, -1.0], [1.0, -1.0]
    ...     D[:, 2, 2], D[:, 2, 3] = 1.0, -2 * b[:, 0]
    ...     return G, D
    >>> fun = continuation_system(system, Layout(rods=1, inputs=1, pose=1), "pose")
    >>> u, b = np.array([[4.0, 2.0, 4.0]]), np.array([[2.0]])       # u = (z1, z2, a)
    >>> f, J = fun(u, b)
    >>> f.tolist(), J[0].tolist()
    ([[0.0, 0.0, 0.0]], [[1.0, 0.0, -1.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    """
    _validate.function(system, "system")
    c = check_type(layout, Layout, "layout").chart
    if _validate.choice(along, ("pose", "inputs"), "along") == "pose":
        columns = layout.inverse_columns

        def fun(u, p):
            G, D = system(u[..., :c], u[..., c:], p)
            return G, D[..., columns]
    else:
        columns = layout.forward_columns

        def fun(u, p):
            G, D = system(u[..., :c], p, u[..., c:])
            return G, D[..., columns]
    return fun


def _counted(fun):
    """``fun -> (f, J)`` that counts its calls in ``counts`` (each gives both)."""
    counts = {"nfev": 0, "njev": 0}

    def f(*args):
        counts["nfev"] += 1
        counts["njev"] += 1
        return fun(*args)

    return f, counts


def search(fun, sample, *, domain, n_starts, check, rng, tol, maxiter, same=1e-8):
    """Every root of ``fun(u) -> (f, J)`` that damped Newton finds from ``n_starts`` starts and
    ``check`` times as many more (:func:`mechnum.newton.solve_all`), with the inputs checked and
    the work counted.

    Returns
    -------
    found : mechnum.newton.RootSet
    nfev, njev : int
        Calls of the residual and of the Jacobian (each on a batch of starts).
    """
    n_starts = _validate.maxiter(n_starts, "n_starts", maximum=MAX_STARTS)
    check = _validate.maxiter(check, "check", minimum=0, maximum=MAX_CHECK)
    found = newton.solve_all(fun, sample, True, n_starts=n_starts, check=check,
                             rng=_validate.rng(rng), domain=domain, tol=tol, maxiter=maxiter,
                             same=same)
    return found, found.nfev, found.njev


def shoot(fun, seed, known, *, width: int, tol: float, maxiter: int):
    """Damped Newton on a shooting system ``fun(X, known) -> (f, J)`` (criterion: the
    residual) from ``seed`` (``(width,)`` or ``(batch, width)``), ``known`` broadcast to the
    batch; the :class:`~mechnum.newton.BatchNewtonResult` and the broadcast ``known``."""
    X0 = np.atleast_2d(_validate.array(seed, "seed", ndim=(1, 2)))
    if X0.shape[1] != width:
        raise ValueError(f"seed must have a last axis of {width} (the study's unknowns), "
                         f"got shape {np.shape(seed)}")
    known = np.asarray(known, dtype=float)
    if known.ndim == 2 and len(known) not in (1, len(X0)):
        raise ValueError(f"{len(known)} known values for {len(X0)} seeds: give one, or one "
                         "per seed")
    known = np.broadcast_to(known, (len(X0), known.shape[-1]))
    maxiter = _validate.maxiter(maxiter, "maxiter", maximum=10_000)
    res = newton.solve_batch(lambda X: fun(X, known), X0, True,
                             tol=_validate.tolerance(tol), maxiter=maxiter,
                             criterion="residual", damping=True, raise_on_failure=False)
    return res, known


def follow(fun, seed, params, *, tol, maxiter=10, domain=None, resume=True, chart=0,
           criterion="residual"):
    """Follow a solution of ``fun(u, p) = 0`` along ``params``
    (:func:`mechnum.continuation.solve_path`), and keep it on its branch.

    A point is "converged" only if it lies on the branch the path started from. Two tests
    catch a step that converged on another branch: the sign of the determinant of ``J`` (on
    one branch it keeps its sign: along a natural parameter a branch cannot pass a fold, where
    it vanishes, so a sign change means Newton leapt across the fold), and, for the first
    ``chart`` unknowns, the signs of the rods' ``t`` (the regular chart is discontinuous at
    ``t = 0``). The first point that fails either, and every point after it (they descend from
    it), get the status "branch-jump". A point where Newton failed keeps the status of its
    failure ("lost" when :func:`mechnum.continuation.solve_path` gives none).

    Parameters
    ----------
    fun : callable
        ``fun(u, p) -> (f, J)``, shapes ``(m, n)`` and ``(m, n, n)`` for rows ``u`` and ``p``.
    seed : ndarray, shape (n,) or (batch, n)
        A solution at (or near) ``params[0]``.
    params : ndarray, shape (steps, p) or (steps, batch, p)
        The parameters of every point, for one path or for ``batch`` paths; ``steps`` may be 0.
    tol, maxiter, domain, resume, criterion
        As in :func:`mechnum.continuation.solve_path` (the residual criterion by default; the step
        criterion, relative, where the residual's round-off floor varies from point to point,
        as with rods in strong tension).
    chart : int, optional
        Leading unknowns that are a chart ``(psi_i, t_i)``, whose ``t`` signs must persist.

    Returns
    -------
    Trace

    Examples
    --------
    ``x**2 = p`` from ``x = 1``: the root follows ``sqrt(p)`` until ``p`` turns negative, where
    the branch ends (a fold at ``p = 0``).

    >>> fun = lambda x, p: (x ** 2 - p, 2 * x[:, :, None])
    >>> tr = follow(fun, np.array([1.0]), np.array([[1.0], [0.25], [-0.25]]), tol=1e-12)
    >>> (tr.status == "converged").tolist(), np.round(tr.x[:2, 0], 12).tolist()
    ([True, True, False], [1.0, 0.5])
    """
    params = _validate.array(params, "params", ndim=(2, 3) if np.size(params) else None)
    u0 = _validate.array(seed, "seed", ndim=(1, 2))
    resume = _validate.flag(resume, "resume")
    if not len(params):
        return trace_of(np.empty((0,) + u0.shape),
                        np.empty((0,) + u0.shape[:-1], STATUS_DTYPE),
                        np.zeros((0,) + u0.shape[:-1], int), 0, 0)
    fun = _validate.function(fun, "fun")
    f, counts = _counted(fun)
    # the branch tests are the signs below (and solve_path's own of det J); solve_path's speed
    # test is off: near a fold of the mechanism (the workspace's edge) the speed grows without
    # bound along the branch itself, and a false jump would cut the rest of the path
    res = continuation.solve_path(f, u0, params, True, tol=tol, maxiter=maxiter, domain=domain,
                            resume=resume, max_jump=None, criterion=criterion)
    ok = np.asarray(res.converged, dtype=bool)
    status = np.asarray(getattr(res, "status", np.where(ok, "converged", "lost")), STATUS_DTYPE)
    x, single = res.x, u0.ndim == 1
    X, P, U = (x[:, None], params[:, None], u0[None]) if single else (x, params, u0)
    OK = ok.reshape(X.shape[:2])
    det = np.full(OK.shape, np.nan)
    if OK.any():
        det[OK] = np.linalg.det(f(X[OK], P[OK])[1])
    ref = np.sign(np.linalg.det(f(U, P[0])[1]))
    first = np.sign(det[np.argmax(OK, axis=0), np.arange(OK.shape[1])])
    ref = np.where(np.isfinite(ref) & (ref != 0), ref, first)
    # a jump that solve_path saw itself counts too: it resumes from the last point before the
    # jump, but nothing then vouches that a later point lies on the branch followed
    jump = (OK & (np.sign(det) != ref)) | (status == "branch-jump").reshape(OK.shape)
    if chart:
        signs = np.sign(X[..., 1:chart:2]) != np.sign(U[..., 1:chart:2])
        jump |= OK & signs.any(axis=-1)
    jumped = (np.cumsum(jump, axis=0) > 0).reshape(ok.shape)
    status = np.where(ok & jumped, "branch-jump", status)
    return trace_of(x, status, np.asarray(res.iterations), counts["nfev"], counts["njev"])


def _outwards(n, start):
    """The indices from ``start`` to the end and back to 0 as two paths of one length (the
    shorter padded with its last index: a step of length zero), and their lengths."""
    up, down = np.arange(start, n), np.arange(start, -1, -1)
    steps = max(len(up), len(down))
    padded = [np.pad(i, (0, steps - len(i)), mode="edge") for i in (up, down)]
    return np.stack(padded, axis=1), (len(up), len(down))


def follow_grid(trace, grid, start, u0) -> Trace:
    """A solution followed over a grid from the grid point ``start``: along the second axis both
    ways, then every column reached along the first axis both ways (each both ways at once).

    Parameters
    ----------
    trace : callable
        ``trace(params (steps, batch, p), u0 (batch, m)) -> Trace`` (:func:`follow` of the
        mechanism's system, with ``resume=False``).
    grid : ndarray, shape (nx, ny, p)
        The parameters at the grid's points.
    start : (int, int)
        The grid point of ``u0``.
    u0 : ndarray, shape (m,)
        The solution at ``grid[start]``.

    Returns
    -------
    Trace
        Shape ``(nx, ny, ...)``; "lost" where the grid was never reached.
    """
    nx, ny = grid.shape[:2]
    x = np.full((nx, ny, len(u0)), np.nan)
    status = np.full((nx, ny), "lost", dtype=STATUS_DTYPE)
    iterations = np.zeros((nx, ny), dtype=int)
    if not (nx and ny):
        return trace_of(x, status, iterations, 0, 0)
    calls = np.zeros(2, dtype=int)

    def both_ways(params, u):              # params (steps, 2, batch, p), u (batch, m)
        steps, _, batch, p = params.shape
        tr = trace(params.reshape(steps, 2 * batch, p), np.concatenate((u, u)))
        calls[:] += tr.nfev, tr.njev
        return (a.reshape((steps, 2, batch) + a.shape[2:])
                for a in (np.where((tr.status == "converged")[..., None], tr.x, np.nan),
                          tr.status, tr.iterations))

    js, lengths = _outwards(ny, start[1])
    column = np.full((ny, len(u0)), np.nan)
    col_x, col_s, col_i = both_ways(grid[start[0], js][:, :, None], u0[None])
    for way, n in enumerate(lengths):
        column[js[:n, way]] = col_x[:n, way, 0]
        status[start[0], js[:n, way]] = col_s[:n, way, 0]
        iterations[start[0], js[:n, way]] = col_i[:n, way, 0]
    alive = np.flatnonzero(np.isfinite(column[:, 0]))
    i_s, lengths = _outwards(nx, start[0])
    got_x, got_s, got_i = both_ways(grid[i_s][:, :, alive], column[alive])
    for way, n in enumerate(lengths):
        rows = i_s[:n, way, None]
        x[rows, alive], status[rows, alive] = got_x[:n, way], got_s[:n, way]
        iterations[rows, alive] = got_i[:n, way]
    return trace_of(x, status, iterations, int(calls[0]), int(calls[1]))


def workspace_edge(trace, centre, u0, *, directions, step, reach, levels):
    """Where a branch ends on ``directions`` rays in the first two coordinates of the pose from
    ``centre`` (the others fixed): followed in steps of ``step`` up to ``reach``, then from
    each ray's last solution again in steps four times shorter, ``levels`` times.

    Parameters
    ----------
    trace : callable
        ``trace(params (steps, rays, d), u (rays, m)) -> Trace``, with ``resume=False``.
    centre : ndarray, shape (d,)
    u0 : ndarray, shape (m,)
        The solution at ``centre``.
    directions : int
        Rays at equal angles, at most :data:`MAX_DIRECTIONS`.
    step, reach : float
        The first step and the largest distance (m); ``reach / step`` at most
        :data:`MAX_RAY_STEPS`.
    levels : int
        Refinements, at most :data:`MAX_LEVELS`.

    Returns
    -------
    edge : ndarray, shape (directions, d)
        The last pose reached on each ray.
    u : ndarray, shape (directions, m)
        The solution there.
    status : ndarray of str, shape (directions,)
        "converged" where the centre's solution was found on the ray.
    nfev, njev : int
    """
    directions = _validate.maxiter(directions, "directions", maximum=MAX_DIRECTIONS)
    levels = _validate.maxiter(levels, "levels", minimum=0, maximum=MAX_LEVELS)
    step, reach = _validate.scalar(step, "step", positive=True), _validate.scalar(
        reach, "reach", positive=True)
    if reach / step > MAX_RAY_STEPS:
        raise ValueError(f"reach / step = {reach / step:.3g} steps per ray, more than "
                         f"{MAX_RAY_STEPS} (a bound on the work): take a longer step")
    angle = 2.0 * np.pi * np.arange(directions) / directions
    ray = np.column_stack((np.cos(angle), np.sin(angle)))
    u = np.tile(u0, (directions, 1))
    r, h, calls = np.zeros(directions), step, np.zeros(2, dtype=int)
    status = np.full(directions, "lost", dtype=STATUS_DTYPE)
    for level in range(levels + 1):
        # each level starts at its rays' last solutions (the centre first), and goes on for
        # three steps of the level before (a step of the secant prediction needs two)
        steps = np.arange(int(np.ceil(reach / h)) + 1) if level == 0 else np.arange(13)
        radii = np.minimum(r + h * steps[:, None], reach)                  # (steps, rays)
        known = np.broadcast_to(centre, radii.shape + (len(centre),)).copy()
        known[..., :2] += radii[..., None] * ray
        tr = trace(known, u)
        calls += tr.nfev, tr.njev
        done = np.sum(tr.status == "converged", axis=0)      # steps before the first failure
        moved = np.flatnonzero(done > 0)
        u[moved], r[moved] = tr.x[done[moved] - 1, moved], radii[done[moved] - 1, moved]
        if level == 0:
            status = np.where(done > 0, "converged", tr.status[0])
        h /= 4.0
    edge = np.broadcast_to(centre, (directions, len(centre))).copy()
    edge[:, :2] += r[:, None] * ray
    return edge, u, status, int(calls[0]), int(calls[1])


def zero_crossings(x, y, values) -> np.ndarray:
    """Where a map over the grid ``x`` by ``y`` changes sign: points on its zero curve.

    Each grid edge whose ends have opposite signs gives one point, by linear interpolation
    (edges touching NaN give none): the singularity curves ``det = 0`` of a map, to the grid's
    resolution.

    Returns
    -------
    ndarray, shape (k, 2)

    Examples
    --------
    >>> g = np.linspace(-1.0, 1.0, 21)
    >>> X, Y = np.meshgrid(g, g, indexing="ij")
    >>> pts = zero_crossings(g, g, X ** 2 + Y ** 2 - 0.25)
    >>> bool(np.allclose(np.hypot(*pts.T), 0.5, atol=0.02)), len(pts)
    (True, 32)
    """
    x, y = _validate.array(x, "x", ndim=1), _validate.array(y, "y", ndim=1)
    v = _validate.array(values, "values", shape=(len(x), len(y)), finite=False)
    X, Y = np.meshgrid(x, y, indexing="ij")
    found = []
    for a, b, Pa, Pb in ((v[:-1], v[1:], (X[:-1], Y[:-1]), (X[1:], Y[1:])),
                         (v[:, :-1], v[:, 1:], (X[:, :-1], Y[:, :-1]), (X[:, 1:], Y[:, 1:]))):
        cut = (a * b < 0) & np.isfinite(a) & np.isfinite(b)
        w = a[cut] / (a[cut] - b[cut])
        found.append(np.column_stack([p[cut] + w * (q[cut] - p[cut]) for p, q in zip(Pa, Pb)]))
    return np.concatenate(found).reshape(-1, 2)


def singular_points(grid, which: str) -> np.ndarray:
    """Points where ``det_fk`` or ``det_ik`` (``which``) of a map changes sign, in the map's
    first two parameters (:func:`zero_crossings`)."""
    check_type(grid, Path, "grid")
    if grid.params.ndim != 3:
        raise ValueError(f"grid must be a map (params of shape (nx, ny, p)), got params of "
                         f"shape {grid.params.shape}")
    values = getattr(grid, _validate.choice(which, ("det_fk", "det_ik"), "which"))
    return zero_crossings(grid.params[:, 0, 0], grid.params[0, :, 1], values)
