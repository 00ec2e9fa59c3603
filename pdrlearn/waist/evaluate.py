"""Metrics of a waist track against the references of a session (Mobilise-D style labels).

- ``step_f1`` and IC timing: detected step events vs every reference initial contact
  (``extras["ics"]``), scored with :func:`pdrlearn.steps.evaluate.score_events`. When the session has
  reference walking bouts, only detections inside the bouts (+- the matching tolerance) are scored,
  because the reference marks contacts only there (decision W9); ``step_f1_all`` scores the whole
  recording. Where the reference has a contact without a time (``extras["ics_untimed"]``: INDIP NaN,
  with the interval between its timed neighbours), up to that many detections inside the interval
  (farther than the tolerance from both neighbours, so they cannot match a timed contact) are not
  scored: the step happened, only its time is unknown (docs/external-data.md X2); ``n_unscored`` counts
  them. Where the session has a second IC reference (``extras["ics_stereophoto"]``, the lab's optical
  motion capture, docs/external-data.md X4), ``ic_timing_stereo_mean_ms`` / ``_sd_ms`` give the timing
  of the detections matched to it and ``stereo_recall`` its recall (no precision: its capture volume
  covers only part of a bout).
- ``distance_error_pct``: distance tracked inside the reference bouts (steps whose midpoint lies in a
  bout) vs the bouts' total reference length; ``bout_distance_error_median_pct`` is the median of the
  per-bout absolute errors (unsigned), ``bout_distance_error_median_signed_pct`` of the signed ones (decision
  L251). ``*_strides_*``: the same against the bout's own reference steps, its number of steps (timed contacts,
  duplicates < 0.1 s apart merged, plus untimed ones, minus one) times half its mean stride length
  (:func:`bout_stride_length`, decision W25): INDIP's ``Length`` is 8-27 % short in bouts with untimed contacts
  (docs/external-data.md X2b).
- ``stride_length_mae_m``: per reference stride, the sum of the tracked steps whose midpoint lies in it.
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.io import Session
from pdrlearn.steps.evaluate import DEFAULT_TOLERANCE_S, score_events, score_steps

log = logging.getLogger(__name__)


def reference_bouts(session: Session) -> pd.DataFrame | None:
    """Reference walking bouts (``start_s``, ``end_s``, ``length_m``), one level only (``wb``)."""
    b = session.extras.get("bouts")
    if b is None or len(b) == 0:
        return None
    missing = sorted({"start_s", "end_s", "length_m"} - set(b.columns))
    if missing:  # say why no distance error is reported instead of dropping it silently
        log.warning("%s: bouts.csv has no %s column(s) (start_ms, end_ms, length_m): no bout distance "
                    "error or bout-limited step scoring", session.name, ", ".join(missing))
        return None
    return _one_level(b).dropna(subset=["start_s", "end_s", "length_m"]).reset_index(drop=True)


def _one_level(b: pd.DataFrame) -> pd.DataFrame:
    """The rows of one level of a bouts table: ``wb`` when it has some, else its first row's level."""
    if "level" in b:
        lv = b["level"].astype(str)
        b = b[lv == ("wb" if (lv == "wb").any() else lv.iloc[0])]
    return b


def reference_wbs(session: Session) -> pd.DataFrame | None:
    """Decision W493: the reference walking bouts WB detection is scored against - :func:`reference_bouts`' rows
    (one level, ``wb``) with a start and an end, a length or not; None without any."""
    b = session.extras.get("bouts")
    if b is None or len(b) == 0 or not {"start_s", "end_s"} <= set(b.columns):
        return None
    b = _one_level(b).dropna(subset=["start_s", "end_s"]).reset_index(drop=True)
    return b if len(b) else None


def _in_intervals(x: np.ndarray, starts: np.ndarray, ends: np.ndarray, pad: float = 0.0) -> np.ndarray:
    m = np.zeros(len(x), dtype=bool)
    for a, b in zip(starts, ends, strict=True):
        m |= (x >= a - pad) & (x <= b + pad)
    return m


