"""The finger's four-bar draws itself: :func:`draw`, for the chapter's figures and animations."""

import numpy as np

from mechnum import _validate, plotting
from mechnum.mechanisms.finger._model import Linkage, checked, place_links


def _parts(ax, pose, index, artists, color):
    """Draw (or move) the chain ``D-E-I-H`` and the ground ``D-H`` of one pose of ``pose``."""
    chain = np.array([pose.D[index], pose.E[index], pose.I[index], pose.H[index]])
    return plotting.parts(ax, {
        "links": (chain, {"marker": "o", "color": color, "lw": 2, "label": "links D-E-I-H"}),
        "ground": (chain[[0, 3]], {"color": "k", "marker": "^", "ls": "--", "ms": 9,
                                   "label": "ground D-H"})}, artists)


def draw(ax: object, mech: Linkage, state: tuple, *, artists: dict | None = None,
         color: str = "C0") -> dict:
    """Draw the linkage in one state: ground ``DH``, rockers and coupler; or move a drawing.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : Linkage
    state : (float, float)
        ``(theta_in, theta_out)``: the input and output angles, rad, of one assembly mode
        (:func:`forward`).
    artists : dict, optional
        What an earlier call returned: moved to ``state`` (for an animation).
    color : str, optional
        Colour of the moving links.

    Returns
    -------
    dict
        ``"links"``, the chain ``D-E-I-H``, and ``"ground"``, the ground link.

    Raises
    ------
    ValueError
        If ``ax`` is not an Axes, ``mech`` not a :class:`Linkage`, or ``state`` not two
        angles.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from mechnum.mechanisms.finger import forward
    >>> fig, ax = plt.subplots()
    >>> L = Linkage(0.030613, 0.0069973, 0.0247825, 0.0069989)
    >>> drawn = draw(ax, L, (5.0, forward(L, [5.0]).x[0, 0]))
    >>> (drawn["links"].get_xydata() * 1e3).round(2).tolist()[1]     # E, in millimetres
    [-20.89, 22.38]
    >>> moved = draw(ax, L, (5.5, forward(L, [5.5]).x[0, 0]), artists=drawn); plt.close(fig)
    """
    plotting.check_axes(ax)
    checked(mech)
    try:
        theta_in, theta_out = (_validate.scalar(v, name) for v, name in
                               zip(state, ("theta_in", "theta_out")))
    except (TypeError, ValueError) as error:
        raise ValueError(f"state must be (theta_in, theta_out), got {state!r:.80}: "
                         f"{error}") from None
    return _parts(ax, place_links(mech, [theta_in], [theta_out]), 0, artists, color)
