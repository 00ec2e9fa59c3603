"""Decision C29: train's CV folds grouped by user (--cv-groups user) when the sessions come from several users."""

from __future__ import annotations

import logging

import numpy as np
import pytest
from sklearn.neighbors import KNeighborsClassifier

from pdrlearn.classify.training import _folds, _oof_proba, session_user, train_user
from pdrlearn.cli import main
from pdrlearn.io import Session
from pdrlearn.sim import simulate


def _meta(meta):
    return Session(name="s", streams={}, meta=meta)


def test_session_user_reads_the_meta_json_user_or_subject():
    assert session_user(_meta({"user": "anna"})) == "user:anna"
    assert session_user(_meta({"user": {"seed": 7, "height_m": 1.7}})) == "user.seed:7"
    assert (session_user(_meta({"subject": {"cohort": "HA", "participant_id": "1001"}}))
            == "subject.cohort:HA.participant_id:1001")  # cohort C32: HA1001 and MS1001 are two people
    assert session_user(_meta({"subject": {"cohort": "healthy adult"}})) is None  # gaitmap: no id
    assert session_user(_meta({})) is None


def _toy(n_users=3, per_class=20, seed=0):
    """Each user's classes sit at user-specific random places: a 1-NN model recognises a user's own strides
    (pooled CV near 100 %) but learns nothing that carries to a new user."""
    rng = np.random.default_rng(seed)
    X, y, g = [], [], []
    for u in range(n_users):
        for c in ("a", "b", "c"):
            centre = rng.normal(0, 10, 5)
            X.append(centre + rng.normal(0, 0.1, (per_class, 5)))
            y += [c] * per_class
            g += [f"u{u}"] * per_class
    return np.vstack(X), np.array(y), np.array(g)


def test_user_folds_hold_out_whole_users_and_score_what_pooled_folds_hide():
    X, y, g = _toy()
    classes = np.array(["a", "b", "c"])
    pooled, n0 = _folds(y, 5, 0, "toy")
    grouped, n_users = _folds(y, 5, 0, "toy", groups=g)
    assert (n0, len(pooled)) == (0, 5)
    assert (n_users, len(grouped)) == (3, 3)  # leave-one-user-out: 3 users <= 5 folds
    for tr, te in grouped:
        assert len(set(g[te])) == 1 and not set(g[te]) & set(g[tr])
    knn = KNeighborsClassifier(1)
    acc = {name: np.mean(classes[_oof_proba(knn, X, y, f, classes).argmax(1)] == y)
           for name, f in (("pooled", pooled), ("user", grouped))}
    assert acc["pooled"] > 0.95
    assert acc["user"] < 0.7


def test_more_users_than_folds_gives_cv_folds_of_whole_users():
    X, y, g = _toy(n_users=7, per_class=4)
    folds, n_users = _folds(y, 3, 0, "toy", groups=g)
    assert (n_users, len(folds)) == (7, 3)
    for tr, te in folds:
        assert not set(g[te]) & set(g[tr])


def test_a_user_without_a_class_falls_back_to_stratified_folds(caplog):
    X, y, g = _toy(n_users=2)
    keep = ~((g == "u1") & (y == "c"))  # user u1 never walked class c: u0's fold would train without it
    with caplog.at_level(logging.WARNING):
        folds, n_users = _folds(y[keep], 5, 0, "toy", groups=g[keep])
    assert (n_users, len(folds)) == (0, 5)
    assert "CV by user not possible" in caplog.text


@pytest.fixture(scope="module")
def two_users():
    return [simulate("terrain", user_seed=u) for u in (1, 2)]


def test_train_passes_user_groups_only_when_asked(two_users, caplog):
    kw = dict(tasks=["terrain"], methods=["svm"], units=["foot"], cv=3, distance_calibration=False)
    steps = train_user(two_users, **kw)
    user = train_user(two_users, cv_groups="user", **kw)
    r0, r1 = steps.tasks["terrain"].cv["svm"]["foot"], user.tasks["terrain"].cv["svm"]["foot"]
    assert (r0["n_folds"], r0["cv_users"], steps.settings["cv_groups"]) == (3, 0, "steps")
    assert (r1["n_folds"], r1["cv_users"], user.settings["cv_users"]) == (2, 2, 2)
    one = train_user(two_users[:1], cv_groups="user", **kw)  # one user: the per-user model, unchanged
    assert one.tasks["terrain"].cv["svm"]["foot"]["n_folds"] == 3
    nameless = [two_users[0], Session(name="anon", streams=two_users[1].streams, steps=two_users[1].steps, meta={})]
    with caplog.at_level(logging.WARNING):
        m = train_user(nameless, cv_groups="user", **kw)
    assert m.tasks["terrain"].cv["svm"]["foot"]["cv_users"] == 0
    assert "session 'anon' names no user" in caplog.text


