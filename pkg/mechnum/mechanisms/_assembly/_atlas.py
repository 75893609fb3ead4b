"""The atlas of a mechanism's assemblies: over a grid of its inputs, how many equilibria it has
at every point, how many of them are stable, and where the stable count changes.

An all-solutions search at every point of a 41 x 41 grid would be 1681 searches. Most of them
would only confirm what the neighbours already say: an equilibrium moves continuously with the
inputs, and the count changes only where a branch ends (a fold, where two equilibria meet and
vanish; or the edge of the chart, where a rod's buckling mode changes). So :func:`atlas_of` finds
the equilibria at a few points, follows each one by continuation to its neighbours, and searches
fully only where the continuation cannot vouch for the count:

1. **Anchors.** The full search (the mechanism's ``forward``: random starts and the ten-times
   check) runs at the anchors: one point per block of :data:`ANCHOR_SPACING` x
   :data:`ANCHOR_SPACING` grid points, at its centre.
2. **Flood.** Every equilibrium found is followed from its point to each of the four neighbours
   (a converged step on the same branch, never across a fold, as
   :func:`follow` decides it; a step that fails is tried again in
   :data:`REFINE` shorter steps), and from every point it reaches on to theirs, until it
   reaches no new point; each point keeps the distinct equilibria that arrive (within
   :data:`SAME` in the chart). Each round of the flood takes its steps for all its edges at
   once, in one lockstep damped Newton on the mechanism's system
   (``track_paths``).
3. **Vouching.** A point's count is *vouched* by continuation when every equilibrium known
   there continued to every neighbour, onto distinct equilibria there, and every equilibrium
   known at every neighbour continued to it: no branch ends on an edge of the point, from
   either side. Where one does (a lost path or a branch jump: a fold nearby, where its partner
   may be unknown, or the chart's edge, or a singular point on the grid) or two land on one
   (a jump), continuation cannot vouch for the count. A count that differs between two
   neighbours is always of this kind (the equilibria of the point with more that the other
   lacks end on the edge between them: had one continued, the flood would have brought it
   over), so both ends of every edge across which the count changes are searched. One
   exception: ends that pair up one-to-one across an edge, with the same position (or pose)
   to within what one step moves it and the same verdict, are taken for one equilibrium
   leaving the chart on one side and entering it on the other (:func:`_paired`).
4. **Search where it cannot vouch.** The points that are not vouched get the full search, a
   spread subset of them per round (:func:`_spread`); what it finds that was unknown is
   flooded in turn (step 2), and steps 3 and 4 repeat until every point is vouched or
   searched.

Stability is carried along the flood: an equilibrium's index (negative eigenvalues of its second
variation) changes only where its Jacobian is singular, where continuation never passes (the
sign of ``det`` is kept), so each equilibrium keeps the verdict of the search that found it; at
a searched point the search's own verdict is used. The evidence: searched counts are the
search's (sampled: the ``complete`` of its ``RootSet``); a vouched count is the count of a
searched point carried over edges where nothing ends. An equilibrium whose whole region of the
grid holds no searched point (an isola, or a sliver narrower than the anchors' spacing that
touches no fold of a known branch) is missed: sampling, not proof.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechnum.mechanisms._assembly import _parallel as parallel
from mechnum.mechanisms._assembly._checks import MAX_POINTS, STATUS_DTYPE
from mechnum.mechanisms._assembly._lockstep import track_paths
from mechnum.mechanisms._assembly._results import State
from mechnum.results import Result

ANCHOR_SPACING = 8
"""Grid points between anchors (the full searches that seed the flood), along each axis."""
SAME = 1e-6
"""Two equilibria at one point are one when their charts differ by less than this (largest
coordinate): continuation converges to ``1e-12`` in the residual, a search to ``1e-12`` in the
step, and distinct equilibria lie far apart."""
FLOOD_BATCH = 20_000
"""Most continuation steps in one batch of the flood (the memory of a batch grows with it)."""
REFINE = 8
"""Steps of the second try of a continuation step that failed: a branch that truly ends
between two points (a fold, the chart's edge) fails again, a numerical failure (a large step
near a fold) does not."""
STEP_TOL = 1e-10
"""Newton's tolerance per continuation step of the atlas, on the step and relative (the
default of ``mechnum.newton.solve``): the residual of a rod in strong tension cannot fall below a
round-off floor that grows with its force (``1e-11`` of ``EI / L**2`` at ``t = 0.99``), where a
fixed residual tolerance would end sound branches."""
PAIRED = 2.0
"""Two equilibria that ended on the two sides of one edge are one, seen in two charts, when
their unknowns past the chart differ by at most this many times the largest change of those
in one continuation step (:func:`_paired`): one equilibrium moves that much from one point to
the next; distinct ones lie farther apart, except at a fold, where no partner waits across."""
SPREAD = 2
"""Searches of one round lie more than this many grid points apart (:func:`_spread`)."""
SEED = 20_250_625
"""The seed of the searches' random starts, with the point's index: ``default_rng([SEED,
index])``, the same on every executor."""
_DIRECTIONS = ((1, 0), (-1, 0), (0, 1), (0, -1))
LEFT = -3   # an equilibrium that left the chart's domain between two points


@dataclass(frozen=True)
class AtlasProblem:
    """What :func:`atlas_of` needs of a mechanism.

    Attributes
    ----------
    search : callable
        ``search((rngs, inputs)) -> list of (chart (r, c), stable (r,), complete, nfev)``:
        the full search at each point of a task, its starts drawn from its ``rng``
        (``default_rng([SEED, index])`` of the point's index, the same on every executor).
        Importable (it runs on the executor's workers).
    system : callable
        ``system(u (rows, m), inputs (rows, k)) -> (G (rows, m), D (rows, m, m))``: the direct
        problem in the continuation's unknowns ``u`` (the chart first), its residual and
        Jacobian in one call, unchecked.
    domain : callable
        ``domain(u (rows, m)) -> (rows,) bool``: where ``system`` is defined (the chart).
    lift : callable
        ``lift(inputs (r, k), chart (r, c)) -> u (r, m)``: a search's equilibria as the
        continuation's unknowns (the chart first).
    chart : int
        ``c``, the chart's width.
    """

    search: object
    system: object
    domain: object
    lift: object
    chart: int


@dataclass(frozen=True, kw_only=True)
class Atlas(Result):
    """The assemblies of a mechanism over a grid of its inputs (:func:`atlas_of`).

    ``status`` per point is "converged" where the count is vouched
    by continuation or searched with a complete check, "undecided" where the search's check
    found equilibria that its first starts had missed (its evidence is weaker); ``iterations``
    per point are the Newton steps of the continuation steps into it.

    Attributes
    ----------
    x : ndarray, shape (nx, ny, m, c)
        The equilibria at every point, the rods in the regular chart (NaN beyond its count),
        in the order they were found.
    inputs : ndarray, shape (nx, ny, k)
        The inputs at every grid point (SI units).
    axes : (ndarray (nx,), ndarray (ny,))
        The map's coordinates of the grid's rows and columns: the inputs at ``(i, j)`` are
        ``origin + axes[0][i] directions[0] + axes[1][j] directions[1]``.
    origin : ndarray, shape (k,)
    directions : ndarray, shape (2, k)
    labels : (str, str)
        The axes' names with the units of ``scale``; ``scale`` multiplies ``axes`` for display.
    counts, stable_counts : ndarray of int, shape (nx, ny)
        Equilibria, and stable ones, at every point.
    stable : ndarray of bool, shape (nx, ny, m)
        Which of them are stable.
    searched, vouched : ndarray of bool, shape (nx, ny)
        Where the full search ran; where continuation vouched for the count.
    folds : ndarray, shape (f, 2)
        The midpoints (in ``axes``) of the grid edges across which the stable count changes:
        where a stable assembly appears, disappears or loses stability, to the grid's step.
    modes : tuple of int
    """

    inputs: np.ndarray
    axes: tuple
    origin: np.ndarray
    directions: np.ndarray
    labels: tuple
    scale: float
    counts: np.ndarray
    stable_counts: np.ndarray
    stable: np.ndarray
    searched: np.ndarray
    vouched: np.ndarray
    folds: np.ndarray
    modes: tuple

    def state(self, i: int, j: int, k: int) -> State:
        """Equilibrium ``k`` at the grid point ``(i, j)``, for the mechanism's ``draw``."""
        if not 0 <= k < self.counts[i, j]:
            raise ValueError(f"the point ({i}, {j}) has {self.counts[i, j]} equilibria, no "
                             f"equilibrium {k}")
        return State(self.inputs[i, j].copy(), self.x[i, j, k].copy(), self.modes)

    def coordinates(self, inputs) -> np.ndarray:
        """The map's coordinates ``(..., 2)`` of inputs ``(..., k)`` (projected on its plane)."""
        inputs = np.asarray(inputs, dtype=float)
        return np.linalg.lstsq(self.directions.T, (inputs - self.origin).reshape(-1, len(
            self.origin)).T, rcond=None)[0].T.reshape(inputs.shape[:-1] + (2,))

    def draw(self, ax, *, trajectory=None, **style):
        """The stable count as a map with the folds drawn on it, and optionally a trajectory
        (``draw_atlas``); its artists."""
        from mechnum.mechanisms._assembly._drawing import draw_atlas

        return draw_atlas(ax, self, trajectory=trajectory, **style)


class _Store:
    """The equilibria known at every grid point: ``u`` (points, slots, m), their verdicts, and
    where each went in each direction (-2 untried, -1 it ended, :data:`LEFT` it left the
    chart's domain, else its slot there)."""

    def __init__(self, points: int, width: int, chart: int):
        self.u = np.full((points, 0, width), np.nan)
        self.stable = np.zeros((points, 0), dtype=bool)
        self.went = np.full((points, 0, 4), -2)
        self.count = np.zeros(points, dtype=int)
        self.chart = chart
        self.move = 0.0     # the largest change of the unknowns past the chart in one step

    def _room(self, slots: int):
        extra = slots - self.u.shape[1]
        if extra > 0:
            self.u = np.pad(self.u, ((0, 0), (0, extra), (0, 0)), constant_values=np.nan)
            self.stable = np.pad(self.stable, ((0, 0), (0, extra)))
            self.went = np.pad(self.went, ((0, 0), (0, extra), (0, 0)), constant_values=-2)

    def insert(self, points, u, stable, *, verdict=False):
        """Add equilibria ``u`` at ``points`` unless known there (within :data:`SAME`, also
        among themselves); with ``verdict``, their ``stable`` replaces a known one's. Returns
        each one's slot and whether it is new."""
        slots, new = np.full(len(points), -1), np.zeros(len(points), dtype=bool)
        pending = np.arange(len(points))
        while pending.size:
            c = self.chart
            gap = np.abs(self.u[points[pending], :, :c] - u[pending, None, :c]).max(axis=-1)
            gap = np.where(np.isnan(gap), np.inf, gap)
            match = np.argmin(gap, axis=1) if gap.shape[1] else np.zeros(len(pending), int)
            known = gap[np.arange(len(pending)), match] < SAME if gap.shape[1] else match < 0
            slots[pending[known]] = match[known]
            if verdict:
                self.stable[points[pending[known]], match[known]] = stable[pending[known]]
            rest = pending[~known]
            first = rest[np.unique(points[rest], return_index=True)[1]]   # one per point
            at = points[first]
            self._room(int(self.count[at].max(initial=0)) + 1)
            slots[first], new[first] = self.count[at], True
            self.u[at, self.count[at]] = u[first]
            self.stable[at, self.count[at]] = stable[first]
            self.count[at] += 1
            pending = np.setdiff1d(rest, first)
        return slots, new


def _neighbours(nx: int, ny: int) -> np.ndarray:
    """The flat index of each point's neighbour in each of :data:`_DIRECTIONS`, -1 if none."""
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    out = np.full((nx * ny, 4), -1)
    for d, (di, dj) in enumerate(_DIRECTIONS):
        inside = (0 <= i + di) & (i + di < nx) & (0 <= j + dj) & (j + dj < ny)
        out[:, d] = np.where(inside, (i + di) * ny + (j + dj), -1).ravel()
    return out


def anchors(nx: int, ny: int, spacing: int = ANCHOR_SPACING) -> np.ndarray:
    """The flat indices of the anchors of an ``nx`` x ``ny`` grid: the centres of blocks of
    about ``spacing`` points along each axis (at least one block per axis).

    Examples
    --------
    >>> anchors(41, 41).size, anchors(9, 9).tolist()
    (25, [40])
    """
    def centres(n):
        blocks = max(1, round(n / spacing))
        return ((np.arange(blocks) + 0.5) * n / blocks).astype(int) if n else np.arange(0)

    i, j = np.meshgrid(centres(nx), centres(ny), indexing="ij")
    return (i * ny + j).ravel()


def _continue(problem, inputs, start, end, u0, tally):
    """Continuation from the points ``start`` (their equilibria ``u0``) to the points ``end``:
    one step, then, for the equilibria that fail, :data:`REFINE` steps as long together.
    Returns which arrived, where, and which of the others left the chart's domain (the first
    of the short steps to fail did so with the status "left-domain")."""
    ok, x = np.zeros(len(start), dtype=bool), np.full(u0.shape, np.nan)
    left = np.zeros(len(start), dtype=bool)
    for attempt in range(2):
        rows = np.flatnonzero(~ok)
        path = np.stack((inputs[start], inputs[end])) if attempt == 0 else np.linspace(
            inputs[start[rows]], inputs[end[rows]], REFINE + 1)
        status, end_x, iterations, calls = track_paths(problem.system, problem.domain,
                                                       problem.chart, path, u0[rows],
                                                       tol=STEP_TOL)
        tally["nfev"] += calls
        tally["njev"] += calls
        tally["steps"] += len(rows) * (len(path) - 1)
        np.add.at(tally["iterations"], end[rows], iterations[1:].sum(axis=0))
        arrived = status[-1] == "converged"
        ok[rows[arrived]], x[rows[arrived]] = True, end_x[arrived]
        if ok.all():
            break
    first = np.argmax(status != "converged", axis=0)
    left[rows] = (status[first, np.arange(len(rows))] == "left-domain") & ~ok[rows]
    return ok, x, left


def _flood(store, entries, problem, inputs, neighbours, tally):
    """Follow the equilibria ``entries`` (points, slots) to their neighbours, and on, until no
    new point is reached."""
    while entries[0].size:
        pts, slots, dirs = (np.repeat(entries[0], 4), np.repeat(entries[1], 4),
                            np.tile(np.arange(4), entries[0].size))
        to = neighbours[pts, dirs]
        keep = (to >= 0) & (store.went[pts, slots, dirs] == -2)
        pts, slots, dirs, to = pts[keep], slots[keep], dirs[keep], to[keep]
        found = ([], [])
        for part in range(0, len(pts), FLOOD_BATCH):
            p, k, d, q = (a[part:part + FLOOD_BATCH] for a in (pts, slots, dirs, to))
            ok, x, left = _continue(problem, inputs, p, q, store.u[p, k], tally)
            store.went[p, k, d] = np.where(left, LEFT, -1)
            c = store.chart
            store.move = max(store.move, np.abs(x[ok, c:] - store.u[p[ok], k[ok], c:]).max(
                initial=0.0))
            there, new = store.insert(q[ok], x[ok], store.stable[p, k][ok])
            store.went[p[ok], k[ok], d[ok]] = there
            found[0].append(q[ok][new])
            found[1].append(there[new])
        entries = tuple(np.concatenate(f).astype(int) if f else np.zeros(0, int) for f in found)


def _vouched(store, neighbours) -> np.ndarray:
    """Where continuation vouches for the count (see the module): no equilibrium ended on an
    edge of the point, from either side, unless the ends pair up across it (:func:`_paired`),
    or left the chart's domain from the point's side; and no two landed on one."""
    slots = store.u.shape[1]
    valid = np.arange(slots) < store.count[:, None]                     # (points, slots)
    exists = (neighbours >= 0)[:, None, :]
    hard = valid[..., None] & ((store.went == -1) | (store.went == -2) & exists)
    ends = hard | valid[..., None] & (store.went == LEFT)
    broken = np.zeros(len(store.count), dtype=bool)
    for d in (0, 2):                                  # each edge once: towards +i and +j
        p = np.flatnonzero(neighbours[:, d] >= 0)
        q = neighbours[p, d]
        for a, b in zip(*(x[ends[p, :, d].any(axis=1) | ends[q, :, d ^ 1].any(axis=1)]
                          for x in (p, q))):
            if _paired(store, a, np.flatnonzero(ends[a, :, d]), b,
                       np.flatnonzero(ends[b, :, d ^ 1])):
                continue
            if hard[a, :, d].any() or hard[b, :, d ^ 1].any():
                broken[[a, b]] = True
            else:       # only exits from the chart: the far side may hold them in another form
                broken[a] |= ends[b, :, d ^ 1].any()
                broken[b] |= ends[a, :, d].any()
    marks = np.where(valid[..., None], store.went, -10 - np.arange(slots)[None, :, None])
    marks = np.sort(marks, axis=1)
    distinct = ~((np.diff(marks, axis=1) == 0) & (marks[:, 1:] >= 0)).any(axis=(1, 2))
    return ~broken & distinct


def _paired(store, a, ended_a, b, ended_b) -> bool:
    """Whether the equilibria ``ended_a`` (slots at point ``a``) that ended towards ``b`` and
    those ``ended_b`` that ended towards ``a`` are one-to-one the same equilibria seen in two
    charts: their unknowns past the chart (a position, a pose) closer than
    :data:`PAIRED` times the largest change of them in one continuation step, with one
    verdict. An equilibrium that leaves the chart on one side of an edge and enters it on the
    other (an angle of the chart wraps) is one of these; at a fold or at a change of mode no
    partner waits on the other side."""
    c = store.chart
    if len(ended_a) != len(ended_b) or store.u.shape[-1] == c or store.move == 0.0:
        return False
    # (ended_a, ended_b): u[b, None, ended_b] would put ended_b's axis first (the indices
    # b and ended_b apart), so the pairs are formed from the two gathered blocks
    gap = np.abs(store.u[a, ended_a, c:][:, None] - store.u[b, ended_b, c:][None]).max(axis=-1)
    gap[store.stable[a, ended_a][:, None] != store.stable[b, ended_b][None, :]] = np.inf
    nearest = gap.argmin(axis=1)
    return (len(set(nearest.tolist())) == len(nearest)
            and bool((gap[np.arange(len(nearest)), nearest] <= PAIRED * store.move).all()))


def _search(problem, store, todo, inputs, executor, searched, undecided, tally):
    """The full search at the points ``todo``, in parallel; what it finds joins the store (its
    verdicts replace the carried ones there). Returns the new equilibria, for the flood."""
    tasks = [([np.random.default_rng([SEED, int(i)]) for i in idx], inputs[idx])
             for idx in parallel.chunks(list(todo), executor)]
    results = [r for chunk in parallel.run(problem.search, tasks, executor) for r in chunk]
    searched[todo] = True
    tally["searches"] += len(todo)
    pts, charts, stable = [], [], []
    for point, (chart, verdicts, complete, nfev) in zip(todo, results):
        undecided[point] = not complete
        tally["nfev"] += nfev
        pts.append(np.full(len(chart), point))
        charts.append(chart)
        stable.append(verdicts)
    pts = np.concatenate(pts).astype(int)
    if not pts.size:
        return pts, pts
    u = problem.lift(inputs[pts], np.concatenate(charts))
    slots, new = store.insert(pts, u, np.concatenate(stable), verdict=True)
    return pts[new], slots[new]


def atlas_of(problem: AtlasProblem, inputs: np.ndarray, frame: tuple, labels: tuple, scale: float,
          modes: tuple, executor=None) -> Atlas:
    """The :class:`Atlas` of a mechanism over the grid ``inputs`` (nx, ny, k), by the method of
    the module.

    Parameters
    ----------
    problem : AtlasProblem
        The mechanism's search, continuation and chart.
    inputs : ndarray, shape (nx, ny, k)
        The inputs at the grid's points, neighbours close enough for continuation (an empty
        grid is valid); ``nx ny`` at most :data:`~mechnum.mechanisms._assembly.MAX_POINTS`.
    frame : (axes, origin, directions)
        The map's coordinates, as :class:`Atlas` holds them.
    labels, scale, modes
        As :class:`Atlas` holds them.
    executor : None, int or dask.distributed.Client, optional
        Where the full searches run (:func:`~mechnum.mechanisms._assembly.run`).

    Returns
    -------
    Atlas
    """
    executor = parallel.checked(executor)
    nx, ny, k = inputs.shape
    if nx * ny > MAX_POINTS:
        raise ValueError(f"a grid of {nx} x {ny} points is more than {MAX_POINTS} (a bound on "
                         "the work)")
    flat = inputs.reshape(nx * ny, k)
    width = problem.lift(flat[:0], np.zeros((0, problem.chart))).shape[-1]
    store, neighbours = _Store(nx * ny, width, problem.chart), _neighbours(nx, ny)
    searched = np.zeros(nx * ny, dtype=bool)
    undecided = np.zeros(nx * ny, dtype=bool)
    tally = {"nfev": 0, "njev": 0, "steps": 0, "searches": 0,
             "iterations": np.zeros(nx * ny, dtype=int)}
    todo = anchors(nx, ny)
    vouched = np.zeros(nx * ny, dtype=bool)
    while todo.size:
        entries = _search(problem, store, todo, flat, executor, searched, undecided, tally)
        _flood(store, entries, problem, flat, neighbours, tally)
        vouched = _vouched(store, neighbours)
        todo = _spread(np.flatnonzero(~vouched & ~searched), ny)
    return _result(store, inputs, frame, labels, scale, modes, searched, vouched, undecided,
                   tally)


def _spread(todo: np.ndarray, ny: int) -> np.ndarray:
    """The points of ``todo`` (flat indices, rows of ``ny``) to search in this round: each
    farther than :data:`SPREAD` points (along either axis) from those chosen before it. What
    one search finds floods along its line of ends, and may pair up the ends of its
    neighbours (:func:`_paired`), which then need no search.

    Examples
    --------
    >>> _spread(np.arange(8), 8).tolist()
    [0, 3, 6]
    """
    chosen, taken = [], np.zeros((0, 2), dtype=int)
    for point in todo:
        ij = np.array(divmod(int(point), ny))
        if not len(taken) or np.abs(taken - ij).max(axis=1).min() > SPREAD:
            chosen.append(point)
            taken = np.vstack((taken, ij))
    return np.array(chosen, dtype=int)


def _folds(stable_counts, axes) -> np.ndarray:
    """The midpoints of the grid edges across which ``stable_counts`` changes."""
    A, B = np.meshgrid(*(np.asarray(axis, dtype=float) for axis in axes), indexing="ij")
    rows = stable_counts[1:] != stable_counts[:-1]
    cols = stable_counts[:, 1:] != stable_counts[:, :-1]
    return np.concatenate((np.column_stack((0.5 * (A[1:] + A[:-1])[rows], B[1:][rows])),
                           np.column_stack((A[:, 1:][cols], 0.5 * (B[:, 1:] + B[:, :-1])[cols]))
                           )).reshape(-1, 2)


def _result(store, inputs, frame, labels, scale, modes, searched, vouched, undecided, tally):
    nx, ny = inputs.shape[:2]
    axes, origin, directions = frame
    slots = store.u.shape[1]
    valid = np.arange(slots) < store.count[:, None]
    stable = store.stable & valid
    counts = store.count.reshape(nx, ny)
    stable_counts = stable.sum(axis=1).reshape(nx, ny)
    status = np.where(undecided, "undecided", "converged").astype(STATUS_DTYPE).reshape(nx, ny)
    folds = _folds(stable_counts, axes)
    message = (f"{nx} x {ny} points: {int(searched.sum())} searched ({anchors(nx, ny).size} "
               f"anchors), {int((vouched & ~searched).sum())} vouched by continuation "
               f"({tally['steps']} steps); {len(folds)} grid edges where the stable count "
               f"changes; {int(undecided.sum())} searches whose check found more")
    return Atlas(x=store.u[..., :store.chart].reshape(nx, ny, slots, store.chart),
                 status=status, message=message,
                 iterations=tally["iterations"].reshape(nx, ny), nfev=tally["nfev"],
                 njev=tally["njev"], inputs=inputs, axes=tuple(axes), origin=origin,
                 directions=directions, labels=labels, scale=scale,
                 counts=counts, stable_counts=stable_counts,
                 stable=stable.reshape(nx, ny, slots), searched=searched.reshape(nx, ny),
                 vouched=vouched.reshape(nx, ny), folds=folds, modes=tuple(modes))
