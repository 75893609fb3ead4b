"""The grader against a determined student: what a submission holds beside its notebook
(a module named like the standard library's, symbolic links, FIFOs, devices), answers built to
hang the grader, writes to the grader's channel, a process count without bound, and names
built for a spreadsheet. Each test fails on the grader as it was before these were closed.
"""

import csv
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import nbformat
import pytest

import mechnum_course
from mechnum_course import grading
from mechnum_course.grading import _check, _sandbox

pytestmark = pytest.mark.skipif(not _sandbox.landlock_abi(),
                                reason="this Linux kernel has no Landlock")
RIGHT = mechnum_course.solution("3.1")
SHADOW = '''\
import os, sys
marker = {marker!r}
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "ran.txt"), "a") as f:
    f.write(os.environ.get("MECHNUM_SANDBOX", "unconfined") + "\\n")
try:
    open(marker, "w").write("ran unconfined")
except OSError:
    pass
here = os.path.dirname(os.path.abspath(__file__))
sys.path[:] = [p for p in sys.path if os.path.abspath(p or ".") != here]
del sys.modules[__name__]
import importlib
sys.modules[__name__] = importlib.import_module(__name__)
globals().update(vars(sys.modules[__name__]))
'''


def submission(path, *cells):
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    nbformat.write(notebook, path)


@pytest.fixture
def work():
    """A folder the unprivileged user a root grader becomes can reach (not pytest's)."""
    folder = Path(tempfile.mkdtemp(prefix="hostile-"))
    os.chmod(folder, 0o755)
    yield folder
    subprocess.run(["rm", "-rf", str(folder)], check=False)


def isolated(code, timeout=60):
    """Run ``code`` in a fresh Python with 2 GB of address space: its output, or "timeout"."""
    def limit():
        import resource
        resource.setrlimit(resource.RLIMIT_AS, (2 * 2 ** 30, 2 * 2 ** 30))
    try:
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              timeout=timeout, preexec_fn=limit)
    except subprocess.TimeoutExpired:
        return "timeout"
    return done.stdout + done.stderr


