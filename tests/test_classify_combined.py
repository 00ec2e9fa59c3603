"""Decision C22: the thesis' feature-level fusion, unit ``combined`` (one SVM / NN on both units' features).

Input sizes are the thesis' (terrain SVM 17, terrain NN 72, direction 25, length 29); the models train and
predict on labelled sessions, are chosen among the two-unit models (C8/C23), survive save/load, export and
the streaming runtime with the offline classes, and a session without the waist unit falls back (C8, E26)
or, when the combined model is asked for, fails in one line naming the waist.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify import load_model, train_user
from pdrlearn.classify.training import TWO_UNIT, UNIT_PREFERENCE, make_estimator
from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.features import TASK_COLUMNS
from tests.runtime_helpers import replay, synthetic_session
from tests.test_classify_training import labelled_session

#: thesis ch. 6.1.1.1 (17), 6.1.1.2 (72), 6.2.1 (25), 6.3.1 (29)
THESIS_SIZES = {("terrain", "svm"): 17, ("terrain", "nn"): 72, ("direction", "svm"): 25, ("direction", "nn"): 25,
                ("length", "svm"): 29, ("length", "nn"): 29}
WAIST = ("wAccelerometer", "wGyroscope", "wBarometer")


@pytest.fixture(scope="module")
def combined(tmp_path_factory):
    """svm and nn trained on foot, waist, fused and combined units (two synthetic sessions), saved."""
    train = [labelled_session(1, 12), labelled_session(2, 12)]
    model = train_user(train, methods=["svm", "nn"], cv=3, seed=0, units=["foot", "waist", "fused", "combined"])
    path = tmp_path_factory.mktemp("combined") / "u1"
    model.save(path)
    return model, path


def test_combined_models_have_the_thesis_input_sizes(combined):
    model, _ = combined
    for (task, method), n in THESIS_SIZES.items():
        est = model.tasks[task].models[method]["combined"]
        assert est[-1].n_features_in_ == n, (task, method)
        names = list(est[0].get_feature_names_out())
        assert len(names) == n
        # both units' sensors are in the one vector (thesis: foot acc + waist acc / gyro)
        assert any(x.startswith("foot_") for x in names) and any(x.startswith("waist_") for x in names)
    # the unit models read fewer features than the combined vector
    assert model.tasks["terrain"].models["svm"]["foot"][-1].n_features_in_ == 11


def test_combined_exists_for_svm_and_nn_only():
    with pytest.raises(DataError, match="svm and nn only"):
        make_estimator("terrain", "dtw", "combined")
    s = labelled_session(3, 8)
    m = train_user([s], tasks=["terrain"], methods=["svm", "dtw"], units=["combined"], cv=2)
    tm = m.tasks["terrain"]
    assert set(tm.models) == {"svm"} and tm.chosen == ("svm", "combined")
    assert any(x.startswith("dtw/combined: only svm and nn") for x in tm.skipped)


def test_chosen_among_two_unit_models_and_predicts_held_out_steps(combined):
    model, path = combined
    test = labelled_session(9, 6)
    for task, tm in model.tasks.items():
        assert tm.chosen[1] in TWO_UNIT
        two = [p for p in tm.ranking() if p[1] in TWO_UNIT]
        assert tm.chosen == two[0]
        for method in ("svm", "nn"):
            df = model.predict_steps(test, tasks=[task], method=method, unit="combined")
            assert (df[f"method_{task}"] == f"{method}/combined").all()
            acc = np.mean(df[TASK_COLUMNS[task]].to_numpy() == test.steps[TASK_COLUMNS[task]].to_numpy())
            assert acc > 0.8, (task, method, acc)
    loaded = load_model(path)
    a = model.predict_steps(test, method="svm", unit="combined")
    b = loaded.predict_steps(test, method="svm", unit="combined")
    assert a.equals(b)


def test_default_units_replace_the_svm_and_nn_soft_votes():
    """Decision C23: with the units left at their default, svm and nn get the combined model and no soft vote;
    dtw (no combined form) and heuristic fusion keep their fused model; naming the units trains both."""
    s = [labelled_session(1, 8)]
    m = train_user(s, tasks=["terrain"], methods=["fusion", "dtw", "svm"], cv=2)
    tm = m.tasks["terrain"]
    assert set(tm.models["svm"]) == {"foot", "waist", "combined"}
    assert set(tm.models["dtw"]) == {"foot", "waist", "fused"} and set(tm.models["fusion"]) == {"fused"}
    assert m.settings["fused_methods"] == ["fusion", "dtw"] and tm.chosen[1] in TWO_UNIT
    named = train_user(s, tasks=["terrain"], methods=["svm"], cv=2, units=["foot", "waist", "fused", "combined"])
    assert set(named.tasks["terrain"].models["svm"]) == {"foot", "waist", "fused", "combined"}
    assert named.settings["fused_methods"] is None


def test_equal_scores_prefer_combined_over_soft_vote():
    from pdrlearn.runtime.classify import _UNIT_PREFERENCE

    assert _UNIT_PREFERENCE == UNIT_PREFERENCE  # the runtime's ranking mirrors the training side's
    assert UNIT_PREFERENCE.index("combined") < UNIT_PREFERENCE.index("fused")


def test_session_without_waist_falls_back_or_names_the_waist(combined):
    model, _ = combined
    s = labelled_session(11, 4)
    for name in ("wAccelerometer", "wGyroscope"):
        del s.streams[name]
    df = model.predict_steps(s)
    for task in model.tasks:
        assert set(df[f"method_{task}"].str.split("/").str[1]) == {"foot"}, task
    with pytest.raises(MissingSensorError,
                       match=r"terrain features \(of both units, unit 'combined'\) need the waist acc ") as exc:
        model.predict_steps(s, tasks=["terrain"], method="svm", unit="combined")
    assert "\n" not in str(exc.value)


def test_length_without_force_skips_the_combined_length_model():
    """The thesis' 29 length features include 3 force features: without force sensors the combined length
    model is not trained (one skip line naming the force); no 26-feature variant stands in (C22)."""
    sessions = [labelled_session(1, 8), labelled_session(2, 8)]
    for s in sessions:
        for name in ("fForceA", "fForceB"):
            del s.streams[name]
    m = train_user(sessions, methods=["svm"], units=["waist", "combined"], cv=2, tasks=["terrain", "length"])
    assert m.tasks["terrain"].chosen == ("svm", "combined")
    tm = m.tasks["length"]
    assert "combined" not in tm.models["svm"] and tm.chosen == ("svm", "waist")
    assert any(x.startswith("svm/combined: length features (of both units, unit 'combined') need the force")
               for x in tm.skipped), tm.skipped


def test_bundle_with_a_combined_model_streams_like_predict_steps(tmp_path):
    """Export a model whose chosen models are combined ones; the runtime computes the combined vector from
    both units' windows and gives predict_steps' classes on the streamed steps, and a foot-only replay takes
    the bundle's foot model (E26)."""
    from pdrlearn.export.from_model import export_model
    from pdrlearn.runtime.tracker import Tracker

    train = synthetic_session(90, seed=0)
    model = train_user([train], methods=["svm", "nn"], units=["foot", "combined"], cv=2, seed=0)
    for tm in model.tasks.values():
        assert tm.chosen[1] == "combined"
    model.save(tmp_path / "model")
    export_model(tmp_path / "model", tmp_path / "bundle")
    tr = Tracker(tmp_path / "bundle")
    test = synthetic_session(30, seed=5, name="held_out")
    steps = replay(tr, test)
    assert len(steps) >= len(test.steps) - 2
    assert tr.step_graph is not None  # the combined models run inside the bundle's step graph (E10)
    got = pd.DataFrame({"start_s": [st.start_s for st in steps], "end_s": [st.end_s for st in steps]})
    ref = model.predict_steps(test, got)
    for task, tm in model.tasks.items():
        assert (ref[f"method_{task}"] == "/".join(tm.chosen)).all()
        assert [st.classes[task] for st in steps] == list(ref[TASK_COLUMNS[task]]), task
        want = ref[[f"p_{task}_{c}" for c in tm.classes]].to_numpy()
        got_p = np.array([[st.proba[task][c] for c in tm.classes] for st in steps])
        assert np.abs(got_p - want).max() <= 1e-5, task
    foot = test.copy()
    for n in WAIST:
        del foot.streams[n]
    tr_foot = Tracker(tmp_path / "bundle", units=("foot",))
    fsteps = replay(tr_foot, foot)
    assert fsteps and all(tr_foot.classifiers[t].unit == "foot" for t in model.tasks)


