# ruff: noqa: B008  (typer declares options as call defaults)
"""``pdrlearn steps``: detect steps in a session and score them against its labels."""

from __future__ import annotations

from pathlib import Path

import typer

from pdrlearn.cli.common import FORCE_HELP, existed, json_safe, out_file, print_json, replaced, warn_gaps
from pdrlearn.cli.registry_help import DETECTOR_NAMES
from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError

#: decision steps 38: warn when more than this fraction of the foot's rest-to-rest strides were merged into a
#: neighbour's detection; a stray one is the detector's usual error (real MS patient: 2 of 74, a simulated
#: 3-year-old at 230 steps/min: 1 of 26), the trial's merged children 15 of 22 and 25 of 26
MERGED_WARN_FRAC = 0.1
#: decision steps 56: the reference clock offset option of `steps` and `score-steps`
REF_OFFSET_HELP = ("The reference clock minus the IMU clock, s: every label time t is scored at t - SECONDS (a Vicon "
                   "clock reading the IMU clock + 5 s: --ref-offset 5; decision steps 56).")
#: decision steps 59: the matched events table
EVENTS_OUT_HELP = ("Write every scored event to this CSV: event (ic | tc), foot, detected_s, reference_s, error_s "
                   "(detected - reference, s), match (matched | false_positive | missed); for Bland-Altman plots "
                   "(decision steps 59).")


