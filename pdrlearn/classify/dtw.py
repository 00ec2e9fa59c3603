"""Dynamic-time-warping step classifier with a per-user reference set (thesis ch. 6.1.2.2, 6.2.2.2, 6.3.2.2).

A detected step's fixed-length signals are compared by DTW with every stored reference step of the user;
the class whose references have the lowest *mean* distance wins (thesis ch. 6.1.2.2). The distances come
from dtaidistance's C implementation with a Sakoe-Chiba window; for :meth:`DTWClassifier.predict`, a class
whose mean LB_Keogh lower bound already exceeds the best exact class mean is pruned without computing its
DTW distances (exact: the argmin is unchanged).

Kernels (pure functions) come first; the estimator class follows.
"""

from __future__ import annotations

import logging
import math

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import column_or_1d, validate_data

from pdrlearn.classify.svm import check_fitted_fast, check_X_fast
from pdrlearn.errors import DataError
from pdrlearn.kernels.proba import softmax  # = scipy.special.softmax, no array-API dispatch

log = logging.getLogger(__name__)
logging.getLogger("be.kuleuven.dtai.distance").setLevel(logging.WARNING)  # one INFO line per call otherwise

#: References per class used by the thesis: terrain 108 = 3 x 36 (thesis ch. 6.1.2.2), direction
#: 24 = 2 x 12 (thesis ch. 6.2.2.2), length 90 = 3 x 30 (thesis ch. 6.3.2.2).
THESIS_REFERENCES_PER_CLASS = {"terrain": 36, "direction": 12, "length": 30}


# --------------------------------------------------------------------------------------------------
# kernels
# --------------------------------------------------------------------------------------------------
def as_series(X: np.ndarray) -> np.ndarray:
    """Return steps as a C-contiguous float64 array ``(n, samples, channels)`` for dtaidistance.

    ``X`` is ``(n, channels, samples)`` (the layout of ``StepWindows.X``) or ``(n, samples)`` (one channel).
    """
    X = np.asarray(X, dtype=np.float64)
    if X.ndim == 2:
        X = X[:, None, :]
    return np.ascontiguousarray(np.transpose(X, (0, 2, 1)))


def dtw_block(queries: np.ndarray, refs: np.ndarray, *, window: int | None) -> np.ndarray:
    """DTW distances of every query to every reference.

    Parameters
    ----------
    queries, refs : ``(n, samples, channels)`` float64 arrays (see :func:`as_series`).
    window : Sakoe-Chiba half-width in samples (``None`` = unconstrained).

    Returns
    -------
    ``(n_queries, n_refs)`` distances (square root of the summed squared Euclidean inner distances,
    dtaidistance's ``dtw_ndim`` convention).
    """
    from dtaidistance import dtw_ndim

    nq, nr = len(queries), len(refs)
    if nq == 0 or nr == 0:
        return np.zeros((nq, nr))
    stacked = np.ascontiguousarray(np.concatenate([queries, refs], axis=0))
    d = dtw_ndim.distance_matrix_fast(
        stacked, window=window, block=((0, nq), (nq, nq + nr)), compact=True, parallel=False
    )
    return np.asarray(d, dtype=np.float64).reshape(nq, nr)


def envelope(series: np.ndarray, *, window: int | None) -> tuple[np.ndarray, np.ndarray]:
    """Upper and lower running envelopes over +-``window`` samples of ``(n, samples, channels)`` series."""
    from numpy.lib.stride_tricks import sliding_window_view

    w = series.shape[1] if window is None else int(window)
    pad = np.pad(series, ((0, 0), (w, w), (0, 0)), mode="edge")
    win = sliding_window_view(pad, 2 * w + 1, axis=1)  # (n, samples, channels, 2w+1)
    return win.max(axis=-1), win.min(axis=-1)


