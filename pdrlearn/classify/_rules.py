"""Rule-table kernels shared by every heuristic classifier (thesis ch. 6.1.2.1, 6.3.2.1, eq. 28).

A :class:`Rule` maps one scalar feature to a class value through ascending cut points
(``thresholds``) and the class value of each interval (``classes``; e.g. ``C1`` = 1, ``C2.5`` = 2.5).
A stage's result is ``R = sum(class_i * weight_i) / sum(weight_i)`` (thesis eq. 28; the thesis weights
of a stage sum to 1, so the division only matters for subsets) rounded to the nearest class value.
Pure functions; no estimator state.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np


@dataclass(frozen=True)
class Rule:
    """One row of a thesis rule table.

    Attributes
    ----------
    sensor : sensor group label (``foot_acc``, ``foot_gyr``, ``waist_acc``, ``force``, ``waist_gyr``)
    number : the feature's number in its thesis table
    feature : rule feature name (``"<signal>:<statistic>"``, :mod:`pdrlearn.features.rules`)
    thresholds : ascending cut points in the feature's SI unit
    classes : class value of each interval (``len(thresholds) + 1``)
    weight : the rule's weight (thesis tables)
    upper_closed : True when a value equal to a cut point falls in the lower interval (``<= t``); a tuple
        of one bool per cut point when the thesis closes its cuts differently (Table 30 #2: ``<= 9``,
        ``< 12``; features decision 15)
    source : citation of the row
    confidence : optional rule feature (0..1) multiplying the weight per step (thesis eq. 32)
    """

    sensor: str
    number: int
    feature: str
    thresholds: tuple[float, ...]
    classes: tuple[float, ...]
    weight: float
    upper_closed: bool | tuple[bool, ...] = True
    source: str = ""
    confidence: str = ""

    def with_weight(self, weight: float) -> Rule:
        return replace(self, weight=float(weight))

    def to_dict(self) -> dict:
        return {"sensor": self.sensor, "number": self.number, "feature": self.feature,
                "thresholds": [float(t) for t in self.thresholds],
                "classes": [float(c) for c in self.classes],
                "weight": float(self.weight), "upper_closed": _closure_to_json(self.upper_closed),
                "source": self.source, "confidence": self.confidence}

    @classmethod
    def from_dict(cls, d: dict) -> Rule:
        return cls(sensor=d["sensor"], number=int(d["number"]), feature=d["feature"],
                   thresholds=tuple(float(t) for t in d["thresholds"]),
                   classes=tuple(float(c) for c in d["classes"]), weight=float(d["weight"]),
                   upper_closed=_closure_from_json(d["upper_closed"]), source=d.get("source", ""),
                   confidence=d.get("confidence", ""))


def _closure_to_json(upper_closed) -> bool | list[bool]:
    if isinstance(upper_closed, (bool, np.bool_)):
        return bool(upper_closed)
    return [bool(c) for c in upper_closed]


def _closure_from_json(v) -> bool | tuple[bool, ...]:
    return tuple(bool(c) for c in v) if isinstance(v, (list, tuple)) else bool(v)


def apply_rule(values: np.ndarray, thresholds, classes, upper_closed) -> np.ndarray:
    """Class value of each feature value (n,).

    ``upper_closed``: one bool for every cut point, or a tuple of one bool per cut point (features
    decision 15). A NaN value falls in the last interval either way (``searchsorted`` order).
    """
    t = np.asarray(thresholds, dtype=float)
    if isinstance(upper_closed, (bool, np.bool_)):
        idx = np.searchsorted(t, values, side="left" if upper_closed else "right")
    else:
        if len(upper_closed) != len(t):
            raise ValueError(f"upper_closed has {len(upper_closed)} entries for {len(t)} cut points")
        idx = sum(np.searchsorted(t[i:i + 1], values, side="left" if c else "right")
                  for i, c in enumerate(upper_closed))
    return np.asarray(classes, dtype=float)[idx]


def stage_score(F: np.ndarray, rules: list[Rule], conf: np.ndarray | None = None) -> np.ndarray:
    """Weighted class value ``R`` (thesis eq. 28) of each row of ``F`` (columns = ``rules`` in order).

    ``conf`` (n, len(rules)) multiplies the weights per step (thesis eq. 32 decision fusion); a floor of
    0.01 keeps the score defined when every source distrusts the step.
    """
    w = np.array([r.weight for r in rules], dtype=float)[None, :]
    if conf is not None:
        w = w * np.clip(conf, 0.01, None)
    votes = np.column_stack([apply_rule(F[:, j], r.thresholds, r.classes, r.upper_closed)
                             for j, r in enumerate(rules)])
    return np.sum(votes * w, axis=1) / np.sum(w, axis=1)


def memberships(score: np.ndarray, values: tuple[float, ...]) -> np.ndarray:
    """Triangular memberships (n, k) of ``score`` to the integer class ``values`` (sum 1 inside the range).

    ``max(0, 1 - |R - c|)``, scores outside the range clipped to it: the rounding rule of the thesis
    picks the class of the largest membership.
    """
    v = np.asarray(values, dtype=float)
    s = np.clip(score, v.min(), v.max())[:, None]
    m = np.clip(1.0 - np.abs(s - v[None, :]), 0.0, None)
    return m / m.sum(axis=1, keepdims=True)


def _balanced_correct(pred: np.ndarray, target: np.ndarray, classes: np.ndarray) -> np.ndarray:
    """Balanced accuracy of each row of ``pred`` (k, n); an intermediate value (C2.5) counts as
    correct for both neighbours (|pred - target| < 0.75)."""
    ok = np.abs(pred - target[None, :]) < 0.75
    return np.mean([ok[:, target == c].mean(axis=1) for c in classes], axis=0)


# The threshold searches below score every candidate set of cut points (m of them) on n labelled steps.
# Materialising the (m, n) predictions costs O(m n) Python-driven numpy work per rule (most of a heuristic
# fit). A step's predicted class depends only on the interval its value falls in, and the cut points of
# a candidate are ascending, so the number of steps of each class in each interval comes from a
# ``searchsorted`` on the sorted values: O((m + n) log n). The counts are exact integers and the balanced
# accuracy is formed from them with the same float operations as ``_balanced_correct`` (a mean of 0/1
# values is count / n_c), so the chosen cut points are bit-identical (tests/test_classify_fastpaths.py).


def _interval_counts(values: np.ndarray, target: np.ndarray, classes: np.ndarray,
                     combos: np.ndarray) -> np.ndarray:
    """Steps of each class in each interval of each candidate: (n_classes, m, k + 1) integers.

    ``combos`` (m, k) holds ascending cut points per row; a value is in interval ``#(value > t)``.
    ``values`` must be finite.
    """
    m, k = combos.shape
    out = np.empty((len(classes), m, k + 1), dtype=np.int64)
    for ci, c in enumerate(classes):
        s = np.sort(values[target == c])
        le = np.searchsorted(s, combos, side="right")  # values <= t: not above the cut point
        out[ci, :, 0] = le[:, 0]
        out[ci, :, 1:k] = np.diff(le, axis=1)
        out[ci, :, k] = len(s) - le[:, k - 1]
    return out


def _balanced_from_counts(counts: np.ndarray, order, classes: np.ndarray) -> np.ndarray:
    """``_balanced_correct`` of the predictions ``order[interval]`` from :func:`_interval_counts`: (m,)."""
    order = np.asarray(order, dtype=float)
    per_class = []
    for ci, c in enumerate(classes):
        ok = np.abs(order - c) < 0.75  # the interval's class counts as correct for class c
        with np.errstate(invalid="ignore", divide="ignore"):  # a class without finite values: NaN, as before
            per_class.append(counts[ci][:, ok].sum(axis=1) / counts[ci].sum(axis=1))
    return np.mean(per_class, axis=0)


def rule_skill(values: np.ndarray, target: np.ndarray, rule: Rule) -> float:
    """Balanced accuracy of ``rule`` alone on labelled values (class values in ``target``), 0..1."""
    ok = np.isfinite(values) & np.isfinite(target)
    values, target = values[ok], target[ok]
    if len(values) == 0:
        return float("nan")
    pred = apply_rule(values, rule.thresholds, rule.classes, rule.upper_closed)[None, :]
    return float(_balanced_correct(pred, target, np.unique(target))[0])


def learn_thresholds(values: np.ndarray, target: np.ndarray, rule: Rule, *, max_candidates: int = 48,
                     bands: bool = False, band_gain: float = 0.05
                     ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Cut points (and interval order) that make ``rule`` agree best with the labels.

    The rule keeps its feature and its class values; the cut points are searched among midpoints of
    quantiles of ``values`` and the interval order may be reversed (a sign convention differing from
    the thesis'), maximising the balanced accuracy of the rule alone on ``target`` (class values).
    Returns ``(thresholds, classes)``; the thesis' own when the data cannot decide (one class only).
    """
    classes_present = np.unique(target)
    finite = np.isfinite(values)
    values, target = values[finite], target[finite]
    if len(classes_present) < 2 or len(values) < 2:
        return rule.thresholds, rule.classes
    q = np.unique(np.quantile(values, np.linspace(0, 1, max_candidates + 1)))
    cands = 0.5 * (q[:-1] + q[1:]) if len(q) > 1 else q
    k = len(rule.thresholds)
    if k == 1:
        combos = cands[:, None]
    else:
        i, j = np.triu_indices(len(cands), k=1)
        combos = np.column_stack([cands[i], cands[j]])
    best = (-1.0, rule.thresholds, rule.classes)
    counts = _interval_counts(values, target, classes_present, combos)
    for order in (tuple(rule.classes), tuple(rule.classes[::-1])):
        # balanced accuracy of every candidate threshold set at once: (n_combos,)
        score = _balanced_from_counts(counts, order, classes_present)
        b = int(np.argmax(score))
        if score[b] > best[0] + 1e-12:
            best = (float(score[b]), tuple(float(t) for t in combos[b]), order)
    if bands and k == 1 and len(set(rule.classes)) == 2:
        # a two-class rule may instead hold one class inside a band [t1, t2] (e.g. flat between up and
        # down); taken only when it gains at least ``band_gain`` balanced accuracy (decisions doc)
        c1, c2 = rule.classes
        i, j = np.triu_indices(len(cands), k=1)
        pairs = np.column_stack([cands[i], cands[j]])
        counts = _interval_counts(values, target, classes_present, pairs)
        for order in ((c1, c2, c1), (c2, c1, c2)):
            score = _balanced_from_counts(counts, order, classes_present)
            b = int(np.argmax(score))
            if score[b] > best[0] + band_gain:
                best = (float(score[b]), tuple(float(t) for t in pairs[b]), order)
    return best[1], best[2]