def steps(
    session_dir: Path = typer.Argument(..., help="PLASYS session folder."),
    detector: str = typer.Option("auto", "--detector", "-d",
                                 help=f"{DETECTOR_NAMES} (the registered ones, decision C157); auto = accel "
                                 "with a foot unit, else waist-ic (the waist-pendulum pipeline's initial contacts; "
                                 "pll without a waist gyroscope); or a plug-in detector (docs/extending.md); "
                                 "NAME:key=value,... sets its settings, e.g. pll:loop_hz=1.5 (decision E94)."),
    out: Path = typer.Option(None, "--out", "-o", help="Write the steps table to this CSV (times in s)."),
    tolerance: float = typer.Option(0.25, "--tolerance", help="Event matching tolerance in seconds."),
    time_origin: str = typer.Option("session", "--time-origin", help="session: --out times in s from the "
                                    "session's first sample (what score-steps reads); export: on the clock of the "
                                    "export 'pdrlearn import' read, its first time added back (E173)."),
    ref_offset: float = typer.Option(0.0, "--ref-offset", help=REF_OFFSET_HELP),
    events_out: Path = typer.Option(None, "--events-out", help=EVENTS_OUT_HELP),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object."),
    keep_pedalling: bool = typer.Option(False, "--keep-pedalling", help="With a foot detector: count the strides "
                                        "that go round a closed loop (cycling?), which track removes and steps "
                                        "leaves out of its count by default; --out's pedalling column marks them "
                                        "(decisions L611, L625)."),
) -> None:
    """Detect steps and, when the session has labels, print precision/recall/F1 and the count error.

    Foot detectors find one event per stride of the instrumented foot and are scored against
    steps.csv (ic_ms); waist detectors find every step and are scored against ics.csv when present.

    Examples:

        pdrlearn steps datasets/real/gaitmap_level_right --detector accel

        pdrlearn steps datasets/real/mobgap_HA001_Test5_Trial1 --detector pll --json

        pdrlearn steps datasets/real/mobgap_HA001_Test11_Trial1 --detector waist-ic

        pdrlearn steps out/sim/D_u1 --detector accel-force --out out/D_steps.csv

        pdrlearn steps datasets/real/mobgap_HA001_Test5_Trial1 --detector pll:loop_hz=1.5   # a detector setting

        pdrlearn steps sessions/walk1 --out walk1_steps.csv --time-origin export   # an import's own clock

        pdrlearn steps sessions/commute --detector accel --keep-pedalling --out c.csv   # count cycling strides too
    """
    from pdrlearn.io import read_session
    from pdrlearn.steps import get_detector
    from pdrlearn.steps.evaluate import check_tolerance
    from pdrlearn.steps.reference_clock import check_ref_offset

    if detector != "auto":
        det = get_detector(detector)
    check_tolerance(tolerance, "--tolerance")  # decision B167: seconds, > 0, at most 2 s
    from pdrlearn.track.clock import TIME_ORIGINS, export_origin_s

    if time_origin not in TIME_ORIGINS:
        raise DataError(f"--time-origin {time_origin!r} is not one of {', '.join(TIME_ORIGINS)} (decision E173)")
    if time_origin == "export" and out is None:
        raise DataError("--time-origin export says on which clock --out writes its times; pass --out FILE.csv (the "
                        "JSON's time_origin_s gives the origin to add) (decision E173)")
    check_ref_offset(ref_offset, "--ref-offset")  # decision B333
    if out is not None:
        out = out_file(out, (".csv",), "steps", force=force)
    events_out = _events_file(events_out, out, force)
    was = out is not None and existed(out)
    session = read_session(session_dir)
    if time_origin == "export":
        if export_origin_s(session.meta) is None:
            raise DataError(f"{session_dir}: --time-origin export adds back the first time of the export 'pdrlearn "
                            "import' read, and this session was not imported (its meta.json has no imported.time."
                            "origin_s): its times are its own; leave --time-origin out (decision E173)")
    if detector == "auto":
        det = auto_detector(session)
    if keep_pedalling and det.unit != "foot":  # decision L625: L611 judges a foot's strides
        raise DataError(f"--keep-pedalling: --detector {det.name} finds lower-back steps, and the pedalling check "
                        "(decision L611) reads a foot unit's strides; leave --keep-pedalling out, or pass a foot "
                        "detector (--detector accel) (decision L625)")
    if det.unit == "foot" and reads_force(det) and session.has("fAccelerometer", "fGyroscope"):
        session = _tared(session, det.name)  # decision B284: an unloaded offset subtracted, with one line
    u = det.unit[0]  # "f" or "w": the unit's inertial streams (+ the force sensors of accel-force)
    warn_gaps(session, [f"{u}Accelerometer", f"{u}Gyroscope", *(("fForceA", "fForceB") if "force" in det.name else ())],
              "no step is detected inside them (recall counts the labelled ones as missed) - re-record or trim "
              "the session")
    try:
        table = det.detect(session)
    except DataError as exc:  # decision W61, as `track`: a waist unit with too little walking for its frame
        if det.unit != "waist" or getattr(exc, "walk_s", None) is None:
            raise
        import logging

        import pandas as pd

        from pdrlearn.track.waist import no_walking_message

        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, no_walking_message(exc.walk_s, "0 steps"))
        table = pd.DataFrame({"start_s": [], "end_s": [], "event_s": [], "unit": pd.Series(dtype="string"),
                              "confidence": []})
    if det.unit == "foot":
        foot_checks(session, table, det.name, force=reads_force(det))
    report(session, table, name=det.name, unit=det.unit, tolerance=tolerance, out=out, was=was, as_json=as_json,
           detector=det, time_origin=time_origin, ref_offset=ref_offset,
           events_out=events_out, pedalling="keep" if keep_pedalling else "drop")


def _events_file(events_out: Path | None, out: Path | None, force: bool) -> Path | None:
    """Decision steps 59: ``--events-out`` checked as an output CSV before any work, not the same file as ``--out``."""
    if events_out is None:
        return None
    events_out = out_file(events_out, (".csv",), "events", force=force)
    if out is not None and events_out.resolve() == out.resolve():
        raise DataError(f"--events-out {events_out}: the same file as --out; give the events table its own name")
    return events_out


def _tared(session, name: str):
    """Decision B284: ``session`` with its force sensors' unloaded offset subtracted (and the line logged); steps
    decision 74 first: a dead force channel left out (and named); decision B409: detector ``name`` (chosen by name:
    `auto` reads no force) refused in one line when no force channel is left; steps decision 78: also when the one
    left is a lone heel that L365's check rejects."""
    import logging

    from pdrlearn.displace.force_channels import live_force, lone_heel_rejected, no_force_left
    from pdrlearn.displace.force_check import tared
    from pdrlearn.orient import unit_data

    refused = no_force_left(session, f"--detector {name}")
    if refused:
        raise DataError(refused)
    session, dead = live_force(session)
    if dead:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, dead)
    session, line = tared(session, unit_data(session, "foot", purpose="the force sensors' unloaded offset"))
    if line:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    refused = lone_heel_rejected(session, unit_data(session, "foot", purpose="the insole check"),  # steps 78
                                 f"--detector {name}")
    if refused:
        raise DataError(refused)
    return session


