"""The 3PFR's atlas: how many equilibria, and how many stable ones, over a plane of its inputs.

The three sliders span a space of inputs; an atlas is a map, so it covers a plane of it, the
grid ``lambdas[i, j] = origin + a[i] u + b[j] v`` of two directions ``u``, ``v``.
:func:`~mechnum.mechanisms.pfr3.atlas` runs :func:`mechnum.mechanisms._assembly.atlas_of` (its
module explains the method) with the 3PFR's closed form: the full search is
:func:`~mechnum.mechanisms.pfr3.forward` with its defaults (none where no platform can close
between the clamps), the continuation that of :func:`~mechnum.mechanisms.pfr3.forward_path`
(the rods and the pose as the sliders move, :func:`~mechnum.mechanisms.pfr3.full_system`).
"""

from __future__ import annotations

from functools import partial

import numpy as np
from numpy.typing import ArrayLike

from mechnum.errors import GeometryError
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.mechanisms.pfr3._elliptic import forward
from mechnum.rods import ClampedRods, in_chart

MAX_SLIDER = 1e100
"""The largest slider input of an atlas's grid (m): the plane's dot products of larger ones
overflow (a grid at 1e300 m did), and no mechanism closes with its sliders that far anyway."""


def search(mech: model.Mechanism, modes: tuple, task: tuple) -> list:
    """The full search at the sliders of a task ``(rngs, lambdas)``: for each point,
    ``(chart, stable, complete, nfev)`` of :func:`forward` (its starts drawn from its
    ``rng``), or no equilibrium where no platform can close."""
    out = []
    for rng, lambdas in zip(*task):
        try:
            eq = forward(mech, lambdas, modes=modes, rng=rng)
        except GeometryError:             # the clamps too far apart, or too close
            out.append((np.zeros((0, 6)), np.zeros(0, dtype=bool), True, 0))
            continue
        out.append((eq.x, eq.stable, eq.search.complete, eq.nfev))
    return out


def atlas(mech: model.Mechanism, a: ArrayLike, b: ArrayLike, *, origin: ArrayLike | None = None,
          directions: ArrayLike | None = None, modes: ArrayLike = (1, 1, 1),
          executor: object = None) -> assembly.Atlas:
    """The mechanism's equilibria over a grid of slider inputs on a plane: their number, the
    stable ones, and the folds where the stable count changes.

    The grid is ``lambdas[i, j] = origin + a[i] directions[0] + b[j] directions[1]``: by
    default ``lambda1 = a[i]``, ``lambda2 = b[j]``, ``lambda3 = 0``. As
    :func:`mechnum.mechanisms.rfr2.atlas`, with the 3PFR's full search
    (:func:`~mechnum.mechanisms.pfr3.forward`: 1000 starts and the check of 10,000, about ten
    times the 2RFR's work) at the anchors and wherever continuation cannot vouch for the
    count.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    a, b : array_like, shapes (nx,) and (ny,)
        The grid's coordinates (m), each strictly increasing or decreasing, neighbours close
        enough for continuation (a few millimetres); ``nx ny`` at most
        ``MAX_POINTS = 1_000_000``. An empty axis gives an empty atlas. Every slider input
        of the grid within ``1e100`` m of zero.
    origin : array_like, shape (3,), optional
        The sliders at ``a = b = 0`` (m); zero by default.
    directions : array_like, shape (2, 3), optional
        The directions of ``a`` and ``b`` in the sliders; ``lambda1`` and ``lambda2`` by
        default.
    modes : (int, int, int), optional
        The rods' buckling modes.
    executor : None, int or dask.distributed.Client, optional
        Where the full searches run (as in :func:`mechnum.mechanisms.rfr2.atlas`).

    Returns
    -------
    mechnum.mechanisms.Atlas
        ``axes = (a, b)`` (m) along ``directions`` from ``origin``.

    Raises
    ------
    ValueError
        If ``mech`` is no Mechanism, an axis is not a finite monotonic 1-D array, a slider
        input beyond ``1e100`` m, the grid too large, ``origin`` or ``directions`` not as
        above, ``modes`` not three integers
        ``>= 1``, or ``executor`` invalid.

    Examples
    --------
    >>> s = np.linspace(-0.002, 0.002, 3)
    >>> at = atlas(model.TABLE8, s, s, executor=1)
    >>> at.counts.tolist()
    [[9, 9, 9], [9, 9, 9], [9, 9, 9]]
    """
    assembly.check_type(mech, model.Mechanism)
    modes = tuple(int(m) for m in assembly.check_modes(modes, 3))
    grid, axes, origin, directions = assembly.plane_grid(
        a, b, origin, directions, 3,
        (MAX_SLIDER, "1e+100 m", "the plane's products would overflow"))
    family = ClampedRods(mech.EI, mech.L, modes)

    def lift(lambdas, chart):
        tip = model.rods_at(family, mech, lambdas, chart, jacobian=False)[0]
        return np.concatenate((chart, model.pose_at(mech, tip)), axis=-1)

    full, columns = model.full_system(mech, modes), model.LAYOUT.forward_columns

    def system(u, lambdas):
        G, D = full(u[:, :6], lambdas, u[:, 6:])
        return G, D[..., columns]

    problem = assembly.AtlasProblem(partial(search, mech, modes), system,
                                    lambda u: in_chart(u[:, :6]), lift, 6)
    labels = tuple(f"{name} (m) along ({', '.join(f'{c:.2f}' for c in d)})"
                   for name, d in zip("ab", directions))
    return assembly.atlas_of(problem, grid, (axes, origin, directions), labels, 1.0, modes,
                             executor)
