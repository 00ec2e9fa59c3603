"""Decision E320: gait values of the streamed strides on the lean runtime (``Tracker(gait=True)``,
:mod:`pdrlearn.runtime.gait`), by the offline tables' kernels (:mod:`pdrlearn.kernels.gait_values`). One short
simulated walk (test user 17149, the shipped bundle) streamed once; the rest on hand-made steps."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.gait_values import cadence_speed, side_pair
from pdrlearn.runtime import Tracker
from pdrlearn.runtime.gait import STRIDE_COLUMNS, StrideGait, bout_end_rows, gait_summary
from pdrlearn.runtime.tracker import Step
from pdrlearn.track.gait import gait_summary as offline_summary
from pdrlearn.track.gait import streamed_gait_columns
from tests.lean_helpers import ROOT
from tests.runtime_helpers import gait_replay

BUNDLE = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def streamed():
    return gait_replay(BUNDLE, 17149, "stand:2, straight:12, stand:2")[1:]


def test_the_strides_equal_runs_steps_table(streamed):
    """The lean values equal what `run` writes for the same steps (streamed_gait_columns on Step.to_dict rows)."""
    tr, steps = streamed
    mine = tr.gait_strides()
    assert list(mine) == list(STRIDE_COLUMNS) and len(mine["start_s"]) == len(steps) >= 6
    table = streamed_gait_columns(pd.DataFrame([st.to_dict() for st in steps]).assign(unit="foot"))
    for c in ("stride_time_s", "cadence_spm", "speed_mps", "turn_angle_rad", "event_s"):
        np.testing.assert_allclose(mine[c], table[c].to_numpy(float), rtol=0, atol=1e-12, err_msg=c)
    assert np.isfinite(mine["stride_time_s"]).sum() >= len(steps) - 2  # the contacts ran (E49)
    off = offline_summary(table)
    got = tr.gait_summary()
    for k in ("median_stride_time_s", "median_cadence_spm", "median_speed_mps"):
        assert got[k] == pytest.approx(off[k], abs=1e-12), k
    assert got["median_stride_length_m"] == pytest.approx(float(np.median(np.abs(table["length_m"]))), abs=1e-12)
    assert got["cv_stride_time_pct"] is None  # fewer than L113's 10 strides
    both = tr.gait_summary(tr)  # the same foot twice: symmetric, but too few strides (L461)
    assert both["stride_time_s_si_pct"] is None and "L461" in both["si_withheld"]
    assert both["stride_time_s_left"] == both["stride_time_s_right"] == got["mean_stride_time_s"]


def test_the_tracker_refuses_gait_without_contacts_and_says_how(streamed):
    with pytest.raises(DataError, match="contacts=True"):
        Tracker(BUNDLE, units=("foot",), gait=True)
    tr = Tracker(streamed[0].bundle, units=("foot",), contacts=True)
    with pytest.raises(DataError, match="gait=True"):
        tr.gait_summary()


def _step(t0, length, event=0.5, **kw):
    return Step(t0, t0 + 1.0, length_m=length, event_s=t0 + event, turn_angle_rad=0.01, **kw)


def test_gap_and_impossible_rows_have_no_gait_values_and_the_indices():
    g = StrideGait()
    g.add([_step(0.0, 1.2), _step(1.0, 1.3), Step(2.0, 5.0, gap_s=2.0), _step(5.0, 1.4), _step(6.0, 0.0,
                                                                                            impossible=True)])
    g.add([_step(7.0, -1.2)])  # a backward stride's length is its |length| (L746)
    s = g.strides()
    np.testing.assert_allclose(s["stride_time_s"], [np.nan, 1.0, np.nan, np.nan, np.nan, np.nan])
    np.testing.assert_allclose(s["stride_length_m"], [1.2, 1.3, np.nan, 1.4, np.nan, 1.2])
    assert math.isnan(s["turn_angle_rad"][2]) and s["turn_angle_rad"][4] == 0.01  # L109: a guarded stride's turn
    cad, speed = cadence_speed([1.3, -1.3], [1.0, 2.0])
    np.testing.assert_allclose(cad, [120.0, 60.0])
    np.testing.assert_allclose(speed, [1.3, 0.65])
    assert s["speed_mps"][1] == pytest.approx(1.3) and s["cadence_spm"][1] == pytest.approx(120.0)
    left, right = StrideGait(), StrideGait()
    left.add([_step(float(i), 1.4) for i in range(12)])
    right.add([_step(i * 1.1, 1.2, event=0.6) for i in range(12)])
    out = gait_summary(left, right)
    assert out["si_withheld"] is None
    assert out["stride_time_s_si_pct"] == pytest.approx(100 * 0.1 / 1.05)  # Robinson's SI of 1.0 and 1.1 s
    assert out["stride_length_m_si_pct"] == pytest.approx(100 * 0.2 / 1.3)
    assert out["stride_length_m_ratio"] == pytest.approx(side_pair("x", 1.4, 1.2)["x_ratio"])
    assert out["left"]["cv_stride_time_pct"] == pytest.approx(0.0, abs=1e-9)  # 11 stride times of 1.0 s


def test_half_strides_leave_the_stride_length_index_e321():
    """Decision E321: a walk started and ended with the feet side by side (L317): the first foot's first stride and
    the last foot's last stride are half strides; they leave the stride-length means, CV and index."""
    left, right = StrideGait(), StrideGait()
    left.add([_step(float(i), 0.7 if i == 0 else 1.4) for i in range(12)])
    right.add([_step(i + 0.5, 0.7 if i == 11 else 1.4) for i in range(12)])
    ends = bout_end_rows(np.r_[left.strides()["event_s"], right.strides()["event_s"]], np.ones(24, bool))
    assert np.flatnonzero(ends).tolist() == [0, 23]  # the walk's first and last contact
    out = gait_summary(left, right)
    assert out["stride_length_m_si_pct"] == pytest.approx(0.0, abs=1e-12)  # E320 read 100 x 0.7 / 12 / 1.3706 %
    assert out["left"]["mean_stride_length_m"] == pytest.approx(1.4) and out["left"]["n_full_strides"] == 11
    assert out["left"]["cv_stride_length_pct"] == pytest.approx(0.0, abs=1e-9)
    assert out["left"]["median_stride_length_m"] == pytest.approx(1.4) and out["left"]["n_strides"] == 12
    one = left.summary()  # one foot: each of its bouts' first and last stride
    assert one["n_full_strides"] == 10 and one["mean_stride_length_m"] == pytest.approx(1.4)
    stop = StrideGait()  # a stop over L79's 3 s splits the bouts
    stop.add([_step(float(i), 1.4) for i in range(5)] + [_step(10.0 + i, 1.4) for i in range(5)])
    assert np.flatnonzero(stop.bout_ends()).tolist() == [0, 4, 5, 9]
