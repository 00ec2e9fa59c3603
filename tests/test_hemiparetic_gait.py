"""Session 30 trial `stroke` (hemiparetic gait on the lower back): W226 (the waist axis test names the stride rhythm
of a walker whose steps alternate short / long), W227 (a calibrated slow walk), W228 (steps per leg, step-time
asymmetry in the summary), W224/W225 (the lower back's cadence and speeds from strides)."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main

HEMI = ["--route", "stand:3, straight:14, stand:3", "--step-length", "0.3", "--step-time", "0.75",
        "--step-time-asymmetry", "0.39", "--step-length-asymmetry", "0.3", "--bounce", "pendulum", "--rate", "100",
        "--user-seed", "5520"]


@pytest.fixture(scope="module")
def hemi10(tmp_path_factory):
    """The trial's `hemi10` walk: steps 0.87 / 0.62 s alternating, stride 1.48 s."""
    out = tmp_path_factory.mktemp("hemi") / "hemi10"
    assert main(["simulate", *HEMI, "--out", str(out)]) == 0
    return out


def _waist_axes(capsys, folder) -> str:
    capsys.readouterr()
    assert main(["info", str(folder)]) == 0
    return next(line for line in capsys.readouterr().out.splitlines() if line.strip().startswith("waist axes"))


def test_info_names_the_stride_rhythm_of_a_slow_asymmetric_walk(hemi10, capsys, monkeypatch):
    """W226: a walk that repeats at its 1.5 s stride but at no step period is named (asymmetric or very slow gait),
    not "no walking rhythm", and not axis-checked; without the stride search it said "no walking rhythm"."""
    from pdrlearn.track import frame_inference

    line = _waist_axes(capsys, hemi10)
    assert "not checked" in line and "repeats at a stride of 1.5" in line and "asymmetric gait" in line, line
    assert "no walking rhythm" not in line and "contradicts" not in line
    monkeypatch.setattr(frame_inference, "STRIDE_ONLY_LAG_S", (1.0, 1.1))  # no stride searched where it lies
    assert "no walking rhythm" in _waist_axes(capsys, hemi10)


def test_calibration_covers_its_widened_cadence_range():
    """W227 (W211's band): inside the calibration walks' range +-10 % is covered, outside not, unjudged is None."""
    from pdrlearn.waist.plausibility import CALIBRATION_SPEED_MARGIN as m
    from pdrlearn.waist.plausibility import calibration_covers, calibration_speed_message

    gait = {"median_cadence_spm": 84.5, "cadence_range_spm": [83.0, 86.0]}
    assert calibration_covers(gait, 86.0 * (1 + m) * 0.99, 30) is True
    assert calibration_covers(gait, 83.0 * (1 - m) * 0.99, 30) is False
    assert calibration_speed_message(gait, 83.0 * (1 - m) * 0.99, 30, "waist-pendulum") is not None
    assert calibration_covers(gait, 85.0, 5) is None and calibration_covers(None, 85.0, 30) is None


@pytest.mark.parametrize("covers,calibrated", [(True, True), (False, False), (None, False)])
def test_a_slow_walk_calibrated_at_its_gait_says_so(covers, calibrated):
    """W227: L95's slow line of a lower-back track calibrated on walks at this cadence says the distance is
    calibrated at this gait (the classes and floors stay unvalidated); outside the range, or unjudged, it keeps
    "not reliable"."""
    from pdrlearn.track.gait import gait_range_warning

    info = {"pipeline": "waist-pendulum", "params_source": "calibrated", "calibration_covers_cadence": covers}
    line = gait_range_warning({"median_cadence_spm": 86.0, "median_speed_straight_mps": 0.45,
                               "n_straight_strides": 50, "info": info})
    assert "slower than the walking" in line
    assert ("distance and speed are calibrated at this gait" in line) is calibrated
    assert ("the distance, the terrain / direction / length classes and the floors are not reliable"
            in line) is not calibrated  # decision L324: the direction class too
    assert "floors are not validated" in line or not calibrated


