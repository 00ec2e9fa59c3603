"""Trial T4 (session 36, a biostatistician reading the cohort tables in R): subject ids written as JSON numbers
(C99, B363), subject and visit in every pooled table and in a single track's summary (C100), no percent change of a
percent error (C101), one natural row order (C102), one float format (C103). One short track-all run of simulated
users 8860-8862."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

#: (folder, subject as meta.json writes it - a JSON number, visit, user id)
SESSIONS = (("S2/visit1", 2, 1, 8860), ("S2/visit2", 2, 2, 8860), ("S10/visit1", 10, 1, 8861),
            ("S10/visit2", 10, 2, 8861), ("S9/visit1", 9, 1, 8862))


def _write(root, folder, subject, visit, user, speed=1.0):
    s = simulate_path(parse_route("stand:2, straight:8, turn:90, straight:4, stand:2"),
                      UserProfile.from_seed(user), rate_hz=100.0, seed=user + 100 * visit)
    write_session(s, root / folder)
    meta = json.loads((root / folder / "meta.json").read_text())
    meta.update(subject=subject, visit=visit)
    (root / folder / "meta.json").write_text(json.dumps(meta))


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    root = tmp_path_factory.mktemp("tidy") / "study"
    for folder, subject, visit, user in SESSIONS:
        _write(root, folder, subject, visit, user)
    out = tmp_path_factory.mktemp("tidy_out") / "o"
    assert main(["track-all", str(root), "--out", str(out)]) == 0
    return root, out


def test_a_subject_written_as_a_json_number_is_its_text(batch):
    """C99: ``"subject": 8830`` (a roster script's number) was replaced by the simulator's ``user.seed:8830``, or
    dropped when meta.json had no ``user`` (no subjects.csv, no changes.csv, exit 0); now it is the id's text."""
    _, out = batch
    sessions = pd.read_csv(out / "sessions.csv", dtype={"subject": str, "visit": str})
    assert sorted(set(sessions["subject"])) == ["10", "2", "9"]
    subjects = pd.read_csv(out / "subjects.csv", dtype={"subject": str})
    assert set(subjects["subject"]) == {"2", "9", "10"}
    changes = pd.read_csv(out / "changes.csv", dtype={"subject": str})
    assert set(changes["subject"]) == {"2", "9", "10"}


def test_a_subject_id_without_user_and_a_refused_one(tmp_path):
    """C99 / B363: a whole number without ``user`` is its text; a fractional number, true/false or a list is one
    line naming the file."""
    from pdrlearn.cohort import session_labels
    from pdrlearn.errors import DataError

    (tmp_path / "meta.json").write_text(json.dumps({"subject": 8830, "visit": 1}))
    assert session_labels(tmp_path) == ("8830", "1")
    for bad in (8830.5, True, [1, 2]):
        (tmp_path / "meta.json").write_text(json.dumps({"subject": bad, "visit": 1}))
        with pytest.raises(DataError, match=r"meta\.json: \"subject\": .* not an id; write the id as text .*B363"):
            session_labels(tmp_path)


def test_every_pooled_table_and_a_session_folder_carries_subject_and_visit(batch):
    """C100: strides.csv had no subject (a stride-level model joined on path first), a session's summary.json no
    subject or visit and its bouts.csv no visit."""
    _, out = batch
    ids = {"subject": str, "visit": str}
    sessions = pd.read_csv(out / "sessions.csv", dtype=ids).set_index("path")
    for table in ("strides.csv", "bouts.csv"):
        pooled = pd.read_csv(out / table, dtype=ids)
        assert {"subject", "visit"} <= set(pooled.columns), table
        assert (pooled["subject"] == pooled["path"].map(sessions["subject"])).all(), table
        assert (pooled["visit"] == pooled["path"].map(sessions["visit"])).all(), table
    summary = json.loads((out / "S10/visit2/summary.json").read_text())
    assert (summary["subject"], summary["visit"]) == ("10", "2")
    bouts = pd.read_csv(out / "S10/visit2/bouts.csv", dtype=ids)
    assert list(bouts.columns[:4]) == ["session", "subject", "visit", "bout"]
    assert set(bouts["visit"]) == {"2"} and set(bouts["subject"]) == {"10"}


def test_a_single_track_prints_and_writes_subject_and_visit(batch, tmp_path, capsys):
    """C100: ``track --json`` and its summary.json name meta.json's subject and visit (a cluster array job of one
    track per session could not tell the visits apart)."""
    root, _ = batch
    capsys.readouterr()
    assert main(["track", str(root / "S9/visit1"), "--out", str(tmp_path / "t"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert (printed["subject"], printed["visit"]) == ("9", "1")
    written = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert (written["subject"], written["visit"]) == ("9", "1")