def _candidates(values: np.ndarray, k: int, max_candidates: int) -> np.ndarray:
    q = np.unique(np.quantile(values, np.linspace(0, 1, max_candidates + 1)))
    cands = 0.5 * (q[:-1] + q[1:]) if len(q) > 1 else q
    if k == 1:
        return cands[:, None]
    i, j = np.triu_indices(len(cands), k=1)
    return np.column_stack([cands[i], cands[j]])


def refine_jointly(F: np.ndarray, target: np.ndarray, rules: list[Rule], values: tuple[float, ...], *,
                   passes: int = 2, max_candidates: int = 24) -> list[Rule]:
    """Coordinate ascent on the *stage decision*: each rule's cut points (and interval order) in turn are
    set to maximise the balanced accuracy of the rounded weighted result ``R`` (eq. 28) of all rules,
    the other rules fixed. Starts from ``rules`` (e.g. per-rule learned cut points); weights unchanged.

    Parameters
    ----------
    F : (n, len(rules)) rule feature values; target : (n,) class values; values : the stage's classes
    """
    classes = np.unique(target)
    if len(classes) < 2:
        return rules
    vals = np.asarray(values, dtype=float)
    w = np.array([r.weight for r in rules], dtype=float)
    wsum = w.sum()
    votes = np.column_stack([apply_rule(F[:, j], r.thresholds, r.classes, r.upper_closed)
                             for j, r in enumerate(rules)])

    def score_of(R: np.ndarray) -> np.ndarray:  # R (m, n) -> balanced accuracy (m,)
        pred = vals[np.argmin(np.abs(R[..., None] - vals), axis=-1)]
        return np.mean([(pred[:, target == c] == c).mean(axis=1) for c in classes], axis=0)

    rules = list(rules)
    best = float(score_of((votes @ w / wsum)[None, :])[0])
    # each column's candidates and sorted layout do not change between passes (its rule keeps the number
    # of cut points): computed once
    cols = [(_candidates(F[:, j], len(r.thresholds), max_candidates), np.isfinite(F[:, j]).all())
            for j, r in enumerate(rules)]
    cols = [(combos, _joint_layout(F[:, j], combos, target, classes) if finite else None)
            for j, (combos, finite) in enumerate(cols)]
    for _ in range(passes):
        improved = False
        for j, r in enumerate(rules):
            base = (votes @ w - votes[:, j] * w[j]) / wsum
            combos, layout = cols[j]
            fast = layout is not None and np.isfinite(base).all()
            for order in (tuple(r.classes), tuple(r.classes[::-1])):
                if fast:
                    s = _joint_scores(base, w[j], wsum, order, layout, vals)
                else:  # NaN features: the direct (m, n) evaluation
                    idx = (F[None, None, :, j] > combos[:, :, None]).sum(axis=1)
                    s = score_of(base[None, :] + w[j] * np.asarray(order, dtype=float)[idx] / wsum)
                b = int(np.argmax(s))
                if s[b] > best + 1e-9:
                    best = float(s[b])
                    votes[:, j] = np.asarray(order, dtype=float)[(F[:, j] > combos[b][:, None]).sum(axis=0)]
                    rules[j] = Rule(r.sensor, r.number, r.feature, tuple(float(t) for t in combos[b]), order,
                                    r.weight, True, r.source.replace(" (cut points learned)", "")
                                    + " (cut points learned jointly)", r.confidence)
                    r = rules[j]
                    improved = True
        if not improved:
            break
    return rules


