"""Subjects and visits of a cohort: each subject's (and visit's) walking totals (``subjects.csv``, cohort C25).
Paired visits (decisions C22, C23): per subject, the change of each summary measure from the baseline
visit to every later visit (``changes.csv``), and per visit and measure the mean change with its paired 95 %
t-interval (``changes_summary.csv``). All three are functions of sessions.csv (its ``subject``, ``visit``, ``status``
and measure columns), so they are the same for the same data, version and options, as sessions.csv is (C18).

The subject and visit of a session are its meta.json's (``pdrlearn.cohort.session_labels``): a study names them
there; folder names are not read (a trial design is not known to the tool, C20)."""

from __future__ import annotations

import re

from pdrlearn.cohort import GROUP_METRICS, SKIPPED, joined_labels, natural_key, t_interval
from pdrlearn.decision_refs import decision_ref

#: changes.csv's leading columns (decision C22; C82: the visits as meta.json wrote them; C83: the trials averaged);
#: ``<measure>_baseline``, ``<measure>_change`` and ``<measure>_change_pct`` (C81) follow per measure
CHANGE_COLUMNS = ("subject", "group", "baseline_visit", "visit", "baseline_visit_as_written", "visit_as_written",
                  "status", "reason", "baseline_n_trials", "n_trials", "baseline_path", "path",
                  "baseline_duplicate_of", "duplicate_of")
#: what a pair of visits is when it is not ``ok`` (C22), in the order they are looked for; a pair of tracked
#: sessions can still be ``pipelines`` (C30) or ``duplicate`` (C31). ``several`` is no longer written (decision C83:
#: repeated trials of a visit are averaged); kept for tables written before it
STATUSES = ("ok", "missing", "failed", "several")
#: the measures a gait study compares most (decision C81): named in B302's / B303's line beside the full list
COMMON_MEASURES = ("gait_speed_mps", "median_cadence_spm", "median_stride_time_s", "stride_time_cv_pct",
                   "median_stride_length_m", "stride_length_cv_pct", "step_time_asymmetry_pct")

#: decision C177: the clinical tests' measures changes.csv compares by default before groups.csv's (GROUP_METRICS),
#: each only where a session has a value (``--corridor``'s walk test and fatigue index, a TUG, a 10 m walk, a
#: timed 25-foot walk): a trial's primary endpoint (the 6MWT distance) is not left out of the default visit change
CLINICAL_MEASURES = ("walk_test_distance_m", "fatigue_index", "tug_time_s", "ten_m_walk_speed_mps", "t25fw_time_s")
#: decision C177: changes.csv's default measures (those without a value in any session are not compared)
CHANGE_METRICS = CLINICAL_MEASURES + GROUP_METRICS
#: decision C211: a measure compared between two visits only when its walkway (this sessions.csv column) is the same
#: at both: a 10 m walkway's speed is not a flying 7.62 m walk's (review R1 F3)
SAME_WALKWAY = {"ten_m_walk_speed_mps": "ten_m_walk_timed_m"}
#: decision C211: changes.csv's reason for a measure left out of a pair ({measure}, {why} :func:`walkway_why`'s,
#: {walkways} "10 m / 7.62 m", {ref})
WALKWAY_REASON = "{measure} not compared: {why} ({walkways} timed, {ref})"


def measure_columns() -> tuple[str, ...]:
    """The number columns of sessions.csv (the data dictionary's, :data:`pdrlearn.columns.SESSIONS`): the measures
    changes.csv can compare (decisions C81, B302)."""
    from pdrlearn.columns import SESSIONS

    return tuple(name for name, _, kind, _ in SESSIONS if kind in ("number", "integer"))


def not_measures() -> tuple[str, ...]:
    """The number columns of the data dictionary's sessions.csv that hold no one number per session (decision B326):
    the lists summary.json alone has (``splits_m``, ``split_times_s``, ...) and ids (``schema_version``)."""
    from pdrlearn.columns import SESSIONS

    return tuple(name for name, unit, kind, text in SESSIONS if kind in ("number", "integer")
                 and (unit == "-" or "(a list)" in text))


def empty_measures(sessions, metrics) -> list[str]:
    """The names of ``metrics`` no session of sessions.csv has a value of (decision B327: warned, one line, by
    track-all; the others compared)."""
    import pandas as pd

    return [m for m in dict.fromkeys(metrics) if m not in sessions
            or not pd.to_numeric(sessions[m], errors="coerce").notna().any()]


def check_measures(metrics, option: str = "change_table(metrics=...)", extra=(), decision: str = "B302"
                   ) -> tuple[str, ...]:
    """``metrics`` as a tuple of names when each is a number column of sessions.csv (:func:`measure_columns`) or one of
    ``extra`` (the columns of the table given); else decisions B302 / B303: one line naming the unknown names, the
    nearest valid names, the common measures and where the full list is (``option`` names the parameter)."""
    import difflib

    from pdrlearn.errors import DataError

    metrics = tuple(dict.fromkeys((metrics,) if isinstance(metrics, str) else metrics))  # B326: each name once
    valid = dict.fromkeys([*measure_columns(), *extra])
    unknown = [m for m in metrics if m not in valid]
    if not metrics:
        raise DataError(f"{option}: no measure given; name one or more of {', '.join(COMMON_MEASURES)} (decision "
                        f"{decision})")
    lists = [m for m in metrics if m in not_measures()]
    if lists:  # decision B326: a list or a version has no change to average
        raise DataError(f"{option}: {', '.join(repr(m) for m in lists)} "
                        f"{'is' if len(lists) == 1 else 'are'} not a measure of one number per session (a list of "
                        f"summary.json, or the version of its keys): leave {'it' if len(lists) == 1 else 'them'} "
                        f"out; e.g. {', '.join(COMMON_MEASURES)} (decision B326)")
    if unknown:
        near = {m: [v for v in valid if str(m).lower() in v] or difflib.get_close_matches(str(m), valid, 3, 0.6)
                for m in unknown}
        hints = "; ".join(f"{m!r}: did you mean {', '.join(n[:3])}?" for m, n in near.items() if n)
        raise DataError(f"{option}: unknown measure {', '.join(repr(m) for m in unknown)}" + (f" ({hints})" if hints
                        else "") + f"; the measures are the number columns of sessions.csv, e.g. "
                        f"{', '.join(COMMON_MEASURES)} (all {len(measure_columns())}: `pdrlearn columns "
                        f"sessions.csv`; decision {decision})")
    return metrics


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
        return _word_rank(v), *natural_key(v)  # decision C102: the natural order every table uses

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


def _as_text(v):
    """A label as text (a column pandas read as numbers gives ``2``, not ``2.0``), None for an empty cell."""
    import pandas as pd

    return None if pd.isna(v) else str(int(v)) if isinstance(v, float) and v.is_integer() else str(v)


