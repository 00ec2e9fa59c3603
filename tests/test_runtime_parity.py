"""Parity of the numpy/onnxruntime runtime with the training side (issue 7, part 3).

A user model is trained once (all five methods, foot / waist / fused) on a synthetic labelled session,
exported with every method, and the runtime must reproduce ``UserModel.predict_steps`` on held-out
steps: same classes, probabilities within 1e-5; its numpy kernels must equal the training side's.
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.classify import load_model
from pdrlearn.errors import ModelError
from pdrlearn.export.bundle import bundle_size_bytes
from pdrlearn.features import TASK_COLUMNS, step_windows
from pdrlearn.kernels import dtw as KD
from pdrlearn.kernels import rotation as KR
from pdrlearn.kernels import stats as KS
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.classify import TaskClassifier
from pdrlearn.runtime.features import step_window
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import REST_METHODS, replay, rest_dirs, synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    root = trained_dirs(tmp_path_factory)["root"]
    model = load_model(root / "model")
    test = synthetic_session(30, seed=5, name="held_out")
    return {"root": root, "model": model, "test": test,
            "windows": step_windows(test, test.steps, n_samples=model.n_samples)}


def _streams(session):
    return {n: (s.t, s.values) for n, s in session.streams.items()}


def test_step_windows_equal_training_side(trained):
    tr = Tracker(trained["root"] / "bundle_all")
    s = trained["test"]
    W = np.stack([step_window(_streams(s), a, b, channels=tr.channels, forward=tr.forward,
                              n_samples=tr.n_samples)
                  for a, b in zip(s.steps["start_s"], s.steps["end_s"], strict=True)])
    ref = trained["windows"].X
    assert np.array_equal(np.isnan(W), np.isnan(ref))
    np.testing.assert_allclose(W, ref, atol=1e-9, equal_nan=True)


def test_every_exported_method_and_unit_matches_predict_steps(trained):
    model, s, W = trained["model"], trained["test"], trained["windows"].X
    bundle = load_bundle(trained["root"] / "bundle_all")
    ctx = {"signals": bundle.manifest["features"]["signals"],
           "channel_index": {c: i for i, c in enumerate(bundle.manifest["features"]["channels"])}}
    checked = 0
    for task, tm in model.tasks.items():
        for method, per in tm.models.items():
            for unit in per:
                ref = model.predict_steps(s, s.steps, tasks=[task], method=method, unit=unit, windows="given")
                clf = TaskClassifier(bundle, task, ctx, method=method, unit=unit)
                classes, proba = clf.predict(W)
                want = ref[[f"p_{task}_{c}" for c in clf.classes]].to_numpy()
                assert list(classes) == list(ref[TASK_COLUMNS[task]]), (task, method, unit)
                assert np.abs(proba - want).max() <= 1e-5, (task, method, unit)
                checked += 1
    assert checked >= 3 * 9  # 3 tasks x (heuristic 2 + fusion 1 + dtw/svm/nn 3 each)


def test_streamed_steps_equal_training_side_on_the_same_steps(trained, monkeypatch):
    """Replay in 0.5 s chunks: every emitted step's classes/probabilities equal predict_steps on it."""
    # decision C191: a stride whose measured length contradicts its class takes the measured class after the
    # classifier (C88's kernel); this test is the classifier's parity, so the measured-length rules are off
    monkeypatch.setattr("pdrlearn.kernels.turn_length.TURN_LENGTH_RULE", False)
    model, s = trained["model"], trained["test"]
    tr = Tracker(trained["root"] / "bundle")
    t = s.streams["fAccelerometer"].t
    steps = []
    for t0 in np.arange(t[0], t[-1] + 0.5, 0.5):
        chunk = {n: (st.t[(st.t >= t0) & (st.t < t0 + 0.5)], st.values[(st.t >= t0) & (st.t < t0 + 0.5)])
                 for n, st in s.streams.items()}
        steps += tr.push(chunk)
    # the synthetic session's 30 labelled strides are stance-to-stance: all but the first are found
    assert len(steps) >= len(s.steps) - 2
    import pandas as pd

    table = pd.DataFrame({"start_s": [st.start_s for st in steps], "end_s": [st.end_s for st in steps]})
    ref = model.predict_steps(s, table)
    for task in tr.classifiers:
        assert [st.classes[task] for st in steps] == list(ref[TASK_COLUMNS[task]])
        for c in tr.classifiers[task].classes:
            got = np.array([st.proba[task][c] for st in steps])
            assert np.abs(got - ref[f"p_{task}_{c}"].to_numpy()).max() <= 1e-5
    # bounded state: no more than buffer_s seconds of samples are kept per sensor
    for name in tr._buf:
        ts, _ = tr._stream(name)
        assert ts[-1] - ts[0] <= tr.buffer_s + 0.1