def reads_force(detector) -> bool:
    """Decision steps 52: whether a foot detector reads the force sensors (its ``input_columns``); None (a table of
    unknown origin, score-steps) counts as reading them, as ``track``'s stance does."""
    return detector is None or any("force" in c for c in getattr(detector, "input_columns", ()))


def foot_checks(session, table, name: str, *, force: bool = False) -> None:
    """Decisions B201, B203: a foot detector's warnings from the foot unit's rests: the accelerometer's scale
    off 1 g, and no stride found on a foot that walks (or a frozen IMU beside force sensors that step); with
    ``force`` (a detector that reads them) decision L365's line when the force sensors disagree with the IMU."""
    import logging

    from pdrlearn.track.foot_rest import foot_rest_stats, foot_scale_warning, frozen_foot_imu, no_strides_warning

    stats = foot_rest_stats(session)
    lines = [foot_scale_warning(stats, session.where)]
    if force:
        from pdrlearn.displace.force_check import checked_stance
        from pdrlearn.orient import unit_data

        foot = unit_data(session, "foot", purpose="the rests between strides")
        lines += [f"{session.where}: {w}" for w in checked_stance(
            session, foot, fix="count on the IMU alone with --detector accel (decision steps 52)")[2]]
    if not len(table):
        lines.append(frozen_foot_imu(session) or no_strides_warning(stats, session.where, name))
    for line in lines:
        if line:
            logging.getLogger("pdrlearn.cli").warning("%s", line)


