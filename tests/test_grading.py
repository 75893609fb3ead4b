"""``make grade``: every check over a folder of student notebooks, each run in a fresh kernel with
a time limit; a notebook that raises, loops or hangs is recorded and never stops the run.

Four fabricated submissions: all right; one wrong answer; a cell that raises, a function that
loops and a top-level loop that the kernel's interrupt stops; a notebook that hangs past its
limit (a loop that ignores the kernel's interrupt)."""

import csv

import nbformat
import pytest

from mechnum import exercises
from mechnum.exercises import grading

WRONG_RK4 = "def rk4_step(f, s, y, h):\n    return y + h * f(s, y)  # Euler, not RK4"
LOOPING = "def loop_equations(q, theta2, r1y, r2, r3):\n    while True:\n        pass"


def submission(path, *cells):
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    nbformat.write(notebook, path)


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    folder = tmp_path_factory.mktemp("submissions")
    right = (exercises.solution("1.1"), exercises.solution("3.1"))
    submission(folder / "ana.ipynb", "import numpy as np", *right,
               'exercises = __import__("mechnum.exercises").exercises', 'print("done")')
    submission(folder / "ben.ipynb", "import numpy as np", right[0], WRONG_RK4)
    submission(folder / "carl.ipynb", "import numpy as np", "1 / 0", LOOPING, right[1],
               "while True:\n    pass")
    submission(folder / "dina.ipynb", "import numpy as np", right[1],
               "import signal\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\n"
               "while True:\n    pass")
    summary = grading.grade(folder, folder / "out", limit=20.0, cell_limit=4.0)
    with open(folder / "out" / "grades.csv", encoding="utf-8") as file:
        rows = {row["notebook"]: row for row in csv.DictReader(file)}
    with open(folder / "out" / "feedback.csv", encoding="utf-8") as file:
        feedback = {(r["notebook"], r["exercise"]): r for r in csv.DictReader(file)}
    return summary, rows, feedback


def test_one_row_per_notebook_one_column_per_exercise(graded):
    summary, rows, _ = graded
    assert sorted(rows) == ["ana.ipynb", "ben.ipynb", "carl.ipynb", "dina.ipynb"]
    assert list(rows["ana.ipynb"]) == ["notebook", "status", "1.1", "3.1", "note"]
    assert summary.startswith("4 notebooks: 2 ran, 1 with errors, 1 timed out\n")
    assert "exercise 1.1: 2 pass, 1 fail, 1 missing" in summary


def test_right_wrong_missing(graded):
    _, rows, feedback = graded
    assert rows["ana.ipynb"]["status"] == rows["ben.ipynb"]["status"] == "ok"
    assert (rows["ana.ipynb"]["1.1"], rows["ana.ipynb"]["3.1"]) == ("pass", "pass")
    assert (rows["ben.ipynb"]["1.1"], rows["ben.ipynb"]["3.1"]) == ("pass", "fail")
    assert "Exercise 3.1: not yet" in feedback["ben.ipynb", "3.1"]["message"]
    assert rows["dina.ipynb"]["1.1"] == "missing"


def test_a_notebook_that_raises_and_loops_is_graded_anyway(graded):
    _, rows, feedback = graded
    carl = rows["carl.ipynb"]
    assert carl["status"] == "errors" and "1, 4" in carl["note"]  # 1 / 0, the top-level loop
    assert (carl["1.1"], carl["3.1"]) == ("fail", "pass")
    assert "endless loop" in feedback["carl.ipynb", "1.1"]["message"]


def test_a_notebook_that_hangs_is_stopped_and_recorded(graded):
    _, rows, _ = graded
    assert rows["dina.ipynb"]["status"] == "timeout" and rows["dina.ipynb"]["3.1"] == "fail"


def test_bad_input(tmp_path):
    with pytest.raises(ValueError, match="no notebook"):
        grading.grade(tmp_path)
    submission(tmp_path / "a.ipynb", "x = 1")
    with pytest.raises(ValueError, match="positive"):
        grading.grade(tmp_path, limit=0)
