"""Session 36 fixer FK (review R3 of the treadmill merge): write_track's bouts / steps.csv at a declared incline
(L442, F1), evaluate_track and `run` read the belt keys (L454, F2), the streamed belt check (L441, F3), short stair
flights inside a ramp climb (L455, F4), the --step-length recipe (S81, F5), TrackResult.summary leaves the
caller's info alone and the "not level" note's backward rows (L456, F6). Simulated users 9020-9029 only."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest


def _simulate(folder, route, user, **meta_extra):
    from pdrlearn.cli import main

    assert main(["simulate", "--route", route, "--user-seed", str(user), "--rate", "100", "--out", str(folder)]) == 0
    if meta_extra:
        meta = json.loads((folder / "meta.json").read_text())
        (folder / "meta.json").write_text(json.dumps({**meta, **meta_extra}))
    return folder


@pytest.fixture(scope="module")
def incline(tmp_path_factory):
    """A 10 % slope walked from standing (user 9020) declared as a 1.0 m/s treadmill belt at 10 %."""
    return _simulate(tmp_path_factory.mktemp("fk") / "incl", "stand:2, slope:30:10, stand:2", 9020,
                     belt_speed_mps=1.0, belt_incline_pct=10)


def test_write_track_folder_equals_track_folder_on_a_declared_incline_l442(incline, tmp_path, capsys):
    from pdrlearn.cli import main
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.folder import write_track

    assert main(["track", "--no-plot", str(incline), "--out", str(tmp_path / "cli")]) == 0
    capsys.readouterr()
    s = read_session(incline)
    write_track(get_pipeline("plasys")(s), s, tmp_path / "api", plot=False)
    cli, api = (json.loads((tmp_path / d / "summary.json").read_text()) for d in ("cli", "api"))
    assert cli["n_cv_strides"] == api["n_cv_strides"] > 0
    for name in ("bouts.csv", "steps.csv"):
        a, b = (pd.read_csv(tmp_path / d / name) for d in ("cli", "api"))
        pd.testing.assert_frame_equal(a, b)
    assert pd.read_csv(tmp_path / "api" / "steps.csv")["steady"].sum() == cli["n_cv_strides"]
    # L442 / L450 (lead, session 36): the bouts' floors are the summary's 0 on a declared incline, on both paths
    assert cli["floors_up"] == 0 and pd.read_csv(tmp_path / "cli" / "bouts.csv")["floors_up"].tolist() == [0]


RUN_BUNDLE = __import__("pathlib").Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def test_evaluate_track_reads_the_declared_incline_and_the_belt_l454(incline):
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.belt import declared_incline
    from pdrlearn.track.evaluate import evaluate_track

    s = read_session(incline)
    res = get_pipeline("plasys")(s)
    got = evaluate_track(res, s)
    want = res.summary(s)
    assert declared_incline() is None  # the scope closed
    assert got["floors_up"] == want["floors_up"] == 0 and "L442" in got["floors_note"]
    assert got["n_cv_strides"] == want["n_cv_strides"] > 0
    assert got["belt_incline_pct"] == 10 and got["belt_speed_error_pct"] == pytest.approx(want["belt_speed_error_pct"])


def test_run_reads_the_declared_incline_and_refuses_a_bad_one_l454_b378(incline, tmp_path, capsys):
    from pdrlearn.cli import main

    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(incline), "--out", str(tmp_path / "run")]) == 0
    assert "floors up 0" in capsys.readouterr().out
    got = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert got["belt_speed_mps"] == 1.0 and got["belt_incline_pct"] == 10 and "L442" in got["floors_note"]
    assert "belt_speed_error_pct" in got and got["floors_up"] == 0
    assert len(pd.read_csv(tmp_path / "run" / "stairs.csv")) == 0
    bad = tmp_path / "bad"
    __import__("shutil").copytree(incline, bad)
    meta = json.loads((bad / "meta.json").read_text())
    (bad / "meta.json").write_text(json.dumps({**meta, "belt_incline_pct": "ten"}))
    assert main(["run", str(RUN_BUNDLE), str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "belt_incline_pct 'ten'" in err and "B365" in err and "\n" not in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()


def test_the_documented_step_length_recipe_labels_as_the_command_s81(tmp_path):
    """docs/simulator.md's Python equivalent of --step-length (run as printed, user 9022 in place of 1) gives the
    command's stride-length class bounds and labels (review R3 F5)."""
    import re
    from pathlib import Path

    from pdrlearn.cli import main

    doc = (Path(__file__).resolve().parents[1] / "docs" / "simulator.md").read_text()
    block = next(b for b in re.findall(r"```python\n(.*?)```", doc, re.S) if "step_length_m=0.3" in b)
    code = block.replace("from_seed(1)", "from_seed(9022)")
    code = code.replace('"out/sim/tenmwt_040_py"', repr(str(tmp_path / "py")))
    exec(compile(code, "docs/simulator.md", "exec"), {})  # noqa: S102 - the documented recipe itself
    assert main(["simulate", "--route", "stand:3, straight:14, stand:3", "--step-length", "0.3", "--step-time", "0.75",
                 "--bounce", "pendulum", "--user-seed", "9022", "--out", str(tmp_path / "cli")]) == 0
    py, cli = (json.loads((tmp_path / d / "meta.json").read_text()) for d in ("py", "cli"))
    assert py["length_class_bounds_m"] == cli["length_class_bounds_m"]
    a, b = (pd.read_csv(tmp_path / d / "steps.csv") for d in ("py", "cli"))
    assert list(a["length_class"]) == list(b["length_class"]) and (a["length_class"] == "short").all()


