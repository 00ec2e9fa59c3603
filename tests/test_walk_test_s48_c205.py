"""Session 48, trial T2 finding F7: a calibrated lower back's walkway pass tracked short is refused with what to do
(decision C205, measured: no wider tolerance adopted; C193's 2 % applies to it as to a foot track)."""

import pandas as pd

from pdrlearn.track.walk_test import (
    DECLARED_SHORT_SHARE,
    DECLARED_SHORT_SHARE_LOWER_BACK,
    declared_short_share,
    ten_metre_walk,
)


def _walk(metres: float, unit: str, step_m: float = 0.5, step_s: float = 0.5) -> pd.DataFrame:
    """Straight steps of ``step_m`` from 3 s on the ``unit``, the last one shortened to end at ``metres``."""
    rows, done, t = [], 0.0, 3.0
    while done < metres - 1e-9:
        m = min(step_m, metres - done)
        rows.append({"start_s": t, "end_s": t + step_s, "event_s": t, "length_m": m, "heading_rad": 0.0,
                     "unit": unit})
        done, t = done + m, t + step_s
    return pd.DataFrame(rows)


def test_a_calibrated_lower_back_pass_tracked_short_says_what_to_do_c205():
    got = ten_metre_walk(_walk(9.48, "waist"), (2.0, 6.0, 2.0), calibrated=True)  # T2: 0.51 m short
    assert got["ten_m_walk_time_s"] is None
    note = got["ten_m_walk_note"]
    assert "decision C205" in note and "1 m beyond the walkway's ends" in note and "foot unit" in note
    foot = ten_metre_walk(_walk(9.48, "foot"), (2.0, 6.0, 2.0))
    assert foot["ten_m_walk_time_s"] is None and "C205" not in foot["ten_m_walk_note"]
    free = ten_metre_walk(_walk(13.5, "waist"), None, calibrated=True)  # no declared walkway: L349's note only
    assert "C205" not in free["ten_m_walk_note"]


def test_the_lower_back_keeps_c193s_share_c205():
    assert DECLARED_SHORT_SHARE_LOWER_BACK is None  # measured, not adopted
    assert declared_short_share(_walk(9.9, "waist"), (2.0, 6.0, 2.0), True) == DECLARED_SHORT_SHARE
    assert declared_short_share(_walk(9.9, "waist"), None, True) == 0.0
    got = ten_metre_walk(_walk(9.9, "waist"), (2.0, 6.0, 2.0), calibrated=True)  # 1 % short: C193 times it
    assert got["ten_m_walk_time_s"] is not None and "within 2 %" in got["ten_m_walk_note"]
