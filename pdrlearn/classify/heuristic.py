"""Heuristic rule-table step classifiers (thesis ch. 6.1.2.1, 6.1.2.3, 6.2.2.1, 6.2.2.3, 6.3.2.1, 6.3.2.3).

Every classifier is a rule table (:class:`pdrlearn.classify._rules.Rule`: feature, cut points, class of
each interval, weight) evaluated stage by stage with thesis eq. 28; the per-task classes below only
declare their tables. Inputs are step windows (:func:`pdrlearn.features.step_windows`; a StepWindows
or its 3-D array), or a 2-D matrix of the table's rule features (:attr:`feature_names_`).

- :class:`HeuristicTerrainClassifier` (unit foot|waist): stage 1 flat vs stairs (Tables 22-24 rules 1-3),
  stage 2 up vs down on stairs (foot acc 4-8, foot gyro 4-6, waist acc 4-6).
- :class:`HeuristicDirectionClassifier` (unit foot|waist): thesis eq. 31 on the forward acceleration.
- :class:`HeuristicLengthClassifier` (unit foot|waist): Tables 29-30 (foot) / Table 31 (waist).
- :class:`HeuristicFusionClassifier` (task): all units' rules with the fusion weights of Table 26
  (terrain) and Table 32 (length); direction = decision fusion of eq. 31 weighted by eq. 32 x
  0.6 (foot) / 0.4 (waist).

``fit`` learns the rules' cut points from the user's labelled calibration steps - the thesis says its
thresholds depend on the pedestrian (ch. 6.1.3, 6.3) and were set from calibration exercises; the
weights and rule structure stay the thesis'. ``thresholds="learn"``: each rule's cut points (and, when
the data says so, the order of its intervals) maximise that rule's own balanced accuracy;
``"joint"`` (default): then coordinate ascent on the stage's rounded result ``R`` (all rules together);
``"thesis"``: the documents' thresholds (converted to SI units and seconds, docs/decisions/features.md).
With ``bands=True`` (default) a two-class rule may, when learning, hold one class inside a band
``[t1, t2]`` instead of beyond one cut point, if that gains >= 5 points of balanced accuracy for the rule
(e.g. the minimum vertical foot acceleration: flat strides lie between up and down); ``bands=False``
keeps the thesis' one-sided rule shape.

``weights="skill"`` (option, not the thesis) scales each thesis weight by the rule's chance-corrected
balanced accuracy on the training steps (``max(0, 2 * bacc - 1)``), so rules that do not separate a
user's classes stop voting.

``predict`` follows the thesis: each stage's ``R`` is rounded to the nearest class. ``predict_proba``
gives triangular memberships of ``R`` to the class values, multiplied along the two terrain stages; its
columns follow :attr:`classes_`, all the task's classes sorted as scikit-learn sorts labels
(``np.unique``: terrain ``down, flat, up``), so probability scorers (``roc_auc_ovr``, ``neg_log_loss``)
read the right columns (decision C19).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.utils.validation import check_is_fitted

from pdrlearn.classify._rules import (
    Rule,
    combine_stages,
    learn_thresholds,
    memberships,
    refine_jointly,
    rule_skill,
    stage_score,
)
from pdrlearn.errors import DataError
from pdrlearn.features.rules import RuleFeatures
from pdrlearn.features.transformers import as_windows
from pdrlearn.features.windows import TASK_CLASSES, StepWindows

log = logging.getLogger(__name__)

THESIS_RATE_HZ = 20.0  # PLASYS period 50 ms (thesis ch. 4.2.3; waist also 20 Hz, ch. 4.3): thesis counts -> s
WAIST_COUNT_RATE_HZ = 100.0  # Table 31 counts (75, 110 samples) read as 100 Hz phone samples (decision)


def _s(samples: float, rate: float = THESIS_RATE_HZ) -> float:
    """Thesis sample count -> seconds (sums of samples -> time integrals use the same factor)."""
    return samples / rate


# -- rule tables -------------------------------------------------------------------------------------
# Rule(sensor, number, feature, thresholds, classes, weight, upper_closed, source); upper_closed as printed
# in each thesis table row (True: ``<= t`` is the lower class), pinned at every cut point by
# tests/test_heuristic.py::test_thesis_tables_closure_at_every_cut_point
# Terrain: C1 = 1 normal (flat), C2 = 2 stairs; C3 = 3 ascending (up), C4 = 4 descending (down).

TERRAIN_STAGE1 = [
    Rule("foot_acc", 1, "foot_acc_v:min", (-5.0,), (1, 2), 0.20, False, "thesis Table 22 #1"),
    Rule("foot_acc", 2, "foot_acc_v:abs_peak_asym", (3.0,), (1, 2), 0.20, True, "thesis Table 22 #2"),
    Rule("foot_acc", 3, "foot_acc_v:abs_dt_peaks", (_s(10),), (1, 2), 0.20, True, "thesis Table 22 #3"),
    Rule("foot_gyr", 1, "foot_pitch:min", (-10.0,), (1, 2), 0.20, False, "thesis Table 23 #1"),
    Rule("foot_gyr", 2, "foot_pitch:abs_dt_peaks", (_s(14),), (1, 2), 0.10, False, "thesis Table 23 #2"),
    Rule("foot_gyr", 3, "foot_pitch:pos_minus_neg", (0.0,), (2, 1), 0.10, False, "thesis Table 23 #3"),
    Rule("waist_acc", 1, "waist_acc_v:abs_dt_peaks", (_s(20),), (2, 1), 0.40, True, "thesis Table 24 #1"),
    Rule("waist_acc", 2, "waist_acc_v:t_min", (_s(15),), (1, 2), 0.30, True, "thesis Table 24 #2"),
    Rule("waist_acc", 3, "waist_acc_v:pos_minus_neg", (0.0,), (2, 1), 0.30, False, "thesis Table 24 #3"),
]
TERRAIN_STAGE2 = [
    Rule("foot_acc", 4, "foot_acc_v:max", (7.0,), (4, 3), 0.10, True, "thesis Table 22 #4"),
    Rule("foot_acc", 5, "foot_acc_v:abs_dt_peaks", (_s(9),), (3, 4), 0.05, True, "thesis Table 22 #5"),
    Rule("foot_acc", 6, "foot_acc_v:sum_neg", (_s(20),), (4, 3), 0.20, True, "thesis Table 22 #6"),
    Rule("foot_acc", 7, "foot_acc_v:sum_pos", (_s(25),), (4, 3), 0.25, True, "thesis Table 22 #7"),
    Rule("foot_acc", 8, "foot_acc_v:range", (10.0,), (4, 3), 0.05, True, "thesis Table 22 #8"),
    Rule("foot_gyr", 4, "foot_pitch:max", (6.0,), (4, 3), 0.15, True, "thesis Table 23 #4"),
    Rule("foot_gyr", 5, "foot_pitch:peak_asym", (0.0,), (4, 3), 0.05, True, "thesis Table 23 #5"),
    Rule("foot_gyr", 6, "foot_pitch:sum_pos", (_s(35),), (4, 3), 0.15, True, "thesis Table 23 #6"),
    Rule("waist_acc", 4, "waist_acc_v:t_max", (_s(20),), (4, 3), 0.35, False, "thesis Table 24 #4"),
    Rule("waist_acc", 5, "waist_acc_v:max", (0.7,), (4, 3), 0.30, True, "thesis Table 24 #5"),
    Rule("waist_acc", 6, "waist_acc_v:pos_minus_neg", (0.0,), (4, 3), 0.35, True, "thesis Table 24 #6"),
]
# Heuristic fusion weights, thesis Table 26: (sensor, feature number) -> weight.
TERRAIN_FUSION_WEIGHTS = {
    ("foot_acc", 1): 0.125, ("foot_acc", 2): 0.15, ("foot_acc", 3): 0.125, ("foot_acc", 4): 0.05,
    ("foot_acc", 5): 0.05, ("foot_acc", 6): 0.15, ("foot_acc", 7): 0.20, ("foot_acc", 8): 0.05,
    ("foot_gyr", 1): 0.10, ("foot_gyr", 2): 0.05, ("foot_gyr", 3): 0.05, ("foot_gyr", 4): 0.11,
    ("foot_gyr", 5): 0.03, ("foot_gyr", 6): 0.11,
    ("waist_acc", 1): 0.15, ("waist_acc", 2): 0.125, ("waist_acc", 3): 0.125, ("waist_acc", 4): 0.09,
    ("waist_acc", 5): 0.07, ("waist_acc", 6): 0.09,
}

# Direction: C1 = 1 forward, C2 = 2 backward; thesis eq. 31 (first half sum > second half sum -> forward).
DIRECTION_RULES = [
    Rule("foot_acc", 1, "foot_acc_fwd:half_balance", (0.0,), (2, 1), 1.0, True, "thesis eq. 31",
         confidence="foot_acc_fwd:step_probability"),
    Rule("waist_acc", 1, "waist_acc_fwd:half_balance", (0.0,), (2, 1), 1.0, True, "thesis eq. 31",
         confidence="waist_acc_fwd:step_probability"),
]
DIRECTION_FUSION_WEIGHTS = {("foot_acc", 1): 0.6, ("waist_acc", 1): 0.4}  # thesis ch. 6.2.2.3

# Length: C1 = 1 short, C2 = 2 normal, C3 = 3 long; C2.5 = normal-or-long (thesis ch. 6.3.2.1).
LENGTH_RULES = [
    Rule("force", 1, "force:air_time", (_s(17), _s(21)), (1, 2, 3), 0.10, False, "thesis Table 29 #1"),
    Rule("force", 2, "force:time_to_peak", (_s(4), _s(7)), (3, 2, 1), 0.07, False, "thesis Table 29 #2"),
    Rule("force", 3, "force:peak_mean_4", (85.0,), (1, 2.5), 0.10, False, "thesis Table 29 #3"),
    Rule("force", 4, "force:contact_force_2", (90.0,), (1, 2.5), 0.10, False, "thesis Table 29 #4"),
    Rule("foot_acc", 1, "foot_acc_fwd:range", (6.5, 9.0), (1, 2, 3), 0.05, True, "thesis Table 30 #1"),
    # thesis Table 30 #2: <= 9 -> C1, > 9 & < 12 -> C2, >= 12 -> C3: the two cuts close differently
    # (features decision 15)
    Rule("foot_acc", 2, "foot_acc_fwd:abs_dt_peaks", (_s(9), _s(12)), (1, 2, 3), 0.50, (True, False),
         "thesis Table 30 #2"),
    Rule("foot_acc", 3, "foot_acc_fwd:range_x_air_time", (_s(135), _s(190)), (1, 2, 3), 0.08, False,
         "thesis Table 30 #3"),
    Rule("waist_gyr", 1, "waist_yaw:amplitude", (0.45, 0.60), (1, 2, 3), 0.40, True, "thesis Table 31 #1"),
    Rule("waist_gyr", 2, "waist_yaw:left_minus_right", (0.0,), (2.5, 1), 0.30, True, "thesis Table 31 #2"),
    Rule("waist_gyr", 3, "waist_yaw:left", (_s(75, WAIST_COUNT_RATE_HZ), _s(110, WAIST_COUNT_RATE_HZ)),
         (1, 2, 3), 0.30, True, "thesis Table 31 #3"),
]
# Heuristic fusion weights, thesis Table 32.
LENGTH_FUSION_WEIGHTS = {
    ("force", 1): 0.03, ("force", 2): 0.02, ("force", 3): 0.03, ("force", 4): 0.03,
    ("foot_acc", 1): 0.02, ("foot_acc", 2): 0.30, ("foot_acc", 3): 0.02,
    ("waist_gyr", 1): 0.25, ("waist_gyr", 2): 0.15, ("waist_gyr", 3): 0.15,
}

DIRECTION_LABELS = {1.0: "forward", 2.0: "backward"}  # C1, C2 (thesis ch. 6.2.2)
LENGTH_LABELS = {1.0: "short", 2.0: "normal", 3.0: "long"}  # C1, C2, C3 (thesis ch. 6.3.2.1)

#: Sensor groups of each unit's rules.
UNIT_RULE_SENSORS = {"foot": ("foot_acc", "foot_gyr", "force"), "waist": ("waist_acc", "waist_gyr")}


@dataclass
class Stage:
    """One stage of a rule classifier: its rules and the label of each class value.

    ``parent`` is the label of the previous stage this stage refines (terrain: ``"stairs"``).
    """

    rules: list[Rule]
    labels: dict[float, str]
    parent: str | None = None
    children: dict[str, str] = field(default_factory=dict)  # task label -> this stage's label


def _terrain_stages(rules1: list[Rule], rules2: list[Rule]) -> list[Stage]:
    return [Stage(rules1, {1.0: "flat", 2.0: "stairs"}, None, {"up": "stairs", "down": "stairs"}),
            Stage(rules2, {3.0: "up", 4.0: "down"}, "stairs")]


def _select(rules: list[Rule], unit: str) -> list[Rule]:
    return [r for r in rules if r.sensor in UNIT_RULE_SENSORS[unit]]


def _fused(rules: list[Rule], weights: dict) -> list[Rule]:
    return [r.with_weight(weights[(r.sensor, r.number)]) for r in rules]


# -- shared estimator ----------------------------------------------------------------------------------


class _RuleClassifier(ClassifierMixin, BaseEstimator):
    """Shared rule-table machinery; subclasses declare ``task`` and ``_stages()``."""

    task = "terrain"

    def _stages(self) -> list[Stage]:
        raise NotImplementedError

    def _check_params(self) -> None:
        if self.thresholds not in ("learn", "joint", "thesis"):
            raise DataError(f"{type(self).__name__}: thresholds must be 'learn', 'joint' or 'thesis', "
                            f"not {self.thresholds!r}")
        if self.weights not in ("thesis", "skill"):
            raise DataError(f"{type(self).__name__}: weights must be 'thesis' or 'skill', "
                            f"not {self.weights!r}")

    @staticmethod
    def _feature_names(stages: list[Stage]) -> list[str]:
        names = [r.feature for st in stages for r in st.rules]
        names += [r.confidence for st in stages for r in st.rules if r.confidence]
        return list(dict.fromkeys(names))

    def _features(self, X, names: list[str]) -> np.ndarray:
        if isinstance(X, StepWindows) or (hasattr(X, "ndim") and X.ndim == 3):
            return RuleFeatures(names=tuple(names), task=self.task).fit_transform(as_windows(X))
        arr = np.asarray(X, dtype=float)
        if arr.ndim != 2 or arr.shape[1] != len(names):
            raise DataError(f"{type(self).__name__}: expected step windows (n, channels, samples) or a rule "
                            f"feature matrix with {len(names)} columns ({', '.join(names)}), got {arr.shape}")
        if not np.isfinite(arr).all():
            raise DataError(f"{type(self).__name__}: the rule features contain NaN or infinite values")
        return arr

    def fit(self, X, y):
        """Check labels, and learn the rules' cut points when ``thresholds="learn"``.

        Parameters
        ----------
        X : step windows or the rule-feature matrix; y : class names of ``TASK_CLASSES[task]``
        """
        self._check_params()
        stages = self._stages()
        names = self._feature_names(stages)
        F = self._features(X, names)
        y = np.asarray(y, dtype=object)
        if y.shape[0] != F.shape[0]:
            raise DataError(f"{type(self).__name__}: {F.shape[0]} steps but {y.shape[0]} labels")
        classes = TASK_CLASSES[self.task]
        unknown = sorted({str(v) for v in y} - set(classes))
        if unknown:
            raise DataError(f"{type(self).__name__}: labels {unknown} are not {self.task} classes "
                            f"({', '.join(classes)}); drop or relabel those steps")
        # scikit-learn convention (decision C19): classes_ sorted as np.unique sorts them, and predict_proba's
        # columns in that order; every internal reader aligns columns by class name
        self.classes_ = np.array(sorted(classes), dtype=object)
        col = {n: i for i, n in enumerate(names)}
        fitted = []
        for st in stages:
            rules = st.rules
            inv = {lab: v for v, lab in st.labels.items()}
            stage_lab = np.array([st.children.get(v, v) for v in y], dtype=object)
            rows = np.array([lab in inv for lab in stage_lab], dtype=bool)
            target = np.array([inv.get(lab, np.nan) for lab in stage_lab], dtype=float)[rows]
            if self.thresholds in ("learn", "joint"):
                new = []
                for r in rules:
                    th, cl = learn_thresholds(F[rows, col[r.feature]], target, r, bands=self.bands)
                    new.append(Rule(r.sensor, r.number, r.feature, th, cl, r.weight, True,
                                    r.source + " (cut points learned)", r.confidence)
                               if (th, cl) != (r.thresholds, r.classes) else r)
                rules = new
            if self.thresholds == "joint" and not any(r.confidence for r in rules):
                rules = refine_jointly(F[rows][:, [col[r.feature] for r in rules]], target, rules,
                                       tuple(st.labels))
            if self.weights == "skill" and len(np.unique(target)) > 1:
                skill = np.array([rule_skill(F[rows, col[r.feature]], target, r) for r in rules])
                w = np.array([r.weight for r in rules]) * np.clip(2 * np.nan_to_num(skill) - 1, 0, None)
                if w.sum() > 0:
                    rules = [r.with_weight(wi) for r, wi in zip(rules, w, strict=True)]
            fitted.append(Stage(rules, st.labels, st.parent, st.children))
        self.stages_ = fitted
        self.feature_names_ = names
        self.n_train_ = int(F.shape[0])
        return self

    def _stage_scores(self, F: np.ndarray) -> list[np.ndarray]:
        col = {n: i for i, n in enumerate(self.feature_names_)}
        out = []
        for st in self.stages_:
            idx = [col[r.feature] for r in st.rules]
            conf = None
            if any(r.confidence for r in st.rules):
                conf = np.column_stack([F[:, col[r.confidence]] if r.confidence else np.ones(len(F))
                                        for r in st.rules])
            out.append(stage_score(F[:, idx], st.rules, conf))
        return out

    def decision_scores(self, X) -> np.ndarray:
        """The stages' results ``R`` (thesis eq. 28), (n_steps, n_stages)."""
        check_is_fitted(self, "stages_")
        return np.column_stack(self._stage_scores(self._features(X, self.feature_names_)))

    def predict_proba(self, X) -> np.ndarray:
        """Class probabilities (n_steps, n_classes), columns in :attr:`classes_` order."""
        check_is_fitted(self, "stages_")
        F = self._features(X, self.feature_names_)
        stages = [(memberships(score, tuple(st.labels)), list(st.labels.values()), st.parent)
                  for st, score in zip(self.stages_, self._stage_scores(F), strict=True)]
        probs = combine_stages(stages)
        return np.column_stack([probs[c] for c in self.classes_])

    def predict(self, X) -> np.ndarray:
        """Thesis decision: each stage's ``R`` rounded to the nearest class value (eq. 28-30)."""
        check_is_fitted(self, "stages_")
        F = self._features(X, self.feature_names_)
        out = np.empty(len(F), dtype=object)
        todo = np.ones(len(F), dtype=bool)
        for st, score in zip(self.stages_, self._stage_scores(F), strict=True):
            values = np.array(list(st.labels), dtype=float)
            lab = np.array([st.labels[v] for v in values], dtype=object)[
                np.argmax(memberships(score, tuple(values)), axis=1)]
            rows = todo if st.parent is None else todo & (out == st.parent)
            out[rows] = lab[rows]
        return out

    def rules_table(self) -> list[dict]:
        """The (fitted) rules as plain dicts, stage by stage (JSON-serialisable)."""
        check_is_fitted(self, "stages_")
        return [dict(r.to_dict(), stage=i + 1) for i, st in enumerate(self.stages_) for r in st.rules]

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.three_d_array = True
        return tags