def test_default_bundle_holds_the_chosen_methods_and_is_small(trained):
    b = load_bundle(trained["root"] / "bundle")
    for task, tm in trained["model"].tasks.items():
        spec = b.tasks[task]
        assert spec["chosen"] == {"method": tm.chosen[0], "unit": tm.chosen[1]}
        assert list(spec["methods"]) == [tm.chosen[0]]
    assert bundle_size_bytes(trained["root"] / "bundle") < 5e6  # issue 7 target
    assert not list((trained["root"] / "bundle").rglob("*.pkl")) and not list(
        (trained["root"] / "bundle").rglob("*.joblib"))


def test_training_side_and_runtime_share_one_kernel_set():
    """No mirrors: the training side's kernels are the very objects the runtime calls (issue 7)."""
    from pdrlearn.classify import fusion
    from pdrlearn.features import _kernels as FK
    from pdrlearn.features import rules, windows
    from pdrlearn.kernels import proba, window
    from pdrlearn.runtime import classify, features
    from pdrlearn.signal import gravity_rotation

    assert gravity_rotation is KR.gravity_rotation
    for name in ("peak_stats", "segment_stats", "force_stats", "propagate_attitude", "half_balance",
                 "step_probability", "yaw_stats", "positive_net_rotation"):
        assert getattr(FK, name) is getattr(KS, name), name
    assert rules.half_balance is KS.half_balance and features.K is KS
    assert windows.fill_step_window is window.fill_step_window is features.fill_step_window
    from pdrlearn.runtime import tracker

    assert windows.rest_boundaries is window.rest_boundaries is tracker.rest_boundaries  # decision C15
    assert fusion.soft_vote is proba.soft_vote is classify.soft_vote
    assert fusion.align_proba is classify.align
    import pdrlearn.runtime

    assert not hasattr(pdrlearn.runtime, "_kernels")


