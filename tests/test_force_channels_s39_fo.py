"""Session 39, fixer FO (review R2 findings 4, 5): one usable force channel (steps 77, 78, decision B409)."""

from __future__ import annotations

import logging
import shutil

import pandas as pd
import pytest


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    return write_session(simulate("B", UserProfile.from_seed(10320), "normal", rate_hz=100.0),
                         tmp_path_factory.mktemp("fo") / "walk")


def _light_heel(folder):  # R2's toe walker: the heel loaded 1 % of its usual (a few N), the forefoot as recorded
    df = pd.read_csv(folder / "fForceA.csv")
    df["x"] = 0.01 * df["x"]
    df.to_csv(folder / "fForceA.csv", index=False)


def test_steps_accel_force_without_usable_force_is_one_error_b409(walk, tmp_path, capsys, caplog):
    from pdrlearn.cli import main

    fore = shutil.copytree(walk, tmp_path / "fore")
    (fore / "fForceA.csv").unlink()  # R2's /tmp/r2/foreonly: the forefoot alone
    with caplog.at_level(logging.WARNING):
        assert main(["steps", str(fore), "--detector", "accel-force"]) == 2
    text = capsys.readouterr().err + caplog.text
    # before: a fall-back warning, then "has no fForceA, fForceB ... (it has: ...)" without the fForceB that is there
    assert "stance from the accelerometer/gyroscope detector" not in text and "has no fForceA" not in text
    assert "fForceB.csv (forefoot) alone times the initial contact late" in text and "--detector accel," in text


def test_light_heel_is_barely_loaded_and_said_once_steps_77(walk, tmp_path):
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    toe = shutil.copytree(walk, tmp_path / "toe")
    _light_heel(toe)
    res = track_plasys(read_session(toe))
    lines = [w for w in res.info["warnings"] if "steps decision 74" in w]
    assert len(lines) == 1 and "fForceA.csv (heel) is barely loaded" in lines[0]
    assert "a toe walker's heel, or a dead channel" in lines[0] and "drop the dead file" not in lines[0]
    assert not any(w.startswith("no force sensors") for w in res.info["warnings"])  # before: said again
