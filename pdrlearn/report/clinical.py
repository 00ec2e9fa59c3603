"""A short per-patient clinical summary of track outputs (decision W420, docs/decisions/waist.md): ``pdrlearn report
SOURCE --out OUT --clinical`` writes ``OUT/clinical.md`` beside report.md and (decision C229) each patient's own
block as ``OUT/clinical/<patient>.md`` (:func:`clinical_texts`, :func:`page_names`).

One block per patient (summary.json ``subject``, else the folder's path under SOURCE, W426): the patient and session
ids, the recording date (summary.json ``recording_start``, else the tracked session's meta.json via run.json, L298's
rule), then one line per clinical test a track measured - the corridor walk test (6MWT), the TUG with its phases,
steps and turn time, the 10 m walk, the gait speed and cadence - each naming the unit it comes from. Nothing
research-only: no errors against a reference, no model or validation warnings, no per-stride tables.

Decision W438: the two feet of one walk are one block. A ``pdrlearn gait`` / ``gait-all`` output under SOURCE
(gait_summary.json, W437) gives the walk's asymmetry line - step time, stance time and step length left / right with
the symmetry index and the longer side - and its gait speed and cadence; the tracks of a left and a right foot session
of one folder (meta.json ``foot``) that no gait output pairs are one block whose line says how to get the asymmetry.
"""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.report.daily_living import daily_living_lines
from pdrlearn.report.spatiotemporal import gait_spatiotemporal_line, measured_leg, normalised_line, spatiotemporal_line
from pdrlearn.report.stairs_asymmetry import asymmetry_line, stairs_line
from pdrlearn.report.travel import travel_lines
from pdrlearn.report.visit_table import (
    change_frame_extras,
    session_meta,
    session_test,
    technical_notes,
    tug_or_stairs_session,
    visit_table_lines,
    walk_not_timed_said,
    warnings_pointer,
)
from pdrlearn.report.walking import walking_line
from pdrlearn.track.stair_lead import FLIGHT_WORDS, flight_line

#: decision W420: the body unit each pipeline's measures come from, as the summary names it
UNIT_NAMES = {"plasys": "foot unit", "waist-pll": "lower-back unit", "waist-pendulum": "lower-back unit"}
#: decision L95: the lowest speed (m/s) and cadence (steps/min) the pipelines are validated on; decision W446: an
#: uncalibrated lower-back gait speed under VALIDATED_MIN_MPS is not given (as L313 withholds its 10 m walk)
VALIDATED_MIN_MPS, VALIDATED_MIN_SPM = 0.5, 70.0


def _read(path: Path) -> dict:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise DataError(f"{path}: cannot read it as JSON ({type(exc).__name__}); re-run the track that wrote it "
                        "(decision W420)") from None
    if not isinstance(data, dict):  # the line plain `report` gives (report/build.py)
        raise DataError(f"{path}: must hold a JSON object, not {type(data).__name__}; regenerate it")
    return data


def recording_date(summary: dict, folder: Path) -> str | None:
    """Decision W420: the recording's date (YYYY-MM-DD): summary.json ``recording_start`` (L298), else the tracked
    session's meta.json (run.json ``session``) read by L298's :func:`~pdrlearn.track.clock.recording_start`."""
    text = summary.get("recording_start")
    if isinstance(text, str) and text:
        return text[:10]
    run = folder / "run.json"
    session = _read(run).get("session") if run.is_file() else None
    return session_date(Path(session)) if session else None


def session_date(session: Path) -> str | None:
    """Decision W420 (W438: a gait pair's left session too): the date (YYYY-MM-DD) of a session folder's meta.json by
    L298's :func:`~pdrlearn.track.clock.recording_start`, None without one."""
    meta = Path(session) / "meta.json"
    if not meta.is_file():
        return None
    from pdrlearn.track.clock import recording_start

    try:
        start = recording_start(_read(meta), str(meta))
    except DataError:
        return None
    return None if start is None else start.date().isoformat()


def _s(v) -> str:
    return f"{v:.1f} s"


def tug_line(summary: dict, folder: Path) -> str | None:
    """Decision W420: the TUG's line - its time, phases, steps and turn time, each with its source unit (W419's
    tug_trials.csv ``steps_source`` / ``turns_source``); several trials: each trial's time and their median."""
    from pdrlearn.waist.tug_phases import PHASE_LABELS, TUG_PHASES

    path = folder / "tug_trials.csv"
    trials = pd.read_csv(path) if path.is_file() else None
    if summary.get("tug_time_s") is None:
        note = summary.get("tug_time_note")
        if isinstance(note, str) and "L648" in note:  # decision L648: a TUG with one transfer missed, said
            return f"- TUG: not timed ({note}; chair transfers: lower-back unit)"
        if not summary.get("n_tug_trials") or trials is None:
            return None
        times = ", ".join(_s(t) for t in trials["tug_time_s"])
        return (f"- TUG: {len(trials)} trials {times} (median {_s(summary['tug_trials_median_s'])}); chair transfers: "
                f"lower-back unit{_daily_tug(summary)}")
    phases = summary.get("tug_phases") or {}
    parts = [f"{PHASE_LABELS[p]} {_s(phases[p]['duration_s'])}" for p in TUG_PHASES if phases.get(p)]
    text = f"- TUG: {_s(summary['tug_time_s'])} ({', '.join(parts)})"
    if trials is not None and len(trials):
        row = trials.iloc[0]
        steps_from = row.get("steps_source", "waist")
        turns_from = row.get("turns_source", "waist")
        count = f"{int(row['n_steps'])} steps ({_unit(steps_from)}"
        count += ", turning steps not seen)" if steps_from == "waist" else ")"
        text += f"; {count}"
        if summary.get("tug_turn_s") is not None:
            text += f"; turn {_s(summary['tug_turn_s'])} ({_unit(turns_from)})"
    return text + f"; chair transfers: lower-back unit{_daily_tug(summary)}"


