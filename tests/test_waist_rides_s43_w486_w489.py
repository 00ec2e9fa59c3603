"""Decisions W486-W489 (session 43, trial T3 F3 / F4 / F5 / F9): a lower-back unit alone in a ride.

W486: a run of contacts with no pelvic-gyro step and a vibration-like vertical signal is named ("vehicle / ride?";
not dropped: its drop rule was not met); W487: the sit veto drops every contact of a seated span (stand-to-sit ..
sit-to-stand); W488: a turn made seated or riding is no stepless turn on the spot; W489: waist-pll's W208 line
compares with the pendulum track's kept contacts. Users 12038-12039 (of the session's fresh range 12030-12039).
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import _kept_reading, track_waist
from pdrlearn.waist.foot_rest import strideless_spans
from pdrlearn.waist.ride_runs import ride_runs, stepless_pelvis
from pdrlearn.waist.transfers import seated_spans
from pdrlearn.waist.turn_steps import CARRIED, mark_carried, stepless_turns


def _phone(s):
    """The lower-back unit alone (the foot unit's streams removed, none left out: W336 cannot act)."""
    return dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if k.startswith("w")})


def _bounce(fs: float, n: int, seed: int, lo: float = 1.0, hi: float = 3.0) -> np.ndarray:
    """Broad-band ``lo``-``hi`` Hz noise as a sum of 30 random tones, unit SD (a vehicle's suspension band, 1-3 Hz,
    and, 5-10 Hz under the 20 Hz Nyquist, its vibration: T3's splicer's bands)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    x = sum(np.sin(2 * np.pi * f * t + p) for f, p in zip(rng.uniform(lo, hi, 30), rng.uniform(0, 6.3, 30),
                                                           strict=True))
    return x / x.std()


def test_ride_runs_kernel_w486():
    """40 contacts every 0.5 s: over a bounce with no pelvic step -> one run; a pelvic step near every contact, or a
    gait's repeating signal -> none; a pelvic step in the middle splits the run."""
    fs = 20.0
    t = np.arange(0, 24, 1 / fs)
    ev = 1.0 + 0.5 * np.arange(40)
    bounce = _bounce(fs, t.size, 1)
    assert [(a, b) for a, b, _ in ride_runs(ev, np.zeros(0), t, bounce, fs)] == [(0, 39)]
    assert ride_runs(ev, ev + 0.1, t, bounce, fs) == []
    gait = np.sin(2 * np.pi * t / 0.5) + 0.3 * np.sin(np.pi * t / 0.5)
    assert ride_runs(ev, np.zeros(0), t, gait, fs) == []
    split = [(a, b) for a, b, _ in ride_runs(ev, np.array([11.0]), t, bounce, fs)]
    assert (23, 39) in split and not any(a <= 20 <= b for a, b in split)  # 10.0-12.0 s lie within 1 s of 11.0
    assert stepless_pelvis(ev[:3], np.array([2.1])).tolist() == [True, False, False]


@pytest.fixture(scope="module")
def ride():
    """User 12038 at 20 Hz, the lower back alone, standing 40 s in a ride: T3's bands added to the waist's
    accelerometer from 3 s after the last walking contact to 3 s before the next (vertical 0.6 m/s^2 at 1-3 Hz and
    1.0 at 5-10 Hz, 0.3 on each horizontal axis)."""
    s = _phone(simulate_path(parse_route("stand:3, straight:12, stand:40, straight:12, stand:3"),
                             UserProfile.from_seed(12038), rate_hz=20.0, seed=12038))
    ic = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    k = int(np.argmax(np.diff(ic)))
    a, b = ic[k] + 3.0, ic[k + 1] - 3.0
    acc = s["wAccelerometer"]
    v = acc.values.copy()
    m = (acc.t > a) & (acc.t < b)
    n = int(m.sum())
    v[m, 1] += 0.6 * _bounce(20.0, n, 1) + 1.0 * _bounce(20.0, n, 2, 5.0, 10.0)  # the simulator's waist: y up
    v[m, 0] += 0.3 * _bounce(20.0, n, 3)
    v[m, 2] += 0.3 * _bounce(20.0, n, 4)
    return dataclasses.replace(s, streams={**s.streams, "wAccelerometer": dataclasses.replace(acc, values=v)}), a, b


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_a_phone_only_ride_is_named_w486(ride, pipeline):
    """Both pipelines count the ride's bounce as steps (main: with only W441's slow-gait line, or none); now one W486
    line names spans inside the ride and "vehicle / ride?", its count is the contacts there (still counted: W486's
    drop rule was not met), and every walk's true contact is still found (the walks are not named)."""
    s, a, b = ride
    res = track_waist(s, pipeline=pipeline)
    lines = [w for w in res.info["warnings"] if "W486" in w and "no pelvic step rhythm" in w]
    assert len(lines) == 1 and "vehicle / ride?" in lines[0] and "still counted" in lines[0]
    spans = [(float(x), float(y)) for x, y in re.findall(r"(\d+\.\d)-(\d+\.\d) s", lines[0])]
    assert spans and all(a - 1.0 <= x < y <= b + 1.0 for x, y in spans)
    ev = res.steps["event_s"].to_numpy(float)
    assert res.info["n_ride_contacts"] == sum(int(((ev >= x - 0.05) & (ev <= y + 0.05)).sum()) for x, y in spans) >= 15
    truth = s.extras["ics"]["ic_s"].to_numpy(float)
    assert sum(bool(np.any(np.abs(ev - x) <= 0.25)) for x in truth) == truth.size
    w441 = [w for w in res.info["warnings"] if "W441" in w]  # the slow-gait line names the ride's share too
    assert all(f"{res.info['n_ride_contacts']} of the contacts lie in the runs named vehicle / ride?" in w
               for w in w441)


