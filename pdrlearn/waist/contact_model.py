"""A learned re-scorer of the offline lower-back contacts: keep or drop each contact the detector found (decision W203).

Per contact, :data:`FEATURES` from signals the `waist-pendulum` pipeline already computes (W189's bounce, W20's lateral
velocity and side, W109 / W184's left/right pairs, the times to its neighbours, the W4/W76 gate, W102's trunk tilt,
W104's flexion window, W127's yaw turned by its step), every one scale-free (divided by the recording's own median or
by a decision's constant). A logistic regression on them, its probability calibrated by C67's mechanism (an inner
cross-validation's held-out scores and a fitted temperature, :mod:`pdrlearn.classify.calibration`): a contact is kept
when p >= :data:`KEEP_P`.

The fitted numbers ship as JSON beside this module (``contact_model.json``; numpy only at run time, no pickle); a file
whose version or feature list is not this code's is refused in one line. Trained by
``experiments/waist_contact_model.py train`` (:func:`fit_contact_model`; deterministic).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.textfile import read_json
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.posture import (
    TRANSFER_PEAK_DEG,
    alternating_pairs,
    contact_tilt_deg,
    drop_contacts,
    flexion_events,
    near_flexion,
    undecided_between,
)

MODEL_PATH = Path(__file__).with_name("contact_model.json")
#: W203: the bundle format; a file with another version is refused (retrain it)
VERSION = 1
#: W203: the features, in the model's column order
FEATURES = ("bounce_rel", "run_bounce_rel", "sway_rel", "side_decided", "paired", "dt_prev_rel", "dt_next_rel",
            "rhythm_irregularity", "log_run_len", "log_gate_rel", "tilt_rel", "flexed", "turn_rel")
#: W203: a missing neighbour's time, in median step times (beyond W16's longest step, 1.5 s, at any cadence)
MISSING_DT_REL = 3.0
#: W203: a contact is kept when its calibrated probability of being a true contact reaches even odds (not tuned)
KEEP_P = 0.5
#: W203: the values of the ``contact_model`` option of ``track_waist``
CONTACT_MODEL_VALUES = (False, "learned")
RETRAIN = "OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_contact_model.py train"


def _rel(x: np.ndarray, scale: float) -> np.ndarray:
    return x / scale if scale > 0 else np.zeros_like(x)


def feature_matrix(event_s: np.ndarray, has_next: np.ndarray, bounce: np.ndarray, v_lat: np.ndarray,
                   side: np.ndarray, gate_ratio: np.ndarray, tilt_deg: np.ndarray, flexed: np.ndarray,
                   dyaw_rad: np.ndarray) -> np.ndarray:
    """The ``(n, len(FEATURES))`` matrix of W203 from per-contact arrays (pure kernel).

    ``bounce``: W189's :func:`~pdrlearn.kernels.waist.contact_bounce`; ``v_lat``: W20's lateral velocity at the
    contact; ``side``: W20's +1 / -1 / 0; ``gate_ratio``: the gate SD at the contact over the gate's threshold;
    ``tilt_deg``: W102's trunk tilt; ``flexed``: inside W104's flexion window; ``dyaw_rad``: the yaw turned from
    the contact to the next (0 for a sequence's last contact)."""
    ev = np.asarray(event_s, dtype=np.float64)
    n = ev.size
    if n == 0:
        return np.zeros((0, len(FEATURES)))
    hn = np.asarray(has_next, dtype=bool)
    b = np.asarray(bounce, dtype=np.float64)
    rid = K.run_ids(hn)
    run_med = np.array([np.median(b[rid == r]) for r in range(rid[-1] + 1)])
    run_len = np.bincount(rid).astype(float)
    b_med = float(np.median(b))
    v = np.abs(np.asarray(v_lat, dtype=np.float64))
    side = np.asarray(side, dtype=int)
    dt = np.diff(ev)
    step_dt = dt[hn[:-1]]
    dt_med = float(np.median(step_dt)) if step_dt.size else 0.0
    dt_next = np.full(n, np.nan)
    dt_next[:-1] = np.where(hn[:-1], dt, np.nan)
    dt_prev = np.full(n, np.nan)
    dt_prev[1:] = dt_next[:-1]
    both = np.isfinite(dt_prev) & np.isfinite(dt_next)
    irr = np.ones(n)
    irr[both] = np.abs(dt_next[both] - dt_prev[both]) / (dt_next[both] + dt_prev[both])
    dt_rel = [np.where(np.isfinite(d), np.minimum(_rel(np.nan_to_num(d), dt_med), MISSING_DT_REL), MISSING_DT_REL)
              for d in (dt_prev, dt_next)]
    paired = alternating_pairs(side, hn) | undecided_between(side, hn, opposite=True)  # W109, W184
    return np.column_stack([
        _rel(b, b_med), _rel(run_med[rid], b_med),  # W189
        _rel(v, float(np.median(v))),  # W20's scale
        (side != 0).astype(float), paired.astype(float),
        dt_rel[0], dt_rel[1], irr, np.log(run_len[rid]),
        np.log(np.maximum(np.asarray(gate_ratio, dtype=np.float64), 1e-3)),  # W4 / W76
        np.asarray(tilt_deg, dtype=np.float64) / TRANSFER_PEAK_DEG,  # W102 over W104's 25 deg
        np.asarray(flexed, dtype=float),  # W104
        np.abs(np.asarray(dyaw_rad, dtype=np.float64)) / np.radians(K.TURN_STEP_DEG),  # W127's 15 deg
    ])


def contact_features(steps: pd.DataFrame, imu: WaistIMU, thr: float, sigma: np.ndarray,
                     gyro_bias_rps: float = 0.0) -> np.ndarray:
    """W203's features of each contact of ``steps`` (``event_s``, ``has_next``) on ``imu``; ``thr`` and ``sigma``:
    the offline gate's threshold and SD signal (:func:`pdrlearn.waist.events.gate_threshold`)."""
    ev = steps["event_s"].to_numpy(float)
    hn = steps["has_next"].to_numpy(bool)
    if ev.size == 0:
        return np.zeros((0, len(FEATURES)))
    idx = np.clip(np.round((ev - imu.t[0]) * imu.fs).astype(int), 0, len(imu.t) - 1)
    v_lat = contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, ev)
    flexed = near_flexion(ev, flexion_events(imu, ev, hn))  # W104's window, as transfer_veto reads it
    nxt = np.append(ev[1:], ev[-1])
    dyaw = np.where(hn, K.integrate_rate(imu.t, imu.w_z - gyro_bias_rps, ev, nxt), 0.0)  # W127
    return feature_matrix(ev, hn, K.contact_bounce(imu.acc_v, imu.fs, idx), v_lat, K.step_sides(v_lat, hn),
                          np.asarray(sigma, dtype=np.float64)[idx] / max(float(thr), 1e-9),
                          contact_tilt_deg(imu, ev, hn), flexed, dyaw)


