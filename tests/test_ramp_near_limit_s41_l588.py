"""Session 41, fixer FP (trial T4 findings 1 and 4): ``near_limit`` in ramps.csv / ramp_runs.csv and the console's
"near the limit" for a grade within 1 point of 1:12 / 1:20 or a run's rise within 0.07 m of 0.76 m (L588)."""

from __future__ import annotations

import pandas as pd

from pdrlearn.track.ramp_audit import FLAG_COLUMNS, audit_flags, near_limit, ramps_line


def test_near_limit_kernel_l588():
    assert near_limit(9.23, 0.7586) is True  # T4: a true 1:12 run read one stride short
    assert near_limit(-7.4, 0.5) is True and near_limit(4.2, 0.1) is True  # within a point of 8.33 / 5 %
    assert near_limit(12.0, 0.5) is False and near_limit(6.5, 0.2) is False and near_limit(2.0, 0.1) is False
    assert near_limit(12.0, -0.818) is True and near_limit(12.0, 0.70) is True and near_limit(12.0, 0.68) is False
    assert near_limit(float("nan"), None) is None and near_limit(None, 0.70) is True
    assert audit_flags(9.23, 0.7586) == {"over_1_12": True, "over_1_20": True, "run_rise_over_0_76": False,
                                         "near_limit": True}
    assert "near_limit" in FLAG_COLUMNS


def test_the_console_line_says_near_the_limit_l588():
    ramps = pd.DataFrame({"max_run_grade_pct": [9.23, 12.0], "rise_m": [1.5, 0.4], "over_1_12": [True, True],
                          "near_limit": [True, False]})
    assert ramps_line(ramps) == ("ramps 2 (steepest 12.0 %, rise +0.40 m; 2 over 1:12; 1 near the limit: measure "
                                 "it; ramps.csv)")
    assert "near" not in ramps_line(ramps.assign(near_limit=False))
