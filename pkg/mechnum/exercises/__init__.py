"""Self-checks for the exercises in which a student implements a piece of a chapter's method.

Each exercise has a number as the book prints it (``"3.1"``), a statement, a starter (the
signature and docstring of the function to write, with ``...`` for its body), and a check that
runs the student's function on the exercise's public cases and compares its answers with the
stored right ones:

>>> from mechnum import exercises
>>> sorted(exercises.CHECKS)[:3]
['1.1', '1.2', '1.3']
>>> def rk4_step(f, s, y, h):
...     return y + h * f(s, y)          # Euler's method, not RK4
>>> result = exercises.check("3.1", rk4_step)
>>> result.passed
False

The check never raises on a wrong answer. It runs the function in a child process, one case at
a time: an exception (``SystemExit`` and ``KeyboardInterrupt`` too), an endless loop (each case
has a time limit, :data:`TIME_LIMIT`, after which the child is killed) or an answer of the wrong
kind (a float where an integer is due, a complex number, an object that only pretends to be a
number) is reported in ``result.message``, with the input it failed on and the likely mistake;
nothing the function does reaches the check itself. It raises ``ValueError`` only on a
malformed call (an unknown exercise).

This package holds what a student may hold: the statements, the starters, the public cases and
their expected answers. The reference solutions, the hidden cases a grade uses, and the grader
are the instructors' (the book's repository, ``course/``).

What a chapter's notebook holds for an exercise, in this order: the ``{exercise}`` directive,
labelled, holding :func:`statement`; the starter cell, :func:`starter`; in the book, the gated
solution; the check cell, :func:`check_code`, whose output is the verdict. :func:`cells` returns
those a student sees. The code cells carry ``{"mechnum": {"exercise": number, "role": role}}``
in their metadata, ``role`` one of :data:`ROLES`, which the student edition and the grader read.
"""

from mechnum.exercises import _ch1, _ch2, _ch3, _ch4, _ch5, _ch6, _ch7, _data, _harness
from mechnum.exercises._harness import TIME_LIMIT, Result

__all__ = ["CHECKS", "EXERCISES", "ROLES", "TIME_LIMIT", "Result", "cells", "check",
           "check_cases", "check_code", "starter", "statement"]

EXERCISES = {e.number: e for e in (
    _ch1.LOOP, _ch1.NEWTON, _ch1.UPDATE, _ch2.SOR, _ch2.LSTSQ, _ch3.RK4, _ch3.SHOOTING,
    _ch4.COMPANION, _ch4.PRR3_NEWTON, _ch5.ELLIPTIC, _ch5.PIN, _ch5.KRAWCZYK, _ch6.INDEX,
    _ch6.RIGID, _ch7.COEFFICIENTS, _ch7.FORCE)}
"""Every self-checked exercise by its number: its statement, starter, public cases, the form
of its answer, its typical mistakes and its points."""

CHECKS = {number: (lambda answer, n=number: check(n, answer)) for number in EXERCISES}
"""Each exercise's check, by its number as the book prints it: ``CHECKS["1.2"](answer)`` is
``check("1.2", answer)``."""

ROLES = ("starter", "solution", "check")
"""The roles of an exercise's code cells, in the notebook's metadata ``mechnum.role``."""


def _exercise(number):
    if not isinstance(number, str) or number not in EXERCISES:
        raise ValueError(f"no self-checked exercise {number!r}; the exercises are "
                         f"{', '.join(EXERCISES)} (numbers are strings, as the book prints "
                         "them)")
    return EXERCISES[number]


def check(number: str, answer: object) -> Result:
    """Run the check of exercise ``number`` on the student's ``answer`` (a function).

    Parameters
    ----------
    number : str
        The exercise's number as the book prints it, ``"1.2"``.
    answer : callable
        The student's function.

    Returns
    -------
    Result
        ``passed`` and a ``message`` (it displays as its message).

    Raises
    ------
    ValueError
        If there is no such exercise.

    Examples
    --------
    >>> from mechnum import exercises
    >>> def one_sor_sweep(A, b, x, omega):
    ...     ...
    >>> exercises.check("2.1", one_sor_sweep).message.split(".")[0]
    'Exercise 2'
    >>> exercises.check("2.1", one_sor_sweep).passed
    False
    """
    exercise = _exercise(number)
    if not callable(answer):
        return _harness.not_a_function(exercise, answer)
    expected, mistakes, probe_mistakes = _data.public(number)
    cases = exercise.cases()
    outcomes = ((case, _harness.run(exercise, answer, case)) for case in cases)
    probes = lambda: [(p, _harness.run(exercise, answer, p)) for p in exercise.probes()]  # noqa: E731
    return _harness.judge(exercise, outcomes, expected, lambda k: mistakes[k], probes,
                          probe_mistakes)


