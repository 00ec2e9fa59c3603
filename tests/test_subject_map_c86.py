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
                 "--json"]) == 0
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
