"""Decision B26 (docs/decisions/bad-input.md): `--force` replaces only a previous output of the same command
kind. A new-user trial lost data with it: `steps --out OTHER_SESSION/wGyroscope.csv --force` overwrote another
session's raw file, `steps --out S/steps.csv --force` the session's own labels, `calibrate --out
MODEL/manifest.json --force` killed a model, and `run` / `track` replaced each other's folders."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _refused(argv, capsys) -> str:
    rc = main([str(a) for a in argv])
    err = [ln for ln in capsys.readouterr().err.strip().splitlines() if not ln.startswith("warning: ")]
    assert rc == 2 and len(err) == 1 and err[0].startswith("error: "), err
    return err[0]


@pytest.fixture()
def two_sessions(tmp_path) -> tuple[Path, Path]:
    a, b = tmp_path / "ph_copyA", tmp_path / "ph_copyB"
    shutil.copytree(WAIST, a)
    shutil.copytree(WAIST, b)
    return a, b


@pytest.fixture(scope="module")
def sim_a(tmp_path_factory) -> Path:
    s = tmp_path_factory.mktemp("force_sim") / "A"
    assert main(["simulate", "-s", "A", "-u", "1", "--out", str(s), "--json"]) == 0
    return s


def test_steps_force_never_overwrites_another_sessions_raw_file(two_sessions, capsys):
    a, b = two_sessions
    before = _snapshot(b)
    err = _refused(["steps", a, "--out", b / "wGyroscope.csv", "--force"], capsys)
    assert str(b / "wGyroscope.csv") in err and "session folder" in err
    assert _snapshot(b) == before


def test_steps_force_never_replaces_the_sessions_own_labels(two_sessions, capsys):
    _, b = two_sessions
    before = _snapshot(b)
    _refused(["steps", b, "--out", b / "steps.csv", "--force"], capsys)
    assert _snapshot(b) == before


def test_steps_force_replaces_its_own_table_but_not_a_foreign_csv(two_sessions, tmp_path, capsys):
    a, _ = two_sessions
    out = tmp_path / "det.csv"
    assert main(["steps", str(a), "--out", str(out)]) == 0
    assert main(["steps", str(a), "--out", str(out), "--force"]) == 0
    assert f"replaced {out}" in capsys.readouterr().err
    other = tmp_path / "notes.csv"
    other.write_text("a,b\n1,2\n")
    err = _refused(["steps", a, "--out", other, "--force"], capsys)
    assert "not a detected steps table" in err
    assert other.read_text() == "a,b\n1,2\n"


def test_calibrate_force_never_overwrites_a_bundle_manifest(tmp_path, capsys):
    b = tmp_path / "bundle"
    shutil.copytree(BUNDLE, b)
    before = _snapshot(b)
    err = _refused(["calibrate", WAIST, "--out", b / "manifest.json", "--force"], capsys)
    assert "waist parameters file" in err
    assert _snapshot(b) == before


def test_calibrate_force_replaces_its_own_parameters(tmp_path, capsys):
    p = tmp_path / "p.json"
    assert main(["calibrate", str(WAIST), "--out", str(p)]) == 0
    assert main(["calibrate", str(WAIST), "--out", str(p), "--force"]) == 0
    assert f"replaced {p}" in capsys.readouterr().err


def test_plot_force_replaces_only_its_own_figure(sim_a, tmp_path, capsys):
    png = tmp_path / "s.png"
    assert main(["plot", str(sim_a), "--out", str(png)]) == 0
    assert main(["plot", str(sim_a), "--out", str(png), "--force"]) == 0
    t = tmp_path / "t"
    assert main(["track", str(sim_a), "--method", "M2", "--out", str(t)]) == 0
    capsys.readouterr()
    before = _snapshot(t)
    _refused(["plot", sim_a, "--out", t / "path.png", "--force"], capsys)  # the track's figure
    err = _refused(["steps", sim_a, "--out", t / "mine.csv"], capsys)  # a new file the next --force would delete
    assert "holds a track" in err
    assert _snapshot(t) == before


def test_run_and_track_never_replace_each_others_folder(sim_a, tmp_path, capsys):
    t, r = tmp_path / "t", tmp_path / "r"
    assert main(["track", str(sim_a), "--method", "M2", "--out", str(t)]) == 0
    assert main(["run", str(BUNDLE), str(sim_a), "--out", str(r)]) == 0
    capsys.readouterr()
    bt, br = _snapshot(t), _snapshot(r)
    err = _refused(["run", BUNDLE, sim_a, "--out", t, "--force"], capsys)
    assert "holds a track" in err and "pdrlearn track" in err
    err = _refused(["track", sim_a, "--method", "M2", "--out", r, "--force"], capsys)
    assert "holds a run" in err
    assert _snapshot(t) == bt and _snapshot(r) == br
    assert main(["run", str(BUNDLE), str(sim_a), "--out", str(r), "--force"]) == 0  # its own kind: replaced
    assert json.loads((r / "summary.json").read_text())["pipeline"] == "runtime"


def test_track_force_never_replaces_a_session_folder(sim_a, tmp_path, capsys):
    s = tmp_path / "S"
    shutil.copytree(sim_a, s)
    for name in ("summary.json",):  # a session that happens to hold every file of a track
        (s / name).write_text(json.dumps({"pipeline": "plasys"}))
    before = _snapshot(s)
    err = _refused(["track", s, "--method", "M2", "--out", s, "--force"], capsys)
    assert "holds a session" in err
    assert _snapshot(s) == before


def test_evaluate_all_force_never_replaces_a_train_all_models_folder(tmp_path, capsys):
    models = tmp_path / "models"
    shutil.copytree(BUNDLE, models / "u1")  # a user folder with a manifest.json + the summary: train-all's
    manifest = json.loads((models / "u1" / "manifest.json").read_text())
    (models / "cohort_summary.csv").write_text("user,ok\nu1,True\n")
    cohort = tmp_path / "cohort"
    (cohort / "u1" / "test").mkdir(parents=True)
    before = _snapshot(models)
    err = _refused(["evaluate-all", models, cohort, "--out", models, "--force", "--serial"], capsys)
    assert "per-user model directories" in err
    assert _snapshot(models) == before and manifest