def report(session, table, *, name: str, unit: str, tolerance: float, out: Path | None = None, was: bool = False,
           as_json: bool = False, per_stride: bool = True, detector=None, time_origin: str = "session",
           ref_offset: float = 0.0, events_out: Path | None = None, pedalling: str | None = None) -> None:
    """Score ``table`` against ``session``'s labels and print the result (``steps`` and ``score-steps``): a foot
    table is first reduced to one row per rest-to-rest stride (decision steps 34) unless ``per_stride`` is False,
    with one warning when the kept rows cover many more rest-to-rest strides (decision steps 38; ``detector``, when
    given, names its shortest stride there); ``out`` gets the scored table, its times on the session's clock or
    with ``time_origin="export"`` on the imported export's (decision E173); ``ref_offset``: the reference clock
    minus the IMU clock (decision steps 56); ``events_out`` gets the events table (decision steps 59).
    ``pedalling`` (decision L625; a foot table, one row per stride): ``"drop"`` leaves L611's pedalling strides out
    of the table, ``"keep"`` keeps them with a ``pedalling`` column, each with one line; None: not judged."""
    import logging

    from pdrlearn.atomic import atomic_file
    from pdrlearn.steps.evaluate import score_steps_events, unscored_reason
    from pdrlearn.steps.reference_clock import offset_line
    from pdrlearn.steps.strides import one_per_stride_counted

    merged = spanned = 0
    # decision steps 52: a detector that reads no force (accel) counts on the foot IMU's own rests; a force-reading
    # one, or a table of unknown origin (score-steps), on track's checked force stance (L365)
    force = reads_force(detector)
    detections = table  # review R1 F1: L611 / L639 judge the strides of the detector's whole table, as track does
    if unit == "foot" and len(table) and per_stride:  # decision steps 34: one row per rest-to-rest stride, as `track`
        table, merged, spanned = one_per_stride_counted(table, session, force=force)
    pedalled = pedalled_rest = 0
    if unit == "foot" and per_stride and pedalling is not None:  # decision L625: L611's pedalling, as track
        table, pedalled, pedalled_rest = _pedalling(session, table, detections, pedalling == "keep", force)
        if pedalled_rest:  # the rests the left-out rows covered are no merged strides
            spanned -= pedalled_rest - pedalled
    result: dict = {"session": session.name, "detector": name, "unit": unit, "count": int(len(table))}
    if pedalling is not None and unit == "foot" and per_stride:
        result["pedalling_strides"] = pedalled
    if merged:
        result["merged_detections"] = merged
    if spanned:  # decision steps 38: strides merged into one detection (track splits them at the rests)
        result["rest_strides"] = int(len(table)) + spanned
    own = None
    # decision steps 47: the foot's own rest-and-swing count; steps 62: also when the detector found nothing (a
    # vibrating belt: "0 strides" without a word before)
    if unit == "foot" and per_stride:
        from pdrlearn.steps.strides import swinging_rest_strides

        own = swinging_rest_strides(session, force=force) - pedalled_rest  # L625: a crank's swings are no walk
        if own > len(table):
            result["foot_swing_strides"] = own
    # decision steps 47: more than steps 38's fraction of the foot's strides lie outside any detection
    # (none when it found nothing: B201's "found no strides" line says so, steps 62)
    missed = own is not None and len(table) > 0 and own - len(table) - spanned > MERGED_WARN_FRAC * own
    if missed or spanned > MERGED_WARN_FRAC * (len(table) + spanned):
        import logging

        line = (short_warning(name, len(table), spanned, own) if missed
                else spanned_warning(len(table), spanned, detector, session.has("fForceA", "fForceB")))
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    range_line = cadence_range_warning(table, session.meta, unit)  # decision steps 44
    if range_line:
        import logging

        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, range_line)
    if unit == "waist" and name != "pelvic-gyro" and len(table) >= 2:  # decision W476: W442's count cross-check
        from pdrlearn.waist.pelvic_rhythm import read_once
        from pdrlearn.waist.plausibility import step_counts, uncountable_steps_line

        gyro_s = read_once(detector, session)  # decision W485: the ones --detector pll read for its band, if it did
        line = uncountable_steps_line(step_counts(session, table["event_s"].to_numpy(float), gyro_s=gyro_s), name)
        if line:
            import logging

            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    score, events = score_steps_events(table, session, tolerance_s=tolerance, unit=unit, ref_offset_s=ref_offset)
    if score is not None:  # decision steps 41: score_steps' own dict, keys and meanings (one_foot: W96)
        result.update(score)
        line = offset_line(score, score["reference_count"], tolerance)  # decision steps 56
        if line:
            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    else:
        why = unscored_reason(session, unit)  # decision steps 58
        if why:
            result["not_scored"] = why
    if events_out is not None and score is None:
        raise DataError(f"--events-out {events_out}: {session.where} has no reference for the {unit}'s events "
                        "(steps.csv or ics.csv); nothing written (decision steps 59)")
    if events_out is not None and not score["ground_truth"]:  # decision steps 59 (amended, review R2)
        raise DataError(f"--events-out {events_out}: {session.where}'s reference is {score['reference']}, "
                        "not event times to table; nothing written, leave "
                        "--events-out out (decision steps 59)")
    from pdrlearn.table_csv import write_table_csv
    from pdrlearn.track.clock import export_origin_s, on_export_clock

    origin = export_origin_s(session.meta)
    if events_out is not None:
        if time_origin == "export":  # decision steps 59 (amended, review R2): on --out's clock, E173
            events = events_on_clock(events, origin)
        was_events = existed(events_out)
        with atomic_file(events_out) as tmp:
            write_table_csv(events, tmp)  # decision C103: as track's tables, no float noise
        replaced(events_out, was_events)
        result["events_out"] = str(events_out)
    if origin is not None:  # decision E173: where the session's 0 s lies on the imported export's clock
        result["time_origin_s"] = origin
    if out is not None:
        written = on_export_clock(table, origin) if time_origin == "export" else table
        with atomic_file(out) as tmp:
            write_table_csv(written, tmp)  # decision C103: 8.7, not 8.700000000000001
        replaced(out, was)
        result["out"] = str(out)
        result["out_clock"] = time_origin
    if as_json:
        print_json(json_safe(result))
        return
    what = "strides" if unit == "foot" else "steps"
    typer.echo(f"{session.name}: {result['count']} {what} ({name})"
               + (f"; {merged} more detection(s) between the same two rests of the foot dropped (one stride each, "
                  "as `track` integrates it; decision steps 34)" if merged else "")
               + (f"; the foot's own rests and swings segment {result['foot_swing_strides']} (decision steps 47)"
                  if "foot_swing_strides" in result else ""))
    if score is not None:
        typer.echo(f"reference: {score['reference_count']} from {score['reference']}")
        if score.get("one_foot"):  # decision W96: a lower-back detector against one foot's strides
            typer.echo(f"recall {score['recall']:.3f} of the {score['one_foot']} foot's {score['reference_count']} "
                       f"contacts ({score['true_positives']} found, tolerance {tolerance:g} s); precision, F1 and "
                       f"count error not scored: the other foot's steps are not labelled")
    if score is not None and not score.get("one_foot"):
        typer.echo(f"precision {score['precision']:.3f}  recall {score['recall']:.3f}  F1 {score['f1']:.3f}  "
                   f"count error {score['count_error_pct']:.1f} %  (tolerance {tolerance:g} s, "
                   f"{score['outside_labels']} detections outside the labelled span"
                   + (f", {score['unscored_untimed']} standing for contacts without a time"
                      if score["unscored_untimed"] else "")
                   + (f", {score['unscored_same_foot_gap']} in same-foot reference gaps (F1 "
                      f"{score['f1_same_foot_gaps_scored']:.3f} counting them)"
                      if score["unscored_same_foot_gap"] else "") + ")")
        if score["ground_truth"]:
            typer.echo(f"timing error {score['timing_error_mean_s']:+.3f} +- {score['timing_error_sd_s']:.3f} s "
                       f"(detected - reference, mean +- SD over the {score['true_positives']} matched pairs)")
    if score is not None:
        for line in score_notes(score, tolerance):
            typer.echo(line)
    elif "not_scored" in result:
        typer.echo(result["not_scored"])
    if unit == "waist" and detector is not None:  # decisions W281, W297: why `track` can count fewer
        typer.echo(track_count_note(session, table))
    if out is not None and origin:  # decision E173
        clock = ("on the export's clock (--time-origin export)" if time_origin == "export"
                 else "from the session's first sample (add it back, or pass --time-origin export)")
        files = f"{out} and {events_out}" if events_out is not None else str(out)
        typer.echo(f"note: {files}: times in s {clock}; the session's 0 s is {origin:.3f} s on the imported "
                   f"export's clock ({decision_ref('E173')})", err=True)  # decision D49
    for path in (events_out, out):
        if path is not None:
            typer.echo(str(path))


