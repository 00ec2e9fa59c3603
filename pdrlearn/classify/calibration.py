"""Calibrated class probabilities: a softmax temperature fitted by an inner cross-validation (decision C67).

A classifier whose probabilities are a softmax of scores (DTW: minus the class mean distances) gets its
temperature from the scores of held-out training steps: :func:`cv_scores` fits clones of the classifier on
the inner folds' training parts and scores their held-out parts, :func:`fit_temperature` minimises the
cross-entropy of ``softmax(scores / T)`` on them. Dividing scores by a positive ``T`` keeps their argmax, so
``predict`` is unchanged; only how sure ``predict_proba`` is moves. The targets are smoothed by Platt's
prior correction (Platt 1999, "Probabilistic outputs for support vector machines", sec. 2.2: the target of a
class with ``n`` held-out examples is ``(n + 1) / (n + 2)``, not 1), so a classifier that is right on every
held-out step gets a finite temperature whose confidence grows with the evidence, instead of ``T -> 0``.

Kernels (pure functions) first; :func:`cv_scores` drives a scikit-learn estimator. Any classifier with a
score method can use the mechanism (it is not DTW-specific); the exported temperature is all the runtime
needs (``pdrlearn.runtime.classify``: ``softmax(-distances / temperature)``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from pdrlearn.kernels.proba import softmax

#: Inner folds of the temperature's cross-validation (decision C67; fewer when a class has fewer steps).
CALIBRATION_FOLDS = 3

#: Search range of the temperature, as multiples of the score scale given to :func:`fit_temperature`.
TEMPERATURE_RANGE = (1e-3, 1e3)


def smoothed_targets(y_idx: np.ndarray, n_classes: int) -> np.ndarray:
    """Soft targets ``(n, n_classes)``: a step of class ``k`` gets ``(n_k + 1) / (n_k + 2)`` on ``k`` (Platt 1999,
    sec. 2.2, ``n_k`` = held-out steps of class ``k``) and the rest, ``1 / (n_k + 2)``, spread evenly over the other
    classes; rows sum to 1."""
    y_idx = np.asarray(y_idx, dtype=int)
    counts = np.bincount(y_idx, minlength=n_classes).astype(float)
    eps = 1.0 / (counts[y_idx] + 2.0)  # Platt 1999 sec. 2.2
    out = np.repeat((eps / max(n_classes - 1, 1))[:, None], n_classes, axis=1)
    out[np.arange(len(y_idx)), y_idx] = 1.0 - eps
    return out


def cross_entropy(scores: np.ndarray, targets: np.ndarray, temperature: float) -> float:
    """Mean cross-entropy of ``softmax(scores / temperature)`` against soft ``targets``."""
    z = scores / temperature
    z = z - z.max(axis=1, keepdims=True)
    log_p = z - np.log(np.exp(z).sum(axis=1, keepdims=True))
    return float(-np.mean(np.sum(targets * log_p, axis=1)))


def fit_temperature(scores: np.ndarray, y_idx: np.ndarray, *, scale: float = 1.0) -> float:
    """Temperature ``T`` minimising :func:`cross_entropy` of held-out ``scores`` ``(n, k)`` (higher = more likely)
    with true class indices ``y_idx`` against :func:`smoothed_targets`.

    The cross-entropy is convex in ``1 / T``; the bounded search runs over ``log T`` in
    ``scale * TEMPERATURE_RANGE``. Returns ``scale`` when there is nothing to fit (fewer than two classes or
    no steps, or scores that do not vary)."""
    from scipy.optimize import minimize_scalar

    scores = np.asarray(scores, dtype=float)
    y_idx = np.asarray(y_idx, dtype=int)
    if scores.ndim != 2 or scores.shape[1] < 2 or len(scores) == 0 or not np.isfinite(scores).all():
        return float(scale)
    if np.ptp(scores - scores.mean(axis=1, keepdims=True)) <= 1e-12:
        return float(scale)
    targets = smoothed_targets(y_idx, scores.shape[1])
    lo, hi = (np.log(scale * r) for r in TEMPERATURE_RANGE)
    res = minimize_scalar(lambda lt: cross_entropy(scores, targets, float(np.exp(lt))), bounds=(lo, hi),
                          method="bounded", options={"xatol": 1e-4})
    return float(np.exp(res.x))


def calibrated_proba(scores: np.ndarray, temperature: float) -> np.ndarray:
    """``softmax(scores / temperature)`` (the runtime's form)."""
    return softmax(np.asarray(scores, dtype=float) / temperature)


def expected_calibration_error(proba: np.ndarray, y_idx: np.ndarray, n_bins: int = 10) -> float:
    """Expected calibration error (Guo et al. 2017, "On calibration of modern neural networks", eq. 3) of class
    probabilities ``(n, k)`` against true class indices: :func:`confidence_ece` of the top probability and
    whether the argmax is right."""
    proba = np.asarray(proba, dtype=float)
    if len(proba) == 0:
        return float("nan")
    return confidence_ece(proba.max(axis=1), proba.argmax(axis=1) == np.asarray(y_idx, dtype=int), n_bins)


def confidence_ece(conf: np.ndarray, right: np.ndarray, n_bins: int = 10) -> float:
    """Guo et al. 2017 eq. 3: the steps binned by confidence into ``n_bins`` equal-width bins over [0, 1]; the
    step-weighted mean of |accuracy - mean confidence| per bin. ``nan`` for no steps."""
    conf = np.asarray(conf, dtype=float)
    right = np.asarray(right, dtype=float)
    if len(conf) == 0:
        return float("nan")
    b = np.minimum((conf * n_bins).astype(int), n_bins - 1)  # bins [i/n, (i+1)/n); conf 1.0 in the last
    total = 0.0
    for k in np.unique(b):
        m = b == k
        total += m.sum() * abs(right[m].mean() - conf[m].mean())
    return float(total / len(conf))


def cv_scores(
    make: Callable[[], object],
    X: np.ndarray,
    y_idx: np.ndarray,
    score: Callable[[object, np.ndarray], np.ndarray],
    *,
    folds: int = CALIBRATION_FOLDS,
    random_state: int | None = 0,
) -> tuple[np.ndarray, np.ndarray] | None:
    """Held-out scores of the training steps by an inner stratified ``folds``-fold cross-validation.

    ``make()`` returns an unfitted classifier (without calibration, so this does not recurse), ``score(fitted,
    X_part)`` its ``(n, n_classes)`` scores in class-index order. Returns ``(scores, y_idx)`` of every step, each
    scored by the fold model that did not see it, or None when a class has fewer than two steps (no fold
    split exists)."""
    from sklearn.model_selection import StratifiedKFold

    y_idx = np.asarray(y_idx, dtype=int)
    counts = np.bincount(y_idx)
    n_classes = len(counts)
    k = int(min(folds, counts.min())) if n_classes >= 2 else 0
    if k < 2:
        return None
    out = np.empty((len(y_idx), n_classes))
    for tr, te in StratifiedKFold(k, shuffle=True, random_state=random_state).split(np.zeros(len(y_idx)), y_idx):
        est = make().fit(X[tr], y_idx[tr])
        out[te] = score(est, X[te])
    return out, y_idx