def lb_keogh(queries: np.ndarray, upper: np.ndarray, lower: np.ndarray) -> np.ndarray:
    """LB_Keogh lower bounds of the DTW distance of each query to each enveloped reference.

    The references' envelopes over +-w samples bound every warping path inside the same Sakoe-Chiba
    band, so ``lb_keogh <= dtw`` for equal-length series (Keogh & Ratanamahatana 2005).

    Parameters
    ----------
    queries : ``(nq, samples, channels)``; upper, lower : ``(nr, samples, channels)`` from :func:`envelope`.

    Returns
    -------
    ``(nq, nr)`` lower bounds in the units of :func:`dtw_block`.
    """
    q = queries[:, None]
    d = np.maximum(q - upper[None], 0.0) + np.maximum(lower[None] - q, 0.0)
    return np.sqrt(np.einsum("qrsc,qrsc->qr", d, d))


def class_mean_distances(dist: np.ndarray, ref_labels: np.ndarray, n_classes: int) -> np.ndarray:
    """Mean distance of each query to the references of each class: ``(n_queries, n_classes)``."""
    out = np.empty((dist.shape[0], n_classes))
    for k in range(n_classes):
        out[:, k] = dist[:, ref_labels == k].mean(axis=1)
    return out


def pruned_nearest_class(
    query: np.ndarray,
    lb: np.ndarray,
    refs: np.ndarray,
    ref_labels: np.ndarray,
    n_classes: int,
    *,
    window: int | None,
    offset: np.ndarray | None = None,
) -> tuple[int, int]:
    """Class index with the lowest mean DTW distance, skipping classes pruned by their lower bounds.

    Classes are visited in order of their mean lower bound ``lb`` (``(n_refs,)``, from :func:`lb_keogh`);
    a class whose mean bound is not below the best exact mean so far cannot win and is skipped (the mean
    of lower bounds bounds the mean distance). ``offset`` (``(n_classes,)``, default 0) is subtracted from
    every class's mean (bound and exact alike, so the pruning stays exact; decision C70).
    Returns ``(class, n_dtw_computed)``.
    """
    off = np.zeros(n_classes) if offset is None else np.asarray(offset, dtype=float)
    lb_mean = np.array([lb[ref_labels == k].mean() for k in range(n_classes)]) - off
    best_k, best_d, computed = -1, math.inf, 0
    for k in np.argsort(lb_mean):
        if lb_mean[k] >= best_d:
            break  # every remaining class has an even larger bound
        members = refs[ref_labels == k]
        d = float(dtw_block(query[None], members, window=window).mean()) - off[k]
        computed += len(members)
        if d < best_d:
            best_k, best_d = int(k), d
    return best_k, computed


def class_spread_offsets(refs: np.ndarray, ref_labels: np.ndarray, n_classes: int, *,
                         window: int | None) -> np.ndarray:
    """Half the mean DTW distance between two different references of each class: ``(n_classes,)``.

    Subtracted from a query's mean distance to the class (decision C70), the score is the one-sample energy
    distance ``E d(q, R) - E d(R, R') / 2`` (Szekely & Rizzo 2013, eq. 2.1 for one point): a class's own spread no
    longer adds to every query's distance to it, so a compact class does not draw the queries of a spread-out one.
    A class with one reference gets 0.
    """
    out = np.zeros(n_classes)
    for k in range(n_classes):
        R = refs[ref_labels == k]
        if len(R) > 1:
            D = dtw_block(R, R, window=window)
            out[k] = 0.5 * float(D[~np.eye(len(R), dtype=bool)].mean())
    return out


