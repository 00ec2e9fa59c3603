"""Decision C223 (session 49, trial T3: a bariatric-surgery study calibrated at each visit): `track-all --params-dir`
finds DIR/SUBJECT/VISIT.json before DIR/SUBJECT.json, matched as changes.csv pairs visits; sessions.csv and each
summary.json say which file; ambiguous or unmatched per-visit files are one line before any tracking."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.params_dir import pseudonym_label, session_params
from pdrlearn.errors import DataError

RELS = ["B01/pre", "B01/post", "B02/BL", "B02/post"]
LABELS = [("B01", "pre"), ("B01", "post"), ("B02", "BL"), ("B02", "Post")]


def _files(root: Path, *names: str) -> Path:
    for name in names:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text("{}")
    return root


def test_a_visits_own_file_comes_before_the_subjects(tmp_path):
    """A per-visit file wins for its visit, the subject's file covers the others; a file's visit is matched with
    C28's spelling-free key (Baseline.json is visit BL, POST.json visit Post) and --visit-map (C29)."""
    d = _files(tmp_path / "cal", "B01.json", "B01/post.json", "B02/Baseline.json", "B02/POST.json")
    got = session_params(d, RELS, LABELS)
    assert [label for _, label in got] == ["B01.json", "B01/post.json", "B02/Baseline.json", "B02/POST.json"]
    assert got[1][0] == d / "B01" / "post.json"
    d2 = _files(tmp_path / "cal2", "B01/before.json", "B01/post.json", "B02.json")
    got = session_params(d2, RELS, LABELS, {"before": "pre"})
    assert [label for _, label in got] == ["B01/before.json", "B01/post.json", "B02.json", "B02.json"]
    # a session naming no visit takes the subject's file; a batch of one visit leaves the other visit's file unused
    assert session_params(d, ["B01/x"], [("B01", None)]) == [(d / "B01.json", "B01.json")]
    assert session_params(d2, ["B01/post"], [("B01", "post")]) == [(d2 / "B01" / "post.json", "B01/post.json")]


def test_a_label_takes_the_pseudonym():
    assert pseudonym_label("B01/post.json", {"B01": "P01"}) == "P01/post.json"
    assert pseudonym_label("B01.json", {"B01": "P01"}) == "P01.json"
    assert pseudonym_label("B03.json", {"B01": "P01"}) == "B03.json"


def test_problems_are_one_line_before_tracking(tmp_path, caplog):
    """Two files of one visit (ambiguous), a per-visit file of a visit the subject has no session of, and a visit
    with neither file: one DataError line naming each; a folder of no subject in the batch: a warning only."""
    d = _files(tmp_path / "cal", "B01/pre.json", "B01/PRE.json", "B01/post-op.json", "B02/BL.json")
    with pytest.raises(DataError) as err:
        session_params(d, RELS, LABELS)
    line = str(err.value)
    assert "\n" not in line and "B01/PRE.json and B01/pre.json are one visit ('pre')" in line, line
    assert "B01/post-op.json: no session of that subject at that visit" in line
    assert "no calibration file for subject 'B01' and 'B02'" in line or "'B01', 'B02'" in line, line
    assert "B01/post.json or B01.json" in line and "B02/Post.json or B02.json" in line and "C223" in line
    ok = _files(tmp_path / "ok", "B01.json", "B02.json", "B03/pre.json")
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        assert [label for _, label in session_params(ok, RELS, LABELS)] == ["B01.json"] * 2 + ["B02.json"] * 2
    assert any("B03" in r.getMessage() and "not used" in r.getMessage() for r in caplog.records)


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    """Two subjects x two visits, each a copy of one short simulated walk (user 16660), so that two sessions'
    distances differ by their calibration only."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("c223") / "study"
    walk = sim.simulate("walk", 16660, length_m=6)  # one walk for the four sessions (copies: C20's warning only)
    for subj in ("B01", "B02"):
        for visit in ("pre", "post"):
            write_session(walk, root / subj / visit)
            meta = root / subj / visit / "meta.json"
            meta.write_text(json.dumps({**json.loads(meta.read_text()), "subject": subj, "visit": visit}))
    return root


def test_track_all_tracks_each_visit_with_its_own_file(study, tmp_path):
    """One track-all: B01's post visit with B01/post.json (K 0.9), its pre visit with B01.json (K 0.5): the same
    walk 1.8 x as long; sessions.csv's params_file and summary.json's info.params_file name the file (under the
    --subject-map pseudonyms, C86); changes.csv is written (the trial needed two runs, and had none)."""
    from pdrlearn.waist.params import WaistParams

    cal = tmp_path / "cal"
    for name, k in (("B01.json", 0.5), ("B01/post.json", 0.9), ("B02.json", 0.7)):
        (cal / name).parent.mkdir(parents=True, exist_ok=True)
        WaistParams(k=k, source="calibrated", pipeline="waist-pendulum").save(cal / name)
    out = tmp_path / "out"
    (tmp_path / "names.csv").write_text("real,pseudonym\nB01,P01\nB02,P02\n")  # C86: params_file renamed too
    assert main(["track-all", "--no-plot", str(study), "--out", str(out), "--pipeline", "waist-pendulum",
                 "--params-dir", str(cal), "--subject-map", str(tmp_path / "names.csv")]) == 0
    table = pd.read_csv(out / "sessions.csv").set_index("path")
    assert table["params_file"].to_dict() == {"P01/post": "P01/post.json", "P01/pre": "P01.json",
                                              "P02/post": "P02.json", "P02/pre": "P02.json"}
    info = json.loads((out / "P01" / "post" / "summary.json").read_text())["info"]
    assert info["params_file"] == "P01/post.json"
    assert table.loc["P01/post", "distance_m"] / table.loc["P01/pre", "distance_m"] == pytest.approx(1.8, rel=1e-3)
    assert (out / "changes.csv").is_file()
    shutil.copy(cal / "B01.json", cal / "B01" / "followup.json")  # a visit B01 has no session of: refused first
    assert main(["track-all", "--no-plot", str(study), "--out", str(tmp_path / "bad"), "--pipeline",
                 "waist-pendulum", "--params-dir", str(cal)]) == 2
    assert not (tmp_path / "bad").exists()