def _daily_tug(summary: dict) -> str:
    """Decision W445: the TUG line's caveat when the recording also holds chair-to-chair walks (daily life)."""
    n = summary.get("n_chair_walks")
    return (f"; found among {n} chair-to-chair walk(s) of daily life: not a supervised test (W445)" if n else "")


def _calibrated(summary: dict) -> bool:
    """Decision W446: whether a lower-back track's step length is the wearer's (``calibrate``'s PARAMS)."""
    return ((summary.get("info") or {}).get("params_source")) == "calibrated"


def gait_speed_line(summary: dict, unit: str) -> str | None:
    """Decisions W420, W446: the gait speed and cadence line. A lower-back speed says whether it is calibrated; an
    uncalibrated one under :data:`VALIDATED_MIN_MPS` is not given (it read +57 % for trial T2's 0.21 m/s walker);
    under L95's validated speed or cadence the line says so."""
    speed, cad = summary.get("gait_speed_mps"), summary.get("median_cadence_spm")
    if speed is None:
        return None
    cadence = f", cadence {cad:.0f} steps/min" if cad is not None else ""
    slow_cad = cad is not None and cad < VALIDATED_MIN_SPM
    if unit != "lower-back unit":
        flags = [f"below the validated {VALIDATED_MIN_SPM:g} steps/min (L95)"] if slow_cad else []
        return f"- Gait speed {speed:.2f} m/s{cadence} ({'; '.join([unit, *flags])})"
    if not _calibrated(summary) and speed < VALIDATED_MIN_MPS:  # decision W446
        flags = [unit] + ([f"cadence below the validated {VALIDATED_MIN_SPM:g} steps/min (L95)"] if slow_cad else [])
        given = f"; cadence {cad:.0f} steps/min" if cad is not None else ""
        return (f"- Gait speed not given: an uncalibrated lower-back reading under the validated "
                f"{VALIDATED_MIN_MPS:g} m/s (L95) is not reliable; calibrate with a 10 m walk at the person's own pace "
                f"(pdrlearn calibrate, W446){given} ({'; '.join(flags)})")
    flags = [unit, "calibrated" if _calibrated(summary) else
             "uncalibrated: step length from body height, no per-user calibration (W169)"]
    if summary.get("walk_test_distance_m") is not None:  # decision L650: not the walk test's speed
        flags.append("all the recording's walking, from step lengths; the walk test's own speed is its line's (L650)")
    if speed < VALIDATED_MIN_MPS or slow_cad:
        flags.append(f"slower than the validated {VALIDATED_MIN_MPS:g} m/s / {VALIDATED_MIN_SPM:g} steps/min (L95)")
    if summary.get("step_count_withheld"):  # decision C247: summed from contacts that are no steps
        from pdrlearn.waist.plausibility import CONTACTS_FLAG

        flags.append(CONTACTS_FLAG)
    scaled = summary.get("gait_speed_corridor_mps")
    if scaled is not None:  # decision W562: the corridor's laps give the step lengths' scale
        return (f"- Gait speed {scaled:.2f} m/s on the corridor's scale (the step lengths x "
                f"{summary['walk_test_scale']:.3f}, the corridor / its median lap less the cone arc; W562; from "
                f"the step lengths alone {speed:.2f} m/s){cadence} ({'; '.join(flags)})")
    return f"- Gait speed {speed:.2f} m/s{cadence} ({'; '.join(flags)})"


def walk_test_pace_line(summary: dict, folder: Path | None = None) -> str | None:
    """Decisions C177, L650: the corridor walk test's minutes and pace under its line - the distance per minute, the
    fatigue index (last / first minute) and the test's own mean speed (its distance from the corridor's laps / its
    duration), said to be the test's, not the gait speed line's (whole recording, step lengths); decision C230: the
    steps in each full minute of the test from ``folder``'s steps.csv (:func:`walk_test_steps_per_minute`); None
    without a walk test."""
    from pdrlearn.track.corridor import walk_test_speed

    speed = walk_test_speed(summary)
    if speed is None:
        return None
    parts = [f"test speed {speed:.2f} m/s (the test's distance from the corridor's laps / its duration; L650)"]
    minutes = summary.get("walk_test_distance_per_minute_m")
    if isinstance(minutes, list) and minutes:
        parts.append("per minute " + " / ".join(f"{m:.0f}" for m in minutes) + " m")
    counts = walk_test_steps_per_minute(summary, folder) if folder is not None else None
    missed = summary.get("turn_steps_missed")  # decision C239: None (W331 could not judge) is not 0
    if counts and not minute_steps_given(summary.get("pipeline") in LOWER_BACK_PIPELINES, missed):  # decision C232
        parts.append(unchecked_turns_text(summary) if missed is None else
                     f"steps per minute not given: {int(missed)} turning steps on the spot are not detected on the "
                     "lower back (W331, C232)")
    elif counts:  # decision C230: the test's own minutes, rests included (not the walking cadence)
        parts.append("steps per minute " + " / ".join(str(c) for c in counts)
                     + " (steps counted in each full minute of the test, rests included; C230)")
    fatigue = summary.get("fatigue_index")
    if fatigue is not None:
        from pdrlearn.track.corridor import fatigue_rest_text

        rest = fatigue_rest_text(summary)  # decision C218: a rest, not slowing, drives it
        parts.append(f"fatigue index {fatigue:.2f} (last / first full minute)" + (f": {rest}" if rest else ""))
    return "  - " + "; ".join(parts)


#: decision C232: the pipelines whose steps are the lower back's contacts
LOWER_BACK_PIPELINES = tuple(k for k, v in UNIT_NAMES.items() if v == "lower-back unit")


def minute_steps_given(lower_back: bool, turn_steps_missed: int | None) -> bool:
    """Decision C232: whether the walk test's steps per minute (C230) are given: a foot unit's always, a lower
    back's only when no turning step on the spot went undetected (summary ``turn_steps_missed``, W331, is 0);
    decision C239: not when it is None (W331 could not judge the turns, or the summary has no such key)."""
    return not lower_back or (turn_steps_missed is not None and turn_steps_missed <= 0)


