"""Decision W174: a sit-to-stand's (stand-to-sit's) barometric height change belongs to the transfer (steps.csv
``transfer_dz_m``), not to the lower-back track's altitude, ascent or floors (trial ``rehab`` finding 3: a TUG that
starts seated read +0.46 m and ascent 0.53 m)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.barometer import held_altitude, pressure_hpa, relative_altitude
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist


def _sim(route: str, user: int, **knobs):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), speed="slow", rate_hz=20.0, seed=0,
                         scenario="route", **knobs)


def test_a_seated_tug_reads_no_climb():
    s = _sim("straight:3, turn:180, straight:3", 11, sit_start_s=5.0, sit_end_s=5.0)  # the trial's r/tug
    res = track_waist(s, pipeline="waist-pendulum")
    ev = evaluate_track(res, s)
    assert abs(ev["altitude_change_m"]) < 0.15 and ev["ascent_m"] < 0.15  # was +0.46 m and 0.53 m
    st = res.steps
    rise = float(s.extras["transfers"]["drop_m"].iloc[0])
    assert st["transfer_dz_m"].sum() == pytest.approx(rise, abs=0.15)  # the stand-up's lift, kept apart
    # dz_m + pause_dz_m + transfer_dz_m is the barometer's altitude at each step's end, as dz + pause_dz was (W158)
    b = s["wBarometer"]
    raw = relative_altitude(b.t, b.values[:, 0], np.r_[res.trajectory["t"].iloc[0], st["end_s"].to_numpy(float)])
    assert np.allclose(np.cumsum(st["dz_m"] + st["pause_dz_m"] + st["transfer_dz_m"]), raw[1:], atol=1e-9)
    assert np.allclose(np.cumsum(st["dz_m"] + st["pause_dz_m"]), res.trajectory["z"].to_numpy()[1:], atol=1e-9)


def test_a_stair_climb_keeps_its_altitude_with_no_transfer():
    s = _sim("straight:5, up:17, straight:5", 3402)
    res = track_waist(s, pipeline="waist-pendulum")
    ev = evaluate_track(res, s)
    assert ev["altitude_change_m"] == pytest.approx(ev["altitude_change_ref_m"], abs=0.3)
    assert ev["ascent_m"] > 2.0  # the storey is climbed (ascent reads the climbs within L172's band)
    assert np.all(res.steps["transfer_dz_m"] == 0.0)


def test_held_altitude_takes_out_the_change_inside_its_windows():
    t = np.arange(0.0, 60.0, 0.05)
    z = np.clip(t - 10.0, 0.0, 0.5) + np.clip((t - 40.0) * 0.3, 0.0, 3.0)  # a 0.5 m rise at 10 s, a climb at 40 s
    p = pressure_hpa(100.0 + z, 1005.0)
    at = np.array([0.0, 5.0, 10.2, 20.0, 39.0, 59.0])
    held, raw = held_altitude(t, p, at, [(9.0, 12.0)])
    assert np.allclose(raw, relative_altitude(t, p, at))
    assert np.allclose(held[:4], 0.0, atol=0.01) and held[-1] == pytest.approx(3.0, abs=0.02)  # the climb is kept
    again, _ = held_altitude(t, p, at, [(9.0, 11.0), (10.5, 12.0)])  # overlapping windows merge: not taken twice
    assert np.allclose(again, held)
    assert np.array_equal(held_altitude(t, p, at, [])[0], raw)


def test_the_live_tracker_keeps_a_transfers_rise():
    """Decision W188: the live lower-back trackers have no W174 (W104's flexion events need the whole recording's
    walking upright): the seated TUG's stand-up stays in the live altitude, while offline holds it in
    ``transfer_dz_m``. Pins the limitation W188 records (a live W174 would change this test)."""
    from pdrlearn.waist import WaistTracker
    from tests.test_runtime_waist import _push_with_barometer

    s = _sim("straight:3, turn:180, straight:3", 11, sit_start_s=5.0, sit_end_s=5.0)  # the trial's r/tug
    rise = float(s.extras["transfers"]["drop_m"].iloc[0])
    live = _push_with_barometer(WaistTracker(20.0, meta=s.meta, frame=s.require_frame("waist")), s,
                                [20] * (len(s["wAccelerometer"].t) // 20 + 1))
    assert live and live[-1].z == pytest.approx(rise, abs=0.15)  # the live track climbed the stand-up
    assert abs(evaluate_track(track_waist(s, pipeline="waist-pendulum"), s)["altitude_change_m"]) < 0.15
