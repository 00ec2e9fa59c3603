"""Session 39, fixer FG (trial T4 findings 5-8): dead force channels (steps 74), one force channel (steps 75)."""

from __future__ import annotations

import copy
import json
import logging
import shutil

import numpy as np
import pandas as pd
import pytest


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    return write_session(simulate("B", UserProfile.from_seed(10130), "normal", rate_hz=100.0),
                         tmp_path_factory.mktemp("fg") / "walk")


@pytest.fixture(scope="module")
def clean(walk):
    """The walk as recorded, read and tracked with the default settings: ``(session, track)`` (the reference of the
    steps 74 / 75 tests and B400's line)."""
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    session = read_session(walk)
    return session, track_plasys(session)


def _copy(src, dst, edit):
    """A copy of session folder ``src`` with ``edit(folder)`` applied (test_force_check_l365's edits the force
    tables; these edit files)."""
    edit(shutil.copytree(src, dst))
    return dst


def _set(name, fn):
    def edit(folder):
        df = pd.read_csv(folder / f"{name}.csv")
        df["x"] = fn(df["x"].to_numpy(float))
        df.to_csv(folder / f"{name}.csv", index=False)
    return edit


def _total(folder):  # the trial's total-force column: heel + forefoot in fForceA, no fForceB
    a, b = (pd.read_csv(folder / f"{n}.csv") for n in ("fForceA", "fForceB"))
    a["x"] = a["x"] + np.interp(a["timestamp"], b["timestamp"], b["x"])
    a.to_csv(folder / "fForceA.csv", index=False)
    (folder / "fForceB.csv").unlink()


def _track(path, **kw):
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    return track_plasys(read_session(path), **kw)


def test_dead_channel_kernel_steps_74():
    from pdrlearn.displace.force_channels import dead_channels

    t = np.linspace(0, 10, 1001)
    heel = np.clip(600 * np.sin(2 * np.pi * t), 0, None)  # a stance/swing modulation
    noise = np.abs(np.random.default_rng(0).normal(0, 2, t.size))  # the trial's noisy dead channel
    assert dead_channels({"fForceA": heel, "fForceB": 0.5 * heel}) == {}
    assert dead_channels({"fForceA": heel, "fForceB": np.zeros_like(t)}) == {"fForceB": "flat"}
    assert dead_channels({"fForceA": heel, "fForceB": noise}) == {"fForceB": "weak"}
    assert dead_channels({"fForceA": np.full_like(t, 250.0)}) == {"fForceA": "flat"}  # a constant ADC offset
    assert dead_channels({"fForceA": heel}) == {}


def test_track_names_a_dead_heel_and_keeps_force_steps_74(walk, clean, tmp_path):
    clean = clean[1]
    dead = _copy(walk, tmp_path / "deadB", _set("fForceB", np.zeros_like))
    res = _track(dead, toe_off=True)
    lines = [w for w in res.info["warnings"] if "steps decision 74" in w]
    assert len(lines) == 1 and "fForceB.csv (forefoot) is flat at 0 N: a dead channel" in lines[0]
    assert "the force is fForceA.csv alone" in lines[0]
    assert not any(w.startswith("no force sensors") for w in res.info["warnings"])  # before: "no force sensors"
    assert res.info["stance_source"] == "force" and len(res.steps) == len(clean.steps)
    # steps 75: the heel's drop-off is no toe-off, so L390's clock check is not run on one channel (it read -210 ms)
    assert res.info["force_offset_s"] is None and not any("decision L390" in w for w in res.info["warnings"])
    m2 = _track(dead, method="M2")  # before: "has no fForceA/fForceB needed by M2", exit 2
    assert len(m2.steps) == len(clean.steps)


def test_noisy_dead_forefoot_is_not_blamed_by_l365_steps_74(walk, tmp_path):
    noisy = _copy(walk, tmp_path / "noisyB",
                  _set("fForceB", lambda x: np.abs(np.random.default_rng(0).normal(0, 2, x.size))))
    res = _track(noisy)
    text = " | ".join(res.info["warnings"])
    assert "fForceB.csv (forefoot) is barely loaded" in text and "a dead channel" in text  # steps 77 wording
    assert "disagree with the foot IMU" not in text  # before: both files blamed, the whole session the IMU's
    assert res.info["stance_source"] == "force"


