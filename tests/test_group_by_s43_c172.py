"""Decision C172 (session 43, fixer FK, review R2 findings 2 and 3): the report's pooled-strides table shows the
``test`` column the walking-totals table has (C171), so a subject's rows per test can be told apart. (C172's warning
that changes.csv averaged a visit's tests under ``--group-by test`` went with decision C174, which pairs each test
on its own: tests/test_changes_by_test_s44_c174.py.)"""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.report.batch import pooled_subject_table


def test_pooled_strides_table_has_the_test_column(tmp_path):
    subjects = pd.DataFrame({"subject": ["A", "A"], "visit": ["1", "1"], "test": ["Test5", "Test11"],
                             "pooled_n_sessions": [1, 1], "pooled_n_strides": [8, 9]})
    subjects.to_csv(tmp_path / "subjects.csv", index=False)
    (tmp_path / "run.json").write_text(json.dumps({"options": {"group_by": "test"}}))
    [(title, table)] = pooled_subject_table(tmp_path)
    assert title.startswith("per subject, visit and test:")
    assert table["test"].tolist() == ["Test5", "Test11"]
    (tmp_path / "run.json").write_text(json.dumps({"options": {"group_by": None}}))  # a run without --group-by
    [(title, table)] = pooled_subject_table(tmp_path)
    assert title.startswith("per subject and visit:") and "test" not in table.columns
