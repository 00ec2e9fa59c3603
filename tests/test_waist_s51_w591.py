"""Decisions W590 / W591 (session 51, I2, issue 8): a slow shuffler's lower back counts extra contacts because W113's
shortest step stops at W16's 0.3 s (and reads a harmonic below ~50 steps/min); ``slow_min_step="slow"`` (an option:
W593 withdrew W592's default) takes the shortest step from the pelvic gyro's median step below 70 steps/min."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.waist.pelvic_rhythm import slow_shortest_step_s


def test_the_shortest_step_follows_only_a_slow_pelvic_rhythm_w591():
    slow = np.arange(12) * 1.2  # 50 steps/min, 12 pelvic-gyro steps
    assert slow_shortest_step_s(slow) == pytest.approx(0.75 * 1.2)  # W113's fraction, no 0.3 s cap
    assert slow_shortest_step_s(np.arange(12) * 0.8) is None  # 75 steps/min: W113's own shortest step stands
    assert slow_shortest_step_s(slow[:9]) is None  # under W99's 10 pelvic-gyro steps
    assert slow_shortest_step_s(None) is None


@pytest.fixture(scope="module")
def shuffle():
    """W590's user 17806 (exploration range, not W591's measured users): 0.25 m steps every 1.1 s, pendulum bounce."""
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS

    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(17806), step_length_m=0.25 / f_len, step_time_s=1.1 / f_time)
    return simulate_path([Stand(2), Straight(8), Stand(2)], u, speed="normal", rate_hz=50, seed=17806,
                         bounce="pendulum")


def test_a_slow_shuffle_counts_its_steps_with_the_option_w591(shuffle):
    from pdrlearn.track.waist import track_waist

    true = len(shuffle.extras["ics"])
    n = {v: len(track_waist(shuffle, pipeline="waist-pendulum", slow_min_step=v).steps) for v in (False, "slow")}
    assert n[False] > true + 3  # W590: extra contacts inside the slow steps (W113's shortest step alone)
    assert abs(n["slow"] - true) <= 1


def test_the_option_is_a_checked_choice_and_named_where_it_does_nothing_w591(shuffle):
    from pdrlearn.errors import DataError
    from pdrlearn.track.waist import OPTION_DEFAULTS, ignored_options_line, track_waist

    o = dict(OPTION_DEFAULTS, slow_min_step="slow")
    line = ignored_options_line(o, "waist-pll", False, "ahe", False, True)
    assert line is not None and 'slow_min_step="slow" applies to the offline waist-pendulum' in line
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True) is None
    assert OPTION_DEFAULTS["slow_min_step"] is False  # W593: W592's default withdrawn (L647's walk split a bout)
    with pytest.raises(DataError, match="slow_min_step 'fast' is not one of false, \"slow\" \\(decisions W591\\)"):
        track_waist(shuffle, pipeline="waist-pendulum", slow_min_step="fast")
