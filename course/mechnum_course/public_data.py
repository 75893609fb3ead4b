"""Write the stored answers of the public cases, ``mechnum/exercises/public.json``.

The student's package compares an answer with the expected answers of the public cases and with
what each typical mistake returns on them; it cannot compute either (it holds no solution).
This module computes both with the reference solutions and the mistakes, and writes them:

    python -m mechnum_course.public_data

after changing an exercise's cases, reference or mistakes (``tests/test_exercises.py`` checks
that the file is current).
"""

import json

from mechnum import exercises
from mechnum.exercises import _data
from mechnum_course import answers


def build():
    """The file's content: for each exercise, the expected answers, and the mistakes' answers
    on each case and each probe."""
    content = {}
    for number, exercise in exercises.EXERCISES.items():
        expected, mistaken = answers(number, exercise.cases())
        _, on_probes = answers(number, exercise.probes())
        content[number] = {
            "expected": [_data.encode(v) for v in expected],
            "mistakes": [{k: _data.encode(v) for k, v in row.items()} for row in mistaken],
            "probes": [{k: _data.encode(v) for k, v in row.items()} for row in on_probes]}
    return content


def main():
    text = json.dumps(build(), indent=1) + "\n"
    _data.PATH.write_text(text, encoding="utf-8")
    print(f"wrote {_data.PATH} ({len(text)} characters)")


if __name__ == "__main__":
    main()