# --------------------------------------------------------------------------------------------------
# estimator
# --------------------------------------------------------------------------------------------------
class DTWClassifier(ClassifierMixin, BaseEstimator):
    """Lowest-mean-DTW-distance classifier over a per-user reference set (thesis ch. 6.1.2.2).

    Parameters
    ----------
    n_references : references kept per class (default 36, thesis ch. 6.1.2.2; use
        :data:`THESIS_REFERENCES_PER_CLASS` for the other tasks). Classes with fewer training steps keep all.
    window : Sakoe-Chiba half-width as a fraction of the step length (0.1 = +-10 %, i.e. +-4 samples of
        a 40-sample step). ``None`` = unconstrained DTW.
    standardize : scale each channel by the training mean/std so that channels in different units
        (m/s^2, rad/s) weigh alike.
    prune : use LB_Keogh class pruning in :meth:`predict` (same result, fewer DTW computations; off by
        default: with 108 references of 40 samples the numpy bound costs as much as it saves, see
        docs/decisions/classifiers.md).
    random_state : seed of the reference subset choice (and of the calibration's inner folds).
    calibration : how :meth:`predict_proba`'s softmin temperature is fitted: ``"gap"`` (decision C4: the median
        leave-one-out gap between the references' own-class and nearest other-class mean distance; soft, not a
        probability) or ``"cv"`` (decision C67: the temperature minimising the cross-entropy of the training
        steps' held-out mean distances in an inner cross-validation, :mod:`pdrlearn.classify.calibration`).
        Either way :meth:`predict` is the same (a positive temperature keeps the argmin).
    rule : ``"mean"`` (thesis ch. 6.1.2.2: the class of lowest mean distance) or ``"spread"`` (decision C70: the
        mean distance minus half the class's mean distance between its own references,
        :func:`class_spread_offsets`).

    Attributes
    ----------
    classes_ : class labels; references_ : ``(m, samples, channels)`` reference steps (standardized);
    reference_labels_ : ``(m,)`` class indices; class_offset_ : ``(n_classes,)`` subtracted from the class mean
    distances (0 with ``rule="mean"``); temperature_ : softmin temperature (distance units) for
    :meth:`predict_proba`; channel_mean_, channel_std_ : ``(channels,)``.
    """

    def __init__(
        self,
        *,
        n_references: int = 36,
        window: float | None = 0.1,
        standardize: bool = True,
        prune: bool = False,
        random_state: int | None = 0,
        calibration: str = "gap",
        rule: str = "mean",
    ):
        self.n_references = n_references
        self.window = window
        self.standardize = standardize
        self.prune = prune
        self.random_state = random_state
        self.calibration = calibration
        self.rule = rule

    # -- helpers ---------------------------------------------------------------------------------
    def _validate(self, X, *, reset: bool, series: bool = True) -> np.ndarray:
        if reset:
            X = validate_data(self, X, reset=True, allow_nd=True, dtype=np.float64)
        else:
            X = check_X_fast(self, X, allow_nd=True)
        if X.ndim not in (2, 3):
            raise DataError(
                f"DTWClassifier: X must be (steps, channels, samples) or (steps, samples), got shape {X.shape}"
            )
        return as_series(X) if series else X

    def _window_samples(self, n_samples: int) -> int | None:
        if self.window is None:
            return None
        return max(1, int(round(float(self.window) * n_samples)))

    def _offset(self) -> np.ndarray | float:
        """The fitted class offsets (decision C70); a model fitted before they existed has none (0)."""
        return getattr(self, "class_offset_", 0.0)

    def _scale(self, S: np.ndarray) -> np.ndarray:
        return np.ascontiguousarray((S - self.channel_mean_) / self.channel_std_)

    # -- protocol --------------------------------------------------------------------------------
    def fit(self, X, y):
        """Store up to ``n_references`` standardized reference steps per class; fit the softmin temperature."""
        if self.calibration not in ("gap", "cv"):
            raise DataError(f"DTWClassifier: calibration must be 'gap' or 'cv', got {self.calibration!r}")
        if self.rule not in ("mean", "spread"):
            raise DataError(f"DTWClassifier: rule must be 'mean' or 'spread', got {self.rule!r}")
        X = self._validate(X, reset=True, series=False)
        S = as_series(X)
        y = column_or_1d(y, warn=True)
        check_classification_targets(y)
        if len(y) != len(S):
            raise DataError(f"DTWClassifier: {len(S)} steps but {len(y)} labels")
        self.classes_, yi = np.unique(y, return_inverse=True)
        if self.standardize:
            self.channel_mean_ = S.mean(axis=(0, 1))
            std = S.std(axis=(0, 1))
            self.channel_std_ = np.where(std > 0, std, 1.0)
        else:
            self.channel_mean_ = np.zeros(S.shape[2])
            self.channel_std_ = np.ones(S.shape[2])
        rng = np.random.default_rng(self.random_state)
        keep = []
        for k in range(len(self.classes_)):
            idx = np.flatnonzero(yi == k)
            if len(idx) > self.n_references:
                idx = np.sort(rng.choice(idx, self.n_references, replace=False))
            keep.append(idx)
        keep = np.concatenate(keep)
        self.references_ = self._scale(S[keep])
        self.reference_labels_ = yi[keep]
        self.window_samples_ = self._window_samples(S.shape[1])
        self.envelope_ = envelope(self.references_, window=self.window_samples_)
        self.class_offset_ = (class_spread_offsets(self.references_, self.reference_labels_, len(self.classes_),
                                                   window=self.window_samples_)
                              if self.rule == "spread" else np.zeros(len(self.classes_)))
        self.temperature_ = self._fit_temperature()
        if self.calibration == "cv":
            self.temperature_ = self._cv_temperature(X, yi)
        return self

    def _cv_temperature(self, X: np.ndarray, yi: np.ndarray) -> float:
        """Decision C67: the temperature fitted on the training steps' held-out mean distances (inner
        cross-validation, :func:`pdrlearn.classify.calibration.cv_scores`); C4's gap temperature is the search's
        scale and stays when a class has too few steps to hold one out."""
        from sklearn.base import clone

        from pdrlearn.classify.calibration import cv_scores, fit_temperature

        held = cv_scores(lambda: clone(self).set_params(calibration="gap"), X, yi,
                         lambda est, Xp: -est.mean_distances(Xp), random_state=self.random_state)
        if held is None:
            return self.temperature_
        return fit_temperature(*held, scale=self.temperature_)

    def _fit_temperature(self) -> float:
        """Softmin temperature: median gap between a reference's own-class and nearest other-class mean
        distance (leave-one-out), so probabilities are neither flat nor saturated. Decision: see
        docs/decisions/classifiers.md."""
        R, lab = self.references_, self.reference_labels_
        if len(self.classes_) < 2 or len(R) < 3:
            return 1.0
        D = dtw_block(R, R, window=self.window_samples_)
        np.fill_diagonal(D, np.nan)
        ks = range(len(self.classes_))
        sums = np.stack([np.nansum(D[:, lab == k], axis=1) for k in ks], axis=1)
        counts = np.stack([np.sum(np.isfinite(D[:, lab == k]), axis=1) for k in ks], axis=1)
        means = np.where(counts > 0, sums / np.maximum(counts, 1), np.nanmax(D)) - self.class_offset_  # C70
        own = means[np.arange(len(R)), lab]
        means[np.arange(len(R)), lab] = np.inf
        gap = np.abs(means.min(axis=1) - own)
        t = float(np.median(gap))
        return t if np.isfinite(t) and t > 1e-12 else 1.0

    def mean_distances(self, X) -> np.ndarray:
        """Mean DTW distance of each step to each class's references, minus :attr:`class_offset_` (0 unless
        ``rule="spread"``, decision C70): ``(n, n_classes)``, the scores :meth:`predict` takes the lowest of."""
        check_fitted_fast(self, "references_")
        S = self._scale(self._validate(X, reset=False))
        D = dtw_block(S, self.references_, window=self.window_samples_)
        return class_mean_distances(D, self.reference_labels_, len(self.classes_)) - self._offset()

    def predict_proba(self, X) -> np.ndarray:
        """Softmin of the class mean distances (temperature :attr:`temperature_`)."""
        return softmax(-self.mean_distances(X) / self.temperature_)

    def predict(self, X) -> np.ndarray:
        """Class with the lowest mean DTW distance (thesis ch. 6.1.2.2)."""
        check_fitted_fast(self, "references_")
        if not self.prune:
            means = self.mean_distances(X)
            return self.classes_[np.argmin(means, axis=1)]
        S = self._scale(self._validate(X, reset=False))
        out = np.empty(len(S), dtype=int)
        computed = 0
        upper, lower = self.envelope_
        for i, q in enumerate(S):
            lb = lb_keogh(q[None], upper, lower)[0]
            out[i], c = pruned_nearest_class(
                q,
                lb,
                self.references_,
                self.reference_labels_,
                len(self.classes_),
                window=self.window_samples_,
                offset=self._offset(),
            )
            computed += c
        if len(S):
            log.debug("DTW: %.1f of %d references computed per step", computed / len(S), len(self.references_))
        return self.classes_[out]

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.allow_nan = False
        return tags
