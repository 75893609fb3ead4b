"""Figures and animations of the book: its style file, the mechanisms' drawing parts, animate.

* :func:`use_book_style` applies the book's Matplotlib style file (:data:`STYLE`): the text sizes
  that keep every figure readable at the web book's width, so that no cell sets a font size.
* :func:`parts` creates a drawing's named artists on its axes, or moves them: every mechanism's
  ``draw(ax, mech, state, *, artists=None)`` is built on it (the mechanism protocol).
* :func:`animate` renders ``draw`` over a sequence of states as an animation that plays in the
  static book: ``animate(draw, mech, states)`` animates any mechanism.

Matplotlib is imported lazily, so the numerical modules never need it.
"""

import base64
import hashlib
import re
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

__all__ = ["JSAnimation", "animate", "check_axes", "parts", "use_book_style"]

STYLE = Path(__file__).with_name("book.mplstyle")
"""The book's Matplotlib style file: text sizes of 9 pt and more (CONTRIBUTING.md)."""
MAX_FRAMES = 200
"""The most frames an animation may have: each is a PNG of some 10 to 50 kB in the page, so 200
make a page of several megabytes (a chapter keeps to a few dozen)."""
MAX_DPI = 300
"""The highest resolution of an animation's frames (the work and the size grow as its square)."""
_KINDS = ("line", "fill", "hline", "vline", "arrow")

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


def use_book_style() -> None:
    """Apply the book's style file (:data:`STYLE`) to every figure drawn from now on.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> with plt.rc_context():
    ...     use_book_style()
    ...     plt.rcParams["legend.fontsize"]
    9.0
    """
    import matplotlib.pyplot as plt

    plt.style.use(STYLE)


def check_axes(ax: object) -> object:
    """``ax`` if it is a Matplotlib ``Axes``; else :class:`ValueError` naming it.

    Examples
    --------
    >>> check_axes(None)
    Traceback (most recent call last):
    ...
    ValueError: ax must be a matplotlib Axes, got None
    """
    from matplotlib.axes import Axes

    if not isinstance(ax, Axes):
        raise ValueError(f"ax must be a matplotlib Axes, got {ax!r:.80}")
    return ax


def parts(ax: object, shapes: dict, artists: dict | None = None) -> dict:
    """A drawing's named parts: created on ``ax``, or, given ``artists``, moved to ``shapes``.

    The building block of every mechanism's ``draw``: the first call creates one artist per
    part, later calls (an animation's frames) move the same artists, so nothing accumulates.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    shapes : dict
        ``{name: (points, style)}``: ``points`` of shape ``(k, 2)`` (NaN rows break a line), and
        the artist's Matplotlib ``style``, whose ``"kind"`` is ``"line"`` (the default: a
        Line2D), ``"fill"`` (a polygon), ``"arrow"`` (from the first point to the second, an
        annotation whose ``style`` is its ``arrowprops``), or ``"hline"``/``"vline"`` (a fixed
        guide across the axes at the first point's y or x; it is not moved later).
    artists : dict, optional
        What an earlier call returned, to move.

    Returns
    -------
    dict
        ``{name: artist}``, in the order of ``shapes`` (the dict ``artists`` itself, if given).

    Raises
    ------
    ValueError
        If ``ax`` is not an Axes, a kind is unknown, or ``artists`` is not the dict of an
        earlier call with the same parts.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> drawn = parts(ax, {"bar": ([[0, 0], [1, 1]], {"color": "k"})})
    >>> moved = parts(ax, {"bar": ([[0, 0], [2, 0]], {})}, drawn)
    >>> moved is drawn, moved["bar"].get_xydata().tolist()
    (True, [[0.0, 0.0], [2.0, 0.0]])
    >>> plt.close(fig)
    """
    check_axes(ax)
    if not isinstance(shapes, dict):
        raise ValueError(f"shapes must be a dict {{name: (points, style)}}, got {shapes!r:.80}")
    if artists is not None and (not isinstance(artists, dict) or set(artists) != set(shapes)):
        raise ValueError(f"artists must be the dict that an earlier draw returned, with the "
                         f"parts {sorted(shapes)}, got {artists!r:.80}")
    out = {} if artists is None else artists
    for name, (points, style) in shapes.items():
        xy = np.asarray(points, dtype=float).reshape(-1, 2)
        style = dict(style)
        kind = style.pop("kind", "line")
        if kind not in _KINDS:
            raise ValueError(f"the kind of part {name!r} must be one of {_KINDS}, got {kind!r}")
        if kind == "arrow" and len(xy) != 2:
            raise ValueError(f"the arrow {name!r} needs two points (tail, head), got {len(xy)}")
        if artists is not None:
            if kind == "line":
                out[name].set_data(xy[:, 0], xy[:, 1])
            elif kind == "fill":
                out[name].set_xy(xy)
            elif kind == "arrow":
                out[name].xy, out[name].xyann = tuple(xy[1]), tuple(xy[0])
        elif kind == "line":
            (out[name],) = ax.plot(xy[:, 0], xy[:, 1], **style)
        elif kind == "fill":
            (out[name],) = ax.fill(xy[:, 0], xy[:, 1], **style)
        elif kind == "arrow":
            out[name] = ax.annotate("", xy=xy[1], xytext=xy[0], arrowprops=style)
        else:
            out[name] = (ax.axhline(xy[0, 1], **style) if kind == "hline"
                         else ax.axvline(xy[0, 0], **style))
    return out


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