def step_metrics(steps: pd.DataFrame, session: Session, *, tolerance_s: float = DEFAULT_TOLERANCE_S) -> dict:
    """``step_f1``, ``step_f1_all``, ``ic_timing_mean_ms``, ``ic_timing_sd_ms`` (empty dict without ICs).

    ``step_f1`` is :func:`pdrlearn.steps.evaluate.score_steps`'s F1, so ``track`` and ``steps`` score the
    same contacts with one rule (decision 19): detections inside the reference bouts (W9; without
    ``bouts.csv``, inside first..last reference contact) +- the tolerance, those standing for untimed
    contacts and one per same-foot reference gap (decision 20) left out."""
    ics = session.extras.get("ics")
    if ics is None or "ic_s" not in ics:
        return {}
    ref = np.sort(ics["ic_s"].dropna().to_numpy(float))
    ev = np.sort(steps["event_s"].to_numpy(float)) if len(steps) else np.zeros(0)
    out = {"step_f1_all": score_events(ev, ref, tolerance_s=tolerance_s)["f1"]}
    sc = score_steps(steps.assign(unit="waist") if len(steps) else steps, session, tolerance_s=tolerance_s,
                     unit="waist")
    if sc is None:  # no timed contact at all
        return out
    out.update(step_f1=sc["f1"], step_precision=sc["precision"], step_recall=sc["recall"],
               ic_timing_mean_ms=1e3 * sc["timing_error_mean_s"],
               ic_timing_sd_ms=1e3 * sc["timing_error_sd_s"],
               n_detected=sc["scored_count"], n_reference=sc["reference_count"],
               n_unscored=sc["unscored_untimed"] + sc["unscored_same_foot_gap"],
               step_f1_same_foot_gaps_scored=sc["f1_same_foot_gaps_scored"])
    second = session.extras.get("ics_stereophoto")
    if second is not None and "ic_s" in second and len(second):
        all_ev = np.sort(steps["event_s"].to_numpy(float)) if len(steps) else np.zeros(0)
        s2 = score_events(all_ev, np.sort(second["ic_s"].dropna().to_numpy(float)), tolerance_s=tolerance_s)
        out.update(ic_timing_stereo_mean_ms=1e3 * s2["timing_error_mean_s"],
                   ic_timing_stereo_sd_ms=1e3 * s2["timing_error_sd_s"], stereo_recall=s2["recall"],
                   n_stereo_matched=s2["true_positives"])
    return out


def _mid(steps: pd.DataFrame) -> np.ndarray:
    return 0.5 * (steps["start_s"].to_numpy(float) + steps["end_s"].to_numpy(float))


def steps_in_interval(steps: pd.DataFrame, start_s: float, end_s: float) -> np.ndarray:
    """Boolean mask of the steps whose length counts toward the walk ``[start_s, end_s]`` (s).

    The one accounting rule of the evaluation and of the calibration (decisions W9, W21): a step (IC to
    next IC) counts when its midpoint lies inside. A reference bout runs from its first to its last
    initial contact, so N detected contacts matching the bout's N contacts give exactly its N - 1 steps;
    the step that ends at the first contact and the one that starts at the last lie outside, and a
    sequence-closing contact (``end_s == start_s``) carries no length.
    """
    mid = _mid(steps)
    return (mid >= start_s) & (mid <= end_s)


DUPLICATE_IC_S = 0.1  # reference contacts closer than this are one contact (no step is that short, W25)


