"""The 3PFR's atlas: how many equilibria, and how many stable ones, over a plane of its inputs.

The three sliders span a space of inputs; an atlas is a map, so it covers a plane of it, given
as a grid ``lambdas_grid[i, j] = lambdas0 + a[i] u + b[j] v`` (:func:`plane` recovers the
axes ``a``, ``b`` and the unit directions ``u``, ``v`` and checks that the grid is one).
:func:`~mechnum.mechanisms.pfr3.atlases.atlas` runs :func:`mechnum.rods.assembly.atlas_of` (its
module explains the method) with the 3PFR's closed form: the full search is
:func:`~mechnum.mechanisms.pfr3.equilibria.forward_elliptic` with its defaults (none where
no platform can close between the clamps), the continuation
:func:`~mechnum.mechanisms.pfr3.paths.forward_trace`.
"""

from __future__ import annotations

from functools import partial

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError
from mechnum.mechanisms.pfr3 import model
from mechnum.mechanisms.pfr3.equilibria import forward_elliptic
from mechnum.mechanisms.pfr3.paths import forward_trace
from mechnum.rods import assembly
from mechnum.rods.assembly import atlas as atlases

PLANE_TOL = 1e-9
"""How far (relative to the largest input, plus 1 m) a grid's point may lie from the plane of
its first row and column: rounding, not a bent grid."""
MAX_SLIDER = 1e100
"""The largest slider input of an atlas's grid (m): the plane's dot products of larger ones
overflow (a grid at 1e300 m did), and no mechanism closes with its sliders that far anyway."""


def plane(lambdas_grid: ArrayLike) -> tuple:
    """The plane of a grid of slider inputs: ``(a, b), lambdas0, (u, v)`` with
    ``lambdas_grid[i, j] = lambdas0 + a[i] u + b[j] v``, ``u`` and ``v`` unit vectors.

    Raises
    ------
    ValueError
        If the grid is not of shape (nx, ny, 3), not finite, beyond :data:`MAX_SLIDER`, larger
        than :data:`~mechnum.rods.assembly.checks.MAX_POINTS` points, or not a grid over a
        plane (its rows and columns not parallel lines, or all on one line).

    Examples
    --------
    >>> s = np.linspace(-0.1, 0.1, 3)
    >>> grid = s[:, None, None] * [1.0, 0.0, 0.0] + s[None, :, None] * [0.0, 1.0, 1.0]
    >>> (a, b), origin, (u, v) = plane(grid)
    >>> np.round(a, 3).tolist(), np.round(v, 4).tolist()
    ([0.0, 0.1, 0.2], [0.0, 0.7071, 0.7071])
    >>> grid[1, 1, 0] += 0.01                              # bent: no longer a plane
    >>> plane(grid)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: lambdas_grid must be a grid over a plane, ...: its point (1, 1) lies 0.01 m ...
    """
    if np.size(lambdas_grid) == 0 and np.ndim(lambdas_grid) != 3:    # [] is an empty grid
        lambdas_grid = np.zeros((0, 0, 3))
    grid = _validate.array(lambdas_grid, "lambdas_grid", shape=(None, None, 3))
    if grid.size and np.abs(grid).max() > MAX_SLIDER:
        raise ValueError(f"lambdas_grid must lie within {MAX_SLIDER:g} m of zero (the plane's "
                         f"products would overflow), got up to {np.abs(grid).max():.3g} m")
    nx, ny = grid.shape[:2]
    assembly.grid_axes(np.zeros(nx), np.zeros(ny), ("the grid's rows", "the grid's columns"))
    if not grid.size:
        return (np.zeros(nx), np.zeros(ny)), np.zeros(3), np.eye(3)[:2]
    origin = grid[0, 0]
    u, v = grid[-1, 0] - origin, grid[0, -1] - origin
    u, v = _unit(u, v), _unit(v, u)
    if abs(u @ v) > 1.0 - 1e-12:
        raise ValueError("lambdas_grid must span a plane: its rows and columns lie on one line")
    a, b = (grid[:, 0] - origin) @ u, (grid[0, :] - origin) @ v
    flat = origin + a[:, None, None] * u + b[None, :, None] * v
    gap = np.abs(grid - flat).max(axis=-1)
    if gap.max() > PLANE_TOL * (1.0 + np.abs(grid).max()):
        i, j = np.unravel_index(np.argmax(gap), gap.shape)
        raise ValueError("lambdas_grid must be a grid over a plane, lambdas_grid[i, j] = "
                         f"lambdas0 + a[i] u + b[j] v: its point ({i}, {j}) lies "
                         f"{gap[i, j]:.3g} m from the plane of its first row and column")
    return (a, b), origin, np.stack((u, v))


