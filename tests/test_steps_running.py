"""Steps decisions 43 / 44 (session 27 runner trial, F4): `pdrlearn steps` at 20 Hz on a run (188 steps/min)
merges strides; its steps 38 line names the count `track` gives only when that is true (with force sensors `track`
counts their contacts, not the foot's rests), and L95's walking-range line is given on the strides' cadence."""

from __future__ import annotations

import json
import logging
import shutil

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def run20(tmp_path_factory):
    """The trial's run31_20hz: steps of 1.0 m in 0.32 s (188 steps/min), sampled at 20 Hz; and a
    copy without the force sensors (one foot IMU, the trial's fo_run31_20hz)."""
    root = tmp_path_factory.mktemp("run")
    out = root / "run31_20hz"
    assert main(["simulate", "--route", "stand:3, straight:100, stand:3", "--step-length", "1.0", "--step-time",
                 "0.32", "--rate", "20", "--user-seed", "1", "--out", str(out)]) == 0
    fo = root / "fo_run31_20hz"
    shutil.copytree(out, fo)
    for name in ("fForceA.csv", "fForceB.csv"):
        (fo / name).unlink()
    return out, fo


def _lines(folder, capsys, caplog):
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        assert main(["steps", str(folder), "--json"]) == 0
    return json.loads(capsys.readouterr().out), [r.getMessage() for r in caplog.records]


def test_merged_line_names_the_foot_imu_track_when_force_sensors_count(run20, capsys, caplog):
    """Steps 43: with force sensors the rest-to-rest count is the foot-IMU-only track's (`--method M1`)."""
    d, lines = _lines(run20[0], capsys, caplog)
    merged = [ln for ln in lines if "steps 38" in ln]
    assert d["rest_strides"] > d["count"] and len(merged) == 1, lines
    assert "--method M1" in merged[0] and "force sensors instead" in merged[0] and "steps 43" in merged[0]
    d, lines = _lines(run20[1], capsys, caplog)  # no force sensors: `track DIR` itself splits at the rests
    merged = [ln for ln in lines if "steps 38" in ln]
    assert len(merged) == 1 and "--method M1" not in merged[0]
    assert f"`pdrlearn track DIR` splits them at the rests (decision L96) and counts {d['rest_strides']}" in merged[0]


def test_steps_gives_the_walking_range_line_on_a_run(run20, capsys, caplog):
    """Steps 44: L95's line (leg-scaled by L148) on the detected strides' cadence, with and without force."""
    for folder in run20:
        _, lines = _lines(folder, capsys, caplog)
        rng = [ln for ln in lines if "steps 44" in ln]
        assert len(rng) == 1 and "decision L95" in rng[0] and "running" in rng[0], lines
        assert "the detected strides: median cadence 18" in rng[0]


def test_no_walking_range_line_on_walks(capsys, caplog):
    """Steps 44: no false alarm on a real walk (foot strides) or a real lower-back walk (waist steps)."""
    for folder, det in (("datasets/real/gaitmap_level_right", "accel"),
                        ("datasets/real/mobgap_HA001_Test5_Trial1", "pll")):
        caplog.clear()
        with caplog.at_level(logging.WARNING):
            assert main(["steps", folder, "--detector", det]) == 0
        assert not [r for r in caplog.records if "steps 44" in r.getMessage()]
    capsys.readouterr()