def _written(sessions):
    """sessions.csv with ``visit`` as meta.json wrote it (decision C82: ``visit_as_written`` when the table has it,
    ``visit`` being then the paired name; a sessions.csv written before C82 has only ``visit``, as written)."""
    if "visit_as_written" not in sessions:
        return sessions
    return sessions.assign(visit=sessions["visit_as_written"])


def _labelled(sessions):
    """The rows of sessions.csv that name both a subject and a visit (as written, C82), both as text (read
    sessions.csv with ``dtype={"subject": str, "visit": str}`` to keep ``007``)."""
    sessions = _written(sessions)
    named = sessions[sessions["subject"].notna() & sessions["visit"].notna()].copy()
    for c in ("subject", "visit"):
        named[c] = named[c].map(_as_text)
    return named


def paired_visits(sessions, visit_map: dict[str, str] | None = None):
    """Decision C82: per row of sessions.csv, its visit as changes.csv and subjects.csv name it - the visits as
    written (``visit``, or ``visit_as_written`` when present) with ``visit_map`` applied and spellings of one visit
    made one (:func:`canonical_visits`, C28, C29) over the sessions naming a subject, as those tables do; empty where
    no visit is named. track-all writes it as sessions.csv's and bouts.csv's ``visit``, so the four tables join on
    (subject, visit)."""
    raw = _written(sessions)["visit"].map(_as_text)
    named = sessions["subject"].notna() & raw.notna()
    names = canonical_visits(raw[named], visit_map)[0] if named.any() else {}
    rest = canonical_visits(raw[~named].dropna(), visit_map)[0]
    return raw.map(lambda v: None if v is None else names.get(v, rest.get(v)))


#: subjects.csv's columns (cohort C25)
SUBJECT_COLUMNS = ("subject", "visit", "group", "n_tracked", "n_failed", "paths", "distance_m", "n_bouts",
                   "walking_time_s", "n_steps", "n_strides", "bouts_distance_m", "gait_speed_mps", "cadence_spm",
                   "visit_as_written",  # decision C82: last, the columns before it kept in place
                   *("floors_up", "floors_down", "time_no_data_s", "standing_time_s", "sitting_time_s",
                     "lying_time_s", "n_sit_to_stand", "n_stand_to_sit"),  # decision C108: after, positions kept
                   "bouts_time_s", "bouts_gait_speed_mps")  # decision W447: C25's bout speed under its own name

#: decision C108: sessions.csv's additive columns subjects.csv sums (a day in parts adds up); its medians, CVs,
#: speeds and errors are not additive and stay per session (gait speed and cadence are pooled instead, C25, L164)
SUMMED_SESSION_COLUMNS = SUBJECT_COLUMNS[SUBJECT_COLUMNS.index("visit_as_written") + 1:
                                         SUBJECT_COLUMNS.index("bouts_time_s")]


def subject_totals(sessions, visit_map: dict[str, str] | None = None, by: str | None = None):
    """subjects.csv from sessions.csv (cohort C25), or ``None`` when no session names a subject: one row per subject
    (natural order) and, when some session names a visit, per visit (:func:`visit_order`; a subject's sessions
    without a visit are one row with an empty visit). ``n_tracked`` / ``n_failed``: its sessions; ``paths``: the
    sessions counted (``; ``-separated, relative to ROOT); ``distance_m``: the tracks' distances summed;
    ``walking_time_s`` and ``gait_speed_mps``: decision W447, sessions.csv's (summary.json's) definition pooled -
    the sessions' ``walking_time_s`` summed and ``distance_m`` over it (empty without walking time), so a one-session
    subject reads what sessions.csv reads; ``n_bouts``, ``n_steps``, ``n_strides``, ``bouts_distance_m``,
    ``bouts_time_s``: the detected walking bouts' count, steps (of both feet, L103), strides, distance and summed
    durations (bouts.csv of each session, under the batch's ``--bout-rule`` / ``--bout-break-s`` /
    ``--bout-min-strides``), ``bouts_gait_speed_mps`` = bouts_distance_m / bouts_time_s (C25's, renamed by W447)
    and ``cadence_spm``: bouts.csv's cadence definition
    (:func:`pdrlearn.track.bouts.cadence_spm`, decision L164) of the bouts pooled - their steps between first and
    last contact (sessions.csv's ``bouts_n_step_intervals``) over their contact spans (``bouts_contact_span_s``).
    Sessions naming no subject are in no row (sessions.csv has them). Visits are named as changes.csv names them
    (:func:`canonical_visits` with ``visit_map``, C28, C29; decision C40: ``BL`` and ``Baseline`` of one subject had
    been two rows). ``by``: a sessions.csv label column (``"test"``, decision C171: track-all's ``--group-by test``)
    whose values split each subject's (and visit's) row further, in natural order, sessions without one last in a row
    with it empty; the column follows ``visit``."""
    import pandas as pd

    if "subject" not in sessions or not sessions["subject"].notna().any():
        return None
    named = _written(sessions)[sessions["subject"].notna()].copy()
    for c in ("subject", "visit", *([by] if by else [])):
        if c not in named:  # decision C171: a sessions.csv without the label column: every row without one
            named[c] = None
        named[c] = named[c].map(_as_text)
    named["visit_as_written"] = named["visit"]
    by_visit = named["visit"].notna().any()
    if by_visit:  # decision C40: the visits as changes.csv names them
        names = canonical_visits(named["visit"].dropna(), visit_map)[0]
        named["visit"] = named["visit"].map(lambda v: None if pd.isna(v) else names[v])
    rows = []
    for subject in visit_order(named["subject"]):
        mine = named[named["subject"] == subject]
        visits = visit_order(mine["visit"].dropna()) + ([None] if mine["visit"].isna().any() else [])
        for visit in visits if by_visit else [None]:
            at_visit = (mine if not by_visit else mine[mine["visit"].isna()] if visit is None
                        else mine[mine["visit"] == visit])
            for label in _labels_of(at_visit, by):  # decision C171: each test of the visit its own row
                rows.append(_subject_row(subject, visit, by, label, at_visit if by is None else
                                         at_visit[at_visit[by].isna()] if label is None else
                                         at_visit[at_visit[by] == label]))
    columns = list(SUBJECT_COLUMNS)
    if by:
        columns.insert(columns.index("visit") + 1, by)
    out = pd.DataFrame(rows, columns=columns)
    for c in ("n_tracked", "n_failed", "n_bouts", "n_steps", "n_strides", "floors_up", "floors_down",
              "n_sit_to_stand", "n_stand_to_sit"):
        out[c] = out[c].astype("Float64").astype("Int64")
    return out


def _labels_of(rows, by: str | None) -> list:
    """Decision C171: the values of label column ``by`` among ``rows`` in natural order, None last when a row has
    none; ``[None]`` without ``by`` (one row)."""
    if by is None:
        return [None]
    return visit_order(rows[by].dropna()) + ([None] if rows[by].isna().any() else [])


