"""Decision C74: ``--methods`` gives one task its own methods (``direction=fusion,heuristic``), the plain methods
before any ``TASK=`` the other tasks'; a bad item is one line naming the option."""

from __future__ import annotations

import json
import re

import pytest

from pdrlearn.classify import load_model, train_user
from pdrlearn.cli import main
from pdrlearn.cli.common import split_methods
from pdrlearn.errors import DataError
from tests.test_classify_training import labelled_session


def test_split_methods_reads_plain_and_per_task_lists():
    assert split_methods(None) == (None, {})
    assert split_methods("nn,svm") == (["nn", "svm"], {})
    assert split_methods("direction=fusion,heuristic") == (None, {"direction": ["fusion", "heuristic"]})
    assert split_methods("nn, svm, direction=fusion,heuristic, length=nn") == (
        ["nn", "svm"], {"direction": ["fusion", "heuristic"], "length": ["nn"]})
    for bad, why in (("direction=", "is not TASK=METHOD"), ("=nn", "is not TASK=METHOD"),
                     ("direction=nn,direction=svm", "given twice"), ("direction=a=b", "is not TASK=METHOD")):
        with pytest.raises(DataError, match=why):
            split_methods(bad)


def test_train_user_gives_a_task_its_own_methods(tmp_path):
    s = [labelled_session(1, 8)]
    m = train_user(s, tasks=["terrain", "direction"], methods=["svm"], cv=2,
                   task_methods={"direction": ["heuristic", "fusion"]})
    assert set(m.tasks["terrain"].cv) == {"svm"}
    assert set(m.tasks["direction"].cv) == {"heuristic", "fusion"}
    assert m.tasks["direction"].chosen[0] in ("heuristic", "fusion")
    assert m.settings["task_methods"] == {"direction": ["heuristic", "fusion"]}
    m.save(tmp_path / "u")
    assert load_model(tmp_path / "u").tasks["direction"].chosen == m.tasks["direction"].chosen
    with pytest.raises(DataError, match=r"^methods \(--methods\): unknown task 'heading'"):
        train_user(s, methods=["svm"], cv=2, task_methods={"heading": ["nn"]})
    with pytest.raises(DataError, match=r"^methods \(--methods\): unknown method knn"):
        train_user(s, methods=["svm"], cv=2, task_methods={"direction": ["knn"]})


def test_train_cli_per_task_methods_and_one_line_errors(tmp_path, capsys):
    from pdrlearn.io import write_session
    from pdrlearn.sim.simulate import simulate

    data = tmp_path / "direction"
    write_session(simulate("direction", user_seed=6141), data)
    for bad, start in (("direction=fusion,hueristic", "error: methods (--methods): unknown method hueristic"),
                       ("heading=nn", "error: methods (--methods): unknown task 'heading'"),
                       ("direction=", "error: --methods 'direction=': 'direction=' is not TASK=METHOD")):
        rc = main(["train", str(data), "--out", str(tmp_path / "bad"), "--methods", bad])
        err = capsys.readouterr().err.strip()
        assert rc == 2 and err.startswith(start) and "\n" not in err, err
        assert not (tmp_path / "bad").exists()
    rc = main(["train", str(data), "--out", str(tmp_path / "m"), "--tasks", "direction", "--cv", "3",
               "--methods", "svm,direction=fusion,heuristic", "--units", "foot,waist,fused", "--json"])
    out = capsys.readouterr()
    assert rc == 0, out.err
    t = json.loads(out.out)["tasks"]["direction"]
    assert set(t["cv"]) == {"fusion", "heuristic"} and t["chosen"]["method"] in ("fusion", "heuristic")
    from typer.testing import CliRunner

    from pdrlearn.cli import app

    for cmd in ("train", "train-all"):  # documented in --help, one text
        out = re.sub(r"[\s│]+", "", CliRunner().invoke(app, [cmd, "--help"], env={"COLUMNS": "300"}).output)
        assert "'direction=fusion,heuristic'" in out and "decisionC74" in out, out
