"""What every mechanism built of rods needs to draw itself: the state it is given, checked,
and its parts drawn, or moved (one frame of an animation); and its atlas (:func:`draw_atlas`),
the stable count over a grid of its inputs with the folds drawn on it."""

from __future__ import annotations

import numpy as np

from mechnum import _validate, plotting
from mechnum.mechanisms._assembly._checks import check_modes, check_type
from mechnum.mechanisms._assembly._results import State


def check_state(state, rods: int) -> State:
    """The :class:`State` a mechanism's ``draw(ax, mech, state)`` or ``workspace(mech, state)`` was
    given, checked.

    Examples
    --------
    >>> s = check_state(State(np.zeros(2), np.ones(4), (1, 1)), 2)
    >>> s.modes
    (1, 1)
    """
    rods = _validate.maxiter(rods, "rods")
    if not isinstance(state, State):
        raise ValueError(f"state must be a State (Equilibria.state(i), Path.state(i)), got "
                         f"{_validate.shown(state)}")
    inputs = _validate.array(state.inputs, "state.inputs", ndim=1)
    chart = _validate.array(state.chart, "state.chart", shape=(2 * rods,))
    return State(inputs, chart, tuple(int(m) for m in check_modes(state.modes, rods)))


def draw_parts(ax, parts: dict, arrow, artists: dict | None, arrow_color: str) -> dict:
    """Draw (or, given the ``artists`` of an earlier call, move) a mechanism's parts, by
    :func:`mechnum.plotting.parts`.

    ``parts`` maps names to ``(x, y, style)`` polylines (a polygon where ``style["fill"]``),
    ``arrow`` is ``(tail, head)`` or None. Returns the artists by name, the arrow's as
    ``"load"``; given ``artists``, it moves them and adds nothing.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> drawn = draw_parts(ax, {"bar": ([0, 1], [0, 0], {})}, None, None, "k")
    >>> moved = draw_parts(ax, {"bar": ([0, 2], [0, 1], {})}, None, drawn, "k")
    >>> moved is drawn, drawn["bar"].get_xydata().tolist(), len(ax.lines)
    (True, [[0.0, 0.0], [2.0, 1.0]], 1)
    >>> plt.close(fig)
    """
    shapes = {}
    for name, (x, y, style) in parts.items():
        style = dict(style)
        if style.pop("fill", False):
            style["kind"] = "fill"
        shapes[name] = (np.column_stack((np.ravel(x), np.ravel(y))), style)
    if arrow is not None:
        shapes["load"] = (np.array(arrow, dtype=float), {
            "kind": "arrow", "arrowstyle": "->", "color": arrow_color, "lw": 1.5})
    return plotting.parts(ax, shapes, artists)


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around grid ``centres``: the midpoints, and half a step beyond each end."""
    if len(centres) == 1:
        return centres[0] + np.array([-0.5, 0.5])
    middle = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate(([2 * centres[0] - middle[0]], middle, [2 * centres[-1] - middle[-1]]))


def fold_segments(values: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The cell boundaries between neighbouring grid points whose ``values`` differ, as
    segments ``(k, 2, 2)`` (the cells of grid point ``(i, j)`` centred at ``(x[i], y[j])``).

    Examples
    --------
    >>> fold_segments(np.array([[0, 1], [0, 1]]), np.array([0.0, 1.0]), np.array([0.0, 1.0]))
    array([[[-0.5,  0.5],
            [ 0.5,  0.5]],
    <BLANKLINE>
           [[ 0.5,  0.5],
            [ 1.5,  0.5]]])
    """
    x, y = (_validate.array(v, name, ndim=1) for v, name in ((x, "x"), (y, "y")))
    values = _validate.array(values, "values", shape=(len(x), len(y)), finite=False)
    ex, ey = _edges(x), _edges(y)
    i, j = np.nonzero(values[1:] != values[:-1])           # between (i, j) and (i + 1, j)
    across = np.stack((np.column_stack((ex[i + 1], ey[j])),
                       np.column_stack((ex[i + 1], ey[j + 1]))), axis=1)
    i, j = np.nonzero(values[:, 1:] != values[:, :-1])     # between (i, j) and (i, j + 1)
    along = np.stack((np.column_stack((ex[i], ey[j + 1])),
                      np.column_stack((ex[i + 1], ey[j + 1]))), axis=1)
    return np.concatenate((across, along))