@dataclass(frozen=True)
class ContactModel:
    """W203's fitted logistic regression: standardised features, weights, intercept and C67's temperature."""

    mean: np.ndarray
    scale: np.ndarray
    coef: np.ndarray
    intercept: float
    temperature: float
    trained_on: str = ""

    def decision(self, X: np.ndarray) -> np.ndarray:
        return ((np.asarray(X, dtype=np.float64) - self.mean) / self.scale) @ self.coef + self.intercept

    def proba(self, X: np.ndarray) -> np.ndarray:
        """Calibrated probability that each contact is a true one: ``softmax((0, d) / T)[1]`` (C67's form)."""
        return 1.0 / (1.0 + np.exp(-self.decision(X) / self.temperature))

    def to_json(self) -> dict:
        return {"version": VERSION, "features": list(FEATURES), "mean": self.mean.round(10).tolist(),
                "scale": self.scale.round(10).tolist(), "coef": self.coef.round(10).tolist(),
                "intercept": round(float(self.intercept), 10), "temperature": round(float(self.temperature), 10),
                "keep_p": KEEP_P, "trained_on": self.trained_on}


def fit_contact_model(X: np.ndarray, y: np.ndarray, *, trained_on: str = "", random_state: int = 0) -> ContactModel:
    """W203: a logistic regression (lbfgs, C = 1) on standardised ``X``, labels ``y`` (1 = a true contact), its
    temperature fitted by C67's inner cross-validation on the two class scores ``(0, d)``."""
    from sklearn.linear_model import LogisticRegression
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    from pdrlearn.classify.calibration import cv_scores, fit_temperature

    X = np.asarray(X, dtype=np.float64)
    y = np.asarray(y, dtype=int)
    if len(np.unique(y)) < 2:
        raise DataError("contact model: the training contacts hold one class only; train on routes with false "
                        "contacts too (decision W203)")

    def make():
        return make_pipeline(StandardScaler(), LogisticRegression(C=1.0, max_iter=1000, random_state=random_state))

    def score(est, Xp):
        d = est.decision_function(Xp)
        return np.column_stack([np.zeros_like(d), d])

    est = make().fit(X, y)
    held = cv_scores(make, X, y, score, random_state=random_state)
    temperature = fit_temperature(*held) if held is not None else 1.0  # C67
    sc, lr = est.named_steps["standardscaler"], est.named_steps["logisticregression"]
    return ContactModel(mean=sc.mean_.copy(), scale=sc.scale_.copy(), coef=lr.coef_[0].copy(),
                        intercept=float(lr.intercept_[0]), temperature=float(temperature), trained_on=trained_on)


