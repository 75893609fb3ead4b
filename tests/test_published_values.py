"""The published-values registry, ``book/published_values.csv``, against the package.

Each chapter's mechanism module has ``reproduce() -> dict[str, float]``, keyed by the
``quantity`` column of that chapter's rows. This test recomputes every row and checks, with
``published.check_row`` (the book's ``book/published.py``), what the row says: the ``computed``
column is what the package computes today (to the digits the column prints, or below the
bound ``<1e-13`` that it stores for a round-off-level value, whose digits vary from machine to
machine), and the verdict
holds in both directions (an agreeing row agrees with ``published`` to the study's printed
digits, any other row does not).
"""

import importlib
import re
from functools import cache
from pathlib import Path

import pytest
from published import VERDICTS, check_row, read_findings, read_registry

BOOK = Path(__file__).resolve().parents[1] / "book"
REGISTRY = BOOK / "published_values.csv"
MODULES = {  # chapter (notebook stem) -> module holding its reproduce()
    "01_newton_hacksaw": "mechnum.mechanisms.hacksaw.study",
    "02_linear_systems_finger": "mechnum.mechanisms.finger.study",
    "03_elastica": "mechnum.mechanisms.elastica.study",
    "04_rigid_3prr": "mechnum.mechanisms.prr3.study",
    "05_flexible_2rfr": "mechnum.mechanisms.rfr2.study",
    "06_flexible_3pfr": "mechnum.mechanisms.pfr3.study",
    "07_actuator_force": "mechnum.mechanisms.actuator.study",
}
NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
BOUND = re.compile(r"^<\d(\.\d*)?[eE]-\d+$")  # a round-off-level value: "<1e-13"
ROWS = read_registry(REGISTRY)
FINDINGS = read_findings(BOOK / "findings.csv")


@cache
def reproduced(chapter):
    return importlib.import_module(MODULES[chapter]).reproduce()


def test_registry_is_well_formed():
    keys = [(r["chapter"], r["quantity"]) for r in ROWS]
    assert len(keys) == len(set(keys)), "quantity must be unique within a chapter"
    for r in ROWS:
        assert r["verdict"] in VERDICTS, r
        assert r["chapter"] in MODULES, r
        assert (BOOK / f"{r['chapter']}.ipynb").exists(), r
        assert r["note"].strip() or r["verdict"] == "reproduced", f"a verdict needs a note: {r}"
        assert not r["computed"] or NUMBER.match(r["computed"]) or BOUND.match(r["computed"]), r


def test_findings_and_rows_refer_to_each_other():
    ids = [f["finding"] for f in FINDINGS]
    assert len(ids) == len(set(ids)), "a finding id is listed twice"
    used = {r["finding"] for r in ROWS if r["finding"]}
    assert used <= set(ids), f"rows name findings that findings.csv lacks: {used - set(ids)}"
    assert set(ids) <= used, f"findings that no row names: {set(ids) - used}"
    for f in FINDINGS:
        assert f["chapter"] in MODULES and all(f[k].strip() for k in ("what", "where", "proof")), f
        chapters = {r["chapter"] for r in ROWS if r["finding"] == f["finding"]}
        assert chapters == {f["chapter"]}, f"{f['finding']} is named by rows of {chapters}"


@pytest.mark.parametrize("row", ROWS, ids=lambda r: f"{r['chapter']}:{r['quantity']}")
def test_row_is_what_the_package_computes(row):
    check_row(row, reproduced(row["chapter"]).get(row["quantity"]))
