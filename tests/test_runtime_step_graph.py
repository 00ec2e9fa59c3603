"""The bundle's step graph (decision E10): one onnxruntime run per step gives the per-model path's numbers.

The graph computes the feature recipes, runs the inlined models and fuses the units; it must equal the
numpy recipes (:func:`pdrlearn.runtime.features.compute_features`) and the per-model classifiers
(which the parity tests pin to the training side) on every exportable method x unit.
"""

from __future__ import annotations

import copy

import numpy as np
import onnx
import onnxruntime as ort
import pytest

from pdrlearn.errors import DataError
from pdrlearn.export.step_graph import build_step_graph, features_graph
from pdrlearn.features import step_windows
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.classify import TaskClassifier
from pdrlearn.runtime.features import compute_features
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    root = trained_dirs(tmp_path_factory)["root"]
    test = synthetic_session(30, seed=5, name="held_out")
    return {"root": root, "test": test, "W": step_windows(test, test.steps, n_samples=40).X}


def _run(model: onnx.ModelProto, W: np.ndarray) -> dict[str, np.ndarray]:
    sess = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    names = [o.name for o in sess.get_outputs()]
    return dict(zip(names, sess.run(names, {"W": W}), strict=True))


def _ctx(bundle):
    fm = bundle.manifest["features"]
    return {"signals": fm["signals"], "channel_index": {c: i for i, c in enumerate(fm["channels"])}}


def _leaves(entry):
    if entry["type"] == "fusion":
        return [x for e in entry["members"].values() for x in _leaves(e)]
    return [entry]


def _random_windows(bundle, n=64, seed=0):
    """Windows with awkward force rows: never zero, zero only at the last sample, all zero, ties."""
    fm = bundle.manifest["features"]
    ci = {c: i for i, c in enumerate(fm["channels"])}
    rng = np.random.default_rng(seed)
    m = int(fm["n_samples"])
    W = rng.normal(size=(n, len(ci), m))
    W[:, ci["t_s"]] = np.linspace(0.0, 1.0, m)[None, :] * rng.uniform(0.4, 2.5, (n, 1))
    W[:, ci["force_a"]] = np.abs(W[:, ci["force_a"]]) * 100
    W[0, ci["force_a"]] = 50.0 + np.arange(m)  # never below 5 % of its peak
    W[0, ci["force_b"]] = 0.0
    W[1, ci["force_a"], -1] = W[1, ci["force_b"], -1] = -1.0  # zero at the last sample only
    W[2, ci["force_a"]] = W[2, ci["force_b"]] = 0.0  # no force at all (peak 0)
    W[3, ci["foot_acc_z"]] = 1.0  # flat signal: argmin/argmax ties
    return W


def test_every_recipe_item_equals_the_numpy_recipe(trained):
    bundle = load_bundle(trained["root"] / "bundle_all")
    recipes = {json_key(leaf["features"]): leaf["features"] for spec in bundle.tasks.values()
               for per in spec["methods"].values() for e in per.values() for leaf in _leaves(e)
               if leaf["type"] == "onnx"}
    ops = {item[0] for r in recipes.values() for item in r}
    assert {"peak", "segments", "force", "yaw", "yaw_sign"} <= ops
    for W in (trained["W"], _random_windows(bundle)):
        for recipe in recipes.values():
            got = _run(features_graph(recipe, bundle.manifest["features"]), W)["F"]
            want = compute_features(W, recipe, **_ctx(bundle))
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12, err_msg=str(recipe))


def json_key(recipe):
    return repr(recipe)


@pytest.mark.parametrize("method", ["svm", "nn"])
def test_step_graph_equals_the_per_model_path_for_every_method_and_unit(trained, method):
    bundle = load_bundle(trained["root"] / "bundle_all")
    models = {rel: onnx.load(bundle.path / rel) for rel in bundle.manifest["files"] if rel.endswith(".onnx")}
    W = trained["W"]
    for unit in ("foot", "waist", "fused"):
        tasks = copy.deepcopy(bundle.tasks)
        for spec in tasks.values():
            spec["chosen"] = {"method": method, "unit": unit}
        model, spec = build_step_graph(tasks, models, bundle.manifest["features"])
        assert set(spec["outputs"]) == set(tasks)
        out = _run(model, W)
        for task in tasks:
            classes, proba = TaskClassifier(bundle, task, _ctx(bundle), method=method, unit=unit).predict(W)
            got = out[spec["outputs"][task]]
            assert np.abs(got - proba).max() <= 1e-9, (task, method, unit)
            assert list(np.asarray(bundle.classes(task))[np.argmax(got, axis=1)]) == list(classes)