def _pedalling(session, table, detections, keep: bool, force: bool):
    """Decision L625: ``(table, rows, rest)``: a foot table without L611's pedalling strides (``keep``: with them,
    marked in a ``pedalling`` column), how many rows were pedalling and the rest-to-rest strides they cover (0 with
    ``keep``: nothing left out); their one line logged. ``detections``: the detector's whole table, ``force``: on
    track's force stance (review R1 F1)."""
    import logging

    from pdrlearn.track.pedalling import pedalling_rows

    rows, rest, line = pedalling_rows(session, table, detections, kept=keep, force=force)
    if line:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    if keep:
        return table.assign(pedalling=rows), int(rows.sum()), 0
    return table[~rows].reset_index(drop=True), int(rows.sum()), rest


def events_on_clock(events, origin: float | None):
    """Decision steps 59 (amended, review R2): the events table's ``detected_s`` and ``reference_s`` on the imported
    export's clock (``origin`` added, decision E173), as ``--out`` writes them with ``--time-origin export``."""
    if origin is None:
        return events
    from pdrlearn.track.clock import on_export_clock

    return on_export_clock(events, origin, ("detected_s", "reference_s"))


def score_notes(score: dict, tolerance: float) -> list[str]:
    """The lines after the scores: the toe-offs' (decision steps 59), the pauses of an ics.csv reference without
    bouts.csv (decision steps 57) and the reference offset given (decision steps 56)."""
    lines = []
    if "tc_f1" in score:
        lines.append(f"toe-offs: precision {score['tc_precision']:.3f}  recall {score['tc_recall']:.3f}  F1 "
                     f"{score['tc_f1']:.3f} of {score['tc_reference_count']} (tolerance {tolerance:g} s); timing "
                     f"error {score['tc_timing_error_mean_s']:+.3f} +- {score['tc_timing_error_sd_s']:.3f} s")
    if score.get("reference_span_only") and score["reference_pauses"]:
        a, b = score["reference_start_s"], score["reference_end_s"]
        lines.append(f"scored over {a:.1f}-{b:.1f} s (first to last reference contact); no bouts.csv: the "
                     f"{score['reference_pauses']} pause(s) of the reference longer than 3 s are scored too, and "
                     f"{score['pause_detections']} detection(s) in them count as false positives; add bouts.csv "
                     "(start_ms,end_ms of each walking bout) to score the walking only (decision steps 57)")
    if score.get("ref_offset_s"):
        off = score["ref_offset_s"]
        lines.append(f"reference times moved by {-off:+g} s (--ref-offset {off:g}: the reference clock minus the IMU "
                     "clock; decision steps 56)")
    return lines