def _subject_row(subject, visit, by: str | None, label, at) -> dict:
    """Cohort C25's row of one subject's sessions ``at`` (sessions.csv rows) at ``visit`` (and, decision C171,
    ``label`` of column ``by``)."""
    import numpy as np
    import pandas as pd

    from pdrlearn.track.bouts import cadence_spm

    ok = at[at["status"] == "ok"]

    def total(col, ok=ok):  # empty when none of the sessions was tracked
        return pd.to_numeric(ok[col], errors="coerce").sum() if col in ok and len(ok) else np.nan

    t = total("bouts_time_s")
    row = {"subject": subject, "visit": visit, "visit_as_written": _names(at["visit_as_written"]),
           "group": joined_labels(at["group"]),  # decision C263: a missing group "", not a crash
           # decision B393: a split part at rest (B389's skipped) is neither tracked nor failed
           "n_tracked": len(ok), "n_failed": int((at["status"] != SKIPPED).sum()) - len(ok),
           "paths": "; ".join(at["path"].astype(str)),
           "distance_m": total("distance_m"), "n_bouts": total("n_bouts"),
           "walking_time_s": total("walking_time_s"),  # decision W447: the summary's, as sessions.csv
           "n_steps": total("bouts_n_steps"), "n_strides": total("bouts_n_strides"),
           "bouts_distance_m": total("bouts_distance_m"), "bouts_time_s": t}
    w = row["walking_time_s"]
    row["gait_speed_mps"] = row["distance_m"] / w if w > 0 else np.nan  # decision W447
    row["bouts_gait_speed_mps"] = row["bouts_distance_m"] / t if t > 0 else np.nan  # cohort C25
    span = total("bouts_contact_span_s")  # decision L164: bouts.csv's cadence, the bouts pooled
    row["cadence_spm"] = cadence_spm(total("bouts_n_step_intervals"), span) if span > 0 else np.nan
    row.update({c: _sum_of_all(ok, c) for c in SUMMED_SESSION_COLUMNS})
    if by:
        row[by] = label
    return row


def _sum_of_all(ok, column: str):
    """Decision C108: ``column`` of the tracked sessions ``ok`` summed; NaN when none was tracked or one of them
    has no value (a foot track's posture times, a session table without the column): a part of a day's total
    must not read as the day's total."""
    import numpy as np
    import pandas as pd

    if column not in ok or not len(ok):
        return np.nan
    values = pd.to_numeric(ok[column], errors="coerce")
    return float(values.sum()) if values.notna().all() else np.nan


def _names(values) -> str | None:
    """Labels as one cell: each once, in order, ``; ``-separated (decision C82); None when there is none."""
    names = [v for v in dict.fromkeys(values) if isinstance(v, str)]
    return "; ".join(names) or None


def _side(rows, visit: str, measures) -> tuple[str, str | None, object]:
    """One subject's sessions at ``visit``: (status, reason, the row of the visit). Decision C83: the tracked
    sessions of a visit (repeated trials of a condition) are averaged - the row holds each measure's mean over them
    (the trials with a value), ``paths`` / ``path`` the sessions averaged and ``n_trials`` their number; a session
    that is a copy of another of the visit (C20's ``duplicate_of``) is counted once, a failed one left out and said
    in the reason; trials tracked by different pipelines are ``pipelines`` (C30: not one method's mean)."""
    import pandas as pd

    if rows.empty:
        return "missing", f"{visit}: no session", None
    reasons = []
    if "duplicate_of" in rows:
        copies = rows["duplicate_of"].isin(rows["path"])
        reasons += [f"{visit}: {p} is a copy of {d}, counted once" for p, d in zip(
            rows.loc[copies, "path"], rows.loc[copies, "duplicate_of"], strict=True)]
        rows = rows[~copies]
    skipped = rows["status"] == SKIPPED  # decision B393: B389's split parts at rest are neither trials nor failed
    if skipped.any():
        rows = rows[~skipped]
        if rows.empty:
            return "missing", f"{visit}: no session tracked ({int(skipped.sum())} split parts at rest skipped)", None
    ok = rows[rows["status"] == "ok"]
    failed = rows.loc[rows["status"] != "ok", "path"].astype(str).tolist()
    if len(rows) == 1:  # one session: its row, as before C83
        row = rows.iloc[0].copy()
        row["n_trials"] = len(ok)
        return ("ok", "; ".join(reasons) or None, row) if len(ok) else ("failed", f"{visit}: {failed[0]} failed", row)
    if ok.empty:
        return "failed", f"{visit}: {', '.join(failed)} failed", None
    if failed:
        reasons.append(f"{visit}: {', '.join(failed)} failed, the mean of the other {len(ok)}")
    pipelines = [p for p in dict.fromkeys(ok["pipeline"]) if isinstance(p, str)] if "pipeline" in ok else []
    if len(pipelines) > 1:
        why = (f"{visit}: its trials were tracked by {', '.join(pipelines)}: a mean across pipelines is the "
               "methods' mix; track every trial with the same --pipeline (decisions C30, C83)")
        return "pipelines", why, None
    reasons += partial_measures(ok, visit, measures)  # decision C176
    row = pd.Series({"path": "; ".join(ok["path"].astype(str)), "paths": ok["path"].astype(str).tolist(),
                     "pipeline": pipelines[0] if pipelines else None, "n_trials": len(ok),
                     "duplicate_of": ok["duplicate_of"].tolist() if "duplicate_of" in ok else [None] * len(ok),  # C84
                     **{m: pd.to_numeric(ok[m], errors="coerce").mean() for m in measures}})  # C83: the trials' mean
    return "ok", "; ".join(reasons) or None, row


def partial_measures(ok, visit: str, measures) -> list[str]:
    """Decision C176: one reason per measure that only some of a visit's averaged sessions ``ok`` have (C83 averages
    the sessions with a value): which sessions it comes from, e.g. a 6MWT's ``walk_test_distance_m`` beside a TUG
    session of the same visit that scores none (L643)."""
    import pandas as pd

    out = []
    for m in measures:
        has = pd.to_numeric(ok[m], errors="coerce").notna() if m in ok else pd.Series(False, index=ok.index)
        if has.any() and not has.all():
            out.append(f"{visit}: {m} from {int(has.sum())} of {len(ok)} sessions ("
                       f"{', '.join(ok.loc[has, 'path'].astype(str))}; the others have none)")
    return out


#: a visit name's leading word and the word it is a spelling of (decision C28), after case and separators are
#: dropped: ``BL`` / ``Baseline`` / ``baseline`` one visit, ``W12`` / ``wk12`` / ``Week 12`` one, ``FU`` /
#: ``follow-up`` / ``followup`` one; a one-letter word only before a number (``W12``, not ``W``)
VISIT_SYNONYMS = {"bl": "baseline", "base": "baseline", "w": "week", "wk": "week", "wks": "week", "weeks": "week",
                  "fu": "followup", "follow": "followup", "m": "month", "mo": "month", "months": "month",
                  "d": "day", "days": "day", "v": "visit"}


