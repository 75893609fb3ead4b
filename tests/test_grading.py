"""``make grade``: a folder of student notebooks graded outside the students' reach.

The fabricated class: a right submission; the cheats (one that replaces ``exercises.check``,
one whose ``pre_run_cell`` hook prints a grade, one that calls the instructors' reference, one
that calls the package's own solution, one that reads the hidden answers from the instructors'
files, one that rewrites another student's notebook and the package from a detached process);
a notebook that ignores SIGINT and SIGTERM in an endless loop; functions defined by a lambda,
an import and ``exec``; a closure, which cannot be graded; a non-JSON ``.ipynb``, a folder named
``x.ipynb`` and a notebook whose cell has no ``source``. The grader must pass the right one,
fail every cheat with its reason, stop the loop within its limit, write an ``invalid`` row for
every bad file, and return in bounded time with every row written.
"""

import csv
import json
import os
import time
from pathlib import Path

import nbformat
import pytest

import mechnum_course
from mechnum_course import grading
from mechnum_course.grading import _report, _sandbox

pytestmark = pytest.mark.skipif(not _sandbox.landlock_abi(),
                                reason="this Linux kernel has no Landlock")
RIGHT = mechnum_course.solution("3.1")
LIMIT, CELL = 40.0, 10.0


def submission(path, *cells):
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    nbformat.write(notebook, path)


