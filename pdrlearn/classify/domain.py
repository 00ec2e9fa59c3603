"""Training-range (domain) check of a user model: is a session's data like the data the model learned?

One mechanism for every classifier (heuristic, DTW, SVM, NN, fused, ensemble; decision C16 in
docs/decisions/classifiers.md): at training time every fitted leaf model (a pipeline or a heuristic rule
classifier) keeps in ``training_range_`` the 1 % and 99 % quantiles of each of *its own inputs* over its
training steps -- the features its classifier sees (SVM / NN feature vectors, the rule features of a
heuristic, the resampled signal samples DTW compares). At prediction time a step's score is its largest
excess beyond a feature's range, in units of that range's width::

    d = max_j max(0, lo_j - f_j, f_j - hi_j) / (hi_j - lo_j)

and a composite model (fused units, ensemble) takes the largest score of its members. A step is out of
domain when ``d > STEP_THRESHOLD``. The fraction of such steps is always reported
(``out_of_domain_fraction``); the detailed one-line warning is opt-in (``warn_at``, CLI ``--warn-out-of-domain``;
without it ``track`` says one short line when more than half the strides are out, decision C61):
with the tested ``FRACTION_THRESHOLD`` it fired on every real gaitmap walk but also on held-out simulated
users walking faster than their calibration, above the 1-in-20 false-alarm rule (decision C16).
``training_range_`` is pickled with the model (joblib), so a model directory keeps it; models saved
before C16 have none (no check, a note).
"""

from __future__ import annotations

import logging
import warnings
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError

log = logging.getLogger(__name__)

#: Training quantiles that bound a feature's range (robust to a few odd training steps; decision C16).
QUANTILES = (0.01, 0.99)
#: A step is out of domain when a feature lies more than this many training-range widths outside its
#: range (C16; fixed before measuring).
STEP_THRESHOLD = 0.5
#: The tested share of out-of-domain steps for the opt-in warning (C16; fixed before measuring, not
#: adopted as a default: 7 of 36 held-out simulated sessions would warn).
FRACTION_THRESHOLD = 0.25
#: Share of a session's checked strides outside the training range above which ``track --model`` and
#: ``track --streaming`` print one warning line without ``--warn-out-of-domain`` (decision C61: a share set by the
#: lead, not measured; C16's per-stride detail line stays opt-in).
DEFAULT_WARN_SHARE = 0.5
#: Fix named in the warning.
FIX = "train a per-user model on this user's labelled sessions: pdrlearn train SESSION_DIR... --out MODEL_DIR"


def fix_text(user: str | None = None) -> str:
    """The fix a training-range line ends with: :data:`FIX` (train a per-user model) for a pooled model; for a
    per-user model (``user``: the one user it was fitted on, :func:`~pdrlearn.classify.training.model_user_key`)
    decision C227's - it already is that user's model, so the strides it never saw go into its calibration."""
    if user is None:
        return FIX
    from pdrlearn.decision_refs import decision_ref

    return (f"this is {user}'s own per-user model, so add strides like these to the calibration: record them in a "
            "labelled session and retrain with it: pdrlearn train CALIBRATION_DIR... NEW_SESSION_DIR --out "
            f"MODEL_DIR ({decision_ref('C227', topic='classifiers')})")


