"""Decision W519 (session 46, I6): a lower-back ramp must rise at least twice the barometer's rest swing - the
median altitude change over the track's standstills - or it is the barometer's own swing (HA001 Test11's 3-4 s swing
of +-0.18 m read two ramps on a lab floor with W517's 4 m slope)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.grade import RAMP_REST_SWING_FACTOR, ramp_runs, rest_rise_floor_m, rest_swing_m, track_ramps

TEST11 = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


def test_rest_swing_is_the_median_stand_change_of_three_or_more_stands_w519():
    still = [0.0, 2.0, 0.5, 3.0, 1.0, 4.0]
    dz = [0.9, -0.3, 0.8, 0.1, 0.2, -0.5]
    assert rest_swing_m(still, dz) == pytest.approx(0.25)  # |-0.3|, |0.1|, |0.2|, |-0.5|: rows under 1 s left out
    assert rest_swing_m(still, dz, ride=[False, True, False, False, False, False]) == pytest.approx(0.2)
    assert rest_swing_m([2.0, 2.0, 0.0], [0.3, 0.3, 0.3]) is None  # two stands: no floor


def test_a_ramp_under_the_floor_is_left_out_w519():
    length = np.full(10, 0.7)
    dz = np.r_[np.zeros(2), np.full(6, 0.03), np.zeros(2)]  # a 4.2 m run rising 0.18 m (4.3 %)
    assert len(ramp_runs(length, dz, window_m=4.0)) == 1
    assert len(ramp_runs(length, dz, window_m=4.0, min_rise_m=0.2)) == 0
    assert len(ramp_runs(length, dz, window_m=4.0, min_rise_m=0.1)) == 1


def _lower_back(swing: float) -> pd.DataFrame:
    """Four walking sequences of 6 steps (0.7 m), each after a 3 s stand whose barometric change is +-``swing``;
    the second climbs 0.03 m a step (a 4.2 m "ramp" rising 0.18 m at 4.3 %)."""
    rows, t = [], 0.0
    for k in range(4):
        for i in range(6):
            rows.append({"start_s": t, "end_s": t + 0.6, "length_m": 0.7, "unit": "waist",
                         "dz_m": 0.03 if k == 1 else 0.0, "has_next": i < 5,
                         "still_before_s": 3.0 if i == 0 else 0.0,
                         "pause_dz_m": (swing if k % 2 else -swing) if i == 0 else 0.0})
            t += 0.6
        t += 3.0
    return pd.DataFrame(rows)


def test_a_lower_back_track_drops_a_ramp_within_its_rest_swing_w519():
    swinging = _lower_back(0.3)
    assert rest_rise_floor_m(swinging) == pytest.approx(RAMP_REST_SWING_FACTOR * 0.3)
    assert track_ramps(swinging, None)[0] == []  # 0.18 m within 2 x 0.3 m: the barometer's own swing
    quiet = _lower_back(0.02)
    got = track_ramps(quiet, None)[0]
    assert len(got) == 1 and got[0]["rise_m"] == pytest.approx(0.18)  # a still barometer keeps it


@pytest.mark.skipif(not (TEST11 / "wBarometer.csv").exists(), reason="needs datasets/real")
def test_test11_has_no_ramp_on_its_lab_floor_w519(tmp_path):
    from pdrlearn.cli import main

    assert main(["track", str(TEST11), "--out", str(tmp_path / "t")]) == 0
    ramps = pd.read_csv(tmp_path / "t" / "ramps.csv")
    assert len(ramps) == 0  # W517 alone: 2 (5.59 s +0.359 m, 119.91 s -0.106 m); INDIP: no incline in any bout