def test_tracker_with_step_graph_streams_the_same_steps(trained):
    s = trained["test"]
    graph = Tracker(trained["root"] / "bundle")
    plain = Tracker(trained["root"] / "bundle", step_graph=False)
    assert graph.step_graph is not None and set(graph.step_graph.tasks) == set(graph.classifiers)
    assert plain.step_graph is None
    assert not graph.bundle._models and plain.bundle._models  # the graph tracker opens no per-model session
    data = {n: (st.t, st.values) for n, st in s.streams.items()}
    a, b = graph.push(data) + graph.flush(), plain.push(data) + plain.flush()
    assert len(a) == len(b) >= len(s.steps) - 2
    for x, y in zip(a, b, strict=True):
        assert x.classes == y.classes
        for task in x.proba:
            assert max(abs(x.proba[task][c] - y.proba[task][c]) for c in x.proba[task]) <= 1e-9
        # positions equal to float rounding: the default bayes rule (L41) weighs lengths by the class
        # probabilities, which the two paths compute to <= 1e-9 (above), so a last-bit difference is expected
        assert np.allclose((x.x, x.y, x.z), (y.x, y.y, y.z), rtol=0, atol=1e-9)


def test_other_methods_and_non_graph_models_use_the_per_model_path(trained):
    bundle = load_bundle(trained["root"] / "bundle_all")
    tr = Tracker(bundle, methods={"terrain": "dtw/foot"})
    assert "terrain" not in (tr.step_graph.tasks if tr.step_graph else [])
    models = {rel: onnx.load(bundle.path / rel) for rel in bundle.manifest["files"] if rel.endswith(".onnx")}
    tasks = copy.deepcopy(bundle.tasks)
    for spec in tasks.values():
        spec["chosen"] = {"method": "dtw", "unit": "foot"}
    assert build_step_graph(tasks, models, bundle.manifest["features"]) is None  # DTW stays in numpy
    W = trained["W"][:5]
    res = tr.classify(W)
    ref = Tracker(bundle, methods={"terrain": "dtw/foot"}, step_graph=False).classify(W)
    for task in res:
        assert list(res[task][0]) == list(ref[task][0])
        assert np.abs(res[task][1] - ref[task][1]).max() <= 1e-9


def test_missing_sensor_in_the_window_is_a_data_error(trained):
    tr = Tracker(trained["root"] / "bundle")
    W = trained["W"][:2].copy()
    ch = tr.step_graph.channels
    W[:, ch[-1]] = np.nan
    with pytest.raises(DataError, match="NaN"):
        tr.classify(W)


def test_head_prunes_zero_weight_units_and_merges_the_networks(trained):
    """Decision E13: a unit of fusion weight 0 is left out of the graph, the networks run as one
    block-diagonal network, and the soft vote is one product; numbers = soft_vote of the per-model path."""
    from pdrlearn.kernels.proba import align_proba, soft_vote
    from pdrlearn.runtime.classify import RuntimeModel

    bundle = load_bundle(trained["root"] / "bundle_all")
    models = {rel: onnx.load(bundle.path / rel) for rel in bundle.manifest["files"] if rel.endswith(".onnx")}
    tasks = copy.deepcopy(bundle.tasks)
    chosen = {"terrain": "nn", "direction": "nn", "length": "svm"}
    for task, spec in tasks.items():
        spec["chosen"] = {"method": chosen[task], "unit": "fused"}
    tasks["terrain"]["methods"]["nn"]["fused"]["weights"] = [1.0, 0.0]  # waist network: weight 0
    tasks["length"]["methods"]["svm"]["fused"]["weights"] = [0.3, 0.7]
    model, spec = build_step_graph(tasks, models, bundle.manifest["features"])
    ops = [n.op_type for n in model.graph.node]
    heads = [n for n in model.graph.node if n.op_type == "Split" and set(n.output) & set(spec["outputs"].values())]
    assert ops.count("Tanh") == 1 and len(heads) == 1  # one network block, one head (E19: the force block splits too)
    assert ops.count("Softmax") == 1  # E19: one Softmax for the network and the SVM blocks
    # E19: the shared scaler and Softmax give the separate blocks' numbers bit for bit (the SVM's two classes
    # padded to the networks' three with a -1e300 score)
    apart, _ = build_step_graph(tasks, models, bundle.manifest["features"], one_softmax=False)
    assert [n.op_type for n in apart.graph.node].count("Softmax") == 2
    for W in (trained["W"], _random_windows(bundle)):
        got, want = _run(model, W), _run(apart, W)
        assert all(np.array_equal(got[k], want[k]) for k in want)
    # the block holds exactly the networks of non-zero weight (the terrain waist network is left out)
    W1_rows = sum(i.dims[0] for i in model.graph.initializer if i.name.endswith("nn_W1"))  # its blocks

    def hidden(e):
        return next(i for i in models[e["file"]].graph.initializer if i.name.endswith("hidden.weight")).dims[0]

    want_hidden = sum(hidden(e) for t in ("terrain", "direction")
                      for e, w in zip(tasks[t]["methods"]["nn"]["fused"]["members"].values(),
                                      tasks[t]["methods"]["nn"]["fused"]["weights"], strict=True) if w != 0)
    assert W1_rows == want_hidden
    assert want_hidden < sum(hidden(e) for t in ("terrain", "direction")
                             for e in tasks[t]["methods"]["nn"]["fused"]["members"].values())
    W = trained["W"]
    out = _run(model, W)
    ctx = _ctx(bundle)
    for task, spec_t in tasks.items():
        entry = spec_t["methods"][chosen[task]]["fused"]
        classes = list(spec_t["classes"])
        probas = []
        for e in entry["members"].values():
            probas.append(align_proba(RuntimeModel(bundle, e, ctx).proba(W), e["classes"], entry["classes"]))
        want = align_proba(soft_vote(probas, entry["weights"]), entry["classes"], classes)
        got = out[spec["outputs"][task]]
        assert np.abs(got - want).max() <= 1e-12, task
        assert (np.argmax(got, axis=1) == np.argmax(want, axis=1)).all()


