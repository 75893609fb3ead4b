"""The mechanism's rods as polylines (:func:`shapes`), and the mechanism drawing itself
(:func:`draw`: one equilibrium, the same call for every frame of an animation)."""

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
from mechnum.mechanisms.rfr2._model import Mechanism, broadcast
from mechnum.rods import shape as rod_shapes

if TYPE_CHECKING:
    from matplotlib.axes import Axes

# Nodes of the rods' polylines for the crossing test and the drawings: a chord of L / 200 is
# within ~1e-5 L of the rods of this chapter (curvatures below ~10 / L).
SHAPE_NODES = 201


def shapes(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1), *,
           nodes: int = SHAPE_NODES) -> tuple[np.ndarray, np.ndarray]:
    """The two rods of equilibria as polylines (closed form, :func:`mechnum.rods.shape`).

    Parameters
    ----------
    mech, modes
        As in :func:`~mechnum.mechanisms.rfr2.forward`.
    theta : array_like, shape (..., 2)
        Motor angles (rad), broadcast with ``chart``.
    chart : array_like, shape (..., 4)
        Equilibria ``(psi1, t1, psi2, t2)``.
    nodes : int, optional
        Points per rod, at most ``MAX_NODES = 100_000``.

    Returns
    -------
    x, y : ndarray, shape (..., 2, nodes)
        Coordinates of the rods (m), from the clamp to the tip.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> x, y = shapes(TABLE7, TABLE7_THETA, chart_from_thesis([5.304574, 0.969830,
    ...                                                        1.825456, -0.992135]))
    >>> gap = np.hypot(x[0, -1] - x[1, -1], y[0, -1] - y[1, -1])   # the printed digits
    >>> x.shape, np.round([x[0, 0], y[0, 0]], 12).tolist(), bool(gap < 1e-5)
    ((2, 201), [-0.3, 0.0], True)
    """
    check_type(mech, Mechanism)
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    theta, z = broadcast(theta, chart)
    rod = rod_shapes(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], check_modes(modes, 2),
                     nodes=nodes)
    c, s = np.cos(theta)[..., None], np.sin(theta)[..., None]
    return (mech.origins[:, 0, None] + c * rod.x - s * rod.y,
            mech.origins[:, 1, None] + s * rod.x + c * rod.y)


def draw(ax: Axes, mech: Mechanism, state: State, *, artists: dict | None = None,
         force_scale: float = 0.3, colors: tuple = ("C0", "C3"),
         label: str | None = None) -> dict:
    """Draw one equilibrium: motors, clamped tangents, both rods, the end effector and the load.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : Mechanism
    state : ~mechnum.mechanisms.State
        The equilibrium (``Equilibria.state(i)``, ``Path.state(i)``, ``Atlas.state(i, j, k)``).
    artists : dict, optional
        The artists of an earlier call on ``ax`` with the same ``mech``: moved to ``state``
        instead of drawn anew (one frame of :func:`mechnum.plotting.animate`).
    force_scale : float, optional
        Length of the load's arrow per newton (m/N).
    colors : (str, str), optional
        Colours of rod 1 and rod 2.
    label : str, optional
        Legend label: "label, rod i" for each rod.

    Returns
    -------
    dict of matplotlib artists
        ``"rod1"``, ``"tangent1"``, ``"motor1"``, the same for rod 2, ``"end_effector"``, and
        ``"load"`` (the load's arrow) if there is a load.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> artists = draw(ax, TABLE7, eq.state(0))
    >>> len(artists), draw(ax, TABLE7, eq.state(1), artists=artists) is artists
    (8, True)
    >>> plt.close(fig)
    """
    state = check_state(state, 2)
    check_type(mech, Mechanism)
    force_scale = _validate.scalar(force_scale, "force_scale")
    x, y = shapes(mech, state.inputs, state.chart, state.modes)
    parts = {}
    for r in range(2):
        tangent = mech.origins[r] + 0.15 * mech.L * np.array([[0.0, 0.0], [
            np.cos(state.inputs[r]), np.sin(state.inputs[r])]])
        parts[f"rod{r + 1}"] = (x[r], y[r], {"color": colors[r], "lw": 2, "label": (
            None if label is None else f"{label}, rod {r + 1}")})
        parts[f"tangent{r + 1}"] = (*tangent.T, {"color": "k", "ls": "--", "lw": 0.8})
        parts[f"motor{r + 1}"] = ([mech.origins[r, 0]], [mech.origins[r, 1]], {
            "marker": "^", "color": "k", "ms": 9, "ls": ""})
    tip = np.array([x[0, -1], y[0, -1]])
    parts["end_effector"] = ([tip[0]], [tip[1]], {"marker": "o", "color": "k", "ms": 5,
                                                  "ls": ""})
    arrow = (tip, tip + force_scale * mech.force) if np.any(mech.force) else None
    return draw_parts(ax, parts, arrow, artists, "C2")
