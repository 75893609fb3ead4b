"""The 2RFR's atlas: how many equilibria, and how many stable ones, over a grid of motor angles.

:func:`~mechnum.mechanisms.rfr2.atlas` runs :func:`mechnum.rods.assembly.atlas_of` (its
module explains the method: full searches at anchors and where continuation cannot vouch for
the count, continuation everywhere else) with the 2RFR's closed form: the full search is
:func:`~mechnum.mechanisms.rfr2.forward_elliptic` with its defaults, the continuation
``continuation.grid_trace``, as :func:`forward_map` follows one
equilibrium.
"""

from __future__ import annotations

from functools import partial

import numpy as np
from numpy.typing import ArrayLike

from mechnum.mechanisms.rfr2.continuation import grid_trace
from mechnum.mechanisms.rfr2.elliptic import forward_elliptic
from mechnum.mechanisms.rfr2.model import Mechanism, rods
from mechnum.rods import assembly
from mechnum.rods.assembly import atlas as atlases

MAX_ANGLE = 4 * np.pi
"""The largest motor angle of an atlas, two turns either way (rad): an angle is defined modulo a
turn, so no atlas needs more, and a larger one is a slip (degrees passed as radians: 40 degrees
as 40 rad is six turns; 1e300 rad gave overflow warnings and a grid of meaningless angles)."""


def search(mech: Mechanism, modes: tuple, task) -> list:
    """The full search at the motor angles of a task ``(indices, thetas)``: for each point,
    ``(chart, stable, complete, nfev)`` of :func:`forward_elliptic`, its starts drawn from
    ``default_rng([SEED, index])`` (the atlas's tasks, run on its executor's workers)."""
    out = []
    for index, theta in zip(*task):
        eq = forward_elliptic(mech, theta, modes,
                              rng=np.random.default_rng([atlases.SEED, int(index)]))
        out.append((eq.chart, eq.stable, eq.search.complete, eq.nfev))
    return out


def atlas(mech: Mechanism, theta1: ArrayLike, theta2: ArrayLike, *, modes: ArrayLike = (1, 1),
          executor=None) -> atlases.Atlas:
    """The mechanism's equilibria over the grid ``theta1 x theta2`` of motor angles: their
    number, the stable ones, and the folds where the stable count changes.

    The full search (:func:`~mechnum.mechanisms.rfr2.forward_elliptic`, 200 starts and the
    check of 2000) runs at the anchors (one per block of 8 x 8 points) and wherever
    continuation cannot vouch for the count: where an equilibrium known at a point does not
    continue to a neighbour (a branch jump or a lost path: a fold, or the edge of the chart
    where a rod's mode changes), or a neighbour has another count. Everywhere else each
    equilibrium is carried from its neighbours by continuation, with its stability
    (:mod:`mechnum.rods.assembly.atlas`).

    Parameters
    ----------
    mech : Mechanism
    theta1, theta2 : array_like, shapes (nx,) and (ny,)
        The motor angles of the grid's rows and columns (rad), close enough for continuation
        (a few degrees); ``nx ny`` at most :data:`~mechnum.rods.assembly.checks.MAX_POINTS`.
        An empty axis gives an empty atlas. Each angle at most :data:`MAX_ANGLE` in size.
    modes : (int, int), optional
        The rods' buckling modes (as in :func:`~mechnum.mechanisms.rfr2.forward_elliptic`).
    executor : None, int or dask.distributed.Client, optional
        Where the full searches run: None, all local cores (joblib); ``n``, ``n`` local
        workers (1: serially, here; more than the local cores are cut to them, with a
        warning); a dask Client, its cluster (:func:`mechnum.rods.assembly.parallel.run`).
        The result does not depend on it.

    Returns
    -------
    mechnum.rods.assembly.Atlas
        ``counts`` and ``stable_counts`` of shape (nx, ny), ``folds`` in radians,
        ``axes = (theta1, theta2)``; ``draw`` shows it in degrees.

    Raises
    ------
    ValueError
        If ``mech`` is no Mechanism, an axis is not a finite 1-D array of angles within
        :data:`MAX_ANGLE`, the grid too large, ``modes`` not two integers ``>= 1``, or
        ``executor`` none of the above.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7
    >>> g = np.radians(np.arange(36.0, 45.0, 2.0))
    >>> at = atlas(TABLE7, g, g + np.radians(20.0), executor=1)
    >>> at.counts.shape, int(at.searched.sum()) < at.counts.size
    ((5, 5), True)
    """
    assembly.check_type(mech, Mechanism)
    modes = tuple(int(m) for m in assembly.check_modes(modes, 2))
    theta1, theta2 = assembly.grid_axes(theta1, theta2, ("theta1", "theta2"),
                                        monotonic=True)
    for axis, name in ((theta1, "theta1"), (theta2, "theta2")):
        if axis.size and np.abs(axis).max() > MAX_ANGLE:
            raise ValueError(f"{name} must lie within 4 pi rad (two turns) of zero, got angles "
                             f"up to {np.abs(axis).max():.3g} rad (in degrees? np.radians "
                             "converts them)")
    grid = np.stack(np.meshgrid(theta1, theta2, indexing="ij"), axis=-1)

    def lift(theta, chart):
        return np.concatenate((chart, rods(mech, theta, chart, modes, jacobian=False)[0][
            ..., 0, :]), axis=-1)

    trace = grid_trace(mech, np.array(modes, dtype=float), tol=atlases.STEP_TOL,
                       criterion="step")
    problem = atlases.AtlasProblem(partial(search, mech, modes), trace, lift, 4)
    return atlases.atlas_of(problem, grid, ((theta1, theta2), np.zeros(2), np.eye(2)),
                         ("theta1 (deg)", "theta2 (deg)"), np.degrees(1.0), modes, executor)
