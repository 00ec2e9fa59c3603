"""Decisions L362, L363, B281 (session 33): a track with a geodetic start also writes track.gpx (GPX 1.1) and
track.geojson (RFC 7946: longitude first) for map tools; none without --start; rows without lat/lon cut the path.
Simulated users 7090-7099."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim.route import parse_route
from pdrlearn.track.geoexport import GPX_NS, geo_pieces, write_geo_files

sim = pytest.importorskip("pdrlearn.sim")
NS = {"g": GPX_NS}
LAT, LON = 41.178, -8.608


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    s = sim.simulate("walk", user_seed=7090, length_m=12.0)
    return write_session(s, tmp_path_factory.mktemp("geo") / "w7090")


@pytest.fixture(scope="module")
def clocked(tmp_path_factory):
    """User 7091's walk with a recording start at +01:00 (L298), and a copy whose start has no offset."""
    out = {}
    for key, start in (("zoned", "2026-12-05T02:13:00+01:00"), ("naive", "2026-12-05T02:13:00")):
        s = sim.simulate("walk", user_seed=7091, length_m=8.0)
        s.meta["recording_start"] = start
        out[key] = write_session(s, tmp_path_factory.mktemp("geo") / f"w7091_{key}")
    return out


def _gpx_points(path):
    root = ET.parse(path).getroot()
    assert root.tag == f"{{{GPX_NS}}}gpx" and root.get("version") == "1.1"
    trks = root.findall("g:trk", NS)
    assert len(trks) == 1
    return trks[0], [pt for seg in trks[0].findall("g:trkseg", NS) for pt in seg.findall("g:trkpt", NS)]


def test_track_with_start_writes_gpx_and_geojson_longitude_first(walk, tmp_path, capsys):
    assert main(["track", "--no-plot", str(walk), "--start", f"{LAT},{LON}", "--out", str(tmp_path / "t")]) == 0
    assert "track.gpx, track.geojson" in capsys.readouterr().out  # named in the "wrote" line
    traj = pd.read_csv(tmp_path / "t" / "trajectory.csv")
    n = int((np.isfinite(traj["lat"]) & np.isfinite(traj["lon"])).sum())
    assert n == len(traj) > 5
    trk, pts = _gpx_points(tmp_path / "t" / "track.gpx")
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert trk.find("g:name", NS).text == summary["session"]
    assert len(trk.findall("g:trkseg", NS)) == 1 and len(pts) == n
    assert (float(pts[0].get("lat")), float(pts[0].get("lon"))) == (LAT, LON)
    np.testing.assert_allclose([float(p.get("lat")) for p in pts], traj["lat"], atol=1e-7)
    np.testing.assert_allclose([float(p.get("lon")) for p in pts], traj["lon"], atol=1e-7)
    assert all(len(p.get("lat").split(".")[1]) == 7 for p in pts)  # L362: 7 decimals
    assert pts[0].find("g:ele", NS) is None  # no ALT: z is the height above the start, no elevation
    assert pts[0].find("g:time", NS) is None  # the simulator writes no recording start
    doc = json.loads((tmp_path / "t" / "track.geojson").read_text())
    assert doc["type"] == "FeatureCollection"
    line, first, last = doc["features"]
    assert line["geometry"]["type"] == "LineString"
    coords = line["geometry"]["coordinates"]
    assert coords[0] == [LON, LAT] and len(coords) == n  # RFC 7946: [lon, lat]
    np.testing.assert_allclose(np.array(coords), traj[["lon", "lat"]].to_numpy(), atol=1e-7)
    assert line["properties"] == {"session": summary["session"], "pipeline": "plasys",
                                  "distance_m": round(summary["distance_m"], 3)}
    assert first["geometry"] == {"type": "Point", "coordinates": [LON, LAT]}
    assert first["properties"]["role"] == "start" and last["properties"]["role"] == "end"
    assert last["geometry"]["coordinates"] == coords[-1]


@pytest.fixture(scope="module")
def stairs(tmp_path_factory):
    """User 7310 walks, climbs 17 stairs and walks on (review R1 finding 4: z changes, so a constant elevation is
    caught)."""
    s = sim.simulate_path(parse_route("straight:3, up:17, straight:3"), sim.UserProfile.from_seed(7310),
                          seed=7310)
    return write_session(s, tmp_path_factory.mktemp("geo") / "u7310")


def test_altitude_gives_elevations(stairs, tmp_path, capsys):
    assert main(["track", "--no-plot", str(stairs), "--start", f"{LAT},{LON},12.5", "--out", str(tmp_path / "t")]) == 0
    traj = pd.read_csv(tmp_path / "t" / "trajectory.csv")
    _, pts = _gpx_points(tmp_path / "t" / "track.gpx")
    assert len(pts) == len(traj) and traj["z"].max() - traj["z"].min() > 2.0  # 17 stairs of 0.17 m
    ele = [float(p.find("g:ele", NS).text) for p in pts]
    assert pts[0].find("g:ele", NS).text == "12.50"
    assert [p.find("g:ele", NS).text for p in pts] == [f"{z:.2f}" for z in traj["z"]]  # every point its own row's z
    coords = json.loads((tmp_path / "t" / "track.geojson").read_text())["features"][0]["geometry"]["coordinates"]
    assert coords[0] == [LON, LAT, 12.5] and len(coords) == len(traj)
    np.testing.assert_allclose([c[2] for c in coords], traj["z"], atol=0.005)
    np.testing.assert_allclose([c[2] for c in coords], ele, atol=0.005)