def visit_key(name: str) -> str:
    """The spelling-free form of a visit name (decision C28): lower case, without spaces, ``-``, ``_`` and other
    separators, leading zeros of numbers dropped and the leading word by :data:`VISIT_SYNONYMS` (``Follow-up 06`` ->
    ``followup6``, ``W12`` -> ``week12``, ``BL`` -> ``baseline``). A separator between two numbers stays, as ``.``
    (decision C40): ``1.5`` is not ``15``, nor ``2026-1-12`` ``2026-11-2``."""
    parts = re.split(r"(?<=\d)[\W_]+(?=\d)", str(name).lower())
    s = ".".join(re.sub(r"\d+", lambda m: str(int(m.group())), re.sub(r"[\W_]", "", p)) for p in parts)
    word = re.match(r"[^\W\d_]*", s).group(0)
    if len(word) == 1 and len(s) == 1:
        return s
    return VISIT_SYNONYMS.get(word, word) + s[len(word):]


def read_visit_map(path) -> dict[str, str]:
    """``track-all --visit-map FILE`` (decision C29): ``{visit as written in meta.json: the visit it is}``, from a JSON
    object or a CSV of two columns (name as written, canonical name; a first row ``raw,canonical`` is its header).
    Bad input: one line naming the file and the fix."""
    fix = 'give a JSON object {"BL": "baseline", ...} or a CSV of two columns raw,canonical (decision C29)'
    return read_name_map(path, "--visit-map", (["raw", "canonical"], ["visit", "canonical"]), fix)


def read_name_map(path, option: str, headers: tuple[list[str], ...], fix: str) -> dict[str, str]:
    """A map of names from a JSON object or a CSV of two columns (a first row among ``headers`` is the header), as
    ``--visit-map`` (C29) and ``--subject-map`` (C86) read it: names stripped, a name mapped twice to different
    names refused. Bad input: one line naming ``option``, the file, the row and ``fix``."""
    import csv
    import json
    from pathlib import Path

    from pdrlearn.errors import DataError

    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise DataError(f"{option} {path}: cannot be read ({exc.__class__.__name__}); {fix}") from None
    if path.suffix.lower() == ".json":
        try:
            pairs = json.loads(text)
        except ValueError as exc:
            raise DataError(f"{option} {path}: not JSON ({exc}); {fix}") from None
        if not isinstance(pairs, dict) or not all(isinstance(v, str | int) for v in pairs.values()):
            raise DataError(f"{option} {path}: not an object of names; {fix}")
        pairs = list(pairs.items())
    else:
        rows = [r for r in csv.reader(text.splitlines()) if any(c.strip() for c in r)]
        if rows and [c.strip().lower() for c in rows[0]] in headers:
            rows = rows[1:]
        bad = next((i for i, r in enumerate(rows, 1) if len(r) != 2 or not all(c.strip() for c in r)), None)
        if bad is not None:
            raise DataError(f"{option} {path}: row {bad} is not two names; {fix}")
        pairs = [(a, b) for a, b in rows]
    out: dict[str, str] = {}
    for raw, canonical in pairs:
        raw, canonical = str(raw).strip(), str(canonical).strip()
        if out.get(raw, canonical) != canonical:
            raise DataError(f"{option} {path}: {raw!r} is mapped to both {out[raw]!r} and {canonical!r}; keep one")
        out[raw] = canonical
    return out


def canonical_visits(visits, visit_map: dict[str, str] | None = None) -> tuple[dict[str, str], str | None]:
    """Decision C28: ``{visit as written: the visit changes.csv pairs it as}`` and the warning, one line, naming the
    spellings taken as one visit (None when there are none). ``visit_map`` (``--visit-map``, C29) is applied first;
    then names with one :func:`visit_key` are one visit, named by that key (``BL``, ``Baseline`` -> ``baseline``); a
    name written one way only stays as written."""
    mapped = {v: (visit_map or {}).get(v, v) for v in sorted({str(v) for v in visits})}
    spellings: dict[str, set[str]] = {}
    for name in mapped.values():
        spellings.setdefault(visit_key(name), set()).add(name)
    label = {key: key if len(names) > 1 else next(iter(names)) for key, names in spellings.items()}
    merged = [f"{', '.join(repr(n) for n in sorted(names))} -> {key!r}" for key, names in sorted(spellings.items())
              if len(names) > 1]
    warning = None if not merged else (
        "visit names spelled differently are paired as one visit in changes.csv: " + "; ".join(merged)
        + "; write one spelling in meta.json's visit, or give track-all --visit-map FILE (raw,canonical) to name "
        "them yourself (decision C28)")
    return {raw: label[visit_key(name)] for raw, name in mapped.items()}, warning


def _firsts(visits) -> list[str]:
    """The visits that can be a baseline (C24, C28): those starting with a baseline word, else the first one."""
    order = visit_order(visits)
    return [v for v in order if _word_rank(v) == 0] or order[:1]


def _baselines(named) -> dict[str, str | None]:
    """Decision C28: each subject's baseline, the first of its own visits (:func:`visit_order`) that starts with a
    baseline word (C24; the study's first visit when no visit name does), ``None`` for a subject without one. A
    subject of a group (site) none of whose visit names is a baseline word takes its group's first visit (decision
    C40: a site naming its visits ``T0`` / ``T1`` beside one naming them ``pre`` / ``post``) - a group seen at two or
    more visits only (decision C264: a group of one subject seen at ``V2`` alone, its folder the group, made ``V2`` a
    baseline, and every subject's ``V2`` left changes.csv). A subject still without one takes the most common
    baseline (C28) among those it has, else among those whose subjects have its visits later (C264: seen at ``V2``
    alone, it is paired against ``V1`` when the others' ``V2`` follows ``V1``, listed ``missing`` there); else
    ``None`` (:func:`change_table`: the study's most common baseline)."""
    import pandas as pd

    firsts = _firsts(named["visit"])
    group = named["group"].astype(str) if "group" in named else pd.Series("", index=named.index)
    local = {g: _firsts(vs) for g, vs in named.groupby(group)["visit"] if vs.nunique() > 1}  # C264: an order
    out, own = {}, {}
    for s, mine in named.groupby("subject"):
        own[s] = set(mine["visit"])
        out[s] = next((v for v in firsts if v in own[s]), None)
        g = str(group[mine.index[0]])
        if out[s] is None and g in local and _word_rank(local[g][0]) != 0:  # C40: the group names its own
            out[s] = next((v for v in local[g] if v in own[s]), None)
    counts = pd.Series([b for b in out.values() if b is not None], dtype=object).value_counts()
    order = visit_order(named["visit"])
    common = sorted(counts.index, key=lambda b: (-counts[b], order.index(b)))
    after = {b: set().union(*(own[s] - {b} for s in out if out[s] == b)) for b in common}
    for s in [s for s, b in out.items() if b is None]:  # decision C264: the baseline its visits belong to
        out[s] = next((b for b in common if b in own[s]), None) or next(
            (b for b in common if own[s] & after[b]), None)
    return out