def test_rebuilt_step_graph_gives_the_same_steps(trained, tmp_path):
    """rebuild_step_graph (decision E13) rewrites a bundle's step graph atomically, checksums included."""
    from pdrlearn.export.bundle import rebuild_step_graph

    src = trained["root"] / "bundle"
    out = rebuild_step_graph(src, tmp_path / "rebuilt")
    b = load_bundle(out, verify=True)
    assert b.manifest["step_graph"]["file"] in b.manifest["files"]
    s = trained["test"]
    data = {n: (st.t, st.values) for n, st in s.streams.items()}
    x_steps = Tracker(src).push(data)
    y_steps = Tracker(b).push(data)
    assert len(x_steps) == len(y_steps) > 0
    for x, y in zip(x_steps, y_steps, strict=True):
        assert x.classes == y.classes and (x.x, x.y, x.z) == (y.x, y.y, y.z)
        for task in x.proba:
            assert max(abs(x.proba[task][c] - y.proba[task][c]) for c in x.proba[task]) <= 1e-12


@pytest.mark.parametrize("kernels,degree", [(("rbf", "rbf", "rbf"), 3), (("poly", "linear"), 3),
                                            (("rbf", "poly", "linear"), 3), (("rbf", "poly", "linear"), 2),
                                            (("poly", "linear"), 2)])
def test_svm_block_equals_each_svm_graph(trained, kernels, degree):
    """Decision E13: the SVM decision graphs of several units/tasks merged into one block (rbf only, poly /
    linear only, mixed; 2 and 3 classes, so the padded class columns are exercised) give each graph's numbers.
    Decision E16: with polynomial degrees 1 and 2 only, the block squares by a product (no Pow node)."""
    from pdrlearn.classify.svm import svc_decision
    from pdrlearn.export.onnx_convert import svm_decision_to_onnx
    from pdrlearn.kernels.proba import soft_vote, softmax

    bundle = load_bundle(trained["root"] / "bundle_all")
    features = bundle.manifest["features"]
    rng = np.random.default_rng(len(kernels))
    recipes = {"foot": [["segments", "foot_acc_fwd", 2]], "waist": [["segments", "waist_acc_v", 3]]}
    models, tasks, want = {}, {}, {}
    W = trained["W"]
    for task, classes in (("a", ["x", "y", "z"][:len(kernels)]), ("b", ["p", "q"])):
        members, probas = {}, []
        for unit, recipe in recipes.items():
            F = compute_features(W, recipe, **_ctx(bundle))
            mean, scale = F.mean(axis=0), F.std(axis=0) + 0.5
            params = []
            for c in range(len(classes)):
                kern, n_sv = kernels[c % len(kernels)], int(rng.integers(3, 9))
                params.append({"kernel": kern, "sv": rng.normal(size=(n_sv, F.shape[1])), "dual": rng.normal(size=n_sv),
                               "b": float(rng.normal()), "gamma": 0.1, "degree": degree if kern == "poly" else 1,
                               "coef0": 1.0 if kern == "poly" else 0.0})
            model, spec = svm_decision_to_onnx(mean, scale, params, classes)
            rel = f"models/{task}_{unit}.onnx"
            models[rel] = model
            members[unit] = {"type": "onnx", "file": rel, "features": recipe, **spec}
            Z = (F - mean) / scale
            scores = np.column_stack([svc_decision(Z, p["sv"], p["dual"], p["b"], kernel=p["kernel"],
                                                   gamma=p["gamma"], degree=p["degree"], coef0=p["coef0"])
                                      for p in params])
            probas.append(softmax(scores))
        weights = [0.35, 0.65]
        tasks[task] = {"classes": classes, "chosen": {"method": "svm", "unit": "fused"},
                       "methods": {"svm": {"fused": {"type": "fusion", "weights": weights, "classes": classes,
                                                     "members": members}}}}
        want[task] = soft_vote(probas, weights)
    model, spec = build_step_graph(tasks, models, features)
    ops = [n.op_type for n in model.graph.node]
    assert ops.count("Softmax") == 1  # one block for the four SVMs
    assert ("Pow" in ops) == ("poly" in kernels and degree == 3)
    out = _run(model, W)
    for task in tasks:
        np.testing.assert_allclose(out[spec["outputs"][task]], want[task], rtol=0, atol=1e-9)


