"""Decision E36 (docs/decisions/export.md): a stride across a short foot gap (0.25-1 s) is levelled and integrated
with the gap counted as one sample interval, as offline ``pdrlearn track`` integrates a stride on the sample index
(before: the streamed stride kernel integrated the interpolated 0.5 s and gave the stride dz +2.03 m on scenario
D, offline +0.26 m).
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.window import gap_clock
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import per_timestamp, trained_dirs, without


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def scenario_d():
    sim = pytest.importorskip("pdrlearn.sim")
    return sim.simulate("D", 1)  # the trial's D (out/sim/D_u1 of make demo)




def test_the_gap_clock_counts_a_gap_as_one_sample_interval_and_leaves_a_regular_clock_alone():
    t = np.arange(20) * 0.05 + 100.0
    assert gap_clock(t) is t  # no gap: the same array (the no-gap numbers bit for bit)
    g = np.concatenate([t[:8], t[15:]])  # 0.4 s interval
    c = gap_clock(g)
    np.testing.assert_array_equal(c[:8], g[:8])
    np.testing.assert_allclose(np.diff(c), 0.05, atol=1e-12)
    x = np.concatenate([t[:8], t[12:]])  # a 0.2 s interval: not a gap (E30's limit, 0.25 s)
    assert gap_clock(x) is x
    np.testing.assert_allclose(gap_clock(np.concatenate([t[:8], t[13:]]))[8:] - t[13:], -0.25, atol=1e-12)


@pytest.mark.parametrize("incremental", [True, False])
def test_a_stride_across_a_short_foot_gap_is_integrated_as_offline_without_the_phantom_height(
        root, scenario_d, incremental):
    s = without(scenario_d, 50.0, 50.5)
    tr = Tracker(root / "bundle", incremental=incremental)
    steps = [st for c in per_timestamp(s) for st in tr.push(c)] + tr.flush()
    across = [st for st in steps if st.start_s < 50.5 and st.end_s > 49.95]
    assert len(across) == 1 and not across[0].classes and across[0].gap_s == 0.0
    dz = across[0].dz_m
    assert abs(dz) < 0.3, dz  # before: +2.03 m (the stride is level: the truth is 0)
    # offline track (FootDisplacement on the sample index, M2: the raw height change) moves the same stride
    # +0.26 m; the integrators differ (Kalman smoother vs trapezoid + linear ZUPT: up to 0.12 m per stride on
    # D without a gap), the rule across the gap is the same
    off = get_pipeline("plasys")(s, method="M2").steps
    row = off[(off.start_s < 50.5) & (off.end_s > 49.95)]
    assert len(row) == 1 and abs(float(row.dz_m.iloc[0]) - dz) < 0.2, (row, dz)
    # track --streaming, the offline streamed path, gives the same stride and trajectory (now also incremental)
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    assert len(res.steps) == len(steps)
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
