"""The student edition (``make book-student``) is the book without the solutions: every
exercise is still there, no solution is.

Compares the two builds: ``MECHNUM_BUILT_HTML`` (the book) and ``MECHNUM_STUDENT_HTML`` (the
student edition); skipped unless both are set, as ``make html-check`` does.
"""

import os
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

BUILT, STUDENT = os.environ.get("MECHNUM_BUILT_HTML"), os.environ.get("MECHNUM_STUDENT_HTML")
pytestmark = pytest.mark.skipif(not (BUILT and STUDENT), reason="both builds are needed")


class Blocks(HTMLParser):
    """The ids of the exercises and the text of the solutions of a page."""

    def __init__(self):
        super().__init__()
        self.exercises, self.solutions, self._depth = [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        classes = (attrs.get("class") or "").split()
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


def chapters():
    return sorted(p.name for p in (Path(BUILT) / "book").glob("[0-9]*.html")) if BUILT else []


def test_the_book_has_solutions_to_hide():
    assert sum(len(blocks(BUILT, name).solutions) for name in chapters()) >= 15


@pytest.mark.parametrize("name", chapters())
def test_every_exercise_and_no_solution(name):
    book, student = blocks(BUILT, name), blocks(STUDENT, name)
    assert student.exercises == book.exercises and book.exercises
    assert not student.solutions
    text = (Path(STUDENT) / "book" / name).read_text(encoding="utf-8")
    for solution in book.solutions:
        words = " ".join(solution.split()[3:15])  # a stretch of the solution's own prose
        assert words not in text, f"{name}: solution text {words!r} in the student edition"
