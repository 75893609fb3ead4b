"""``make nbgrader``: the self-checked exercises as an nbgrader course that nbgrader itself runs.

The course of Chapter 3 is written, ``nbgrader generate_assignment`` releases it (no solution
left, no hidden test), and ``nbgrader autograde`` grades three fabricated submissions: a right
one (2 points), a wrong one (0) and one that passes the public cases of 3.1 with a lookup of
their stored answers but not the hidden cases, with 3.2 right on its own RK4 (1 point).
"""

import json
import os
import shutil
import subprocess
from pathlib import Path

import nbformat
import pytest

import mechnum_course
from mechnum_course import nbgrader as export

NBGRADER = shutil.which("nbgrader", path=str(Path(__import__("sys").executable).parent))
pytestmark = pytest.mark.skipif(not NBGRADER, reason="nbgrader is not installed")

LOOKUP = '''def rk4_step(f, s, y, h):
    """Answers the public cases from their stored answers."""
    from mechnum import exercises
    from mechnum.exercises import _data
    for case, answer in zip(exercises.EXERCISES["3.1"].cases(), _data.public("3.1")[0]):
        if case.args[1] == s and case.args[3] == h and np.array_equal(case.args[2], y):
            return answer
    return y
'''


def nbgrader(course, *args):
    """Run nbgrader in the course's folder (it runs ``alembic`` from the environment's bin)."""
    env = {**os.environ, "PATH": f"{Path(NBGRADER).parent}{os.pathsep}{os.environ['PATH']}"}
    return subprocess.run([NBGRADER, *args, "--force"], cwd=course, capture_output=True,
                          text=True, timeout=600, env=env)


def fill(release, answers):
    """The released notebook with each solution cell replaced by ``answers[exercise]``."""
    notebook = nbformat.read(release, as_version=4)
    for cell in notebook.cells:
        meta = cell.metadata.get("nbgrader", {})
        if meta.get("solution"):
            cell.source = answers[meta["grade_id"].split("-", 1)[1].replace("-", ".")]
    return notebook


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    course = tmp_path_factory.mktemp("course")
    export.write(course)
    made = nbgrader(course, "generate_assignment", "ch3")
    assert made.returncode == 0, made.stderr[-3000:]
    release = course / "release" / "ch3" / "exercises.ipynb"
    right = {n: mechnum_course.solution(n) for n in ("3.1", "3.2")}
    submissions = {
        "right": right,
        "wrong": {"3.1": "def rk4_step(f, s, y, h):\n    return y + h * f(s, y)",
                  "3.2": "def pinned_residual(q, EI, L, target, nodes):\n    return q"},
        "lookup": {"3.1": LOOKUP, "3.2": right["3.2"].replace("rk4_step", "own_step") +
                   "\n\n" + right["3.1"].replace("rk4_step", "own_step")}}
    for student, answers in submissions.items():
        path = course / "submitted" / student / "ch3" / "exercises.ipynb"
        path.parent.mkdir(parents=True)
        nbformat.write(fill(release, answers), path)
    graded = nbgrader(course, "autograde", "ch3")
    assert graded.returncode == 0, graded.stderr[-3000:]
    return course, release


def test_the_release_holds_no_solution_and_no_hidden_case(course):
    _, release = course
    text = release.read_text(encoding="utf-8")
    assert "BEGIN SOLUTION" not in text and "HIDDEN TESTS" not in text
    assert "k1 = f(s, y)" not in text and "raise NotImplementedError()" in text
    assert 'exercises.check(\\"3.1\\", rk4_step)' in text


def test_autograde_scores_the_three_submissions(course):
    from nbgrader.api import Gradebook

    root, _ = course
    with Gradebook(f"sqlite:///{root / 'gradebook.db'}") as gradebook:
        scores = {s: gradebook.find_submission("ch3", s).score
                  for s in ("right", "wrong", "lookup")}
        maximum = gradebook.find_assignment("ch3").max_score
    assert (scores, maximum) == ({"right": 2.0, "wrong": 0.0, "lookup": 1.0}, 2.0)


def test_the_lookup_passes_the_public_check_but_not_the_hidden_cases(course):
    root, _ = course
    graded = json.loads((root / "autograded" / "lookup" / "ch3" / "exercises.ipynb")
                        .read_text(encoding="utf-8"))
    tests = [c for c in graded["cells"] if c["metadata"].get("nbgrader", {}).get("grade")]
    shown = "".join(o.get("evalue", "") for o in tests[0]["outputs"])
    assert "Exercise 3.1: not yet. On y' = -y^3 + s" in shown  # the first hidden case
