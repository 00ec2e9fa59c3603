"""Decision E266 (session 42, fixer FT, review R2 finding 7): with PDRLEARN_NO_PICKLE=1, `refuse_pickle` called
every model argument "a model folder is pickle ... use its bundle instead", a bundle and a folder that does not exist
too; it now stays silent for those and the command's own line names what the path is."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdrlearn.classify.model_dir import refuse_pickle
from pdrlearn.cli import main
from pdrlearn.errors import ModelError

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture
def no_pickle(monkeypatch):
    monkeypatch.setenv("PDRLEARN_NO_PICKLE", "1")


def test_refuse_pickle_is_silent_for_a_bundle_and_a_missing_folder(tmp_path, no_pickle):
    refuse_pickle(BUNDLE)
    refuse_pickle(tmp_path / "nosuchdir")
    (tmp_path / "model").mkdir()  # a folder that is no bundle (a model directory, a train-all folder): refused
    (tmp_path / "model" / "manifest.json").write_text(json.dumps({"kind": "pdrlearn user model"}))
    with pytest.raises(ModelError, match="a model folder is pickle"):
        refuse_pickle(tmp_path / "model")
    with pytest.raises(ModelError, match="a model folder is pickle"):
        refuse_pickle(tmp_path)


@pytest.mark.parametrize("argv, said", [
    (["track", "S", "--model", str(BUNDLE), "--out", "OUT", "--no-plot"], "an exported runtime bundle"),
    (["track", "S", "--model", "MISSING", "--out", "OUT", "--no-plot"], "no such model directory"),
    (["evaluate", "MISSING", "S"], "no such model directory"),
    (["export", str(BUNDLE), "--out", "OUT"], "an exported runtime bundle"),
])
def test_commands_give_their_own_line_for_a_bundle_or_missing_folder(argv, said, tmp_path, no_pickle, capsys):
    (tmp_path / "s").mkdir()  # refused before the session is read
    subs = {"S": str(tmp_path / "s"), "OUT": str(tmp_path / "out"), "MISSING": str(tmp_path / "nosuchdir")}
    assert main([subs.get(a, a) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and err.count("\n") == 1 and said in err and "pickle" not in err, err