def _naming_warning(named) -> str | None:
    """Decision C264: one line when the subjects' baselines (:func:`_baselines`) are named differently and one of
    them is no baseline word - a study mixing visit-naming schemes (``baseline`` / ``week12`` beside ``V1`` / ``V2``,
    C40's per-site baseline) is paired within each scheme, and changes_summary.csv never pools the schemes (C28);
    None when one name is everybody's baseline, or each is a baseline word (``baseline`` beside ``pre``: named so)."""
    import pandas as pd

    counts = pd.Series(list(_baselines(named).values()), dtype=object).dropna().value_counts()
    if len(counts) < 2 or all(_word_rank(b) == 0 for b in counts.index):  # C28: pre / post sites named so
        return None
    order = visit_order(counts.index)
    listed = ", ".join(f"{b!r} ({n} subject{'s' * (n != 1)})" for b in order for n in [int(counts[b])])
    return (f"the subjects' baseline visits are named differently: {listed}; changes.csv pairs each naming's visits "
            "on their own and changes_summary.csv never pools them; if they are one study's visits, give track-all "
            f"--visit-map FILE (raw,canonical, e.g. {order[-1]},{order[0]}) "
            f"({decision_ref('C264', topic='cohort')})")


def _twins(named) -> dict[str, list[str]]:
    """Decision C31: per session path, the other sessions holding the identical recording (C20's ``duplicate_of``
    read both ways: the copy names the first, the first is named by its copies)."""
    if "duplicate_of" not in named:
        return {}
    first = {str(p): d if isinstance(d, str) and d else str(p) for p, d in zip(named["path"], named["duplicate_of"],
                                                                             strict=True)}
    same: dict[str, set[str]] = {}
    for p, root in first.items():
        same.setdefault(root, {root}).add(p)
    return {p: sorted(same[first[p]] - {p}) for p in first}


def _pair_problem(b_row, v_row, subject_of: dict[str, str], twins: dict[str, list[str]]) -> tuple[str, str] | None:
    """A tracked pair that is no change of one subject: (status, reason) - ``pipelines`` when the two visits were
    tracked by different pipelines (C30: a foot pipeline's gait speed against a waist pipeline's is a change of
    method), ``duplicate`` when a visit's recording is also another subject's (C31: which subject it is, is not in
    the data) - else None."""
    bp, vp = b_row.get("pipeline"), v_row.get("pipeline")
    if isinstance(bp, str) and isinstance(vp, str) and bp != vp:
        return "pipelines", (f"{b_row['path']} tracked by {bp}, {v_row['path']} by {vp}: a change across pipelines "
                             "(units) is the methods' difference; track both visits with the same sensors and "
                             "--pipeline (decision C30)")
    for row in (b_row, v_row):
        for path in row.get("paths", [str(row["path"])]):  # decision C83: each trial averaged
            others = [q for q in twins.get(path, []) if subject_of.get(q) != subject_of.get(path)]
            if others:
                whose = ", ".join(sorted({subject_of.get(q) or "none named" for q in others}))
                return "duplicate", (f"{path} holds the same recording as {', '.join(others)} (subject {whose}): "
                                     "which subject it is, is not in the data (duplicate_of, decision C31)")
    return None


def _trials(row) -> list[tuple[str, object]]:
    """A visit's row as its trials: (path, C20's ``duplicate_of``) of each session averaged (decision C83), or of its
    one session."""
    if "paths" in row and isinstance(row["paths"], list):
        return list(zip(row["paths"], row["duplicate_of"], strict=True))
    return [(str(row["path"]), row.get("duplicate_of"))]


def _copies(b_row, v_row) -> list[tuple[str, str]]:
    """Decision C84 (C20 with C83): (later trial, baseline trial) for each trial of the later visit that holds the
    same recording as a trial of the baseline (its ``duplicate_of``)."""
    base = {p for p, _ in _trials(b_row)}
    return [(p, d) for p, d in _trials(v_row) if isinstance(d, str) and d in base]


def walkways_differ(base_rows, visit_rows, measure: str) -> str | None:
    """Decision C211: "10 m / 7.62 m" when ``measure``'s walkway (:data:`SAME_WALKWAY`, the baseline's and the later
    visit's sessions.csv rows) differs between the two visits; None when it agrees, is not known at either, or the
    measure has none."""
    import pandas as pd

    col = SAME_WALKWAY.get(measure)
    if col is None or col not in base_rows or col not in visit_rows:
        return None
    b, v = (sorted(set(pd.to_numeric(r.loc[pd.to_numeric(r[measure], errors="coerce").notna(), col],
                                     errors="coerce").dropna())) for r in (base_rows, visit_rows))
    if not b or not v or b == v and len(b) == 1:
        return None
    return " / ".join("+".join(f"{x:g} m" for x in side) for side in (b, v))


def walkway_why(walkways: str) -> str:
    """Decision C211 (review R2 F5): why :func:`walkways_differ`'s ``walkways`` ("10 m / 7.62 m") are not compared:
    "walkways differ", or "mixed walkways within a visit" when both visits timed the same two (or more)."""
    base, later = walkways.split(" / ")
    return "mixed walkways within a visit" if base == later else "walkways differ"


def tug_or_stairs(sessions):
    """Decision C276: a boolean Series over sessions.csv's rows: the session timed a TUG (``tug_time_s`` or
    ``tug_trials_median_s``) or walked stair strides (``n_stair_strides`` > 0) - its strides are a TUG's turn and
    closing strides of two short legs, or stair and landing strides, not the walk's."""
    import pandas as pd

    def number(c):
        return pd.to_numeric(sessions[c], errors="coerce") if c in sessions else pd.Series(float("nan"),
                                                                                           index=sessions.index)

    return (number("tug_time_s").notna() | number("tug_trials_median_s").notna()
            | (number("n_stair_strides").fillna(0) > 0))


