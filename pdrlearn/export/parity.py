"""Decision E80: a bundle is written only when its models give the trained model's probabilities.

``pdrlearn export`` translates each estimator into ONNX graphs, feature recipes and NPZ/JSON tables. Before the
bundle's folder is renamed into place (:func:`pdrlearn.export.bundle.write_bundle`'s ``loader`` hook), every
exported entry is run on a few step windows of a simulated calibration walk and compared with the estimator's own
``predict_proba``: a model the translation does not reproduce (a subclass, an extra pipeline step that slipped
through, a changed formula) stops the export instead of shipping a bundle that classifies differently.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from pdrlearn.errors import ModelError

#: largest difference of a probability allowed between the bundle and ``predict_proba`` (as
#: :func:`pdrlearn.export.onnx_convert.check_parity`; the float64 graphs agree to ~1e-12, decision E4)
PARITY_ATOL = 1e-5
#: the simulated user (and scenario) whose steps the check classifies: a terrain exercise has level, up and down
#: steps, so the windows cover the classifiers' range (a check input, not a measurement)
PARITY_USER, PARITY_SCENARIO, PARITY_WINDOWS = 0, "terrain", 12


@lru_cache(maxsize=4)
def parity_windows(n_samples: int, boundaries: str = "given") -> np.ndarray:
    """``PARITY_WINDOWS`` step windows ``(n, channels, n_samples)`` of the simulated terrain exercise, spread over
    the walk, without missing samples."""
    from pdrlearn.features import step_windows
    from pdrlearn.sim import simulate

    s = simulate(PARITY_SCENARIO, PARITY_USER, rate_hz=20.0)
    W = step_windows(s, s.steps, n_samples=int(n_samples), boundaries=boundaries).X
    W = W[np.isfinite(W).all(axis=(1, 2))]
    pick = np.unique(np.linspace(0, len(W) - 1, PARITY_WINDOWS).round().astype(int))
    out = W[pick]
    out.setflags(write=False)
    return out


def check_bundle_parity(bundle, models: dict, W: np.ndarray, *, atol: float = PARITY_ATOL) -> dict:
    """Compare every model entry of an opened ``bundle``, and its step graph (decision E10: what the Tracker
    runs for the chosen models), with the estimators on windows ``W``.

    ``models``: task -> method -> unit -> fitted estimator (``UserModel.tasks[task].models``). Returns
    ``{"task method/unit": max abs difference}`` (the graph's as ``"task step graph"``); raises
    :class:`ModelError` naming the first that differs.
    """
    from pdrlearn.runtime.classify import RuntimeModel, StepGraph, TaskClassifier

    fm = bundle.manifest["features"]
    ctx = {"signals": fm["signals"], "channel_index": {c: i for i, c in enumerate(fm["channels"])}}
    out: dict = {}
    for task, spec in bundle.tasks.items():
        for method, per in spec["methods"].items():
            for unit, entry in per.items():
                got = RuntimeModel(bundle, entry, ctx).proba(W.copy())
                out[f"{task} {method}/{unit}"] = _compare(f"{task} {method}/{unit} model", models[task][method][unit],
                                                          got, entry["classes"], W, atol)
    graph = StepGraph.open(bundle, {t: TaskClassifier(bundle, t, ctx) for t in bundle.tasks})
    if graph is not None:
        probs = graph.predict(np.ascontiguousarray(W, dtype=np.float64))
        for task in graph.tasks:
            chosen = bundle.tasks[task]["chosen"]
            est = models[task][chosen["method"]][chosen["unit"]]
            out[f"{task} step graph"] = _compare(f"{task} step graph ({chosen['method']}/{chosen['unit']})", est,
                                                 probs[task], bundle.tasks[task]["classes"], W, atol)
    return out


def _compare(name: str, est, got: np.ndarray, classes, W: np.ndarray, atol: float) -> float:
    """The largest difference of the bundle's probabilities ``got`` (columns ``classes``) from ``est``'s."""
    from pdrlearn.kernels.proba import align_proba

    classes = [str(c) for c in classes]
    want = align_proba(np.asarray(est.predict_proba(W.copy()), dtype=float), [str(c) for c in est.classes_], classes)
    diff = float(np.abs(np.asarray(got, dtype=float) - want).max()) if W.size else 0.0
    if not diff <= atol:
        raise ModelError(
            f"export: the bundle's {name} ({type(est).__name__}) gives probabilities up to {diff:.3g} away from its "
            f"predict_proba on {len(W)} simulated steps, so no bundle was written (decision E80); use the model in "
            "Python (pdrlearn track --model) or export pdrlearn's own classes (pdrlearn train)")
    return diff