def unchecked_turns_text(summary: dict) -> str:
    """Decision C239: the pace line's part when a lower back's steps per minute are withheld because its turns on
    the spot could not be checked (summary ``turn_steps_missed`` None or absent), with why."""
    from pdrlearn.waist.turn_steps import MIN_INTERVALS, STEP_GAP_MAX_S

    why = (f"the walk has fewer than {MIN_INTERVALS} step gaps under {STEP_GAP_MAX_S:g} s to judge them by"
           if "turn_steps_missed" in summary else "the summary predates the check")
    # bare codes as the pace line's other parts: W420's clinical.md names no "decision" (no decision_ref path)
    return f"steps per minute not given: turns on the spot could not be checked ({why}; W331, C232, C239)"


def walk_test_steps_per_minute(summary: dict, folder: Path) -> list[int] | None:
    """Decision C230: the steps in each full minute of a timed walk test (``walk_test_start_s`` + 60 k; as many
    minutes as ``walk_test_distance_per_minute_m``, else the full minutes of ``walk_test_duration_s``) from
    ``folder``'s steps.csv (:func:`pdrlearn.track.corridor.steps_per_minute`); None without a timed test, without
    steps.csv or when it cannot be read (the line leaves the part out)."""
    from pdrlearn.io.plasys import read_table
    from pdrlearn.track.corridor import MINUTE_S, steps_per_minute

    start, dur = summary.get("walk_test_start_s"), summary.get("walk_test_duration_s")
    path = Path(folder) / "steps.csv"
    if start is None or dur is None or summary.get("walk_test_distance_m") is None or not path.is_file():
        return None
    minutes = summary.get("walk_test_distance_per_minute_m")
    n = len(minutes) if isinstance(minutes, list) and minutes else int(float(dur) // MINUTE_S)
    try:
        steps = read_table(path)
    except DataError:
        return None
    return steps_per_minute(steps, float(start), n) or None


def walk_test_rests_line(summary: dict) -> str | None:
    """Decision C217: clinical.md's "Rests during the test: N (durations, start times)" under a timed corridor
    walk test; None without a timed test."""
    from pdrlearn.track.corridor import rests_text

    text = rests_text(summary) if summary.get("walk_test_distance_m") is not None else None
    return f"  - {text}" if text else None


#: decision C177: clinical.md's change-from-baseline measures (visits.CLINICAL_MEASURES): (name, unit, digits)
CHANGE_LINE_MEASURES = {"walk_test_distance_m": ("walk test distance", "m", 0), "fatigue_index": ("fatigue index", "",
                        2), "tug_time_s": ("TUG", "s", 1), "ten_m_walk_speed_mps": ("10 m walk", "m/s", 2),
                        # decision C275: no T25FW is run, L387 times the walk's first 7.62 m from standing
                        "t25fw_time_s": ("T25FW (derived from the walk's first 7.62 m, L387)", "s", 1),
                        # decision W562: the lower back's gait speed on the corridor's scale (trial s49t1 F2)
                        "gait_speed_corridor_mps": ("gait speed (corridor's scale, W562)", "m/s", 2)}


def walk_names(tracks: list[dict], row) -> dict[str, str]:
    """Decision C211: ``{"ten_m_walk_speed_mps": name}`` of a changes row's two visits - the walkway's own name
    (:func:`pdrlearn.track.walk_test.walk_test_name`: "10 m walk", "7.62 m walk"), both visits' names joined by " /
    " when they differ; {} without a speed at either visit (``tracks``: the patient's summaries)."""
    from pdrlearn.track.walk_test import walk_test_name

    written = {v for k in ("baseline_visit_as_written", "visit_as_written") for v in str(row.get(k) or "").split("; ")}
    names = dict.fromkeys(walk_test_name(s) for s in tracks
                          if str(s["visit"]) in written and s.get("ten_m_walk_speed_mps") is not None)
    return {"ten_m_walk_speed_mps": " / ".join(names)} if names else {}


def walkway_reason(reason, measure: str) -> str | None:
    """Decision C211: the "walkways differ (10 m / 7.62 m timed, C211)" part of a changes row's ``reason`` for
    ``measure`` (or "mixed walkways within a visit (...)", review R2 F5); None without one."""
    from pdrlearn.visits import WALKWAY_REASON

    head = WALKWAY_REASON.split("{why}")[0].format(measure=measure)
    part = next((p for p in str(reason or "").split("; ") if p.startswith(head)), None)
    return None if part is None else part[len(head):]


def change_lines(rows: list) -> list[str]:
    """Decision C177: one patient's change-from-baseline lines, one per later visit: each clinical test measure
    (:data:`CHANGE_LINE_MEASURES`) both visits have, baseline -> later (change, percent change), paired by
    :func:`pdrlearn.visits.change_table`'s rules (C28 baseline, C83 a visit's trials averaged); none when the
    patient's tracks name fewer than two visits (summary.json ``visit``). Decision C211: the 10 m walk's speed is
    named by its walkway (:func:`walk_names`) and not compared across two walkways (said instead)."""
    from pdrlearn.track.walk_test import walkway_timed_m
    from pdrlearn.visits import change_table

    tracks = [r[3] for r in rows if r[0] == "track" and r[3].get("subject") and r[3].get("visit")]
    if len({str(s["visit"]) for s in tracks}) < 2:
        return []
    extra, named = change_frame_extras(rows, skip=CHANGE_LINE_MEASURES)  # decision C275: --metrics, stair times
    line_measures = {**CHANGE_LINE_MEASURES, **named}
    frame = pd.DataFrame([{"subject": str(r[3]["subject"]), "group": "", "visit": str(r[3]["visit"]), "path": r[2],
                           "status": "ok", "pipeline": r[3].get("pipeline"),
                           "ten_m_walk_timed_m": walkway_timed_m(r[3]),  # decision C211: the speed's walkway
                           **{m: r[3].get(m) for m in CHANGE_LINE_MEASURES}, **more}
                          for r, more in zip([r for r in rows if r[0] == "track" and r[3].get("subject")
                                              and r[3].get("visit")], extra, strict=True)])
    frame[list(line_measures)] = frame[list(line_measures)].apply(pd.to_numeric, errors="coerce")
    measures = [m for m in line_measures if frame[m].notna().any()]
    if not measures:
        return []
    changes = change_table(frame, metrics=measures)
    lines = []
    for _, row in (changes.iterrows() if changes is not None else iter(())):
        parts = []
        for m in measures:
            base, change = row.get(f"{m}_baseline"), row.get(f"{m}_change")
            apart = walkway_reason(row.get("reason"), m)  # decision C211: a speed on two walkways is not compared
            if apart:
                parts.append(f"{walk_names(tracks, row).get(m, line_measures[m][0])} not compared: {apart}")
            if pd.isna(base) or pd.isna(change):
                continue
            name, unit, k = line_measures[m]
            name = walk_names(tracks, row).get(m, name)  # decision C211: the walkway's own name
            parts.append(change_part(name, unit, k, base, change, row.get(f"{m}_change_pct"))
                         + measure_sources(frame, row, m))  # decision C252: which recordings
        if row["status"] != "ok":
            parts = [f"not paired ({row['status']}: {row['reason']})"]
        if parts:
            lines.append(f"- Change from baseline ({row['baseline_visit']} -> {row['visit']}, C177): "
                         + "; ".join(parts))
    return lines


def measure_sources(frame, row, measure: str) -> str:
    """Decision C252: " [from A, B; C252]" - the recordings (their folder names) a changes row's ``measure`` comes
    from at each visit (``frame``: the patient's sessions, ``path`` and ``visit`` as written), "A -> B" when the two
    visits' differ; "" when each visit has one session (nothing to tell apart)."""
    from pathlib import PurePath

    names = []
    for key in ("baseline_visit_as_written", "visit_as_written"):
        at = frame[frame["visit"].isin(str(row.get(key) or "").split("; "))]
        names.append((len(at), [PurePath(str(p)).name for p in at.loc[at[measure].notna(), "path"]]))
    if all(n <= 1 for n, _ in names):
        return ""
    (_, b), (_, v) = names
    return f" [from {', '.join(b)}" + ("" if b == v else f" -> {', '.join(v)}") + "; C252]"


def change_part(name: str, unit: str, k: int, base: float, change: float, pct=None) -> str:
    """Decision C177: one measure's "name base -> later unit (change unit, percent %)" of a change line (``k``
    decimals; no percent when ``pct`` is None or NaN; cohort C242: a symmetry index's change in points, no percent)."""
    u = f" {unit}" if unit else ""
    rel = f", {pct:+.0f} %" if pct is not None and not pd.isna(pct) else ""
    by = f"{change:+.{k}f} points" if unit == "%" else f"{change:+.{k}f}{u}"
    return f"{name} {base:.{k}f} -> {base + change:.{k}f}{u} ({by}{rel})"


#: cohort C242: the bilateral walk measures a patient's gait change line gives (name, unit, decimals; a symmetry
#: index's change in points): the trial's symmetry outcomes and the pace
GAIT_CHANGE_LINE_MEASURES = {"step_time_s_si_pct": ("step-time SI", "%", 1),
                             "stance_time_s_si_pct": ("stance SI", "%", 1), "swing_time_s_si_pct": ("swing SI", "%", 1),
                             "step_length_m_si_pct": ("step-length SI", "%", 1),
                             "gait_speed_mps": ("gait speed", "m/s", 2), "cadence_spm": ("cadence", "steps/min", 1)}


def gait_change_lines(rows: list) -> list[str]:
    """Cohort C242: one patient's bilateral gait change lines, one per later visit: the symmetry indices and pace
    (:data:`GAIT_CHANGE_LINE_MEASURES`) of its gait outputs, baseline -> later, paired as gait-all's
    gait_changes.csv (:func:`pdrlearn.track.gait_changes.gait_change_tables`: C22's baseline, C83 a visit's walks
    averaged); none under two visits."""
    from pdrlearn.track.gait_changes import gait_change_tables

    walks = [{"path": r[2], "subject": r[3].get("subject"), "visit": r[3].get("visit"), "walk": r[3].get("walk")}
             for r in rows if r[0] == "gait"]
    changes, _ = gait_change_tables(walks)
    lines = []
    for _, row in (changes.iterrows() if changes is not None else iter(())):
        parts = [change_part(*GAIT_CHANGE_LINE_MEASURES[m], row[f"{m}_baseline"], row[f"{m}_change"])
                 for m in GAIT_CHANGE_LINE_MEASURES if f"{m}_change" in row and not pd.isna(row[f"{m}_change"])]
        if row["status"] != "ok":
            parts = [f"not paired ({row['status']}: {row['reason']})"]
        n = f"; {int(row['baseline_n_trials'])} / {int(row['n_trials'])} walks averaged" if row["status"] == "ok" \
            and max(row["baseline_n_trials"], row["n_trials"]) > 1 else ""
        if parts:
            lines.append(f"- Gait change, both feet ({row['baseline_visit']} -> {row['visit']}{n}, C242): "
                         + "; ".join(parts))
    return lines


def warnings_line(summary: dict) -> str | None:
    """Decision W446: the track's warnings at the end of its block; decision C209 (trial T2 finding F4 of session 48:
    codes alone said nothing to a clinic): each warning below the count, indented, with its code and its text as the
    track gave it (what it means and what to do), one line per distinct warning."""
    info = summary.get("info") or {}
    warnings, codes = info.get("warnings") or [], info.get("warning_codes") or []
    if not warnings:
        return None
    named = f" ({', '.join(dict.fromkeys(c for c in codes if c))})" if any(codes) else ""
    pairs = zip(warnings, list(codes) + [None] * (len(warnings) - len(codes)), strict=False)
    items = [f"  - {f'{c}: ' if c else ''}{' '.join(str(w).split())}" for w, c in dict.fromkeys(pairs)]
    return "\n".join([f"- Track warnings: {len(warnings)}{named}, what each means and what to do (C209; also in "
                       "report.md and summary.json info.warnings):", *items])


def _unit(source: str) -> str:
    return "foot unit" if source == "foot" else "lower-back unit"


def walk_test_line(summary: dict, unit: str) -> str | None:
    """Decisions W420, L644: the corridor walk test's line, named by the duration asked (2MWT, 6MWT, "N-min walk
    test"; untimed: none), with the span it covers, a stop or a span shorter than asked, and (L643) a test not
    scored."""
    from pdrlearn.track.corridor import clock_text, walk_test_label

    corridor, protocol = summary.get("corridor_m"), summary.get("walk_test_protocol_s")
    name = f" ({walk_test_label(protocol)})" if protocol is not None else ""
    if summary.get("walk_test_distance_m") is None:
        note = summary.get("walk_test_note")
        return f"- Corridor walk test{name}: not scored: {note} ({unit})" if corridor and note else None
    laps = f", {summary['n_laps']} laps of {corridor:g} m" if corridor and summary.get("n_laps") is not None else ""
    dur = summary.get("walk_test_duration_s")
    span = f" in {dur / 60:.1f} min" if dur else ""
    short = protocol is not None and dur is not None and dur < protocol - 1e-6  # decision L644: shorter than asked
    if summary.get("walk_test_stopped_s") is not None:
        span = (f"; walking stopped after {clock_text(summary['walk_test_stopped_s'])} of "
                f"{clock_text(protocol or dur or 0.0)}" + (f" (recording ends at {clock_text(dur)})" if short else ""))
    elif short:
        span += f" (the recording ends {clock_text(dur)} after the start: incomplete {walk_test_label(protocol)})"
    extra = f"; {summary['walk_test_note']}" if summary.get("walk_test_note") else ""
    return f"- Corridor walk test{name}: {summary['walk_test_distance_m']:.0f} m{laps}{span}{extra} ({unit})"


def contact_line(summary: dict, unit: str) -> str | None:
    """Decision L756: the steady strides' toe-contact share (summary.json ``toe_contact_share_pct``), None without
    it (a lower-back track, under 5 steady strides)."""
    from pdrlearn.kernels.contact_type import FLAT_CONTACT_DEG

    pct, n = summary.get("toe_contact_share_pct"), summary.get("n_contact_strides")
    if pct is None:
        return None
    return (f"- Toe contact: {pct:.0f} % of {n} steady strides land on the forefoot (sole angle at contact below "
            f"-{FLAT_CONTACT_DEG:g} deg; steps.csv contact; {unit}; L756)")


def clinical_lines(summary: dict, folder: Path) -> list[str]:
    """Decision W420: one line per clinical test the track in ``folder`` (its ``summary``) measured."""
    unit = UNIT_NAMES.get(str(summary.get("pipeline")), str(summary.get("pipeline")))
    lines = []
    walk = walk_test_line(summary, unit)
    if walk:
        lines.append(walk)
        pace = walk_test_pace_line(summary, folder)  # decisions C177, L650, C230: minutes, fatigue, speed
        if pace:
            lines.append(pace)
        rests = walk_test_rests_line(summary)  # decision C217: the test's own rests
        if rests:
            lines.append(rests)
    tug = tug_line(summary, folder)
    if tug:
        lines.append(tug)
    if summary.get("ten_m_walk_speed_mps") is not None:  # L531: the walkway's timed metres and every trial (L524)
        from pdrlearn.track.walk_test import (
            free_walking_text,
            timed_stretch,
            trials_text,
            walk_test_name,
            walkway_zones,
        )

        trials = trials_text(summary)
        free = free_walking_text(summary)  # decision L679: an automatic walk test is no declared test
        name = walk_test_name(summary)  # decision C206: the walkway's own timed metres
        lines.append(f"- {name}: {summary['ten_m_walk_speed_mps']:.2f} m/s ({_s(summary['ten_m_walk_time_s'])} "
                     f"over {timed_stretch(*walkway_zones(summary))}"  # decision L536
                     f"{f'; {trials}' if trials else ''}; {unit}{f'; {free}' if free else ''})")
    else:
        from pdrlearn.track.walk_test import declared_refusal, walk_test_name

        refused = declared_refusal(summary)  # decision C194: a declared test not timed says so, before the speed
        if refused and walk_not_timed_said(summary):  # decision C274: not on a TUG's / another test's block; C206
            lines.append(f"- {walk_test_name(summary)}: not timed ({refused[0]}; {unit}): {refused[1]}")
    speed = gait_speed_line(summary, unit)
    if speed:
        lines.append(speed)
    own = unit != "lower-back unit" or _calibrated(summary)  # W446, C197: the wearer's step length, not the model's
    walking = walking_line(summary, folder, unit, distance_given=own
                           or (summary.get("gait_speed_mps") or 0.0) >= VALIDATED_MIN_MPS,  # W515, W446
                           uncalibrated=not own)  # decision C222
    if walking:
        lines.append(walking)
    if not tug_or_stairs_session(summary):  # decision C276: a TUG's / stairs' strides are not the walk's
        lines += [x for x in (spatiotemporal_line(summary, unit, stride_given=own),  # decisions C195, C197
                              _normalised(summary, unit, speed is not None and own, own)) if x]  # C196, C197
    lines += [x for x in (stairs_line(summary, folder, unit), asymmetry_line(summary, unit)) if x]  # decision C190
    contact = contact_line(summary, unit)  # decision L756: a toe walker's outcome
    if contact:
        lines.append(contact)
    lines += travel_lines(summary, folder, unit)  # decision L582: backward / side strides, turns
    lines += daily_living_lines(summary, folder)
    warnings = warnings_pointer(summary)  # decision C273: C209's texts once, in the page's technical notes
    if warnings:
        lines.append(warnings)
    return lines


def _normalised(summary: dict, unit: str, speed_given: bool, stride_given: bool) -> str | None:
    """Decisions C196, C197: a track's leg-length-normalised line: the gait speed when its line gives it (W446) and
    the median stride length, each only when ``*_given`` says it is a foot unit's or a calibrated lower back's (an
    uncalibrated one is the height model's step length, not the walker's)."""
    return normalised_line(summary.get("gait_speed_mps") if speed_given else None,
                           summary.get("median_stride_length_m")  # decision C247: no stride of W476's contacts
                           if stride_given and not summary.get("step_count_withheld") else None,
                           measured_leg(summary.get("leg_length_m"), summary.get("leg_length_source")), unit)


#: decision W438: the asymmetry line's measures (gait_summary.json ``walk`` ``X_left`` / ``X_right`` / ``X_si_pct``)
ASYMMETRY_MEASURES = (("step_time_s", "step time", "s"), ("stance_time_s", "stance", "s"),
                      ("step_length_m", "step length", "m"))


def _number(v) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None


def asymmetry_lines(walk: dict, stairs=None, leg_m: float | None = None, affected: str | None = None,
                    caveat: str | None = None) -> list[str]:
    """Decision W438: a gait_summary.json ``walk``'s clinical lines: left / right, the symmetry index and the longer
    side of step time, stance and step length (each read defensively: a measure gait left out is left out), then the
    gait speed and cadence (L539) when given, (C195) stride length, stance % and double support, (C196) with a
    measured ``leg_m`` the leg-length-normalised speed and stride length, then (L561) its ``stairs`` flights: pattern
    and leading foot. Cohort C245: with ``affected`` ("left" / "right", gait_summary.json affected_side) the longer
    side is worded affected / unaffected; cohort C244: the per-side median foot angles after the asymmetry.
    ``caveat`` (decision L762): gait_summary.json's ``reason``, the foot units' support bias said in words beside
    the stance and double support."""
    from pdrlearn.track.affected_side import side_word, sides_note

    parts = []
    for key, name, unit in ASYMMETRY_MEASURES:
        left, right = _number(walk.get(f"{key}_left")), _number(walk.get(f"{key}_right"))
        if left is None or right is None:
            continue
        si = _number(walk.get(f"{key}_si_pct"))
        side = "equal" if left == right else f"{side_word('left' if left > right else 'right', affected)} longer"
        parts.append(f"{name} L/R {left:.3f} / {right:.3f} {unit} "
                     + (f"(SI {si:.1f} %, {side})" if si is not None else f"({side}; no symmetry index)"))
    if parts and _number(walk.get("step_length_m_left")) is None and "step_length_scale_pct" in walk \
            and walk.get("step_length_scale_pct") is None:  # decisions L311, C208: say why, not just leave it out
        parts.append("step length not given (the walk is not one straight length from standing to standing, L311 / "
                     "C208: see gait_summary.json warnings)")
    basis = {"level": "level straight steps", "all": "all steps"}.get(str(walk.get("headline_steps")))
    lines = []
    if parts:
        key = sides_note(affected)  # cohort C245
        lines.append(f"- Asymmetry (both feet{f', {basis}' if basis else ''}{f'; {key}' if key else ''}): "
                     + "; ".join(parts))
        withheld = walk.get("si_withheld")
        if isinstance(withheld, str) and withheld:
            lines.append(f"  (symmetry indices withheld: {withheld})")
    else:
        lines.append("- Asymmetry: not measured (too few steps on a side)")
    angles = foot_angle_line(walk, affected)  # cohort C244
    if angles:
        lines.append(angles)
    from pdrlearn.track.affected_side import toe_clearance_text

    clearance = toe_clearance_text(walk, affected)
    if clearance:  # decision L795, cohort C260
        lines.append(f"- {clearance[0].upper()}{clearance[1:]}")
    speed, cad = _number(walk.get("gait_speed_mps")), _number(walk.get("cadence_spm"))
    if speed is not None:
        lines.append(f"- Gait speed {speed:.2f} m/s{f', cadence {cad:.0f} steps/min' if cad is not None else ''} "
                     "(both foot units)")
    spatio = gait_spatiotemporal_line(walk, caveat)  # decision C195; L762: the bias in words
    if spatio:
        lines.append(spatio)
    left, right = _number(walk.get("stride_length_m_left")), _number(walk.get("stride_length_m_right"))
    stride = (left + right) / 2.0 if left is not None and right is not None else None
    normal = normalised_line(speed, stride, leg_m, "both foot units")  # decision C196
    if normal:
        lines.append(normal)
    flights = [f for f in stairs if isinstance(f, dict) and f.get("kind") in FLIGHT_WORDS] \
        if isinstance(stairs, list) else []
    if flights:  # decision L561
        lines.append("- Stairs (both foot units, L561): " + "; ".join(flight_line(f) for f in flights))
    return lines


def foot_angle_line(walk: dict, affected: str | None = None) -> str | None:
    """Cohort C244: "- Foot angles ...": each side's median sole angle at contact and at toe-off (gait_summary.json
    walk ``ic_angle_deg_left`` ..., the track's L421 angles, + toes up), the sides named affected / unaffected with
    ``affected`` (C245); None without any."""
    from pdrlearn.track.affected_side import side_word

    parts = []
    for s, tag in (("left", "L"), ("right", "R")):
        ic, tc = _number(walk.get(f"ic_angle_deg_{s}")), _number(walk.get(f"tc_angle_deg_{s}"))
        if ic is None and tc is None:
            continue
        name = tag if affected not in ("left", "right") else f"{tag} ({side_word(s, affected)})"
        parts.append(f"{name} {'-' if ic is None else f'{ic:.1f}'} / {'-' if tc is None else f'{tc:.1f}'} deg")
    if not parts:
        return None
    return ("- Foot angles at contact / toe-off (sole, + toes up, medians of the same steps; L421, C244): "
            + "; ".join(parts))


def _pairs_row(folder: Path, root: Path) -> dict:
    """Decision W438: gait-all's gait_pairs.csv row of the visit folder a gait_summary.json is in (the nearest
    folder up to ``root`` holding gait_pairs.csv), ``{}`` for a `gait --out` folder."""
    for up in [folder, *folder.parents]:
        table = up / "gait_pairs.csv"
        if table.is_file():
            rel = folder.relative_to(up).as_posix() if folder != up else "."
            try:
                rows = pd.read_csv(table, dtype=str, keep_default_na=False)
            except (OSError, ValueError, pd.errors.ParserError):
                return {}
            hit = rows[rows["path"] == rel] if "path" in rows else rows.iloc[:0]
            return hit.iloc[0].to_dict() if len(hit) else {}
        if up == root:
            break
    return {}


def _same(a, b) -> bool:
    try:
        return bool(a) and bool(b) and Path(a).resolve() == Path(b).resolve()
    except (OSError, ValueError):
        return False


def _gait_walks(root: Path) -> list[dict]:
    """Decision W438: every gait_summary.json under ``root`` (gait --out, gait-all's W437 per-pair files) as ``{folder,
    rel, subject, left, right (session paths), names, walk}``; one not written by gait is the line plain report
    gives."""
    from pdrlearn.cohort import meta_visit
    from pdrlearn.track.gait import leg_length

    walks = []
    for path in sorted(root.rglob("gait_summary.json")) if root.is_dir() else []:
        summary = _read(path)
        walk, sessions = summary.get("walk"), summary.get("sessions")
        if not isinstance(walk, dict):
            raise DataError(f"{path}: no \"walk\" object; not a gait_summary.json written by `pdrlearn gait --out`; "
                            "regenerate it")
        sessions = sessions if isinstance(sessions, dict) else {}
        side = {s: (sessions.get(s) or {}).get("session") if isinstance(sessions.get(s), dict) else None
                for s in ("left", "right")}
        row = _pairs_row(path.parent, root)
        meta = {s: session_meta(side[s]) for s in ("left", "right")}
        subject = row.get("subject") or meta["left"].get("subject") or meta["right"].get("subject")
        rel = path.parent.relative_to(root).as_posix() if path.parent != root else path.parent.name
        names = {s: row.get(f"session_{s}") or (Path(side[s]).name if side[s] else "?") for s in ("left", "right")}
        found = leg_length(meta["left"] or meta["right"])  # decision C196: a measured leg only
        # decision C238: the visit too (gait_pairs.csv's, else meta.json's), so C221 orders the gait rows
        visit = row.get("visit") or meta_visit(meta["left"]) or meta_visit(meta["right"])
        walks.append({"folder": path.parent, "rel": rel, "subject": subject or None, "visit": visit or None,
                      "walk": walk, **side,
                      "names": names, "stairs": summary.get("stairs"),  # L561: stairs
                      "affected": summary.get("affected_side"),  # cohort C245
                      "reason": summary.get("reason") if isinstance(summary.get("reason"), str) else None,  # L762
                      "leg_m": measured_leg(found.get("leg_length_m"), found.get("leg_length_source"))})
    return walks


def _patients(source: str | Path) -> dict[str, list]:
    """Decision W420: every track output (summary.json) and (W438) every bilateral gait output (gait_summary.json)
    under ``source`` as ``{patient: rows}`` in clinical.md's order; one :class:`DataError` line when there is
    neither."""
    root = Path(source)
    found = sorted(root.rglob("summary.json")) if root.is_dir() else []
    tracks = [(p.parent, _read(p)) for p in found]
    tracks = [(f, s) for f, s in tracks if s.get("pipeline") in UNIT_NAMES]
    gaits = _gait_walks(root)
    if not tracks and not gaits:
        raise DataError(f"{root}: --clinical reads track outputs (summary.json of `pdrlearn track`) or bilateral gait "
                        "outputs (gait_summary.json of `pdrlearn gait --out` / `gait-all`) and there is none under it; "
                        "track the sessions first (pdrlearn track SESSION --out DIR) or drop --clinical")
    patients: dict[str, list] = {}
    for folder, summary in tracks:
        # W426: without a subject, the folder's path under SOURCE stands for the patient: two patients' session
        # folders may share a name (patientA/tug, patientB/tug), the session id alone merged them
        rel = folder.relative_to(root).as_posix() if folder != root else folder.name
        key = str(summary["subject"]) if summary.get("subject") else f"{rel}{NO_SUBJECT}"
        patients.setdefault(key, []).append(("track", folder, rel, summary))
    for g in gaits:
        key = str(g["subject"]) if g["subject"] else f"{g['rel']}{NO_SUBJECT}"
        patients.setdefault(key, []).append(("gait", g["folder"], g["rel"], g))
    return patients


def _patient_lines(rows: list) -> list[str]:
    """Decision W420: one patient's blocks (C221's visit order) and (C177) change-from-baseline lines."""
    rows = in_visit_order(rows)  # decision C221: the baseline's sessions first, as the change line pairs them
    table = visit_table_lines(rows)  # decision C273: one visit x measure table first
    out: list[str] = table + [""] if table else []
    changes = change_lines(rows) + gait_change_lines(rows)  # decision C177; cohort C242: the gait outputs'
    if changes:  # decision C273: the changes under the table, the sessions' details after them
        out += changes + [""]
    for block in walk_blocks(rows):
        out += block + [""]
    notes = technical_notes(rows)  # decision C273: each warning once, at the end
    if notes:
        out += notes + [""]
    return out


def clinical_markdown(source: str | Path) -> str:
    """Decision W420: clinical.md's text for every track output (summary.json) and (W438) every bilateral gait
    output (gait_summary.json) under ``source``; one :class:`DataError` line when there is neither."""
    return clinical_texts(source)[0]


def clinical_texts(source: str | Path) -> tuple[str, dict[str, str]]:
    """Decisions W420, C229: clinical.md's text and ``{file name: text}`` of each patient's own page (the patient's
    block of clinical.md under its own title; :func:`page_names`' file-safe, unique names, ``P01.md``)."""
    patients = _patients(source)
    out, pages = ["# Clinical summary", ""], {}
    names = page_names(list(patients))
    for patient, rows in patients.items():
        lines = _patient_lines(rows)
        out += [f"## Patient {patient}", "", *lines]
        page = "\n".join([f"# Clinical summary: patient {patient}", "", *lines]).rstrip()
        pages[f"{names[patient]}.md"] = page + "\n"
    return "\n".join(out), pages


#: decision W426: the patient name of a track without a subject (its folder's path under SOURCE before it)
NO_SUBJECT = " (no subject in meta.json)"
#: decision C229: the longest page file name (characters, before ".md")
PAGE_NAME_MAX = 80


def page_names(patients: list[str]) -> dict[str, str]:
    """Decision C229: ``{patient: file name stem}``: the name (W426's folder path without :data:`NO_SUBJECT`) with
    every character but an ASCII letter, digit, ``-``, ``_`` or ``.`` as ``_``, no leading dot, at most
    :data:`PAGE_NAME_MAX` characters ("patient" when nothing is left); a name that collides (case-blind, as on a
    case-blind disk) with an earlier one gets ``_2``, ``_3``, ..."""
    names: dict[str, str] = {}
    taken: set[str] = set()
    for patient in patients:
        bare = patient.removesuffix(NO_SUBJECT)
        safe = "".join(c if c.isascii() and (c.isalnum() or c in "-_.") else "_" for c in bare)
        safe = safe.lstrip(".")[:PAGE_NAME_MAX] or "patient"
        name, k = safe, 1
        while name.lower() in taken:
            k += 1
            name = f"{safe[:PAGE_NAME_MAX - len(str(k)) - 1]}_{k}"
        taken.add(name.lower())
        names[patient] = name
    return names


def in_visit_order(rows: list) -> list:
    """Decision C221: one patient's rows (track or gait) with their visits in study order (``visits.visit_order``:
    ``pre`` before ``post`` whatever the alphabet says, C24), stable within a visit; rows without a visit keep their
    place after the visits' rows. Before, the rows came in the folders' text order, so a ``P01_post`` folder was listed
    above ``P01_pre`` while the change line (C177) read pre -> post."""
    from pdrlearn.visits import visit_order

    def visit(row):
        v = row[3].get("visit")
        return None if v in (None, "") else str(v)

    rank = {v: i for i, v in enumerate(visit_order(filter(None, map(visit, rows))))}
    return sorted(rows, key=lambda r: rank.get(visit(r), len(rank)))


def _track_block(folder: Path, rel: str, summary: dict, head: str = "Session") -> list[str]:
    date = recording_date(summary, folder)
    when = f"recorded {date}" if date else "recording date unknown (no meta.json recording_start)"
    visit = f", visit {summary['visit']}" if summary.get("visit") else ""  # decision C177
    test = session_test(summary)  # decision C273: the test's name, not the recording's file name
    first = (f"{test}{visit} ({rel})" if test and head == "Session"
             else f"{head} {summary.get('session')} ({rel}){visit}")
    return [f"{first}, {when}:",
            *(clinical_lines(summary, folder) or ["- no clinical test measured"])]


def walk_blocks(rows: list) -> list[list[str]]:
    """Decision W438: one patient's blocks of lines. The two tracks of a left and a right foot session of one folder
    are one walk block (each foot's lines under its side, then the walk's asymmetry from the gait output pairing the
    same two sessions, or the line saying how to get it); a gait output no track matches is its own walk block; every
    other track is W420's session block."""
    from pdrlearn.track.bilateral import session_foot

    tracks = [r for r in rows if r[0] == "track"]
    gaits = [r[3] for r in rows if r[0] == "gait"]
    feet: dict[str, dict[str, list]] = {}
    for r in tracks:
        session = r[3].get("input_dir")
        foot = session_foot(session_meta(session)) if session else None  # decision L260's meta.json keys
        if foot is not None:
            feet.setdefault(str(Path(session).parent), {}).setdefault(foot, []).append(r)
    paired = {id(v[0]): k for k, d in feet.items() if all(len(d.get(s, [])) == 1 for s in ("left", "right"))
              for v in (d["left"], d["right"])}
    used, blocks, done = set(), [], set()
    for r in tracks:
        key = paired.get(id(r))
        if key is None:
            blocks.append(_track_block(r[1], r[2], r[3]))
            continue
        if key in done:
            continue
        done.add(key)
        left, right = feet[key]["left"][0], feet[key]["right"][0]
        block = [f"Walk {Path(key).name}: left and right foot of one walk (W438):"]
        for side, (_, folder, rel, summary) in (("Left foot", left), ("Right foot", right)):
            lines = _track_block(folder, rel, summary, head=f"{side}, session")
            block += [lines[0], *[f"  {line}" for line in lines[1:]]]
        g = next((g for g in gaits if _same(g["left"], left[3].get("input_dir"))
                  and _same(g["right"], right[3].get("input_dir"))), None)
        if g is None:
            block.append("- Asymmetry: not measured; pair the two feet with `pdrlearn gait-all ROOT --out G` (or "
                         "`pdrlearn gait LEFT RIGHT --out G`) and report a folder holding G too (W437, W438)")
        else:
            used.add(id(g))
            block += asymmetry_lines(g["walk"], g["stairs"], g["leg_m"], g["affected"], g.get("reason"))
        blocks.append(block)
    for g in gaits:
        if id(g) in used:
            continue
        date = session_date(Path(g["left"])) if g["left"] else None
        when = f"recorded {date}" if date else "recording date unknown (no meta.json recording_start)"
        blocks.append([f"Walk {g['rel']} (left {g['names']['left']} + right {g['names']['right']}; pdrlearn gait), "
                       f"{when}:",
                       *asymmetry_lines(g["walk"], g["stairs"], g["leg_m"], g["affected"], g.get("reason"))])
    return blocks
