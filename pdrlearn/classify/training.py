"""Per-user training of every task x method x unit, cross-validated, with the best fused method chosen.

:func:`train_user` reads labelled sessions, cuts fixed-length step windows
(:func:`pdrlearn.features.step_windows`), and for each task trains the methods (heuristic, heuristic fusion,
DTW, SVM, NN) on each unit (foot, waist) and fused across units. Every model is an estimator on the raw
window array ``(steps, channels, samples)`` (features are computed inside its pipeline), so the same object
classifies new steps. :class:`UserModel` holds the fitted models and the metrics; :meth:`UserModel.save` /
:func:`pdrlearn.classify.model_dir.load_model` write/read the model directory.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import pandas as pd
from sklearn.base import clone
from sklearn.model_selection import GroupKFold, StratifiedKFold
from sklearn.pipeline import Pipeline
from sklearn.preprocessing import FunctionTransformer

from pdrlearn.classify.domain import (
    attach_class_ranges,
    attach_joint,
    attach_ranges,
    domain_report,
    has_ranges,
    joint_fraction,
    step_joint_score,
    step_score,
    summarize,
)
from pdrlearn.classify.dtw import THESIS_REFERENCES_PER_CLASS, DTWClassifier
from pdrlearn.classify.fusion import (
    UnitFusionClassifier,
    align_proba,
    best_weights,
    fused_from_fitted,
    soft_vote,
)
from pdrlearn.classify.hyper import check_params, stored
from pdrlearn.classify.nn import NNClassifier
from pdrlearn.classify.svm import SVMClassifier
from pdrlearn.classify.users import (  # noqa: F401 (re-exported: the names callers import from here)
    _USER_KEY_PREFIXES,
    _one_user,
    bundle_own_user,
    model_user_key,
    own_user,
    session_user,
)
from pdrlearn.errors import DataError, MissingSensorError, PdrlearnError
from pdrlearn.plugins import Registry

log = logging.getLogger(__name__)

TASKS = ("terrain", "direction", "length")
#: the built-in classifier methods (the thesis' five and the opt-in ensemble, C14); :data:`METHODS` adds plug-ins
BUILTIN_METHODS = ("heuristic", "fusion", "dtw", "svm", "nn", "ensemble")
#: Methods trained when none are named: the thesis' five; ``ensemble`` (not thesis) is opt-in.
DEFAULT_METHODS = ("heuristic", "fusion", "dtw", "svm", "nn")
#: Members of the per-unit ``ensemble`` method, an equal-weight soft vote (decision C14).
ENSEMBLE_MEMBERS = ("nn", "svm", "dtw")
UNITS = ("foot", "waist", "fused", "combined")
#: Units of models that read both body units: ``fused`` = soft vote of the foot and waist models (decision C7),
#: ``combined`` = one SVM / NN on the thesis' combined feature vector (decision C22). C8 chooses among these.
TWO_UNIT = ("fused", "combined")
#: Methods with a ``combined`` model: the thesis' learned fusion rows (thesis ch. 6.1.1.1, 6.1.1.2, 6.2.1, 6.3.1).
COMBINED_METHODS = ("svm", "nn")
#: Per-unit methods; "fusion" (heuristic fusion, thesis ch. 6.1.2.3) exists only fused.
UNIT_METHODS = ("heuristic", "dtw", "svm", "nn")
#: Fewest labelled steps per class for training and CV (decision: docs/decisions/classifiers.md).
MIN_STEPS_PER_CLASS = 5
#: Decision S98 (trial T2 finding F9): what train's refusal of a length task without every class adds - a slow (or
#: fast) walker's strides fall in one class of the user's own bounds (S81) unless the bounds are the walker's
LENGTH_CLASSES_HINT = (
    "; the length classes are the session's stride-length classes (steps.csv length_class, bounds in meta.json "
    "length_class_bounds_m): a walker much slower or faster than the simulated user's own gait puts every stride in "
    "one class, so simulate the exercise with --length-bounds SHORT_NORMAL,NORMAL_LONG around the walker's own "
    "short / normal / long strides (decision S98), or relabel length_class by them; a model trained on other "
    "walkers can class a walker's strides against the session's own median with track --length-reference session "
    "(C117)")
#: decision C75: a trained task warns when a class has fewer labelled steps than this: 12 per class is the smallest
#: set the thesis calls sufficient, and that for its DTW templates (thesis ch. 6.2.2: "24 (12 forward and 12
#: backward) signals ... proved to be sufficient"); its learned models had 190-260 per class (ch. 6.2.1)
FEW_STEPS_PER_CLASS = 12
#: decision C75: the methods that need no fitted weights (rules and templates), named by the few-steps line
TEMPLATE_METHODS = ("heuristic", "fusion", "dtw")
#: decision C77 (trial 31 finding 7): a model whose every chosen classifier reads the lower back only is still used
#: by the foot pipeline alone; said once at train time
WAIST_ONLY_MODEL_LINE = (
    "every chosen classifier reads the lower-back unit only: `track --model` / `run` of its bundle use it in the "
    "foot pipeline (PLASYS), so the tracked session still needs a foot unit; the lower-back pipelines (waist-pendulum, "
    "waist-pll) take no model, so a waist-only recording is tracked without these classes and its backward steps "
    "count forward (decisions W173, C77)")
#: Tie-break order when two fused methods score alike (the thesis' best first, Tables 27, 28, 33).
PREFERENCE = ("nn", "svm", "fusion", "dtw", "heuristic", "ensemble")

#: How the trained DTW models' softmin temperature is fitted (``DTWClassifier(calibration=...)``): ``"gap"``
#: (decision C4) or ``"cv"`` (decision C67, an inner cross-validation on the training steps; adoption rule C67).
DTW_CALIBRATION = "cv"

#: The trained DTW models' decision rule (``DTWClassifier(rule=...)``): ``"mean"`` (thesis ch. 6.1.2.2, the class of
#: lowest mean distance) or ``"spread"`` (decision C70: minus half the class's own mean reference distance).
DTW_RULE = "mean"

#: Step signals compared by DTW per task and unit: terrain foot accelerometer + gyroscope / waist
#: accelerometer (thesis ch. 6.1.2.2); direction foot / waist forward acceleration (thesis ch. 6.2.2.2);
#: length foot acceleration + force / pelvic rotation (thesis ch. 6.3.2.2, sensors of Tables 29-31).
DTW_SIGNALS: dict[str, dict[str, tuple[str, ...]]] = {
    "terrain": {"foot": ("foot_acc_v", "foot_pitch"), "waist": ("waist_acc_v",)},
    "direction": {"foot": ("foot_acc_fwd",), "waist": ("waist_acc_fwd",)},
    "length": {"foot": ("foot_acc_fwd", "force"), "waist": ("waist_yaw",)},
}


# --------------------------------------------------------------------------------------------------
# model factories
# --------------------------------------------------------------------------------------------------
def select_signals(X: np.ndarray, *, names: Sequence[str]) -> np.ndarray:
    """Derived step signals ``(steps, len(names), samples)`` of a window array, for DTW."""
    from pdrlearn.features import as_windows, signal

    arr = as_windows(X)
    out = np.stack([signal(arr, n) for n in names], axis=1)
    if not np.isfinite(out).all():
        raise MissingSensorError(
            f"DTW signals {', '.join(names)}: the step windows lack (part of) them; "
            "record the sensor or use another unit"
        )
    return out


def _heuristic_module():
    try:
        from pdrlearn.classify import heuristic
    except ImportError:  # part 1 of issue 5 not merged yet
        return None
    return heuristic


def _call_factory(factory: Callable, method: str, task: str, unit: str, seed: int, kw: Mapping[str, object]):
    """Decision C122: a plug-in factory called with its ``--param`` keywords; a ``**kwargs`` factory that refuses
    one (a TypeError or ValueError while the keywords are given) is one line naming the ``--param``s (review R4)."""
    try:
        return factory(task, unit, seed=seed, **kw)
    except (TypeError, ValueError) as e:
        if not kw:
            raise
        given = " ".join(f"--param {method}.{k}" for k in kw)
        raise DataError(f"classifier method '{method}': its factory refused {given}: {type(e).__name__}: "
                        f"{str(e).splitlines()[0] if str(e) else ''}; drop or correct the --param (decision C122)"
                        ) from None


def make_estimator(task: str, method: str, unit: str, *, seed: int = 0, weights: Sequence[float] | None = None,
                   params: Mapping[str, Mapping[str, object]] | None = None):
    """A fresh estimator on step-window arrays for ``task`` x ``method`` x ``unit``.

    ``unit="fused"`` gives a :class:`UnitFusionClassifier` over the foot and waist models (``weights``
    given, or learned on a validation split when ``None``), except for ``method="fusion"`` (heuristic
    fusion with the thesis weights: Table 26 terrain, ch. 6.2.2.3 direction 0.6/0.4, Table 32 length).
    ``unit="combined"`` (svm, nn) is one classifier on the thesis' feature vector of both units (decision
    C22): terrain 17 SVM features (thesis ch. 6.1.1.1) or 72 NN inputs (ch. 6.1.1.2), direction 25
    (ch. 6.2.1), length 29 (ch. 6.3.1). ``params``: ``{"svm": {"C": 10.0}, "nn": {"hidden": 32}, "dtw": {...}}``,
    the built-in estimators' settings that replace the thesis defaults (decision C96, ``train --param``).
    """
    from pdrlearn.features import make_features

    params = params or {}

    if unit == "combined" and method not in COMBINED_METHODS and can_combine(method):
        pass  # decision C123: a plug-in registered with combined=True gets unit="combined" (below)
    elif unit == "combined":
        if method not in COMBINED_METHODS:
            raise DataError(f"unit 'combined' (one model on both units' features, thesis ch. 6.1.1) exists for "
                            f"{' and '.join(COMBINED_METHODS)} only, not {method!r}; use unit 'fused' for {method} "
                            "(a plug-in: register_method(..., combined=True), decision C123)")
        unit = "both"  # the feature transformers' name of the combined vector (pdrlearn.features)

    if method == "fusion" or (method == "heuristic" and unit != "fused"):
        mod = _heuristic_module()
        if mod is None:
            raise MissingSensorError("heuristic classifiers (pdrlearn.classify.heuristic) are not available")
        return mod.make_heuristic(task, "both" if method == "fusion" else unit, **params.get(method, {}))  # C139
    if unit == "fused" and method not in BUILTIN_METHODS:  # decision E86: a plug-in's soft vote of its two units
        members = [(u, make_estimator(task, method, u, seed=seed, params=params), slice(None))
                   for u in ("foot", "waist")]
        return UnitFusionClassifier(members, weights=None if weights is None else list(weights), random_state=seed)
    if method not in BUILTIN_METHODS or method not in METHODS.builtin:  # decision E86: a registered plug-in
        try:
            factory = METHODS[method]
        except KeyError:
            raise METHODS.unknown(method) from None
        est = _call_factory(factory, method, task, unit, seed, params.get(method, {}))
        if not (hasattr(est, "fit") and hasattr(est, "predict_proba")):
            raise DataError(f"classifier method '{method}': {_no_proba_line(est)}")
        return est
    if unit == "fused":
        if method == "heuristic":
            raise DataError("heuristic has no fused unit; use method 'fusion' (heuristic fusion)")
        members = [(u, make_estimator(task, method, u, seed=seed, params=params), slice(None))
                   for u in ("foot", "waist")]
        return UnitFusionClassifier(members, weights=None if weights is None else list(weights), random_state=seed)
    if method == "svm":
        return Pipeline([("features", make_features(task, unit, "svm")),
                         ("clf", SVMClassifier(task=task, random_state=seed, **params.get("svm", {})))])
    if method == "ensemble":  # equal-weight soft vote of the unit's learned classifiers (decision C14)
        members = [(m, make_estimator(task, m, unit, seed=seed, params=params), slice(None))
                   for m in ENSEMBLE_MEMBERS]
        return UnitFusionClassifier(members, weights=[1.0] * len(members), random_state=seed)
    if method == "nn":
        return Pipeline(
            [
                ("features", make_features(task, unit, "nn")),
                ("clf", NNClassifier(task=task, random_state=seed, **params.get("nn", {}))),
            ]
        )
    if method == "dtw":
        return Pipeline(
            [
                ("signals", FunctionTransformer(select_signals, kw_args={"names": DTW_SIGNALS[task][unit]})),
                ("clf", DTWClassifier(**{"n_references": THESIS_REFERENCES_PER_CLASS[task],
                                         "calibration": DTW_CALIBRATION, "rule": DTW_RULE,
                                         **params.get("dtw", {})},  # decision C139: --param dtw.rule, dtw.calibration
                                      random_state=seed)),
            ]
        )
    raise METHODS.unknown(method)


def _no_proba_line(est) -> str:
    """What a plug-in factory's estimator lacks and the fix (trial T4 finding 8): a Pipeline has ``fit``, its last
    step lacks ``predict_proba`` (``hasattr(pipeline, "predict_proba")`` follows the last step)."""
    steps = getattr(est, "steps", None)
    if hasattr(est, "fit") and steps:
        last = type(steps[-1][1]).__name__
        return (f"its factory returned a Pipeline whose last step {steps[-1][0]!r} ({last}) has no predict_proba; "
                f"end it with a probabilistic classifier (SVC(probability=True), or wrap it: "
                f"CalibratedClassifierCV({last}(...))) (docs/extending.md)")
    what = "fit / predict_proba" if not hasattr(est, "fit") else "predict_proba"
    return (f"its factory returned {type(est).__name__}, which has no {what}; return an unfitted scikit-learn "
            "classifier with predict_proba (docs/extending.md)")


def _builtin_method(name: str):
    def factory(task: str, unit: str, *, seed: int = 0):
        return make_estimator(task, name, unit, seed=seed)

    factory.__qualname__ = f"builtin_method[{name}]"
    return factory


def _check_method(name: str, factory):
    """A plug-in method is a function ``factory(task, unit, *, seed) -> unfitted classifier`` (decision E86)."""
    if not callable(factory):
        raise DataError(f"classifier method '{name}': {factory!r} is not a function factory(task, unit, *, seed) "
                        "-> an unfitted scikit-learn classifier (docs/extending.md)")
    if name in UNITS or "," in name or "/" in name:
        raise DataError(f"classifier method '{name}': the name must not be a unit nor hold ',' or '/'")
    return factory


#: method name -> estimator factory ``factory(task, unit, *, seed)`` (decision E86): the built-ins and those added by
#: :func:`register_method` or installed (entry point group ``pdrlearn.methods``); ``pdrlearn train --methods``
METHODS = Registry("classifier method", "pdrlearn.methods", adapt=_check_method, helper="register_method")
for _name in BUILTIN_METHODS:
    METHODS.register(_name, _builtin_method(_name))


def plugin_factories() -> dict:
    """The registered plug-in methods (not built-in): name -> factory (``--param PLUGIN.KEY=VALUE``, decision C122)."""
    return {m: METHODS[m] for m in METHODS if m not in METHODS.builtin}


def plugin_records(methods) -> dict[str, dict]:
    """Decision C121 (amended): ``{method: {"module", "path", "sha256"}}`` of the plug-in methods among
    ``methods`` (the model's manifest says which code trained it)."""
    from pdrlearn.plugin_modules import module_record

    factories = plugin_factories()
    return {m: module_record(factories[m]) for m in dict.fromkeys(methods) if m in factories}


#: plug-in methods registered with ``combined=True`` (decision C123): name -> the factory registered so
COMBINED_PLUGINS: dict[str, Callable] = {}


def can_combine(method: str) -> bool:
    """Whether ``method`` trains the ``combined`` unit: svm, nn (decision C22) or a plug-in registered with
    ``combined=True`` (decision C123; the same factory still registered)."""
    return method in COMBINED_METHODS or (method in COMBINED_PLUGINS
                                          and METHODS.get(method) is COMBINED_PLUGINS[method])


def register_method(name: str, factory, *, replace: bool = False, combined: bool = False):
    """Make ``factory(task, unit, *, seed=0) -> an unfitted classifier`` (``fit(X, y)`` / ``predict_proba(X)`` on
    step-window arrays, string class labels; e.g. a Pipeline of ``pdrlearn.features.make_features(task, unit,
    "svm")`` and your classifier) the training method ``name``: ``pdrlearn train --methods NAME`` trains it per
    unit (and its fused soft vote), cross-validated as the built-ins; ``evaluate`` and ``track --model`` use it;
    ``export`` refuses it (the runtime has no recipe for it). A built-in name is refused unless ``replace=True``
    (decision E81). ``combined=True`` (decision C123): the factory also takes ``unit="combined"`` (one model on
    both units' windows; ``make_features(task, "combined", ...)`` is the thesis' combined vector) and train
    trains it on the ``combined`` unit as svm and nn."""
    out = METHODS.register(name, factory, replace=replace)
    if combined:
        COMBINED_PLUGINS[name] = METHODS[name]
    else:
        COMBINED_PLUGINS.pop(name, None)
    return out


# --------------------------------------------------------------------------------------------------
# data
# --------------------------------------------------------------------------------------------------
@dataclass
class TaskData:
    """Labelled step windows of one task, pooled over sessions."""

    task: str
    X: np.ndarray
    y: np.ndarray
    session: np.ndarray  # session index per step
    n_skipped: int = 0  # rows whose label is not a class of the task (e.g. 'unclear')
    foot: np.ndarray | None = None  # per step: its session has the foot accelerometer (and no gap, B11)
    waist: np.ndarray | None = None  # per step: its session has the waist accelerometer (and no gap, B11)
    step: np.ndarray | None = None  # per step: its row in its session's (cleaned) steps table (decision C42)
    times: np.ndarray | None = None  # per step: (start_s, end_s) of its steps.csv row (block folds, decision C95)
    side: np.ndarray | None = None  # per step: its steps.csv 'foot' ('' without the column; decision C95)

    def unit_mask(self, unit: str) -> np.ndarray:
        """Steps whose session has the unit (``fused``: both units)."""
        if unit == "foot":
            return self.foot
        if unit == "waist":
            return self.waist
        return self.foot & self.waist


def session_windows(sessions, *, n_samples: int, boundaries: str = "given", purpose: str = "train"):
    """Step windows of every labelled step of every session (one :class:`StepWindows` per session);
    ``boundaries`` as :func:`pdrlearn.features.step_windows` (``"rest"``: rest-to-rest windows);
    ``purpose`` ("train" | "evaluate") words the error for a session without labelled steps."""
    from pdrlearn.classify import detected
    from pdrlearn.classify.labels import clean_steps, misaligned_text
    from pdrlearn.features import step_windows

    out = []
    for s in sessions:
        if s.steps is None or len(s.steps) == 0:
            where = f"{s.folder}" if s.folder is not None else f"session '{s.name}'"
            fix = ("label its steps to train on it" if purpose == "train" else
                   "evaluate needs labelled sessions: label its steps, or track an unlabelled walk with "
                   "`pdrlearn track SESSION --model MODEL`")
            raise DataError(f"{where}: no labelled steps (steps.csv); {fix}")
        steps = clean_steps(s, s.steps)  # labels any case, each step once (decisions C32, C33)
        if purpose == "train" and boundaries == "given":  # decision C55 (adopted; C162: no switch)
            steps = detected.runtime_bout_edges(s, steps)  # bout edges as the runtime cuts them
        shifted = misaligned_text(s, steps, boundaries)  # labels off the foot's rest periods (C37)
        try:
            w = step_windows(s, steps, n_samples=n_samples, boundaries=boundaries)
        except DataError as exc:
            msg = str(exc)
            head = f"session '{s.name}'"  # step_windows' prefix: the folder instead, as a copied folder keeps
            if s.folder is not None and msg.startswith(head):  # its meta.json name (B34, decision C37)
                msg = str(s.folder) + msg[len(head):]
            if shifted is not None:  # the frame check fails on steps cut mid-swing: say what is likelier
                msg = f"{shifted} (cutting the step windows then failed: {msg})"
            raise DataError(msg) from None
        if shifted is not None:
            log.warning(shifted)
        out.append(w)
    return out


def _named(w):
    """A stand-in naming a session by its windows' session name (no folder known)."""
    from types import SimpleNamespace

    return SimpleNamespace(folder=None, where=f"session '{w.session}'")


def task_data(windows, task: str, sessions=None) -> TaskData | None:
    """Pool the steps labelled for ``task``; ``None`` when no session has that label column. ``sessions`` (the
    windows' sessions, in order) name the files in the warnings about left-out labels (decision C33)."""
    from pdrlearn.classify.labels import bad_label_warning
    from pdrlearn.features import TASK_COLUMNS, task_labels

    Xs, ys, sess, skipped, foot, waist, rows, times, sides = [], [], [], 0, [], [], [], [], []
    for i, w in enumerate(windows):
        if TASK_COLUMNS[task] not in w.steps or w.steps[TASK_COLUMNS[task]].notna().sum() == 0:
            continue
        y, keep, _ = task_labels(w.steps, task, source=f"session '{w.session}'")
        # decision C33: the left-out labels (empty cells too) named in one warning per session and task
        n_skip, line = bad_label_warning(sessions[i] if sessions is not None else _named(w), w.steps, task)
        if line:
            log.warning(line)
        skipped += n_skip
        Xs.append(w.X[keep])
        ys.append(y)
        sess.append(np.full(len(y), i))
        rows.append(np.flatnonzero(keep))
        kept = w.steps[keep]
        times.append(kept[["start_s", "end_s"]].to_numpy(float))  # decision C95: blocks by time, not by row
        sides.append(kept["foot"].fillna("").astype(str).to_numpy(object) if "foot" in kept
                     else np.full(len(kept), "", dtype=object))
        lost = getattr(w, "gap_steps", {})  # steps overlapping a sensor gap lose that unit (decision B11)
        for unit, has, acc in (("foot", foot, "foot_acc"), ("waist", waist, "waist_acc")):
            ok = np.full(len(y), acc in w.available)
            if unit in lost:
                ok &= ~lost[unit][keep]
                log.warning("session '%s': %s task: %d labelled steps overlap a %s sensor gap and are left "
                            "out of the %s models", w.session, task, int(lost[unit][keep].sum()), unit, unit)
            has.append(ok)
    if not Xs:
        return None
    return TaskData(
        task,
        np.concatenate(Xs),
        np.concatenate(ys).astype(str),
        np.concatenate(sess),
        skipped,
        np.concatenate(foot),
        np.concatenate(waist),
        np.concatenate(rows),
        np.concatenate(times),
        np.concatenate(sides),
    )


class TrainingData(NamedTuple):
    """:func:`training_data`'s steps: ``X`` the step windows ``(steps, channels, samples)``, ``y`` the labels,
    ``session`` each step's session name, ``user`` each step's user (:func:`session_user`; None when the session's
    meta.json names none)."""

    X: np.ndarray
    y: np.ndarray
    session: np.ndarray
    user: np.ndarray


def training_data(sessions, task: str, *, unit: str | None = None, n_samples: int = 40, boundaries: str = "given",
                  resample_hz: float | None = None) -> TrainingData:
    """The labelled step windows ``train`` cross-validates for ``task`` (decision C120): cut as
    :func:`train_user` cuts them (bout edges as the runtime cuts them, decision C55; ``boundaries``, ``n_samples``
    and ``resample_hz`` as train's), pooled over ``sessions``; ``unit`` ("foot", "waist", "fused", "combined")
    keeps the steps train fits that unit's models on (None: every labelled step). With scikit-learn,
    ``cross_val_predict(make_estimator(task, method, unit), d.X, d.y, groups=d.user, cv=GroupKFold(k))`` then
    scores the windows ``train --cv-groups user`` scores; :func:`pdrlearn.features.step_windows` on the labelled
    steps as given cuts other windows at a bout's first and last step."""
    if task not in TASKS:
        raise DataError(f"training_data: task {task!r}; choose one of {', '.join(TASKS)}")
    if unit is not None and unit not in UNITS:
        raise DataError(f"training_data: unit {unit!r}; choose one of {', '.join(UNITS)} (or None: every step)")
    sessions = session_list(sessions, "training_data")
    if not sessions:
        raise DataError("training_data: no sessions given; pass at least one labelled session")
    sessions = one_rate(sessions, session_rates(sessions), resample_hz, "training_data")  # decision C56, as train
    data = task_data(session_windows(sessions, n_samples=n_samples, boundaries=boundaries), task, sessions)
    if data is None:
        raise DataError(_no_labels_message(task, sessions))
    keep = np.ones(len(data.y), bool) if unit is None else data.unit_mask(unit)
    names = np.asarray([s.name for s in sessions], dtype=object)
    users = np.asarray([session_user(s) for s in sessions], dtype=object)
    return TrainingData(data.X[keep], data.y[keep], names[data.session][keep], users[data.session][keep])


def check_classes(
    data: TaskData,
    *,
    min_per_class: int = MIN_STEPS_PER_CLASS,
    y: np.ndarray | None = None,
) -> None:
    """Raise :class:`DataError` for a missing class or a class with too few steps (of ``y``, default
    ``data.y``)."""
    from pdrlearn.features import TASK_CLASSES

    y = data.y if y is None else y
    counts = {c: int(np.sum(y == c)) for c in TASK_CLASSES[data.task]}
    missing = [c for c, n in counts.items() if n == 0]
    if missing:
        have = ", ".join(f"{c}={n}" for c, n in counts.items() if n)
        raise DataError(
            f"task {data.task}: no steps labelled {', '.join(repr(m) for m in missing)} "
            f"(labelled: {have or 'none'}); record and label steps of every class, at least "
            f"{min_per_class} each" + (LENGTH_CLASSES_HINT if data.task == "length" else "")
        )
    few = {c: n for c, n in counts.items() if n < min_per_class}
    if few:
        raise DataError(
            f"task {data.task}: too few steps for class(es) "
            f"{', '.join(f'{c} ({n})' for c, n in few.items())}; at least {min_per_class} "
            "labelled steps per class are needed" + (LENGTH_CLASSES_HINT if data.task == "length" else "")
        )


# --------------------------------------------------------------------------------------------------
# metrics
# --------------------------------------------------------------------------------------------------
def class_metrics(y_true: np.ndarray, y_pred: np.ndarray, classes: Sequence[str]) -> dict:
    """Accuracy, balanced accuracy, per-class recall ("accuracy per class" of thesis Tables 27, 28, 33),
    per-class ``precision`` and ``f1`` (decision C37) and the confusion matrix (rows = true class, columns =
    predicted, in ``classes`` order)."""
    from sklearn.metrics import confusion_matrix

    y_true, y_pred = np.asarray(y_true).astype(str), np.asarray(y_pred).astype(str)
    classes = [str(c) for c in classes]
    per_class = {c: (float(np.mean(y_pred[y_true == c] == c)) if np.any(y_true == c) else None) for c in classes}
    present = [v for v in per_class.values() if v is not None]
    # decision C37: per-class precision (None: never predicted) and F1 beside the recall
    precision = {c: (float(np.mean(y_true[y_pred == c] == c)) if np.any(y_pred == c) else None) for c in classes}
    f1 = {c: (None if per_class[c] is None or precision[c] is None else
              (0.0 if per_class[c] + precision[c] == 0 else
               2 * per_class[c] * precision[c] / (per_class[c] + precision[c]))) for c in classes}
    return {
        "precision": precision,
        "f1": f1,
        "accuracy": float(np.mean(y_true == y_pred)) if len(y_true) else None,
        "balanced_accuracy": float(np.mean(present)) if present else None,
        "per_class": per_class,
        "n_steps": int(len(y_true)),
        "confusion": confusion_matrix(y_true, y_pred, labels=list(classes)).tolist(),
    }


#: Tie-break between units of one method with equal scores: the order they were always trained in, with the
#: thesis' combined feature vector (one model) before our soft vote of two (decision C23).
UNIT_PREFERENCE = ("foot", "waist", "combined", "fused")


def best_pair(ranking: list[tuple[str, str]], one_unit=()) -> tuple[str, str] | None:
    """Decision C8 / C23: the chosen ``(method, unit)`` of a task's ``ranking`` (best first): the best two-unit
    model (soft vote or combined features), else the best of any unit; None for an empty ranking. ``one_unit``: the
    soft votes that read one unit only (a zero unit weight, :meth:`TaskModel.one_unit_votes`, decision C124), which
    do not count as two-unit models."""
    return next((p for p in ranking if p[1] in TWO_UNIT and p not in one_unit), ranking[0] if ranking else None)


def zero_weight_unit(record: dict) -> str | None:
    """Decision C124: the unit a fused CV record's soft vote gives weight 0 (``weights`` of the record, e.g. foot 1,
    waist 0 -> ``"waist"``), so the vote reads the other unit only; None when both count (or no weights)."""
    w = record.get("weights") or {}
    return next((u for u, v in w.items() if v is not None and float(v) <= 0.0), None)


def _score_key(metrics: dict, method: str, unit: str = "fused") -> tuple:
    pref = PREFERENCE.index(method) if method in PREFERENCE else len(PREFERENCE)  # a plug-in ties last (E86)
    return (-(metrics["balanced_accuracy"] or 0.0), -(metrics["accuracy"] or 0.0), pref,
            UNIT_PREFERENCE.index(unit) if unit in UNIT_PREFERENCE else len(UNIT_PREFERENCE))


# --------------------------------------------------------------------------------------------------
# user model
# --------------------------------------------------------------------------------------------------
@dataclass
class TaskModel:
    """Fitted models of one task: ``models[method][unit]``, CV metrics, the chosen ``(method, unit)``."""

    task: str
    classes: list[str]
    models: dict[str, dict[str, object]] = field(default_factory=dict)
    cv: dict[str, dict[str, dict]] = field(default_factory=dict)
    chosen: tuple[str, str] | None = None
    fusion_weights: dict[str, list[float]] = field(default_factory=dict)
    skipped: list[str] = field(default_factory=list)
    n_steps: int = 0
    n_skipped_labels: int = 0
    #: decision C161: training steps of the kinds the task's classes do not cover (``{"side": n, "turn": n}``);
    #: None: not known (a model from before C161, or sessions without ``kind``)
    trained_kinds: dict | None = None

    def ranking(self) -> list[tuple[str, str]]:
        """(method, unit) pairs from best to worst CV score."""
        pairs = [(m, u) for m, per in self.cv.items() for u in per if u in self.models.get(m, {})]
        return sorted(pairs, key=lambda p: _score_key(self.cv[p[0]][p[1]], p[0], p[1]))

    def one_unit_votes(self) -> set[tuple[str, str]]:
        """Decision C124: the fused soft votes with a zero unit weight (they read one unit only)."""
        return {(m, "fused") for m, per in self.cv.items() if "fused" in per and zero_weight_unit(per["fused"])}


@dataclass
class UserModel:
    """A user's trained step classifiers (all tasks), with the training summary and CV metrics."""

    user: str
    tasks: dict[str, TaskModel]
    n_samples: int = 40
    sampling_rate_hz: dict[str, float] = field(default_factory=dict)
    data_summary: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)
    created: str = ""
    skipped: list[str] = field(default_factory=list)

    @property
    def boundaries(self) -> str:
        """Step-window boundaries the model was trained with (``settings["boundaries"]``; models saved
        before the option existed: ``"given"``); prediction cuts windows the same way."""
        return str((self.settings or {}).get("boundaries", "given"))

    def save(self, path) -> None:
        """Write the model directory atomically (see :mod:`pdrlearn.classify.model_dir`)."""
        from pdrlearn.classify.model_dir import save_model

        save_model(self, path)

    def _candidates(self, tm: TaskModel, windows, method: str | None, unit: str | None) -> list[tuple[str, str]]:
        """(method, unit) pairs to try: the requested one only, else the chosen one and then the ranking,
        keeping those whose units the windows have."""
        if method is not None or unit is not None:
            m = method or (tm.chosen[0] if tm.chosen else None)
            units = [unit] if unit else [u for mm, u in tm.ranking() if mm == m]
            pairs = [(m, u) for u in units if u in tm.models.get(m, {})]
            if not pairs:
                raise DataError(
                    f"model task {tm.task}: no trained method {m!r} unit {unit!r}; trained: "
                    f"{', '.join(f'{a}/{b}' for a, b in tm.ranking())}"
                )
            return pairs[:1]
        order = list(dict.fromkeys(([tm.chosen] if tm.chosen else []) + tm.ranking()))
        return [(m, u) for m, u in order if _units_available(u, windows.available, m)]

    def _predict_task(self, tm: TaskModel, windows, method: str | None, unit: str | None):
        """``(method, unit, proba)`` of the first candidate model that runs on the windows."""
        reasons = []
        for m, u in self._candidates(tm, windows, method, unit):
            est = tm.models[m][u]
            try:
                proba = estimator_proba(est, windows.X, tm.classes, f"model task {tm.task} {m}/{u}")
            except MissingSensorError as exc:  # e.g. a length model needing force sensors
                if method is not None or unit is not None:
                    raise
                reasons.append(f"{m}/{u}: {exc}")
                continue
            return m, u, proba
        raise MissingSensorError(
            f"session '{windows.session}' lacks the sensors of every {tm.task} model "
            f"(it has {', '.join(windows.available) or 'none'}){'; ' if reasons else ''}{'; '.join(reasons)}"
        )

    def predict_steps(
        self,
        session,
        steps: pd.DataFrame | None = None,
        *,
        tasks: Sequence[str] | None = None,
        method: str | None = None,
        unit: str | None = None,
        windows: str | None = None,
        warn_rate: bool = True,
        joint_domain: bool = False,
    ) -> pd.DataFrame:
        """Classify every step of ``steps`` (default ``session.steps``).

        ``windows`` (decision C51): ``"track"`` (the default when ``steps`` is given, e.g. a detector's table)
        classifies each step on the window ``pdrlearn track --method M3`` classifies it on
        (:func:`pdrlearn.track.plasys.model_windows`: the rest-to-rest stride the step makes, re-cut on the
        streaming segmenter's stride), so the classes equal track's; ``"given"`` (the default for the session's
        labelled steps, the windows the model was trained on) classifies on the steps' own ``start_s``/``end_s``.
        With ``"track"`` the table also has the ``window_start_s``/``window_end_s`` classified.
        ``warn_rate``: log decision C18's line when a unit runs at another rate than the model was trained at
        (decision C52; ``track`` passes False and gives the line in its own warnings).
        ``joint_domain`` (decision C71, an option: it failed its adoption rule): add ``ood_joint_<task>``, the joint
        (Mahalanobis) domain score of each step (> 1: out; NaN for a model trained before C71).

        Returns a DataFrame (one row per step, same index as ``steps``) with, per trained task, the class
        column (``terrain``, ``direction``, ``length_class``; ``str``), the probabilities ``p_<task>_<class>`` and
        ``method_<task>`` (``"<method>/<unit>"``). By default each task uses the model's chosen method, or,
        when the session lacks one of its units, the best cross-validated method it can run. A task no
        model can run on the session (e.g. length without force sensors) gets ``None`` classes, NaN
        probabilities and ``method_<task> = "none"`` (logged) unless ``tasks``/``method``/``unit`` were
        given, which makes it a :class:`MissingSensorError`.
        """
        from pdrlearn.features import TASK_COLUMNS, step_windows

        mode = windows or ("given" if steps is None else "track")
        if mode not in PREDICT_WINDOWS:
            raise DataError(f"predict_steps: windows={windows!r}; choose one of {', '.join(PREDICT_WINDOWS)}")
        steps = session.steps if steps is None else steps
        cut = steps
        if mode == "track" and steps is not None and {"start_s", "end_s"} <= set(steps.columns):
            from pdrlearn.track.plasys import model_windows

            cut = model_windows(session, steps).set_axis(steps.index)  # decision C51
            odd = {k: cut.attrs.get(k, 0) for k in ("own_bounds", "several_strides")}
            if any(odd.values()):
                log.info("%s: predict_steps: %d step(s) are no stride between two rests (classified on their own "
                         "bounds), %d span several strides (classified on their whole span; track splits them)",
                         session.where, odd["own_bounds"], odd["several_strides"])
        windows = step_windows(session, cut, n_samples=self.n_samples, boundaries=self.boundaries)
        out = pd.DataFrame(index=steps.index if steps is not None else None)
        for col in ("start_s", "end_s"):
            if col in steps:
                out[col] = steps[col].to_numpy()
        if cut is not steps:
            out["window_start_s"], out["window_end_s"] = cut["start_s"].to_numpy(), cut["end_s"].to_numpy()
        gap_unclassified: dict[tuple, list[str]] = {}  # (lost units, n steps) -> tasks (one line each, B34)
        for task in tasks or list(self.tasks):
            if task not in self.tasks:
                raise DataError(
                    f"model of user '{self.user}' has no {task} classifier; trained tasks: {', '.join(self.tasks)}"
                )
            tm = self.tasks[task]
            out[TASK_COLUMNS[task]] = None
            for c in tm.classes:
                out[f"p_{task}_{c}"] = np.nan
            out[f"method_{task}"] = "none"
            out[f"ood_{task}"] = np.nan  # distance to the training range (decision C16)
            out[f"ood_feature_{task}"] = None
            if joint_domain:
                out[f"ood_joint_{task}"] = np.nan  # joint score (decision C71, opt-in)
            for rows, win, lost in _gap_groups(windows):
                try:
                    m, u, proba = self._predict_task(tm, win, method, unit)
                except MissingSensorError as exc:
                    if len(rows) == len(out) and (tasks is not None or method is not None or unit is not None):
                        raise
                    if lost:  # steps that lost units to a gap: "lacks the sensors (it has none)" misled (B34)
                        gap_unclassified.setdefault((lost, len(rows)), []).append(task)
                    else:
                        log.warning("%s: %s task left unclassified for %d steps: %s", session.where, task,
                                    len(rows), exc)
                    continue
                col = out.columns.get_loc(TASK_COLUMNS[task])
                # plain str classes (decision B178: a model's classes may be numpy strings)
                out.iloc[rows, col] = np.asarray([str(c) for c in tm.classes], dtype=object)[np.argmax(proba, axis=1)]
                for j, c in enumerate(tm.classes):
                    out.iloc[rows, out.columns.get_loc(f"p_{task}_{c}")] = proba[:, j]
                out.iloc[rows, out.columns.get_loc(f"method_{task}")] = f"{m}/{u}"
                dist = step_score(tm.models[m][u], win.X)  # decision C16: outside the training range?
                if dist is not None:
                    out.iloc[rows, out.columns.get_loc(f"ood_{task}")] = dist[0]
                    out.iloc[rows, out.columns.get_loc(f"ood_feature_{task}")] = np.asarray(dist[1], dtype=object)
                joint = step_joint_score(tm.models[m][u], win.X) if joint_domain else None  # decision C71
                if joint is not None:
                    out.iloc[rows, out.columns.get_loc(f"ood_joint_{task}")] = joint
        for (lost, n), done in gap_unclassified.items():
            log.warning("%s: %d step(s) overlapping a sensor gap lost the %s unit%s; no trained %s model runs "
                        "without %s, so they are left unclassified", session.where, n, " and ".join(lost),
                        "s" if len(lost) > 1 else "", "/".join(done), "them" if len(lost) > 1 else "it")
        off = rate_mismatch(self, session, out)  # decision C52: the line track and evaluate give (C18)
        if off and warn_rate:
            from pdrlearn.kernels.distance import classifier_rate_warning

            log.warning("%s: %s", session.where, classifier_rate_warning(off))
        return out

    def domain_report(self, pred: pd.DataFrame, *, warn_at: float | None = None) -> dict | None:
        """Out-of-domain summary (decision C16) of a :meth:`predict_steps` table: per task the fraction of
        classified steps outside the training range, the unit and the feature most often off; ``None`` when
        the model stores no training ranges (saved before C16) or no task was checked. ``warn_at``: the
        fraction at which ``warn`` is set (None: never, the default)."""
        per_task = {}
        for task in self.tasks:
            if f"ood_{task}" not in pred:
                continue
            d = pred[f"ood_{task}"].to_numpy(float)
            if not np.isfinite(d).any():
                continue
            used = pred[f"method_{task}"].astype(str).to_numpy()[np.isfinite(d)]
            unit = ", ".join(sorted(set(used)))  # "<method>/<unit>" of the models checked
            per_task[task] = summarize(d, [str(v) for v in pred[f"ood_feature_{task}"].fillna("")], unit)
        if not per_task:
            return None
        rep = domain_report(per_task, warn_at=warn_at)
        if any(c.startswith("ood_joint_") for c in pred.columns):  # decision C71's option
            rep["joint_out_of_domain_fraction"] = joint_fraction(pred, self.tasks)
        return rep

    @property
    def has_domain(self) -> bool:
        """Whether the model stores training ranges (decision C16; models saved before it do not)."""
        return any(has_ranges(est) for tm in self.tasks.values() for per in tm.models.values()
                   for est in per.values())


