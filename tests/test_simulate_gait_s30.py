"""`simulate --step-length M --step-time S` (decision S30): a chosen step and cadence from the command line, a
slow patient below the ~0.5 m/s of --speed slow x short; sessions simulated in Python are no longer all "sim"."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path


@pytest.mark.parametrize("speed", ["slow", "normal"])
def test_step_length_and_time_are_walked(tmp_path, capsys, speed):
    out = tmp_path / "p040"
    assert main(["simulate", "--route", "stand:2, straight:8, stand:2", "--user-seed", "1", "--speed", speed,
                 "--step-length", "0.3", "--step-time", "0.75", "--out", str(out), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["step_length_m"] == 0.3 and d["step_time_s"] == 0.75
    s = read_session(out)
    assert s.name == f"route_u1_{speed}_s0_step0.3m_0.75s"
    st = s.steps[s.steps["steady"].astype(bool)]
    assert np.median(st["length_m"]) == pytest.approx(0.6, rel=0.05)  # a stride is two steps
    ic = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    assert np.median(np.diff(ic)) == pytest.approx(0.75, rel=0.05)
    # 0.40 m/s: below the ~0.51 m/s that --speed slow with short route items gave (the trial's slowest)
    assert np.median(st["length_m"]) / (2 * np.median(np.diff(ic))) == pytest.approx(0.4, rel=0.07)


def test_only_one_of_them_keeps_the_users_other(tmp_path, capsys):
    out = tmp_path / "cad"
    assert main(["simulate", "--route", "straight:4", "--user-seed", "1", "--step-time", "1.0",
                 "--out", str(out), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    user = UserProfile.from_seed(1)
    assert d["step_time_s"] == 1.0 and d["step_length_m"] == pytest.approx(user.step_length("normal"), abs=1e-4)


@pytest.mark.parametrize("args, message", [
    (["--step-length", "0.05"], "--step-length 0.05: give 0.1-1 m"),
    (["--step-length", "1.5"], "give 0.1-1 m"), (["--step-length", "nan"], "give 0.1-1 m"),
    (["--step-time", "0.2"], "--step-time 0.2: give 0.25-2.5 s"), (["--step-time", "inf"], "give 0.25-2.5 s"),
    (["--step-time", "-1"], "give 0.25-2.5 s")])  # decision S38: down to a fast 3-year-old's 0.25 s
def test_bad_step_values_are_one_line(tmp_path, capsys, args, message):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", "straight:4", "--user-seed", "1", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and message in err and "\n" not in err, err
    assert not out.exists()


def test_scenarios_keep_the_users_gait(tmp_path, capsys):
    assert main(["simulate", "--scenario", "A", "--user-seed", "1", "--step-length", "0.3",
                 "--out", str(tmp_path / "a")]) == 2
    assert "--route" in capsys.readouterr().err and not (tmp_path / "a").exists()


def test_python_sessions_are_named_after_their_user():
    user = UserProfile.from_seed(1)
    assert simulate_path([Straight(2)], user, seed=3).name == "sim_u1_normal_s3"
    slow = dataclasses.replace(user, step_length_m=0.3, step_time_s=0.75)
    assert simulate_path([Straight(2)], slow, speed="slow").name == "sim_u1_slow_s0_custom_user"
    assert simulate_path([Stand(1)], user, name="mine").name == "mine"
