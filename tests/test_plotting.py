"""Tests of mechnum.plotting: animations play offline."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

from mechnum.plotting import JSAnimation, animate  # noqa: E402


def test_animation_is_self_contained_html():
    fig, ax = plt.subplots()
    (line,) = ax.plot([], [])
    html = animate(fig, lambda i: line.set_data([0, i], [0, i]), frames=4)
    assert isinstance(html, JSAnimation) and html._repr_html_() == str(html)
    assert "http" not in html and 'class="fa ' not in html
    assert html.count("data:image/png;base64") == 4
    assert not plt.fignum_exists(fig.number)  # the figure was closed


def line_animation(frames):
    fig, ax = plt.subplots()
    (line,) = ax.plot([], [])
    return animate(fig, lambda i: line.set_data([0, i], [0, i]), frames=frames)


def test_controls_are_inline_svg_and_ids_are_reproducible():
    html = line_animation(3)
    assert html.count("<svg") == 9  # one icon per control button
    assert not any(glyph in html for glyph in "\u23ee\u23ed\u23f8\u25b6\u25c0")  # fonts lack
    assert html == line_animation(3) != line_animation(4)  # same frames, same HTML


def test_outside_html_an_animation_is_its_first_frame_and_one_line():
    html = line_animation(3)
    assert html._repr_png_().startswith(b"\x89PNG\r\n\x1a\n")
    assert repr(html) == "<animation of 3 frames: it plays in the HTML book>"
