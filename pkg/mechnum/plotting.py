"""Figure and animation helpers shared by the chapters.

Matplotlib is imported lazily, so the numerical modules never need it.
"""


class JSAnimation(str):
    """The HTML of a JavaScript animation; a notebook displays it as the animation itself."""

    def _repr_html_(self):
        return str(self)


def animate(fig, update, frames, *, interval=80, dpi=72):
    """Render ``update(i)`` for ``i`` in ``frames`` as a self-contained JavaScript animation.

    The frames are embedded as PNG images in the HTML, so the animation plays in the static book
    with no server and no network. Keep ``frames`` small (a few dozen): every frame adds to the
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
    >>> html.startswith("\\n<link rel=\\"stylesheet\\"") or "<script" in html
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
    return JSAnimation(html)