CHEATS = {
    "patches_check": ("import numpy as np\nfrom mechnum import exercises\n"
                      "exercises.check = lambda n, f: exercises.Result(n, True, 'passed')",
                      "def rk4_step(f, s, y, h):\n    return y + h * f(s, y)",
                      'exercises.check("3.1", rk4_step)'),
    "hook": ("import numpy as np\nip = get_ipython()\n"
             "ip.events.register('pre_run_cell', lambda info: print("
             "'MECHNUM-SOURCES {\"rk4_step\": {\"source\": \"rk4_step = 1\"}}', "
             "'Exercise 3.1: passed'))",
             "def rk4_step(f, s, y, h):\n    return y"),
    "reference": ("from mechnum_course import reference",
                  "def rk4_step(f, s, y, h):\n    return reference('3.1')(f, s, y, h)"),
    "package": ("import numpy as np\nfrom mechnum import ode",
                "def rk4_step(f, s, y, h):\n    return ode.rk4(f, y, np.array([s, s + h]))[-1]"),
    "reads_files": ("import numpy as np",
                    "def rk4_step(f, s, y, h):\n"
                    f"    exec(open({mechnum_course.solutions._ch3.__file__!r}).read(), "
                    "globals())\n    return rk4_step(f, s, y, h)"),
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    folder = tmp_path_factory.mktemp("class")
    submission(folder / "right.ipynb", "import numpy as np\nfrom mechnum import exercises",
               RIGHT, mechnum_course.solution("3.2"), 'exercises.check("3.1", rk4_step)',
               "1 / 0")
    for name, cells in CHEATS.items():
        submission(folder / f"{name}.ipynb", *cells)
    submission(folder / "loop.ipynb", "import numpy as np", RIGHT,
               "import signal\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\n"
               "signal.signal(signal.SIGTERM, signal.SIG_IGN)\nwhile True:\n    pass")
    script = "\n".join([  # leaves its session, then strikes every second for a minute
        "import os, time", "os.fork() and os._exit(0)", "os.setsid()",
        f"# vandal-{os.getpid()}", "for _ in range(60):", "    time.sleep(1)",
        *(f"    try: open({str(target)!r}, 'w').write('gone')\n    except OSError: pass"
          for target in (folder / "right.ipynb", folder / "grading" / "grades.csv"))])
    submission(folder / "vandal.ipynb", "import numpy as np",
               f"import subprocess, sys\nsubprocess.Popen([sys.executable, '-c', {script!r}], "
               "start_new_session=True)",
               "import mechnum, pathlib\n"
               "p = pathlib.Path(mechnum.__file__).parent / 'exercises' / '_answers.py'\n"
               "p.write_text(p.read_text() + '\\n')",
               RIGHT)
    submission(folder / "slow.ipynb", "import numpy as np",
               "def rk4_step(f, s, y, h):\n    while True:\n"
               "        np.linalg.eigvals(np.ones((400, 400)))")
    submission(folder / "lambda.ipynb", "import numpy as np\n" + RIGHT.replace(
        "def rk4_step", "def my_step") + "\nrk4_step = lambda f, s, y, h: my_step(f, s, y, h)")
    submission(folder / "executed.ipynb", f"import numpy as np\nexec({RIGHT!r})")
    submission(folder / "closure.ipynb", "import numpy as np\ndef make(c):\n"
               "    def rk4_step(f, s, y, h):\n        return c * y\n    return rk4_step\n"
               "rk4_step = make(1.0)")
    (folder / "notjson.ipynb").write_text("this is not JSON", encoding="utf-8")
    (folder / "x.ipynb").mkdir()
    broken = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1")])
    del broken.cells[0]["source"]
    (folder / "nosource.ipynb").write_text(json.dumps(broken))
    imported = folder / "imported"
    imported.mkdir()
    (imported / "mine.py").write_text("import numpy as np\n\n\n" + RIGHT)
    submission(imported / "work.ipynb", "from mine import rk4_step")
    right_before = (folder / "right.ipynb").read_bytes()
    began = time.monotonic()
    summary = grading.grade(folder, limit=LIMIT, cell_limit=CELL)
    seconds = time.monotonic() - began
    time.sleep(4)  # the vandal's detached process would have struck by now
    with open(folder / "grading" / "grades.csv", encoding="utf-8") as file:
        rows = {row["student"]: row for row in csv.DictReader(file)}
    feedback = {p.stem: p.read_text(encoding="utf-8")
                for p in (folder / "grading" / "feedback").glob("*.md")}
    return summary, rows, feedback, seconds, folder, right_before


def test_every_row_is_written_in_bounded_time(graded):
    summary, rows, feedback, seconds, _, _ = graded
    expected = {"right", *CHEATS, "loop", "vandal", "slow", "lambda", "executed", "closure",
                "notjson", "x", "nosource", "imported"}
    assert set(rows) == expected == set(feedback)
    assert list(next(iter(rows.values())))[:6] == ["student", "status", "total", "maximum",
                                                    "3.1", "3.2"]
    assert list(next(iter(rows.values())))[-1] == "note"
    assert seconds < len(expected) * (LIMIT + 30), seconds
    assert "file-system sandbox: Landlock" in summary and "WARNING" not in summary


def test_the_right_submission_passes(graded):
    _, rows, feedback, _, _, _ = graded
    right = rows["right"]
    assert (right["3.1"], right["3.2"], right["total"], right["maximum"]) == ("1", "1", "2",
                                                                                "2")
    assert right["status"] == "errors"  # its last cell divides by zero: reported, not fatal
    assert "(3 of them hidden)" in feedback["right"]
    assert "Cell In [5] (code cell 5, cell 5 of the notebook) raised ZeroDivisionError" in \
        feedback["right"]


@pytest.mark.parametrize("name, reason", [
    ("patches_check", "Exercise 3.1: not yet. On the rod's equations"),
    ("hook", "Exercise 3.1: not yet"),
    ("reference", "calls the instructors' reference solution"),
    ("package", "calls `mechnum.ode.rk4`"),
    ("reads_files", "raised PermissionError")])
def test_every_cheat_fails_with_its_reason(graded, name, reason):
    _, rows, feedback, _, _, _ = graded
    assert rows[name]["3.1"] == "0" and rows[name]["total"] == "0"
    assert reason in feedback[name], feedback[name]


def test_the_endless_loop_is_stopped_and_its_function_graded(graded):
    _, rows, feedback, _, _, _ = graded
    assert rows["loop"]["status"] in ("errors", "timeout")
    assert rows["loop"]["3.1"] == "1"  # graded from the notebook's text
    assert "ignored the interrupt" in rows["loop"]["note"] or "longer than" in \
        rows["loop"]["note"]


def test_no_process_outlives_the_grading_and_nothing_was_overwritten(graded):
    _, rows, feedback, _, folder, right_before = graded
    assert (folder / "right.ipynb").read_bytes() == right_before
    assert (folder / "grading" / "grades.csv").read_text().startswith("student,")
    alive = []
    for entry in Path("/proc").iterdir():
        try:
            if f"vandal-{os.getpid()}" in (entry / "cmdline").read_text(errors="replace"):
                alive.append(entry.name)
        except OSError:
            continue
    assert not alive, f"the detached process survived the grading: {alive}"
    assert rows["vandal"]["3.1"] == "1"  # its function is still graded
    assert rows["vandal"]["status"] == "errors"
    assert "raised PermissionError" in feedback["vandal"] and "SyntaxError" not in \
        feedback["vandal"]  # the detached process started; writing the package was refused


def test_a_function_stuck_in_a_c_call_is_killed_at_its_time_limit(graded):
    _, rows, feedback, _, _, _ = graded
    assert rows["slow"]["3.1"] == "0" and rows["slow"]["status"] == "ok"
    assert "ran for more than 2 s and was stopped" in feedback["slow"]


def test_lambda_import_and_exec_are_graded_and_a_closure_is_not(graded):
    _, rows, feedback, _, _, _ = graded
    for name in ("lambda", "executed", "imported"):
        assert rows[name]["3.1"] == "1", feedback[name]
    assert rows["closure"]["3.1"] == "0"
    assert "not gradable" in feedback["closure"] and "define it" in feedback["closure"]


def test_bad_files_are_invalid_rows(graded):
    _, rows, _, _, _, _ = graded
    assert rows["notjson"]["status"] == "invalid" and "not JSON" in rows["notjson"]["note"]
    assert rows["x"]["status"] == "invalid" and "is a folder" in rows["x"]["note"]
    assert rows["nosource"]["status"] == "invalid" and "not a valid notebook" in \
        rows["nosource"]["note"]
    assert rows["x"]["total"] == "0" and rows["x"]["maximum"] == "2"


def test_the_rubric_covers_every_exercise_without_a_check():
    import re

    from mechnum import exercises
    checked = {e.label for e in exercises.EXERCISES.values()}
    labels = set()
    for path in Path(grading.BOOK).glob("0*.ipynb"):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] == "markdown":
                labels |= set(re.findall(r"\{exercise\}[^\n]*\n:label: ([\w-]+)",
                                         "".join(cell["source"])))
    rubric = _report.rubric()
    assert labels - checked == set(rubric), (labels - checked) ^ set(rubric)
    assert all(points > 0 and len(text) > 40 for points, text in rubric.values())


def test_bad_input(tmp_path):
    with pytest.raises(ValueError, match="no notebook"):
        grading.grade(tmp_path)
    submission(tmp_path / "a.ipynb", "x = 1")
    with pytest.raises(ValueError, match="positive"):
        grading.grade(tmp_path, limit=0)
    with pytest.raises(ValueError, match="no self-checked exercise 9.9"):
        grading.grade(tmp_path, numbers=["9.9"], limit=20, cell_limit=5)
    assert os.path.isdir(tmp_path)


def test_the_sandbox_reads_nothing_of_the_instructors_package():
    read = _sandbox.config("/nonexistent", cpu=1, memory=1, file_size=1)["read"]
    assert _sandbox.exposed(read) == []
    course = Path(mechnum_course.__file__).resolve().parents[1]
    assert _sandbox.exposed([*read, str(course.parent)]) == [str(course.parent)]
