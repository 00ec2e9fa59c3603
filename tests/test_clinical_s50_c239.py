"""Decision C239 (review R1 F4): a lower back's walk-test steps per minute are withheld, with why, when W331 could
not check its turns on the spot (summary ``turn_steps_missed`` None: fewer than 4 step gaps under 1.5 s) or the
summary has no such key; C232 had read None as 0 and given them."""

from __future__ import annotations

import pandas as pd

from pdrlearn.report.clinical import minute_steps_given, walk_test_pace_line
from pdrlearn.waist.turn_steps import stepless_summary


def test_a_shuffler_whose_turns_could_not_be_checked_gets_no_steps_per_minute(tmp_path):
    # the reviewer's reproducer (c232_none.py): a 37 steps/min shuffler, every step gap over W331's 1.5 s
    t = [5.0 + 1.6 * i for i in range(220)]
    pd.DataFrame({"start_s": t, "end_s": [x + 1.6 for x in t], "event_s": t, "length_m": 0.2,
                  "unit": "waist"}).to_csv(tmp_path / "steps.csv", index=False)
    w331 = stepless_summary(t, [{"start_s": 100.0, "end_s": 104.0, "angle_deg": 180.0}])
    assert w331["turn_steps_missed"] is None
    s = {"pipeline": "waist-pendulum", "walk_test_distance_m": 70.0, "walk_test_duration_s": 360.0,
         "walk_test_start_s": 5.0, "walk_test_distance_per_minute_m": [12.0] * 6, **w331}
    line = walk_test_pace_line(s, tmp_path)
    assert ("steps per minute not given: turns on the spot could not be checked (the walk has fewer than 4 step "
            "gaps under 1.5 s to judge them by; W331, C232, C239)") in line
    assert "38 / 37" not in line  # main gave "steps per minute 38 / 37 / 38 / 37 / 38 / 32"
    assert "decision" not in line  # W420: clinical.md names no research terms
    old = {k: v for k, v in s.items() if k != "turn_steps_missed"}  # a summary written before W331
    assert "could not be checked (the summary predates the check;" in walk_test_pace_line(old, tmp_path)
    assert "steps per minute 38 / 37 / 38 / 37 / 38 / 32" in walk_test_pace_line({**s, "pipeline": "plasys"},
                                                                                  tmp_path)  # a foot unit's
    assert "steps per minute 38 / 37" in walk_test_pace_line({**s, "turn_steps_missed": 0}, tmp_path)
    assert not minute_steps_given(True, None) and minute_steps_given(False, None) and minute_steps_given(True, 0)
