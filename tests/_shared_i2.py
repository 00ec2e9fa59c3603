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
