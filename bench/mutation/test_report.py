"""The committed mutation report (bench/mutation.md, written by `make mutate`) covers the modules
as they are: each module's files and their content hash are recorded, so changing a covered module
without running `make mutate` again fails here (intended: the kill rates are then unknown)."""

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("mutate", ROOT / "bench" / "mutation" / "mutate.py")
mutate = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mutate)
RESULTS = json.loads(mutate.RESULTS.read_text()) if mutate.RESULTS.exists() else {}
MODULES = mutate.modules()


@pytest.mark.parametrize("name", list(MODULES))
def test_report_covers_the_module_as_it_is(name):
    assert name in RESULTS, f"{name} was never mutated: make mutate MODULES={name}"
    files = mutate.source_files(MODULES[name])
    assert files, f"modules.toml's globs for {name} match no file"
    assert RESULTS[name]["files"] == files, (
        f"{name}'s files changed since its mutation run: make mutate MODULES={name}")
    assert RESULTS[name]["sha256"] == mutate.content_hash(files), (
        f"{name} changed since its mutation run: make mutate MODULES={name}")


@pytest.mark.parametrize("name", list(MODULES))
def test_every_module_kills_nine_mutants_in_ten(name):
    entry = RESULTS.get(name)
    if entry is None:
        pytest.fail(f"{name} was never mutated")
    equivalent, alive = mutate.classify(name, entry, mutate.equivalents())
    killed, total, rate = mutate.score(entry, len(equivalent))
    assert total > 0
    assert rate >= mutate.REQUIRED, (
        f"{name}: {killed} of {total - len(equivalent)} non-equivalent mutants killed; "
        f"survivors: {[s['mutant'] for s, _ in alive]}")


def test_the_committed_report_is_the_rendered_one():
    assert (ROOT / "bench" / "mutation.md").read_text() == mutate.render()


def test_every_listed_equivalent_is_a_survivor():
    # an entry that matches no survivor is stale (its mutant is killed now, or its code is gone)
    survivors = {(name, s["function"], tuple(map(tuple, mutate.changed_lines(s["diff"]))))
                 for name, entry in RESULTS.items() for s in entry["survivors"]}
    for e in mutate.equivalents().get("equivalent", []):
        key = (e["module"], e["function"], (tuple(e["removed"]), tuple(e["added"])))
        assert key in survivors, f"stale entry in equivalents.toml: {e}"