def change_table(sessions, metrics=CHANGE_METRICS, visit_map: dict[str, str] | None = None, by: str | None = None,
                 walk_strides_only=("median_stride_length_m", "stride_length_cv_pct", "median_speed_mps")):
    """changes.csv from sessions.csv (a DataFrame), or ``None`` when the sessions naming a subject and a visit name
    fewer than two visits (decision C22). Visit names are first made one per visit (:func:`canonical_visits`,
    decisions C28, C29: ``BL`` and ``baseline`` one visit). One row per subject (natural order) and later visit: the
    change of each measure from the subject's own baseline (:func:`_baselines`, C28), later minus baseline. The
    later visits of a subject are those of the subjects with its baseline (a subject without a baseline visit, or
    whose baseline nobody has a later visit of: of the most common baseline), and its own. A subject without a
    tracked session at either visit is a row too, ``status`` ``missing`` (no session), ``failed`` (its session
    failed), with the ``reason`` and empty changes - listed, never dropped; several tracked sessions of a subject at
    one visit (repeated trials of a condition) are averaged, ``n_trials`` / ``baseline_n_trials`` counting them
    (decision C83, :func:`_side`; C22 had listed them as ``several``, unpaired); a tracked pair is ``pipelines``
    when the visits were tracked by different pipelines (C30) and ``duplicate`` when a recording is also another
    subject's (C31; ``baseline_duplicate_of`` / ``duplicate_of`` name the other sessions holding it). A copy of
    the baseline recording at a later visit of the same subject (C20's ``duplicate_of``) stays ``ok`` and is said
    in ``reason``. ``metrics``: sessions.csv's number columns compared (default :data:`CHANGE_METRICS`, C177; an
    unknown name is one error line, decision B302); each gets ``<m>_baseline``, ``<m>_change`` and ``<m>_change_pct``
    (:func:`pct_change`, C81); a measure of :data:`SAME_WALKWAY` measured on different walkways at the two visits
    is left empty and said in ``reason`` (decision C211). ``baseline_visit_as_written`` / ``visit_as_written``: the
    visits as meta.json wrote them (C82). ``by``: a sessions.csv label column (``"test"``, decision C174:
    track-all's ``--group-by test``): the
    visits are paired as without it, but each of the subject's values on its own - its Test5 at the follow-up against
    its Test5 at baseline, never a visit's tests averaged (C172's finding) - one row per subject, value (natural
    order, sessions naming none last with it empty) and later visit, the column after ``visit``; a test the subject
    did at one of the two visits only is ``missing`` there, listed. Decision C276: the measures of
    ``walk_strides_only`` are left empty for a TUG or stairs session (:func:`tug_or_stairs`: its strides are the turns'
    and the stairs', not the walk's: trial s53t1's TUG stride length read -28.6 % while the walk's grew +36.6 %) and
    the row's ``reason`` says so."""
    import numpy as np
    import pandas as pd

    metrics = check_measures(metrics, extra=[c for c in sessions.columns if pd.api.types.is_numeric_dtype(
        sessions[c])])  # decision B302: an unknown name is an error, not a measure silently left out
    if "subject" not in sessions or "visit" not in sessions:  # a sessions.csv written before C22
        return None
    named = _labelled(sessions)
    mixed = tug_or_stairs(named)  # decision C276: a TUG's / stairs' strides are no walk's
    left_out = [m for m in walk_strides_only if m in named and mixed.any()
                and pd.to_numeric(named.loc[mixed, m], errors="coerce").notna().any()]
    named.loc[mixed, left_out] = np.nan
    mixed_paths = set(named.loc[mixed, "path"].astype(str)) if left_out and "path" in named else set()
    named["visit_as_written"] = named["visit"]  # decision C82
    named["visit"] = named["visit"].map(canonical_visits(named["visit"], visit_map)[0])
    visits = visit_order(named["visit"])
    if len(visits) < 2:
        return None
    if by is not None:  # decision C174: the label as text, a sessions.csv without the column naming none
        named[by] = named[by].map(_as_text) if by in named else None
    measures = [m for m in metrics if m in sessions and pd.to_numeric(sessions[m], errors="coerce").notna().any()]
    base_of = _baselines(named)
    counts = pd.Series([b for b in base_of.values() if b is not None], dtype=object).value_counts()
    common = min(counts.index, key=lambda b: (-counts[b], visits.index(b))) if len(counts) else visits[0]
    baselines = set(base_of.values())
    later: dict[str, list[str]] = {}
    for subject, mine in named.groupby("subject"):
        if base_of[subject]:
            later.setdefault(base_of[subject], []).extend(v for v in mine["visit"] if v not in baselines)
    subject_of = dict(zip(named["path"].astype(str), named["subject"], strict=True))
    twins = _twins(named)
    rows = []
    for subject in visit_order(named["subject"]):
        everything = named[named["subject"] == subject]
        base = base_of[subject] or common
        own = (later[base] or later[common]) + [v for v in everything["visit"] if v not in baselines]
        for label, visit in ((label, visit) for label in _labels_of(everything, by) for visit in visit_order(own)):
            # decision C174: with ``by``, the visits the subject's sessions pair (C28) compared within each test
            mine = everything if by is None else everything[
                everything[by].isna() if label is None else everything[by] == label]
            b_status, b_reason, b_row = _side(mine[mine["visit"] == base], base, measures)
            v_status, v_reason, v_row = _side(mine[mine["visit"] == visit], visit, measures)
            status = next(s for s in ("missing", "failed", "pipelines", "ok") if s in (b_status, v_status))
            reasons = [r for r in (b_reason, v_reason) if r]
            problem = _pair_problem(b_row, v_row, subject_of, twins) if status == "ok" else None
            if problem:
                status = problem[0]
                reasons.append(problem[1])
            elif status == "ok":  # decision C20's copy; C84: of each trial averaged
                reasons += [f"{p} holds the same recording as {d} (duplicate_of)" for p, d in _copies(b_row, v_row)]
            out_paths = {p for r in (b_row, v_row) if r is not None for p in str(r["path"]).split("; ")}
            gone = [m for m in left_out if m in measures] if out_paths & mixed_paths else []
            if gone:  # decision C276
                reasons.append(f"{', '.join(gone)} of a TUG / stairs session left out: its strides are the turns' "
                               "and the stairs', not the walk's (C276)")
            apart = {m: walkways_differ(mine[mine["visit"] == base], mine[mine["visit"] == visit], m)
                     for m in measures} if status == "ok" else {}  # decision C211: one walkway at both visits
            reasons += [WALKWAY_REASON.format(measure=m, why=walkway_why(w), walkways=w,
                                              ref=decision_ref("C211", topic="cohort")) for m, w in apart.items() if w]
            row = {"subject": subject, "group": everything["group"].astype(str).iloc[0], "baseline_visit": base,
                   "visit": visit, "status": status, "reason": "; ".join(reasons) or None,
                   **{f"{k}visit_as_written": _names(mine.loc[mine["visit"] == w, "visit_as_written"])
                      for k, w in (("baseline_", base), ("", visit))},
                   **{f"{k}n_trials": None if r is None else r["n_trials"] for k, r in (("baseline_", b_row),
                                                                                         ("", v_row))},
                   "baseline_path": None if b_row is None else b_row["path"],
                   "path": None if v_row is None else v_row["path"],
                   **{f"{k}duplicate_of": None if r is None else "; ".join(twins.get(str(r["path"]), [])) or None
                      for k, r in (("baseline_", b_row), ("", v_row))}}
            for m in measures:
                both = status == "ok" and not apart.get(m)  # decision C211: not across walkways
                b = pd.to_numeric(b_row[m], errors="coerce") if both else np.nan
                v = pd.to_numeric(v_row[m], errors="coerce") if both else np.nan
                row[f"{m}_baseline"] = b
                row[f"{m}_change"] = v - b  # later visit minus baseline (decision C22)
                if "change_pct" in change_kinds(m):  # decision C101: none of a percent error
                    row[f"{m}_change_pct"] = pct_change(b, v)  # decision C81
                se_col = standard_error_column(m)
                if se_col is not None and se_col in sessions:  # decision C271: the change's standard error
                    row.update(change_uncertainty(m, v - b, [pair_se(mine[mine["visit"] == w], r, se_col)
                                                             for w, r in ((base, b_row), (visit, v_row))]))
            rows.append({**row, **({by: label} if by else {})})
    columns = list(CHANGE_COLUMNS)
    if by:
        columns.insert(columns.index("visit") + 1, by)
    out = pd.DataFrame(rows).reindex(columns=[*columns, *(f"{m}_{k}" for m in measures for k in change_kinds(m)),
                                              *(c for m in measures if standard_error_column(m) in sessions
                                                for c in (f"{m}_change_se", f"{m}_change_uncertain"))])  # C271
    for c in ("baseline_n_trials", "n_trials"):
        out[c] = out[c].astype("Int64")
    return out


