"""Event-level evaluation of step detectors: one-to-one matching within a tolerance.

Tolerance (docs/decisions/steps.md "Matching tolerance"): a detected event matches a reference event
when ``|t_det - t_ref| <= tolerance_s`` (default 0.25 s = half of a 0.5 s step at a cadence of
120 steps/min, so one detection can never sit within tolerance of two reference steps of a normal walk);
pairs are matched greedily from the closest, each event at most once.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels.nearest import nearest_distance
from pdrlearn.steps.base import check_event_span, check_unit

DEFAULT_TOLERANCE_S = 0.25
#: decision B167: the largest matching tolerance accepted (s). A stride lasts about 1-1.4 s, so a tolerance above
#: 2 s matches a detection with steps it is not; a tolerance typed in milliseconds (50, 250) lands far above it
MAX_TOLERANCE_S = 2.0


def check_tolerance(tolerance_s, where: str = "tolerance_s") -> float:
    """Decision B167: a matching tolerance in seconds, finite, > 0 and at most :data:`MAX_TOLERANCE_S`; else one
    :class:`DataError` line naming ``where`` (the argument or CLI option)."""
    try:
        tol = float(tolerance_s)
    except (TypeError, ValueError):
        raise DataError(f"{where} {tolerance_s!r}: give the event matching tolerance in seconds, e.g. 0.25") from None
    if not (np.isfinite(tol) and 0 < tol <= MAX_TOLERANCE_S):
        hint = f" (it looks like milliseconds: {tol:g} ms is {tol / 1000:g} s)" if tol > MAX_TOLERANCE_S else ""
        raise DataError(f"{where} {tolerance_s!r}: the tolerance is in seconds, > 0 and at most "
                        f"{MAX_TOLERANCE_S:g} s{hint}; e.g. 0.25")
    return tol


def match_events(detected, reference, tolerance_s: float | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Indices ``(i_det, i_ref)`` into the caller's ``detected`` and ``reference`` (any order) of one-to-one
    matched pairs, matched closest first and returned in reference-time order (steps decision 36):
    ``detected[i_det[k]]`` is matched with ``reference[i_ref[k]]``.

    ``tolerance_s`` is a scalar or one tolerance per reference event (s), in the order of ``reference``.
    """
    d_in = np.asarray(detected, dtype=float).ravel()
    r_in = np.asarray(reference, dtype=float).ravel()
    order_d = np.argsort(d_in, kind="stable")
    order_r = np.argsort(r_in, kind="stable")
    d, r = d_in[order_d], r_in[order_r]
    tol = np.broadcast_to(np.asarray(tolerance_s, dtype=float), r_in.shape)[order_r]
    if d.size == 0 or r.size == 0:
        return np.zeros(0, int), np.zeros(0, int)
    tmax = float(tol.max())
    lo = np.searchsorted(r, d - tmax, side="left")
    hi = np.searchsorted(r, d + tmax, side="right")
    pairs = [(abs(d[i] - r[j]), i, j) for i in range(d.size) for j in range(lo[i], hi[i])
             if abs(d[i] - r[j]) <= tol[j]]
    pairs.sort()
    used_d: set[int] = set()
    used_r: set[int] = set()
    out_d, out_r = [], []
    for _, i, j in pairs:
        if i not in used_d and j not in used_r:
            used_d.add(i)
            used_r.add(j)
            out_d.append(i)
            out_r.append(j)
    order = np.argsort(out_r)
    return order_d[np.asarray(out_d, int)[order]], order_r[np.asarray(out_r, int)[order]]


