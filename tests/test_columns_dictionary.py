"""Cohort decision C35: the data dictionary (pdrlearn/columns.py, `pdrlearn columns`, docs/columns.md) names every
column track-all writes into sessions.csv, groups.csv, subjects.csv and bouts.csv, with unit, type and meaning."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import TABLES, expanded, markdown, undocumented

DOC = Path(__file__).resolve().parent.parent / "docs" / "columns.md"


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """Two subjects x two visits: site a foot + waist (plasys), site b waist only (a waist pipeline); one broken."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("dict") / "study"
    for i, (site, subject, visit) in enumerate((("a", "S1", "v1"), ("a", "S1", "v2"), ("b", "S2", "v1"),
                                                ("b", "S2", "v2"))):
        d = root / site / subject / visit
        write_session(sim.simulate("walk", 812 + i, length_m=10), d)
        meta = json.loads((d / "meta.json").read_text())
        (d / "meta.json").write_text(json.dumps({**meta, "subject": subject, "visit": visit}))
        if site == "b":
            for f in d.glob("f*.csv"):
                f.unlink()
    (root / "b" / "S3" / "v1").mkdir(parents=True)
    (root / "b" / "S3" / "v1" / "meta.json").write_text('{"subject": "S3", "visit": "v1"}')  # fails: no sensor file
    out = tmp_path_factory.mktemp("dict_out") / "o"
    assert main(["track-all", str(root), "--out", str(out)]) == 1
    return out


def test_every_column_written_is_in_the_dictionary(batch):
    from pdrlearn.cli.cohort import SESSION_COLUMNS
    from pdrlearn.track.bouts import BOUT_COLUMNS
    from pdrlearn.visits import SUBJECT_COLUMNS

    sessions = pd.read_csv(batch / "sessions.csv")
    assert set(sessions["pipeline"].dropna()) >= {"plasys"} and len(set(sessions["pipeline"].dropna())) == 2
    written = {"sessions.csv": list(sessions.columns), "groups.csv": list(pd.read_csv(batch / "groups.csv").columns),
               "subjects.csv": list(pd.read_csv(batch / "subjects.csv").columns),
               "bouts.csv": sorted({c for p in batch.rglob("bouts.csv") for c in pd.read_csv(p).columns})}
    assert len(list(batch.rglob("bouts.csv"))) == 4
    waist = [p for p in batch.rglob("steps.csv") if "b" in p.relative_to(batch).parts[:1]]  # site b: lower back
    assert len(waist) == 2
    written["steps.csv"] = sorted({c for p in waist for c in pd.read_csv(p).columns})
    assert "side" in written["steps.csv"]  # decision W129
    for table, cols in written.items():
        assert undocumented(table, cols) == [], table
    for table, cols in (("sessions.csv", SESSION_COLUMNS), ("bouts.csv", BOUT_COLUMNS),
                        ("subjects.csv", SUBJECT_COLUMNS)):
        assert undocumented(table, cols) == [], table
    for table in TABLES:  # every entry has a unit, a type and a meaning
        for name, unit, kind, meaning in expanded(table).values():
            assert unit and kind in ("text", "integer", "number", "true/false") and len(meaning) > 5, name


def test_the_documented_dictionary_is_the_generated_one(capsys):
    assert DOC.read_text() == markdown() + "\n"
    assert main(["columns", "bouts.csv", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert list(got) == ["bouts.csv"] and [c["column"] for c in got["bouts.csv"]][:2] == ["bout", "start_s"]
    assert got["bouts.csv"][1]["unit"] == "s" and got["bouts.csv"][1]["type"] == "number"
    assert undocumented("sessions.csv", ["path", "no_such_column"]) == ["no_such_column"]
