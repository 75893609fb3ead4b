"""The student edition of a notebook: every solution removed, every exercise and starter kept.

A solution is a ``{solution}`` directive, or a gated one, ``{solution-start}`` ... cells ...
``{solution-end}``, whose cells may be code. :func:`student_notebook` removes both, down to the
fences (text before or after them in the same Markdown cell stays), and any code cell whose
metadata says it is a solution. The check cell of an implement-it-yourself exercise keeps its
code; its output becomes what it prints for the unfilled starter, computed here by running the
notebook's starter cell and the check cell (no kernel needed): "not yet", not the full edition's
"passed".

Run on a folder (every ``.ipynb`` and ``.md`` in it, in place)::

    python -m mechnum_course.student book_copy/
"""

import ast
import contextlib
import io
import json
import re
import sys
from pathlib import Path

import numpy as np

FENCE = re.compile(r"^\s*(`{3,}|:{3,})\{(solution|solution-start|solution-end)\}")


def _fence_end(lines, start, fence):
    """The index of the line that closes the fence opened at ``lines[start]``."""
    for k in range(start + 1, len(lines)):
        stripped = lines[k].strip()
        if stripped and set(stripped) == {fence[0]} and len(stripped) >= len(fence):
            return k
    raise ValueError(f"unclosed fence {lines[start].strip()!r}")


def _strip(text, gated):
    """``text`` without its solutions, and whether it ends inside a gated solution."""
    lines, kept, k = text.splitlines(keepends=True), [], 0
    while k < len(lines):
        match = FENCE.match(lines[k])
        if match and not (gated and match.group(2) != "solution-end"):
            end = _fence_end(lines, k, match.group(1))
            gated = match.group(2) == "solution-start"
            k = end + 1
            continue
        if match:  # a solution directive inside a gated solution: skipped with it
            k = _fence_end(lines, k, match.group(1)) + 1
            continue
        if not gated:
            kept.append(lines[k])
        k += 1
    return "".join(kept), gated


def strip_markdown(text):
    """A Markdown page (or cell) without its solutions.

    Examples
    --------
    >>> page = "Intro.\\n\\n````{solution} ex-1\\n:class: dropdown\\nIt is 42.\\n````\\nAfter.\\n"
    >>> strip_markdown(page)
    'Intro.\\n\\nAfter.\\n'
    """
    kept, gated = _strip(text, False)
    if gated:
        raise ValueError("a {solution-start} without its {solution-end}")
    return kept


def _role(cell):
    return cell.get("metadata", {}).get("mechnum", {}).get("role")


def _run(source, namespace):
    """Run a cell's code; the value of its last expression, and what it printed."""
    tree = ast.parse(source)
    last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(tree, "<cell>", "exec"), namespace)
        value = eval(compile(ast.Expression(last.value), "<cell>", "eval"),
                     namespace) if last else None
    return value, out.getvalue()


def _unfilled_check(cell, starters):
    """The outputs of a check cell run on the notebook's unfilled starter."""
    from mechnum import exercises

    number = cell["metadata"]["mechnum"]["exercise"]
    namespace = {"np": np, "exercises": exercises}
    _run(starters.get(number, exercises.starter(number)), namespace)
    value, printed = _run(_source(cell), namespace)
    outputs = [{"output_type": "stream", "name": "stdout", "text": printed}] if printed else []
    if value is not None:
        outputs.append({"output_type": "execute_result", "metadata": {},
                        "execution_count": cell.get("execution_count"),
                        "data": {"text/plain": repr(value)}})
    return outputs


def _source(cell):
    source = cell["source"]
    return source if isinstance(source, str) else "".join(source)


def student_notebook(notebook):
    """The student edition of a notebook (a dictionary in the notebook format; a new one).

    Examples
    --------
    >>> from mechnum import exercises
    >>> full = {"cells": exercises.cells("3.1"), "metadata": {}, "nbformat": 4,
    ...         "nbformat_minor": 5}
    >>> cells = student_notebook(full)["cells"]
    >>> [cell.get("metadata", {}).get("mechnum", {}).get("role") for cell in cells]
    [None, 'starter', 'check']
    >>> print(cells[-1]["outputs"][0]["data"]["text/plain"][:28])
    Exercise 3.1: not yet. On th
    """
    starters = {cell["metadata"]["mechnum"]["exercise"]: _source(cell)
                for cell in notebook["cells"] if _role(cell) == "starter"}
    cells, gated = [], False
    for cell in notebook["cells"]:
        cell = json.loads(json.dumps(cell))  # a copy
        if cell["cell_type"] == "markdown":
            text, gated_after = _strip(_source(cell), gated)
            gated = gated_after
            if text.strip():
                cell["source"] = text
                cells.append(cell)
        elif not gated and _role(cell) != "solution":
            if _role(cell) == "check":
                cell["outputs"] = _unfilled_check(cell, starters)
            cells.append(cell)
    if gated:
        raise ValueError("a {solution-start} without its {solution-end}")
    return {**notebook, "cells": cells}


def student_folder(folder):
    """Make every ``.ipynb`` and ``.md`` file under ``folder`` its student edition, in place;
    the number of files changed."""
    changed = 0
    for path in sorted(Path(folder).rglob("*")):
        if path.suffix not in (".ipynb", ".md") or ".ipynb_checkpoints" in path.parts:
            continue
        text = path.read_text(encoding="utf-8")
        if path.suffix == ".md":
            new = strip_markdown(text)
        else:
            new = json.dumps(student_notebook(json.loads(text)), indent=1,
                             ensure_ascii=False) + "\n"
        if new != text:
            path.write_text(new, encoding="utf-8")
            changed += 1
    return changed


if __name__ == "__main__":  # pragma: no cover - the command line of the Makefile
    for name in sys.argv[1:]:
        print(f"student edition of {name}: {student_folder(name)} files without solutions")
