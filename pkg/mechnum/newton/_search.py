"""Every root damped Newton finds from many starts: :func:`solve_all`, with the evidence.

Examples
--------
>>> import numpy as np
>>> found = solve_all(lambda z: z ** 2 - 1.0, lambda rng, m: rng.uniform(-2, 2, (m, 1)),
...                   lambda z: 2 * z[:, :, None], n_starts=20, rng=0)
>>> found.x.tolist(), found.complete
([[-1.0], [1.0]], True)
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.newton._batch import solve_batch
from mechnum.newton._core import HALVINGS_LIMIT, ROOT_TOL, SEARCH_HALVINGS, Equations
from mechnum.results import Result, status_counts

STARTS_LIMIT = 10_000_000
"""The most starts of one search, check included (``n_starts (1 + check)`` plus the ``seeds``):
a batch of that many Newton iterations holds a few gigabytes of Jacobians for ``n = 6``."""
SAME = 1e-8
"""Default distance (largest component) below which two converged starts are one root: far above
the round-off of a converged root (the tolerance, ``1e-12``), far below the
distance between two roots that a mechanism can tell apart."""


@dataclass(frozen=True, kw_only=True)
class RootSet(Result):
    """The outcome of :func:`solve_all`: the distinct roots, and how hard they were looked for.

    Attributes
    ----------
    x : ndarray, shape (r, n)
        The distinct roots, ``r >= 0``, in the order of their first component.
    status, iterations : ndarray, shape (starts,)
        What became of every start (the given ``seeds``, then the search's, then the
        check's), and its Newton steps.
    message : str
        The count of roots and of the starts' outcomes.
    nfev, njev : int
        Calls of ``fun`` and ``jac`` (on batches).
    hits : ndarray of int, shape (r,)
        How many starts (of both runs) converged to each root: a root with few hits has a small
        basin of attraction, a warning that others like it may have been missed.
    residual_norms : ndarray, shape (r,)
        ``||f||`` at each root.
    n_starts : int
        Starts of the search.
    n_check : int
        Starts of the completeness check (new ones, ``check`` times as many).
    new_in_check : int
        Roots that only the check found (they are in ``roots``). Zero is the evidence of
        completeness: ten times more starts found nothing new. It is evidence, not proof: a
        root whose basin no start hits stays unseen.
    """

    hits: np.ndarray
    residual_norms: np.ndarray
    n_starts: int
    n_check: int
    new_in_check: int

    @property
    def status_counts(self) -> dict:
        """dict: how many starts of both runs ended in each word of
        :data:`~mechnum.results.STATUSES`."""
        return status_counts(self.status)

    @property
    def complete(self) -> bool:
        """bool: whether the completeness check found no new root."""
        return self.new_in_check == 0


def _distinct(points, same):
    """Group the rows of ``points`` that lie within ``same`` (inf-norm) of a group's first row.

    Returns the representatives and, for every row, the index of its group (one pass over
    the groups, each comparing all the rows at once)."""
    label = np.full(len(points), -1)
    reps = []
    while (free := np.flatnonzero(label < 0)).size:
        rep = points[free[0]]
        near = free[np.max(np.abs(points[free] - rep), axis=1) <= same]
        label[near] = len(reps)
        reps.append(rep)
    return np.array(reps).reshape(-1, points.shape[1]), label


def solve_all(fun: Callable, sample: Callable, jac: Callable | bool | None = None, *,
              n_starts: int = 1000, check: int = 10,
              rng: np.random.Generator | int | None = None, seeds: ArrayLike | None = None,
              tol: float = ROOT_TOL, maxiter: int = 50, domain: Callable | None = None,
              same: float = SAME, halvings: int = SEARCH_HALVINGS) -> RootSet:
    """Every root that damped Newton finds from many starts, deduplicated, with evidence.

    The search runs :func:`~mechnum.newton.solve_batch` (damped, with the status of each
    start) from ``n_starts`` starts drawn by ``sample`` (after any given ``seeds``); starts that
    stagnate, leave the ``domain`` or hit a singular Jacobian are dropped. The converged ends
    are grouped into distinct roots (those within ``same`` of each other) and counted. A
    completeness check runs ``check * n_starts`` new starts: the number of roots that only it
    finds, ``new_in_check``, is zero when the search looks complete. The starts of both run in
    one batch (each ends as it would alone: the systems are independent), the search's first.

    Parameters
    ----------
    fun : callable
        The batched residual, ``fun(x) -> (batch, n)`` for ``x`` of shape ``(batch, n)``; with
        ``jac=True``, ``fun(x) -> (f, J)``.
    sample : callable
        ``sample(rng, m) -> ndarray (m, n)``: ``m`` random starts.
    jac : callable, True or None, optional
        The batched Jacobian, ``(batch, n, n)``, or ``True``; default forward differences.
    n_starts : int, optional
        Random starts of the search, ``>= 1``.
    check : int, optional
        The completeness check uses ``check * n_starts`` starts; 0 skips it. The starts of
        both runs are at most :data:`STARTS_LIMIT`.
    rng : numpy.random.Generator or int, optional
        The random generator (or its seed): no hidden randomness.
    seeds : array_like, shape (m, n), optional
        Initial guesses tried before the random starts (a continuation's points, starts aimed
        at small basins).
    tol, maxiter, domain
        As in :func:`~mechnum.newton.solve_batch` (``criterion="step"``, relative); ``fun``,
        ``jac`` and ``domain`` must not depend on the position in the batch
        (``independent=True``).
    same : float, optional
        Two converged points closer than this (largest component) are one root.
    halvings : int, optional
        Most halvings of a Newton step (default 4: a start whose step must be cut below 1/16
        lies where Newton's linear model is poor, and dropping it costs hits, not roots); a
        start that needs more is dropped, as "stagnated" or "left-domain".

    Returns
    -------
    RootSet

    Raises
    ------
    ValueError
        An invalid option, ``sample`` returning the wrong shape or non-finite starts, or
        ``fun``, ``jac``, ``domain`` returning the wrong shapes.

    Examples
    --------
    The circle ``x**2 + y**2 = 4`` meets the hyperbola ``x y = 1`` in four points:

    >>> import numpy as np
    >>> fun = lambda z: np.stack([z[:, 0]**2 + z[:, 1]**2 - 4, z[:, 0] * z[:, 1] - 1], axis=-1)
    >>> jac = lambda z: np.stack([np.stack([2 * z[:, 0], 2 * z[:, 1]], -1),
    ...                           np.stack([z[:, 1], z[:, 0]], -1)], axis=1)
    >>> found = solve_all(fun, lambda rng, m: rng.uniform(-3, 3, (m, 2)), jac, n_starts=200, rng=0)
    >>> found.x.round(6).tolist()
    [[-1.931852, -0.517638], [-0.517638, -1.931852], [0.517638, 1.931852], [1.931852, 0.517638]]
    >>> found.complete, bool(found.hits.sum() == found.status_counts["converged"])
    (True, True)
    """
    rng = _validate.rng(rng)
    n_starts = _validate.maxiter(n_starts, "n_starts", maximum=STARTS_LIMIT)
    check = _validate.maxiter(check, "check", minimum=0, maximum=STARTS_LIMIT // n_starts - 1)
    same = _validate.tolerance(same, "same")
    halvings = _validate.maxiter(halvings, "halvings", maximum=HALVINGS_LIMIT)
    if not callable(sample):
        raise ValueError(f"sample must be callable, got {_validate.shown(sample)}")
    Equations(fun, jac)  # fun and jac checked before any work
    extra = None if seeds is None else _validate.array(seeds, "seeds", ndim=2)
    width = None if extra is None else extra.shape[1]
    parts = []
    for m, given in ((n_starts, extra), (check * n_starts, None)):
        starts = _sample(sample, rng, m, width) if m else np.empty((0, width or 0))
        width = starts.shape[1] if m else width
        parts.append(starts if given is None else np.concatenate([given, starts]))
    # the search and its check in one lockstep batch: the starts are independent, so each
    # ends as it would alone, and a few slow ones cost no more than they do alone
    run = solve_batch(fun, np.concatenate(parts).reshape(-1, width), jac, tol=tol,
                      maxiter=maxiter, damping=True, domain=domain, raise_on_failure=False,
                      independent=True, halvings=halvings)
    split = len(parts[0])
    ends = [run.x[:split][run.converged[:split]], run.x[split:][run.converged[split:]]]
    roots, label = _distinct(np.concatenate(ends).reshape(-1, width), same)
    first = len(np.unique(label[:len(ends[0])]))
    order = np.lexsort(roots.T[::-1]) if len(roots) else np.arange(0)
    hits = np.bincount(label, minlength=len(roots))
    residual_norms = (np.linalg.norm(Equations(fun, jac).value(roots[order])[0], axis=-1)
                      if len(roots) else np.empty(0))
    counts = {s: c for s, c in status_counts(run.status).items() if c}
    return RootSet(x=roots[order], status=run.status,
                   message=f"{len(roots)} roots from {len(run.status)} starts ({counts}); "
                           f"{len(roots) - first} new in the check",
                   iterations=run.iterations, nfev=run.nfev + bool(len(roots)),
                   njev=run.njev, hits=hits[order],
                   residual_norms=residual_norms, n_starts=n_starts, n_check=check * n_starts,
                   new_in_check=len(roots) - first)


def _sample(sample, rng, m, width):
    """``m`` starts from ``sample``, checked: finite, shape ``(m, n)`` (``n = width`` if
    known)."""
    starts = _validate.array(sample(rng, m), "the starts that sample returned", ndim=2)
    if len(starts) != m or starts.shape[1] == 0 or width not in (None, starts.shape[1]):
        want = f"({m}, {width if width is not None else 'n'})"
        raise ValueError(f"sample(rng, {m}) must return {m} starts, shape {want}, got shape "
                         f"{starts.shape}")
    return starts
