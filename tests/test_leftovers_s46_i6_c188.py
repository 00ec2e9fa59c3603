"""Decision C188 (session 46, I6): a 10 m walk's passes (L673's `pass_rows`) and turns.csv's turns (L104's
`_turn_spans`, L653, L678) answer two questions and neither follows the other: a turnaround made in pieces or as a
slow wide curve splits the walk into two timed passes while turns.csv counts no turn of 80 deg."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from pdrlearn.track.clinical import turn_rows
from pdrlearn.track.walk_test import pass_rows, ten_metre_walk_trials

STRIDE_S = 1.1  # L678's stride: its rate threshold is 16.5 deg per stride


def _rows(t0: float, n: int, length: float, heading: float, turn_deg: float = 0.0) -> list[dict]:
    rows = []
    for i in range(n):
        heading += math.radians(turn_deg)
        rows.append({"start_s": t0 + i * STRIDE_S, "end_s": t0 + (i + 1) * STRIDE_S,
                     "event_s": t0 + (i + 1) * STRIDE_S, "length_m": length, "heading_rad": heading,
                     "turn_angle_rad": math.radians(turn_deg), "unit": "foot"})
    return rows


def _walk(middle) -> pd.DataFrame:
    """14 m out (1.4 m strides), the turnaround ``middle(t0, heading)`` gives, 14 m back."""
    rows = _rows(3.0, 10, 1.4, 0.0)
    rows += middle(rows[-1]["end_s"], rows[-1]["heading_rad"])
    rows += _rows(rows[-1]["end_s"], 10, 1.4, rows[-1]["heading_rad"])
    return pd.DataFrame(rows)


def _three_pivots(t0: float, h: float) -> list[dict]:
    """Three 60 deg pivots on the spot, a walking stride between each (L653: each stride ends its turn)."""
    rows = []
    for k in range(3):
        rows += _rows(t0, 1, 0.15, h, 60.0)
        t0, h = rows[-1]["end_s"], rows[-1]["heading_rad"]
        if k < 2:
            rows += _rows(t0, 1, 1.4, h)
            t0 = rows[-1]["end_s"]
    return rows


def _wide_curve(t0: float, h: float) -> list[dict]:
    """A 180 deg curve in strides of 16 deg (L79's 15 deg or more; 14.5 deg/s, under L678's rate)."""
    rows = _rows(t0, 11, 1.4, h, 16.0)
    rows += _rows(rows[-1]["end_s"], 1, 1.4, rows[-1]["heading_rad"], 4.0)
    return rows


@pytest.mark.parametrize("middle", [_three_pivots, _wide_curve])
def test_a_turnaround_turns_csv_does_not_count_still_ends_a_pass_c188(middle):
    steps = _walk(middle)
    angles, _ = turn_rows(steps)
    assert not (abs(angles) >= 80.0).any()  # turns.csv: no turn of 80 deg (L653 / L678), turn_count 0
    passes = pass_rows(steps, 0, len(steps))
    assert len(passes) == 2  # L673: the heading came round 180 deg between two straight stretches
    trials = ten_metre_walk_trials(steps, (2.0, 8.0, 2.0))
    assert trials["speed_mps"].tolist() == pytest.approx([1.4 / STRIDE_S] * 2)  # both passes timed


def test_a_turn_on_the_spot_is_one_turn_and_one_pass_boundary_in_both_c188():
    def spot(t0: float, h: float) -> list[dict]:
        return _rows(t0, 3, 0.15, h, 60.0)

    steps = _walk(spot)
    angles, _ = turn_rows(steps)
    assert list(abs(angles) >= 80.0).count(True) == 1
    assert len(pass_rows(steps, 0, len(steps))) == 2