@dataclass
class FeatureRange:
    """Per-feature training range of one leaf model's inputs: ``lo``/``hi`` quantiles over ``n_steps``
    training steps (``model``: the leaf's class name)."""

    model: str
    features: list[str]
    lo: np.ndarray
    hi: np.ndarray
    n_steps: int

    def width(self) -> np.ndarray:
        """Range width per feature, floored so that a constant training feature still has a scale."""
        w = self.hi - self.lo
        floor = 1e-9 + 1e-3 * np.maximum(np.abs(self.lo), np.abs(self.hi))
        return np.maximum(w, floor)

    def excess(self, F: np.ndarray) -> np.ndarray:
        """Per step and feature, the excess beyond the range in range widths (>= 0; NaN features -> 0)."""
        F = np.asarray(F, dtype=float)
        ex = np.maximum(np.maximum(self.lo - F, F - self.hi), 0.0) / self.width()
        return np.nan_to_num(ex, nan=0.0)

    def to_dict(self) -> dict:
        return {"model": self.model, "features": list(self.features),
                "quantiles": list(QUANTILES), "lo": [float(v) for v in self.lo],
                "hi": [float(v) for v in self.hi], "n_steps": int(self.n_steps)}

    @classmethod
    def from_dict(cls, d: dict) -> FeatureRange:
        lo, hi = np.asarray(d["lo"], dtype=float), np.asarray(d["hi"], dtype=float)
        if lo.shape != hi.shape or len(lo) != len(d["features"]):
            raise DataError(f"training range of {d.get('model')}: lo, hi and features differ in length; "
                            "retrain the model")
        return cls(str(d.get("model", "")), list(d["features"]), lo, hi, int(d.get("n_steps", 0)))


#: Decision C71: a stride's joint score is its Mahalanobis distance to the nearest class mean in the leaf's
#: standardized input space, divided by the out-of-fold JOINT_QUANTILE of the training strides' own distances; a
#: stride is out of domain when its joint score exceeds 1 (fixed before measuring).
JOINT_QUANTILE = 0.99
#: Decision C71: folds of the out-of-fold calibration of the joint threshold (fixed before measuring).
JOINT_FOLDS = 5
# Decision C71: ``track --model`` / ``track_plasys`` do not compute the joint score: the candidate failed its
# adoption rule (it flagged neither the 8 % street ramp nor the 4 Hz soft foot); the option is
# ``UserModel.predict_steps(joint_domain=True)`` (``ood_joint_<task>``) and ``domain_report`` of its rows (decision
# C162: no module switch).


@dataclass
class JointDomain:
    """Decision C71: the joint (not per-feature) domain model of one leaf's inputs. ``center`` / ``scale``
    standardize the inputs (training median, C16's 1-99 % range width); ``means`` (classes x features) are the
    class means and ``precision`` the inverse of the Ledoit-Wolf shrunk within-class covariance (one for all
    classes) of the standardized inputs; ``tau`` the out-of-fold :data:`JOINT_QUANTILE` of the training strides'
    distances. Numpy only at prediction time (the lean runtime)."""

    model: str
    center: np.ndarray
    scale: np.ndarray
    means: np.ndarray
    precision: np.ndarray
    tau: float
    n_steps: int

    def distance(self, F: np.ndarray) -> np.ndarray:
        """Per step, the Mahalanobis distance to the nearest class mean (NaN features -> the center)."""
        Z = np.nan_to_num((np.asarray(F, dtype=float) - self.center) / self.scale, nan=0.0)
        return _nearest_mahalanobis(Z, self.means, self.precision)

    def score(self, F: np.ndarray) -> np.ndarray:
        """Per step, the joint score: distance / ``tau`` (> 1: out of domain, decision C71)."""
        return self.distance(F) / self.tau

    def to_dict(self) -> dict:
        return {"model": self.model, "center": self.center.tolist(), "scale": self.scale.tolist(),
                "means": self.means.tolist(), "precision": self.precision.tolist(), "tau": float(self.tau),
                "quantile": JOINT_QUANTILE, "n_steps": int(self.n_steps)}

    @classmethod
    def from_dict(cls, d: dict) -> JointDomain:
        c, s = np.asarray(d["center"], dtype=float), np.asarray(d["scale"], dtype=float)
        m, p = np.asarray(d["means"], dtype=float), np.asarray(d["precision"], dtype=float)
        n = len(c)
        if s.shape != (n,) or m.ndim != 2 or m.shape[1] != n or p.shape != (n, n) or not float(d["tau"]) > 0:
            raise DataError(f"joint domain model of {d.get('model')}: arrays of inconsistent shapes; retrain the "
                            "model")
        return cls(str(d.get("model", "")), c, s, m, p, float(d["tau"]), int(d.get("n_steps", 0)))


