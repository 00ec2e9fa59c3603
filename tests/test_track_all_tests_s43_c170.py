"""Decisions C170, C171 (session 43, fixer FF, trial T1 finding F5): track-all's sessions.csv carries meta.json's
``test`` and ``trial`` (mobgap's Test5 / Test11, Trial1 / Trial2), and ``--group-by test`` gives subjects.csv a row per
subject and test instead of pooling a straight-walk test with daily activities; without it the pooling is warned."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.visits import subject_totals


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("tests") / "study"
    for i, (test, trial) in enumerate((("Test5", "Trial1"), ("Test5", "Trial2"), ("Test11", "Trial1"))):
        d = root / f"S1_{test}_{trial}"
        write_session(sim.simulate("walk", 830 + i, length_m=8), d)
        meta = json.loads((d / "meta.json").read_text())
        (d / "meta.json").write_text(json.dumps({**meta, "subject": "S1", "test": test, "trial": trial}))
    return root


def test_sessions_carry_test_and_trial_and_pooling_is_warned_c170(study, tmp_path, caplog):
    out = tmp_path / "o"
    with caplog.at_level("WARNING"):
        assert main(["track-all", str(study), "--out", str(out), "--no-plot"]) == 0
    sessions = pd.read_csv(out / "sessions.csv", dtype=str)
    cols = list(sessions.columns)
    assert cols[cols.index("visit_as_written") + 1:cols.index("visit_as_written") + 3] == ["test", "trial"]
    assert sessions[["path", "test", "trial"]].values.tolist() == [
        ["S1_Test5_Trial1", "Test5", "Trial1"], ["S1_Test5_Trial2", "Test5", "Trial2"],
        ["S1_Test11_Trial1", "Test11", "Trial1"]]
    subjects = pd.read_csv(out / "subjects.csv", dtype={"subject": str})
    assert len(subjects) == 1 and "test" not in subjects.columns  # as before: the subject's tests pooled
    assert any("subjects.csv pools each subject's tests (Test5, Test11; 1 subject with more than one): pass "
               "--group-by test" in r.getMessage() for r in caplog.records)


def test_group_by_test_gives_a_row_per_subject_and_test_c171(study, tmp_path, caplog):
    out = tmp_path / "o"
    with caplog.at_level("WARNING"):
        assert main(["track-all", str(study), "--out", str(out), "--no-plot", "--group-by", "test"]) == 0
    assert not any("pools each subject's tests" in r.getMessage() for r in caplog.records)
    subjects = pd.read_csv(out / "subjects.csv", dtype=str)
    assert list(subjects.columns[:3]) == ["subject", "visit", "test"]
    assert subjects[["subject", "test", "n_tracked", "paths"]].values.tolist() == [
        ["S1", "Test5", "2", "S1_Test5_Trial1; S1_Test5_Trial2"], ["S1", "Test11", "1", "S1_Test11_Trial1"]]
    sessions = pd.read_csv(out / "sessions.csv")
    one = sessions[sessions["path"] == "S1_Test11_Trial1"].iloc[0]
    row = subjects[subjects["test"] == "Test11"].iloc[0]
    assert float(row["distance_m"]) == pytest.approx(float(one["distance_m"]))  # its one session's distance
    from pdrlearn.report.build import _batch_section

    tables = dict(_batch_section(out, out).tables)  # the report's subject rows are subjects.csv's (run.json)
    shown = tables["per subject and visit: walking totals of the detected bouts (subjects.csv; distance_m: the "
                   "tracks summed)"]
    assert shown["test"].tolist() == ["Test5", "Test11"]


def test_group_by_is_checked_before_tracking_c171(study, tmp_path, capsys):
    assert main(["track-all", str(study), "--out", str(tmp_path / "a"), "--group-by", "trial"]) == 2
    err = capsys.readouterr().err
    assert "--group-by trial: not a choice; pass --group-by test" in err and "decision C171" in err  # C202: or visit
    meta = json.loads((study / "S1_Test5_Trial1" / "meta.json").read_text())
    copy = tmp_path / "plain2" / "s"
    copy.mkdir(parents=True)
    for f in (study / "S1_Test5_Trial1").iterdir():
        (copy / f.name).write_bytes(f.read_bytes())
    (copy / "meta.json").write_text(json.dumps({k: v for k, v in meta.items() if k not in ("test", "trial")}))
    assert main(["track-all", str(copy.parent), "--out", str(tmp_path / "b"), "--group-by", "test"]) == 2
    assert "no session under" in capsys.readouterr().err
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()


def test_subject_totals_by_test_keeps_untested_sessions_apart_c171():
    rows = [{"path": p, "group": ".", "subject": "S1", "visit": None, "test": t, "status": "ok", "distance_m": d,
             "walking_time_s": 10.0} for p, t, d in (("a", "Test5", 5.0), ("b", None, 7.0), ("c", "Test11", 30.0),
                                                      ("d", "Test5", 6.0))]
    out = subject_totals(pd.DataFrame(rows), by="test")
    assert out["test"].tolist()[:2] == ["Test5", "Test11"] and pd.isna(out["test"].iloc[2])  # none named: last
    assert out["distance_m"].tolist() == [11.0, 30.0, 7.0]
    assert subject_totals(pd.DataFrame(rows))["distance_m"].tolist() == [48.0]  # without by: one row, as before
