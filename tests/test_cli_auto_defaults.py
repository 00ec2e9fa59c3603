"""Decision L36: `track` and `steps` pick the pipeline / detector from the session's units by default."""

from __future__ import annotations

import json

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.base import resolve_pipeline


def test_resolve_pipeline_by_units(real_dir, gaitmap_level_left, mobgap_test5):
    assert resolve_pipeline("auto", read_session(gaitmap_level_left)) == "plasys"
    assert resolve_pipeline("auto", read_session(mobgap_test5)) == "waist-pendulum"
    assert resolve_pipeline("waist-pll", read_session(gaitmap_level_left)) == "waist-pll"


def test_track_and_steps_on_a_lower_back_recording_without_options(mobgap_test5, tmp_path, capsys):
    assert main(["track", "--no-plot", str(mobgap_test5), "--out", str(tmp_path / "t"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pipeline"] == "waist-pendulum" and out["step_f1"] == 1.0 and "distance_error_pct" in out
    assert main(["steps", str(mobgap_test5), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["detector"] == "waist-ic" and out["unit"] == "waist" and out["f1"] >= 0.95


def test_steps_on_a_foot_recording_without_options(gaitmap_level_left, capsys):
    assert main(["steps", str(gaitmap_level_left), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["detector"] == "accel" and out["f1"] >= 0.98
