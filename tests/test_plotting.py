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
    assert not plt.get_fignums()  # the figure was closed
