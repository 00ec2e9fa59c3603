"""Review R1 (session 46) of session 45's merges. F1 / W529: W516's share of stands decided causally for the live
lower back and its realtime replay (live == replay on a rollator walk); F2 / W530: a lower-back stair flight reads no
ramps at its ends; F3 / E305: the live Tracker's waist rings stay bounded through a long stand; F4: calibrate's W514
line names the ``pause_steps`` in force; L675's tie (no events: the first row) and L679's words on a lower back."""

from __future__ import annotations

import logging
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track import grade as G
from pdrlearn.waist import _kernels as K
from tests.test_pause_steps_s45_w514 import rollator_walk  # noqa: F401  (the module's fixture: T1's damped c10)

ROOT = Path(__file__).resolve().parents[1]


# -- F1 / W529 ----------------------------------------------------------------------------------------------------
def _stand(run_s, causal):
    run = np.asarray(run_s, dtype=float)
    closes = np.zeros(run.size, bool)
    closes[-1] = True
    return np.flatnonzero(K.standing_step_mask(run, np.full(run.size, 0.9), ~closes, closes, causal=causal))


def test_the_causal_share_counts_the_steps_so_far():
    n = np.nan
    # W134 stands at rows 7, 15, then every other row from 17: 11 of 29 over the walk (W516: none), but rows 7 and
    # 15 came when the stands so far were at most a quarter of the steps so far (W529: kept), as the rollator's
    run = [n] * 7 + [0.5] + [n] * 7 + [0.5] + [n] + [0.5, n] * 6 + [0.5, n, n]
    assert _stand(run, causal=False).size == 0
    # 6 of 24 at row 23 (a quarter); 7 of 26 at row 25 is over it, and so is every later one
    np.testing.assert_array_equal(_stand(run, causal=True), [7, 15, 17, 19, 21, 23])
    assert K.stands_within_share(1, 4) and not K.stands_within_share(2, 7)
    # a stand among the first steps is rare only once the walk has four: row 2 (1 of 3) is dropped causally
    run = [n, n, 0.5] + [n] * 9
    assert _stand(run, causal=False).tolist() == [2] and _stand(run, causal=True).size == 0


def test_live_stands_equal_the_realtime_replay_on_the_rollator_walk(rollator_walk):  # noqa: F811
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist import WaistTracker
    from tests.runtime_helpers import push_waist

    s = rollator_walk
    params = {"walk_threshold_mps2": 0.21}  # R1's: the live gate opens on the damped trunk
    replay = track_waist(s, pipeline="waist-pendulum", realtime=True, params=params).steps
    n = len(s["wAccelerometer"].t)
    for chunks in ([n], list(np.random.default_rng(7).integers(1, 300, 2000))):
        tr = WaistTracker(100.0, meta=s.meta, frame=s.require_frame("waist"), params=params)
        out = push_waist(tr, s, chunks)
        assert len(out) == len(replay) > 40
        np.testing.assert_allclose([o.length_m for o in out], replay["length_m"], atol=1e-9, rtol=0)
    off = track_waist(s, pipeline="waist-pendulum", params=params).steps  # offline keeps W516's whole walk
    assert (off["pause_factor"] < 1).sum() == 0 and (replay["pause_factor"] < 1).sum() < 8  # W134 alone: 16


# -- F4 (W514) ------------------------------------------------------------------------------------------------------
def test_calibrate_names_the_pause_steps_in_force(rollator_walk, caplog, monkeypatch):  # noqa: F811
    from pdrlearn.waist import calibration as C

    with caplog.at_level(logging.WARNING):
        C.calibrate([rollator_walk], "waist-pendulum", distances=[14.0],
                    params={"options": {"pause_steps": "progression"}})
    lines = [r.getMessage() for r in caplog.records if r.getMessage().startswith("calibrate: ")
             and "shortened as pauses" in r.getMessage()]
    assert len(lines) == 1 and '(pause_steps "progression", W122)' in lines[0] and "W134" not in lines[0]
    seen = []  # W111's true shortens none of this walk's steps: the value handed to the line is what counts
    monkeypatch.setattr(C, "pause_scaled_message", lambda *a: seen.append(a[2:]))
    C.calibrate([rollator_walk], "waist-pendulum", distances=[14.0], params={"options": {"pause_steps": True}})
    assert seen == [(True,)]


# -- F2 / W530 ------------------------------------------------------------------------------------------------------
def _flight_table(level=8, flight=11, rise=-0.17, tread=0.7, edge=(0.45, 0.75)):
    """Level rows, a stair flight (its first / last rows carry part of a stair, as the pendulum steps straddle the
    flight's ends), level rows: a lower-back table's length and dz."""
    dz = np.zeros(level + flight + level)
    dz[level:level + flight] = rise
    dz[level], dz[level + 1] = edge[0] * rise, edge[1] * rise
    dz[level + flight - 1], dz[level + flight - 2] = edge[0] * rise, edge[1] * rise
    return np.full(dz.size, tread), dz


