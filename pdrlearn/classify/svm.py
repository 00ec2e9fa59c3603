"""One-vs-rest support vector machines with the thesis kernels per task (thesis ch. 6.1.1.1, 6.2.1.1,
6.3.1.1).

Each class gets its own binary SVM (positive = that class) with its own kernel; a step goes to the class
whose model gives the highest decision score (thesis ch. 6.1.1.1, "the index of the element with the
highest score"). Features are standardized first (scikit-learn Pipeline).
"""

from __future__ import annotations

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin, clone
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler
from sklearn.svm import SVC
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import check_is_fitted, validate_data

from pdrlearn.errors import DataError
from pdrlearn.kernels.proba import softmax  # = scipy.special.softmax, no array-API dispatch

#: Kernel per class and task. Terrain: three one-vs-rest 3rd-order polynomial models (thesis ch. 6.1.1.1);
#: direction: linear (thesis ch. 6.2.1.1); length: short rbf with automatic scale, normal 2nd-order
#: polynomial, long linear (thesis ch. 6.3.1.1).
THESIS_KERNELS: dict[str, dict[str, dict]] = {
    "terrain": {c: {"kernel": "poly", "degree": 3} for c in ("flat", "up", "down")},
    "direction": {c: {"kernel": "linear"} for c in ("forward", "backward")},
    "length": {
        "short": {"kernel": "rbf"},
        "normal": {"kernel": "poly", "degree": 2},
        "long": {"kernel": "linear"},
    },
}
#: Kernel of a class the table does not name (and of every class when ``task`` is None).
DEFAULT_KERNEL = {"kernel": "rbf"}


def kernel_for(task: str | None, label) -> dict:
    """SVC keyword arguments of the one-vs-rest model of ``label`` in ``task``."""
    return dict(THESIS_KERNELS.get(task or "", {}).get(str(label), DEFAULT_KERNEL))


def svc_decision(
    Z: np.ndarray,
    sv: np.ndarray,
    dual: np.ndarray,
    b: float,
    *,
    kernel: str,
    gamma: float,
    degree: int,
    coef0: float,
) -> np.ndarray:
    """Decision values ``sum_i dual_i K(sv_i, z) + b`` of a fitted binary SVC, ``(n,)``.

    Same numbers as :meth:`sklearn.svm.SVC.decision_function` (positive = the class labelled 1), without
    its per-call overhead (a few microseconds for one step instead of ~0.15 ms).
    """
    if kernel == "linear":
        K = Z @ sv.T
    elif kernel == "poly":
        K = (gamma * (Z @ sv.T) + coef0) ** degree
    elif kernel == "rbf":
        d2 = np.sum(Z**2, axis=1)[:, None] - 2 * Z @ sv.T + np.sum(sv**2, axis=1)[None, :]
        K = np.exp(-gamma * np.maximum(d2, 0.0))
    else:  # pragma: no cover - kernels are fixed by THESIS_KERNELS
        raise DataError(f"svc_decision: unsupported kernel {kernel!r}")
    return K @ dual + b


def stack_decisions(params: list[dict]) -> dict:
    """The per-class decision parameters of :func:`svc_decision` stacked for :func:`ovr_scores`: every
    class's support vectors as rows of one ``sv`` array (one product ``Z @ sv.T`` for all classes), the
    intercepts ``b``, and per class its row range, kernel settings, dual coefficients and (rbf) squared
    support-vector norms computed once."""
    bounds = np.cumsum([0] + [len(p["sv"]) for p in params])
    blocks = []
    for p, a, b in zip(params, bounds[:-1], bounds[1:], strict=True):
        sv_sq = np.sum(p["sv"] ** 2, axis=1)[None, :] if p["kernel"] == "rbf" else None
        blocks.append((int(a), int(b), p["kernel"], p["gamma"], p["degree"], p["coef0"], p["dual"], sv_sq))
    return {"sv": np.ascontiguousarray(np.vstack([p["sv"] for p in params])), "blocks": blocks,
            "b": np.array([p["b"] for p in params], dtype=float)}


