"""Conversion of learned models to ONNX: scikit-learn pipelines (skl2onnx) and torch networks.

Each converter returns ``(model, spec)``: the :class:`onnx.ModelProto` and its manifest entry (input
name and dtype, output roles, classes) that :class:`pdrlearn.runtime.bundle.OnnxModel` reads.

Decision E4 (docs/decisions/export.md): a scikit-learn classifier is exported as *one* graph with up
to three outputs: ``label`` and ``scores`` from the raw decision function (so the label equals
``predict``, which for SVC and one-vs-rest uses the decision values, not the probabilities) and
``proba`` equal to ``predict_proba`` where the model has it. skl2onnx converts the two views
separately; the graphs are merged here with a shared input.
"""

from __future__ import annotations

import io
import logging
import warnings

import numpy as np
import onnx

from pdrlearn.errors import ModelError

log = logging.getLogger(__name__)

OPSET = 17  # issue 7: opset >= 17
ML_OPSET = 3


def _decision_view(est):
    """A deep copy whose SVCs report decision values instead of Platt probabilities.

    skl2onnx emits the SVM operator's probabilities for ``SVC(probability=True)`` (``raw_scores`` only
    negates them), while ``predict`` of SVC and of one-vs-rest uses the decision values. The fitted
    support vectors and coefficients are the same either way, so switching the flag off on a copy gives
    the decision-function graph (decision E4).
    """
    import copy

    view = copy.deepcopy(est)

    def off(e) -> None:
        if hasattr(e, "probability"):
            e.probability = False
            if hasattr(e, "_probA"):  # skl2onnx emits Platt probabilities whenever probA_ is non-empty
                e._probA, e._probB = np.empty(0), np.empty(0)
        for sub in getattr(e, "estimators_", []) or []:
            off(sub)

    off(_final(view))
    return view


def _final(est):
    return est.steps[-1][1] if hasattr(est, "steps") else est


def _convert(est, n_features: int, dtype: str, options: dict):
    from skl2onnx import to_onnx
    from skl2onnx.common.data_types import DoubleTensorType, FloatTensorType

    tt = DoubleTensorType if dtype == "float64" else FloatTensorType
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return to_onnx(
            est,
            initial_types=[("X", tt([None, n_features]))],
            options=options,
            target_opset={"": OPSET, "ai.onnx.ml": ML_OPSET},
        )


def _merge(scores_model: onnx.ModelProto, proba_model: onnx.ModelProto) -> onnx.ModelProto:
    """One graph: the first model's outputs plus the second's probabilities, sharing the input ``X``."""
    p = onnx.compose.add_prefix(proba_model, "p_", rename_inputs=False)
    g = onnx.helper.make_graph(
        list(scores_model.graph.node) + list(p.graph.node),
        "pdrlearn_classifier",
        list(scores_model.graph.input),
        list(scores_model.graph.output) + [o for o in p.graph.output if o.name == "p_probabilities"],
        initializer=list(scores_model.graph.initializer) + list(p.graph.initializer),
    )
    opsets = {o.domain: o.version for o in scores_model.opset_import}
    for o in proba_model.opset_import:
        opsets[o.domain] = max(opsets.get(o.domain, 0), o.version)
    m = onnx.helper.make_model(
        g, opset_imports=[onnx.helper.make_opsetid(d, v) for d, v in opsets.items()], producer_name="pdrlearn"
    )
    m.ir_version = scores_model.ir_version
    return m


