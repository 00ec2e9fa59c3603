"""Decision C152: C138's other-user line fires when the model's user and a session's user are both known and differ,
whatever their form (a name given at training, ``train --user P001``, E174; a session's pseudonym ``"user": "P002"``
or a simulated user's object), and says nothing when either is missing. Users 9993-9995."""

from __future__ import annotations

import json

import pytest

from pdrlearn.classify import evaluate_model, train_user
from pdrlearn.classify.training import other_user_line
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate
from pdrlearn.track.plasys import track_plasys


def _train(session, user=None):
    return train_user([session], tasks=["terrain"], methods=["svm"], units=["foot"], cv=3,
                      distance_calibration=False, user=user)


def _named(user_seed, name, seed=7):
    s = simulate("terrain", user_seed=user_seed, seed=seed)
    s.meta.pop("user_seed", None)
    if name is None:
        s.meta.pop("user", None)
    else:
        s.meta["user"] = name
    return s


@pytest.fixture(scope="module")
def p001():
    """A pseudonymised model: user 9993's sessions, stored as P001 (E174)."""
    return _train(simulate("terrain", user_seed=9993), user="P001")


def _c138(lines):
    return [w for w in lines if "decision C138" in w]


def test_a_pseudonymised_model_on_another_users_sessions_warns(p001):
    line = other_user_line(p001, [simulate("terrain", user_seed=9994, seed=7)])
    assert line is not None and "trained on P001" in line and "user.seed:9994" in line
    assert 'write "user": "P001" in their meta.json' in line  # the given name's own clause
    [line] = _c138(evaluate_model(p001, [_named(9994, "P002")], latency=False)["warnings"])
    assert "trained on P001" in line and "user:P002" in line


def test_a_pseudonymised_model_on_its_own_pseudonyms_sessions_says_nothing(p001):
    assert other_user_line(p001, [_named(9993, "P001")]) is None
    own = _train(_named(9993, "P001", seed=0))  # the sessions' pseudonym: the model's user is user:P001
    assert own.data_summary["users"] == ["user:P001"]
    assert other_user_line(own, [_named(9993, "P001")]) is None
    assert "trained on user:P001" in other_user_line(own, [_named(9994, "P002")])


def test_either_id_missing_says_nothing(p001):
    assert other_user_line(p001, [_named(9994, None)]) is None  # the session names no user
    anon = _train(_named(9993, None, seed=0))  # sessions naming none: the model names none
    assert anon.data_summary["users"] == []
    assert other_user_line(anon, [_named(9994, "P002")]) is None
    assert other_user_line(anon, [simulate("terrain", user_seed=9994, seed=7)]) is None


def test_evaluate_and_track_of_a_saved_pseudonymised_model_warn(p001, tmp_path, capsys):
    p001.save(tmp_path / "m")
    other = write_session(_named(9995, "P003"), tmp_path / "s")
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "m"), str(other), "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    [line] = _c138(res["warnings"])
    assert "trained on P001" in line and "user:P003" in line and "C138" in res["warning_codes"]
    walk = simulate("A", 9995)
    [line] = _c138(track_plasys(walk, method="M3", model=p001).info["warnings"])
    assert line.startswith("track: the model was trained on P001")
