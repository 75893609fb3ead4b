"""Tests of mechnum.published: the printed-digits rule and the registry reader."""

import numpy as np
import pytest

from mechnum.published import COLUMNS, agrees, below, half_unit, read_registry


@pytest.mark.parametrize("printed, half", [("1.942", 5e-4), ("-0.099672", 5e-7), ("62", 0.5),
                                           ("6.032e-4", 5e-8), ("0", 0.5)])
def test_half_unit(printed, half):
    assert half_unit(printed) == pytest.approx(half)


def test_half_unit_rejects_text():
    with pytest.raises(ValueError, match="not a printed number"):
        half_unit("0.1'")


@pytest.mark.parametrize("published, value, ok", [
    ("1.942", 1.94163, True), ("1.942", 1.94149, False), ("-0.099672", -0.0996725, True),
    ("<1e-13", 9.9e-14, True), ("<1e-13", 1.1e-13, False),
    ("~1e-12", 9e-12, True), ("~1e-12", 2e-11, False), ("~1e-12", 1e-14, False)])
def test_agrees(published, value, ok):
    assert agrees(published, value) is ok


def test_read_registry_checks_the_columns(tmp_path):
    path = tmp_path / "registry.csv"
    path.write_text("seed,quantity\n000,T\n")
    with pytest.raises(ValueError, match="columns"):
        read_registry(path)
    path.write_text(",".join(COLUMNS) + "\n000,a,q1,1,s,1,reproduced,01,\n000,a,q2,1,s,1,"
                    "reproduced,02,\n")
    assert [r["quantity"] for r in read_registry(path, chapter="02")] == ["q2"]


def test_below_prints_the_bound_it_checks():
    assert below(-3e-16, 1e-13) == "< 1e-13"
    assert below([np.zeros(2), [1e-30, -2e-30, 0.0]], 1e-25) == "< 1e-25"
    for value in (1e-13, [0.0, -2e-13], float("nan")):
        with pytest.raises(AssertionError, match="is not below"):
            below(value, 1e-13)
