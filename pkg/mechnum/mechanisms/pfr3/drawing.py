"""The 3PFR's rods as polylines (:func:`shapes`), and the mechanism drawing itself
(:func:`draw`: guides, sliders, rods, platform and load; the same call for every frame of an
animation)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.pfr3 import model
from mechnum.rods import profile
from mechnum.rods.assembly import (
    MAX_NODES,
    State,
    check_modes,
    check_type,
    draw_parts,
    drawing_state,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes

GUIDE_HALF_LENGTH = 0.25
"""Half the length of the drawn guides, as a fraction of ``L``."""
SHAPE_NODES = 201
"""Nodes of the rods' polylines for the crossing test and the drawings."""


def shapes(mech: model.Mechanism, lambdas: ArrayLike, z: ArrayLike, modes: ArrayLike = (1, 1, 1),
           *, nodes: int = SHAPE_NODES):
    """The three rods of equilibria as polylines (closed form, :func:`mechnum.rods.profile.shape`).

    Parameters
    ----------
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    z : array_like, shape (..., 6)
        Equilibria in the chart.
    nodes : int, optional
        Points per rod, at most :data:`~mechnum.rods.assembly.checks.MAX_NODES`.

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
    z = model.check_chart(z)
    rod = profile.shape(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], check_modes(modes, 3),
                        nodes=nodes)
    cos, sin = np.cos(mech.clamp_angles)[:, None], np.sin(mech.clamp_angles)[:, None]
    return (c[:, 0, None] + cos * rod.x - sin * rod.y,
            c[:, 1, None] + sin * rod.x + cos * rod.y)


def draw(ax: Axes, mech: model.Mechanism, state: State | ArrayLike, z: ArrayLike = None,
         modes: ArrayLike = None, *, artists: list | None = None, force_scale: float = 0.3,
         colors: tuple = ("C0", "C3", "C2"), label: str | None = None):
    """Draw one equilibrium: guides, sliders, rods, the platform and its load.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : ~mechnum.mechanisms.pfr3.model.Mechanism
    state : ~mechnum.rods.assembly.State
        The equilibrium (``Equilibria.state(i)``, ``Path.state(i)``). The former call
        ``draw(ax, mech, lambdas, z, modes)`` still works, with a DeprecationWarning.
    artists : list, optional
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
    list of matplotlib artists
        For each rod its guide, slider and rod; then the platform and its pins; the load's
        arrow last, if there is a load.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from mechnum.mechanisms.pfr3 import forward_elliptic
    >>> eq = forward_elliptic(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> fig, ax = plt.subplots()
    >>> artists = draw(ax, model.TABLE8, eq.state(0))
    >>> len(artists), draw(ax, model.TABLE8, eq.state(1), artists=artists) is artists
    (12, True)
    >>> plt.close(fig)
    """
    state = drawing_state(state, z, modes, 3)
    check_type(mech, model.Mechanism)
    force_scale = _validate.scalar(force_scale, "force_scale")
    x, y = shapes(mech, state.inputs, state.chart, state.modes)
    clamps = model.clamps(mech, state.inputs)
    parts = []
    for i in range(3):
        along = np.array([np.cos(mech.guide_angles[i]), np.sin(mech.guide_angles[i])])
        ends = clamps[i] + np.outer([-1.0, 1.0], GUIDE_HALF_LENGTH * mech.L * along)
        parts += [(*ends.T, {"color": "0.6", "lw": 3, "solid_capstyle": "butt"}),
                  ([clamps[i, 0]], [clamps[i, 1]],
                   {"marker": "s", "color": "k", "ms": 6, "ls": ""}),
                  (x[i], y[i], {"color": colors[i], "lw": 2,
                                    "label": None if label is None else f"{label}, rod {i + 1}"})]
    pins = np.column_stack((x[:, -1], y[:, -1]))
    parts += [(*pins.T, {"fill": True, "color": "0.3", "alpha": 0.6}),
              (*pins.T, {"marker": "o", "color": "k", "ms": 4, "ls": ""})]
    centre = pins.mean(axis=0)
    arrow = (centre, centre + force_scale * mech.force) if np.any(mech.force) else None
    return draw_parts(ax, parts, arrow, artists, "m")
