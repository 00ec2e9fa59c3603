"""Decision L498 (session 38, trial T5 finding 1): the streamed waist turn between two strides covers the whole stop
(up to 60 s), so the pelvis's turn back into its rest early in a stop is not lost at every stop of 3 s or more."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.kernels import stride as K

ROOT = Path(__file__).resolve().parents[1]


def _waist_stop(stop_s: float, turn_rad: float = 0.05):
    """A waist at rest (gravity on +z) that turns ``turn_rad`` about the vertical in the first 0.5 s of a stop of
    ``stop_s`` s between a stride ending at 10 s and the next starting at 10 + stop_s (100 Hz)."""
    t = np.arange(9.0, 10.0 + stop_s + 0.5, 0.01)
    gyr = np.zeros((len(t), 3))
    gyr[(t >= 10.0) & (t < 10.5), 2] = turn_rad / 0.5
    acc = np.tile([0.0, 0.0, 9.80665], (len(t), 1))
    streams = {"wGyroscope": (t, gyr), "wAccelerometer": (t, acc)}
    return streams.__getitem__, 10.0, 10.0 + stop_s


@pytest.mark.parametrize("stop_s", [1.0, 3.0, 10.0, 59.0])
def test_waist_gap_yaw_keeps_a_turn_early_in_a_stop_l498(stop_s):
    stream, t_end, t_next = _waist_stop(stop_s)
    assert K.waist_gap_max_s(t_end, t_next) == pytest.approx(stop_s)
    got = K.stride_gap_yaw(None, "waist-gyro", stream, t_end, t_next, waist=True)  # the runtime's call
    assert got == pytest.approx(0.05, abs=2e-3)  # L31's last second alone: 0 for the 3-59 s stops


def test_whole_gap_is_the_rule_not_a_module_switch_w413():
    """W413: L498 was adopted, so the whole stop is the kernel's rule; no ``WAIST_GAP_WHOLE`` global to flip back to
    L31's last second (that arm is at commit d3ffb129)."""
    stream, t_end, t_next = _waist_stop(3.0)
    assert K.stride_gap_yaw(None, "waist-gyro", stream, t_end, t_next, waist=True) == pytest.approx(0.05, abs=2e-3)
    assert not hasattr(K, "WAIST_GAP_WHOLE")


def test_a_rest_over_a_minute_keeps_the_last_second_l498():
    stream, t_end, t_next = _waist_stop(120.0)
    assert K.waist_gap_max_s(t_end, t_next) == K.GAP_YAW_MAX_S  # E205's radius skips exactly these gaps
    assert K.stride_gap_yaw(None, "waist-gyro", stream, t_end, t_next, waist=True) == 0.0


def test_streamed_heading_does_not_step_at_each_stop_l498(tmp_path):
    """End to end: a slow walk with five stops of 3-10 s (user 9750) through `run`'s replay of the shipped bundle:
    the heading after the last stop is within 2 deg of the heading after the first stride (before L498 it fell
    2-3 deg at every stop of 3 s or more: about -11 deg here)."""
    import pandas as pd

    from pdrlearn.cli import main

    walk = tmp_path / "walk"
    route = ("stand:3, straight:6, stand:3, straight:6, stand:5, straight:6, stand:10, straight:6, stand:4, "
             "straight:6, stand:3, straight:6, stand:3")
    assert main(["simulate", "--route", route, "--step-length", "0.5", "--step-time", "0.7", "--bounce", "pendulum",
                 "--user-seed", "9750", "--out", str(walk)]) == 0
    assert main(["run", "--no-plot", str(ROOT / "models" / "plasys-sim-default"), str(walk), "--out",
                 str(tmp_path / "o")]) == 0
    h = np.degrees(pd.read_csv(tmp_path / "o" / "steps.csv")["heading_rad"].to_numpy())
    assert len(h) > 20
    assert math.fabs(np.median(h[-5:]) - np.median(h[1:5])) < 2.0, h.round(1)


def _live_steps(walk: Path, chunk_s: float):
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.runtime.replay import read_streams, replay_chunks

    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    tracker = Tracker(bundle)
    streams, _ = read_streams(walk, bundle)
    steps = [s for chunk in replay_chunks(streams, chunk_s) for s in tracker.push(chunk)]
    return tracker, steps + list(tracker.flush())


def test_turns_read_from_turn_and_pivot_e210(tmp_path):
    """E210: an app pushing 0.1 s chunks announces turns from turn_angle_rad + pivot_rad (the heading unit's change,
    = Tracker.heading's), as docs/deploying.md shows; and L498: a 10 s stop's samples stay buffered live, so the
    0.1 s chunks give the heading one whole push gives."""
    from pdrlearn.cli import main

    walk = tmp_path / "walk"
    assert main(["simulate", "--route", "stand:3, straight:6, stand:10, straight:4, turn:90, straight:4, stand:3",
                 "--step-length", "0.5", "--step-time", "0.7", "--bounce", "pendulum", "--user-seed", "9751",
                 "--out", str(walk)]) == 0
    tracker, steps = _live_steps(walk, 0.1)
    turned = sum(s.turn_angle_rad + s.pivot_rad for s in steps)
    assert turned == pytest.approx(tracker.heading, abs=1e-6)  # initial heading 0
    assert 60.0 < math.degrees(turned) < 120.0
    whole, steps_whole = _live_steps(walk, 1e6)
    assert [round(s.heading_rad, 6) for s in steps] == [round(s.heading_rad, 6) for s in steps_whole]
    text = (ROOT / "docs" / "deploying.md").read_text()
    assert "Announcing turns live" in text and "turn_angle_rad + step.pivot_rad" in text


def test_live_tracker_keeps_a_stops_samples_for_the_waist_gap_yaw_l498(tmp_path):
    """L498: pushed in 0.1 s chunks, the Tracker still holds the waist's samples from the last stride's end 10 s into
    a 12 s stop (before: trimmed to buffer_s = 8 s, so a turn early in the stop was lost live)."""
    from pdrlearn.cli import main
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.runtime.replay import read_streams, replay_chunks

    walk = tmp_path / "walk"
    assert main(["simulate", "--route", "stand:3, straight:6, stand:12, straight:4, stand:3", "--step-length", "0.5",
                 "--step-time", "0.7", "--bounce", "pendulum", "--user-seed", "9752", "--out", str(walk)]) == 0
    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    tracker = Tracker(bundle)
    streams, _ = read_streams(walk, bundle)
    checked = False
    for chunk in replay_chunks(streams, 0.1):
        tracker.push(chunk)
        end = tracker._prev_end
        if end is not None and tracker._latest - end > 10.0:
            t, _ = tracker._buf["wGyroscope"].view()
            assert t[0] <= end, (t[0], end)
            checked = True
            break
    assert checked
