"""Decision C16: a model keeps the training range of its inputs and says when it is applied to data unlike
them (a new user's trial: the demo's simulated 20 Hz model called a real 204.8 Hz level walk "up" with
p >= 0.99 and nothing but a calibration-rate line warned)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.classify import evaluate_model, load_model, train_user
from pdrlearn.classify.domain import (
    DEFAULT_WARN_SHARE,
    FRACTION_THRESHOLD,
    NO_RANGES_NOTE,
    STEP_THRESHOLD,
    FeatureRange,
    _leaves,
    domain_report,
    has_ranges,
    session_warning_line,
    step_score,
    summarize,
    warning_line,
)
from pdrlearn.io import Stream
from tests.test_classify_training import labelled_session

METHODS = ("dtw", "svm", "nn", "heuristic")


@pytest.fixture(scope="module")
def model():
    """Foot-unit terrain and direction models of every method, on the hand-made separable steps."""
    train = [labelled_session(1, 12), labelled_session(2, 12)]
    return train_user(train, tasks=["terrain", "direction"], methods=list(METHODS), units=["foot"], cv=3,
                      seed=0)


def _scaled(session, factor: float):
    """The session with the foot accelerometer and gyroscope signals (minus gravity) times ``factor``:
    steps of the same shape, far larger than any the model was trained on."""
    out = session.copy()
    for name in ("fAccelerometer", "fGyroscope"):
        st = session.streams[name]
        v = np.array(st.values, dtype=float)
        g = np.array([0.0, 0.0, 9.80665]) if name == "fAccelerometer" else 0.0
        out.streams[name] = Stream(name, st.t, (v - g) * factor + g)
    return out


def test_excess_is_hand_computed():
    r = FeatureRange("x", ["a", "b"], np.array([0.0, 10.0]), np.array([2.0, 20.0]), 100)
    F = np.array([[1.0, 15.0], [3.0, 15.0], [-1.0, 35.0], [np.nan, 10.0]])
    np.testing.assert_allclose(r.excess(F), [[0, 0], [0.5, 0], [0.5, 1.5], [0, 0]])
    assert FeatureRange.from_dict(json.loads(json.dumps(r.to_dict()))).to_dict() == r.to_dict()


@pytest.mark.parametrize("method", METHODS)
def test_every_classifier_keeps_the_range_of_its_own_inputs(model, method):
    """One mechanism for all: each fitted leaf stores ``training_range_`` of what its classifier reads."""
    est = model.tasks["terrain"].models[method]["foot"]
    assert has_ranges(est)
    r = est.training_range_
    assert r.n_steps == 72 and len(r.lo) == len(r.features) and np.all(r.hi >= r.lo)


@pytest.mark.parametrize("method", METHODS)
def test_same_kind_of_steps_do_not_warn(model, method):
    test = labelled_session(9, 12)
    pred = model.predict_steps(test, test.steps, method=method, unit="foot", windows="given")
    rep = model.domain_report(pred, warn_at=FRACTION_THRESHOLD)
    assert rep["out_of_domain_fraction"] < FRACTION_THRESHOLD, rep
    assert warning_line(rep) is None


@pytest.mark.parametrize("method", METHODS)
def test_larger_steps_than_trained_warn(model, method):
    test = _scaled(labelled_session(9, 12), 4.0)
    pred = model.predict_steps(test, test.steps, method=method, unit="foot", windows="given")
    assert (pred["ood_terrain"] > STEP_THRESHOLD).mean() > 0.9
    assert not model.domain_report(pred)["warn"]  # the warning is opt-in (decision C16)
    rep = model.domain_report(pred, warn_at=FRACTION_THRESHOLD)
    assert rep["warn"] and rep["out_of_domain_fraction"] > 0.9
    line = warning_line(rep)
    assert "\n" not in line and f"{method}/foot" in line and "pdrlearn train" in line
    assert line.startswith(f"{rep['tasks']['terrain']['n_out']} of 36 steps (")


def test_more_than_half_out_warns_once_by_default(model):
    """Decision C61: without --warn-out-of-domain, `track`'s domain check (shared by the offline and the
    streaming track) appends one short line when more than half the strides are out, naming the option; with
    the option, C16's detailed line alone (unchanged); in range, nothing."""
    from pdrlearn.track.plasys import domain_check

    far = _scaled(labelled_session(9, 12), 4.0)
    pred = model.predict_steps(far, far.steps, method="svm", unit="foot", windows="given")
    said: list[str] = []
    assert domain_check(model, pred, said)["out_of_domain_fraction"] > DEFAULT_WARN_SHARE
    assert len(said) == 1 and "\n" not in said[0] and "--warn-out-of-domain" in said[0], said
    assert "classes" in said[0] and "unreliable" in said[0] and "pdrlearn train" in said[0]
    detail: list[str] = []
    domain_check(model, pred, detail, FRACTION_THRESHOLD)
    assert detail == [warning_line(model.domain_report(pred, warn_at=FRACTION_THRESHOLD), what="strides")]
    near = labelled_session(9, 12)
    quiet: list[str] = []
    domain_check(model, model.predict_steps(near, near.steps, method="svm", unit="foot", windows="given"), quiet)
    assert quiet == []


def test_default_line_needs_more_than_half():
    """C61's share is strict: half the strides out is not enough, two of three is."""
    half = domain_report({"terrain": summarize(np.array([0.0, 1.0]), ["", "acc"], "svm/foot")})
    most = domain_report({"terrain": summarize(np.array([0.0, 1.0, 2.0]), ["", "acc", "acc"], "svm/foot")})
    assert session_warning_line(half) is None
    assert session_warning_line(most).startswith("2 of 3 strides (67 %) lie outside the model's training range")


