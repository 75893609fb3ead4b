"""The 2RFR's atlas: how many equilibria, and how many stable ones, over a grid of motor angles.

:func:`~mechnum.mechanisms.rfr2.atlas` runs :func:`mechnum.mechanisms._assembly.atlas_of` (its
module explains the method: full searches at anchors and where continuation cannot vouch for
the count, continuation everywhere else) with the 2RFR's closed form: the full search is
:func:`~mechnum.mechanisms.rfr2.forward`'s with its defaults, and the stability of what it
finds (not its crossings or strain, which the atlas does not show); the continuation follows
the rods and the end effector as the motors turn, on the compiled closed form
(:class:`mechnum.rods.MeetingRods`).
"""

from __future__ import annotations

from functools import partial

import numpy as np
from numpy.typing import ArrayLike

from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.rfr2._analysis import stabilities
from mechnum.mechanisms.rfr2._elliptic import CHECK, N_STARTS, in_chart_rows, search_roots
from mechnum.mechanisms.rfr2._model import Mechanism, rods
from mechnum.rods import MeetingRods

MAX_ANGLE = 4 * np.pi
"""The largest motor angle of an atlas, two turns either way (rad): an angle is defined modulo a
turn, so no atlas needs more, and a larger one is a slip (degrees passed as radians: 40 degrees
as 40 rad is six turns; 1e300 rad gave overflow warnings and a grid of meaningless angles)."""


def search(mech: Mechanism, modes: tuple, task: tuple) -> list:
    """The full search at the motor angles of a task ``(rngs, thetas)``: for each point,
    ``(chart, stable, complete, nfev)`` of :func:`~mechnum.mechanisms.rfr2.forward`, its
    starts drawn from its ``rng`` (the atlas's tasks, run on its executor's workers); only the
    stability of the equilibria is classified."""
    out = []
    for rng, theta in zip(*task):
        found, nfev, _ = search_roots(mech, theta, modes, N_STARTS, CHECK, rng)
        z = found.x
        index = stabilities(mech, np.broadcast_to(theta, (len(z), 2)), z, modes)
        out.append((z, (index == 0).all(axis=1), found.complete, nfev))
    return out


def atlas(mech: Mechanism, a: ArrayLike, b: ArrayLike, *, origin: ArrayLike | None = None,
          directions: ArrayLike | None = None, modes: ArrayLike = (1, 1),
          executor: object = None) -> assembly.Atlas:
    """The mechanism's equilibria over a grid of motor angles: their number, the stable ones,
    and the folds where the stable count changes.

    The grid is ``theta[i, j] = origin + a[i] directions[0] + b[j] directions[1]``: by default
    ``theta1 = a[i]``, ``theta2 = b[j]``. The full search
    (:func:`~mechnum.mechanisms.rfr2.forward`, 200 starts and the check of 2000) runs at the
    anchors (one per block of 8 x 8 points) and wherever continuation cannot vouch for the
    count: where an equilibrium known at a point does not continue to a neighbour (a branch
    jump or a lost path: a fold, or the edge of the chart where a rod's mode changes), or a
    neighbour has another count. Everywhere else each equilibrium is carried from its
    neighbours by continuation, with its stability (``assembly``'s atlas module).

    Parameters
    ----------
    mech : Mechanism
    a, b : array_like, shapes (nx,) and (ny,)
        The grid's coordinates (rad), each strictly increasing or decreasing, close enough
        for continuation (a few degrees); ``nx ny`` at most
        ``MAX_POINTS = 1_000_000``. An empty axis gives an empty atlas. Every motor angle of
        the grid at most ``4 pi`` (two turns) in size.
    origin : array_like, shape (2,), optional
        The motor angles at ``a = b = 0`` (rad); zero by default.
    directions : array_like, shape (2, 2), optional
        The directions of ``a`` and ``b`` in the motor angles; ``theta1`` and ``theta2`` by
        default.
    modes : (int, int), optional
        The rods' buckling modes (as in :func:`~mechnum.mechanisms.rfr2.forward`).
    executor : None, int or dask.distributed.Client, optional
        Where the full searches run: None, all local cores (joblib); ``n``, ``n`` local
        workers (1: serially, here; more than the local cores are cut to them, with a
        warning); a dask Client, its cluster. The result does not depend on it.

    Returns
    -------
    mechnum.mechanisms.Atlas
        ``counts`` and ``stable_counts`` of shape (nx, ny), ``folds`` in ``(a, b)`` (rad),
        ``axes = (a, b)``; ``draw`` shows it in degrees.

    Raises
    ------
    ValueError
        If ``mech`` is no Mechanism, an axis is not a finite monotonic 1-D array, a motor
        angle beyond ``4 pi``, the grid too large, ``origin`` or ``directions`` not as above,
        ``modes`` not two integers ``>= 1``, or ``executor`` none of the above.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7
    >>> g = np.radians(np.arange(36.0, 45.0, 2.0))
    >>> at = atlas(TABLE7, g, g + np.radians(20.0), executor=1)
    >>> at.counts.shape, int(at.searched.sum()) < at.counts.size
    ((5, 5), True)
    """
    assembly.check_type(mech, Mechanism)
    modes = tuple(int(m) for m in assembly.check_modes(modes, 2))
    grid, axes, origin, directions = assembly.plane_grid(
        a, b, origin, directions, 2, (MAX_ANGLE, "4 pi rad", "two turns; in degrees? np.radians "
                                      "converts them"))
    default = not np.any(origin) and np.array_equal(directions, np.eye(2))
    labels = (("theta1 (deg)", "theta2 (deg)") if default else tuple(
        f"{name} (deg) along ({', '.join(f'{c:.2f}' for c in d)})"
        for name, d in zip("ab", directions)))

    def lift(theta, chart):
        return np.concatenate((chart, rods(mech, theta, chart, modes, jacobian=False)[0][
            ..., 0, :]), axis=-1)

    rods_meet = MeetingRods(mech.EI, mech.L, mech.origins, modes, mech.force)

    def system(u, theta):
        return rods_meet.joined(theta, u)

    problem = assembly.AtlasProblem(partial(search, mech, modes), system,
                                    lambda u: in_chart_rows(u[:, :4]), lift, 4)
    return assembly.atlas_of(problem, grid, (axes, origin, directions), labels,
                             np.degrees(1.0), modes, executor)
