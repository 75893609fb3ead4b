"""How a self-check judges a student's function: its cases, the expected answers, the feedback.

An :class:`Exercise` holds what a student may see: the statement, the starter, the public cases
(the inputs), a comparison of an answer with the expected one, the form the answer must have
(:mod:`mechnum.exercises._answers`), and the typical mistakes by name and hint. The expected
answers of the public cases, and what each typical mistake returns on them, are stored data
(``public.json``, written by the instructors' package from the reference solutions, which the
student's package does not hold). When an answer is wrong, the mistake whose stored answer it
matches names the likely mistake.

:func:`judge` is the one place that turns what a function did into a verdict: the self-check
(:func:`mechnum.exercises.check`, the function run in a child process of the notebook) and the
grader (the function run in a sandbox, on the hidden cases too) both use it.
"""

import copy
import re
from dataclasses import dataclass

import numpy as np

from mechnum.exercises import _answers, _child

TIME_LIMIT = 2.0
"""Seconds a student's function may take on one case (the references take milliseconds): beyond
it the process running it is killed and the check reports an endless loop."""


@dataclass(frozen=True)
class Case:
    """One input of a check: what it is, in words, and the arguments of the function."""

    label: str
    args: tuple


@dataclass(frozen=True)
class Mistake:
    """A typical wrong implementation, by name, with the hint that a student who made it needs
    (what it returns on the public cases is stored data)."""

    name: str
    hint: str


@dataclass(frozen=True)
class Exercise:
    """An implement-it-yourself exercise and its self-check.

    ``compare(expected, got)`` returns ``None`` when ``got`` (already converted by ``returns``,
    a spec of :mod:`mechnum.exercises._answers`) is right, else what is wrong, in words.
    ``probes()`` gives extra inputs that only serve to tell the mistakes apart. ``points`` is
    what the exercise is worth in a grade. ``forbidden`` names the library functions that the
    statement rules out (``"numpy.linalg.lstsq"``): the check runs the function with them
    unavailable. ``agree(mistaken, got)``, when given, says whether an answer is a mistake's
    (``compare`` by default; for a comparison that is not symmetric).
    """

    number: str
    label: str
    title: str
    statement: str
    starter: str
    cases: object
    compare: object
    returns: object
    mistakes: tuple = ()
    hint: str = ""
    time_limit: float = TIME_LIMIT
    probes: object = tuple
    points: float = 1
    forbidden: tuple = ()
    agree: object = None

    @property
    def name(self):
        """The name of the function the student writes (the starter's)."""
        return re.match(r"def (\w+)\(", self.starter).group(1)

    @property
    def parameters(self):
        """The names of the function's parameters, from the starter."""
        head = re.match(r"def \w+\((.*?)\)", self.starter, re.S).group(1)
        return tuple(p.split("=")[0].strip() for p in head.split(",") if p.strip())


@dataclass(frozen=True)
class Result:
    """The verdict of a check: ``passed`` and a ``message`` that says what failed, on which
    input, and the likely mistake. It displays as its message."""

    number: str
    passed: bool
    message: str

    def __repr__(self):
        return self.message

    __str__ = __repr__


def changed(before, after):
    """Whether an argument was modified in place (arrays compared element by element)."""
    if isinstance(before, np.ndarray):
        return (not isinstance(after, np.ndarray) or before.shape != after.shape
                or not np.array_equal(before, after, equal_nan=True))
    if isinstance(before, (list, tuple)):
        return any(changed(b, a) for b, a in zip(before, after))
    return False


def run(exercise, function, case, seconds=None):
    """What ``function`` does on ``case``, run in a child process: an Outcome."""
    return _child.call(function, copy.deepcopy(case.args), seconds or exercise.time_limit,
                       exercise.parameters, changed, exercise.forbidden)


def convert(exercise, outcome):
    """The answer an Outcome of kind ``"value"`` holds, converted (``WrongForm`` if it is not of
    the documented kind)."""
    return exercise.returns.convert(_answers.loads(outcome.value), "your answer")


