"""Decision L646 (session 44, FF, trial T1 finding F12): laps that track under half the corridor (a pipeline that
lost steps) give no per-minute distances or fatigue index; the lap count and distance stay."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.track.corridor import corridor_laps, corridor_line
from tests.walk_test_s44_helpers import laps_after, strides, turns_at


def test_laps_tracked_far_short_withhold_the_minutes_l646():
    t, cones = laps_after(0.0, 6)
    steps = strides(t, step_m=0.15, unit="waist")
    laps, s, warnings = corridor_laps(steps, turns_at(cones), 30.0, duration_s=180.0)
    assert s["n_laps"] == 5 and s["walk_test_distance_m"] == pytest.approx(180.0)  # L740: lap 6 ends at the timer
    assert s["walk_test_distance_per_minute_m"] is None and s["fatigue_index"] is None
    assert "withheld" in s["walk_test_note"] and "lost steps" in s["walk_test_note"]
    assert [w for w in warnings if "L646" in w and "withheld" in w]
    l518 = [w for w in warnings if "L518" in w]
    assert len(l518) == 1 and "(0.15 x), outside the 0.74-1.35 x" in l518[0] and "lose steps" in l518[0]
    assert "per minute" not in corridor_line(s) and "withheld" in corridor_line(s)
    # a foot track 20 % short (a uniform scale error) keeps its minutes
    _, s_foot, _ = corridor_laps(strides(t, step_m=0.8), turns_at(cones), 30.0, duration_s=180.0)
    assert s_foot["walk_test_distance_per_minute_m"] == pytest.approx([60.0, 60.0, 60.0])


def test_waist_pll_on_a_slow_walker_withholds_its_minutes_l646(tmp_path):
    """User 12402 at 0.3 m/s (1.0 s steps of 0.3 m, 2 x 15 m): waist-pll loses most steps."""
    ses = tmp_path / "slow"
    assert main(["simulate", "--route", "straight:15, turn:180, straight:15, turn:180, straight:15",
                 "--step-length", "0.3", "--step-time", "1.0", "--bounce", "pendulum", "--user-seed", "12402",
                 "--rate", "100", "--out", str(ses)]) == 0
    pll = {}
    for pipe in ("waist-pll", "waist-pendulum"):
        out = tmp_path / pipe
        assert main(["track", str(ses), "--pipeline", pipe, "--corridor", "15", "--walk-test-duration", "120",
                     "--no-plot", "--out", str(out)]) == 0
        pll[pipe] = json.loads((out / "summary.json").read_text())
    assert pll["waist-pll"]["walk_test_distance_per_minute_m"] is None
    assert "withheld" in pll["waist-pll"]["walk_test_note"]
    assert pll["waist-pendulum"]["walk_test_note"] is None
    assert len(pll["waist-pendulum"]["walk_test_distance_per_minute_m"]) == 2
