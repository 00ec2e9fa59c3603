"""The `lie:S[:TURNS_PER_H]` route item: lying down on a bed, turning over, getting up (decisions S58-S61)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Lie, Straight, UserProfile, simulate_path
from pdrlearn.sim.lying import LIE_DOWN_S, LIE_TILT_DEG, MAX_LIE_S, POSTURES, ROLL_GAP_S, draw_lying, lying_angles
from pdrlearn.sim.route import parse_route


def test_lie_parses_and_bad_values_are_one_line():
    assert parse_route("straight:3, lie:600, straight:2") == [Straight(3.0), Lie(600.0), Straight(2.0)]
    assert parse_route("lie:600:4") == [Lie(600.0, 4.0)] and parse_route("lie:60:0") == [Lie(60.0, 0.0)]
    for spec, message in (("lie", "takes 1 or 2 value"), ("lie:-2", "positive"), ("lie:soon", "not a number"),
                          ("lie:90000", "at most 86400 s"), ("lie:60:99", "TURNS_PER_H must be 0-60"),
                          ("lie:60:-1", "TURNS_PER_H must be 0-60")):
        with pytest.raises(DataError, match=message):
            parse_route(spec)


def _angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    return math.degrees(math.acos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1.0, 1.0)))


def _mean(stream, t0: float, t1: float) -> np.ndarray:
    m = (stream.t >= t0) & (stream.t <= t1)
    return stream.values[m].mean(axis=0)


@pytest.mark.parametrize("user", [5961, 5962])
def test_lying_session_gravity_horizontal_rolls_no_steps_feet_still(user):
    """Exact physics (noise off), 100 Hz, 400 s lying at 20 turns an hour: S58's tilt and S59's rolls in the waist
    unit's gravity, no contact from the sit-down to the stand-up, the foot unit still, labels consistent."""
    s = simulate_path(parse_route("straight:4, lie:400:20, straight:4"), UserProfile.from_seed(user), rate_hz=100.0,
                      seed=1, noise=False)
    tr, ly, rolls = s.extras["transfers"].iloc[0], s.extras["lying"].iloc[0], s.extras["rolls"]
    acc = s["wAccelerometer"]
    up = _mean(acc, 0.5, 2.5)  # standing still before the walk: the unit's up direction
    # labels: the lying inside the bed-edge sit, its movements 2-4 s, the rolls inside the lying, postures chained
    assert tr.seated_s < ly.start_s < ly.lying_s < ly.rise_s < ly.end_s < tr.rise_s
    assert LIE_DOWN_S[0] <= ly.lying_s - ly.start_s <= LIE_DOWN_S[1] and ly.rise_s - ly.lying_s == pytest.approx(400)
    assert len(rolls) == ly.n_turns >= 1 and ly.first_posture == "supine"
    assert ly.last_posture == rolls.to_posture.iloc[-1]
    assert (rolls.start_s >= ly.lying_s + ROLL_GAP_S).all() and (rolls.end_s <= ly.rise_s - ROLL_GAP_S).all()
    assert (rolls.from_posture.iloc[1:].to_numpy() == rolls.to_posture.iloc[:-1].to_numpy()).all()
    # lying supine: gravity turned by the drawn tilt (85-95 deg) from the standing up direction, i.e. horizontal
    supine = _angle_deg(up, _mean(acc, ly.lying_s + 0.5, rolls.start_s.iloc[0] - 0.5))
    print(f"user {user}: supine tilt {supine:.1f} deg, {len(rolls)} turns")
    assert LIE_TILT_DEG[0] - 5 <= supine <= LIE_TILT_DEG[1] + 5
    # each turn turns gravity in the unit by its roll (about the ~horizontal long axis)
    bounds = [ly.lying_s, *rolls.start_s, ly.rise_s]
    ends = [ly.lying_s, *rolls.end_s]
    for k, r in enumerate(rolls.itertuples()):
        before = _mean(acc, ends[k] + 0.5, r.start_s - 0.5)
        after = _mean(acc, r.end_s + 0.5, bounds[k + 2] - 0.5)
        assert _angle_deg(before, after) == pytest.approx(abs(r.angle_deg), abs=12.0)
    # standing again after the stand-up: the roll and the lying undone
    assert _angle_deg(up, _mean(acc, tr.end_s + 0.1, tr.end_s + 0.45)) < 3.0  # before the walk on (0.5 s)
    # no step: no contact from the sit-down to the stand-up; the foot unit rests
    ics = s.extras["ics"].ic_s.to_numpy()
    assert not ((ics > tr.start_s - 0.5) & (ics < tr.end_s + 0.5)).any() and (ics < tr.start_s).sum() >= 4
    ft = s.extras["foot_trajectory"]
    still = ft[(ft.t_s > tr.start_s) & (ft.t_s < tr.end_s)][["x", "y", "z"]].to_numpy()
    assert np.ptp(still, axis=0).max() < 1e-9
    gyr = s["fGyroscope"]
    assert np.abs(gyr.values[(gyr.t > tr.start_s) & (gyr.t < tr.end_s)]).max() < 1e-6