def score_events(detected_times, reference_times, *, tolerance_s: float = DEFAULT_TOLERANCE_S) -> dict:
    """Precision, recall, F1, step-count error and timing error of detected events.

    Parameters
    ----------
    detected_times, reference_times : event times (s)
    tolerance_s : matching tolerance (s), see the module docstring

    Returns
    -------
    dict with ``count``, ``reference_count``, ``true_positives``, ``false_positives``, ``false_negatives``,
    ``precision``, ``recall``, ``f1``, ``count_error_pct`` (100 |n_det - n_ref| / n_ref, the thesis
    Tables 20-21 measure), ``timing_error_mean_s`` and ``timing_error_sd_s`` (detected - reference over
    matched pairs; NaN when none), ``tolerance_s``.
    """
    d = np.asarray(detected_times, dtype=float).ravel()
    r = np.asarray(reference_times, dtype=float).ravel()
    if np.ndim(tolerance_s) == 0:  # a caller's tolerance (per-reference arrays come from reference_events)
        check_tolerance(tolerance_s, "score_events: tolerance_s")
    tol = np.broadcast_to(np.asarray(tolerance_s, dtype=float), r.shape)
    if not (np.all(np.isfinite(d)) and np.all(np.isfinite(r))):
        raise DataError("score_events: event times contain NaN or inf; drop undefined events first")
    if tol.size and not np.all(tol > 0):
        raise DataError(f"score_events: tolerance {tolerance_s} s must be positive")
    i_d, i_r = match_events(d, r, tol)
    tp = int(i_d.size)
    fp, fn = int(d.size - tp), int(r.size - tp)
    precision = tp / d.size if d.size else float("nan")
    recall = tp / r.size if r.size else float("nan")
    f1 = 2 * tp / (d.size + r.size) if (d.size + r.size) else float("nan")
    err = d[i_d] - r[i_r]
    return {
        "count": int(d.size),
        "scored_count": int(d.size),  # every detection given is scored here (score_steps: inside the labels)
        "reference_count": int(r.size),
        "true_positives": tp,
        "false_positives": fp,
        "false_negatives": fn,
        "precision": float(precision),
        "recall": float(recall),
        "f1": float(f1),
        "count_error_pct": float(100.0 * abs(d.size - r.size) / r.size) if r.size else float("nan"),
        "timing_error_mean_s": float(err.mean()) if tp else float("nan"),
        "timing_error_sd_s": float(err.std(ddof=1)) if tp > 1 else float("nan"),
        "timing_error_abs_mean_s": float(np.abs(err).mean()) if tp else float("nan"),
        "tolerance_s": float(np.max(tol)) if tol.size else float(np.asarray(tolerance_s).max()),
    }


@dataclass
class Reference:
    """Reference events of a session for one unit.

    Attributes
    ----------
    times : (n,) reference event times (s)
    tolerance_s : scalar or (n,) matching tolerance (s)
    intervals : (k, 2) time intervals that the labels cover (s); detections outside are not scored
    description : where the events come from
    ground_truth : ``False`` for a segmentation (``source=detected``): scored by window, no timing error
    from_ics : the events are lower-back initial contacts (``extras["ics"]``), which may have contacts
        without a time (``extras["ics_untimed"]``, decision 19)
    one_foot : a lower-back detector scored against one foot's strides (no ``ics.csv``): that foot's name
        ("the labelled" when steps.csv does not say); only its contacts' recall is scored (decision W96)
    span_only : the labelled interval is first..last initial contact of an ``ics.csv`` with no ``bouts.csv``, so
        pauses of the reference inside it are scored (decision steps 57)
    feet : each event's foot (left / right, "" unknown), in the order of ``times`` (the events table, steps 59)
    """

    times: np.ndarray
    tolerance_s: float | np.ndarray
    intervals: np.ndarray
    description: str
    ground_truth: bool = True
    from_ics: bool = False
    one_foot: str | None = None
    span_only: bool = False
    feet: np.ndarray | None = None


def _span(times: np.ndarray, *more: np.ndarray) -> np.ndarray:
    allv = np.concatenate([times, *more]) if more else times
    return np.array([[float(allv.min()), float(allv.max())]])


def _chains(lo: np.ndarray, hi: np.ndarray, gap_s: float = 1e-3) -> np.ndarray:
    """``[a, b]`` rows covering the labelled strides ``[lo_i, hi_i]``: strides that touch or overlap
    (within ``gap_s``) form one interval; a gap between two strides (unlabelled walking) splits them."""
    order = np.argsort(lo, kind="stable")
    out: list[list[float]] = []
    for a, b in zip(lo[order], hi[order], strict=True):
        if out and a <= out[-1][1] + gap_s:
            out[-1][1] = max(out[-1][1], float(b))
        else:
            out.append([float(a), float(b)])
    return np.asarray(out, dtype=float).reshape(-1, 2)