def standard_error_column(measure: str) -> str | None:
    """Decision C271: the sessions.csv column holding ``measure``'s standard error, None for a measure without one:
    the foot + lower-back step-time asymmetry's (L490, L677, L686)."""
    return "step_time_asymmetry_se_points" if measure == "step_time_asymmetry_pct" else None


def pair_se(rows, row, column: str) -> float:
    """Decision C271: the standard error (``column``) of one visit's value in changes.csv: the session's own, or of
    its trials' mean (C83) sqrt(sum se^2) / n over the tracked trials with one; NaN without."""
    import numpy as np
    import pandas as pd

    if row is None:
        return float("nan")
    if column in row.index:
        return float(pd.to_numeric(row[column], errors="coerce"))
    se = pd.to_numeric(rows.loc[rows["status"] == "ok", column], errors="coerce").dropna() if column in rows else []
    return float(np.sqrt(np.sum(np.square(se))) / len(se)) if len(se) else float("nan")


def change_uncertainty(measure: str, change: float, ses) -> dict:
    """Decision C271: changes.csv's ``<measure>_change_se`` (the two visits' standard errors in quadrature; NaN
    without both) and ``<measure>_change_uncertain`` (:func:`pdrlearn.track.labelled_asymmetry.asymmetry_uncertain`
    of |change| and that standard error: within noise, under 1.96 of it, or it over 3 points; empty without)."""
    import numpy as np

    from pdrlearn.track.labelled_asymmetry import asymmetry_uncertain

    se = float(np.hypot(*ses)) if all(np.isfinite(ses)) else float("nan")
    flag = asymmetry_uncertain(abs(change), se) if np.isfinite(change) else None
    return {f"{measure}_change_se": se, f"{measure}_change_uncertain": flag}


#: each measure's columns in changes.csv, in order (decisions C22, C81; C101: a percent error has no ``change_pct``)
CHANGE_KINDS = ("baseline", "change", "change_pct")
#: decision C101: a measure that is itself a percent error against a reference (``distance_error_pct``, signed;
#: ``stride_length_mae_pct``, unsigned): its change is in percentage points; a percent change of it (a ratio of a
#: ratio, near 0 for a good track: +7746 % in trial T4) is no outcome
ERROR_PCT = re.compile(r"(?:error|mae)\w*_pct$")


def change_kinds(measure: str) -> tuple[str, ...]:
    """changes.csv's columns of ``measure`` (:data:`CHANGE_KINDS`), without ``change_pct`` for a percent error
    (:data:`ERROR_PCT`, decision C101: its absolute change is kept)."""
    return CHANGE_KINDS[:2] if ERROR_PCT.search(measure) else CHANGE_KINDS


def pct_change(baseline, later):
    """Decision C81: 100 x (later - baseline) / |baseline|, the percent change - the dual-task cost when the visits
    are the single and the dual task (session 34 trial T1, finding F5: DTC = (dual - single) / single x 100, a
    positive single-task value); NaN when the baseline is 0 or missing. C81 amended (review R2): over |baseline|, so a
    negative measure (``final_x_m``) that rises has a positive change; floats or arrays (a float for floats)."""
    import numpy as np

    b, v = np.asarray(baseline, dtype=float), np.asarray(later, dtype=float)
    out = np.full(np.broadcast(b, v).shape, np.nan)
    # C81 amended (review R2): a rise of a negative measure is a positive change; np.divide's where: no 1 / 0
    np.divide(100.0 * (v - b), np.abs(b), out=out, where=b != 0)
    return float(out) if out.ndim == 0 else out


def _lookalike(subject: str) -> str:
    """A subject id as a typo would not change it (C33): lower case, no separators, ``l`` / ``i`` as ``1``, ``o`` as
    ``0`` (``S7l8`` and ``s718`` are ``S718``'s)."""
    return re.sub(r"[\W_]", "", subject.lower()).translate(str.maketrans("lio", "110"))


def label_warnings(sessions, visit_map: dict[str, str] | None = None) -> list[str]:
    """What track-all warns about the subjects and visits of sessions.csv, one line each: visit names spelled
    differently taken as one visit (C28), a subject id in more than one group (C32: one person, or site-local ids
    that collide?), and subjects seen at one visit whose id looks like another subject's (C33: a typo?)."""
    named = _labelled(sessions)
    if named.empty:
        return []
    names, merged = canonical_visits(named["visit"], visit_map)
    out = [w for w in (merged, _naming_warning(named.assign(visit=named["visit"].map(names)))) if w]
    groups = named.groupby("subject")["group"].agg(lambda g: sorted(set(map(str, g))))
    spans = [f"{s!r} ({', '.join(g)})" for s, g in groups.items() if len(g) > 1]
    if spans:
        out.append(f"subject id {'; '.join(spans[:5])}{' and more' if len(spans) > 5 else ''} has sessions in more "
                   "than one group: paired as one person; if ids are per site, name the site in meta.json "
                   '("subject": {"site": "A", "id": "001"}) (decision C32)')
    n_visits = named.groupby("subject")["visit"].nunique()
    by_look: dict[str, list[str]] = {}
    for s in n_visits.index:
        by_look.setdefault(_lookalike(s), []).append(s)
    alike = [f"{s!r} like {', '.join(repr(o) for o in by_look[_lookalike(s)] if o != s)}" for s in
             visit_order(n_visits.index) if n_visits[s] == 1 and len(by_look[_lookalike(s)]) > 1]
    if alike:
        out.append(f"subject ids seen at one visit look like another subject's: {'; '.join(alike)}: a typo in "
                   "meta.json's subject? (decision C33)")
    return out


def change_measures(changes) -> list[str]:
    """The measures of a changes.csv, in its order: those with a ``<m>_change`` column (decisions C22, C81)."""
    return [c[:-len("_change")] for c in changes.columns if c.endswith("_change")]  # "_change_pct": its percent