def _nearest_mahalanobis(Z: np.ndarray, means: np.ndarray, precision: np.ndarray) -> np.ndarray:
    D = np.empty((len(Z), len(means)))
    for k, mu in enumerate(means):
        R = Z - mu
        D[:, k] = np.einsum("ij,jk,ik->i", R, precision, R)
    return np.sqrt(np.maximum(D.min(axis=1), 0.0))


def _joint_fit(Z: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Class means and the precision of the Ledoit-Wolf shrunk pooled within-class covariance of ``Z``."""
    from sklearn.covariance import ledoit_wolf  # training side only: the runtime reads the stored arrays

    classes = sorted(set(y.tolist()), key=str)
    means = np.array([Z[y == c].mean(axis=0) for c in classes])
    R = Z - means[[classes.index(v) for v in y.tolist()]]
    cov, _ = ledoit_wolf(R, assume_centered=True)
    return means, np.linalg.pinv(cov, hermitian=True)


def fit_joint(est, X: np.ndarray, y: np.ndarray) -> JointDomain:
    """Decision C71: the joint domain model of a leaf's inputs over its training windows ``X`` with labels
    ``y``; the threshold ``tau`` from out-of-fold distances (:data:`JOINT_FOLDS` interleaved folds)."""
    F, _ = model_inputs(est, X)
    F = np.asarray(F, dtype=float)
    y = np.asarray(y).astype(str)
    with warnings.catch_warnings():  # a feature NaN on every training step (a unit's missing sensor) -> 0
        warnings.simplefilter("ignore", RuntimeWarning)
        center = np.nan_to_num(np.nanmedian(F, axis=0))
        lo, hi = np.nan_to_num(np.nanquantile(F, QUANTILES, axis=0))
    scale = FeatureRange("", [], np.asarray(lo), np.asarray(hi), len(F)).width()
    Z = np.nan_to_num((F - center) / scale, nan=0.0)
    order = np.argsort(y, kind="stable")  # interleave within classes so that each fold holds every class
    fold = np.empty(len(y), dtype=int)
    fold[order] = np.arange(len(y)) % JOINT_FOLDS
    oof = np.full(len(y), np.nan)
    for k in range(JOINT_FOLDS):
        te, tr = fold == k, fold != k
        if te.any() and len(set(y[tr].tolist())) == len(set(y.tolist())):
            m, p = _joint_fit(Z[tr], y[tr])
            oof[te] = _nearest_mahalanobis(Z[te], m, p)
    means, precision = _joint_fit(Z, y)
    ok = np.isfinite(oof)
    tau = float(np.quantile(oof[ok], JOINT_QUANTILE)) if ok.any() else float(
        np.quantile(_nearest_mahalanobis(Z, means, precision), JOINT_QUANTILE))
    return JointDomain(type(est).__name__, center, scale, means, precision, max(tau, 1e-9), int(len(F)))


def attach_joint(est, X: np.ndarray, y: np.ndarray) -> int:
    """Decision C71: store ``training_joint_`` on every leaf of the fitted ``est`` that has none yet; returns how
    many leaves have one. A leaf whose inputs cannot be computed keeps none."""
    return _attach(est, X, "training_joint_", lambda leaf, Xl: fit_joint(leaf, Xl, y), "joint domain model",
                   np.linalg.LinAlgError)


def step_joint_score(est, X: np.ndarray) -> np.ndarray | None:
    """Decision C71: per step, the joint score of the windows ``X`` (composite model: the largest over its
    leaves); None when a leaf has no joint model (trained before C71) or its inputs cannot be computed."""
    X = np.asarray(X, dtype=float)
    out = np.zeros(len(X))
    for leaf, Xl in _leaves(est, X):
        j = getattr(leaf, "training_joint_", None)
        if j is None:
            return None
        try:
            F = model_inputs(leaf, Xl)[0]
        except (MissingSensorError, DataError, ValueError):
            return None
        if F.ndim != 2 or F.shape[1] != len(j.center):
            return None
        out = np.maximum(out, j.score(F))
    return out


def _leaves(est, X: np.ndarray) -> list[tuple[object, np.ndarray]]:
    """The leaf models of ``est`` with the window columns each one reads (fused units / ensemble members
    of a :class:`~pdrlearn.classify.fusion.UnitFusionClassifier` recursively)."""
    members = getattr(est, "estimators_", None)
    if members is not None and hasattr(est, "units"):
        out = []
        for member, (_, _, cols) in zip(members, est.units, strict=True):
            out += _leaves(member, X[:, cols])
        return out
    return [(est, X)]


def model_inputs(est, X: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """What a leaf model's classifier sees for the windows ``X``: ``(n_steps, n_features)`` and the feature
    names. A pipeline: the output of every step before the classifier (flattened: DTW's signals become
    their samples ``signal[k]``); a heuristic rule classifier: its rule features."""
    from sklearn.pipeline import Pipeline

    if isinstance(est, Pipeline):
        Xt = X
        for _, step in est.steps[:-1]:
            Xt = step.transform(Xt)
        Xt = np.asarray(Xt, dtype=float)
        first = est.steps[0][1]
        if Xt.ndim == 3:  # DTW: (steps, signals, samples)
            sigs = list((getattr(first, "kw_args", None) or {}).get("names", ()))
            if len(sigs) != Xt.shape[1]:
                sigs = [f"signal{i}" for i in range(Xt.shape[1])]
            names = [f"{s}[{k}]" for s in sigs for k in range(Xt.shape[2])]
            return Xt.reshape(len(Xt), -1), names
        try:
            names = [str(n) for n in first.get_feature_names_out()]
        except Exception:  # noqa: BLE001 - names are informative only
            names = []
        if len(names) != Xt.shape[1]:
            names = [f"feature{j}" for j in range(Xt.shape[1])]
        return Xt, names
    if hasattr(est, "_features") and hasattr(est, "_stages"):  # heuristic rule classifiers
        names = list(est._feature_names(est._stages()))
        return np.asarray(est._features(X, names), dtype=float), names
    raise DataError(f"{type(est).__name__}: no known inputs for the training-range check")


def fit_range(est, X: np.ndarray) -> FeatureRange:
    """The training range of a leaf model's inputs over the step windows ``X`` it was trained on."""
    F, names = model_inputs(est, X)
    lo, hi = np.nanquantile(F, QUANTILES, axis=0)
    return FeatureRange(type(est).__name__, names, np.asarray(lo), np.asarray(hi), int(len(F)))


def attach_ranges(est, X: np.ndarray) -> int:
    """Store ``training_range_`` on every leaf of the fitted ``est`` that has none yet (training windows
    ``X``); returns how many leaves have one. A leaf whose inputs cannot be computed keeps none."""
    return _attach(est, X, "training_range_", fit_range, "training range")


def _attach(est, X: np.ndarray, attr: str, fit, what: str, *also) -> int:
    """The one mechanism of :func:`attach_ranges`, :func:`attach_joint` and :func:`attach_class_ranges`: ``attr`` =
    ``fit(leaf, leaf's inputs)`` on every leaf of ``est`` that has none yet; returns how many leaves have one. A leaf
    whose inputs cannot be computed (or whose fit raises one of ``also``) keeps none, said at INFO as "no WHAT"."""
    n = 0
    for leaf, Xl in _leaves(est, X):
        if getattr(leaf, attr, None) is None:
            try:
                setattr(leaf, attr, fit(leaf, Xl))
            except (MissingSensorError, DataError, ValueError, *also) as exc:
                log.info("no %s for %s: %s", what, type(leaf).__name__, exc)
                continue
        n += 1
    return n


def fit_class_ranges(est, X: np.ndarray, y: np.ndarray, *, min_steps: int = 10) -> dict[str, FeatureRange]:
    """Steps decision 96: per class with at least ``min_steps`` training steps, :func:`fit_range` of a leaf's inputs
    over that class's windows (C16's quantiles, one class at a time)."""
    y = np.asarray(y).astype(str)
    return {c: fit_range(est, np.asarray(X)[y == c]) for c in sorted(set(y.tolist())) if (y == c).sum() >= min_steps}


def attach_class_ranges(est, X: np.ndarray, y: np.ndarray) -> int:
    """Steps decision 96: store ``training_class_ranges_`` (:func:`fit_class_ranges`) on every leaf of the fitted
    ``est`` that has none yet; returns how many leaves have them. A leaf whose inputs cannot be computed keeps none."""
    return _attach(est, X, "training_class_ranges_", lambda leaf, Xl: fit_class_ranges(leaf, Xl, y),
                   "per-class training ranges")


def step_class_score(est, X: np.ndarray, labels) -> tuple[np.ndarray, list[str]] | None:
    """Steps decision 96: per step, C16's score of the windows ``X`` against the training range of its labelled
    class (``labels``) and the feature that set it (composite model: the largest over its leaves); NaN for a class
    the model kept no range of. None when a leaf has no per-class ranges (trained before 96) or no inputs."""
    X = np.asarray(X, dtype=float)
    labels = np.asarray(labels).astype(str)
    d = np.zeros(len(X))
    known = np.ones(len(X), dtype=bool)
    worst = np.full(len(X), "", dtype=object)
    for leaf, Xl in _leaves(est, X):
        ranges = getattr(leaf, "training_class_ranges_", None)
        if ranges is None:
            return None
        try:
            F = np.asarray(model_inputs(leaf, Xl)[0], dtype=float)
        except (MissingSensorError, DataError, ValueError):
            return None
        for c in set(labels.tolist()):
            rows = labels == c
            if c not in ranges or F.shape[1] != len(ranges[c].lo):
                known &= ~rows
                continue
            ex = ranges[c].excess(F[rows])
            du, arg = ex.max(axis=1), ex.argmax(axis=1)
            better = du > d[rows]
            idx = np.flatnonzero(rows)[better]
            d[idx] = du[better]
            worst[idx] = [ranges[c].features[j] for j in arg[better]]
    return np.where(known, d, np.nan), list(worst)


def class_domain(d: np.ndarray, labels, worst: list[str]) -> dict[str, dict]:
    """Steps decision 96: per labelled class, :func:`summarize` of its steps' :func:`step_class_score`."""
    d = np.asarray(d, dtype=float)
    labels = np.asarray(labels).astype(str)
    w = np.asarray(worst, dtype=object)
    return {c: summarize(d[labels == c], list(w[labels == c]), "") for c in sorted(set(labels.tolist()))}


def class_domain_line(task: str, by_class: dict[str, dict], pooled: float | None, *,
                      share: float = DEFAULT_WARN_SHARE, min_steps: int = 10) -> str | None:
    """Steps decision 96: the one line when more than ``share`` (C61's) of some class's labelled steps (at least
    ``min_steps`` checked) lie outside the range of the training steps of that class; the class most off. ``pooled``:
    C16's share over the whole training range, said for contrast. None otherwise, and None when more than ``share``
    lie outside the whole range (C16's printed share says it; its detailed line stays opt-in)."""
    from pdrlearn.decision_refs import decision_ref

    if pooled is not None and pooled > share:
        return None
    off = {c: s for c, s in by_class.items()
           if s.get("fraction") is not None and s["n_steps"] >= min_steps and s["fraction"] > share}
    if not off:
        return None
    c, s = max(off.items(), key=lambda kv: kv[1]["fraction"])
    feat = f", most often {s['feature']}" if s.get("feature") else ""
    also = [f"{o} {100 * so['fraction']:.0f} %" for o, so in off.items() if o != c]
    whole = "" if pooled is None else f", though {100 * pooled:.0f} % lie outside its whole training range"
    return (f"{task}: {s['n_out']} of {s['n_steps']} labelled '{c}' steps ({100 * s['fraction']:.0f} %{feat}"
            f"{'; also ' + ', '.join(also) if also else ''}) lie outside the range of the steps the model learned "
            f"'{c}' from{whole}: it learned the class from other steps than these (e.g. trained on stairs, "
            f"evaluated on slopes), so these scores are not its accuracy on the data it was trained for; train on "
            f"labelled steps like these ({decision_ref(96, topic='steps')})")


def has_ranges(est) -> bool:
    """Whether every leaf of ``est`` stores a training range (models saved before C16: False)."""
    members = getattr(est, "estimators_", None)
    if members is not None and hasattr(est, "units"):
        return all(has_ranges(m) for m in members)
    return getattr(est, "training_range_", None) is not None


def step_score(est, X: np.ndarray) -> tuple[np.ndarray, list[str]] | None:
    """Per step, the score ``d`` (module doc) of the windows ``X`` against the training range of the model
    ``est`` (composite: the largest over its members) and the feature that set it. None when a leaf has
    no range (a model saved before C16) or its inputs cannot be computed on ``X``."""
    X = np.asarray(X, dtype=float)

    def inputs(leaf, Xl):
        try:
            return model_inputs(leaf, Xl)[0]
        except (MissingSensorError, DataError, ValueError):
            return None

    return combine_scores(((getattr(leaf, "training_range_", None), lambda leaf=leaf, Xl=Xl: inputs(leaf, Xl))
                           for leaf, Xl in _leaves(est, X)), len(X))


def combine_scores(leaves, n: int) -> tuple[np.ndarray, list[str]] | None:
    """The score ``d`` (module doc) of ``n`` steps over a model's leaves, given as ``(FeatureRange or None, inputs)``
    pairs (``inputs()``: the leaf's ``(n, features)`` inputs, or None when they cannot be computed): the largest
    excess over the leaves and the feature that set it; None when a leaf has no range or no inputs of the range's
    width. One mechanism for the trained model (:func:`step_score`) and the exported bundle
    (:mod:`pdrlearn.runtime.domain`, decision E105)."""
    d = np.zeros(n)
    worst = np.full(n, "", dtype=object)
    for r, inputs in leaves:
        if r is None:
            return None
        F = inputs()
        if F is None or F.ndim != 2 or F.shape[1] != len(r.lo):
            return None
        ex = r.excess(F)
        du = ex.max(axis=1)
        arg = ex.argmax(axis=1)
        better = du > d
        d = np.where(better, du, d)
        worst[better] = [r.features[j] for j in arg[better]]
    return d, list(worst)


def joint_fraction(pred, tasks) -> float | None:
    """Decision C71: the largest task's share of checked steps whose joint score (``ood_joint_<task>`` of a
    prediction table) exceeds 1; None when no step has one (the check is unavailable: a model trained before
    C71)."""
    shares = []
    for task in tasks:
        col = f"ood_joint_{task}"
        if col in pred:
            v = np.asarray(pred[col], dtype=float)
            v = v[np.isfinite(v)]
            if len(v):
                shares.append(float((v > 1).mean()))
    return max(shares) if shares else None


def summarize(d: np.ndarray, worst: list[str], unit: str) -> dict:
    """A task's out-of-domain summary over its checked steps (``d``: :func:`step_score` per step, NaN =
    not checked): fraction, counts, the models checked, the feature most often farthest out, the largest
    and median score."""
    d = np.asarray(d, dtype=float)
    ok = np.isfinite(d)
    out = d[ok] > STEP_THRESHOLD
    names = [w for w, o, k in zip(worst, d > STEP_THRESHOLD, ok, strict=True) if o and k and w]
    # the most frequent; a tie goes to the first name in sorted order (session 52, I3: max over a set followed the
    # string hash, so summary.json's feature changed with PYTHONHASHSEED)
    top = min(set(names), key=lambda w: (-names.count(w), w)) if names else None
    return {"unit": unit, "n_steps": int(ok.sum()), "n_out": int(out.sum()),
            "fraction": float(out.mean()) if ok.any() else None,
            "max_score": float(d[ok].max()) if ok.any() else None,
            "median_score": float(np.median(d[ok])) if ok.any() else None,
            "feature": top}


def domain_report(per_task: dict[str, dict], *, warn_at: float | None = None) -> dict:
    """Session-level result: ``out_of_domain_fraction`` (largest task fraction; None when no task was
    checked), ``tasks`` (per task :func:`summarize`), the thresholds and ``warn`` (the fraction reaches
    ``warn_at``; always False when ``warn_at`` is None, the default)."""
    check_warn_at(warn_at)
    checked = {t: s for t, s in per_task.items() if s.get("fraction") is not None}
    frac = max((s["fraction"] for s in checked.values()), default=None)
    return {"out_of_domain_fraction": frac, "tasks": per_task,
            "step_threshold": STEP_THRESHOLD, "warn_at": warn_at,
            "warn": warn_at is not None and frac is not None and frac >= warn_at}


def check_warn_at(warn_at: float | None) -> None:
    """``warn_at`` must be None or a fraction in (0, 1]."""
    if warn_at is not None and not (np.isfinite(warn_at) and 0 < warn_at <= 1):
        raise DataError(f"--warn-out-of-domain {warn_at!r}: give a fraction of strides in (0, 1], e.g. "
                        f"{FRACTION_THRESHOLD}")


def warning_line(report: dict, *, what: str = "steps", user: str | None = None) -> str | None:
    """The one warning line for a session whose data lie outside the model's training range, else None:
    the fraction, the task/unit it concerns (others in brackets), the feature most often off, and the fix
    (:func:`fix_text`: C227's for a per-user model of ``user``)."""
    if not report or not report.get("warn"):
        return None
    tasks = {t: s for t, s in report["tasks"].items() if s.get("fraction") is not None}
    t, s = max(tasks.items(), key=lambda kv: kv[1]["fraction"])
    others = [f"{o} {so['unit']} {100 * so['fraction']:.0f} %" for o, so in tasks.items()
              if o != t and so["fraction"] >= report["warn_at"]]
    feat = f", most often {s['feature']}" if s.get("feature") else ""
    return (f"{s['n_out']} of {s['n_steps']} {what} ({100 * s['fraction']:.0f} %) lie outside the model's "
            f"training range for the {t} classifier ({s['unit']}{feat}"
            f"{'; also ' + ', '.join(others) if others else ''}): the model was trained on data unlike this "
            f"session and its classes are unreliable here; {fix_text(user)}")


def session_warning_line(report: dict | None, *, what: str = "strides", user: str | None = None) -> str | None:
    """Decision C61: the line ``track`` prints for a session's report: C16's detailed line when the opt-in
    ``warn_at`` is reached, else, when more than :data:`DEFAULT_WARN_SHARE` of the checked strides of a task lie
    outside the training range, one short line saying what it means for the classes and naming
    ``--warn-out-of-domain`` for the detail; else None. ``user``: the per-user model's user (C227, :func:`fix_text`)."""
    line = warning_line(report, what=what, user=user)
    if line or not report or report.get("out_of_domain_fraction") is None:
        return line
    tasks = {t: s for t, s in report["tasks"].items() if s.get("fraction") is not None}
    t, s = max(tasks.items(), key=lambda kv: kv[1]["fraction"])
    if s["fraction"] <= DEFAULT_WARN_SHARE:
        return None
    return (f"{s['n_out']} of {s['n_steps']} {what} ({100 * s['fraction']:.0f} %) lie outside the model's training "
            f"range ({t} classifier): the model never saw strides like these, so its terrain / direction / length "
            f"classes (and the heights and lengths they set) are unreliable for this session "
            f"(--warn-out-of-domain 0.25 details the classifier and the feature most often off); {fix_text(user)}")


NO_RANGES_NOTE = ("the model stores no training ranges (trained before pdrlearn checked them): data unlike its "
                  "training data are not detected; retrain it to enable the check")


__all__ = ["QUANTILES", "STEP_THRESHOLD", "FRACTION_THRESHOLD", "FeatureRange", "model_inputs", "fit_range",
           "attach_ranges", "has_ranges", "step_score", "combine_scores", "check_warn_at", "summarize", "domain_report",
           "warning_line", "session_warning_line", "DEFAULT_WARN_SHARE",
           "NO_RANGES_NOTE", "JOINT_QUANTILE", "JOINT_FOLDS", "JointDomain", "fit_joint",
           "attach_joint", "step_joint_score", "joint_fraction", "fit_class_ranges", "attach_class_ranges",
           "step_class_score", "class_domain", "class_domain_line"]
