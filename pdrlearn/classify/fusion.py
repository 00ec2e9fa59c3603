"""Decision fusion across body units: a weighted soft vote of per-unit classifiers (thesis ch. 6, "SVM
Fusion" / "Neural Network Fusion" rows of Tables 27, 28, 33).

Each unit's model sees its own columns of ``X`` (axis 1: feature columns of a 2-D array, or channels of a
``(steps, channels, samples)`` array), like :class:`sklearn.compose.ColumnTransformer`. The fused
probability is ``sum_u w_u p_u`` with weights summing to 1, given or learned on a held-out validation
split (grid over the weight simplex, highest validation accuracy, ties broken by log-loss).
"""

from __future__ import annotations

import itertools
import logging

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin, clone
from sklearn.model_selection import train_test_split
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import validate_data

from pdrlearn.classify.svm import check_fitted_fast, check_X_fast
from pdrlearn.errors import DataError
from pdrlearn.kernels.proba import align_proba, soft_vote  # noqa: F401 (shared with the runtime)

log = logging.getLogger(__name__)


# -- kernels ---------------------------------------------------------------------------------------
def simplex_grid(n_units: int, step: float) -> np.ndarray:
    """All weight vectors with entries in multiples of ``step`` summing to 1: ``(m, n_units)``."""
    k = int(round(1.0 / step))
    rows = [c for c in itertools.product(range(k + 1), repeat=n_units) if sum(c) == k]
    return np.array(rows, dtype=float) / k


def best_weights(probas: list[np.ndarray], y_idx: np.ndarray, *, step: float = 0.05) -> np.ndarray:
    """Simplex weights maximising validation accuracy of the soft vote, ties -> lowest log-loss, then
    the most even weights."""
    best_key, best_w = None, None
    even = np.full(len(probas), 1.0 / len(probas))
    for w in simplex_grid(len(probas), step):
        p = soft_vote(probas, w)
        acc = float(np.mean(np.argmax(p, axis=1) == y_idx))
        ll = float(-np.mean(np.log(np.clip(p[np.arange(len(y_idx)), y_idx], 1e-12, None))))
        key = (-acc, round(ll, 9), float(np.abs(w - even).sum()))
        if best_key is None or key < best_key:
            best_key, best_w = key, w
    return best_w


