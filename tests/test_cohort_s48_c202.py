"""Decision C202 (session 48, fixer FI, trial T3 finding F5): ``track-all --group-by visit`` gives groups.csv one
row per visit (a condition: shoe A / B) across subjects - the visit changes.csv pairs, ``--visit-map`` applied -
where the folder groups pooled both conditions of each participant. The command itself (groups.csv per visit,
sessions.csv's folder group kept, the report reading them) is pinned in tests/test_conditions_c81.py's track-all run,
which tracks the sessions anyway."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli.cohort import _check_group_by
from pdrlearn.cohort import NO_VISIT_GROUP, group_table
from pdrlearn.errors import DataError


def _sessions(groups, visits, values, status=None):
    return pd.DataFrame({"group": groups, "visit": visits, "status": status or ["ok"] * len(groups),
                         "gait_speed_mps": values})


def test_group_table_by_visit_pools_subjects_per_visit_c202():
    s = _sessions(["P1", "P1", "P2", "P2", "P3"], ["baseline", "followup", "baseline", "followup", None],
                  [1.0, 1.2, 2.0, 1.4, 9.0], status=["ok", "ok", "ok", "ok", "failed"])
    g = group_table(s, by="visit")
    assert g["group"].tolist() == ["(no visit)", "baseline", "followup"] == sorted([NO_VISIT_GROUP, "baseline",
                                                                                      "followup"])
    row = g.set_index("group")
    assert row.loc["baseline", "gait_speed_mps_mean"] == pytest.approx(1.5)
    assert row.loc["followup", "gait_speed_mps_mean"] == pytest.approx(1.3)
    assert row.loc["baseline", "gait_speed_mps_n"] == 2 and row.loc[NO_VISIT_GROUP, "n_failed"] == 1
    assert group_table(s)["group"].tolist() == ["P1", "P2", "P3"]  # without it: the folders, as before


def test_group_by_visit_is_checked_before_tracking_c202(tmp_path):
    with pytest.raises(DataError, match="no session under .* names one"):
        _check_group_by("visit", [{}], tmp_path, [("P1", None)])
    with pytest.raises(DataError, match="--group-depth 2 by folder; give one of them"):
        _check_group_by("visit", [{}], tmp_path, [("P1", "A")], group_depth=2)
    with pytest.raises(DataError, match="--group-by shoe: not a choice; pass --group-by test .* or --group-by visit"):
        _check_group_by("shoe", [{}], tmp_path, [("P1", "A")])
    _check_group_by("visit", [{}], tmp_path, [("P1", "A")])  # accepted

