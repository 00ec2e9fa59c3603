"""Session 31 treadmill trial: B260 (quiet standing near the force load level is no stepping), B261 (`steps` short
of the foot's own swing count), B262 (unknown meta.json keys), L319-L323 and steps 47-48."""

from __future__ import annotations

import json
import logging

import numpy as np
import pytest

from pdrlearn.kernels.frozen_foot import FORCE_LOAD_LEVEL, frozen_foot_evidence, load_onsets


def test_standing_force_noise_at_the_load_level_is_no_stepping_b260():
    # the simulated 10 % incline's final stand: both sensors 74-119 N against block references of ~430 N, i.e. around
    # FORCE_LOAD_LEVEL x ref = 86 N; the foot IMU is still. Before B260 the noise read as 3+ loads (B213's warning).
    rng = np.random.default_rng(3)
    n = 700
    ref = 430.0
    still_acc, still_gyr = np.tile([0.0, 9.81, 0.0], (n, 1)), np.zeros((n, 3))
    stand = [FORCE_LOAD_LEVEL * ref + 10.0 + rng.normal(0, 10.0, n) for _ in range(2)]
    assert load_onsets(stand, [ref, ref]) == 0
    assert frozen_foot_evidence(still_acc, still_gyr, stand, refs=[ref, ref]) is None
    # real steps (the foot unloads in swing) still count, and a frozen IMU beside them is still found (B203 / B213)
    steps = (np.arange(n) // 50) % 2 == 1
    force = [np.where(steps, 600.0, 5.0) + rng.normal(0, 1, n)]
    assert load_onsets(force, [600.0]) == 7
    got = frozen_foot_evidence(still_acc, still_gyr, force)
    assert got is not None and got[0] == 7


# --- steps 47 (trial F2): `steps` short of the foot's own rest-and-swing stride count -------------------------------

@pytest.fixture(scope="module")
def walk_a(tmp_path_factory):
    from pdrlearn.io import read_session, write_session
    from pdrlearn.sim import UserProfile, simulate

    out = tmp_path_factory.mktemp("s31") / "A_u6110"
    write_session(simulate("A", UserProfile.from_seed(6110), "normal", rate_hz=100.0), out)
    return read_session(out)


def _report(session, table, capsys, caplog):
    from pdrlearn.cli.steps import report

    caplog.clear()
    with caplog.at_level(logging.WARNING):
        report(session, table, name="accel", unit="foot", tolerance=0.25, as_json=True)
    return json.loads(capsys.readouterr().out), [r.getMessage() for r in caplog.records if "steps 47" in r.getMessage()]


def test_steps_short_of_the_foots_own_strides_is_said_steps_47(walk_a, capsys, caplog):
    from pdrlearn.steps import AccelStepDetector
    from pdrlearn.steps.strides import swinging_rest_strides

    table = AccelStepDetector().detect(walk_a)
    own = swinging_rest_strides(walk_a)
    d, lines = _report(walk_a, table, capsys, caplog)
    assert d["count"] == own and "foot_swing_strides" not in d and not lines  # a clean walk: nothing said
    # strides the detector missed outside any detection (trial: a vibrating foot, 49 of 51, then 23 of 51)
    one = table.drop(index=len(table) // 2).reset_index(drop=True)
    d, lines = _report(walk_a, one, capsys, caplog)
    assert d["count"] == own - 1 and d["foot_swing_strides"] == own and not lines  # a stray one: the count only
    many = table.drop(index=range(2, 2 + len(table) // 3)).reset_index(drop=True)
    d, lines = _report(walk_a, many, capsys, caplog)
    assert d["foot_swing_strides"] == own and len(lines) == 1 and "\n" not in lines[0], lines
    assert f"accel kept {d['count']} strides, but the foot's own rests and swings segment {own}" in lines[0]
    assert "`pdrlearn track DIR`" in lines[0]


# --- L319 (trial F3): a reference trajectory that does not travel (lab-frame mocap on a treadmill) ------------------

@pytest.fixture(scope="module")
def belt(tmp_path_factory):
    """A 14 m straight walk (user 6111) and a copy whose trajectory.csv wobbles in place (the lab frame of a belt)."""
    import pandas as pd

    from pdrlearn.cli import main

    base = tmp_path_factory.mktemp("belt")
    walk = base / "walk"
    assert main(["simulate", "--route", "stand:2, straight:14, stand:2", "--user-seed", "6111", "--rate", "100",
                 "--out", str(walk)]) == 0
    lab = base / "lab"
    import shutil

    shutil.copytree(walk, lab)
    for name in ("steps.csv", "ics.csv"):
        (lab / name).unlink(missing_ok=True)
    tr = pd.read_csv(lab / "trajectory.csv")
    ts = tr["timestamp"].to_numpy(float) / 1000.0
    tr["x"], tr["y"] = 0.05 * np.sin(2 * np.pi * ts), 0.03 * np.cos(np.pi * ts)
    tr.to_csv(lab / "trajectory.csv", index=False)
    return walk, lab


def _track(folder, out, capsys, caplog):
    from pdrlearn.cli import main

    caplog.clear()
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(folder), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    return json.loads((out / "summary.json").read_text()), printed, [r.getMessage() for r in caplog.records]


def test_reference_that_does_not_travel_gives_no_distance_error_l319(belt, tmp_path, capsys, caplog):
    walk, lab = belt
    s, printed, lines = _track(lab, tmp_path / "lab", capsys, caplog)
    assert "distance_error_pct" not in s and "final_position_error_m" not in s, s  # was +-hundreds of %
    assert s["reference_travel_m"] < 0.1 and s["distance_m"] > 10
    mine = [ln for ln in lines if "decision L319" in ln]
    assert len(mine) == 1 and "treadmill" in mine[0] and "docs/frames.md" in mine[0] and "\n" not in mine[0]
    assert "distance error" not in printed
    s, printed, lines = _track(walk, tmp_path / "walk", capsys, caplog)  # an ordinary walk: as before
    assert "reference_travel_m" not in s and "final_position_error_m" in s and "distance_error_pct" in s
    assert not [ln for ln in lines if "decision L319" in ln]


# --- B262 / L321 (trial F5): unknown meta.json keys are named; a declared treadmill belt speed -----------------------

def _with_meta(src, dst, **extra):
    import shutil

    shutil.copytree(src, dst)
    meta = json.loads((dst / "meta.json").read_text())
    meta.update(extra)
    (dst / "meta.json").write_text(json.dumps(meta))
    return dst


def test_unknown_meta_keys_are_named_by_info_and_track_b262(belt, tmp_path, capsys, caplog):
    from pdrlearn.cli import main

    folder = _with_meta(belt[0], tmp_path / "decl", treadmill=True, x_operator="AB", activity="treadmill walking")
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        assert main(["info", str(folder)]) == 0
    lines = [r.getMessage() for r in caplog.records if "decision B262" in r.getMessage()]
    assert len(lines) == 1 and "'treadmill'" in lines[0] and "x_operator" not in lines[0] and "activity" not in lines[0]
    assert "belt_speed_mps" in lines[0] and "meta.json" in lines[0]
    _, _, lines = _track(folder, tmp_path / "t", capsys, caplog)
    assert len([ln for ln in lines if "decision B262" in ln]) == 1


def test_no_meta_key_the_project_writes_is_called_unknown_b262(belt):
    from pathlib import Path

    from pdrlearn.io.meta_keys import unknown_meta_keys

    root = Path(__file__).resolve().parents[1] / "datasets"
    metas = [*root.glob("real/*/meta.json"), *root.glob("external/*/meta.json"), belt[0] / "meta.json"]
    assert len(metas) > 5
    assert {str(m): unknown_meta_keys(json.loads(m.read_text())) for m in metas
            if unknown_meta_keys(json.loads(m.read_text()))} == {}


def test_declared_belt_speed_is_compared_with_the_foot_l321(belt, tmp_path, capsys, caplog):
    from pdrlearn.cli import main

    plain, _, _ = _track(belt[0], tmp_path / "plain", capsys, caplog)
    assert "belt_speed_mps" not in plain
    v = round(plain["median_speed_straight_mps"], 1)
    s, printed, _ = _track(_with_meta(belt[0], tmp_path / "belt", belt_speed_mps=v), tmp_path / "t", capsys, caplog)
    assert s["belt_speed_mps"] == v
    assert s["belt_speed_error_pct"] == pytest.approx(100 * (s["median_speed_belt_mps"] - v) / v)  # L441
    assert f"treadmill belt {v:.2f} m/s (meta.json belt_speed_mps)" in printed and "belt distance" in printed
    assert s["distance_m"] == plain["distance_m"]  # no new physics
    bad = _with_meta(belt[0], tmp_path / "bad", belt_speed_mps="fast")
    caplog.clear()
    assert main(["track", str(bad), "--out", str(tmp_path / "b")]) != 0
    err = capsys.readouterr().err
    assert "belt_speed_mps 'fast'" in err and "decision L321" in err and "Traceback" not in err
    assert not (tmp_path / "b").exists()


# --- L320 (trial F7): periods.csv says what n_steps counts and gives each period's stride time and cadence ----------

def test_periods_say_what_n_steps_counts_and_give_cadence_l320(belt, tmp_path):
    import pandas as pd

    from pdrlearn.cli import main
    from pdrlearn.columns import undocumented

    out = tmp_path / "per"
    assert main(["track", "--no-plot", str(belt[0]), "--per", "6s", "--out", str(out)]) == 0
    per, steps = pd.read_csv(out / "periods.csv"), pd.read_csv(out / "steps.csv")
    s = json.loads((out / "summary.json").read_text())
    assert undocumented("periods.csv", per.columns) == []
    assert (per["n_steps_counts"] == s["n_steps_counts"]).all() and s["n_steps_counts"] == "strides of the tracked foot"
    assert per["n_steps"].sum() == s["n_steps"]
    mid = 0.5 * (steps["start_s"] + steps["end_s"])
    for _, row in per.iterrows():
        inside = steps[(mid >= row["start_s"]) & (mid < row["end_s"])]
        want = inside["cadence_spm"].median()
        if np.isfinite(want):
            assert row["median_cadence_spm"] == pytest.approx(want)
            assert row["median_stride_time_s"] == pytest.approx(inside["stride_time_s"].median())
        else:
            assert not np.isfinite(row["median_cadence_spm"])


# --- L322 (trial F6): an option keeps a steady incline's strides in the stride-time CV ------------------------------

def test_cv_keeps_ramp_strides_with_the_option_l322():
    """L322's rule, reached by L442's declared belt incline (L594: no module switch ``CV_KEEPS_RAMPS``)."""
    import pandas as pd

    from pdrlearn.track import belt, clinical

    # a 10 % incline walked steadily: 30 strides of 1.2 m rising 0.12 m (over L179's 0.10 m), stride time ~1.2 s
    rng = np.random.default_rng(6112)
    n = 30
    t = 1.2 + rng.normal(0, 0.02, n)
    start = np.r_[0.0, np.cumsum(t)[:-1]] + 3.0
    steps = pd.DataFrame({"start_s": start, "end_s": start + t, "ic_s": start + t, "stride_time_s": t,
                          "length_m": 1.2, "dz_m": 0.12, "turn_angle_rad": 0.0, "heading_rad": 0.0,
                          "unit": "foot", "gap_s": 0.0})
    off = clinical.clinical_summary(steps)
    assert off["stride_time_cv_pct"] is None and "belt_incline_pct" in off["stride_time_cv_withheld"]["level_note"]
    assert "CV_KEEPS_RAMPS" not in off["stride_time_cv_withheld"]["level_note"]
    with belt.incline_scope(10.0):
        on = clinical.clinical_summary(steps)
        stairs = steps.assign(length_m=0.6, dz_m=0.34)  # a stair climb (57 % grade) stays out
        assert clinical.clinical_summary(stairs)["stride_time_cv_pct"] is None
    steady = t[1:-1]
    assert on["stride_time_cv_pct"] == pytest.approx(100 * steady.std(ddof=1) / steady.mean())
