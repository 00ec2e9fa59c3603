"""Session 29's Parkinson's trial (findings 3 and 4): uncalibrated lower-back tracks of shuffling walks.

3. `waist-pendulum` read a 0.25 m / 0.6 s shuffle +30 % long at "0.55 m/s" with no line: L95 judges the inflated
   speed and W100's walk ratio sat inside its band. Decision W207: a median pendulum step under half the comfortable
   step of the stature warns - an option (``short_step_check``), its adoption rule was not met (a real daily-activity
   recording warned).
4. `waist-pll` read the same walk +141 % with no line, and a 0.2 m/s walk -64 % (8 of ~70 steps) with W139's line
   saying it "reads long". Decision W208 (adopted): the pll track is judged by W207's test on the pendulum reading,
   far fewer contacts than the pendulum's says it misses steps, and the line's direction is the reading's."""

from __future__ import annotations

import dataclasses

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist.plausibility import (
    PLAUSIBILITY_MIN_PAIRS,
    WALK_RATIO_BAND,
    pll_missed_steps_message,
    short_step_limit,
    short_step_message,
    walk_ratio_message,
)

ROUTE = parse_route("stand:3, straight:10, stand:3")


def _walk(user: int, step: tuple[float, float] | None = None):
    """User ``user`` walking normally, or the trial's slow shuffle (step length m, step time s), pendulum bounce."""
    u = UserProfile.from_seed(user)
    if step is not None:
        u = dataclasses.replace(u, step_length_m=step[0], step_time_s=step[1])
    return simulate_path(ROUTE, u, speed="normal", rate_hz=100, seed=user, bounce="pendulum")


def _lines(r, decision: str) -> list[str]:
    return [w for w in r.info["warnings"] if f"decision {decision}" in w]


@pytest.fixture(scope="module")
def v040():
    return _walk(4803, (0.25, 0.6))  # the trial's v040 (0.42 m/s): pendulum +30 %, pll +141 %


def test_w207_the_short_step_limit_is_half_w6s_comfortable_step():
    assert short_step_limit(1.70) == pytest.approx(0.5 * 0.415 * 1.70)
    assert short_step_message(0.30, 40, 1.70) is not None
    assert short_step_message(0.36, 40, 1.70) is None  # above 0.353 m
    assert short_step_message(0.30, PLAUSIBILITY_MIN_PAIRS - 1, 1.70) is None  # too few steps to judge
    assert short_step_message(0.30, 40, 1.30) is None  # a child's short step is no shuffle (limit 0.27 m)
    line = short_step_message(0.30, 40, 1.70)
    assert "decision W207" in line and "pdrlearn calibrate" in line and "0.35 m" in line


def test_w207_a_shuffle_on_waist_pendulum_warns_with_short_step_check_only(v040):
    assert OPTION_DEFAULTS["short_step_check"] is False  # W207's rule was not met: an option
    plain = track_waist(v040, pipeline="waist-pendulum")
    assert not _lines(plain, "W207") and not _lines(plain, "W100")  # today's default: silent (documented)
    checked = track_waist(v040, pipeline="waist-pendulum", short_step_check=True)
    line, = _lines(checked, "W207")
    assert "not reliable" in line and "calibrate" in line
    normal = track_waist(_walk(4803), pipeline="waist-pendulum", short_step_check=True)
    assert not _lines(normal, "W207")


def test_w208_waist_pll_is_judged_by_w207_on_the_pendulum_reading(v040):
    r = track_waist(v040, pipeline="waist-pll")
    line, = _lines(r, "W207")
    assert "W208" in line and "longer than the pendulum model's" in line
    assert not _lines(track_waist(_walk(4803), pipeline="waist-pll"), "W207")


def test_w208_a_pll_track_that_misses_steps_says_so_and_not_that_it_reads_long():
    slow = _walk(4801, (0.15, 0.75))  # the trial's v020 (0.2 m/s): pll finds a handful of ~70 steps
    r = track_waist(slow, pipeline="waist-pll")
    line, = [w for w in r.info["warnings"] if "W208" in w]
    assert "misses steps" in line and "shorter than the pendulum's" in line
    assert not any("reads long" in w or "longer than" in w for w in r.info["warnings"])
    assert not _lines(r, "W100")  # W139's walk-ratio line is replaced, not added


def test_w208_the_missed_steps_count_and_the_walk_ratio_lines_direction():
    assert pll_missed_steps_message(8, 71, 3.6, 19.6) is not None
    assert pll_missed_steps_message(50, 71, 30.0, 19.6) is None  # 30 % fewer is not more than 30 %
    assert pll_missed_steps_message(5, 9, 2.0, 4.0) is None  # the pendulum's count under W99's 10
    low = WALK_RATIO_BAND[0] * 0.8
    short = walk_ratio_message(low, 40, 0.3, 100.0, pll_length=0.35, pll_m=5.0, pendulum_m=12.0)
    long_ = walk_ratio_message(low, 40, 0.3, 100.0, pll_length=0.7, pll_m=24.0, pendulum_m=12.0)
    assert "reads long" not in short and "shorter than the pendulum's" in short
    assert "reads long" in long_ and "longer than the pendulum's" in long_
