"""Decisions W384 / W385: ``turn_bridge="side"`` -- of the contacts W374's bridge adds, only those whose W20 side is
decided and alternates with the previous kept contact's are kept; the contacts without the bridge are all kept
(adopted as the default of the offline `waist-pendulum`)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.waist import alternating_bridged, bridge_additions, contacts_offline
from pdrlearn.steps.evaluate import score_events
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist.live import live_value, unapplied_options_line
from tests.test_waist_turn_bridge_w374 import _tug, _turn_rate  # W374's hand-made turn and simulated TUG

FS = 100.0


def test_an_added_contact_stays_only_with_a_decided_side_opposite_the_previous_kept_one():
    peaks = np.array([0, 50, 100, 150, 200, 250, 300, 600])
    sd = np.array([1, -1, 0, 1, -1, -1, 1, 1])
    added = np.array([False, False, True, True, True, True, False, True])
    keep = alternating_bridged(peaks, sd, added, max_gap=150)
    # 100: added, undecided (no weight shift) -> out; 150: +1 after the kept -1 at 50 -> in; 200: -1 after +1 -> in;
    # 250: -1 after the kept -1 at 200 -> out; 300: not added, kept whatever its side; 600: added, decided, the
    # previous kept contact (300) more than max_gap before -> a decided side is enough
    np.testing.assert_array_equal(keep, [True, True, False, True, True, False, True, True])
    # a contact found without the bridge is never dropped, even on the side of the one before it
    np.testing.assert_array_equal(alternating_bridged(peaks, np.ones(8, int), np.zeros(8, bool), 150), True)


def test_bridge_additions_keeps_every_default_contact_and_adds_no_duplicate():
    v = np.zeros(1000)
    v[[100, 300, 400, 500, 700]] = [1.0, -1.0, 1.0, 0.0, 1.0]  # lateral velocity at the maxima below
    off = (np.array([95, 295, 695]), np.array([110, 310, 710]), np.array([100, 300, 700]), None)
    # the bridged detector: 100 moved by 0.1 s (the same step: within W16's 0.3 s), 300 dropped by its rules,
    # 400 (+1 after -1: kept), 500 (undecided: dropped), 700 as before
    on = (np.array([105, 395, 495, 695]), np.array([120, 410, 510, 710]), np.array([110, 400, 500, 700]), "ap")
    ic, fc, vm, ap = bridge_additions(off, on, v, FS, max_step_s=1.5)
    np.testing.assert_array_equal(vm, [100, 300, 400, 700])
    np.testing.assert_array_equal(ic, [95, 295, 395, 695])
    np.testing.assert_array_equal(fc, [110, 310, 410, 710])
    assert ap == "ap"


TURN_S = 6.0


def _walk_turn_walk():
    """A hand-made lower-back walk at 2 steps/s (1.6 m/s^2 bounce, 1 Hz lateral sway: a weight shift to the stance
    side at every step) for 8 s, a 180 deg turn of ``TURN_S`` with a small bounce at the same rhythm, whose first half
    has NO lateral sway (bounces without a weight shift: no steps) and whose second half sways as the walk, then 8 s
    of walking."""
    n = int((16 + TURN_S) * FS)
    t = np.arange(n) / FS
    turn = (t >= 8.0) & (t < 8.0 + TURN_S)
    acc_v = np.where(turn, 0.2, 1.6) * np.cos(2 * np.pi * 2.0 * t)
    acc_ap = 0.8 * np.cos(2 * np.pi * 2.0 * (t + 0.08))
    still = (t >= 8.0) & (t < 8.0 + TURN_S / 2)
    acc_ml = np.where(still, 0.0, 0.6 * np.sin(2 * np.pi * 1.0 * t))
    return t, acc_v, acc_ap, acc_ml, _turn_rate(n, 8.0, 8.0 + TURN_S)


def test_side_keeps_the_bridged_steps_with_a_weight_shift_and_drops_the_bounces_without():
    t, acc_v, acc_ap, acc_ml, w = _walk_turn_walk()
    res = {v: contacts_offline(acc_v, acc_ap, acc_ml, w, FS, walk_threshold=0.5, turn_bridge=v)[0]
           for v in (False, True, "side")}
    first = lambda ic: t[ic][(t[ic] > 9.0) & (t[ic] < 8.0 + TURN_S / 2 - 0.3)]  # noqa: E731 (no sway, gate closed)
    second = lambda ic: t[ic][(t[ic] > 8.0 + TURN_S / 2 + 0.5) & (t[ic] < 8.0 + TURN_S - 0.3)]  # noqa: E731
    assert first(res[False]).size == 0 and first(res[True]).size >= 3  # W374's bridge takes the bounces for steps
    assert first(res["side"]).size == 0  # W384: no weight shift, no step
    assert second(res[True]).size >= 3  # the swaying half's steps, found by the bridge ...
    np.testing.assert_array_equal(second(res["side"]), second(res[True]))  # ... alternate, and are kept
    assert set(res[False]) <= set(res["side"])  # every contact without the bridge is kept


def test_the_default_is_side_on_the_offline_track_and_not_applied_live():
    assert OPTION_DEFAULTS["turn_bridge"] == "side"  # W385: adopted
    s = _tug(8916)  # W384's diagnosis users (8910-8929)
    ev = {v: track_waist(s, pipeline="waist-pendulum", turn_bridge=v).steps["event_s"].to_numpy(float)
          for v in (None, False, "side")}
    np.testing.assert_array_equal(ev[None], ev["side"])
    assert set(np.round(ev[False], 6)) <= set(np.round(ev["side"], 6))  # it only adds contacts
    rt = {v: track_waist(s, pipeline="waist-pendulum", realtime=True, turn_bridge=v).steps["event_s"].to_numpy()
          for v in (None, False)}
    np.testing.assert_array_equal(rt[None], rt[False])  # realtime: the default changes nothing
    assert live_value("turn_bridge") is False  # the live tracker tracks without it and says so (E107)

    class P:
        options = None

    assert 'turn_bridge="side" (the offline default)' in unapplied_options_line(P())


@pytest.mark.parametrize("user, counts", [
    (8916, {False: (12, 12), True: (17, 16), None: (13, 13)}),  # a turn step gained, the bridge's extra left out
    (8911, {False: (15, 15), True: (17, 16), None: (15, 15)}),  # the bridge's extra left out
])
def test_the_default_keeps_the_bridges_alternating_turn_steps_only(user, counts):
    s = _tug(user)  # W384's diagnosis users (8910-8929); (detected, matched one-to-one within 0.25 s)
    truth = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    got = {}
    for v in counts:
        ev = track_waist(s, pipeline="waist-pendulum", turn_bridge=v).steps["event_s"].to_numpy(float)
        got[v] = (ev.size, int(score_events(ev, truth, tolerance_s=0.25)["true_positives"]))
    assert got == counts


@pytest.mark.parametrize("bad", ["yes", 2, "sides"])
def test_a_bad_value_is_one_line(bad, caplog):
    with caplog.at_level(logging.WARNING, logger="pdrlearn"), pytest.raises(DataError) as e:
        track_waist(_tug(8911), pipeline="waist-pendulum", turn_bridge=bad)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith("turn_bridge ") and '"side"' in msg and "W384" in msg