def _fit(ax, draw, mech, states, artists, options):
    """Limits that hold every frame, unless the axes' limits are set (autoscale off)."""
    if not (ax.get_autoscalex_on() or ax.get_autoscaley_on()):
        return
    from matplotlib.transforms import Bbox

    boxes = []
    for state in states:
        draw(ax, mech, state, artists=artists, **options)
        ax.relim(visible_only=True)
        boxes.append(ax.dataLim.frozen())
    ax.dataLim.set(Bbox.union(boxes))
    ax.autoscale_view()
    ax.set_autoscale_on(False)  # the frames keep these limits


def _render(fig, update, frames, interval, dpi):
    """The frames of ``update`` as self-contained HTML; the figure is closed."""
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


def _controls(interval, dpi):
    """``interval`` and ``dpi``, checked."""
    from mechnum import _validate

    interval = _validate.scalar(interval, "interval", positive=True)
    dpi = _validate.scalar(dpi, "dpi", positive=True)
    if dpi > MAX_DPI:
        raise ValueError(f"dpi must be at most {MAX_DPI} (a bound on the work), got {dpi!r}")
    return interval, dpi


def _frame_count(count, name):
    if not 1 <= count <= MAX_FRAMES:
        raise ValueError(f"an animation needs 1 to {MAX_FRAMES} {name} (a bound on the page's "
                         f"size), got {count}")
    return count


def animate(draw: Callable, mech: object, states: Sequence, *, ax: object = None,
            titles: Sequence[str] | None = None, interval: float = 80, dpi: float = 72,
            **options: object) -> JSAnimation:
    """Animate any mechanism: ``draw(ax, mech, state)`` over ``states``, as HTML that plays offline.

    The first state is drawn anew (``draw(ax, mech, states[0], **options)``), every other one
    moves those artists (``artists=``), so the mechanism moves and nothing accumulates. Unless
    the axes' limits are set, they are fitted to hold every frame. The frames are embedded as
    PNG images in the HTML, so the animation plays in the static book with no server and no
    network (the control icons are inline SVG, not a web font); every frame adds to the page,
    so keep to a few dozen. A figure without a layout engine of its own is laid out once, on
    the first frame, so that no label or title is cropped, and keeps that layout in every frame.
    The figure is closed, so it is not displayed again as a still. The HTML is the same
    whenever the frames are: its element ids are a hash of the content.

    Parameters
    ----------
    draw : callable
        A mechanism's ``draw(ax, mech, state, *, artists=None, **options)``: it draws one state
        and returns its artists, or moves the ``artists`` it is given.
    mech : object
        The mechanism.
    states : sequence
        The states, one per frame (1 to :data:`MAX_FRAMES`).
    ax : matplotlib.axes.Axes, optional
        Where to draw (with whatever title, labels, limits or background it already has); a new
        figure by default.
    titles : sequence of str, optional
        One title per frame.
    interval : float, optional
        Milliseconds between frames.
    dpi : float, optional
        Resolution of the embedded frames (at most :data:`MAX_DPI`).
    **options
        Passed to ``draw`` (``color=``, ``legend=``, ...).

    Returns
    -------
    JSAnimation
        The HTML (a ``str``) that a notebook displays as the animation.

    Raises
    ------
    ValueError
        If ``draw`` is not callable, there are no states or too many, ``titles`` does not give
        one per state, ``ax`` is not an Axes, or ``interval`` or ``dpi`` is not a positive
        number (``dpi`` at most :data:`MAX_DPI`).

    Examples
    --------
    >>> def draw(ax, mech, state, *, artists=None):      # a bar of length mech, at an angle
    ...     tip = mech * np.array([np.cos(state), np.sin(state)])
    ...     return parts(ax, {"bar": ([[0, 0], tip], {"lw": 3})}, artists)
    >>> html = animate(draw, 1.0, np.linspace(0, np.pi, 4), titles=["a", "b", "c", "d"])
    >>> "<script" in html and "http" not in html and "<svg" in html, repr(html)
    (True, '<animation of 4 frames: it plays in the HTML book>')
    """
    if not callable(draw):
        raise ValueError(f"draw must be a mechanism's draw(ax, mech, state), got {draw!r:.80}")
    states = list(states)
    _frame_count(len(states), "states")
    if titles is not None:
        titles = [str(title) for title in titles]
        if len(titles) != len(states):
            raise ValueError(f"titles must give one title per state ({len(states)}), "
                             f"got {len(titles)}")
    interval, dpi = _controls(interval, dpi)
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    check_axes(ax)
    artists = draw(ax, mech, states[0], **options)
    _fit(ax, draw, mech, states, artists, options)

    def update(i):
        draw(ax, mech, states[i], artists=artists, **options)
        if titles is not None:
            ax.set_title(titles[i])

    update(0)
    _lay_out(ax.figure)
    return _render(ax.figure, update, range(len(states)), interval, dpi)


def _lay_out(fig):
    """Lay out the figure once, on its first frame, so that no label or title is cropped, and
    keep that layout for every frame (laid out per frame, the axes would jump as the titles
    change). A figure that has a layout engine of its own keeps it."""
    if fig.get_layout_engine() is not None:
        return
    fig.set_layout_engine("constrained")
    fig.draw_without_rendering()
    fig.set_layout_engine("none")