def bout_stride_length(session: Session, start_s: float, end_s: float) -> tuple[float, int]:
    """``(length_m, n_steps)`` of the reference bout ``[start_s, end_s]`` from its own strides (decision W25):
    ``n_steps`` = its timed initial contacts (duplicates closer than :data:`DUPLICATE_IC_S` merged) plus
    its untimed ones (``extras["ics_untimed"]``), minus one; length = ``n_steps`` x half the mean length of
    the reference strides inside the bout (a stride is two steps). NaN without contacts or strides with
    a length."""
    ics, st = session.extras.get("ics"), session.steps
    if ics is None or "ic_s" not in ics or st is None or "length_m" not in st:
        return float("nan"), 0
    eps = 1e-6
    ic = np.sort(ics["ic_s"].dropna().to_numpy(float))
    ic = ic[(ic >= start_s - eps) & (ic <= end_s + eps)]
    n_ic = int(ic.size and 1 + np.sum(np.diff(ic) >= DUPLICATE_IC_S))
    u = session.extras.get("ics_untimed")
    if u is not None and {"after_s", "before_s"} <= set(u.columns):
        n_ic += int(((u["after_s"] >= start_s - eps) & (u["before_s"] <= end_s + eps)).sum())
    s = st.dropna(subset=["length_m"])
    s = s[(s["start_s"] >= start_s - eps) & (s["end_s"] <= end_s + eps)]
    if n_ic < 2 or not len(s):
        return float("nan"), max(n_ic - 1, 0)
    return float((n_ic - 1) * s["length_m"].mean() / 2.0), n_ic - 1


def distance_metrics(steps: pd.DataFrame, session: Session) -> dict:
    """``distance_error_pct`` (total over the bouts), per-bout errors and their median (empty without
    bouts); the same against the bouts' own reference strides (``*_strides_*``, :func:`bout_stride_length`)
    where the session has them."""
    bouts = reference_bouts(session)
    if bouts is None:
        return {}
    lengths = steps["length_m"].abs().to_numpy(float)
    has_next = steps["has_next"].to_numpy(bool) if "has_next" in steps else np.ones(len(steps), dtype=bool)
    per = []
    for _, b in bouts.iterrows():
        m = steps_in_interval(steps, b.start_s, b.end_s)
        est = float(lengths[m].sum())
        ref_s, n_ref = bout_stride_length(session, b.start_s, b.end_s)
        per.append({"start_s": float(b.start_s), "end_s": float(b.end_s), "reference_m": float(b.length_m),
                    "tracked_m": est, "error_pct": 100.0 * (est - b.length_m) / b.length_m,
                    "reference_strides_m": ref_s, "error_strides_pct": 100.0 * (est - ref_s) / ref_s,
                    "n_steps": int((m & has_next).sum()), "n_reference_steps": n_ref})
    ref_total = float(bouts.length_m.sum())
    est_total = float(sum(p["tracked_m"] for p in per))
    out = {"distance_error_pct": 100.0 * (est_total - ref_total) / ref_total,
           "bout_distance_m": est_total, "bout_reference_m": ref_total,
           "bout_distance_error_median_pct": float(np.median([abs(p["error_pct"]) for p in per])),
           # decision L251: the median above is of |error| (its sign is lost); the signed median is a bias
           "bout_distance_error_median_signed_pct": float(np.median([p["error_pct"] for p in per])),
           "bouts": per}
    es = np.array([p["error_strides_pct"] for p in per])
    if np.isfinite(es).all():
        ref_s_total = float(sum(p["reference_strides_m"] for p in per))
        out.update(distance_error_strides_pct=100.0 * (est_total - ref_s_total) / ref_s_total,
                   bout_reference_strides_m=ref_s_total,
                   bout_distance_error_strides_median_pct=float(np.median(np.abs(es))))
    return out


def stride_metrics(steps: pd.DataFrame, session: Session) -> dict:
    """``stride_length_mae_m`` over reference strides with a length (empty without them)."""
    st = session.steps
    if st is None or "length_m" not in st or not st["length_m"].notna().any():
        return {}
    st = st.dropna(subset=["length_m"])
    lengths = steps["length_m"].abs().to_numpy(float)
    est = np.array([lengths[steps_in_interval(steps, r.start_s, r.end_s)].sum() for r in st.itertuples()])
    err = est - st["length_m"].to_numpy(float)
    return {"stride_length_mae_m": float(np.mean(np.abs(err))), "stride_length_bias_m": float(np.mean(err)),
            "n_strides": int(len(err))}


def waist_metrics(steps: pd.DataFrame, session: Session) -> dict:
    """All of the above in one flat dict (``bouts`` = per-bout list)."""
    out: dict = {}
    out.update(step_metrics(steps, session))
    out.update(distance_metrics(steps, session))
    out.update(stride_metrics(steps, session))
    return out
