"""Published numbers against computed ones: the rules of the book's registry, and its one table.

The book's module, not the package's: every chapter imports it as ``published`` (the chapters run
in ``book/``), and the chapters' zip serves it beside them (``.ci/chapters_zip.py``).

A study prints a number with some digits; the number it stands for lies within half a unit of the
last printed digit. :func:`agrees` applies that rule, and its variants for claims:

* ``"1.942"``: within half a unit of the last printed digit, ``[1.9415, 1.9425]``;
* ``"0"``: an exact zero, which a computation meets to round-off (``|value| < 1e-12``); a zero
  printed with decimals (``"0.000"``) follows the half-unit rule;
* ``"<1e-13"``: an upper bound, ``|value| < 1e-13``;
* ``"~1e-12"``: an order of magnitude, "of the order of ``10^-12``": the power of ten nearest
  to ``|value|`` on a logarithmic scale is ``10^-12``, ``10^-12.5 <= |value| < 10^-11.5``
  (from ``3.2e-13`` to ``3.2e-12``).

The registry ``book/published_values.csv`` has one row per number a study publishes, with the
columns :data:`COLUMNS`: where the study prints it, the package's value (``computed``), a verdict
(:data:`VERDICTS`), and the ``finding``, a short id shared by every row that one demonstration
explains. :func:`check_row` asserts what a row claims; :func:`reproduction_table` checks and
renders a chapter's rows, the one reproduction table of every chapter.

The book prints its own numbers by the converse rule: only digits that the mathematics
determines. A quantity at round-off level (an error against a closed form, a residual that
is zero in exact arithmetic) changes with the BLAS kernel and the SIMD path of the machine, so
it is printed as a bound that is checked (:func:`below`), never as its noisy digits; the
registry stores such a ``computed`` value as ``"<1e-13"`` too.
"""

import csv
import numbers
from decimal import Decimal, InvalidOperation
from os import PathLike

import numpy as np

COLUMNS = ("seed", "location", "quantity", "published", "unit", "computed", "verdict",
           "chapter", "finding", "note")
VERDICTS = ("reproduced", "within-input-rounding", "reproduced-after-correction",
            "not-reproduced", "source-error", "claim-refuted")
"""The verdicts, from agreement to refutation:

* ``reproduced``: the package's value agrees with the published one to its printed digits;
* ``within-input-rounding``: it agrees once the study's inputs are taken unrounded, within the
  rounding of their printed digits (the study computed from more digits than it printed);
* ``reproduced-after-correction``: it agrees once an identified slip is corrected (a typo in an
  input, a garbled symbol); the note names it;
* ``not-reproduced``: the number does not follow from the study's own data and method;
* ``source-error``: the study itself is wrong there (a wrong formula, a bug in its code, a slip
  between two of its numbers);
* ``claim-refuted``: a claim (a ranking, an optimum, a cause) that the computation contradicts.
"""
AGREEING = ("reproduced", "within-input-rounding")
FINDING_COLUMNS = ("finding", "chapter", "seeds", "what", "where", "proof")
"""The columns of ``book/findings.csv``: one line per finding, its id (the registry's
``finding``), its chapter, the studies it concerns, what it is, where the study prints it, and
how the chapter proves it (one sentence each)."""
_EXACT_ZERO = 1e-12  # a printed "0" is met by round-off of unit-sized quantities
_EPS = float(np.finfo(float).eps)
_ROOT_10 = 10 ** 0.5  # an order of magnitude spans a factor sqrt(10) either way of its power


def half_unit(printed: str) -> float:
    """Half a unit in the last digit of a printed number: the rounding it may hide.

    Examples
    --------
    >>> half_unit("1.234"), half_unit("12"), half_unit("2.5e-3")
    (0.0005, 0.5, 5e-05)
    """
    try:
        number = Decimal(printed.strip())
    except (InvalidOperation, AttributeError):
        number = None
    if number is None or not number.is_finite():
        raise ValueError(f"not a printed number: {printed!r}")
    return 0.5 * 10.0 ** number.as_tuple().exponent


