"""Benchmarks of Chapter 2 (the finger study): the study's whole SOR omega study, which it says
took 26 hours, in this package.

Run with ``make bench`` (or ``pytest bench/bench_finger.py -o python_files='bench_*.py'
--benchmark-only``)."""

import numpy as np

from mechnum import linear
from mechnum.mechanisms import finger as F
from mechnum.mechanisms.finger import study as FS


def omega_study(n_omegas=200):
    """The fits (QR, LU, SOR at the study's five omegas) and the spectral radius and iteration
    count of SOR for ``n_omegas`` relaxation factors in (0, 2)."""
    fits = [F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, FS.TABLE1_R4, m)
            for m in ("qr", "lu")]
    fits += [F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, FS.TABLE1_R4, "sor", w,
                          tol=1e-10) for w in FS.STUDY_OMEGAS]
    A, b = F.design_matrix(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT)
    sweep = linear.sor_sweep(A.T @ A, A.T @ b, np.linspace(0.05, 1.95, n_omegas), tol=1e-10)
    return fits, sweep


def test_full_omega_study(benchmark):
    fits, sweep = benchmark(omega_study)
    assert sweep.converged.all()
    assert all(np.allclose(f.k, fits[0].k, atol=1e-8) for f in fits)


def test_least_squares_fit_qr(benchmark):
    fit = benchmark(F.synthesize, FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, FS.TABLE1_R4, "qr")
    assert fit.linkage.r1 > 0


def test_registry_reproduction(benchmark):
    values = benchmark(FS.reproduce)
    assert len(values) > 300
