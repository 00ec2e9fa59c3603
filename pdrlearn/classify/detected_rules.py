"""Decision C226: ``evaluate`` scores the length class ``track`` / ``run`` report on the detected strides.

``evaluate``'s figures are the classifier's own; ``track`` / ``run`` then give a stride the class of its measured
length when it turns (C88) or when that length contradicts its class by the margin (C191). On a session the
classifier never saw (trial s49t2's tandem walk: 11 of 11 strides called ``long``), evaluate read 0.0 % while track
wrote ``short`` for all 11. This module measures each detected stride's length as track does (the foot's
rest-to-rest ZUPT displacement, :class:`~pdrlearn.displace.FootDisplacement`, with the model's distance gain, L26)
and applies the runtime's kernel (:func:`~pdrlearn.kernels.turn_length.turn_length_class_one`, C91)."""

from __future__ import annotations

import numpy as np
import pandas as pd


def measured_strides(session, strides: pd.DataFrame, gain: float = 1.0) -> pd.DataFrame | None:
    """Decision C226: each of ``strides``' (``start_s`` / ``end_s``) horizontal length (m, with the level-stride
    ``gain``, decision L26) and foot turn (rad) as track's M3 measures them (rows aligned; NaN for a stride
    without a swing between two rests); None without the foot accelerometer and gyroscope."""
    from pdrlearn.displace import FootDisplacement
    from pdrlearn.displace.force_check import checked_stance
    from pdrlearn.kernels.distance import apply_level_gain
    from pdrlearn.orient.filters import unit_data

    if not len(strides) or not session.has("fAccelerometer", "fGyroscope"):
        return None
    foot = unit_data(session, "foot", purpose="evaluate's measured stride lengths (C226)")
    stance = checked_stance(session, foot)[0]  # as M3 (L365)
    fd = FootDisplacement().estimate(foot, strides[["start_s", "end_s"]].reset_index(drop=True), stance=stance)
    out = pd.DataFrame({"length_m": np.nan, "turn_rad": np.nan}, index=range(len(strides)))
    if len(fd.rows_):
        disp = apply_level_gain(fd.disp_, gain)
        rows = np.asarray(fd.rows_, dtype=int)
        out.loc[rows, "length_m"] = np.hypot(disp[:, 0], disp[:, 1])
        out.loc[rows, "turn_rad"] = np.asarray(fd.yaw_change_, dtype=float)
    return out


def track_length_classes(pred, measured: pd.DataFrame, bounds) -> np.ndarray:
    """Decisions C88 / C191 (C226): the length classes track reports for the classifier's ``pred`` (one per
    stride) from ``measured`` (:func:`measured_strides`) and the model's ``bounds`` (``{class: (lo, hi)}``)."""
    from pdrlearn.kernels.turn_length import TURN_LENGTH_RULE, turn_length_class_one

    pred = np.asarray(pred, dtype=object)
    if not TURN_LENGTH_RULE or not bounds:
        return pred.copy()
    out = pred.copy()
    for i, (label, length, turn) in enumerate(zip(pred, measured["length_m"].to_numpy(float),
                                                  measured["turn_rad"].to_numpy(float), strict=True)):
        if np.isfinite(length):
            out[i] = turn_length_class_one(label, None, length, turn, bounds)[0]
    return out


def model_bounds_and_gain(model) -> tuple[dict | None, float]:
    """The model's length-class bounds (parsed) and its distance gain (1 without an applicable calibration)."""
    from pdrlearn.displace import model_distance_calibration, model_length_bounds, parse_bounds

    raw = model_length_bounds(model)
    rec = model_distance_calibration(model)
    return (None if raw is None else parse_bounds(raw)), float((rec or {}).get("gain", 1.0))


def track_length_score(model, data, windows, sess_rows: dict, detected) -> dict | None:
    """Decision C226: the length task on the strides the runtime detects (C49's matching, IoU >= ``MIN_IOU``) as
    track / run report it: the chosen model's class after C88 / C191 (:func:`track_length_classes`).
    ``accuracy`` over ``n_steps`` matched and classified steps, ``n_changed`` the strides whose class the rules
    changed; None without bounds, without a detector or without a matched step."""
    from pdrlearn.classify.detected import MIN_IOU
    from pdrlearn.track.evaluate import match_by_overlap

    bounds, gain = model_bounds_and_gain(model)
    if not bounds:
        return None
    y_true, y_pred, changed = [], [], 0
    for i, rows in sess_rows.items():
        got = detected.session(i)
        if got is None or got[1] is None or "length_class" not in got[1]:
            continue
        strides, pred = got
        measured = measured_strides(detected.sessions[i], strides, gain)
        if measured is None:
            continue
        cls = pred["length_class"].to_numpy(dtype=object)
        new = track_length_classes(cls, measured, bounds)
        lab = windows[i].steps.iloc[data.step[rows]][["start_s", "end_s"]].reset_index(drop=True)
        for si, li in match_by_overlap(strides, lab, min_iou=MIN_IOU):
            if isinstance(cls[si], str):
                y_true.append(str(data.y[rows[li]]))
                y_pred.append(str(new[si]))
                changed += int(new[si] != cls[si])
    if not y_true:
        return None
    yt, yp = np.array(y_true), np.array(y_pred)
    return {"accuracy": float(np.mean(yt == yp)), "n_steps": len(yt), "n_changed": changed}


def track_length_line(det: dict | None, track: dict | None) -> str | None:
    """Decision C226: the line evaluate adds under the length task when track's rules (C88 / C191) change the
    class of at least one detected stride: what track / run report there, the count changed, the decisions."""
    if not track or not track["n_changed"]:
        return None
    from pdrlearn.decision_refs import decision_ref

    before = "" if not det or not det.get("n_steps") else f" (the classifier's own: {100 * det['accuracy']:.1f} %)"
    return (f"length as track / run report it: {100 * track['accuracy']:.1f} % on the strides the runtime detects"
            f"{before}: the measured-length rules changed the class of {track['n_changed']} of {track['n_steps']} "
            "strides (a turning stride, or one whose measured length contradicts its class by more than 5 %, takes "
            f"the class of its measured length; {decision_ref('C88', 'C191', 'C226', topic='classifiers')})")
