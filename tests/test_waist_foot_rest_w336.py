"""Decision W336: lower-back contacts while the foot unit makes no stride (standing in a moving vehicle, S71) are
named in one warning line per run, and dropped with the track option ``foot_rest_veto``. Users 7182-7185."""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.units import keep_units
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.foot_rest import MIN_STILL_CONTACTS, foot_rest_keep, still_foot_runs


def test_runs_need_four_contacts_away_from_swinging_strides():
    """Pure kernel: strides every 1.1 s over 0-10 s and 40-50 s (one of them a vibration 'stride' that does not
    turn the foot); contacts every 0.55 s over 0-50 s: the contacts from 11 s to 39 s form one run; three contacts
    alone form none; no foot unit, no run."""
    t0 = np.r_[np.arange(0.0, 10.0, 1.1), np.arange(40.0, 50.0, 1.1), 25.0]
    strides = (t0, t0 + 1.1, np.r_[np.full(t0.size - 1, 1.5), 0.05])
    ev = np.arange(0.0, 50.0, 0.55)
    runs = still_foot_runs(ev, strides, (0.0, 52.0))
    assert len(runs) == 1
    a, b = runs[0]
    assert 11.0 <= ev[a] <= 12.2 and 38.0 <= ev[b] <= 39.0
    keep = foot_rest_keep(ev.size, runs)
    assert keep.sum() == ev.size - (b - a + 1)
    few = np.r_[np.arange(0.0, 10.0, 0.55), 20.0, 20.5, 21.0, np.arange(40.0, 50.0, 0.55)]
    assert len(few[few < 30]) and still_foot_runs(few, strides, (0.0, 52.0)) == []
    assert MIN_STILL_CONTACTS == 4
    assert still_foot_runs(ev, None, None) == []


@pytest.fixture(scope="module")
def ride():
    route = parse_route("stand:3, straight:12, vehicle:60:1.0, straight:12, stand:3")
    return simulate_path(route, UserProfile.from_seed(7182), rate_hz=100.0, seed=7182)


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_a_vehicle_ride_is_named_and_dropped_with_the_option(ride, pipeline, caplog):
    """S71's ride with the foot unit present: with foot_rest_veto False (the code before W337) the track counts the
    bounce as steps and says so in one line naming the span; by default (W337) the ride holds no contact, the
    distance comes back to the walk's and the line says they were dropped."""
    row = ride.extras["rides"].iloc[0]
    walked = float(ride.steps["length_m"].sum())
    n_true = len(ride.extras["ics"])
    off = track_waist(ride, pipeline=pipeline, foot_rest_veto=False)
    ev = off.steps["event_s"].to_numpy(float)
    inside = int(((ev > row.start_s) & (ev < row.end_s)).sum())
    lines = [w for w in off.info["warnings"] if "decision W336" in w]
    print(pipeline, "off", len(ev), "contacts,", inside, "in the ride; true", n_true, lines)
    assert inside > 20  # the phantom steps (T1 finding 1), reproduced
    assert len(lines) == 1 and "foot_rest_veto drops them" in lines[0]
    on = track_waist(ride, pipeline=pipeline)  # W337: the default
    ev_on = on.steps["event_s"].to_numpy(float)
    dist = float(np.nansum(on.steps["length_m"]))
    print(pipeline, "on", len(ev_on), "contacts", round(dist, 2), "m, walked", round(walked, 2))
    assert int(((ev_on > row.start_s + 1.0) & (ev_on < row.end_s - 1.0)).sum()) == 0
    # W342: the veto drops the ride, not the walk around it (W336's rest-to-rest strides missed the last stride before
    # the ride, and the line dropped the walk's last contacts with it): the walk's contacts of the track without it
    assert abs(len(ev_on) - (len(ev) - inside)) <= 2 and abs(len(ev_on) - n_true) <= 6
    assert abs(dist - walked) < 0.35 * walked
    assert any("dropped (foot_rest_veto, decision W336)" in w for w in on.info["warnings"])


