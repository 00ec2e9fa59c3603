"""Per-user training: train -> save -> load -> identical predictions, named errors, real foot terrain."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify import load_model, train_user
from pdrlearn.classify.evaluation import evaluate_model, markdown_tables
from pdrlearn.errors import DataError, ModelError
from pdrlearn.io import AxisFrame, Session, Stream, read_session

G = 9.80665
FLU = AxisFrame(x="forward", y="left", z="up")


def labelled_session(
    seed: int = 0, n_per_class: int = 12, rate: float = 50.0, *, waist: bool = True, name: str = "synthetic"
) -> Session:
    """A hand-made labelled session: 1-s steps (0.3 s stance, 0.6 s swing) whose foot and waist signals
    depend on the step's terrain, direction and length class (plus noise). Sensor axes = body FLU."""
    rng = np.random.default_rng(seed)
    terr = np.resize(["flat", "up", "down"], 3 * n_per_class)
    dirs = np.resize(["forward", "forward", "backward"], len(terr))
    lens = np.resize(["short", "normal", "long", "normal"], len(terr))
    order = rng.permutation(len(terr))
    terr, dirs, lens = terr[order], dirs[order], lens[order]
    n_step = int(rate)
    t = np.arange((len(terr) + 2) * n_step) / rate
    facc = np.tile([0.0, 0.0, G], (len(t), 1))
    fgyr = np.zeros((len(t), 3))
    force = np.ones(len(t))
    wacc = np.tile([0.0, 0.0, G], (len(t), 1))
    wgyr = np.zeros((len(t), 3))
    rows = []
    for i, (te, di, le) in enumerate(zip(terr, dirs, lens, strict=True)):
        k0 = (i + 1) * n_step
        u = np.arange(n_step) / n_step
        s = np.clip((u - 0.3) / 0.6, 0, 1)
        swing = (u >= 0.3) & (u < 0.9)
        amp = {"short": 0.6, "normal": 1.0, "long": 1.5}[le] * rng.uniform(0.9, 1.1)
        sign = 1.0 if di == "forward" else -1.0
        vert = {
            "flat": 3 * np.sin(2 * np.pi * s),
            "up": 5 * np.sin(np.pi * s),
            "down": -5 * np.sin(np.pi * s),
        }[te]
        sl = slice(k0, k0 + n_step)
        facc[sl, 0] += swing * sign * 6 * amp * np.sin(2 * np.pi * s)
        facc[sl, 2] += swing * vert
        fgyr[sl, 1] = swing * -4 * amp * np.sin(2 * np.pi * s)
        force[sl] = np.where(swing, 0.0, 1.0 + 0.5 * amp * (u < 0.15))
        wacc[sl, 2] += {"flat": 1.0, "up": 1.6, "down": 0.5}[te] * np.sin(2 * np.pi * u)
        wacc[sl, 0] += sign * 0.8 * np.sin(2 * np.pi * u)
        wgyr[sl, 2] = (1 if i % 2 else -1) * 0.4 * amp * np.sin(np.pi * u)
        rows.append(
            {"start_s": t[k0], "end_s": t[k0] + 1.0, "terrain": te, "direction": di, "length_class": le}
        )
    noise = lambda a, sd: a + rng.normal(0, sd, a.shape)  # noqa: E731
    streams = {
        "fAccelerometer": Stream("fAccelerometer", t, noise(facc, 0.3)),
        "fGyroscope": Stream("fGyroscope", t, noise(fgyr, 0.05)),
        "fForceA": Stream("fForceA", t, force),
        "fForceB": Stream("fForceB", t, force * 0.5),
    }
    frames = {"foot": FLU}
    if waist:
        streams["wAccelerometer"] = Stream("wAccelerometer", t, noise(wacc, 0.3))
        streams["wGyroscope"] = Stream("wGyroscope", t, noise(wgyr, 0.05))
        frames["waist"] = FLU
    return Session(name=name, streams=streams, steps=pd.DataFrame(rows), frames=frames)


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    train = [labelled_session(1, 12), labelled_session(2, 12)]
    model = train_user(train, methods=["dtw", "svm", "nn"], cv=3, seed=0, units=["foot", "waist", "fused", "combined"])
    path = tmp_path_factory.mktemp("model") / "u1"
    model.save(path)
    return model, path


