"""Session 39, fixer FO (review R2 findings 4, 5): one usable force channel (steps 77, 78, decision B409)."""

from __future__ import annotations

import logging
import shutil

import numpy as np
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


def test_lone_heel_of_toe_walker_is_refused_steps_78(walk, tmp_path, capsys):
    from pdrlearn.cli import main

    heel = shutil.copytree(walk, tmp_path / "heel")
    (heel / "fForceB.csv").unlink()  # a heel-only insole on a normal walker: counted on the heel (steps 75)
    assert main(["steps", str(heel), "--detector", "accel-force"]) == 0
    toe = shutil.copytree(heel, tmp_path / "toe")
    df = pd.read_csv(toe / "fForceA.csv")  # R2's /tmp/r2/toe_heelonly: the heel barely loaded, a few N baseline
    df["x"] = 0.01 * df["x"] + np.abs(np.random.default_rng(0).normal(2.5, 1.5, len(df)))
    df.to_csv(toe / "fForceA.csv", index=False)
    capsys.readouterr()
    assert main(["steps", str(toe), "--detector", "accel-force"]) == 2  # before: 0, with 0 or 5 of the strides
    err = capsys.readouterr().err
    assert "steps decision 78" in err and "--detector accel" in err and "Traceback" not in err
