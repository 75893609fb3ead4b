"""Figure and animation helpers shared by the chapters.

Matplotlib is imported lazily, so the numerical modules never need it.
"""

import base64
import hashlib
import re

# Matplotlib's animation controls use Font Awesome icons loaded from a CDN, and the book works
# offline; plain characters such as U+23EE are missing from common fonts (empty boxes). So the
# icons become small inline SVG drawings (16 x 16, in the button's text colour), and the
# stylesheet link is dropped.
_PATHS = {
    "fa-minus": "M2 7h12v2H2z",
    "fa-plus": "M7 2h2v5h5v2H9v5H7V9H2V7h5z",
    "fa-play": "M4 2l9 6-9 6z",
    "fa-play fa-flip-horizontal": "M12 2L3 8l9 6z",
    "fa-pause": "M3 2h4v12H3zM9 2h4v12H9z",
    "fa-fast-backward": "M2 2h2v12H2zM14 2L5 8l9 6z",
    "fa-step-backward": "M3 3h2v10H3zM12 4L7 8l5 4z",
    "fa-step-forward": "M11 3h2v10h-2zM4 4l5 4-5 4z",
    "fa-fast-forward": "M12 2h2v12h-2zM2 2l9 6-9 6z",
}
_ICON = ('<svg class="anim-icon" width="16" height="16" viewBox="0 0 16 16" aria-hidden="true">'
         '<path fill="currentColor" d="{}"/></svg>')


class JSAnimation(str):
    """The HTML of a JavaScript animation; a notebook displays it as the animation itself.

    Where HTML cannot play (a PDF, a terminal), it shows its first frame as a still image and a
    one-line description, not its HTML source.
    """

    def _repr_html_(self):
        return str(self)

    def _repr_png_(self):
        first = re.search(r'frames\[0\] = "data:image/png;base64,([^"]+)"', self).group(1)
        return base64.b64decode(first.replace("\\\n", "").replace("\\n", ""))

    def __repr__(self):
        frames = len(re.findall(r"frames\[\d+\] = ", self))
        return f"<animation of {frames} frames: it plays in the HTML book>"


def animate(fig, update, frames, *, interval=80, dpi=72):
    """Render ``update(i)`` for ``i`` in ``frames`` as a self-contained JavaScript animation.

    The frames are embedded as PNG images in the HTML, so the animation plays in the static book
    with no server and no network (the control icons are inline SVG, not a web font). Keep
    ``frames`` small (a few dozen): every frame adds to the size of the page. The figure is
    closed, so it is not displayed a second time as a still. The HTML is the same whenever the
    frames are: its element ids are a hash of the content, not random.

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
    >>> "<script" in html and "http" not in html and "<svg" in html
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
    html = re.sub(r'<i class="fa ([^"]+)"></i>', lambda m: _ICON.format(_PATHS[m.group(1)]), html)
    # matplotlib names the animation's elements with a random id; a hash of the content instead
    # makes re-executing an unchanged chapter write the same output
    uid = re.search(r'id="_anim_img(\w+)"', html).group(1)
    digest = hashlib.sha1(html.replace(uid, "").encode()).hexdigest()[:32]
    return JSAnimation(html.replace(uid, digest))
