"""Decision C263 (session 52, FB, review s52r1 F3): a group, subject or visit named "NA" (or null, None, nan) is a
name, not a missing value: `pdrlearn report` on a `track-all --repeated` folder with a group folder "NA" crashed
("TypeError: sequence item 0: expected str instance, float found"). Kernel level, a hand-written sessions.csv."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cohort import group_table, joined_labels
from pdrlearn.io.plasys import read_table
from pdrlearn.report.batch import batch_tables, pooled_table, read_batch, subject_tables


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    d = tmp_path_factory.mktemp("c263")
    sessions = pd.DataFrame({
        "path": ["NA/p1/shift1", "NA/p1/shift2", "EU/NA/shift1", "EU/p3/shift1"], "group": ["NA", "NA", "EU", "EU"],
        "status": ["ok"] * 4, "error": [""] * 4, "subject": ["p1", "p1", "NA", "p3"],
        "visit": ["shift1", "shift2", "shift1", "shift1"], "time_span_s": [3600, 7200, 3600, 3600],
        "time_no_data_s": [0, 0, 0, 0], "n_steps_both_feet": [1000, 3000, 500, 700], "distance_m": [100, 200, 50, 70]})
    sessions.to_csv(d / "sessions.csv", index=False)
    group_table(sessions).to_csv(d / "groups.csv", index=False)  # as track-all writes it, from the in-memory text
    return d


def test_a_group_and_a_subject_named_na_are_reported_c263(batch):
    sessions, groups = read_batch(batch)
    assert list(sessions["group"]) == ["NA", "NA", "EU", "EU"] and sorted(groups["group"]) == ["EU", "NA"]
    assert list(sessions["subject"]) == ["p1", "p1", "NA", "p3"]
    pooled = pooled_table(sessions)[0][1].set_index("subject")
    assert pooled.loc["p1", "group"] == "NA" and pooled.loc["NA", "group"] == "EU"
    assert pooled.loc["p1", "distance_m_per_h"] == pytest.approx(100.0)  # (100 + 200) m over 3 h
    totals = subject_tables(sessions)[0][1]
    assert set(totals["subject"]) == {"p1", "NA", "p3"} and set(totals["group"]) == {"NA", "EU"}
    text, tables = batch_tables(sessions, groups, repeated=True)
    assert "4 of 4 sessions tracked" in text and any("repeated sessions pooled" in name for name, _ in tables)


def test_label_cells_as_written_only_an_empty_one_missing_c263(tmp_path):
    (tmp_path / "t.csv").write_text("group,subject,x\nNA,null,1.5\nNone,nan,\n,007,2\n")
    t = read_table(tmp_path / "t.csv", text_columns=("group", "subject"))
    assert list(t["group"][:2]) == ["NA", "None"] and pd.isna(t["group"][2])
    assert list(t["subject"]) == ["null", "nan", "007"]
    assert t["x"].dtype.kind == "f" and np.isnan(t["x"][1])  # the other columns as before
    assert joined_labels(pd.Series(["NA", np.nan, "NA", "EU"])) == "NA; ; EU"
