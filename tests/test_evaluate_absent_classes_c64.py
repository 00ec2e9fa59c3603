"""Decision C64 (session-26 newcomer trial, U1): `evaluate` on test data without a class (the Workflow's held-out
terrain exercise has no backward step) scored that task 100 % with no word; it now names the absent classes in one
warning per task and in the JSON (``tasks.<t>.absent_classes``)."""

from __future__ import annotations

import json

import numpy as np

from pdrlearn.classify.evaluation import absent_classes, absent_warning
from pdrlearn.cli import main


def test_absent_classes_and_warning_by_hand():
    assert absent_classes(["flat", "up", "down"], np.array(["flat", "up", "flat"])) == ["down"]
    assert absent_classes(["forward", "backward"], np.array(["backward", "forward"])) == []
    assert absent_warning("terrain", []) is None
    line = absent_warning("terrain", ["up", "down"])
    assert line.startswith("terrain: the test data hold no 'up' or 'down' step; its accuracy says nothing about them")
    assert "--scenario terrain" in line and "C64" in line
    assert "--scenario" not in absent_warning("my_task", ["x"])  # no scenario of that name to suggest


def test_evaluate_names_a_class_the_test_data_lack(tmp_path, capsys):
    train, test = tmp_path / "direction", tmp_path / "terrain"
    assert main(["simulate", "--scenario", "direction", "--user-seed", "3", "--out", str(train), "--json"]) == 0
    assert main(["simulate", "--scenario", "terrain", "--user-seed", "3", "--seed", "7", "--out", str(test),
                 "--json"]) == 0
    model = tmp_path / "model"
    assert main(["train", str(train), "--out", str(model), "--methods", "heuristic", "--tasks", "direction",
                 "--cv", "3", "--json"]) == 0
    capsys.readouterr()
    assert main(["evaluate", str(model), str(test), "--json"]) == 0
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    line = "direction: the test data hold no 'backward' step; its accuracy says nothing about them"
    assert out["tasks"]["direction"]["absent_classes"] == ["backward"]
    assert [w for w in out["warnings"] if w.startswith(line)]
    assert f"warning: {line}" in cap.err
    # test data holding both classes: no such warning, an empty list
    assert main(["evaluate", str(model), str(train), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["tasks"]["direction"]["absent_classes"] == []
    assert not [w for w in out["warnings"] if "the test data hold no" in w]