def sklearn_to_onnx(
    est, n_features: int, *, dtype: str = "float64", name: str = "model"
) -> tuple[onnx.ModelProto, dict]:
    """Convert a fitted scikit-learn classifier or pipeline (scaler + SVC / one-vs-rest SVC ...).

    Parameters
    ----------
    est : fitted estimator with ``classes_``.
    n_features : number of input columns.
    dtype : input dtype of the graph (``float64`` keeps the scaler exact; the SVM operator computes in
        float32 internally either way).
    name : used in messages.

    Returns
    -------
    model, spec : the ONNX model and its manifest entry (``kind="sklearn"``).
    """
    final = _final(est)
    classes = [str(c) for c in getattr(final, "classes_", getattr(est, "classes_", []))]
    if not classes:
        raise ModelError(f"{name}: estimator is not a fitted classifier (no classes_)")
    zip_opt = {"zipmap": False}
    raw_opt = {"zipmap": False, "raw_scores": True}
    has_dec = hasattr(final, "decision_function")
    try:
        if has_dec:
            view = _decision_view(est)
            ovr = hasattr(final, "estimators_")
            opts = {id(view): zip_opt, id(_final(view)): raw_opt if ovr else zip_opt}
            scores = _convert(view, n_features, dtype, opts)
        else:
            scores = _convert(est, n_features, dtype, {id(est): zip_opt})
    except Exception as exc:  # skl2onnx raises many types for unsupported constructs
        raise ModelError(
            f"{name}: skl2onnx cannot convert {type(final).__name__} ({exc}); see docs/decisions/export.md"
        ) from None
    outputs = {"label": scores.graph.output[0].name}
    second = scores.graph.output[1].name if len(scores.graph.output) > 1 else None
    if has_dec and second:
        outputs["scores"] = second
    model = scores
    proba_ok = _proba_available(final)
    if proba_ok and has_dec:
        proba = _convert(est, n_features, dtype, {id(est): zip_opt})
        model = _merge(scores, proba)
        outputs["proba"] = "p_probabilities"
    elif proba_ok and second:
        outputs["proba"] = second
    onnx.checker.check_model(model, full_check=True)
    spec = {
        "kind": "sklearn",
        "estimator": type(final).__name__,
        "input": "X",
        "dtype": dtype,
        "n_features": int(n_features),
        "outputs": outputs,
        "classes": classes,
    }
    return model, spec


def _proba_available(final) -> bool:
    """predict_proba exists and is usable (SVC(probability=False) hides it)."""
    try:
        final.predict_proba  # noqa: B018
    except AttributeError:
        return False
    if hasattr(final, "estimators_"):  # one-vs-rest: every binary estimator needs it
        return all(_proba_available(e) for e in final.estimators_)
    return True


def torch_to_onnx(
    module,
    n_features: int,
    *,
    classes: list[str],
    softmax: bool = True,
    name: str = "network",
    dtype: str = "float32",
) -> tuple[onnx.ModelProto, dict]:
    """Export a torch network ``(batch, n_features) -> (batch, n_classes)`` logits (opset 17, dynamic batch).

    Parameters
    ----------
    module : ``torch.nn.Module`` returning logits.
    classes : class labels in the order of the output columns.
    softmax : append a softmax so the graph also outputs probabilities (role ``proba``).
    dtype : ``float32`` (runs in OpenCV's dnn fallback too) or ``float64`` (the module is converted to
        double; parity with a float64 numpy network to ~1e-12, decision E4).
    """
    import torch

    class _WithProba(torch.nn.Module):
        def __init__(self, inner):
            super().__init__()
            self.inner = inner

        def forward(self, x):
            logits = self.inner(x)
            return logits, torch.softmax(logits, dim=1)

    net = _WithProba(module) if softmax else module
    tdt = torch.float64 if dtype == "float64" else torch.float32
    net = net.to(tdt)
    was_training = module.training
    module.eval()
    out_names = ["logits", "proba"] if softmax else ["logits"]
    f = io.BytesIO()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            torch.onnx.export(
                net,
                (torch.zeros(2, n_features, dtype=tdt),),
                f,
                input_names=["X"],
                output_names=out_names,
                opset_version=OPSET,
                dynamic_axes={"X": {0: "batch"}, **{o: {0: "batch"} for o in out_names}},
                dynamo=False,
            )
    except Exception as exc:
        raise ModelError(f"{name}: torch.onnx.export failed ({exc})") from None
    finally:
        module.train(was_training)
    model = onnx.load_from_string(f.getvalue())
    onnx.checker.check_model(model, full_check=True)
    spec = {
        "kind": "network",
        "input": "X",
        "dtype": dtype,
        "n_features": int(n_features),
        "outputs": {o: o for o in out_names},
        "classes": [str(c) for c in classes],
    }
    return model, spec


