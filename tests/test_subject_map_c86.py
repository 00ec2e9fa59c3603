"""Session 35, fixer FC (trial T4 findings 4-5): ``track-all --subject-map FILE.csv`` writes pseudonyms for the
real folder, subject and session names in the output tree, every table, each session's files and the figure titles
(decision C86); a malformed map is one line, exit 2, nothing written (B340)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

MAP = "real,pseudonym\nDoe_Jane_1950-03-02,P01\nDoe_Jane,P01\nDoe_Jane_walk,P01_walk\nRoe_Rick_1960-01-01,P02\n"


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """Doe_Jane_1950-03-02/{baseline,followup} (user 8437, subject Doe_Jane, the first session named Doe_Jane_walk)
    and Roe_Rick_1960-01-01/baseline (user 8438, subject Roe_Rick: not in the map's subjects)."""
    root = tmp_path_factory.mktemp("c86") / "study"
    for rel, seed, k, subject, visit in (("Doe_Jane_1950-03-02/baseline", 8437, 0, "Doe_Jane", "baseline"),
                                         ("Doe_Jane_1950-03-02/followup", 8437, 1, "Doe_Jane", "followup"),
                                         ("Roe_Rick_1960-01-01/baseline", 8438, 0, "Roe_Rick", "baseline")):
        write_session(simulate("A", user_seed=seed, seed=k), root / rel)
        meta = json.loads((root / rel / "meta.json").read_text())
        meta.update(subject=subject, visit=visit)
        if k == 0 and seed == 8437:
            meta["session"] = "Doe_Jane_walk"
        (root / rel / "meta.json").write_text(json.dumps(meta))
    (root.parent / "map.csv").write_text(MAP)
    return root


def test_track_all_subject_map_pseudonymizes_tree_tables_files_and_titles(study, tmp_path, monkeypatch, capsys):
    """C86: no output file (hidden ones too) names Doe_Jane's folder, subject or session; the tree is P01/...,
    P02/...; sessions.csv's path, group, subject and session are the pseudonyms (Roe_Rick, not in the map as a
    subject, keeps his); the figure titles carry the pseudonym; run.json keeps the map's SHA-256 only."""
    import pdrlearn.track.plots as plots

    titles = []
    real_plot = plots.plot_paths
    monkeypatch.setattr(plots, "plot_paths", lambda *a, **k: (titles.append(k.get("title")), real_plot(*a, **k))[1])
    out = tmp_path / "ta"
    assert main(["track-all", str(study), "--out", str(out), "--subject-map", str(study.parent / "map.csv"),
                 "--json"]) == 0  # draws: the test reads the figures' titles
    printed = capsys.readouterr().out
    hits = [str(p.relative_to(out)) for p in out.rglob("*") if p.is_file() and b"Doe_Jane" in p.read_bytes()]
    assert hits == [] and "Doe_Jane" not in printed
    assert sorted(p.name for p in out.iterdir() if p.is_dir()) == ["P01", "P02"]
    assert (out / "P01" / "followup" / ".track-all-session.json").is_file()
    rows = {r["path"]: r for r in json.loads(printed)["sessions"]}
    assert set(rows) == {"P01/baseline", "P01/followup", "P02/baseline"}
    assert [rows["P01/baseline"][k] for k in ("group", "subject", "session")] == ["P01", "P01", "P01_walk"]
    assert rows["P02/baseline"]["subject"] == "Roe_Rick"  # only the names the map lists are replaced
    assert any(t.startswith("P01_walk:") for t in titles) and not any("Doe_Jane" in t for t in titles)
    run = json.loads((out / "run.json").read_text())
    assert set(run["options"]["subject_map"]) == {"sha256", "n_names"}
    assert "changes.csv" in {p.name for p in out.iterdir()}  # P01's two visits still pair


@pytest.mark.parametrize("text, says", [
    (None, "cannot be read"),
    ("real,pseudonym\nDoe_Jane,P01,extra\n", "row 1 is not two names"),
    ("real,pseudonym\nDoe_Jane,P01\nDoe_Jane,P09\n", "mapped to both"),
    ("real,pseudonym\n", "no names"),
    ("real,pseudonym\nDoe_Jane_1950-03-02,a/b\n", "is not a folder name"),
    ("real,pseudonym\nDoe_Jane,P01\nP01,P02\n", "is also a real name"),
    ("real,pseudonym\nDoe_Jane_1950-03-02,P01\nRoe_Rick_1960-01-01,P01\n", "would both be P01/baseline"),
])
def test_malformed_subject_map_is_one_line_b340(study, tmp_path, capsys, text, says):
    """B340: each malformed map (or one that makes two sessions one path) is one line naming --subject-map and the
    fix, exit 2, no output folder."""
    path = tmp_path / "map.csv"
    if text is not None:
        path.write_text(text)
    assert main(["track-all", str(study), "--out", str(tmp_path / "ta"), "--subject-map", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--subject-map" in err[0] and says in err[0]
    assert "real,pseudonym" in err[0] or "keep one" in err[0]  # the fix
    assert not (tmp_path / "ta").exists()


def _numbers(obj, where=""):
    """Every number of a JSON object by where it stands (keys as they are)."""
    if isinstance(obj, dict):
        return {k2: v for k, val in obj.items() for k2, v in _numbers(val, f"{where}/{k}").items()}
    if isinstance(obj, list):
        return {k2: v for i, val in enumerate(obj) for k2, v in _numbers(val, f"{where}/{i}").items()}
    return {where: obj} if isinstance(obj, int | float) and not isinstance(obj, bool) else {}


def test_track_all_subject_map_numeric_subject_folders(tmp_path, monkeypatch, capsys):
    """C86 amended (session 35, review R3 finding 2): subject folders named 1 and 2 (users 8630, 8631) mapped to
    P01, P02: the batch tracks (it failed on a renamed JSON number before), the tree and sessions.csv's paths are the
    pseudonyms, and every number of summary.json and the tables is the run's without the map."""
    import pandas as pd

    root = tmp_path / "studyN"
    for folder, seed in (("1", 8630), ("2", 8631)):
        write_session(simulate("A", user_seed=seed), root / folder / "w")
    (tmp_path / "mapN.csv").write_text("real,pseudonym\n1,P01\n2,P02\n")
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "plain")]) == 0
    assert main(["track-all", "--no-plot", str(root), "--subject-map", str(tmp_path / "mapN.csv"),
                 "--out", str(tmp_path / "share")]) == 0
    share, plain = tmp_path / "share", tmp_path / "plain"
    assert sorted(p.name for p in share.iterdir() if p.is_dir()) == ["P01", "P02"]
    assert list(pd.read_csv(share / "sessions.csv")["path"]) == ["P01/w", "P02/w"]
    for folder, pseudo in (("1", "P01"), ("2", "P02")):
        red = json.loads((share / pseudo / "w" / "summary.json").read_text())
        org = json.loads((plain / folder / "w" / "summary.json").read_text())
        assert _numbers(red) == _numbers(org) and red["distance_m"] == org["distance_m"]
        for name in ("steps.csv", "trajectory.csv"):
            assert (share / pseudo / "w" / name).read_text() == (plain / folder / "w" / name).read_text()
    a, b = pd.read_csv(share / "bouts.csv"), pd.read_csv(plain / "bouts.csv")
    numeric = [c for c in b.columns if pd.api.types.is_numeric_dtype(b[c])]
    pd.testing.assert_frame_equal(a[numeric], b[numeric])


def test_rename_text_numeric_names_only_as_names():
    """C86 amended: a numeric real name is renamed as a path's folder or a name field's whole value, never a number
    inside a message or a count."""
    from pdrlearn.pseudonyms import rename_csv, rename_json, rename_text

    names = {"1": "P01", "Doe": "P02"}
    assert rename_text("1/w: line 1 column 32 of root/1", names) == "P01/w: line 1 column 32 of root/P01"
    assert rename_text("Doe walked 1 km", names) == "P02 walked 1 km"
    assert rename_json({"subject": "1", "visit": "1", "n": 1, "1/w": 1.0}, names) == {
        "subject": "P01", "visit": "1", "n": 1, "P01/w": 1.0}
    assert rename_csv("path,subject,n_strides\n1/w,1,1\n", names) == "path,subject,n_strides\nP01/w,P01,1\n"
