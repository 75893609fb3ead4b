"""The actuator mechanism draws itself: :func:`draw`, for figures and animations."""

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.actuator.loop import positions
from mechnum.mechanisms.actuator.model import ANNEX, _mechanism


def draw(ax, a, mech=ANNEX, artists=None):
    """Draw the mechanism at the stroke ``a``, or move a drawing made before to it.

    The barrel (thick, from ``O2`` to its upper end ``ls``), the rod (from the piston to ``A``),
    the rocker (from ``O4`` through ``A`` to its centre of mass or beyond), the ground pivots and
    the centres of mass. A new drawing sets equal aspect and fits the limits; moving one keeps
    them. Labels and titles are the caller's.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Where to draw.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.
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
        If ``a`` is not a finite real number, or ``artists`` lacks one of the keys.
    UnreachablePoseError
        If the loop cannot close at ``a``.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> parts = draw(ax, 0.6)
    >>> np.round(parts["rod"].get_xydata(), 6).tolist()      # from the piston to A
    [[0.0, 0.6], [0.0, 1.0]]
    >>> parts = draw(ax, 0.62, artists=parts)
    >>> plt.close(fig)
    """
    a = _validate.scalar(a, "a")
    mech = _mechanism(mech)
    th2, th4 = (float(x) for x in positions(a, mech))
    e2, e4 = np.exp(1j * th2), np.exp(1j * th4)
    o4 = complex(-mech.o2, mech.o4)
    points = {
        "barrel": [0.0, mech.ls * e2],
        "rod": [a * e2, (a + mech.l) * e2],
        "rocker": [o4, o4 + max(mech.b, mech.g4) * e4],
        "pivots": [0.0, o4],
        "centres": [mech.g2 * e2, (a + mech.g3) * e2, o4 + mech.g4 * e4],
    }
    new = artists is None
    if new:
        styles = {"barrel": dict(lw=9, color="tab:blue", alpha=0.5, solid_capstyle="butt",
                                 label="barrel (2)"),
                  "rod": dict(lw=3, color="tab:orange", zorder=3, label="rod (3)"),
                  "rocker": dict(lw=3, color="tab:green", label="rocker (4)"),
                  "pivots": dict(ls="none", marker="^", ms=10, color="k", label="pivots"),
                  "centres": dict(ls="none", marker="o", ms=4, color="k", zorder=4,
                                  label="centres of mass")}
        artists = {name: ax.plot([], [], **style)[0] for name, style in styles.items()}
        ax.set_aspect("equal")
    elif not isinstance(artists, dict) or set(artists) != set(points):
        raise ValueError(f"artists must be the dict that draw returned, with the keys "
                         f"{sorted(points)}, got {_validate._shown(artists)}")
    for name, ends in points.items():
        z = np.array(ends, dtype=complex)
        artists[name].set_data(z.real, z.imag)
    if new:  # fit a new drawing; a moving one keeps the limits (an animation's frame)
        ax.relim()
        ax.autoscale_view()
    return artists
