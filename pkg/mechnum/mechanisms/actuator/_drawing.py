"""The actuator mechanism draws itself: :func:`draw`, for figures and animations."""

import numpy as np

from mechnum import _validate, plotting
from mechnum.mechanisms.actuator._model import Actuator, checked

# A state whose angles miss the loop's closure by more than this (relative to the pivots'
# distance) is no configuration of the mechanism: drawn, it would show links that do not meet.
_CLOSURE_RTOL = 1e-6


def draw(ax: object, mech: Actuator, state: tuple, *, artists: dict | None = None) -> dict:
    """Draw the mechanism in one state, or move a drawing made before to it.

    The barrel (thick, from ``O2`` to its upper end ``ls``), the rod (from the piston to ``A``),
    the rocker (from ``O4`` through ``A`` to its centre of mass or beyond), the ground pivots and
    the centres of mass. A new drawing sets equal aspect and fits the limits; moving one keeps
    them. Labels and titles are the caller's.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Where to draw.
    mech : Actuator
    state : (float, array_like)
        ``(a, (theta2, theta4))``: the stroke (m) and the link angles (rad) of one assembly
        mode at it (:func:`forward`).
    artists : dict, optional
        The artists returned by an earlier call on ``ax``: they are moved, nothing is added
        (for an animation).

    Returns
    -------
    dict
        The artists, keyed ``"barrel"``, ``"rod"``, ``"rocker"``, ``"pivots"``, ``"centres"``.

    Raises
    ------
    ValueError
        If ``ax`` is not an Axes, ``state`` is not a stroke and two angles that close the loop,
        or ``artists`` lacks one of the keys.

    Examples
    --------
    >>> from mechnum.mechanisms.actuator.study import ANNEX
    >>> from mechnum.mechanisms.actuator import forward
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> parts = draw(ax, ANNEX, (0.6, forward(ANNEX, 0.6).x[0]))
    >>> np.round(parts["rod"].get_xydata(), 6).tolist()      # from the piston to A
    [[0.0, 0.6], [0.0, 1.0]]
    >>> parts = draw(ax, ANNEX, (0.62, forward(ANNEX, 0.62).x[0]), artists=parts)
    >>> plt.close(fig)
    """
    plotting.check_axes(ax)
    mech = checked(mech)
    try:
        a, angles = state
    except (TypeError, ValueError):
        raise ValueError(f"state must be (a, (theta2, theta4)), got {state!r:.80}") from None
    a = _validate.scalar(a, "a")
    th2, th4 = _validate.array(angles, "angles", shape=(2,))
    e2, e4 = np.exp(1j * th2), np.exp(1j * th4)
    o4 = complex(-mech.o2, mech.o4)
    if abs((a + mech.l) * e2 - o4 - mech.b * e4) > _CLOSURE_RTOL * mech.d:
        raise ValueError(f"state must close the loop: the angles {[th2, th4]} do not assemble "
                         f"the mechanism at a = {a!r} m")
    shapes = {
        "barrel": ([0.0, mech.ls * e2], {"lw": 9, "color": "tab:blue", "alpha": 0.5,
                                          "solid_capstyle": "butt", "label": "barrel (2)"}),
        "rod": ([a * e2, (a + mech.l) * e2], {"lw": 3, "color": "tab:orange", "zorder": 3,
                                               "label": "rod (3)"}),
        "rocker": ([o4, o4 + max(mech.b, mech.g4) * e4], {"lw": 3, "color": "tab:green",
                                                          "label": "rocker (4)"}),
        "pivots": ([0.0, o4], {"ls": "none", "marker": "^", "ms": 10, "color": "k",
                               "label": "pivots"}),
        "centres": ([mech.g2 * e2, (a + mech.g3) * e2, o4 + mech.g4 * e4],
                    {"ls": "none", "marker": "o", "ms": 4, "color": "k", "zorder": 4,
                     "label": "centres of mass"}),
    }
    shapes = {name: (np.column_stack([np.real(z), np.imag(z)]), style)
              for name, (z, style) in shapes.items()}
    drawn = plotting.parts(ax, shapes, artists)
    if artists is None:  # fit a new drawing; a moving one keeps the limits (an animation's)
        ax.set_aspect("equal")
        ax.relim()
        ax.autoscale_view()
    return drawn
