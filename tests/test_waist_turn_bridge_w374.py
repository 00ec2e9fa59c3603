"""Decisions W374 / W375: `turn_bridge`, waist-pendulum's motion gate bridged over a yaw-rate turn inside a walk
(opt-in, off by default)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.waist import contacts_offline, turn_bridge_gate
from pdrlearn.steps.evaluate import score_events
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS

FS = 100.0


def _turn_rate(n: int, a_s: float, b_s: float, deg: float = 180.0) -> np.ndarray:
    """A levelled yaw rate (rad/s): a half-sine turn of ``deg`` from ``a_s`` to ``b_s``, still elsewhere."""
    t = np.arange(n) / FS
    w = np.zeros(n)
    inside = (t >= a_s) & (t < b_s)
    dur = b_s - a_s
    w[inside] = np.radians(deg) * np.pi / (2 * dur) * np.sin(np.pi * (t[inside] - a_s) / dur)
    return w


def test_the_gate_is_bridged_over_a_turn_with_walking_on_both_sides_only():
    n = int(20 * FS)
    t = np.arange(n) / FS
    walk_turn_walk = (t < 6.0) | (t >= 9.0)
    w = _turn_rate(n, 6.0, 9.0)
    out = turn_bridge_gate(walk_turn_walk, w, FS, max_step_s=1.5)
    assert out[(t >= 6.5) & (t < 8.5)].all()  # the turn's inside, closed before, now open
    np.testing.assert_array_equal(out[walk_turn_walk], True)  # nothing open is closed
    assert not walk_turn_walk[(t >= 6.5) & (t < 8.5)].any()  # the input is not changed
    # the same turn with no walk after it (a turn to sit down, a turn while standing): nothing opened
    walk_then_stand = t < 6.0
    np.testing.assert_array_equal(turn_bridge_gate(walk_then_stand, w, FS, max_step_s=1.5), walk_then_stand)
    # walking after it but more than max_step_s later: nothing opened either
    far = (t < 6.0) | (t >= 11.0)
    np.testing.assert_array_equal(turn_bridge_gate(far, w, FS, max_step_s=1.5), far)


TURN_S = 6.0  # a slow 180 deg turn on the spot: the centred 2 s SD gate stays closed over its middle


def _walk_turn_walk(turn_amp: float = 0.2):
    """A hand-made lower-back walk at 2 steps/s: 1.6 m/s^2 vertical bounce and 1 Hz lateral sway (left / right weight
    shift) for 8 s, a 180 deg turn of ``TURN_S`` on the spot with a small bounce (``turn_amp``) and the same sway and
    rhythm, then 8 s of walking; the true steps are the vertical maxima, one every 0.5 s (8.0, 8.5, ... s)."""
    n = int((16 + TURN_S) * FS)
    t = np.arange(n) / FS
    turn = (t >= 8.0) & (t < 8.0 + TURN_S)
    acc_v = np.where(turn, turn_amp, 1.6) * np.cos(2 * np.pi * 2.0 * t)
    acc_ap = 0.8 * np.cos(2 * np.pi * 2.0 * (t + 0.08))
    acc_ml = 0.6 * np.sin(2 * np.pi * 1.0 * t)
    return t, turn, acc_v, acc_ap, acc_ml, _turn_rate(n, 8.0, 8.0 + TURN_S)


def _in_turn(t: np.ndarray, ic: np.ndarray) -> np.ndarray:
    return t[ic][(t[ic] > 8.3) & (t[ic] < 8.0 + TURN_S - 0.3)]


def test_the_bridge_recovers_the_turn_steps_of_a_hand_made_walk_and_keeps_the_others():
    t, turn, acc_v, acc_ap, acc_ml, w = _walk_turn_walk()
    off, *_ = contacts_offline(acc_v, acc_ap, acc_ml, w, FS, walk_threshold=0.5)
    on, *_ = contacts_offline(acc_v, acc_ap, acc_ml, w, FS, walk_threshold=0.5, turn_bridge=True)
    true_steps = np.arange(8.5, 8.0 + TURN_S - 0.3, 0.5)  # the turn's steps away from its edges: 11
    assert _in_turn(t, off).size == 6  # the SD gate is closed over the turn's middle: 5 of its steps missed
    found = _in_turn(t, on)
    assert found.size == true_steps.size  # bridged: every turn step found, none twice
    assert np.abs(found - true_steps).max() < 0.15  # each at its step (the AP maximum before the vertical one)
    outside = lambda ic: np.sort(ic[(t[ic] < 7.5) | (t[ic] > 8.5 + TURN_S)])  # noqa: E731
    np.testing.assert_array_equal(outside(on), outside(off))  # the walking contacts are the same


def test_a_turn_while_standing_gets_no_contacts():
    t, turn, acc_v, acc_ap, acc_ml, w = _walk_turn_walk()
    still = t >= 8.0 + TURN_S  # the walk ends at the turn: a turn to stand (or sit), no walk after it
    acc_v, acc_ap, acc_ml = (np.where(still, 0.0, x) for x in (acc_v, acc_ap, acc_ml))
    off, *_ = contacts_offline(acc_v, acc_ap, acc_ml, w, FS, walk_threshold=0.5)
    on, *_ = contacts_offline(acc_v, acc_ap, acc_ml, w, FS, walk_threshold=0.5, turn_bridge=True)
    np.testing.assert_array_equal(on, off)


def _tug(user: int):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("straight:3, turn:180, straight:3"), UserProfile.from_seed(user), rate_hz=100,
                         seed=user, speed="slow", scenario="route", sit_start_s=5.0, sit_end_s=5.0)


def _matched(ev: np.ndarray, truth: np.ndarray) -> int:
    return int(score_events(ev, truth, tolerance_s=0.25)["true_positives"])  # one-to-one within 0.25 s


def test_the_option_reaches_the_offline_pendulum_track():
    assert OPTION_DEFAULTS["turn_bridge"] == "side"  # W375: true not adopted; W385: "side" adopted (W384's tests)
    s = _tug(8763)  # W374's diagnosis users (8760-8779): its TUG turn's two steps are behind a closed gate
    truth = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    ev = {v: track_waist(s, pipeline="waist-pendulum", turn_bridge=v).steps["event_s"].to_numpy(float)
          for v in (False, True)}
    assert (ev[False].size, _matched(ev[False], truth)) == (12, 12)
    assert (ev[True].size, _matched(ev[True], truth)) == (14, 14)  # both turn steps found, no extra


def test_realtime_and_live_tracks_do_not_apply_it_and_say_so(caplog):
    s = _tug(8763)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        on = track_waist(s, pipeline="waist-pendulum", realtime=True, turn_bridge=True)
    off = track_waist(s, pipeline="waist-pendulum", realtime=True, turn_bridge=False)
    np.testing.assert_array_equal(on.steps["event_s"].to_numpy(), off.steps["event_s"].to_numpy())
    assert any("turn_bridge=true applies to the offline waist-pendulum" in w and "W193" in w
               for w in on.info["warnings"])
    assert "turn_bridge" in LIVE_UNAPPLIED_OPTIONS  # the live tracker names it (E107) instead of applying it


@pytest.mark.parametrize("bad", ["yes", 2, "on"])
def test_a_bad_value_is_one_line(bad):
    with pytest.raises(DataError) as e:
        track_waist(_tug(8763), pipeline="waist-pendulum", turn_bridge=bad)
    msg = str(e.value)
    assert "\n" not in msg and "turn_bridge" in msg and "false, true" in msg  # W384: one of false, true, "side"
