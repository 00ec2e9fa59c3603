"""New-user trial (session 14, indoor walks across floors): `pdrlearn run` writes what `pdrlearn track` writes.

- E43: run's ``heading_rad`` is wrapped to [-pi, pi) as track's (it was the runtime's unwrapped heading:
  -0.08 to 52.79 rad on the trial's tower walk).
- E44: run writes ``path.png`` and takes ``--start LAT,LON`` (its lat/lon columns were always empty).
- L56: ``--start LAT,LON,ALT`` of track and run: the z column starts at ALT (only ``Tracker(start=...)`` could).
- E45: ``run --units foot`` on a session that has a waist unit says the waist is not used, not "no waist unit".
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.track.geodetic import parse_start
from tests.runtime_helpers import synthetic_session, trained_dirs

START = "41.178,-8.608"


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """A two-unit walk that turns 0.3 rad per stride: 7 rad in all, past +-pi."""
    d = tmp_path_factory.mktemp("walk") / "turning"
    write_session(synthetic_session(24, seed=11, name="turning", turn_rad_per_step=0.3), d)
    return d


def _wrapped_diff(a, b):
    return np.angle(np.exp(1j * (np.asarray(a, float) - np.asarray(b, float))))


def test_run_heading_is_wrapped_as_track_writes_it(root, walk, tmp_path, capsys):
    assert main(["run", "--no-plot", str(root / "bundle"), str(walk), "--out", str(tmp_path / "r")]) == 0
    assert main(["track", "--no-plot", str(walk), "--model", str(root / "model"), "--streaming",
                 "--out", str(tmp_path / "t")]) == 0
    # without --start neither summary has lat/lon keys
    for d in ("r", "t"):
        assert set(json.loads((tmp_path / d / "summary.json").read_text())["final_position"]) == set("xyz")
    run, trk = (pd.read_csv(tmp_path / d / "steps.csv") for d in ("r", "t"))
    h = run["heading_rad"].to_numpy(float)
    assert len(h) >= 20
    assert np.all((h >= -np.pi) & (h <= np.pi)), (h.min(), h.max())
    # the walk turned past pi: an unwrapped heading would leave the interval (this test would not pass by luck)
    assert np.ptp(np.unwrap(h)) > np.pi
    assert np.abs(_wrapped_diff(h, trk["heading_rad"])).max() < 1e-3  # the same angles as track --streaming
    # still the direction each step was placed along: the trajectory's increments
    traj = pd.read_csv(tmp_path / "r" / "trajectory.csv")
    L = run["length_m"].to_numpy(float)
    np.testing.assert_allclose(np.diff(traj["x"]), L * np.cos(h), atol=1e-6)
    np.testing.assert_allclose(np.diff(traj["y"]), L * np.sin(h), atol=1e-6)


def test_run_writes_path_png_and_lat_lon_with_start(root, walk, tmp_path, capsys):
    out = tmp_path / "r"
    assert main(["run", str(root / "bundle"), str(walk), "--start", START, "--out", str(out)]) == 0
    assert main(["track", str(walk), "--model", str(root / "model"), "--streaming", "--start", START,
                 "--out", str(tmp_path / "t")]) == 0
    assert (out / "path.png").stat().st_size > 1000
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in (tmp_path / "t").iterdir())
    # decision L122: both record their run; run's names the bundle by its manifest's SHA-256 (= manifest.sha256)
    import json

    rec_run, rec_track = (json.loads((tmp_path / d / "run.json").read_text()) for d in ("r", "t"))
    assert rec_run["command"] == "run" and rec_run["session"] == str(walk) and rec_run["options"]["start"] == START
    assert rec_run["bundle"]["manifest_sha256"] == (root / "bundle/manifest.sha256").read_text().split()[0]
    assert rec_track["command"] == "track" and rec_track["options"]["streaming"] is True
    assert rec_track["model"]["path"] == str(root / "model") and len(rec_track["model"]["manifest_sha256"]) == 64
    run, trk = (pd.read_csv(tmp_path / d / "trajectory.csv") for d in ("r", "t"))
    assert list(run.columns) == ["t", "x", "y", "z", "lat", "lon", "pos_sigma_m", "z_rides", "floor"]  # L128, L630
    np.testing.assert_allclose(run["pos_sigma_m"], trk["pos_sigma_m"], atol=0.01)  # the same model as --streaming
    assert run[["lat", "lon"]].notna().all().all()
    assert run["lat"].iloc[0] == pytest.approx(41.178) and run["lon"].iloc[0] == pytest.approx(-8.608)
    # track's geodetic update (thesis eq. 56/57) on the same steps: within 1 mm (1e-8 deg ~ 1 mm)
    np.testing.assert_allclose(run[["lat", "lon"]].to_numpy(), trk[["lat", "lon"]].to_numpy(), atol=1e-8)
    # and consistent with x (east) / y (north) in metres on the sphere of R = 6371 km
    dlat = np.radians(run["lat"] - 41.178) * 6371e3
    dlon = np.radians(run["lon"] + 8.608) * 6371e3 * np.cos(np.radians(41.178))
    np.testing.assert_allclose(dlat, run["y"], atol=0.01)
    np.testing.assert_allclose(dlon, run["x"], atol=0.01)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["final_position"]["lat"] == pytest.approx(run["lat"].iloc[-1])
    # a capture has no session: path.png without a ground truth
    from pdrlearn.io import format_protocol

    cap = tmp_path / "capture.txt"
    cap.write_text("".join(format_protocol(synthetic_session(15, seed=11))))
    assert main(["run", str(root / "bundle"), "--protocol", str(cap), "--out", str(tmp_path / "p")]) == 0
    assert (tmp_path / "p" / "path.png").is_file()


def test_start_altitude_shifts_z_only(root, walk, tmp_path, capsys):
    b, w = str(root / "bundle"), str(walk)
    assert main(["run", "--no-plot", b, w, "--start", START, "--out", str(tmp_path / "r0")]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", b, w, "--start", START + ",12.5", "--out", str(tmp_path / "r1"), "--json"]) == 0
    s1 = json.loads(capsys.readouterr().out)
    r0, r1 = (pd.read_csv(tmp_path / d / "trajectory.csv") for d in ("r0", "r1"))
    assert r1["z"].iloc[0] == 12.5
    np.testing.assert_allclose(r1["z"] - 12.5, r0["z"], atol=1e-9)
    for c in ("x", "y", "lat", "lon"):
        np.testing.assert_array_equal(r1[c], r0[c])
    assert s1["final_position"]["z"] == pytest.approx(12.5 + r0["z"].iloc[-1])
    # the steps' own z (the runtime's position) starts there too
    assert pd.read_csv(tmp_path / "r1" / "steps.csv")["z"].iloc[0] == pytest.approx(12.5 + r0["z"].iloc[1])
    # track: the same option, the same rule
    m = str(root / "model")
    assert main(["track", "--no-plot", w, "--model", m, "--streaming", "--start", START,
                 "--out", str(tmp_path / "t0")]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", w, "--model", m, "--streaming", "--start", START + ",-3",
                 "--out", str(tmp_path / "t1"), "--json"]) == 0
    t1s = json.loads(capsys.readouterr().out)
    t0, t1 = (pd.read_csv(tmp_path / d / "trajectory.csv") for d in ("t0", "t1"))
    assert t1["z"].iloc[0] == -3.0
    np.testing.assert_allclose(t1["z"] + 3.0, t0["z"], atol=1e-9)
    assert t1s["final_position"]["z"] == pytest.approx(t1["z"].iloc[-1])


def test_parse_start_altitude():
    assert parse_start("41.178,-8.608,12.5", altitude=True) == (41.178, -8.608, 12.5)
    assert parse_start("41.178,-8.608", altitude=True) == (41.178, -8.608, 0.0)
    for bad in ("1,2,3,4", "1,2,nan", "1,2,x", "91,0,3"):
        with pytest.raises(DataError, match="--start"):
            parse_start(bad, altitude=True)
    with pytest.raises(DataError, match=r"LAT,LON in decimal"):  # the Python default: two numbers
        parse_start("1,2,3")


def test_bad_start_is_one_line_naming_the_form(root, walk, tmp_path, capsys):
    for cmd in (["run", str(root / "bundle"), str(walk)], ["track", str(walk)]):
        assert main([*cmd, "--start", "41,-8,high", "--out", str(tmp_path / cmd[0])]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "LAT,LON[,ALT]" in err, err
        assert not (tmp_path / cmd[0]).exists()


def test_units_foot_on_a_session_with_a_waist_does_not_say_no_waist_unit(root, walk, tmp_path, capsys):
    assert main(["run", "--no-plot", str(root / "bundle"), str(walk), "--units", "foot",
                 "--out", str(tmp_path / "r")]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    # the toy model's C28 line (E47, as track's), the toy walk's L95 line (0.13 m/s, as track --streaming's) and
    # L145's (the toy model's foot altitude +0.95 m against the barometer's -0.05 m), and the toy model's C89 line on
    # its turning strides (run counts it since C94, as track --streaming), and E215's first-walk line (the toy walk
    # heads 10 deg or more from the foot unit's facing), and L652's (the toy model classes forward-travelling strides
    # backward; run says it since E287)
    err = [e for e in err if "terrain classes contradict" not in e and "decision L95" not in e
           and "disagrees with the waist barometer's" not in e and "decision C89" not in e
           and "decision E215" not in e and "decision L652" not in e]
    assert err == ["warning: turning: waist unit not used (--units foot): heading from the foot's own integrated "
                   "yaw (relative to the start)"], err
    # a foot-only bundle on the same two-unit session: no heading line claiming the waist is absent
    assert main(["run", "--no-plot", str(root / "bundle_foot"), str(walk), "--out", str(tmp_path / "f")]) == 0
    assert "no waist unit" not in capsys.readouterr().err


def test_run_takes_track_bout_options_and_detects_the_bouts_once(root, walk, tmp_path, monkeypatch):
    """L130: `run` has track's --bout-break-s / --bout-min-strides (the same typer options); E73: bouts.csv and the
    summary's n_bouts come from one detection."""
    import pdrlearn.track.bouts as bouts_mod

    calls = []
    real = bouts_mod.detected_bouts
    monkeypatch.setattr(bouts_mod, "detected_bouts", lambda *a, **k: calls.append(1) or real(*a, **k))
    assert main(["run", "--no-plot", str(root / "bundle"), str(walk), "--out", str(tmp_path / "d")]) == 0
    assert len(calls) == 1  # was 2: evaluate_track's n_bouts and _write's bouts.csv
    default = json.loads((tmp_path / "d" / "summary.json").read_text())
    assert default["n_bouts"] == len(pd.read_csv(tmp_path / "d" / "bouts.csv")) >= 1
    assert main(["run", "--no-plot", str(root / "bundle"), str(walk), "--bout-break-s", "3",
                 "--bout-min-strides", "1000", "--out", str(tmp_path / "r")]) == 0
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["bout_definition"] == {"break_s": 3.0, "min_strides": 1000, "gap": "rhythm"}
    assert summary["n_bouts"] == 0
    assert len(pd.read_csv(tmp_path / "r" / "bouts.csv")) == 0
    rec = json.loads((tmp_path / "r" / "run.json").read_text())["options"]
    assert rec["bout_break_s"] == 3.0 and rec["bout_min_strides"] == 1000
    assert main(["run", str(root / "bundle"), str(walk), "--bout-break-s", "0", "--out", str(tmp_path / "x")]) == 2
    assert not (tmp_path / "x").exists()


