"""Figure and animation helpers shared by the chapters.

Matplotlib is imported lazily, so the numerical modules never need it.
"""

import re

# Matplotlib's animation controls use Font Awesome icons loaded from a CDN; the book works offline,
# so the icons become plain characters and the stylesheet link is dropped.
_ICONS = {"fa-play fa-flip-horizontal": "\u25c0", "fa-play": "\u25b6", "fa-pause": "\u23f8",
          "fa-minus": "\u2212", "fa-plus": "+", "fa-fast-backward": "\u23ee",
          "fa-fast-forward": "\u23ed", "fa-step-backward": "|\u25c0", "fa-step-forward": "\u25b6|"}


class JSAnimation(str):
    """The HTML of a JavaScript animation; a notebook displays it as the animation itself."""

    def _repr_html_(self):
        return str(self)


def animate(fig, update, frames, *, interval=80, dpi=72):
    """Render ``update(i)`` for ``i`` in ``frames`` as a self-contained JavaScript animation.

    The frames are embedded as PNG images in the HTML, so the animation plays in the static book
    with no server and no network (the control icons are plain characters, not a web font). Keep ``frames`` small (a few dozen): every frame adds to the
    size of the page. The figure is closed, so it is not displayed a second time as a still.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to animate.
    update : callable
        ``update(frame)`` redraws the figure for one frame (its return value is ignored).
    frames : int or iterable
        The frames, as for :class:`matplotlib.animation.FuncAnimation`.
    interval : float, optional
        Milliseconds between frames.
    dpi : float, optional
        Resolution of the embedded frames.

    Returns
    -------
    JSAnimation
        The HTML (a ``str``) that a notebook displays as the animation.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> (line,) = ax.plot([], [])
    >>> html = animate(fig, lambda i: line.set_data([0, i], [0, i]), frames=3)
    >>> "<script" in html and "http" not in html
    True
    """
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    anim = FuncAnimation(fig, update, frames=frames, interval=interval, blit=False)
    saved = plt.rcParams["savefig.dpi"]
    try:
        plt.rcParams["savefig.dpi"] = dpi
        html = anim.to_jshtml(default_mode="loop")
    finally:
        plt.rcParams["savefig.dpi"] = saved
        plt.close(fig)
    html = re.sub(r"<link[^>]*font-awesome[^>]*>", "", html)
    html = re.sub(r'<i class="fa ([^"]+)"></i>', lambda m: _ICONS[m.group(1)], html)
    return JSAnimation(html)
