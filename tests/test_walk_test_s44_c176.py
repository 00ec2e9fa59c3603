"""Decision C176 (session 44, FF, trial T1 finding F2): a visit's measure that only some of its averaged sessions
have (a 6MWT beside a TUG that scores no walk test, L643) is their mean, and changes.csv's reason names it."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.visits import change_table


def test_a_walk_test_measure_from_one_of_a_visits_sessions_is_named_c176():
    sessions = pd.DataFrame({
        "path": ["P01/baseline/6mwt", "P01/baseline/tug", "P01/m3/6mwt", "P01/m3/tug"],
        "subject": "P01", "visit": ["baseline", "baseline", "m3", "m3"], "group": "MS", "status": "ok",
        "pipeline": "waist-pendulum", "walk_test_distance_m": [245.2, np.nan, 197.9, np.nan],
        "tug_time_s": [np.nan, 25.6, np.nan, 28.9]})
    c = change_table(sessions, metrics=["walk_test_distance_m", "tug_time_s"])
    row = c.iloc[0]
    assert row["walk_test_distance_m_baseline"] == pytest.approx(245.2)
    assert row["walk_test_distance_m_change"] == pytest.approx(-47.3)
    assert "baseline: walk_test_distance_m from 1 of 2 sessions (P01/baseline/6mwt; the others have none)" in \
        row["reason"]
    assert "m3: tug_time_s from 1 of 2 sessions (P01/m3/tug" in row["reason"]
