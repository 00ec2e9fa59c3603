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
    assert main(["track-all", "--no-plot", str(root), "--out", str(out)]) == 0
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
    assert main(["track", "--no-plot", str(root / "S9/visit1"), "--out", str(tmp_path / "t"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert (printed["subject"], printed["visit"]) == ("9", "1")
    written = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert (written["subject"], written["visit"]) == ("9", "1")


def test_no_percent_change_of_a_percent_error_and_no_scientific_notation():
    """C101: the default changes table gave ``distance_error_pct_change_pct`` (+7746 % for an error going from 0.1 %
    to 7.8 %) and printed ``+2.07e+03 [-3.96e+03, 8.11e+03]``; a percent error keeps its change in points only, and
    the printed summary is in plain decimals."""
    from pdrlearn.visits import change_summary, change_table, changes_text

    rows = [{"path": f"{s}/{v}", "group": s, "subject": s, "visit": v, "status": "ok", "pipeline": "plasys",
             "duplicate_of": None, "distance_error_pct": e, "gait_speed_mps": g,
             "median_cadence_spm": 3000.0 if v == "visit1" else 1170.0,
             "stride_length_mae_pct": abs(e)}
            for s, (e1, e2) in (("S1", (0.1, 7.8)), ("S2", (-0.2, 0.4)), ("S3", (0.05, -9.0)))
            for v, e, g in (("visit1", e1, 1.2), ("visit2", e2, 1.0 + len(s) / 100))]
    sessions = pd.DataFrame(rows)
    changes = change_table(sessions, metrics=("distance_error_pct", "gait_speed_mps", "median_cadence_spm",
                                              "stride_length_mae_pct"))
    assert "distance_error_pct_change" in changes and "distance_error_pct_change_pct" not in changes
    assert "stride_length_mae_pct_change_pct" not in changes and "gait_speed_mps_change_pct" in changes
    default = change_table(sessions)
    assert "distance_error_pct_change_pct" not in default and "gait_speed_mps_change_pct" in default
    summary = change_summary(changes)
    err = summary[summary["measure"] == "distance_error_pct"].iloc[0]
    assert pd.isna(err["mean_pct_change"]) and err["mean_change"] == pytest.approx((7.7 + 0.6 - 9.05) / 3)
    text = changes_text(summary).to_string()
    assert "e+" not in text and "e-" not in text
    assert "-1830 [-1830, -1830]" in text  # median_cadence_spm, not -1.83e+03
    assert "nan" not in changes_text(summary).to_markdown(index=False).lower()



def test_every_pooled_table_lists_subjects_in_natural_order(batch):
    """C102: sessions.csv, bouts.csv, strides.csv and groups.csv listed S10, S2, S9 (text order) while subjects.csv
    listed 2, 9, 10 (natural order); now all are S2 < S9 < S10."""
    _, out = batch
    natural = ["S2", "S9", "S10"]
    for table in ("sessions.csv", "bouts.csv", "strides.csv"):
        paths = pd.read_csv(out / table, dtype={"path": str})["path"]
        assert list(dict.fromkeys(p.split("/")[0] for p in paths)) == natural, table
    assert pd.read_csv(out / "groups.csv")["group"].tolist() == natural
    assert pd.read_csv(out / "subjects.csv", dtype={"subject": str})["subject"].drop_duplicates().tolist() == [
        "2", "9", "10"]
    assert pd.read_csv(out / "changes.csv", dtype={"subject": str})["subject"].tolist() == ["2", "9", "10"]


def test_float_cells_have_no_exponent_and_no_float_noise(tmp_path):
    """C103: steps.csv / strides.csv held ``-8.067625715e-05`` beside plain decimals, and the pooled tables' full
    precision ``8.700000000000001``; one writer, 10 significant digits in plain decimals."""
    from pdrlearn.table_csv import float_text, write_table_csv

    assert float_text(-8.067625715e-05) == "-0.00008067625715" and float_text(8.700000000000001) == "8.7"
    assert float_text(1.5e-05, digits=None) == "0.000015" and float_text(1e-09) == "0.000000001"
    df = pd.DataFrame({"turn_angle_rad": [-8.067625715e-05, 0.5, float("nan")], "length_m": [8.700000000000001,
                                                                                            1.0, 2.0]})
    write_table_csv(df, tmp_path / "t.csv")
    text = (tmp_path / "t.csv").read_text()
    assert text == "turn_angle_rad,length_m\n-0.00008067625715,8.7\n0.5,1\n,2\n"
    back = pd.read_csv(tmp_path / "t.csv")
    assert back["turn_angle_rad"].iloc[0] == pytest.approx(-8.067625715e-05, rel=1e-12)


def test_pooled_tables_and_steps_out_write_plain_decimals(batch, tmp_path):
    """C103: track-all's pooled tables and ``steps --out`` are written as a track's tables (10 significant digits,
    no exponent); sessions.csv keeps its full precision, without an exponent either."""
    import re

    root, out = batch
    number = re.compile(r"^-?\d+(\.\d+)?$")
    for table in ("strides.csv", "bouts.csv"):
        cells = pd.read_csv(out / table, dtype=str, keep_default_na=False).to_numpy().ravel()
        floats = [c for c in cells if re.fullmatch(r"-?[\d.]+(e[-+]\d+)?", c)]
        assert floats and all(number.match(c) for c in floats), table
        assert all(len(c.lstrip("-").replace(".", "").lstrip("0")) <= 10 for c in floats), table
    assert "e-0" not in (out / "sessions.csv").read_text()
    assert main(["steps", str(root / "S2/visit1"), "--out", str(tmp_path / "s.csv")]) == 0
    cells = pd.read_csv(tmp_path / "s.csv", dtype=str, keep_default_na=False).to_numpy().ravel()
    assert all(len(c.lstrip("-").replace(".", "").lstrip("0")) <= 10 for c in cells if number.match(c))


def test_import_writes_the_visit_and_refuses_an_empty_one(tmp_path, capsys):
    """B364: ``import`` had ``--subject`` but no ``--visit``, so a visit could only be set by editing meta.json; now
    ``--visit`` writes it (kept by ``--merge``), and an empty one is one line, nothing written."""
    from tests.sim_helpers import lab_columns, quiet_walk

    lab_columns(quiet_walk("straight:8", 8863, seed=2)).to_csv(tmp_path / "u.csv", index=False)
    imp = ["import", str(tmp_path / "u.csv"), "--acc-unit", "m/s^2", "--gyro-unit", "rad/s"]
    assert main([*imp, "--subject", "030", "--visit", "visit2", "--out", str(tmp_path / "a")]) == 0
    meta = json.loads((tmp_path / "a" / "meta.json").read_text())
    assert (meta["subject"], meta["visit"]) == ("030", "visit2")
    from pdrlearn.cohort import session_labels

    assert session_labels(tmp_path / "a") == ("030", "visit2")
    capsys.readouterr()
    assert main([*imp, "--visit", " ", "--out", str(tmp_path / "b")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: import: --visit is empty; give the visit")
    assert err.count("\n") == 1 and "Traceback" not in err and not (tmp_path / "b").exists()


def test_simulate_writes_subject_and_visit(tmp_path, capsys):
    """B364: ``simulate --subject / --visit`` write meta.json's ids (a study built without editing JSON); blank is
    one line before anything is simulated."""
    sim = ["simulate", "--route", "stand:1, straight:4, stand:1", "-u", "8864", "--rate", "100"]
    assert main([*sim, "--subject", "030", "--visit", "2", "--out", str(tmp_path / "s")]) == 0
    meta = json.loads((tmp_path / "s" / "meta.json").read_text())
    assert (meta["subject"], meta["visit"]) == ("030", "2")
    capsys.readouterr()
    assert main([*sim, "--subject", "", "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: simulate: --subject is empty; give the subject's id") and "B364" in err
    assert err.count("\n") == 1 and not (tmp_path / "t").exists()
