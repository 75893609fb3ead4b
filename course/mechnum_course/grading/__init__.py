"""Grade a folder of student notebooks (``make grade SUBMISSIONS=folder``).

Each entry of the folder is one student: a notebook ``name.ipynb`` (the student ``name``), or a
folder ``name/`` of notebooks and the student's own files. For each notebook:

1. a temporary copy of the student's entry, with the data files the chapters read
   (:data:`DATA_FILES` of ``book/``), is made; the notebook runs there in a fresh kernel
   confined by :mod:`._sandbox` (its own session, limits of CPU, memory, file size and output,
   Landlock where Linux has it), only to learn the source of each exercise's function
   (:mod:`._extract`); every process of that run is killed at the end, the kernel included;
2. each function is then graded from its source alone, in a fresh confined process with the
   pristine package, on the public and the hidden cases, each case within its time limit
   (:mod:`._check`); a function that calls the package's own solution of the exercise, the
   instructors' reference or a function its statement forbids fails with that reason.

Nothing stops the run: a file that is not a notebook (not JSON, a folder named ``x.ipynb``, a
cell without ``source``) is a row with the status ``invalid`` and its reason, and so is a
notebook that cannot start (its functions are still graded from its text, for the instructor to
see); a notebook that overruns its time is stopped and graded from its text. Written into the
output folder (by default ``FOLDER/grading``): ``grades.csv`` (:mod:`._report`),
``feedback/<student>.md`` and ``summary.txt``.

Command line: ``python -m mechnum_course.grading FOLDER [--out FOLDER] [--limit SECONDS]
[--cell-limit SECONDS] [--exercises 3.1,3.2]``.
"""

import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import nbformat

from mechnum import exercises
from mechnum_course.grading import _check, _extract, _report, _sandbox
from mechnum_course.grading._check import RUNNER_CPU

__all__ = ["CELL_LIMIT", "DATA_FILES", "KERNEL_MEMORY", "MAX_OUTPUT", "NOTEBOOK_LIMIT", "grade"]

NOTEBOOK_LIMIT = 300.0
"""Seconds (wall clock) a notebook may run, its kernel's start included (a chapter runs in
30 s); its kernel also has this many seconds of CPU."""
CELL_LIMIT = 60.0
"""Seconds one cell may run before the kernel is interrupted."""
KERNEL_MEMORY = 8 * 2 ** 30
"""Bytes of address space of a notebook's kernel."""
MAX_FILE = 64 * 2 ** 20
"""The largest file (bytes) a notebook's kernel may write; also the largest notebook read."""
MAX_OUTPUT = 4 * 2 ** 20
"""Bytes of cell output kept from one notebook; more is dropped (and said so)."""
BOOK = Path(__file__).resolve().parents[3] / "book"
DATA_FILES = ("published_values.csv", "findings.csv", "references.bib", "certificates")
"""What the chapters read beside them, copied from ``book/`` next to every notebook."""


def _invalid(reason):
    return {"status": "invalid", "note": reason, "verdicts": {}, "errors": [], "notes": []}


def read_notebook(path):
    """The notebook at ``path``, or the reason it is none (a string)."""
    if path.is_dir():
        return f"{path.name} is a folder, not a notebook"
    if path.stat().st_size > MAX_FILE:
        return f"{path.name} is larger than {MAX_FILE // 2 ** 20} MB"
    try:
        text = path.read_text(encoding="utf-8")
        data = json.loads(text)
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        return f"{path.name} is not a notebook: not JSON ({error})"
    try:
        notebook = nbformat.reads(text, as_version=4)
        nbformat.validate(notebook)
    except Exception as error:
        return f"{path.name} is not a valid notebook ({type(error).__name__}: " + \
            f"{str(error).splitlines()[0][:200]})"
    return notebook if isinstance(data, dict) else f"{path.name} is not a notebook"


def students(folder, out):
    """``[(student, [notebooks] or the reason the entry is invalid, entry)]``, by name."""
    found = []
    for entry in sorted(Path(folder).iterdir()):
        if entry.name.startswith((".", "_")) or entry.resolve() == Path(out).resolve():
            continue
        if entry.suffix == ".ipynb":
            found.append((entry.stem, [entry], entry))
        elif entry.is_dir():
            books = sorted(p for p in entry.rglob("*.ipynb")
                           if ".ipynb_checkpoints" not in p.parts)
            found.append((entry.name, books or "the folder holds no notebook", entry))
    return found


def _sandbox_copy(entry, work):
    """A temporary copy of a student's entry and of the chapters' data files."""
    folder = Path(tempfile.mkdtemp(prefix="nb-", dir=work))
    target = folder / entry.name
    if entry.is_dir():
        shutil.copytree(entry, target, symlinks=False, ignore_dangling_symlinks=True)
    else:
        shutil.copy(entry, target)
    home = target if entry.is_dir() else folder
    for name in DATA_FILES:
        source = BOOK / name
        if source.is_dir():
            shutil.copytree(source, home / name, dirs_exist_ok=True)
        elif source.exists():
            shutil.copy(source, home / name)
    return folder


