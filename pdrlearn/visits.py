"""Subjects and visits of a cohort: each subject's (and visit's) walking totals (``subjects.csv``, cohort C25).
Paired visits (decisions C22, C23): per subject, the change of each summary measure from the baseline
visit to every later visit (``changes.csv``), and per visit and measure the mean change with its paired 95 %
t-interval (``changes_summary.csv``). All three are functions of sessions.csv (its ``subject``, ``visit``, ``status``
and measure columns), so they are the same for the same data, version and options, as sessions.csv is (C18).

The subject and visit of a session are its meta.json's (``pdrlearn.cohort.session_labels``): a study names them
there; folder names are not read (a trial design is not known to the tool, C20)."""

from __future__ import annotations

import re

from pdrlearn.cohort import GROUP_METRICS, t_interval

#: changes.csv's leading columns (decision C22); ``<measure>_baseline`` and ``<measure>_change`` follow per measure
CHANGE_COLUMNS = ("subject", "group", "baseline_visit", "visit", "status", "reason", "baseline_path", "path")
#: what a pair of visits is when it is not ``ok`` (C22), in the order they are looked for
STATUSES = ("ok", "missing", "failed", "several")


#: a visit name's leading word that marks it as the baseline, or as a later visit (decision C24): ``pre`` comes before
#: ``post`` whatever the alphabet says (text order had made ``post`` the baseline, every change's sign reversed)
BASELINE_WORDS = frozenset({"baseline", "bl", "base", "screening", "screen", "pre", "before", "admission", "intake"})
LATER_WORDS = frozenset({"post", "after", "discharge"})
FOLLOW_UP_WORDS = frozenset({"followup", "follow", "fu", "final", "end", "exit"})  # after ``post``


def _word_rank(v: str) -> int:
    """0 for a baseline word, 2 for a later-visit word, 3 for a follow-up word, 1 otherwise (decision C24)."""
    word = re.match(r"[a-z]*", v.lower()).group(0)
    return 0 if word in BASELINE_WORDS else 2 if word in LATER_WORDS else 3 if word in FOLLOW_UP_WORDS else 1


def visit_order(visits) -> list[str]:
    """Visit names in study order: a name starting with a baseline word (``baseline``, ``pre``, ``screening``, ...)
    first, one starting with ``post`` / ``after`` / ``discharge`` later and a follow-up (``followup``, ``fu``, ...)
    last (decision C24), within these natural order, runs of digits compared as numbers (``visit2`` before
    ``visit10``, ``week4`` before ``week12``, ``1`` before ``2``), then by the text; the first is the baseline
    (decision C22)."""
    def key(v: str):
        return _word_rank(v), [(0, int(t), "") if t.isdigit() else (1, 0, t) for t in re.split(r"(\d+)", v) if t], v

    return sorted({str(v) for v in visits}, key=key)


def visit_order_guess(visits) -> str | None:
    """The warning when the study order of ``visits`` is only the alphabet's (decision C24): no name holds a number
    and some name is neither a baseline nor a later-visit word (``clinic`` / ``home``); None when the order is
    known."""
    names = visit_order(visits)
    if len(names) < 2 or any(re.search(r"\d", v) for v in names) or all(_word_rank(v) != 1 for v in names):
        return None
    return (f"visits {', '.join(repr(v) for v in names)} hold no number: taken in text order, so {names[0]!r} is the "
            "baseline of changes.csv; name them in study order (visit1, visit2, or pre / post) if it is not "
            "(decision C24)")


def _labelled(sessions):
    """The rows of sessions.csv that name both a subject and a visit, both as text (a column pandas read as numbers
    gives ``2``, not ``2.0``; read sessions.csv with ``dtype={"subject": str, "visit": str}`` to keep ``007``)."""
    named = sessions[sessions["subject"].notna() & sessions["visit"].notna()].copy()
    for c in ("subject", "visit"):
        named[c] = named[c].map(lambda v: str(int(v)) if isinstance(v, float) and v.is_integer() else str(v))
    return named


#: subjects.csv's columns (cohort C25)
SUBJECT_COLUMNS = ("subject", "visit", "group", "n_tracked", "n_failed", "paths", "distance_m", "n_bouts",
                   "walking_time_s", "n_steps", "n_strides", "bouts_distance_m", "gait_speed_mps", "cadence_spm")