def test_cli_rejects_an_unknown_grouping(tmp_path, capsys):
    code = main(["train", str(tmp_path), "--out", str(tmp_path / "m"), "--cv-groups", "subject"])
    assert code != 0
    assert "--cv-groups 'subject'; choose one of steps, user" in capsys.readouterr().err


def test_user_folds_choose_c_and_fused_weights_inside_each_training_fold(two_users, monkeypatch):
    """Decision C57: with folds of whole users the SVM's C is chosen by each outer training fold's inner CV (the
    template keeps C="cv"), and the fused weights of a fold come from the other folds' steps; with folds of
    steps C5 holds (one C, fixed in the template)."""
    from pdrlearn.classify import training

    seen_c, votes = [], []
    real_oof, real_vote = training._oof_proba, training.fold_fitted_vote

    def spy_oof(est, X, y, folds, classes):
        seen_c.append(est.get_params().get("clf__C"))
        return real_oof(est, X, y, folds, classes)

    def spy_vote(probas, y_idx, folds):
        votes.append(len(folds))
        return real_vote(probas, y_idx, folds)

    monkeypatch.setattr(training, "_oof_proba", spy_oof)
    monkeypatch.setattr(training, "fold_fitted_vote", spy_vote)
    kw = dict(tasks=["terrain"], methods=["svm"], units=["foot", "waist", "fused"], cv=3, distance_calibration=False)
    train_user(two_users, cv_groups="user", **kw)
    assert seen_c == ["cv", "cv"] and votes == [2]
    seen_c.clear()
    train_user(two_users, **kw)
    assert all(isinstance(c, float) for c in seen_c) and votes == [2]


def test_fold_fitted_vote_scores_each_fold_with_weights_of_the_other_folds():
    from pdrlearn.classify.fusion import best_weights, soft_vote
    from pdrlearn.classify.training import fold_fitted_vote

    rng = np.random.default_rng(2450)
    y = rng.integers(0, 3, 60)
    probas = [rng.dirichlet(np.ones(3), 60) for _ in range(2)]
    folds = [(np.arange(30, 60), np.arange(30)), (np.arange(30), np.arange(30, 60))]
    P = fold_fitted_vote(probas, y, folds)
    for tr, te in folds:
        w = best_weights([p[tr] for p in probas], y[tr])
        assert np.allclose(P[te], soft_vote([p[te] for p in probas], w))


def test_session_folds_never_split_a_session(caplog):
    """Decision C59: --cv-groups session holds out whole sessions (the steps of one walk stay on one side); the
    record says how many sessions and which one each fold held out; one session falls back, said."""
    from pdrlearn.cli.train import cv_title, louo_line

    walks = [simulate("terrain", user_seed=2451, seed=s) for s in (0, 1, 2)]
    kw = dict(tasks=["terrain"], methods=["svm"], units=["waist"], cv=5, distance_calibration=False)
    m = train_user(walks, cv_groups="session", **kw)
    r = m.tasks["terrain"].cv["svm"]["waist"]
    names = [w.name for w in walks]
    assert (r["n_folds"], r["cv_sessions"], r["cv_users"]) == (3, 3, 0)
    assert sorted(r["folds"]["sessions"]) == sorted(names) and "users" not in r["folds"]
    sizes = {w.name: len(w.steps) for w in walks}
    assert r["folds"]["n_steps"] == [sizes[s] for s in r["folds"]["sessions"]]  # each fold: one whole session
    assert (m.settings["cv_groups"], m.settings["cv_sessions"]) == ("session", 3)
    assert cv_title(r) == "leave-one-session-out CV accuracy (3 sessions)"
    assert louo_line(r).startswith(f"chosen model per held-out session: {r['folds']['sessions'][0]} ")
    with caplog.at_level(logging.WARNING):
        one = train_user(walks[:1], cv_groups="session", **kw)
    assert one.tasks["terrain"].cv["svm"]["waist"]["cv_sessions"] == 0 and "one session" in caplog.text
