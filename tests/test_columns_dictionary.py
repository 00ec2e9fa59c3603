"""Cohort decision C35: the data dictionary (pdrlearn/columns.py, `pdrlearn columns`, docs/columns.md) names every
column track-all writes into sessions.csv, groups.csv, subjects.csv and bouts.csv, with unit, type and meaning."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
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
    assert len(list(batch.rglob("bouts.csv"))) == 5  # each session's and track-all's combined one (L165)
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
    assert list(got) == ["bouts.csv"] and [c["column"] for c in got["bouts.csv"]][4:6] == ["bout", "start_s"]
    assert got["bouts.csv"][5]["unit"] == "s" and got["bouts.csv"][5]["type"] == "number"
    assert undocumented("sessions.csv", ["path", "no_such_column"]) == ["no_such_column"]


def test_the_dictionary_says_what_track_writes_into_bouts_csv(batch):
    """Decisions L164-L166 (Mobilise-D trial, session 24): docs/columns.md had bouts.csv's ``bout`` from 0 (it is
    from 1), ``n_strides`` empty on the lower back (filled), cadence as 60 n_steps / duration (n - 1 steps over the
    contact span), turns of "about 90 deg" (>= 80); subjects.csv's cadence counted one step too many per bout.
    Each documented fact is checked against the tables track-all wrote."""
    from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG

    doc = {c: m for c, _, _, m in expanded("bouts.csv").values()}
    sessions = pd.read_csv(batch / "sessions.csv")
    ok = sessions[sessions["status"] == "ok"]
    per = {p: pd.read_csv(batch / p / "bouts.csv") for p in ok["path"]}
    assert all(len(b) for b in per.values())
    assert "from 1" in doc["bout"] and all(b["bout"].tolist() == list(range(1, len(b) + 1)) for b in per.values())
    for p, b in per.items():
        waist = ok.loc[ok["path"] == p, "pipeline"].iloc[0] != "plasys"
        if waist:  # lower back: n_strides filled, n_steps - 2; stride length 2 x the mean step
            assert "n_steps - 2" in doc["n_strides"] and (b["n_strides"] == b["n_steps"] - 2).all()
            # W602: the cadence's terms are the inner steps, second contact to last-but-one (none under 4 contacts)
            assert "second contact" in doc["contact_span_s"]
            assert (b["n_step_intervals"] == (b["n_steps"] - 3).clip(lower=0)).all()
            assert np.allclose(b["stride_length_m"], 2 * b["distance_m"] / (b["n_steps"] - 1))
        else:
            assert np.allclose(b["stride_length_m"], b["distance_m"] / b["n_strides"])
        assert "60 x n_step_intervals / contact_span_s" in doc["cadence_spm"]
        assert np.allclose(b["cadence_spm"], 60 * b["n_step_intervals"] / b["contact_span_s"].where(
            b["contact_span_s"] > 0), equal_nan=True)
        assert (b["longest_contact_gap_s"] <= b["duration_s"] + 1e-9).all()
        assert (b["session"] == json.loads((batch / p / "summary.json").read_text())["session"]).all()
        assert (b["subject"].astype(str) == str(ok.loc[ok["path"] == p, "subject"].iloc[0])).all()
    assert f">= {TURN_COUNT_MIN_DEG:g} deg" in doc["n_turns"]
    assert all(json.loads((batch / p / "summary.json").read_text())["turn_count_min_deg"] == TURN_COUNT_MIN_DEG
               for p in per)
    # track-all's OUT/bouts.csv: every session's rows, keyed by sessions.csv's path
    both = pd.read_csv(batch / "bouts.csv")
    assert len(both) == sum(len(b) for b in per.values()) and set(both["path"]) == set(per)
    assert list(both.columns[:4]) == ["path", "visit", "session", "subject"]
    # subjects.csv's cadence: the same definition, the bouts pooled
    subjects = pd.read_csv(batch / "subjects.csv", dtype={"visit": str})
    for _, row in subjects[subjects["n_tracked"] > 0].iterrows():
        mine = both[(both["subject"] == row["subject"]) & (both["visit"].astype(str) == row["visit"])]
        assert row["cadence_spm"] == pytest.approx(60 * mine["n_step_intervals"].sum() / mine["contact_span_s"].sum())