def _problem(exercise, outcome, expected, where):
    """What is wrong with an outcome, in words (``None``: right), and the converted answer."""
    name = exercise.name
    if outcome.kind == "forbidden":
        return (f"{where}, your function called {outcome.message}, which this exercise rules "
                "out: write the method yourself."), None
    if isinstance(expected, _answers.Raises):
        if outcome.kind == "raised" and outcome.error == expected.name:
            return None, None  # the exception the statement asks for
        if outcome.kind in ("value", "raised"):
            did = ("returned" if outcome.kind == "value" else
                   f"raised {outcome.error}: {outcome.message}".rstrip(": ") + ",")
            return (f"{where}, your function {did} where it must raise {expected.name} (the "
                    "statement says when)."), None
    if outcome.kind == "timeout":
        return (f"{where}, your function ran for more than {exercise.time_limit:g} s and was "
                "stopped: an endless loop? Every loop needs a test that ends it, and an "
                "iteration a bound on its count."), None
    if outcome.kind == "raised":
        what = {"SystemExit": " (it called sys.exit, which would end the notebook's kernel)",
                "KeyboardInterrupt": " (it was interrupted)"}.get(outcome.error, "")
        return (f"{where}, your function raised {outcome.error}{what}: "
                f"{outcome.message}").rstrip(": "), None
    if outcome.kind == "died":
        return f"{where}, {outcome.message}", None
    if outcome.changed:
        return (f"{where}, your function changed its argument `{outcome.changed[0]}` in place; "
                "work on a copy."), None
    try:
        value = _answers.loads(outcome.value)
        if value is None:
            return (f"{where}, `{name}` returned None: its body is still `...` (or lacks a "
                    "`return`). Write it, then run this cell again."), None
        got = exercise.returns.convert(value, "your answer")
        problem = exercise.compare(expected, got)
    except _answers.WrongForm as error:  # a message about the answer's type, no hint
        return f"{where}: {error}.", _WRONG_FORM
    except Exception as error:  # a comparison that cannot read the answer
        return (f"{where}: the answer has the wrong form ({type(error).__name__}: {error}).",
                _WRONG_FORM)
    return (f"{where}: {problem}." if problem else None), got


_WRONG_FORM = object()  # what _problem returns for an answer of the wrong kind


def agrees(exercise, mistaken, got):
    """Whether an answer equals a mistake's stored (or computed) answer."""
    try:
        if mistaken is None or isinstance(mistaken, _answers.Raises):
            return False
        if exercise.agree is not None:
            return bool(exercise.agree(mistaken, got))
        return exercise.compare(mistaken, got) is None
    except Exception:
        return False


def judge(exercise, outcomes, expected, mistakes_on, probe_outcomes=(), probe_mistakes=(),
          head=None, passed=None):
    """The :class:`Result` of a function's outcomes on the cases.

    Parameters
    ----------
    exercise : Exercise
    outcomes : iterable of (Case, Outcome)
        The function's outcome on each case, in order (consumed until one is wrong).
    expected : sequence
        The right answer of each case.
    mistakes_on : callable
        ``mistakes_on(k)``: ``{mistake name: its answer}`` on case ``k``.
    probe_outcomes : callable, optional
        Called only when a case is wrong: the function's outcomes on the probes.
    probe_mistakes : sequence of dict
        ``{mistake name: its answer}`` on each probe.
    head, passed : str, optional
        The message's beginning, and the message of a pass.
    """
    head = head or f"Exercise {exercise.number}"
    count = 0
    for k, (case, outcome) in enumerate(outcomes):
        problem, got = _problem(exercise, outcome, expected[k], f"On {case.label}")
        count += 1
        if problem:
            plain = (outcome.kind == "forbidden" or got is _WRONG_FORM
                     or isinstance(expected[k], _answers.Raises))
            hint = "" if plain else _diagnose(exercise, got, mistakes_on(k), probe_outcomes,
                                              probe_mistakes)
            return Result(exercise.number, False, f"{head}: not yet. {problem} {hint}".rstrip())
    return Result(exercise.number, True, passed or f"{head}: passed, all {count} cases "
                  f"({exercise.title}).")


def _diagnose(exercise, got, mistaken, probe_outcomes, probe_mistakes):
    hints = {m.name: m.hint for m in exercise.mistakes}
    if got is not None:
        for name, answer in mistaken.items():
            if name in hints and agrees(exercise, answer, got):
                return f"Likely mistake, {name}: {hints[name]}"
    if probe_mistakes and probe_outcomes:
        answers = []
        for _, outcome in probe_outcomes():
            if outcome.kind != "value":
                return f"Hint: {exercise.hint}" if exercise.hint else ""
            try:
                answers.append(convert(exercise, outcome))
            except Exception:
                return f"Hint: {exercise.hint}" if exercise.hint else ""
        for name in hints:
            if all(agrees(exercise, p.get(name), a) for p, a in zip(probe_mistakes, answers)):
                return f"Likely mistake, {name}: {hints[name]}"
    return f"Hint: {exercise.hint}" if exercise.hint else ""


def not_a_function(exercise, answer):
    """The Result for an answer that is not a function."""
    return Result(exercise.number, False,
                  f"Exercise {exercise.number}: not yet. Pass the function itself, "
                  f"exercises.check({exercise.number!r}, {exercise.name}), "
                  f"not {type(answer).__name__!r}.")
