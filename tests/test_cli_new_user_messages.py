"""Error lines a new user met in a fresh-clone trial said what was wrong but not what to do: a session folder
given as the model ("(retrain it)"), a cohort user without test/ ("evaluate explicitly"), a waist bundle fed
the foot's Bluetooth protocol ("export a foot-only model", without how)."""

from __future__ import annotations

import io
import shutil
import sys
from pathlib import Path

import pytest

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
BUNDLE = ROOT / "models" / "plasys-sim-default"


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    return err[0]


def test_session_given_as_model_says_arguments_swapped(capsys):
    session = REAL / "gaitmap_level_left"
    assert main(["evaluate", str(session), str(session)]) == 2
    msg = _err(capsys)
    assert "not a model directory written by 'pdrlearn train'" in msg and "session folder" in msg
    assert "retrain it" not in msg


def test_cohort_user_without_test_folder_is_told_how(tmp_path):
    from pdrlearn.cohort import user_sessions
    from pdrlearn.errors import DataError

    user = tmp_path / "cohort" / "u1"
    shutil.copytree(REAL / "gaitmap_level_left", user / "s1")  # no test/ folder
    with pytest.raises(DataError) as err:
        user_sessions(user, "test")
    assert str(user / "test") in str(err.value) and "pdrlearn evaluate MODEL_DIR" in str(err.value)


def test_protocol_with_a_waist_bundle_says_how_to_make_a_foot_one(tmp_path, capsys, monkeypatch):
    """Since decision E26 the waist bundle replays the protocol with the foot unit alone (a warning); asking
    for both units is the error, which names the option."""
    still = "%$1 0 9.81 0$2 0 0 0\n" * 40  # 2 s of a foot at rest (an empty capture is refused since B193)
    monkeypatch.setattr(sys, "stdin", io.StringIO(still))
    assert main(["run", "--no-plot", str(BUNDLE), "--protocol", "-", "--out", str(tmp_path / "o")]) == 0
    assert "has no waist unit" in capsys.readouterr().err
    monkeypatch.setattr(sys, "stdin", io.StringIO(""))
    assert main(["run", "--no-plot", str(BUNDLE), "--protocol", "-", "--units", "foot,waist", "--out",
                 str(tmp_path / "p")]) == 2
    assert "--units foot" in _err(capsys)


def test_folder_of_sessions_given_to_a_one_session_command(tmp_path, capsys):
    shutil.copytree(REAL / "gaitmap_level_left", tmp_path / "calib" / "walk1")
    shutil.copytree(REAL / "gaitmap_level_right", tmp_path / "calib" / "walk2")
    assert main(["info", str(tmp_path / "calib")]) == 2
    msg = _err(capsys)
    assert "holds session folders (walk1, walk2)" in msg and str(tmp_path / "calib" / "walk1") in msg


def test_missing_fix_file_is_refused_before_tracking(tmp_path, capsys):
    """Before, the session was tracked first (a 'no model' warning, then the error)."""
    assert main(["track", "--no-plot", str(REAL / "gaitmap_level_left"), "--gnss", str(tmp_path / "none.nmea"), "--out",
                 str(tmp_path / "o")]) == 2
    assert "no such fix file" in _err(capsys)  # the only stderr line
    assert not (tmp_path / "o").exists()
