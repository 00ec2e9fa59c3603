"""Decision S98 (session 42, trial T2 finding F9): ``pdrlearn simulate --length-bounds SHORT_NORMAL,NORMAL_LONG``
labels steps.csv's ``length_class`` by a slow walker's own bounds (S81 keeps the user's own otherwise, so every
stride of a 0.3 m-step length exercise was ``short``); bad bounds are one ``error:`` line and no folder; train's
refusal of a length task without every class names the option."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main

USER = 11846  # this session's simulated users for FC: 11840-11849
ROUTE = ["--route", "straight:3:short, stand:1, straight:3:normal, stand:1, straight:3:long", "--stand", "1",
         "--step-length", "0.3", "--step-time", "0.8", "--rate", "20", "--user-seed", str(USER), "--no-noise"]


def _classes(d):
    import pandas as pd

    st = pd.read_csv(d / "steps.csv")
    return st, json.loads((d / "meta.json").read_text())


def test_length_bounds_label_a_slow_walkers_own_classes_s98(tmp_path):
    assert main(["simulate", *ROUTE, "--out", str(tmp_path / "own")]) == 0
    own, own_meta = _classes(tmp_path / "own")
    assert set(own["length_class"]) == {"short"}  # S81: the healthy user's bounds, the trial's finding
    assert main(["simulate", *ROUTE, "--length-bounds", "0.45,0.65", "--out", str(tmp_path / "b")]) == 0
    st, meta = _classes(tmp_path / "b")
    assert meta["length_class_bounds_m"] == [0.45, 0.65] and meta["user"]["length_bounds_m"] == [0.45, 0.65]
    assert "length_bounds_m" not in own_meta["user"]  # written only when given
    walk = st[st["kind"] == "walk"]
    expect = np.where(walk["length_m"] <= 0.45, "short", np.where(walk["length_m"] <= 0.65, "normal", "long"))
    assert (walk["length_class"].to_numpy() == expect).all()
    assert {"short", "normal", "long"} <= set(walk["length_class"])  # the exercise's three items, each its class


@pytest.mark.parametrize("bad", ["0.6", "0.6,0.4", "0,0.5", "0.4,nan", "a,b", "0.4,5"])
def test_bad_length_bounds_are_one_line_and_no_folder_s98(tmp_path, capsys, bad):
    assert main(["simulate", *ROUTE, f"--length-bounds={bad}", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--length-bounds" in err and "e.g." in err, err
    assert not (tmp_path / "x").exists()


def test_train_refusal_of_a_one_class_length_task_names_the_way_out_s98():
    from pdrlearn.classify.training import TaskData, check_classes
    from pdrlearn.errors import DataError

    y = np.array(["short"] * 20)
    data = TaskData("length", np.zeros((20, 1)), y, np.zeros(20, int))
    with pytest.raises(DataError, match=r"simulate the exercise with --length-bounds .*decision S98"):
        check_classes(data)
