"""Speed of the aiding filters (skipped in the default run; `pytest -m bench --benchmark-enable`)."""

import pytest

from pdrlearn.aid.colombo import ColomboTracker
from pdrlearn.aid.fixgen import gnss_fixes, infrastructure_fixes
from pdrlearn.aid.gnss import GnssPdrFusion
from pdrlearn.aid.sporadic import SporadicFixFusion
from pdrlearn.aid.synth import pdr_with_drift, synthetic_waist_session, synthetic_walk

pytestmark = pytest.mark.bench


@pytest.fixture(scope="module")
def walk():
    steps, truth = synthetic_walk(0, length_m=1000)
    return pdr_with_drift(steps, 0), truth


def test_bench_gnss_pdr_1km(benchmark, walk):
    pdr, truth = walk
    fx = gnss_fixes(truth, seed=0)
    benchmark(lambda: GnssPdrFusion(mode="best").run(pdr.steps, fx))


def test_bench_sporadic_1km(benchmark, walk):
    pdr, truth = walk
    fx = infrastructure_fixes(truth, seed=0)
    benchmark(lambda: SporadicFixFusion(period_s=4.0).run(pdr.steps, fx))


def test_bench_colombo_10s_100hz(benchmark):
    ses, truth = synthetic_waist_session(0, duration_s=10.0)
    fx = infrastructure_fixes(truth, seed=0)
    benchmark.pedantic(lambda: ColomboTracker(period_s=4.0).run(ses, fx), rounds=3, iterations=1)