def _within_half_unit(value, printed):
    """``|value - printed| <= half a unit of its last digit``, allowing for the binary rounding
    of both numbers (the printed decimal is itself a float)."""
    number = float(printed)
    slack = 4 * _EPS * max(abs(value), abs(number))
    return bool(abs(value - number) <= half_unit(printed) + slack)


def is_claim(published: str) -> bool:
    """Whether a published text is a number or a numeric claim that :func:`agrees` can test.

    Examples
    --------
    >>> is_claim("1.942"), is_claim("<1e-13"), is_claim("~1e-12"), is_claim("n_y cos(theta)")
    (True, True, True, False)
    """
    if not isinstance(published, str):
        raise ValueError(f"published must be the printed text (a str), got {published!r:.80}")
    try:
        half_unit(published.lstrip("<~"))
    except ValueError:
        return False
    return True


def _number(value, name="value"):
    """``value`` as a float, if it is one real number (a Python or NumPy number, not text)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.number)) \
            or isinstance(value, np.complexfloating):
        raise ValueError(f"{name} must be a real number, got {value!r:.80}")
    return float(value)


def agrees(published: str, value: float) -> bool:
    """Whether ``value`` bears out a published number or claim, by the rules of the module.

    Raises
    ------
    ValueError
        If ``published`` is no printed number or numeric claim, or ``value`` is not a real
        number (NaN agrees with nothing).

    Examples
    --------
    >>> agrees("1.942", 1.9416), agrees("62", 61.4), agrees("0", 3e-17), agrees("0", 0.3)
    (True, False, True, False)
    >>> agrees("<1e-13", 2e-14), agrees("~1e-12", 2e-12), agrees("~1e-12", 5e-12)
    (True, True, False)
    """
    if not is_claim(published):
        raise ValueError(f"not a printed number or numeric claim: {published!r}")
    value = _number(value)
    if published.startswith("<"):
        return bool(abs(value) < float(published[1:]))
    if published.startswith("~"):
        magnitude = float(published[1:])
        return bool(magnitude / _ROOT_10 <= abs(value) < magnitude * _ROOT_10)
    if published.strip() in ("0", "-0", "+0"):
        return bool(abs(value) < _EXACT_ZERO)
    return _within_half_unit(value, published)


def below(value: object, bound: float) -> str:
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
    >>> below(3e-14 + 4e-14j, 1e-13)    # the magnitude of a complex number
    '< 1e-13'
    """
    bound = _number(bound, "bound")
    if not (np.isfinite(bound) and bound > 0):
        raise ValueError(f"bound must be a finite positive number, got {bound!r}")
    parts = value if isinstance(value, (list, tuple)) else [value]
    try:
        largest = max(np.max(np.abs(np.asarray(p)).astype(float), initial=0.0) for p in parts)
    except (TypeError, ValueError):
        raise ValueError(f"value must be numbers (arrays), got {value!r:.80}") from None
    if not largest < bound:
        raise AssertionError(f"{largest!r} is not below {bound!r}")
    mantissa, _, exponent = f"{bound:g}".partition("e")
    return f"< {mantissa}" + (f"e{int(exponent)}" if exponent else "")


def _read(path, columns):
    if not isinstance(path, (str, PathLike)):
        raise ValueError(f"path must be a file name (str or path), got {path!r:.80}")
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        if tuple(reader.fieldnames or ()) != columns:
            raise ValueError(f"{path}: columns {reader.fieldnames}, expected {list(columns)}")
        return list(reader)


def read_findings(path: str | PathLike) -> list[dict]:
    """The findings (dicts keyed by :data:`FINDING_COLUMNS`), in the file's order.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "findings.csv"
    >>> _ = path.write_text(",".join(FINDING_COLUMNS) + "\\nch1-t,ch1,002,T is 2T,slide 3,sympy\\n")
    >>> [f["what"] for f in read_findings(path)]
    ['T is 2T']
    """
    return _read(path, FINDING_COLUMNS)