#: decision W281: `steps` prints a lower-back detector's contacts; `track` keeps those of walking (trial s32 finding 4)
TRACK_COUNT_NOTE = ("note: these are the detector's contacts; `pdrlearn track` keeps walking contacts only (it drops "
                    "those of a rise, a sit or a bend, W104 / W185, and on waist-pendulum of standing sway, W189), "
                    "so its steps.csv can count fewer (W281)")


#: decision W297: at most this many transfer contacts' times are listed in the note
NOTE_TIMES = 10


def track_count_note(session, table) -> str:
    """Decisions W281, W297: the note after a lower-back detector's count. `steps` keeps counting (and scoring) the
    detector's raw contacts; when `track`'s default sit veto drops some of them at the chair transfers it finds
    (:func:`pdrlearn.track.waist.transfer_contacts`: W104 / W185, W277's upright without walking), the note names
    how many and when, and the transfers; else W281's general note."""
    from pdrlearn.track.waist import transfer_contacts
    from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT

    try:
        dropped, transfers = transfer_contacts(table, session) if len(table) else ((), None)
    except DataError:  # W61: no frame to read the trunk in: the general note
        dropped, transfers = (), None
    if not len(dropped):
        return TRACK_COUNT_NOTE
    kinds = transfers["kind"].tolist() if transfers is not None and len(transfers) else []
    times = ", ".join(f"{t:.1f}" for t in dropped[:NOTE_TIMES]) + (", ..." if len(dropped) > NOTE_TIMES else "")
    verb = "lies" if len(dropped) == 1 else "lie"
    return (f"note: these are the detector's contacts; {len(dropped)} of them (at {times} s) {verb} at the trunk "
            f"flexion of a rise, a sit or a bend ({kinds.count(SIT_TO_STAND)} sit-to-stand, "
            f"{kinds.count(STAND_TO_SIT)} stand-to-sit found; W104 / W185, W277): `pdrlearn track` drops them as no "
            "walking (and on waist-pendulum standing sway, W189), so its steps.csv counts fewer; `steps` counts and "
            "scores the detector's own contacts (W281, W297)")


def spanned_warning(count: int, spanned: int, det, has_force: bool = False) -> str:
    """Decision steps 38: the line when ``spanned`` more rest-to-rest strides of the foot lie inside the ``count``
    detections (one detection across several strides: strides merged, e.g. a child's shorter than the detector's
    shortest stride, or too weak a swing between two); ``det``: the detector (its ``min_stride_s`` when it has one).
    Decision steps 43: the rest-to-rest count is what a track from the foot IMU alone gives; with force sensors
    (``has_force``) `track` takes its strides from them, so the line names the foot-IMU-only track instead."""
    shortest = getattr(det, "min_stride_s", None)
    why = (f"strides shorter than the detector's {shortest:g} s shortest stride, or swings below its threshold"
           if shortest is not None else "swings below the detector's threshold")
    head = (f"the {count} detected strides cover {count + spanned} rest-to-rest strides of the foot: {spanned} "
            f"stride(s) merged into their neighbours ({why}); ")
    if has_force:  # decision steps 43: `track DIR` counts this session's force-sensor contacts, not the rests
        return head + ("a track from the foot IMU alone (`pdrlearn track DIR --method M1`) splits them at the rests "
                       f"(decision L96) and counts {count + spanned}; `pdrlearn track DIR` takes this session's "
                       "strides from its force sensors instead (decisions steps 38, steps 43)")
    return head + ("`pdrlearn track DIR` splits them at the rests (decision L96) and counts "
                   f"{count + spanned} (decision steps 38)")


