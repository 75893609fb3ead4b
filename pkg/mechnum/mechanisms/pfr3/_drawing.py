"""The 3PFR's rods as polylines (:func:`shapes`), and the mechanism drawing itself
(:func:`draw`: guides, sliders, rods, platform and load; the same call for every frame of an
animation)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms._assembly import (
    MAX_NODES,
    State,
    check_modes,
    check_state,
    check_type,
    draw_parts,
)
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.rods import shape as rod_shapes

if TYPE_CHECKING:
    from matplotlib.axes import Axes

GUIDE_HALF_LENGTH = 0.25
"""Half the length of the drawn guides, as a fraction of ``L``."""
SHAPE_NODES = 201
"""Nodes of the rods' polylines for the crossing test and the drawings."""


def shapes(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
           modes: ArrayLike = (1, 1, 1), *, nodes: int = SHAPE_NODES) -> tuple:
    """The three rods of equilibria as polylines (closed form, :func:`mechnum.rods.shape`).

    Parameters
    ----------
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    chart : array_like, shape (..., 6)
        Equilibria in the chart.
    nodes : int, optional
        Points per rod, at most :data:`~mechnum.mechanisms._assembly.MAX_NODES`.

    Returns
    -------
    x, y : ndarray, shape (..., 3, nodes)
        Coordinates (m), from each clamp to its tip.

    Examples
    --------
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> x, y = shapes(model.TABLE8, model.TABLE8_LAMBDAS, z)
    >>> x.shape, round(float(x[0, 0]), 4), round(float(y[0, 0]), 4)
    ((3, 201), -0.866, -0.5)
    """
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    c = model.clamps(mech, _validate.array(lambdas, "lambdas", shape=(3,)))
    z = model.check_chart(chart)
    rod = rod_shapes(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], check_modes(modes, 3),
                     nodes=nodes)
    cos, sin = np.cos(mech.clamp_angles)[:, None], np.sin(mech.clamp_angles)[:, None]
    return (c[:, 0, None] + cos * rod.x - sin * rod.y,
            c[:, 1, None] + sin * rod.x + cos * rod.y)


def draw(ax: Axes, mech: model.Mechanism, state: State, *, artists: dict | None = None,
         force_scale: float = 0.3, colors: tuple = ("C0", "C3", "C2"),
         label: str | None = None) -> dict:
    """Draw one equilibrium: guides, sliders, rods, the platform and its load.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    state : ~mechnum.mechanisms.State
        The equilibrium (``Equilibria.state(i)``, ``Path.state(i)``, ``Atlas.state(i, j, k)``).
    artists : dict, optional
        The artists of an earlier call on ``ax`` with the same ``mech``: moved to ``state``
        instead of drawn anew (one frame of :func:`mechnum.plotting.animate`).
    force_scale : float, optional
        Length of the load's arrow per newton (m/N).
    colors : three colours, optional
        Of rods 1, 2 and 3.
    label : str, optional
        Legend label: "label, rod i" for each rod.

    Returns
    -------
    dict of matplotlib artists
        ``"guide1"``, ``"slider1"``, ``"rod1"`` and the same for rods 2 and 3, ``"platform"``,
        ``"pins"``, and ``"load"`` (the load's arrow) if there is a load.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from mechnum.mechanisms.pfr3 import forward
    >>> eq = forward(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> fig, ax = plt.subplots()
    >>> artists = draw(ax, model.TABLE8, eq.state(0))
    >>> len(artists), draw(ax, model.TABLE8, eq.state(1), artists=artists) is artists
    (12, True)
    >>> plt.close(fig)
    """
    state = check_state(state, 3)
    check_type(mech, model.Mechanism)
    force_scale = _validate.scalar(force_scale, "force_scale")
    x, y = shapes(mech, state.inputs, state.chart, state.modes)
    clamps = model.clamps(mech, state.inputs)
    parts = {}
    for i in range(3):
        along = np.array([np.cos(mech.guide_angles[i]), np.sin(mech.guide_angles[i])])
        ends = clamps[i] + np.outer([-1.0, 1.0], GUIDE_HALF_LENGTH * mech.L * along)
        parts[f"guide{i + 1}"] = (*ends.T, {"color": "0.6", "lw": 3, "solid_capstyle": "butt"})
        parts[f"slider{i + 1}"] = ([clamps[i, 0]], [clamps[i, 1]], {
            "marker": "s", "color": "k", "ms": 6, "ls": ""})
        parts[f"rod{i + 1}"] = (x[i], y[i], {"color": colors[i], "lw": 2, "label": (
            None if label is None else f"{label}, rod {i + 1}")})
    pins = np.column_stack((x[:, -1], y[:, -1]))
    parts["platform"] = (*pins.T, {"fill": True, "color": "0.3", "alpha": 0.6})
    parts["pins"] = (*pins.T, {"marker": "o", "color": "k", "ms": 4, "ls": ""})
    centre = pins.mean(axis=0)
    arrow = (centre, centre + force_scale * mech.force) if np.any(mech.force) else None
    return draw_parts(ax, parts, arrow, artists, "m")
