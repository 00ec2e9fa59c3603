"""Session 40, trial T2 finding F7 (residents walking with a rollator, lower-back IMU): a trunk a rollator steadies read
27-61 % short while W100's walk-ratio line said the gait "reads long" (W454); ``calibrate`` printed that line,
which asks for a calibration, while calibrating (W455); ``trolley:`` is a free walk, not a walking aid (W456)."""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

from pdrlearn.route_forms import ROUTE_FORMS
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.plausibility import WALK_RATIO_ADVICE, WALK_RATIO_BAND, walk_ratio_message

DOCS = Path(__file__).resolve().parents[1] / "docs"


def test_w454_a_low_walk_ratio_names_both_directions_and_a_walking_aid():
    low = walk_ratio_message(WALK_RATIO_BAND[0] * 0.8, 40, 0.22, 80.0)
    assert "walking aid" in low and "rollator" in low and "cane" in low
    assert "reads long on short steps" in low and "short on a trunk" in low
    assert "may be too long or too short" in low and "decision W454" in low
    high = walk_ratio_message(WALK_RATIO_BAND[1] * 1.2, 40, 0.8, 62.0)
    assert "implausibly long" in high and "W454" not in high  # the far-over line is unchanged
    # W208: a pll track that reads shorter than the pendulum drops the whole direction clause
    short = walk_ratio_message(WALK_RATIO_BAND[0] * 0.8, 40, 0.3, 100.0, pll_length=0.35, pll_m=5.0, pendulum_m=12.0)
    assert "and is not reliable" in short and "reads long" not in short and "W454" not in short


def _short_steps(seed: int):
    """A short-stepping walker (0.15 m every 0.4 s, the pendulum bounce): its uncalibrated track warns (W100)."""
    u = dataclasses.replace(UserProfile.from_seed(seed), step_length_m=0.15, step_time_s=0.4)
    return simulate_path([Stand(3), Straight(10), Stand(3)], u, speed="normal", rate_hz=100, seed=seed,
                         bounce="pendulum")


def test_w455_calibrate_does_not_print_the_walk_ratio_line_its_walk_gets(caplog):
    walk = _short_steps(11040)
    assert any(WALK_RATIO_ADVICE in w for w in track_waist(walk, pipeline="waist-pendulum").info["warnings"])
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        calibrate([walk], "waist-pendulum", distances=[10.0])
    logged = [r.getMessage() for r in caplog.records]
    assert not any("decision W100" in m or WALK_RATIO_ADVICE in m for m in logged)
    with caplog.at_level(logging.WARNING):  # outside calibrate the track still says it
        caplog.clear()
        track_waist(walk, pipeline="waist-pendulum")
    assert any(WALK_RATIO_ADVICE in r.getMessage() for r in caplog.records)


def test_w456_trolley_is_documented_as_a_free_walk_not_a_walking_aid():
    form = ROUTE_FORMS["trolley"]
    assert "free walk" in form and "walking aid (rollator, cane) is not simulated" in form
    text = (DOCS / "simulator.md").read_text()
    assert "a walking aid is not\n  simulated" in text and "decision W456" in text
