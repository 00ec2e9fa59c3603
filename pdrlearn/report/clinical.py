"""A short per-patient clinical summary of track outputs (decision W420, docs/decisions/waist.md): ``pdrlearn report
SOURCE --out OUT --clinical`` writes ``OUT/clinical.md`` beside report.md.

One block per patient (summary.json ``subject``, else the folder's path under SOURCE, W426): the patient and session
ids, the recording date (summary.json ``recording_start``, else the tracked session's meta.json via run.json, L298's
rule), then one line per clinical test a track measured - the corridor walk test (6MWT), the TUG with its phases,
steps and turn time, the 10 m walk, the gait speed and cadence - each naming the unit it comes from. Nothing
research-only: no errors against a reference, no model or validation warnings, no per-stride tables.
"""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.report.daily_living import daily_living_lines

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
    meta = Path(session) / "meta.json" if session else None
    if meta is None or not meta.is_file():
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
    if speed < VALIDATED_MIN_MPS or slow_cad:
        flags.append(f"slower than the validated {VALIDATED_MIN_MPS:g} m/s / {VALIDATED_MIN_SPM:g} steps/min (L95)")
    return f"- Gait speed {speed:.2f} m/s{cadence} ({'; '.join(flags)})"


def warnings_line(summary: dict) -> str | None:
    """Decision W446: a pointer to the track's warnings (clinical.md leaves their text to report.md)."""
    info = summary.get("info") or {}
    warnings, codes = info.get("warnings") or [], info.get("warning_codes") or []
    if not warnings:
        return None
    named = f" ({', '.join(dict.fromkeys(c for c in codes if c))})" if any(codes) else ""
    return (f"- Track warnings: {len(warnings)}{named}; read them in report.md or summary.json info.warnings before "
            "using these numbers")


def _unit(source: str) -> str:
    return "foot unit" if source == "foot" else "lower-back unit"


def clinical_lines(summary: dict, folder: Path) -> list[str]:
    """Decision W420: one line per clinical test the track in ``folder`` (its ``summary``) measured."""
    unit = UNIT_NAMES.get(str(summary.get("pipeline")), str(summary.get("pipeline")))
    lines = []
    if summary.get("walk_test_distance_m") is not None:
        corridor = summary.get("corridor_m")
        laps = f", {summary['n_laps']} laps of {corridor:g} m" if corridor and summary.get("n_laps") is not None \
            else ""
        dur = summary.get("walk_test_duration_s")
        lines.append(f"- Corridor walk test (6MWT): {summary['walk_test_distance_m']:.0f} m{laps}"
                     f"{f' in {dur / 60:.1f} min' if dur else ''} ({unit})")
    tug = tug_line(summary, folder)
    if tug:
        lines.append(tug)
    if summary.get("ten_m_walk_speed_mps") is not None:  # L531: the walkway's timed metres and every trial (L524)
        from pdrlearn.track.walk_test import timed_stretch, trials_text, walkway_zones

        trials = trials_text(summary)
        lines.append(f"- 10 m walk: {summary['ten_m_walk_speed_mps']:.2f} m/s ({_s(summary['ten_m_walk_time_s'])} "
                     f"over {timed_stretch(*walkway_zones(summary))}"  # decision L536
                     f"{f'; {trials}' if trials else ''}; {unit})")
    speed = gait_speed_line(summary, unit)
    if speed:
        lines.append(speed)
    lines += daily_living_lines(summary, folder)
    warnings = warnings_line(summary)
    if warnings:
        lines.append(warnings)
    return lines


def clinical_markdown(source: str | Path) -> str:
    """Decision W420: clinical.md's text for every track output (summary.json) under ``source``; one
    :class:`DataError` line when there is none."""
    root = Path(source)
    found = sorted(root.rglob("summary.json")) if root.is_dir() else []
    tracks = [(p.parent, _read(p)) for p in found]
    tracks = [(f, s) for f, s in tracks if s.get("pipeline") in UNIT_NAMES]
    if not tracks:
        raise DataError(f"{root}: --clinical reads track outputs (summary.json of `pdrlearn track`) and there is none "
                        "under it; track the sessions first (pdrlearn track SESSION --out DIR) or drop --clinical")
    patients: dict[str, list] = {}
    for folder, summary in tracks:
        # W426: without a subject, the folder's path under SOURCE stands for the patient: two patients' session
        # folders may share a name (patientA/tug, patientB/tug), the session id alone merged them
        rel = folder.relative_to(root).as_posix() if folder != root else folder.name
        key = str(summary["subject"]) if summary.get("subject") else f"{rel} (no subject in meta.json)"
        patients.setdefault(key, []).append((folder, rel, summary))
    out = ["# Clinical summary", ""]
    for patient, rows in patients.items():
        out += [f"## Patient {patient}", ""]
        for folder, rel, summary in rows:
            date = recording_date(summary, folder)
            when = f"recorded {date}" if date else "recording date unknown (no meta.json recording_start)"
            out.append(f"Session {summary.get('session')} ({rel}), {when}:")
            out += clinical_lines(summary, folder) or ["- no clinical test measured"]
            out.append("")
    return "\n".join(out)
