"""Session 36 treadmill trial T3 (fixer FB): L441 (the belt check over the belt's steady strides, level or inclined),
L442 / L443 (an inclined belt and a constant-grade ramp are no stair flight), B365, steps 62. Simulated users
8870-8879 only."""

from __future__ import annotations

import json
import logging
import shutil

import numpy as np
import pandas as pd
import pytest


def _strides(n=30, dz=0.12, length=1.2, t=1.2, seed=8871):
    """A steady walk of ``n`` strides in a steps table (gait columns included), every stride rising ``dz``."""
    rng = np.random.default_rng(seed)
    times = t + rng.normal(0, 0.01, n)
    start = np.r_[0.0, np.cumsum(times)[:-1]] + 3.0
    stride = np.r_[np.nan, times[1:]]
    return pd.DataFrame({"start_s": start, "end_s": start + times, "event_s": start + times - 0.1,
                         "length_m": length, "dz_m": dz, "turn_angle_rad": 0.0, "heading_rad": 0.0,
                         "stride_time_s": stride, "speed_mps": length / stride, "unit": "foot", "gap_s": 0.0})


def test_belt_rows_take_the_steady_strides_at_the_belts_grade_l441():
    from pdrlearn.track.belt import belt_rows, belt_speeds

    incline = _strides()
    rows = belt_rows(incline)
    # the first stride has no stride time, its successor no steady neighbour before it, the last none after it
    assert rows.sum() == len(incline) - 3 and not rows[:2].any() and not rows[-1]
    assert np.allclose(belt_speeds(incline), (1.2 * np.sqrt(1 + 0.1 ** 2) / incline["stride_time_s"])[rows])
    level = _strides(dz=0.0)
    assert np.array_equal(belt_rows(level), rows)
    assert np.allclose(belt_speeds(level), level["speed_mps"][rows])  # level: the horizontal speed itself
    odd = incline.copy()
    odd.loc[10, "dz_m"] = 0.40  # a stride off the belt's grade (a stumble, drift) is left out, and so is a turn
    odd.loc[20, "turn_angle_rad"] = 0.5
    got = belt_rows(odd)
    assert not got[10] and not got[20] and not got[19] and not got[21] and got[9] and got[11]


def test_belt_check_needs_five_belt_strides_l441():
    from pdrlearn.track.belt import MIN_BELT_STRIDES, belt_line, belt_summary

    short = _strides(n=MIN_BELT_STRIDES + 2)  # 4 belt strides
    s = belt_summary({"belt_speed_mps": 1.0}, {"distance_m": 8.4}, "x", short)
    assert s["n_belt_strides"] == MIN_BELT_STRIDES - 1 and "belt_speed_error_pct" not in s
    assert "5 needed" in s["belt_check_note"] and "L441" in s["belt_check_note"]
    assert "no belt speed check" in belt_line({**s, "distance_m": 8.4})
    enough = _strides(n=MIN_BELT_STRIDES + 3)
    s = belt_summary({"belt_speed_mps": 1.0}, {}, "x", enough)
    assert s["n_belt_strides"] == MIN_BELT_STRIDES and "belt_check_note" not in s
    assert s["belt_speed_error_pct"] == pytest.approx(100 * (s["median_speed_belt_mps"] - 1.0))


@pytest.fixture(scope="module")
def incline(tmp_path_factory):
    """A 10 % slope walked from standing (user 8870) declared as a 1.0 m/s treadmill belt."""
    from pdrlearn.cli import main

    folder = tmp_path_factory.mktemp("s36") / "incl"
    assert main(["simulate", "--route", "stand:2, slope:30:10, stand:2", "--user-seed", "8870", "--rate", "100",
                 "--out", str(folder)]) == 0
    meta = json.loads((folder / "meta.json").read_text())
    (folder / "meta.json").write_text(json.dumps({**meta, "belt_speed_mps": 1.0}))
    return folder


def _track(folder, out, capsys, caplog, *extra):
    from pdrlearn.cli import main

    caplog.clear()
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(folder), "--out", str(out), *extra]) == 0
    printed = capsys.readouterr().out
    return json.loads((out / "summary.json").read_text()), printed, [r.getMessage() for r in caplog.records]


