"""Decisions E349 / E350 (session 52, FF, trial s52t1 F7 / F9): the live trackers' lines. E349: the phone tracker's
gap line says what the live tracker does (no "re-record or trim"); a sample out of order names the runtime's
Reorderer; the waist barometer's order refusal gives the times and the drop_duplicate_timestamps fix (the motion
push's mechanism), and drops repeats with that option; ``export --frame`` of a misspelt file says no such file.
E350: the live Tracker says offline track's L95 line for a walk below the validated range. All at kernel level."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from pdrlearn.errors import DataError


def test_the_live_waist_gap_line_says_what_the_tracker_does_e349():
    from pdrlearn.runtime.waist import WaistTracker

    tr = WaistTracker.__new__(WaistTracker)
    tr._proc, tr._n_gaps, tr.warnings = SimpleNamespace(gaps={"online stream": [(60.0, 63.0)]}), 0, []
    tr._gap_warnings()
    (line,) = tr.warnings
    assert "3.0 s at 60.0 s" in line and "re-record" not in line and "goes on" in line and "filled as a rest" in line


def test_a_foot_sample_out_of_order_names_the_reorderer_e349():
    from pdrlearn.runtime import Tracker
    from pdrlearn.runtime.links import order_error

    t = np.array([60.0, 60.01, 60.03, 60.02, 60.04])
    with pytest.raises(DataError, match=r"not increasing \(at 60\.020 s after 60\.030 s\).*Reorderer\(hold_s="):
        Tracker.__new__(Tracker)._checked_arrays("fAccelerometer", t, np.zeros((5, 3)))
    late = order_error("fAccelerometer", 60.0, 60.99, duplicate=False, max_lag_s=5.0, offset_s=0.0, other_newest=None)
    assert "Reorderer(hold_s=" in str(late) and "in the order it sent them" in str(late)


def test_the_barometer_order_line_gives_the_times_and_the_fix_e349():
    from pdrlearn.waist import WaistTracker  # the phone tracker; the bundle's shares WaistStream.push_barometer

    t = np.round(np.arange(60.0, 60.5, 0.01), 2)
    tr = WaistTracker(100.0, sensor_height_m=1.0)
    tr.push_barometer(t, np.full(50, 1000.0))
    with pytest.raises(DataError) as e:  # the same chunk pushed again (trial F7: a packet sent twice)
        tr.push_barometer(t, np.full(50, 1000.0))
    msg = str(e.value)
    assert msg.startswith("WaistTracker.push_barometer: timestamps must increase strictly across pushes")
    assert "(t=60.000000 s)" in msg and "(t=60.490000 s)" in msg and "sort the samples" in msg
    with pytest.raises(DataError, match=r"repeats the previous push's last \(t=60\.490000 s\); pass "
                                        r"drop_duplicate_timestamps=True"):
        tr.push_barometer([60.49, 60.5], [1000.0, 1000.0])
    keep = WaistTracker(100.0, sensor_height_m=1.0)
    keep._drop_dups = True  # what the bundle's WaistTracker(drop_duplicate_timestamps=True) sets (E203)
    keep.push_barometer(t, np.full(50, 1000.0))
    keep.push_barometer([60.49, 60.5], [1000.0, 1000.0])  # the repeat dropped, the new sample taken
    assert keep.n_dropped_duplicates == 1 and keep._baro_last == 60.5


def _export(path, frame):
    from pdrlearn.cli.export import export

    export(path, out=path.parent / "out", methods=None, length_bounds=None, no_training_samples=False, float32=False,
           units=None, force=False, as_json=False, frame=frame)


def test_export_frame_of_a_missing_file_says_no_such_file_e349(tmp_path):
    with pytest.raises(DataError, match=r"nosuch\.json: no such file; --frame exports a waist calibration"):
        _export(tmp_path / "nosuch.json", "x=up,y=right,z=forward")
    (tmp_path / "other.json").write_text("{}")
    with pytest.raises(DataError, match="is not a waist calibration"):
        _export(tmp_path / "other.json", "x=up,y=right,z=forward")
    (tmp_path / "model").mkdir()
    with pytest.raises(DataError, match="is a model directory"):
        _export(tmp_path / "model", "x=up,y=right,z=forward")


def test_the_streamed_slow_line_is_offlines_e350():
    from pdrlearn.kernels.gait_range import streamed_slow_line
    from pdrlearn.track.gait import gait_range_warning

    cad, speed, straight = np.full(12, 97.0), np.full(12, 0.45), np.ones(12, bool)
    line = streamed_slow_line(cad, speed, straight)
    offline = gait_range_warning({"median_cadence_spm": 97.0, "median_speed_straight_mps": 0.45,
                                  "n_straight_strides": 12, "info": {"streaming": True}})
    assert line == offline and "straight-walking speed 0.45 m/s" in line
    assert streamed_slow_line(cad, np.full(12, 1.2), straight) is None  # inside the range
    few = streamed_slow_line(cad, np.r_[np.full(4, 0.3), np.full(8, 0.9)], np.r_[np.ones(4, bool), np.zeros(8, bool)])
    assert few is None  # L123: 4 straight strides are too few; all strides' median 0.9 m/s is judged


def test_the_live_tracker_says_the_slow_line_at_flush_e350():
    from pdrlearn.runtime import Tracker
    from pdrlearn.runtime.tracker import Step

    tr = Tracker.__new__(Tracker)
    tr.warnings, tr.bundle = [], SimpleNamespace(path="b")
    prev = (0.0, 1.2, math.nan)
    for k in range(1, 10):  # 1.24 s strides of 0.56 m: 97 steps/min, 0.45 m/s, straight and level
        st = Step(1.24 * k, 1.24 * k + 1.2, length_m=0.558, turn_angle_rad=0.01)
        tr._note_range(st, prev)
        prev = (st.start_s, st.end_s, math.nan)
    tr._slow_line()
    tr._slow_line()  # said once
    assert len(tr.warnings) == 1 and "slower than the walking the pipelines were validated on" in tr.warnings[0]
    assert "0.45 m/s" in tr.warnings[0] and "E350" in tr.warnings[0]