def test_streamed_foot_only_tracks_get_their_own_sigma_model(root, walk, tmp_path):
    """L150: a foot-only streamed track (`run` of a foot-only bundle, `run --units foot`, `track --streaming
    --units foot`) gets the `plasys-foot-streaming` parameters, not the offline foot-only `plasys-foot` ones, and
    run and track write the same pos_sigma_m."""
    from pdrlearn.track.position_sigma import SIGMA_PARAMS

    assert main(["run", "--no-plot", str(root / "bundle_foot"), str(walk), "--out", str(tmp_path / "r")]) == 0
    assert main(["run", "--no-plot", str(root / "bundle"), str(walk), "--units", "foot",
                 "--out", str(tmp_path / "u")]) == 0
    assert main(["track", "--no-plot", str(walk), "--model", str(root / "model_foot"), "--streaming",
                 "--units", "foot", "--out", str(tmp_path / "t")]) == 0
    for d in ("r", "u", "t"):
        info = json.loads((tmp_path / d / "summary.json").read_text())["info"]["position_sigma"]
        assert info == {"model": "plasys-foot-streaming", **SIGMA_PARAMS["plasys-foot-streaming"],
                        "bounded": False}, d  # L333: whether the end's radius is the distance bound
    run, trk = (pd.read_csv(tmp_path / d / "trajectory.csv") for d in ("r", "t"))
    np.testing.assert_allclose(run["pos_sigma_m"], trk["pos_sigma_m"], atol=0.01)
