"""Speed of the waist pipelines on the real 137.6 s daily-activity recording (run with `make bench`)."""

from __future__ import annotations

from pathlib import Path

import pytest

pytestmark = pytest.mark.bench

SESSION = Path(__file__).resolve().parents[2] / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


@pytest.fixture(scope="module")
def session():
    if not SESSION.exists():
        pytest.skip("real data not bundled")
    from pdrlearn.io import read_session

    return read_session(SESSION)


@pytest.mark.parametrize("pipeline,opts", [("waist-pendulum", {}), ("waist-pendulum", {"realtime": True}),
                                           ("waist-pll", {}), ("waist-pll", {"heading": "ellipse"})])
def test_bench_waist_pipeline(benchmark, session, pipeline, opts):
    from pdrlearn.track import get_pipeline

    fn = get_pipeline(pipeline)
    res = benchmark(fn, session, **opts)
    assert len(res.steps) > 40


def test_bench_waist_ahrs(benchmark, session):
    from pdrlearn.waist import waist_imu

    imu = benchmark(waist_imu, session)
    assert len(imu.t) == len(session["wAccelerometer"])


def test_bench_live_radius_5000_reports(benchmark):
    """Decision E355: a live waist tracker's position radius (``LiveStep.pos_sigma_m``) reported for 5000 steps, one
    after the other, from the carried state (``experiments/live_radius_s53_e355.py``: E352's recomputation over every
    step cost 30.818 ms a report at 5000 steps on a loaded 2-core machine, E355's state 2.277 ms)."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "experiments"))
    import live_radius_s53_e355 as e355

    ms = benchmark.pedantic(e355.per_report_ms, args=(5000,), rounds=1, iterations=1)
    assert ms > 0