def test_numpy_kernels_equal_the_library_references():
    """The numpy-only kernels against scipy / dtaidistance (which the runtime cannot import)."""
    from dtaidistance import dtw_ndim
    from scipy.ndimage import uniform_filter1d
    from scipy.spatial.transform import Rotation

    from pdrlearn.kernels.window import box_filter

    rng = np.random.default_rng(3)
    w = rng.normal(size=(20, 3)) * 0.5
    np.testing.assert_allclose(KR.rotvec_to_matrix(w), Rotation.from_rotvec(w).as_matrix(), atol=1e-12)
    np.testing.assert_allclose(KR.rotvec_to_matrix(w * 1e-10), Rotation.from_rotvec(w * 1e-10).as_matrix(),
                               atol=1e-15)
    for R in Rotation.from_rotvec(w).as_matrix():
        np.testing.assert_allclose(KR.matrix_to_rotvec(R), Rotation.from_matrix(R).as_rotvec(), atol=1e-9)
    for g in [rng.normal(size=3) for _ in range(5)] + [np.array([0, 0, 9.8]), np.array([0, 0, -9.8])]:
        R = KR.gravity_rotation(g)
        np.testing.assert_allclose(R @ g, [0, 0, np.linalg.norm(g)], atol=1e-12)
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
    gyr, dt = rng.normal(size=(30, 3)), np.full(29, 0.05)
    r0 = KR.gravity_rotation(rng.normal(size=3))
    want = [r0]  # sample-by-sample scipy propagation forward from k0 = 0
    for k in range(29):
        want.append(want[-1] @ Rotation.from_rotvec(0.5 * (gyr[k] + gyr[k + 1]) * dt[k]).as_matrix())
    np.testing.assert_allclose(KS.propagate_attitude(gyr, dt, 0, r0), np.array(want), atol=1e-12)
    t = np.cumsum(rng.uniform(0.01, 0.05, size=(4, 40)), axis=1)
    np.testing.assert_allclose(KS.row_gradient(t), np.gradient(t, axis=1), atol=1e-15)
    v = rng.normal(size=(50, 3))
    for width in (1, 3, 5, 11):
        np.testing.assert_allclose(box_filter(v, width), uniform_filter1d(v, width, axis=0, mode="nearest"),
                                   atol=1e-12)
    from pdrlearn.displace._kernels import level_rotation
    from pdrlearn.kernels.strapdown import level_quat

    g = np.vstack([rng.normal(size=(5, 3)), [[0, 0, 9.8], [1e-14, 0, 9.8], [0.3, -0.2, -9.8]]])
    np.testing.assert_allclose(level_quat(g), level_rotation(g).as_quat()[:, [3, 0, 1, 2]], atol=1e-12)  # B129
    refs = rng.normal(size=(7, 40, 2))
    q = rng.normal(size=(40, 2))
    for window in (None, 4, 1):
        want = [dtw_ndim.distance(q, r, window=window) for r in refs]
        np.testing.assert_allclose(KD.dtw_to_refs(q, refs, window), want, rtol=1e-10)


