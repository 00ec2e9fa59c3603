"""Decision B422 (session 42, trial T1 finding F1): `--force` replaced an output folder as a whole and deleted
what a user had added to it (clinician_notes.txt, a sub-folder) for track, run, train and export; simulate,
import and train-all already refused. Every --force folder replacement now refuses, in one line naming the
foreign entries, and deletes nothing; the command's own earlier output is still replaced."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.own_files import OWN, foreign_entries
from tests.cli_helpers import simulated_session_and_model

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
ROUTE = ["--route", "stand:2, straight:6, stand:2"]


@pytest.fixture(scope="module")
def made(tmp_path_factory) -> dict[str, Path]:
    root = tmp_path_factory.mktemp("b422")
    terrain, model = simulated_session_and_model(root, "terrain")
    walk = root / "walk"
    assert main(["simulate", *ROUTE, "--user-seed", "11850", "--out", str(walk), "--json"]) == 0
    cohort = root / "cohort" / "siteA"
    cohort.mkdir(parents=True)
    shutil.copytree(walk, cohort / "s1")
    return {"terrain": terrain, "model": model, "walk": walk, "cohort": root / "cohort"}


#: command -> its argv with OUT for the output folder (tiny inputs; --no-plot where there is a figure)
COMMANDS = {
    "track": lambda m: ["track", m["walk"], "--out", "OUT", "--no-plot"],
    "run": lambda m: ["run", "--no-plot", BUNDLE, m["walk"], "--out", "OUT"],
    "train": lambda m: ["train", m["terrain"], "--out", "OUT", "--methods", "heuristic", "--tasks", "terrain",
                        "--cv", "3"],
    "export": lambda m: ["export", m["model"], "--out", "OUT"],
    "train-report": lambda m: ["train", m["terrain"], "--out", "OUT.model", "--report", "OUT", "--methods",
                               "heuristic", "--tasks", "terrain", "--cv", "3"],
    "report": lambda m: ["report", m["model"], "--out", "OUT"],
    "track-all": lambda m: ["track-all", m["cohort"], "--out", "OUT", "--no-plot", "--jobs", "1"],
    "simulate": lambda m: ["simulate", *ROUTE, "--user-seed", "11851", "--out", "OUT"],
}


#: the folder kind (pdrlearn.outfolder.FOLDER_KINDS) of a command whose name is not its kind
KIND = {"train": "model", "export": "bundle", "simulate": "session"}


def _argv(command: str, made: dict, out: Path) -> list[str]:
    return [str(a).replace("OUT", str(out)) if str(a).startswith("OUT") else str(a) for a in COMMANDS[command](made)]


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_force_refuses_to_delete_added_files_and_still_replaces_its_own(command, made, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(_argv(command, made, out)) == 0
    (out / "clinician_notes.txt").write_text("keep")
    (out / "sub").mkdir()
    (out / "sub" / "x").write_text("k")
    before = _snapshot(out)
    capsys.readouterr()
    assert main([*_argv(command, made, out), "--force"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {out}: holds clinician_notes.txt, sub/, which "), err
    assert "--force would delete" in err[0]
    assert _snapshot(out) == before  # nothing deleted, nothing written
    (out / "clinician_notes.txt").unlink()
    shutil.rmtree(out / "sub")
    assert main([*_argv(command, made, out), "--force"]) == 0  # its own earlier output: replaced as before
    assert foreign_entries(out, OWN[KIND.get(command, command)]) == []  # every file it writes is its own


def test_a_file_added_inside_a_track_all_session_folder_is_named_with_its_path(made, tmp_path, capsys):
    out = tmp_path / "tracks"
    assert main(_argv("track-all", made, out)) == 0
    (out / "siteA" / "s1" / "notes.txt").write_text("keep")
    before = _snapshot(out)
    capsys.readouterr()
    assert main([*_argv("track-all", made, out), "--force"]) == 2
    err = capsys.readouterr().err
    assert "holds siteA/s1/notes.txt, which 'pdrlearn track-all' did not write" in err
    assert _snapshot(out) == before


def test_a_symlink_is_never_the_commands_own(tmp_path):
    (tmp_path / "steps.csv").symlink_to(tmp_path / "elsewhere.csv")
    (tmp_path / "summary.json").write_text("{}")
    assert foreign_entries(tmp_path, OWN["track"]) == ["steps.csv"]


def test_file_manager_clutter_and_atomic_leftovers_are_not_foreign(tmp_path):
    (tmp_path / ".DS_Store").write_text("")
    (tmp_path / ".x.tmp-1-habcdef01-zz").mkdir()
    assert foreign_entries(tmp_path, OWN["track"]) == []
