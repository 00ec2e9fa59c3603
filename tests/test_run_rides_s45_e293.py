"""Decision E293 (session 45, I4): ``pdrlearn run`` of a foot bundle reads a ride as ``track`` does (L378's
barometric rides, L615 / L616's vehicle, L624's vehicle without a barometer) through track's own function
(``pdrlearn.track.rides.foot_rides``) and writes track's rides.csv, steps.csv ``ride``, trajectory.csv ``ride`` (L623)
and summary ``n_rides``; ``track --streaming`` too (E6: run's strides are its strides, so its rides.csv is run's to
the byte). Before E293 neither wrote rides.csv and ``n_rides`` was null. Simulated user 12751 (seed = user, 20 Hz), a
40 s bus between two walks and a quiet 25 s stand."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = str(ROOT / "models" / "plasys-sim-default")
#: run's strides are the streamed segmenter's, track's the offline ones: a standstill's ends (a stride's end, the next
#: one's start) differ by a sample or two, so the ride's span read inside it may too (measured: 0.02 s at 100 Hz)
SPAN_TOL_S = 0.2


@pytest.fixture(scope="module")
def bus(tmp_path_factory):
    s = simulate_path(parse_route("stand:3, straight:10, vehicle:40, straight:10, stand:25, straight:5, stand:3"),
                      UserProfile.from_seed(12751), seed=12751, scenario="route")
    root = tmp_path_factory.mktemp("e293")
    foot = dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if k.startswith("f")})
    for name, sess in (("full", s), ("foot", foot)):
        write_session(sess, root / name)
        assert main(["track", "--no-plot", str(root / name), "--out", str(root / f"{name}_track")]) == 0
        assert main(["run", "--no-plot", BUNDLE, str(root / name), "--out", str(root / f"{name}_run")]) == 0
        assert main(["track", "--no-plot", "--streaming", str(root / name), "--out", str(root / f"{name}_stream")]) == 0
    return s, root


@pytest.mark.parametrize("name", ["full", "foot"])
def test_run_writes_tracks_rides_csv_e293(bus, name):
    """The same rides.csv columns and rows (kind, ride number; the span within SPAN_TOL_S), summary ``n_rides``,
    steps.csv ``ride`` on the first stride after the bus, trajectory.csv ``ride`` last; ``foot``: no wBarometer
    (L624: ``dz_m`` empty)."""
    s, root = bus
    tr, rn = root / f"{name}_track", root / f"{name}_run"
    assert (rn / "rides.csv").is_file()  # main: no rides.csv
    a, b = pd.read_csv(tr / "rides.csv"), pd.read_csv(rn / "rides.csv")
    assert list(b.columns) == list(a.columns)
    assert len(a) == len(b) == 1 and list(b["kind"]) == list(a["kind"]) == ["vehicle"]
    assert np.abs(b[["start_s", "end_s"]].to_numpy() - a[["start_s", "end_s"]].to_numpy()).max() < SPAN_TOL_S
    assert b["dz_m"].isna().all() == (name == "foot")
    assert (rn / "rides.csv").read_bytes() == (root / f"{name}_stream" / "rides.csv").read_bytes()
    truth = s.extras["rides"]
    assert b["start_s"].iloc[0] < float(truth["end_s"].iloc[0]) and b["end_s"].iloc[0] > float(truth["start_s"].iloc[0])
    summary = json.loads((rn / "summary.json").read_text())
    assert summary["n_rides"] == json.loads((tr / "summary.json").read_text())["n_rides"] == 1
    assert sum("vehicle ride(s)" in w for w in summary["info"]["warnings"]) == 1
    steps = pd.read_csv(rn / "steps.csv", keep_default_na=False)
    assert list(steps["ride"][steps["ride"] != ""]) == ["vehicle"]
    traj = pd.read_csv(rn / "trajectory.csv")
    assert list(traj.columns)[-1] == "ride" and traj["ride"].notna().sum() == 1


def test_run_without_a_ride_writes_the_header_alone_e293(tmp_path):
    """A walk without a ride: rides.csv is the header alone, as track's; no ``ride`` column in trajectory.csv
    (L623: none without a ride)."""
    s = simulate_path(parse_route("stand:3, straight:15, stand:3"), UserProfile.from_seed(12752), seed=12752,
                      scenario="route")
    write_session(s, tmp_path / "w")
    assert main(["run", "--no-plot", BUNDLE, str(tmp_path / "w"), "--out", str(tmp_path / "o")]) == 0
    assert (tmp_path / "o" / "rides.csv").read_text().strip() == (
        "ride,start_s,end_s,kind,dz_m,duration_s,vertical_rate_mps,vibration_mps2,horizontal_est_m")
    assert json.loads((tmp_path / "o" / "summary.json").read_text())["n_rides"] == 0
    assert "ride" not in pd.read_csv(tmp_path / "o" / "trajectory.csv").columns