#: ``UserModel.predict_steps(windows=...)``: track's windows of a detected table, or the steps' own (decision C51)
PREDICT_WINDOWS = ("track", "given")
#: the units whose sensors a classifier of ``method_<task> = "<method>/<unit>"`` reads
_UNIT_OF = {"foot": ("foot",), "waist": ("waist",), "fused": ("foot", "waist"), "combined": ("foot", "waist")}
_UNIT_ACC = {"foot": "fAccelerometer", "waist": "wAccelerometer"}


def rate_mismatch(model, session, pred: pd.DataFrame | None = None) -> dict | None:
    """Decisions C18 / C52: unit -> ``{"trained_hz", "session_hz"}`` of the units whose accelerometer runs at
    another rate than the model's classifiers were trained at (tolerance of
    :func:`~pdrlearn.kernels.distance.rate_differs`); with a :meth:`UserModel.predict_steps` table ``pred`` only
    the units its ``method_<task>`` columns used, else both. None: none differ, or a model without rates. One
    mechanism for ``predict_steps``, ``track`` and ``evaluate``."""
    from pdrlearn.kernels.distance import rate_differs

    rates = getattr(model, "sampling_rate_hz", None) or {}
    if not rates:
        return None
    used = set(_UNIT_ACC) if pred is None else {
        u for c in pred.columns if c.startswith("method_")
        for v in pred[c].dropna().astype(str).unique() if "/" in v for u in _UNIT_OF.get(v.split("/")[1], ())}
    off = {}
    for unit in sorted(used):
        name = _UNIT_ACC[unit]
        if rates.get(name) and name in session.streams:
            fs = float(session.streams[name].rate_hz)
            if np.isfinite(fs) and rate_differs(float(rates[name]), fs):
                off[unit] = {"trained_hz": float(rates[name]), "session_hz": fs}
    return off or None


