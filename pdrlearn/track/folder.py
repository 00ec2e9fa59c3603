"""Decision E166 (session 34, trial T4 finding 8): :func:`write_track`, the folder ``pdrlearn track --out`` writes,
from a :class:`~pdrlearn.track.base.TrackResult` a Python worker made (``get_pipeline(...)(session)``): the same
files by the same code (``pdrlearn.cli.track.write_track``), atomically, with a run.json (decision L122)."""

from __future__ import annotations

import dataclasses
from pathlib import Path


def write_track(result, session, out, force: bool = False) -> Path:
    """Write ``result`` (a track of ``session``) to the folder ``out`` as ``pdrlearn track SESSION --out OUT`` does
    with its defaults: trajectory.csv, steps.csv, bouts.csv (default bout rule), turns.csv, path.png,
    summary.json (with the time accounting and steadiness flags, L275, L415), track.gpx / track.geojson with a
    start, and run.json (``command`` "write_track", the session's folder and its files' SHA-256, cwd and argv).
    All files or none (:func:`pdrlearn.atomic.atomic_directory`); an existing track folder is replaced only with
    ``force`` and anything else in ``out`` is refused (one :class:`~pdrlearn.errors.DataError` line, as ``track``).
    ``result`` is not changed. Returns ``out``."""
    from pdrlearn.atomic import atomic_directory
    from pdrlearn.cli.common import out_folder
    from pdrlearn.cli.provenance import input_hashes, run_record, write_run_json
    from pdrlearn.cli.track import write_track as write_folder
    from pdrlearn.track.bouts import detected_bouts, session_key, session_leg_m
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.periods import time_accounting
    from pdrlearn.track.steady import add_steady_column
    from pdrlearn.track.units import tracked_unit
    from pdrlearn.warning_lines import machine_summary

    out = out_folder(Path(out), "track", force=force, inputs=(session.folder,) if session.folder else ())
    pipeline = result.info.get("pipeline", "plasys")
    result = dataclasses.replace(result, steps=result.steps.copy(), info=dict(result.info))  # the caller's untouched
    bouts = detected_bouts(result.steps, None, **session_key(session), leg_m=session_leg_m(session))  # L124, L165
    summary = track_summary(result, session, pipeline=pipeline, bout_table=bouts)  # C13, C14: TrackResult.summary
    add_steady_column(result.steps)  # decision L415, as track's steps.csv
    summary.update(time_accounting(result, session, tracked_unit(pipeline)))  # decision L275
    summary = machine_summary(summary, [], session.where)  # decisions E154, E155
    tracked = {"session": session, "result": result, "summary": summary, "pipeline": pipeline,
               "aided": "aid" in result.info, "dpi": None, "bouts": bouts}
    with atomic_directory(out) as tmp:
        write_folder(tmp, tracked)
        write_run_json(tmp, run_record(
            "write_track", {}, session=session.where, pipeline=pipeline, method=result.info.get("method"),
            input_sha256=input_hashes(session.folder) if session.folder is not None else {}))  # L122, L136
    return out
