"""Export a trained per-user model directory (``pdrlearn train --out MODEL_DIR``) as a runtime bundle.

Reads the model with :func:`pdrlearn.classify.model_dir.load_model`; converts every exported
task x method x unit: SVM (per-class scaler + SVC pipelines -> one ONNX graph), NN (torch -> ONNX),
DTW (reference steps -> NPZ), unit fusion (weights in the manifest, members as above). Feature
transformers become *recipes* (JSON lists) that :mod:`pdrlearn.runtime.features` evaluates.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from pdrlearn.errors import ModelError
from pdrlearn.export.bundle import base_manifest, write_bundle
from pdrlearn.export.onnx_convert import svm_decision_to_onnx, torch_to_onnx
from pdrlearn.export.parity import PARITY_ATOL, check_bundle_parity, parity_windows
from pdrlearn.export.precision import FLOAT32_PARITY_ATOL, bundle_to_float32, check_float32_ranges
from pdrlearn.export.sizes import onnx_stats
from pdrlearn.export.step_graph import build_step_graph

STEP_GRAPH_FILE = "models/step.onnx"
#: the values of ``export --units`` (decision E218): a bundle of the models that read one body unit alone. Decision
#: E233 (review R0 finding 4): foot only; a waist-only classifier bundle could not be run (the runtime detects steps
#: on the foot unit's gyroscope, E7), so ``--units waist`` is refused and names the waist bundle (E57)
EXPORT_UNITS = ("foot",)

log = logging.getLogger(__name__)

#: Thesis frames of the PLASYS units (thesis ch.4, Figs. 28-29; docs/decisions.md D2), the bundle default.
DEFAULT_FRAMES = {
    "foot": {"x": "forward", "y": "up", "z": "right"},
    "waist": {"x": "left", "y": "up", "z": "forward"},
}
#: Sensors of each unit (thesis ch.4.3.3).
UNIT_SENSORS = {"foot": ["fAccelerometer", "fGyroscope"], "waist": ["wAccelerometer", "wGyroscope"]}
OPTIONAL_SENSORS = ["fForceA", "fForceB", "wMagneticField", "wBarometer"]


def feature_recipe(transformer) -> list:
    """The runtime recipe of a feature transformer of :mod:`pdrlearn.features.transformers`."""
    from pdrlearn.features import transformers as T

    name = type(transformer).__name__
    kind = type(transformer)  # decision E79: exact types (a subclass's overrides would not reach the runtime)
    if kind is T.TerrainSVMFeatures:
        return [["peak", sig, stat] for sig, stat in transformer._spec()]
    if kind is T.SegmentFeatures:
        return [["segments", c, int(transformer.n_segments)] for c in transformer.channels]
    if kind is T.DirectionFeatures:
        out = [["segments", transformer._acc(), int(transformer.n_segments)]]
        return out + ([["yaw_sign"]] if transformer.unit != "foot" else [])
    if kind is T.LengthFeatures:
        out = []
        if transformer.unit != "waist":
            out.append(["segments", "foot_acc_fwd", int(transformer.n_segments)])
            out += [["force", s, float(transformer.zero_fraction)] for s in T.LENGTH_FORCE_STATS]
        if transformer.unit != "foot":
            out += [["yaw", s] for s in T.LENGTH_WAIST_STATS]
        return out
    raise ModelError(f"feature transformer {name} has no runtime recipe; see docs/decisions/export.md")


def _exportable_types() -> tuple:
    """The estimator and transformer classes the bundle has a runtime translation of (decision E79)."""
    from sklearn.pipeline import Pipeline
    from sklearn.preprocessing import FunctionTransformer

    from pdrlearn.classify import heuristic as H
    from pdrlearn.classify.dtw import DTWClassifier
    from pdrlearn.classify.fusion import UnitFusionClassifier
    from pdrlearn.classify.nn import NNClassifier
    from pdrlearn.classify.svm import SVMClassifier
    from pdrlearn.features import transformers as T

    return (Pipeline, FunctionTransformer, UnitFusionClassifier, DTWClassifier, NNClassifier, SVMClassifier,
            T.TerrainSVMFeatures, T.SegmentFeatures, T.DirectionFeatures, T.LengthFeatures,
            H.HeuristicTerrainClassifier, H.HeuristicDirectionClassifier, H.HeuristicLengthClassifier,
            H.HeuristicFusionClassifier)


def _check_exportable(est, stem: str) -> None:
    """Decision E79: refuse, in one line, what the runtime would run as something else: a subclass of an
    exportable class (its overrides never reach the bundle, which holds the base class's formula) and a pipeline
    that is not (feature transformer or signal selection, classifier): the bundle keeps exactly two steps."""
    from sklearn.pipeline import Pipeline

    from pdrlearn.classify.dtw import DTWClassifier
    from pdrlearn.classify.training import select_signals

    known = _exportable_types()
    parts = [est] + ([s for _, s in est.steps] if isinstance(est, Pipeline) else [])
    for obj in parts:
        base = next((k for k in known if isinstance(obj, k)), None)
        if base is not None and type(obj) not in known:
            raise ModelError(
                f"{stem}: {type(obj).__name__} is a subclass of {base.__name__}; a bundle would run "
                f"{base.__name__}'s own formula, not the subclass's overrides. Use it in Python (pdrlearn track "
                f"--model), or export a model of {base.__name__} itself (decision E79)")
    if isinstance(est, Pipeline):
        names = [n for n, _ in est.steps]
        first, clf = est.steps[0][1], est.steps[-1][1]
        selects = getattr(first, "func", None) is select_signals
        if len(est.steps) != 2 or (type(clf) is DTWClassifier) != selects:
            raise ModelError(
                f"{stem}: a Pipeline of {len(names)} steps ({', '.join(names)}) cannot be exported: a bundle runs "
                "(feature transformer, classifier) or, for DTW, (select_signals, DTWClassifier) pipelines only. "
                "Fold the extra step into the classifier, or use the model in Python (pdrlearn track --model) "
                "(decision E79)")


class _Collector:
    """Accumulates the ONNX / NPZ files of a bundle while entries are built."""

    def __init__(self):
        self.onnx: dict = {}
        self.npz: dict = {}
        self.json: dict = {}

    def entry(self, est, stem: str) -> dict:
        from pdrlearn.classify.fusion import UnitFusionClassifier

        _check_exportable(est, stem)  # decision E79
        if type(est) is UnitFusionClassifier:
            members = {u: self.entry(e, f"{stem}_{u}") for u, e in zip(est.unit_names_, est.estimators_, strict=True)}
            return {
                "type": "fusion",
                "weights": [float(w) for w in est.weights_],
                "members": members,
                "classes": [str(c) for c in est.classes_],
            }
        out = self._leaf(est, stem)
        rng = getattr(est, "training_range_", None)  # decision C16's range of the leaf's own inputs
        if rng is not None:  # decision E105: the runtime's out-of-domain check (C61's line from `pdrlearn run`)
            out["training_range"] = rng.to_dict()
        return out

    def _leaf(self, est, stem: str) -> dict:
        """The entry of a leaf model (rule table, DTW pipeline, SVM / NN pipeline) without its training range."""
        from sklearn.pipeline import Pipeline

        from pdrlearn.classify.dtw import DTWClassifier
        from pdrlearn.classify.nn import NNClassifier
        from pdrlearn.classify.svm import SVMClassifier

        if hasattr(est, "stages_") and hasattr(est, "feature_names_"):  # heuristic rule tables
            rel = f"params/{stem}.json"
            self.json[rel] = {
                "estimator": type(est).__name__,
                "feature_names": list(est.feature_names_),
                "stages": [
                    {
                        "rules": [r.to_dict() for r in st.rules],
                        "labels": [[float(v), str(lab)] for v, lab in st.labels.items()],
                        "parent": st.parent,
                    }
                    for st in est.stages_
                ],
            }
            return {"type": "heuristic", "file": rel, "classes": [str(c) for c in est.classes_]}
        if type(est) is not Pipeline:
            raise ModelError(f"{stem}: {type(est).__name__} cannot be exported yet (see docs/decisions/export.md)")
        first, clf = est.steps[0][1], est.steps[-1][1]
        classes = [str(c) for c in clf.classes_]
        if type(clf) is DTWClassifier:
            rel = f"params/{stem}.npz"
            self.npz[rel] = {
                "references": clf.references_,
                "reference_labels": clf.reference_labels_.astype(np.int64),
                "channel_mean": clf.channel_mean_,
                "channel_std": clf.channel_std_,
            }
            return {
                "type": "dtw",
                "file": rel,
                "signals": list(first.kw_args["names"]),
                "window": clf.window_samples_,
                "temperature": float(clf.temperature_),
                "classes": classes,
                "n_references": int(len(clf.references_)),
                # decision C70: subtracted from the class mean distances (written only when a rule sets it)
                **({"class_offset": [float(v) for v in clf._offset()]} if np.any(clf._offset()) else {}),
            }
        recipe = feature_recipe(first)
        n_features = int(clf.n_features_in_)
        rel = f"models/{stem}.onnx"
        if type(clf) is SVMClassifier:
            # exact float64 graph of SVMClassifier's own decision formula (decision E4)
            model, spec = svm_decision_to_onnx(clf.mean_, clf.scale_, clf.decision_params_, classes, name=stem)
        elif type(clf) is NNClassifier:
            model, spec = torch_to_onnx(_nn_module(clf), n_features, classes=classes, name=stem, dtype="float64")
            # float32 twin for OpenCV's dnn module (the documented fallback without onnxruntime)
            self.onnx[f"models/{stem}.f32.onnx"] = torch_to_onnx(
                _nn_module(clf), n_features, classes=classes, name=stem, dtype="float32"
            )[0]
            spec["fallback_file"] = f"models/{stem}.f32.onnx"
        else:
            raise ModelError(f"{stem}: classifier {type(clf).__name__} cannot be exported yet")
        self.onnx[rel] = model
        return {"type": "onnx", "file": rel, "features": recipe, **spec}


def _nn_module(clf):
    """A torch module equal to ``NNClassifier._logits``: standardize, tanh hidden layer, linear output."""
    import torch

    class MLP(torch.nn.Module):
        def __init__(self):
            super().__init__()
            f32 = torch.float64
            self.register_buffer("mean", torch.tensor(clf.mean_, dtype=f32))
            self.register_buffer("scale", torch.tensor(clf.scale_, dtype=f32))
            self.hidden = torch.nn.Linear(*clf.coefs_[0].shape)
            self.out = torch.nn.Linear(*clf.coefs_[1].shape)
            with torch.no_grad():
                self.hidden.weight.copy_(torch.tensor(clf.coefs_[0].T, dtype=f32))
                self.hidden.bias.copy_(torch.tensor(clf.intercepts_[0], dtype=f32))
                self.out.weight.copy_(torch.tensor(clf.coefs_[1].T, dtype=f32))
                self.out.bias.copy_(torch.tensor(clf.intercepts_[1], dtype=f32))

        def forward(self, x):
            return self.out(torch.tanh(self.hidden((x - self.mean) / self.scale)))

    return MLP().eval()


def _builtin_of(tm, known) -> str:
    """The built-in methods a task model holds, for an error line (decision E86)."""
    return ",".join(m for m in tm.models if m in known) or "nn"


def _foot_models(tm, chosen, methods, allowed=lambda p: True) -> list:
    """Decision E26: the foot models of a task's bundle entry in the order the foot-only fallback takes them: the
    chosen one when it reads the foot only, then the others by rank (of ``methods`` when given, of those
    ``allowed``)."""
    return [p for p in dict.fromkeys(([chosen] if chosen else []) + tm.ranking())
            if p[1] == "foot" and (not methods or p[0] in methods) and allowed(p)]


def _foot_only(tm, chosen, methods, allowed=lambda p: True):
    """Decision E26: the first of :func:`_foot_models`; None when there is none."""
    return next(iter(_foot_models(tm, chosen, methods, allowed)), None)


def _warn_dropped(dropped: list[str], methods) -> None:
    """Decision E68 amended (review): one warning per requested method that ``--no-training-samples`` left out
    (with ``--methods``), else one for the task models the default export would have held."""
    by = {m: [d for d in dropped if d.split()[1].split("/")[0] == m] for m in (methods or [])}
    groups = ([(f"--methods {m}", ds) for m, ds in by.items()] if methods else
              [("the chosen or foot-only models", dropped)])
    for what, ds in groups:
        if ds:
            log.warning("export --no-training-samples: %s left out (%s: they embed training samples; manifest "
                        "export.dropped lists them)", what, ", ".join(ds))


def embeds_training_samples(est) -> bool:
    """Decision E68: whether a fitted model carries the user's training samples into a bundle: a DTW classifier
    (its references are the standardised training step windows, reversible with the stored mean and sd) or an
    SVM (its support vectors are scaled training feature vectors), also as a member of a soft vote (the
    ``fused`` unit, the ``ensemble`` method). Networks and rule tables hold fitted weights and thresholds."""
    from pdrlearn.classify.dtw import DTWClassifier
    from pdrlearn.classify.fusion import UnitFusionClassifier
    from pdrlearn.classify.svm import SVMClassifier

    if isinstance(est, UnitFusionClassifier):
        return any(embeds_training_samples(e) for e in est.estimators_)
    last = est.steps[-1][1] if getattr(est, "steps", None) else est  # a Pipeline's classifier
    return isinstance(last, (DTWClassifier, SVMClassifier))


def _units_of(entry: dict, unit: str) -> set[str]:
    """Body units (foot / waist) an entry of ``unit`` reads (:func:`pdrlearn.runtime.classify.entry_units`)."""
    from pdrlearn.runtime.classify import entry_units

    return entry_units(entry, unit)


def export_model(
    model_dir: str | Path,
    out_dir: str | Path,
    *,
    methods: Sequence[str] | None = None,
    frames: dict | None = None,
    displacement: dict | None = None,
    length_bounds=None,
    overwrite: bool = False,
    model=None,
    training_samples: bool = True,
    float32: bool = False,
    units: str | None = None,
) -> Path:
    """Write the runtime bundle of a trained model directory.

    Parameters
    ----------
    model_dir : folder written by ``pdrlearn train`` (read with ``load_model``); or pass ``model``.
    out_dir : bundle folder to create (atomically).
    methods : methods to export for every task (all their units; the bundle's ``chosen`` is the model's
        chosen one when exported, else the best-ranked exported one, in any order given: decision E183);
        default: each task's chosen method/unit only (the smallest bundle that classifies like
        ``UserModel.predict_steps``), and, when
        that reads the waist, the foot model ``predict_steps`` uses on a session without the waist unit
        (``tasks[task]["foot_only"]``, decision E26; with ``methods``: the best-ranked of those methods; it
        classifies on the per-model path: a step graph of it saved no instructions).
    frames : placement -> ``{"x": ..., "y": ..., "z": ...}`` axis frames of the data the bundle will
        see (default: the thesis frames).
    displacement : displacement parameters (default:
        :data:`pdrlearn.runtime.tracker.DEFAULT_DISPLACEMENT`).
    length_bounds : per-user stride-length class bounds (m): ``{"short": [lo, hi], ...}`` or two edges
        ``[short/normal, normal/long]``; default: the model's ``length_bounds_m`` (settings or training
        summary, as ``pdrlearn track`` reads them); a model without them gets none (``length_bounds_m`` None,
        ``length_bounds_source`` "none", one warning; decision L59: the runtime then skips the length rule, as
        ``pdrlearn track --model``; the thesis step bounds x 2 clamp typical strides, L50).
    training_samples : False (``pdrlearn export --no-training-samples``, decision E68) leaves out every model
        that embeds training samples (:func:`embeds_training_samples`: DTW, SVM, soft votes with either): a
        task whose chosen model does is given the model training would have chosen without them (the best
        ranked two-unit one, else the best ranked), its foot-only fallback likewise; a task left without
        any model is a :class:`ModelError`.
    float32 : every ONNX graph (step graph, SVMs, networks) computes in float32 and the networks' ``.f32`` twins
        are left out (``pdrlearn export --float32``, decision E217: single-precision targets); the parity check
        before writing allows :data:`pdrlearn.export.precision.FLOAT32_PARITY_ATOL`.
    units : ``"foot"`` (``pdrlearn export --units``, decision E218; E233: ``"waist"`` is refused): only the models
        that read that unit alone (not the soft votes or combined models, which read both); each task's chosen model
        is the best ranked of those (as ``--no-training-samples`` chooses); a task without one is a
        :class:`ModelError`.
    """
    from pdrlearn.classify.model_dir import load_model, read_manifest
    from pdrlearn.classify.training import BUILTIN_METHODS, METHODS, best_pair
    from pdrlearn.features import CHANNELS
    from pdrlearn.features.transformers import SIGNALS

    known = BUILTIN_METHODS  # issue 5 methods + opt-in C14
    plug = [m for m in methods or [] if m not in known and m in METHODS]
    if plug:  # decision E86: the runtime has a recipe for the built-in estimators only
        raise ModelError(f"--methods {', '.join(plug)}: a plug-in classifier method (pdrlearn.methods), which the "
                         f"runtime bundle cannot carry; export built-in methods ({', '.join(known)})")
    bad = [m for m in methods or [] if m not in known]
    if bad:
        raise ModelError(f"unknown method(s) {', '.join(bad)}; choose from {', '.join(known)}")
    if units == "waist":  # decision E233: nothing could run the bundle
        from pdrlearn.runtime.bundle import waist_only_hint

        raise ModelError(f"--units waist: a classifier bundle needs the foot unit, whose gyroscope the runtime detects "
                         f"steps on (decision E7), so a waist-only one could not be run; {waist_only_hint()} "
                         "(decisions E57, E233)")
    if units is not None and units not in EXPORT_UNITS:
        raise ModelError(f"--units {units!r}: choose {' or '.join(EXPORT_UNITS)} (a single-unit bundle, decisions "
                         "E218, E233)")
    if model is None:
        model = load_model(model_dir)
        src_manifest = read_manifest(model_dir)
    else:
        src_manifest = {}
    if not model.tasks:  # decision C17: trained on level walks only, the model holds a distance calibration
        raise ModelError(f"{model_dir}: the model has no trained classifier (training skipped every task), only "
                         "its distance calibration, which `pdrlearn track --model` applies; a runtime bundle needs "
                         "a classifier: retrain with terrain, direction or length labels")
    col = _Collector()
    tasks: dict = {}
    used_units: set[str] = set()
    skipped: list[str] = []
    dropped: list[str] = []  # decision E68: models left out by --no-training-samples
    for task, tm in model.tasks.items():
        chosen = tm.chosen

        def keeps(p, tm=tm) -> bool:  # decision E68: --no-training-samples
            return training_samples or not embeds_training_samples(tm.models[p[0]][p[1]])

        def allowed(p, keeps=keeps) -> bool:  # decision E218: --units keeps the models of that unit alone
            return keeps(p) and (units is None or p[1] == units)

        if not training_samples or units:
            ok = [p for p in tm.ranking() if allowed(p) and (not methods or p[0] in methods)]
            if not ok and units and not [p for p in tm.ranking() if p[1] == units and (not methods or p[0] in methods)]:
                have = ", ".join(f"{m}/{u}" for m, u in tm.ranking() if not methods or m in methods)
                raise ModelError(f"{model_dir}: --units {units} leaves task {task} without a model (it has {have}); "
                                 f"train the model with the {units} unit (pdrlearn train --units {units}), or "
                                 "export without --units (decision E218)")
            if not ok:
                left = [f"{m}/{u}" for m, per in tm.models.items() for u in per if not methods or m in methods]
                raise ModelError(f"{model_dir}: --no-training-samples leaves task {task} without a model (its "
                                 f"{', '.join(left) or 'requested'} models embed training samples: DTW references "
                                 "or SVM support vectors); export without --no-training-samples, or train nn or "
                                 "heuristic models (pdrlearn train --methods nn,heuristic,fusion)")
            chosen = chosen if chosen in ok else best_pair(ok, tm.one_unit_votes())  # as training (C8, C23, C124)
        if methods:
            wanted = [(m, u) for m in methods for u in tm.models.get(m, {}) if allowed((m, u))]
        else:
            wanted = [chosen] if chosen else []
            if chosen and chosen[0] in METHODS and chosen[0] not in known:  # decision E86
                raise ModelError(f"{model_dir}: task {task}'s chosen model {chosen[0]}/{chosen[1]} is a plug-in "
                                 "classifier method, which the runtime bundle cannot carry; export built-in "
                                 f"methods with --methods (e.g. --methods {_builtin_of(tm, known)})")
        # decision E26: the model `pdrlearn track` (UserModel.predict_steps) classifies a session without the
        # waist unit with: the chosen one when it reads the foot only, else the best-ranked foot model (of the
        # methods asked for, as the chosen one)
        foot_models = _foot_models(tm, chosen, methods, allowed)
        foot_only = next(iter(foot_models), None)
        if not training_samples:  # E68 amended (review): what the request would have exported without the option
            asked = ([(m, u) for m in methods for u in tm.models.get(m, {})] if methods else
                     [p for p in (tm.chosen, _foot_only(tm, tm.chosen, methods)) if p])
            dropped += [f"{task} {m}/{u}" for m, u in dict.fromkeys(asked) if not keeps((m, u))]
        if foot_only is not None and foot_only not in wanted:
            wanted = [*wanted, foot_only]
        entries: dict = {}
        converted: dict = {}  # decision E207: each model of the task converted once, its entry or None (skipped)

        def convert(p, task=task, tm=tm, converted=converted):
            if p not in converted:
                try:
                    converted[p] = col.entry(tm.models[p[0]][p[1]], f"{task}_{p[0]}_{p[1]}")
                except ModelError as exc:
                    skipped.append(f"{task} {p[0]}/{p[1]}: {exc}")
                    log.warning("skipped %s %s/%s: %s", task, p[0], p[1], exc)
                    converted[p] = None
            return converted[p]

        for m, u in wanted:
            if (e := convert((m, u))) is not None:
                entries.setdefault(m, {})[u] = e
        # decision E201: a foot model the bundle cannot carry (a plug-in) gives way to the next exportable one
        for p in foot_models[1:] if foot_only is not None and "foot" not in entries.get(foot_only[0], {}) else ():
            if (e := convert(p)) is None:
                continue
            log.warning("export: task %s's foot-only fallback is %s/foot (%s/foot skipped: the bundle cannot carry "
                        "it)", task, p[0], foot_only[0])
            entries.setdefault(p[0], {})[p[1]] = e
            foot_only = p
            break
        if not entries:
            skipped.append(f"{task}: nothing exportable")
            continue
        if not (chosen and chosen[1] in entries.get(chosen[0], {})):
            # decision E183: the chosen model left out, the best-ranked exported one as training chooses
            # (decisions C8, C23, E26), whatever order --methods lists them in
            chosen = best_pair([p for p in tm.ranking() if p[1] in entries.get(p[0], {})], tm.one_unit_votes()) or next(
                (m, u) for m, per in entries.items() for u in per)
        exp_chosen = {"method": chosen[0], "unit": chosen[1]}
        for per in entries.values():
            for u, e in per.items():
                used_units |= _units_of(e, u)
        tasks[task] = {
            "classes": list(tm.classes),
            "chosen": exp_chosen,
            "methods": entries,
            # decision E287: C161's side / turn strides in the training data, for run's C137 line (as track's)
            **({"trained_kinds": dict(tm.trained_kinds)} if getattr(tm, "trained_kinds", None) else {}),
            # decision E26: what a foot-only replay (`pdrlearn run --units foot`) classifies with, as track
            **({"foot_only": {"method": foot_only[0], "unit": "foot"}}
               if foot_only is not None and foot_only[1] in entries.get(foot_only[0], {}) else {}),
            "cv": {
                m: {
                    u: {k: v for k, v in met.items() if k in ("accuracy", "balanced_accuracy", "per_class", "n_steps")}
                    for u, met in per.items()
                }
                for m, per in tm.cv.items()
            },
        }
    if not tasks:
        raise ModelError(f"{model_dir}: no task could be exported ({'; '.join(skipped)})")
    _warn_dropped(dropped, methods)
    rates = {k: float(v) for k, v in (model.sampling_rate_hz or {}).items()}
    core = [s for u in sorted(used_units) for s in UNIT_SENSORS[u]]
    rate = float(np.median([rates[s] for s in core if s in rates])) if any(s in rates for s in core) else 20.0
    features = {
        "n_samples": int(model.n_samples),
        "heading": "pca",
        "rest_search_s": 0.3,
        # where windows are cut: "given" = at the segmenter's stance boundaries, "rest" = each boundary
        # moved to the middle of the foot's rest (kernels.window.rest_boundaries; decisions 13 / C13)
        "boundaries": model.boundaries,
        "channels": list(CHANNELS),
        "signals": {k: [list(v[0]), float(v[1])] for k, v in SIGNALS.items()},
    }
    step = build_step_graph(tasks, col.onnx, features)  # one session run per step (decision E10)
    manifest = base_manifest(
        user=model.user,
        tasks=tasks,
        sampling={"rate_hz": rate, "rate_tolerance": 0.05, "source_rates_hz": rates},
        sensors={"required": core, "optional": [s for s in OPTIONAL_SENSORS if s in rates]},
        units={
            "fAccelerometer": "m/s^2",
            "fGyroscope": "rad/s",
            "fForceA": "N",
            "fForceB": "N",
            "wAccelerometer": "m/s^2",
            "wGyroscope": "rad/s",
            "wMagneticField": "uT",
            "wBarometer": "hPa",
            "time": "s",
        },
        frames=frames or {u: DEFAULT_FRAMES[u] for u in sorted(used_units)},
        features=features,
        displacement=_displacement(displacement, length_bounds, model,
                                   f"model {model_dir}" if model_dir else "the model"),
        training={
            "data": model.data_summary,
            "settings": model.settings,
            "model_created": model.created,
            # decision E67: the folder's name only; the path as typed could name the user's home and host
            "source_model_dir": Path(model_dir).resolve().name if model_dir else None,
            "source_package_version": src_manifest.get("package_version"),
        },
        metrics={t: v["cv"] for t, v in tasks.items()},
        export={"methods": list(methods) if methods else "chosen", "skipped": skipped,
                "training_samples": bool(training_samples), "dropped": dropped,  # decision E68
                **({"units": units} if units else {})},  # decision E218
    )
    if step is not None:
        col.onnx[STEP_GRAPH_FILE] = step[0]
        manifest["step_graph"] = {"file": STEP_GRAPH_FILE, **step[1]}
    atol = PARITY_ATOL
    if float32:  # decision E217
        onnx64, col.onnx = col.onnx, bundle_to_float32(col.onnx, manifest)
        check_float32_ranges(onnx64, col.onnx, manifest)  # decision E221: before anything is written
        atol = FLOAT32_PARITY_ATOL
    # decision E219: each graph's flash, parameters and multiply-accumulates per step, for a port's budget
    manifest["export"]["model_sizes"] = {rel: onnx_stats(m) for rel, m in sorted(col.onnx.items())}
    models = {t: tm.models for t, tm in model.tasks.items()}
    W = parity_windows(int(model.n_samples), model.boundaries or "given")

    def verified(path, verify=True):  # decision E80: the bundle reproduces predict_proba before it is renamed
        from pdrlearn.runtime import load_bundle

        bundle = load_bundle(path, verify=verify)
        check_bundle_parity(bundle, models, W, atol=atol)
        return bundle

    return write_bundle(out_dir, manifest, onnx_models=col.onnx, npz_files=col.npz, json_files=col.json,
                        overwrite=overwrite, loader=verified)


def _displacement(displacement: dict | None, length_bounds, model, where: str = "the model") -> dict:
    """Displacement parameters with the length-class bounds resolved (see :func:`export_model`); ``where``
    names the model in the warning of a model without bounds (decision L59)."""
    from pdrlearn.displace.calibration import PRE_L41_CALIBRATION, predates_streaming_calibration
    from pdrlearn.displace.rules import model_length_bounds, parse_bounds
    from pdrlearn.kernels.stride import NO_BOUNDS_SOURCE, STANCE_L27_DEFAULTS, no_length_bounds_warning
    from pdrlearn.runtime.tracker import DEFAULT_DISPLACEMENT

    out = {**STANCE_L27_DEFAULTS, **DEFAULT_DISPLACEMENT}  # decision L27: the stance rule's settings
    out.update(_calibration_fields(model))
    explicit = dict(displacement or {})
    rec = (getattr(model, "data_summary", None) or {}).get("distance_calibration")
    if predates_streaming_calibration(rec) and not {"rules", "min_confidence"} & explicit.keys():
        out.update(rules="thesis", min_confidence=0.0)  # decision L41, as pdrlearn track --streaming
        log.warning("%s", PRE_L41_CALIBRATION)
    if {"distance_gain", "stride_sigma_rel"} & explicit.keys() and not any(k.startswith("streaming_")
                                                                          for k in explicit):
        # decision L41: an explicit calibration overrides the model's for the runtime too (which would
        # otherwise take the model's streamed fields first)
        for k in STREAMING_CALIBRATION_FIELDS:
            out.pop(k, None)
    out.update(explicit)
    if length_bounds is None:
        length_bounds = explicit.get("length_bounds_m")
    if length_bounds is None:
        length_bounds = model_length_bounds(model)  # as pdrlearn track reads them
    if length_bounds is None:
        # decision L59: no bounds measured for this user -> the bundle records none (its runtime skips the length
        # rule, as pdrlearn track does), not the thesis fallback as if it were the user's (L50: -27 % on scenario A)
        out["length_bounds_m"] = None
        out["length_bounds_source"] = NO_BOUNDS_SOURCE
        if "length" in (getattr(model, "tasks", None) or {}):
            log.warning("%s", no_length_bounds_warning(
                where, 'the bundle records none (displacement.length_bounds_source "none") and '
                "`pdrlearn run` skips the length rule, as `pdrlearn track --model` does"))
        return out
    if isinstance(length_bounds, dict):
        bounds = {str(k): [float(v[0]), float(v[1])] for k, v in length_bounds.items()}
    else:
        e = [float(v) for v in length_bounds]
        if len(e) != 2 or not 0 < e[0] < e[1]:
            raise ModelError(f"length bounds {length_bounds!r}: give two increasing stride lengths in metres")
        bounds = e
    # decision E25: the bounds `pdrlearn track` uses (parse_bounds: an open "long" class ends at 10 m). The bayes
    # rule's prior is uniform over each class, so the bound of the open class weighs it (an earlier export's
    # 20 m halved the "long" density against the track's 10 m: 1 cm on a 1.55 m stride); the thesis clamp
    # never reaches either
    out["length_bounds_m"] = {k: [lo, hi] for k, (lo, hi) in parse_bounds(bounds).items()}
    out["length_bounds_source"] = "user"
    return out


#: the bundle's fields of the streamed stride kernel's calibration (decision L41)
STREAMING_CALIBRATION_FIELDS = ("streaming_distance_gain", "streaming_stride_sigma_rel",
                                "streaming_distance_calibration_reason")


def _calibration_fields(model) -> dict:
    """The user's distance calibration (decision L26) as bundle displacement parameters (decision E14):
    ``distance_gain`` (factor on the level strides' horizontal displacement), ``distance_gain_rate_hz``
    (foot rate it applies at, +-1 %) and ``stride_sigma_rel`` (relative sd of one stride's length; None
    when the calibration was refused). Empty for a model without a calibration record. A model calibrated
    since decision L41 also gives ``streaming_distance_gain`` / ``streaming_stride_sigma_rel`` /
    ``streaming_distance_calibration_reason``: the same estimate made with the streamed stride kernel, which
    the runtime applies (the offline fields stay for the record and for older runtimes)."""
    rec = (getattr(model, "data_summary", None) or {}).get("distance_calibration")
    if not isinstance(rec, dict):
        return {}
    ok = rec.get("reason") is None
    out = {
        "distance_gain": float(rec.get("gain", 1.0)),
        "distance_gain_rate_hz": None if rec.get("rate_hz") is None else float(rec["rate_hz"]),
        "stride_sigma_rel": float(rec["stride_sd"]) if ok and rec.get("stride_sd") else None,
        "distance_calibration_reason": rec.get("reason"),
    }
    sub = rec.get("streaming")
    if isinstance(sub, dict):  # decision L41: the streamed stride kernel's own gain, which the runtime applies
        ok = sub.get("reason") is None
        out.update({
            "streaming_distance_gain": float(sub.get("gain", 1.0)),
            "streaming_stride_sigma_rel": float(sub["stride_sd"]) if ok and sub.get("stride_sd") else None,
            "streaming_distance_calibration_reason": sub.get("reason"),
        })
    return out