def short_warning(name: str, count: int, spanned: int, own: int) -> str:
    """Decision steps 47: the line when a foot detector ``name`` kept ``count`` strides, more than
    :data:`MERGED_WARN_FRAC` of the ``own`` rest-to-rest strides in which the foot swings
    (:func:`pdrlearn.steps.strides.swinging_rest_strides`) outside any detection, ``spanned`` more merged into a
    neighbour's (B201's "found no strides" line, for a detector that found some; it replaces steps 38's line,
    which counts only the merged ones)."""
    import numpy as np

    from pdrlearn.kernels.units import FOOT_NO_SWING

    outside = own - count - spanned
    return (f"{name} kept {count} strides, but the foot's own rests and swings segment {own} (rest-to-rest strides "
            f"swinging over {np.degrees(FOOT_NO_SWING):.0f} deg/s): {own - count} missed ("
            + (f"{spanned} merged into a neighbour's detection, " if spanned else "")
            + f"{outside} outside any detection): its thresholds did not fire (foot vibration, a weak or odd swing); "
            "`pdrlearn track DIR` segments the strides at the foot's rests (decisions B201, steps 47)")


def cadence_range_warning(table, meta: dict | None, unit: str) -> str | None:
    """Decision steps 44: L95's walking-range line (:func:`pdrlearn.track.gait.gait_range_warning`, leg-scaled by
    L148) on the cadence of the detections ``table`` (``event_s``, s): a foot table's strides give 120 / their
    median stride time (L176's formula), a waist table's too, over two consecutive steps (W225); intervals longer than
    :data:`pdrlearn.kernels.contact.MAX_STRIDE_S` (half of it for a step) are pauses, not strides. Only the cadence
    is judged (no speed without a track); None inside the range or with fewer than L123's minimum intervals."""
    from pdrlearn.track.gait import contact_cadence_spm, gait_range_warning, leg_length

    if "event_s" not in table or len(table) < 2:
        return None
    cad = contact_cadence_spm(table["event_s"].to_numpy(float), unit)  # shared with track's L431
    if cad is None:
        return None
    line = gait_range_warning({"median_cadence_spm": cad, **leg_length(meta)})
    if line is None:
        return None
    return (f"the detected {'strides' if unit == 'foot' else 'steps'}: {line}; the step detectors are validated in "
            "that range too (decision steps 44)")


def score_steps_command(
    session_dir: Path = typer.Argument(..., help="PLASYS session folder with labels (steps.csv or ics.csv)."),
    detections: Path = typer.Argument(..., help="Detections CSV: event_s (s since the session's first sample); "
                                      "start_s, end_s for a foot table; unit (foot | waist) or --unit."),
    unit: str = typer.Option(None, "--unit", help="foot (strides of the instrumented foot, scored against "
                             "steps.csv) or waist (every step, scored against ics.csv); default: the CSV's unit "
                             "column."),
    tolerance: float = typer.Option(0.25, "--tolerance", help="Event matching tolerance in seconds."),
    all_rows: bool = typer.Option(False, "--all-rows", help="Score every row of a foot table (default: one per "
                                  "rest-to-rest stride, as `pdrlearn steps`; decision steps 34)."),
    ref_offset: float = typer.Option(0.0, "--ref-offset", help=REF_OFFSET_HELP),
    events_out: Path = typer.Option(None, "--events-out", help=EVENTS_OUT_HELP),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object."),
    keep_pedalling: bool = typer.Option(False, "--keep-pedalling", help="A foot table: score the strides that go "
                                        "round a closed loop (cycling?) as steps, which score-steps leaves out by "
                                        "default, as steps does (decisions L611, L625, steps 85)."),
) -> None:
    """Score an existing detections CSV (your own detector's, or `pdrlearn steps --out`'s) against a session's
    labels, with the rules of `pdrlearn steps` (decision steps 39): a foot table is first reduced to one row per
    rest-to-rest stride (pdrlearn.steps.one_per_stride) unless --all-rows, and its pedalling strides (a bike ride's
    crank turns, L611) are left out with one line unless --keep-pedalling (decision steps 85).

    Examples:

        pdrlearn score-steps out/sim/D_u1 out/D_steps.csv

        pdrlearn score-steps out/sim/D_u1 out/D_steps.csv --all-rows --tolerance 0.1 --json

        pdrlearn score-steps out/sim/D_u1 out/D_steps.csv --ref-offset 5 --events-out out/D_events.csv   # a Vicon
        clock 5 s ahead of the IMU's; one row per event for Bland-Altman plots (decisions steps 56, 59)
    """
    from pdrlearn.io import read_session
    from pdrlearn.steps.evaluate import check_tolerance
    from pdrlearn.steps.reference_clock import check_ref_offset

    check_tolerance(tolerance, "--tolerance")  # decision B167
    check_ref_offset(ref_offset, "--ref-offset")  # decision B333
    events_out = _events_file(events_out, None, force)
    table, unit = read_detections(detections, unit=unit, per_stride=not all_rows)
    if keep_pedalling and (unit != "foot" or all_rows):  # decision steps 85: L611 judges a foot's strides
        raise DataError(f"--keep-pedalling: {detections} " + ("holds lower-back steps, and the pedalling check "
                        "(decision L611) reads a foot unit's strides" if unit != "foot" else "is scored row by row "
                        "with --all-rows, which judges no pedalling") + "; leave --keep-pedalling out")
    session = read_session(session_dir)
    report(session, table, name=detections.name, unit=unit, tolerance=tolerance, as_json=as_json,
           per_stride=not all_rows, ref_offset=ref_offset, events_out=events_out,
           pedalling="keep" if keep_pedalling else "drop")  # decision steps 85: as steps (L625)


