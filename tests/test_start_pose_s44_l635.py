"""Session 44, fixer FC, trial T3 findings F4, F5, F7 (an IPIN competitor given the start pose, scored at timed
waypoints): L635 `--turn-to-heading` turns an absolute (compass) track to `--initial-heading`; L636 `hard_iron_fit`
in `--params`; D50 fixes before the first stride are start fixes; L637 `--start-xy X,Y` and `--initial-heading`
with `--fixes`; B447 an epoch-number import gives the recording start; B448 trajectory.csv's `time` column; L638
`track --at-times FILE`."""

from __future__ import annotations

import json
import math
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import TrackResult

ROUTE = "stand:8, straight:15, turn:90, straight:10, stand:3"  # about 35 s


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """One simulated two-unit session (user 12270, 20 Hz, setting off at 30 deg) with its waist compass."""
    root = tmp_path_factory.mktemp("start_pose")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(12270), rate_hz=20, seed=12270, heading0_deg=30.0)
    write_session(s, root / "walk")
    return root


def _track(root: Path, name: str, *args) -> Path:
    out = root / name
    assert main(["track", "--no-plot", str(root / "walk"), "--out", str(out), *args]) == 0
    return out


# --- L635: a known start heading on an absolute track -------------------------------------------------------------

def _result(head_deg, length=1.2, t0=10.0):
    head = np.radians(np.asarray(head_deg, float))
    n = len(head)
    steps = pd.DataFrame({"start_s": t0 + np.arange(n), "end_s": t0 + 1 + np.arange(n), "length_m": length,
                          "heading_rad": head, "dz_m": 0.0})
    xy = np.vstack([[0.0, 0.0], np.cumsum(np.c_[length * np.cos(head), length * np.sin(head)], axis=0)])
    traj = pd.DataFrame({"t": np.r_[t0, steps["end_s"]], "x": xy[:, 0], "y": xy[:, 1], "z": 0.0})
    return TrackResult(steps, traj, {"pipeline": "plasys", "heading_source": "fused"})


def test_first_straight_strides_end_at_the_first_turn_l635():
    from pdrlearn.track.start_pose import first_straight_heading

    got, n = first_straight_heading(_result([36, 38, 37, 35, 37, 127, 127, 127]).steps)
    assert n == 5 and math.degrees(got) == pytest.approx(36.6, abs=0.05)
    assert first_straight_heading(_result([10] * 30).steps)[1] == 10  # at most START_MAX_STRIDES


def test_turn_to_start_heading_turns_the_whole_track_about_its_start_l635():
    from pdrlearn.track.geodetic import geodetic_track
    from pdrlearn.track.start_pose import turn_to_start_heading

    r = _result([36, 37, 36, 127, 127])  # a compass 6.3 deg off a start heading of 30 deg
    start = (41.178, -8.598)
    ll = geodetic_track(start, r.steps["length_m"], r.steps["heading_rad"])
    r.trajectory["lat"], r.trajectory["lon"] = ll[:, 0], ll[:, 1]
    out = turn_to_start_heading(r, math.radians(30.0), start=start)
    rec = out.info["start_heading"]
    assert rec["turn_deg"] == pytest.approx(-6.333, abs=1e-3) and rec["n_strides"] == 3
    np.testing.assert_allclose(np.degrees(out.steps["heading_rad"]), [29.667, 30.667, 29.667, 120.667, 120.667],
                               atol=1e-3)
    d0 = np.hypot(r.trajectory["x"], r.trajectory["y"])
    np.testing.assert_allclose(np.hypot(out.trajectory["x"], out.trajectory["y"]), d0)  # about its start
    assert math.degrees(math.atan2(out.trajectory["y"].iloc[3], out.trajectory["x"].iloc[3])) == pytest.approx(30.0)
    assert np.abs(out.trajectory["lat"] - r.trajectory["lat"]).max() > 1e-6  # recomputed from the turned steps
    again = geodetic_track(start, out.steps["length_m"], out.steps["heading_rad"])
    np.testing.assert_allclose(out.trajectory[["lat", "lon"]].to_numpy(), again)
    assert r.steps["heading_rad"].iloc[0] == pytest.approx(math.radians(36))  # the caller's track untouched


