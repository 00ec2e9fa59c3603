"""Decision W493 (session 43, issue 8, trial T1 finding F2): walking-bout-level evaluation of a track against the
reference walking bouts of its session (``bouts.csv`` level ``wb``, Mobilise-D's INDIP WBs), as mobgap's
validation reports it: WB detection (each reference WB matched to a detected bout by overlap: TP / FP / FN,
precision, recall, F1) and the per-WB digital mobility outcomes (cadence, stride length, walking speed) of each
matched pair against the reference's.

The matching is mobgap's ``categorize_intervals`` (mobgap/gait_sequences/evaluation.py, re-exported by
mobgap.pipeline.evaluation): a detected bout and a reference WB are a true positive when their overlap is at least
``overlap_threshold`` (default 0.8) of BOTH intervals' durations; a threshold above 0.5 makes the pairing one-to-one.
A detected bout matched to no WB is a false positive, a WB matched to no bout a false negative. The relative error
is mobgap's ``rel_error`` (mobgap/pipeline/_error_metrics.py): (detected - reference) / reference, here in %.

The table (``wb_scores.csv``, :data:`WB_SCORE_COLUMNS`) has one row per reference WB (``tp`` or ``fn``) and one per
unmatched detected bout (``fp``); a ``fn`` row names the detected bout that overlaps it most (if any) with its
overlap and DMO errors, so that why it failed to match is visible, but the summary's medians are over ``tp`` rows
only, as mobgap's. Pure functions; the track calls :func:`wb_evaluation`.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: mobgap's categorize_intervals default overlap_threshold (mobgap/gait_sequences/evaluation.py); it must exceed 0.5
OVERLAP_THRESHOLD = 0.8

#: the DMOs compared per WB: (name in the table, reference bouts.csv column (INDIP's), detected bouts.csv column)
DMOS = (("cadence", "cadence_spm", "cadence_spm"),
        ("stride_length", "avg_stride_length_m", "stride_length_m"),
        ("speed", "speed_mps", "speed_mps"))
_UNITS = {"cadence": "spm", "stride_length": "m", "speed": "mps"}

#: wb_scores.csv's columns, in order (docs/columns.md)
WB_SCORE_COLUMNS = ("match", "ref_wb", "ref_start_s", "ref_end_s", "bout", "bout_start_s", "bout_end_s", "overlap_s",
                    "overlap_ref_frac", "overlap_bout_frac", "start_diff_s", "end_diff_s",
                    *(c for name, _, _ in DMOS for c in (f"ref_{name}_{_UNITS[name]}", f"{name}_{_UNITS[name]}",
                                                        f"{name}_error_pct")))


def check_threshold(overlap_threshold: float) -> float:
    """``overlap_threshold`` as a float in (0.5, 1] (mobgap's bounds), else one ValueError line."""
    t = float(overlap_threshold)
    if not 0.5 < t <= 1.0:
        raise ValueError(f"overlap_threshold {overlap_threshold!r}: give a fraction above 0.5 and at most 1 (mobgap's "
                         "categorize_intervals bounds: above 0.5 a bout can match one WB only), e.g. 0.8")
    return t


def overlaps(det: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """``(n_ref, n_det)`` overlap durations (s, >= 0) of the intervals ``ref`` and ``det`` (rows ``[start, end]``)."""
    det, ref = np.asarray(det, float).reshape(-1, 2), np.asarray(ref, float).reshape(-1, 2)
    lo = np.maximum(ref[:, None, 0], det[None, :, 0])
    hi = np.minimum(ref[:, None, 1], det[None, :, 1])
    return np.clip(hi - lo, 0.0, None)


def match_intervals(det: np.ndarray, ref: np.ndarray, overlap_threshold: float = OVERLAP_THRESHOLD) -> np.ndarray:
    """For each reference interval the index of the detected interval matched to it, -1 when none (mobgap's
    ``categorize_intervals``: the overlap is at least ``overlap_threshold`` of both durations)."""
    t = check_threshold(overlap_threshold)
    det, ref = np.asarray(det, float).reshape(-1, 2), np.asarray(ref, float).reshape(-1, 2)
    ov = overlaps(det, ref)
    dur_r = (ref[:, 1] - ref[:, 0])[:, None]
    dur_d = (det[:, 1] - det[:, 0])[None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        ok = (ov > 0) & (ov >= t * dur_r) & (ov >= t * dur_d)
    out = np.full(len(ref), -1, dtype=int)
    for i in range(len(ref)):
        hit = np.flatnonzero(ok[i])
        if hit.size:  # above 0.5 at most one can pass (mobgap's reason for the bound)
            out[i] = int(hit[0])
    return out


def _rel_pct(det: float, ref: float) -> float:
    """mobgap's rel_error, in %: 100 (det - ref) / ref; NaN without both values or with a zero reference."""
    if not (np.isfinite(det) and np.isfinite(ref)) or ref == 0:
        return float("nan")
    return 100.0 * (det - ref) / ref


def _num(row, col: str) -> float:
    v = row.get(col) if row is not None else None
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def wb_score_table(bouts: pd.DataFrame, reference: pd.DataFrame,
                   overlap_threshold: float = OVERLAP_THRESHOLD) -> pd.DataFrame:
    """:data:`WB_SCORE_COLUMNS` of the detected ``bouts`` (bouts.csv: ``bout``, ``start_s``, ``end_s`` and the DMO
    columns of :data:`DMOS`) against the ``reference`` WBs (``start_s``, ``end_s``, optional ``wb_id`` and INDIP's
    DMO columns); module docstring. Rows in time order of the reference WB (an ``fp`` row at its bout's start)."""
    t = check_threshold(overlap_threshold)
    bouts = bouts.reset_index(drop=True) if bouts is not None else pd.DataFrame(columns=["bout", "start_s", "end_s"])
    reference = reference.reset_index(drop=True)
    det = bouts[["start_s", "end_s"]].to_numpy(float) if len(bouts) else np.zeros((0, 2))
    ref = reference[["start_s", "end_s"]].to_numpy(float)
    matched = match_intervals(det, ref, t)
    ov = overlaps(det, ref)
    rows = []
    for i, r in reference.iterrows():
        j = int(matched[i]) if matched[i] >= 0 else (int(np.argmax(ov[i])) if ov.shape[1] and ov[i].max() > 0
                                                     else -1)
        rows.append(_row("tp" if matched[i] >= 0 else "fn", r, i, bouts.iloc[j] if j >= 0 else None,
                         float(ov[i, j]) if j >= 0 else float("nan")))
    for j in sorted(set(range(len(bouts))) - set(int(m) for m in matched if m >= 0)):
        rows.append(_row("fp", None, None, bouts.iloc[j], float("nan")))
    table = pd.DataFrame(rows, columns=list(WB_SCORE_COLUMNS))
    key = table["ref_start_s"].fillna(table["bout_start_s"])
    return table.iloc[np.argsort(key.to_numpy(float), kind="stable")].reset_index(drop=True)


def _row(match: str, ref, i, det, overlap_s: float) -> dict:
    rs, re_ = _num(ref, "start_s"), _num(ref, "end_s")
    ds, de = _num(det, "start_s"), _num(det, "end_s")
    out = {"match": match,
           "ref_wb": (int(ref["wb_id"]) if "wb_id" in ref and pd.notna(ref["wb_id"]) else int(i)) if ref is not None
           else None,
           "ref_start_s": rs, "ref_end_s": re_,
           "bout": int(det["bout"]) if det is not None and "bout" in det else None,
           "bout_start_s": ds, "bout_end_s": de, "overlap_s": overlap_s,
           "overlap_ref_frac": overlap_s / (re_ - rs) if re_ > rs else float("nan"),
           "overlap_bout_frac": overlap_s / (de - ds) if de > ds else float("nan"),
           "start_diff_s": ds - rs, "end_diff_s": de - re_}
    for name, ref_col, det_col in DMOS:
        u = _UNITS[name]
        rv, dv = _num(ref, ref_col), _num(det, det_col)
        out[f"ref_{name}_{u}"], out[f"{name}_{u}"] = rv, dv
        out[f"{name}_error_pct"] = _rel_pct(dv, rv)
    return out


def wb_score_summary(table: pd.DataFrame, overlap_threshold: float = OVERLAP_THRESHOLD) -> dict:
    """summary.json's WB keys of a :func:`wb_score_table`: counts, precision / recall / F1 (NaN -> None when
    undefined) and, over the ``tp`` rows, the median |relative error| and the median signed one of each DMO
    (as L251's ``bout_distance_error_median_pct`` / ``_signed_pct``)."""
    n = {k: int((table["match"] == k).sum()) for k in ("tp", "fp", "fn")}
    p = n["tp"] / (n["tp"] + n["fp"]) if n["tp"] + n["fp"] else None
    r = n["tp"] / (n["tp"] + n["fn"]) if n["tp"] + n["fn"] else None
    f1 = 2 * p * r / (p + r) if p is not None and r is not None and p + r > 0 else (0.0 if n["tp"] == 0 and
                                                                                   n["fp"] + n["fn"] else None)
    out = {"wb_overlap_threshold": float(overlap_threshold), "n_wb_reference": n["tp"] + n["fn"],
           "n_wb_tp": n["tp"], "n_wb_fp": n["fp"], "n_wb_fn": n["fn"], "wb_precision": p, "wb_recall": r, "wb_f1": f1}
    tp = table[table["match"] == "tp"]
    for name, _, _ in DMOS:
        e = tp[f"{name}_error_pct"].to_numpy(float)
        e = e[np.isfinite(e)]
        out[f"wb_{name}_error_median_pct"] = float(np.median(np.abs(e))) if e.size else None
        out[f"wb_{name}_error_median_signed_pct"] = float(np.median(e)) if e.size else None
    return out


def outside_spans(bouts: pd.DataFrame | None, spans: list[dict] | None) -> pd.DataFrame | None:
    """Decision W499 (a pure kernel): the rows of ``bouts`` (``start_s`` / ``end_s``) that overlap none of ``spans``
    (``{"start_s", "end_s"}`` rows: the reference WBs a ``--window`` cut); ``bouts`` itself without spans."""
    if not spans or bouts is None or not len(bouts):
        return bouts
    a, b = bouts["start_s"].to_numpy(float), bouts["end_s"].to_numpy(float)
    hit = np.zeros(len(bouts), dtype=bool)
    for span in spans:
        hit |= (b > float(span["start_s"])) & (a < float(span["end_s"]))
    return bouts[~hit].reset_index(drop=True)


def wb_evaluation(bouts: pd.DataFrame, reference: pd.DataFrame | None,
                  overlap_threshold: float = OVERLAP_THRESHOLD) -> tuple[pd.DataFrame | None, dict]:
    """``(table, summary keys)`` of :func:`wb_score_table` / :func:`wb_score_summary`; ``(None, {})`` without
    reference WBs."""
    if reference is None or not len(reference):
        return None, {}
    table = wb_score_table(bouts, reference, overlap_threshold)
    return table, wb_score_summary(table, overlap_threshold)
