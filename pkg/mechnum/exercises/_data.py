"""The stored answers of the public cases: ``public.json`` beside this module.

For each exercise, the expected answer of each public case, and what each typical mistake
returns on each case and each probe, as plain values (floats, ints, strings, float arrays and
tuples of them). The instructors' package writes the file from its reference solutions and
mistaken implementations (``python -m mechnum_course.public_data``) and tests that it is
current; the student's package only reads it.
"""

import functools
import json
from pathlib import Path

import numpy as np

from mechnum.exercises import _answers

PATH = Path(__file__).with_name("public.json")


def encode(value):
    """A plain value as JSON data (arrays and tuples tagged).

    Examples
    --------
    >>> encode((np.array([1.5, 2.0]), 3, "unique"))
    {'tuple': [{'array': [1.5, 2.0], 'shape': [2]}, 3, 'unique']}
    """
    if isinstance(value, np.ndarray):
        return {"array": value.astype(float).ravel().tolist(), "shape": list(value.shape)}
    if isinstance(value, tuple):
        return {"tuple": [encode(v) for v in value]}
    if isinstance(value, _answers.Raises):
        return {"raises": value.name}
    if value is None or type(value) in (bool, int, float, str):
        return value
    raise TypeError(f"cannot store a {type(value).__name__}")


def decode(data):
    """The inverse of :func:`encode`.

    Examples
    --------
    >>> decode(encode((np.array([1.5, 2.0]), 3)))
    (array([1.5, 2. ]), 3)
    """
    if isinstance(data, dict) and "array" in data:
        return np.array(data["array"], dtype=float).reshape(data["shape"])
    if isinstance(data, dict) and "tuple" in data:
        return tuple(decode(v) for v in data["tuple"])
    if isinstance(data, dict) and "raises" in data:
        return _answers.Raises(data["raises"])
    return data


@functools.cache
def _load():
    return json.loads(PATH.read_text(encoding="utf-8"))


def public(number):
    """``(expected, mistakes, probes)`` of exercise ``number``: the expected answer of each
    public case, and ``{mistake name: answer}`` on each case and on each probe."""
    entry = _load()[number]
    def answers(rows):
        return [{name: decode(v) for name, v in row.items()} for row in rows]
    return ([decode(v) for v in entry["expected"]], answers(entry["mistakes"]),
            answers(entry["probes"]))