def test_initial_heading_on_the_compass_track_needs_turn_to_heading_l635(walk, capsys):
    with pytest.raises(DataError, match="--turn-to-heading"):
        from pdrlearn.cli.track import settings_of, track_session

        track_session(walk / "walk", settings_of({"initial_heading": 30.0, "no_plot": True}))
    out = _track(walk, "turned", "--initial-heading", "30", "--turn-to-heading")
    err = capsys.readouterr().err
    assert "note:" in err and "decision L635" in err
    info = json.loads((out / "summary.json").read_text())["info"]
    assert info["start_heading"]["given_deg"] == 30.0 and info["start_heading"]["turn_deg"] is not None
    from pdrlearn.track.start_pose import first_straight_heading

    got, _ = first_straight_heading(pd.read_csv(out / "steps.csv"))
    assert math.degrees(got) == pytest.approx(30.0, abs=0.01)  # the track's first straight strides head 30 deg
    assert main(["track", str(walk / "walk"), "--turn-to-heading", "--out", str(walk / "x")]) == 2  # no DEG


# --- L636 ---------------------------------------------------------------------------------------------------------

def test_hard_iron_fit_in_params_l636(tmp_path):
    from pdrlearn.cli.track import _track_params

    par, keys = _track_params({"hard_iron_fit": True, "rest_s": 0.05}, tmp_path / "p.json", False)
    assert keys == {"hard_iron_fit": True} and par == {"rest_s": 0.05}
    with pytest.raises(DataError, match="hard_iron_fit.*--streaming"):
        _track_params({"hard_iron_fit": True}, tmp_path / "p.json", True)
    with pytest.raises(DataError, match="true or false"):
        _track_params({"hard_iron_fit": "yes"}, tmp_path / "p.json", False)


# --- D50, L637: the start of an aided track in local metres ------------------------------------------------------

def _fixes(walk: Path, rows: list[tuple[float, float, float, float]]) -> Path:
    path = walk / f"fixes_{len(rows)}_{int(rows[0][0])}.csv"
    path.write_text("t,x,y,accuracy_m\n" + "".join(f"{t},{x},{y},{a}\n" for t, x, y, a in rows))
    return path


def _building_fixes(walk: Path, times, start=True):
    """Fixes of the truth moved to a building frame where the start is (100, 50)."""
    truth = pd.read_csv(walk / "walk" / "trajectory.csv")
    tt = truth["timestamp"].to_numpy(float) / 1000
    bx, by = truth["x"] - truth["x"].iloc[0] + 100, truth["y"] - truth["y"].iloc[0] + 50
    rows = [(0.0, 100.0, 50.0, 0.3)] if start else []
    rows += [(t, float(np.interp(t, tt, bx)), float(np.interp(t, tt, by)), 1.0) for t in times]
    return _fixes(walk, rows)


def test_start_fix_at_t0_gives_the_start_position_d50(walk):
    out = _track(walk, "aided", "--units", "foot", "--fixes", str(_building_fixes(walk, [22.0, 33.0])))
    traj = pd.read_csv(out / "trajectory.csv")
    assert traj["t"].iloc[0] > 5  # the foot track starts at its first stride, after the standstill
    assert (traj["x"].iloc[0], traj["y"].iloc[0]) == pytest.approx((100.0, 50.0), abs=1e-6)
    fx = json.loads((out / "summary.json").read_text())["info"]["aid"]["fixes"]
    assert fx["start_fix"] == {"t": 0.0, "x": 100.0, "y": 50.0, "accuracy_m": 0.3}
    assert fx["fixes_outside_track"] == 0 and fx["fixes_used"] == 3


