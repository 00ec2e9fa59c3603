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
    assert t25fw(late, any_recording=True)["t25fw_time_s"] is not None
    assert t25fw(late, walkway=True)["t25fw_time_s"] is not None  # decision L779: a declared walkway, as before
    assert t25fw(late)["t25fw_time_s"] is None  # L779: a recording with a flight is no walk-test recording


def test_one_drifting_stride_is_no_flight_and_the_walk_is_timed_l438():
    """Decision L438 (session 35, review R3 finding 4): on a level walk one stride over 0.10 m (gaitmap_level_right's
    +0.12 m drift) makes no stair flight and the 10 m walk and T25FW are still timed; two such strides in a row are a
    flight and the tests are not timed."""
    from pdrlearn.track.stair_flights import flight_table

    dz = np.zeros(20)
    dz[[4, 12]] = [0.123, 0.101]  # two lone drifting strides, as R3's gaitmap_level_right
    drift = _walk(dz)
    drift["length_m"] = 1.3
    assert len(flight_table(drift)) == 0
    assert ten_metre_walk(drift)["ten_m_walk_time_s"] is not None and t25fw(drift)["t25fw_time_s"] is not None
    dz[5] = 0.12  # strides 4 and 5: a run of two
    pair = _walk(dz)
    pair["length_m"] = 1.3
    pair.loc[[4, 5], "length_m"] = 0.4  # decision L443: a stair's grade (30 %); at 1.3 m (9 %) the pair is a ramp
    assert list(flight_table(pair)["n_strides"]) == [2]
    assert ten_metre_walk(pair)["ten_m_walk_time_s"] is None and "L438" in ten_metre_walk(pair)["ten_m_walk_note"]
