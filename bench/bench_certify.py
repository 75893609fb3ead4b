"""Benchmarks of the certified equilibria (mechnum.certify), beside the sampling they certify.

The peer of each proof is the package's own sampling solver on the same input (the proof
certifies what the sampling found, and more): the module prints, at its end, the time of the
proof over the time of the sampling and what was proven (count, complete, boxes, evaluations).
The issue's targets, on this 2-core machine:

* Chapter 3's pinned rod (``EI = L = 1``, tip ``(0.8, 0.1)``), modes 1 to 3, certified
  complete: <= 10 s (``rods.certify_pinned`` against ``rods.pinned_equilibria``);
* Table 7, modes ``(1, 1)``, certified complete with stability: <= 60 s;
* Table 8, modes ``(1, 1, 1)``, certified with stability: <= 10 min (``make certify``), and
  verifying its stored certificate: <= 20 s;
* Table 7, every mode pair up to 3, certified complete: report the time.

Table 7's whole chart is searched by co-refinement (``certify_forward`` without ``around``)
and its certificate re-checked (``verify_certificate``), beside the sampling; the other
whole-chart searches (Table 7's other modes, Table 8) run for many minutes here and are
measured only with ``MECHNUM_BENCH_FULL=1``; by default Table 8's benchmark proves the sampled
equilibria one by one (``around``), a lower bound of the count.

Run with ``make bench``, or ``pytest bench/bench_certify.py -o python_files='bench_*.py'
--benchmark-only``.
"""

import os
import pathlib

import pytest

from mechnum import certify, rods
from mechnum.mechanisms import pfr3, rfr2
from mechnum.mechanisms.pfr3 import certified as pfr3_certified
from mechnum.mechanisms.pfr3.study import TABLE8, TABLE8_LAMBDAS
from mechnum.mechanisms.rfr2 import certified as rfr2_certified
from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA

CERTIFICATES = pathlib.Path(__file__).parent.parent / "book" / "certificates"
FULL = os.environ.get("MECHNUM_BENCH_FULL") == "1"
RESULTS = {}
MADE = {}
"""Certificates made by one benchmark for another to verify."""


@pytest.fixture(scope="module", autouse=True)
def ratios(request):
    """Print the proof's time over the sampling's, and what was proven, at the module's end."""
    yield
    lines = ["", "bench_certify: proof / sampling (minimum over rounds), and what was proven"]
    for what, entry in RESULTS.items():
        ours, peer = entry.get("mechnum"), entry.get("peer")
        ratio = f" = {ours / peer:6.1f}" if ours and peer else ""
        peer_text = f"{peer:8.2f} s" if peer else "       - "
        lines.append(f"  {what:44} {ours:8.2f} s / {peer_text}{ratio}   {entry.get('note', '')}")
    with request.config.pluginmanager.getplugin("capturemanager").global_and_fixture_disabled():
        print("\n".join(lines))


def record(benchmark, what, who, note=None):
    RESULTS.setdefault(what, {})[who] = benchmark.stats.stats.min
    if note:
        RESULTS[what]["note"] = note


def _proven(result):
    if hasattr(result, "corefined"):
        last = result.corefined.rounds[-1]
        return (f"count {result.count}, complete {result.complete}, stable {result.stable}, "
                f"{result.iterations} rounds, {last['boxes']} boxes of the charts, "
                f"{result.nfev} + {result.njev} evaluations")
    return (f"count {result.count}, complete {result.complete}, boxes {result.boxes}, "
            f"evaluations {result.nfev} + {result.njev}, undecided {len(result.undecided)} "
            f"({result.undecided_fraction:.2%} of the volume)")


def test_pinned_certified(benchmark):
    result = benchmark.pedantic(rods.certify_pinned, args=(1.0, 1.0, [0.8, 0.1], (1, 2, 3)),
                                rounds=1, iterations=1)
    assert result.complete and result.count == 9
    record(benchmark, "Chapter 3 pinned rod, modes 1-3", "mechnum", _proven(result))


def test_pinned_sampled(benchmark):
    benchmark.pedantic(rods.pinned_equilibria, args=(1.0, 1.0, [0.8, 0.1], (1, 2, 3)),
                       rounds=1, iterations=1)
    record(benchmark, "Chapter 3 pinned rod, modes 1-3", "peer")


@pytest.fixture(scope="module")
def table7():
    return rfr2.forward(TABLE7, TABLE7_THETA, rng=0)


@pytest.fixture(scope="module")
def table8():
    return pfr3.forward(TABLE8, TABLE8_LAMBDAS, rng=0)


