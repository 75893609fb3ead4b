"""Self-checks for the exercises in which a student implements a piece of a chapter's method.

Each exercise has a number as the book prints it (``"3.1"``), a statement, a starter (the
signature and docstring of the function to write, with ``...`` for its body), a reference
solution, and a check that runs the student's function on cases the student has not seen:

>>> from mechnum import exercises
>>> sorted(exercises.CHECKS)[:3]
['1.1', '1.2', '1.3']
>>> def rk4_step(f, s, y, h):
...     return y + h * f(s, y)          # Euler's method, not RK4
>>> result = exercises.check("3.1", rk4_step)
>>> result.passed
False
>>> exercises.check("3.1", exercises.reference("3.1")).passed
True

The check never raises on a wrong answer: an exception or an endless loop in the student's code
(each case has a time limit, :data:`TIME_LIMIT`) is reported in ``result.message``, with the input
it failed on and the likely mistake. It raises ``ValueError`` only on a malformed call (an
unknown exercise).

What a chapter's notebook holds for an exercise, in this order (:func:`cells` returns them):

1. a Markdown cell with the ``{exercise}`` directive, labelled, holding :func:`statement`;
2. the starter cell, :func:`starter`;
3. the gated solution: ``{solution-start}``, a code cell holding :func:`solution` (which fills
   the starter in), ``{solution-end}``;
4. the check cell, :func:`check_code`, whose output is the verdict.

The code cells carry ``{"mechnum": {"exercise": number, "role": role}}`` in their metadata,
``role`` one of :data:`ROLES`, which the student edition and the grader read.
"""

from mechnum.exercises import _ch1, _ch2, _ch3, _ch4, _ch5, _ch6, _ch7
from mechnum.exercises._harness import TIME_LIMIT, Result, run_check
from mechnum.exercises._harness import source as _source
from mechnum.exercises._harness import starter as _starter

__all__ = ["CHECKS", "ROLES", "TIME_LIMIT", "Result", "cells", "check", "check_code",
           "reference", "solution", "starter", "statement"]

_EXERCISES = (_ch1.LOOP, _ch1.NEWTON, _ch1.UPDATE, _ch2.SOR, _ch2.LSTSQ, _ch3.RK4, _ch3.SHOOTING,
              _ch4.COMPANION, _ch4.PRR3_NEWTON, _ch5.ELLIPTIC, _ch5.PIN, _ch5.KRAWCZYK,
              _ch6.INDEX, _ch6.RIGID, _ch7.COEFFICIENTS, _ch7.FORCE)

CHECKS = {exercise.number: (lambda answer, e=exercise: run_check(e, answer))
          for exercise in _EXERCISES}
"""Each exercise's check, by its number as the book prints it: ``CHECKS["1.2"](answer)`` is
``check("1.2", answer)``."""

ROLES = ("starter", "solution", "check")
"""The roles of an exercise's code cells, in the notebook's metadata ``mechnum.role``."""

_BY_NUMBER = {exercise.number: exercise for exercise in _EXERCISES}


def _exercise(number):
    if not isinstance(number, str) or number not in _BY_NUMBER:
        raise ValueError(f"no self-checked exercise {number!r}; the exercises are "
                         f"{', '.join(_BY_NUMBER)} (numbers are strings, as the book prints "
                         "them)")
    return _BY_NUMBER[number]


def check(number, answer):
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
    return run_check(_exercise(number), answer)


def reference(number):
    """The reference solution of exercise ``number``: the function the student writes.

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum import exercises
    >>> rk4_step = exercises.reference("3.1")
    >>> float(rk4_step(lambda s, y: y, 0.0, np.array([1.0]), 1.0)[0])  # e = 2.718...
    2.708333333333333
    """
    return _exercise(number).reference


def starter(number):
    """The starter cell of exercise ``number``: signature, docstring, and ``...`` for the body.

    Examples
    --------
    >>> from mechnum import exercises
    >>> print(exercises.starter("3.1").splitlines()[0])
    def rk4_step(f, s, y, h):
    >>> exercises.starter("3.1").rstrip().endswith("...")
    True
    """
    return _starter(_exercise(number).reference)


def solution(number):
    """The solution cell of exercise ``number``: the reference's source, which redefines the
    starter's function.

    Examples
    --------
    >>> from mechnum import exercises
    >>> exercises.solution("1.2").startswith(exercises.starter("1.2").rstrip()[:-3])
    True
    """
    return _source(_exercise(number).reference)


def statement(number):
    """The statement of exercise ``number`` (Markdown, for the ``{exercise}`` directive).

    Examples
    --------
    >>> from mechnum import exercises
    >>> exercises.statement("5.3").startswith("**Implement it yourself.**")
    True
    """
    return _exercise(number).statement


def check_code(number):
    """The check cell of exercise ``number``.

    Examples
    --------
    >>> from mechnum import exercises
    >>> exercises.check_code("1.2")
    'exercises.check("1.2", newton_damped)'
    """
    return f'exercises.check("{number}", {_exercise(number).name})'


def cells(number):
    """The cells of exercise ``number`` for a chapter's notebook, in order, as dictionaries in
    the notebook format (``nbformat.from_dict`` accepts them): the exercise, the starter, the
    gated solution, the check.

    Examples
    --------
    >>> from mechnum import exercises
    >>> [cell["cell_type"] for cell in exercises.cells("4.1")]
    ['markdown', 'code', 'markdown', 'code', 'markdown', 'code']
    >>> exercises.cells("4.1")[0]["source"].splitlines()[:2]
    ['```{exercise}', ':label: ch4-ex-companion']
    """
    exercise = _exercise(number)
    stem = "ex" + number.replace(".", "-")  # cell ids, unique in a notebook

    def markdown(text, part):
        return {"cell_type": "markdown", "id": f"{stem}-{part}", "metadata": {}, "source": text}

    def code(text, role):
        return {"cell_type": "code", "id": f"{stem}-{role}", "execution_count": None,
                "metadata": {"mechnum": {"exercise": number, "role": role}},
                "source": text.rstrip("\n"), "outputs": []}

    return [markdown(f"```{{exercise}}\n:label: {exercise.label}\n\n{exercise.statement}\n```",
                     "exercise"),
            code(starter(number), "starter"),
            markdown(f"```{{solution-start}} {exercise.label}\n:class: dropdown\n```",
                     "solution-start"),
            code(solution(number), "solution"),
            markdown("```{solution-end}\n```", "solution-end"),
            code(check_code(number), "check")]