def test_summary_leaves_the_callers_info_alone(incline):
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    s = read_session(incline)
    res = get_pipeline("plasys")(s)
    before = dict(res.info)
    got = res.summary(s)
    assert got["info"]["belt_incline_pct"] == 10 and got["floors_up"] == 0
    assert res.info == before and "belt_incline_pct" not in res.info  # before: 10.0 written into the caller's info


def test_not_level_note_leaves_out_a_model_free_tracks_backward_strides_l456():
    from pdrlearn.track.clinical import _not_level

    n = 30
    t = 1.1 + 0.01 * np.sin(np.arange(n))
    start = 3.0 + np.r_[0.0, np.cumsum(t)[:-1]]
    steps = pd.DataFrame({"start_s": start, "end_s": start + t, "length_m": 1.2, "raw_length_m": 1.2, "dz_m": 0.0,
                          "turn_angle_rad": 0.0, "stride_time_s": np.r_[np.nan, t[1:]], "unit": "foot", "gap_s": 0.0,
                          "direction": ""})  # a model-free track: no direction class
    back = np.arange(n) >= 15  # the second half travels backward (L203), over a drifting climb
    steps.loc[back, "raw_length_m"] = -1.2
    steps.loc[back, "dz_m"] = 0.2
    n_straight, n_not_level = _not_level(steps)
    assert n_straight == 14 and n_not_level == 0  # before: 29 straight, 15 of them "not level"


def _climb(dz, length, t=1.2):
    """A steps table (gait columns included) of strides rising ``dz`` over ``length``, one every ``t`` s."""
    n = len(dz)
    start = 3.0 + t * np.arange(n)
    return pd.DataFrame({"start_s": start, "end_s": start + t, "event_s": start + t - 0.1, "length_m": length,
                         "dz_m": dz, "turn_angle_rad": 0.0, "heading_rad": 0.0,
                         "stride_time_s": np.r_[np.nan, np.full(n - 1, t)], "speed_mps": np.asarray(length) / t,
                         "unit": "foot", "gap_s": 0.0})


def test_a_stair_beside_a_ramp_keeps_its_flight_with_the_l455_option():
    """L466 adopted L455's steep strides with 3-stride in-ramp flights (L595: the rule, no switch; L443 alone kept no
    flight here)."""
    from pdrlearn.track.evaluate import ramp_climb_rows
    from pdrlearn.track.grade import stair_grade_set  # L470: on at the default 20 % and with --stair-grade 30
    from pdrlearn.track.stair_flights import flight_table

    # 30 strides up a 10 % ramp, then 3 stair strides of 0.34 m over 0.56 m (61 %, R3's route), then level
    dz = np.r_[np.zeros(3), np.full(30, 0.12), np.full(3, 0.34), np.zeros(3)]
    length = np.r_[np.full(33, 1.2), np.full(3, 0.56), np.full(3, 1.2)]
    st = _climb(dz, length)
    assert ramp_climb_rows(st)[3:36].all()  # L302 calls the whole climb a ramp
    table = flight_table(st)
    assert len(table) == 1 and table["direction"].iloc[0] == "up" and table["n_strides"].iloc[0] == 3  # before: none
    assert table["height_m"].iloc[0] == pytest.approx(1.02)
    with stair_grade_set(30.0):  # L469's trail grade: the 61 % stair is still a flight
        assert flight_table(st)["n_strides"].tolist() == [3]
    ramp_only = _climb(dz[:33], length[:33])  # the ramp alone keeps no flight (L443)
    assert len(flight_table(ramp_only)) == 0


def test_evaluate_track_sets_the_declared_incline_on_the_result_it_is_given_l456(incline):
    """Review R5 F2: evaluate_track (L454's one place) sets info["belt_incline_pct"] on the result it is given, for
    stairs.csv; TrackResult.summary gives it a copy (L456), so the caller's result is untouched there."""
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import evaluate_track

    s = read_session(incline)
    res = get_pipeline("plasys")(s)
    res.summary(s)
    assert res.info.get("belt_incline_pct") is None
    evaluate_track(res, s)
    assert res.info.get("belt_incline_pct") == 10.0
