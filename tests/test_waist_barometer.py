"""Decisions W89-W91: a lower-back track's altitude from the waist barometer (relative to the start, the
barometric formula the simulator writes it with), the floors counted from it as the foot pipeline counts them,
one warning when there is no barometer, and the ``stairs_length`` option (a stair step at most the tread)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.kernels.barometer import altitude_m, pressure_hpa, relative_altitude
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import NO_BAROMETER, STAIR_TREAD_M


def _waist_only(session, *, barometer: bool = True):
    keep = {k: v for k, v in session.streams.items() if k.startswith("w") and (barometer or k != "wBarometer")}
    return dataclasses.replace(session, streams=keep, steps=None,
                               frames={k: v for k, v in session.frames.items() if k == "waist"})


@pytest.fixture(scope="module")
def stairs():
    """A storey up (18 x 0.17 m) between two level walks, a belt unit only."""
    return _waist_only(simulate_path(parse_route("straight:4, up:18, straight:4"), UserProfile.from_seed(2),
                                     rate_hz=20.0, seed=1, scenario="route", bounce="pendulum"))


def test_altitude_inverts_the_simulators_pressure():
    z = np.linspace(0.0, 9.0, 200)
    for p0 in (996.5, 1013.25, 1029.0):  # thesis Table 18's 30-day range of the sea-level pressure
        assert np.allclose(altitude_m(pressure_hpa(75.0 + z, p0), p0) - 75.0, z, atol=1e-6)


def test_relative_altitude_is_the_change_from_the_first_time_and_smooths_the_noise():
    t = np.arange(0.0, 60.0, 0.05)
    z = np.clip((t - 20.0) * 0.3, 0.0, 6.0)  # a 6 m climb at 0.3 m/s
    p = pressure_hpa(100.0 + z, 1005.0) + np.random.default_rng(0).normal(0.0, 0.0157, len(t))  # Table 18 noise
    h = relative_altitude(t, p, np.array([10.0, 15.0, 45.0, 59.0]))
    assert h[0] == 0.0
    assert abs(h[1]) < 0.15 and abs(h[2] - 6.0) < 0.15 and abs(h[3] - 6.0) < 0.15


def test_a_storey_climbed_gives_altitude_and_one_floor(stairs):
    res = get_pipeline("waist-pendulum")(stairs)
    ev = evaluate_track(res, stairs)
    assert ev["altitude_change_ref_m"] == pytest.approx(3.06, abs=0.1)
    assert ev["altitude_change_m"] == pytest.approx(ev["altitude_change_ref_m"], abs=0.3)
    assert (ev["floors_up"], ev["floors_down"]) == (1, 0) == (ev["floors_up_ref"], ev["floors_down_ref"])
    # W158: a step's dz_m is its own change, pause_dz_m the standstill's before it (here the start's)
    assert np.allclose(np.cumsum(res.steps["dz_m"] + res.steps["pause_dz_m"]), res.trajectory["z"].to_numpy()[1:])
    assert NO_BAROMETER not in res.info["warnings"]


def test_no_barometer_says_no_altitude(stairs):
    s = _waist_only(stairs, barometer=False)
    res = get_pipeline("waist-pendulum")(s)
    assert NO_BAROMETER in res.info["warnings"]
    assert (res.trajectory["z"] == 0.0).all() and (res.steps["stairs"] == False).all()  # noqa: E712


def test_stairs_length_bounds_only_the_stair_steps_by_the_tread(stairs):
    off = get_pipeline("waist-pendulum")(stairs)
    on = get_pipeline("waist-pendulum")(stairs, stairs_length=True)
    st = on.steps["stairs"].to_numpy(bool)
    assert 10 <= st.sum() <= 24  # the 18 stairs, give or take the steps at the flight's ends
    assert (off.steps["length_m"].to_numpy()[st] > STAIR_TREAD_M).any()
    assert (on.steps["length_m"].to_numpy()[st] <= STAIR_TREAD_M).all()
    assert np.array_equal(on.steps["length_m"].to_numpy()[~st], off.steps["length_m"].to_numpy()[~st])


def test_a_climb_is_a_run_of_one_sign_higher_than_the_floor_and_the_noise():  # decision W108
    from pdrlearn.kernels.barometer import STAIR_CLIMB_MIN_M, climb_mask

    up = np.array([0, 1, 1, 1, 1, 0, -1, -1, 1])
    start = np.array([0.0, 0.0, 0.5, 1.0, 1.5, 2.0, 2.0, 1.8, 1.6])
    end = np.array([0.0, 0.5, 1.0, 1.5, 2.0, 2.0, 1.8, 1.6, 1.7])
    # the 2.0 m climb counts, the 0.4 m dip and the one-step rise do not
    assert climb_mask(up, start, end, 0.0).tolist() == [False, True, True, True, True, False, False, False, False]
    # a noisier barometer needs a higher climb: 3 sqrt(2) x 0.5 m = 2.12 m > 2.0 m
    assert not climb_mask(up, start, end, 0.5).any()
    assert STAIR_CLIMB_MIN_M == 1.5 and not climb_mask(up, start, end * 0.7, 0.0).any()  # 1.4 m: under half a storey
    assert not climb_mask(-up, start, end, 0.0).any()  # proposed down, but the altitude rose


def test_still_altitude_sd_is_the_wander_before_and_after_the_walk():  # decision W108
    from pdrlearn.kernels.barometer import still_altitude_sd

    t = np.arange(0.0, 20.0, 0.01)
    wander = np.where(t < 5.0, 0.3 * np.sin(2 * np.pi * t / 4.0), 0.0)  # 0.3 m amplitude, 4 s period
    p = pressure_hpa(50.0 + wander + np.where(t > 5.0, 3.0, 0.0), 1008.0)  # a storey while walking (5-15 s)
    sd = still_altitude_sd(t, p, 5.5, 15.0)
    assert 0.1 < sd < 0.3
    assert still_altitude_sd(t, p, 0.6, 19.9) == 0.0  # under 1 s still: no noise measured


def test_a_level_real_walk_has_no_stairs_and_stays_on_its_floor(mobgap_test5):  # decision W108
    from pdrlearn.io import read_session

    s = read_session(mobgap_test5)
    res = get_pipeline("waist-pendulum")(s, stairs_climb=True)
    assert not res.steps["stairs"].any()  # W91's test alone called 6 of its 11 steps stairs
    assert abs(res.trajectory["z"].iloc[-1]) < 0.2  # W89's altitude alone ended at +0.30 m
    assert (res.steps["dz_m"] == 0.0).all()


def test_the_climb_keeps_the_storey_and_its_stair_steps(stairs):  # decision W108
    res = get_pipeline("waist-pendulum")(stairs, stairs_climb=True)
    ev = evaluate_track(res, stairs)
    assert (ev["floors_up"], ev["floors_down"]) == (1, 0)
    assert ev["altitude_change_m"] == pytest.approx(ev["altitude_change_ref_m"], abs=0.3)
    st = res.steps["stairs"].to_numpy(bool)
    assert 10 <= st.sum() <= 24
    assert (res.steps["dz_m"].to_numpy()[~st] == 0.0).all()
