"""Decision L644 (session 44, FF, trial T1 findings F3 and F9): a timed walk test reports the span it covers - a
recording that ends early, a walk that stops early - its fatigue index over the full minutes walked, and its label
by the duration asked (2MWT, 6MWT, "N-min walk test")."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.report.clinical import walk_test_line
from pdrlearn.track.corridor import corridor_laps, corridor_line, walk_test_label
from tests.walk_test_s44_helpers import laps_after, strides, turns_at


def test_a_walk_that_stops_early_is_named_and_its_minutes_cut_l644():
    """4 laps + 10 m in 250 s, then sitting until the 360 s test's end (trial T1's P08, 1 m strides)."""
    t, cones = laps_after(0.0, 4, extra=10)
    steps = strides(t)
    laps, s, warnings = corridor_laps(steps, turns_at(cones), 30.0, duration_s=360.0, data_end=400.0)
    assert s["walk_test_duration_s"] == pytest.approx(360.0) and s["walk_test_protocol_s"] == 360.0
    assert s["walk_test_stopped_s"] == pytest.approx(130.0)
    assert s["walk_test_distance_per_minute_m"] == pytest.approx([60.0, 60.0])  # two full minutes walked
    assert s["fatigue_index"] == pytest.approx(1.0)  # main: 0.00 over an empty last minute
    assert [w for w in warnings if "walking stopped 2:10" in w and "L644" in w]
    assert "walking stopped at 2:10" in corridor_line(s)
    assert "walking stopped after 2:10 of 6:00" in walk_test_line(s, "foot unit")


def test_a_recording_that_ends_early_is_an_incomplete_test_l644():
    t, cones = laps_after(0.0, 11, extra=0)
    steps = strides(t[t < 320.0])
    _, s, warnings = corridor_laps(steps, turns_at([c for c in cones if c < 320.0]), 30.0, duration_s=360.0,
                                   data_end=321.0)
    assert s["walk_test_duration_s"] == pytest.approx(321.0)  # main: 360
    assert s["walk_test_stopped_s"] is None and len(s["walk_test_distance_per_minute_m"]) == 5
    assert [w for w in warnings if "recording ends 321 s after" in w and "incomplete" in w]
    assert "5:21 of 6:00 (incomplete)" in corridor_line(s)
    assert "incomplete 6MWT" in walk_test_line(s, "foot unit")


def test_the_label_follows_the_duration_asked_l644():
    assert [walk_test_label(v) for v in (120.0, 360.0, 180.0, None)] == ["2MWT", "6MWT", "3-min walk test",
                                                                        "corridor walk test"]
    t, cones = laps_after(0.0, 5)
    _, s, _ = corridor_laps(strides(t), turns_at(cones), 30.0, duration_s=120.0, data_end=float(np.max(t)) + 1)
    line = walk_test_line(s, "foot unit")
    # main: "(6MWT)"; L740: the 4th lap ends at the timer, a 30 m partial lap
    assert line.startswith("- Corridor walk test (2MWT): 120 m, 3 laps of 30 m in 2.0 min")
    assert corridor_line(s).startswith("corridor 2MWT (30 m): 3 lap(s)")