def _unit(w, other):
    """``w`` normalised; a unit vector across ``other`` if ``w`` vanishes (one row or column)."""
    size = np.linalg.norm(w)
    if size > 0:
        return w / size
    trial = np.eye(3)[np.argmin(np.abs(other))]
    trial = trial - (trial @ other) * other / max(other @ other, np.finfo(float).tiny)
    return trial / np.linalg.norm(trial)


def search(mech: model.Mechanism, modes: tuple, task) -> list:
    """The full search at the sliders of a task ``(indices, lambdas)``: for each point,
    ``(chart, stable, complete, nfev)`` of :func:`forward_elliptic` (starts from
    ``default_rng([SEED, index])``), or no equilibrium where no platform can close."""
    out = []
    for index, lambdas in zip(*task):
        try:
            eq = forward_elliptic(mech, lambdas, modes,
                                  rng=np.random.default_rng([atlases.SEED, int(index)]))
        except GeometryError:             # the clamps too far apart, or too close
            out.append((np.zeros((0, 6)), np.zeros(0, dtype=bool), True, 0))
            continue
        out.append((eq.chart, eq.stable, eq.search.complete, eq.nfev))
    return out


def atlas(mech: model.Mechanism, lambdas_grid: ArrayLike, *, modes: ArrayLike = (1, 1, 1),
          executor=None) -> atlases.Atlas:
    """The mechanism's equilibria over a grid of slider inputs on a plane: their number, the
    stable ones, and the folds where the stable count changes.

    As :func:`mechnum.mechanisms.rfr2.atlas`, with the 3PFR's full search
    (:func:`~mechnum.mechanisms.pfr3.equilibria.forward_elliptic`: 1000 starts and the
    check of 10,000, about ten times the 2RFR's work) at the anchors and wherever
    continuation cannot vouch for the count.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.model.Mechanism
    lambdas_grid : array_like, shape (nx, ny, 3)
        The sliders (m) at the points of a grid over a plane, ``lambdas_grid[i, j] = lambdas0 +
        a[i] u + b[j] v`` (:func:`plane`), neighbours close enough for continuation (a few
        millimetres); ``nx ny`` at most :data:`~mechnum.rods.assembly.checks.MAX_POINTS`. An
        empty grid gives an empty atlas.
    modes : (int, int, int), optional
        The rods' buckling modes.
    executor : None, int or dask.distributed.Client, optional
        Where the full searches run (as in :func:`mechnum.mechanisms.rfr2.atlas`).

    Returns
    -------
    mechnum.rods.assembly.Atlas
        ``axes = (a, b)`` (m) along ``directions = (u, v)`` from ``origin = lambdas0``.

    Raises
    ------
    ValueError
        If ``mech`` is no Mechanism, ``lambdas_grid`` no grid over a plane (:func:`plane`),
        ``modes`` not three integers ``>= 1``, or ``executor`` invalid.

    Examples
    --------
    >>> s = np.linspace(-0.002, 0.002, 3)
    >>> grid = s[:, None, None] * [1.0, 0.0, 0.0] + s[None, :, None] * [0.0, 1.0, 0.0]
    >>> at = atlas(model.TABLE8, grid, executor=1)
    >>> at.counts.tolist()
    [[9, 9, 9], [9, 9, 9], [9, 9, 9]]
    """
    assembly.check_type(mech, model.Mechanism)
    modes = tuple(int(m) for m in assembly.check_modes(modes, 3))
    axes, origin, directions = plane(lambdas_grid)
    grid = np.asarray(lambdas_grid, dtype=float).reshape(len(axes[0]), len(axes[1]), 3)

    def lift(lambdas, z):
        tip = model.rods(mech, lambdas, z, modes, jacobian=False)[0]
        return np.concatenate((z, model.pose_of_tips(mech, tip)), axis=-1)

    trace = forward_trace(mech, np.array(modes, dtype=float), tol=atlases.STEP_TOL,
                          criterion="step")
    problem = atlases.AtlasProblem(partial(search, mech, modes), trace, lift, 6)
    labels = tuple(f"{name} (m) along ({', '.join(f'{c:.2f}' for c in d)})"
                   for name, d in zip("ab", directions))
    return atlases.atlas_of(problem, grid, (axes, origin, directions), labels, 1.0, modes,
                         executor)
