"""Grade a folder of student notebooks with the exercises' self-checks (``make grade``).

Each notebook runs top to bottom in a fresh kernel, in its own process with a time limit
(:data:`NOTEBOOK_LIMIT`); a cell that raises is recorded and the next cells still run, a cell that
runs longer than :data:`CELL_LIMIT` is interrupted, and a notebook that overruns its limit is
stopped and recorded; nothing stops the run. Then every check runs on the functions the notebook
defines. Written beside each other in the output folder:

* ``grades.csv``: one row per notebook, its ``status`` (``ok``, ``errors``, ``timeout``) and one
  column per exercise, ``pass``, ``fail`` or ``missing`` (the notebook does not define the
  exercise's function at all);
* ``feedback.csv``: each check's message, to hand back;
* ``summary.txt``: the counts, which is also printed.

The columns are the exercises whose function at least one notebook defines.

Command line: ``python -m mechnum.exercises.grading FOLDER [--out FOLDER] [--limit SECONDS]``.
"""

import argparse
import ast
import csv
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

NOTEBOOK_LIMIT = 300.0
"""Seconds a notebook may run, its checks included (a chapter runs in 30 s)."""

CELL_LIMIT = 60.0
"""Seconds one cell may run before the kernel is interrupted and the next cell runs."""

MARK = "MECHNUM-GRADES "


def defined(notebook):
    """The exercise numbers whose function the notebook's code cells define.

    Examples
    --------
    >>> cells = [{"cell_type": "code", "source": "def rk4_step(f, s, y, h):\\n    pass"}]
    >>> defined({"cells": cells})
    ['3.1']
    """
    from mechnum import exercises

    names = set()
    for cell in notebook["cells"]:
        if cell["cell_type"] != "code":
            continue
        source = cell["source"] if isinstance(cell["source"], str) else "".join(cell["source"])
        try:
            tree = ast.parse(source)
        except SyntaxError:
            continue
        names |= {node.name for node in ast.walk(tree) if isinstance(node, ast.FunctionDef)}
    return [n for n in exercises.CHECKS if exercises.reference(n).__name__ in names]


def report(namespace, numbers):
    """Run the checks of ``numbers`` on the functions of ``namespace`` (a kernel's
    ``globals()``) and print them as one line of JSON after :data:`MARK`.

    Examples
    --------
    >>> from mechnum import exercises
    >>> report({"rk4_step": exercises.reference("3.1")}, ["3.1", "1.1"])  # doctest: +ELLIPSIS
    MECHNUM-GRADES {"3.1": ["pass", "Exercise 3.1: passed, ..."], "1.1": ["missing", ...]}
    """
    from mechnum import exercises

    verdicts = {}
    for number in numbers:
        function = namespace.get(exercises.reference(number).__name__)
        if function is None:
            verdicts[number] = ("missing", "the notebook does not define the function")
        else:
            result = exercises.check(number, function)
            verdicts[number] = ("pass" if result.passed else "fail", result.message)
    print(MARK + json.dumps(verdicts))


def _grade_one(path, numbers, cell_limit):
    """Execute one notebook with a last cell that reports the checks (in a child process)."""
    import nbformat
    from nbclient import NotebookClient

    notebook = nbformat.read(path, as_version=4)
    notebook.cells.append(nbformat.v4.new_code_cell(
        f"from mechnum.exercises import grading as _grading\n"
        f"_grading.report(globals(), {numbers!r})"))
    NotebookClient(notebook, timeout=cell_limit, allow_errors=True, interrupt_on_timeout=True,
                   kernel_name="python3",
                   resources={"metadata": {"path": str(Path(path).parent)}}).execute()
    errors = [k for k, cell in enumerate(notebook.cells[:-1]) if cell.cell_type == "code" and
              any(out.output_type == "error" for out in cell.outputs)]
    text = "".join(out.get("text", "") for out in notebook.cells[-1].outputs)
    line = next((ln for ln in text.splitlines() if ln.startswith(MARK)), None)
    verdicts = json.loads(line[len(MARK):]) if line else {}
    print(json.dumps({"errors": errors, "verdicts": verdicts}))