def test_kernels_package_imports_numpy_only():
    import subprocess
    import sys

    code = ("import sys, pdrlearn.kernels.window, pdrlearn.kernels.dtw, pdrlearn.kernels.proba, "
            "pdrlearn.kernels.stride, pdrlearn.kernels.contact, pdrlearn.kernels.handedness; "
            "print(sorted(m for m in ('scipy', 'pandas', 'sklearn', 'torch') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip() == "[]"


def test_every_rule_feature_equals_training_side(trained):
    """Each named feature of the thesis rule tables, computed by the runtime, equals RuleFeatures'."""
    from pdrlearn.classify import heuristic as H
    from pdrlearn.features import CHANNELS
    from pdrlearn.features.rules import RuleFeatures
    from pdrlearn.features.transformers import SIGNALS
    from pdrlearn.runtime.features import compute_features

    rules = [r for name in dir(H) if name.isupper() and isinstance(getattr(H, name), list)
             for r in getattr(H, name) if hasattr(r, "feature")]
    names = sorted({r.feature for r in rules} | {r.confidence for r in rules if r.confidence})
    assert len(names) >= 10
    W = trained["windows"].X
    want = RuleFeatures(names=tuple(names)).fit_transform(W)
    got = compute_features(W, [["rule", n] for n in names],
                           signals={k: [list(v[0]), v[1]] for k, v in SIGNALS.items()},
                           channel_index={c: i for i, c in enumerate(CHANNELS)})
    np.testing.assert_allclose(got, want, atol=1e-9, err_msg=str(names))


def test_opencv_fallback_runs_the_network_like_onnxruntime(trained):
    """Without onnxruntime the network runs in OpenCV's dnn module (its float32 twin graph)."""
    pytest.importorskip("cv2")
    bundle = load_bundle(trained["root"] / "bundle_all")
    cv = load_bundle(trained["root"] / "bundle_all", backend="opencv")
    ctx = {"signals": bundle.manifest["features"]["signals"],
           "channel_index": {c: i for i, c in enumerate(bundle.manifest["features"]["channels"])}}
    W = trained["windows"].X
    for task in ("terrain", "direction", "length"):
        c1, p1 = TaskClassifier(bundle, task, ctx, method="nn", unit="foot").predict(W)
        c2, p2 = TaskClassifier(cv, task, ctx, method="nn", unit="foot").predict(W)
        assert cv.model(bundle.tasks[task]["methods"]["nn"]["foot"]["file"],
                        bundle.tasks[task]["methods"]["nn"]["foot"]).backend == "opencv"
        assert np.abs(p1 - p2).max() < 1e-4
        assert np.mean(c1 == c2) >= 0.95
    with pytest.raises(ModelError, match="needs onnxruntime"):
        TaskClassifier(cv, "terrain", ctx, method="svm", unit="foot")


def test_step_windows_equal_training_side_on_real_204hz_foot_data(gaitmap_level_left):
    """Real 204.8 Hz foot recording with its own mounting: resampling filter, rest search, attitude."""
    from pdrlearn.features import CHANNELS
    from pdrlearn.io import read_session
    from pdrlearn.runtime.tracker import forward_vector

    s = read_session(gaitmap_level_left)
    steps = s.steps.iloc[:8]
    ref = step_windows(s, steps, n_samples=40).X
    fwd = {"foot": forward_vector(s.frames["foot"].to_dict())}
    W = np.stack([step_window(_streams(s), a, b, channels=list(CHANNELS), forward=fwd, n_samples=40)
                  for a, b in zip(steps["start_s"], steps["end_s"], strict=True)])
    np.testing.assert_allclose(W, ref, atol=1e-8, equal_nan=True)


def test_real_foot_recordings_stream_like_the_training_side(real_dir, tmp_path_factory):
    """Terrain model trained on the real gaitmap foot recordings (204.8 Hz), exported, and the real
    right-foot walk streamed through the runtime: every streamed step classified as predict_steps does (the saved
    model, made once per test run and shared with test_runtime_resample.py)."""
    import pandas as pd

    from pdrlearn.io import read_session
    from tests._shared_i2 import GAITMAP_TRAIN, gaitmap_bundle

    root = gaitmap_bundle(tmp_path_factory)
    model = load_model(root / "model")
    for s in (read_session(real_dir / "gaitmap_level_right"), read_session(real_dir / GAITMAP_TRAIN[1])):
        tr = Tracker(root / "bundle", frames={p: f.to_dict() for p, f in s.frames.items()})
        t = s.streams["fAccelerometer"].t
        steps = []
        for a in np.arange(t[0], t[-1] + 0.5, 0.5):
            steps += tr.push({n: (st.t[(st.t >= a) & (st.t < a + 0.5)], st.values[(st.t >= a) & (st.t < a + 0.5)])
                              for n, st in s.streams.items()})
        assert len(steps) >= len(s.steps) - 1
        ref = model.predict_steps(s, pd.DataFrame({"start_s": [x.start_s for x in steps],
                                                   "end_s": [x.end_s for x in steps]}))
        assert [x.classes["terrain"] for x in steps] == list(ref["terrain"])
        for c in ("flat", "up", "down"):
            got = np.array([x.proba["terrain"][c] for x in steps])
            assert np.abs(got - ref[f"p_terrain_{c}"].to_numpy()).max() <= 1e-5


def test_late_waist_samples_delay_the_step_instead_of_changing_it(trained):
    """Foot chunks arrive 1 s before the waist's: the same steps come out, just later; flush() ends."""
    s = trained["test"]
    foot = [n for n in s.streams if n.startswith("f")]
    waist = [n for n in s.streams if n.startswith("w")]

    def chunk(names, a, b):
        return {n: (s.streams[n].t[(s.streams[n].t >= a) & (s.streams[n].t < b)],
                    s.streams[n].values[(s.streams[n].t >= a) & (s.streams[n].t < b)]) for n in names}

    t_end = s.streams["fAccelerometer"].t[-1] + 0.5
    together, late = Tracker(trained["root"] / "bundle"), Tracker(trained["root"] / "bundle")
    a_steps, b_steps = [], []
    for a in np.arange(0.0, t_end + 1.0, 0.5):
        a_steps += together.push(chunk(foot + waist, a, a + 0.5))
        b_steps += late.push(chunk(foot, a, a + 0.5))
        b_steps += late.push(chunk(waist, a - 1.0, a - 0.5))
    a_steps += together.flush()
    b_steps += late.flush()
    assert len(a_steps) == len(b_steps) >= len(s.steps) - 2
    for x, y in zip(a_steps, b_steps, strict=True):
        assert (x.start_s, x.end_s, x.classes) == (y.start_s, y.end_s, y.classes)
        assert abs(x.length_m - y.length_m) < 1e-9 and abs(x.x - y.x) < 1e-9


# -- a model trained on rest-to-rest windows (decision 13) with the ensemble (C14) ---------------------
@pytest.fixture(scope="module")
def trained_rest(tmp_path_factory):
    root = rest_dirs(tmp_path_factory)["rest_root"]
    test = synthetic_session(30, seed=5, name="held_out")
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):  # the model is foot-only
        del test.streams[name]
    return {"root": root, "model": load_model(root / "model"), "test": test}