def reference_events(session: Session, unit: str, *,
                     tolerance_s: float = DEFAULT_TOLERANCE_S) -> Reference | None:
    """Reference events of ``session`` for a detector on ``unit`` (``None`` without labels).

    - ``waist``: every initial contact of both feet (``extras["ics"].ic_s``) when present, else the steps
      table as for the foot. Labelled intervals: the walking bouts (``extras["bouts"]``, level ``wb``)
      when present, else first..last IC: the references label only walking bouts, and the steps a
      subject takes outside them (turning on the spot, shuffling, the first/last steps) are unlabelled.
    - ``foot``: one event per stride of the instrumented foot, ``steps.ic_s`` (plus every ``pre_ic_s``
      that is no stride's ``ic_s``: the motion-captured initial contact that opens a chain of labelled
      strides), else ``steps.start_s``. Labelled intervals: with ``pre_ic_s``, each chain of touching
      strides, from its first event to its last stride end (a reference that labels only some strides of
      a walk, e.g. those inside a mocap volume, leaves the strides between chains unscored); without it,
      first event .. last stride end (every stride is labelled: a detection in a pause is a false positive).
    - rows marked ``source == "detected"`` are a rest-based segmentation, NOT ground truth: a detection
      matches a stride when it falls inside the stride's ``[start_s, end_s]`` window.
    Every interval is widened by ``tolerance_s`` on both sides.
    """
    check_unit(unit, "reference_events")  # decision B168: 'Waist' was scored as the foot's strides
    ref = _reference_events(session, unit, check_tolerance(tolerance_s, "reference_events: tolerance_s"))
    if ref is not None and unit == "waist" and not ref.from_ics:  # decision W96: one foot's strides
        st = session.steps
        feet = st["foot"].dropna().astype(str).unique() if "foot" in st else []
        if len(feet) <= 1:
            foot = str(feet[0]) if len(feet) else "the labelled"
            return dataclasses.replace(ref, one_foot=foot, description=(
                f"{ref.description}; the {foot} foot's contacts only (no ics.csv labels both feet's): the recall of "
                "that foot's contacts is scored, the other foot's steps are neither hits nor false positives, so "
                "precision, F1 and the count error are not"))
    return ref


def _reference_events(session: Session, unit: str, tolerance_s: float) -> Reference | None:
    tol = float(tolerance_s)
    if unit == "waist" and "ics" in session.extras and "ic_s" in session.extras["ics"]:
        return _ics_reference(session.extras["ics"], session, tol, "extras['ics'].ic_s", from_ics=True)
    st = session.steps
    if st is None or len(st) == 0:
        side = ics_foot(session)  # decision steps 58: a foot detector against its own foot's contacts of ics.csv
        if unit == "foot" and side is not None:
            ics = session.extras["ics"]
            return _ics_reference(ics[ics["foot"].astype(str).str.lower() == side], session, tol,
                                  f"extras['ics'].ic_s of the {side} foot (meta.json foot; no steps.csv)")
        return None
    se = st[["start_s", "end_s"]].to_numpy(float)
    if "source" in st and (st["source"].astype(str) == "detected").all():
        mid = se.mean(axis=1)
        half = np.maximum(0.5 * (se[:, 1] - se[:, 0]), 1e-3)
        return Reference(mid, half, _span(se[:, 0], se[:, 1]) + [-tol, tol],
                         "steps.csv stride windows (source=detected: a rest-based segmentation, "
                         "NOT ground truth)",
                         ground_truth=False)
    if "ic_s" in st and st["ic_s"].notna().any():
        ev = st["ic_s"].dropna().to_numpy(float)
        desc = "steps.ic_s"
        lo = se[:, 0].copy()
        partial = "pre_ic_s" in st and st["pre_ic_s"].notna().any()
        if partial:
            pre = st["pre_ic_s"].to_numpy(float)
            lo = np.fmin(lo, pre)
            pre = pre[np.isfinite(pre)]
            # a pre_ic that is no stride's ic opens a chain of labelled strides (mocap ICs)
            extra = pre[nearest_distance(pre, ev) > 1e-3] if ev.size else pre  # decision L546
            if extra.size:
                ev = np.concatenate([extra, ev])
                desc += " + pre_ic_s opening each chain of strides"
        ev = np.unique(ev)
        hi = np.fmax(se[:, 1], st["ic_s"].to_numpy(float))
        # chains only where pre_ic_s says where each labelled chain opens (decision 15); a reference
        # without it labels every stride, so a gap between strides is a pause and detections in it are
        # false positives (simulated sessions, calibration exercises)
        iv = _chains(lo, hi) if partial else _span(ev, hi[np.isfinite(hi)])
        return Reference(ev, tol, iv + [-tol, tol], desc)
    ev = np.sort(se[:, 0])
    return Reference(ev, tol, _span(ev, se[:, 1]) + [-tol, tol],
                     "steps.start_s (steps.csv has no ic_ms column: each labelled stride's start is its event)")


