"""Repeated recordings of one condition (shifts, monitoring days) pooled per subject (``track-all --repeated``,
cohort decisions C257, C258): ``subjects_pooled.csv`` - each subject's sessions, every visit, pooled into the mean per
session and the rate per hour of its activity measures - and ``groups_pooled.csv`` - those per group with the subject
as the unit. Both are functions of sessions.csv, as subjects.csv and changes.csv are (C18)."""

from __future__ import annotations

from pdrlearn.cohort import SKIPPED, describe_groups, joined_labels, natural_key

#: decision C257: sessions.csv's activity measures subjects_pooled.csv pools (additive per session: a count or a
#: time or a distance); ``n_steps_both_feet`` is the steps of both feet (L103), empty where W476 withheld the count
#: (C246), so contacts that are no steps are never pooled as steps
POOLED_MEASURES = ("n_steps_both_feet", "distance_m", "n_bouts", "walking_time_s", "standing_time_s",
                   "sitting_time_s", "lying_time_s", "n_sit_to_stand", "floors_up", "floors_down")
#: decision C257: subjects_pooled.csv's leading columns; ``<measure>_per_session`` and ``<measure>_per_h`` follow
#: per measure, then ``reason``
POOLED_COLUMNS = ("subject", "group", "n_tracked", "n_failed", "visits", "paths", "hours_recorded")


def pooled_kinds(measure: str) -> tuple[str, str]:
    """Decision C257: the two subjects_pooled.csv columns of ``measure``."""
    return f"{measure}_per_session", f"{measure}_per_h"


def pooled_subjects(sessions, visit_map: dict[str, str] | None = None, measures=POOLED_MEASURES):
    """subjects_pooled.csv from sessions.csv (a DataFrame; decision C257), or None when no session names a subject:
    one row per subject (natural order) over all its sessions. ``hours_recorded``: the tracked sessions'
    ``time_span_s`` less ``time_no_data_s`` (L275), summed, in hours; per measure ``<m>_per_session`` - the mean over
    the tracked sessions with a value - and ``<m>_per_h`` - their values summed over their hours (a ratio of totals:
    a long shift weighs more than a short one). A failed session is counted in ``n_failed`` only; a copy of another
    of the subject's sessions (C20's ``duplicate_of``) is counted once; ``reason`` names each (and, C176's wording,
    a measure only some sessions have). ``visits`` as changes.csv names them (``visit_map``, C28, C29)."""
    import pandas as pd

    from pdrlearn.visits import paired_visits, partial_measures, visit_order

    if "subject" not in sessions or not sessions["subject"].notna().any():
        return None
    named = sessions[sessions["subject"].notna()].copy()
    named["subject"] = named["subject"].map(lambda v: str(int(v)) if isinstance(v, float) and v.is_integer()
                                            else str(v))
    named["visit"] = paired_visits(sessions, visit_map)[named.index] if "visit" in sessions else None
    rows = [_pooled_row(subject, named[named["subject"] == subject], measures, partial_measures)
            for subject in visit_order(named["subject"])]
    columns = list(POOLED_COLUMNS) + [c for m in measures for c in pooled_kinds(m)] + ["reason"]
    out = pd.DataFrame(rows, columns=columns)
    for c in ("n_tracked", "n_failed"):
        out[c] = out[c].astype("Int64")
    return out


def _pooled_row(subject: str, mine, measures, partial_measures) -> dict:
    """Decision C257: one subject's row of subjects_pooled.csv from its sessions.csv rows ``mine``."""
    import numpy as np
    import pandas as pd

    reasons = []
    if "duplicate_of" in mine:  # decision C20 / C83: a re-uploaded recording counted once
        copies = mine["duplicate_of"].isin(mine["path"])
        reasons += [f"{p} is a copy of {d}, counted once" for p, d in zip(
            mine.loc[copies, "path"], mine.loc[copies, "duplicate_of"], strict=True)]
        mine = mine[~copies]
    ok = mine[mine["status"] == "ok"]
    failed = mine.loc[(mine["status"] != "ok") & (mine["status"] != SKIPPED), "path"].astype(str).tolist()
    reasons += [f"{p} failed, pooled nowhere" for p in failed]
    reasons += [r.split(": ", 1)[1] for r in partial_measures(ok, subject, [m for m in measures if m in ok])]

    def column(name):
        return pd.to_numeric(ok[name], errors="coerce") if name in ok else pd.Series(np.nan, index=ok.index)

    hours = (column("time_span_s") - column("time_no_data_s").fillna(0.0)) / 3600.0  # L275: worn time with data
    visits = [v for v in dict.fromkeys(mine["visit"]) if isinstance(v, str)] if "visit" in mine else []
    row = {"subject": subject, "group": joined_labels(mine["group"]),  # decision C263: C25's text, one helper
           "n_tracked": len(ok), "n_failed": len(failed),
           "visits": "; ".join(sorted(visits, key=natural_key)) or None,
           "paths": "; ".join(mine["path"].astype(str)),
           "hours_recorded": float(hours.sum()) if len(ok) and hours.notna().all() else np.nan}
    for m in measures:
        values = column(m)
        has = values.notna() & hours.notna()
        per_session, per_h = pooled_kinds(m)
        row[per_session] = float(values[values.notna()].mean()) if values.notna().any() else np.nan
        h = float(hours[has].sum())
        row[per_h] = float(values[has].sum()) / h if has.any() and h > 0 else np.nan
    row["reason"] = "; ".join(reasons) or None
    return row


def pooled_groups(subjects):
    """groups_pooled.csv from subjects_pooled.csv (decision C258): one row per ``group`` (natural order) with
    ``n_subjects`` and groups.csv's statistics (C12, C20: n, mean, sd, median, 95 % t-interval) of
    ``hours_recorded`` and every ``_per_session`` / ``_per_h`` column over the group's subjects with a value - the
    subject as the unit, where groups.csv counts each session as a person."""
    import pandas as pd

    groups = sorted(subjects["group"].astype(str).unique(), key=natural_key)
    out = pd.DataFrame({"group": groups})
    out["n_subjects"] = [int((subjects["group"].astype(str) == g).sum()) for g in groups]
    tracked = subjects[subjects["n_tracked"] > 0]
    measures = ["hours_recorded"] + [c for c in subjects.columns if c.endswith(("_per_session", "_per_h"))]
    return describe_groups(out, tracked, tracked["group"].astype(str), measures)


#: decision C259: the leading words of visit names that are repeated recordings of one condition (``shift3``);
#: ``day`` is not one of them (``day30`` is a trial's follow-up as often as a monitoring day)
REPEATED_WORDS = frozenset({"shift", "night", "recording", "rec"})


def repeated_visits_hint(visits) -> str | None:
    """Decision C259: the one-line hint when every visit name (as changes.csv names them) starts with a
    :data:`REPEATED_WORDS` word - repeated shifts compared as visits - else None."""
    import re

    from pdrlearn.decision_refs import decision_ref

    names = sorted({str(v) for v in visits if isinstance(v, str) and v}, key=natural_key)
    words = [re.match(r"[a-z]*", v.lower()).group(0) for v in names]
    if len(names) < 2 or not all(w in REPEATED_WORDS for w in words):
        return None
    return (f"the visits ({', '.join(names[:4])}{' ...' if len(names) > 4 else ''}) look like repeated recordings "
            f"of one condition, yet changes.csv compares each with {names[0]} as a baseline; for shifts or days "
            f"pooled per subject (subjects_pooled.csv, groups_pooled.csv, no changes.csv) pass --repeated "
            f"({decision_ref('C259', topic='cohort')})")