def _where(session) -> str:
    """How a warning names a session (decision B34): its folder's name, not meta.json's (a copied folder keeps the
    original's "session" name); the name of a session built in memory."""
    folder = getattr(session, "folder", None)
    return folder.name if folder is not None else str(getattr(session, "name", session))


def other_user_line(model, sessions, what: str = "evaluate") -> str | None:
    """Decision C138: one warning line when a per-user model (:func:`model_user_key`) is scored on / classifies
    sessions whose meta.json names another user (:func:`session_user`, the mechanism of train's mixed-users warning,
    C35); None when no user is known on either side or every session is the model's user."""
    key = model_user_key(model)
    if key is None:
        return None
    # decision C152: both ids known and different, whatever their form: a given name (P001) is the same user as a
    # session whose meta.json 'user' / 'subject' is that text (key user:P001)
    other = [(s, u) for s in sessions if (u := session_user(s)) is not None and key not in (u, _one_user(s))]
    if not other:
        return None
    users = ", ".join(sorted({u for _, u in other}))
    names = ", ".join(_where(s) for s, _ in other[:3]) + (f" and {len(other) - 3} more" if len(other) > 3 else "")
    # decision C156: the model keeps no trace of the id a given name hides (a hash of it, salt stored beside it,
    # would confirm a guessed id), so the own sessions are recognised only by that name: import --subject
    given = ("" if key.startswith(_USER_KEY_PREFIXES) else
             f"; {key} is the name given at training (train --user, E174) and the model keeps no trace of the id it "
             "hides (decision C156): if these are that user's sessions the line is expected; to have them "
             f"recognised, import them with --subject {key}, or write \"user\": \"{key}\" in their meta.json")
    return (f"{what}: the model was trained on {key} but {len(other)} of {len(sessions)} session(s) are of {users} "
            f"({names}): a per-user model is applied to another user, so the figures are not the model's held-out "
            f"accuracy on its user{given} (decision C138; train that user's model, or a pooled one with --cv-groups "
            "user)")