def _ics_reference(ics: pd.DataFrame, session: Session, tol: float, desc: str, from_ics: bool = False
                   ) -> Reference | None:
    """The initial contacts of ``ics`` (``ic_s``) as a reference, labelled within the walking bouts
    (``extras["bouts"]``, level ``wb``) when given, else from the first to the last contact (decision steps 57:
    its pauses are scored; ``span_only``)."""
    ics = ics.dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    t = ics["ic_s"].to_numpy(float)
    if t.size == 0:
        return None
    feet = ics["foot"].astype(str).str.lower().to_numpy() if "foot" in ics else np.full(t.size, "")
    bouts = session.extras.get("bouts")
    if bouts is not None and {"start_s", "end_s"} <= set(bouts.columns):
        b = bouts[bouts["level"].astype(str) == "wb"] if "level" in bouts else bouts
        iv = b[["start_s", "end_s"]].to_numpy(float)
        desc += " within extras['bouts'] (wb)"
        span_only = False
    else:
        iv, span_only = _span(t), True
    return Reference(t, tol, iv + [-tol, tol], desc, from_ics=from_ics, span_only=span_only, feet=feet)


def ics_foot(session: Session) -> str | None:
    """Decision steps 58: the instrumented foot's side (meta.json ``foot``) when ``ics.csv`` labels that foot's
    contacts (a ``foot`` column holding it), else None."""
    ics = session.extras.get("ics")
    side = str(session.meta.get("foot") or "").strip().lower()
    if ics is None or "ic_s" not in ics or "foot" not in ics or side not in ("left", "right"):
        return None
    return side if (ics["foot"].astype(str).str.lower() == side).any() else None


def unscored_reason(session: Session, unit: str) -> str | None:
    """Decision steps 58: why ``session`` gives a ``unit`` detector no reference although it has labels, as one
    line (None when it has none at all, or when it is scored)."""
    ics = session.extras.get("ics")
    if unit != "foot" or ics is None or (session.steps is not None and len(session.steps)):
        return None
    if ics_foot(session) is not None:
        return None
    why = ("ics.csv has no foot column" if "foot" not in ics else
           "meta.json names no foot (left or right)" if not session.meta.get("foot") else
           f"ics.csv has no contact of the {session.meta.get('foot')} foot (meta.json foot)")
    return (f"not scored: foot strides are scored against steps.csv (start_ms,end_ms,ic_ms per stride) or against "
            f"the instrumented foot's contacts of ics.csv (ic_ms,foot with meta.json \"foot\": \"left\" or "
            f"\"right\", `pdrlearn import --foot`), and {why}; or score every contact with --unit waist "
            "(decision steps 58)")


#: decision steps 57: an interval between two reference contacts longer than the longest stride is a pause (the
#: Mobilise-D stride selection's maximum stride time, pdrlearn.waist.gait_rules.MAX_STRIDE_S)
def reference_pauses(times: np.ndarray, max_gap_s: float | None = None) -> np.ndarray:
    """``[a, b]`` rows of the gaps between consecutive reference events (sorted ``times``) longer than
    ``max_gap_s`` (default: :data:`pdrlearn.kernels.contact.MAX_STRIDE_S`, 3 s)."""
    from pdrlearn.kernels.contact import MAX_STRIDE_S

    gap = MAX_STRIDE_S if max_gap_s is None else max_gap_s
    t = np.sort(np.asarray(times, dtype=float))
    i = np.flatnonzero(np.diff(t) > gap)
    return np.column_stack([t[i], t[i + 1]]) if i.size else np.empty((0, 2))


def in_intervals(times: np.ndarray, intervals: np.ndarray) -> np.ndarray:
    """Boolean mask of ``times`` inside any ``[a, b]`` row of ``intervals``."""
    times = np.asarray(times, dtype=float)
    m = np.zeros(times.shape, dtype=bool)
    for a, b in np.asarray(intervals, dtype=float).reshape(-1, 2):
        m |= (times >= a) & (times <= b)
    return m


