"""Decision L434 (session 35, trial T3 finding 4): the timed 25-foot walk and the 10 m walk test are level-walkway
tests; a span holding a stair stride is not timed, and the note names the stairs."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.walk_test import t25fw, ten_metre_walk


def _walk(dz) -> pd.DataFrame:
    n = len(dz)
    start = np.arange(n, dtype=float)
    return pd.DataFrame({"start_s": start, "end_s": start + 1.0, "event_s": start + 0.8,
                         "length_m": np.where(np.abs(dz) > 0, 0.6, 1.3), "heading_rad": 0.0, "dz_m": dz,
                         "gap_s": 0.0, "unit": "foot"})


def test_a_level_walk_is_timed_and_one_with_stairs_is_not_l434():
    level = _walk(np.zeros(20))
    assert t25fw(level)["t25fw_time_s"] is not None and t25fw(level)["t25fw_note"] is None
    assert ten_metre_walk(level)["ten_m_walk_time_s"] is not None
    stairs = _walk(np.r_[np.zeros(3), np.full(6, 0.34), np.zeros(12)])  # 3 m level, then a flight up (T3's 8390)
    for out, key in ((t25fw(stairs), "t25fw"), (ten_metre_walk(stairs), "ten_m_walk")):
        assert out[f"{key}_time_s"] is None and out[f"{key}_speed_mps"] is None
        assert "stair stride" in out[f"{key}_note"] and "L434" in out[f"{key}_note"]
    # stairs after the timed span leave the test timed: 6 level strides are 7.8 m
    late = _walk(np.r_[np.zeros(6), np.full(6, -0.34)])
    assert t25fw(late)["t25fw_time_s"] is not None