def test_leg_summary_counts_steps_by_side_and_reads_the_asymmetry():
    """W228 by hand: a lower-back table's sides counted (undecided apart); steps alternating 0.8 / 0.4 s read the
    symmetry index 100 x 0.4 / 0.6 = 66.7 % (from 20 % it is given); a foot table has no per-leg count."""
    import numpy as np
    import pandas as pd

    from pdrlearn.track.clinical import LEG_KEYS, leg_summary

    st = np.cumsum([0.0] + [0.8, 0.4] * 8)
    waist = pd.DataFrame({"start_s": st, "end_s": np.append(st[1:], st[-1]), "length_m": 0.4, "unit": "waist",
                          "has_next": [True] * (len(st) - 1) + [False],
                          "side": (["left", "right"] * 9)[:len(st) - 1] + [""]})
    g = leg_summary(waist)
    assert set(g) == set(LEG_KEYS)
    assert (g["n_steps_left"], g["n_steps_right"], g["n_steps_side_undecided"]) == (8, 8, 1)
    assert g["step_time_asymmetry_pct"] == pytest.approx(200 / 3) and "asymmetric" in g["step_time_asymmetry_reason"]
    foot = waist.assign(unit="foot").drop(columns="side")
    f = leg_summary(foot)
    assert f["n_steps_left"] is None and f["step_time_asymmetry_pct"] is None
    assert "not observable from one foot" in f["step_time_asymmetry_reason"]
    assert leg_summary(waist.iloc[:0])["n_steps_left"] is None


def test_track_all_writes_the_per_leg_counts_and_asymmetry(hemi10, tmp_path):
    """W228: the trial's walk in sessions.csv: 24 / 24 steps by side, the lower back's step-time index given."""
    import json
    import shutil

    import pandas as pd

    d = tmp_path / "in" / "hemi10"
    shutil.copytree(hemi10, d, ignore=shutil.ignore_patterns("f*.csv"))  # the lower-back unit only
    assert main(["track-all", "--no-plot", str(tmp_path / "in"), "--out", str(tmp_path / "o")]) == 0
    row = pd.read_csv(tmp_path / "o" / "sessions.csv").iloc[0]
    assert row["pipeline"].startswith("waist")
    assert row["n_steps_left"] + row["n_steps_right"] + row["n_steps_side_undecided"] == row["n_steps"]
    assert abs(row["n_steps_left"] - row["n_steps_right"]) <= 2
    assert row["step_time_asymmetry_pct"] >= 20 and row["step_time_asymmetry_raw_pct"] >= 20
    summary = json.loads(next((tmp_path / "o").rglob("summary.json")).read_text())
    assert summary["n_steps_left"] == row["n_steps_left"] and summary["step_time_asymmetry_reason"]


def test_lower_back_cadence_and_speed_come_from_strides(tmp_path, capsys):
    """W225 on the trial's severe command (user 5526, A 0.75): the summary's cadence is near the truth of ics.csv
    (W70's step median read 91.0 for 74.7), and L95's slow line fires (it was hidden by 91.0 and 0.56 m/s)."""
    import json

    import numpy as np
    import pandas as pd

    from pdrlearn.track.bouts import cadence_spm

    sim, out = tmp_path / "c075", tmp_path / "c075_wp"
    assert main(["simulate", "--route", "stand:3, straight:12, stand:3", "--step-length", "0.3", "--step-time", "0.8",
                 "--step-time-asymmetry", "0.75", "--bounce", "pendulum", "--pelvis", "realistic", "--rate", "100",
                 "--user-seed", "5526", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--pipeline", "waist-pendulum", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    ic = np.sort(pd.read_csv(sim / "ics.csv")["ic_ms"].to_numpy(float)) / 1000
    truth = cadence_spm(len(ic) - 1, ic[-1] - ic[0])
    s = json.loads((out / "summary.json").read_text())
    assert abs(s["median_cadence_spm"] - truth) < 3.0, (s["median_cadence_spm"], truth)
    assert s["median_speed_straight_mps"] < 0.5 and s["gait_out_of_range"] is True
    assert "slower than the walking the pipelines were validated on" in err