def untimed_mask(ev: np.ndarray, session: Session, tolerance_s: float = DEFAULT_TOLERANCE_S) -> np.ndarray:
    """Detections (sorted times ``ev``) that stand for reference contacts without a time: in each interval
    of ``extras["ics_untimed"]`` holding k such contacts, the first k detections farther than
    ``tolerance_s`` from both of its (timed) ends (docs/external-data.md X2: the step happened, only its
    time is unknown, so such a detection is neither a hit nor a false positive)."""
    out = np.zeros(len(ev), dtype=bool)
    u = session.extras.get("ics_untimed")
    if u is None or not {"after_s", "before_s"} <= set(u.columns) or len(u) == 0:
        return out
    for (a, b), g in u.groupby(["after_s", "before_s"]):
        inside = np.flatnonzero((ev > a + tolerance_s) & (ev < b - tolerance_s) & ~out)
        out[inside[:len(g)]] = True
    return out


def same_foot_gap_mask(ev: np.ndarray, session: Session, tolerance_s: float = DEFAULT_TOLERANCE_S,
                       taken: np.ndarray | None = None) -> np.ndarray:
    """Detections (sorted times ``ev``) that stand for a contact the reference lost without saying so: two
    consecutive timed contacts of the *same* foot inside one walking bout (``extras["ics"]`` with ``foot``
    and ``wb_id``) bound a contact of the other foot that INDIP did not record; the first detection farther
    than ``tolerance_s`` from both ends (and not already in ``taken``) is neither a hit nor a false positive
    (decision 20 of docs/decisions/steps.md, the rule of :func:`untimed_mask` for a loss with no
    ``ics_untimed`` entry). A gap that holds an ``ics_untimed`` interval is left to :func:`untimed_mask`."""
    out = np.zeros(len(ev), dtype=bool)
    ics = session.extras.get("ics")
    if ics is None or not {"ic_s", "foot"} <= set(ics.columns) or len(ics) < 2:
        return out
    taken = np.zeros(len(ev), dtype=bool) if taken is None else np.asarray(taken, dtype=bool)
    df = ics.dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    t = df["ic_s"].to_numpy(float)
    foot = df["foot"].astype(str).str.lower().to_numpy()
    bout = df["wb_id"].to_numpy() if "wb_id" in df else np.zeros(len(df))
    u = session.extras.get("ics_untimed")
    known = (u[["after_s", "before_s"]].to_numpy(float) if u is not None and len(u)
             and {"after_s", "before_s"} <= set(u.columns) else np.empty((0, 2)))
    for i in np.flatnonzero((foot[1:] == foot[:-1]) & (bout[1:] == bout[:-1]) & (t[1:] > t[:-1])):
        a, b = t[i], t[i + 1]
        if np.any((known[:, 0] >= a - 1e-9) & (known[:, 1] <= b + 1e-9)):
            continue
        inside = np.flatnonzero((ev > a + tolerance_s) & (ev < b - tolerance_s) & ~taken & ~out)
        out[inside[:1]] = True
    return out


def _table_events(steps, session: Session, unit: str | None) -> tuple[np.ndarray, str]:
    """The event times and unit of a steps table to score, checked (decisions B168-B170): a DataFrame with
    ``event_s`` (s, on the session's clock) and one known ``unit`` (its column, ``attrs``, or ``unit=``)."""
    if not isinstance(steps, pd.DataFrame):
        raise DataError(f"score_steps: steps is a {type(steps).__name__}, not a steps table; pass a DataFrame with "
                        "event_s (s) and unit columns as StepDetector.detect returns, e.g. "
                        "pd.DataFrame({'event_s': times, 'unit': 'foot'})")
    if "event_s" not in steps:
        raise DataError(f"score_steps: the steps table has no event_s column (the step times in s); it has "
                        f"{', '.join(map(str, steps.columns)) or 'no columns'}")
    if unit is None:
        units = sorted(set(steps["unit"].astype(str))) if "unit" in steps and len(steps) else []
        if len(units) > 1:
            raise DataError(f"score_steps: the steps table mixes units {', '.join(units)}; score each unit's rows "
                            "on their own")
        unit = units[0] if units else steps.attrs.get("unit", None if len(steps) else "foot")
        if unit is None:
            raise DataError("score_steps: the steps table has no unit column; add one (foot or waist) or pass unit=")
    check_unit(unit, "score_steps")
    ev = pd.to_numeric(steps["event_s"], errors="coerce").to_numpy(float)
    if np.isnan(ev).sum() > steps["event_s"].isna().sum():
        raise DataError("score_steps: column event_s has non-numeric values; give the step times in seconds")
    if not np.isfinite(ev).all():  # decision B210: a NaN event had been counted but never scored, silently
        bad = ~np.isfinite(ev)
        raise DataError(f"score_steps: {int(bad.sum())} of {ev.size} step event(s) have no finite event_s (first: row "
                        f"{int(np.flatnonzero(bad)[0])}); a detection needs its time in s: drop those rows "
                        "(steps.dropna(subset=['event_s'])) or give their times")
    if any(len(st) for st in session.streams.values()):  # a labels-only session has no clock span to check
        check_event_span(ev, session.t_start, session.t_end, "score_steps")
    return ev, unit


