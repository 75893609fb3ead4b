"""The saw draws itself: its joints and one state in a figure.

:func:`~mechnum.mechanisms.hacksaw.joints` gives the points ``O``, ``A``, ``B`` of states;
:func:`~mechnum.mechanisms.hacksaw.draw` draws one state, for the chapter's figures and
animations.
"""

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.hacksaw.model import STUDY, _check

DRAW_PAD = 0.25  # blank border around a drawing, in crank lengths: room for the joints' dots


def joints(x, theta2, geometry=STUDY):
    """The crank pivot ``O``, crank pin ``A`` and slider pin ``B`` of the states ``x``.

    Parameters
    ----------
    x : array_like, shape (..., 9) or (..., 3)
        States (or positions ``(r1, theta1, theta3)``).
    theta2 : array_like
        Crank angles, broadcasting against ``x.shape[:-1]``.
    geometry : Geometry, optional

    Returns
    -------
    O, A, B : ndarray, shape: the broadcast batch shape ``+ (2,)``
        Points in metres; ``A - O`` has length ``r2``, and at a solution ``B - A`` has length
        ``r3`` and ``B`` lies on the guide.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> O, A, B = joints(closed_form(0.0), 0.0)
    >>> A.tolist(), round(float(B[1]), 12)
    ([0.075, 0.0], 0.045)
    """
    x = _validate.array(x, "x")
    width = 3 if x.shape[-1:] == (3,) else 9
    x, theta2 = _check(geometry, [("x", x, width)], [("theta2", theta2)])
    A = geometry.r2 * np.stack(np.broadcast_arrays(np.cos(theta2), np.sin(theta2)), axis=-1)
    B = x[..., 0, None] * np.stack([np.cos(x[..., 1]), np.sin(x[..., 1])], axis=-1)
    A, B = np.broadcast_arrays(A, B)
    return np.zeros_like(A), A, B


def draw(ax, x, theta2, geometry=STUDY, *, legend=True):
    """Draw the saw in the state ``x`` at the crank angle ``theta2`` on the axes ``ax``.

    The guide, the crank ``O A``, the coupler ``A B``, the vector ``r1`` from ``O`` to ``B``
    (dashed) and the slider; the axes get equal scales, labels in metres, and limits that
    hold the mechanism in every pose (so that an animation does not jump).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    x : array_like, shape (9,) or (3,)
        One state (or its positions).
    theta2 : float
    geometry : Geometry, optional
    legend : bool, optional
        Whether to label the parts in a legend.

    Returns
    -------
    list of matplotlib.artist.Artist
        The guide, crank, coupler, ``r1`` and slider, in that order.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> guide, crank, coupler, r1, slider = draw(ax, closed_form(0.0), 0.0)
    >>> crank.get_xydata().tolist()
    [[0.0, 0.0], [0.075, 0.0]]
    >>> plt.close(fig)
    """
    O, A, B = joints(x, theta2, geometry)
    if O.ndim != 1:
        raise ValueError(f"draw takes one state, got a batch of shape {O.shape[:-1]}")
    g = geometry
    parts = [ax.axhline(g.r1y, color="0.75", lw=6, zorder=0, label="guide of the saw frame"),
             *ax.plot(*np.stack([O, A]).T, "o-", lw=3, label="crank $r_2$"),
             *ax.plot(*np.stack([A, B]).T, "o-", lw=3, label="coupler $r_3$"),
             *ax.plot(*np.stack([O, B]).T, "k--", lw=1, label=r"$\vec r_1 = \vec r_2 + \vec r_3$"),
             *ax.plot(*B, "ks", ms=12, label="slider $B$")]
    pad = DRAW_PAD * g.r2
    ax.set_xlim(-g.r2 - g.r3 - pad, g.r2 + pad)  # the slider's farthest left, the crank's right
    ax.set_ylim(-g.r2 - pad, max(g.r1y, g.r2) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if legend:
        ax.legend(loc="lower left")
    return parts