def test_round_trip_keeps_the_ranges(model, tmp_path):
    model.save(tmp_path / "m")
    loaded = load_model(tmp_path / "m")
    for task, tm in model.tasks.items():
        for method, per in tm.models.items():
            a, b = per["foot"].training_range_, loaded.tasks[task].models[method]["foot"].training_range_
            assert a.to_dict() == b.to_dict()
    manifest = json.loads((tmp_path / "m" / "manifest.json").read_text())
    assert manifest["tasks"]["terrain"]["training_ranges"]["svm"] == {"foot": True}
    test = _scaled(labelled_session(9, 12), 4.0)
    np.testing.assert_array_equal(model.predict_steps(test)["ood_terrain"], loaded.predict_steps(test)["ood_terrain"])


def test_model_without_ranges_loads_and_says_so(model, tmp_path, caplog):
    """A model saved before C16 (no ``training_range_``): it loads and predicts; no check, no warning,
    a note in the result."""
    import copy

    old = copy.deepcopy(model)
    for tm in old.tasks.values():
        for per in tm.models.values():
            for est in per.values():
                for leaf, _ in _leaves(est, np.zeros((1, 1, 1))):
                    del leaf.training_range_
    old.save(tmp_path / "old")
    loaded = load_model(tmp_path / "old")
    assert not loaded.has_domain
    test = _scaled(labelled_session(9, 12), 4.0)
    pred = loaded.predict_steps(test)
    assert pred["ood_terrain"].isna().all() and loaded.domain_report(pred) is None
    assert step_score(loaded.tasks["terrain"].models["svm"]["foot"], np.zeros((2, 1, 1))) is None
    with caplog.at_level("WARNING"):
        res = evaluate_model(loaded, [test], latency=False, warn_out_of_domain=FRACTION_THRESHOLD)
    assert res["out_of_domain_fraction"] is None and res["out_of_domain"]["note"] == NO_RANGES_NOTE
    assert not [r for r in caplog.records if "training range" in r.getMessage()]


def test_evaluate_reports_the_fraction_and_warns_once(model, caplog):
    with caplog.at_level("WARNING"):
        same = evaluate_model(model, [labelled_session(9, 12)], latency=False, warn_out_of_domain=FRACTION_THRESHOLD)
    assert same["out_of_domain_fraction"] < FRACTION_THRESHOLD
    assert not [r for r in caplog.records if "training range" in r.getMessage()]
    far_session = _scaled(labelled_session(9, 12), 4.0)
    caplog.clear()
    with caplog.at_level("WARNING"):
        far = evaluate_model(model, [far_session], latency=False)  # default: reported, not warned
    assert far["out_of_domain_fraction"] > 0.9
    assert not [r for r in caplog.records if "training range" in r.getMessage()]
    with caplog.at_level("WARNING"):
        evaluate_model(model, [far_session], latency=False, warn_out_of_domain=FRACTION_THRESHOLD)
    lines = [r.getMessage() for r in caplog.records if "training range" in r.getMessage()]
    assert len(lines) == 1 and "labelled steps" in lines[0] and "pdrlearn train" in lines[0]


def test_simulated_model_on_the_real_level_walk(gaitmap_level_left, tmp_path, capsys):
    """The new user's case: user 1's simulated 20 Hz model (as `make demo`, SVM and NN on the fused units
    to keep the test fast) on the real 204.8 Hz level walk: the fraction in summary.json and the printed
    line; with --warn-out-of-domain one warning line. The same model on its own user's simulated walk (the
    demo's scenario D): in range, no warning."""
    sim = pytest.importorskip("pdrlearn.sim")
    from pdrlearn.cli import main as cli
    from pdrlearn.track.plasys import track_plasys

    cal = [sim.simulate(e, user_seed=1, speed="normal") for e in ("terrain", "direction", "length")]
    m = train_user(cal, methods=("svm", "nn"), units=("fused",), cv=2, user="u1")  # no CV score is read: 2 folds
    own = track_plasys(sim.simulate("D", user_seed=1, speed="normal"), method="M3", model=m,
                       warn_out_of_domain=FRACTION_THRESHOLD).info
    assert own["out_of_domain"]["out_of_domain_fraction"] < FRACTION_THRESHOLD
    assert not [w for w in own["warnings"] if "training range" in w]
    m.save(tmp_path / "u1")
    base = ["track", "--no-plot", str(gaitmap_level_left), "--model", str(tmp_path / "u1")]
    assert cli([*base, "--out", str(tmp_path / "t")]) == 0
    out, err = capsys.readouterr()
    assert "% of the strides outside the model's training range" in out
    default = [ln for ln in err.splitlines() if "training range" in ln]  # decision C61: one line without the option
    assert len(default) == 1 and "--warn-out-of-domain" in default[0] and "unreliable" in default[0], err
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert summary["out_of_domain_fraction"] >= FRACTION_THRESHOLD
    assert summary["info"]["out_of_domain"]["tasks"]["terrain"]["unit"].endswith("/foot")
    assert cli([*base, "--warn-out-of-domain", "0.25", "--out", str(tmp_path / "w")]) == 0
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if "training range" in ln]
    assert len(lines) == 1 and "terrain classifier" in lines[0] and "pdrlearn train" in lines[0], err
    assert lines[0] != default[0]  # the option's detailed line (C16) replaces C61's short one
    assert cli([*base, "--warn-out-of-domain", "1.5", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--warn-out-of-domain 1.5" in err
