"""Decision L585 (review R2 finding 1, amends L570): a ramp's / flight's start position is the trajectory row at or
before its ``start_s`` (trajectory.csv has one row at the END of each stride: the walker stands at the row before
until the first stride ends), not a time interpolation across a standstill; the same for the GeoJSON feature's
first point and the GPX waypoint (one shared kernel, ``ramp_audit.trajectory_values``)."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.geoexport import GPX_NS, feature_geometry
from pdrlearn.track.ramp_audit import trajectory_values, with_end_positions

#: an origin row, the last stride before a 10 s stand (x 6.0), then the first stair stride's end (x 6.5)
TRAJ = pd.DataFrame({"t": [0.0, 10.0, 21.0, 22.0], "x": [0.0, 6.0, 6.5, 7.0], "y": 0.0,
                     "lat": [48.0, 48.0, 48.0, 48.0], "lon": [11.0, 11.00008, 11.000087, 11.000094]})


def test_a_start_after_a_stand_is_the_row_before_it_and_an_end_is_interpolated():
    t, x = TRAJ["t"].to_numpy(), TRAJ["x"].to_numpy()
    assert trajectory_values(t, x, [20.0, 10.0, 0.0, 22.0], held=True).tolist() == [6.0, 6.0, 0.0, 7.0]
    assert trajectory_values(t, x, [21.5])[0] == pytest.approx(6.75)  # interpolated (an end)
    assert np.isnan(trajectory_values(t, x, [-1.0, 23.0], held=True)).all()  # outside the rows' span
    out = with_end_positions(pd.DataFrame({"start_s": [20.0], "end_s": [22.0]}), TRAJ)
    assert (out["start_x_m"].iloc[0], out["start_lon"].iloc[0]) == (6.0, 11.00008)
    assert out["end_x_m"].iloc[0] == 7.0


def test_a_feature_after_a_stand_starts_at_the_row_before_it():
    t, lat, lon = (TRAJ[c].to_numpy(float) for c in ("t", "lat", "lon"))
    coords = feature_geometry(t, lat, lon, None, 20.0, 22.0)
    assert coords == [[11.00008, 48.0], [11.000087, 48.0], [11.000094, 48.0]]


@pytest.fixture(scope="module")
def stairs_after_stand(tmp_path_factory):
    """R2's reproducer 1 (user 11660): a flight climbed after a 10 s stand, tracked with a geodetic start."""
    d = tmp_path_factory.mktemp("l585")
    assert main(["simulate", "--route", "straight:6, stand:10, up:10, straight:4", "--user-seed", "11660",
                 "--out", str(d / "s")]) == 0
    assert main(["track", str(d / "s"), "--no-plot", "--start", "48.0,11.0", "--out", str(d / "t")]) == 0
    return d / "t"


def test_a_tracked_flight_after_a_stand_starts_where_the_walker_stood(stairs_after_stand):
    traj = pd.read_csv(stairs_after_stand / "trajectory.csv")
    flight = pd.read_csv(stairs_after_stand / "stairs.csv").iloc[0]
    before = traj[traj["t"] <= flight["start_s"]].iloc[-1]
    assert traj["t"].gt(before["t"]).any() and flight["start_s"] - before["t"] > 5.0  # the stand lies between
    assert flight["start_x_m"] == pytest.approx(before["x"], abs=1e-9)
    assert flight["start_y_m"] == pytest.approx(before["y"], abs=1e-9)
    geo = json.loads((stairs_after_stand / "track.geojson").read_text())
    feat = next(f for f in geo["features"] if f["properties"].get("kind") == "stairs")
    first = feat["geometry"]["coordinates"][0]
    assert first[:2] == pytest.approx([before["lon"], before["lat"]], abs=1e-7)
    wpt = ET.parse(stairs_after_stand / "track.gpx").getroot().find(f"{{{GPX_NS}}}wpt")
    assert (float(wpt.get("lat")), float(wpt.get("lon"))) == pytest.approx((first[1], first[0]))