def _gap_groups(windows):
    """``(rows, windows, lost units)`` triples: the steps that lost the same units (``("foot", "waist")``, ``()``
    for none) to sensor gaps, with those units removed from ``available`` (decision B11), so a model of the
    remaining unit classifies them."""
    from pdrlearn.features.windows import UNIT_GROUPS

    gaps = getattr(windows, "gap_steps", {})
    if not gaps:
        return [(np.arange(len(windows)), windows, ())]
    units = sorted(gaps)
    key = np.stack([gaps[u] for u in units], axis=1)
    groups = []
    for k in np.unique(key, axis=0):
        rows = np.flatnonzero((key == k).all(axis=1))
        win = windows.subset(rows)
        lost_units = tuple(u for u, b in zip(units, k, strict=True) if b)
        lost = {g for u in lost_units for g in UNIT_GROUPS[u]}
        win.available = tuple(g for g in win.available if g not in lost)
        groups.append((rows, win, lost_units))
    return groups


def _units_available(unit: str, available: Sequence[str], method: str) -> bool:
    foot = "foot_acc" in available
    waist = "waist_acc" in available
    if unit == "foot":
        return foot
    if unit == "waist":
        return waist
    return foot and waist


def estimator_proba(est, X, classes, where: str) -> np.ndarray:
    """Probabilities ``(n, len(classes))`` of a fitted estimator in the task's class order (decision B172).

    An estimator gives ``predict_proba`` or ``decision_function`` (scikit-learn's classifiers, docs/extending.md);
    decision values become probabilities by a row softmax (a binary ``(n,)`` score d as ``[-d, d]``), the SVM's own
    rule (decision E4).
    An estimator fitted on other labels (encoded integers, other class names) or with neither method is one line
    naming ``where`` (the model) and the fix, not a KeyError / AttributeError from inside."""
    from pdrlearn.kernels.proba import softmax

    name = type(est).__name__
    own = np.asarray(getattr(est, "classes_", [])).astype(str)
    alien = [c for c in own if c not in set(map(str, classes))]
    if alien or not own.size:
        raise DataError(f"{where}: {name} predicts classes {', '.join(alien) or '(none: not fitted?)'}, not the "
                        f"task's {', '.join(map(str, classes))}; fit it on the label strings (y from "
                        "StepWindows.labels), not encoded integers")
    if hasattr(est, "predict_proba"):
        proba = np.asarray(est.predict_proba(X), dtype=float)
    elif hasattr(est, "decision_function"):
        d = np.asarray(est.decision_function(X), dtype=float)
        proba = softmax(np.column_stack([-d, d]) if d.ndim == 1 else d)
    else:
        raise DataError(f"{where}: {name} has neither predict_proba nor decision_function; "
                        "wrap it, e.g. sklearn.calibration.CalibratedClassifierCV")
    return align_proba(proba, own, np.asarray(classes))


