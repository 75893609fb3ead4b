"""Run a student's function on an exercise's cases, in the sandbox, from its source alone.

The grader copies this file, the hidden cases' inputs (``hidden.py``) and a job (``job.json``:
the exercise, the function's name and source, the functions it may not call) into a fresh
folder and runs ``python runner.py FOLDER`` there, confined (:mod:`._sandbox`). This process
imports the student's package and the cases' inputs, never the instructors' package (the import
fails, and reading its files is denied): it holds no expected answer. It defines the function
from its source, then, for each public case, each hidden case and each probe in turn, writes
one record to the grader: what the function did, as :mod:`mechnum.exercises._child` reports it.
The grader reads each record within the case's time limit, or kills this process.

Before the student's source runs, every function it may not call (the package's own solution of
the exercise, the library functions its statement forbids) is replaced, wherever a module holds
it, by one that ends this process at once with :data:`DELEGATED` as its exit status, and any
import of the instructors' package does the same: an answer that delegates fails, whatever it
catches.
"""

import copy
import importlib.abc
import json
import os
import struct
import sys

DELEGATED = 86
"""The exit status of a runner whose function called a function it may not call."""


class _Refuse(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] == "mechnum_course":
            _delegated(name)
        return None


def _delegated(name):
    try:
        os.write(_OUT, b"D" + struct.pack("<I", len(name.encode())) + name.encode())
    finally:
        os._exit(DELEGATED)


def _forbid(dotted):
    """Replace the function named ``dotted`` in every loaded module that holds it."""
    import importlib

    module, _, attribute = dotted.rpartition(".")
    try:
        original = getattr(importlib.import_module(module), attribute)
    except (ImportError, AttributeError):
        return

    def refused(*args, **kwargs):
        _delegated(dotted)
    for loaded in list(sys.modules.values()):
        for key, value in list(getattr(loaded, "__dict__", {}).items()):
            if value is original:
                setattr(loaded, key, refused)


def _send(data, kind=b"R"):
    view = memoryview(kind + struct.pack("<I", len(data)) + data)
    while view:
        view = view[os.write(_OUT, view):]


def main(folder):
    import importlib.util

    import numpy as np  # noqa: F401 -- imported before the student's code can change it

    from mechnum import exercises
    from mechnum.exercises import _child, _harness

    job = json.loads(open(os.path.join(folder, "job.json"), encoding="utf-8").read())
    spec = importlib.util.spec_from_file_location("hidden", os.path.join(folder, "hidden.py"))
    hidden = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hidden)
    exercise = exercises.EXERCISES[job["number"]]
    cases = exercise.cases() + hidden.HIDDEN[job["number"]]() + list(exercise.probes())
    sys.meta_path.insert(0, _Refuse())
    for dotted in job["forbidden"]:
        _forbid(dotted)
    namespace = {"__name__": "submission"}
    try:
        exec(compile(job["source"], "<submission>", "exec"), namespace)
        function = namespace[job["name"]]
    except BaseException as error:  # noqa: B036 -- the student's source, whatever it raises
        _send(_child.pack(_child.Outcome("raised", error=type(error).__name__,
                                          message=f"(defining the function) {error}"[:2000])))
        return
    _send(b"", b"S")  # started: the cases' time limits run from here
    for case in cases:
        args = copy.deepcopy(case.args)
        _send(_child.report(function, args, exercise.parameters, _harness.changed))


if __name__ == "__main__":
    _OUT = os.dup(1)  # the records' channel; the student's prints go nowhere
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.dup2(null, 2)
    main(sys.argv[1])
    os._exit(0)