def subject_totals(sessions):
    """subjects.csv from sessions.csv (cohort C25), or ``None`` when no session names a subject: one row per subject
    (natural order) and, when some session names a visit, per visit (:func:`visit_order`; a subject's sessions
    without a visit are one row with an empty visit). ``n_tracked`` / ``n_failed``: its sessions; ``paths``: the
    sessions counted (``; ``-separated, relative to ROOT); ``distance_m``: the tracks' distances summed;
    ``n_bouts``, ``walking_time_s``, ``n_steps``, ``n_strides``, ``bouts_distance_m``: the detected walking bouts'
    count, summed durations, steps (of both feet, L103), strides and distance (bouts.csv of each session, under the
    batch's ``--bout-break-s`` / ``--bout-min-strides``); ``gait_speed_mps`` = bouts_distance_m / walking_time_s and
    ``cadence_spm`` = 60 n_steps / walking_time_s: the bouts pooled, each weighed by its duration (empty without
    walking time). Sessions naming no subject are in no row (sessions.csv has them)."""
    import numpy as np
    import pandas as pd

    if "subject" not in sessions or not sessions["subject"].notna().any():
        return None
    named = sessions[sessions["subject"].notna()].copy()
    for c in ("subject", "visit"):
        named[c] = named[c].map(lambda v: None if pd.isna(v) else str(int(v)) if isinstance(v, float)
                                and v.is_integer() else str(v))
    by_visit = named["visit"].notna().any()
    rows = []
    for subject in visit_order(named["subject"]):
        mine = named[named["subject"] == subject]
        visits = visit_order(mine["visit"].dropna()) + ([None] if mine["visit"].isna().any() else [])
        for visit in visits if by_visit else [None]:
            at = mine if not by_visit else mine[mine["visit"].isna()] if visit is None else mine[mine["visit"] == visit]
            ok = at[at["status"] == "ok"]

            def total(col, ok=ok):  # empty when none of the sessions was tracked
                return pd.to_numeric(ok[col], errors="coerce").sum() if col in ok and len(ok) else np.nan

            t = total("bouts_time_s")
            row = {"subject": subject, "visit": visit, "group": "; ".join(dict.fromkeys(at["group"].astype(str))),
                   "n_tracked": len(ok), "n_failed": len(at) - len(ok), "paths": "; ".join(at["path"].astype(str)),
                   "distance_m": total("distance_m"), "n_bouts": total("n_bouts"), "walking_time_s": t,
                   "n_steps": total("bouts_n_steps"), "n_strides": total("bouts_n_strides"),
                   "bouts_distance_m": total("bouts_distance_m")}
            row["gait_speed_mps"] = row["bouts_distance_m"] / t if t > 0 else np.nan
            row["cadence_spm"] = 60.0 * row["n_steps"] / t if t > 0 else np.nan
            rows.append(row)
    out = pd.DataFrame(rows, columns=list(SUBJECT_COLUMNS))
    for c in ("n_tracked", "n_failed", "n_bouts", "n_steps", "n_strides"):
        out[c] = out[c].astype("Int64")
    return out


def _side(rows, visit: str) -> tuple[str, str | None, object]:
    """One subject's sessions at ``visit``: (status, reason, the row when there is exactly one tracked)."""
    if rows.empty:
        return "missing", f"{visit}: no session", None
    if len(rows) > 1:
        return "several", f"{visit}: {len(rows)} sessions ({', '.join(rows['path'].astype(str))})", None
    row = rows.iloc[0]
    if row["status"] != "ok":
        return "failed", f"{visit}: {row['path']} failed", row
    return "ok", None, row