def score_steps(steps: pd.DataFrame, session: Session, *, tolerance_s: float = DEFAULT_TOLERANCE_S,
                unit: str | None = None, ref_offset_s: float = 0.0) -> dict | None:
    """Score a detector's steps table against the session's labels (``None`` without labels).

    Only detections inside the labelled intervals are scored (see :func:`reference_events`); the result
    says how many were left out (``outside_labels``) and where the reference comes from (``reference``).
    Against lower-back initial contacts, detections that stand for a contact without a time
    (:func:`untimed_mask`) are not scored either (``unscored_untimed``), as in ``pdrlearn track``'s
    ``step_f1`` (decision 19): the same contacts get the same F1 from ``steps`` and ``track``; nor is one
    detection per same-foot gap of the reference (:func:`same_foot_gap_mask`, ``unscored_same_foot_gap``,
    decision 20; ``f1_same_foot_gaps_scored`` is the F1 with them counted as false positives).

    Decision steps 41: ``count`` is every detection of ``steps`` (``total_count``, its old alias), the key
    ``pdrlearn steps --json`` gives (that JSON is this dict plus session, detector, unit); the metrics and
    ``count_error_pct`` use the detections scored, ``scored_count`` (``count`` before decision steps 41).

    ``steps`` is scored as given. ``pdrlearn steps`` and ``pdrlearn score-steps`` first reduce a foot table to
    one row per rest-to-rest stride (:func:`pdrlearn.steps.one_per_stride`, decision steps 34/39): call it
    before this to get their numbers for a detector that fires more than once per stride.

    ``ref_offset_s``: the reference clock minus the session's clock (s); every label time is moved to
    ``t - ref_offset_s`` first (decision steps 56). The result always has ``ref_offset_s`` and, with 3 events on
    each side, the offset check of :func:`pdrlearn.steps.reference_clock.offset_check`
    (``ref_offset_estimate_s``, ``ref_offset_suspect`` ...). Against ``ics.csv`` contacts without ``bouts.csv``
    (``reference_span_only``), ``pause_detections`` counts the scored detections inside the ``reference_pauses``
    gaps of the reference longer than 3 s (decision steps 57). A foot table with ``tc_s`` against a steps.csv
    with ``tc_ms`` also gets the toe-offs' scores, keys ``tc_*`` (decision steps 59).
    """
    return score_steps_events(steps, session, tolerance_s=tolerance_s, unit=unit, ref_offset_s=ref_offset_s)[0]


