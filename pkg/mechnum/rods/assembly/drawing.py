"""What every mechanism built of rods needs to draw itself: the state it is given, checked,
and its parts drawn, or moved (one frame of an animation)."""

from __future__ import annotations

import warnings

import numpy as np

from mechnum import _validate
from mechnum.rods.assembly.checks import check_modes, check_type
from mechnum.rods.assembly.results import State


def drawing_state(state, chart, modes, rods: int) -> State:
    """The :class:`State` a mechanism's ``draw(ax, mech, state)`` was given, checked; the former
    call ``draw(ax, mech, inputs, chart, modes)`` still works, with a DeprecationWarning.

    Examples
    --------
    >>> s = drawing_state(State(np.zeros(2), np.ones(4), (1, 1)), None, None, 2)
    >>> s.modes
    (1, 1)
    """
    if isinstance(state, State):
        if chart is not None or modes is not None:
            raise ValueError("give draw a State, or (deprecated) the inputs, chart and modes, "
                             "not both")
        inputs, chart, modes = state.inputs, state.chart, state.modes
    else:
        warnings.warn("draw(ax, mech, inputs, chart, modes) is deprecated: pass one State, "
                      "draw(ax, mech, eq.state(i)) or draw(ax, mech, path.state(i))",
                      DeprecationWarning, stacklevel=3)
        if chart is None:
            raise ValueError("draw needs a State (or, deprecated, the inputs and the chart)")
        inputs, modes = state, (1,) * rods if modes is None else modes
    inputs = _validate.array(inputs, "state.inputs", ndim=1)
    chart = _validate.array(chart, "state.chart", shape=(2 * rods,))
    return State(inputs, chart, tuple(int(m) for m in check_modes(modes, rods)))


def draw_parts(ax, parts, arrow, artists, arrow_color):
    """Draw (or, given the ``artists`` of an earlier call, move) a mechanism's parts.

    ``parts`` are ``(x, y, style)`` polylines (a polygon where ``style["fill"]``), ``arrow`` is
    ``(tail, head)`` or None. Returns the artists, in the order of ``parts``, the arrow last.
    """
    from matplotlib.axes import Axes

    check_type(ax, Axes, "ax")
    if artists is None:
        artists = []
        for x, y, style in parts:
            style = dict(style)
            artists += (ax.fill(x, y, **{k: v for k, v in style.items() if k != "fill"})
                        if style.get("fill") else ax.plot(x, y, **style))
        if arrow is not None:
            artists.append(ax.annotate("", xy=arrow[1], xytext=arrow[0], arrowprops={
                "arrowstyle": "->", "color": arrow_color, "lw": 1.5}))
        return artists
    if len(artists) != len(parts) + (arrow is not None):
        raise ValueError(f"artists must be the {len(parts) + (arrow is not None)} artists of "
                         f"an earlier draw of this mechanism, got {len(artists)}")
    for artist, (x, y, style) in zip(artists, parts):
        if style.get("fill"):
            artist.set_xy(np.column_stack((x, y)))
        else:
            artist.set_data(x, y)
    if arrow is not None:
        artists[-1].xy, artists[-1].xyann = tuple(arrow[1]), tuple(arrow[0])
    return artists
