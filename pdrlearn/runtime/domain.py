"""The out-of-domain check of a bundle's classifiers (decision E105; C16 / C61 on the training side), numpy only.

``pdrlearn export`` stores in each leaf model entry (ONNX, DTW, heuristic) the ``training_range`` of that model's
own inputs (:meth:`pdrlearn.classify.domain.FeatureRange.to_dict`: the 1 % / 99 % training quantiles). The runtime
computes the same inputs from the step window: the ONNX model's feature recipe, the DTW model's signals (samples
flattened signal by signal, as :func:`pdrlearn.classify.domain.model_inputs`), the rule features of a heuristic;
a fusion entry is its members. The score of a stride, the threshold, the session summary and the warning line are
the training side's (:func:`~pdrlearn.classify.domain.combine_scores`, ``STEP_THRESHOLD``,
:func:`~pdrlearn.classify.domain.summarize`, :func:`~pdrlearn.classify.domain.domain_report`,
:func:`~pdrlearn.classify.domain.session_warning_line`; that module imports numpy only). A bundle exported
before E105 has no ranges: nothing is checked (no line, no error), as a model saved before C16.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.classify.domain import FeatureRange, combine_scores, domain_report, summarize
from pdrlearn.errors import DataError, ModelError
from pdrlearn.runtime.features import compute_features


def entry_range(entry: dict) -> FeatureRange | None:
    """The training range a leaf entry carries (decision E105), None when it has none (exported before)."""
    d = entry.get("training_range")
    if d is None:
        return None
    try:
        return FeatureRange.from_dict(d)
    except (KeyError, TypeError, ValueError) as exc:
        raise ModelError(f"a model entry's training_range is malformed ({exc}); re-export the bundle") from None


def _range_of(leaf) -> FeatureRange | None:
    """:func:`entry_range` of a leaf model, parsed once per model."""
    if not hasattr(leaf, "_training_range"):
        leaf._training_range = entry_range(leaf.entry)
    return leaf._training_range


def _leaves(model) -> list:
    """The leaf :class:`~pdrlearn.runtime.classify.RuntimeModel` objects of ``model`` (fusion: its members)."""
    if model.type == "fusion":
        return [leaf for m in model.members for leaf in _leaves(m)]
    return [model]


def leaf_inputs(model, rng: FeatureRange, W: np.ndarray, cache: dict | None = None) -> np.ndarray | None:
    """What a leaf model's classifier sees for the windows ``W`` ``(n, features)``, in the order of its training
    range; None when the windows lack a channel it reads (the stride is not checked, as offline)."""
    if model.type == "onnx":
        recipe = model.entry["features"]
    elif model.type == "dtw":
        recipe = [["signals", model.entry["signals"]]]
    else:  # heuristic: the rule features named by the range (the model's own, in their order)
        recipe = [["rule", n] for n in rng.features]
    try:
        F = compute_features(W, recipe, cache=cache, **model.ctx)
    except (DataError, KeyError, ValueError):
        return None
    return np.asarray(F, dtype=float).reshape(len(W), -1)  # DTW: (n, signals, samples) -> signal by signal


def model_score(model, W: np.ndarray, cache: dict | None = None) -> tuple[np.ndarray, list[str]] | None:
    """Per window of ``W``, the score ``d`` of :mod:`pdrlearn.classify.domain` against the training ranges of
    ``model``'s leaves and the feature that set it; None when a leaf has no range (a bundle exported before E105)."""
    leaves = [(leaf, _range_of(leaf)) for leaf in _leaves(model)]
    return combine_scores(((rng, lambda leaf=leaf, rng=rng: None if rng is None else leaf_inputs(leaf, rng, W, cache))
                           for leaf, rng in leaves), len(W))


class DomainLog:
    """The strides' scores of one tracked session, per task (decision E105): :meth:`score` the window of a stride
    with each task's model, :meth:`add` the scores of a processed stride, :meth:`report` the training side's
    session summary (:func:`~pdrlearn.classify.domain.domain_report`) or None when nothing was checked."""

    def __init__(self) -> None:
        self._d: dict[str, list[float]] = {}
        self._worst: dict[str, list[str]] = {}
        self._used: dict[str, list[str]] = {}

    @staticmethod
    def has_ranges(classifiers: dict) -> bool:
        """Whether a task's model carries training ranges (a bundle exported since E105)."""
        return any(all(_range_of(leaf) is not None for leaf in _leaves(c.model))
                   for c in classifiers.values() if c.model is not None)

    @staticmethod
    def score(classifiers: dict, W: np.ndarray) -> dict[str, tuple[float, str, str]]:
        """Task -> (score, feature, ``method/unit``) of one stride's window ``W (channels, samples)``; a task whose
        model has no ranges, or whose inputs the window lacks, is left out."""
        out, cache = {}, {}
        for task, clf in classifiers.items():
            if clf.model is None:
                continue
            s = model_score(clf.model, W[None], cache)
            if s is not None:
                out[task] = (float(s[0][0]), str(s[1][0]), f"{clf.method}/{clf.unit}")
        return out

    def add(self, scores: dict[str, tuple[float, str, str]] | None, tasks) -> None:
        """Record a classified stride's ``scores`` (:meth:`score`); the ``tasks`` it has no score of get NaN."""
        for task in tasks:
            d, worst, used = (scores or {}).get(task, (np.nan, "", ""))
            self._d.setdefault(task, []).append(d)
            self._worst.setdefault(task, []).append(worst)
            self._used.setdefault(task, []).append(used)

    def report(self, warn_at: float | None = None) -> dict | None:
        """The session's out-of-domain report (``out_of_domain_fraction``, per task ``summarize``, ``warn``), as
        ``pdrlearn track --model`` gives it; None when no stride was checked."""
        per_task = {}
        for task, d in self._d.items():
            arr = np.asarray(d, dtype=float)
            if not np.isfinite(arr).any():
                continue
            used = sorted({u for u, x in zip(self._used[task], arr, strict=True) if np.isfinite(x)})
            per_task[task] = summarize(arr, self._worst[task], ", ".join(used))
        return domain_report(per_task, warn_at=warn_at) if per_task else None


__all__ = ["entry_range", "leaf_inputs", "model_score", "DomainLog"]