def draw_atlas(ax, atlas, *, trajectory=None, searched: bool = False, cmap: str = "viridis",
               fold_color: str = "black", colorbar: bool = True) -> dict:
    """Draw an atlas: its stable count as a map, the folds on it, optionally a trajectory.

    Each grid point is a cell coloured by its number of stable equilibria; the folds (cell
    edges across which the stable count changes: where a stable assembly appears, disappears
    or loses stability) are drawn as lines. A trajectory of inputs is drawn over the map, with
    a cross wherever it passes into a cell of another stable count: where, moving along it,
    the mechanism may have to jump (it does when the assembly it holds is the one that ends).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    atlas : mechnum.mechanisms.Atlas
    trajectory : array_like, shape (n, k), optional
        Inputs along a path (the atlas's inputs' units: rad, m), projected on its plane.
    searched : bool, optional
        Also mark the points where the full search ran.
    cmap, fold_color : str, optional
    colorbar : bool, optional
        Add a colour bar of the stable counts.

    Returns
    -------
    dict
        The artists: "map", "folds", and "colorbar", "searched", "trajectory", "crossings"
        where drawn.
    """
    from matplotlib.axes import Axes
    from matplotlib.collections import LineCollection
    from matplotlib.colors import BoundaryNorm

    check_type(ax, Axes, "ax")
    x, y = (np.asarray(a, dtype=float) * atlas.scale for a in atlas.axes)
    top = int(atlas.stable_counts.max(initial=0))
    norm = BoundaryNorm(np.arange(top + 2) - 0.5, ncolors=256)
    artists = {}
    if x.size and y.size:
        artists["map"] = ax.pcolormesh(_edges(x), _edges(y), atlas.stable_counts.T, cmap=cmap,
                                       norm=norm)
        artists["folds"] = ax.add_collection(LineCollection(
            fold_segments(atlas.stable_counts, x, y), colors=fold_color, linewidths=1.2))
        if colorbar:
            artists["colorbar"] = ax.figure.colorbar(artists["map"], ax=ax,
                                                     ticks=np.arange(top + 1),
                                                     label="stable assemblies")
    if _validate.flag(searched, "searched") and atlas.searched.any():
        i, j = np.nonzero(atlas.searched)
        artists["searched"] = ax.plot(x[i], y[j], ".", color="white", ms=3,
                                      label="full search")[0]
    if trajectory is not None:
        path = _validate.array(trajectory, "trajectory", ndim=2)
        if path.shape[1] != atlas.inputs.shape[-1]:
            raise ValueError(f"trajectory must have shape (n, {atlas.inputs.shape[-1]}) (the "
                             f"inputs), got shape {path.shape}")
        xy = atlas.coordinates(path) * atlas.scale
        artists["trajectory"] = ax.plot(xy[:, 0], xy[:, 1], color="white", lw=1.5)[0]
        if x.size and y.size:
            cell = (np.abs(xy[:, :1] - x).argmin(axis=1), np.abs(xy[:, 1:] - y).argmin(axis=1))
            change = np.flatnonzero(np.diff(atlas.stable_counts[cell]) != 0)
            mid = 0.5 * (xy[change] + xy[change + 1])
            artists["crossings"] = ax.plot(mid[:, 0], mid[:, 1], "x", color="red", ms=7,
                                           mew=2)[0]
    ax.set_xlabel(atlas.labels[0])
    ax.set_ylabel(atlas.labels[1])
    return artists
