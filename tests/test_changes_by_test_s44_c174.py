"""Decision C174: with ``track-all --group-by test`` changes.csv and changes_summary.csv are per (subject, test): each
test's visits paired on their own (a ``test`` column after ``visit``), so a Mobilise-D study sees Test5's change apart
from Test11's; C172's setup (review R2: visit 1 Test5 fast + Test11 slow against visit 2 Test5 alone had read +30 %)
gives Test5's own change and Test11 listed as missing at visit 2."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.visits import change_summary, change_table, changes_text


def _r2():
    rows = [("A1_T5", "A", "1", "Test5", 1.2), ("A1_T11", "A", "1", "Test11", 0.8), ("A2_T5", "A", "2", "Test5", 1.3),
            ("B1_T5", "B", "1", "Test5", 1.0), ("B2_T5", "B", "2", "Test5", 1.1)]
    return pd.DataFrame(rows, columns=["path", "subject", "visit", "test", "gait_speed_mps"]).assign(
        group="g", status="ok")


def _cells(df, cols) -> list[list]:
    """The rows of ``cols``, an empty cell as None."""
    return [[None if pd.isna(v) else v for v in row] for row in df[cols].astype(object).values.tolist()]


def test_each_test_is_paired_on_its_own_c174():
    pooled = change_table(_r2(), metrics=["gait_speed_mps"])  # without by: A's visit 1 averages its two tests
    assert pooled["gait_speed_mps_change_pct"].round(6).tolist() == [30.0, 10.0] and "test" not in pooled
    c = change_table(_r2(), metrics=["gait_speed_mps"], by="test")
    cols = list(c.columns)
    assert cols[cols.index("visit") + 1] == "test"
    assert _cells(c, ["subject", "test", "status", "baseline_path", "path"]) == [
        ["A", "Test5", "ok", "A1_T5", "A2_T5"], ["A", "Test11", "missing", "A1_T11", None],
        ["B", "Test5", "ok", "B1_T5", "B2_T5"]]
    assert c["gait_speed_mps_change"].round(6).tolist()[::2] == [0.1, 0.1]  # Test5 against Test5
    s = change_summary(c, by="test")
    assert list(s.columns[:4]) == ["visit", "baseline_visit", "test", "measure"]
    assert _cells(s, ["test", "n_subjects", "not_paired"]) == [
        ["Test5", 2, None], ["Test11", 0, "A"]]
    assert s["mean_change"].iloc[0] == pytest.approx(0.1)
    text = changes_text(s)
    assert list(text.columns[:3]) == ["visit", "test", "measure"] and text["test"].tolist() == ["Test5", "Test11"]
    # a session naming no test: its own rows, the test empty (as subjects.csv's, C171)
    none = _r2().assign(test=lambda d: d["test"].where(d["subject"] == "A"))
    c = change_table(none, metrics=["gait_speed_mps"], by="test")
    assert _cells(c, ["subject", "test", "status"]) == [["A", "Test5", "ok"], ["A", "Test11", "missing"],
                                                        ["B", None, "ok"]]
    assert c[c["subject"] == "B"]["gait_speed_mps_change"].round(6).tolist() == [0.1]


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("c174") / "study"
    for i, (visit, test, length) in enumerate((("1", "Test5", 8), ("1", "Test11", 16), ("2", "Test5", 8),
                                               ("2", "Test11", 16))):
        d = root / f"S1_v{visit}_{test}"
        write_session(sim.simulate("walk", 840 + i, length_m=length), d)
        meta = json.loads((d / "meta.json").read_text())
        (d / "meta.json").write_text(json.dumps({**meta, "subject": "S1", "visit": visit, "test": test,
                                                 "trial": "Trial1"}))
    return root


def test_track_all_group_by_test_writes_changes_per_test_c174(study, tmp_path, caplog, capsys):
    out = tmp_path / "o"
    with caplog.at_level("WARNING"):
        assert main(["track-all", str(study), "--out", str(out), "--no-plot", "--group-by", "test"]) == 0
    assert not any("averaging a visit's" in r.getMessage() for r in caplog.records)  # C172's warning: gone
    printed = capsys.readouterr().out
    changes = pd.read_csv(out / "changes.csv", dtype=str)
    cols = list(changes.columns)
    assert cols[cols.index("visit") + 1] == "test"
    assert changes[["subject", "test", "baseline_path", "path", "n_trials"]].values.tolist() == [
        ["S1", "Test5", "S1_v1_Test5", "S1_v2_Test5", "1"], ["S1", "Test11", "S1_v1_Test11", "S1_v2_Test11", "1"]]
    sessions = pd.read_csv(out / "sessions.csv").set_index("path")
    for _, row in changes.iterrows():  # each test's change is its own sessions' difference
        want = sessions.loc[row["path"], "gait_speed_mps"] - sessions.loc[row["baseline_path"], "gait_speed_mps"]
        assert float(row["gait_speed_mps_change"]) == pytest.approx(want)
    summary = pd.read_csv(out / "changes_summary.csv", dtype=str)
    assert summary["test"].drop_duplicates().tolist() == ["Test5", "Test11"]
    assert "| test " in printed.split("paired change from the baseline visit")[1]
    from pdrlearn.report.build import _batch_section

    tables = _batch_section(out, out).tables  # the report's changes are changes.csv's (run.json's --group-by)
    [(title, table)] = [t for t in tables if t[0].startswith("paired change")]
    assert "per subject and test" in title and table["test"].drop_duplicates().tolist() == ["Test5", "Test11"]
    from pdrlearn.columns import undocumented

    assert undocumented("changes.csv", cols) == [] and undocumented("changes_summary.csv", summary.columns) == []
