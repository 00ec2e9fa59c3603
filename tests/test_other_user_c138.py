"""Decision C138 (trial T4 finding 1): a per-user model scored on (or tracking) another user's sessions says so in
one line, in ``evaluate``'s JSON ``warnings`` and in ``track``'s; the model's own user, a pooled model or sessions
naming no user give nothing (a pseudonymised model: decision C152, tests/test_other_user_c152.py)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.classify import evaluate_model, train_user
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate
from pdrlearn.track.plasys import track_plasys


@pytest.fixture(scope="module")
def model_9600():
    return train_user([simulate("terrain", user_seed=9600)], tasks=["terrain"], methods=["svm"], units=["foot"],
                      cv=3, distance_calibration=False)


def _c138(lines):
    return [w for w in lines if "decision C138" in w]


def test_evaluate_warns_when_the_sessions_are_another_users(model_9600, tmp_path, capsys):
    other = write_session(simulate("terrain", user_seed=9601, seed=7), tmp_path / "u9601")
    model_9600.save(tmp_path / "m")
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "m"), str(other), "--json"]) == 0
    cap = capsys.readouterr()
    res = json.loads(cap.out)
    [line] = _c138(res["warnings"])
    assert "trained on user.seed:9600" in line and "user.seed:9601" in line and "not the model's held-out" in line
    assert "C138" in res["warning_codes"]
    assert cap.err.count("decision C138") == 1  # one line on stderr
    own = evaluate_model(model_9600, [simulate("terrain", user_seed=9600, seed=7)], latency=False)
    assert not _c138(own["warnings"])


def test_no_user_known_on_either_side_says_nothing(model_9600):
    anon = simulate("terrain", user_seed=9601, seed=7)
    anon.meta.pop("user", None)
    anon.meta.pop("user_seed", None)
    assert not _c138(evaluate_model(model_9600, [anon], latency=False)["warnings"])
    pooled = train_user([simulate("terrain", user_seed=9600), simulate("terrain", user_seed=9602)],
                        tasks=["terrain"], methods=["svm"], units=["foot"], cv=3, distance_calibration=False)
    assert not _c138(evaluate_model(pooled, [simulate("terrain", user_seed=9601, seed=7)], latency=False)["warnings"])
    # a model named by --user (E174) warns since decision C152: tests/test_other_user_c152.py


def test_track_with_another_users_model_warns(model_9600):
    walk = simulate("A", 9603)
    res = track_plasys(walk, method="M3", model=model_9600)
    [line] = _c138(res.info["warnings"])
    assert line.startswith("track: the model was trained on user.seed:9600")
    own = track_plasys(simulate("A", 9600), method="M3", model=model_9600)
    assert not _c138(own.info["warnings"])