def ovr_scores(Z: np.ndarray, stack: dict) -> np.ndarray:
    """Decision values ``(n, n_classes)`` of every class's binary SVC: the formulas of :func:`svc_decision`
    per class, with the products of all classes in one matrix product (per-step latency, issue 5; equal
    to the per-class calls within 1e-12, tests/test_classify_length_fast.py)."""
    G = Z @ stack["sv"].T
    out = np.empty((Z.shape[0], len(stack["blocks"])))
    for j, (a, b, kernel, gamma, degree, coef0, dual, sv_sq) in enumerate(stack["blocks"]):
        g = G[:, a:b]
        if kernel == "linear":
            K = g
        elif kernel == "poly":
            K = (gamma * g + coef0) ** degree
        elif kernel == "rbf":  # |z - s|^2 = |z|^2 - 2 <z, s> + |s|^2, as svc_decision
            K = np.exp(-gamma * np.maximum((Z * Z).sum(axis=1)[:, None] - 2 * g + sv_sq, 0.0))
        else:  # pragma: no cover - kernels are fixed by THESIS_KERNELS
            raise DataError(f"ovr_scores: unsupported kernel {kernel!r}")
        out[:, j] = K @ dual
    out += stack["b"]  # + each class's intercept
    return out


def check_fitted_fast(est, attribute: str) -> None:
    """``check_is_fitted(est)``, skipping scikit-learn's tag lookups (~30 us a call) when ``attribute``, which
    ``fit`` sets, exists: per-step latency (issue 5)."""
    if not hasattr(est, attribute):
        check_is_fitted(est)


def check_X_fast(est, X, *, allow_nd: bool = False, finite: bool = True) -> np.ndarray:
    """Fast path of ``validate_data(est, X, reset=False)`` for a float64 array of the fitted width (2-D,
    or 2-/3-D with ``allow_nd``; finite unless ``finite=False``) - one step at a time is the runtime case;
    anything else goes through scikit-learn's checks."""
    if (
        type(X) is np.ndarray
        and X.dtype == np.float64
        and (X.ndim == 2 or (allow_nd and X.ndim == 3))
        and X.shape[0] > 0
        and X.shape[1] == getattr(est, "n_features_in_", -1)
        and (not finite or np.isfinite(X).all())
    ):
        return X
    return validate_data(est, X, reset=False, dtype=np.float64, allow_nd=allow_nd, ensure_all_finite=finite)


def refuse_step_windows(est, X, method: str) -> None:
    """A 3-D step-window array given to a classifier of 2-D feature matrices: say which pipeline takes it
    (scikit-learn's own message was "Found array with dim 3")."""
    if getattr(X, "ndim", None) == 3:  # not np.ndim: array-likes may refuse __array_function__
        task = getattr(est, "task", None) or "terrain"
        name = type(est).__name__
        raise DataError(
            f"{name} takes a 2-D feature matrix (steps, features), not step windows of shape {tuple(X.shape)}: "
            f"use pdrlearn.classify.make_estimator({task!r}, {method!r}, 'foot') (features + classifier), or "
            f"Pipeline([('features', make_features({task!r}, 'foot', {method!r})), ('clf', {name}(...))])"
        )


