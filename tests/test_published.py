"""Tests of the book's registry rules (book/published.py): the printed-digits rules, the registry
and its one table."""

from decimal import Decimal

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from published import (
    COLUMNS,
    agrees,
    below,
    check_row,
    half_unit,
    is_claim,
    read_findings,
    read_published,
    read_registry,
    reproduction_table,
    verdict_summary,
)


@pytest.mark.parametrize("printed, half", [("1.942", 5e-4), ("-0.099672", 5e-7), ("62", 0.5),
                                           ("6.032e-4", 5e-8), ("0", 0.5)])
def test_half_unit(printed, half):
    # half a unit of the last printed digit is a power of ten over two: pytest's default rel 1e-6
    # only absorbs its float representation
    assert half_unit(printed) == pytest.approx(half)


def test_half_unit_rejects_text():
    with pytest.raises(ValueError, match="not a printed number"):
        half_unit("0.1'")


@pytest.mark.parametrize("published, value, ok", [
    ("1.942", 1.94163, True), ("1.942", 1.94149, False), ("-0.099672", -0.0996725, True),
    ("<1e-13", 9.9e-14, True), ("<1e-13", 1.1e-13, False), ("<1e-13", -2e-13, False),
    ("~1e-12", 3.1e-12, True), ("~1e-12", 1e-12, True), ("~1e-12", -4e-13, True),
    ("~1e-12", 3.2e-12, False), ("~1e-12", 3.1e-13, False), ("~1e-12", 1e-14, False),
    ("0", 3e-17, True), ("0", -9e-13, True), ("0", 0.3, False), ("0", 2e-12, False),
    ("0.000", 4e-4, True), ("0.000", 6e-4, False)])
def test_agrees(published, value, ok):
    assert agrees(published, value) is ok


def test_read_registry_checks_the_columns(tmp_path):
    path = tmp_path / "registry.csv"
    path.write_text("seed,quantity\n000,T\n")
    with pytest.raises(ValueError, match="columns"):
        read_registry(path)
    path.write_text(",".join(COLUMNS) + "\n000,a,q1,1,s,1,reproduced,01,,\n000,a,q2,1,s,1,"
                    "reproduced,02,,\n")
    assert [r["quantity"] for r in read_registry(path, chapter="02")] == ["q2"]


def test_below_prints_the_bound_it_checks():
    assert below(-3e-16, 1e-13) == "< 1e-13"
    assert below([np.zeros(2), [1e-30, -2e-30, 0.0]], 1e-25) == "< 1e-25"
    for value in (1e-13, [0.0, -2e-13], float("nan")):
        with pytest.raises(AssertionError, match="is not below"):
            below(value, 1e-13)


ROW = {"quantity": "T", "published": "1.942", "computed": "1.941626", "verdict": "reproduced"}


@pytest.mark.parametrize("row, value", [
    (ROW, 1.9416259),
    (dict(ROW, verdict="within-input-rounding"), 1.9416259),
    (dict(ROW, published="1.883", verdict="source-error"), 1.9416259),
    (dict(ROW, published="0", computed="<1e-25"), 3e-32),
    (dict(ROW, published="12", computed="", verdict="not-reproduced"), None),
    (dict(ROW, published="n_y cos(theta)", computed="", verdict="source-error"), None),
])
def test_check_row_accepts_a_true_row(row, value):
    check_row(row, value)


@pytest.mark.parametrize("row, value, match", [
    (ROW, 1.9417, "the registry says 1.941626"),                    # computed column is stale
    (ROW, None, "the package gives None"),
    (ROW, float("nan"), "the package gives nan"),
    (dict(ROW, computed="<1e-13"), 2e-13, "bounds it by <1e-13"),
    (dict(ROW, computed=""), 1.9, "computed is blank"),
    (dict(ROW, published="1.943", computed="1.9430"), 1.943, None),  # agrees: fine
    (dict(ROW, published="1.950", computed="1.9416"), 1.9416, "disagree, yet the verdict"),
    (dict(ROW, verdict="not-reproduced"), 1.9416259, "agrees with"),
])
def test_check_row_refuses_a_false_row(row, value, match):
    if match is None:
        check_row(row, value)
        return
    with pytest.raises(AssertionError, match=match):
        check_row(row, value)


