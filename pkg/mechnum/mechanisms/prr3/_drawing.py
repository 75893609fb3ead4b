"""The 3PRR draws itself: :func:`draw`, for the chapter's figures and animations."""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, plotting
from mechnum.mechanisms.prr3 import _kernels as kernels
from mechnum.mechanisms.prr3._geometry import Geometry, check, vectors

_GAP = np.full((1, 2), np.nan)  # breaks a line between two of its segments


def draw(ax: object, mech: Geometry, state: tuple[ArrayLike, ArrayLike], *,
         artists: dict | None = None, color: str = "tab:blue", alpha: float = 1.0,
         guides: bool = True) -> dict:
    """Draw one configuration, or move a drawing made before to it.

    The fixed guides and the motors' origins (``guides``), the three bars ``C_i P_i``, the
    sliders ``C_i`` and the platform; equal scales on both axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : ~mechnum.mechanisms.prr3.Geometry
    state : (array_like, array_like)
        ``(lambdas, pose)``: the inputs and the platform's pose that they assemble, each of
        shape (3,).
    artists : dict, optional
        What an earlier call returned: moved to ``state`` (for an animation).
    color : str, optional
        Colour of the bars and sliders.
    alpha : float, optional
        Opacity (to overlay several assembly modes).
    guides : bool, optional
        Whether to draw the fixed guides and the motors' origins.

    Returns
    -------
    dict
        The artists: ``"platform"``, ``"bars"``, ``"sliders"``, and with ``guides``
        ``"guide 1-2"``, ``"guide 3"``, ``"origins"``.

    Raises
    ------
    ValueError
        If ``ax`` is not an Axes, ``state`` is not one input and one pose, or an option is
        invalid.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> drawn = draw(ax, g, ([1.516515, 0.483485, -0.182541], [0.6, 0.4, 0.0]))
    >>> sorted(drawn)
    ['bars', 'guide 1-2', 'guide 3', 'origins', 'platform', 'sliders']
    >>> plt.close(fig)
    """
    plotting.check_axes(ax)
    check(mech)
    try:
        lambdas, pose = state
    except (TypeError, ValueError):
        raise ValueError(f"state must be (lambdas, pose), got {state!r:.80}") from None
    lambdas, pose = vectors(lambdas, "lambdas"), vectors(pose, "pose")
    if lambdas.shape != (3,) or pose.shape != (3,):
        raise ValueError(f"draw takes one input and one pose, each of shape (3,), got shapes "
                         f"{lambdas.shape} and {pose.shape}")
    alpha = _validate.scalar(alpha, "alpha", nonnegative=True)
    guides = _validate.flag(guides, "guides")
    v, c = kernels.vertices(mech, pose), kernels.sliders(mech, lambdas)
    legs = np.concatenate([np.concatenate([ci[None], pi[None], _GAP]) for ci, pi in zip(c, v)])
    shapes = {}
    if guides:
        shapes = {"guide 1-2": ([[0.0, 0.0]], {"kind": "hline", "color": "0.75", "lw": 1}),
                  "guide 3": ([[mech.B3, 0.0]], {"kind": "vline", "color": "0.75", "lw": 1}),
                  "origins": ([[0.0, 0.0], [mech.B2, 0.0], [mech.B3, mech.H3]],
                              {"ls": "none", "marker": "^", "color": "k", "ms": 5})}
    shapes |= {"platform": (v, {"kind": "fill", "color": "tab:orange", "alpha": 0.6 * alpha}),
               "bars": (legs, {"color": color, "lw": 2, "alpha": alpha}),
               "sliders": (c, {"ls": "none", "marker": "s", "color": color, "ms": 6,
                               "alpha": alpha})}
    drawn = plotting.parts(ax, shapes, artists)
    if artists is None:
        ax.set_aspect("equal")
    return drawn