def test_start_fixes_window_is_session_start_to_first_stride_d50():
    from pdrlearn.aid.track import start_fixes

    assert list(start_fixes([-1.0, 0.0, 3.0, 8.5, 8.6, 20.0], 0.0, 8.5)) == [1, 2, 3]


def test_start_xy_moves_the_track_and_frames_the_fixes_l637(walk):
    out = _track(walk, "xy", "--units", "foot", "--start-xy", "100,50")
    traj = pd.read_csv(out / "trajectory.csv")
    assert (traj["x"].iloc[0], traj["y"].iloc[0]) == (100.0, 50.0)
    plain = pd.read_csv(_track(walk, "plain_foot", "--units", "foot") / "trajectory.csv")
    np.testing.assert_allclose(traj["x"] - 100, plain["x"], atol=1e-9)
    fixes = _building_fixes(walk, [22.0, 33.0], start=False)
    aided = pd.read_csv(_track(walk, "xy_aided", "--units", "foot", "--start-xy", "100,50", "--initial-heading",
                               "30", "--fixes", str(fixes)) / "trajectory.csv")
    assert (aided["x"].iloc[0], aided["y"].iloc[0]) == pytest.approx((100.0, 50.0))
    truth = pd.read_csv(walk / "walk" / "trajectory.csv")
    tt = truth["timestamp"] / 1000
    at = float(aided["t"].iloc[5])  # before the first fix: the given start and heading, not (0, 0)
    bx = np.interp(at, tt, truth["x"] - truth["x"].iloc[0] + 100)
    by = np.interp(at, tt, truth["y"] - truth["y"].iloc[0] + 50)
    assert math.hypot(aided["x"].iloc[5] - bx, aided["y"].iloc[5] - by) < 1.0