def check_cases(number: str, answer: object, cases: list, expected: list) -> Result:
    """Run the student's ``answer`` on the given ``cases`` of exercise ``number`` and compare it
    with their ``expected`` answers (as :func:`check` does with the public ones): an nbgrader
    test cell holds an exercise's hidden cases and their answers, and calls this.

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum import exercises
    >>> from mechnum.exercises._harness import Case
    >>> case = Case("y' = y from 1, h = 1", (lambda s, y: y, 0.0, np.array([1.0]), 1.0))
    >>> exercises.check_cases("3.1", lambda f, s, y, h: y + h * f(s, y), [case],
    ...                       [np.array([2.708333333333333])]).passed
    False
    """
    exercise = _exercise(number)
    if not callable(answer):
        return _harness.not_a_function(exercise, answer)
    if not isinstance(cases, (list, tuple)) or not all(isinstance(c, _harness.Case)
                                                       for c in cases):
        raise ValueError(f"cases must be a list of Case, got {type(cases).__name__}")
    if not isinstance(expected, (list, tuple)) or len(cases) != len(expected):
        raise ValueError(f"expected must be a list of one answer per case ({len(cases)}), "
                         f"got {type(expected).__name__}")
    outcomes = ((case, _harness.run(exercise, answer, case)) for case in cases)
    return _harness.judge(exercise, outcomes, list(expected), lambda k: {})


def starter(number: str) -> str:
    """The starter cell of exercise ``number``: signature, docstring, and ``...`` for the body.

    Examples
    --------
    >>> from mechnum import exercises
    >>> print(exercises.starter("3.1").splitlines()[0])
    def rk4_step(f, s, y, h):
    >>> exercises.starter("3.1").rstrip().endswith("...")
    True
    """
    return _exercise(number).starter


def statement(number: str) -> str:
    """The statement of exercise ``number`` (Markdown, for the ``{exercise}`` directive).

    Examples
    --------
    >>> from mechnum import exercises
    >>> exercises.statement("5.3").startswith("**Implement it yourself.**")
    True
    """
    return _exercise(number).statement


def check_code(number: str) -> str:
    """The check cell of exercise ``number``.

    Examples
    --------
    >>> from mechnum import exercises
    >>> exercises.check_code("1.2")
    'exercises.check("1.2", newton_damped)'
    """
    return f'exercises.check("{number}", {_exercise(number).name})'


def markdown_cell(number: str, source: str, part: str) -> dict:
    """A Markdown cell of exercise ``number`` (a dictionary in the notebook format)."""
    return {"cell_type": "markdown", "id": f"ex{number.replace('.', '-')}-{part}",
            "metadata": {}, "source": source}


def code_cell(number: str, source: str, role: str) -> dict:
    """A code cell of exercise ``number`` with its role in the metadata."""
    return {"cell_type": "code", "id": f"ex{number.replace('.', '-')}-{role}",
            "execution_count": None, "metadata": {"mechnum": {"exercise": number, "role": role}},
            "source": source.rstrip("\n"), "outputs": []}


def cells(number: str) -> list[dict]:
    """The cells of exercise ``number`` that a student sees, in order, as dictionaries in the
    notebook format (``nbformat.from_dict`` accepts them): the exercise, the starter, the
    check. (The book's chapters also hold the gated solution between the starter and the
    check: the instructors' package, ``mechnum_course.cells``, gives all of them.)

    Examples
    --------
    >>> from mechnum import exercises
    >>> [cell["cell_type"] for cell in exercises.cells("4.1")]
    ['markdown', 'code', 'code']
    >>> exercises.cells("4.1")[0]["source"].splitlines()[:2]
    ['```{exercise}', ':label: ch4-ex-companion']
    """
    exercise = _exercise(number)
    return [markdown_cell(number, f"```{{exercise}}\n:label: {exercise.label}\n\n"
                                  f"{exercise.statement}\n```", "exercise"),
            code_cell(number, starter(number), "starter"),
            code_cell(number, check_code(number), "check")]