def score_steps_events(steps: pd.DataFrame, session: Session, *, tolerance_s: float = DEFAULT_TOLERANCE_S,
                       unit: str | None = None, ref_offset_s: float = 0.0) -> tuple[dict | None, pd.DataFrame]:
    """:func:`score_steps`' dict and the events table of decision steps 59 (one row per scored detection and per
    reference event: :data:`EVENT_COLUMNS`; matched pairs share a row)."""
    from pdrlearn.steps.reference_clock import check_ref_offset, offset_check, shifted_labels

    tolerance_s = check_tolerance(tolerance_s, "score_steps: tolerance_s")  # decision B167
    ref_offset_s = check_ref_offset(ref_offset_s, "score_steps: ref_offset_s")  # decision B333
    ev, unit = _table_events(steps, session, unit)
    session = shifted_labels(session, ref_offset_s, tolerance_s=tolerance_s, where="ref_offset_s")  # steps 56
    if unit == "waist":  # decision W380: the lower back's steps against labels on the simulated waist clock
        from pdrlearn.steps.reference_clock import waist_clock_labels

        session = waist_clock_labels(session)
    ref = reference_events(session, unit, tolerance_s=tolerance_s)
    if ref is None:
        return None, pd.DataFrame(columns=list(EVENT_COLUMNS))
    order = np.argsort(ev, kind="stable")
    ev = ev[order]
    inside = in_intervals(ev, ref.intervals)
    scored = ev[inside]
    untimed = (untimed_mask(scored, session, tolerance_s) if ref.from_ics
               else np.zeros(scored.size, dtype=bool))
    lost = (same_foot_gap_mask(scored, session, tolerance_s, taken=untimed) if ref.from_ics
            else np.zeros(scored.size, dtype=bool))
    kept = scored[~(untimed | lost)]
    out = score_events(kept, ref.times, tolerance_s=ref.tolerance_s)
    det_feet = _table_feet(steps, unit, session)[order][inside][~(untimed | lost)]
    ref_feet = ref.feet if ref.feet is not None else np.full(ref.times.size, _unit_foot(session, unit), dtype=object)
    events = [event_rows(kept, ref.times, ref.tolerance_s, "ic", det_feet, ref_feet)]
    if ref.one_foot is not None:  # decision W96: the other foot's steps match nothing and are no error
        out.update(precision=float("nan"), f1=float("nan"), count_error_pct=float("nan"), one_foot=ref.one_foot)
    out["tolerance_s"] = float(tolerance_s)
    # decision steps 41: "count" is every detection of the table, as in `pdrlearn steps --json` (the same dict);
    # the metrics (precision, count_error_pct ...) use the detections scored, "scored_count"
    out["scored_count"] = out["count"]
    out["count"] = out["total_count"] = int(ev.size)
    out["outside_labels"] = int((~inside).sum())
    out["unscored_untimed"] = int(untimed.sum())
    out["unscored_same_foot_gap"] = int(lost.sum())
    # the F1 with those detections counted as false positives (they lie > tolerance from every contact)
    n = out["scored_count"] + int(lost.sum()) + out["reference_count"]
    out["f1_same_foot_gaps_scored"] = (float(2 * out["true_positives"] / n) if n and ref.one_foot is None
                                       else float("nan"))
    out["reference"] = ref.description
    out["ground_truth"] = ref.ground_truth
    out["ref_offset_s"] = ref_offset_s
    out["timing_error_median_s"] = float(np.median(events[0]["error_s"].dropna())) if out["true_positives"] \
        else float("nan")
    if not ref.ground_truth:
        for k in ("timing_error_mean_s", "timing_error_sd_s", "timing_error_abs_mean_s", "timing_error_median_s"):
            out[k] = float("nan")
        events = []
    elif ref.one_foot is None:  # decision steps 56: does the reference look offset from the IMU clock?
        # (not against one foot's contacts, W96: the other foot's steps, half a stride away, match it shifted by
        # one step, an alias the rule's gain cannot tell from a clock; steps 56 amended, review R2)
        out.update(offset_check(ev, ref.times, tolerance_s, ref_offset_s))
    if ref.span_only:  # decision steps 57: ics.csv without bouts.csv scores the reference's pauses too
        pauses = reference_pauses(ref.times)
        out["reference_span_only"] = True
        out["reference_start_s"], out["reference_end_s"] = float(ref.times.min()), float(ref.times.max())
        out["reference_pauses"] = int(len(pauses))
        out["pause_detections"] = int(in_intervals(kept, pauses + [tolerance_s, -tolerance_s]).sum())
    if unit == "foot" and ref.ground_truth:  # decision steps 59: the toe-offs, when both sides have them
        tc = _toe_off_scores(steps, session, ref, tolerance_s)
        if tc is not None:
            out.update(tc[0])
            events.append(tc[1])
    table = (pd.concat(events, ignore_index=True).sort_values(["event", "reference_s", "detected_s"],
                                                               kind="stable", ignore_index=True)
             if events else pd.DataFrame(columns=list(EVENT_COLUMNS)))
    return out, table


#: decision steps 59: the columns of ``--events-out`` (pdrlearn.columns EVENTS documents them)
EVENT_COLUMNS = ("event", "foot", "detected_s", "reference_s", "error_s", "match")


