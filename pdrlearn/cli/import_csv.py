"""``pdrlearn import``: a one-CSV lab export -> a session folder (decision D12)."""
# ruff: noqa: B008  (typer options are declared as defaults)

from __future__ import annotations

import json
from pathlib import Path

import typer

from pdrlearn.cli.common import non_session_files, print_json, split_list
from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError, shell_quote
from pdrlearn.textfile import read_json

#: decision B468: --drop-duplicate-timestamps dropping more than this share of a stream's rows is said
DROPPED_SHARE_NOTE = 0.01


def _mapping_file(path: Path | None) -> dict:
    """The ``--mapping`` JSON: ``{"time": COL, "acc": [X, Y, Z], "gyro": [...], "units": {"time": "ms",
    "acc": "g", "gyro": "deg/s"}, "unit": "waist", "frames": {...}, "sensor_height_m": 0.95}`` (all optional)."""
    if path is None:
        return {}
    try:
        m = read_json(Path(path))
    except OSError as exc:
        raise DataError(f"{path}: cannot read the mapping file ({exc.strerror})") from None
    except json.JSONDecodeError as exc:
        raise DataError(f"{path}: invalid JSON (line {exc.lineno}); fix the mapping file") from None
    if not isinstance(m, dict):
        raise DataError(f"{path}: the mapping must be a JSON object such as {{\"acc\": [\"ax\", \"ay\", \"az\"]}}")
    known = {"time", "acc", "gyro", "mag", "baro", "heel", "toe", "units", "unit", "frames", "sensor_height_m",
             "height_m", "leg_length_m"}
    unknown = sorted(set(m) - known)
    if unknown:
        raise DataError(f"{path}: unknown key(s) {', '.join(unknown)}; the mapping takes {', '.join(sorted(known))}")
    return m


#: what ``pdrlearn import`` may replace with --force, and what --merge may rewrite: the files a session
#: folder holds (sensor CSVs, label CSVs, meta.json); anything else in the folder would be lost
_session_files_only = non_session_files


def _import_written(meta: dict) -> set[str]:
    """The files an earlier ``pdrlearn import`` wrote into its folder, from its ``meta.json["imported"]``
    record(s): the sensor files, steps.csv when labels were imported (--steps), meta.json (decision D12)."""
    recs = meta.get("imported")
    recs = recs if isinstance(recs, list) else [recs] if isinstance(recs, dict) else []
    out = {"meta.json"}
    for r in recs:
        if not isinstance(r, dict):
            continue
        out.update(f"{s}.csv" for s in (r.get("streams") or {}))
        if r.get("steps"):
            out.add("steps.csv")
        for f in (r.get("labels") or {}) if isinstance(r.get("labels"), dict) else ():
            out.add(f if str(f).endswith(".csv") else f"{f}.csv")
    return out


