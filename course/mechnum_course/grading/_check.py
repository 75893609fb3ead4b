"""Grade one exercise from the source of a student's function, outside the student's reach.

The function runs in a fresh, confined process (:mod:`._runner`), on the public cases, the
hidden cases and the probes; this process, which runs no student code, reads what it did case
by case, each within the exercise's time limit (the runner and everything it started are killed
when a limit passes, also inside a C call), and judges it with the references' answers
(:func:`mechnum_course.answers`) and the mistakes' for the feedback.
"""

import json
import os
import select
import shutil
import struct
import subprocess
import sys
import time
from pathlib import Path

from mechnum import exercises
from mechnum.exercises import _child, _harness
from mechnum_course import HIDDEN, SOLUTIONS, answers
from mechnum_course.grading import _sandbox

HERE = Path(__file__).resolve().parent
RUNNER_CPU = 60
"""CPU seconds of the process that runs one exercise's cases."""
RUNNER_MEMORY = 4 * 2 ** 30
"""Bytes of address space of that process."""
STARTUP = 20.0
"""Seconds the runner may take to start (Python, numpy, the cases) before its first case."""


def _read_record(stream, deadline):
    """The next record of the runner: ``("R", bytes)``, ``("D", name)``, or None (time up or
    end)."""
    head = _read_exactly(stream, 5, deadline)
    if head is None:
        return None
    size = struct.unpack("<I", head[1:])[0]
    if size > _child.MAX_ANSWER_BYTES:
        return None
    body = _read_exactly(stream, size, deadline)
    if body is None:
        return None
    return chr(head[0]), body


def _read_exactly(stream, size, deadline):
    data = b""
    while len(data) < size:
        left = deadline - time.monotonic()
        if left <= 0 or not select.select([stream], [], [], left)[0]:
            return None
        chunk = os.read(stream, size - len(data))
        if not chunk:
            return None
        data += chunk
    return data


def run_function(number, name, source, folder, keep=()):
    """What the function ``name`` of ``source`` does on each case of exercise ``number``
    (public, hidden, probes), run in a confined process in ``folder``: a list of Outcomes, and
    the function it delegated to (or ""). Every process started is killed at the end, but
    those in ``keep``."""
    exercise = exercises.EXERCISES[number]
    folder.mkdir(parents=True, exist_ok=True)
    shutil.copy(HERE / "_runner.py", folder / "runner.py")
    shutil.copy(HERE.parent / "hidden.py", folder / "hidden.py")
    (folder / "job.json").write_text(json.dumps({
        "number": number, "name": name, "source": source,
        "forbidden": list(dict.fromkeys([*exercise.forbidden,
                                         *SOLUTIONS[number].forbidden]))}), encoding="utf-8")
    confinement = _sandbox.config(folder, cpu=RUNNER_CPU, memory=RUNNER_MEMORY,
                                  file_size=10 * 2 ** 20)
    (folder / "sandbox.json").write_text(json.dumps(confinement), encoding="utf-8")
    env = {**_environment(folder), "PYTHONPATH": ""}
    child = subprocess.Popen(
        [sys.executable, "-m", "mechnum_course.grading._sandbox", str(folder / "sandbox.json"),
         "--", sys.executable, "-s", str(folder / "runner.py"), str(folder)],
        cwd=folder, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL, env=env, start_new_session=True)
    count = len(exercise.cases()) + len(HIDDEN[number]()) + len(exercise.probes())
    outcomes, delegated, limit = [], "", STARTUP
    try:
        while len(outcomes) < count:
            record = _read_record(child.stdout.fileno(), time.monotonic() + limit)
            limit = exercise.time_limit  # after the start, each case's own limit
            if record is None:
                break
            kind, body = record
            if kind == "D":
                delegated = body.decode(errors="replace")
                break
            if kind == "R":
                outcomes.append(_child.unpack(body))
    finally:
        if child.poll() is None:
            child.kill()
        child.wait()  # its status, before the sweep reaps what it started
        _sandbox.kill_descendants(keep)
        child.stdout.close()
    if child.returncode == DELEGATED_STATUS and not delegated:
        delegated = "a function it may not call"
    if not delegated and child.returncode == -9 and len(outcomes) < count:
        outcomes.append(_child.Outcome("timeout"))
    elif not delegated and len(outcomes) < count:
        outcomes.append(_child.Outcome("died", message=_ended(child.returncode)))
    return outcomes, delegated


def _ended(status):
    if status == DELEGATED_STATUS:
        return "your function called a function it may not call"
    if status and status < 0:
        return (f"the process running your function was killed (signal {-status}: a limit "
                "of CPU time, memory or file size?)")
    return "the process running your function ended without an answer"


DELEGATED_STATUS = 86


def _environment(folder):
    keep = ("PATH", "LANG", "LC_ALL", "OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")
    env = {k: os.environ[k] for k in keep if k in os.environ}
    tmp = Path(folder) / "tmp"
    tmp.mkdir(exist_ok=True)
    return {**env, "HOME": str(folder), "TMPDIR": str(tmp), "MPLCONFIGDIR": str(tmp),
            "NUMBA_CACHE_DIR": str(tmp), "PYTHONDONTWRITEBYTECODE": "1",
            "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"}


def grade(number, name, source, folder, keep=()):
    """The :class:`~mechnum.exercises.Result` of a function's source on exercise ``number``:
    the public cases, then the hidden ones (their labels marked "hidden")."""
    exercise = exercises.EXERCISES[number]
    public, hidden = exercise.cases(), HIDDEN[number]()
    hidden = [_harness.Case(f"a hidden case ({case.label})", case.args) for case in hidden]
    cases, probes = public + hidden, list(exercise.probes())
    outcomes, delegated = run_function(number, name, source, folder, keep)
    if delegated:
        what = ("the instructors' reference solution" if delegated.startswith("mechnum_course")
                else delegated if delegated.startswith("a function") else f"`{delegated}`")
        return exercises.Result(number, False, f"Exercise {number}: fail. Your `{name}` calls "
                                f"{what}, the solution the exercise asks you to write (or a "
                                "function its statement forbids): write it yourself.")
    expected, mistaken = answers(number, cases[:min(len(outcomes), len(cases))])
    _, probe_mistakes = answers(number, probes)
    pairs = list(zip(cases, outcomes))
    probe_outcomes = list(zip(probes, outcomes[len(cases):]))
    return _harness.judge(
        exercise, pairs, expected, lambda k: mistaken[k],
        (lambda: probe_outcomes) if len(probe_outcomes) == len(probes) else None,
        probe_mistakes, passed=f"Exercise {number}: passed, all {len(cases)} cases "
        f"({len(hidden)} of them hidden): {exercise.title}.")
