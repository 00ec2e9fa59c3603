"""Benchmarks of the gait simulator: scenario C at 20 Hz (target well under 2 s) and a 1 km walk
(target a few seconds). Run with ``pytest -m bench --benchmark-enable tests/benchmarks/test_bench_sim.py``."""

from __future__ import annotations

import pytest

from pdrlearn.sim import simulate

pytestmark = pytest.mark.bench


def test_bench_scenario_c(benchmark):
    s = benchmark(simulate, "C", 1)
    assert s.steps is not None and len(s.steps) > 40


def test_bench_walk_1km(benchmark):
    s = benchmark.pedantic(simulate, args=("walk", 2), kwargs={"length_m": 1000.0}, rounds=2, iterations=1)
    assert s.meta["distance_m"] > 900