def test_info_flags_a_dead_channel_steps_74(walk, tmp_path, caplog):
    from pdrlearn.cli import main

    dead = _copy(walk, tmp_path / "deadA", _set("fForceA", np.zeros_like))
    with caplog.at_level(logging.WARNING):
        assert main(["info", str(dead), "--json"]) == 0
    assert "fForceA.csv (heel) is flat at 0 N: a dead channel" in caplog.text
    assert "fForceB.csv (forefoot) alone times the initial contact late" in caplog.text


def test_one_total_channel_tracks_and_counts_steps_75(walk, clean, tmp_path, capsys):
    from pdrlearn.cli import main
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelForceStepDetector

    clean = clean[1]
    total = _copy(walk, tmp_path / "total", _total)
    res = _track(total)  # before: "has no fForceB needed by the accelerometer + force step detector"
    assert res.info["stance_source"] == "force" and len(res.steps) == len(clean.steps)
    two = AccelForceStepDetector().detect(read_session(walk))
    one = AccelForceStepDetector().detect(read_session(total))
    assert len(one) == len(two) and np.allclose(one["event_s"], two["event_s"], atol=0.011)
    capsys.readouterr()
    assert main(["steps", str(total), "--detector", "accel-force", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] > 10


def test_lone_forefoot_falls_back_to_the_imu_steps_75(walk, tmp_path):
    dead = _copy(walk, tmp_path / "deadA", _set("fForceA", np.zeros_like))
    res = _track(dead)
    text = " | ".join(res.info["warnings"])
    assert "fForceA.csv (heel) is flat at 0 N" in text and "fForceB.csv (forefoot) alone times" in text
    assert res.info["stance_source"].startswith("inertial")
    from pdrlearn.errors import MissingSensorError

    with pytest.raises(MissingSensorError, match=r"needed by M2 .*fForceA.csv \(heel\) is flat at 0 N"):
        _track(dead, method="M2")


def _insole_csv(walk, path):
    """The trial's mk.py "plain" layout: time_s, acc in g, gyro in deg/s, heel, midfoot, forefoot (N)."""
    a, g = (pd.read_csv(walk / f"{n}.csv") for n in ("fAccelerometer", "fGyroscope"))
    h, f = (pd.read_csv(walk / f"{n}.csv")["x"].to_numpy(float) for n in ("fForceA", "fForceB"))
    n = min(len(a), len(g), len(h), len(f))
    df = pd.DataFrame({"time_s": a.timestamp[:n] / 1000.0, **{f"acc_{c}_g": a[c][:n] / 9.80665 for c in "xyz"},
                       **{f"gyr_{c}_dps": np.degrees(g[c][:n]) for c in "xyz"}})
    df["heel"], df["midfoot"], df["forefoot"] = h[:n], 0.5 * (h[:n] + f[:n]), f[:n]
    df.to_csv(path, index=False)
    return path


def test_import_names_a_midfoot_channel_and_where_to_add_it_b399(walk, tmp_path, capsys):
    from pdrlearn.cli import main

    csv = _insole_csv(walk, tmp_path / "insole.csv")
    assert main(["import", str(csv), "--out", str(tmp_path / "imp"), "--heel", "heel", "--toe", "forefoot"]) == 0
    err = capsys.readouterr().err
    assert "unused columns: midfoot" in err  # before: this line alone
    assert "midfoot: a further force channel?" in err and "into the forefoot column" in err and "B399" in err


def test_no_stance_line_says_why_the_insoles_give_no_toe_off_b400(walk, clean, tmp_path):
    from pdrlearn.cli.common import NO_STANCE_CLAUSE, gait_line

    s, track = copy.copy(clean[0]), copy.copy(clean[1])
    track.steps = track.steps.copy()  # summary() adds columns to the steps: the shared track is left as it was
    with_force = gait_line(track.summary(s))
    assert NO_STANCE_CLAUSE in with_force and "with force insoles too: --toe-off takes the gyroscope's" in with_force
    assert "steps decision 76" in with_force and "B400" in with_force
    without = gait_line(_track(walk, ignore_force=True).summary(s))
    assert without.endswith(NO_STANCE_CLAUSE) and "B400" not in without  # an IMU-only stance: as before