@pytest.fixture(scope="module")
def attacked():
    """A class graded once: a student folder whose modules shadow the standard library's, one
    with a symbolic link to the instructors' package, one whose notebook is a link to another
    student's, two entries of one student, and names a spreadsheet would run."""
    root = Path(tempfile.mkdtemp(prefix="hostile-class-"))
    os.chmod(root, 0o755)
    folder = root / "class"
    folder.mkdir()
    marker = root / "PWNED"
    inject = folder / "inject"
    inject.mkdir()
    for name in ("textwrap", "json", "ctypes", "resource", "argparse"):
        (inject / f"{name}.py").write_text(SHADOW.format(marker=str(marker)))
    submission(inject / "work.ipynb", "import numpy as np", RIGHT)
    linker = folder / "linker"
    linker.mkdir()
    course = Path(mechnum_course.__file__).resolve().parents[1]
    (linker / "course").symlink_to(course)
    submission(linker / "work.ipynb", "import numpy as np",
               "leaked = open('course/mechnum_course/hidden.py').read()")
    submission(folder / "victim.ipynb", "import numpy as np", RIGHT)
    (folder / "thief").mkdir()
    (folder / "thief" / "copy.ipynb").symlink_to("../victim.ipynb")
    (folder / "alice").mkdir()
    submission(folder / "alice" / "one.ipynb", "import numpy as np", RIGHT)
    submission(folder / "alice.ipynb", "x = 1")
    submission(folder / "_underscore.ipynb", "x = 1")
    submission(folder / '=HYPERLINK("x").ipynb', "x = 1")
    before = (folder / "victim.ipynb").read_bytes()
    summary = grading.grade(folder, limit=60, cell_limit=20)
    with open(folder / "grading" / "grades.csv", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    feedback = {p.stem: p.read_text(encoding="utf-8")
                for p in (folder / "grading" / "feedback").glob("*.md")}
    yield SimpleResult(summary, rows, feedback, marker, folder, before)
    subprocess.run(["rm", "-rf", str(root)], check=False)


class SimpleResult:
    def __init__(self, summary, rows, feedback, marker, folder, before):
        self.summary, self.rows, self.feedback = summary, rows, feedback
        self.marker, self.folder, self.before = marker, folder, before
        self.by = {row["student"]: row for row in rows}


def test_no_module_of_a_students_folder_runs_outside_the_sandbox(attacked):
    assert not attacked.marker.exists(), attacked.marker.read_text()
    assert attacked.by["inject"]["3.1"] == "1", attacked.feedback["inject"]
    assert (attacked.folder / "victim.ipynb").read_bytes() == attacked.before


def test_a_link_to_the_instructors_package_is_not_followed(attacked):
    assert "raised FileNotFoundError" in attacked.feedback["linker"], attacked.feedback["linker"]
    assert "course is a symbolic link" in attacked.by["linker"]["note"]


def test_a_link_to_another_students_notebook_is_refused(attacked):
    assert attacked.by["victim"]["3.1"] == "1"
    thief = attacked.by["thief"]
    assert (thief["status"], thief["total"]) == ("invalid", "0"), thief
    assert "copy.ipynb is a symbolic link" in thief["note"]


def test_one_row_per_student_and_no_formula(attacked):
    students = [row["student"] for row in attacked.rows]
    assert len(students) == len(set(students)) == 7, students
    assert attacked.by["alice"]["3.1"] == "1"  # alice/one.ipynb and alice.ipynb: one row
    assert "_underscore" in attacked.by
    assert "'=HYPERLINK(\"x\")" in attacked.by
    assert not any(row["student"].startswith(("=", "+", "-", "@")) for row in attacked.rows)


def test_a_student_folder_named_like_the_output_is_refused(tmp_path):
    submission(tmp_path / "a.ipynb", "x = 1")
    (tmp_path / "grading").mkdir()
    submission(tmp_path / "grading" / "work.ipynb", "x = 1")
    with pytest.raises(ValueError, match="is a student's entry"):
        grading.grade(tmp_path, limit=20, cell_limit=5)


def test_a_students_notebooks_share_a_time_budget(work):
    hog = work / "hog"
    hog.mkdir()
    for k in range(3):
        submission(hog / f"loop{k}.ipynb", "import numpy as np", RIGHT,
                   "import signal\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\n"
                   "while True:\n    pass")
    began = time.monotonic()
    grading.grade(work, limit=15, cell_limit=15, student_limit=25)
    seconds = time.monotonic() - began
    with open(work / "grading" / "grades.csv", encoding="utf-8") as file:
        row = next(csv.DictReader(file))
    notes = row["note"].split("; ")
    assert notes[0] == "loop0.ipynb: the notebook ran longer than 15 s and was stopped", row
    assert notes[1].startswith("loop1.ipynb: the notebook ran longer than "), row  # the rest
    assert notes[2].startswith("loop2.ipynb: not run: the student's notebooks spent"), row
    assert row["status"] == "timeout" and row["3.1"] == "1"  # graded from their text
    assert seconds < 25 + 3 * 40, seconds  # the budget, and each check's own limits


def test_a_self_referential_or_shared_list_answer_is_refused_at_once():
    out = isolated(
        "from mechnum.exercises import _answers\n"
        "looped = []\nlooped.append(looped)\n"
        "shared = [1.0]\nfor _ in range(40):\n    shared = [shared, shared]\n"
        "wide = [1.0]\nfor _ in range(21):\n    wide = [wide, wide]\n"
        "for answer in (looped, shared, wide):\n"
        "    try:\n        _answers.Array().convert(answer, 'x')\n"
        "    except _answers.WrongForm as error:\n        print(error)\n", timeout=30)
    assert out.count("nests lists more than 32 deep") == 2, out
    assert "x has more than 1048576 entries" in out, out


def _channel_writer(kind):
    return ("import os, sys, time, struct\n"
            "def rk4_step(f, s, y, h):\n"
            "    out = sys.modules['__main__']._OUT\n"
            "    while True:\n        time.sleep(0.3)\n"
            f"        os.write(out, {kind!r} + struct.pack('<I', 0))\n")


@pytest.mark.parametrize("kind", [b"S", b"X"])
def test_records_written_to_the_channel_do_not_move_the_deadline(work, kind):
    found = {}

    def run():
        found["result"] = _check.run_function("3.1", "rk4_step", _channel_writer(kind),
                                              work / "check", keep=set(_sandbox.descendants()))
    thread = threading.Thread(target=run, daemon=True)
    began = time.monotonic()
    thread.start()
    thread.join(_check.STARTUP + 10)
    assert not thread.is_alive(), "the runner held the grader past its deadline"
    outcomes, delegated = found["result"]
    assert time.monotonic() - began < _check.STARTUP + 10
    assert not delegated and outcomes[-1].kind in ("timeout", "died"), outcomes


def test_special_files_are_refused_and_never_followed(work):
    student = work / "mallory"
    student.mkdir()
    (student / "zero.bin").symlink_to("/dev/zero")
    (student / "x.ipynb").symlink_to("/dev/zero")
    os.mkfifo(student / "pipe.ipynb")
    (student / "own.py").write_text("x = 1\n")
    out = isolated(
        "from pathlib import Path\nfrom mechnum_course import grading\n"
        f"folder = Path({str(student)!r})\n"
        "print(grading.read_notebook(folder / 'x.ipynb'))\n"
        "print(grading.read_notebook(folder / 'pipe.ipynb'))\n"
        f"copy, refused = grading._sandbox_copy(folder, Path({str(work)!r}))\n"
        "print(sorted(p.name for p in (copy / 'mallory').iterdir()), refused)\n"
        f"print(grading.students(folder.parent, {str(work / 'out')!r})[0])\n", timeout=60)
    assert "x.ipynb is a symbolic link, not a regular file" in out, out
    assert "pipe.ipynb is a FIFO, not a regular file" in out, out
    copied = out.splitlines()[2]
    assert "'own.py'" in copied and "zero.bin'" not in copied and "pipe" not in copied.split(
        "]")[0], out
    assert "zero.bin is a symbolic link: refused" in out, out
    assert "the folder holds no notebook" in out, out
    from mechnum_course.grading import _files
    assert _files.read("/dev/zero") == "zero is a device, not a regular file"


def sandboxed(folder, code):
    """Run ``code`` as the grader runs a student's function (launcher started in ``folder``,
    as the grader did before); its output."""
    config = _sandbox.config(folder, cpu=20, memory=2 ** 31, file_size=2 ** 20)
    (folder / "sandbox.json").write_text(json.dumps(config))
    done = subprocess.run(
        [sys.executable, "-I", "-m", "mechnum_course.grading._sandbox",
         str(folder / "sandbox.json"), "--", sys.executable, "-I", "-c", code],
        cwd=_sandbox.launch_folder(folder.parent) if hasattr(_sandbox, "launch_folder")
        else folder, capture_output=True, text=True, timeout=60, env={"PATH": "/usr/bin"})
    if hasattr(_sandbox, "remove_pids_groups"):
        _sandbox.remove_pids_groups()
    return done.stdout + done.stderr


def test_the_sandbox_reads_no_device_but_the_harmless_ones_and_writes_no_shared_memory(work):
    folder = work / "box"
    folder.mkdir()
    probe = Path(f"/dev/shm/mechnum-probe-{os.getpid()}")
    out = sandboxed(folder, "\n".join([
        "import os, resource",
        f"for path in ('/dev', '/dev/ptmx', {str(probe)!r}, '/dev/null'):",
        "    try:",
        "        os.listdir(path) if path == '/dev' else open(path, 'rb' if 'shm' not in path "
        "else 'wb').close()",
        "        print(path, 'open')",
        "    except OSError as error:",
        "        print(path, 'refused', error.errno)",
        "import threading, time",
        "threading.stack_size(2 ** 16)  # memory is not what stops them",
        "started = 0",
        "for _ in range(400):",
        "    try:",
        "        threading.Thread(target=time.sleep, args=(5,), daemon=True).start()",
        "        started += 1",
        "    except RuntimeError:",
        "        break",
        "print('threads', started)"]))
    assert "/dev refused" in out and "/dev/ptmx refused" in out, out
    written = probe.exists()
    probe.unlink(missing_ok=True)
    assert f"{probe} refused" in out and "/dev/null open" in out and not written, out
    started = int(out.split("threads ")[1].split()[0])
    assert 0 < started < _sandbox.MAX_PROCESSES, out  # a bound on processes, root's too


def test_every_forbidden_name_is_a_function_of_the_library():
    """A name that no longer resolves (a module renamed) would forbid nothing, silently."""
    import fnmatch
    import importlib

    from mechnum_course import SOLUTIONS
    for number, found in SOLUTIONS.items():
        for dotted in found.forbidden:
            module, _, pattern = dotted.rpartition(".")
            held = vars(importlib.import_module(module))
            assert fnmatch.filter(list(held), pattern), (number, dotted)


DELEGATES = {  # answers of a line or two that call the library's own solution
    "1.1": ("loop_equations", "from types import SimpleNamespace\n"
            "from mechnum.mechanisms.hacksaw import _kernels as kernels\n"
            "def loop_equations(q, theta2, r1y, r2, r3):\n"
            "    g = SimpleNamespace(r1y=r1y, r2=r2, r3=r3)\n"
            "    q = np.asarray(q, dtype=float)\n"
            "    return kernels.loop(g, q, kernels.crank(theta2)), kernels.loop_jacobian(g, q)"),
    "1.2": ("newton_study", "import importlib\nimport mechnum.newton._single as single\n"
            "def newton_study(F, J, x0, tol=1e-6, maxiter=50):\n"
            "    r = importlib.reload(single).solve(F, x0, J, tol=tol, maxiter=maxiter)\n"
            "    return r.x, r.iterations"),
    "2.2": ("lstsq_householder", "import scipy.linalg.lapack as lapack, scipy.linalg\n"
            "def lstsq_householder(A, b):\n"
            "    n = A.shape[1]\n"
            "    lqr, tau, work, info = lapack.dgeqrf(np.array(A, float))\n"
            "    qtb, work, info = lapack.dormqr('L', 'T', lqr, tau, "
            "np.array(b, float)[:, None], max(1, A.shape[0]))\n"
            "    return scipy.linalg.solve_triangular(np.triu(lqr[:n, :n]), qtb[:n, 0])"),
    "3.1": ("rk4_step", "import importlib\nimport mechnum.ode\n"
            "def rk4_step(f, s, y, h):\n"
            "    return importlib.reload(mechnum.ode).rk4(f, y, [s, s + h])[-1]"),
    "3.2": ("pinned_residual", "from mechnum.rods import _rod as rod\n"
            "def pinned_residual(q, EI, L, target, nodes):\n"
            "    m0, nx, ny = (float(v) for v in q)\n"
            "    x, y, t, m = rod.sweep(EI, L, m0, nx, ny, 0.0, nodes, keep=False)\n"
            "    return np.array([x[0] - target[0], y[0] - target[1], m[0]])"),
    "4.1": ("companion", "def companion(c):\n"
            "    return np.polynomial.polynomial.polycompanion(np.asarray(c, dtype=float))"),
    "4.2": ("prr3_newton_step", "import importlib\n"
            "def prr3_newton_step(pose, lam, g):\n"
            "    direct = importlib.import_module('mechnum.mechanisms.prr3._direct')\n"
            "    new, _ = direct._newton_step(g, np.asarray(pose, float)[None], "
            "np.asarray(lam, float))\n    return new[0]"),
    "5.1": ("elliptic_tip", "import importlib, mechnum.rods._elliptic\n"
            "def elliptic_tip(EI, L, psi, k_rel, mode):\n"
            "    e = importlib.reload(mechnum.rods._elliptic)\n"
            "    return e.clamped_pinned(EI, L, psi, k_rel, mode).tip"),
    "7.2": ("force_by_virtual_power", "from mechnum.mechanisms import actuator\n"
            "def force_by_virtual_power(kin, mech, g):\n"
            "    K = actuator.stroke_kinematics(mech, kin.a, kin.a_dot, kin.a_ddot)\n"
            "    return float(actuator.kane_force(K, g))"),
}


@pytest.mark.parametrize("number", sorted(DELEGATES))
def test_an_answer_that_delegates_to_the_library_fails(work, number):
    name, source = DELEGATES[number]
    result = _check.grade(number, name, "import numpy as np\n" + source, work / "check")
    assert not result.passed and "calls" in result.message, result.message


def test_a_companion_matrix_is_compared_entry_by_entry():
    reference = mechnum_course.reference("4.1")
    assert mechnum_course.check("4.1", reference).passed
    transposed = mechnum_course.check("4.1", lambda c: reference(c).T)  # same eigenvalues
    assert not transposed.passed and "the matrix at index" in transposed.message