def test_train_save_load_identical_predictions(trained):
    model, path = trained
    test = labelled_session(9, 6)
    loaded = load_model(path)
    a, b = (m.predict_steps(test, test.steps, windows="given") for m in (model, loaded))  # labelled (C51)
    pd.testing.assert_frame_equal(a, b)
    assert {"terrain", "direction", "length_class", "p_terrain_up", "method_terrain"} <= set(a.columns)
    np.testing.assert_allclose(a[[f"p_terrain_{c}" for c in ("flat", "up", "down")]].sum(axis=1), 1.0)
    # held-out accuracy of the chosen methods is far above chance on these separable steps
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        assert np.mean(a[col] == test.steps[col]) > 0.8, task


def test_manifest_contents(trained):
    model, path = trained
    m = json.loads((path / "manifest.json").read_text())
    assert m["schema_version"] == 1 and m["n_samples"] == 40
    assert m["tasks"]["terrain"]["classes"] == ["flat", "up", "down"]
    assert m["tasks"]["length"]["chosen"]["unit"] in ("fused", "combined")  # the two-unit models (C8, C23)
    assert set(m["tasks"]["direction"]["models"]["svm"]) == {"foot", "waist", "fused", "combined"}
    assert m["tasks"]["direction"]["feature_spec"]["svm"]["combined"]["params"]["unit"] == "both"  # C22
    assert "torch" in m["versions"] and m["training_data"]["steps"]["terrain"]["per_class"]["up"] == 24
    spec = m["tasks"]["terrain"]["feature_spec"]["svm"]["foot"]
    assert spec["transformer"] == "TerrainSVMFeatures" and len(spec["features"]) == 11
    assert m["tasks"]["terrain"]["feature_spec"]["dtw"]["waist"]["dtw_signals"] == ["waist_acc_v"]
    w = m["tasks"]["terrain"]["cv"]["svm"]["fused"]["weights"]
    assert w["foot"] + w["waist"] == pytest.approx(1.0)


