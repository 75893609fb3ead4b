"""The student edition (``make book-student``) is the book without the solutions: every exercise
and every starter is still there, no solution is, in the pages, in every ``.ipynb`` they offer
and in the served zip.

The machinery (:mod:`mechnum_course.student`) is tested on a small fixture chapter
(``tests/fixtures/exercise_chapter.ipynb``: two implement-it-yourself exercises, a prose solution
and a computed one) and on the real chapters. The built books are compared when both are given,
``MECHNUM_BUILT_HTML`` (the book) and ``MECHNUM_STUDENT_HTML`` (the student edition), as
``make html-check`` does.
"""

import json
import os
import re
import zipfile
from html.parser import HTMLParser
from pathlib import Path

import pytest

from mechnum import exercises
from mechnum_course.student import strip_markdown, student_notebook

ROOT = Path(__file__).resolve().parents[1]
FIXTURE = ROOT / "tests" / "fixtures" / "exercise_chapter.ipynb"
CHAPTERS = sorted((ROOT / "book").glob("*.ipynb"))
BUILT, STUDENT = os.environ.get("MECHNUM_BUILT_HTML"), os.environ.get("MECHNUM_STUDENT_HTML")
built = pytest.mark.skipif(not (BUILT and STUDENT), reason="both builds are needed")
LABEL = re.compile(r"```\{exercise\}[^\n]*\n:label: ([\w-]+)")


def text(cell):
    return cell["source"] if isinstance(cell["source"], str) else "".join(cell["source"])


def role(cell):
    return cell.get("metadata", {}).get("mechnum", {}).get("role")


def solution_code(notebook):
    """The code cells of the full notebook's gated solutions, found cell by cell (an oracle
    independent of the fence parser: a gated solution opens and closes in Markdown cells)."""
    found, inside = [], False
    for cell in notebook["cells"]:
        if cell["cell_type"] == "markdown":
            source = text(cell)
            if "{solution-start}" in source:
                inside = True
            if "{solution-end}" in source:
                inside = False
        elif inside or role(cell) == "solution":
            found.append(text(cell))
    return found


def shown(cell):
    """What a code cell displays, as text."""
    return "".join(text({"source": o.get("data", {}).get("text/plain", o.get("text", ""))})
                   for o in cell["outputs"])


def assert_student_edition(full, student, name):
    """Every exercise and starter of ``full`` is in ``student``, and no solution."""
    joined = "\n".join(text(c) for c in student["cells"])
    assert "{solution" not in joined, f"{name}: a solution directive is left"
    full_joined = "\n".join(text(c) for c in full["cells"])
    assert LABEL.findall(joined) == LABEL.findall(full_joined), f"{name}: exercises differ"
    starters = [text(c) for c in full["cells"] if role(c) == "starter"]
    assert starters == [text(c) for c in student["cells"] if role(c) == "starter"]
    student_code = [text(c) for c in student["cells"] if c["cell_type"] == "code"]
    for code in solution_code(full):
        if code.strip():
            assert code not in student_code, f"{name}: solution code {code[:60]!r} is left"
    for cell in student["cells"]:
        if role(cell) == "check":
            number = cell["metadata"]["mechnum"]["exercise"]
            assert shown(cell).startswith(f"Exercise {number}: not yet."), shown(cell)


def test_the_fixture_chapter():
    full = json.loads(FIXTURE.read_text(encoding="utf-8"))
    student = student_notebook(full)
    assert_student_edition(full, student, FIXTURE.name)
    joined = "\n".join(text(c) for c in student["cells"])
    for secret in ("secret prose answer", "secret_product", "secret_power", "gated prose",
                   "closing words", "r1, theta1, theta3 = q", "def down(v)"):
        assert secret not in joined, secret
    for kept in ("Text after the prose solution stays.", "Text after the gated solution stays.",
                 "What is six times seven?", "Compute two to the tenth."):
        assert kept in joined, kept
    full_checks = [c for c in full["cells"] if role(c) == "check"]
    assert len(full_checks) == 2 and all("passed" in shown(c) for c in full_checks)
    for cell in (c for c in student["cells"] if role(c) == "check"):
        number = cell["metadata"]["mechnum"]["exercise"]
        namespace = {}
        exec(exercises.starter(number), {}, namespace)
        expected = exercises.check(number, namespace[exercises.EXERCISES[number].name])
        assert shown(cell) == expected.message
    assert json.loads(json.dumps(student)) == student  # still a notebook (JSON)


