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


# No solution in what a student can download: the wheel, the zip, the pages, the search index.
def solution_lines(number):
    """The lines of the reference solution below its starter (its body), stripped."""
    import mechnum_course

    starter = exercises.starter(number).rstrip()[:-3]
    body = mechnum_course.solution(number)[len(starter):]
    return [line.strip() for line in body.splitlines() if len(line.strip()) > 12]


def holds_solution(text, number, run=3):
    """Whether ``text`` holds ``run`` consecutive lines of the solution of ``number``."""
    lines = solution_lines(number)
    flat = "\n".join(line.strip() for line in text.splitlines())
    return any("\n".join(lines[k:k + run]) in flat for k in range(len(lines) - run + 1))


def test_the_solution_text_detector_finds_a_solution():
    import mechnum_course

    for number in exercises.EXERCISES:
        assert len(solution_lines(number)) >= 3, number
        assert holds_solution(mechnum_course.solution(number), number)
        assert not holds_solution(exercises.starter(number), number)


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """The served wheel (the student edition's, when it is built), else one built here by
    the same command as ``make downloads``."""
    import subprocess
    import sys

    if STUDENT:
        page = (Path(STUDENT) / "book" / "run_yourself.html").read_text(encoding="utf-8")
        links = [link for link in re.findall(r'href="(\.\./_downloads/[^"]+)"', page)
                 if link.endswith(".whl")]
        assert links, "the student edition serves no wheel"
        return (Path(STUDENT) / "book" / links[0]).resolve()
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps",
                    "--disable-pip-version-check", "--wheel-dir", str(out), str(ROOT / "pkg")],
                   check=True)
    return next(out.glob("mechnum-*.whl"))


def test_the_wheel_is_the_package_and_holds_no_instructors_file(wheel):
    """The served wheel holds exactly this repository's ``pkg/mechnum`` (so the functions
    tested below are the wheel's), and nothing of the instructors' package."""
    package = ROOT / "pkg"
    with zipfile.ZipFile(wheel) as w:
        names = [n for n in w.namelist() if not n.split("/")[0].endswith(".dist-info")]
        assert not [n for n in w.namelist() if "mechnum_course" in n or "hidden" in n]
        for name in names:
            assert w.read(name) == (package / name).read_bytes(), name
        for number in exercises.EXERCISES:
            for name in names:
                if name.endswith(".py"):
                    text = w.read(name).decode("utf-8")
                    assert not holds_solution(text, number), (name, number)
    shipped = {str(p.relative_to(package)) for p in (package / "mechnum").rglob("*")
               if p.is_file() and "__pycache__" not in p.parts}
    assert shipped == set(names)


def _candidates():
    """Every function of the package (module level, and classes' static and class methods),
    with the dotted name it is reached by."""
    import importlib
    import inspect
    import pkgutil

    import mechnum

    found = {}
    for info in pkgutil.walk_packages(mechnum.__path__, "mechnum."):
        if info.name == "mechnum.exercises._child":  # forks and writes to file descriptors
            continue
        try:
            module = importlib.import_module(info.name)
        except Exception:  # an optional dependency missing: nothing of it is served working
            continue
        for name, value in vars(module).items():
            targets = [(name, value)]
            if inspect.isclass(value) and value.__module__ == module.__name__:
                targets += [(f"{name}.{k}", getattr(value, k)) for k, v in vars(value).items()
                            if isinstance(v, (staticmethod, classmethod))]
            for label, function in targets:
                if inspect.isfunction(function) or inspect.ismethod(function):
                    found.setdefault(id(function), (f"{module.__name__}.{label}", function))
    return list(found.values())


def _takes(function, count):
    import inspect

    try:
        parameters = inspect.signature(function).parameters.values()
    except (TypeError, ValueError):
        return False
    positional = [p for p in parameters if p.kind in (p.POSITIONAL_ONLY,
                                                       p.POSITIONAL_OR_KEYWORD)]
    required = [p for p in positional if p.default is p.empty]
    varargs = any(p.kind == p.VAR_POSITIONAL for p in parameters)
    return len(required) <= count and (len(positional) >= count or varargs)


@built
def test_no_function_of_the_wheel_passes_a_check_but_the_packages_own_methods(wheel):
    """Every function the served wheel holds (about 2,300 pairs of a function and a check of
    its arity, two minutes) is run through the check with the public and the hidden cases:
    none passes, but the package's own methods that two exercises ask a student to write
    (``linear.sweep_by_components``, ``polynomials.companion``), which the grader fails as a
    delegation (``mechnum_course.SOLUTIONS[n].forbidden``)."""
    import warnings

    import numpy as np

    import mechnum_course

    passing, tried = [], 0
    for number, exercise in exercises.EXERCISES.items():
        forbidden = mechnum_course.SOLUTIONS[number].forbidden
        for dotted, function in _candidates():
            if not _takes(function, len(exercise.parameters)):
                continue
            tried += 1
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                if mechnum_course.check(number, function).passed:
                    passing.append((number, dotted))
                    assert any(dotted.endswith(f.rpartition(".")[2]) and
                               f.split(".")[1] in dotted for f in forbidden), (number, dotted)
    assert tried > 1000
    assert {n for n, _ in passing} == {"2.1", "4.1"}, passing  # the test can see a pass


@built
def test_no_solution_in_the_student_pages_zip_and_search_index():
    """No page, notebook of the zip or term of the search index of the student edition holds a
    solution: no three consecutive lines of a reference solution's body anywhere, and none of
    the words that only the full edition's solutions use in its search index."""
    texts = {p: p.read_text(encoding="utf-8", errors="replace")
             for p in Path(STUDENT).rglob("*") if p.suffix in (".html", ".ipynb", ".js", ".txt")
             and p.is_file()}
    page = (Path(STUDENT) / "book" / "run_yourself.html").read_text(encoding="utf-8")
    for link in re.findall(r'href="(\.\./_downloads/[^"]+\.zip)"', page):
        with zipfile.ZipFile(Path(STUDENT) / "book" / link) as z:
            texts.update({f"zip/{n}": z.read(n).decode("utf-8", "replace")
                          for n in z.namelist()})
    for number in exercises.EXERCISES:
        for where, text in texts.items():
            assert not holds_solution(text, number), (number, where)

    def terms(root):
        text = (Path(root) / "searchindex.js").read_text(encoding="utf-8")
        return set(json.loads(text[text.index("(") + 1:text.rindex(")")])["terms"])

    from sphinx.search.en import SearchEnglish
    stem = SearchEnglish({}).stem
    words = set()
    for name in pages():
        for solution in blocks(BUILT, name).solutions:
            words |= {stem(w.lower()) for w in re.findall(r"[A-Za-z]{7,}", solution)}
    shown = set()
    for path in (Path(STUDENT) / "book").glob("*.html"):
        html = re.sub(r"<[^>]+>", " ", path.read_text(encoding="utf-8"))
        shown |= {stem(w.lower()) for w in re.findall(r"[A-Za-z]{7,}", html)}
    only_in_solutions = (words - shown) & terms(BUILT)
    assert only_in_solutions, "the full edition's index holds no solution word to look for"
    assert not only_in_solutions & terms(STUDENT), sorted(only_in_solutions & terms(STUDENT))
