"""The saw draws itself: its joints and one state in a figure.

:func:`~mechnum.mechanisms.hacksaw.joints` gives the points ``O``, ``A``, ``B`` of states;
:func:`~mechnum.mechanisms.hacksaw.draw` draws one state, ``(theta2, x)``, for the chapter's
figures and animations (:func:`mechnum.plotting.animate`).
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, plotting
from mechnum.mechanisms.hacksaw._model import Geometry, checked

DRAW_PAD = 0.25  # blank border around a drawing, in crank lengths: room for the joints' dots


def joints(mech: Geometry, x: ArrayLike, theta2: ArrayLike) -> tuple[np.ndarray, ...]:
    """The crank pivot ``O``, crank pin ``A`` and slider pin ``B`` of the states ``x``.

    Parameters
    ----------
    mech : Geometry
    x : array_like, shape (..., 9) or (..., 3)
        States (or positions ``(r1, theta1, theta3)``).
    theta2 : array_like
        Crank angles, broadcasting against ``x.shape[:-1]``.

    Returns
    -------
    O, A, B : ndarray, shape: the broadcast batch shape ``+ (2,)``
        Points in metres; ``A - O`` has length ``r2``, and at a solution ``B - A`` has length
        ``r3`` and ``B`` lies on the guide.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> O, A, B = joints(STUDY, closed_form(STUDY, 0.0), 0.0)
    >>> A.tolist(), round(float(B[1]), 12)
    ([0.075, 0.0], 0.045)
    """
    x = _validate.array(x, "x")
    width = 3 if x.shape[-1:] == (3,) else 9
    x, theta2 = checked(mech, [("x", x, width)], [("theta2", theta2)])
    A = mech.r2 * np.stack(np.broadcast_arrays(np.cos(theta2), np.sin(theta2)), axis=-1)
    B = x[..., 0, None] * np.stack([np.cos(x[..., 1]), np.sin(x[..., 1])], axis=-1)
    A, B = np.broadcast_arrays(A, B)
    return np.zeros_like(A), A, B


def draw(ax: object, mech: Geometry, state: tuple, *, artists: dict | None = None,
         legend: bool = True) -> dict:
    """Draw the saw in one state on the axes ``ax``, or move a drawing made before to it.

    The guide, the crank ``O A``, the coupler ``A B``, the vector ``r1`` from ``O`` to ``B``
    (dashed) and the slider; a new drawing gets equal scales, labels in metres, and limits that
    hold the mechanism in every pose (so that an animation does not jump).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : Geometry
    state : (float, array_like)
        ``(theta2, x)``: the crank angle and the state, shape (9,), or its positions, shape (3,).
    artists : dict, optional
        What an earlier call returned: moved to ``state`` (for an animation).
    legend : bool, optional
        Whether a new drawing labels the parts in a legend.

    Returns
    -------
    dict
        The artists: ``"guide"``, ``"crank"``, ``"coupler"``, ``"r1"``, ``"slider"``.

    Raises
    ------
    ValueError
        If ``ax`` is not an Axes, ``state`` is not one crank angle and one state, or
        ``legend`` is not a bool.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> parts = draw(ax, STUDY, (0.0, closed_form(STUDY, 0.0)))
    >>> parts["crank"].get_xydata().tolist()
    [[0.0, 0.0], [0.075, 0.0]]
    >>> plt.close(fig)
    """
    plotting.check_axes(ax)
    legend = _validate.flag(legend, "legend")
    try:
        theta2, x = state
    except (TypeError, ValueError):
        raise ValueError(f"state must be (theta2, x), got {state!r:.80}") from None
    O, A, B = joints(mech, x, theta2)
    if O.ndim != 1:
        raise ValueError(f"draw takes one state, got a batch of shape {O.shape[:-1]}")
    g = mech
    drawn = plotting.parts(ax, {
        "guide": ([[0.0, g.r1y]], {"kind": "hline", "color": "0.75", "lw": 6, "zorder": 0,
                                   "label": "guide of the saw frame"}),
        "crank": ([O, A], {"marker": "o", "lw": 3, "label": "crank $r_2$"}),
        "coupler": ([A, B], {"marker": "o", "lw": 3, "label": "coupler $r_3$"}),
        "r1": ([O, B], {"color": "k", "ls": "--", "lw": 1,
                        "label": r"$\vec r_1 = \vec r_2 + \vec r_3$"}),
        "slider": ([B], {"color": "k", "marker": "s", "ms": 12, "ls": "none",
                         "label": "slider $B$"})}, artists)
    if artists is None:
        pad = DRAW_PAD * g.r2
        ax.set_xlim(-g.r2 - g.r3 - pad, g.r2 + pad)  # the slider's farthest left, the crank's
        ax.set_ylim(-g.r2 - pad, max(g.r1y, g.r2) + pad)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        if legend:
            ax.legend(loc="lower left")
    return drawn