class SVMClassifier(ClassifierMixin, BaseEstimator):
    """One-vs-rest SVMs with per-class kernels behind one scikit-learn estimator.

    Parameters
    ----------
    task : ``"terrain"``, ``"direction"``, ``"length"`` or ``None`` (rbf for every class).
    C : soft-margin penalty of every binary model, or ``"cv"``: the value of ``C_grid`` with the best
        inner stratified 3-fold CV accuracy (thesis ch. 2.4.2.2: "each combination of parameter choices is
        checked using cross validation, and the parameters with best cross validation accuracy are
        chosen"); ties -> the smallest C (widest margin).
    C_grid : candidates for ``C="cv"``.
    coef0 : independent term of the polynomial kernels; 1.0 gives MATLAB's ``(1 + x'y)^p`` form (decision
        in docs/decisions/classifiers.md).
    class_weight : ``"balanced"`` (each binary SVC balances its positive class against the rest), ``None``,
        or a dict label -> weight applied as per-step weights.
    random_state : seed of the inner folds of ``C="cv"`` and of every binary SVC (decisions C65, C66: each
        draws from its own generator, never numpy's global one; ``None`` is scikit-learn's global generator).

    Attributes
    ----------
    classes_ : labels; estimators_ : one fitted ``StandardScaler -> SVC`` pipeline per class;
    kernels_ : the kernel settings used per class.
    """

    def __init__(
        self,
        *,
        task: str | None = None,
        C: float | str = "cv",
        C_grid: tuple[float, ...] = (0.3, 1.0, 3.0, 10.0),
        coef0: float = 1.0,
        class_weight: str | dict | None = "balanced",
        random_state: int | None = 0,
    ):
        self.task = task
        self.C = C
        self.C_grid = C_grid
        self.coef0 = coef0
        self.class_weight = class_weight
        self.random_state = random_state

    def fit(self, X, y):
        refuse_step_windows(self, X, "svm")
        X, y = validate_data(self, X, y, dtype=np.float64)
        check_classification_targets(y)
        self.classes_ = np.unique(y)
        if len(self.classes_) < 2:
            raise DataError(f"SVMClassifier: only one class ({self.classes_[0]!r}); label steps of at least 2 classes")
        sample_weight = None
        if isinstance(self.class_weight, dict):  # per original class -> per step
            sample_weight = np.array([self.class_weight.get(v, 1.0) for v in y], dtype=float)
        binary_weight = self.class_weight if self.class_weight == "balanced" else None
        self.C_ = self._select_C(X, y) if isinstance(self.C, str) else float(self.C)
        self.kernels_ = {}
        self.estimators_ = []
        for c in self.classes_:  # one model per class, also for 2 classes (symmetric scores)
            kw = kernel_for(self.task, c)
            self.kernels_[str(c)] = kw
            # decision C65: SVC draws a libsvm seed from random_state when fitting; None would draw it from
            # numpy's global generator (fitting would change what runs after it)
            svc = SVC(C=self.C_, coef0=self.coef0, gamma="scale", class_weight=binary_weight,
                      random_state=self.random_state, **kw)
            model = clone(make_pipeline(StandardScaler(), svc))
            model.fit(X, (y == c).astype(int), svc__sample_weight=sample_weight)
            self.estimators_.append(model)
        scaler = self.estimators_[0][0]  # every model standardizes the same X identically
        self.mean_, self.scale_ = scaler.mean_, scaler.scale_
        self.decision_params_ = [
            dict(
                sv=m[1].support_vectors_,
                dual=m[1].dual_coef_[0],
                b=float(m[1].intercept_[0]),
                kernel=m[1].kernel,
                gamma=float(m[1]._gamma),
                degree=int(m[1].degree),
                coef0=float(m[1].coef0),
            )
            for m in self.estimators_
        ]
        self.decision_stack_ = stack_decisions(self.decision_params_)
        return self

    def __setstate__(self, state):
        super().__setstate__(state)
        self.__dict__.setdefault("random_state", 0)  # models saved before C65: their folds used seed 0
        if "decision_params_" in self.__dict__ and "decision_stack_" not in self.__dict__:
            self.decision_stack_ = stack_decisions(self.decision_params_)  # models saved before the stack

    def _select_C(self, X: np.ndarray, y: np.ndarray) -> float:
        if self.C != "cv":
            raise DataError(f"SVMClassifier: C must be a number or 'cv', not {self.C!r}")
        from sklearn.model_selection import StratifiedKFold

        counts = np.unique(y, return_counts=True)[1]
        if counts.min() < 3 or not self.C_grid:
            return 1.0
        # decision C66: the inner folds follow random_state (fixed at 0 before; 0 is the default)
        folds = list(StratifiedKFold(3, shuffle=True, random_state=self.random_state).split(X, y))
        best_c, best_acc = 1.0, -1.0
        for c in sorted(self.C_grid):
            acc = 0.0
            for tr, te in folds:
                if len(np.unique(y[tr])) < 2:
                    continue
                m = SVMClassifier(task=self.task, C=float(c), coef0=self.coef0, class_weight=self.class_weight,
                                  random_state=self.random_state)
                acc += float(np.sum(m.fit(X[tr], y[tr]).predict(X[te]) == y[te]))
            if acc > best_acc:
                best_c, best_acc = float(c), acc
        return best_c

    def decision_function(self, X) -> np.ndarray:
        """One-vs-rest scores ``(n, n_classes)`` (for 2 classes, the score of ``classes_[1]``)."""
        scores = self._scores(X)
        return scores[:, 1] - scores[:, 0] if len(self.classes_) == 2 else scores

    def _scores(self, X) -> np.ndarray:
        check_fitted_fast(self, "decision_stack_")
        Z = (check_X_fast(self, X) - self.mean_) / self.scale_
        return ovr_scores(Z, self.decision_stack_)

    def predict(self, X) -> np.ndarray:
        """Class of the model with the highest score (thesis ch. 6.1.1.1)."""
        scores = self._scores(X)
        return self.classes_[np.argmax(scores, axis=1)]

    def predict_proba(self, X) -> np.ndarray:
        """Softmax of the one-vs-rest scores (a confidence, not a calibrated probability)."""
        return softmax(self._scores(X))
