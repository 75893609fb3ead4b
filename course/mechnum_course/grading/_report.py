"""What ``make grade`` writes: ``grades.csv``, a feedback page per student, ``summary.txt``.

``grades.csv`` has one row per student and always the same columns, in this order, so that a
gradebook imports it: ``student``, ``status`` (``ok``, ``errors``: a cell raised, ``timeout``,
``invalid``: no notebook could be read), ``total`` and ``maximum`` (the points of the
self-checked exercises), one column per self-checked exercise (its points: the exercise's
``points`` when it passes, else 0), one empty column per exercise without a check of the same
chapters (``rubric <label>``, for the instructor, by the rubric in ``course/rubric.md``), and
``note``.
"""

import csv
import re
from pathlib import Path

from mechnum import exercises

RUBRIC = Path(__file__).resolve().parents[2] / "rubric.md"
"""The rubric of the exercises without a check: a Markdown table, one row per exercise."""


def rubric():
    """``{label: (points, criteria)}`` from :data:`RUBRIC`, in the order of the table."""
    rows = {}
    for line in RUBRIC.read_text(encoding="utf-8").splitlines():
        match = re.match(r"\|\s*`(ch\d-ex-[\w-]+)`\s*\|\s*([\d.]+)\s*\|(.*)\|\s*$", line)
        if match:
            rows[match.group(1)] = (float(match.group(2)), match.group(3).strip())
    return rows


def _columns(rows, numbers):
    if numbers is None:
        seen = {n for _, graded in rows for g in graded for n in g["verdicts"]}
        numbers = [n for n in exercises.EXERCISES if n in seen]
    unknown = [n for n in numbers if n not in exercises.EXERCISES]
    if unknown:
        raise ValueError(f"no self-checked exercise {', '.join(unknown)}")
    chapters = {n.split(".")[0] for n in numbers}
    manual = [label for label in rubric() if label[2] in chapters]
    return list(numbers), manual


def _points(number, verdict):
    return exercises.EXERCISES[number].points if verdict == "pass" else 0


def _merge(graded, number):
    """A student's verdict on an exercise over their notebooks: a pass anywhere, else the
    first verdict, else missing."""
    found = [g["verdicts"][number] for g in graded if number in g["verdicts"]]
    return next((v for v in found if v[0] == "pass"), found[0] if found else
                ("missing", "no notebook defines the function"))


def _status(graded):
    """The worst status of a student's notebooks."""
    order = ("invalid", "timeout", "errors", "ok")
    return min((g["status"] for g in graded), key=order.index)


def write(rows, out, numbers=None, *, sandbox=0, limits=None):
    """Write the three outputs into ``out`` for ``rows`` (``[(student, [graded notebook])]``);
    the summary."""
    numbers, manual = _columns(rows, numbers)
    maximum = sum(exercises.EXERCISES[n].points for n in numbers)
    out = Path(out)
    (out / "feedback").mkdir(parents=True, exist_ok=True)
    table = []
    for student, graded in rows:
        verdicts = {n: _merge(graded, n) for n in numbers}
        points = {n: _points(n, v[0]) for n, v in verdicts.items()}
        notes = "; ".join(f"{g['notebook']}: {g['note']}" if g.get("notebook") else g["note"]
                          for g in graded if g["note"])
        table.append({"student": student, "status": _status(graded),
                      "total": _number(sum(points.values())), "maximum": _number(maximum),
                      **{n: _number(p) for n, p in points.items()},
                      **{f"rubric {label}": "" for label in manual}, "note": notes})
        (out / "feedback" / f"{student}.md").write_text(
            _feedback(student, graded, verdicts, points, maximum, manual), encoding="utf-8")
    fields = ["student", "status", "total", "maximum", *numbers,
              *(f"rubric {label}" for label in manual), "note"]
    with open(out / "grades.csv", "w", newline="", encoding="utf-8") as file:
        writer = csv.DictWriter(file, fieldnames=fields)
        writer.writeheader()
        writer.writerows(table)
    summary = _summary(table, numbers, rows, sandbox, limits or {})
    (out / "summary.txt").write_text(summary, encoding="utf-8")
    return summary


def _number(value):
    return f"{value:g}"


def _feedback(student, graded, verdicts, points, maximum, manual):
    lines = [f"# Feedback for {student}", "",
             f"Self-checked exercises: {_number(sum(points.values()))} of {_number(maximum)} "
             "points.", ""]
    for number, (verdict, message) in verdicts.items():
        lines.append(f"- **Exercise {number}** ({verdict}, {_number(points[number])} of "
                     f"{_number(exercises.EXERCISES[number].points)}): {message}")
    for g in graded:
        lines += ["", f"## {g.get('notebook', student)}: {g['status']}", ""]
        if g["note"]:
            lines.append(g["note"])
        for error in g["errors"]:
            count = error.get("count")
            where = (f"Cell In [{count}]" if count else "A cell") + \
                f" (code cell {error['code_cell']}, cell {error['cell']} of the notebook)"
            lines.append(f"- {where} raised {error['ename']}: {error['evalue']}")
    if manual:
        lines += ["", "## Graded by your instructor", ""]
        lines += [f"- `{label}`" for label in manual]
    return "\n".join(lines) + "\n"


def _summary(table, numbers, rows, sandbox, limits):
    statuses = [row["status"] for row in table]
    lines = [f"{len(table)} students: " + ", ".join(
        f"{statuses.count(s)} {s}" for s in ("ok", "errors", "timeout", "invalid")
        if s in statuses)]
    for number in numbers:
        verdicts = [_merge(g, number)[0] for _, g in rows]
        lines.append(f"exercise {number}: " + ", ".join(
            f"{verdicts.count(v)} {v}" for v in ("pass", "fail", "not gradable", "missing")
            if v in verdicts))
    for row in table:
        if row["status"] != "ok":
            lines.append(f"{row['student']}: {row['status']} ({row['note']})")
    from mechnum_course.grading import _sandbox
    readable = _sandbox.exposed(_sandbox.config("/nonexistent", cpu=1, memory=1,
                                                file_size=1)["read"])
    if readable:
        lines.append(f"WARNING: the instructors' package is under {readable[0]}, which the "
                     "sandbox lets a notebook read: install it from course/ (environment.txt)")
    lines.append(f"file-system sandbox: Landlock ABI {sandbox}" if sandbox else
                 "WARNING: this Linux kernel has no Landlock: notebooks could read and write "
                 "outside their folders; grade summative work in a container (the book's page "
                 "on grading)")
    if limits:
        lines.append("limits: " + ", ".join(f"{k} {v:g} s" for k, v in limits.items()))
    return "\n".join(lines) + "\n"