def test_process_step_resamples_only_the_channels_the_graph_reads(trained):
    """Decision E13: with every task in the step graph, process_step fills only the graph's channels; those
    equal the full window's bit for bit, and a tracker with full windows (step_graph=False) emits the same
    steps."""
    s = trained["test"]
    tr = Tracker(trained["root"] / "bundle")
    assert tr._step_channels is not None and len(tr._step_channels) < len(tr.channels)
    assert Tracker(trained["root"] / "bundle_all", methods={"terrain": "dtw/foot"})._step_channels is None
    for n, st in s.streams.items():
        tr._append(n, st.t, st.values)
    used = [tr.ci[c] for c in sorted(tr._step_channels)]
    unused = [j for j in range(len(tr.channels)) if j not in used]
    for a, b in zip(s.steps["start_s"][1:6], s.steps["end_s"][1:6], strict=True):
        part, full = tr._window(a, b)[0], tr._window(a, b, channels=None)[0]
        np.testing.assert_array_equal(part[used], full[used])
        assert np.isnan(part[unused]).all() and np.isfinite(full[unused]).any()
        # the foot levelled at push time (decision E15) rounds differently from the shared kernel alone
        np.testing.assert_allclose(full, tr.window(a, b), rtol=0, atol=1e-12)


@pytest.mark.parametrize("stats", [["air_time"], ["time_to_peak"], ["peak_mean_4"], ["contact_force_2"],
                                   ["takeoff_force"], ["takeoff_force", "time_to_peak", "air_time"],
                                   ["contact_force_2", "peak_mean_4", "time_to_peak", "takeoff_force", "air_time"]])
def test_force_block_computes_only_the_asked_statistics_like_the_kernel(trained, stats):
    """Decision E16: the force block gathers and interpolates only the instants its statistics need, and
    the segment block's differences are +-1 products; every column still equals the numpy recipe."""
    bundle = load_bundle(trained["root"] / "bundle_all")
    recipe = [["force", st, zf] for zf in (0.05, 0.2) for st in stats] + [["segments", "foot_pitch", 6],
                                                                          ["segments", "foot_acc_fwd", 3]]
    model = features_graph(recipe, bundle.manifest["features"])
    for W in (trained["W"], _random_windows(bundle)):
        got = _run(model, W)["F"]
        want = compute_features(W, recipe, **_ctx(bundle))
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12, err_msg=str(stats))
    ops = [n.op_type for n in model.graph.node]
    interpolated = bool({"peak_mean_4", "contact_force_2", "takeoff_force"} & set(stats))
    # one interpolation per zero fraction when a statistic needs one (E19: one LessOrEqual, the end rule
    # without a Where), and one contact-peak mask when a statistic needs the peak
    assert ops.count("LessOrEqual") == 2 * interpolated
    assert ops.count("GreaterOrEqual") == 2 * bool({"time_to_peak", "peak_mean_4"} & set(stats))


def test_nan_window_names_the_empty_channels(trained):
    """Second new-user trial: 'step features are NaN: the stream lacks a sensor the model needs' did not say
    which; the error names the window channels that are empty."""
    from pdrlearn.errors import DataError

    tr = Tracker(trained["root"] / "bundle")
    g = tr.step_graph
    W = np.zeros((1, len(tr.channels), tr.n_samples))
    name = g.channel_names[-1]
    W[0, tr.ci[name]] = np.nan
    with pytest.raises(DataError, match=rf"window channels {name} are empty\); push those sensors"):
        g.predict(W)
