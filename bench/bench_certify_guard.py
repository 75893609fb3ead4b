"""The cost of the guard of mechnum.certify: the same searches with and without it.

With the guard (``mechnum.certify._guard``), a search hands the residual ``certify.Ball``\\ s and
checks everything it returns (lengths, types, finite at points); the peer is the same search
handing plain Arb balls that only carry their box's float ends (which the rods' enclosures need
to pick a branch) and converting what comes back without a check, as before the guard. The
module prints, at its end, the time with the guard over the time without it (the median of the
rounds) for Chapter 3's pinned rod (mode 1, the whole chart) and Table 7 (modes ``(1, 1)``: the
leaf of the issue's reproducer, searched to 1,500 boxes). Target: below 1.2.

Run with ``pytest bench/bench_certify_guard.py -o python_files='bench_*.py' --benchmark-only``.
"""

import numpy as np
import pytest
from flint import arb

from mechnum import certify
from mechnum.certify import _guard as guard
from mechnum.certify import _krawczyk as kr
from mechnum.certify import _search as sr
from mechnum.certify import balls
from mechnum.mechanisms import rfr2
from mechnum.mechanisms.rfr2 import certified as rfr2_certified
from mechnum.rods import certified

RESULTS = {}
LEAF = np.array([[1.9, 2.0], [-0.24979192672217018, 0.0],
                 [4.785677901888251, 4.914237202517668],
                 [0.7493757801665105, 0.8742717435275956]])


class Marked(arb):
    """A plain ball that carries its box's ends, nothing more."""

    __slots__ = ("interval",)


def _marked(box):
    out = []
    for lo, hi in box:
        x = Marked(balls.ball(lo, hi))
        x.interval = (float(lo), float(hi))
        out.append(x)
    return out


def _plain(out, n):
    return [v if isinstance(v, arb) else arb(v) for v in out]


@pytest.fixture
def unguarded(monkeypatch):
    """The search without the guard (the peer)."""
    for module in (kr, sr):
        monkeypatch.setattr(module, "guarded", _marked)
    monkeypatch.setattr(certified, "interval", lambda x: getattr(x, "interval", None))
    monkeypatch.setattr(guard, "values", lambda f, X, n, point=False: _plain(f(X), n))
    monkeypatch.setattr(guard, "matrix", lambda J, X, n: [_plain(row, n) for row in J(X)])
    monkeypatch.setattr(guard, "decision", lambda exclude, X: bool(exclude(X)))


@pytest.fixture(scope="module", autouse=True)
def ratios(request):
    yield
    lines = ["", "bench_certify_guard: with the guard / without (median of the rounds)"]
    for what, entry in RESULTS.items():
        ours, peer = entry.get("guarded"), entry.get("plain")
        if ours and peer:
            lines.append(f"  {what:40} {ours:7.2f} s / {peer:7.2f} s = {ours / peer:5.2f}"
                         f"   {entry['note']}")
    with request.config.pluginmanager.getplugin("capturemanager").global_and_fixture_disabled():
        print("\n".join(lines))


def pinned():
    f, J = certified.pinned_system(1.0, 1.0, [0.8, 0.1], 1)
    return certify.roots(f, J, certified.branch_boxes(1))


def table7():
    f, J, _, exclude = rfr2_certified.system(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA)
    return certify.roots(f, J, LEAF, max_boxes=1500, exclude=exclude, split=exclude.split)


def _run(benchmark, search, what, who):
    result = benchmark.pedantic(search, rounds=3, iterations=1)
    RESULTS.setdefault(what, {})[who] = benchmark.stats.stats.median
    RESULTS[what]["note"] = f"count {result.count}, boxes {result.boxes}"
    return result


def test_pinned_guarded(benchmark):
    assert _run(benchmark, pinned, "pinned rod, mode 1, whole chart", "guarded").count == 1


def test_pinned_plain(benchmark, unguarded):
    assert _run(benchmark, pinned, "pinned rod, mode 1, whole chart", "plain").count == 1


def test_table7_guarded(benchmark):
    _run(benchmark, table7, "Table 7 (1, 1), the issue's leaf", "guarded")


def test_table7_plain(benchmark, unguarded):
    _run(benchmark, table7, "Table 7 (1, 1), the issue's leaf", "plain")
