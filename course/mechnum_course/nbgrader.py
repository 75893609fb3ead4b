"""The self-checked exercises as an nbgrader course (``make nbgrader``).

One assignment per chapter, ``chN``, whose source notebook ``source/chN/exercises.ipynb``
holds, for each self-checked exercise of the chapter: its statement (a read-only cell), its
solution cell (the starter with the reference's body between nbgrader's ``### BEGIN
SOLUTION`` and ``### END SOLUTION``, which ``nbgrader generate_assignment`` replaces by
``raise NotImplementedError()``) and an autograded test cell worth the exercise's points: the
public check, and between ``### BEGIN HIDDEN TESTS`` and ``### END HIDDEN TESTS`` the hidden
cases (their inputs' code) with the references' answers, which the released notebook does not
show. Written beside them: ``nbgrader_config.py`` (the course's folder and gradebook).

nbgrader runs the tests in the student's own kernel: its grades have nbgrader's trust model,
not ``make grade``'s.

Command line: ``python -m mechnum_course.nbgrader FOLDER``.
"""

import ast
import inspect
import json
import sys
from pathlib import Path

import nbformat

from mechnum import exercises
from mechnum.exercises import _data
from mechnum_course import HIDDEN, answers, hidden, solution


def _cell(kind, source, grade_id, *, grade=False, solution=False, locked=False, points=0):
    make = nbformat.v4.new_markdown_cell if kind == "markdown" else nbformat.v4.new_code_cell
    cell = make(source)
    cell.metadata["nbgrader"] = {"grade": grade, "solution": solution, "locked": locked,
                                 "grade_id": grade_id, "schema_version": 3,
                                 **({"points": points} if grade else {})}
    return cell


def _solution_cell(number):
    """The starter with the reference's body between the solution markers."""
    head = exercises.starter(number).rstrip()[:-3].rstrip()
    body = solution(number)[len(head):].strip("\n")
    indent = " " * (len(body) - len(body.lstrip(" ")))
    return (f"{head}\n{indent}### BEGIN SOLUTION\n{body}\n{indent}### END SOLUTION")


def _hidden_header():
    """The import lines of :mod:`mechnum_course.hidden` (what its case builders use)."""
    text = inspect.getsource(hidden)
    return "\n".join(ast.get_source_segment(text, node) for node in ast.parse(text).body
                     if isinstance(node, (ast.Import, ast.ImportFrom)))


def test_code(number):
    """The autograded test cell of exercise ``number``: the public check, then the hidden
    cases and their expected answers."""
    exercise = exercises.EXERCISES[number]
    builder = HIDDEN[number]
    expected, _ = answers(number, builder())
    stored = json.dumps([_data.encode(v) for v in expected])
    return "\n".join([
        f'result = exercises.check("{number}", {exercise.name})',
        "assert result.passed, result.message",
        "### BEGIN HIDDEN TESTS",
        _hidden_header(),
        "from mechnum.exercises._data import decode",
        inspect.getsource(builder).rstrip(),
        f"expected = [decode(v) for v in __import__('json').loads({stored!r})]",
        f'result = exercises.check_cases("{number}", {exercise.name}, {builder.__name__}(), '
        "expected)",
        "assert result.passed, result.message",
        "### END HIDDEN TESTS"])


def assignment(chapter):
    """The source notebook of chapter ``chapter``'s assignment."""
    numbers = [n for n in exercises.EXERCISES if n.split(".")[0] == str(chapter)]
    cells = [_cell("markdown", f"# Chapter {chapter}: the exercises that check themselves\n\n"
                   "Write each function, run its cell, then its check.", f"ch{chapter}-intro",
                   locked=True),
             _cell("code", "import numpy as np\n\nfrom mechnum import exercises",
                   f"ch{chapter}-imports", locked=True)]
    for number in numbers:
        exercise = exercises.EXERCISES[number]
        stem = number.replace(".", "-")
        cells += [_cell("markdown", f"## Exercise {number}: {exercise.title}\n\n"
                        f"{exercise.statement}", f"statement-{stem}", locked=True),
                  _cell("code", _solution_cell(number), f"solution-{stem}", solution=True),
                  _cell("code", test_code(number), f"test-{stem}", grade=True, locked=True,
                        points=exercise.points)]
    notebook = nbformat.v4.new_notebook(cells=cells)
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                       "language": "python"}
    return notebook


def write(folder):
    """Write the course into ``folder``; the chapters written."""
    folder = Path(folder)
    chapters = sorted({int(n.split(".")[0]) for n in exercises.EXERCISES})
    for chapter in chapters:
        path = folder / "source" / f"ch{chapter}" / "exercises.ipynb"
        path.parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(assignment(chapter), path)
    (folder / "nbgrader_config.py").write_text(
        "c = get_config()  # noqa: F821\n"
        "c.CourseDirectory.course_id = 'mechnum'\n"
        f"c.CourseDirectory.root = {str(folder.resolve())!r}\n"
        f"c.CourseDirectory.db_url = 'sqlite:///{(folder / 'gradebook.db').resolve()}'\n"
        "c.Execute.timeout = 120\n", encoding="utf-8")
    return chapters


if __name__ == "__main__":
    written = write(sys.argv[1])
    print(f"nbgrader course in {sys.argv[1]}: assignments ch{', ch'.join(map(str, written))}")
