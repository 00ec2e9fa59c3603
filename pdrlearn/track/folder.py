"""Decision E166 (session 34, trial T4 finding 8): :func:`write_track`, the folder ``pdrlearn track --out`` writes,
from a :class:`~pdrlearn.track.base.TrackResult` a Python worker made (``get_pipeline(...)(session)``): the same
files by the same code (:func:`write_folder`, which ``pdrlearn track`` calls), atomically, with a run.json (decision
L122). Decision E169 (session 35): the writer and the output-folder checks it uses are library code (this module,
:mod:`pdrlearn.outfolder`, :mod:`pdrlearn.table_csv`, :mod:`pdrlearn.provenance`); the CLI calls them, and nothing
here imports ``pdrlearn.cli``."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from pdrlearn.table_csv import write_table_csv


def write_track(result, session, out, force: bool = False, *, plot: bool = True) -> Path:
    """Write ``result`` (a track of ``session``) to the folder ``out`` as ``pdrlearn track SESSION --out OUT`` does
    with its defaults: trajectory.csv, steps.csv, bouts.csv (default bout rule), turns.csv, path.png (none with
    ``plot=False``, as ``--no-plot``: decision L533), summary.json (with the time accounting and steadiness flags,
    L275, L415), track.gpx / track.geojson with a start, and run.json (``command`` "write_track", the session's
    folder and its files' SHA-256, cwd and argv).
    All files or none (:func:`pdrlearn.atomic.atomic_directory`); an existing track folder is replaced only with
    ``force`` and anything else in ``out`` is refused (one :class:`~pdrlearn.errors.DataError` line, as ``track``).
    ``result`` is not changed. Returns ``out``."""
    from pdrlearn.atomic import atomic_directory
    from pdrlearn.outfolder import out_folder
    from pdrlearn.provenance import input_hashes, run_record, write_run_json
    from pdrlearn.track.belt import session_incline
    from pdrlearn.track.bouts import track_bouts
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.freezes import add_freeze_columns
    from pdrlearn.track.periods import bout_ascent, bout_floors, time_accounting
    from pdrlearn.track.steady import add_steady_column
    from pdrlearn.track.units import tracked_unit
    from pdrlearn.warning_lines import machine_summary

    out = out_folder(Path(out), "track", force=force, inputs=(session.folder,) if session.folder else ())
    pipeline = result.info.get("pipeline", "plasys")
    result = dataclasses.replace(result, steps=result.steps.copy(), info=dict(result.info))  # the caller's untouched
    with session_incline(session):  # decisions L442, L454: bouts.csv's and steps.csv's CV strides as track's
        bouts = track_bouts(result, session)  # L124, W480
        bouts = bout_floors(bouts, result.steps, result.info)  # decision L450, as track's bouts.csv
        bouts = bout_ascent(bouts, result)  # decision L467
        summary = track_summary(result, session, pipeline=pipeline, bout_table=bouts)  # C13, C14
        add_steady_column(result.steps)  # decision L415, as track's steps.csv
    bouts = add_freeze_columns(bouts, result.steps, result.info.get("freezes"))  # decision W397, as track's
    summary.update(time_accounting(result, session, tracked_unit(pipeline)))  # decision L275
    summary = machine_summary(summary, [], session.where)  # decisions E154, E155
    tracked = {"session": session, "result": result, "summary": summary, "pipeline": pipeline,
               "aided": "aid" in result.info, "dpi": None, "plot": plot, "bouts": bouts}
    with atomic_directory(out) as tmp:
        write_folder(tmp, tracked)
        write_run_json(tmp, run_record(
            "write_track", {}, session=session.where, pipeline=pipeline, method=result.info.get("method"),
            input_sha256=input_hashes(session.folder) if session.folder is not None else {}))  # L122, L136
    return out


def event_tables(result, bouts, periods=None, start=None, laps=None, splits=None, segments=None) -> dict:
    """Decision L298: every event table a track or run writes - ``bouts.csv`` (L124), :func:`clinical_tables`'s,
    ``periods.csv`` (L277, when given) and ``laps.csv`` (L383, with --corridor) - with their clock columns when the
    recording's ``start`` is known."""
    from pdrlearn.track.bouts import csv_table
    from pdrlearn.track.clock import with_clock_columns

    tables = {"bouts.csv": csv_table(bouts), **clinical_tables(result, bouts)}
    if periods is not None:
        tables["periods.csv"] = periods
    if laps is not None:
        tables["laps.csv"] = laps
    if splits is not None:  # decision L411: --splits
        tables["splits.csv"] = splits
    if segments is not None:  # decision L619: --segments
        tables["segments.csv"] = segments
    return {name: with_clock_columns(table, start) for name, table in tables.items()}


def clinical_tables(result, bouts) -> dict:
    """The per-event tables a track writes beside bouts.csv: ``turns.csv`` (decision L200: each turn of at least
    ``turn_count_min_deg``, any pipeline) and, on the lower back, ``transfers.csv`` (decision W182: each
    sit-to-stand / stand-to-sit; a foot track has none: a foot unit does not see the trunk; with a TUG time its
    phases, ``tug_phases.csv``, decision W293; with a TUG trial, ``tug_trials.csv``, W325) and ``freezes.csv``
    (decision W213: the freeze index's episodes of the tracked unit), ``ramps.csv`` (decision L301) and
    ``ramp_runs.csv`` (L568: its runs and landings), ``stairs.csv``
    (decision L432: the stair flights of a foot track, ``n_stairs`` from ``info["stair_rise_m"]``; none on the lower
    back, L440), ``curbs.csv`` (decision L573: a foot track's single level changes; none on the lower back) and, on
    the lower back with a barometer, ``rides.csv`` (decision L377); on a session with reference walking bouts,
    ``wb_scores.csv`` (decision W493)."""
    import pandas as pd

    from pdrlearn.track.clinical import add_turn_steps, turn_table
    from pdrlearn.track.grade import ramp_table
    from pdrlearn.waist.transfers import TRANSFER_COLUMNS

    out = {"turns.csv": add_turn_steps(turn_table(result.steps, bouts, yaw_turns=result.info.get("yaw_turns"),
                                                  gap_turns=result.info.get("waist_gap_turns")),  # L701
                                       result.steps, result.info)}  # L210; W398 / L749: steps per turn
    from pdrlearn.track.clinical import _is_lower_back
    from pdrlearn.track.grade import info_stair_grade, track_ramps
    from pdrlearn.track.ramp_audit import ramp_run_table, with_end_positions
    from pdrlearn.track.stair_flights import flight_table

    traj = result.trajectory
    with info_stair_grade(result.info):  # decision L469: --stair-grade
        # decision L301: the ramps (header alone: no grade); L569: their flags, L570: their ends' positions
        found = track_ramps(result.steps, result.info)  # session 42: found once, for the three tables
        out["ramps.csv"] = ramp_table(result.steps, result.info, traj, found=found)
        out["ramp_runs.csv"] = ramp_run_table(result.steps, result.info, traj, found=found)  # L568: runs, landings
        if not _is_lower_back(result.steps):  # decision L440: no stairs.csv on the lower back (no flights to list)
            # decision L432: a foot track's stair flights; n_stairs with --stair-rise
            # decision L442: a declared inclined belt (info["belt_incline_pct"]) has no stair flight: the header alone
            out["stairs.csv"] = with_end_positions(  # decision L570: the flights' ends' positions
                flight_table(result.steps if result.info.get("belt_incline_pct") is None
                             else result.steps.iloc[:0], result.info.get("stair_rise_m")), traj)
            from pdrlearn.track.curbs import curb_table

            # decision L573: single level changes (curbs) outside flights and ramps
            out["curbs.csv"] = curb_table(result.steps, result.trajectory, result.info, found=found)
    from pdrlearn.track.travel import direction_change_table

    changes = direction_change_table(result.steps)  # decision L412: a foot track's changes of travel direction
    if changes is not None:
        out["direction_changes.csv"] = changes
    if result.info.get("rides") is not None:  # decision L377: a lower-back track's rides
        from pdrlearn.track.rides import ride_table

        out["rides.csv"] = ride_table(result.info)
    if result.info.get("transfers") is not None:
        out["transfers.csv"] = pd.DataFrame(result.info["transfers"], columns=list(TRANSFER_COLUMNS))
        from pdrlearn.track.trunk_tug import foot_strides, tug_contacts, tug_yaw_turns
        from pdrlearn.waist.tug_phases import tug_phase_table, tug_phases, tug_trial_table

        # decision W418: a foot track's TUG reads the waist's contacts; W419: the foot's turns.csv and strides
        phases = tug_phases(result.info["transfers"], out["turns.csv"], tug_contacts(result),  # decision W293
                            yaw_turns=tug_yaw_turns(result), walk=foot_strides(result))  # W307, W490 / L614
        if phases is not None:
            out["tug_phases.csv"] = tug_phase_table(phases)
        trials = tug_trial_table(result.info["transfers"], out["turns.csv"], tug_contacts(result),  # decision W325
                                 yaw_turns=tug_yaw_turns(result), foot=foot_strides(result))
        if len(trials):
            out["tug_trials.csv"] = trials
    from pdrlearn.track.walk_test import ramp_numbers, ten_metre_walk_trials

    trials = ten_metre_walk_trials(result.steps, result.info.get("ten_m_walk_m"),  # decision L524: every trial
                                   result.info.get("params_source") == "calibrated",  # L649
                                   ramps=ramp_numbers(result.steps, found))  # decision L679: not on a ramp
    if len(trials) and not result.info.get("walk_test_recording"):  # decision C249: a 6MWT's passes are no trials
        out["ten_m_walk_trials.csv"] = trials
    if result.info.get("flights") is not None:  # decision W417: each unit's flight phases, with a jump height
        from pdrlearn.track.flight import FLIGHT_COLUMNS

        out["flights.csv"] = pd.DataFrame(result.info["flights"], columns=list(FLIGHT_COLUMNS))
    if result.info.get("wb_scores") is not None:  # decision W493: the detected bouts against the reference WBs
        from pdrlearn.track.wb_scores import WB_SCORE_COLUMNS

        out["wb_scores.csv"] = pd.DataFrame(result.info["wb_scores"], columns=list(WB_SCORE_COLUMNS))
    if result.info.get("freezes") is not None:  # decision W213: the freeze index's episodes, foot or lower back
        from pdrlearn.track.freezes import freeze_table

        out["freezes.csv"] = freeze_table(result.info["freezes"])
    return out


def write_folder(dest: Path, tracked: dict) -> tuple[dict, bool]:
    """Write :func:`track_session`'s track into the existing folder ``dest`` (the caller's temporary folder):
    ``trajectory.csv``, ``steps.csv``, ``bouts.csv`` (decision L124), ``path.png`` (``aided.png`` with fixes; neither
    when ``tracked["plot"]`` is false, decision L533) and ``summary.json``; return the summary and whether the track
    was aided."""
    from pdrlearn.track.plots import plot_paths

    session, result, summary, pipeline, aided, dpi = (tracked[k] for k in ("session", "result", "summary",
                                                                              "pipeline", "aided", "dpi"))
    plot = tracked.get("plot", True)  # decision L533: --no-plot draws no figure; nothing else changes
    traj = result.trajectory.copy()
    for c in ("lat", "lon"):
        if c not in traj:
            traj[c] = float("nan")
    if "pos_sigma_m" in traj:  # decision L128: appended after the columns trajectory.csv always had
        traj = traj[[c for c in traj.columns if c != "pos_sigma_m"] + ["pos_sigma_m"]]
    from pdrlearn.track.floor_column import with_floor_columns

    traj = with_floor_columns(traj, result, summary.get("storey_height_m"))  # decisions L630, L631
    from pdrlearn.track.rides import with_ride_column

    traj = with_ride_column(traj, result.info)  # decision L623: the rows a ride's line reaches (not walked), last
    if aided and plot:
        from pdrlearn.aid import plot_aided

        plot_aided(result, dest / "aided.png", truth=session.trajectory,
                   title=f"{session.name}: {pipeline} {result.info.get('method', '')} + fixes", dpi=dpi)
    if tracked.get("start") is not None:  # decision B448: each row's clock time (L298's form), the last column
        from pdrlearn.track.clock import clock_texts

        traj["time"] = clock_texts(tracked["start"], traj["t"])
    write_table_csv(traj, dest / "trajectory.csv")
    from pdrlearn.track.evaluate import with_reference_columns

    write_table_csv(with_reference_columns(result, session), dest / "steps.csv")  # decision E135: the reference pairs
    # decisions L124 (E98: the old speed_m_s last), L200, W182, L277; L298: clock columns with a recording start
    tables = event_tables(result, tracked["bouts"], tracked.get("periods"), tracked.get("start"),
                          tracked.get("laps"), tracked.get("splits"), tracked.get("segments"))
    for name, table in tables.items():
        write_table_csv(table, dest / name)
    if tracked.get("at_times") is not None:  # decision L638: OUT/at_times.csv, the positions at the given times
        write_table_csv(tracked["at_times"], dest / "at_times.csv")
    if plot:
        plot_paths({f"{pipeline} {result.info.get('method', '')}".strip(): result}, dest / "path.png",
                   session=session, title=f"{session.name}: {pipeline} {result.info.get('method', '')}", dpi=dpi)
    (dest / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    from pdrlearn.track.geoexport import write_geo_files
    from pdrlearn.track.ramp_audit import route_features

    # decisions L362, L363: track.gpx and track.geojson of a track with lat/lon (--start, geodetic fixes), none without
    write_geo_files(dest, traj, session=session.name, pipeline=summary.get("pipeline"),
                    distance_m=summary.get("distance_m"), start=tracked.get("start"),
                    with_ele=bool(tracked.get("start_ele")), features=route_features(tables))  # L570
    return summary, aided
