"""Published numbers against computed ones: the rules of the book's registry.

A study prints a number with some digits; the number it stands for lies within half a unit of the
last printed digit. These helpers apply that rule (and its two variants for claims: an upper
bound ``"<1e-13"`` and an order of magnitude ``"~1e-12"``), and read the registry
``book/published_values.csv``, whose columns are ``seed, location, quantity, published, unit,
computed, verdict, chapter, note``.

The book prints its own numbers by the converse rule: only digits that the mathematics
determines. A quantity at round-off level (an error against a closed form, a residual that
is zero in exact arithmetic) changes with the BLAS kernel and the SIMD path of the machine, so
it is printed as a bound that is checked (:func:`below`), never as its noisy digits; the
registry stores such a ``computed`` value as ``"<1e-13"`` too.
"""

import csv
from decimal import Decimal, InvalidOperation

import numpy as np

COLUMNS = ("seed", "location", "quantity", "published", "unit", "computed", "verdict",
           "chapter", "note")
VERDICTS = ("reproduced", "reproduced-after-correction", "not-reproduced", "seed-error",
            "claim-refuted")


def half_unit(printed):
    """Half a unit in the last digit of a printed number: the rounding it may hide.

    Examples
    --------
    >>> half_unit("1.234"), half_unit("12"), half_unit("2.5e-3")
    (0.0005, 0.5, 5e-05)
    """
    try:
        exponent = Decimal(printed.strip()).as_tuple().exponent
    except InvalidOperation:
        raise ValueError(f"not a printed number: {printed!r}") from None
    return 0.5 * 10.0 ** exponent


def agrees(published, value):
    """Whether ``value`` bears out a published number or claim, to its printed digits.

    ``"1.942"``: within half a unit of the last printed digit; ``"<1e-13"``: below it;
    ``"~1e-12"`` (an order of magnitude): within a factor of ten of it.

    Examples
    --------
    >>> agrees("1.942", 1.9416), agrees("<1e-13", 2e-14), agrees("~1e-12", 2e-12), agrees("62", 61.4)
    (True, True, True, False)
    """
    if published.startswith("<"):
        return value < float(published[1:])
    if published.startswith("~"):
        return 0.1 <= abs(value) / float(published[1:]) <= 10
    return abs(value - float(published)) <= half_unit(published) * (1 + 1e-9)


def below(value, bound):
    """Check that a round-off-level quantity is below ``bound``, and return ``"< bound"``.

    The text to print in place of the quantity's own digits, which differ from machine to
    machine. ``value`` may be an array, or a list of arrays of different shapes: its largest
    magnitude is checked.

    Raises
    ------
    AssertionError
        If some ``|value|`` is not below ``bound`` (or is NaN): the claim to print is false.

    Examples
    --------
    >>> below(3.1e-16, 1e-13)
    '< 1e-13'
    >>> below([2e-15, -4e-15], 1e-14)
    '< 1e-14'
    >>> below([np.zeros(3), np.full(6, 1e-30)], 1e-25), below(0.04, 0.5), below(2e-6, 1e-5)
    ('< 1e-25', '< 0.5', '< 1e-5')
    """
    parts = value if isinstance(value, (list, tuple)) else [value]
    largest = max(np.max(np.abs(np.asarray(p, dtype=float)), initial=0.0) for p in parts)
    if not largest < bound:
        raise AssertionError(f"{largest!r} is not below {bound!r}")
    mantissa, _, exponent = f"{bound:g}".partition("e")
    return f"< {mantissa}" + (f"e{int(exponent)}" if exponent else "")


def read_registry(path, chapter=None):
    """The registry's rows (dicts keyed by :data:`COLUMNS`), optionally of one chapter only.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "registry.csv"
    >>> _ = path.write_text(",".join(COLUMNS) + "\\n000,Tab. 1,T,1.942,s,1.941626,reproduced,01,\\n")
    >>> [row["published"] for row in read_registry(path, chapter="01")]
    ['1.942']
    """
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        if tuple(reader.fieldnames or ()) != COLUMNS:
            raise ValueError(f"{path}: columns {reader.fieldnames}, expected {list(COLUMNS)}")
        return [row for row in reader if chapter is None or row["chapter"] == chapter]
