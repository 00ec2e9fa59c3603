"""Review R1's findings fixed in session 39 (fixer FL): decisions W425, W425, L528, L529, L530."""

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.test_court_flags_w416 import add_jumps


@pytest.fixture(scope="module")
def jumps_then_walk(tmp_path_factory):
    sim = tmp_path_factory.mktemp("w424") / "jw"
    assert main(["simulate", "--route", "stand:2, straight:14, stand:2", "--user-seed", "10250",
                 "--out", str(sim)]) == 0
    add_jumps(sim, 1.0, 2.0, files=("fAccelerometer", "wAccelerometer"))  # flights at about 2.25-6 s
    return sim


@pytest.mark.parametrize("units", ["foot", "waist"])
def test_a_window_after_the_jumps_has_no_flights_w424(jumps_then_walk, tmp_path, units):
    out, whole = tmp_path / "win", tmp_path / "whole"
    assert main(["track", str(jumps_then_walk), "--units", units, "--window", "9,16", "--no-plot",
                 "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert (s["n_flight_phases"], s["flight_time_s"]) == (0, 0.0)
    assert pd.read_csv(out / "flights.csv").empty
    assert not [w for w in s["info"]["warnings"] if "flight phase" in w]
    # the window holding the jumps keeps them (the cut is the window's, not a loss of the test)
    assert main(["track", str(jumps_then_walk), "--units", units, "--window", "0,9", "--no-plot",
                 "--out", str(whole)]) == 0
    s = json.loads((whole / "summary.json").read_text())
    assert s["n_flight_phases"] == 3
    assert len(pd.read_csv(whole / "flights.csv")) >= 3


def _net_within_distance(per: pd.DataFrame) -> None:
    net = np.hypot(per["dx_m"], per["dy_m"])
    assert (net <= per["distance_m"] + 1e-6).all(), per[["start_s", "distance_m", "n_steps", "dx_m", "dy_m"]]


def test_periods_net_displacement_is_never_longer_than_its_distance_l528(jumps_then_walk, tmp_path):
    # review R1's case: the position at the last stride end before each edge lagged a stride behind distance_m's rule
    out, win = tmp_path / "per", tmp_path / "win"
    assert main(["track", str(jumps_then_walk), "--per", "5", "--no-plot", "--out", str(out)]) == 0
    per = pd.read_csv(out / "periods.csv")
    _net_within_distance(per)
    final = json.loads((out / "summary.json").read_text())["final_position"]
    assert abs(per["dx_m"].sum() - final["x"]) < 1e-6 and abs(per["dy_m"].sum() - final["y"]) < 1e-6
    # under --window, each period's start is a position of the window's trajectory
    assert main(["track", str(jumps_then_walk), "--per", "5", "--window", "7,16", "--no-plot", "--out", str(win)]) == 0
    per, traj = pd.read_csv(win / "periods.csv"), pd.read_csv(win / "trajectory.csv")
    _net_within_distance(per)
    assert all(np.isclose(traj["x"], x).any() for x in per["start_x_m"]), (per["start_x_m"], traj["x"])


@pytest.mark.parametrize("user,route,units,every", [
    (10251, "stand:2, straight:8, turn:90, straight:6, stand:2", "foot", "3"),
    (10252, "stand:1, straight:5, side:3, backward:2, stand:2", "foot", "4"),
    (10253, "stand:2, straight:10, turn:-90, straight:5, stand:1", "waist", "2.5"),
])
def test_periods_net_displacement_property_over_simulated_walks_l528(tmp_path, user, route, units, every):
    sim, out = tmp_path / "s", tmp_path / "o"
    assert main(["simulate", "--route", route, "--user-seed", str(user), "--out", str(sim)]) == 0
    assert main(["track", str(sim), "--units", units, "--per", every, "--no-plot", "--out", str(out)]) == 0
    per = pd.read_csv(out / "periods.csv")
    _net_within_distance(per)
    assert np.allclose(per["end_x_m"].to_numpy()[:-1], per["start_x_m"].to_numpy()[1:])


@pytest.fixture(scope="module")
def clipped_walks(tmp_path_factory):
    """A 100 Hz walk with a turn (user 10254), its foot gyroscope clipped at +-250 deg/s (L525's case), one spike (the
    global extreme held 4 samples, review R1's spike.py) and the clipped copy without the waist unit."""
    import shutil

    root = tmp_path_factory.mktemp("l529")
    clean = root / "clean"
    assert main(["simulate", "--route", "stand:3, straight:12, turn:90, straight:8, stand:3", "--rate", "100",
                 "--user-seed", "10254", "--out", str(clean)]) == 0
    g = pd.read_csv(clean / "fGyroscope.csv")
    out = {"clean": clean}
    for name in ("clip", "spike", "foot_clip"):
        out[name] = root / name
        shutil.copytree(clean, out[name])
        v = g.copy()
        xyz = v[["x", "y", "z"]].to_numpy().copy()
        if name == "spike":
            i = int(np.argmax(np.abs(xyz).max(1)))
            ax = int(np.argmax(np.abs(xyz[i])))
            xyz[i:i + 4, ax] = xyz[i, ax]
        else:
            xyz = np.clip(xyz, -np.deg2rad(250.0), np.deg2rad(250.0))
        v[["x", "y", "z"]] = xyz
        v.to_csv(out[name] / "fGyroscope.csv", index=False)
    for f in out["foot_clip"].glob("w*.csv"):
        f.unlink()
    return out


@pytest.fixture(scope="module")
def clipped_track(clipped_walks):
    """The clipped walk read and tracked with the default settings (L529 and L530 read the same track)."""
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    session = read_session(clipped_walks["clip"])
    return session, track_plasys(session)


def test_a_spike_in_the_foot_gyroscope_leaves_the_track_alone_l529(clipped_walks, clipped_track, caplog):
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    clean = track_plasys(read_session(clipped_walks["clean"]))
    with caplog.at_level("WARNING"):
        spike = read_session(clipped_walks["spike"])
    line = next(r.getMessage() for r in caplog.records if "fGyroscope.csv" in r.getMessage())
    assert "keeps its usual settings, decision L529" in line and "heads by the waist unit" not in line
    res = track_plasys(spike)
    assert not [w for w in res.info["warnings"] if "L525" in w]
    assert res.info["heading_source"] == clean.info["heading_source"] == "fused"
    clipped = clipped_track[1]  # a clipped swing still switches (L525)
    assert [w for w in clipped.info["warnings"] if "L525" in w] and clipped.info["heading_source"] == "waist"


def test_the_l525_line_names_a_params_file_and_the_settings_used_l530(clipped_walks, clipped_track, tmp_path):
    from pdrlearn.track.plasys import track_plasys

    session, default = clipped_track
    line = next(w for w in default.info["warnings"] if "L525" in w)
    assert "--params '{" not in line and '--params JSON file with {"tilt_dedrift": false}' in line
    assert "tilt_dedrift true, accel_scale_error 0" in line
    own = {"tilt_dedrift": False, "accel_scale_error": 0.01}
    line = next(w for w in track_plasys(session, params=own).info["warnings"] if "L525" in w)
    assert "tilt_dedrift true" not in line and "accel_scale_error 0," not in line and "your --params file" in line
    params = tmp_path / "p.json"  # the advice works: a params file
    params.write_text(json.dumps({"tilt_dedrift": False}))
    assert main(["track", str(clipped_walks["clip"]), "--params", str(params), "--no-plot", "--out",
                 str(tmp_path / "o")]) == 0


def test_b401_line_of_a_foot_only_session_names_the_foots_own_heading_l530(clipped_walks, caplog):
    from pdrlearn.io import read_session

    with caplog.at_level("WARNING"):
        read_session(clipped_walks["foot_clip"])
    line = next(r.getMessage() for r in caplog.records if "fGyroscope.csv" in r.getMessage())
    assert "heads by the waist unit" not in line and "keeps the foot's own stride yaw" in line


@pytest.fixture(scope="module")
def short_walk(tmp_path_factory):
    """A short walk without a jump (user 10255), simulated once for both tracks of the flights.csv test."""
    sim = tmp_path_factory.mktemp("w424_flights") / "s"
    assert main(["simulate", "--route", "stand:2, straight:6, stand:2", "--user-seed", "10255", "--out", str(sim)]) == 0
    return sim


@pytest.mark.parametrize("streaming", [False, True])
def test_every_track_writes_flights_csv_header_only_without_a_flight_w424(short_walk, tmp_path, streaming):
    out = tmp_path / "o"
    assert main(["track", str(short_walk), "--no-plot", "--out", str(out),
                 *(["--streaming"] if streaming else [])]) == 0
    flights = pd.read_csv(out / "flights.csv")
    assert flights.empty and list(flights.columns) == ["unit", "start_s", "end_s", "flight_time_s", "jump_height_m"]
