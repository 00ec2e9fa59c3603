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
    assert abs(len(ev_on) - n_true) <= 4
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