def _run(path, numbers, limit, cell_limit):
    """The grades of one notebook: its status, a note, and a verdict per exercise."""
    command = [sys.executable, "-m", "mechnum.exercises.grading", "--one", str(path),
               "--numbers", ",".join(numbers), "--cell-limit", str(cell_limit)]
    child = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             start_new_session=True)
    try:
        out, err = child.communicate(timeout=limit)
    except subprocess.TimeoutExpired:
        os.killpg(child.pid, signal.SIGKILL)
        child.communicate()
        return "timeout", f"stopped after {limit:g} s", {}
    try:
        result = json.loads(out.strip().splitlines()[-1])
    except (IndexError, json.JSONDecodeError):
        return "failed", (err.strip().splitlines() or ["no output"])[-1], {}
    verdicts = result["verdicts"]
    if result["errors"]:
        note = "cells that raised or were interrupted: " + ", ".join(
            str(k) for k in result["errors"])
        return "errors", note, verdicts
    return ("ok", "", verdicts) if verdicts else ("failed", "the checks did not run", {})


def grade(folder, out=None, *, limit=NOTEBOOK_LIMIT, cell_limit=CELL_LIMIT):
    """Grade every ``.ipynb`` in ``folder``; write ``grades.csv``, ``feedback.csv`` and
    ``summary.txt`` into ``out`` (default: ``folder``) and return the summary.

    Parameters
    ----------
    folder : str or pathlib.Path
        The students' notebooks.
    out : str or pathlib.Path, optional
        Where to write the three files.
    limit, cell_limit : float
        Seconds per notebook and per cell.

    Returns
    -------
    str
        The summary.
    """
    import nbformat

    folder = Path(folder)
    out = Path(out) if out else folder
    paths = sorted(p for p in folder.glob("*.ipynb"))
    if not paths:
        raise ValueError(f"no notebook (*.ipynb) in {folder}")
    if not limit > 0 or not cell_limit > 0:
        raise ValueError(f"the time limits must be positive, got {limit}, {cell_limit}")
    found = {p: defined(nbformat.read(p, as_version=4)) for p in paths}
    numbers = [n for n in _all_numbers() if any(n in f for f in found.values())]
    rows, feedback = [], []
    for path in paths:
        status, note, verdicts = _run(path, found[path], limit, cell_limit)
        row = {"notebook": path.name, "status": status, "note": note}
        for number in numbers:
            verdict, message = verdicts.get(number, ("missing" if number not in found[path]
                                                     else "fail", note or "not checked"))
            row[number] = verdict
            feedback.append({"notebook": path.name, "exercise": number, "verdict": verdict,
                             "message": message})
        rows.append(row)
    out.mkdir(parents=True, exist_ok=True)
    _write(out / "grades.csv", ["notebook", "status", *numbers, "note"], rows)
    _write(out / "feedback.csv", ["notebook", "exercise", "verdict", "message"], feedback)
    summary = _summary(rows, numbers)
    (out / "summary.txt").write_text(summary, encoding="utf-8")
    return summary


def _all_numbers():
    from mechnum import exercises

    return list(exercises.CHECKS)


def _write(path, fields, rows):
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.DictWriter(file, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)


def _summary(rows, numbers):
    statuses = [row["status"] for row in rows]
    words = {"ok": "ran", "errors": "with errors", "timeout": "timed out",
             "failed": "failed to run"}
    lines = [f"{len(rows)} notebooks: " + ", ".join(
        f"{statuses.count(s)} {word}" for s, word in words.items() if s in statuses)]
    for number in numbers:
        verdicts = [row[number] for row in rows]
        lines.append(f"exercise {number}: " + ", ".join(
            f"{verdicts.count(v)} {v}" for v in ("pass", "fail", "missing")))
    for row in rows:
        if row["status"] != "ok":
            lines.append(f"{row['notebook']}: {row['status']} ({row['note']})")
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?")
    parser.add_argument("--out")
    parser.add_argument("--limit", type=float, default=NOTEBOOK_LIMIT)
    parser.add_argument("--cell-limit", type=float, default=CELL_LIMIT)
    parser.add_argument("--one", help=argparse.SUPPRESS)
    parser.add_argument("--numbers", default="", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        _grade_one(args.one, [n for n in args.numbers.split(",") if n], args.cell_limit)
    elif args.folder:
        print(grade(args.folder, args.out, limit=args.limit, cell_limit=args.cell_limit), end="")
    else:
        parser.error("give the folder of the notebooks")


if __name__ == "__main__":
    main()