def check_parity(
    model: onnx.ModelProto,
    spec: dict,
    est_predict,
    est_proba,
    X: np.ndarray,
    *,
    atol: float = 1e-5,
    name: str = "model",
) -> dict:
    """Compare the ONNX graph with the source estimator on ``X``; returns a summary, raises on mismatch.

    ``est_predict`` / ``est_proba`` are callables of the training side (``est_proba`` may be None).
    """
    import onnxruntime as ort

    sess = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    names = [o.name for o in sess.get_outputs()]
    out = dict(zip(names, sess.run(None, {spec["input"]: np.asarray(X, dtype=spec["dtype"])}), strict=True))
    res: dict = {"n": int(len(X))}
    classes = np.asarray(spec["classes"])
    if "label" in spec["outputs"]:
        onnx_labels = np.asarray(out[spec["outputs"]["label"]]).astype(str)
    else:
        onnx_labels = classes[np.argmax(out[spec["outputs"]["logits"]], axis=1)]
    want = np.asarray(est_predict(X)).astype(str)
    res["label_agreement"] = float(np.mean(onnx_labels == want)) if len(X) else 1.0
    if est_proba is not None and "proba" in spec["outputs"]:
        d = np.abs(out[spec["outputs"]["proba"]] - est_proba(X))
        res["proba_max_abs_diff"] = float(d.max()) if d.size else 0.0
    if res["label_agreement"] < 1.0 or res.get("proba_max_abs_diff", 0.0) > atol:
        raise ModelError(f"{name}: ONNX export differs from the trained model ({res}); see docs/decisions/export.md")
    return res