def test_turn_rate_knob_and_no_turns_at_zero():
    """S59: the turns come as a Poisson process of TURNS_PER_H (with S59's gaps); 0 never turns; the roll left at the
    end is unwound to a whole turn by the sit-up."""
    rng = np.random.default_rng(5960)
    assert draw_lying(0, 0.0, 36_000.0, 0.0, 0.1, 0.0, rng).roll_starts == ()
    counts = [len(draw_lying(0, 0.0, 36_000.0, 4.0, 0.1, 0.0, rng).roll_starts) for _ in range(5)]
    counts_default = [len(draw_lying(0, 0.0, 36_000.0, None, 0.1, 0.0, rng).roll_starts) for _ in range(5)]
    print(f"10 h at 4/h: {counts}; at the default 2/h: {counts_default}")
    # expected ~ 10 h / (15 min + the 5 s gap and ~2.5 s turn): 39.7; at 2/h 19.9
    assert 30 <= np.mean(counts) <= 50 and 13 <= np.mean(counts_default) <= 27
    ep = draw_lying(0, 0.0, 3600.0, 30.0, 0.1, 0.0, np.random.default_rng(3))
    t = np.arange(-1.0, ep.total_s + 1.0, 0.01)
    unrecline, yaw, pitch, roll, back = lying_angles(t, [ep], np.array([0.0]))
    assert set(ep.postures) <= set(POSTURES) and len(ep.roll_starts) > 5
    final = {"supine": 0.0, "left": 90.0, "right": -90.0, "prone": 180.0}[ep.postures[-1]]
    lying = (t > ep.down_s + ep.roll_starts[-1] + ep.roll_durations[-1]) & (t < ep.down_s + ep.lying_s)
    wrapped = (np.degrees(roll[lying]) - final + 180.0) % 360.0 - 180.0
    assert np.abs(wrapped).max() < 1e-9
    for x in (unrecline, yaw, pitch, back):
        assert np.abs(x[(t < 0) | (t > ep.total_s)]).max() == 0.0
    assert abs(math.remainder(roll[-1], 2 * math.pi)) < 1e-12


def test_simulate_help_lists_the_lie_item_and_the_seated_cap_is_a_day():
    """S58 / S61: `simulate --help` names `lie:28800`; --sit-start / --sit-end accept up to a day (was an hour)."""
    from typer.testing import CliRunner

    from pdrlearn.cli import app
    from pdrlearn.cli.simulate import SIT_MAX_S

    out = CliRunner().invoke(app, ["simulate", "--help"], terminal_width=200).output
    out = " ".join(out.replace("\u2502", " ").split())  # rich's box and wrapping: where a line breaks is not the point
    assert "'lie:28800'" in out and "turning over" in out
    assert SIT_MAX_S == MAX_LIE_S == 86_400.0
    res = CliRunner().invoke(app, ["simulate", "--route", "straight:2", "-u", "5963", "--sit-end", "90000",
                                   "--out", "unused_s61"])
    message = res.output + str(res.exception)
    assert res.exit_code != 0 and "--sit-end 90000" in message and "86400" in message