def test_rest_boundary_windows_equal_training_side(trained_rest):
    """The runtime moves a step's ends with the training side's own kernel (rest_boundaries) and cuts the
    same window as step_windows(boundaries="rest")."""
    import pandas as pd

    from pdrlearn.kernels.window import rest_boundaries

    s = trained_rest["test"]
    tr = Tracker(trained_rest["root"] / "bundle")
    tr._trim = lambda *a: None  # keep the whole session buffered, to cut every step's window afterwards
    assert tr.boundaries == "rest" and tr.bundle.manifest["features"]["boundaries"] == "rest"
    steps = replay(tr, s)
    table = pd.DataFrame({"start_s": [st.start_s for st in steps], "end_s": [st.end_s for st in steps]})
    g = s.streams["fGyroscope"]
    a, b = rest_boundaries(g.t, g.values, table["start_s"].to_numpy(), table["end_s"].to_numpy())
    got = np.array([tr.window_bounds(x, y) for x, y in zip(table["start_s"], table["end_s"], strict=True)])
    np.testing.assert_allclose(got, np.column_stack([a, b]), atol=1e-12)
    assert np.abs(got - table.to_numpy()).max() > 1e-3  # the windows really moved off the stance boundaries
    ref = step_windows(s, table, n_samples=tr.n_samples, boundaries="rest").X
    W = np.stack([tr.window(x, y) for x, y in zip(table["start_s"], table["end_s"], strict=True)])
    np.testing.assert_allclose(W, ref, atol=1e-9, equal_nan=True)


@pytest.mark.parametrize("method", REST_METHODS)
def test_rest_boundary_model_streams_like_predict_steps(trained_rest, method, monkeypatch):
    """Streamed steps of a rest-window model, each method incl. the ensemble: classes equal the training
    side's (predict_steps on the streamed step times, which cuts at the rest too), probabilities within 1e-5."""
    # decision C191: a stride whose measured length contradicts its class takes the measured class after the
    # classifier (C88's kernel); this test is the classifier's parity, so the measured-length rules are off
    monkeypatch.setattr("pdrlearn.kernels.turn_length.TURN_LENGTH_RULE", False)
    import pandas as pd

    model, s = trained_rest["model"], trained_rest["test"]
    b = load_bundle(trained_rest["root"] / "bundle")
    tr = Tracker(b, methods={t: f"{method}/foot" for t in b.tasks})
    steps = replay(tr, s)
    assert len(steps) >= len(s.steps) - 2
    table = pd.DataFrame({"start_s": [st.start_s for st in steps], "end_s": [st.end_s for st in steps]})
    ref = model.predict_steps(s, table, method=method, unit="foot")
    for task in tr.classifiers:
        assert [st.classes[task] for st in steps] == list(ref[TASK_COLUMNS[task]]), (task, method)
        got = np.array([[st.proba[task][c] for c in tr.classifiers[task].classes] for st in steps])
        want = ref[[f"p_{task}_{c}" for c in tr.classifiers[task].classes]].to_numpy()
        assert np.abs(got - want).max() <= 1e-5, (task, method)
