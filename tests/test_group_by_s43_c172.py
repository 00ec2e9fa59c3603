"""Decision C172 (session 43, fixer FK, review R2 findings 2 and 3): with ``track-all --group-by test``, changes.csv
still pairs a subject's visits over all its tests (C83 averages a visit's sessions): said once, naming the
subject-visits whose sessions span several tests; the report's pooled-strides table shows the ``test`` column the
walking-totals table has (C171), so a subject's rows per test can be told apart."""

from __future__ import annotations

import json
import logging

import pandas as pd

from pdrlearn.cli.cohort import _paired_tests_warning
from pdrlearn.report.batch import pooled_subject_table


def _sessions(tests_a1):
    rows = [("A1_T5", "A", "1", tests_a1[0]), ("A1_T11", "A", "1", tests_a1[1]), ("A2_T5", "A", "2", "Test5"),
            ("B1_T5", "B", "1", "Test5"), ("B2_T5", "B", "2", "Test5")]
    return pd.DataFrame(rows, columns=["path", "subject", "visit", "test"])


def test_a_visit_of_several_tests_is_said(caplog):
    with caplog.at_level(logging.WARNING, logger="pdrlearn.cli"):
        _paired_tests_warning(_sessions(("Test5", "Test11")), "test")
    lines = [r.getMessage() for r in caplog.records]
    assert len(lines) == 1 and "1 subject-visit(s) span several (A visit 1 (Test5, Test11))" in lines[0]
    assert "changes.csv pairs each subject's visits" in lines[0] and "(decision C172)" in lines[0]
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn.cli"):  # one test per visit: nothing to say
        _paired_tests_warning(_sessions(("Test5", "Test5")), "test")
    assert not caplog.records


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