def import_command(
    csv: Path = typer.Argument(..., help="The lab export: one CSV with a timestamp column and channel columns, or "
                               "a MATLAB v5/v7 .mat file of N x 3 arrays (B335)."),
    out: Path = typer.Option(..., "--out", "-o", help="Session folder to write (or, with --merge, to add to)."),
    unit: str = typer.Option(None, "--unit", help="Which unit the channels are: foot or waist (default foot)."),
    time: str = typer.Option(None, "--time", help="Timestamp column (default: the one named like a time)."),
    acc: str = typer.Option(None, "--acc", help="Accelerometer columns X,Y,Z (default: guessed from the names); -NAME "
                            "negates a column, e.g. --acc=-ax,-ay,-az for an iOS export (gravity -1 g, decision B48)."),
    gyro: str = typer.Option(None, "--gyro", help="Gyroscope columns X,Y,Z (default: guessed; -NAME negates one)."),
    mag: str = typer.Option(None, "--mag", help="Magnetometer columns X,Y,Z (waist; default: guessed)."),
    baro: str = typer.Option(None, "--baro", help="Barometer column (waist, hPa; default: guessed)."),
    heel: str = typer.Option(None, "--heel", help="Heel force column (foot; default: guessed)."),
    toe: str = typer.Option(None, "--toe", help="Forefoot force column (foot; default: guessed)."),
    mapping: Path = typer.Option(None, "--mapping", help="JSON file with the column mapping, units, unit and "
                                 "frames (the options override it)."),
    time_unit: str = typer.Option(None, "--time-unit", help="ms, s, us or ns (default: the header's '(ms)', else "
                                  "inferred from the sampling rate, decision B22)."),
    rate: float = typer.Option(None, "--rate", help="The time column holds sample numbers (0, 1, 2 ...) at this "
                               "rate in Hz (decision B39; consecutive integers are refused without it or "
                               "--time-unit); with no time column at all (acc_x ... gyr_z only, gaitmap / "
                               "NilsPod style), the rows are at this rate from t = 0 (B323); with date-times "
                               "that lost their milliseconds, the rows at this rate, placed by them (B84, B111; "
                               "refused on date-times with milliseconds)."),
    time_format: str = typer.Option(None, "--time-format", help="Format of a date-time text column, e.g. "
                                    "'%d/%m/%Y %H:%M:%S' (needed when day and month cannot be told apart, B43)."),
    time_zone: str = typer.Option(None, "--time-zone", help="Zone of date-time text without one, e.g. +01:00 or "
                                  "Europe/Berlin (default: UTC, said in the summary; B43)."),
    acc_unit: str = typer.Option(None, "--acc-unit", help="m/s2, g or mg, or raw counts as the size of one "
                                 "count and a unit, '1/2048 g', as meta.json's units (B313) (default: the header's "
                                 "'(g)' or '_g', else m/s2)."),
    gyro_unit: str = typer.Option(None, "--gyro-unit", help="rad/s or deg/s, or the size of one count, '1/16.4 "
                                  "deg/s' (B313) (default: the header's, else rad/s)."),
    acc_range: str = typer.Option(None, "--acc-range", help="The accelerometer's full scale from its datasheet, e.g. "
                                  "'4 g' (meta.json full_scale): clipping is judged at it, samples within 5 % of it "
                                  "count (decision B456)."),
    gyro_range: str = typer.Option(None, "--gyro-range", help="The gyroscope's full scale, e.g. '500 deg/s' "
                                   "(meta.json full_scale; decision B456)."),
    heel_unit: str = typer.Option(None, "--heel-unit", help="The --heel force column's unit: N, kgf (kg, kp; x "
                                  "9.80665) or counts (raw ADC, unitless; B286) (default: the header's '(kg)' or "
                                  "'_kg', '_N', '_adc', else N; B397)."),
    toe_unit: str = typer.Option(None, "--toe-unit", help="The --toe force column's unit, as --heel-unit (B397)."),
    frames: str = typer.Option(None, "--frames", help="The unit's axes, e.g. x=forward,y=up,z=right (default: "
                               "none; commands infer it from the data, decision D8)."),
    sensor_height: float = typer.Option(None, "--sensor-height", help="The waist unit's height above "
                                        "the ground (m), written to meta.json sensor_height_m: the waist pendulum's "
                                        "leg length (W10) only without --leg-length, which is taken first (B155; "
                                        "the import says so, B462); refused with --unit foot (B175)."),
    subject_height: float = typer.Option(None, "--subject-height", help="The subject's height (m), written to "
                                         "meta.json height_m (default: none; commands assume 1.7 m and say so)."),
    leg_length: float = typer.Option(None, "--leg-length", help="The subject's leg length (m, greater-trochanter "
                                     "height), written to meta.json leg_length_m: a child's measured leg scales "
                                     "the walking range (L148) and the waist pendulum (B390)."),
    steps: Path = typer.Option(None, "--steps", help="Labelled steps (start_ms,end_ms,terrain,... as steps.csv) in "
                               "ms on the export's clock; written as the session's steps.csv. A list of initial "
                               "contacts only (ic_ms, optional foot or side column: --foot picks) becomes strides "
                               "from contact to contact, pre_ic_ms the opening one (mocap events, B338); a "
                               "walkway's tc_ms and length_m per footfall go on those strides (D51)."),
    labels: list[Path] = typer.Option(None, "--labels", help="An extra label table (ics.csv, bouts.csv, turns.csv "
                                      "...: *_ms columns on the export's clock), shifted as --steps and written "
                                      "under its file name; repeat for each (lower-back scoring uses ics.csv and "
                                      "bouts.csv)."),
    labels_relative: bool = typer.Option(False, "--labels-relative", help="The --steps and --labels times are "
                                         "ms from this export's first sample (also with --merge), not on the "
                                         "export's clock (B42)."),
    labels_offset: float = typer.Option(0.0, "--labels-offset", help="The --steps and --labels times' clock minus "
                                        "the export's, s (a Vicon clock reading the IMU's + 5 s: 5): each time t is "
                                        "imported at t - SECONDS; the sign of steps --ref-offset (decision steps "
                                        "56)."),
    skip_rows: int = typer.Option(None, "--skip-rows", help="Rows directly under the header that are not data "
                                  "(default: a units row such as ms, m/(s^2), deg/s is recognised, skipped and read "
                                  "for the units; B66)."),
    force_frame: bool = typer.Option(False, "--force-frame", help="Write the --frames axes even when the data "
                                     "contradict them (refused otherwise, B67)."),
    foot: str = typer.Option(None, "--foot", help="The foot the unit is on, left or right, written to meta.json "
                             "\"foot\" (pdrlearn gait checks the side given against it; B321)."),
    subject: str = typer.Option(None, "--subject", help="The subject's id, written to meta.json \"subject\" "
                                "(sessions.csv and subjects.csv group by it; B345)."),
    visit: str = typer.Option(None, "--visit", help="The visit's name, written to meta.json \"visit\" (track-all "
                              "pairs each subject's visits by it in changes.csv; B364)."),
    encoding: str = typer.Option(None, "--encoding", help="The CSV's text encoding, e.g. cp1252 (German Excel's "
                                 "plain 'CSV (Trennzeichen-getrennt)'; default utf-8, a BOM accepted), also of the "
                                 "--steps, --labels and --add-gravity tables that are not UTF-8 (B344)."),
    name: str = typer.Option(None, "--name", help="Session name, written to meta.json (default: the --out "
                             "folder's name; with --merge the session's own)."),
    merge: bool = typer.Option(False, "--merge", help="Add this unit to the existing session --out (the other "
                               "unit's files, labels and meta.json are kept)."),
    split_at_clock_reset: bool = typer.Option(False, "--split-at-clock-reset", help="The export's clock restarts "
                                              "(a jump back of over 1 s, B73): write one session per recording, "
                                              "--out/part1, --out/part2 ... (refused without it; not with --merge, "
                                              "--steps or --labels; B80)."),
    drop_duplicate_timestamps: bool = typer.Option(False, "--drop-duplicate-timestamps", help="Keep the first of "
                                                   "rows with the same timestamp (a phone app's batched samples; "
                                                   "refused otherwise, B150)."),
    sort_timestamps: bool = typer.Option(False, "--sort-timestamps", help="Sort the rows by timestamp first (a phone "
                                         "app's batched log writes some out of order; refused otherwise, B383)."),
    retime: float = typer.Option(None, "--retime", help="The sensor's output rate in Hz: re-time the samples at it, "
                                 "anchored to their stamps (a Bluetooth IMU's notifications carry several samples on "
                                 "one receive time; lost notifications are counted; B186)."),
    add_gravity: Path = typer.Option(None, "--add-gravity", help="A gravity file of the same recording (Sensor "
                                     "Logger's Gravity.csv) added to the --acc columns sample by sample, for an "
                                     "accelerometer written without gravity (iOS Sensor Logger's Accelerometer.csv; "
                                     "B166)."),
    no_header: bool = typer.Option(False, "--no-header", help="The CSV has no header line (MATLAB writematrix / "
                                   "csvwrite): its columns are named 0, 1, 2 ... (--time 0 --acc 1,2,3 --gyro 4,5,6); "
                                   "unmapped, 7 columns are time, acc, gyro and 6 acc, gyro with --rate (B336)."),
    no_acc: bool = typer.Option(False, "--no-acc", help="Write a waist session without an accelerometer (a phone's "
                                "gyroscope file imported first; add the accelerometer's file next with --acc X,Y,Z "
                                "--merge): every lower-back pipeline needs one, so without this it is refused "
                                "(B463)."),
    force: bool = typer.Option(False, "--force", help="Replace a session folder that 'pdrlearn import' wrote."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object with every mapping choice."),
) -> None:
    """Turn a one-CSV lab export into a session folder (fAccelerometer.csv, fGyroscope.csv, meta.json ...).

    Columns are guessed from common names (acc_x, ax, AccX, accelerometer_x, gyr_x, gx, GyroX, acc_x_g, and
    German ones: Zeit, Datum/Uhrzeit, Beschl. X, Drehrate X, Magnetfeld X, Luftdruck, B345 ...;
    units from hints such as 'AccX (g)', 'Time (ms)', 'gyr_x_dps' or 'time_s') unless given; every guess is
    printed on stderr and kept in meta.json ("imported"). Comma, semicolon and tab separated files with
    decimal commas are read (B24), and Shimmer Consensys exports: a 'sep=' first line, a units row under the
    header (ms, m/(s^2), deg/s: used for the units), Shimmer_XXXX_..._CAL names (B66). A --frames entry the
    data contradict is refused (--force-frame keeps it, B67). An export whose clock restarts (the time jumps
    back by over 1 s) is refused; --split-at-clock-reset writes each recording as its own session, OUT/part1,
    OUT/part2 ... (B80).
    Timestamps are written in ms since the export's first one (its value is kept in meta.json; --steps
    and --labels tables on the export's clock are shifted alike). Check the result with 'pdrlearn info'.

    Examples:

        pdrlearn import labx_export.csv --out sessions/walk1

        pdrlearn import export.csv --out sessions/walk1 --unit foot --acc ax,ay,az --gyro gx,gy,gz \\
            --time-unit s --acc-unit g --gyro-unit deg/s --frames x=forward,y=up,z=right

        pdrlearn import phone.csv --out sessions/walk1 --unit waist --merge --sensor-height 1.0

        pdrlearn import child.csv --out sessions/child1 --subject-height 1.25 --leg-length 0.62   # a child

        pdrlearn import lowback.csv --out sessions/lb1 --unit waist --steps strides.csv --labels ics.csv \\
            --labels bouts.csv --labels turns.csv

        pdrlearn import restarted.csv --out sessions/walk2 --split-at-clock-reset   # walk2/part1, walk2/part2

        pdrlearn import s01_left.csv --rate 204.8 --foot left --gyro-unit deg/s --out s01_left  # no time column

        pdrlearn import trial.mat --acc acc --gyro gyr --acc-unit g --gyro-unit deg/s --out s01  # data.acc, data.gyr

        pdrlearn import matrix.csv --no-header --time 0 --acc 1,2,3 --gyro 4,5,6 --out s01  # writematrix

        pdrlearn import insole.csv --heel heel --toe forefoot --heel-unit counts --toe-unit counts --out s02  # ADC
    """
    from pdrlearn.atomic import expect_unchanged
    from pdrlearn.io import read_session, write_session
    from pdrlearn.io.importer import (
        KINDS,
        import_csv,
        import_csv_parts,
        import_labels,
        import_steps,
        merge_offset_note,
        merge_sessions,
        merge_span_warning,
    )
    from pdrlearn.io.unit_check import assumed_unit_note, unit_mixup
    from pdrlearn.steps.reference_clock import check_ref_offset

    check_ref_offset(labels_offset, "--labels-offset")  # decision B333
    if labels_offset and steps is None and not labels:
        raise DataError("import: --labels-offset moves the --steps and --labels times; pass those tables, or leave "
                        "it out")
    m = _mapping_file(mapping)
    if leg_length is None and "leg_length_m" in m:  # decision B394: a bad mapping value is named as its key
        from pdrlearn.io.importer import check_leg_length

        given_height = subject_height if subject_height is not None else m.get("height_m")
        check_leg_length(m["leg_length_m"], given_height, f"{mapping}: \"leg_length_m\"",
                         "--subject-height" if subject_height is not None else "\"height_m\"")
    if force_frame and frames is None and m.get("frames") is None:  # decision B69: it would be ignored
        raise DataError(f"{csv}: --force-frame keeps a --frames entry the data contradict (B67), and none is given; "
                        "add --frames AXES (e.g. x=forward,y=up,z=right) or drop --force-frame")
    if split_at_clock_reset:  # decision B80: labels on a clock that restarted belong to which part? not known
        clash = [o for o, given in (("--merge", merge), ("--steps", steps is not None), ("--labels", bool(labels)),
                                    ("--labels-relative", labels_relative),
                                    ("--labels-offset", bool(labels_offset))) if given]
        if clash:
            raise DataError(f"{csv}: --split-at-clock-reset writes one session per recording and cannot take "
                            f"{', '.join(clash)} (which recording their rows belong to is not known); import without "
                            "them, then put each part's labels in its folder (ms from that part's first sample)")
    unit_given = bool(unit or m.get("unit"))  # decision B287: an assumed unit is said
    unit = unit or m.get("unit") or "foot"
    if no_acc and unit != "waist":  # decision B463: the option is the lower back's only
        raise DataError(f"{csv}: --no-acc writes a waist session without its accelerometer, and this is a {unit} "
                        "unit's import: add --unit waist, or drop --no-acc (decision B463)")
    columns: dict[str, list[str]] = {}
    for kind in KINDS:
        v = m.get(kind)
        if v is not None:
            columns[kind] = [v] if isinstance(v, str) else [str(c) for c in v]
    for kind, opt in (("acc", acc), ("gyro", gyro), ("mag", mag), ("baro", baro), ("heel", heel), ("toe", toe)):
        cols = split_list(opt, f"--{kind}")
        if cols is not None:
            columns[kind] = cols
    mu = m.get("units") or {}
    if not isinstance(mu, dict):
        raise DataError(f"{mapping}: \"units\" must be an object such as {{\"acc\": \"g\", \"gyro\": \"deg/s\"}}")
    units = {k: v for k, v in mu.items() if k != "time"}
    units.update({k: v for k, v in (("acc", acc_unit), ("gyro", gyro_unit), ("heel", heel_unit), ("toe", toe_unit))
                  if v is not None})  # decision B397: the force columns' units as options too
    # the output, checked before any work: never the input's folder, never a folder of other files
    src = csv.resolve()
    if out.exists() and not out.is_dir():
        raise DataError(f"{out}: is a file; --out must be a session folder")
    if out.is_dir() and src.is_relative_to(out.resolve()):
        raise DataError(f"{out}: holds the input {csv}; write the session to another folder")
    base = None
    if merge:
        if not out.is_dir():
            raise DataError(f"{out}: no such session folder to --merge into; import the first unit without --merge")
        base = read_session(out)
        other = _session_files_only(out)
        if other:
            raise DataError(f"{out}: holds {', '.join(other[:3])}, which a session rewrite would drop; move them "
                            "out first")
    elif out.is_dir() and any(out.iterdir()) and _split_written(out):  # decision B80: an earlier split import
        if not force:
            raise DataError(f"{out}: already holds the parts of an imported session; pass --force to replace them")
    elif out.is_dir() and any(out.iterdir()):
        meta = out / "meta.json"
        try:
            old_meta = read_json(meta)
            ours = "imported" in old_meta
        except (OSError, ValueError, TypeError):
            ours = False
        if not ours:
            raise DataError(f"{out}: exists and is not a session 'pdrlearn import' wrote; choose another --out "
                            "(or --merge to add a unit to it)")
        if not force:
            raise DataError(f"{out}: already holds an imported session; pass --force to replace it, or --merge "
                            "to add the other unit")
        # files added to the import's folder by hand (ics.csv, bouts.csv, a sub-folder ...) are never deleted
        # silently: decision B422's one check of every --force
        from pdrlearn.own_files import Own, refuse_foreign

        refuse_foreign(out, Own(tuple(sorted(_import_written(old_meta)))), "pdrlearn import")
    if merge or out.is_dir():
        expect_unchanged(out)  # decision B20: the replacement deletes only what was checked here
    origin = None
    if base is not None:  # a second export of the same clock goes onto the first one's origin
        recs = base.meta.get("imported")
        recs = recs if isinstance(recs, list) else [recs] if isinstance(recs, dict) else []
        origin = next((r["time"]["origin_s"] for r in recs if isinstance(r, dict)
                       and isinstance(r.get("time"), dict) and r["time"].get("origin_s") is not None), None)
    kw = dict(unit=unit, columns=columns, time_column=time or m.get("time"), time_unit=time_unit or mu.get("time"),
              units=units, frame=frames if frames is not None else m.get("frames"),
              sensor_height_m=sensor_height if sensor_height is not None else m.get("sensor_height_m"),
              name=name or (None if merge else out.name),
              subject_height_m=subject_height if subject_height is not None else m.get("height_m"),
              leg_length_m=leg_length if leg_length is not None else m.get("leg_length_m"),
              rate_hz=rate, time_format=time_format, time_zone=time_zone, skip_rows=skip_rows,
              drop_duplicate_timestamps=drop_duplicate_timestamps, sort_timestamps=sort_timestamps,
              add_gravity=add_gravity, retime_hz=retime,
              foot=foot, no_header=no_header, encoding=encoding, subject=subject,
              visit=visit)
    from pdrlearn.cli.import_fixes import import_with_fixes
    from pdrlearn.provenance import command_line

    if split_at_clock_reset:  # decision B438: every problem an option fixes, said in one message
        parts = import_with_fixes(lambda **k: import_csv_parts(csv, **k), kw, str(csv), command_line())
        _check_force_unit_used(csv, parts[0][1], heel_unit, toe_unit)  # decision B408, before any write
        for part, part_record in parts:
            _require_waist_acc(part, part_record, csv, no_acc)  # decision B463, before any write
        if len(parts) > 1:
            _write_parts(parts, csv, unit, out, force_frame, as_json)
            return
        session, record = parts[0]
    else:
        session, record = import_with_fixes(lambda **k: import_csv(csv, origin_s=origin, **k), kw, str(csv),
                                            command_line())  # decision B438
        _check_force_unit_used(csv, record, heel_unit, toe_unit)  # decision B408, before any write
    if steps is not None:
        if base is not None and base.steps is not None:
            raise DataError(f"{out}: already has steps.csv; --steps with --merge would replace it -- leave --steps out")
        session = import_steps(steps, session, record["time"]["origin_s"], relative=labels_relative, foot=foot,
                               offset_s=labels_offset, unit=unit, encoding=encoding)
        record["steps"] = {"file": Path(steps).name, "rows": len(session.steps)}
        if "from_ics" in session.steps.attrs:  # decision B338
            record["steps"]["from_ics"] = session.steps.attrs["from_ics"]
        if session.steps.attrs.get("footfall_columns"):  # decision D51
            record["steps"]["footfall_columns"] = session.steps.attrs["footfall_columns"]
    if labels_relative and steps is None and not labels:
        raise DataError("import: --labels-relative says how --steps and --labels times are written; pass those "
                        "tables, or leave it out")
    if labels_relative:
        record["labels_relative"] = True
    if labels_offset:
        record["labels_offset_s"] = labels_offset
    if labels:
        session, rows = import_labels(labels, session, record["time"]["origin_s"],
                                      taken=() if base is None else tuple(base.extras), relative=labels_relative,
                                      offset_s=labels_offset, encoding=encoding)
        record["labels"] = {f"{n}.csv": {"file": Path(p).name, "rows": rows[n]} for n, p in
                            zip(rows, labels, strict=True)}
    axes_warning = _check_axes(session, unit, record, csv)  # decision L71: before anything is written
    frame_warning = _check_frame(session, unit, record, csv, force_frame)  # decision B67: before writing too
    span_warning = offset_note = None
    if base is not None:
        span_warning = merge_span_warning(base, session)  # trial 2, finding 11 (decision D12)
        offset_note = None if span_warning else merge_offset_note(base, session)  # decision B83
        session = merge_sessions(base, session)
        mixup = unit_mixup(session)  # decision B91: before anything is written
        if mixup:
            raise DataError(f"{csv}: {mixup} (nothing written)")
    session = _declare_ranges(session, unit, acc_range, gyro_range)  # decision B456: before anything is written
    _require_waist_acc(session, record, csv, no_acc)  # decision B463: before anything is written
    existed = out.is_dir() and any(out.iterdir())
    write_session(session, out, overwrite=True)
    if not unit_given:  # decision B287: the assumed foot unit said, and a lower back's data named
        typer.echo(f"note: {csv}: {assumed_unit_note(session)}", err=True)
    if not as_json:
        _say(record, session, out, merge, existed)
        if split_at_clock_reset:
            typer.echo(f"note: {csv}: no clock reset found, so nothing to split: one session written to {out} "
                       f"({decision_ref('B80')})", err=True)  # decision D49
    else:
        print_json({"out": str(out), "merged": merge, "imported": record,
                    "frames": {p: f.to_dict() for p, f in session.frames.items()}})
    leg_line = _pendulum_leg_line(session.meta, sensor_height is not None or "sensor_height_m" in m,
                                  leg_length is not None or "leg_length_m" in m)
    if leg_line:  # decision B462: the dropped value said where it is dropped, not only in summary.json
        typer.echo(f"warning: {out}: {leg_line}", err=True)
    if span_warning:
        typer.echo(f"warning: {out}: {span_warning}", err=True)
    if offset_note:
        typer.echo(f"note: {out}: {offset_note}", err=True)
    if axes_warning:
        typer.echo(f"warning: {out}: {axes_warning}", err=True)
    if frame_warning:
        typer.echo(f"warning: {out}: {frame_warning}", err=True)
    _say_clipping(session, out)  # decisions B77, B456, B455: at once, as info / track will


def _declare_ranges(session, unit: str, acc_range: str | None, gyro_range: str | None):
    """Decision B456: ``--acc-range`` / ``--gyro-range`` as meta.json's ``full_scale`` of the imported unit's
    accelerometer / gyroscope (a --merge keeps the other unit's); a one-line error naming the option otherwise."""
    from pdrlearn.kernels.clipping import FULL_SCALE_KEY, parse_full_scale

    given = {k: v for k, v in (("accelerometer", acc_range), ("gyroscope", gyro_range)) if v is not None}
    if not given:
        return session
    prefix = "w" if unit == "waist" else "f"
    declared = dict(session.meta.get(FULL_SCALE_KEY) or {})
    for kind, text in given.items():
        opt = "--acc-range" if kind == "accelerometer" else "--gyro-range"
        try:
            parse_full_scale(text, kind)
        except ValueError as exc:
            raise DataError(f"{opt} {text}: {exc} (decision B456; nothing written)") from None
        name = prefix + kind.capitalize()
        if name not in session.streams:
            raise DataError(f"{opt} {text}: the import maps no {kind} columns ({name}); name them with "
                            f"{'--acc' if kind == 'accelerometer' else '--gyro'} COLUMNS or leave {opt} out")
        declared[name] = text.strip()
    session.meta[FULL_SCALE_KEY] = declared
    return session


def _say_clipping(session, out: Path) -> None:
    """Decisions B77 / B311 / B456 and B455: the clipping and stuck-axis lines ``info`` and ``track`` give for the
    files just written, said by ``import`` at once (trial T3 finding F6)."""
    import copy

    from pdrlearn.io.plasys import warn_saturation, warn_stuck

    written = copy.copy(session)
    written.folder = out
    warn_saturation(written)
    warn_stuck(written)


def _check_force_unit_used(csv: Path, record: dict, heel_unit: str | None, toe_unit: str | None) -> None:
    """Decision B408: ``--heel-unit`` / ``--toe-unit`` given for a force column the import did not map is one line
    (it had been ignored without a word: the unit the user meant for a column that stayed unused)."""
    from pdrlearn.errors import DataError

    mapped = {r[-6:] for r in record["streams"]}  # fForceA / wForceA ...: ForceA is heel, ForceB toe (KINDS)
    for opt, given, kind, stream in (("--heel-unit", heel_unit, "heel", "ForceA"),
                                     ("--toe-unit", toe_unit, "toe", "ForceB")):
        if given is not None and stream not in mapped:
            unused = record.get("unused_columns") or []
            raise DataError(f"{csv}: {opt} {given} is given, but no {kind} force column is mapped"
                            + (f" (unused columns: {', '.join(map(str, unused))})" if unused else "")
                            + f"; name it with --{kind} COLUMN, or leave {opt} out (decision B408)")


def _split_written(folder: Path) -> bool:
    """Decision B80: ``folder`` holds only what ``pdrlearn import --split-at-clock-reset`` wrote there: folders
    ``part1``, ``part2`` ..., each holding only the files its import wrote (meta.json ``"imported"``)."""
    import re

    entries = list(folder.iterdir())
    for p in entries:
        if not (p.is_dir() and re.fullmatch(r"part\d+", p.name)):
            return False
        try:
            meta = read_json(p / "meta.json")
        except (OSError, ValueError):
            return False
        if not isinstance(meta, dict) or "imported" not in meta:
            return False
        if any(q.name not in _import_written(meta) for q in p.iterdir()):
            return False
    return bool(entries)


def _pendulum_leg_line(meta: dict, sensor_given: bool, leg_given: bool) -> str | None:
    """Decision B462: the one line when the written meta.json holds both ``leg_length_m`` and ``sensor_height_m``
    and this import gave one of them: the waist pendulum takes the leg (B155's order, read as
    :func:`pdrlearn.waist.params.leg_length_note` reads it), and the unit's height is kept but not used; what to
    enter for a crouched walker. None otherwise (or when both are the same)."""
    from pdrlearn.waist.params import _meta_numbers

    found = dict(_meta_numbers(meta, "leg_length_m", "sensor_height_m"))
    leg, unit_h = found.get("leg_length_m"), found.get("sensor_height_m")
    if leg is None or unit_h is None or leg == unit_h or not (sensor_given or leg_given):
        return None
    return (f"the waist pendulum's leg is leg_length_m {leg:g} m (--leg-length), not the unit's height "
            f"sensor_height_m {unit_h:g} m (--sensor-height), which is kept in meta.json but not used: the leg is "
            "taken first (decision B155). For a crouched walker give the measured leg (it also scales the walking "
            "range, L148) and calibrate waist-pendulum on this walker's 10 m walk ('pdrlearn calibrate DIR "
            "--pipeline waist-pendulum --distance 10'): its gain K takes up a shorter working pendulum (decision "
            "B462)")


def _require_waist_acc(session, record: dict, csv: Path, no_acc: bool) -> None:
    """Decision B463: a waist session (after any --merge) without an accelerometer is refused before anything is
    written, unless ``--no-acc`` asks for it: both lower-back pipelines need one (the gyroscope alone finds no contact,
    W130), and a note under a written session was missed (trial T1 F9). An accelerometer without a gyroscope stays a
    note: 'pdrlearn steps --detector pll' finds its contacts (W130)."""
    if record["unit"] != "waist" or session.has("wAccelerometer") or no_acc:
        return
    sets = (record.get("ambiguous_columns") or {}).get("acc")
    found = (f"several accelerometer column sets ({', '.join(sets)}) and none guessed" if sets
             else "no accelerometer columns recognised")
    unused = record.get("unused_columns") or []
    among = f" (unused columns: {', '.join(unused[:6])})" if unused else ""
    from pdrlearn.io.sensors import SENSORS

    kinds = " and ".join(SENSORS[n].kind if n in SENSORS else n for n in session.streams)  # review R1 F5 (session 48)
    raise DataError(f"{csv}: {found}, and every lower-back pipeline needs the waist accelerometer; nothing written: "
                    f"map them with --acc X,Y,Z{among} (with --acc-unit g | m/s2 | mg), or pass --no-acc to write "
                    f"the {kinds} now and add the accelerometer's own file with --acc X,Y,Z --merge (decision B463)")


def _write_parts(parts: list, csv: Path, unit: str, out: Path, force_frame: bool, as_json: bool) -> None:
    """Decision B80: check every part of a split export as one import is checked (L71's axes, B67's frame), then
    write them as ``out/part1``, ``out/part2`` ... in one atomic step (all parts or none), and say what was
    written: each part's summary, then one line listing the parts."""
    from pdrlearn.atomic import atomic_directory
    from pdrlearn.io import write_session

    warnings = []
    for session, record in parts:
        lines = record["part"]["lines"]
        for w in (_check_axes(session, unit, record, csv), _check_frame(session, unit, record, csv, force_frame)):
            if w:
                warnings.append(f"{lines}: {w}")
    existed = out.is_dir() and any(out.iterdir())
    with atomic_directory(out) as tmp:  # all parts or none; --force keeps the old parts until then
        for k, (session, _) in enumerate(parts, start=1):
            write_session(session, tmp / f"part{k}")
    listed = [f"{out / f'part{k}'} ({r['part']['lines']}, {s.t_end - s.t_start:.2f} s)"
              for k, (s, r) in enumerate(parts, start=1)]
    if as_json:
        print_json({"out": str(out), "merged": False,
                    "parts": [{"out": str(out / f"part{k}"), "imported": r,
                               "frames": {p: f.to_dict() for p, f in s.frames.items()}}
                              for k, (s, r) in enumerate(parts, start=1)]})
    else:
        for k, (session, record) in enumerate(parts, start=1):
            _say(record, session, out / f"part{k}", False, False)
        verb = "replaced" if existed else "written"
        typer.echo(f"clock reset(s): {csv} split into {len(parts)} sessions, {verb}: {'; '.join(listed)}",
                   err=True)
    for w in warnings:
        typer.echo(f"warning: {out}: {w}", err=True)


def _check_axes(session, unit: str, record: dict, csv: Path) -> str | None:
    """Decision L71: the axis checks every command runs on the unit (D11 and its amendment,
    :func:`pdrlearn.io.handedness.check_handedness`), at import. Mirrored data (a left-handed pair, which
    ``track`` refuses or tracks wrongly) are refused, naming the axis and the --acc/--gyro options that
    negate it back; a gyroscope whose axes differ from the accelerometer's is returned as a warning."""
    from pdrlearn.io.handedness import check_handedness, mirrored_message

    h, msg = check_handedness(session, unit, ratio=False)
    if h is None or not h.mirrored or h.axes_differ:
        return msg
    prefix = "f" if unit == "foot" else "w"

    def option(kind: str, sensor: str, axis: str | None) -> str | None:
        r = record["streams"].get(prefix + sensor)
        if r is None or axis is None:
            return None
        neg = set(r.get("negated", ()))
        k = "xyz".index(axis)
        cols = ",".join(f"-{c}" if (c in neg) != (i == k) else c for i, c in enumerate(r["columns"]))
        return shell_quote(f"--{kind}={cols}")

    def how(axis: str | None) -> str:
        acc, gyr = option("acc", "Accelerometer", axis), option("gyro", "Gyroscope", axis)
        if acc is None or gyr is None:
            return "in both --acc and --gyro (-NAME negates a column) and import again"
        return f"in both sensors: import again with {acc} {gyr}"

    raise DataError(f"{csv}: {mirrored_message(h, unit, how=how)} (nothing written)")


def _origin_text(origin_s: float) -> str:
    """Decision B68: the origin in s with millisecond precision, and as a UTC time when it is a clock since
    the epoch (B39's EPOCH_START), in the ISO form the date-time summary uses."""
    from datetime import UTC, datetime

    from pdrlearn.io.validate import EPOCH_START

    text = f"{origin_s:.3f} s"
    if abs(origin_s) >= EPOCH_START:
        try:
            iso = datetime.fromtimestamp(origin_s, tz=UTC).isoformat(timespec="milliseconds")
        except (OverflowError, OSError, ValueError):
            return text
        text += f" ({iso})"
    return text


def _check_frame(session, unit: str, record: dict, csv: Path, force: bool) -> str | None:
    """Decision B67: a --frames entry the unit's data contradict with confidence (D10's test: an up, forward or
    left more than 60 deg from the measured one) is refused before anything is written, naming the frame the
    data give; ``--force-frame`` writes it anyway (recorded, and returned as a warning). A left-handed frame is
    refused whatever the data say (decision B130: its handedness needs no data), ``--force-frame`` keeps it."""
    frame = session.frames.get(unit)
    if frame is None:
        return None
    from pdrlearn.track.frame_inference import CHECK_SPAN_S, frame_disagreement, infer_session_frame

    given = ",".join(f"{k}={v}" for k, v in frame.to_dict().items())
    try:
        found = infer_session_frame(session, unit, max_s=CHECK_SPAN_S)
    except DataError:
        found = None  # the data do not fix the axes: the declared frame stands (D8, D10) if right-handed
    off = frame_disagreement(frame, found) if found is not None else {}
    if not off and not frame.right_handed:  # decision B130
        if force:
            record["frame_forced"] = {"declared": frame.to_dict(), "data": None}
            return f"--frames {given} is left-handed; written as given (--force-frame)"
        raise DataError(f"{csv}: --frames {given} is left-handed (IMU axes are right-handed: one of the three "
                        "directions is probably reversed); nothing written: import again with the axis corrected "
                        "(or without --frames, to infer them), or pass --force-frame to keep yours")
    if not off:
        return None
    data = ",".join(f"{k}={v}" for k, v in found.frame.to_dict().items())
    hand = "left-handed and " if not frame.right_handed else ""
    angles = ", ".join(f"{k} {v:.0f} deg off" for k, v in off.items())
    if force:
        record["frame_forced"] = {"declared": frame.to_dict(), "data": found.frame.to_dict()}
        return (f"--frames {given} is {hand}contradicted by the data ({data}; {angles}); written as given "
                "(--force-frame)")
    extra = ""
    if set(off) == {"left"}:  # up and forward agree: the declaration mirrors the data (D10)
        extra = "; if the device really has those axes, its data are mirrored: negate that axis with --acc/--gyro"
    raise DataError(f"{csv}: --frames {given} is {hand}contradicted by the data, which give {data} ({angles}); "
                    f"nothing written: import again with --frames {data} (or without "
                    f"--frames){extra}, or pass --force-frame to keep yours")


def _say(record: dict, session, out: Path, merge: bool, existed: bool) -> None:
    """What was mapped and guessed (stderr, one line each); the folder on stdout."""
    def err(msg: str) -> None:
        typer.echo(msg, err=True)

    t = record["time"]
    if t["column"] == "(row index)":  # decision B323 (importer.ROW_INDEX; this module imports no numpy)
        err(f"time: no time column: {t['source']}; 0 ms = the first row")
    else:
        err(f"time: column '{t['column']}' in {t['unit']} ({t['source']}); 0 ms = {_origin_text(t['origin_s'])} on "
            "the export's clock")
    sk = record.get("skipped_rows")
    if sk:  # decision B66
        if sk.get("units"):
            shown = ", ".join(dict.fromkeys(sk["units"].values()))
            err(f"note: line {sk['line']} read as a units row ({shown}): not data; the units it names are used "
                "(--skip-rows 0 reads it as data)")
        else:
            err(f"note: {sk['rows']} row(s) under the header skipped ({sk['source']})")
    dt = t.get("datetime")
    if dt and dt.get("time_of_day"):  # decision B86
        err(f"time: read {dt['order']}: {dt['first']} to {dt['last']}")
    elif dt:  # decision B43: what the date-time text was read as
        err(f"time: date-time text read {dt.get('order', 'as written')}: {dt['first']} to {dt['last']} (UTC); "
            f"zone {dt['zone']}")
    if merge and len(session.meta.get("imported", [])) < 2:
        # no recorded origin to share: the added unit was moved like a first import (its first timestamp
        # taken off), so an offset it had on a clock shared with the session is gone
        err(f"note: the session was not imported, so its clock's origin is unknown: the added unit starts at 0 ms "
            f"({_origin_text(t['origin_s'])} on the export's clock taken off), as the session's files do; if both were "
            "on one clock with another origin, import both units (clocks up to 2 s apart: `pdrlearn track "
            "--align-units`, decision L162)")
    if record.get("sorted_rows"):  # decision B383
        err(f"{record['sorted_rows']} row(s) out of time order moved by --sort-timestamps (decision B383)")
    for sensor, r in record["streams"].items():
        conv = "" if r["factor"] == 1.0 else f", x {r['factor']:.6g} to {session.streams[sensor].spec.unit}"
        dropped = record["dropped_rows"].get(sensor)
        dups = (record.get("duplicate_rows") or {}).get(sensor)  # decision B150
        neg = set(r.get("negated", ()))  # B48: the summary shows what was read, -NAME for a negated column
        cols = ",".join(f"-{c}" if c in neg else c for c in r["columns"])
        err(f"{sensor}: {cols} ({r['columns_source']}) in {r['unit']} ({r['unit_source']}{conv}), "
            f"{r['samples']} samples at {r['rate_hz']:g} Hz" + (f", {dropped} empty rows skipped" if dropped else "")
            + (f", {dups} rows repeating a timestamp dropped (--drop-duplicate-timestamps)" if dups else "")
            + (f" - {100 * dups / (r['samples'] + dups):.2g} % of the rows: if the stamps are coarser than the "
               "sensor's period these were real samples; import again with --retime HZ instead (decision B468)"
               if dups and dups > DROPPED_SHARE_NOTE * (r['samples'] + dups) else "")
            + (_retimed_text(record["retimed"][sensor]) if sensor in record.get("retimed", {}) else "")
            + (f", plus the gravity of {r['gravity_added']} (--add-gravity)" if r.get("gravity_added") else ""))
        iphone = "mat" not in record  # decision B358: a MAT file is no phone app's export: no iPhone note
        if iphone and r.get("gravity_added") and len(neg) < 3:  # decisions B166, B146: Core Motion's sign
            fix = shell_quote("--acc=" + ",".join(f"-{c}" for c in r["columns"]))
            err(f"note: gravity added from {r['gravity_added']}: Sensor Logger on iOS (Core Motion) reports gravity "
                "as -1 g and every turn comes out mirrored unless negated: if this is an iPhone's, import again with "
                f"{fix} (decisions B146, B166)")
        if iphone and sensor == "wAccelerometer" and r["unit"] == "g" and len(neg) < 3:  # decision B146
            fix = shell_quote("--acc=" + ",".join(f"-{c}" for c in r["columns"]))
            err(f"note: an accelerometer in g at the waist: if this is an iPhone (Core Motion) export, it reports "
                f"gravity as -1 g and every turn comes out mirrored unless negated: import again with {fix} "
                "(decision B146)")
    if record.get("steps"):
        st = record["steps"]
        built = (f", strides built from its {st['from_ics']} initial contacts: pre_ic_ms the opening one, ic_ms the "
                 "closing one (decision B338)" if st.get("from_ics") else "")
        kept = st.get("footfall_columns") or {}
        if kept:  # decision D51: the walkway's toe-off / stride length, each on the stride it belongs to
            names = {"tc_s": "tc_ms (the opening contact's toe-off)", "length_m": "length_m (the closing contact's)"}
            built += "; kept " + ", ".join(f"{names[c]} on {n}" for c, n in kept.items()) + " (decision D51)"
        err(f"steps: {st['rows']} labelled steps from {st['file']} (shifted to the session's clock{built})")
    for name, lab in (record.get("labels") or {}).items():
        err(f"labels: {name} with {lab['rows']} rows from {lab['file']} (shifted to the session's clock)")
    if record["unused_columns"]:
        err(f"unused columns: {', '.join(record['unused_columns'])}")
        if record["unit"] == "foot":
            from pdrlearn.displace.force_channels import extra_force_line

            extra = extra_force_line(record["unused_columns"])  # decision B399: a midfoot channel
            if extra:
                err(extra)
    prefix = "f" if record["unit"] == "foot" else "w"
    ambiguous = record.get("ambiguous_columns") or {}
    for key, kind, sensor, opt in (("acc", "accelerometer", "Accelerometer", "--acc"),
                                   ("gyro", "gyroscope", "Gyroscope", "--gyro")):
        if prefix + sensor in record["streams"]:
            continue
        if prefix + sensor in session.streams:  # the folder holds it already (--merge of a phone's files)
            err(f"{prefix + sensor}: kept from the session in {out} (this file maps no {kind} columns)")
            continue
        if key in ambiguous:  # several sets, none guessed: name them (a Shimmer3's LN and WR accelerometers)
            cols = ambiguous[key]
            shimmer = (" (Shimmer3: Accel_WR is the wide-range accelerometer, Accel_LN the low-noise one of "
                       "+-2 g, which a foot's heel strikes exceed)"
                       if key == "acc" and any("_WR_" in c.upper() for c in cols)
                       and any("_LN_" in c.upper() for c in cols) else "")
            err(f"note: several {kind} column sets ({', '.join(cols)}): none guessed{shimmer}; the pipelines need "
                f"one: map it with {opt} X,Y,Z")
        else:  # every pipeline needs both (README "Session folders")
            err(f"note: no {kind} columns recognised; the pipelines need one: map them with {opt} X,Y,Z, or "
                f"import the {kind}'s own file into this folder with {opt} X,Y,Z --merge (a phone's separate files)")
    unit = record["unit"]
    if unit in session.frames:
        err(f"{unit} frame: {json.dumps(session.frames[unit].to_dict())}")
    else:
        err(f"{unit} frame: not declared; commands infer it from the data (decision D8); pass --frames to declare it"
            + (" (always for a prosthetic or stiff foot, whose little sagittal rotation the inference may not read: "
               "decision B418)" if unit == "foot" else ""))
    verb = "added to" if merge else ("replaced" if existed else "written to")
    err(f"{unit} unit {verb} {out}; check it with: pdrlearn info {shell_quote(out)}")
    typer.echo(str(out))


def register(app: typer.Typer) -> None:
    app.command("import")(import_command)


def _retimed_text(r: dict) -> str:
    """Decision B186: what ``--retime`` did to a stream, for the import summary."""
    lost = f", {r['lost']} samples counted as lost between them" if r["lost"] else ""
    return (f", re-timed at {r['rate_hz']:g} Hz from {r['stamps']} stamps ({r['samples_per_stamp']:g} samples per "
            f"stamp on the median{lost}; the stamps hold {r['stamp_rate_hz']:.5g} Hz, --retime)")
