"""Decisions S38 / S39 (session 23 paediatric trial, finding 8): the simulator makes a child. `UserProfile.scaled`
and `simulate --height/--leg-length` scale the body by stature and the gait by dynamic similarity (Hof 1996), step
times go down to 0.25 s, and `simulate(scenario, profile)` walks a scenario with a custom profile (no private
`_rng`)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.sim import SCENARIOS, UserProfile, simulate, simulate_path
from pdrlearn.sim.simulate import _rng


def test_scaled_profile_by_hand():
    a = UserProfile.from_seed(1)
    c = a.scaled(0.95, 0.45)
    r, rl = 0.95 / a.height_m, 0.45 / a.leg_length_m
    assert (c.height_m, c.leg_length_m) == (0.95, 0.45)
    for k in ("foot_length_m", "sensor_height_m", "step_width_m", "swing_height_m", "toe_clearance_m",
              "pelvis_bounce_m", "pelvis_sway_m"):
        assert getattr(c, k) == pytest.approx(getattr(a, k) * r, abs=6e-5), k
    assert c.step_length_m == pytest.approx(a.step_length_m * rl, abs=6e-5)  # Hof 1996: step length / L
    assert c.step_time_s == pytest.approx(a.step_time_s * math.sqrt(rl), abs=6e-5)  # step time / sqrt(L/g)
    assert c.mass_kg == pytest.approx(a.mass_kg * r**3, abs=0.01)
    assert (c.seed, c.foot_misalignment_deg, c.stance_fraction) == (a.seed, a.foot_misalignment_deg, a.stance_fraction)
    assert a.scaled(0.95).leg_length_m == pytest.approx(a.leg_length_m * r, abs=6e-5)  # the user's own proportion
    assert a.scaled(a.height_m) == a


@pytest.mark.parametrize("length", [0.1, 1.0])
def test_step_time_down_to_a_fast_child(tmp_path, capsys, length):
    """The S30 corners at 0.25 s steps: the simulator walks the steps asked for."""
    out = tmp_path / "c"
    assert main(["simulate", "--route", "stand:2, straight:8, stand:2", "--user-seed", "1", "--rate", "100",
                 "--step-length", str(length), "--step-time", "0.25", "--out", str(out), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["step_time_s"] == 0.25
    s = read_session(out)
    ic = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    assert np.median(np.diff(ic)) == pytest.approx(0.25, rel=0.05)
    st = s.steps[s.steps["steady"].astype(bool)]
    assert np.median(st["length_m"]) == pytest.approx(2 * length, rel=0.05)


def test_cli_height_makes_a_child(tmp_path, capsys):
    out = tmp_path / "age3"
    assert main(["simulate", "--route", "stand:2, straight:10, stand:2", "--user-seed", "1", "--rate", "100",
                 "--height", "0.95", "--leg-length", "0.45", "--step-time", "0.3", "--out", str(out),
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    want = UserProfile.from_seed(1).scaled(0.95, 0.45)
    assert (d["height_m"], d["leg_length_m"], d["step_time_s"]) == (0.95, 0.45, 0.3)
    assert d["step_length_m"] == pytest.approx(want.step_length_m, abs=1e-4)
    s = read_session(out)
    assert s.name.startswith("route_u1_normal_s0_h0.95m_step") and s.name.endswith("m_0.3s")
    assert (s.meta["height_m"], s.meta["leg_length_m"]) == (0.95, 0.45)
    assert s.meta["user"]["foot_length_m"] == want.foot_length_m < 0.16  # not the adult's 27 cm
    ic = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    assert np.median(np.diff(ic)) == pytest.approx(0.3, rel=0.05)  # 200 steps/min


def test_scenario_with_a_custom_profile_is_public():
    """S39: `simulate(scenario, profile)` = what the trial had to build with SCENARIOS and the private `_rng`."""
    kid = UserProfile.from_seed(951).scaled(1.22, 0.61)
    got = simulate("terrain", kid, rate_hz=20.0, seed=2)
    segs = SCENARIOS["terrain"](kid, "normal", _rng(kid.seed, 2, "terrain", "normal", "path"), length_m=1000.0)
    ref = simulate_path(segs, kid, rate_hz=20.0, seed=2, scenario="terrain")
    assert got.name == "sim_terrain_u951_normal_s2_custom_user" == ref.name
    np.testing.assert_array_equal(got["fAccelerometer"].values, ref["fAccelerometer"].values)
    assert got.meta["height_m"] == 1.22
    adult = simulate("A", UserProfile.from_seed(3), seed=1)  # a drawn profile = its seed, bit for bit
    np.testing.assert_array_equal(adult["wAccelerometer"].values, simulate("A", 3, seed=1)["wAccelerometer"].values)
    assert adult.name == "sim_A_u3_normal_s1"


@pytest.mark.parametrize("args, message", [
    (["--height", "0.5"], "--height 0.5: give the stature in metres, 0.7-2.2"),
    (["--height", "nan"], "give the stature in metres"),
    (["--leg-length", "0.45"], "--leg-length needs --height"),
    (["--height", "1.0", "--leg-length", "0.7"], "--leg-length 0.7: give 0.35-0.60 m for --height 1"),
])
def test_bad_height_is_one_line(tmp_path, capsys, args, message):
    out = tmp_path / "bad"
    assert main(["simulate", "--scenario", "A", "--user-seed", "1", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and message in err and "\n" not in err, err
    assert not out.exists()