def test_load_model_errors(trained, tmp_path):
    _, path = trained
    with pytest.raises(ModelError, match="no such model directory"):
        load_model(tmp_path / "nope")
    import shutil

    bad = tmp_path / "bad"
    shutil.copytree(path, bad)
    m = json.loads((bad / "manifest.json").read_text())
    m["schema_version"] = 99
    (bad / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(ModelError, match="schema version 99"):
        load_model(bad)
    m["schema_version"] = 1
    (bad / "manifest.json").write_text(json.dumps(m))
    first = next(iter(m["files"]))
    (bad / first).unlink()
    with pytest.raises(ModelError, match="missing"):
        load_model(bad)


def test_evaluate_shape(trained):
    model, _ = trained
    r = evaluate_model(model, [labelled_session(5, 5)], latency_steps=3)
    t = r["tasks"]["terrain"]
    assert t["n_steps"] == 15 and 0 <= t["accuracy"] <= 1
    assert set(t["methods"]) == {"dtw", "svm", "nn"} and t["methods"]["svm"]["unit"] in ("fused", "combined")
    assert t["methods"]["dtw"]["units"]["foot"]["latency_ms"] > 0
    assert "| svm | fused |" in markdown_tables(r) and "| svm | combined |" in markdown_tables(r)
    assert r["boundaries"] == "given"  # the model's step-window cut (decision C13)


def test_errors_are_named():
    s = labelled_session(3, 12)
    with pytest.raises(DataError, match="at least 5 labelled steps per class"):
        few = s.copy()
        few.steps = pd.concat(
            [s.steps[s.steps.terrain != "down"], s.steps[s.steps.terrain == "down"].head(3)]
        )
        train_user([few], tasks=["terrain"], methods=["svm"], cv=3)
    no_up = s.copy()
    no_up.steps = s.steps[s.steps.terrain != "up"]
    with pytest.raises(DataError, match="no steps labelled 'up'"):
        train_user([no_up], tasks=["terrain"], methods=["svm"], cv=3)
    unlabelled = s.copy()
    unlabelled.steps = s.steps.drop(columns=["length_class"])
    with pytest.raises(DataError, match="no session has length labels"):
        train_user([unlabelled], tasks=["length"], methods=["svm"], cv=3)
    with pytest.raises(DataError, match="unknown method"):
        train_user([s], methods=["svm", "knn"])
    # without --tasks the unlabelled task is skipped and reported
    m = train_user([unlabelled], methods=["svm"], units=["foot"], cv=3)
    assert "length" not in m.tasks and any("length" in x for x in m.skipped)


def test_lengths_without_classes_say_what_is_missing():
    """steps.csv with length_m but no length_class said only "no session has length labels", which read as
    if the lengths were ignored: the message now names the missing column and that classes are not derived
    from length_m."""
    s = labelled_session(3, 12)
    lengths = s.copy()
    lengths.steps = s.steps.drop(columns=["length_class"]).assign(length_m=1.3)
    with pytest.raises(DataError, match="no session has length labels") as err:
        train_user([lengths], tasks=["length"], methods=["svm"], cv=3)
    msg = str(err.value)
    assert "'length_m'" in msg and "no 'length_class' column" in msg and "does not derive" in msg
    assert "--tasks terrain,direction" in msg
    bare = s.copy()  # no lengths either: the short message
    bare.steps = s.steps.drop(columns=["length_class"])
    with pytest.raises(DataError) as err:
        train_user([bare], tasks=["length"], methods=["svm"], cv=3)
    assert "length_m" not in str(err.value)


def test_foot_only_sessions_train_foot_models():
    s = labelled_session(4, 10, waist=False)
    m = train_user([s], tasks=["terrain"], methods=["svm", "nn"], cv=3)
    tm = m.tasks["terrain"]
    assert set(tm.models["svm"]) == {"foot"} and tm.chosen[1] == "foot"
    assert any(x.startswith("svm/combined: needs both units") for x in tm.skipped)


def test_real_gaitmap_terrain_cross_validated(real_dir):
    names = ("level_left", "level_right", "stairs_up_left", "stairs_down_left")
    sessions = [read_session(real_dir / f"gaitmap_{n}") for n in names]
    m = train_user(sessions, methods=["svm"], cv=5, seed=0)
    assert list(m.tasks) == ["terrain"]  # direction has only 'forward', length has no classes
    tm = m.tasks["terrain"]
    assert tm.n_skipped_labels == 1  # the 'unclear' stride
    assert tm.cv["svm"]["foot"]["accuracy"] > 0.8  # chance (majority class) = 0.66


def test_rest_boundaries_setting_is_saved_and_used_for_prediction(tmp_path):
    """boundaries="rest" is stored in the manifest; the loaded model cuts prediction windows the same way
    (steps given late, like a swing detector's, classify as the training steps did); bad value named."""
    from pdrlearn.features import step_windows

    s = labelled_session(4, 10, waist=False)
    m = train_user([s], tasks=["terrain"], methods=["svm"], cv=3, boundaries="rest")
    assert m.settings["boundaries"] == "rest" and m.boundaries == "rest"
    m.save(tmp_path / "m")
    loaded = load_model(tmp_path / "m")
    assert loaded.boundaries == "rest"
    late = s.steps.copy()
    late[["start_s", "end_s"]] += 0.2  # boundaries in the swing, the rests 0.1-0.2 s earlier
    df = loaded.predict_steps(s, late, windows="given")
    est = m.tasks["terrain"].models["svm"]["foot"]
    expect = est.predict(step_windows(s, late, n_samples=m.n_samples, boundaries="rest").X)
    assert df["terrain"].tolist() == list(expect)
    assert np.mean(df["terrain"] == s.steps["terrain"]) >= 0.9
    assert evaluate_model(loaded, [s], latency=False)["boundaries"] == "rest"
    assert train_user([s], tasks=["terrain"], methods=["svm"], cv=3).boundaries == "given"  # default
    with pytest.raises(DataError, match="boundaries 'stance'"):
        train_user([s], tasks=["terrain"], methods=["svm"], cv=3, boundaries="stance")


def test_real_gaitmap_terrain_rest_to_rest_windows(real_dir):
    """Issue 5 real target (>= 97 %): the recordings' labelled boundaries sit at different gait phases
    (mocap mid-stance vs a converter's detection); cut rest to rest, dtw gains 5-8 points (5-fold
    89.4-91.5 -> 96.8-97.9 % over seeds 0-3) and the chosen model reaches 97 % (decision 13 in
    docs/decisions/features.md)."""
    names = ("level_left", "level_right", "stairs_up_left", "stairs_down_left")
    sessions = [read_session(real_dir / f"gaitmap_{n}") for n in names]
    m = train_user(sessions, tasks=["terrain"], methods=["nn", "svm", "dtw", "ensemble"], cv=5, seed=0,
                   boundaries="rest")
    cv = m.tasks["terrain"].cv
    assert cv["dtw"]["foot"]["accuracy"] >= 0.95  # 0.89-0.92 with the given boundaries
    # the three learned classifiers err on different strides; their equal-weight vote (decision C14):
    # 95.7-97.9 % over seeds 0-3 since the rest-reference fix (decision 14; 96.8-100 before it)
    assert cv["ensemble"]["foot"]["accuracy"] >= 0.95  # 0.95-0.98 with the given boundaries
    chosen = m.tasks["terrain"].chosen
    assert cv[chosen[0]][chosen[1]]["accuracy"] >= 0.97


def test_ensemble_is_the_equal_vote_of_its_members(tmp_path):
    """methods=[..., "ensemble"]: per unit the mean of the nn, svm and dtw probabilities (fitted models
    reused), CV from their out-of-fold probabilities, a fused ensemble over both units; saved and loaded
    with identical predictions; skipped with a reason when a member is not trained; not a default."""
    from pdrlearn.classify.training import DEFAULT_METHODS, check_settings

    s = labelled_session(7, 8)
    m = train_user([s], tasks=["terrain"], methods=["ensemble", "nn", "svm", "dtw"], cv=2, seed=1)
    tm = m.tasks["terrain"]
    assert set(tm.models["ensemble"]) == {"foot", "waist", "fused"}
    ens = tm.models["ensemble"]["foot"]
    X = session_windows_X(s)
    members = [tm.models[k]["foot"].predict_proba(X) for k in ("nn", "svm", "dtw")]
    np.testing.assert_allclose(ens.predict_proba(X), np.mean(members, axis=0), atol=1e-12)
    assert tm.cv["ensemble"]["foot"]["accuracy"] > 0.6
    m.save(tmp_path / "m")
    a = m.predict_steps(s, method="ensemble", unit="fused")
    b = load_model(tmp_path / "m").predict_steps(s, method="ensemble", unit="fused")
    np.testing.assert_allclose(a["p_terrain_up"], b["p_terrain_up"], atol=1e-12)
    only = train_user([s], tasks=["terrain"], methods=["svm", "ensemble"], units=["foot"], cv=3)
    assert "ensemble" not in only.tasks["terrain"].models
    assert any("ensemble/foot: needs nn, dtw" in x for x in only.tasks["terrain"].skipped)
    assert "ensemble" not in DEFAULT_METHODS and "ensemble" not in check_settings()[1]


def session_windows_X(s):
    from pdrlearn.features import step_windows

    return step_windows(s, s.steps).X


def test_mounting_rotation_leaves_predictions_unchanged(real_dir):
    """Features live in the gravity-aligned step frame, so a fixed extra mounting rotation of the foot
    sensor (here 40 deg pitch + 15 deg roll, like the lateral-vs-instep mounts) keeps the classes."""
    from scipy.spatial.transform import Rotation

    names = ("level_left", "level_right", "stairs_up_left", "stairs_down_left")
    sessions = [read_session(real_dir / f"gaitmap_{n}") for n in names]
    # cv=2, the fewest folds: the cross-validation is not what this test reads (the fitted models are)
    model = train_user(sessions, tasks=["terrain"], methods=["svm", "nn"], cv=2, seed=0)
    R = Rotation.from_euler("yx", [40, 15], degrees=True).as_matrix()
    for s in (sessions[1], sessions[2]):
        rotated = s.copy()
        for name in ("fAccelerometer", "fGyroscope"):
            rotated.streams[name] = Stream(name, s.streams[name].t, s.streams[name].values @ R.T)
        for method in ("svm", "nn"):
            a = model.predict_steps(s, method=method, unit="foot")
            b = model.predict_steps(rotated, method=method, unit="foot")
            assert np.mean(a["terrain"] == b["terrain"]) >= 0.95, (s.name, method)
            assert np.abs(a["p_terrain_up"] - b["p_terrain_up"]).mean() < 0.05


def test_predict_steps_falls_back_to_the_units_a_session_has(trained):
    from pdrlearn.errors import MissingSensorError

    model, _ = trained
    s = labelled_session(11, 4)
    foot_only = s.copy()
    for name in ("wAccelerometer", "wGyroscope"):
        del foot_only.streams[name]
    df = model.predict_steps(foot_only)
    assert set(df["method_terrain"].str.split("/").str[1]) == {"foot"}  # chosen fused -> best foot model
    no_force = foot_only.copy()
    for name in ("fForceA", "fForceB"):
        del no_force.streams[name]
    df = model.predict_steps(no_force)
    assert (df["method_length"] == "none").all() and df["length_class"].isna().all()
    assert df["terrain"].notna().all()
    with pytest.raises(MissingSensorError, match="force"):
        model.predict_steps(no_force, tasks=["length"])
