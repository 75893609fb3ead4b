"""The reference solutions of the self-checked exercises and their typical mistakes, as
functions: what the student's package (``mechnum.exercises``) must not hold.

``SOLUTIONS[number]`` is a :class:`Solution`: ``reference``, the function the student writes;
``mistakes``, ``{name: mistaken function}`` by the names of the public catalogue; ``forbidden``,
the functions an answer may not call.
"""

from mechnum_course.solutions import _ch1, _ch2, _ch3, _ch4, _ch5, _ch6, _ch7
from mechnum_course.solutions._solution import Solution

__all__ = ["SOLUTIONS", "Solution"]

SOLUTIONS = {**_ch1.SOLUTIONS, **_ch2.SOLUTIONS, **_ch3.SOLUTIONS, **_ch4.SOLUTIONS,
             **_ch5.SOLUTIONS, **_ch6.SOLUTIONS, **_ch7.SOLUTIONS}