def test_length_units_train_the_length_tasks_own_units_and_a_one_unit_vote_yields_to_its_unit(tmp_path):
    """Decision C38: ``length_units`` gives the length task its own units (every soft vote they allow, no
    combined model, so C8 chooses among foot/waist/fused); terrain keeps the default combined model. Here the soft
    vote gives the foot weight 0, so C124 chooses the waist model it equals (renamed after review R4: no soft vote
    is chosen in this fixture)."""
    s = [labelled_session(1, 8)]
    m = train_user(s, tasks=["terrain", "length"], methods=["svm"], cv=2, length_units=["foot", "waist", "fused"])
    assert set(m.tasks["length"].models["svm"]) == {"foot", "waist", "fused"}
    # C8 chooses among the soft votes; this one gives the foot weight 0, so it is the waist model and the waist
    # model itself is chosen (decision C124; before C124: svm/fused, equal CV scores)
    assert m.tasks["length"].cv["svm"]["fused"]["weights"] == {"foot": 0.0, "waist": 1.0}
    assert m.tasks["length"].chosen == ("svm", "waist")
    assert set(m.tasks["terrain"].models["svm"]) == {"foot", "waist", "combined"}
    assert m.settings["length_units"] == ["foot", "waist", "fused"]
    m.save(tmp_path / "u")
    assert load_model(tmp_path / "u").tasks["length"].chosen == ("svm", "waist")
    default = train_user(s, tasks=["length"], methods=["svm"], cv=2)
    assert default.tasks["length"].chosen == ("svm", "combined") and default.settings["length_units"] is None
    with pytest.raises(DataError, match=r"^length_units \(--length-units\): unknown unit hand"):
        train_user(s, tasks=["length"], methods=["svm"], cv=2, length_units=["hand"])
