"""Decision W403: a turn belongs to one bout. A yaw-rate turn (L210) whose steps fall into two step-heading spans (a
pause between them, where bouts.csv starts a new bout) was written twice to turns.csv, once per span and bout, with
the same times and angle (trial T2 finding 5: 23.47-26.43 s, 180.05 deg, in bout 1 and bout 2; turn_count 5 against
bouts' n_turns summing to 4). Now the first span's row takes it, in its bout, with both spans' rows."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.clinical import turn_table


def _walk():
    t = np.arange(20.0, 30.0, 0.5)
    dh = np.zeros(len(t) - 1)
    dh[5:9] = 30.0  # 120 deg, 22.5-24.5 s
    dh[11:13] = 30.0  # 60 deg more after two still intervals (the bout boundary), 25.5-26.5 s
    heading = np.radians(np.r_[0.0, np.cumsum(dh)])
    steps = pd.DataFrame({"start_s": t, "end_s": t + 1.5, "heading_rad": heading, "length_m": 0.6})
    yaw = [{"start_s": 22.4, "end_s": 26.6, "peak_s": 25.7, "angle_deg": 180.0, "peak_dps": 60.0,
            "start_5_s": 22.6, "end_95_s": 26.4}]
    bouts = pd.DataFrame({"bout": [1, 2], "start_s": [20.0, 25.0], "end_s": [24.9, 30.0]})
    return steps, yaw, bouts


def test_a_turn_over_a_bout_boundary_is_one_row_in_one_bout():
    steps, yaw, bouts = _walk()
    table = turn_table(steps, bouts, yaw_turns=yaw)
    assert len(table) == 1  # main: two rows, 22.4-26.6 s, 180 deg, bouts 1 and 2
    row = table.iloc[0]
    assert row["angle_deg"] == 180.0 and row["bout"] == 1 and (row["start_s"], row["end_s"]) in ((22.4, 26.6),
                                                                                                  (22.6, 26.4))
    assert row["n_rows"] >= 6  # both spans' rows


def test_without_the_yaw_angle_the_spans_angles_add_up():
    steps, yaw, bouts = _walk()
    table = turn_table(steps, bouts, yaw_turns=yaw, yaw_angle=False)
    assert len(table) == 1 and table.iloc[0]["angle_deg"] >= 170.0