def change_table(sessions, metrics=GROUP_METRICS):
    """changes.csv from sessions.csv (a DataFrame), or ``None`` when the sessions naming a subject and a visit name
    fewer than two visits (decision C22). One row per subject (natural order) and later visit: the change of each
    measure from the subject's baseline visit (the first in :func:`visit_order` of every visit found), later minus
    baseline. A subject without a tracked session at either visit is a row too, ``status`` ``missing`` (no session),
    ``failed`` (its session failed) or ``several`` (more than one session of the subject at that visit: which one
    is the visit is not in the data), with the ``reason`` and empty changes - listed, never dropped. A copy of the
    baseline recording at a later visit (C20's ``duplicate_of``) stays ``ok`` and is said in ``reason``."""
    import numpy as np
    import pandas as pd

    if "subject" not in sessions or "visit" not in sessions:  # a sessions.csv written before C22
        return None
    named = _labelled(sessions)
    visits = visit_order(named["visit"])
    if len(visits) < 2:
        return None
    measures = [m for m in metrics if m in sessions and pd.to_numeric(sessions[m], errors="coerce").notna().any()]
    base = visits[0]
    rows = []
    for subject in visit_order(named["subject"]):
        mine = named[named["subject"] == subject]
        b_status, b_reason, b_row = _side(mine[mine["visit"] == base], base)
        for visit in visits[1:]:
            v_status, v_reason, v_row = _side(mine[mine["visit"] == visit], visit)
            status = next(s for s in STATUSES[1:] + ("ok",) if s in (b_status, v_status))
            reasons = [r for r in (b_reason, v_reason) if r]
            if status == "ok" and v_row.get("duplicate_of") == b_row["path"]:  # decision C20's copy
                reasons.append(f"{v_row['path']} holds the same recording as {b_row['path']} (duplicate_of)")
            row = {"subject": subject, "group": mine["group"].astype(str).iloc[0], "baseline_visit": base,
                   "visit": visit, "status": status, "reason": "; ".join(reasons) or None,
                   "baseline_path": None if b_row is None else b_row["path"],
                   "path": None if v_row is None else v_row["path"]}
            for m in measures:
                both = status == "ok"
                b = pd.to_numeric(b_row[m], errors="coerce") if both else np.nan
                v = pd.to_numeric(v_row[m], errors="coerce") if both else np.nan
                row[f"{m}_baseline"] = b
                row[f"{m}_change"] = v - b  # later visit minus baseline (decision C22)
            rows.append(row)
    return pd.DataFrame(rows).reindex(columns=[*CHANGE_COLUMNS, *(f"{m}_{k}" for m in measures
                                                                  for k in ("baseline", "change"))])


def change_summary(changes, metrics=GROUP_METRICS):
    """changes_summary.csv from changes.csv (decision C23): one row per later visit (in order) and measure with
    ``n_subjects`` (subjects with a change: both visits tracked and the measure present at both), ``mean_change``,
    ``sd_change`` (n - 1) and ``ci95_low`` / ``ci95_high``, the paired 95 % t-interval of the mean change (the
    one-sample interval of the differences, :func:`pdrlearn.cohort.t_interval`; empty under two subjects), and
    ``n_not_paired`` / ``not_paired``: the subjects of that visit whose row is not ``ok`` (``;``-separated)."""
    import pandas as pd

    rows = []
    for visit in visit_order(changes["visit"]):
        at = changes[changes["visit"] == visit]
        unpaired = at[at["status"] != "ok"]["subject"].astype(str).tolist()
        for m in metrics:
            if f"{m}_change" not in at:
                continue
            d = pd.to_numeric(at[f"{m}_change"], errors="coerce").dropna()
            mean, sd = (d.mean(), d.std()) if len(d) else (float("nan"), float("nan"))
            low, high = t_interval(mean, sd, len(d))
            rows.append({"visit": visit, "baseline_visit": at["baseline_visit"].iloc[0], "measure": m,
                         "n_subjects": len(d), "mean_change": mean, "sd_change": sd, "ci95_low": float(low),
                         "ci95_high": float(high), "n_not_paired": len(unpaired),
                         "not_paired": "; ".join(unpaired) or None})
    return pd.DataFrame(rows)


def changes_text(summary):
    """changes_summary.csv as track-all prints it and a batch report shows it (decision C23): per later visit and
    measure the subjects paired, ``mean change [low, high]`` (the paired 95 % t-interval) and the subjects not
    paired."""
    import pandas as pd

    def cell(r) -> str:
        if pd.isna(r.mean_change):
            return ""
        return f"{r.mean_change:+.3g}" + ("" if pd.isna(r.ci95_low) else f" [{r.ci95_low:.3g}, {r.ci95_high:.3g}]")

    return pd.DataFrame({"visit": [f"{v} - {b}" for v, b in zip(summary["visit"], summary["baseline_visit"],
                                                                 strict=True)],
                         "measure": summary["measure"], "n_subjects": summary["n_subjects"],
                         "mean change [95 % CI]": [cell(r) for r in summary.itertuples()],
                         "not paired": summary["not_paired"].fillna("")})
