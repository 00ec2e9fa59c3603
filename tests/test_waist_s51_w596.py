"""Decisions W596 / W597 (trial s51t1 F2): a W108 climb that travels more than 40 m, or whose neighbouring steps keep
changing the altitude its way, is a trail slope, not stairs:
W155's stairs line does not count it and ``stairs_length: "climbs"`` (W156) does not bound it."""

from __future__ import annotations

import dataclasses
import logging
import re

import numpy as np
import pytest

from pdrlearn.kernels.barometer import slope_climbs


def test_a_climb_that_travels_over_40_m_is_a_slope_a_stairwell_is_not():
    straight = [(0, 200, 30.0)]  # 200 steps of 0.7 m one way: a trail
    flight = [(0, 20, 3.4)]  # one straight flight of 20 steps
    lengths = np.full(200, 0.7)
    assert slope_climbs(straight, lengths, np.zeros(200)) == [True]
    assert slope_climbs(flight, lengths, np.zeros(200)) == [False]
    u_turns = np.repeat([0.0, np.pi], 17)  # a stairwell: 34 steps, a U-turn at each landing
    assert slope_climbs([(0, 34, 5.8), (0, 34, 5.8)], np.full(34, 1.5), np.tile(u_turns, 1)) == [False, False]
    assert slope_climbs(straight, lengths, np.zeros(200), slope_travel_m=None) == [False]  # before W596
    assert slope_climbs(straight, lengths, np.zeros(200), slope_travel_m=150.0) == [False]
    # candidate C: a 30-step climb of 2.4 m (0.08 m per step) between 20 steps on either side
    n = 70
    flat = np.zeros(n)
    on_slope = np.arange(n) * -0.06  # the flanks keep descending at 0.06 m per step
    frag = [(20, 50, -2.4)]
    level = np.concatenate([np.zeros(20), -0.08 * np.arange(1, 31), np.full(20, -2.4)])  # a flight between floors
    lengths = np.full(n, 0.65)
    assert slope_climbs(frag, lengths, flat, on_slope, on_slope - 0.06) == [True]
    assert slope_climbs(frag, lengths, flat, np.r_[0.0, level[:-1]], level) == [False]
    assert slope_climbs(frag, lengths, flat, on_slope, on_slope - 0.06, flank_min_rise_m=None) == [False]
    assert slope_climbs(frag, lengths, flat) == [False]  # no altitudes: no flank test
    drop = np.concatenate([np.zeros(20), np.full(30, 0.08), np.full(4, 0.06), np.full(10, 0.16), np.zeros(6)])
    end = -np.cumsum(drop)  # two flights down with a 4-step landing between them, level floors around
    start = np.r_[0.0, end[:-1]]
    stairwell = [(20, 50, -2.4), (54, 64, -1.6)]
    assert slope_climbs(stairwell, lengths, flat, start, end) == [False, False]  # a landing is too short to judge
    assert slope_climbs(stairwell, lengths, flat, start, end, flank_min_steps=3) == [True, True]


@pytest.fixture(scope="module")
def hill():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track import get_pipeline

    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:5, straight:10, up:17, straight:10, slope:60:25, straight:10, stand:5"),
                          UserProfile.from_seed(18250), rate_hz=20.0, seed=3, scenario="route")
        s = dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if k.startswith("w")},
                                frames={k: v for k, v in s.frames.items() if k == "waist"})  # lower back only
        pipe = get_pipeline("waist-pendulum")
        return pipe(s), pipe(s, stairs_length="climbs")
    finally:
        logging.disable(logging.NOTSET)


def test_the_stairs_line_counts_the_flight_not_the_slope(hill):
    plain, _ = hill
    lines = [w for w in plain.info["warnings"] if "steps are on stairs" in w]
    assert len(lines) == 1 and "W596" in lines[0]
    n = int(re.search(r"(\d+) steps are on stairs", lines[0]).group(1))
    left = int(re.search(r"(\d+) steps of climbs that travel over 40 m or lie on a slope", lines[0]).group(1))
    assert 12 <= n <= 24 and left >= 40  # the 17-step flight, not the 60 m slope at 25 %
    assert n + left == int(plain.steps["climb"].sum())  # the steps column keeps W108's climbs


def test_the_climbs_option_bounds_the_flight_only(hill):
    plain, bounded = hill
    a, b = plain.steps["length_m"].to_numpy(float), bounded.steps["length_m"].to_numpy(float)
    changed = ~np.isclose(a, b)
    assert 8 <= changed.sum() <= 24 and (b[changed] <= 0.30 + 1e-9).all()
    assert a.sum() - b.sum() < 0.5 * a[changed].sum() + 1e-9 and changed.sum() < 0.5 * plain.steps["climb"].sum()