def test_table7_sampled(benchmark):
    benchmark.pedantic(rfr2.forward, args=(TABLE7, TABLE7_THETA),
                       kwargs={"rng": 0}, rounds=1, iterations=1)
    record(benchmark, "Table 7 (1, 1), each sampled one proven", "peer")


def test_table7_around(benchmark, table7):
    result = benchmark.pedantic(rfr2.certify_forward, args=(TABLE7, TABLE7_THETA),
                                kwargs={"around": table7.x}, rounds=1, iterations=1)
    assert result.count == 3
    record(benchmark, "Table 7 (1, 1), each sampled one proven", "mechnum", _proven(result))


def test_table7_whole_chart_corefined(benchmark):
    result = benchmark.pedantic(rfr2.certify_forward, args=(TABLE7, TABLE7_THETA),
                                rounds=1, iterations=1)
    assert result.complete and result.count == 3 and result.stable == [True, True, True]
    record(benchmark, "Table 7 (1, 1), whole chart (<= 60 s)", "mechnum", _proven(result))
    cert = result.certificate(rfr2_certified.certificate_inputs(TABLE7,
                                                                TABLE7_THETA))
    MADE["table7"] = cert


def test_table7_whole_chart_sampled(benchmark):
    benchmark.pedantic(rfr2.forward, args=(TABLE7, TABLE7_THETA),
                       kwargs={"rng": 0}, rounds=1, iterations=1)
    record(benchmark, "Table 7 (1, 1), whole chart (<= 60 s)", "peer")


def test_table7_verify_corefined(benchmark):
    cert = MADE.get("table7") or rods.CoCertificate.load(
        CERTIFICATES / "ch5_table7_all_modes11.json")
    checked = benchmark.pedantic(rfr2_certified.verify_certificate,
                                 args=(cert, TABLE7, TABLE7_THETA), rounds=1,
                                 iterations=1)
    assert checked.count == 3 and checked.complete
    record(benchmark, "Table 7 whole-chart certificate, verify (<= 20 s)", "mechnum",
           f"{checked.rounds} rounds, {checked.evaluations} evaluations")


def test_table8_sampled(benchmark):
    benchmark.pedantic(pfr3.forward, args=(TABLE8, TABLE8_LAMBDAS),
                       kwargs={"rng": 0}, rounds=1, iterations=1)
    record(benchmark, "Table 8 (1, 1, 1), each sampled one proven", "peer")


def test_table8_around(benchmark, table8):
    result = benchmark.pedantic(pfr3.certify_forward, args=(TABLE8, TABLE8_LAMBDAS),
                                kwargs={"around": table8.x}, rounds=1, iterations=1)
    assert result.count == 9
    record(benchmark, "Table 8 (1, 1, 1), each sampled one proven", "mechnum",
           _proven(result))


def test_table8_verify_stored(benchmark):
    cert = certify.Certificate.load(CERTIFICATES / "ch6_table8_modes111.json")
    f, J, _, exclude = pfr3_certified.system(TABLE8, TABLE8_LAMBDAS)
    checked = benchmark.pedantic(certify.verify, args=(cert, f, J, exclude),
                                 kwargs={"domain": rods.certified.branch_boxes(3)}, rounds=3,
                                 iterations=1)
    assert checked.count == 9
    record(benchmark, "Table 8 stored certificate, verify (<= 20 s)", "mechnum",
           f"{checked.iterations} leaves, {checked.nfev} + {checked.njev} evaluations")


FULL_REASON = "whole-chart searches take many minutes: MECHNUM_BENCH_FULL=1 runs them"


@pytest.mark.skipif(not FULL, reason=FULL_REASON)
@pytest.mark.parametrize("modes", [(m1, m2) for m1 in (1, 2, 3) for m2 in (1, 2, 3)
                                   if (m1, m2) != (1, 1)])
def test_table7_whole_chart(benchmark, modes):
    result = benchmark.pedantic(rfr2.certify_forward, args=(TABLE7, TABLE7_THETA),
                                kwargs={"modes": modes}, rounds=1, iterations=1)
    record(benchmark, f"Table 7 {modes}, whole chart", "mechnum", _proven(result))


@pytest.mark.skipif(not FULL, reason=FULL_REASON)
def test_table8_whole_chart(benchmark):
    result = benchmark.pedantic(pfr3.certify_forward, args=(TABLE8, TABLE8_LAMBDAS),
                                rounds=1, iterations=1)
    record(benchmark, "Table 8 (1, 1, 1), whole chart", "mechnum", _proven(result))