def test_no_foot_unit_no_line_and_a_walk_is_untouched(ride):
    """Without the foot unit nothing is said (W338's phone-only cue is another decision); a plain walk with the foot
    (user 7183) gives no line and the option changes nothing."""
    phone = keep_units(ride, ("waist",))
    phone = dataclasses.replace(phone, _left_out={})  # the foot unit gone, not merely left out
    res = track_waist(phone, pipeline="waist-pendulum", foot_rest_veto=True)
    assert not [w for w in res.info["warnings"] if "decision W336" in w]
    walk = simulate_path(parse_route("stand:3, straight:14, turn:180, straight:14, stand:3"),
                         UserProfile.from_seed(7183), rate_hz=100.0, seed=7183)
    a = track_waist(walk, pipeline="waist-pendulum", foot_rest_veto=False)
    b = track_waist(walk, pipeline="waist-pendulum")
    assert not [w for w in a.info["warnings"] if "decision W336" in w]
    assert np.array_equal(a.steps["event_s"].to_numpy(), b.steps["event_s"].to_numpy())


def test_the_option_reaches_params_and_the_live_list():
    from pdrlearn.track.waist import OPTION_DEFAULTS
    from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS

    assert OPTION_DEFAULTS["foot_rest_veto"] is True  # decision W337
    assert "foot_rest_veto" in LIVE_UNAPPLIED_OPTIONS
    logging.getLogger("pdrlearn").debug("W336 option registered")


def test_swings_are_not_lengthened_by_the_rests_around_them():
    """Pure kernel, decision W342: rests 0-5 s, 5.7-6.2 s and 6.9-12 s at 50 Hz: two swings of 0.7 s between them.
    D9's rest-to-rest strides run from rest middle to rest middle (2.5-5.95 s, 5.95-9.45 s: over 3 s) and are none;
    the swings are both, from the last rest sample to the first of the next; a motion over 3 s is no swing."""
    from pdrlearn.track.frame_inference import rest_swings, rest_to_rest

    fs = 50.0
    t = np.arange(0.0, 12.0, 1 / fs)
    stance = (t < 5.0) | ((t >= 5.7) & (t < 6.2)) | (t >= 6.9)
    assert len(rest_to_rest(stance, fs)[0]) == 0
    i0, i1 = rest_swings(stance, fs)
    assert np.allclose(t[i0], [4.98, 6.18]) and np.allclose(t[i1], [5.7, 6.9])
    long = (t < 2.0) | (t >= 5.5)
    assert len(rest_swings(long, fs)[0]) == 0


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
@pytest.mark.parametrize("rate_hz", [50.0, 100.0])
def test_a_two_stride_bout_between_long_rests_keeps_its_contacts(pipeline, rate_hz):
    """Decision W342 (the lead's finding, tests/test_track_bouts.py): user 7330 walks 4 m and 2 m between rests of
    3-4 s; the foot strides twice in each bout. W336's rest-to-rest strides next to those rests were over 3 s and
    dropped, so the default veto dropped the walking contacts (5 of them at 11.2-17.5 s, waist-pendulum, 50 Hz); the
    foot's swings keep them: no W336 line, the default track equals the track without the veto, the last bout has its
    contacts."""
    walk = simulate_path(parse_route("stand:3, straight:4, stand:4, straight:2, stand:3"),
                         UserProfile.from_seed(7330), rate_hz=rate_hz, seed=7330)
    on = track_waist(walk, pipeline=pipeline)
    off = track_waist(walk, pipeline=pipeline, foot_rest_veto=False)
    assert not [w for w in on.info["warnings"] if "decision W336" in w]
    assert np.array_equal(on.steps["event_s"].to_numpy(), off.steps["event_s"].to_numpy())
    ev = on.steps["event_s"].to_numpy(float)
    assert int((ev > walk.steps["start_s"].iloc[-2] - 0.5).sum()) >= 4