def test_no_files_without_start(walk, tmp_path, capsys):
    assert main(["track", "--no-plot", str(walk), "--out", str(tmp_path / "t")]) == 0
    assert "track.gpx" not in capsys.readouterr().out
    assert not (tmp_path / "t" / "track.gpx").exists() and not (tmp_path / "t" / "track.geojson").exists()
    assert (tmp_path / "t" / "trajectory.csv").is_file()


def test_times_are_utc_from_the_recording_start(clocked, tmp_path, capsys):
    assert main(["track", "--no-plot", str(clocked["zoned"]), "--start", f"{LAT},{LON}", "--out",
                 str(tmp_path / "z")]) == 0
    traj = pd.read_csv(tmp_path / "z" / "trajectory.csv")
    _, pts = _gpx_points(tmp_path / "z" / "track.gpx")
    times = [p.find("g:time", NS).text for p in pts]
    t0 = pd.Timestamp("2026-12-05T01:13:00Z")  # 02:13 at +01:00
    # every point: the start plus its own row's t, in UTC with milliseconds and Z (review R1 finding 4)
    assert len(times) == len(traj) > 5
    assert times == [(t0 + pd.Timedelta(milliseconds=round(1000 * t))).strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"
                     for t in traj["t"]]
    assert all(b > a for a, b in zip([pd.Timestamp(t) for t in times], [pd.Timestamp(t) for t in times[1:]],
                                     strict=False))  # strictly increasing
    feats = json.loads((tmp_path / "z" / "track.geojson").read_text())["features"]
    assert feats[1]["properties"]["time"] == times[0] and feats[2]["properties"]["time"] == times[-1]
    # a start without an offset: a local clock time of no known zone -> no UTC time is made up
    assert main(["track", "--no-plot", str(clocked["naive"]), "--start", f"{LAT},{LON}", "--out",
                 str(tmp_path / "n")]) == 0
    _, pts = _gpx_points(tmp_path / "n" / "track.gpx")
    assert len(pts) == len(traj) and all(p.find("g:time", NS) is None for p in pts)


def test_rows_without_lat_lon_cut_the_path(tmp_path):
    """Decision B281: a gap gives a new <trkseg> and a MultiLineString; leading / trailing gaps are left out; a
    piece of one point is a two-position line in GeoJSON (RFC 7946: a line has two or more positions)."""
    nan = float("nan")
    traj = pd.DataFrame({"t": np.arange(9.0), "x": 0.0, "y": 0.0, "z": 0.0,
                         "lat": [nan, 41.0, 41.1, nan, 41.2, nan, nan, 41.3, 41.4],
                         "lon": [nan, -8.0, -8.1, nan, -8.2, nan, nan, -8.3, nan]})
    assert [list(p) for p in geo_pieces(traj["lat"], traj["lon"])] == [[1, 2], [4], [7]]
    # a session name with characters XML 1.0 cannot hold (a control character; B295: U+FFFF, U+FFFE, a lone
    # surrogate) still gives a GPX file a reader parses; U+FFFD and a character above U+FFFF are kept
    assert write_geo_files(tmp_path, traj, session="s\x01x\uffff\ufffey\ud800z\ufffd\U0001f600", pipeline="plasys",
                           distance_m=3.0) == ("track.gpx", "track.geojson")
    trk, pts = _gpx_points(tmp_path / "track.gpx")
    assert trk.find("g:name", NS).text == "sxyz\ufffd\U0001f600"
    assert [len(s.findall("g:trkpt", NS)) for s in trk.findall("g:trkseg", NS)] == [2, 1, 1]
    assert len(pts) == int(np.isfinite(traj[["lat", "lon"]]).all(axis=1).sum())
    line = json.loads((tmp_path / "track.geojson").read_text())["features"][0]["geometry"]
    assert line == {"type": "MultiLineString", "coordinates": [[[-8.0, 41.0], [-8.1, 41.1]], [[-8.2, 41.2]] * 2,
                                                               [[-8.3, 41.3]] * 2]}
    # no row with lat/lon (no geodetic start): nothing is written
    empty = tmp_path / "empty"
    empty.mkdir()
    assert write_geo_files(empty, traj.assign(lat=nan), session="s", pipeline="plasys", distance_m=3.0) == ()
    assert not any(empty.iterdir())