def test_reproduction_table_renders_and_checks(tmp_path):
    path = tmp_path / "registry.csv"
    path.write_text(",".join(COLUMNS) + "\n000,Sec. 4,T,1.942,s,1.941626,reproduced,ch1,,\n"
                    "000,\"Tab. 1, |x|\",q,0,,<1e-25,reproduced,ch1,,\n")
    table = reproduction_table("ch1", {"T": 1.9416259, "q": 1e-30}, path)
    assert table._repr_markdown_().splitlines()[2:] == [
        "| Sec. 4 | T |  | 1.942 s | 1.941626 | reproduced |",
        "| Tab. 1, \\|x\\| | q |  | 0 | <1e-25 | reproduced |"]
    with pytest.raises(AssertionError, match="bounds it"):
        reproduction_table("ch1", {"T": 1.9416259, "q": 1e-3}, path)
    with pytest.raises(ValueError, match="no row for the chapter 'ch9'"):
        reproduction_table("ch9", {}, path)


def test_verdict_summary_counts_checked_rows(tmp_path):
    path = tmp_path / "registry.csv"
    path.write_text(",".join(COLUMNS) + "\n000,Sec. 4,T,1.942,s,1.941626,reproduced,ch1,,\n"
                    "002,Slide,T2,1.883,s,1.941626,source-error,ch1,T-2T,slip\n"
                    "002,Slide,T3,1.883,s,1.941626,source-error,ch1,T-2T,slip\n")
    values = {"T": 1.9416259, "T2": 1.9416259, "T3": 1.9416259}
    assert verdict_summary("ch1", values, path)._repr_markdown_().splitlines()[2:] == [
        "| reproduced | 1 |  |", "| source-error | 2 | T-2T |"]
    with pytest.raises(AssertionError, match="the registry says"):
        verdict_summary("ch1", {**values, "T": 1.95}, path)
    with pytest.raises(ValueError, match="no row for the chapter 'ch9'"):
        verdict_summary("ch9", {}, path)


# --- the valid domain and just outside it (issue 13) -------------------------------------------

@settings(max_examples=300, deadline=None)
@given(value=st.floats(-1e6, 1e6, allow_nan=False), digits=st.integers(0, 8))
def test_a_value_agrees_with_its_own_rounding_and_not_with_a_unit_off(value, digits):
    printed = f"{value:.{digits}f}"
    half = half_unit(printed)
    assert half == 0.5 * 10.0 ** -digits
    if abs(Decimal(printed)) > 0 or digits:  # a bare "0" is the exact-zero rule
        assert agrees(printed, value)
        assert not agrees(printed, float(Decimal(printed)) + 3 * half)


@settings(max_examples=200, deadline=None)
@given(value=st.floats(0, 1e3, allow_nan=False), exponent=st.integers(-30, 3))
def test_below_prints_exactly_the_bounds_that_hold(value, exponent):
    bound = 10.0 ** exponent
    if value < bound:
        assert below(value, bound).startswith("< ") and float(below(value, bound)[2:]) == bound
    else:
        with pytest.raises(AssertionError, match="is not below"):
            below(value, bound)


@pytest.mark.parametrize("text", ["", "abc", "inf", "nan", "1.2.3", "n_y cos(theta)", "<", "~x"])
def test_texts_that_are_no_numbers_are_named(text):
    assert not is_claim(text)
    with pytest.raises(ValueError, match="not a printed number"):
        agrees(text, 1.0)
    with pytest.raises(ValueError, match="not a printed number"):
        half_unit(text)


def test_findings_file_with_the_wrong_columns_is_named(tmp_path):
    path = tmp_path / "findings.csv"
    path.write_text("finding,what\nx,y\n")
    with pytest.raises(ValueError, match="columns"):
        read_findings(path)


def test_read_published_gives_the_printed_text_by_quantity(tmp_path):
    path = tmp_path / "registry.csv"
    path.write_text(",".join(COLUMNS) + "\n000,a,q1,1.50,s,1.5,reproduced,01,,\n"
                    "000,a,q2,7,s,7,reproduced,02,,\n")
    assert read_published(path, "01") == {"q1": "1.50"}


@pytest.mark.parametrize("published, value, match", [
    ("1.0", "x", "value must be a real number"),  # was a TypeError of abs()
    ("1.0", None, "value must be a real number"),
    ("1.0", 1 + 2j, "value must be a real number"),
    ("1.0", True, "value must be a real number"),
    (1.0, 1.0, "published must be the printed text"),  # was an AttributeError
])
def test_agrees_names_what_is_no_number(published, value, match):
    with pytest.raises(ValueError, match=match):
        agrees(published, value)


def test_agrees_takes_numpy_numbers_and_nan_agrees_with_nothing():
    assert agrees("1.942", np.float32(1.9416)) and agrees("62", np.int64(62))
    assert not agrees("0", float("nan")) and not agrees("<1e-13", float("nan"))


@pytest.mark.parametrize("bound", [0.0, -1e-13, float("nan"), float("inf"), "1e-13"])
def test_below_refuses_a_bound_that_is_no_positive_number(bound):
    with pytest.raises(ValueError, match="bound must be"):
        below(1e-20, bound)
