"""Session 33 gait-lab trial T2 (fixer F9), findings 7 and 8: the insoles' clock offset against the foot IMU
(decisions L389 not adopted, L390 adopted, B297's line) and the force drop-off as the toe-off (L388, not adopted:
opt-in). The shifted copies delay both force files by 60 / 150 ms, as the trial's ``shift150``."""

from __future__ import annotations

import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace.force_clock import clock_offset, toe_offs_in


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    out = tmp_path_factory.mktemp("f9") / "A_u7368"
    write_session(simulate("A", UserProfile.from_seed(7368), "normal", rate_hz=100.0), out)
    return out


def _shifted(src, dst, ms: float):
    """A copy of ``src`` whose force files read ``ms`` later (the value at t is the original's at t - ms)."""
    shutil.copytree(src, dst)
    for name in ("fForceA", "fForceB"):
        df = pd.read_csv(dst / f"{name}.csv")
        t = df.timestamp.to_numpy(float)
        df.assign(x=np.interp(t - ms, t, df.x.to_numpy(float))).to_csv(dst / f"{name}.csv", index=False)
    return dst


def _track(path, **kw):
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    return track_plasys(read_session(path), **kw)


def test_clock_offset_kernel_pairs_each_event_with_the_nearest():
    imu = np.array([1.0, 2.1, 3.2, 4.3])
    force = imu + np.array([0.05, 0.06, 0.07, 0.9])  # the last is no pair (beyond 0.3 s of every IMU event)
    off, n = clock_offset(force, imu)
    assert n == 3 and off == pytest.approx(0.06)
    assert clock_offset([], imu) == (pytest.approx(np.nan, nan_ok=True), 0)
    off, n = clock_offset(imu - 0.2, imu[::-1])  # early force, IMU events in any order
    assert n == 4 and off == pytest.approx(-0.2)


def test_toe_offs_in_takes_the_last_drop_off_before_the_ic():
    off = [0.5, 0.9, 2.0]
    tc = toe_offs_in(off, [0.4, 1.8, 3.0], [1.2, 2.9, 3.9])
    assert tc[0] == pytest.approx(0.9) and tc[1] == pytest.approx(2.0) and np.isnan(tc[2])


def test_force_offset_follows_a_shift_and_is_warned_l390(walk, tmp_path):
    clean = _track(walk)
    r60 = _track(_shifted(walk, tmp_path / "s60", 60.0))
    r150 = _track(_shifted(walk, tmp_path / "s150", 150.0))
    off = [r.info["force_offset_s"] for r in (clean, r60, r150)]
    assert abs(off[0]) < 0.02  # a clean session: the two toe-offs agree (L390: about -5 ms)
    assert off[1] - off[0] == pytest.approx(0.060, abs=0.005)
    assert off[2] - off[0] == pytest.approx(0.150, abs=0.005)
    assert not [w for w in clean.info["warnings"] if "L390" in w]
    for r in (r60, r150):
        lines = [w for w in r.info["warnings"] if "L390" in w and "L161" not in w]
        assert len(lines) == 1 and "fForceA.csv, fForceB.csv" in lines[0] and "--ignore-force" in lines[0]
        assert "--merge" in lines[0] and "not shifted" in lines[0]
    assert clean.info["stance_source"] == r150.info["stance_source"] == "force"  # L365 passes the shift
    assert "tc_s" not in clean.steps and clean.info["toe_off_source"] is None  # the check adds no --toe-off columns


def test_the_track_cli_writes_force_offset_s_and_one_line(walk, tmp_path, capsys):
    import json

    from pdrlearn.cli import main

    src = _shifted(walk, tmp_path / "s150", 150.0)
    code = main(["track", "--no-plot", str(src), "--out", str(tmp_path / "t")])
    err = capsys.readouterr().err
    assert code == 0 and "Traceback" not in err
    assert len([ln for ln in err.splitlines() if "decision L390" in ln and "fForceA.csv" in ln]) == 1
    # B297: L161's line no longer blames the waist alone (the trial: "the waist unit's steps fall -0.21 s ...")
    l161 = [ln for ln in err.splitlines() if "decision L161" in ln]
    assert all("force insoles'" in ln for ln in l161)
    info = json.loads((tmp_path / "t" / "summary.json").read_text())["info"]
    assert info["force_offset_s"] == pytest.approx(0.145, abs=0.02)


def test_force_toe_off_is_the_drop_off_when_switched_on_l388(walk, monkeypatch):
    import pdrlearn.track.plasys as P
    from pdrlearn.displace.force_clock import force_events
    from pdrlearn.io import read_session

    gyro = _track(walk, toe_off=True)
    assert gyro.info["toe_off_source"] == "gyroscope"  # L388 not adopted: the default stays L73's
    monkeypatch.setattr(P, "FORCE_TOE_OFF", True)
    res = _track(walk, toe_off=True)
    assert res.info["toe_off_source"] in ("force", "force+gyroscope")
    offs = force_events(read_session(walk))["start_s"].to_numpy(float)
    tc = res.steps["tc_s"].to_numpy(float)
    tc = tc[np.isfinite(tc)]
    assert len(tc) > 5 and np.isin(np.round(tc, 9), np.round(offs, 9)).mean() > 0.8
    assert not np.allclose(tc, gyro.steps["tc_s"].to_numpy(float)[np.isfinite(gyro.steps["tc_s"])][:len(tc)])
    assert _track(walk, toe_off=True, ignore_force=True).info["toe_off_source"] == "gyroscope"


def test_a_clean_20hz_walk_is_not_warned_l390_amended(tmp_path):
    """L390 amended (session 33, the lead): both events are dated to a whole sample, so the bound is at least two
    foot sample periods; before it, the default 20 Hz scenario A (user 1, clean insoles) read +53 ms and was warned
    (tests/test_cli_outputs.py caught the extra line)."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    out = tmp_path / "A_u1"
    write_session(simulate("A", UserProfile.from_seed(1), "normal", rate_hz=20.0), out)
    r = _track(out)
    assert r.info["force_offset_s"] is not None and abs(r.info["force_offset_s"]) <= 0.1
    assert not any("L390" in w for w in r.info.get("warnings", []))
