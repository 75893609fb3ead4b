"""The instructors' package of *Numerical Methods for Mechanisms*: what a student must not hold.

The student's package, ``mechnum.exercises``, holds the exercises' statements, starters and
public cases with their expected answers. This package adds the reference solutions and the
typical mistakes as functions (:mod:`mechnum_course.solutions`), the hidden cases
(:mod:`mechnum_course.hidden`), the grader (:mod:`mechnum_course.grading`, ``make grade``), the
student edition's builder (:mod:`mechnum_course.student`, ``make book-student``) and the
nbgrader course (:mod:`mechnum_course.nbgrader`, ``make nbgrader``). The book's environment
installs it; the book serves it to nobody.

>>> import mechnum_course
>>> mechnum_course.check("3.1", mechnum_course.reference("3.1")).passed
True
"""

import copy
import functools
import inspect
import textwrap
import warnings

import numpy as np

from mechnum import exercises
from mechnum.exercises import _harness
from mechnum.exercises._answers import Raises
from mechnum_course.hidden import HIDDEN
from mechnum_course.solutions import SOLUTIONS

__all__ = ["HIDDEN", "SOLUTIONS", "answers", "cells", "check", "reference", "solution"]


def reference(number):
    """The reference solution of exercise ``number``: the function the student writes.

    Examples
    --------
    >>> import numpy as np
    >>> rk4_step = reference("3.1")
    >>> float(rk4_step(lambda s, y: y, 0.0, np.array([1.0]), 1.0)[0])  # e = 2.718...
    2.708333333333333
    """
    exercises.statement(number)  # a ValueError for an unknown exercise
    return SOLUTIONS[number].reference


def solution(number):
    """The solution cell of exercise ``number``: the reference's source, which fills the
    starter in.

    Examples
    --------
    >>> from mechnum import exercises
    >>> solution("1.2").startswith(exercises.starter("1.2").rstrip()[:-3])
    True
    """
    return textwrap.dedent(inspect.getsource(reference(number)))


def answers(number, cases):
    """The reference's answer on each case, converted as an answer is (the expected answers),
    and ``{mistake: its answer}`` on each case (``None`` where the mistake raises)."""
    exercise, found = exercises.EXERCISES[number], SOLUTIONS[number]
    expected, mistaken = [], []
    for case in cases:
        try:  # the reference, or the exact answer where the reference approximates it
            value = (found.expected or found.reference)(*copy.deepcopy(case.args))
        except Exception as error:  # the statement asks for this exception here
            expected.append(Raises(type(error).__name__))
        else:
            expected.append(exercise.returns.convert(value, "the reference"))
        row = {}
        for name, function in found.mistakes.items():
            try:  # a mistake may diverge: its warnings say nothing to the grader
                with warnings.catch_warnings(), np.errstate(all="ignore"):
                    warnings.simplefilter("ignore")
                    got = function(*copy.deepcopy(case.args))
                row[name] = exercise.returns.convert(got, name)
            except Exception:
                row[name] = None
        mistaken.append(row)
    return expected, mistaken


def check(number, answer, *, hidden=True):
    """The check of exercise ``number`` on the public cases and (``hidden=True``) the hidden
    ones, in this process (the grader runs the answer in a sandbox instead)."""
    exercise = exercises.EXERCISES[number]
    if not callable(answer):
        return _harness.not_a_function(exercise, answer)
    cases, probes, expected, mistaken, on_probes = _answered(number, hidden)
    outcomes = ((case, _harness.run(exercise, answer, case)) for case in cases)
    return _harness.judge(exercise, outcomes, expected, lambda k: mistaken[k],
                          lambda: [(p, _harness.run(exercise, answer, p)) for p in probes],
                          on_probes)


@functools.cache
def _answered(number, hidden):
    """The cases and probes of an exercise with the references' and mistakes' answers."""
    exercise = exercises.EXERCISES[number]
    cases = exercise.cases() + (HIDDEN[number]() if hidden else [])
    probes = exercise.probes()
    return (cases, probes, *answers(number, cases), answers(number, probes)[1])


def cells(number):
    """The cells of exercise ``number`` in a chapter of the book, in order, as dictionaries
    in the notebook format: the exercise, the starter, the gated solution, the check (the
    student edition removes the solution).

    Examples
    --------
    >>> [cell["cell_type"] for cell in cells("4.1")]
    ['markdown', 'code', 'markdown', 'code', 'markdown', 'code']
    """
    label = exercises.EXERCISES[number].label
    shown = exercises.cells(number)
    return [shown[0], shown[1],
            exercises.markdown_cell(number, f"```{{solution-start}} {label}\n:class: dropdown\n"
                                            "```", "solution-start"),
            exercises.code_cell(number, solution(number), "solution"),
            exercises.markdown_cell(number, "```{solution-end}\n```", "solution-end"),
            shown[2]]
