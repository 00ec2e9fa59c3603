"""Decision L766 (not adopted; ``trunk_pause_seconds(..., min_share=0.75)``, the default stays L687's 0.5): L687's
lower-back stride used only when it is at least 0.75 of the foot's 10th-percentile stride time. Trial s50t3 (F5): a
slow shuffler's lower back counted two contacts per 0.75 s step (median interval 0.38 s), so L687 judged the foot's
1.45 s strides against a 0.76 s "stride" and the 2 s interval across a 180 deg turn's small steps read as a pause
that split a 20 m walk into two bouts."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track import trunk_pauses as tp
from pdrlearn.track.bouts import bout_ranges


def _shuffle() -> pd.DataFrame:
    """A foot table as trial s50t3's 17402: 14 strides of 1.45 s, a turn's two strides, an interval of 2.0 s from
    the turn's last stride to the next (as 4582.37 -> 4584.39 s), 13 more strides of 1.45 s."""
    start = np.r_[np.arange(14) * 1.45, 14 * 1.45 + np.array([0.0, 1.5]), 14 * 1.45 + 3.5 + np.arange(13) * 1.45]
    end = start + 1.4
    event = start + 1.0
    stride = np.r_[np.nan, np.diff(event)]
    heading = np.r_[np.zeros(14), np.pi * 0.55, np.pi * 0.95, np.full(13, np.pi)]
    return pd.DataFrame({"start_s": start, "end_s": end, "event_s": event, "length_m": 0.45, "heading_rad": heading,
                         "dz_m": 0.0, "stride_time_s": stride, "cadence_spm": 120.0 / stride, "speed_mps": 0.3,
                         "turn_angle_rad": np.r_[0.0, np.diff(heading)], "gap_s": 0.0, "unit": "foot"})


def test_a_lower_back_counting_two_contacts_per_step_leaves_the_foots_rule_l766():
    steps = _shuffle()
    dense = np.arange(0.0, float(steps["end_s"].iloc[-1]), 0.38)  # ~2 contacts per 0.75 s step, as 17402's
    assert tp.trunk_pause_seconds(steps, dense, min_share=0.75) is None  # 0.76 s / 1.45 s = 0.52
    assert len(bout_ranges(steps)) == 1  # the foot's own rule: the turn ends no bout
    steps[tp.COLUMN] = tp.trunk_pause_seconds(steps, dense)  # L687's default 0.5 lets it through: the turn splits
    assert len(bout_ranges(steps)) == 2


def test_a_lower_back_counting_the_steps_still_judges_the_pauses_l766():
    steps = _shuffle()
    true = np.arange(0.0, float(steps["end_s"].iloc[-1]), 0.725)  # one contact per step
    col = tp.trunk_pause_seconds(steps, true, min_share=0.75)
    assert col is not None and not (col > 0).any()  # L687 still applies, and the turn's 2 s is no pause
    steps[tp.COLUMN] = col
    assert len(bout_ranges(steps)) == 1