class _UnitRuleClassifier(_RuleClassifier):
    def __init__(self, *, unit: str = "foot", thresholds: str = "joint", weights: str = "thesis",
                 bands: bool = True):
        self.unit = unit
        self.thresholds = thresholds
        self.weights = weights
        self.bands = bands

    def _check_params(self) -> None:
        super()._check_params()
        if self.unit not in UNIT_RULE_SENSORS:
            raise DataError(f"{type(self).__name__}: unit must be 'foot' or 'waist' (use "
                            f"HeuristicFusionClassifier for both), not {self.unit!r}")


class HeuristicTerrainClassifier(_UnitRuleClassifier):
    """Two-stage terrain heuristic of one unit (thesis ch. 6.1.2.1, Tables 22-24, eq. 28).

    Stage 1: flat (C1) vs stairs (C2) from rules 1-3 of each sensor; stage 2 (stairs only): up (C3) vs
    down (C4) from foot accelerometer rules 4-8 and gyroscope rules 4-6, or waist rules 4-6.
    """

    task = "terrain"

    def _stages(self):
        return _terrain_stages(_select(TERRAIN_STAGE1, self.unit), _select(TERRAIN_STAGE2, self.unit))


class HeuristicDirectionClassifier(_UnitRuleClassifier):
    """Direction heuristic of one unit (thesis eq. 31): forward when the first half of the forward
    acceleration sums higher than the second half."""

    task = "direction"

    def _stages(self):
        rules = [Rule(r.sensor, r.number, r.feature, r.thresholds, r.classes, r.weight, r.upper_closed,
                      r.source) for r in _select(DIRECTION_RULES, self.unit)]
        return [Stage(rules, DIRECTION_LABELS)]