def test_run_writes_them_as_track(walk, tmp_path, capsys):
    from tests.conftest import ROOT

    bundle = ROOT / "models" / "plasys-sim-default"
    assert main(["run", "--no-plot", str(bundle), str(walk), "--start", f"{LAT},{LON},3", "--out",
                 str(tmp_path / "r")]) == 0
    traj = pd.read_csv(tmp_path / "r" / "trajectory.csv")
    _, pts = _gpx_points(tmp_path / "r" / "track.gpx")
    assert len(pts) == len(traj) and (float(pts[0].get("lat")), float(pts[0].get("lon"))) == (LAT, LON)
    assert pts[0].find("g:ele", NS).text == "3.00"
    coords = json.loads((tmp_path / "r" / "track.geojson").read_text())["features"][0]["geometry"]["coordinates"]
    assert coords[0] == [LON, LAT, 3.0] and len(coords) == len(traj)
    assert main(["run", "--no-plot", str(bundle), str(walk), "--out", str(tmp_path / "r0")]) == 0
    assert not (tmp_path / "r0" / "track.gpx").exists() and not (tmp_path / "r0" / "track.geojson").exists()


def test_track_all_writes_them_per_session(walk, tmp_path, capsys):
    import shutil

    root = tmp_path / "root"
    shutil.copytree(walk, root / "a")
    assert main(["track-all", "--no-plot", str(root), "--start", f"{LAT},{LON}", "--out", str(tmp_path / "all")]) == 0
    gpx = sorted((tmp_path / "all").rglob("track.gpx"))
    assert len(gpx) == 1 and (gpx[0].parent / "track.geojson").is_file()
    # in the session's own folder, beside its trajectory.csv (review R1 finding 4)
    assert gpx[0].parent == tmp_path / "all" / "a" and (gpx[0].parent / "trajectory.csv").is_file()


def test_session_name_with_uffff_gives_a_parsable_gpx_b295(tmp_path, capsys):
    """Decision B295 (review R1 finding 2): meta.json ``"session": "walk\\uffffx"`` gave a track.gpx no reader
    parsed (``not well-formed (invalid token)``)."""
    s = sim.simulate("walk", user_seed=7311, length_m=6.0)
    s.meta["session"] = "walk\uffffx"
    d = write_session(s, tmp_path / "u7311")
    assert main(["track", "--no-plot", str(d), "--start", f"{LAT},{LON}", "--out", str(tmp_path / "t")]) == 0
    trk, pts = _gpx_points(tmp_path / "t" / "track.gpx")
    assert trk.find("g:name", NS).text == "walkx" and len(pts) > 3


@pytest.mark.parametrize("start", ["0001-01-01T00:00:00+01:00", "9999-12-31T23:59:00-01:00"])
def test_a_start_near_the_date_limits_writes_no_times_b296(start, tmp_path, capsys):
    """Decision B296 (review R1 finding 3): a recording start whose UTC times fall outside the years 1-9999 gave an
    OverflowError traceback; now the files have no times and one warning line says why."""
    s = sim.simulate("walk", user_seed=7312, length_m=6.0)
    s.meta["recording_start"] = start
    d = write_session(s, tmp_path / "u7312")
    assert main(["track", "--no-plot", str(d), "--start", f"{LAT},{LON}", "--out", str(tmp_path / "t")]) == 0
    err = capsys.readouterr().err
    _, pts = _gpx_points(tmp_path / "t" / "track.gpx")
    assert len(pts) > 3 and all(p.find("g:time", NS) is None for p in pts)
    feats = json.loads((tmp_path / "t" / "track.geojson").read_text())["features"]
    assert "time" not in feats[1]["properties"] and "time" not in feats[2]["properties"]
    lines = [ln for ln in err.splitlines() if "B296" in ln]
    assert len(lines) == 1 and start in lines[0] and "recording_start" in lines[0] and "Traceback" not in err
    # track-all: the session is tracked, not "failed"
    import shutil

    shutil.copytree(d, tmp_path / "root" / "a")
    assert main(["track-all", "--no-plot", str(tmp_path / "root"), "--start", f"{LAT},{LON}", "--out",
                 str(tmp_path / "all")]) == 0
    assert (tmp_path / "all" / "a" / "track.gpx").is_file()


def test_clock_columns_after_9999_are_empty_not_a_traceback_b296(tmp_path, capsys):
    """Decision B296: without --start too, L298's clock columns of instants past 9999-12-31 are empty cells (they
    raised OverflowError); the instants before it keep their clock time."""
    from datetime import datetime

    from pdrlearn.track.clock import clock_texts

    start = datetime.fromisoformat("9999-12-31T23:59:59+00:00")
    assert clock_texts(start, [0.5, 2.0, float("nan")]) == ["9999-12-31T23:59:59.500+00:00", None, None]
    s = sim.simulate("walk", user_seed=7313, length_m=6.0)
    s.meta["recording_start"] = "9999-12-31T23:59:59+00:00"
    d = write_session(s, tmp_path / "u7313")
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t")]) == 0
    bouts = pd.read_csv(tmp_path / "t" / "bouts.csv")
    assert len(bouts) and bouts["end_time"].isna().all()