# --------------------------------------------------------------------------------------------------
# training
# --------------------------------------------------------------------------------------------------
def _oof_proba(est, X, y, folds, classes) -> np.ndarray:
    """Out-of-fold probabilities ``(n, n_classes)`` of ``est`` over ``folds``."""
    P = np.zeros((len(y), len(classes)))
    for tr, te in folds:
        model = clone(est).fit(X[tr], y[tr])
        P[te] = align_proba(model.predict_proba(X[te]), np.asarray(model.classes_).astype(str), classes)
    return P


def fold_fitted_vote(probas: list[np.ndarray], y_idx: np.ndarray, folds) -> np.ndarray:
    """Decision C57: the soft vote of out-of-fold probabilities ``probas`` with weights chosen without the
    scored fold: each fold's steps are voted with :func:`best_weights` of the other folds' steps, so a held-out
    user (session) takes no part in choosing the weights it is scored with."""
    P = np.zeros_like(probas[0])
    for tr, te in folds:
        w = best_weights([p[tr] for p in probas], y_idx[tr])
        P[te] = soft_vote([p[te] for p in probas], w)
    return P


CV_GROUPS = ("steps", "user", "session", "block")  # train's --cv-groups (decisions C29, C59, C95)


#: the model's user when no session names one in meta.json ``user`` / ``subject`` and ``--user`` is not given
#: (decision B88: not the first session's folder name, which ``pdrlearn import`` takes from ``--out``)
UNNAMED_USER = "unnamed"


def check_user(user: str | None, where: str = "train: --user") -> str | None:
    """Decision B339: a blank ``user`` (``--user ""``) asked for no name and got the sessions' subject back; it is
    refused in one line. ``None`` (not given) and a name pass through, stripped."""
    if user is None:
        return None
    if not str(user).strip():
        raise DataError(f"{where} is blank; give a name to store (a pseudonym such as P001), or leave the option out "
                        "for the sessions' meta.json 'user' / 'subject'")
    return str(user).strip()


def user_pseudonyms(named: Sequence[str], user: str | None) -> dict[str, str]:
    """Decision E174: what a given ``user`` name replaces. The users the sessions name (``named``, sorted) become
    ``user`` (one user) or ``user-1``, ``user-2``, ... in that order (several: a pooled model keeps apart whom its
    leave-one-user-out folds held out, without their names); ``{}`` when no name is given."""
    if user is None:
        return {}
    if len(named) <= 1:
        return dict.fromkeys(named, user)
    return {n: f"{user}-{i}" for i, n in enumerate(named, 1)}


def default_user(sessions, fallback: str = UNNAMED_USER) -> str:
    """The stored name of a model trained without a given name (decisions B88, C35, E175): ``pooled: a, b`` when
    the sessions name several users, else the one user's meta.json ``user`` / ``subject``, else ``fallback``
    (``unnamed`` for train; train-all passes the user's folder name)."""
    named = sorted({u for u in (session_user(s) for s in sessions) if u is not None})
    if len(named) > 1:
        return f"pooled: {', '.join(named)}"
    return _one_user(sessions[0]) or fallback


def _folds(y: np.ndarray, cv: int, seed: int, task: str, groups: np.ndarray | None = None,
           notes: list[str] | None = None, kind: str = "user", times: np.ndarray | None = None,
           side: np.ndarray | None = None) -> tuple[list, int]:
    """Stratified, shuffled folds; fewer than ``cv`` when the smallest class has fewer steps. With ``groups``
    (the user of each step, decision C29) and at least two users: folds of whole users (leave-one-user-out when
    there are at most ``cv`` users), unless a training fold would then lack a class (stratified, one line).
    Returns the folds and the number of users they hold out (0: stratified over steps). ``notes``: collect the
    warning lines there (the caller logs each once, decision C36) instead of logging them. ``kind``: what a group
    is, ``"user"`` or ``"session"`` (decision C59), for the warning; ``"block"`` (decision C95): ``groups`` are the
    steps' sessions, ``times`` their (start, end) and ``side`` their foot, folds of contiguous blocks of each session
    in time (:func:`pdrlearn.classify.blocks.block_folds`; returns the number of folds)."""
    say = notes.append if notes is not None else log.warning
    if kind == "block" and groups is not None:
        from pdrlearn.classify.blocks import block_folds

        folds = block_folds(groups, times[:, 0], times[:, 1], cv, side)
        short = [i for i, (tr, _) in enumerate(folds) if len(np.unique(y[tr])) < len(np.unique(y))]
        if not short:
            return folds, len(folds)
        lack = [str(c) for c in np.unique(y) if c not in set(y[folds[short[0]][0]])]
        say(f"task {task}: CV by blocks not possible: fold {short[0] + 1} leaves no {', '.join(lack)} step to train "
            f"on (too few of them, all in one stretch); stratified folds over steps instead (decision C95)")
        groups = None
    if groups is not None and len(np.unique(groups)) >= 2:
        n_users = len(np.unique(groups))
        folds = list(GroupKFold(n_splits=min(cv, n_users)).split(np.zeros(len(y)), y, groups))
        short = [i for i, (tr, _) in enumerate(folds) if len(np.unique(y[tr])) < len(np.unique(y))]
        if not short:
            return folds, n_users
        tr, te = folds[short[0]]  # decision C43: say which user's steps hold which class alone
        lack = [str(c) for c in np.unique(y) if c not in set(y[tr])]
        out_users = ", ".join(sorted({str(u) for u in groups[te]}))
        only = ", ".join(sorted({str(u) for u in groups[np.isin(y, lack)]}))
        say(f"task {task}: CV by {kind} not possible: holding out {out_users} leaves no {', '.join(lack)} step to "
            f"train on (only {only} {'walked' if kind == 'user' else 'has'} it); stratified folds over steps instead")
    n_splits = int(min(cv, min(np.sum(y == c) for c in np.unique(y))))
    if n_splits < cv:
        say(f"task {task}: {n_splits}-fold CV instead of {cv} (smallest class has {n_splits} steps)")
    return list(StratifiedKFold(n_splits=n_splits, shuffle=True, random_state=seed).split(np.zeros(len(y)), y)), 0


def blocks_used(tasks: dict) -> int:
    """Decision C114: the most block folds any task's method x unit CV used (``cv_blocks`` of its record; 0: none
    held out blocks). Block folds with no test step are dropped (C95), so a model trained on sessions of fewer
    labelled steps than ``--cv`` used fewer folds than asked."""
    return max((int(r.get("cv_blocks") or 0) for tm in tasks.values() for per in tm.cv.values()
                for r in per.values() if isinstance(r, dict)), default=0)


def cv_groups_used(tasks: dict, asked: str) -> tuple[dict[str, str], str]:
    """Decision B210: the grouping each task's CV folds used - ``asked`` when some method x unit held out whole users
    / sessions (``cv_users`` / ``cv_sessions`` > 0), ``"steps"`` when it fell back to stratified folds over steps
    (one line on stderr had been the only record) - and the model's: ``"steps"`` when no task used ``asked``, else
    ``asked`` (``cv_groups_by_task`` tells a mixed model's tasks apart)."""
    by_task = {}
    for name, tm in tasks.items():
        held = any((r.get("cv_users") or r.get("cv_sessions") or r.get("cv_blocks") or 0) > 0  # C59, C95
                   for per in tm.cv.values() for r in per.values() if isinstance(r, dict))
        by_task[name] = asked if asked != "steps" and held else "steps"
    used = asked if asked != "steps" and any(v == asked for v in by_task.values()) else "steps"
    return by_task, used


def _cv_entry(y, y_pred, classes, folds, cv_users: int, groups=None, kind: str = "user", **extra) -> dict:
    """One method x unit's CV record: the pooled out-of-fold metrics (:func:`class_metrics`), the folds'
    spread (decision C41), ``n_folds``, ``cv_users`` (decision C29; with folds of whole sessions, ``kind``
    ``"session"``, 0 and ``cv_sessions`` the number of sessions, decision C59) and ``extra``."""
    from pdrlearn.classify.spread import fold_spread

    by = ({"cv_users": cv_users} if kind == "user" else {"cv_users": 0, f"cv_{kind}s": cv_users})  # C59, C95
    return dict(class_metrics(y, y_pred, classes), folds=fold_spread(y, y_pred, folds, groups, kind=kind),
                n_folds=len(folds), **by, **extra)


def _split_units(units: Sequence[str]) -> tuple[list[str], bool, bool]:
    """Per-unit models to train, whether to fuse (the fused model needs both unit models) and whether to train
    the combined-feature models (decision C22; they need no unit model)."""
    combined = "combined" in units
    if "fused" in units:
        return ["foot", "waist"], True, combined
    return [u for u in ("foot", "waist") if u in units], False, combined


def as_names(values, name: str):
    """Decision B171: tasks / methods / units of the Python API as a list of names: a string is one name or
    comma-separated names, as the CLI's ``--methods svm,nn`` (``methods="svm"`` was read letter by letter); an
    object that is no name (an estimator) is one line. ``None`` stays ``None`` (the defaults)."""
    if values is None:
        return None
    if isinstance(values, str):
        values = values.split(",")
    bad = [type(v).__name__ for v in values if not isinstance(v, str)]
    if bad:
        own = (" (your own estimator trains on step_windows + make_features: docs/characterization.md)"
               if name == "method" else "")
        raise DataError(f"{name}s: give names, e.g. {name}s=['...'], not {', '.join(bad)} objects{own}")
    return [v.strip() for v in values if v.strip()]


def _check_choice(name: str, values: Sequence[str], allowed: Sequence[str]) -> list[str]:
    values = as_names(values, name)
    bad = [v for v in values if v not in allowed]
    if bad or not values:
        from pdrlearn.plugin_modules import PLUGIN_HINT

        hint = f"; {PLUGIN_HINT}" if name == "method" and bad else ""  # decision C121
        raise DataError(
            # decision B177: the parameter and the CLI flag, so the line fits train_user and `pdrlearn train`
            f"{name}s (--{name}s): unknown {name} {', '.join(bad) or '(none given)'}; choose from {', '.join(allowed)}"
            f"{hint}"
        )
    return values


def check_settings(
    *,
    tasks: Sequence[str] | None = None,
    methods: Sequence[str] | None = None,
    units: Sequence[str] | None = None,
    cv: int = 10,
    seed: int = 0,
    resample_hz: float | None = None,
) -> tuple[list[str], list[str], list[str]]:
    """Validate training settings before any data is read; returns the task, method and unit lists.

    ``None`` means all of :data:`TASKS` / :data:`DEFAULT_METHODS` / :data:`UNITS`; an empty list is an error.
    Raises :class:`DataError` naming the parameter and its CLI flag (``tasks (--tasks)`` ...) and the allowed values.
    """
    out = [
        _check_choice(name, (DEFAULT_METHODS if name == "method" else all_) if values is None else values, all_)
        for name, values, all_ in (("task", tasks, TASKS), ("method", methods, METHODS), ("unit", units, UNITS))
    ]
    if cv < 2:
        raise DataError(f"train: --cv {cv}; cross-validation needs at least 2 folds")
    if not 0 <= seed < 2**32:
        raise DataError(f"train: --seed {seed}; use an integer from 0 to 2**32 - 1")
    check_resample_hz(resample_hz)
    return out[0], out[1], out[2]


def few_steps_line(task: str, y: np.ndarray, classes: Sequence[str], chosen: tuple[str, str]) -> str | None:
    """Decision C75: one line when a class of a trained task has fewer than :data:`FEW_STEPS_PER_CLASS` labelled
    steps (None otherwise): its CV score rests on a handful of steps (trial 31: 6 backward of 189, the chosen
    nn/combined scored 91.7 % in CV and 56 % on held-out backward steps)."""
    counts = {c: int(np.sum(np.asarray(y) == c)) for c in classes}
    few = {c: n for c, n in counts.items() if 0 < n < FEW_STEPS_PER_CLASS}
    if not few:
        return None
    named = ", ".join(f"'{c}' has {n}" for c, n in few.items())
    alt = "" if chosen[0] in TEMPLATE_METHODS else (
        f"; or give the task the rule / template methods, e.g. --methods {task}={','.join(TEMPLATE_METHODS)} "
        "(decision C74)")
    return (f"task {task}: few labelled steps per class ({named} of {len(y)}; under {FEW_STEPS_PER_CLASS}, the "
            f"fewest the thesis calls sufficient, ch. 6.2.2): the chosen {chosen[0]}/{chosen[1]}'s CV score of that "
            f"class rests on them and may not hold on new walks; record at least {FEW_STEPS_PER_CLASS} steps of "
            f"each class{alt} (decision C75)")


