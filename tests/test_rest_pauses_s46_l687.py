"""Decision L687: a foot + lower-back track judges the foot's intervals against the lower back's stride (two of its
median contact intervals), so a rest on every stair of a step-to flight is a pause and the cadence the walking
strides'. Trial T1 (user 4615): 0 pauses and 43 steps/min for 16 rests and ~86 steps/min; the lower back alone
found the 16."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track import trunk_pauses as tp
from pdrlearn.track.clinical import pauses
from pdrlearn.track.gait import trimmed_gait_summary
from pdrlearn.track.stair_flights import flight_spans


def _walk():
    """A foot table as T1's: 3 level strides of 1.4 s, 8 step-to strides up and 8 down each with a ~1.65 s rest
    (3.05 s from row to row, +-0.17 m), 3 level strides; and the lower back's contacts, a step every 0.7 s while
    walking, none during the rests."""
    start, dz = [], []
    t = 0.0
    for k in range(22):
        stair = 3 <= k < 19
        start.append(t)
        dz.append(0.0 if not stair else (0.17 if k < 11 else -0.17))
        t += 3.05 if 2 <= k < 19 else 1.4
    start = np.asarray(start)
    end = start + 1.4
    event = start + 1.1
    stride = np.r_[np.nan, np.diff(event)]
    steps = pd.DataFrame({"start_s": start, "end_s": end, "event_s": event, "length_m": 0.84, "heading_rad": 0.0,
                          "dz_m": dz, "stride_time_s": stride, "cadence_spm": 120.0 / stride,
                          "speed_mps": 0.84 / stride, "turn_angle_rad": 0.0, "gap_s": 0.0, "unit": "foot"})
    trunk = np.concatenate([np.arange(s, s + 1.4, 0.7) for s in start])
    return steps, trunk


def test_the_rests_are_the_pauses_with_the_lower_back_l687():
    steps, trunk = _walk()
    assert len(pauses(steps)) == 0  # the foot alone: L605's slow rhythm takes the 3 s strides for the walker's
    col = tp.trunk_pause_seconds(steps, trunk)
    assert (col > 0).sum() == 17 and col.max() == pytest.approx(3.05 - 1.4)  # 3.05 s less two 0.7 s steps
    with_col = steps.assign(**{tp.COLUMN: col})
    assert len(pauses(with_col)) == 17
    assert trimmed_gait_summary(steps)["median_cadence_spm"] < 60.0  # the rests in the cadence
    assert trimmed_gait_summary(with_col)["median_cadence_spm"] == pytest.approx(120.0 / 1.4)


def test_a_continuous_walk_has_no_pause_l687():
    """A steady walk (1.4 s strides, the lower back stepping every 0.7 s): no pause, the cadence unchanged."""
    steps, _ = _walk()
    steps = steps.assign(dz_m=0.0, start_s=np.arange(22) * 1.4, end_s=np.arange(22) * 1.4 + 1.4)
    trunk = np.arange(0.0, 30.8, 0.7)
    col = tp.trunk_pause_seconds(steps, trunk)
    assert not col.any() and len(pauses(steps.assign(**{tp.COLUMN: col}))) == 0


def test_a_rest_on_a_stair_ends_no_flight_l687():
    steps, trunk = _walk()
    with_col = steps.assign(**{tp.COLUMN: tp.trunk_pause_seconds(steps, trunk)})
    assert flight_spans(with_col) == flight_spans(steps) == [(3, 11, 1), (11, 19, -1)]


def test_the_track_adds_the_column_from_the_trunk_contacts_l687():
    from types import SimpleNamespace

    steps, trunk = _walk()
    res = SimpleNamespace(steps=steps.copy(), info={"trunk_contacts": [{"start_s": t, "end_s": t + 0.7,
                                                                         "event_s": t} for t in trunk]})
    tp.add_trunk_pauses(res)
    assert tp.COLUMN in res.steps and (res.steps[tp.COLUMN] > 0).sum() == 17
    assert list(res.steps.columns).index(tp.COLUMN) == list(res.steps.columns).index("gap_s") - 1
    alone = SimpleNamespace(steps=steps.copy(), info={})
    tp.add_trunk_pauses(alone)  # no lower-back unit: nothing changes
    assert tp.COLUMN not in alone.steps


def test_spurious_lower_back_contacts_leave_the_foots_rule_l687():
    """L605's slow walker (5 s strides) whose lower back counts contacts every 0.3 s: its 0.6 s "stride" is under
    half the foot's shortest strides, so no column - the foot's own rule (no pause) stays (the second rule)."""
    steps, _ = _walk()
    start = np.arange(10) * 5.0
    slow = pd.DataFrame({"start_s": start, "end_s": start + 3.5, "event_s": start + 3.0, "length_m": 0.9,
                         "heading_rad": 0.0, "dz_m": 0.0, "stride_time_s": np.r_[np.nan, np.full(9, 5.0)],
                         "cadence_spm": 24.0, "speed_mps": 0.18, "turn_angle_rad": 0.0, "gap_s": 0.0, "unit": "foot"})
    assert tp.trunk_pause_seconds(slow, np.arange(0.0, 50.0, 0.3)) is None


def test_missed_lower_back_contacts_fall_back_on_the_foots_windows_l687():
    """A lower back that misses contacts (median interval 1.0 s for 0.7 s steps): the foot's 1.4 s rest-to-rest
    windows bound the stride, so a 2.85 s interval still holds a pause (u14247's descent)."""
    steps, trunk = _walk()
    sparse = np.concatenate([trunk[::2], trunk[::2] + 1.0])
    col = tp.trunk_pause_seconds(steps, np.sort(sparse))
    assert (col > 0).sum() == 17 and col.max() == pytest.approx(3.05 - 1.4)
