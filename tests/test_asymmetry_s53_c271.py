"""Session 53 (FE, trial s53t1): C271 - a foot + lower-back step-time asymmetry and its visit change carry their
standard error and an "uncertain" flag (summary / sessions.csv, changes.csv, changes_summary.csv, the printed
change); C272 - a 14 m walk tracked a few cm short without ``--ten-m-walk`` names ``2,10,2``; L802 - L414's
stance-bias line comes with L285's "under 55 %" line."""

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.labelled_asymmetry import asymmetry_uncertain, side_keys
from pdrlearn.visits import change_summary, change_table, changes_text


def test_index_uncertain_when_its_standard_error_is_comparable_or_over_3_points_c271():
    assert asymmetry_uncertain(24.9, 15.95) is True  # trial s53t1 P19900 w02: within noise and over 3 points
    assert asymmetry_uncertain(5.0, 2.9) is True  # within noise (under 1.96 x 2.9)
    assert asymmetry_uncertain(4.0, 3.5) is True  # over 3 points
    assert asymmetry_uncertain(20.0, 2.0) is False
    assert asymmetry_uncertain(None, 2.0) is None and asymmetry_uncertain(10.0, float("nan")) is None
    res = {"step_time_asymmetry_pct": 24.9, "standard_error_points": 15.95, "step_time_s_instrumented": 0.8,
           "step_time_s_other": 0.64}
    keys = side_keys(res, type("S", (), {"meta": {}})())
    assert keys["step_time_asymmetry_uncertain"] is True and keys["step_time_asymmetry_se_points"] == 15.95


def _sessions(with_se: bool = True) -> pd.DataFrame:
    rows = []
    #            subject, visit, index, se
    for s, v, pct, se in (("P1", "w02", 24.9, 15.95), ("P1", "w06", 16.5, 11.43), ("P2", "w02", 14.0, 1.0),
                          ("P2", "w06", 6.0, 1.2), ("P3", "w02", 5.1, 7.04), ("P3", "w06", 27.2, 15.38)):
        rows.append({"path": f"{s}/{v}", "subject": s, "visit": v, "group": "g", "status": "ok",
                     "pipeline": "plasys", "step_time_asymmetry_pct": pct,
                     **({"step_time_asymmetry_se_points": se} if with_se else {})})
    return pd.DataFrame(rows)


def test_changes_carry_the_standard_error_and_the_flag_c271():
    ch = change_table(_sessions(), metrics=("step_time_asymmetry_pct",)).set_index("subject")
    assert ch.loc["P1", "step_time_asymmetry_pct_change_se"] == pytest.approx(math.hypot(15.95, 11.43))
    assert ch.loc["P1", "step_time_asymmetry_pct_change_uncertain"] == True  # noqa: E712 - -8.4 with 19.6 points
    assert ch.loc["P2", "step_time_asymmetry_pct_change_uncertain"] == False  # noqa: E712 - -8.0 with 1.56 points
    assert ch.loc["P3", "step_time_asymmetry_pct_change_uncertain"] == True  # noqa: E712 - +22.1 with 16.9 points
    summary = change_summary(ch.reset_index())
    row = summary[summary["measure"] == "step_time_asymmetry_pct"].iloc[0]
    assert row["n_uncertain"] == 2 and row["n_subjects"] == 3
    text = changes_text(summary)
    assert "2 of 3 uncertain" in text["mean change [95 % CI]"].iloc[0] and "C271" in text.iloc[0, 3]
    # a changes.csv without a standard error column has no new column and no note
    plain = change_table(_sessions(with_se=False), metrics=("step_time_asymmetry_pct",))
    assert not [c for c in plain.columns if c.endswith(("_change_se", "_change_uncertain"))]
    assert "uncertain" not in changes_text(change_summary(plain))["mean change [95 % CI]"].iloc[0]


def test_short_14m_walk_names_2_10_2_c272():
    from pdrlearn.track.walk_test import ten_metre_walk

    strides = [{"start_s": 3.0 + i, "end_s": 4.0 + i, "event_s": 4.0 + i, "length_m": 0.7, "heading_rad": 0.0}
               for i in range(20)]
    strides[-1]["length_m"] = 0.68  # 13.98 m: a 14 m walkway walked end to end, tracked 2 cm short
    steps = pd.DataFrame(strides)
    got = ten_metre_walk(steps)
    assert got["ten_m_walk_time_s"] is None
    assert "track --ten-m-walk 2,10,2 times a pass tracked up to 2 % short" in got["ten_m_walk_note"]
    assert ten_metre_walk(steps, (2.0, 10.0, 2.0))["ten_m_walk_time_s"] is not None  # C193: declared, timed
    assert "2,10,2" not in ten_metre_walk(steps, (2.0, 10.5, 2.0))["ten_m_walk_note"]  # declared: as before


def _summary(stance_s: float, l285: bool) -> dict:
    from pdrlearn.warning_lines import coded

    line = coded("toe-off: median stance 50.9 % of the gait cycle of the right foot over 18 strides, under 55 % "
                 "(walking: ~60 %, more when slower; decisions L285, L315): ...", "L285")
    return {"median_stance_time_s": stance_s, "median_stance_pct": 50.9, "median_stride_time_s": 1.46,
            "rate_hz": 100.0, "info": {"warnings": [line] if l285 else []}}


def test_l285_line_brings_the_bias_line_l802():
    from pdrlearn.track.toeoff import stance_range_warning
    from pdrlearn.warning_lines import warning_code

    assert stance_range_warning(_summary(0.735, l285=False)) is None  # L414 alone: a checked stance length
    line = stance_range_warning(_summary(0.735, l285=True))
    assert line is not None and warning_code(line) == "L802"
    assert "50.9 % of the gait cycle, is under 55 %" in line and "percentage points of stance" in line
    assert "below 0.69 s" in stance_range_warning(_summary(0.60, l285=True))  # L414's own line under 0.69 s
    # the summary read back from summary.json: a plain string is recognised by its decision
    plain = _summary(0.735, l285=True)
    plain["info"]["warnings"] = [str(w) for w in plain["info"]["warnings"]]
    assert np.char.find(stance_range_warning(plain), "L802") >= 0