def check_task_methods(task_methods: Mapping[str, Sequence[str]] | None,
                       tasks: Sequence[str] | None = None) -> dict[str, list[str]]:
    """Decision C74: per-task method lists (``--methods direction=fusion,heuristic``), checked as ``methods`` is
    (:func:`check_settings`): a known task, known methods, no empty list; ``{}`` for None. Decision C78: with
    ``tasks`` (the checked tasks to train), an entry for a task that is not trained is refused (it was ignored)."""
    out: dict[str, list[str]] = {}
    for task, methods in (task_methods or {}).items():
        if task not in TASKS:
            raise DataError(f"methods (--methods): unknown task {task!r} in {task}=...; choose from "
                            f"{', '.join(TASKS)} (decision C74)")
        if tasks is not None and task not in tasks:
            raise DataError(f"methods (--methods): {task}=... is for a task that is not trained (--tasks "
                            f"{','.join(tasks)}); add {task} to --tasks or drop {task}=... (decision C78)")
        out[task] = _check_choice("method", methods, METHODS)
    return out


#: decision B212: the fastest rate ``--resample HZ`` trains at (Hz): a ms clock's whole steps reach 1000 Hz
#: (B161's ``IMU_MS_MAX_HZ`` less its 10 % tolerance), above every IMU the project reads (PLASYS 20 Hz, thesis
#: ch.4.2.3; real 100 and 204.8 Hz; phones up to 500 Hz); ``--resample 1e6`` grew to 18.8 GB before it was killed
TRAIN_RESAMPLE_MAX_HZ = 1000.0


def check_resample_hz(resample_hz: float | None) -> None:
    """Decisions C56, B212: ``resample_hz`` (``--resample HZ``) is None or a rate from the 20 Hz the step detectors
    are validated at (:data:`~pdrlearn.io.plasys.MIN_VALIDATED_RATE_HZ`, decision B23, thesis ch.4.2.3) to
    :data:`TRAIN_RESAMPLE_MAX_HZ`; ``train`` and ``train-all`` check it before any data is read (decision C62),
    ``train_user`` again."""
    from pdrlearn.io.plasys import MIN_VALIDATED_RATE_HZ

    if resample_hz is None:
        return
    ok = isinstance(resample_hz, (int, float, np.number)) and not isinstance(resample_hz, bool)
    if not (ok and np.isfinite(resample_hz) and MIN_VALIDATED_RATE_HZ <= resample_hz <= TRAIN_RESAMPLE_MAX_HZ):
        shown = f"{resample_hz:g}" if ok else repr(resample_hz)
        raise DataError(f"train: --resample {shown}; give a rate from {MIN_VALIDATED_RATE_HZ:g} Hz (the "
                        f"slowest the step detectors are validated at, decision B23) to {TRAIN_RESAMPLE_MAX_HZ:g} Hz, "
                        "e.g. --resample 100")


def check_length_units(units: Sequence[str]) -> list[str]:
    """The length task's own units (decision C38), checked as ``units`` is; the error names ``length_units
    (--length-units)``."""
    try:
        return check_settings(units=units)[2]
    except DataError as exc:
        raise DataError(str(exc).replace("units (--units):", "length_units (--length-units):", 1)) from None


def train_task(
    data: TaskData,
    *,
    methods: Sequence[str],
    units: Sequence[str],
    cv: int,
    seed: int,
    advance: Callable[[int], None] = lambda n=1: None,
    soft_vote_methods: Sequence[str] | None = None,
    groups: np.ndarray | None = None,
    group_kind: str = "user",
    params: Mapping[str, Mapping[str, object]] | None = None,
) -> TaskModel:
    """Cross-validate and fit every method x unit of one task (see :func:`train_user`). ``soft_vote_methods``: the
    methods whose ``fused`` soft vote is trained when ``units`` has it (None: every method). ``groups``: the user
    of every step; folds then hold out whole users when there are two or more (decision C29); ``group_kind``
    ``"session"``: ``groups`` name each step's session, folds hold out whole sessions (decision C59); ``"block"``:
    contiguous blocks of each session (decision C95). ``params``: the estimators' settings (decision C96)."""
    from pdrlearn.features import TASK_CLASSES

    classes = np.asarray(TASK_CLASSES[data.task])
    tm = TaskModel(data.task, list(classes), n_steps=len(data.y), n_skipped_labels=data.n_skipped)
    per_unit, want_fused, want_combined = _split_units(units)
    subsets: dict[str, tuple[np.ndarray, list] | str] = {}  # unit -> (step mask, folds) or skip reason
    cv_users: dict[str, int] = {}  # unit -> users its folds hold out (0: stratified over steps, C29)
    notes: list[str] = []  # the folds' warnings, each logged once for the task (decision C36)
    fold_groups: dict[str, np.ndarray] = {}  # unit -> the user of each of its steps, when folds hold out users
    for unit in [*per_unit, *(["fused"] if want_fused else []), *(["combined"] if want_combined else [])]:
        mask = data.unit_mask(unit)
        if not mask.any():
            subsets[unit] = f"no session has the {unit} unit" if unit not in TWO_UNIT else "needs both units"
            continue
        try:
            check_classes(data, y=data.y[mask])
        except DataError as exc:
            subsets[unit] = f"steps with the {unit} unit: {exc}"
            continue
        folds, cv_users[unit] = _folds(data.y[mask], cv, seed, data.task,
                                       None if groups is None else groups[mask], notes=notes,
                                       kind=group_kind, times=None if data.times is None else data.times[mask],
                                       side=None if data.side is None else data.side[mask])
        if cv_users[unit] and group_kind != "block":  # folds of whole users: each names whom it held out (C43)
            fold_groups[unit] = groups[mask]
        subsets[unit] = (mask, folds)
    for line in dict.fromkeys(notes):
        log.warning(line)
    oof_by: dict[tuple[str, str], np.ndarray] = {}  # (method, unit) -> out-of-fold probabilities
    for method in sorted(methods, key=lambda m: m == "ensemble"):  # the ensemble reuses its members
        oof: dict[str, np.ndarray] = {}
        unit_list = ["fused"] if method == "fusion" else list(per_unit)
        if want_combined and can_combine(method):  # decisions C22, C123
            unit_list.append("combined")  # one model on both units' features (decision C22)
        elif want_combined and not per_unit and method != "fusion":
            tm.skipped.append(f"{method}/combined: only {' and '.join(COMBINED_METHODS)} have a combined-feature "
                              "model (decision C22; a plug-in: register_method(..., combined=True), C123)")
        for unit in unit_list:
            if unit == "fused" and not want_fused:
                continue
            if isinstance(subsets.get(unit), str):
                tm.skipped.append(f"{method}/{unit}: {subsets[unit]}")
                continue
            mask, folds = subsets[unit]
            X, y = data.X[mask], data.y[mask]
            t0 = time.perf_counter()
            if method == "ensemble":
                missing = [m for m in ENSEMBLE_MEMBERS if (m, unit) not in oof_by]
                if missing:
                    tm.skipped.append(f"ensemble/{unit}: needs {', '.join(missing)}/{unit} trained in the same run "
                                      f"(add {', '.join(missing)} to the methods)")
                    continue
                # equal-weight soft vote of the fitted members; CV = the same vote of their out-of-fold
                # probabilities (no weight is chosen on the folds, decision C14)
                w = np.full(len(ENSEMBLE_MEMBERS), 1.0 / len(ENSEMBLE_MEMBERS))
                P = soft_vote([oof_by[(m, unit)] for m in ENSEMBLE_MEMBERS], w)
                template = make_estimator(data.task, "ensemble", unit, seed=seed, params=params)
                est = fused_from_fitted(template.units, [tm.models[m][unit] for m in ENSEMBLE_MEMBERS], w,
                                        n_features_in=X.shape[1], random_state=seed)
                tm.models.setdefault(method, {})[unit] = est
                tm.cv.setdefault(method, {})[unit] = _cv_entry(
                    y, classes[P.argmax(1)], classes, folds, cv_users[unit], fold_groups.get(unit), group_kind,
                    cv_seconds=time.perf_counter() - t0)
                oof_by[(method, unit)] = P
                if mask.all():
                    oof[unit] = P
                advance(1)
                continue
            try:
                est = make_estimator(data.task, method, unit, seed=seed, params=params)
                est.fit(X, y)  # the final model first: fails fast on missing sensors
                template = make_estimator(data.task, method, unit, seed=seed, params=params)
                # C picked once by the final model's inner CV (decision C5) with folds of steps; with folds of
                # whole users / sessions each outer training fold picks its own C (nested, decision C57), so the
                # held-out group takes no part in choosing it
                if method == "svm" and not cv_users[unit]:
                    template.set_params(clf__C=est[-1].C_)
                P = _oof_proba(template, X, y, folds, classes)
            except MissingSensorError as exc:
                tm.skipped.append(f"{method}/{unit}: {exc}")
                log.info("task %s: skipped %s/%s: %s", data.task, method, unit, exc)
                continue
            except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
                # one method failing on these data (e.g. a degenerate rule threshold) must not stop the others
                tm.skipped.append(f"{method}/{unit}: failed ({type(exc).__name__}: {exc})")
                log.warning("task %s: %s/%s failed: %s: %s", data.task, method, unit, type(exc).__name__, exc)
                continue
            if mask.all() and unit in ("foot", "waist"):
                oof[unit] = P
            oof_by[(method, unit)] = P
            tm.models.setdefault(method, {})[unit] = est
            tm.cv.setdefault(method, {})[unit] = _cv_entry(
                y, classes[P.argmax(1)], classes, folds, cv_users[unit], fold_groups.get(unit), group_kind,
                cv_seconds=time.perf_counter() - t0)
            advance(1)
        if not want_fused or method in ("fusion", "heuristic") or (
            soft_vote_methods is not None and method not in soft_vote_methods
        ):
            continue
        if isinstance(subsets.get("fused"), str) or not {"foot", "waist"} <= set(tm.models.get(method, {})):
            tm.skipped.append(f"{method}/fused: needs a trained foot and waist model on the same steps")
            continue
        mask, folds = subsets["fused"]
        X, y = data.X[mask], data.y[mask]
        t0 = time.perf_counter()
        if not {"foot", "waist"} <= set(oof):  # the units were trained on other step sets: redo on these
            for unit in ("foot", "waist"):
                oof[unit] = _oof_proba(make_estimator(data.task, method, unit, seed=seed, params=params), X, y,
                                       folds, classes)
        # unit weights from the out-of-fold probabilities of the foot and waist models (decision in
        # docs/decisions/classifiers.md), then the fused CV score of that soft vote
        yi = np.array([list(classes).index(v) for v in y])
        w = best_weights([oof["foot"], oof["waist"]], yi)
        P = (fold_fitted_vote([oof["foot"], oof["waist"]], yi, folds) if cv_users["fused"]
             else soft_vote([oof["foot"], oof["waist"]], w))  # decision C57: nested with folds of groups
        template = make_estimator(data.task, method, "fused", seed=seed, weights=w, params=params)
        fitted = [tm.models[method][u] for u in ("foot", "waist")]
        if subsets["foot"][0].sum() != mask.sum() or subsets["waist"][0].sum() != mask.sum():
            fitted = [clone(e).fit(X, y) for _, e, _ in template.units]  # units were fitted on other steps
        tm.models[method]["fused"] = fused_from_fitted(
            template.units, fitted, w, n_features_in=X.shape[1], random_state=seed
        )
        tm.fusion_weights[method] = [float(v) for v in w]
        tm.cv[method]["fused"] = _cv_entry(
            y, classes[P.argmax(1)], classes, folds, cv_users["fused"], fold_groups.get("fused"), group_kind,
            weights={"foot": float(w[0]), "waist": float(w[1])}, cv_seconds=time.perf_counter() - t0)
        advance(1)
    # decision C16: every leaf model keeps the range of its own inputs over its training steps (units first,
    # so that fused/ensemble members fitted on the unit's steps keep that range)
    for unit in sorted(subsets, key=lambda u: u == "fused"):
        if isinstance(subsets[unit], str):
            continue
        for per in tm.models.values():
            if unit in per:
                attach_ranges(per[unit], data.X[subsets[unit][0]])
                attach_joint(per[unit], data.X[subsets[unit][0]], data.y[subsets[unit][0]])  # decision C71
                attach_class_ranges(per[unit], data.X[subsets[unit][0]], data.y[subsets[unit][0]])  # steps 96
    tm.chosen = best_pair(tm.ranking(), tm.one_unit_votes())  # decisions C8, C124
    if tm.chosen is None:
        raise DataError(f"task {data.task}: no method could be trained ({'; '.join(tm.skipped)})")
    return tm


