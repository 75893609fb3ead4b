"""Drawing a 3PFR equilibrium: guides, sliders, rods, platform and load."""

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.pfr3 import model
from mechnum.mechanisms.pfr3.equilibria import shapes

GUIDE_HALF_LENGTH = 0.25
"""Half the length of the drawn guides, as a fraction of ``L``."""


def draw(ax, mech, lambdas, z, modes=(1, 1, 1), *, force_scale=0.3,
         colors=("C0", "C3", "C2"), label=None):
    """Draw one equilibrium: guides, sliders, rods, the platform and its load.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : ~mechnum.mechanisms.pfr3.model.Mechanism
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    z : array_like, shape (6,)
        The equilibrium in the chart.
    modes : (int, int, int), optional
    force_scale : float, optional
        Length of the load's arrow per newton (m/N).
    colors : three colours, optional
        Of rods 1, 2 and 3.
    label : str, optional
        Legend label: "label, rod i" for each rod.

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> z = model.chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> len(draw(ax, model.TABLE8, model.TABLE8_LAMBDAS, z)) > 9
    True
    >>> plt.close(fig)
    """
    lambdas = model._lambdas(lambdas)
    x, y = shapes(mech, lambdas, _validate.array(z, "z", shape=(6,)), modes)
    clamps = model.clamps(mech, lambdas)
    artists = []
    for i in range(3):
        along = np.array([np.cos(mech.guide_angles[i]), np.sin(mech.guide_angles[i])])
        ends = clamps[i] + np.outer([-1.0, 1.0], GUIDE_HALF_LENGTH * mech.L * along)
        artists += ax.plot(*ends.T, color="0.6", lw=3, solid_capstyle="butt")
        artists += ax.plot(*clamps[i], marker="s", color="k", ms=6)
        artists += ax.plot(x[i], y[i], color=colors[i], lw=2,
                           label=None if label is None else f"{label}, rod {i + 1}")
    pins = np.column_stack((x[:, -1], y[:, -1]))
    artists += ax.fill(*pins.T, color="0.3", alpha=0.6)
    artists += ax.plot(*pins.T, "ko", ms=4)
    centre = pins.mean(axis=0)
    if np.any(mech.force):
        artists.append(ax.annotate("", xy=centre + force_scale * mech.force, xytext=centre,
                                   arrowprops=dict(arrowstyle="->", color="m", lw=1.5)))
    return artists
