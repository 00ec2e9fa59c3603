"""Session 47, trial T1 F5: a declared walkway (``track --ten-m-walk``) tracked at most 2 % short with its timed
stretch's end mark passed is timed (decision C193); a declared test that is not timed says so on the console and in
clinical.md (decision C194)."""

from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli.common import transfer_line
from pdrlearn.report.clinical import clinical_lines
from pdrlearn.track.walk_test import DECLARED_SHORT_SHARE, ten_metre_walk, ten_metre_walk_trials


def _walk(metres: float, stride_m: float = 0.83, stride_s: float = 0.8) -> pd.DataFrame:
    """Straight strides of ``stride_m`` at ``stride_s`` from 3 s, the last one shortened to end at ``metres``."""
    rows, done, t = [], 0.0, 3.0
    while done < metres - 1e-9:
        m = min(stride_m, metres - done)
        rows.append({"start_s": t, "end_s": t + stride_s, "event_s": t + stride_s, "length_m": m, "heading_rad": 0.0})
        done, t = done + m, t + stride_s
    return pd.DataFrame(rows)


def test_a_declared_walkway_tracked_a_little_short_is_timed_c193():
    got = ten_metre_walk(_walk(9.96), (2.0, 6.0, 2.0))  # trial T1: 9.96 m for a 10 m walkway
    assert got["ten_m_walk_speed_mps"] == pytest.approx(0.83 / 0.8)
    assert "0.04 m short of the 10 m walkway" in got["ten_m_walk_note"] and "C193" in got["ten_m_walk_note"]
    assert "passed by 1.96 m" in got["ten_m_walk_note"]
    assert len(ten_metre_walk_trials(_walk(9.96), (2.0, 6.0, 2.0))) == 1  # a trial of ten_m_walk_trials.csv too
    edge = 10.0 * (1.0 - DECLARED_SHORT_SHARE)
    assert ten_metre_walk(_walk(edge + 0.001), (2.0, 6.0, 2.0))["ten_m_walk_time_s"] is not None
    short = ten_metre_walk(_walk(edge - 0.01), (2.0, 6.0, 2.0))  # over 2 % short: L349's refusal as before
    assert short["ten_m_walk_time_s"] is None and "decision L349" in short["ten_m_walk_note"]
    assert ten_metre_walk(_walk(9.6), (2.0, 6.0, 2.0))["ten_m_walk_time_s"] is None
    # the timed stretch's end mark must be passed: on a 2,6,0.1 walkway (8.1 m) 8.05 m passes 8 m and is timed,
    # 7.98 m is 1.5 % short too but stops before the 8 m mark
    assert ten_metre_walk(_walk(8.05), (2.0, 6.0, 0.1))["ten_m_walk_time_s"] is not None
    assert ten_metre_walk(_walk(7.98), (2.0, 6.0, 0.1))["ten_m_walk_time_s"] is None


def test_free_walking_keeps_l349s_refusal_c193():
    free = ten_metre_walk(_walk(13.9))  # no --ten-m-walk: 14 m, 0.7 % short
    assert free["ten_m_walk_time_s"] is None and "decision L349" in free["ten_m_walk_note"]
    assert ten_metre_walk(_walk(13.9), (2.0, 10.0, 2.0))["ten_m_walk_time_s"] is not None


def test_a_declared_test_not_timed_says_so_on_the_console_and_in_clinical_md_c194(tmp_path: Path):
    refused = ten_metre_walk(_walk(9.6), (2.0, 6.0, 2.0))
    summary = {"pipeline": "plasys", "gait_speed_mps": 0.92, **refused}
    line = transfer_line(summary)
    assert line.startswith("10 m walk test not timed (the middle 6 m of a 10 m walkway): no walking bout of 10 m")
    assert "decision L349" in line
    lines = clinical_lines(summary, tmp_path)
    walk = [x for x in lines if x.startswith("- 10 m walk")]
    assert len(walk) == 1 and walk[0].startswith("- 10 m walk: not timed (the middle 6 m of a 10 m walkway; ")
    assert "no walking bout of 10 m" in walk[0]
    assert lines.index(walk[0]) < next(i for i, x in enumerate(lines) if "ait speed" in x)  # before the speed
    free = {**summary, "ten_m_walk_declared": False}  # found in free walking: no test was declared (L679)
    assert transfer_line(free) is None and not [x for x in clinical_lines(free, tmp_path) if "10 m walk" in x]