def read_detections(path: Path, *, unit: str | None = None, per_stride: bool = True):
    """A detections CSV as a steps table (times in s) and its unit; bad input: one line naming the file."""
    import pandas as pd

    if not path.is_file():
        raise DataError(f"{path}: no such file; give the detections CSV (event_s column, times in s)")
    try:
        table = pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise DataError(f"{path}: not a readable CSV ({' '.join(str(exc).split())}); write it with a header row "
                        "and an event_s column") from None
    if "event_s" not in table:
        hint = " (times in ms: divide by 1000 and name the column event_s)" if "event_ms" in table else ""
        raise DataError(f"{path}: no event_s column{hint}; give each detection's time in s since the session's "
                        f"first sample (columns: {', '.join(map(str, table.columns))})")
    units = sorted(set(table["unit"].dropna().astype(str))) if "unit" in table else []
    if unit is None:
        if len(units) != 1:
            raise DataError(f"{path}: " + (f"the unit column holds {', '.join(units)}; score one unit's rows"
                                           if units else "no unit column") + "; pass --unit foot or --unit waist")
        unit = units[0]
    from pdrlearn.steps.base import STEP_UNITS

    if unit not in STEP_UNITS:  # decision B168's units
        raise DataError(f"{path}: unit '{unit}' is not foot or waist; pass --unit foot or --unit waist")
    for col in ("event_s", "start_s", "end_s"):
        if col in table and not pd.api.types.is_numeric_dtype(table[col]):
            raise DataError(f"{path}: column {col} is not numeric; give times in s")
    if unit == "foot" and per_stride and not {"start_s", "end_s"} <= set(table.columns):
        raise DataError(f"{path}: a foot table needs start_s and end_s (each stride's span, s) to keep one row per "
                        "rest-to-rest stride; add them or pass --all-rows")
    table = table.copy()
    table["unit"] = unit
    return table, unit


def auto_detector(session):
    """The detector of ``--detector auto``: a foot unit's strides, else the lower back's steps (decision 17);
    also ``pdrlearn plot --steps detected`` (decision L70)."""
    from pdrlearn.steps import get_detector
    from pdrlearn.track.base import warn_foot_unit_ignored

    warn_foot_unit_ignored(session, "detecting the waist's steps")  # decision B204
    return get_detector("accel" if session.has("fAccelerometer") or not session.has("wAccelerometer")
                        else "waist-ic" if session.has("wGyroscope") else "pll")


def register(app: typer.Typer) -> None:
    app.command("steps")(steps)
    app.command("score-steps")(score_steps_command)
