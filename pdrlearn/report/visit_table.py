"""The clinical page's visit x measure table, its choice of each visit's walking session and its technical notes
(decisions C273-C276, docs/decisions/cohort.md; trial s53t1 findings F2-F4): a physiotherapist's page gave every
track warning's text under every session (E153 27 times on one page) and no table compared the visits.

A visit's walking measures (speed, cadence, stride, stance, asymmetry) come from its walking sessions
(:func:`walking_rows`): a TUG's strides are turn and closing strides of two 3 m legs, a stairs session's stair and
landing strides (C276); its TUG and stair times from the sessions that have them."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pandas as pd


def session_meta(session: str | Path | None) -> dict:
    """The session folder's meta.json as a dict ({} without one or when it cannot be read)."""
    path = Path(session) / "meta.json" if session else None
    if path is None or not path.is_file():
        return {}
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}


def session_test(summary: dict) -> str | None:
    """Decision C274: the tracked session's meta.json ``test`` (summary.json ``input_dir``), None without one."""
    test = session_meta(summary.get("input_dir")).get("test")
    return str(test) if test not in (None, "") else None


def looks_like_walk_test(test: str | None) -> bool:
    """Decision C274: whether a meta.json ``test`` names a walk test ("10mwt", "10 m walk", "gait", "T25FW", ...)."""
    return bool(test) and re.search(r"walk|mwt|10 ?m|gait|t25", str(test), re.IGNORECASE) is not None


def tug_or_stairs_session(summary: dict) -> bool:
    """Decision C276: whether a track is a TUG or stairs session (:func:`pdrlearn.visits.tug_or_stairs`)."""
    from pdrlearn.visits import tug_or_stairs

    keys = ("tug_time_s", "tug_trials_median_s", "n_stair_strides")
    return bool(tug_or_stairs(pd.DataFrame([{k: summary.get(k) for k in keys}])).iloc[0])


def names_another_test(test: str | None) -> bool:
    """Decision C274: whether a meta.json ``test`` names a test that is no walk test (a TUG, stairs, sit-to-stand,
    chair or balance test); an unknown label (mobgap's "Test5") is not taken for one."""
    return bool(test) and not looks_like_walk_test(test) and re.search(
        r"tug|up.?and.?go|stair|sit|sts|chair|balance", str(test), re.IGNORECASE) is not None


def walk_not_timed_said(summary: dict) -> bool:
    """Decision C274: whether a session's clinical block says its declared 10 m walk was not timed (C194): not for a
    session that timed a TUG, nor one whose meta.json ``test`` names another test (:func:`names_another_test`)."""
    if summary.get("tug_time_s") is not None or summary.get("n_tug_trials"):
        return False
    return not names_another_test(session_test(summary))


def walking_rows(rows: list) -> list:
    """Decision C276: of one visit's track rows, those whose walking measures stand for the visit: the sessions with
    a timed 10 m walk, else those whose ``test`` looks like a walk test, else those that are neither a TUG nor a
    stairs session; [] when none is."""
    for pick in (lambda s: s.get("ten_m_walk_speed_mps") is not None,
                 lambda s: looks_like_walk_test(session_test(s)),
                 lambda s: not tug_or_stairs_session(s)):
        chosen = [r for r in rows if pick(r[3])]
        if chosen:
            return chosen
    return []


def _visit(row) -> str | None:
    v = row[3].get("visit")
    return None if v in (None, "") else str(v)


def _mean(values) -> float | None:
    got = pd.to_numeric(pd.Series(list(values), dtype=object), errors="coerce").dropna()
    return float(got.mean()) if len(got) else None


def visit_values(rows: list) -> dict[str, float | None]:
    """Decision C273: one visit's table values from its track ``rows``: the walking measures the mean over
    :func:`walking_rows`, the TUG's over the sessions timing one, the stairs' up / down times
    (:func:`pdrlearn.report.stairs_asymmetry.flight_times`) over the sessions with flights (C83's mean of trials)."""
    from pdrlearn.report.stairs_asymmetry import flight_times

    walk = [r[3] for r in walking_rows(rows)]
    out = {m: _mean(s.get(m) for s in walk) for m in ("ten_m_walk_speed_mps", "gait_speed_mps", "median_cadence_spm",
                                                       "median_stride_length_m", "median_stance_pct",
                                                       "step_time_asymmetry_pct")}
    out["tug_time_s"] = _mean(r[3].get("tug_time_s") for r in rows)
    times = [flight_times(r[1]) for r in rows if r[1] is not None]
    for way in ("up", "down"):
        out[f"stairs_{way}_time_s"] = _mean(t.get(way) for t in times)
    return out


