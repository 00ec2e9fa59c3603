"""Set-ups shared by the CLI test files (session 46, I2: made once per test run instead of once per file).

Every folder returned here is read-only by contract (root ignores file modes, so it is not enforced): a test that
edits a session or a model copies it first (``shutil.copytree``), as the callers do.
"""

from __future__ import annotations

from pathlib import Path

from tests.runtime_helpers import made_once

_CACHE: dict[str, Path] = {}


def _make_cli_sessions(root: Path) -> None:
    """Scenario A (user 1, 26.5 s, foot + waist, labelled), the calibration exercise "terrain" (user 3) and a
    heuristic terrain model trained on it (3 folds), written by the CLI as a user would."""
    from pdrlearn.cli import main

    assert main(["simulate", "-s", "A", "-u", "1", "--out", str(root / "A"), "--json"]) == 0
    assert main(["simulate", "-s", "terrain", "-u", "3", "--out", str(root / "terrain"), "--json"]) == 0
    assert main(["train", str(root / "terrain"), "--out", str(root / "model"), "--methods", "heuristic", "--tasks",
                 "terrain", "--cv", "3", "--json"]) == 0


def cli_sessions(tmp_path_factory) -> dict[str, Path]:
    """``{"root", "A", "terrain", "model"}`` of :func:`_make_cli_sessions`, made once per test run
    (:func:`tests.runtime_helpers.made_once`): tests/test_cli_outputs.py and tests/test_cli_bad_input_sweep.py each
    made the same three before (~5 s of simulating and training per file)."""
    if "root" not in _CACHE:
        _CACHE["root"] = made_once(tmp_path_factory, "cli_sessions_i2", _make_cli_sessions)
    root = _CACHE["root"]
    return {"root": root, "A": root / "A", "terrain": root / "terrain", "model": root / "model"}


def edited_copy(src: Path, folder: Path, key: str, edit, copy=None) -> Path:
    """``folder / key / "session"``: a copy of ``src`` changed by ``edit(copy)``, made at the first call and returned
    as it is at the next ones (a ``done`` marker beside it: ``edit`` may delete the copy). For the tables of
    malformed sessions that several commands read (session 46: each case copied and edited its own; the commands
    stop while reading it or write only into their --out): read-only, like :func:`cli_sessions`'s folders.
    ``copy(src, dst)``: how to copy (``shutil.copytree`` by default)."""
    import shutil

    s = folder / key / "session"
    done = s.with_name("done")
    if not done.exists():
        (copy or shutil.copytree)(src, s)
        edit(s)
        done.touch()
    return s


#: the real foot recordings of the 204.8 Hz terrain bundle (gaitmap, left foot: level, stairs up, stairs down)
GAITMAP_TRAIN = ("gaitmap_level_left", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left")


def _make_gaitmap_bundle(root: Path) -> None:
    """An SVM terrain model trained on :data:`GAITMAP_TRAIN` (3 folds, seed 0) and its bundle with their foot frame."""
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.io import read_session
    from tests.conftest import REAL

    train = [read_session(REAL / n) for n in GAITMAP_TRAIN]
    train_user(train, tasks=["terrain"], cv=3, seed=0, methods=["svm"]).save(root / "model")
    export_model(root / "model", root / "bundle", frames={"foot": train[0].frames["foot"].to_dict()})


def gaitmap_bundle(tmp_path_factory) -> Path:
    """The folder holding ``model`` and ``bundle`` of :func:`_make_gaitmap_bundle`, made once per test run
    (test_runtime_resample.py's 204.8 Hz bundle and test_runtime_parity.py's real-recording test trained the same
    model each); read-only, like :func:`cli_sessions`'s folders."""
    if "gaitmap" not in _CACHE:
        _CACHE["gaitmap"] = made_once(tmp_path_factory, "gaitmap_bundle_i2", _make_gaitmap_bundle)
    return _CACHE["gaitmap"]
