"""Decisions L195-L197, W177-W178 (docs/decisions/localization.md, waist.md): L95's walking range judged per bout
(bouts.csv ``gait_out_of_range``, summary ``gait_out_of_range``), the stride-time CV pooled over bouts of different
rhythm named, and the fast-gait wording (session 27 runner trial, F1-F3, F6)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.bouts import BoutsTable, detected_bouts
from pdrlearn.track.clinical import clinical_summary, pooled_cv_warning
from pdrlearn.track.evaluate import add_gait_range_flag, summary_warnings
from pdrlearn.track.gait import bout_range_flags, bout_range_warning, gait_range_warning

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"

#: decision C192: L95's fast line at a walking speed states the cadence above the validated range first
_SHORT_FAST = ("a cadence above the walking range the pipelines were validated on (short fast steps: quick dance "
               "steps, a festinating or shuffling gait; or running)")


def _bouts(rows):
    cols = ("n_strides", "cadence_spm", "speed_mps")
    return BoutsTable([dict(zip(cols, r, strict=True)) for r in rows])


def test_bout_flags_judge_the_fast_side_on_bouts_of_5_strides():
    t = _bouts([(81, 109.0, 1.34), (31, 188.2, 2.93), (4, 190.0, 3.0), (20, 60.0, 0.3), (20, 163.0, 1.4)])
    # the run is flagged; 4 strides are too few; a slow bout is left to the session's check (L195: fast side only)
    assert bout_range_flags(t, None).tolist() == [False, True, False, False, True]
    # L148: a 0.84 m leg's range reaches 165 steps/min, so 163 steps/min is inside it
    assert bout_range_flags(t, 0.84).tolist() == [False, True, False, False, False]
    assert bout_range_flags(_bouts([]), None).tolist() == []


def _walk_run_summary(**kw):
    return {"median_cadence_spm": 110.0, "median_speed_straight_mps": 1.37, "n_straight_strides": 150,
            "n_bouts": 3, "n_bouts_out_of_range": 1,
            "bouts_out_of_range": [{"bout": 2, "start_s": 113.12, "end_s": 133.35, "cadence_spm": 188.2,
                                    "speed_mps": 2.93}], **kw}


def test_the_bout_line_names_the_bout_and_the_flag_is_set():
    s = _walk_run_summary()
    line = bout_range_warning(s)
    assert line.startswith("1 of 3 walking bout(s) lie above the walking range (the session's median cadence 110 "
                           "steps/min is inside it): bout 2 (113.1-133.3 s, cadence 188 steps/min, speed 2.93 m/s: "
                           "looks like running)")
    assert "decision L195" in line and "\n" not in line and line in summary_warnings(s)
    assert add_gait_range_flag(s)["gait_out_of_range"] is True
    # a session L95 already calls fast gets no second line; its flag is set
    fast = _walk_run_summary(median_cadence_spm=185.0)
    assert bout_range_warning(fast) is None and gait_range_warning(fast) is not None
    assert add_gait_range_flag(fast)["gait_out_of_range"] is True
    quiet = _walk_run_summary(n_bouts_out_of_range=0, bouts_out_of_range=[])
    assert bout_range_warning(quiet) is None and add_gait_range_flag(quiet)["gait_out_of_range"] is False
    # the flag follows L95's slow side too
    assert add_gait_range_flag({**quiet, "median_speed_straight_mps": 0.3})["gait_out_of_range"] is True


def _foot_table(stride_times: list[list[float]], pause_s: float = 20.0) -> pd.DataFrame:
    """A foot steps table of straight level strides, one list of stride times per bout, bouts ``pause_s`` apart."""
    rows, t = [], 0.0
    for bout in stride_times:
        for s in bout:
            rows.append({"start_s": t, "end_s": t + 0.6 * s, "event_s": t + 0.6 * s, "stride_time_s": s,
                         "turn_angle_rad": 0.0, "gap_s": 0.0, "length_m": 1.0, "dz_m": 0.0, "heading_rad": 0.0,
                         "unit": "foot"})
            t += s
        t += pause_s
    return pd.DataFrame(rows)


def test_a_cv_over_bouts_of_different_rhythm_is_named_and_kept():
    rng = np.random.default_rng(0)
    walk = list(1.10 * (1 + 0.02 * rng.standard_normal(20)))
    run = list(0.64 * (1 + 0.02 * rng.standard_normal(15)))
    out = clinical_summary(_foot_table([walk, run, walk]))
    assert out["stride_time_cv_pct"] > 15  # kept, as before (L196 warns, it does not withhold)
    assert out["stride_time_cv_within_bouts_pct"] < 3
    assert [b["bout"] for b in out["stride_time_cv_bouts"]] == [1, 2, 3]
    assert [round(b["median_stride_time_s"], 1) for b in out["stride_time_cv_bouts"]] == [1.1, 0.6, 1.1]
    line = pooled_cv_warning(out)
    assert "pools walking bouts of different rhythm" in line and "decision L196" in line
    # bouts of one rhythm: no line, the keys empty
    same = clinical_summary(_foot_table([walk, walk]))
    assert same["stride_time_cv_within_bouts_pct"] is None and same["stride_time_cv_bouts"] == []
    assert pooled_cv_warning(same) is None
    # a bout with fewer than 5 of the CV's strides is not judged: one judged bout, no line
    short = clinical_summary(_foot_table([walk, run[:6]]))
    assert short["stride_time_cv_bouts"] == [] and pooled_cv_warning(short) is None


@pytest.mark.parametrize(("summary", "first"), [
    # W178: 200 steps/min at 1.95 m/s (the trial's uncalibrated lower back) names running first
    ({"median_cadence_spm": 200.0, "median_speed_straight_mps": 1.95, "n_straight_strides": 50},
     "median cadence 200 steps/min, straight-walking speed 1.95 m/s: "
     "a cadence above the walking range the pipelines were validated on (running, or short fast steps"),
    # W144 kept: festination at 0.33 m/s
    ({"median_cadence_spm": 200.0, "median_speed_mps": 0.33},
     "median cadence 200 steps/min, speed 0.33 m/s: " + _SHORT_FAST),
    # L197: a downhill run, no speed judged (slope strides, L179), its gait speed above the range
    ({"median_cadence_spm": 183.1, "median_speed_straight_mps": 1.59, "n_straight_strides": 1, "n_stair_strides": 30,
      "gait_speed_mps": 2.85},
     "median cadence 183 steps/min, gait speed 2.85 m/s: this looks like running, and running is not supported"),
    # ... and a stair descent at a walking gait speed keeps W144's wording
    ({"median_cadence_spm": 183.1, "n_straight_strides": 1, "n_stair_strides": 30, "gait_speed_mps": 0.8},
     "median cadence 183 steps/min: " + _SHORT_FAST),
])
def test_the_fast_gait_is_named_by_its_speed(summary, first):
    assert gait_range_warning(summary).startswith(first)


def test_the_gait_line_counts_too_few_straight_strides():
    from pdrlearn.cli.common import gait_line

    base = {"gait_speed_mps": 2.85, "distance_m": 59.18, "walking_time_s": 20.73, "median_speed_straight_mps": 1.59,
            "median_cadence_spm": 183.1}
    assert "straight strides 1.59 m/s (over 1 stride only, under the 5 L95 judges; L197)" in \
        gait_line({**base, "n_straight_strides": 1})
    assert "straight strides 1.59 m/s, cadence" in gait_line({**base, "n_straight_strides": 5})


def test_the_walk_ratio_line_at_a_running_cadence_says_short():
    from pdrlearn.waist.plausibility import walk_ratio_message

    run = walk_ratio_message(0.0030, 108, 0.60, 200.0, 1.73)  # the trial's intervals on waist-pendulum (W177)
    assert "at a running cadence" in run and "probably too short" in run and "reads long" not in run
    fest = walk_ratio_message(0.0018, 40, 0.27, 150.0, 1.73)  # W100's festinating walks keep their wording
    assert "reads long" in fest and "running cadence" not in fest


def _simulate(tmp: Path, name: str, length: float, time: float) -> Path:
    assert main(["simulate", "--route", "stand:3, straight:30, stand:3", "--step-length", str(length),
                 "--step-time", str(time), "--rate", "100", "--user-seed", "1", "--out", str(tmp / name)]) == 0
    return tmp / name


@pytest.fixture(scope="module")
def walk_run_walk(tmp_path_factory) -> Path:
    """The trial's mixWRW in small: 30 m walked, 30 m at running cadence and speed, 30 m walked, one foot IMU (with
    force sensors), the parts joined in their standstills."""
    tmp = tmp_path_factory.mktemp("wrw")
    walk, run = _simulate(tmp, "w", 0.75, 0.55), _simulate(tmp, "r", 1.0, 0.32)
    out = tmp / "root" / "wrw"
    out.mkdir(parents=True)
    for k in ("fAccelerometer", "fGyroscope", "fForceA", "fForceB"):
        t0, frames = 0.0, []
        for p in (walk, run, walk):
            d = pd.read_csv(p / f"{k}.csv")
            d["timestamp"] = d["timestamp"] + t0
            frames.append(d)
            t0 = float(d["timestamp"].iloc[-1]) + 10.0
        pd.concat(frames).to_csv(out / f"{k}.csv", index=False)
    shutil.copy(walk / "meta.json", out / "meta.json")
    return out


def test_track_and_track_all_flag_the_running_bout(walk_run_walk, tmp_path, capsys):
    assert main(["track", "--no-plot", str(walk_run_walk), "--out", str(tmp_path / "o")]) == 0
    err = capsys.readouterr().err
    assert "1 of 3 walking bout(s) lie above the walking range" in err and "bout 2 (" in err
    assert "stride-time CV" in err and "pools walking bouts of different rhythm" in err
    bouts = pd.read_csv(tmp_path / "o" / "bouts.csv")
    assert bouts["gait_out_of_range"].tolist() == [False, True, False]
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["gait_out_of_range"] is True and summary["n_bouts_out_of_range"] == 1
    assert gait_range_warning(summary) is None  # the session's medians alone are walking (the trial's miss)
    assert main(["track-all", "--no-plot", str(walk_run_walk.parent), "--out", str(tmp_path / "all")]) == 0
    row = pd.read_csv(tmp_path / "all" / "sessions.csv").iloc[0]
    assert bool(row["gait_out_of_range"]) and row["n_bouts_out_of_range"] == 1
    assert row["stride_time_cv_within_bouts_pct"] < 5 and "decision L195" in row["warnings"]


def test_a_real_walk_gets_no_flag(tmp_path, capsys):
    assert main(["track", "--no-plot", str(REAL / "gaitmap_level_left"), "--out", str(tmp_path / "o"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["gait_out_of_range"] is False and out["n_bouts_out_of_range"] == 0
    assert out["stride_time_cv_within_bouts_pct"] is None
    assert not [w for w in out["info"]["warnings"] if "L195" in w or "L196" in w]
    assert pd.read_csv(tmp_path / "o" / "bouts.csv")["gait_out_of_range"].eq(False).all()


def test_detected_bouts_scale_the_range_to_the_leg():
    steps = _foot_table([[0.73] * 12])  # 164 steps/min: above an adult's 160, inside a 0.84 m leg's 165.7 (L148)
    steps["cadence_spm"] = 120.0 / steps["stride_time_s"]
    assert detected_bouts(steps)["gait_out_of_range"].tolist() == [True]
    assert detected_bouts(steps, leg_m=0.84)["gait_out_of_range"].tolist() == [False]
