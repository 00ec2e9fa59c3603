"""Decision C211: the 10 m walk's change from baseline is named by its walkway ("7.62 m walk" for a flying 25-foot
walk) and not compared between visits on two walkways - in clinical.md's line and in changes.csv (review R1 F3)."""

from __future__ import annotations

import math

import pandas as pd

from pdrlearn.report.clinical import change_lines, walkway_reason
from pdrlearn.tables import summary_row
from pdrlearn.visits import change_table, walkway_why, walkways_differ

TEN, FLYING = [2.0, 10.0, 2.0], [1.0, 7.62, 3.38]
APART = "not compared: walkways differ (10 m / 7.62 m timed, docs/decisions/cohort.md C211)"


def _summary(visit: str, speed: float, zones) -> dict:
    return {"subject": "P1", "visit": visit, "ten_m_walk_time_s": 7.62 / speed, "ten_m_walk_speed_mps": speed,
            "ten_m_walk_zones_m": zones, "tug_time_s": 10.0 if visit == "1" else 9.0, "pipeline": "waist-pendulum"}


def _lines(zones_1, zones_2) -> list[str]:
    return change_lines([("track", f"P1_v{v}", f"a/P1_v{v}", _summary(v, s, z))
                         for v, s, z in (("1", 1.333, zones_1), ("2", 1.604, zones_2))])


def test_one_walkway_at_both_visits_is_named_by_it():
    (line,) = _lines(FLYING, FLYING)
    assert "7.62 m walk 1.33 -> 1.60 m/s (+0.27 m/s, +20 %)" in line and "10 m walk" not in line  # main: "10 m walk"
    (line,) = _lines(TEN, TEN)
    assert "10 m walk 1.33 -> 1.60 m/s" in line


def test_two_walkways_are_not_compared_and_said():
    (line,) = _lines(TEN, FLYING)
    assert f"10 m walk / 7.62 m walk {APART}" in line
    assert "1.33 -> 1.60" not in line and "TUG 10.0 -> 9.0 s" in line  # main paired the speeds without a word


def test_sessions_row_carries_the_walkway_and_changes_csv_does_not_pair_across_walkways():
    assert summary_row(_summary("2", 1.6, FLYING))["ten_m_walk_timed_m"] == 7.62
    assert summary_row({**_summary("1", 1.3, None), "ten_m_walk_zones_m": None})["ten_m_walk_timed_m"] == 10.0  # L312
    assert "ten_m_walk_timed_m" not in summary_row({"ten_m_walk_speed_mps": None})

    def sessions(zones_2):
        return pd.DataFrame([{"path": f"P1_v{v}", "group": "", "subject": "P1", "visit": v, "status": "ok",
                              "pipeline": "waist-pendulum", **summary_row(_summary(v, s, z))}
                             for v, s, z in (("1", 1.333, TEN), ("2", 1.604, zones_2))])

    apart = change_table(sessions(FLYING)).iloc[0]
    assert math.isnan(apart["ten_m_walk_speed_mps_change"]) and apart["tug_time_s_change"] == -1.0
    assert f"ten_m_walk_speed_mps {APART}" in apart["reason"]
    same = change_table(sessions(TEN)).iloc[0]
    assert round(same["ten_m_walk_speed_mps_change"], 3) == 0.271 and not same["reason"]


def test_two_visits_mixing_the_same_walkways_say_so():
    """Review R2 F5: both visits timed on the same two walkways are mixed within a visit, not "walkways differ"."""
    b = pd.DataFrame({"ten_m_walk_speed_mps": [1.1, 1.2], "ten_m_walk_timed_m": [10.0, 7.62]})
    v = pd.DataFrame({"ten_m_walk_speed_mps": [1.2, 1.3], "ten_m_walk_timed_m": [10.0, 7.62]})
    mixed = walkways_differ(b, v, "ten_m_walk_speed_mps")
    assert walkway_why(mixed) == "mixed walkways within a visit"  # main: walkways differ
    assert walkway_why("10 m / 7.62 m") == walkway_why("10 m / 7.62 m+10 m") == "walkways differ"
    reason = f"tug_time_s x; ten_m_walk_speed_mps not compared: mixed walkways within a visit ({mixed} timed, C211)"
    assert walkway_reason(reason, "ten_m_walk_speed_mps") == f"mixed walkways within a visit ({mixed} timed, C211)"