def test_seated_spans_w487():
    """A stand-to-sit then a sit-to-stand bound a seated span; a flagged transfer or the wrong order bound none."""
    tr = pd.DataFrame({"kind": ["stand-to-sit", "sit-to-stand", "stand-to-sit"], "start_s": [10.0, 50.0, 70.0],
                       "end_s": [11.5, 51.5, 71.0], "flag": ["", "", ""]})
    assert seated_spans(tr) == [(11.5, 50.0)]
    assert seated_spans(tr.assign(flag=["", "walking on both sides", ""])) == []
    assert seated_spans(tr.iloc[1:]) == []
    assert seated_spans(pd.DataFrame()) == []


def test_a_rhythmic_seat_has_no_steps_w487():
    """waist-pll in a seat bouncing at a steady 1.8 Hz (an engine's rhythm: W486 keeps it, its signal repeats):
    the seated span between the two transfers keeps no contact (main: W104 only looks +-1 s round the peaks)."""
    s = simulate_path(parse_route("stand:2, straight:8, sit:30, straight:8, stand:2"), UserProfile.from_seed(12039),
                      rate_hz=20.0, seed=12039)
    tr = s.extras["transfers"]
    a, b = float(tr["seated_s"].iloc[0]) + 2.0, float(tr["rise_s"].iloc[0]) - 2.0
    acc = s["wAccelerometer"]
    v = acc.values.copy()
    m = (acc.t > a) & (acc.t < b)
    v[m, 1] += 1.5 * np.sin(2 * np.pi * 1.8 * acc.t[m])  # the simulator's waist frame: y up
    s = dataclasses.replace(s, streams={**s.streams, "wAccelerometer": dataclasses.replace(acc, values=v)})
    res = track_waist(_phone(s), pipeline="waist-pll")
    ev = res.steps["event_s"].to_numpy(float)
    assert not ((ev > a) & (ev < b)).any()
    assert res.info["n_vetoed_contacts"] >= 10


def test_carried_turns_are_no_stepless_turns_w488():
    """A 90 deg turn inside a seated or ride span is marked carried and left out of W331's stepless turns; one
    outside is still counted; no span leaves the records as they were."""
    ev = np.arange(0.0, 10.0, 0.5)  # a walk: the step time
    turns = [{"start_s": 20.0, "end_s": 26.0, "start_5_s": 20.2, "end_95_s": 25.8, "angle_deg": 90.0},
             {"start_s": 60.0, "end_s": 66.0, "start_5_s": 60.2, "end_95_s": 65.8, "angle_deg": -90.0}]
    marked = mark_carried(turns, [(15.0, 40.0)])
    assert marked[0][CARRIED] is True and CARRIED not in marked[1]
    assert [t["start_s"] for t in stepless_turns(ev, turns)] == [20.2, 60.2]
    assert [t["start_s"] for t in stepless_turns(ev, marked)] == [60.2]
    assert mark_carried(turns, []) is turns


def test_kept_reading_w489():
    """W139's raw pendulum reading cut to the contacts the pendulum track kept (within 0.05 s): a dropped contact
    ends the step before it."""
    raw = pd.DataFrame({"start_s": [1.0, 1.5, 2.0, 2.5], "end_s": [1.5, 2.0, 2.5, 2.5], "event_s": [1.0, 1.5, 2.0, 2.5],
                        "has_next": [True, True, True, False], "length_m": [0.7, 0.7, 0.7, 0.7]})
    kept = _kept_reading(raw, np.array([1.01, 1.52, 2.5]))
    assert kept["event_s"].tolist() == [1.0, 1.5, 2.5]
    assert kept["has_next"].tolist() == [True, False, False]
    assert len(_kept_reading(raw, np.zeros(0))) == 0


def test_a_turn_with_the_foot_at_rest_is_carried_w488():
    """W336's foot strides: a turn with no walking stride within 1 s (inside the foot's recording) is the seat's or
    the vehicle's; one with a stride nearby, or at the recording's edge, or without a foot unit is not judged."""
    strides = (np.array([10.0, 11.0, 40.0]), np.array([10.8, 11.8, 40.8]), np.array([1.2, 1.2, 0.1]))
    spans = [(12.5, 15.0), (20.0, 26.0), (39.5, 41.0), (0.5, 3.0)]
    assert strideless_spans(spans, strides, (0.0, 100.0)) == [(20.0, 26.0), (39.5, 41.0)]
    assert strideless_spans(spans, None, None) == []
