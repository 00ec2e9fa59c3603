"""Session 41, fixer FG (trial T3, an accessibility audit: findings F3, F5, F8, F9): ``curbs.csv`` (L573), the line
that ramps need ``--altitude fused`` (L574), no ascent without a lower-back barometer (L575), the terrain check that
names a ramp (C159), the lower-back grade warning (W463) and the lower-back grade window kept (W465)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.kernels.altitude_check import steady_slope, terrain_dz_check
from pdrlearn.track.curbs import CURB_COLUMNS, curb_rows, curb_table
from pdrlearn.track.evaluate import lower_back_grade_warning, ramps_need_fused_warning, summary_warnings

#: T3's F3 route: two 1.8 m curb ramps (1:12), a 0.15 m curb up and one down (truth: up at x 17.6, down at x 9.6)
CURB_ROUTE = ("stand:3, straight:6, slope:1.8:8.33, straight:8, slope:1.8:-8.33, straight:6, turn:180, straight:6, "
              "up:1:0.15:0.3, straight:8, down:1:0.15:0.3, straight:6, stand:3")


@pytest.fixture(scope="module")
def curb_session(tmp_path_factory):
    d = tmp_path_factory.mktemp("curb") / "s"
    assert main(["simulate", "--route", CURB_ROUTE, "--user-seed", "11487", "--out", str(d)]) == 0
    return d


@pytest.mark.parametrize("fused", [False, True])
def test_a_curb_up_and_down_are_listed_l573(curb_session, tmp_path, fused):
    out = tmp_path / "t"
    assert main(["track", str(curb_session), "--out", str(out), "--no-plot",
                 *(["--altitude", "fused"] if fused else [])]) == 0
    curbs = pd.read_csv(out / "curbs.csv")
    assert list(curbs.columns) == list(CURB_COLUMNS)
    # fused: the curbs alone (its curb ramps read 0.04 m); the foot's own heights: also the 1.8 m curb ramp down,
    # whose one stride fell 0.107 m (L573's measurement; the docs say a curb ramp may read as a curb)
    assert len(curbs) == (2 if fused else 3)
    curbs = curbs.iloc[-2:]
    assert curbs["direction"].tolist() == ["up", "down"]
    assert (curbs["dz_m"].abs() >= 0.10).all() and (curbs["dz_m"].abs() <= 0.20).all()
    assert curbs["x_m"].tolist() == pytest.approx([17.6, 9.6], abs=1.2)  # within a stride of the curbs
    assert len(pd.read_csv(out / "stairs.csv")) == 0  # one stride is no flight (L438): it was listed nowhere


def _steps(dz, unit="foot"):
    n = len(dz)
    length = np.where(np.abs(np.asarray(dz)) >= 0.17, 0.56, 1.2)  # stair strides short, others full
    return pd.DataFrame({"start_s": np.arange(n) * 1.0, "end_s": np.arange(n) + 1.0, "length_m": length,
                         "dz_m": dz, "gap_s": 0.0, "unit": unit, "heading_rad": 0.0})


def test_curbs_leave_out_flights_and_the_lower_back_l573():
    dz = [0, 0, 0.15, 0, 0, 0, 0, 0, 0.34, 0.34, 0.34, 0, 0, 0, 0, 0, 0, -0.12, 0, 0]
    traj = pd.DataFrame({"t": np.arange(len(dz) + 1) * 1.0, "x": np.arange(len(dz) + 1) * 1.2, "y": 0.0})
    t = curb_table(_steps(dz), traj, {})
    assert t["start_s"].tolist() == [2.0, 17.0] and t["direction"].tolist() == ["up", "down"]  # not the flight
    assert t["x_m"].tolist() == pytest.approx([3.0, 21.0])  # halfway through the stride
    assert curb_table(_steps(dz, unit="waist"), traj, {}).empty  # a barometer does not see a curb
    assert curb_rows([0.09, 0.10, -0.3], [True] * 3, [False, False, True]).tolist() == [False, True, False]


def test_ramps_need_fused_is_said_l574():
    s = {"barometer_unused": True, "grade_source": None, "barometer_ascent_m": 0.56, "barometer_descent_m": 0.61}
    line = ramps_need_fused_warning(s)
    assert "ramps / grades need --altitude fused (L300)" in line and line in summary_warnings(s)
    assert ramps_need_fused_warning({**s, "barometer_ascent_m": 0.0, "barometer_descent_m": 0.0}) is None  # level
    assert ramps_need_fused_warning({**s, "barometer_unused": False, "grade_source": "fused"}) is None


def test_no_barometer_gives_no_ascent_l575(curb_session, tmp_path):
    d = tmp_path / "nobaro"
    shutil.copytree(curb_session, d)
    (d / "wBarometer.csv").unlink()
    out = tmp_path / "w"
    assert main(["track", str(d), "--pipeline", "waist-pendulum", "--out", str(out), "--no-plot"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["ascent_m"] is None and s["descent_m"] is None and s["altitude_drift_m"] is None
    assert pd.read_csv(out / "bouts.csv")["ascent_m"].isna().all()


def test_terrain_check_names_a_ramp_on_a_steady_slope_c159():
    # T3's -6 % ramp through the shipped model: 10 strides classed up whose integrated heights fall 0.09-0.12 m
    terr = ["flat"] * 4 + ["up"] * 10 + ["flat"] * 4
    raw = np.array([-0.01, -0.02, -0.01, 0.0] + [-0.102, -0.109, -0.093, -0.11, -0.112, -0.11, -0.107, -0.109,
                                                  -0.097, -0.115] + [-0.01] * 4)
    msg, info = terrain_dz_check(terr, raw, raw)
    assert "a ramp or slope the model never saw" in msg and info["steady_slope_strides"] == 10
    # a stair flight classed against its sign: strides of 0.3 m are no slope
    msg, info = terrain_dz_check(terr, np.where(np.abs(raw) > 0.05, raw * 3, raw), raw)
    assert "contradict" in msg and "never saw" not in msg and "steady_slope_strides" not in info
    assert steady_slope([True] * 6, [0.05, 0.05, -0.05, 0.05, 0.05, 0.05]) is None  # 4 in a row are not 5


def test_lower_back_grades_warn_about_calibration_w463():
    s = {"grade_source": "barometer", "n_ramps": 2, "info": {"params_source": "defaults"}}
    assert "pdrlearn calibrate" in lower_back_grade_warning(s) and lower_back_grade_warning(s) in summary_warnings(s)
    assert "calibration sets it" in lower_back_grade_warning({**s, "info": {"params_source": "calibrated"}})
    assert lower_back_grade_warning({**s, "grade_source": "fused"}) is None
    assert lower_back_grade_warning({**s, "n_ramps": 0}) is None


def test_lower_back_grade_window_kept_w465():
    from pdrlearn.track.grade import GRADE_WINDOW_ROWS, WAIST_SLOPE_WINDOW_M

    # W465: 5 and 7 rows failed the rule (one-ramp sessions 7 of 14, not 12); W517 replaced the three rows by a 4 m
    # least-squares slope (tests/test_waist_ramps_s45_w517.py)
    assert "waist" not in GRADE_WINDOW_ROWS and WAIST_SLOPE_WINDOW_M == 4.0


def test_a_lone_noisy_step_splits_no_lower_back_ramp_w464():
    from pdrlearn.track.grade import ramp_runs, ramp_table

    # a 1:12 ramp of 0.7 m steps with one step of 0.15 m (21 %, a stair row) in its middle, level before and after
    dz = np.r_[np.zeros(4), np.full(6, 0.058), 0.15, np.full(6, 0.058), np.zeros(4)]
    length = np.full(len(dz), 0.7)
    assert len(ramp_runs(length, dz, 3)) == 2  # L301 alone: the stair row splits it
    assert len(ramp_runs(length, dz, 3, lone_stair_joins=True)) == 1
    steps = pd.DataFrame({"start_s": np.arange(len(dz)) * 0.5, "end_s": np.arange(len(dz)) * 0.5 + 0.5,
                          "length_m": length, "dz_m": dz, "gap_s": 0.0, "unit": "waist"})
    assert len(ramp_table(steps, {})) == 1  # the lower back's ramps.csv joins them (W464)
    two = np.r_[np.zeros(4), np.full(6, 0.058), 0.15, 0.15, np.full(6, 0.058), np.zeros(4)]  # two stair steps
    assert len(ramp_runs(np.full(len(two), 0.7), two, 3, lone_stair_joins=True)) == 2