def test_a_broken_gate_is_an_error():
    cells = [{"cell_type": "markdown", "metadata": {}, "source": "```{solution-start} x\n```"}]
    with pytest.raises(ValueError, match="without its"):
        student_notebook({"cells": cells})
    with pytest.raises(ValueError, match="unclosed fence"):
        strip_markdown("````{solution} x\nsecret\n")


@pytest.mark.parametrize("path", CHAPTERS, ids=[p.stem for p in CHAPTERS])
def test_the_chapters(path):
    full = json.loads(path.read_text(encoding="utf-8"))
    assert_student_edition(full, student_notebook(full), path.name)


def test_the_pages_have_no_solution():
    for path in (ROOT / "book").glob("*.md"):
        page = path.read_text(encoding="utf-8")
        assert strip_markdown(page) == page or "{solution" in page


class Blocks(HTMLParser):
    """The ids of the exercises and the text of the solutions of a page."""

    def __init__(self):
        super().__init__()
        self.exercises, self.solutions, self.links, self._depth = [], [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        classes = (attrs.get("class") or "").split()
        if tag == "a" and (attrs.get("href") or "").split("#")[0].endswith(".ipynb"):
            self.links.append(attrs["href"])
        if tag == "div" and "exercise" in classes:
            self.exercises.append(attrs.get("id"))
        if self._depth:
            self._depth[-1] += tag == "div"
        if tag == "div" and "solution" in classes:
            self.solutions.append("")
            self._depth.append(1)

    def handle_endtag(self, tag):
        if self._depth and tag == "div":
            self._depth[-1] -= 1
            if not self._depth[-1]:
                self._depth.pop()

    def handle_data(self, data):
        if self._depth:
            self.solutions[-1] += data


def blocks(root, name):
    parser = Blocks()
    parser.feed((Path(root) / "book" / name).read_text(encoding="utf-8"))
    return parser


def pages():
    return sorted(p.name for p in (Path(BUILT) / "book").glob("[0-9]*.html")) if BUILT else []


@built
def test_the_book_has_solutions_to_hide():
    assert sum(len(blocks(BUILT, name).solutions) for name in pages()) >= 15


@built
@pytest.mark.parametrize("name", pages())
def test_every_exercise_and_no_solution_in_the_html(name):
    book, student = blocks(BUILT, name), blocks(STUDENT, name)
    assert student.exercises == book.exercises
    assert book.exercises or name.endswith("_study.html"), f"{name}: a lecture without exercises"
    assert not student.solutions
    html = (Path(STUDENT) / "book" / name).read_text(encoding="utf-8")
    for solution in book.solutions:
        words = " ".join(solution.split()[3:15])  # a stretch of the solution's own prose
        assert words not in html, f"{name}: solution text {words!r} in the student edition"


@built
@pytest.mark.parametrize("name", pages())
def test_every_notebook_a_page_offers_is_the_student_edition(name):
    links = blocks(STUDENT, name).links
    assert links, f"{name} offers no .ipynb download"
    full = json.loads((ROOT / "book" / name.replace(".html", ".ipynb")).read_text("utf-8"))
    for link in links:
        path = (Path(STUDENT) / "book" / link.split("#")[0]).resolve()
        assert_student_edition(full, json.loads(path.read_text(encoding="utf-8")), str(path))


@built
def test_the_served_zip_is_the_student_edition():
    page = (Path(STUDENT) / "book" / "run_yourself.html").read_text(encoding="utf-8")
    served = [link for link in re.findall(r'href="(\.\./_downloads/[^"]+)"', page)
              if link.endswith("/mechnum-chapters.zip")]
    assert served, "the student edition serves no zip"
    with zipfile.ZipFile(Path(STUDENT) / "book" / served[0]) as z:
        names = set(z.namelist())
        assert "references.bib" in names
        for path in CHAPTERS:
            assert path.name in names
            full = json.loads(path.read_text(encoding="utf-8"))
            assert_student_edition(full, json.loads(z.read(path.name)), f"zip/{path.name}")