# -- estimator -------------------------------------------------------------------------------------
class UnitFusionClassifier(ClassifierMixin, BaseEstimator):
    """Weighted soft vote of per-unit classifiers.

    Parameters
    ----------
    units : list of ``(name, estimator, columns)``: each estimator (with ``predict_proba``) is fitted on
        ``X[:, columns]``; ``columns`` is a list of indices or a slice along axis 1.
    weights : ``None`` (learn on a validation split) or one weight per unit (normalized to sum 1), e.g.
        the foot 0.6 / waist 0.4 of thesis ch. 6.2.2.3.
    validation_size : share of the training steps held out (stratified) to learn the weights; the unit
        models are then refitted on all steps.
    weight_step : grid step of the weight search.
    random_state : seed of the validation split.

    Attributes
    ----------
    classes_, estimators_ (fitted per unit, same order as ``units``), weights_ (``(n_units,)``),
    unit_names_, validation_accuracy_ (per unit and ``"fused"``, when weights were learned).
    """

    def __init__(
        self,
        units,
        *,
        weights=None,
        validation_size: float = 0.25,
        weight_step: float = 0.05,
        random_state: int | None = 0,
    ):
        self.units = units
        self.weights = weights
        self.validation_size = validation_size
        self.weight_step = weight_step
        self.random_state = random_state

    @staticmethod
    def _columns(X: np.ndarray, cols) -> np.ndarray:
        return X[:, cols]

    def _check_units(self) -> None:
        if not self.units:
            raise DataError("UnitFusionClassifier: give at least one (name, estimator, columns) unit")
        if self.weights is not None and len(self.weights) != len(self.units):
            raise DataError(f"UnitFusionClassifier: {len(self.weights)} weights for {len(self.units)} units")

    def _fit_units(self, X, y) -> list:
        return [clone(est).fit(self._columns(X, cols), y) for _, est, cols in self.units]

    def _probas(self, estimators, X) -> list[np.ndarray]:
        return [
            aligned_proba(unit_predict_proba(est, self._columns(X, cols)), est.classes_, self.classes_)
            for est, (_, _, cols) in zip(estimators, self.units, strict=True)
        ]

    def fit(self, X, y):
        self._check_units()
        # NaN channels (a sensor the session lacks) are left to the unit models, which use their own columns
        X, y = validate_data(self, X, y, allow_nd=True, dtype=np.float64, ensure_all_finite=False)
        check_classification_targets(y)
        self.classes_, y_idx = np.unique(y, return_inverse=True)
        self.unit_names_ = [name for name, _, _ in self.units]
        self.validation_accuracy_ = {}
        if self.weights is not None:
            w = np.asarray(self.weights, dtype=float)
            if np.any(w < 0) or w.sum() <= 0:
                raise DataError(f"UnitFusionClassifier: weights must be >= 0 and not all 0, got {list(w)}")
            self.weights_ = w / w.sum()
        elif len(self.units) == 1:
            self.weights_ = np.ones(1)
        else:
            self.weights_ = self._learn_weights(X, y, y_idx)
        self.estimators_ = self._fit_units(X, y)
        return self

    def _learn_weights(self, X, y, y_idx) -> np.ndarray:
        counts = np.bincount(y_idx)
        n_val = int(round(self.validation_size * len(y)))
        if counts.min() < 2 or n_val < len(self.classes_) or len(y) - n_val < len(self.classes_):
            log.info("fusion: too few steps for a validation split, equal weights")
            return np.full(len(self.units), 1.0 / len(self.units))
        Xt, Xv, yt, yv = train_test_split(X, y, test_size=n_val, stratify=y, random_state=self.random_state)
        yv_idx = np.searchsorted(self.classes_, yv)
        probas = self._probas(self._fit_units(Xt, yt), Xv)
        w = best_weights(probas, yv_idx, step=self.weight_step)
        for name, p in zip(self.unit_names_, probas, strict=True):
            self.validation_accuracy_[name] = float(np.mean(np.argmax(p, axis=1) == yv_idx))
        self.validation_accuracy_["fused"] = float(np.mean(np.argmax(soft_vote(probas, w), axis=1) == yv_idx))
        return w

    def unit_proba(self, X) -> dict[str, np.ndarray]:
        """Each unit's probabilities, aligned to :attr:`classes_`."""
        check_fitted_fast(self, "estimators_")
        X = check_X_fast(self, X, allow_nd=True, finite=False)
        return dict(zip(self.unit_names_, self._probas(self.estimators_, X), strict=True))

    def predict_proba(self, X) -> np.ndarray:
        """Weighted soft vote of the units' probabilities."""
        return soft_vote(list(self.unit_proba(X).values()), self.weights_)

    def predict(self, X) -> np.ndarray:
        proba = self.predict_proba(X)
        return self.classes_[np.argmax(proba, axis=1)]


def aligned_proba(proba: np.ndarray, model_classes, classes) -> np.ndarray:
    """:func:`align_proba`, returning ``proba`` itself when it is already float64 in the order of
    ``classes`` (the usual case; the copy would hold the same numbers): per-step latency, issue 5."""
    if (
        proba.dtype == np.float64
        and type(model_classes) is np.ndarray
        and type(classes) is np.ndarray
        and model_classes.ndim == 1
        and model_classes.tolist() == classes.tolist()
    ):
        return proba
    return align_proba(proba, model_classes, classes)


def unit_predict_proba(est, X) -> np.ndarray:
    """``est.predict_proba(X)``; a fitted Pipeline's steps are called directly (what ``Pipeline.predict_proba``
    does without routed parameters, minus its per-call tag and fitted-state lookups: per-step latency)."""
    steps = getattr(est, "steps", None)
    if steps is None:
        return est.predict_proba(X)
    for _, step in steps[:-1]:
        if step is not None and step != "passthrough":
            X = step.transform(X)
    return steps[-1][1].predict_proba(X)


def fused_from_fitted(units, fitted: list, weights, *, n_features_in: int, random_state: int | None = 0):
    """A fitted :class:`UnitFusionClassifier` from already-fitted unit models (no refit).

    ``units`` as for the class (the unfitted templates, kept as parameters so ``clone`` works),
    ``fitted`` the fitted models in the same order, ``weights`` the unit weights.
    """
    w = np.asarray(weights, dtype=float)
    est = UnitFusionClassifier(units, weights=list(w), random_state=random_state)
    est._check_units()
    if len(fitted) != len(units):
        raise DataError(f"fused_from_fitted: {len(fitted)} fitted models for {len(units)} units")
    est.classes_ = np.unique(np.concatenate([np.asarray(m.classes_) for m in fitted]))
    est.estimators_ = list(fitted)
    est.weights_ = w / w.sum()
    est.unit_names_ = [name for name, _, _ in units]
    est.validation_accuracy_ = {}
    est.n_features_in_ = int(n_features_in)
    return est
