"""Tests of mechnum.plotting: animations play offline, any mechanism animates, the book's style."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from mechnum.plotting import (  # noqa: E402
    MAX_DPI,
    MAX_FRAMES,
    STYLE,
    JSAnimation,
    animate,
    check_axes,
    parts,
    use_book_style,
)


def bar(ax, mech, state, *, artists=None, color="C0"):
    """A mechanism of one bar of length ``mech`` at the angle ``state``: the protocol's draw."""
    tip = mech * np.array([np.cos(state), np.sin(state)])
    return parts(ax, {"bar": ([[0.0, 0.0], tip], {"lw": 3, "color": color})}, artists)


def test_animation_is_self_contained_html():
    before = set(plt.get_fignums())
    html = animate(bar, 1.0, np.linspace(0, np.pi, 4))
    assert isinstance(html, JSAnimation) and html._repr_html_() == str(html)
    assert "http" not in html and 'class="fa ' not in html
    assert html.count("data:image/png;base64") == 4
    assert set(plt.get_fignums()) == before  # its figure was closed


def test_animate_moves_one_set_of_artists_and_fits_every_frame():
    fig, ax = plt.subplots()
    seen = []

    def spy(ax_, mech, state, *, artists=None):
        out = bar(ax_, mech, state, artists=artists)
        seen.append((artists is None, len(ax_.lines), state))
        return out

    animate(spy, 2.0, [0.0, np.pi / 2, np.pi], ax=ax, titles=["a", "b", "c"])
    assert [new for new, _, _ in seen].count(True) == 1  # drawn once, then moved
    assert {count for _, count, _ in seen} == {1}  # nothing accumulates
    (x0, x1), (_, y1) = ax.get_xlim(), ax.get_ylim()
    assert x0 <= -2.0 and x1 >= 2.0 and y1 >= 2.0  # limits hold every frame's bar
    assert ax.get_title() == "c"


def test_set_limits_are_kept():
    fig, ax = plt.subplots()
    ax.set_xlim(-5, 5)
    ax.set_ylim(-1, 1)
    animate(bar, 1.0, [0.0, 1.0], ax=ax, color="k")
    assert ax.get_xlim() == (-5, 5) and ax.get_ylim() == (-1, 1)


def wide(ax, mech, state, *, artists=None):
    """A bar drawn as a mechanism's draw draws a wide linkage: equal scales, set limits,
    labelled axes (Chapter 1's saw in a short figure)."""
    out = bar(ax, mech, state, artists=artists)
    if artists is None:
        ax.set(xlim=(-2.6, 0.9), ylim=(-0.9, 0.9), aspect="equal", xlabel="x (m)",
               ylabel="y (m)")
    return out


def test_the_frames_crop_no_label_or_title():
    """Laid out once on its first frame, the animation's labels and title lie inside the
    figure (without the layout, the x label of this short figure is cut off)."""
    fig, ax = plt.subplots(figsize=(6, 3.2))
    animate(wide, 0.8, np.linspace(0, np.pi, 3), ax=ax, titles=["a", "b", "c"])
    fig.draw_without_rendering()  # as a frame is drawn: the layout is not redone
    page = fig.bbox
    for text in (ax.xaxis.label, ax.yaxis.label, ax.title):
        box = text.get_window_extent()
        assert page.x0 <= box.x0 and box.x1 <= page.x1, text.get_text()
        assert page.y0 <= box.y0 and box.y1 <= page.y1, text.get_text()
    assert fig.get_layout_engine().__class__.__name__ == "PlaceHolderLayoutEngine"


def test_a_figure_with_its_own_layout_keeps_it():
    fig, ax = plt.subplots(figsize=(6, 3.2), layout="tight")
    animate(wide, 0.8, [0.0, 1.0], ax=ax)
    assert fig.get_layout_engine().__class__.__name__ == "TightLayoutEngine"


def line_animation(frames):
    return animate(bar, 1.0, np.linspace(0, 1, frames))


def test_controls_are_inline_svg_and_ids_are_reproducible():
    html = line_animation(3)
    assert html.count("<svg") == 9  # one icon per control button
    assert not any(glyph in html for glyph in "\u23ee\u23ed\u23f8\u25b6\u25c0")  # fonts lack
    assert html == line_animation(3) != line_animation(4)  # same frames, same HTML


def test_outside_html_an_animation_is_its_first_frame_and_one_line():
    html = line_animation(3)
    assert html._repr_png_().startswith(b"\x89PNG\r\n\x1a\n")
    assert repr(html) == "<animation of 3 frames: it plays in the HTML book>"


@pytest.mark.parametrize("kwargs, match", [
    (dict(draw=None, mech=1.0, states=[0.0]), "draw must be"),
    (dict(draw=bar, mech=1.0, states=[]), "1 to 200 states"),
    (dict(draw=bar, mech=1.0, states=np.zeros(MAX_FRAMES + 1)), "a bound on the page"),
    (dict(draw=bar, mech=1.0, states=[0.0, 1.0], titles=["one"]), "one title per state"),
    (dict(draw=bar, mech=1.0, states=[0.0], ax="axes"), "ax must be a matplotlib Axes"),
    (dict(draw=bar, mech=1.0, states=[0.0], dpi=MAX_DPI + 1), "dpi must be at most"),
    (dict(draw=bar, mech=1.0, states=[0.0], interval=-1), "interval must be positive"),
])
def test_animate_refuses_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        animate(**kwargs)


def test_parts_refuse_bad_input():
    fig, ax = plt.subplots()
    drawn = parts(ax, {"bar": ([[0, 0], [1, 1]], {})})
    with pytest.raises(ValueError, match="artists must be the dict"):
        parts(ax, {"bar": ([[0, 0], [1, 1]], {}), "pin": ([[0, 0]], {})}, drawn)
    with pytest.raises(ValueError, match="kind of part 'bar' must be one of"):
        parts(ax, {"bar": ([[0, 0]], {"kind": "spline"})})
    with pytest.raises(ValueError, match="arrow 'load' needs two points"):
        parts(ax, {"load": ([[0, 0]], {"kind": "arrow"})})
    with pytest.raises(ValueError, match="ax must be a matplotlib Axes"):
        parts(None, {"bar": ([[0, 0]], {})})
    with pytest.raises(ValueError, match="ax must be"):
        check_axes(fig)
    plt.close(fig)


def test_the_book_style_sets_every_text_to_9_points_or_more():
    with plt.rc_context():
        use_book_style()
        sizes = {key: plt.rcParams[key] for key in (
            "font.size", "axes.titlesize", "axes.labelsize", "xtick.labelsize",
            "ytick.labelsize", "legend.fontsize", "figure.titlesize")}
    assert STYLE.exists() and min(float(size) for size in sizes.values()) >= 9.0
    assert plt.rcParams["legend.fontsize"] == matplotlib.rcParamsDefault["legend.fontsize"]
