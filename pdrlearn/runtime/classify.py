"""Step classifiers of a bundle: ONNX models on feature recipes, DTW references, unit fusion.

A task's manifest entry names its ``classes`` (the output order), the ``chosen`` ``{method, unit}`` and
``methods[method][unit]`` model entries:

* ``{"type": "onnx", "file", "features": recipe, "outputs": {"proba": ...}, "classes", ...}``
* ``{"type": "dtw", "file": npz, "signals": [...], "window", "temperature", "classes"}`` (+ ``"class_offset"``, C70)
* ``{"type": "fusion", "weights": [...], "members": {unit: entry}, "classes"}``

Class = argmax of the probabilities aligned to the task's classes, as on the training side
(:meth:`pdrlearn.classify.training.UserModel.predict_steps`).
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import DataError, ModelError
from pdrlearn.kernels.dtw import dtw_to_refs
from pdrlearn.kernels.proba import align_proba as align
from pdrlearn.kernels.proba import soft_vote, softmax
from pdrlearn.kernels.window import GROUP_STREAMS, GROUPS
from pdrlearn.runtime.bundle import Bundle, OnnxModel, SharedByCopies
from pdrlearn.runtime.features import compute_features, recipe_channels

#: the keys of a heuristic model's JSON file in a bundle (``export`` writes them; decision B125 checks them)
HEURISTIC_KEYS = ("feature_names", "stages")


class RuntimeModel:
    """One model entry of a bundle; :meth:`proba` maps windows ``(n, channels, samples)`` to
    probabilities ``(n, len(classes))`` in the entry's class order."""

    def __init__(self, bundle: Bundle, entry: dict, feature_ctx: dict, *, lazy: bool = False):
        self.entry = entry
        self.type = entry.get("type")
        self.classes = list(entry["classes"])
        self.ctx = feature_ctx
        self.bundle = bundle
        self._model = None
        if self.type == "onnx":
            if not lazy:
                self.open()
        elif self.type == "dtw":
            z = bundle.npz(entry["file"], keys=("references", "reference_labels", "channel_mean", "channel_std"))
            self.refs = np.ascontiguousarray(z["references"])
            self.ref_labels = z["reference_labels"].astype(int)
            self.mean, self.std = z["channel_mean"], z["channel_std"]
            self.window = None if entry.get("window") is None else int(entry["window"])
            self.temperature = float(entry["temperature"])
            self.offset = np.asarray(entry.get("class_offset", 0.0), dtype=float)  # decision C70 (absent: 0)
        elif self.type == "heuristic":
            spec = bundle.json(entry["file"], keys=HEURISTIC_KEYS)
            self.recipe = [["rule", n] for n in spec["feature_names"]]
            self.col = {n: i for i, n in enumerate(spec["feature_names"])}
            self.stages = spec["stages"]
        elif self.type == "fusion":
            self.members = [RuntimeModel(bundle, e, feature_ctx, lazy=lazy) for e in entry["members"].values()]
            self.weights = np.asarray(entry["weights"], dtype=float)
        else:
            raise ModelError(f"bundle {bundle.path}: unknown model type {self.type!r}; re-export it")

    def open(self) -> None:
        """Open the ONNX session(s) now (they are opened on first use when created with ``lazy=True``)."""
        if self.type == "onnx" and self._model is None:
            self._model = self.bundle.model(self.entry["file"], self.entry)
        for m in getattr(self, "members", []):
            m.open()

    @property
    def model(self):
        self.open()
        return self._model

    def proba(self, W: np.ndarray, cache: dict | None = None) -> np.ndarray:
        if self.type == "onnx":
            F = compute_features(W, self.entry["features"], cache=cache, **self.ctx)
            out = self.model.run(F)
            if "proba" in out:
                return np.asarray(out["proba"], dtype=np.float64)
            return softmax(np.asarray(out["logits"], dtype=np.float64))
        if self.type == "dtw":
            S = compute_features(W, [["signals", self.entry["signals"]]], cache=cache, **self.ctx)
            S = (np.transpose(S, (0, 2, 1)) - self.mean) / self.std  # (n, samples, channels)
            n_cls = len(self.classes)
            out = np.empty((len(S), n_cls))
            for i, q in enumerate(S):
                d = dtw_to_refs(q, self.refs, self.window)
                out[i] = [d[self.ref_labels == k].mean() for k in range(n_cls)]
            return softmax(-(out - self.offset) / self.temperature)
        if self.type == "heuristic":
            return heuristic_proba(self, W, cache)
        probas = [align(m.proba(W, cache), m.classes, self.classes) for m in self.members]
        return soft_vote(probas, self.weights)


