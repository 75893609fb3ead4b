"""The web book's layout where the theme's defaults hide something (``static/web_layout.css``,
``static/web_layout.js``); ``tests/test_browser.py`` checks each at 1280 px and on a 390 px phone.

* **Tables of verdicts**: a table with a ``verdict`` column (a reproduction table, the
  appendix's lists of rows) shows its ``verdict`` and ``finding`` right after the ``quantity``
  (the first questions a reader asks of a row), and its other cells wrap anywhere (those two at
  their hyphens), so that the table fits the column without scrolling sideways (the notebooks' outputs and the printed book keep
  the order the registry gives).
* **Long inline formulas**: one wider than its line scrolls inside its own box instead of
  being cut off (MathJax 3 does not break a formula across lines); the script marks them.
* **The self-checks' feedback**: the output of an exercise's check cell (its cell metadata
  ``mechnum.role == "check"``) wraps, so that the whole message is read without scrolling.
"""

from pathlib import Path

from docutils import nodes
from sphinx.transforms.post_transforms import SphinxPostTransform

STATIC = Path(__file__).resolve().parent / "static"
FIRST = ("verdict", "finding")
"""The columns moved right after ``quantity`` (or first, without one)."""


def _headings(table):
    head = next(table.findall(nodes.thead), None)
    row = next(head.findall(nodes.row), None) if head is not None else None
    return [entry.astext().strip() for entry in row.children] if row is not None else []


def column_order(headings):
    """The new order of a table's columns, as indices into ``headings``.

    Examples
    --------
    >>> column_order(["where", "quantity", "finding", "published", "computed", "verdict"])
    [0, 1, 5, 2, 3, 4]
    >>> column_order(["verdict", "rows", "findings"])
    [0, 1, 2]
    """
    moved = [headings.index(name) for name in FIRST if name in headings]
    rest = [k for k in range(len(headings)) if k not in moved]
    at = rest.index(headings.index("quantity")) + 1 if "quantity" in headings else 0
    return rest[:at] + moved + rest[at:]


class VerdictsFirst(SphinxPostTransform):
    """Move the verdict and finding columns of the tables of verdicts, and mark those tables
    and the self-checks' cells for the style sheet."""

    default_priority = 400
    formats = ("html",)

    def apply(self, **kwargs):
        for table in list(self.document.findall(nodes.table)):
            headings = _headings(table)
            if "verdict" not in headings:
                continue
            table["classes"].append("table-of-verdicts")
            order = column_order(headings)
            group = next(table.findall(nodes.tgroup))
            specs = [c for c in group.children if isinstance(c, nodes.colspec)]
            rows = list(group.findall(nodes.row))
            if any(len(row.children) != len(headings) for row in rows):
                continue              # a spanned cell: left as it is
            for row in rows:         # a verdict or a finding breaks at its hyphens only
                for k in (headings.index(name) for name in FIRST if name in headings):
                    row.children[k]["classes"].append("whole-words")
            if order == sorted(order):
                continue
            for parent, children in [(group, specs)] + [(row, list(row.children)) for row in rows]:
                first = parent.index(children[0])
                for child in children:
                    parent.remove(child)
                for k, position in enumerate(order):
                    parent.insert(first + k, children[position])
        for cell in self.document.findall(nodes.container):
            role = (cell.get("cell_metadata") or {}).get("mechnum", {}).get("role")
            if cell.get("nb_element") == "cell_code" and role == "check":
                cell["classes"].append("exercise-check")


def setup(app):
    app.connect("config-inited", lambda app, config: config.html_static_path.append(str(STATIC)))
    app.add_css_file("web_layout.css")
    app.add_js_file("web_layout.js", loading_method="defer")
    app.add_post_transform(VerdictsFirst)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