def _no_labels_message(task: str, sessions) -> str:
    """Why ``task`` has no labels and how to get them. Stride lengths (``length_m``) without classes read
    as if the lengths were ignored: say that the classes are a column of their own, which pdrlearn does
    not derive from the lengths (thesis ch. 6.3: the user's short/normal/long classes come from calibration
    exercises walked that way; docs/decisions/simulator.md S2), and what ``length_m`` is used for."""
    column = {"length": "length_class"}.get(task, task)
    msg = f"task {task}: no session has {task} labels; label the steps ('{column}' column) or drop the task"
    has_lengths = any(s.steps is not None and "length_m" in s.steps.columns and s.steps["length_m"].notna().any()
                      for s in sessions)
    if task != "length" or not has_lengths:
        return msg
    return ("task length: no session has length labels: the steps have stride lengths ('length_m', used by the "
            "distance calibration, decision L26) but no 'length_class' column; pdrlearn does not derive the "
            "user's short/normal/long classes from 'length_m' (thesis ch. 6.3: they come from calibration "
            "exercises walked short, normal and long) -- add 'length_class' (short, normal or long per step) to "
            "steps.csv, or drop the task (--tasks terrain,direction)")


def length_class_bounds(sessions) -> list[float] | None:
    """The user's stride-length class edges ``[short/normal, normal/long]`` (m), used by M3's clamp.

    Thesis ch.6.3: the short/normal/long intervals "must be defined from a set of exercises for a
    pedestrian in specific". Taken from the sessions' ``meta.json`` (``length_class_bounds_m``, as the
    simulator and a calibration protocol record them; the median when sessions differ); otherwise derived
    from the labelled steps that have both ``length_m`` and ``length_class``: each edge is the midpoint
    between the neighbouring classes' median lengths. ``None`` when neither is available.
    """
    declared = [s.meta.get("length_class_bounds_m") for s in sessions]
    declared = [b for b in declared if isinstance(b, list | tuple) and len(b) == 2]
    if declared:
        lo, hi = np.median(np.asarray(declared, dtype=float), axis=0)
        return [float(lo), float(hi)]
    frames = [s.steps[["length_m", "length_class"]] for s in sessions
              if s.steps is not None and {"length_m", "length_class"} <= set(s.steps.columns)]
    if not frames:
        return None
    df = pd.concat(frames).dropna()
    med = df.groupby("length_class")["length_m"].median()
    if not {"short", "normal", "long"} <= set(med.index):
        return None
    lo, hi = (med["short"] + med["normal"]) / 2, (med["normal"] + med["long"]) / 2
    return [float(lo), float(hi)] if 0 < lo < hi else None


def session_rates(sessions) -> dict[str, dict[str, float]]:
    """Sensor -> {session name -> its recorded rate (Hz, 3 decimals)} over ``sessions``."""
    out: dict[str, dict[str, float]] = {}
    for s in sessions:
        for name, st in s.streams.items():
            if len(st) > 1 and np.isfinite(float(st.rate_hz)):
                out.setdefault(name, {})[s.where] = round(float(st.rate_hz), 3)
    return out


def mixed_rates(recorded: dict[str, dict[str, float]]) -> dict[str, dict[float, list[str]]]:
    """The sensors of :func:`session_rates` whose rates differ between sessions (beyond the tolerance of
    :func:`~pdrlearn.kernels.distance.rate_differs`): sensor -> {rate -> sessions}."""
    from pdrlearn.kernels.distance import rate_differs

    out = {}
    for name, by in recorded.items():
        lo, hi = min(by.values()), max(by.values())
        if rate_differs(lo, hi):
            groups: dict[float, list[str]] = {}
            for where, r in by.items():
                groups.setdefault(r, []).append(where)
            out[name] = dict(sorted(groups.items()))
    return out


def session_list(sessions, caller: str = "train_user") -> list:
    """One :class:`pdrlearn.io.Session` as a list of one (``training_data(session)``, ``train_user(session)``; review
    R4: a TypeError before), else the sessions as a list. Decision B391: a path (``str`` / ``os.PathLike``), alone or
    in the list, is read as ``pdrlearn train`` reads it (a session folder, or a folder of sessions:
    :func:`pdrlearn.session_dirs.find_session_dirs`; otherwise one :class:`DataError` naming the path); anything else
    that is not a session is :func:`pdrlearn.io.session.as_session`'s one line naming ``caller`` (decision B395: a
    single non-iterable value and a bytes path too)."""
    import os

    from pdrlearn.io import Session
    from pdrlearn.io.session import as_session
    from pdrlearn.session_dirs import read_session_dirs

    if isinstance(sessions, Session | str | os.PathLike | bytes | bytearray):
        sessions = [sessions]
    elif sessions is not None and not hasattr(sessions, "__iter__"):  # decision B395: `train_user(5)` was a
        as_session(sessions, caller)  # TypeError traceback ("'int' object is not iterable"): the one line
    out = []
    for s in sessions or []:
        if isinstance(s, str | os.PathLike):
            out.extend(read_session_dirs([s]))  # decision B391 (a raw AttributeError before)
        else:
            out.append(as_session(s, caller))
    return out


def one_rate(sessions, recorded: dict[str, dict[str, float]], resample_hz: float | None,
             who: str = "train") -> list:
    """Decision C56: the sessions at one rate per sensor. ``resample_hz``: every stream resampled to it (one
    warning naming the recorded rates when they differ); None: sessions at different rates are a one-line
    :class:`DataError` (B197) naming the rates, the sessions and ``--resample HZ`` (a model holds one rate per
    sensor: its manifest, the rate warnings of track / evaluate and the distance calibration all read it)."""
    mixed = mixed_rates(recorded)
    if resample_hz is None:
        if mixed:
            name, groups = next(iter(mixed.items()))
            said = "; ".join(f"{r:g} Hz: {w[0]}{f' and {len(w) - 1} more' if len(w) > 1 else ''}"
                             for r, w in groups.items())
            raise DataError(f"{who}: the sessions were recorded at different rates ({name} {said}); a model is "
                            f"trained at one rate: pass --resample HZ (e.g. --resample {max(groups):g}; from the "
                            f"API resample_hz={max(groups):g}) to resample every session to it, or train the rates "
                            "apart")
        return list(sessions)
    check_resample_hz(resample_hz)
    from pdrlearn.io.resample import resample_session

    if mixed:
        name, groups = next(iter(mixed.items()))
        log.warning("train: the sessions were recorded at %s Hz (%s); every stream resampled to %g Hz",
                    " / ".join(f"{r:g}" for r in groups), name, resample_hz)
    return [resample_session(s, dict.fromkeys(s.streams, float(resample_hz))) for s in sessions]


#: decision C53: train_user's warning when the labels allow no classifier and the model holds only the user's
#: distance calibration (decision C17)
NO_CLASSIFIER_LINE = ("no classifier trained (the labels allow none); the model holds the distance calibration: "
                      "tracking with it (`pdrlearn track SESSION --model DIR`, model=) applies it, the class rules "
                      "as without a model")


