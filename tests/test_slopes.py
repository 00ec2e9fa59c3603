"""Slopes and hills on the foot altitude (decisions L144-L146): the sustained-slope option (not adopted), the
cross-check against the session's unused waist barometer and the cumulative ascent / descent."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels import distance
from pdrlearn.kernels.altitude_check import ascent_descent
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import count_floors_by_climb, track_summary
from pdrlearn.track.plasys import track_plasys


def _summary(route: str, user: int, **kw) -> dict:
    s = simulate_path(parse_route(route), UserProfile.from_seed(user), seed=user)
    return track_summary(track_plasys(s, **kw), s)


def test_ascent_descent_hysteresis():
    z = np.r_[0.0, 0.3, 0.1, 0.4, 1.2, 0.2, 0.25]
    assert ascent_descent(z) == pytest.approx((0.3 + 0.3 + 0.8 + 0.05, 0.2 + 1.0))  # every rise and drop
    up, down = ascent_descent(z, 0.5)  # 0 -> 1.2 (counted at 1.2), -> 0.2 (1.0 down), remainder +0.05
    assert (up, down) == pytest.approx((1.25, 1.0))
    rng = np.random.default_rng(0)
    level = rng.normal(0.0, 0.13, 400)  # W89: 0.13 m of altitude noise per barometer sample
    up, down = ascent_descent(level, 0.5)
    assert up - down == pytest.approx(level[-1] - level[0]) and up < 0.6 and down < 0.6
    assert sum(ascent_descent(level)) > 20  # without the band the noise is a climb
    assert ascent_descent([1.0]) == (0.0, 0.0)


def test_the_sustained_slope_candidate_is_an_option_off_by_default():
    dz = np.r_[np.full(3, 0.02), np.full(30, 0.07), np.full(30, -0.065), np.full(5, 0.05)]
    assert distance.SUSTAINED_SLOPE is False  # L144: not adopted
    assert not distance.level_dz(dz).any() and count_floors_by_climb(dz) == (0, 0, 0)
    kept = distance.level_dz(dz, slope=True)
    assert kept.sum() == pytest.approx(30 * 0.07 - 30 * 0.065)  # the 5-stride run and the 0.02s stay level
    assert count_floors_by_climb(np.r_[dz, np.full(20, 0.07)], slope=True) == (1, 1, 0)  # 3.5 m up is a storey


def test_summary_has_ascent_and_descent():
    s = _summary("straight:3, slope:20:15, straight:2, turn:180, slope:20:-15, straight:3", 1061)
    assert s["ascent_m"] > 2.0 and s["descent_m"] > 2.0  # 3 m up and down; the net is near 0
    assert s["ascent_m"] - s["descent_m"] == pytest.approx(s["altitude_change_m"])


def test_a_ramp_on_the_foot_warns_against_the_barometer(caplog):
    with caplog.at_level(logging.WARNING):
        s = _summary("straight:3, slope:40:5, straight:3", 1062)  # +2 m, most strides under 0.10 m
    assert s["barometer_altitude_change_m"] == pytest.approx(2.0, abs=0.3)
    assert s["barometer_altitude_change_m"] - s["altitude_change_m"] > s["barometer_disagree_limit_m"]
    assert s["info"]["altitude_check"]["level_zeroed_m"] > 1.0  # the height L39 called level
    line = [w for w in s["info"]["warnings"] if "disagrees with the waist barometer's" in w]
    assert len(line) == 1 and "L39 set" in line[0] and "--pipeline waist-pendulum" in line[0]
    assert "disagrees with the waist barometer's" in caplog.text


def test_a_level_walk_with_a_barometer_does_not_warn():
    s = _summary("straight:30", 1063, streaming=True)
    assert s["barometer_unused"] and abs(s["barometer_altitude_change_m"]) < 0.5
    assert not [w for w in s["info"]["warnings"] if "barometer's" in w]