#: the body units of the bundles' models (thesis ch.4); a model of unit "fused" (soft vote, decision C7) or
#: "combined" (one model on both units' features, decision C22) reads both
BODY_UNITS = ("foot", "waist")
TWO_UNIT = ("fused", "combined")


def entry_units(entry: dict, unit: str) -> set[str]:
    """Body units (foot / waist) a model entry of ``unit`` reads. Fusion members are units (foot/waist of a
    fused model) or methods (an ``ensemble``'s nn/svm/dtw, decision C14): those read their parent's unit."""
    if entry["type"] == "fusion":
        return set().union(*(entry_units(e, u if u in BODY_UNITS else unit) for u, e in entry["members"].items()))
    return set(BODY_UNITS) if unit in TWO_UNIT else {unit}


def entry_sensors(bundle: Bundle, entry: dict, signals: dict) -> set[str]:
    """The sensor streams (``fForceA``, ...) whose window channels a model entry reads (decision E26 amended:
    a replay whose data lack one leaves the task to another model, or unclassified)."""
    if entry["type"] == "fusion":
        return set().union(*(entry_sensors(bundle, e, signals) for e in entry["members"].values()))
    if entry["type"] == "dtw":
        recipe = [["signals", entry["signals"]]]
    elif entry["type"] == "heuristic":
        recipe = [["rule", n] for n in bundle.json(entry["file"], keys=HEURISTIC_KEYS)["feature_names"]]
    else:
        recipe = entry["features"]
    chans = set(recipe_channels(recipe, signals))
    return {s for g, cs in GROUPS.items() if chans & set(cs) for s in GROUP_STREAMS[g]}


#: the training side's tie-break between methods of equal score (``pdrlearn.classify.training.PREFERENCE``;
#: the runtime does not import the training side), then between units (``...training.UNIT_PREFERENCE``, C23)
_PREFERENCE = ("nn", "svm", "fusion", "dtw", "heuristic", "ensemble")
_UNIT_PREFERENCE = ("foot", "waist", "combined", "fused")


def _no_unit_fix(units) -> str:
    """Decision E201: what to do when a bundle has no model that reads only the data's unit(s): the model may
    have one the export left out (a plug-in's is skipped, export's ``skipped`` lists it), so re-export with a
    built-in method first; train only when the model has none."""
    u = "+".join(units)
    return (f"re-export with a built-in method that has a {u} model (pdrlearn export MODEL --methods svm; the "
            f"bundle's manifest export.skipped lists what was left out), or train the model with the {u} unit")


def _ranked(spec: dict) -> list[tuple[str, str]]:
    """The task's exported (method, unit) pairs, the chosen one first, then by cross-validated score (as
    :meth:`pdrlearn.classify.training.TaskModel.ranking`: balanced accuracy, accuracy, method; unscored last)."""
    cv = spec.get("cv") or {}
    exported = [(m, u) for m, per in spec["methods"].items() for u in per]
    pairs = list(dict.fromkeys([(m, u) for m, per in cv.items() for u in per if (m, u) in exported] + exported))

    def key(p):
        s = (cv.get(p[0]) or {}).get(p[1]) or {}
        pref = _PREFERENCE.index(p[0]) if p[0] in _PREFERENCE else len(_PREFERENCE)
        upref = _UNIT_PREFERENCE.index(p[1]) if p[1] in _UNIT_PREFERENCE else len(_UNIT_PREFERENCE)
        return (-(s.get("balanced_accuracy") or -1.0), -(s.get("accuracy") or -1.0), pref, upref)

    chosen = spec.get("chosen") or {}
    first = [(chosen.get("method"), chosen.get("unit"))]
    return list(dict.fromkeys([p for p in first if p in pairs] + sorted(pairs, key=key)))


