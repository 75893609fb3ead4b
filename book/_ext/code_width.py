"""Every code cell of a page holds a line of 76 characters (CONTRIBUTING.md) without scrolling
sideways: the cells that sit in a narrower box than the column (a solution's dropdown, a folded
cell) get slightly smaller type (``static/code_width.css``). ``tests/test_browser.py`` measures
every code cell of the lecture pages."""

from pathlib import Path

STATIC = Path(__file__).resolve().parent / "static"


def setup(app):
    app.connect("config-inited", lambda app, config: config.html_static_path.append(str(STATIC)))
    app.add_css_file("code_width.css")
    return {"parallel_read_safe": True, "parallel_write_safe": True}
