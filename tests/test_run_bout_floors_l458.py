"""Decision L458 (session 37): `pdrlearn run` fills bouts.csv's floors_up / floors_down from its summary's climbs, as
`track` does (L450); they were empty. Simulated user 9106 only."""

from __future__ import annotations

import contextlib
import io
import json

import pandas as pd
import pytest

from pdrlearn.cli import main

ROUTE = "stand:3, straight:20, stand:10, straight:5, up:17, turn:180, down:17, stand:10, straight:20, stand:3"


def _quiet(args) -> int:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main(args)


@pytest.fixture(scope="module")
def stairs(tmp_path_factory):
    sim = tmp_path_factory.mktemp("l458") / "s"
    assert _quiet(["simulate", "--route", ROUTE, "-u", "9106", "-o", str(sim)]) == 0
    return sim


def _floors(out):
    bouts = pd.read_csv(out / "bouts.csv")
    summary = json.loads((out / "summary.json").read_text())
    return bouts[["bout", "floors_up", "floors_down"]], summary


@pytest.mark.parametrize("unit", ["foot", "waist"])
def test_run_bouts_count_the_floors_as_tracks_do_l458(stairs, tmp_path, tmp_path_factory, unit):
    if unit == "foot":
        from tests.runtime_helpers import trained_dirs

        bundle, track_args = trained_dirs(tmp_path_factory)["root"] / "bundle_foot", []
    else:
        cal = tmp_path / "cal.json"
        cal.write_text(json.dumps({"leg_m": 0.92, "k": 1.37, "source": "calibrated", "pipeline": "waist-pendulum"}))
        bundle, track_args = tmp_path / "wb", ["--pipeline", "waist-pendulum", "--params", str(cal)]
        assert _quiet(["export", str(cal), "--out", str(bundle)]) == 0
    assert _quiet(["run", "--no-plot", str(bundle), str(stairs), "--out", str(tmp_path / "run")]) == 0
    assert _quiet(["track", "--no-plot", str(stairs), *track_args, "--out", str(tmp_path / "track")]) == 0
    run, run_summary = _floors(tmp_path / "run")
    track, _ = _floors(tmp_path / "track")
    assert run_summary["floors_up"] == 1 and run_summary["floors_down"] == 1, run_summary["floors_up"]
    assert run[["floors_up", "floors_down"]].notna().all().all(), run  # empty before L458
    assert int(run["floors_up"].sum()) == 1 and int(run["floors_down"].sum()) == 1
    assert len(run) == len(track) and (run.to_numpy() == track.to_numpy()).all(), (run, track)
