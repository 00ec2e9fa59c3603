"""Session 30: the input checks that read a whole session's sd / 99th percentile, on a long, mostly still recording.

B251 made B203's frozen-foot test judge B213's 10 s blocks. The same whole-session figures hid real faults on a night
with a short walk: B201's mis-scaled foot accelerometer and B134's foot unit that is not on the foot (decision B253:
"walks" and "swings" are the largest 10 s block's), and B91's swapped foot / waist files (decision B256: each unit's
largest 10 s block swing rate), and B37's gyroscope read 57.3 times too small (decision B257: the largest 10 s
block figures). Each test fails on main (the whole night read still, so no line).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.kernels.frozen_foot import block_swing_rate
from pdrlearn.kernels.units import FOOT_NO_SWING, WAIST_SWINGS, swing_rate
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def night():
    """User 5762 (fresh): 30 min seated, a 10 m walk at normal speed, 10 min seated (20 Hz)."""
    route = parse_route("sit:1800, straight:10, sit:600")
    return simulate_path(route, UserProfile.from_seed(5762), speed="normal", rate_hz=20, seed=0)


def _with(session, **streams):
    """``session`` with streams replaced: ``name=(source stream name, scale)``."""
    new = dict(session.streams)
    for name, (src, k) in streams.items():
        st = session.streams[src]
        new[name] = Stream(name, st.t, k * np.asarray(st.values, dtype=float))
    return dataclasses.replace(session, streams=new)


def test_block_swing_rate_takes_the_swinging_block_b256():
    t = np.arange(0.0, 3600.0, 0.05)
    gyr = 0.01 * np.random.default_rng(2).standard_normal((len(t), 3))
    walk = (t >= 1800.0) & (t < 1830.0)  # 30 s of a swinging foot in an hour (0.8 %)
    gyr[walk, 1] = 6.0 * np.sin(2 * np.pi * t[walk])
    assert swing_rate(gyr) < FOOT_NO_SWING  # the whole hour reads still (before B256)
    assert block_swing_rate(t, gyr) > WAIST_SWINGS
    assert block_swing_rate(t[:3], gyr[:3]) == pytest.approx(swing_rate(gyr[:3]))  # under a block: whole, as before


def test_a_mis_scaled_foot_accelerometer_is_warned_on_a_night_b253(night):
    from pdrlearn.track.foot_rest import foot_rest_stats, foot_scale_warning

    assert night.duration_s > 2400.0
    assert foot_scale_warning(foot_rest_stats(night), "n") is None
    line = foot_scale_warning(foot_rest_stats(_with(night, fAccelerometer=("fAccelerometer", 0.9))), "n")
    assert line is not None and "% off the 1 g" in line and line.endswith("(decision B201)")


def test_a_lower_back_unit_in_the_foot_files_is_warned_on_a_night_b253(night):
    from pdrlearn.track.foot_rest import foot_placement_warning, foot_rest_stats

    assert foot_placement_warning(foot_rest_stats(night), "n") is None
    moved = _with(night, fAccelerometer=("wAccelerometer", 1.0), fGyroscope=("wGyroscope", 1.0))
    line = foot_placement_warning(foot_rest_stats(moved), "n")
    assert line is not None and "never swings like a foot" in line and line.endswith("decision B134)")


def test_swapped_foot_and_waist_files_are_refused_on_a_night_b256(night):
    from pdrlearn.io.unit_check import unit_mixup

    assert unit_mixup(night) is None
    swapped = _with(night, fAccelerometer=("wAccelerometer", 1.0), fGyroscope=("wGyroscope", 1.0),
                    wAccelerometer=("fAccelerometer", 1.0), wGyroscope=("fGyroscope", 1.0))
    line = unit_mixup(swapped)
    assert line is not None and "the foot and waist files look swapped" in line and "(decision B91)" in line


def test_a_still_noisy_unit_is_not_refused_as_rad_s_b257_withdrawn():
    """B257 withdrawn: the largest 10 s block's |acc| sd of a still unit with 0.05 g noise crosses B37's 0.5 m/s^2
    by chance (test_ble_timing's export was refused); B37 judges the whole recording again."""
    from pdrlearn.kernels.units import check_imu_pair

    rng = np.random.default_rng(1)
    n = 4000
    t = np.arange(n) / 104.0
    acc = 9.80665 * np.c_[rng.normal(0, 0.05, n), 1.0 + rng.normal(0, 0.05, n), rng.normal(0, 0.05, n)]
    gyro = np.deg2rad(rng.normal(0, 2, (n, 3)))
    check_imu_pair(t, acc, t, gyro, "foot", "a", "g")  # B257's blocks refused it as rad/s read as deg/s
