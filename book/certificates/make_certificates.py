"""Recompute every stored certificate of the book (``make certify``).

Each file is a :class:`~mechnum.certify.Certificate` as JSON: its scope, the search
that made it, the inputs, the searched boxes, the leaves with the test each passed, the root
enclosures and the work done. Re-check one with :func:`~mechnum.certify.verify`, the
residual of the same ``system`` and the chart as the domain
(:func:`~mechnum.rods.certified.branch_boxes`; see each entry below).

* ``ch3_pinned_mode{1,2,3}.json``: Chapter 3's pinned rod (``EI = L = 1``, tip ``(0.8, 0.1)``),
  the chart of each mode searched whole (:func:`~mechnum.rods.certified.certify_pinned`):
  scope ``"all"``, complete.
* ``ch5_table7_modes11.json``: Table 7's mode ``(1, 1)`` equilibria, each proven in a box around
  the sampled one (:func:`~mechnum.mechanisms.rfr2.certify_forward` with ``around``): scope
  ``"existence"``.
* ``ch5_table7_all_modes11.json``: every equilibrium of Table 7 with modes ``(1, 1)``, the whole
  chart searched by co-refinement up to the a-priori bound on the rods' load
  (:func:`~mechnum.mechanisms.rfr2.certify_forward` without ``around``): a
  :class:`~mechnum.rods.CoCertificate` of scope ``"all"``, re-checked against the caller's
  inputs by :func:`~mechnum.mechanisms.rfr2.certified.verify_certificate`.
* ``ch6_table8_modes111.json``: Table 8's mode ``(1, 1, 1)`` equilibria, likewise
  (:func:`~mechnum.mechanisms.pfr3.certified.certify_forward` with ``around``): scope
  ``"existence"``; Chapter 6 verifies it. With ``MECHNUM_CERTIFY_FULL=1`` the whole chart is
  searched by co-refinement too (:func:`~mechnum.mechanisms.pfr3.certified.certify_forward`
  without ``around``, its rounds printed: live triples, boxes, time, the live share of the
  domain), and ``ch6_table8_all_modes111.json`` stored if the search is complete. It is not:
  the default bound on the live triples (``rods.certified.MAX_LIVE``, 2 million) stops it after
  round 2 (2.9 million); allowed 6 million, it reaches 8.9 million in round 6, after 300 s of CPU.
  Cutting one rod per round instead of all three does not help: after each rod is cut once the
  same triples are live (1,678,829 against 1,678,833), after more tests (4.7 million against
  4.0 million). After round 1 fewer than 0.05 % of the live triples have a rod whose load is
  surely above 1 N (``Lambda`` about 4.4): a tighter bound on the load would not cut them.
  Cutting each box across its relatively wider side (``psi / 2 pi`` against ``t``) instead of
  where its enclosures widen most leaves more: 3.6 million after round 2. And 98 % of round 2's
  live triples lie farther than 0.5 from each of the nine sampled roots (in the chart, in one
  coordinate at least): settling boxes around the nine early would not close the search.
"""

import os
import pathlib
import sys
import time

from mechnum import rods
from mechnum.mechanisms import pfr3, rfr2
from mechnum.mechanisms.pfr3 import certified as pfr3_certified
from mechnum.mechanisms.rfr2 import certified as rfr2_certified

HERE = pathlib.Path(__file__).parent


def store(name, part, inputs):
    cert = part.certificate(inputs)
    cert.save(HERE / name)
    print(f"{name}: scope {cert.scope}, {part.message} ({part.seconds:.1f} s)")


def main():
    start = time.perf_counter()
    pinned = rods.certify_pinned(1.0, 1.0, [0.8, 0.1], modes=(1, 2, 3))
    for mode, part in zip((1, 2, 3), pinned.parts):
        store(f"ch3_pinned_mode{mode}.json", part,
              {"function": "mechnum.rods.certified.pinned_system", "EI": 1.0, "L": 1.0,
               "target": [0.8, 0.1], "mode": mode, "unknowns": ["psi", "t"]})
    sampled = rfr2.forward(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA, rng=0)
    table7 = rfr2.certify_forward(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA, around=sampled.x)
    store("ch5_table7_modes11.json", table7.parts[0],
          {"function": "mechnum.mechanisms.rfr2.certified.system", "mechanism": "TABLE7",
           "theta": rfr2.study.TABLE7_THETA.tolist(), "modes": [1, 1],
           "searched": "boxes around the sampled equilibria (a lower bound of the count)",
           "around": sampled.x.tolist(), "unknowns": ["psi1", "t1", "psi2", "t2"]})
    table7 = rfr2.certify_forward(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA)
    cert = table7.certificate(rfr2_certified.certificate_inputs(rfr2.study.TABLE7,
                                                                rfr2.study.TABLE7_THETA))
    cert.save(HERE / "ch5_table7_all_modes11.json")
    print(f"ch5_table7_all_modes11.json: {table7.message}; stable {table7.stable} "
          f"({table7.seconds:.1f} s)")
    sampled = pfr3.forward(pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS, rng=0)
    table8 = pfr3.certify_forward(pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS, around=sampled.x)
    store("ch6_table8_modes111.json", table8.parts[0],
          {"function": "mechnum.mechanisms.pfr3.certified.system", "mechanism": "TABLE8",
           "lambdas": pfr3.study.TABLE8_LAMBDAS.tolist(), "modes": [1, 1, 1],
           "searched": "boxes around the sampled equilibria (a lower bound of the count)",
           "around": sampled.x.tolist(),
           "unknowns": ["psi1", "t1", "psi2", "t2", "psi3", "t3"]})
    stable = pfr3_certified.certify_stability(pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS,
                                              table8.roots)
    print(f"ch6: the nine proven stable: {stable}")
    if os.environ.get("MECHNUM_CERTIFY_FULL") == "1":
        whole = pfr3.certify_forward(pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS)
        for r, h in enumerate(whole.corefined.rounds):
            print(f"  round {r}: {h['live']} live triples, {h['boxes']} boxes, "
                  f"{h['seconds']:.0f} s, live share {h['volume']:.1e}")
        print(f"ch6 whole chart: {whole.message} ({whole.seconds:.0f} s)")
        if whole.complete:
            inputs = pfr3_certified.certificate_inputs(pfr3.study.TABLE8,
                                                       pfr3.study.TABLE8_LAMBDAS)
            whole.certificate(inputs).save(HERE / "ch6_table8_all_modes111.json")
    print(f"all certificates in {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
