"""Decision B12: `--force` replaces a previous output of the same command only. A model directory and a
runtime bundle share the `manifest.json` marker, so `export --force` must not take a model directory for a
previous bundle (`export M --out M --force` deleted the trained model) and `train --force` must not replace
a bundle; a folder that is one of the command's inputs is never replaced."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main
from tests.cli_helpers import simulated_session_and_model

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def model(tmp_path_factory) -> dict[str, Path]:
    terrain, m = simulated_session_and_model(tmp_path_factory.mktemp("force_kinds"), "terrain")
    return {"terrain": terrain, "model": m}


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _refused(argv, capsys) -> str:
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and err[0].startswith("error: "), err
    return err[0]


def test_export_force_never_replaces_its_own_model(model, tmp_path, capsys):
    m = tmp_path / "m"
    shutil.copytree(model["model"], m)
    before = _snapshot(m)
    err = _refused(["export", m, "--out", m, "--force"], capsys)
    assert str(m) in err and "model directory" in err
    assert _snapshot(m) == before  # the trained model is still there


def test_export_force_never_replaces_another_model_directory(model, tmp_path, capsys):
    other = tmp_path / "other_model"
    shutil.copytree(model["model"], other)
    before = _snapshot(other)
    _refused(["export", model["model"], "--out", other, "--force"], capsys)
    assert _snapshot(other) == before


def test_train_force_never_replaces_a_bundle(model, tmp_path, capsys):
    b = tmp_path / "bundle"
    shutil.copytree(BUNDLE, b)
    before = _snapshot(b)
    err = _refused(["train", model["terrain"], "--out", b, "--methods", "heuristic", "--tasks", "terrain",
                    "--cv", "3", "--force"], capsys)
    assert "runtime bundle" in err
    assert _snapshot(b) == before


def test_export_force_still_replaces_a_bundle(model, tmp_path, capsys):
    b = tmp_path / "b"
    assert main(["export", str(model["model"]), "--out", str(b)]) == 0
    assert main(["export", str(model["model"]), "--out", str(b), "--force"]) == 0
    assert f"replaced {b}" in capsys.readouterr().err


def test_run_summary_scores_the_strides_like_track_streaming(tmp_path, capsys):
    """B14 / L36: `run`'s summary is evaluate_track's, so it reports the stride F1 that `track --streaming`
    (the same kernel) reports; before, the runtime's steps.csv had no `unit` column and step_f1 was missing."""
    import json

    s = tmp_path / "A"
    assert main(["simulate", "-s", "A", "-u", "1", "--out", str(s), "--json"]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", str(BUNDLE), str(s), "--out", str(tmp_path / "r"), "--json"]) == 0
    rj = json.loads(capsys.readouterr().out)
    assert main(["track", "--no-plot", str(s), "--method", "M2", "--streaming", "--out", str(tmp_path / "t"),
                 "--json"]) == 0
    tj = json.loads(capsys.readouterr().out)
    assert "step_f1" in tj and "step_f1" in rj
    assert rj["n_steps"] == tj["n_steps"] and abs(rj["step_f1"] - tj["step_f1"]) < 1e-9


@pytest.mark.parametrize("command", ["track", "run", "report", "train", "export"])
def test_a_file_in_the_way_of_the_output_folder_is_one_error_line(model, tmp_path, capsys, command):
    """`--out FILE/sub` (a file where a parent folder must go): one line naming it before any work, exit 2;
    before, FileExistsError escaped as a traceback after the command had done all its work."""
    (tmp_path / "afile").write_text("not a folder")
    out = tmp_path / "afile" / "sub"
    argv = {"track": ["track", "--no-plot", model["terrain"], "--method", "M2", "--out", out],
            "run": ["run", "--no-plot", BUNDLE, model["terrain"], "--out", out],
            "report": ["report", model["model"], "--out", out],
            "train": ["train", model["terrain"], "--out", out, "--methods", "heuristic", "--tasks", "terrain",
                      "--cv", "3"],
            "export": ["export", model["model"], "--out", out]}[command]
    err = _refused(argv, capsys)
    assert "afile" in err and "is a file" in err


def test_an_output_the_system_refuses_is_one_error_line(model, tmp_path, capsys):
    """An output folder/file that cannot be created (here under /proc, where even root cannot mkdir) is one
    `error:` line naming the path, not an OSError traceback; exit 2, nothing written (decision B152)."""
    if not Path("/proc/self").is_dir():
        pytest.skip("needs Linux /proc")
    for argv in (["track", "--no-plot", model["terrain"], "--method", "M2", "--out", "/proc/pdrlearn_test_out"],
                 ["steps", model["terrain"], "--out", "/proc/pdrlearn_test_out.csv"]):
        rc = main([str(a) for a in argv])
        # decision L290: M2's foot (+0.34 m) and the barometer's net (-0.28 m) on this 8.5 m up-and-down exercise
        # differ by 0.61 m, over L145's 0.58 m: that warning comes before the write; the error is still one line
        err = [e for e in capsys.readouterr().err.strip().splitlines() if not e.startswith("warning: ")]
        assert rc == 2 and len(err) == 1 and err[0].startswith("error: /proc/"), err  # decision B152: was 1
