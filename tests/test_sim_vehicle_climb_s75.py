"""Decision S75: ``vehicle:S:RMS:RISE``, a vehicle that climbs RISE m in its cruise while the walker stands.
Simulated users 7650-7699 (seed = user)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Straight, UserProfile, Vehicle, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.vehicle import VEHICLE_GRADE, draw_vehicle


def test_the_climb_parses_and_bad_ones_are_one_line():
    assert parse_route("vehicle:60::4, vehicle:90:0.8:-6, vehicle:30") == [
        Vehicle(60.0, None, 4.0), Vehicle(90.0, 0.8, -6.0), Vehicle(30.0)]
    for bad, word in (("vehicle:60:0.5:500", "-100 to \\+100 m"), ("vehicle:60:0.5:x", "not a number"),
                      ("vehicle:60:0.5:2:1", "takes")):
        with pytest.raises(DataError, match=word) as e:
            parse_route(f"straight:3, {bad}")
        assert "\n" not in str(e.value)
    with pytest.raises(DataError, match="too short for a grade") as e:  # 90 m in a 20 s hop: steeper than 20 %
        simulate_path([Straight(3.0), Vehicle(20.0, 0.5, 90.0), Straight(3.0)], UserProfile.from_seed(7690))
    assert "\n" not in str(e.value)


def test_a_level_ride_draws_as_before_and_a_climb_takes_the_spare_draw():
    """S75 draws the grade from the uniform S71 left unused: every other value of the ride is the level ride's."""
    level = draw_vehicle(0, 60.0, None, 0.0, np.zeros(2), np.random.default_rng(7691), delay_s=1.0)
    climb = draw_vehicle(0, 60.0, None, 0.0, np.zeros(2), np.random.default_rng(7691), delay_s=1.0, rise_m=4.0)
    assert (level.rise_m, level.climb_m) == (0.0, 0.0)
    assert (climb.speed_mps, climb.bend_rad, climb.vib_rms, climb.tones) == (
        level.speed_mps, level.bend_rad, level.vib_rms, level.tones)
    grade = 1.875 * 4.0 / climb.climb_m  # the quintic's peak slope 15/8
    assert VEHICLE_GRADE[0] - 1e-9 <= grade <= VEHICLE_GRADE[1] + 1e-9


def test_a_climbing_vehicle_carries_the_walker_up_smoothly():
    """User 7651, noise-free: rides.csv's vehicle row rises 4 m, both trajectories rise 4 m across the ride and not
    before it, the rise is smooth (its vertical rate under 1 m/s) and no contact falls in the ride."""
    s = simulate_path(parse_route("stand:3, straight:6, vehicle:60:0.5:4, straight:6"), UserProfile.from_seed(7651),
                      seed=7651, scenario="route", noise=False)
    row = s.extras["rides"].iloc[0]
    assert row.kind == "vehicle" and row.dz_m == pytest.approx(4.0, abs=1e-6)
    for track in (s.trajectory, s.extras["foot_trajectory"]):
        t, z = track.iloc[:, 0].to_numpy(), track["z"].to_numpy()
        inside = (t > row.start_s) & (t < row.end_s)
        assert np.median(z[t > row.end_s + 1][:50]) - np.median(z[t < row.start_s - 1][-50:]) == pytest.approx(
            4.0, abs=0.1)
        rate = np.diff(z[inside]) / np.diff(t[inside])
        assert np.max(np.abs(np.convolve(rate, np.ones(50) / 50, mode="valid"))) < 1.0
    ics = s.extras["ics"]["ic_s"].to_numpy()
    assert not np.any((ics > row.start_s) & (ics < row.end_s))


def test_a_signed_value_that_is_not_finite_is_asked_to_be_finite_b300():
    """B300: a route value that may be negative (a vehicle's climb, a lift's rise, a curve's angle) and is nan / inf
    is asked to be a finite number, not "a positive number" (before: "must be a positive number")."""
    for bad in ("vehicle:60:0.5:nan", "lift:inf", "curve:-inf:2"):
        with pytest.raises(DataError, match="must be a finite number") as e:
            parse_route(f"straight:3, {bad}")
        assert "positive" not in str(e.value) and "\n" not in str(e.value)
    with pytest.raises(DataError, match="must be a positive number"):  # a positive value keeps its line
        parse_route("straight:inf")
