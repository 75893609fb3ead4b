"""Benchmarks of the actuator force (seed 004): Q over 1000 instants, by both routes.

The target is 10 ms or less for 1000 instants (kinematics included).
"""

import numpy as np
import pytest

from mechnum.mechanisms.actuator import kinematics, lagrange_force, virtual_power_force

T = np.linspace(0.0, 1.0, 1000)


@pytest.mark.parametrize("model", ["exact", "annex"])
def test_lagrange_force_1000_instants(benchmark, model):
    q = benchmark(lambda: lagrange_force(kinematics(T, model=model)))
    assert q.shape == T.shape


@pytest.mark.parametrize("model", ["exact", "annex"])
def test_virtual_power_force_1000_instants(benchmark, model):
    q = benchmark(lambda: virtual_power_force(kinematics(T, model=model)))
    assert q.shape == T.shape