class TaskClassifier:
    """The bundle's classifier of one task (its chosen method/unit unless another is asked for).

    ``units`` (decision E26): the body units the data has (default: all the bundle's). When the chosen model
    reads another unit, the task classifies with the model ``pdrlearn track`` picks for such a session: the
    bundle's ``foot_only`` record (written by ``pdrlearn export`` since E26; not in the step graph, which
    holds the chosen models: the per-model path); a bundle exported before has none, and a fused model's
    member of those units stands in (``note`` says so)."""

    def __init__(
        self,
        bundle: Bundle,
        task: str,
        feature_ctx: dict,
        *,
        method: str | None = None,
        unit: str | None = None,
        lazy: bool = False,
        units: tuple[str, ...] | None = None,
        sensors=None,
    ):
        spec = bundle.tasks[task]
        self.task = task
        self.classes = list(spec["classes"])
        self.class_array = np.asarray(self.classes, dtype=object)
        #: why this task does not classify with the model track would pick (an old bundle), else None
        self.note: str | None = None
        chosen = spec.get("chosen") or {}
        methods = spec["methods"]
        asked = method is not None or unit is not None
        method = method or chosen.get("method")
        unit = unit or chosen.get("unit")
        if method not in methods or unit not in methods[method]:
            have = ", ".join(f"{m}/{u}" for m, per in methods.items() for u in per)
            raise ModelError(
                f"bundle {bundle.path}: task {task} has no {method}/{unit} model "
                f"(it has {have}); export it with --methods"
            )
        entry = methods[method][unit]
        if units is not None and not entry_units(entry, unit) <= set(units):
            fo = spec.get("foot_only") if tuple(units) == ("foot",) and not asked else None
            members = entry.get("members", {}) if entry["type"] == "fusion" else {}
            if fo is not None and fo.get("unit") in methods.get(fo.get("method"), {}):
                method, unit = fo["method"], fo["unit"]
                entry = methods[method][unit]
            elif not asked and len(units) == 1 and units[0] in members:  # a bundle exported before E26
                self.note = (f"{task} from the {units[0]} member of its {method}/{unit} model")
                unit, entry = units[0], members[units[0]]
            else:
                where = f"the {method}/{unit} model" if asked else "no model"
                raise ModelError(
                    f"bundle {bundle.path}: task {task} has {where} that reads the {'+'.join(units)} unit only "
                    f"(it has {', '.join(f'{m}/{u}' for m, per in methods.items() for u in per)}); "
                    f"{'choose another (Tracker methods=)' if asked else _no_unit_fix(units)}"
                )
        #: the sensors the data lack that this task's model reads (decision E26 amended); not empty: the task
        #: is left unclassified (``model`` is None)
        self.missing: list[str] = []
        if sensors is not None and not asked:
            have, ctx = set(sensors), feature_ctx["signals"]
            need = entry_sensors(bundle, entry, ctx)
            if not need <= have:  # another exported model the data can run, in track's order, else none
                self.missing = sorted(need - have)
                for m, u in _ranked(spec):
                    e = methods[m][u]
                    if (units is None or entry_units(e, u) <= set(units)) and entry_sensors(bundle, e, ctx) <= have:
                        method, unit, entry, self.missing, self.note = m, u, e, [], None
                        break
        self.method, self.unit = method, unit
        #: the sensor streams this task's model reads (decision B140: checked against the pushed ones)
        self.reads = entry_sensors(bundle, entry, feature_ctx["signals"])
        if self.missing:
            self.is_chosen, self.model = False, None
            return
        self.is_chosen = (method, unit) == (chosen.get("method"), chosen.get("unit")) and self.note is None
        self.model = RuntimeModel(bundle, entry, feature_ctx, lazy=lazy)

    def predict(self, W: np.ndarray, cache: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``(classes (n,), probabilities (n, n_classes))`` for windows ``W``."""
        p = align(self.model.proba(W, cache), self.model.classes, self.classes)
        return self.class_array[np.argmax(p, axis=1)], p


def heuristic_proba(self: RuntimeModel, W: np.ndarray, cache: dict | None = None) -> np.ndarray:
    """Stage scores (thesis eq. 28) -> triangular memberships -> chained stage probabilities, with the
    training side's own pure functions (``pdrlearn.classify._rules``, numpy only)."""
    from pdrlearn.classify._rules import Rule, combine_stages, memberships, stage_score

    F = compute_features(W, self.recipe, cache=cache, **self.ctx)
    stages = []
    for st in self.stages:
        rules = [Rule.from_dict(r) for r in st["rules"]]
        conf = None
        if any(r.confidence for r in rules):
            conf = np.column_stack([F[:, self.col[r.confidence]] if r.confidence else np.ones(len(F)) for r in rules])
        score = stage_score(F[:, [self.col[r.feature] for r in rules]], rules, conf)
        m = memberships(score, tuple(float(v) for v, _ in st["labels"]))
        stages.append((m, [lab for _, lab in st["labels"]], st.get("parent")))
    probs = combine_stages(stages)
    return np.column_stack([probs[c] for c in self.classes])


class StepGraph(SharedByCopies):
    """The bundle's step graph (decision E10): the step window in, every covered task's probabilities
    out, in one onnxruntime session run (features, models, class alignment and unit fusion inside).

    Built only for the tasks that classify with their chosen (exported) model; the others stay on the
    per-model path. ``StepGraph.open`` returns None when the bundle has no step graph or runs on
    OpenCV's dnn module (which lacks the graph's operators). Read-only: a tracker's deep copy shares it (E252).
    """

    def __init__(self, bundle: Bundle, spec: dict, tasks: list[str]):
        self.tasks = tasks
        self.model = OnnxModel(bundle.file(spec["file"]),
                               {"input": spec.get("input", "W"), "dtype": spec.get("dtype", "float64"),
                                "outputs": {t: spec["outputs"][t] for t in tasks}}, backend="onnxruntime")
        ci = {c: i for i, c in enumerate(bundle.manifest["features"]["channels"])}
        self.channels = np.array([ci[c] for c in spec["channels"]], dtype=np.intp)
        self.channel_names = [str(c) for c in spec["channels"]]
        m = self.model  # the session's run with its output names, for float64 C-ordered windows (E13);
        # the compiled session's own run (onnxruntime's Python wrapper only checks the input names, which are
        # fixed here, and the ownership of OrtValue inputs, which numpy windows are not; decision E15)
        sess = m._sess if m.backend == "onnxruntime" else None
        self._run = None if sess is None else getattr(sess, "_sess", sess).run
        self._wanted = getattr(m, "_wanted", [])
        by_name = {name: role for role, name in m.outputs.items()}
        self._roles = [by_name[name] for name in self._wanted]

    @classmethod
    def open(cls, bundle: Bundle, classifiers: dict[str, TaskClassifier]) -> StepGraph | None:
        spec = bundle.manifest.get("step_graph")
        if not spec or bundle.backend == "opencv":
            return None
        tasks = [t for t, c in classifiers.items() if t in spec["outputs"] and c.is_chosen]
        if not tasks:
            return None
        try:
            return cls(bundle, spec, tasks)
        except ModelError:  # no onnxruntime: the per-model path (OpenCV fallback) still works
            return None

    def predict(self, W: np.ndarray) -> dict[str, np.ndarray]:
        """Task -> probabilities ``(n, n_classes)`` (the task's class order) of windows ``W``."""
        x = W[:, self.channels]  # as compute_features: never classify NaN; the sum is finite iff every value
        if not (math.isfinite(float(np.add.reduce(x, axis=None))) or np.isfinite(x).all()):  # is (bar overflow, E17)
            missing = [c for j, c in enumerate(self.channel_names) if not np.isfinite(x[:, j]).all()]
            raise DataError(f"step features are NaN: the stream lacks a sensor the model needs (window channels "
                            f"{', '.join(missing)} are empty); push those sensors, or export a model trained "
                            "without them")
        if self._run is not None and W.dtype != self.model.dtype:  # a float32 step graph (decision E217)
            W = np.ascontiguousarray(W, dtype=self.model.dtype)
        if self._run is not None and W.dtype == self.model.dtype and W.flags.c_contiguous:
            return dict(zip(self._roles, self._run(self._wanted, {self.model.input_name: W}, None), strict=True))
        return self.model.run(W)
