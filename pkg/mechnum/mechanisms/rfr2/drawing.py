"""The mechanism draws itself: :func:`~mechnum.mechanisms.rfr2.draw`, one equilibrium."""

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.rfr2.analysis import shapes
from mechnum.mechanisms.rfr2.model import _theta


def draw(ax, mech, theta, chart, modes=(1, 1), *, force_scale=0.3, colors=("C0", "C3"),
         label=None):
    """Draw one equilibrium: motors, clamped tangents, both rods, the end effector and the load.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech, modes
        As in :func:`forward_elliptic`.
    theta, chart : array_like, shapes (2,) and (4,)
        The equilibrium.
    force_scale : float, optional
        Length of the load's arrow per newton (m/N).
    colors : (str, str), optional
        Colours of rod 1 and rod 2.
    label : str, optional
        Legend label of rod 1 (rod 2 gets ``label`` too, with " (rod 2)").

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, chart_from_thesis
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> len(draw(ax, TABLE7, TABLE7_THETA, z)) > 4
    True
    >>> plt.close(fig)
    """
    theta = _theta(theta)
    x, y = shapes(mech, theta, _validate.array(chart, "chart", shape=(4,)), modes)
    artists = []
    for r in range(2):
        artists += ax.plot(x[r], y[r], color=colors[r], lw=2,
                           label=None if label is None else f"{label}, rod {r + 1}")
        O = mech.origins[r]
        artists += ax.plot(*np.column_stack((O, O + 0.15 * mech.L * np.array(
            [np.cos(theta[r]), np.sin(theta[r])]))), "k--", lw=0.8)
        artists += ax.plot(*O, marker="^", color="k", ms=9)
    tip = (x[0, -1], y[0, -1])
    artists += ax.plot(*tip, "ko", ms=5)
    if np.any(mech.force):
        artists.append(ax.annotate("", xy=tip + force_scale * mech.force, xytext=tip,
                                   arrowprops=dict(arrowstyle="->", color="C2", lw=1.5)))
    return artists