def run_notebook(path, copy, work, *, limit, cell_limit, keep):
    """Run the notebook ``path`` (inside the sandbox folder ``copy``) and extract the
    functions' sources; the supervisor's result, or its problem."""
    names = [e.name for e in exercises.EXERCISES.values()]
    result = Path(tempfile.mkdtemp(prefix="result-", dir=work)) / "result.json"
    env = _check._environment(copy)
    env.pop("MPLBACKEND")
    confinement = _sandbox.config(copy, cpu=limit, memory=KERNEL_MEMORY, file_size=MAX_FILE,
                                  tcp=True)
    job = {"notebook": str(path), "folder": str(copy), "names": names,
           "cell_limit": cell_limit, "max_output": MAX_OUTPUT, "env": env,
           "confinement": confinement, "result": str(result)}
    (result.parent / "job.json").write_text(json.dumps(job), encoding="utf-8")
    supervisor = subprocess.Popen(
        [sys.executable, "-m", "mechnum_course.grading._notebook", str(result.parent / "job.json")],
        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        start_new_session=True)
    began = time.monotonic()
    try:
        supervisor.wait(timeout=limit)
        timed_out = False
    except subprocess.TimeoutExpired:
        timed_out = True
    finally:
        _sandbox.kill_descendants(keep)
        supervisor.wait()
    try:
        outcome = json.loads(result.read_text(encoding="utf-8"))
        sources = json.loads(outcome["sources"]) if outcome["sources"] else {}
        if not isinstance(sources, dict):
            raise ValueError
    except (OSError, ValueError, KeyError, TypeError):
        outcome, sources = {"errors": [], "problem": "", "dropped": 0}, {}
    if timed_out:
        outcome["problem"] = f"the notebook ran longer than {limit:g} s and was stopped"
    outcome["seconds"] = time.monotonic() - began
    return outcome, sources


def grade_notebook(path, entry, work, *, limit, cell_limit, keep):
    """The grades of one notebook: status, note, verdicts, cell errors, notes."""
    notebook = read_notebook(path)
    if isinstance(notebook, str):
        return _invalid(notebook)
    copy = _sandbox_copy(entry, work)
    inside = copy / path.relative_to(entry.parent)
    outcome, sources = run_notebook(inside, copy, work, limit=limit, cell_limit=cell_limit,
                                    keep=keep)
    names = {e.name: n for n, e in exercises.EXERCISES.items()}
    cells = [c.source for c in notebook.cells if c.cell_type == "code"]
    if not sources or outcome["problem"]:
        fallback = _extract.static(cells, list(names))
        sources = {k: v for k, v in sources.items() if isinstance(v, dict) and "source" in v}
        sources = {**fallback, **sources}
    verdicts = {}
    for name, number in names.items():
        found = sources.get(name)
        if not isinstance(found, dict) or found.get("error") == "missing":
            continue
        if "source" not in found or not isinstance(found["source"], str):
            verdicts[number] = ("not gradable", str(found.get("error", "no source"))[:500])
            continue
        source = _extract.with_imports(found["source"], cells)
        result = _check.grade(number, name, source, Path(tempfile.mkdtemp(
            prefix=f"check-{number}-", dir=work)), keep)
        notes = [str(n) for n in found.get("notes", [])][:5]
        message = result.message + "".join(f" (Note: {n}.)" for n in notes)
        verdicts[number] = ("pass" if result.passed else "fail", message)
    status = ("invalid" if outcome["problem"].startswith("the notebook could not run") else
              "timeout" if "longer than" in outcome["problem"] else
              "errors" if outcome["errors"] or outcome["problem"] else "ok")
    notes = [outcome["problem"]] if outcome["problem"] else []
    if outcome.get("dropped"):
        notes.append(f"{outcome['dropped']} bytes of output beyond {MAX_OUTPUT // 2 ** 20} MB "
                     "were dropped")
    return {"status": status, "note": "; ".join(notes), "verdicts": verdicts,
            "errors": outcome["errors"], "notes": notes, "notebook": path.name}


def grade(folder, out=None, *, limit=NOTEBOOK_LIMIT, cell_limit=CELL_LIMIT, numbers=None):
    """Grade every student of ``folder``; write ``grades.csv``, ``feedback/`` and
    ``summary.txt`` into ``out`` (default ``folder/grading``) and return the summary.

    Parameters
    ----------
    folder : str or pathlib.Path
        The students' notebooks (a notebook or a folder per student).
    out : str or pathlib.Path, optional
        Where to write the results.
    limit, cell_limit : float
        Seconds per notebook (and CPU seconds of its kernel) and per cell.
    numbers : sequence of str, optional
        The exercises graded (default: every exercise that a notebook defines or whose
        starter it holds).
    """
    folder = Path(folder)
    out = Path(out) if out else folder / "grading"
    if not folder.is_dir():
        raise ValueError(f"{folder} is not a folder of notebooks")
    if not (0 < limit <= 3600 and 0 < cell_limit <= limit):
        raise ValueError(f"the time limits must be positive, at most an hour, the cell's within "
                         f"the notebook's; got {limit}, {cell_limit}")
    entries = students(folder, out)
    if not entries:
        raise ValueError(f"no notebook (*.ipynb) or student folder in {folder}")
    _sandbox.become_subreaper()
    keep = set(_sandbox.descendants())
    rows = []
    with tempfile.TemporaryDirectory(prefix="mechnum-grade-") as work:
        for student, books, entry in entries:
            if isinstance(books, str):
                rows.append((student, [_invalid(books)]))
                continue
            graded = []
            for path in books:
                try:
                    graded.append(grade_notebook(path, entry, Path(work), limit=limit,
                                                 cell_limit=cell_limit, keep=keep))
                except Exception as error:  # nothing stops the run
                    graded.append(_invalid(f"{path.name} could not be graded "
                                           f"({type(error).__name__}: {error})"))
                graded[-1].setdefault("notebook", path.name)
            rows.append((student, graded))
        _sandbox.kill_descendants(keep)
    return _report.write(rows, out, numbers, sandbox=_sandbox.landlock_abi(),
                         limits={"notebook": limit, "cell": cell_limit, "runner": RUNNER_CPU})
