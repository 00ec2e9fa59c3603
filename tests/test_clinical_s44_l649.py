"""Decision L649 (session 44, trial T1 finding F7): the lower back's walk-test refusal names the marks asked and
whether the track was calibrated; a calibrated lower back (``calibrate``'s parameters) times a walkway with an
acceleration zone (the 10 m walk measured within 2.31 %, T1's 1,7.62,3.38 within 2.58 % on users 12462-12470), not
a walk from standing (the T25FW read +9.1 % median)."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.walk_test import lower_back_note, t25fw, ten_metre_walk, ten_metre_walk_trials


def _waist_walk(length_m: float, step_m: float = 0.5, step_s: float = 0.6) -> pd.DataFrame:
    """A steady straight lower-back walk of ``length_m`` (0.5 m steps in 0.6 s: 0.83 m/s)."""
    n = int(round(length_m / step_m))
    t = 3.0 + step_s * np.arange(n)
    return pd.DataFrame({"start_s": t, "end_s": t + step_s, "event_s": t + step_s, "length_m": step_m,
                         "heading_rad": 0.0, "unit": "waist"})


def test_the_note_names_the_marks_asked_and_the_calibration():
    walk = _waist_walk(16.0)
    note = ten_metre_walk(walk, (1.0, 7.62, 3.38))["ten_m_walk_note"]
    assert "the 1 m and 8.62 m marks" in note and "uncalibrated" in note and "2 m and 12 m" not in note
    assert "the 2 m and 12 m marks" in ten_metre_walk(walk)["ten_m_walk_note"]
    calibrated_t25 = t25fw(walk, calibrated=True)["t25fw_note"]
    assert "calibrated lower back from standing" in calibrated_t25 and "+9.1 %" in calibrated_t25
    assert "uncalibrated" in t25fw(walk)["t25fw_note"] and "the 7.62 m mark" in t25fw(walk)["t25fw_note"]
    assert lower_back_note(0.0, 6.0, calibrated=True).startswith("not given on the calibrated lower back")


def test_a_calibrated_lower_back_times_a_walkway_with_an_acceleration_zone():
    walk = _waist_walk(16.0)
    r = ten_metre_walk(walk, (1.0, 7.62, 3.38), calibrated=True)
    assert r["ten_m_walk_time_s"] == pytest.approx(7.62 / 0.5 * 0.6) and r["ten_m_walk_note"] is None
    assert len(ten_metre_walk_trials(walk, (1.0, 7.62, 3.38), calibrated=True)) == 1
    assert ten_metre_walk(walk, calibrated=True)["ten_m_walk_time_s"] == pytest.approx(12.0)  # 2,10,2
    assert ten_metre_walk(walk, (0.0, 7.62, 4.0), calibrated=True)["ten_m_walk_time_s"] is None  # from standing
    assert t25fw(walk, calibrated=True)["t25fw_time_s"] is None


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    d = tmp_path_factory.mktemp("l649")
    common = ["--user-seed", "12466", "--rate", "100", "--bounce", "pendulum", "--step-length", "0.45",
              "--step-time", "0.8"]
    assert main(["simulate", "--route", "stand:3, straight:30, stand:3", *common, "--seed", "9",
                 "--out", str(d / "cal")]) == 0
    assert main(["calibrate", str(d / "cal"), "-d", "30", "--out", str(d / "p.json")]) == 0
    assert main(["simulate", "--route", "stand:3, straight:16, stand:3", *common, "--out", str(d / "w")]) == 0
    return d


def test_track_times_the_10m_walk_on_a_calibrated_lower_back(walks):
    tr = pd.read_csv(walks / "w" / "trajectory.csv")
    t, x = tr["timestamp"].to_numpy(float) / 1000, tr["x"].to_numpy(float) - tr["x"].iloc[0]
    truth = float(t[np.argmax(x >= 12.0)] - t[np.argmax(x >= 2.0)])  # 17.72 s
    assert main(["track", "--no-plot", str(walks / "w"), "--units", "waist", "--params", str(walks / "p.json"),
                 "--out", str(walks / "cal_t")]) == 0
    s = json.loads((walks / "cal_t" / "summary.json").read_text())
    assert s["ten_m_walk_time_s"] == pytest.approx(truth, rel=0.03)
    assert main(["track", "--no-plot", str(walks / "w"), "--units", "waist", "--out", str(walks / "raw_t")]) == 0
    raw = json.loads((walks / "raw_t" / "summary.json").read_text())
    assert raw["ten_m_walk_time_s"] is None and "uncalibrated" in raw["ten_m_walk_note"]
