"""Benchmark: step detection over one hour of two-unit (foot + waist) 20 Hz data.

Target (issue 4): < 0.5 s for a foot and a waist detector together. Run with
``pytest -m bench --benchmark-enable tests/benchmarks/test_bench_steps.py`` (skipped in the default run).
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io.session import Session, Stream
from pdrlearn.steps import get_detector


def _hour(s: Session, seconds: float = 3600.0) -> Session:
    streams = {}
    for name, st in s.streams.items():
        period = st.t[-1] - st.t[0] + st.period_s
        k = int(np.ceil(seconds / period))
        t = np.concatenate([st.t + i * period for i in range(k)])
        keep = t < st.t[0] + seconds
        streams[name] = Stream(name, t[keep], np.tile(st.values, (k, 1))[keep])
    return Session(f"{s.name}_1h", streams)


@pytest.fixture(scope="module")
def hour_session():
    sim = pytest.importorskip("pdrlearn.sim")
    return _hour(sim.simulate("B", 1, speed="normal"))


@pytest.mark.bench
@pytest.mark.parametrize("pair", [("accel", "pelvic-gyro"), ("accel-force", "pll"), ("accel", "pll")])
def test_bench_two_unit_hour(benchmark, hour_session, pair):
    foot, waist = (get_detector(n) for n in pair)

    def run():
        return len(foot.detect(hour_session)), len(waist.detect(hour_session))

    n_foot, n_waist = benchmark.pedantic(run, rounds=3, iterations=1)
    assert n_foot > 1000 and n_waist > 2000


@pytest.mark.bench
@pytest.mark.parametrize("name", ["accel", "accel-force", "pelvic-gyro", "pll"])
def test_bench_detector_hour(benchmark, hour_session, name):
    det = get_detector(name)
    steps = benchmark.pedantic(lambda: det.detect(hour_session), rounds=3, iterations=1)
    assert len(steps) > 1000
