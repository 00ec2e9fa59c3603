"""Decision L678 (trial T1, finding F3): a foot table's turn rate is judged per stride of the walker's own rhythm -
``TURN_RATE_MIN_DPS`` x min(1, 1.1 s / rhythm) - so a rollator walker turning ~28 deg per 2 s stride (14 deg/s,
under L104's 15 deg/s) turns; a healthy walker's threshold and a slow walker's gentle curve are unchanged."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.clinical import TURN_RATE_MIN_DPS, TURN_RATE_STRIDE_S, turn_rate_threshold, turn_table


def _table(turn_deg, stride_s, length_m=0.6):
    n = len(turn_deg)
    start = np.arange(n) * stride_s
    length = np.where(np.abs(turn_deg) > 5, 0.15, length_m)  # the pivot's small strides (L653: no walking row)
    return pd.DataFrame({"start_s": start, "end_s": start + 0.9 * stride_s, "length_m": length,
                         "raw_length_m": length, "heading_rad": np.radians(np.cumsum(turn_deg)),
                         "turn_angle_rad": np.radians(turn_deg), "gap_s": 0.0, "sideways": False, "unit": "foot"})


def test_a_slow_pivot_in_small_strides_is_a_turn():
    # 2.0 s strides, 4 strides of 28 deg (14 deg/s each): main read no turn
    st = _table([0.0] * 6 + [28.0] * 4 + [0.0] * 6, 2.0)
    assert turn_rate_threshold(st) == pytest.approx(TURN_RATE_MIN_DPS * TURN_RATE_STRIDE_S / 2.0)
    assert np.round(turn_table(st)["angle_deg"].to_numpy(float)).tolist() == [112.0]


def test_a_healthy_walkers_threshold_is_unchanged():
    # 1.0 s strides: a gentle curve of 12 deg per stride (12 deg/s) over 8 strides is no turn, as before
    st = _table([0.0] * 6 + [12.0] * 8 + [0.0] * 6, 1.0, length_m=1.3)
    assert turn_rate_threshold(st) == TURN_RATE_MIN_DPS
    assert len(turn_table(st)) == 0


def test_a_slow_walkers_gentle_curve_is_no_turn():
    # 2.0 s strides of 0.6 m on a ~5 m radius: 7 deg per stride (3.5 deg/s) over 15 strides, 105 deg in all
    st = _table([0.0] * 6 + [7.0] * 15 + [0.0] * 6, 2.0)
    st["length_m"] = st["raw_length_m"] = 0.6
    assert len(turn_table(st)) == 0


def test_the_lower_back_threshold_is_unchanged():
    st = _table([0.0] * 6 + [14.0] * 8 + [0.0] * 6, 1.0)
    st["unit"] = "waist"
    assert turn_rate_threshold(st) == TURN_RATE_MIN_DPS