class HeuristicLengthClassifier(_UnitRuleClassifier):
    """Length heuristic of one unit (thesis ch. 6.3.2.1): foot = force Table 29 + accelerometer Table 30,
    waist = pelvic rotation Table 31; ``R`` rounded to short (1) / normal (2) / long (3)."""

    task = "length"

    def _stages(self):
        return [Stage(_select(LENGTH_RULES, self.unit), LENGTH_LABELS)]


class HeuristicFusionClassifier(_RuleClassifier):
    """Heuristic fusion of both units (thesis ch. 6.1.2.3, 6.2.2.3, 6.3.2.3).

    terrain: every rule of Tables 22-24 with the Table 26 weights; length: Tables 29-31 with the
    Table 32 weights; direction: eq. 31 per unit, each weighted by its eq. 32 step probability x
    0.6 (foot) / 0.4 (waist).
    """

    def __init__(self, *, task: str = "terrain", thresholds: str = "joint", weights: str = "thesis",
                 bands: bool = True):
        self.task = task
        self.thresholds = thresholds
        self.weights = weights
        self.bands = bands

    def _check_params(self) -> None:
        super()._check_params()
        if self.task not in TASK_CLASSES:
            raise DataError(f"HeuristicFusionClassifier: task must be one of {', '.join(TASK_CLASSES)}, "
                            f"not {self.task!r}")

    def _stages(self):
        if self.task == "terrain":
            return _terrain_stages(_fused(TERRAIN_STAGE1, TERRAIN_FUSION_WEIGHTS),
                                   _fused(TERRAIN_STAGE2, TERRAIN_FUSION_WEIGHTS))
        if self.task == "direction":
            return [Stage(_fused(DIRECTION_RULES, DIRECTION_FUSION_WEIGHTS), DIRECTION_LABELS)]
        return [Stage(_fused(LENGTH_RULES, LENGTH_FUSION_WEIGHTS), LENGTH_LABELS)]


def make_heuristic(task: str, unit: str = "both", *, thresholds: str = "joint", bands: bool = True,
                   weights: str = "thesis") -> _RuleClassifier:
    """The heuristic of ``task`` for ``unit`` (``both`` -> :class:`HeuristicFusionClassifier`)."""
    if unit == "both":
        return HeuristicFusionClassifier(task=task, thresholds=thresholds, weights=weights, bands=bands)
    cls = {"terrain": HeuristicTerrainClassifier, "direction": HeuristicDirectionClassifier,
           "length": HeuristicLengthClassifier}.get(task)
    if cls is None:
        raise DataError(f"make_heuristic: unknown task '{task}'; choose terrain, direction or length")
    return cls(unit=unit, thresholds=thresholds, weights=weights, bands=bands)
