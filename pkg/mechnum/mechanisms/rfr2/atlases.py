"""The 2RFR's atlas: how many equilibria, and how many stable ones, over a grid of motor angles.

:func:`~mechnum.mechanisms.rfr2.atlas` runs :func:`mechnum.rods.assembly.atlas_of` (its
module explains the method: full searches at anchors and where continuation cannot vouch for
the count, continuation everywhere else) with the 2RFR's closed form: the full search is
:func:`~mechnum.mechanisms.rfr2.forward_elliptic`'s with its defaults, and the stability of
what it finds (not its crossings or strain, which the atlas does not show); the continuation
follows the rods and the end effector as the motors turn, on the compiled closed form
(:func:`mechnum.rods.kernels.joined`).
"""

from __future__ import annotations

from functools import partial

import numpy as np
from numpy.typing import ArrayLike

from mechnum.mechanisms.rfr2.analysis import stabilities
from mechnum.mechanisms.rfr2.elliptic import CHECK, N_STARTS, in_chart_rows, search_roots
from mechnum.mechanisms.rfr2.model import Mechanism, rods
from mechnum.rods import assembly, kernels
from mechnum.rods.assembly import atlas as atlases


def search(mech: Mechanism, modes: tuple, task) -> list:
    """The full search at the motor angles of a task ``(indices, thetas)``: for each point,
    ``(chart, stable, complete, nfev)`` of :func:`forward_elliptic`, its starts drawn from
    ``default_rng([SEED, index])`` (the atlas's tasks, run on its executor's workers); only
    the stability of the equilibria is classified."""
    out = []
    for point, theta in zip(*task):
        found, nfev, _ = search_roots(mech, theta, modes, N_STARTS, CHECK,
                                      np.random.default_rng([atlases.SEED, int(point)]))
        z = found.x
        index = stabilities(mech, np.broadcast_to(theta, (len(z), 2)), z, modes)
        out.append((z, (index == 0).all(axis=1), found.complete, nfev))
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
        An empty axis gives an empty atlas.
    modes : (int, int), optional
        The rods' buckling modes (as in :func:`~mechnum.mechanisms.rfr2.forward_elliptic`).
    executor : None, int or dask.distributed.Client, optional
        Where the full searches run: None, all local cores (joblib); ``n``, ``n`` local
        workers (1: serially, here); a dask Client, its cluster
        (:func:`mechnum.rods.assembly.parallel.run`). The result does not depend on it.

    Returns
    -------
    mechnum.rods.assembly.Atlas
        ``counts`` and ``stable_counts`` of shape (nx, ny), ``folds`` in radians,
        ``axes = (theta1, theta2)``; ``draw`` shows it in degrees.

    Raises
    ------
    ValueError
        If ``mech`` is no Mechanism, an axis is not a finite 1-D array, the grid too large,
        ``modes`` not two integers ``>= 1``, or ``executor`` none of the above.

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
    grid = np.stack(np.meshgrid(theta1, theta2, indexing="ij"), axis=-1)

    def lift(theta, chart):
        return np.concatenate((chart, rods(mech, theta, chart, modes, jacobian=False)[0][
            ..., 0, :]), axis=-1)

    float_modes = np.array(modes, dtype=float)

    def system(u, theta):
        return kernels.joined(mech.EI, mech.L, mech.origins, theta, float_modes, mech.force, u)

    problem = atlases.AtlasProblem(partial(search, mech, modes), system,
                                   lambda u: in_chart_rows(u[:, :4]), lift, 4)
    return atlases.atlas_of(problem, grid, ((theta1, theta2), np.zeros(2), np.eye(2)),
                         ("theta1 (deg)", "theta2 (deg)"), np.degrees(1.0), modes, executor)