def test_inclined_belt_is_checked_over_its_steady_strides_l441(incline, tmp_path, capsys, caplog):
    s, printed, _ = _track(incline, tmp_path / "t", capsys, caplog)
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    # trial T3: the inclined strides are no level straight strides, so the check read one start stride (-47.7 %)
    assert s["n_straight_strides"] < 5 and s["n_belt_strides"] >= 5
    rising = steps["dz_m"].iloc[2:-1]
    assert (rising >= 0.10).all()  # every inclined stride rises over L179's 0.10 m
    want = np.median(steps["speed_mps"].iloc[2:-1] * np.sqrt(1 + (rising / steps["length_m"].iloc[2:-1]) ** 2))
    assert s["median_speed_belt_mps"] == pytest.approx(want)
    assert s["belt_speed_error_pct"] == pytest.approx(100 * (want - 1.0))
    assert f"the foot's {s['n_belt_strides']} steady straight strides at the belt's grade" in printed


def test_a_constant_grade_climb_is_no_stair_flight_l443(incline, tmp_path, capsys, caplog):
    from pdrlearn.track.stair_flights import flight_table

    ramp = _strides()  # 10 %: every stride rises 0.12 m over 1.2 m
    assert flight_table(ramp).empty  # trial T3: a 49-stride "flight" beside floors_up_stairs 0
    stairs = _strides(dz=0.34, length=0.6)  # 57 %: a stair stays a flight
    assert flight_table(stairs)["n_strides"].tolist() == [len(stairs)]
    s, printed, _ = _track(incline, tmp_path / "t", capsys, caplog)
    assert s["n_stair_strides"] >= 5 and s["n_flights_up"] == 0 and "stair flights" not in printed
    assert pd.read_csv(tmp_path / "t" / "stairs.csv").empty


def _with_meta(src, dst, **extra):
    shutil.copytree(src, dst)
    meta = json.loads((dst / "meta.json").read_text())
    (dst / "meta.json").write_text(json.dumps({**meta, **extra}))
    return dst


def test_declared_incline_counts_no_floors_or_flights_and_keeps_the_cv_l442(incline, tmp_path, capsys, caplog):
    from pdrlearn.track.belt import declared_incline

    plain, _, _ = _track(incline, tmp_path / "plain", capsys, caplog)
    assert plain["stride_time_cv_pct"] is None and "belt_incline_pct" in plain["stride_time_cv_withheld"]["reason"]
    folder = _with_meta(incline, tmp_path / "decl", belt_incline_pct=10)
    s, printed, lines = _track(folder, tmp_path / "t", capsys, caplog, "--storey-height", "1.5")
    assert s["belt_incline_pct"] == 10.0 and "L442" in s["floors_note"]
    assert s["floors_up"] == 0 and s["floors_up_ramps"] == 0 and s["n_flights_up"] == 0
    assert s["ascent_m"] == plain["ascent_m"]  # the belt's virtual climb is still reported
    steady = pd.read_csv(tmp_path / "t" / "steps.csv")
    assert s["n_cv_strides"] == int(steady["steady"].sum()) >= 5
    assert s["stride_time_cv_pct"] == pytest.approx(steady.loc[steady["steady"], "stride_time_s"].std(ddof=1)
                                                    / steady.loc[steady["steady"], "stride_time_s"].mean() * 100)
    assert "at 10 % incline (belt_incline_pct" in printed
    assert not [ln for ln in lines if "B262" in ln]  # the key is read, not "unknown"
    assert declared_incline() is None  # the next session of a batch starts undeclared
    high = _track(incline, tmp_path / "h", capsys, caplog, "--storey-height", "1.5")[0]
    assert high["floors_up"] >= 1  # the same walk undeclared climbs 1.5 m storeys


@pytest.mark.parametrize(("extra", "says"), [
    ({"belt_incline_pct": "10"}, "belt_incline_pct '10'"), ({"belt_incline_pct": True}, "belt_incline_pct True"),
    ({"belt_incline_pct": 55}, "at most 40"), ({"belt_incline_pct": [5, 10]}, "belt_incline_pct [5, 10]"),
    ({"belt_incline_pct": 5, "belt_speed_mps": None}, "without belt_speed_mps")])
