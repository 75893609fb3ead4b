"""What the instructors hold of an exercise: its reference solution and its typical mistakes."""

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Solution:
    """The reference solution of an exercise, its typical mistakes as functions (by the names
    of the public catalogue, whose hints the student's package holds), and ``forbidden``: the
    dotted names of the functions an answer may not call, the package's own solution of the
    exercise and the library functions its statement forbids (a call fails the answer)."""

    reference: object
    mistakes: dict = field(default_factory=dict)
    forbidden: tuple = ()