def _joint_layout(x: np.ndarray, combos: np.ndarray, target: np.ndarray, classes: np.ndarray) -> tuple:
    """Steps sorted by ``x`` (finite), each candidate's interval edges in that order, the classes' masks."""
    srt = np.argsort(x, kind="stable")
    pos = np.searchsorted(x[srt], combos, side="right")  # (m, k) steps at or below each cut point
    edges = np.concatenate([np.zeros((len(combos), 1), dtype=np.int64), pos,
                            np.full((len(combos), 1), len(x), dtype=np.int64)], axis=1)
    tgt = target[srt]
    is_c = tgt[None, :] == np.asarray(classes)[:, None]  # (n_classes, n)
    return srt, edges, tgt, is_c, is_c.sum(axis=1)


def _joint_scores(base: np.ndarray, wj: float, wsum: float, order, layout: tuple, vals: np.ndarray) -> np.ndarray:
    """Balanced accuracy (m,) of the rounded stage result when rule ``j`` (weight ``wj``) uses each
    candidate's cut points and interval classes ``order`` and the other rules give ``base``.

    Same result as rounding ``base + wj * order[interval] / wsum`` for every candidate (``refine_jointly``),
    from per-interval counts: a step's rounded class depends only on its interval (finite values).
    """
    srt, edges, tgt, is_c, n_c = layout
    order = np.asarray(order, dtype=float)
    R = base[None, :] + (wj * order / wsum)[:, None]  # (k + 1, n): every step's result for each interval's vote
    correct = vals[np.argmin(np.abs(R[..., None] - vals), axis=-1)][:, srt] == tgt  # same rounding as score_of
    n = len(tgt)
    cum = np.zeros((len(order), len(n_c), n + 1), dtype=np.int64)  # correct steps of each class, cumulated
    np.cumsum(correct[:, None, :] & is_c[None, :, :], axis=-1, out=cum[..., 1:])
    hits = sum(cum[i][:, edges[:, i + 1]] - cum[i][:, edges[:, i]] for i in range(len(order)))  # (classes, m)
    return np.mean(hits / n_c[:, None], axis=0)


def combine_stages(stages: list[tuple[np.ndarray, list[str], str | None]]) -> dict[str, np.ndarray]:
    """Class probabilities from the memberships of chained stages (decisions doc, section 9).

    Each item is ``(m, labels, parent)``: memberships ``m`` (n, k) of the stage's class values, their
    labels, and the label of the previous stage this stage refines (``None`` for the first stage).
    A refined label's mass is split by the stage's memberships; the parent stage's other labels are
    scaled by the stage's best membership, so the argmax equals the stage-by-stage rounded decision.
    Rows are normalised to sum 1. Returns label -> (n,) probabilities.
    """
    probs: dict[str, np.ndarray] = {}
    for m, labels, parent in stages:
        if parent:
            base = probs.pop(parent)
            best = m.max(axis=1)
            for k in probs:
                probs[k] = probs[k] * best
        else:
            base = np.ones(m.shape[0])
        for j, lab in enumerate(labels):
            probs[lab] = base * m[:, j]
    total = np.sum(list(probs.values()), axis=0)
    return {k: v / total for k, v in probs.items()}
