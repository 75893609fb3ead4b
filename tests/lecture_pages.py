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


# Markdown: a fence opens a code block (```python), a directive (```{exercise}, :::{admonition})
# or, inside a directive, its options (:label: x); $$ and \begin{...} open display maths
FENCE = re.compile(r"^\s*(`{3,}|~{3,}|:{3,})\s*(?:\{([\w:-]+)\})?\s*(.*)$")
NOT_PROSE = {"code", "code-block", "code-cell", "sourcecode", "math", "raw", "literalinclude",
             "bibliography", "eval-rst"}
NOT_CODE = {"math", "raw", "bibliography", "eval-rst"}
OPTION = re.compile(r"^\s*:[\w-]+:")
SKIPPED_LINE = re.compile(r"^\s*(\([\w-]+\)=|%|\+\+\+)")  # a target, a comment, a cell break
INLINE = [(re.compile(r"\{[\w:-]+\}(`+).*?\1"), " reference "),     # a role: one word
          (re.compile(r"(`+).+?\1"), " "),                            # inline code
          (re.compile(r"\$\$.+?\$\$|(?<![\\$])\$(?=\S)[^$]*?(?<=\S)\$"), " "),  # inline maths
          (re.compile(r"!\[[^\]]*\]\([^)]*\)"), " "),                 # an image
          (re.compile(r"\[([^\]]*)\]\([^)]*\)"), r"\1"),              # a link: its text
          (re.compile(r"<[^>]*>"), " ")]                              # HTML, autolinks


def read_markdown(source):
    """``(words, code lines)`` of a Markdown cell: the words of its prose, and the lines of the
    code blocks it shows (see CONTRIBUTING.md, "The lecture's budget")."""
    source = re.sub(r"<!--.*?-->", " ", source, flags=re.DOTALL)
    words, code, blocks, maths, options = 0, [], [], None, False
    for line in source.splitlines():
        fence = FENCE.match(line)
        if blocks and fence and not fence[2] and not fence[3] \
                and fence[1][0] == blocks[-1][0][0] and len(fence[1]) >= len(blocks[-1][0]):
            blocks.pop()
            continue
        inside = blocks[-1] if blocks else (None, "prose")
        if inside[1] in ("code", "hidden"):
            code += [line] if inside[1] == "code" else []
            continue
        if fence:
            name = fence[2]
            kind = "prose" if name and name not in NOT_PROSE else \
                "hidden" if name in NOT_CODE else "code"
            blocks.append((fence[1], kind))
            options = bool(name)
            words += count_words(fence[3]) if kind == "prose" else 0  # a directive's title
            continue
        if options and (OPTION.match(line) or not line.strip()):
            continue
        options = False
        if maths:
            maths = None if maths in line else maths
        elif line.lstrip().startswith("$$"):
            maths = None if line.rstrip().endswith("$$") and len(line.strip()) > 2 else "$$"
        elif re.match(r"^\s*\\begin\{([\w*]+)\}", line):
            env = re.match(r"^\s*\\begin\{([\w*]+)\}", line)[1]
            maths = None if f"\\end{{{env}}}" in line else f"\\end{{{env}}}"
        elif not SKIPPED_LINE.match(line):
            words += count_words(line)
    return words, code


def count_words(text):
    """The words of a line of prose: what is left of it without inline code and maths, link
    targets and HTML, split at spaces, each piece holding a letter or a digit."""
    for pattern, replacement in INLINE:
        text = pattern.sub(replacement, text)
    return sum(bool(re.search(r"[^\W_]", token)) for token in text.split())


def budget(page):
    """``{"words", "code lines", "long lines"}`` of a page: words of prose, non-blank source
    lines of its code cells, and every line of code it shows longer than ``MAX_LINE``."""
    words, lines, shown = 0, 0, []
    for cell in notebook(page).cells:
        if cell.cell_type == "markdown":
            more, code = read_markdown(cell.source)
            words, shown = words + more, shown + code
        elif cell.cell_type == "code":
            source = cell.source.splitlines()
            lines, shown = lines + sum(bool(line.strip()) for line in source), shown + source
    return {"words": words, "code lines": lines,
            "long lines": [line for line in shown if len(line) > MAX_LINE]}
