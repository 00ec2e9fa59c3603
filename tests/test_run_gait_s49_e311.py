"""Decision E311 (session 49, I1; trial T3 F4 of session 48): `pdrlearn run BUNDLE SESSION --gait OTHER_FOOT` writes
`pdrlearn gait`'s four files of the two feet's streamed strides, by gait's own functions. Simulated user 16238."""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.gait import GAIT_FILES, summary_json
from pdrlearn.outfolder import folder_kind
from pdrlearn.track.bilateral import pair_sessions
from pdrlearn.track.gait_tables import gait_tables

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    root = tmp_path_factory.mktemp("e311")
    for foot in ("left", "right"):
        assert main(["simulate", "--route", "stand:2, straight:8, stand:2", "--user-seed", "16238", "--seed", "1",
                     "--rate", "50", "--foot", foot, "--out", str(root / foot[0].upper())]) == 0
    out, err, here = root / "run", io.StringIO(), os.getcwd()
    # SESSION is the right foot: the sides come from meta.json, not from the order; folders typed bare (E176)
    os.chdir(root)
    try:
        with contextlib.redirect_stderr(err):
            assert main(["run", str(BUNDLE), "R", "--gait", "L", "--contacts", "--units", "foot", "--no-plot",
                         "--redact-paths", "--out", "run"]) == 0
    finally:
        os.chdir(here)
    return root, out, pair_sessions(root / "L", root / "R"), err.getvalue()  # offline: what `gait L R` computes


def test_run_gait_writes_gaits_files_and_columns(pair):
    root, out, offline, _ = pair
    assert folder_kind(out) == "run"  # gait's files in a run folder keep it run's (`run --force` replaces it)
    for name, table in gait_tables(offline).items():
        mine = pd.read_csv(out / name)
        assert list(mine.columns) == list(table.columns), name
        assert len(mine) == len(table), name
    summary = json.loads((out / "gait_summary.json").read_text())
    assert set(summary) == set(summary_json(offline)) and set(summary["walk"]) == set(offline["walk"])
    assert summary["contact_source"] == {"left": "force", "right": "force"}
    # --redact-paths: the two sessions as typed are redacted in gait_summary.json and run.json (E176)
    assert {s["session"] for s in summary["sessions"].values()} == {"<redacted>"}
    assert json.loads((out / "run.json").read_text())["options"]["gait_other"] == "<redacted>"
    assert set(GAIT_FILES) <= {p.name for p in out.iterdir()}
    # each foot's own trust lines as gait's (L461; its numbers the streamed ones), e.g. L414's stance line
    for side in ("left", "right"):
        mine, theirs = (x["sessions"][side]["warnings"] for x in (summary, offline))
        assert [w[:29] for w in mine] == [w[:29] for w in theirs] and any("stance" in w for w in mine), side


def test_run_gait_steps_are_the_streamed_strides_within_the_measured_difference(pair):
    """The stated difference (E311): the same steps and kinds; contacts, step and stride times within a few ms of
    offline gait's, stance (L73's toe-off on the streamed stride windows) within 10 ms."""
    root, out, offline, _ = pair
    steps, cycles = pd.read_csv(out / "gait_steps.csv"), pd.read_csv(out / "gait_cycles.csv")
    run_steps = pd.read_csv(out / "steps.csv")  # the right foot's replay: its contacts are gait's right steps'
    right_ic = steps.loc[steps["side"] == "right", "ic_s"].to_numpy(float)
    assert np.abs(right_ic[:, None] - run_steps["event_s"].to_numpy(float)[None, :]).min(axis=1).max() < 1e-6
    a, c = offline["steps"], offline["cycles"]
    assert steps["side"].tolist() == a["side"].tolist() and steps["kind"].tolist() == a["kind"].tolist()
    assert np.abs(steps["ic_s"] - a["ic_s"]).max() < 0.005
    assert np.abs(steps["step_time_s"] - a["step_time_s"]).max() < 0.005
    assert np.abs(cycles["stride_time_s"] - c["stride_time_s"]).max() < 0.005
    d = np.abs(cycles["stance_time_s"] - c["stance_time_s"]).to_numpy(float)
    assert np.nanmax(d) < 0.010 and np.isfinite(d).sum() >= len(d) - 2


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    return err


def test_run_gait_refusals_are_one_line_before_any_replay(pair, tmp_path, capsys):
    root, _, _, _ = pair
    waist = tmp_path / "wbundle"
    waist.mkdir()
    (waist / "manifest.json").write_text(json.dumps({"schema": "pdrlearn-waist-bundle"}))
    assert main(["run", str(waist), str(root / "R"), "--gait", str(root / "L")]) == 2
    assert "run: --gait is for a foot-unit bundle" in _err(capsys)
    assert main(["run", str(BUNDLE), "--protocol", "x.txt", "--gait", str(root / "L")]) == 2
    assert "a --protocol capture is no session folder" in _err(capsys)
    no_foot = tmp_path / "nofoot"
    shutil.copytree(root / "L", no_foot, ignore=shutil.ignore_patterns("fAccelerometer.csv", "fGyroscope.csv"))
    capsys.readouterr()
    assert main(["run", str(BUNDLE), str(root / "R"), "--gait", str(no_foot), "--out", str(tmp_path / "o")]) == 2
    assert f"gait: {no_foot} has no foot unit" in _err(capsys)
    assert main(["run", str(BUNDLE), str(root / "R"), "--gait", str(root / "R")]) == 2
    assert "hold the same recording" in _err(capsys)
    assert not (tmp_path / "o").exists()


def test_the_feet_replays_do_not_repeat_runs_warnings(pair):
    """Each foot's replay says the bundle's rate lines again; run says them once (E311's said_once)."""
    err = pair[3]
    assert err.count("not the bundle's 20 Hz") == 1 and err.count("step classifiers were trained at") == 1, err


def test_the_lean_command_names_run_gait_in_one_line(pair, tmp_path, capsys):
    """The lean command has no gait (pandas, scipy): `--gait` is one line naming `pdrlearn run ... --gait`."""
    from pdrlearn.runtime.__main__ import main as lean_main

    root = pair[0]
    assert lean_main([str(BUNDLE), str(root / "R"), "--gait", str(root / "L"), "--out", str(tmp_path / "o")]) == 2
    assert f"`pdrlearn run {BUNDLE} {root / 'R'} --gait {root / 'L'}`" in _err(capsys)
    assert not (tmp_path / "o").exists()
