"""Cohort C242: visit-against-visit changes of bilateral gait (``gait-all``'s gait_changes.csv and
gait_changes_summary.csv, ``report --clinical``'s gait change line). Each paired visit folder's gait_summary.json
``walk`` is one "session" row (its subject, visit, folder group and measures) and track-all's own pairing
(:func:`pdrlearn.visits.change_table`: C22's baseline, C28's visit names, C83's repeated trials averaged) and summary
(:func:`pdrlearn.visits.change_summary`, C23's paired t-interval) make the tables: the same mechanism, other
measures - the symmetry indices and each side's means that track-all's sessions.csv does not have."""

from __future__ import annotations

#: cohort C242: gait_summary.json walk measures compared visit against visit, in this order (those no pair has a
#: value of are left out): the symmetry indices first (the trial's outcome), then each side's means, the support and
#: the pace, then (C244) each side's median sole angles
GAIT_CHANGE_MEASURES = (
    "step_time_s_si_pct", "stance_time_s_si_pct", "swing_time_s_si_pct", "step_length_m_si_pct",
    "stride_length_m_si_pct", "stride_time_s_si_pct",
    "step_time_s_left", "step_time_s_right", "stance_time_s_left", "stance_time_s_right",
    "swing_time_s_left", "swing_time_s_right", "step_length_m_left", "step_length_m_right",
    "stride_length_m_left", "stride_length_m_right", "double_support_pct", "gait_speed_mps", "cadence_spm",
    "ic_angle_deg_left", "ic_angle_deg_right", "tc_angle_deg_left", "tc_angle_deg_right")


def gait_visit_rows(pairs: list[dict]):
    """Cohort C242: a sessions.csv-like table of bilateral walks: one row per ``pairs`` item ``{"path", "subject",
    "visit", "walk"}`` (a walk with subject and visit; ``walk`` a gait_summary.json ``walk``) with ``group`` (the
    path's first folder, track-all's ``--group-depth 1``), ``status`` ok and :data:`GAIT_CHANGE_MEASURES` as
    numbers."""
    import pandas as pd

    from pdrlearn.cohort import session_group

    rows = [{"path": p["path"], "subject": str(p["subject"]), "visit": str(p["visit"]),
             "group": session_group(str(p["path"]), 1), "status": "ok",
             **{m: (p.get("walk") or {}).get(m) for m in GAIT_CHANGE_MEASURES}}
            for p in pairs if p.get("subject") and p.get("visit")]
    frame = pd.DataFrame(rows, columns=["path", "subject", "visit", "group", "status", *GAIT_CHANGE_MEASURES])
    frame[list(GAIT_CHANGE_MEASURES)] = frame[list(GAIT_CHANGE_MEASURES)].apply(pd.to_numeric, errors="coerce")
    return frame


def gait_change_tables(pairs: list[dict]):
    """Cohort C242: ``(gait_changes, gait_changes_summary)`` - :func:`pdrlearn.visits.change_table` and
    :func:`pdrlearn.visits.change_summary` of :func:`gait_visit_rows` over the measures some walk has - or
    ``(None, None)`` when the walks naming a subject and a visit name fewer than two visits (or have no measure)."""
    from pdrlearn.visits import change_summary, change_table

    frame = gait_visit_rows(pairs)
    measures = [m for m in GAIT_CHANGE_MEASURES if frame[m].notna().any()]
    if frame.empty or not measures:
        return None, None
    changes = change_table(frame, metrics=measures)
    if changes is None:
        return None, None
    return changes, change_summary(changes, measures)