def train_user(
    sessions,
    *,
    tasks: Sequence[str] | None = None,
    methods: Sequence[str] | None = None,
    units: Sequence[str] | None = None,
    cv: int = 10,
    seed: int = 0,
    n_samples: int = 40,
    boundaries: str = "given",
    user: str | None = None,
    strict: bool | None = None,
    distance_calibration: bool = True,
    advance: Callable[[int], None] = lambda n=1: None,
    cv_groups: str = "steps",
    length_units: Sequence[str] | None = None,
    resample_hz: float | None = None,
    task_methods: Mapping[str, Sequence[str]] | None = None,
    params: Mapping[str, Mapping[str, object]] | None = None,
) -> UserModel:
    """Train a user's step classifiers from labelled sessions.

    Parameters
    ----------
    sessions : labelled :class:`~pdrlearn.io.Session` objects (``steps`` with ``start_s``/``end_s`` and
        ``terrain`` / ``direction`` / ``length_class`` labels).
    tasks, methods, units : subsets of :data:`TASKS`, :data:`METHODS`, :data:`UNITS` (default: all tasks
        and units, the thesis' five methods :data:`DEFAULT_METHODS`); ``fused`` also trains the foot and
        waist models it combines; ``combined`` trains svm and nn on the thesis' feature vector of both units
        (decision C22); with ``units`` left at None the combined models replace the svm and nn soft votes
        (decision C23: dtw, heuristic fusion and ensemble keep their ``fused`` model), units named explicitly
        train every soft vote they allow; ``ensemble`` (opt-in, decision C14) is the equal-weight soft vote of
        the unit's nn, svm and dtw models and needs them in the same run.
    length_units : units of the length task only (default None: ``units``); named, they train every soft vote
        they allow, e.g. ``("foot", "waist", "fused")``: the length task as before C22 (no combined model, C8
        chooses among the soft votes), terrain and direction as ``units`` (decision C38).
    task_methods : per-task methods, e.g. ``{"direction": ["fusion", "heuristic"]}``: those tasks train (and
        choose among) these methods, the others ``methods`` (decision C74; ``--methods direction=fusion,...``).
    cv : folds of the stratified cross-validation that scores every model (thesis ch. 6: 10-fold);
        reduced to the smallest class size when a class has fewer steps.
    cv_groups : ``"steps"`` (default): stratified folds of steps, pooled over the sessions; ``"user"``: when the
        sessions come from two or more users (:func:`session_user`), folds of whole users (leave-one-user-out
        with at most ``cv`` users), so a model is scored on users it was not fitted on (decision C29); one user,
        or a session without a user in its meta.json: stratified folds as with ``"steps"``.
        ``"session"``: folds of whole sessions (decision C59); ``"block"``: each session's steps cut into ``cv``
        contiguous blocks in walking order, fold k holds out block k of every session and leaves the neighbouring
        step on each side out of training (decision C95; works with one session per exercise).
    seed : seed of the folds, the DTW reference choice and the network initialisation.
    n_samples : samples per resampled step window.
    boundaries : ``"given"`` (default) cuts each step at its labelled ``start_s``/``end_s``; ``"rest"``
        moves each boundary to the foot's quietest sample within 0.3 s first, so steps labelled at other
        gait phases (motion-capture events, a converter's detection) become rest-to-rest windows
        (:func:`pdrlearn.features.windows.rest_boundaries`). Stored in ``settings``; prediction and
        evaluation cut windows the same way (decision C13).
    strict : raise on a task without labels / with a missing class. Default: strict when ``tasks`` is
        given explicitly; otherwise such tasks are skipped, listed in ``UserModel.skipped`` and logged (one
        warning each, decision C53; with no task left the model holds only the distance calibration, one more
        warning, or :class:`DataError` when there is none either).
    params : the built-in estimators' hyperparameters, ``{"svm": {"C": 10.0}, "nn": {"hidden": 32}}`` (decision
        C96, ``train --param``; names and checks: :data:`pdrlearn.classify.hyper.HYPERPARAMETERS`; decision C139:
        also ``{"heuristic": {"thresholds": "thesis"}, "dtw": {"rule": "spread"}}``); stored in
        ``settings["params"]``. None: the thesis defaults.
    resample_hz : resample every stream of every session to this rate (Hz) first, by the runtime's resampler
        (:func:`pdrlearn.io.resample.resample_session`); needed when the sessions were recorded at different rates
        (decision C56: without it that is a one-line :class:`DataError`, B197). The recorded rates are kept in
        ``data_summary["recorded_rates_hz"]``.
    distance_calibration : estimate the user's distance gain from the sessions' labelled stride lengths
        (:func:`pdrlearn.displace.calibrate_distance`, docs/decisions/localization.md L26), stored in
        ``data_summary["distance_calibration"]`` and used by PLASYS M3 with this model.
    user : the name the model stores (decision E174): it replaces every user name the sessions' meta.json gives,
        in ``user``, ``data_summary["users"]`` and the CV folds' held-out users (several users: ``user-1``,
        ``user-2``, ...), so a pseudonym hides the subject everywhere; blank is refused (B339). None: the
        sessions' own name (:func:`default_user`).

    Returns
    -------
    :class:`UserModel` with, per task, the fitted models, CV metrics and the chosen two-unit model (the best
    balanced CV accuracy among the fused and combined models, or among all when only one unit was trained).
    """
    import pdrlearn
    from pdrlearn.buildinfo import created_utc

    sessions = session_list(sessions)
    if not sessions:
        raise DataError("train: no sessions given; pass at least one labelled session folder")
    user = check_user(user)  # decision B339
    strict = (tasks is not None) if strict is None else strict
    # decision C23: by default the combined feature vector replaces the soft vote of the svm and nn unit models;
    # units named explicitly (e.g. "foot,waist,fused,combined") train every soft vote they allow
    tasks, methods, units = (as_names(v, n) for v, n in ((tasks, "task"), (methods, "method"), (units, "unit")))
    named_units = units is not None
    tasks, methods, units = check_settings(tasks=tasks, methods=methods, units=units, cv=cv, seed=seed)
    own_methods = check_task_methods(task_methods, tasks)  # decisions C74, C78
    params = check_params(params, [*methods, *(m for t in tasks for m in own_methods.get(t, ()))],  # decision C96
                          plugin_factories())  # decision C122
    for m, kw in params.items():  # decision C122 (review R4): a factory refusing a --param fails here, in one line,
        if kw and m in plugin_factories():  # not later as one skipped model per unit
            _call_factory(plugin_factories()[m], m, tasks[0], "foot", seed, kw)

    def voted_of(ms):  # decision C23's soft votes of a method list (None: units named, every soft vote)
        return None if named_units else [m for m in ms if m not in COMBINED_METHODS]

    voted = voted_of(methods)
    if length_units is not None:  # decision C38: the length task's own units (named: every soft vote they allow)
        length_units = check_length_units(length_units)
    from pdrlearn.features.windows import BOUNDARIES

    if boundaries not in BOUNDARIES:
        raise DataError(f"train: boundaries {boundaries!r}; choose one of {', '.join(BOUNDARIES)}")
    if cv_groups not in CV_GROUPS:
        raise DataError(f"train: --cv-groups {cv_groups!r}; choose one of {', '.join(CV_GROUPS)}")
    ids = [s.content_id() for s in sessions]  # decision B87: before anything reads the streams
    recorded = session_rates(sessions)
    sessions = one_rate(sessions, recorded, resample_hz)  # decision C56
    from pdrlearn.classify.force_scale import training_force

    # decision C153: the force unit and level the force features are fitted on; C155: mixed units refused here,
    # before any fit
    force = training_force(sessions)
    windows = session_windows(sessions, n_samples=n_samples, boundaries=boundaries)
    users = [session_user(s) for s in sessions]
    named = sorted({u for u in users if u is not None})  # the users the sessions name (decision C35)
    # decision E174: a given name replaces every user name the model stores (data users, CV folds, the warning)
    rename = user_pseudonyms(named, user)
    users = [rename.get(u, u) for u in users]
    named = sorted({rename.get(u, u) for u in named})
    n_users = 0
    if cv_groups == "user":
        if None in users:
            log.warning("train: --cv-groups user: %s names no user (meta.json 'user' or 'subject'); "
                        "stratified folds over steps", sessions[users.index(None)].where)
            users = []
        else:
            n_users = len(set(users))
            if n_users < 2:  # decision C35: say the fallback, the header alone read "10-fold CV"
                log.warning("train: --cv-groups user: every session is of one user (%s); stratified folds over "
                            "steps instead (folds of whole users need two or more)", named[0])
    elif cv_groups == "session":  # decision C59: folds of whole sessions (the steps of one walk stay together)
        users = [s.name for s in sessions]
        if len(set(users)) < len(users):
            users = [s.where for s in sessions]
        n_users = len(sessions)
        if n_users < 2:
            log.warning("train: --cv-groups session: one session; stratified folds over steps instead (folds of "
                        "whole sessions need two or more)")
    if cv_groups != "user" and len(named) > 1:  # decision C35: pooled users; folds score on users fitted on
        cal = ("; the distance calibration pools their strides into one gain (--no-distance-calibration for a "
               "pooled model)" if distance_calibration else "")
        log.warning("train: the sessions come from %d users (%s): the CV folds mix their steps, so a model is "
                    "scored on users it was fitted on (optimistic for a new user); --cv-groups user scores on "
                    "held-out users%s", len(named), ", ".join(named), cal)
    out: dict[str, TaskModel] = {}
    skipped: list[str] = []
    datas: dict[str, TaskData] = {}
    for task in tasks:
        data = datas[task] = task_data(windows, task, sessions)  # logs its gap steps once (B13)
        try:
            if data is None:
                raise DataError(_no_labels_message(task, sessions))
            check_classes(data)
        except DataError as exc:
            if strict:
                raise
            skipped.append(str(exc))
            continue
        groups = np.asarray(users, dtype=object)[data.session] if n_users >= 2 else None  # decision C29
        if cv_groups == "block":  # decision C95: the folds cut each session's steps into contiguous blocks
            groups = data.session
        own = task == "length" and length_units is not None  # decision C38
        ms = own_methods.get(task, methods)  # decision C74
        out[task] = train_task(data, methods=ms, units=length_units if own else units, cv=cv, seed=seed,
                               advance=advance, soft_vote_methods=None if own else voted_of(ms), groups=groups,
                               group_kind=cv_groups if cv_groups in ("session", "block") else "user", params=params)
        from pdrlearn.classify.uncovered import trained_kinds

        out[task].trained_kinds = trained_kinds(task, data, windows)  # decision C161: side steps seen in training
        few = out[task].chosen and few_steps_line(task, data.y, out[task].classes, out[task].chosen)  # C75
        if few:
            log.warning("train: %s", few)
    calibration = None
    if distance_calibration:  # per-user distance gain from the labelled stride lengths (localization L26)
        from pdrlearn.displace.calibration import calibrate_distance

        calibration = calibrate_distance(sessions)
        from pdrlearn.classify.calibration_note import calibration_skipped_line

        skipped_cal = calibration_skipped_line(calibration, sessions)  # decision C154: said, not only stored
        if skipped_cal:
            log.warning("%s", skipped_cal)
    if not out and (calibration is None or calibration.get("reason")):
        # decision C17: a model without classifiers is worth writing only for its distance calibration
        why = ("distance calibration off" if calibration is None
               else f"no distance calibration either: {calibration['reason']}")
        if not any(s.has("fAccelerometer") for s in sessions):  # decision B47: say where a waist user calibrates
            why += (" (train's distance calibration is the foot pipeline's; a lower-back-only recording "
                    "calibrates its step length with 'pdrlearn calibrate DIR --distance METERS', or with the "
                    "reference walking bouts of bouts.csv)")
        raise DataError("train: nothing to train; " + " | ".join(skipped) + f" | {why}")
    for line in skipped:  # decision C53: the API says what the CLI printed (after the error above, which lists them)
        log.warning("train: skipped %s", line)
    if not out:  # decision C53 (C17 kept): a calibration-only model is a warning, not an error
        log.warning("train: %s", NO_CLASSIFIER_LINE)
    elif all(tm.chosen and tm.chosen[1] == "waist" for tm in out.values()):  # decision C77
        log.warning("train: %s", WAIST_ONLY_MODEL_LINE)
    by_task, used = cv_groups_used(out, cv_groups)  # decision B210
    rates: dict[str, float] = {}
    for s in sessions:
        for name, st in s.streams.items():
            rates.setdefault(name, round(float(st.rate_hz), 3))
    summary = {"sessions": [s.name for s in sessions], "session_ids": ids, "n_sessions": len(sessions), "steps": {},
               "users": named}  # every user the sessions name (decision C35)
    if resample_hz is not None:  # decision C56: the rates the sessions were recorded at, before resampling
        summary["recorded_rates_hz"] = {n: sorted(set(v.values())) for n, v in recorded.items()}
        summary["resampled_hz"] = float(resample_hz)
    bounds = length_class_bounds(sessions)
    if bounds is not None:
        summary["length_bounds_m"] = bounds
    if calibration is not None:
        summary["distance_calibration"] = calibration
    if force is not None:
        summary["force"] = force
    for t, m in out.items():
        data = datas[t]
        summary["steps"][t] = {
            "n_steps": m.n_steps,
            "n_skipped_labels": m.n_skipped_labels,
            "per_class": {c: int(np.sum(data.y == c)) for c in m.classes},
        }
    return UserModel(
        # decision C35: a model pooled over users is not the first user's ("pooled: <users>")
        user=user if user is not None else default_user(sessions, UNNAMED_USER),
        tasks=out,
        n_samples=n_samples,
        sampling_rate_hz=rates,
        data_summary=summary,
        settings={
            "cv": cv,
            # decision B210: the grouping the folds used ("steps" when every task fell back to stratified folds),
            # what was asked, and each task's
            "cv_groups": used,
            "cv_groups_asked": cv_groups,
            "cv_groups_by_task": by_task,
            # users in the training data when grouped by user (decision C29); sessions when by session (C59)
            "cv_users": n_users if cv_groups == "user" and used != "steps" else 0,
            **({"cv_sessions": n_users if used != "steps" else 0} if cv_groups == "session" else {}),
            # decisions C95, C114: the block folds used (the most any task's models used; each model records its
            # own, fewer than --cv when no session has cv labelled steps) and the number asked (--cv)
            **({"cv_blocks": blocks_used(out) if used != "steps" else 0, "cv_blocks_asked": cv}
               if cv_groups == "block" else {}),
            "seed": seed,
            "methods": list(methods),
            **({"task_methods": own_methods} if own_methods else {}),  # decision C74
            "params": stored(params),  # decision C96: the hyperparameters given (--param), {} = the defaults
            # decision C121 (amended, review R4): each trained plug-in method's module, file and sha256
            **({"plugins": plugins} if (plugins := plugin_records([*methods, *(
                m for ms in own_methods.values() for m in ms)])) else {}),
            "units": list(units),
            "length_units": length_units,  # the length task's own units, None = "units" (decision C38)
            # methods whose unit fused model was trained (soft vote; heuristic fusion); None = every method (C23)
            "fused_methods": None if voted is None else [m for m in methods if m in voted],
            "min_steps_per_class": MIN_STEPS_PER_CLASS,
            "boundaries": boundaries,
            "package_version": pdrlearn.__version__,
        },
        created=created_utc(),  # decision E159: SOURCE_DATE_EPOCH when set
        skipped=skipped,
    )


__all__ = [
    "TASKS",
    "METHODS",
    "BUILTIN_METHODS",
    "register_method",
    "DEFAULT_METHODS",
    "UNITS",
    "TWO_UNIT",
    "COMBINED_METHODS",
    "MIN_STEPS_PER_CLASS",
    "DTW_SIGNALS",
    "make_estimator",
    "train_user",
    "train_task",
    "training_data",
    "TrainingData",
    "session_user",
    "CV_GROUPS",
    "UserModel",
    "TaskModel",
    "class_metrics",
    "PdrlearnError",
]