def read_registry(path: str | PathLike, chapter: str | None = None) -> list[dict]:
    """The registry's rows (dicts keyed by :data:`COLUMNS`), optionally of one chapter only.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "registry.csv"
    >>> _ = path.write_text(",".join(COLUMNS)
    ...                     + "\\n000,Tab. 1,T,1.942,s,1.941626,reproduced,01,,\\n")
    >>> [row["published"] for row in read_registry(path, chapter="01")]
    ['1.942']
    """
    return [row for row in _read(path, COLUMNS) if chapter is None or row["chapter"] == chapter]


def read_published(path: str | PathLike, chapter: str) -> dict[str, str]:
    """The numbers a chapter's study publishes, as printed: ``{quantity: published text}``.

    For a chapter that works with the study's printed numbers (a table it audits, a value it
    quotes), so that no published number is typed into a notebook or a test.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "registry.csv"
    >>> _ = path.write_text(",".join(COLUMNS)
    ...                     + "\\n000,Tab. 1,T,1.942,s,1.941626,reproduced,01,,\\n")
    >>> read_published(path, "01")
    {'T': '1.942'}
    """
    return {row["quantity"]: row["published"] for row in read_registry(path, chapter)}


def check_row(row: dict, value: float | None) -> None:
    """Assert what a registry row says of ``value``, the package's number for it (or None).

    * The ``computed`` column is what the package computes: ``value`` lies within half a unit of
      its last digit, or below the bound ``"<1e-13"`` that it stores for a round-off-level value;
      a blank ``computed`` (a claim with no single number) means the package has no value.
    * An agreeing verdict (:data:`AGREEING`) agrees with ``published``; any other verdict on a
      numeric ``published`` does not: the verdict is checked in both directions.

    Raises
    ------
    AssertionError
        Naming the row and the numbers, if the row's claim is false.

    Examples
    --------
    >>> row = dict(quantity="T", published="1.942", computed="1.941626", verdict="reproduced")
    >>> check_row(row, 1.9416259)
    >>> check_row(dict(row, verdict="not-reproduced"), 1.9416259)
    Traceback (most recent call last):
    ...
    AssertionError: T: published 1.942 agrees with 1.9416259, yet the verdict is not-reproduced
    """
    if not isinstance(row, dict):
        raise ValueError(f"row must be a registry row (a dict), got {row!r:.80}")
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    value = None if value is None else _number(value)
    name, computed, published = row["quantity"], row["computed"], row["published"]
    if not computed:
        if value is not None:
            raise AssertionError(f"{name}: computed is blank, yet the package gives {value!r}")
    elif value is None or not np.isfinite(value):
        raise AssertionError(f"{name}: the registry says {computed}, the package gives {value!r}")
    elif computed.startswith("<"):
        if not abs(value) < float(computed[1:]):
            raise AssertionError(f"{name}: the registry bounds it by {computed}, "
                                 f"the package gives {value!r}")
    elif not _within_half_unit(value, computed):
        raise AssertionError(f"{name}: the registry says {computed}, the package gives {value!r}")
    if row["verdict"] in AGREEING:
        if value is None or not agrees(published, value):
            raise AssertionError(f"{name}: published {published} and computed {value!r} "
                                 f"disagree, yet the verdict is {row['verdict']}")
    elif value is not None and is_claim(published) and agrees(published, value):
        raise AssertionError(f"{name}: published {published} agrees with {value!r}, "
                             f"yet the verdict is {row['verdict']}")


class Markdown:
    """Markdown text that a notebook displays rendered, and a console prints as it is."""

    def __init__(self, text: str):
        self.text = text

    def _repr_markdown_(self):
        return self.text

    def __repr__(self):
        return self.text


