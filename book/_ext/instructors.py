"""The page for instructors: its plan of the term, read from the lectures themselves.

The directive ``{term-plan}`` prints a table with one row per lecture page of ``_toc.yml``'s
numbered part: its week, the lecture (a link to its page), its slides (``book/_ext/slides.py``;
in the PDF, their path in the web book) and its exercises, split into the ones that check
themselves (an implement-it-yourself exercise: its check cell, whose metadata says
``"mechnum": {"role": "check"}``, calls ``exercises.check("N.k", function)``, and ``make grade``
grades it) and the ones graded by hand against the answer key. The exercises are numbered as
the book numbers them, N.1, N.2, ... in the order of the chapter's ``{exercise}`` directives, and
each is a link to its statement; so the plan follows the lectures when they change.
"""

import json
import posixpath
import re
from pathlib import Path

import yaml
from docutils import nodes
from sphinx import addnodes
from sphinx.util.docutils import SphinxDirective

from slides import deck_uri

WEEKS_PER_LECTURE = 2
"""A lecture's week, then a week of work on its study page and exercises."""
EXERCISE = re.compile(r"^\s*(`{3,}|:{3,})\{exercise\}[^\n]*\n(?:\s*:[\w-]+:[^\n]*\n)*", re.M)
LABEL = re.compile(r":label:\s*([\w-]+)")
CHECK = re.compile(r"check\(\s*\"(\d+\.\d+)\"\s*,\s*(\w+)\s*\)")


def lecture_entries(srcdir):
    """The lecture pages of ``_toc.yml``'s numbered parts, as ``book/<stem>``, in order."""
    toc = yaml.safe_load((Path(srcdir) / "_toc.yml").read_text(encoding="utf-8"))
    return [entry["file"] for part in toc["parts"] if part.get("numbered")
            for entry in part["chapters"]]


def exercises(notebook, chapter):
    """A lecture notebook's exercises: ``[(number, label, function or None)]``, ``function``
    being the name its self-check checks (None: graded by hand)."""
    cells = json.loads(Path(notebook).read_text(encoding="utf-8"))["cells"]
    text = lambda cell: "".join(cell["source"])  # noqa: E731
    labels = []
    for cell in cells:
        if cell["cell_type"] == "markdown":
            for fence in EXERCISE.finditer(text(cell)):
                label = LABEL.search(fence.group(0))
                labels.append(label.group(1) if label else None)
    checked = {}
    for cell in cells:
        role = cell.get("metadata", {}).get("mechnum", {}).get("role")
        if cell["cell_type"] == "code" and role == "check":
            for number, function in CHECK.findall(text(cell)):
                checked[number] = function
    return [(f"{chapter}.{k}", label, checked.get(f"{chapter}.{k}"))
            for k, label in enumerate(labels, 1)]


def _title(notebook):
    for cell in json.loads(Path(notebook).read_text(encoding="utf-8"))["cells"]:
        heading = re.search(r"^# (.+)$", "".join(cell["source"]), re.M)
        if cell["cell_type"] == "markdown" and heading:
            return heading.group(1).strip()
    return Path(notebook).stem


def _cell(*children):
    return nodes.entry("", nodes.paragraph("", "", *children))


def _doc_link(docname, text):
    return addnodes.pending_xref("", nodes.inline("", text), refdomain="std", reftype="doc",
                                 reftarget="/" + docname, refexplicit=True)


def _exercise_links(found):
    children = []
    for number, label, function in found:
        if children:
            children.append(nodes.Text(", "))
        text = nodes.inline("", number)
        if label:
            text = addnodes.pending_xref("", text, refdomain="std", reftype="ref",
                                         reftarget=label, refexplicit=True)
        children.append(text)
        if function:
            children += [nodes.Text(" ("), nodes.literal("", function), nodes.Text(")")]
    return children or [nodes.Text("none")]


class TermPlan(SphinxDirective):
    """``{term-plan}``: the table of the term's lectures, their slides and exercises."""

    def run(self):
        heads = ["week", "lecture", "slides", "self-checked, graded by make grade",
                 "graded by hand (answer key)"]
        rows = []
        for chapter, docname in enumerate(lecture_entries(self.env.srcdir), 1):
            notebook = Path(self.env.srcdir) / f"{docname}.ipynb"
            self.env.note_dependency(str(notebook))
            found = exercises(notebook, chapter)
            deck = deck_from(self.env.docname, docname)
            slides = addnodes.only(expr="html")
            slides += nodes.paragraph("", "", nodes.reference("", "deck", refuri=deck))
            printed = addnodes.only(expr="latex")
            printed += nodes.paragraph("", "", nodes.literal(
                "", f"slides/{Path(docname).name}.html"))
            row = nodes.row("", _cell(nodes.Text(str(WEEKS_PER_LECTURE * chapter - 1))),
                            _cell(_doc_link(docname, f"{chapter}. {_title(notebook)}")),
                            nodes.entry("", slides, printed),
                            _cell(*_exercise_links([e for e in found if e[2]])),
                            _cell(*_exercise_links([e for e in found if not e[2]])))
            rows.append(row)
        group = nodes.tgroup(cols=len(heads))
        group += [nodes.colspec(colwidth=w) for w in (6, 30, 10, 28, 26)]
        group += nodes.thead("", nodes.row("", *[_cell(nodes.Text(h)) for h in heads]))
        group += nodes.tbody("", *rows)
        return [nodes.table("", group, classes=["term-plan"])]


def deck_from(page, docname):
    """The deck of lecture ``docname`` relative to the page ``page``."""
    target = posixpath.join(posixpath.dirname(docname), deck_uri(docname))
    return posixpath.relpath(posixpath.normpath(target), posixpath.dirname(page) or ".")


def setup(app):
    app.add_directive("term-plan", TermPlan)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
