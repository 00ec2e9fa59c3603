"""The `sit:S` route item: sitting down on a chair and standing up again, no steps (decision S36)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Sit, Straight, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.transfer import FLEXION_DEG, RECLINE_DEG, draw_transfer, transfer_motion


def test_sit_parses_and_bad_values_are_one_line():
    assert parse_route("straight:3, sit:20, straight:2") == [Straight(3.0), Sit(20.0), Straight(2.0)]
    for spec, message in (("sit", "takes 1 value"), ("sit:-2", "positive"), ("sit:soon", "not a number")):
        with pytest.raises(DataError, match=message):
            parse_route(spec)


def test_transfer_motion_forward_then_upright_then_reclined():
    tr = draw_transfer(0, 0.5, 10.0, np.random.default_rng(5))
    t = np.arange(0.0, tr.total_s + 1.0, 0.01)
    back, lower, pitch = transfer_motion(t, [tr], np.array([0.5]))
    assert math.radians(FLEXION_DEG[0] - RECLINE_DEG[1]) <= pitch.max() <= math.radians(FLEXION_DEG[1])
    seated = (t > 0.5 + tr.down_s) & (t < 0.5 + tr.down_s + tr.seat_s)
    np.testing.assert_allclose(pitch[seated], -tr.recline_rad, atol=1e-12)
    np.testing.assert_allclose(lower[seated], tr.drop_m, atol=1e-12)
    # back to standing after the stand-up, nothing before the sit-down
    assert np.abs(np.r_[back, lower, pitch][np.r_[t, t, t] > 0.5 + tr.total_s]).max() < 1e-12
    assert np.abs(np.r_[back, lower, pitch][np.r_[t, t, t] < 0.5]).max() == 0.0
    # the trunk leans forward before the pelvis lowers (flexion-momentum phase)
    i_peak = int(np.argmax(pitch[t < 0.5 + tr.down_s]))
    assert lower[i_peak] < 0.6 * tr.drop_m


@pytest.mark.parametrize("user", [620, 621, 622])
def test_sit_session_pitch_drop_no_steps_feet_still(user):
    s = simulate_path(parse_route("straight:5, sit:10, straight:5"), UserProfile.from_seed(user), seed=1, noise=False)
    assert len(s.extras["transfers"]) == 1
    tr = s.extras["transfers"].iloc[0]
    assert 1.5 <= tr.seated_s - tr.start_s <= 2.5 and 1.5 <= tr.end_s - tr.rise_s <= 2.5
    assert tr.rise_s - tr.seated_s == pytest.approx(10.0)
    # waist tilt from gravity (exact physics): the accelerometer turns 25-50 deg from its standing direction
    acc = s.streams["wAccelerometer"]
    m = (acc.t >= tr.start_s) & (acc.t <= tr.end_s)
    ref = acc.values[(acc.t > tr.start_s - 0.4) & (acc.t < tr.start_s)].mean(0)
    cos = acc.values[m] @ ref / np.linalg.norm(acc.values[m], axis=1) / np.linalg.norm(ref)
    assert 25.0 <= np.degrees(np.arccos(np.clip(cos, -1, 1))).max() <= 50.0
    # the waist unit lowers 0.35-0.5 m and is back up afterwards
    tj = s.trajectory
    z0 = tj.z[(tj.t > tr.start_s - 0.4) & (tj.t < tr.start_s)].mean()
    assert 0.35 <= z0 - tj.z[(tj.t >= tr.start_s) & (tj.t <= tr.end_s)].min() <= 0.5
    assert abs(tj.z[(tj.t > tr.end_s) & (tj.t < tr.end_s + 0.4)].mean() - z0) < 0.01
    # no contact during the transfer, walking on both sides of it (the sit splits the bouts)
    ic = s.extras["ics"]["ic_s"].to_numpy()
    assert not ((ic >= tr.start_s) & (ic <= tr.end_s)).any()
    assert (ic < tr.start_s).sum() >= 6 and (ic > tr.end_s).sum() >= 6
    # the instrumented foot does not move and does not turn
    ft = s.extras["foot_trajectory"]
    fm = (ft.t_s >= tr.start_s) & (ft.t_s <= tr.end_s)
    assert np.ptp(ft.loc[fm, ["x", "y", "z"]].to_numpy(), axis=0).max() < 1e-9
    gyr = s.streams["fGyroscope"]
    assert np.abs(gyr.values[(gyr.t >= tr.start_s) & (gyr.t <= tr.end_s)]).max() < 1e-6


def test_sit_at_either_end_and_default_sessions_without_table():
    user = UserProfile.from_seed(623)
    first = simulate_path(parse_route("sit:3, straight:3"), user, seed=2, noise=False)
    last = simulate_path(parse_route("straight:3, sit:3"), user, seed=2, noise=False)
    for s in (first, last):
        tr = s.extras["transfers"].iloc[0]
        assert tr.end_s < s.trajectory.t.iloc[-1]
        ic = s.extras["ics"]["ic_s"].to_numpy()
        assert not ((ic >= tr.start_s) & (ic <= tr.end_s)).any()
    assert "transfers" not in simulate_path([Straight(3.0)], user, seed=2).extras
