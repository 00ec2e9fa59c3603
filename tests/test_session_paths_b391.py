"""Decision B391 (trial T4 finding 3): ``train_user``, ``training_data`` and ``evaluate_model`` take a session
folder's path (``str`` / ``Path``, alone or in a list) or a folder of sessions, as README says and ``pdrlearn train``
reads them; a path that is no session is one DataError naming it. Decision B392: a folder whose sessions lie one
level further down names where they are."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.classify import evaluate_model, train_user
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

KW = {"tasks": ["terrain"], "methods": ["svm"], "units": ["foot"], "cv": 3, "distance_calibration": False}


@pytest.fixture(scope="module")
def user_tree(tmp_path_factory):
    root = tmp_path_factory.mktemp("u9604")
    write_session(simulate("terrain", user_seed=9604), root / "calib" / "terrain")
    write_session(simulate("terrain", user_seed=9604, seed=7), root / "test" / "terrain")
    return root


def test_train_user_and_evaluate_model_take_paths(user_tree):
    one = train_user([str(user_tree / "calib" / "terrain")], **KW)
    assert one.data_summary["sessions"] == ["sim_terrain_u9604_normal_s0"]
    for given in (user_tree / "calib", str(user_tree / "calib" / "terrain"), [Path(user_tree / "calib")]):
        assert train_user(given, **KW).data_summary["session_ids"] == one.data_summary["session_ids"]
    res = evaluate_model(one, str(user_tree / "test" / "terrain"), latency=False)
    assert res["sessions"] == ["sim_terrain_u9604_normal_s7"] and res["tasks"]["terrain"]["accuracy"] > 0.5
    assert evaluate_model(one, [user_tree / "test"], latency=False)["sessions"] == res["sessions"]


def test_a_path_that_is_no_session_is_one_line_naming_it(user_tree, tmp_path):
    with pytest.raises(DataError, match="no such folder"):
        train_user(str(tmp_path / "nowhere"), **KW)
    (tmp_path / "empty").mkdir()
    with pytest.raises(DataError, match=r"empty: neither a session folder"):
        evaluate_model(train_user(user_tree / "calib", **KW), tmp_path / "empty", latency=False)


def test_train_a_folder_with_sessions_one_level_down_names_them(user_tree, capsys):
    with pytest.raises(DataError, match=r"found sessions one level further down, in .*calib, .*test: pass one"):
        train_user(user_tree, **KW)
    capsys.readouterr()
    assert main(["train", str(user_tree), "--out", str(user_tree.parent / "m9604"), "--tasks", "terrain"]) == 2
    err = capsys.readouterr().err
    assert "one level further down" in err and str(user_tree / "calib") in err and "Traceback" not in err


def test_evaluate_with_the_arguments_swapped_gives_the_order(user_tree, tmp_path, capsys):
    train_user(user_tree / "calib", **KW).save(tmp_path / "m")
    capsys.readouterr()
    assert main(["evaluate", str(user_tree / "test"), str(tmp_path / "m")]) == 2
    err = capsys.readouterr().err
    assert "the model comes first" in err and f"pdrlearn evaluate {tmp_path / 'm'} {user_tree / 'test'}" in err
    assert len(err.strip().splitlines()) == 1


def test_a_missing_waist_sensor_names_the_unit_the_model_reads():
    """B392 (T4): a heuristic/waist or nn/waist model on a foot-only session said `(of both units, unit
    'combined')`; heuristic fusion reads both units and says so."""
    from pdrlearn.classify.training import make_estimator, training_data
    from pdrlearn.errors import MissingSensorError

    s = simulate("terrain", user_seed=9604)
    d = training_data([s], "terrain")
    s.streams = {n: st for n, st in s.streams.items() if not n.startswith("w")}
    foot = training_data([s], "terrain")
    for method, said in (("heuristic", "(unit='waist')"), ("nn", "(unit='waist')")):
        est = make_estimator("terrain", method, "waist")
        feats = est if method == "heuristic" else est[0]
        if method == "heuristic":
            est.fit(d.X, d.y)
        with pytest.raises(MissingSensorError) as exc:
            (est.predict if method == "heuristic" else feats.transform)(foot.X)
        assert said in str(exc.value) and "combined" not in str(exc.value)
    fusion = make_estimator("terrain", "fusion", "fused").fit(d.X, d.y)
    with pytest.raises(MissingSensorError, match="of both units, heuristic fusion"):
        fusion.predict(foot.X)