def visit_table_lines(rows: list) -> list[str]:
    """Decision C273: "Summary by visit": a markdown table, one row per visit of the patient's track rows (C221's
    order), a column per measure any visit has; [] when no track names a visit or no visit has a measure."""
    from pdrlearn.visits import visit_order

    tracks = [r for r in rows if r[0] == "track" and _visit(r)]
    visits = visit_order(dict.fromkeys(_visit(r) for r in tracks))
    if not visits:
        return []
    # (measure, header, decimals): the visit's walking session's measures, then the TUG's and the stairs'
    columns = (("ten_m_walk_speed_mps", "10 m walk (m/s)", 2), ("gait_speed_mps", "gait speed (m/s)", 2),
               ("median_cadence_spm", "cadence (steps/min)", 0), ("median_stride_length_m", "stride (m)", 2),
               ("median_stance_pct", "stance (%)", 1), ("step_time_asymmetry_pct", "step-time asymmetry (%)", 1),
               ("tug_time_s", "TUG (s)", 1), ("stairs_up_time_s", "stairs up (s)", 1),
               ("stairs_down_time_s", "stairs down (s)", 1))
    values = {v: visit_values([r for r in tracks if _visit(r) == v]) for v in visits}
    shown = [c for c in columns if any(values[v][c[0]] is not None for v in visits)]
    if not shown:
        return []
    lines = ["Summary by visit (walking measures from each visit's walk test session, not its TUG or stairs; TUG and "
             "stairs times from their own sessions; the sessions below give each one's unit and caveats; C273, C276):",
             "", "| visit | " + " | ".join(c[1] for c in shown) + " |", "|---" * (len(shown) + 1) + "|"]
    for v in visits:
        cells = ["-" if values[v][m] is None else f"{values[v][m]:.{k}f}" for m, _, k in shown]
        lines.append(f"| {v} | " + " | ".join(cells) + " |")
    return lines


def warnings_pointer(summary: dict) -> str | None:
    """Decision C273: a session block's one warnings line: their count and codes, pointing to the page's technical
    notes (:func:`technical_notes`); None without a warning."""
    info = summary.get("info") or {}
    warnings, codes = info.get("warnings") or [], info.get("warning_codes") or []
    if not warnings:
        return None
    named = f" ({', '.join(dict.fromkeys(c for c in codes if c))})" if any(codes) else ""
    return (f"- Track warnings: {len(warnings)}{named}: each explained once under \"Technical notes\" at the end of "
            "this page (C273)")


def technical_notes(rows: list) -> list[str]:
    """Decision C273: the page's "Technical notes" appendix: each distinct warning of the patient's tracks (by its
    code; one without a code by its text) once, with the number of sessions giving it and the first one's text
    (C209's words); [] without a warning."""
    seen: dict[str, list] = {}
    for r in rows:
        if r[0] != "track":
            continue
        info = r[3].get("info") or {}
        warnings, codes = info.get("warnings") or [], info.get("warning_codes") or []
        mine = {}
        for w, c in zip(warnings, list(codes) + [None] * (len(warnings) - len(codes)), strict=False):
            mine.setdefault(c or " ".join(str(w).split()), (c, " ".join(str(w).split())))
        for key, (code, text) in mine.items():
            seen.setdefault(key, [code, text, []])[2].append(r[2])
    if not seen:
        return []
    n = len([r for r in rows if r[0] == "track"])
    lines = ["Technical notes (for the analyst, not clinical findings; each warning once, the first session's text; "
             "every session's own numbers in report.md's Warnings and its summary.json; C273):"]
    for code, text, where in seen.values():
        lines.append(f"- {f'{code}: ' if code else ''}{len(where)} of {n} sessions (first {where[0]}): {text}")
    return lines


def batch_metrics(rows: list) -> list[str]:
    """Decision C275: the measures of ``track-all --metrics`` (run.json ``options.metrics`` of the nearest track-all
    output folder above the patient's tracks), in their order; [] without one."""
    for r in rows:
        if r[0] != "track" or r[1] is None:
            continue
        for up in Path(r[1]).parents:
            run = up / "run.json"
            if not run.is_file():
                continue
            try:
                data = json.loads(run.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                return []
            options = data.get("options") if isinstance(data, dict) and data.get("command") == "track-all" else None
            if not isinstance(options, dict):
                continue
            metrics = options.get("metrics")
            names = metrics.split(",") if isinstance(metrics, str) else metrics if isinstance(metrics, list) else []
            return [str(m).strip() for m in names if str(m).strip()]
    return []


def change_frame_extras(rows: list, skip=()) -> tuple[list[dict], dict[str, tuple[str, str, int]]]:
    """Decision C275: the extra columns of clinical.md's change line, one dict per track row of ``rows`` (the rows
    naming a subject and a visit, in order), and ``{measure: (name, unit, decimals)}``: the stairs' up and down times
    (:func:`pdrlearn.report.stairs_asymmetry.flight_times`) and each :func:`batch_metrics` measure not in ``skip``,
    the latter from each visit's walking sessions only (:func:`walking_rows`, C276)."""
    from pdrlearn.report.stairs_asymmetry import flight_times

    tracks = [r for r in rows if r[0] == "track" and r[3].get("subject") and _visit(r)]
    walking = {id(r) for v in dict.fromkeys(map(_visit, tracks)) for r in walking_rows(
        [t for t in tracks if _visit(t) == v])}
    extras = [m for m in batch_metrics(tracks) if m not in skip and any(
        isinstance(r[3].get(m), int | float) and not isinstance(r[3].get(m), bool) for r in tracks)]
    names = {"stairs_up_time_s": ("stairs up", "s", 1), "stairs_down_time_s": ("stairs down", "s", 1),
             **{m: (f"{m} (walk session)", "%" if m.endswith("_pct") else "", 2) for m in extras}}
    values = []
    for r in tracks:
        times = flight_times(r[1]) if r[1] is not None else {}
        values.append({"stairs_up_time_s": times.get("up"), "stairs_down_time_s": times.get("down"),
                       **{m: r[3].get(m) if id(r) in walking else None for m in extras}})
    return values, names
