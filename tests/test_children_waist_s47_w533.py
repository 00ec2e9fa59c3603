"""Session 47, trial T1 finding F4: an uncalibrated child's lower-back line gave the error range of the height-scaled
default cadence (W405: "~45 % long"), while clinical paediatric cadences read waist-pll +50 to +108 % and
waist-pendulum -19 to +40 %. Decisions W533 (the range of the walker's own step-time band) and W534 (waist-pendulum
warns too, and both name calibrating waist-pendulum on a 10 m walk)."""
from __future__ import annotations

import dataclasses

import pytest

from pdrlearn.waist.plausibility import (
    CHILD_STEP_BANDS,
    DEFAULT_CADENCE_RANGES,
    short_walker_message,
    short_walker_ranges,
)


def _span(r):
    return f"{r[0]:+.1f} to {r[1]:+.1f} %"


def test_w533_bands_by_step_time():
    for lo, hi, ranges, n in CHILD_STEP_BANDS:
        assert n >= 3 and all(a <= b for a, b in ranges.values())
        assert short_walker_ranges((lo + hi) / 2 if lo else hi - 0.01)[1] is ranges
    assert short_walker_ranges(0.5)[1] is DEFAULT_CADENCE_RANGES  # slower than the children measured: W405's
    assert short_walker_ranges(None)[1] is DEFAULT_CADENCE_RANGES
    line = short_walker_message({"height_m": 1.3}, "waist-pendulum", 0.40)
    ranges = short_walker_ranges(0.40)[1]
    assert f"read {_span(ranges['waist-pendulum'])} in distance" in line and "(waist-pll " + _span(
        ranges["waist-pll"]) in line and "stepping every 0.40 s (150 steps/min)" in line
    assert "--pipeline waist-pendulum --distance 10" in line and "decision W393" in line
    assert short_walker_message({"height_m": 1.6}, "waist-pendulum", 0.40) is None


@pytest.mark.parametrize("pipeline", ["waist-pll", "waist-pendulum"])
def test_w533_w534_an_uncalibrated_child_at_150_steps_per_min(pipeline):
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
    from pdrlearn.track.units import keep_units
    from pdrlearn.track.waist import track_waist

    child = dataclasses.replace(UserProfile.from_seed(14990).scaled(1.30, 0.68), step_length_m=0.42, step_time_s=0.40)
    s = keep_units(simulate_path([Stand(2), Straight(12), Stand(2)], child, rate_hz=100, seed=14990), ("waist",))
    warned = [w for w in track_waist(s, pipeline=pipeline).info["warnings"] if "decision W405" in w]
    assert len(warned) == 1 and f"uncalibrated {pipeline} on a walker of about 1.30 m stepping every 0.4" in warned[0]
    assert "decision W533" in warned[0] and "decision W534" in warned[0], warned
    own = {"leg_m": 0.68, "k": 1.1, "source": "calibrated", "pipeline": pipeline}
    assert not [w for w in track_waist(s, pipeline=pipeline, params=own).info["warnings"] if "decision W405" in w]