def event_rows(detected: np.ndarray, reference: np.ndarray, tolerance_s, event: str,
               det_feet: np.ndarray | None = None, ref_feet: np.ndarray | None = None) -> pd.DataFrame:
    """Decision steps 59: one row per matched pair (``match`` = ``matched``, ``error_s`` = detected - reference),
    per unmatched detection (``false_positive``) and per unmatched reference event (``missed``)."""
    d = np.asarray(detected, dtype=float)
    r = np.asarray(reference, dtype=float)
    dfeet = np.full(d.size, "", dtype=object) if det_feet is None else np.asarray(det_feet, dtype=object)
    rfeet = np.full(r.size, "", dtype=object) if ref_feet is None else np.asarray(ref_feet, dtype=object)
    i_d, i_r = match_events(d, r, tolerance_s)
    fp = np.setdiff1d(np.arange(d.size), i_d)
    fn = np.setdiff1d(np.arange(r.size), i_r)
    nan = np.nan
    rows = {"event": event,
            "foot": np.concatenate([np.where(rfeet[i_r] != "", rfeet[i_r], dfeet[i_d]), dfeet[fp], rfeet[fn]]),
            "detected_s": np.concatenate([d[i_d], d[fp], np.full(fn.size, nan)]),
            "reference_s": np.concatenate([r[i_r], np.full(fp.size, nan), r[fn]]),
            "error_s": np.concatenate([d[i_d] - r[i_r], np.full(fp.size + fn.size, nan)]),
            "match": ["matched"] * i_d.size + ["false_positive"] * fp.size + ["missed"] * fn.size}
    return pd.DataFrame(rows, columns=list(EVENT_COLUMNS))


def _table_feet(steps: pd.DataFrame, unit: str, session: Session) -> np.ndarray:
    """Each detection's foot: the table's ``foot`` or ``side`` column, a foot table's meta.json ``foot``, else ""."""
    for col in ("foot", "side"):
        if col in steps:
            return steps[col].fillna("").astype(str).str.lower().to_numpy(dtype=object)
    return np.full(len(steps), _unit_foot(session, unit), dtype=object)


def _unit_foot(session: Session, unit: str) -> str:
    """A foot unit's side, else "": meta.json ``foot`` or ``instrumented_foot`` (the simulator's, decision L260's
    keys), else the one side steps.csv's ``foot`` column names (decision B357)."""
    if unit != "foot":
        return ""
    from pdrlearn.track.bilateral import SIDES, session_foot

    side = session_foot(session.meta if isinstance(session.meta, dict) else {})
    st = session.steps
    if side is None and st is not None and "foot" in st:  # decision B357: the labelled strides' one foot
        named = {str(v).strip().lower() for v in st["foot"].dropna()}
        side = named.pop() if len(named) == 1 and named <= set(SIDES) else None
    return side or ""


def _toe_off_scores(steps: pd.DataFrame, session: Session, ref: Reference, tolerance_s: float
                    ) -> tuple[dict, pd.DataFrame] | None:
    """Decision steps 59: the detected toe-offs (``steps.tc_s``) against the reference's (steps.csv ``tc_ms``)
    inside the labelled intervals, :func:`score_events` keys prefixed ``tc_``; None when either side has none."""
    st = session.steps
    if "tc_s" not in steps or st is None or "tc_s" not in st:
        return None
    d = pd.to_numeric(steps["tc_s"], errors="coerce").to_numpy(float)
    r = st["tc_s"].to_numpy(float)
    d, r = np.sort(d[np.isfinite(d)]), np.sort(r[np.isfinite(r)])
    if not d.size or not r.size:
        return None
    # inside the labelled intervals or a labelled stride (a stride's toe-off can precede the first labelled IC)
    strides = st[["start_s", "end_s"]].to_numpy(float) + [-tolerance_s, tolerance_s]
    d = d[in_intervals(d, np.vstack([ref.intervals, strides]))]
    sc = score_events(d, r, tolerance_s=tolerance_s)
    keys = ("count", "reference_count", "true_positives", "false_positives", "false_negatives", "precision",
            "recall", "f1", "timing_error_mean_s", "timing_error_sd_s")
    side = _unit_foot(session, "foot")
    return ({f"tc_{k}": sc[k] for k in keys},
            event_rows(d, r, tolerance_s, "tc", np.full(d.size, side, dtype=object),
                       np.full(r.size, side, dtype=object)))