def load_contact_model(path: str | Path = MODEL_PATH) -> ContactModel:
    """The shipped (or given) model; a missing or unreadable file, another version or another feature list is refused
    in one line naming the file and the retrain command (decision W203)."""
    path = Path(path)
    try:
        d = read_json(path)
    except (OSError, ValueError) as exc:
        raise DataError(f"{path}: cannot read the contact model ({exc.__class__.__name__}); retrain it: "
                        f"{RETRAIN}") from None
    if not isinstance(d, dict) or d.get("version") != VERSION:
        got = d.get("version") if isinstance(d, dict) else None
        raise DataError(f"{path}: contact model version {got!r}, this pdrlearn reads version {VERSION} "
                        f"(decision W203); retrain it: {RETRAIN}")
    if d.get("features") != list(FEATURES):
        raise DataError(f"{path}: contact model features differ from this pdrlearn's (decision W203); retrain it: "
                        f"{RETRAIN}")
    try:
        arr = {k: np.asarray(d[k], dtype=np.float64) for k in ("mean", "scale", "coef")}
        m = ContactModel(mean=arr["mean"], scale=arr["scale"], coef=arr["coef"], intercept=float(d["intercept"]),
                         temperature=float(d["temperature"]), trained_on=str(d.get("trained_on", "")))
    except (KeyError, TypeError, ValueError):
        raise DataError(f"{path}: contact model fields missing or not numbers (decision W203); retrain it: "
                        f"{RETRAIN}") from None
    if any(a.shape != (len(FEATURES),) for a in (m.mean, m.scale, m.coef)) or not (m.scale > 0).all() \
            or not m.temperature > 0:
        raise DataError(f"{path}: contact model arrays do not fit its {len(FEATURES)} features (decision W203); "
                        f"retrain it: {RETRAIN}")
    return m


def save_contact_model(model: ContactModel, path: str | Path = MODEL_PATH) -> None:
    from pdrlearn.atomic import atomic_file

    with atomic_file(path) as tmp:
        tmp.write_text(json.dumps(model.to_json(), indent=1) + "\n")


def rescore_contacts(steps: pd.DataFrame, imu: WaistIMU, thr: float, sigma: np.ndarray, *,
                     gyro_bias_rps: float = 0.0, model: ContactModel | None = None) -> pd.DataFrame:
    """``steps`` without the contacts whose calibrated probability (:meth:`ContactModel.proba`) is under
    :data:`KEEP_P` (decision W203); ``attrs["n_rescored"]`` counts the dropped, ``attrs["contact_p"]`` holds every
    input contact's probability."""
    if steps.empty:
        out = steps.copy()
        out.attrs["n_rescored"] = 0
        return out
    model = model or load_contact_model()
    p = model.proba(contact_features(steps, imu, thr, sigma, gyro_bias_rps))
    out = drop_contacts(steps, p >= KEEP_P, "n_rescored")
    out.attrs["contact_p"] = p
    return out