def change_summary(changes, metrics=None, by: str | None = None):
    """changes_summary.csv from changes.csv (decision C23): one row per later visit and baseline (in order; subjects
    whose baselines differ, C28, are never pooled) and measure with
    ``n_subjects`` (subjects with a change: both visits tracked and the measure present at both), ``mean_change``,
    ``sd_change`` (n - 1) and ``ci95_low`` / ``ci95_high``, the paired 95 % t-interval of the mean change (the
    one-sample interval of the differences, :func:`pdrlearn.cohort.t_interval`; empty under two subjects), and
    ``n_not_paired`` / ``not_paired``: the subjects of that visit whose row is not ``ok`` (``;``-separated). Decision
    C81: ``mean_pct_change``, ``sd_pct_change``, ``pct_ci95_low`` / ``pct_ci95_high``, the same of the subjects'
    percent changes (the mean dual-task cost with its interval). ``metrics``: default changes.csv's measures.
    ``by``: changes.csv's label column (decision C174, ``change_table(by=)``): the rows per visit, baseline and value
    (natural order; a subject's Test5 change never averaged with its Test11 change), the column after
    ``baseline_visit``."""
    import pandas as pd

    metrics = change_measures(changes) if metrics is None else metrics
    rows = []
    order = visit_order([*changes["visit"], *changes["baseline_visit"]])
    pairs = dict.fromkeys(zip(changes["visit"], changes["baseline_visit"], strict=True))  # decision C28
    for visit, base in sorted(pairs, key=lambda vb: (order.index(vb[0]), order.index(vb[1]))):
        both = changes[(changes["visit"] == visit) & (changes["baseline_visit"] == base)]
        for label in _labels_of(both, by):  # decision C174: each test's changes on their own
            at = both if by is None else both[both[by].isna()] if label is None else both[both[by] == label]
            rows += _summary_rows(at, metrics, {"visit": visit, "baseline_visit": base,
                                                **({by: label} if by else {})})
    columns = list(SUMMARY_COLUMNS)
    if by:
        columns.insert(columns.index("baseline_visit") + 1, by)
    out = pd.DataFrame(rows, columns=columns)  # B327: its columns without a measure too
    out["n_uncertain"] = pd.to_numeric(out["n_uncertain"], errors="coerce").astype("Int64")  # C271: a count
    return out


def _summary_rows(at, metrics, keys: dict) -> list[dict]:
    """changes_summary.csv's rows (one per measure, each starting with ``keys``) of changes.csv's rows ``at``, one
    visit and baseline (and, decision C174, one test): :func:`change_summary`'s statistics."""
    import pandas as pd

    rows = []
    unpaired = at[at["status"] != "ok"]["subject"].astype(str).tolist()
    for m in metrics:
        if f"{m}_change" not in at:
            continue
        row = {**keys, "measure": m}
        for kind, name in (("change", "change"), ("change_pct", "pct_change")):  # decision C81: and the percent
            if f"{m}_{kind}" not in at:
                continue
            d = pd.to_numeric(at[f"{m}_{kind}"], errors="coerce").dropna()
            mean, sd = (d.mean(), d.std()) if len(d) else (float("nan"), float("nan"))
            low, high = t_interval(mean, sd, len(d))
            pre = "" if kind == "change" else "pct_"
            row.update({"n_subjects" if kind == "change" else "n_pct_subjects": len(d)})  # C85: both counts
            row.update({f"mean_{name}": mean, f"sd_{name}": sd, f"{pre}ci95_low": float(low),
                        f"{pre}ci95_high": float(high)})
        flags = at.loc[pd.to_numeric(at[f"{m}_change"], errors="coerce").notna(), f"{m}_change_uncertain"] \
            if f"{m}_change_uncertain" in at else None  # decision C271: the subjects' changes within their noise
        rows.append({**row, "n_not_paired": len(unpaired), "not_paired": "; ".join(unpaired) or None,
                     "n_uncertain": None if flags is None else int((flags == True).sum())})  # noqa: E712 (object)
    return rows


#: changes_summary.csv's columns (decisions C23, C81; C85: ``n_pct_subjects``, the subjects of the percent change)
SUMMARY_COLUMNS = ("visit", "baseline_visit", "measure", "n_subjects", "mean_change", "sd_change", "ci95_low",
                   "ci95_high", "n_pct_subjects", "mean_pct_change", "sd_pct_change", "pct_ci95_low", "pct_ci95_high",
                   "n_not_paired", "not_paired", "n_uncertain")  # C271: n_uncertain


def uncertain_note(n_uncertain, n_subjects) -> str:
    """Decision C271: what the printed change of a measure with a standard error adds when some subjects' changes
    are within their noise (changes.csv ``<measure>_change_uncertain``): ", k of n uncertain (C271)"; "" otherwise."""
    import pandas as pd

    if pd.isna(n_uncertain) or not int(n_uncertain):
        return ""
    return f", {int(n_uncertain)} of {int(n_subjects)} uncertain ({decision_ref('C271', topic='cohort')})"


def changes_text(summary):
    """changes_summary.csv as track-all prints it and a batch report shows it (decision C23): per later visit and
    measure the subjects paired, ``mean change [low, high]`` (the paired 95 % t-interval), the same of the percent
    changes with the subjects it covers (C81, C85: ``n % change``, fewer when a baseline is 0) and the subjects not
    paired; a summary per test (decision C174) shows its ``test`` after the visit."""
    import pandas as pd

    from pdrlearn.cohort import plain_number

    def cell(mean, low, high) -> str:  # decision C101: no scientific notation
        if pd.isna(mean):
            return ""
        return plain_number(mean, sign=True) + ("" if pd.isna(low) else
                                                f" [{plain_number(low)}, {plain_number(high)}]")

    split = [c for c in summary.columns if c not in SUMMARY_COLUMNS]  # decision C174: change_summary's ``by``
    nan = pd.Series(float("nan"), index=summary.index)
    pct = [summary.get(c, nan) for c in ("mean_pct_change", "pct_ci95_low", "pct_ci95_high")]  # decision C81
    return pd.DataFrame({"visit": [f"{v} - {b}" for v, b in zip(summary["visit"], summary["baseline_visit"],
                                                                 strict=True)],
                         **{c: summary[c].fillna("") for c in split},
                         "measure": summary["measure"], "n_subjects": summary["n_subjects"],
                         "mean change [95 % CI]": [cell(*r) + uncertain_note(u, n) for *r, u, n in zip(
                             summary["mean_change"], summary["ci95_low"], summary["ci95_high"],
                             summary.get("n_uncertain", nan), summary["n_subjects"], strict=True)],
                         "mean % change [95 % CI]": [cell(*r) for r in zip(*pct, strict=True)],
                         "n % change": ["" if pd.isna(n) else int(n) for n in  # C85: a zero baseline: 0
                                        summary.get("n_pct_subjects", nan)],  # C101: a percent error none at all
                         "not paired": summary["not_paired"].fillna("")})