def _cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def reproduction_table(chapter: str, values: dict,
                       path: str | PathLike = "published_values.csv") -> Markdown:
    """Check a chapter's registry rows against the package, and render them as a table.

    Every row of ``chapter`` is checked by :func:`check_row` with ``values[quantity]``; the
    table shows, for each, where the study prints it, the quantity, the finding that explains it
    (first after the quantity, so that a reader who scrolls no further still sees it), the
    published and computed numbers and the verdict. A lecture page shows the narrow
    :func:`verdict_summary` instead; the full table belongs on the study page.

    Parameters
    ----------
    chapter : str
        The chapter's notebook name, as in the registry's ``chapter`` column.
    values : dict
        The package's numbers, keyed by ``quantity`` (a mechanism module's ``reproduce()``).
    path : str or path-like, optional
        The registry (a chapter runs in ``book/``, beside it).

    Returns
    -------
    Markdown

    Raises
    ------
    ValueError
        If the registry has no row for ``chapter``.
    AssertionError
        If a row's claim is false (see :func:`check_row`).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "registry.csv"
    >>> _ = path.write_text(",".join(COLUMNS) + "\\n000,Sec. 4,T,1.942,s,1.941626,reproduced,"
    ...                     "ch1,,\\n000,Sec. 4,T2,1.883,s,1.941626,source-error,ch1,T-2T,slip\\n")
    >>> print(reproduction_table("ch1", {"T": 1.9416259, "T2": 1.9416259}, path))
    | where | quantity | finding | published | computed | verdict |
    |---|---|---|---|---|---|
    | Sec. 4 | T |  | 1.942 s | 1.941626 | reproduced |
    | Sec. 4 | T2 | T-2T | 1.883 s | 1.941626 | source-error |
    """
    lines = ["| where | quantity | finding | published | computed | verdict |",
             "|---|---|---|---|---|---|"]
    for row in _checked_rows(chapter, values, path):
        published = f"{row['published']} {row['unit']}".strip()
        lines.append(f"| {_cell(row['location'])} | {_cell(row['quantity'])} | {row['finding']} "
                     f"| {_cell(published)} | {_cell(row['computed']) or '-'} | {row['verdict']} |")
    return Markdown("\n".join(lines))


def _checked_rows(chapter, values, path):
    """The registry rows of ``chapter``, each checked by :func:`check_row` against ``values``."""
    if not isinstance(values, dict):
        raise ValueError(f"values must be a dict {{quantity: value}}, got {values!r:.80}")
    rows = read_registry(path, chapter)
    if not rows:
        raise ValueError(f"the registry {path} has no row for the chapter {chapter!r}")
    for row in rows:
        check_row(row, values.get(row["quantity"]))
    return rows


def verdict_summary(chapter: str, values: dict,
                    path: str | PathLike = "published_values.csv") -> Markdown:
    """Check a chapter's registry rows as :func:`reproduction_table` does, and count them.

    The narrow table a lecture page shows (it fits the book's column): for each verdict, the
    number of rows and the findings that explain them; the study page shows every row.

    Parameters
    ----------
    chapter, values, path
        As for :func:`reproduction_table`.

    Returns
    -------
    Markdown

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "registry.csv"
    >>> _ = path.write_text(",".join(COLUMNS) + "\\n000,Sec. 4,T,1.942,s,1.941626,reproduced,"
    ...                     "ch1,,\\n000,Sec. 4,T2,1.883,s,1.941626,source-error,ch1,T-2T,slip\\n")
    >>> print(verdict_summary("ch1", {"T": 1.9416259, "T2": 1.9416259}, path))
    | verdict | rows | findings |
    |---|---|---|
    | reproduced | 1 |  |
    | source-error | 1 | T-2T |
    """
    rows = _checked_rows(chapter, values, path)
    lines = ["| verdict | rows | findings |", "|---|---|---|"]
    for verdict in VERDICTS:
        mine = [r for r in rows if r["verdict"] == verdict]
        if mine:
            findings = sorted({r["finding"] for r in mine if r["finding"]})
            lines.append(f"| {verdict} | {len(mine)} | {', '.join(findings)} |")
    return Markdown("\n".join(lines))