def test_a_flights_blurred_ends_are_no_ramps():
    length, dz = _flight_table()
    kw = {"lone_stair_joins": True, "window_m": G.WAIST_SLOPE_WINDOW_M}
    assert len(G.ramp_runs(length, dz, **kw)) == 2  # W517 alone: a "ramp" at each end of the flight
    assert G.ramp_runs(length, dz, stair_ends=True, **kw) == []
    # a ramp longer than the window that runs into stairs of its own way stays (9 m at 1:12, then the flight)
    ramp = np.full(13, 0.7)
    length2 = np.concatenate([np.full(6, 0.7), ramp, length[8:]])
    dz2 = np.concatenate([np.zeros(6), -ramp / 12, dz[8:]])
    found = G.ramp_runs(length2, dz2, stair_ends=True, **kw)
    assert [r["direction"] for r in found] == ["down"] and found[0]["horizontal_run_m"] > G.WAIST_SLOPE_WINDOW_M


@pytest.fixture(scope="module")
def stair_route(tmp_path_factory):
    """R1's repro: user 14108 down a 10-step flight between two 8 m level walks (no ramp in the truth)."""
    from pdrlearn.io import read_session

    out = tmp_path_factory.mktemp("w530") / "stairs"
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route",
                    "stand:3, straight:8, down:10, straight:8, stand:3", "--user-seed", "14108", "--rate", "100",
                    "--out", str(out)], check=True, capture_output=True, cwd=ROOT)
    return read_session(out)


def test_a_lower_back_stair_flight_has_no_ramps(stair_route, monkeypatch):
    from pdrlearn.track.waist import track_waist

    res = track_waist(stair_route, pipeline="waist-pendulum")
    steps = res.steps.assign(unit="waist")
    assert steps["stairs"].sum() >= 8  # W91 reads the flight
    assert G.track_ramps(steps, res.info)[0] == []
    orig = G.ramp_runs
    monkeypatch.setattr(G, "ramp_runs", lambda *a, **kw: orig(*a, **{**kw, "stair_ends": False}))
    assert len(G.track_ramps(steps, res.info)[0]) == 2  # R1: 13.85-15.38 s and 18.57-20.18 s without W530


# -- F3 / E305 ------------------------------------------------------------------------------------------------------
def test_the_live_waist_rings_stay_bounded_through_a_long_stand():
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from tests.runtime_helpers import time_chunks

    s = simulate_path(parse_route("stand:3, straight:6, stand:600, straight:6, stand:3"), UserProfile.from_seed(14104),
                      seed=14104, scenario="route")
    rate = s["wAccelerometer"].rate_hz
    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), tasks=[], sensors=list(s.streams))
    longest: dict[str, int] = {}
    n = 0
    for _, c in time_chunks(s, 1.0):
        n += len(tr.push(c))
        for k, r in tr._buf.items():
            longest[k] = max(longest.get(k, 0), len(r))
    n += len(list(tr.flush()))
    assert n >= 8 and set(longest) >= {"wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"}
    # L498's stop of up to 60 s is held (and buffer_s, the look-back); the 600 s stand is not (E289 held 12130) but in
    # the two rings carried_yaw reads: decision E324 keeps up to 600 s of them for a turn made on the spot (its
    # long_stop_span bounds them, tests/test_live_stops_s50_e324.py)
    carried = ("wAccelerometer", "wGyroscope")
    assert max(v for k, v in longest.items() if k not in carried) < 100 * rate
    assert max(longest[k] for k in carried) < (600 + 30) * rate


# -- minor: L675, L679 ----------------------------------------------------------------------------------------------
def test_a_stride_without_events_keeps_its_first_row():
    from pdrlearn.displace.foot import _latest_per_stride

    i0, i1 = np.array([10, 10, 10, 50]), np.array([40, 40, 40, 80])
    assert _latest_per_stride(i0, i1, np.array([np.nan, np.nan, np.nan, 1.0])).tolist() == [0, 3]
    assert _latest_per_stride(i0, i1, np.array([2.0, np.nan, 3.0, 1.0])).tolist() == [2, 3]  # the latest event


def test_the_walk_test_ramp_refusal_counts_a_lower_backs_steps():
    from pdrlearn.track.walk_test import _ramp_note

    start = np.arange(30) * 0.9
    st = pd.DataFrame({"start_s": start, "end_s": start + 0.9, "length_m": 0.6, "unit": "waist"})
    ramps = np.zeros(30, int)
    ramps[3:20] = 1
    note = _ramp_note(st, 0, 24, 14.0, 10.0, ramps)
    assert "hold 17 step(s) of ramp 1" in note and "stride" not in note
    assert "hold 17 stride(s) of ramp 1" in _ramp_note(st.assign(unit="foot"), 0, 24, 14.0, 10.0, ramps)