def test_bad_belt_incline_is_one_line_b365(incline, tmp_path, capsys, extra, says):
    from pdrlearn.cli import main

    bad = _with_meta(incline, tmp_path / "bad", **extra)
    if extra.get("belt_speed_mps", 0) is None:
        meta = json.loads((bad / "meta.json").read_text())
        meta.pop("belt_speed_mps")
        (bad / "meta.json").write_text(json.dumps(meta))
    assert main(["track", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert says in err and "B365" in err and "meta.json" in err and "\n" not in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()


def test_steps_names_the_foots_own_strides_when_the_detector_finds_none_steps_62(incline, capsys, caplog):
    from pdrlearn.cli.steps import report
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelStepDetector
    from pdrlearn.steps.strides import swinging_rest_strides

    session = read_session(incline)
    empty = AccelStepDetector().detect(session).iloc[:0]  # trial T3's vibrating belt: accel kept nothing
    own = swinging_rest_strides(session, force=False)
    assert own >= 20
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        report(session, empty, name="accel", unit="foot", tolerance=0.25, as_json=True)
    d = json.loads(capsys.readouterr().out)
    assert d["count"] == 0 and d["foot_swing_strides"] == own  # before: "0 strides (accel)" and nothing more
    assert not [r for r in caplog.records if "steps 47" in r.getMessage()]  # B201's line says it, not a second one


def test_a_backward_walk_has_its_own_stride_time_cv_l444():
    from pdrlearn.track.clinical import clinical_summary

    back = _strides(n=25, dz=0.0).assign(direction="backward")
    s = clinical_summary(back)
    steady = back["stride_time_s"].to_numpy()[2:-1]  # the steady strides: neighbours with a stride time
    assert s["stride_time_cv_direction"] == "backward" and s["n_cv_strides"] == len(steady)
    assert s["stride_time_cv_pct"] == pytest.approx(100 * steady.std(ddof=1) / steady.mean())  # before: withheld
    fwd = clinical_summary(back.assign(direction="forward"))
    assert fwd["stride_time_cv_direction"] == "forward" and fwd["stride_time_cv_pct"] == s["stride_time_cv_pct"]
    # a walk with enough forward strides keeps them alone (its backward stretch has its own rhythm)
    mixed = pd.concat([_strides(n=15, dz=0.0), _strides(n=15, dz=0.0, seed=8873).assign(direction="backward")])
    mixed["start_s"] = 3.0 + 1.2 * np.arange(len(mixed))
    mixed["end_s"] = mixed["start_s"] + 1.2
    m = clinical_summary(mixed.reset_index(drop=True))
    assert m["stride_time_cv_direction"] == "forward" and m["n_cv_strides"] == 12
    too_few = clinical_summary(_strides(n=8, dz=0.0).assign(direction="backward"))
    assert too_few["stride_time_cv_pct"] is None and too_few["stride_time_cv_direction"] is None


def test_toe_off_track_prints_its_stance_and_swing_steps_63():
    from pdrlearn.cli.common import gait_line

    base = {"gait_speed_mps": 1.0, "distance_m": 60.0, "walking_time_s": 60.0, "median_cadence_spm": 100.0,
            "median_stride_time_s": 1.2, "info": {"toe_off_source": None}, "n_stance_times": 0}
    assert "add --toe-off for them" in gait_line(base)  # L423, as before
    toe = {**base, "info": {"toe_off_source": "gyro"}, "n_stance_times": 48, "median_stance_time_s": 0.727,
           "median_swing_time_s": 0.473, "median_stance_pct": 60.57}
    line = gait_line(toe)  # trial T3: with --toe-off the line said nothing of stance (summary.json only)
    assert "stance 0.73 s, swing 0.47 s (60.6 % stance) over 48 strides (decisions L73" in line


def test_walkway_tests_are_not_timed_on_a_declared_belt_l445(tmp_path, capsys, caplog):
    from pdrlearn.cli import main

    walk = tmp_path / "walk"
    assert main(["simulate", "--route", "stand:2, straight:16, stand:2", "--user-seed", "8874", "--rate", "100",
                 "--out", str(walk)]) == 0
    plain, printed, _ = _track(walk, tmp_path / "p", capsys, caplog)
    assert plain["ten_m_walk_time_s"] is not None and "10 m walk test" in printed  # overground: timed, as before
    s, printed, _ = _track(_with_meta(walk, tmp_path / "belt", belt_speed_mps=1.0), tmp_path / "t", capsys, caplog)
    for key in ("ten_m_walk", "t25fw"):  # trial T3: "10 m walk test 9.96 s ... timed 25-foot walk 8.04 s" on a belt
        assert s[f"{key}_time_s"] is None and s[f"{key}_speed_mps"] is None and "L445" in s[f"{key}_note"]
    assert "10 m walk test" not in printed and "25-foot" not in printed


def test_length_class_bounds_stay_the_users_under_step_length_s81(tmp_path):
    import pandas as pd

    from pdrlearn.cli import main
    from pdrlearn.sim import UserProfile

    runs = {}
    for name, extra in (("own", []), ("belt", ["--step-length", "0.5"])):
        out = tmp_path / name
        assert main(["simulate", "--route", "stand:2, straight:12, stand:2", "--user-seed", "8875", "--rate", "100",
                     "--out", str(out), *extra]) == 0
        runs[name] = (json.loads((out / "meta.json").read_text()), pd.read_csv(out / "steps.csv"))
    own, belt = runs["own"][0], runs["belt"][0]
    # trial T3: [1.03, 1.53] on the calibration, [0.775, 1.15] on the 0.5 m belt walk of the same user
    assert belt["length_class_bounds_m"] == own["length_class_bounds_m"]
    assert belt["user"]["class_step_length_m"] == own["user"]["step_length_m"] != belt["user"]["step_length_m"]
    assert "class_step_length_m" not in own["user"]  # an ordinary session's meta.json is as before
    assert (runs["belt"][1]["length_class"] == "short").all()  # 1.0 m strides are short for this user
    assert UserProfile(**belt["user"]).length_class_bounds_m == tuple(own["length_class_bounds_m"])


def test_calibrate_belt_takes_belt_speed_times_the_contact_span_w378_b366(tmp_path, capsys):
    import re

    from pdrlearn.cli import main

    walk = tmp_path / "belt"
    assert main(["simulate", "--route", "stand:3, straight:24, stand:3", "--step-length", "0.6", "--step-time", "0.6",
                 "--bounce", "pendulum", "--user-seed", "8876", "--rate", "100", "--out", str(walk)]) == 0
    meta = json.loads((walk / "meta.json").read_text())
    (walk / "meta.json").write_text(json.dumps({**meta, "belt_speed_mps": 1.0}))
    capsys.readouterr()
    assert main(["calibrate", str(walk), "--belt", "--start", "6", "--end", "24", "-o", str(tmp_path / "b.json")]) == 0
    belt = json.loads((tmp_path / "b.json").read_text())
    note = [n for n in belt["notes"] if "W378" in n]
    assert len(note) == 1, belt["notes"]
    m = re.search(r"1\.00 m/s x ([\d.]+) s of contacts .* = ([\d.]+) m of belt", note[0])
    assert m and float(m.group(2)) == pytest.approx(float(m.group(1)), abs=0.06)
    # the manual recipe it replaces (docs/frames.md): --distance = belt speed x the contacts' span, same fit
    span = [n for n in belt["notes"] if "--distance" in n]
    assert not span
    manual = tmp_path / "d.json"
    assert main(["calibrate", str(walk), "-d", m.group(2), "--start", "6", "--end", "24", "-o", str(manual)]) == 0
    assert json.loads(manual.read_text())["k"] == pytest.approx(belt["k"], rel=1e-3)
    capsys.readouterr()
    assert main(["calibrate", str(walk), "--belt", "-d", "10", "-o", str(tmp_path / "x.json")]) == 2  # not both
    assert "not both" in capsys.readouterr().err and not (tmp_path / "x.json").exists()
    (walk / "meta.json").write_text(json.dumps(meta))  # B366: no belt speed declared
    assert main(["calibrate", str(walk), "--belt", "-o", str(tmp_path / "y.json")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--belt needs meta.json belt_speed_mps" in err and "B366" in err and "\n" not in err
    assert not (tmp_path / "y.json").exists()


def test_streamed_track_keeps_the_belt_check_without_contacts_l441(tmp_path, capsys, caplog):
    """Review R3 F3 (fixer FK, user 9021): `track --streaming` without --contacts has no stride time (E51); its belt
    strides take their speed from the time to the next stride's start (L222) as median_speed_straight_mps does."""
    from pdrlearn.cli import main

    folder = tmp_path / "level"
    assert main(["simulate", "--route", "stand:2, straight:40, stand:2", "--user-seed", "9021", "--out",
                 str(folder)]) == 0
    meta = json.loads((folder / "meta.json").read_text())
    (folder / "meta.json").write_text(json.dumps({**meta, "belt_speed_mps": 1.3}))
    summary, printed, _ = _track(folder, tmp_path / "strm", capsys, caplog, "--streaming")
    assert pd.read_csv(tmp_path / "strm" / "steps.csv")["speed_mps"].isna().all()  # no stride time streamed
    assert summary["n_belt_strides"] >= 20 and "belt_check_note" not in summary
    assert abs(summary["belt_speed_error_pct"]) < 5
    plain, _, _ = _track(folder, tmp_path / "offline", capsys, caplog)
    assert summary["median_speed_belt_mps"] == pytest.approx(plain["median_speed_belt_mps"], rel=0.05)
