"""The book's lecture pages, their study pages, and what a lecture's budget counts (issue 20).

A *lecture page* is a chapter entry of ``_toc.yml``, ``book/0N_<name>``; its *study page*,
``book/0N_<name>_study``, is nested under it with ``sections:``. CONTRIBUTING.md ("The lecture's
budget") states the limits and how words and lines are counted; this module counts them.
"""

import re
from pathlib import Path

import nbformat
import yaml

ROOT = Path(__file__).resolve().parents[1]

MAX_WORDS, MAX_CODE_LINES, MAX_LINE, MAX_SECONDS = 3000, 250, 76, 30.0
CHAPTER = re.compile(r"book/0\d_\w+")


def lectures():
    """``{lecture: [pages nested under it]}`` in the order of ``_toc.yml``, as ``book/<stem>``."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    return {entry["file"]: [section["file"] for section in entry.get("sections", [])]
            for part in toc["parts"] for entry in part.get("chapters", [])
            if CHAPTER.fullmatch(entry["file"])}


def chapter_pages():
    """Every lecture page and every page nested under one, as ``book/<stem>``."""
    return [page for lecture, nested in lectures().items() for page in [lecture, *nested]]


def notebook(page):
    return nbformat.read(ROOT / f"{page}.ipynb", as_version=4)


# Markdown: a fence opens a code block (```python) or a directive (```{exercise},
# :::{admonition}); only a code block's lines are code that the page shows
FENCE = re.compile(r"^\s*(`{3,}|~{3,}|:{3,})\s*(?:\{([\w:-]+)\})?\s*(.*)$")
SHOWN_CODE = {None, "code", "code-block", "code-cell", "sourcecode"}


def count_words(source):
    """Every word of a Markdown cell, its mathematics included: the pieces of its source
    between white space (a formula read aloud or worked on the board is part of the lecture,
    so ``$x_k^2 + 1$`` is three words; so is a directive's option line, a target or a
    comment: nothing is left out)."""
    return len(source.split())


def shown_code(source):
    """The lines of the code blocks that a Markdown cell shows (for the width of the column);
    a directive's body (an exercise, a ``{math}`` block) is not code."""
    code, blocks = [], []
    for line in source.splitlines():
        fence = FENCE.match(line)
        if blocks and fence and not fence[2] and not fence[3] \
                and fence[1][0] == blocks[-1][0][0] and len(fence[1]) >= len(blocks[-1][0]):
            blocks.pop()
        elif blocks and blocks[-1][1]:
            code.append(line)
        elif fence:
            blocks.append((fence[1], fence[1][0] != ":" and fence[2] in SHOWN_CODE))
    return code


def budget(page):
    """``{"words", "code lines", "long lines"}`` of a page: every word of its Markdown cells
    (mathematics included), the non-blank source lines of its code cells, and every line of code
    it shows longer than ``MAX_LINE``."""
    words, lines, shown = 0, 0, []
    for cell in notebook(page).cells:
        if cell.cell_type == "markdown":
            words, shown = words + count_words(cell.source), shown + shown_code(cell.source)
        elif cell.cell_type == "code":
            source = cell.source.splitlines()
            lines, shown = lines + sum(bool(line.strip()) for line in source), shown + source
    return {"words": words, "code lines": lines,
            "long lines": [line for line in shown if len(line) > MAX_LINE]}
