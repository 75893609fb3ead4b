"""What the instructors hold of an exercise: its reference solution and its typical mistakes."""

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Solution:
    """The reference solution of an exercise, its typical mistakes as functions (by the names
    of the public catalogue, whose hints the student's package holds), and ``forbidden``: the
    dotted names of the functions an answer may not call, the package's own solution of the
    exercise and the library functions its statement forbids (a call fails the answer).
    ``expected``, when given, computes the expected answers instead of the reference: the
    exact answer that the reference only encloses (exercise 5.3)."""

    reference: object
    mistakes: dict = field(default_factory=dict)
    forbidden: tuple = ()
    expected: object = None