@pytest.mark.parametrize(("args", "said"), [
    (["--start-xy", "100"], "two finite numbers"),
    (["--start-xy", "1,nan"], "two finite numbers"),
    (["--start-xy", "1,2", "--start", "41.1,-8.6"], "drop one of them"),
])
def test_bad_start_xy_is_one_line_l637(walk, capsys, args, said):
    assert main(["track", str(walk / "walk"), *args, "--out", str(walk / "bad")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and said in err[0]
    assert not (walk / "bad").exists()


# --- B447, B448, L638: clock time ----------------------------------------------------------------------------------

EPOCH_MS = 1757930100000  # 2025-09-15T09:55:00Z


@pytest.fixture(scope="module")
def imported(walk):
    """The lower-back unit exported with an epoch-milliseconds column and imported, as the trial's phone CSV."""
    acc = pd.read_csv(walk / "walk" / "wAccelerometer.csv")
    gyr = pd.read_csv(walk / "walk" / "wGyroscope.csv")
    df = acc.merge(gyr, on="timestamp", suffixes=("_a", "_g"))
    df.insert(0, "epoch_ms", df.pop("timestamp") + EPOCH_MS)
    df.columns = ["epoch_ms", "ax", "ay", "az", "gx", "gy", "gz"]
    df.to_csv(walk / "epoch.csv", index=False)
    assert main(["import", str(walk / "epoch.csv"), "--unit", "waist", "--out", str(walk / "imp")]) == 0
    return walk / "imp"


def test_epoch_ms_import_gives_the_recording_start_b447(imported):
    from pdrlearn.track.clock import recording_start

    meta = json.loads((imported / "meta.json").read_text())
    assert recording_start(meta) == datetime(2025, 9, 15, 9, 55, tzinfo=UTC)
    imp = meta["imported"][0] if isinstance(meta["imported"], list) else meta["imported"]
    imp["time"]["origin_s"] = 12.5  # a device clock from boot: no start
    assert recording_start(meta) is None


def test_trajectory_time_column_and_at_times_b448_l638(imported, walk):
    (walk / "times.csv").write_text("time\n2025-09-15T09:55:02Z\n2025-09-15T09:55:20.5+00:00\n")
    out = walk / "imp_track"
    assert main(["track", "--no-plot", str(imported), "--at-times", str(walk / "times.csv"), "--out", str(out)]) == 0
    traj = pd.read_csv(out / "trajectory.csv")
    assert list(traj.columns)[-1] == "time"
    first = datetime.fromisoformat(traj["time"].iloc[0])
    assert (first - datetime(2025, 9, 15, 9, 55, tzinfo=UTC)).total_seconds() == pytest.approx(traj["t"].iloc[0])
    at = pd.read_csv(out / "at_times.csv")
    assert list(at["t"]) == pytest.approx([2.0, 20.5])
    assert (at["x"].iloc[0], at["y"].iloc[0]) == (traj["x"].iloc[0], traj["y"].iloc[0])  # standing at the start
    k = int(np.searchsorted(traj["t"], 20.5))  # inside a step: linear from its start (the row before) to its end
    steps = pd.read_csv(out / "steps.csv")
    s0 = max(steps["start_s"].iloc[k - 1], traj["t"].iloc[k - 1])
    assert at["x"].iloc[1] == pytest.approx(np.interp(20.5, [s0, traj["t"].iloc[k]], traj["x"].iloc[k - 1:k + 1]))
    assert at["time"].iloc[1] == "2025-09-15T09:55:20.500+00:00"
    from pdrlearn.columns import undocumented

    assert undocumented("at_times.csv", at.columns) == []
    assert undocumented("trajectory.csv", traj.columns) == []


def test_positions_at_holds_the_start_steps_a_floor_and_refuses_outside_l638():
    from pdrlearn.track.at_times import positions_at

    traj = pd.DataFrame({"t": [10.0, 11.0, 12.0], "x": [0.0, 1.0, 3.0], "y": 0.0, "floor": [0.0, 0.0, 1.0]})
    got = positions_at(traj, np.array([0.0, 10.5, 11.5, 20.0]), (0.0, 20.0))
    assert list(got["x"]) == [0.0, 0.5, 2.0, 3.0] and list(got["floor"]) == [0.0, 0.0, 0.0, 1.0]
    held = positions_at(traj, np.array([10.5, 11.25, 11.75]), (0.0, 20.0), step_starts=[10.0, 11.5])
    assert list(held["x"]) == [0.5, 1.0, 2.0]  # the second step starts at 11.5 s: held at 1.0 m until then
    with pytest.raises(DataError, match=r"row 3 \(25.000 s\) lies outside the recording"):
        positions_at(traj, np.array([1.0, 25.0]), (0.0, 20.0), "w.csv")


@pytest.mark.parametrize(("text", "said"), [
    ("x\n1\n", "exactly one column t"),
    ("t\n1\nabc\n", "row 3 t 'abc' is not a finite"),
    ("t\n", "at least one row"),
    ("", "cannot read it as a CSV"),  # an empty file
])
def test_bad_times_file_is_one_line_before_tracking_l638(walk, capsys, text, said):
    bad = walk / "bad_times.csv"
    bad.write_text(text)
    assert main(["track", str(walk / "walk"), "--at-times", str(bad), "--out", str(walk / "bad_at")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and said in err[0]


def test_a_missing_times_file_is_one_line_l638(walk, capsys):
    assert main(["track", str(walk / "walk"), "--at-times", str(walk / "nope.csv"), "--out", str(walk / "no_at")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "nope.csv: no such file" in err[0] and not (walk / "no_at").exists()


def test_iso_times_need_a_recording_start_l638(walk, capsys):
    (walk / "iso_times.csv").write_text("time\n2025-09-15T09:55:02Z\n")
    assert main(["track", "--no-plot", str(walk / "walk"), "--at-times", str(walk / "iso_times.csv"), "--out",
                 str(walk / "no_start")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "recording_start" in err[0] and not (walk / "no_start").exists()