def svm_decision_to_onnx(
    mean: np.ndarray, scale: np.ndarray, params: list[dict], classes: list[str], *, name: str = "svm"
) -> tuple[onnx.ModelProto, dict]:
    """A float64 graph of the one-vs-rest SVM decision values, built from standard ONNX operators.

    ``Z = (X - mean) / scale``; per class ``d_k = K(Z, SV_k) @ dual_k + b_k`` with the linear, polynomial
    ``(gamma Z.SV + coef0)^degree`` or rbf ``exp(-gamma max(|Z|^2 - 2 Z.SV + |SV|^2, 0))`` kernel
    (the formula of :func:`pdrlearn.classify.svm.svc_decision`); ``scores`` = the ``d_k`` side by side,
    ``proba = softmax(scores)``. Unlike the ``ai.onnx.ml`` SVM operator (float32 inside; decision values
    off by ~1e-4 when large kernel terms cancel), this keeps float64 end to end (decision E4).

    All classes' support vectors share one product ``Z @ SV.T``; the kernels are applied column-wise
    (linear = polynomial with gamma 1, coef0 0, degree 1, which is exact) and one product with the
    block matrix of the dual coefficients gives every ``d_k`` (a fixed number of nodes per model, so the
    runtime's step graph stays small).
    """
    from onnx import TensorProto, helper, numpy_helper

    D = TensorProto.DOUBLE
    n_features = int(len(mean))
    for p in params:
        if p["kernel"] not in ("linear", "poly", "rbf"):
            raise ModelError(f"{name}: kernel {p['kernel']!r} has no ONNX translation; see docs/decisions/export.md")
    svs = [np.asarray(p["sv"], np.float64).reshape(-1, n_features) for p in params]
    sizes = [len(v) for v in svs]
    sv = np.concatenate(svs, axis=0)
    col_kernel = np.repeat([p["kernel"] for p in params], sizes)
    col = {k: np.repeat([float(p[k]) if p["kernel"] == "poly" else d for p in params], sizes)
           for k, d in (("gamma", 1.0), ("coef0", 0.0), ("degree", 1.0))}
    dual = np.zeros((len(sv), len(params)))
    for k, (o, p) in enumerate(zip(np.cumsum([0] + sizes[:-1]), params, strict=True)):
        dual[o:o + sizes[k], k] = np.asarray(p["dual"], np.float64).reshape(-1)
    inits = [
        numpy_helper.from_array(np.asarray(mean, np.float64), "mean"),
        numpy_helper.from_array(np.asarray(scale, np.float64), "scale"),
        numpy_helper.from_array(np.ascontiguousarray(sv.T), "svT"),
        numpy_helper.from_array(dual, "dual"),
        numpy_helper.from_array(np.array([p["b"] for p in params], np.float64), "b"),
    ]
    nodes = [helper.make_node("Sub", ["X", "mean"], ["Xc"]), helper.make_node("Div", ["Xc", "scale"], ["Z"]),
             helper.make_node("MatMul", ["Z", "svT"], ["dot"])]
    is_rbf = col_kernel == "rbf"
    if not is_rbf.all():
        inits += [numpy_helper.from_array(col[k], k) for k in ("gamma", "coef0", "degree")]
        nodes += [
            helper.make_node("Mul", ["dot", "gamma"], ["gd"]),
            helper.make_node("Add", ["gd", "coef0"], ["base"]),
            helper.make_node("Pow", ["base", "degree"], ["K_poly"]),
        ]
    if is_rbf.any():
        gam = np.repeat([float(p["gamma"]) if p["kernel"] == "rbf" else 0.0 for p in params], sizes)
        inits += [
            numpy_helper.from_array(np.ones((n_features, 1)), "ones_col"),
            numpy_helper.from_array(np.zeros(1), "zero"),
            numpy_helper.from_array(np.array([-2.0]), "m2"),
            numpy_helper.from_array(-gam, "neg_gamma"),
            numpy_helper.from_array(np.sum(sv**2, axis=1)[None, :], "sv_sq"),
        ]
        nodes += [
            helper.make_node("Mul", ["Z", "Z"], ["Z2"]),
            helper.make_node("MatMul", ["Z2", "ones_col"], ["z_sq"]),  # (n, 1)
            helper.make_node("Mul", ["dot", "m2"], ["m2dot"]),
            helper.make_node("Add", ["z_sq", "m2dot"], ["a"]),
            helper.make_node("Add", ["a", "sv_sq"], ["d2raw"]),
            helper.make_node("Max", ["d2raw", "zero"], ["d2"]),
            helper.make_node("Mul", ["d2", "neg_gamma"], ["e"]),
            helper.make_node("Exp", ["e"], ["K_rbf"]),
        ]
    if is_rbf.all():
        K = "K_rbf"
    elif not is_rbf.any():
        K = "K_poly"
    else:
        inits.append(numpy_helper.from_array(is_rbf, "is_rbf"))
        nodes.append(helper.make_node("Where", ["is_rbf", "K_rbf", "K_poly"], ["K"]))
        K = "K"
    nodes += [
        helper.make_node("MatMul", [K, "dual"], ["kd"]),
        helper.make_node("Add", ["kd", "b"], ["scores"]),
        helper.make_node("Softmax", ["scores"], ["proba"], axis=1),
    ]

    g = helper.make_graph(
        nodes,
        name,
        [helper.make_tensor_value_info("X", D, [None, n_features])],
        [
            helper.make_tensor_value_info("scores", D, [None, len(params)]),
            helper.make_tensor_value_info("proba", D, [None, len(params)]),
        ],
        initializer=inits,
    )
    model = helper.make_model(g, opset_imports=[helper.make_opsetid("", OPSET)], producer_name="pdrlearn")
    model.ir_version = 8  # onnxruntime >= 1.14 reads IR 8 / opset 17
    onnx.checker.check_model(model, full_check=True)
    spec = {
        "kind": "svm",
        "estimator": "SVMClassifier (one-vs-rest, float64 decision graph)",
        "input": "X",
        "dtype": "float64",
        "n_features": n_features,
        "outputs": {"scores": "scores", "proba": "proba"},
        "classes": [str(c) for c in classes],
    }
    return model, spec
