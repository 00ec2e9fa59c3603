"""``pdrlearn export`` (model directory -> bundle) and ``pdrlearn run`` (replay through the runtime)."""
# ruff: noqa: B008  (typer declares options as argument defaults)

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import typer

from pdrlearn.cli import track as _track
from pdrlearn.cli.common import (
    CSV_FLOAT_FORMAT,
    DPI_HELP,
    FORCE_HELP,
    INITIAL_HEADING_HELP,
    PICKLE_HELP,
    START_HELP,
    check_no_plot,
    clock_progress,
    count_phrase,
    existed,
    gait_line,
    initial_heading_option,
    json_safe,
    out_folder,
    print_json,
    replaced,
    start_option,
    storey_height_option,
    write_table_csv,
)
from pdrlearn.cli.gaplines import GapLines
from pdrlearn.decision_refs import decision_ref


def bundle_refusal(model_dir: Path) -> str | None:
    """Decision L780: ``export``'s one line when ``model_dir`` is an exported runtime bundle (such as the shipped
    ``models/plasys-sim-default``, a 20 Hz bundle): what it is (its rate), that ``run`` replays sessions through it,
    and the commands that make a bundle of one's own (train a model, then export it); None for anything else (the
    model directory's own checks follow)."""
    import json

    from pdrlearn.decision_refs import decision_ref

    mf = Path(model_dir) / "manifest.json"
    try:
        manifest = json.loads(mf.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(manifest, dict) or manifest.get("schema") != "pdrlearn-bundle":
        return None
    rate = (manifest.get("sampling") or {}).get("rate_hz")
    rate = f"a {float(rate):.4g} Hz " if isinstance(rate, (int, float)) else "a "
    return (f"export {model_dir}: {rate}runtime bundle, exported already (an exported runtime bundle, not a model "
            f"directory): nothing to export. Replay sessions through it with 'pdrlearn run {model_dir} SESSION'; "
            "for a bundle of your own, train a model on your labelled sessions (e.g. the calibration exercises) "
            "and export that: 'pdrlearn train SESSION... --out models/u1', then 'pdrlearn export models/u1 --out "
            f"bundles/u1' (README 'Workflow'; {decision_ref('L780')})")


def export(
    model_dir: Path = typer.Argument(..., help=f"Model directory written by 'pdrlearn train' ({PICKLE_HELP}), or a "
                                     "waist calibration "
                                     "(PARAMS.json of 'pdrlearn calibrate': a waist-only bundle, decision E57)."),
    out: Path = typer.Option(..., "--out", "-o", help="Bundle folder to create."),
    methods: str = typer.Option(None, help="Comma-separated methods to export for every task "
                                "(heuristic,fusion,dtw,svm,nn,ensemble); default: each task's chosen method."),
    length_bounds: str = typer.Option(None, "--length-bounds", help="Stride-length class edges (m) "
                                      "SHORT_NORMAL,NORMAL_LONG; default: the model's; a model without them: none "
                                      "(the length rule is skipped, with a warning)."),
    no_training_samples: bool = typer.Option(False, "--no-training-samples", help="Leave out the models that "
                                             "embed the user's training samples (DTW references, SVM support "
                                             "vectors, soft votes with them): each task gets the best-ranked model "
                                             "without them (docs/deploying.md, privacy; decision E68)."),
    float32: bool = typer.Option(False, "--float32", help="Every ONNX graph in float32 (step graph, SVMs, "
                                 "networks), no float64 twins: for single-precision targets such as a Cortex-M4F "
                                 "(docs/deploying.md; decision E217)."),
    units: str = typer.Option(None, "--units", help="foot: a single-unit bundle, only the models that read the "
                              "foot unit alone (the smallest bundle for a one-sensor device; decision E218). Not "
                              "waist: the runtime detects steps on the foot unit; a waist-only device runs a waist "
                              "bundle, `pdrlearn export CAL.json` of `pdrlearn calibrate` (decisions E57, E233)."),
    force: bool = typer.Option(False, "--force", "--overwrite", help=FORCE_HELP + " --overwrite is the old name."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object."),
    frame: str = typer.Option(None, "--frame", help="Waist calibration only: the waist unit's axes, e.g. "
                              "x=up,y=right,z=forward (recorded in the waist bundle; without it the live "
                              "WaistTracker needs frame=, and 'pdrlearn run' takes the session's)."),
) -> None:
    """Export a trained model as a portable bundle (manifest.json + ONNX + JSON/NPZ, no pickle); a waist
    calibration as a waist-only bundle (decision E57).

    Examples:

        pdrlearn export out/models/u1 --out out/bundle_u1

        pdrlearn export out/models/u1 --out out/bundle_u1_all --methods svm,nn,dtw --json

        pdrlearn export out/models/u1 --out out/bundle_u1_shared --no-training-samples

        pdrlearn export out/models/u1 --out out/bundle_u1_f32 --float32   # a float32-only bundle (E217)

        pdrlearn export out/models/u1 --out out/bundle_u1_foot --units foot --methods nn --float32

        pdrlearn export p.json --out wbundle --frame x=up,y=right,z=forward   # a waist calibration (calibrate)
    """
    from pdrlearn.errors import DataError
    from pdrlearn.export.bundle import bundle_size_bytes
    from pdrlearn.export.from_model import export_model
    from pdrlearn.export.sizes import bundle_sizes, sizes_lines
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.bundle import _is_waist_calibration

    if _is_waist_calibration(model_dir):  # decision E57: a belt-phone user's calibration -> a waist bundle
        if methods or length_bounds or float32 or units:
            raise DataError(f"export {model_dir}: a waist calibration has no classifiers; drop --methods / "
                            "--length-bounds / --float32 / --units")
        return _export_waist(model_dir, out, frame, force, as_json)
    if frame is not None:  # decision E349: a misspelt calibration file is no model directory
        if not Path(model_dir).exists():
            raise DataError(f"export --frame: {model_dir}: no such file; --frame exports a waist calibration, the "
                            "PARAMS.json `pdrlearn calibrate` wrote: check the file's name")
        if not Path(model_dir).is_dir():
            raise DataError(f"export --frame: {model_dir} is not a waist calibration (a JSON file whose \"pipeline\" "
                            "is a waist pipeline, `pdrlearn calibrate`'s PARAMS.json): give that file")
        raise DataError(f"export --frame: only for a waist calibration; {model_dir} is a model directory, whose "
                        "bundle records its training sessions' frames")
    refused = bundle_refusal(model_dir)  # decision L780: a runtime bundle is exported already
    if refused:
        raise DataError(refused)
    meths = [m.strip() for m in methods.split(",") if m.strip()] if methods else None
    bounds = None
    if length_bounds:
        from pdrlearn.cli.common import parse_length_bounds

        bounds = parse_length_bounds(length_bounds)
    out_folder(out, "bundle", force=force, inputs=(model_dir,))
    was = existed(out)
    path = export_model(model_dir, out, methods=meths, length_bounds=bounds, overwrite=force,
                        training_samples=not no_training_samples, float32=float32,
                        units=units)
    replaced(out, was)
    b = load_bundle(path)
    summary = {
        "bundle": str(path), "user": b.manifest["user"], "size_bytes": bundle_size_bytes(path),
        "files": sorted(b.manifest["files"]), "rate_hz": b.rate_hz,
        "boundaries": b.manifest["features"].get("boundaries", "given"),
        "tasks": {t: {"chosen": v["chosen"], "methods": {m: sorted(per) for m, per in v["methods"].items()}}
                  for t, v in b.tasks.items()},
        "skipped": b.manifest.get("export", {}).get("skipped", []),
        "training_samples": b.manifest.get("export", {}).get("training_samples", True),
        "model_sizes": bundle_sizes(path, b.manifest["files"]),  # decision E219
    }
    if as_json:
        print_json(json_safe(summary))
        return
    typer.echo(f"bundle {path} ({summary['size_bytes'] / 1e3:.1f} kB, {len(summary['files'])} files, "
               f"{summary['boundaries']} step boundaries)")
    for t, v in summary["tasks"].items():
        typer.echo(f"  {t}: {v['chosen']['method']}/{v['chosen']['unit']}  (exported: "
                   + ", ".join(f"{m}/{u}" for m, us in v["methods"].items() for u in us) + ")")
    for s in summary["skipped"]:
        typer.echo(f"  skipped: {s}")
    typer.echo("files (flash; parameters and multiply-accumulates per step of each ONNX graph, "
               f"{decision_ref('E219')}):")  # decision D49
    for line in sizes_lines(summary["model_sizes"]):
        typer.echo(line)


def _export_waist(cal: Path, out: Path, frame: str | None, force: bool, as_json: bool) -> None:
    """``pdrlearn export CAL.json``: the waist-only bundle (decision E57) and its one-line summary."""
    from pdrlearn.export.bundle import bundle_size_bytes
    from pdrlearn.export.waist import export_waist
    from pdrlearn.runtime.waist import load_waist_bundle

    out_folder(out, "bundle", force=force, inputs=(cal,))
    was = existed(out)
    path = export_waist(cal, out, frame=frame, overwrite=force)
    replaced(out, was)
    b = load_waist_bundle(path)
    p = b.params
    summary = {"bundle": str(path), "kind": "waist", "size_bytes": bundle_size_bytes(path),
               "files": sorted(b.manifest["files"]), "pipeline": b.manifest["pipeline"], "rate_hz": b.rate_hz,
               "params": {"leg_m": p.leg_m, "k": p.k, "f_m": p.f_m, "gyro_bias_rps": p.gyro_bias_rps,
                          "source": p.source},
               "frame": b.manifest["frames"].get("waist"), "frame_from": b.manifest.get("frame_from"),  # E367
               "warnings": b.manifest.get("warnings", []),
               "not_applied_live": b.manifest.get("not_applied_live")}  # decision E368
    if as_json:
        print_json(json_safe(summary))
        return
    import logging

    for w in summary["warnings"]:  # the calibration's (e.g. a leg length from a default height, W62)
        logging.getLogger("pdrlearn.cli").warning("%s: %s", cal, w)
    rate = f"calibrated at {b.rate_hz:.4g} Hz" if b.rate_hz == b.rate_hz else "no calibration rate recorded"
    fr = (",".join(f"{k}={v}" for k, v in summary["frame"].items()) if summary["frame"]
          else "no frame (pass --frame, or run takes the session's)")
    if summary["frame"] and summary["frame_from"] not in (None, "--frame"):
        fr += f" (from {summary['frame_from']})"  # decision E367
    typer.echo(f"waist bundle {path} ({summary['size_bytes'] / 1e3:.1f} kB, {len(summary['files'])} file(s)): "
               f"waist-pendulum, K {p.k:.4f}, leg {p.leg_m:.3f} m, {p.source}, {rate}; frame {fr}")
    if not summary["frame"]:  # decision E367: the bundle the live WaistTracker refuses without frame=, said now
        logging.getLogger("pdrlearn.cli").warning(
            "%s: neither --frame nor the calibration gives the waist unit's axes: `pdrlearn run` takes each session's, "
            "but `WaistTracker(load_waist_bundle(...))` needs frame=; re-export with --frame AXES (a phone upright in "
            "a belt clip at the front, screen out: --frame x=left,y=up,z=forward; docs/deploying.md)", cal)
    if summary["not_applied_live"]:  # decision E368: what the live tracker does without, said once, here
        typer.echo(f"  live: {summary['not_applied_live']}")


def frames_of(session, bundle, units=None) -> dict:
    """Each unit's frame for the runtime: declared (checked against the data, decisions D10, D23); else inferred
    from the session's data (decision D8, with its warning); else, when the data does not fix the axes, the
    bundle's (its training sessions'), warned. A unit the replay leaves out (``units``, decision E26:
    ``--units foot``) keeps the bundle's, unsaid."""
    import logging

    from pdrlearn.errors import DataError

    frames = {p: f.to_dict() for p, f in session.frames.items()}
    for p, f in bundle.manifest["frames"].items():
        if p in frames:
            if units is None or p in units:  # checked against the data as track does (D10; D23 refuses a reversal)
                frames[p] = session.require_frame(p).to_dict()
            continue
        if units is not None and p not in units:  # not replayed: its frame is never used, nothing to warn about
            frames[p] = f
            continue
        try:
            frames[p] = session.require_frame(p).to_dict()
        except DataError:
            logging.getLogger(__name__).warning("session '%s' declares no %s frame and its data does not fix the "
                                                "axes; using the bundle's %s", session.name, p, f)
            frames[p] = f
    return frames


def _warn_short_streams(session, tracker, steps) -> None:
    """Decision E23 for a recording: a stream the bundle uses that ends before the foot gyroscope (which
    finds the strides): say where, which steps ran past its end (measured with its last sample held) and
    where the tracked walk ends."""
    import logging

    g = session.streams.get("fGyroscope")
    if g is None or not len(g):
        return
    for n in tracker.used_sensors:
        st = session.streams.get(n)
        if st is None or not len(st) or n == "fGyroscope":
            continue
        end = float(st.t[-1])
        short = float(g.t[-1]) - end
        if short > 2.0 / max(st.rate_hz, 1e-9):  # more than two of its sample intervals (NaN rate: never)
            past = [x for x in steps if x.end_s > end]
            if past:
                what = (f"{len(past)} step(s) ({past[0].start_s:.2f} to {past[-1].end_s:.2f} s) ran past its end and "
                        f"were measured with its last sample held; the walk is tracked to {steps[-1].end_s:.2f} s")
            else:
                what = ("no step runs past its end; the walk is tracked to "
                        + (f"{steps[-1].end_s:.2f} s" if steps else "nowhere (no step)"))
            logging.getLogger("pdrlearn.cli").warning(
                "%s: %s ends at %.2f s, %.2f s before fGyroscope (%.2f s): %s; trim the session to where every "
                "sensor has data, or re-record", session.name, n, end, short, float(g.t[-1]), what)


def _units_for(bundle, units: str | None, have: set[str] | None, where: str):
    """The body units ``run`` replays (decision E26): ``--units`` as given; without it, the bundle's, or the foot
    alone when the data lack a waist sensor the bundle requires (``have`` = the data's sensors; None = the
    foot unit's Bluetooth protocol), with one warning line. Returns ``(units, said)``: ``said`` = that line
    was logged (it names the foot heading too, so the separate heading line is not repeated)."""
    import logging

    from pdrlearn.runtime.tracker import check_units
    from pdrlearn.track.plasys import NO_WAIST_HEADING

    if units is not None:
        return check_units(bundle, [u for u in units.split(",") if u.strip()]), False
    req = bundle.sensors_of(("waist",))[0]
    lacking = [n for n in req if have is None or n not in have]
    no_foot = have is not None and not set(bundle.sensors_of(("foot",))[0]) <= have  # an error follows anyway
    if "waist" not in bundle.body_units or "foot" not in bundle.body_units or not lacking or no_foot:
        return bundle.body_units, False
    heading = NO_WAIST_HEADING.removeprefix("no waist unit: ")
    logging.getLogger("pdrlearn.cli").warning(
        "%s has no %s (the waist unit bundle %s also uses): the foot unit only, as `pdrlearn track` - classes from "
        "the foot models, %s (--units foot chooses this without the warning)", where,
        "waist unit" if have is None else ", ".join(lacking), bundle.path, heading)
    return check_units(bundle, ("foot",)), True


def _unit_clocks(session, units, align: bool, offset_s: float | None = None, drift: float | None = None):
    """Decisions L161, L170: a replay with the foot and the waist unit checks their clocks as ``track`` does (the
    same function, :func:`pdrlearn.track.plasys.unit_offset_line`, on the whole recording: the replay has it) and
    warns when the units' steps are over 0.2 s apart, naming ``run --align-units``; with ``align`` the waist clock
    is moved onto the foot's first (:func:`pdrlearn.track.plasys.align_clocks`, L162's); with ``offset_s`` (``run
    --clock-offset``, decision E111) by that offset, as ``track --clock-offset``, and the clocks then checked (with
    ``drift``, ``run --clock-drift-ppm`` as a fraction, decision B265: also by that drift). Returns
    the session to replay and the alignment applied (``{"offset_s", "drift", "source", ...}``; None without ``align``
    or ``offset_s``, or when the estimate failed)."""
    import logging

    from pdrlearn.cli.track import given_clock_options, no_waist_for_clock
    from pdrlearn.track.plasys import align_clocks, move_waist_clock, unit_offset_line

    two = "waist" in units and session.has("fAccelerometer", "wAccelerometer", "wGyroscope")
    given = given_clock_options(offset_s, drift)  # E111; B265: also the drift
    for option, asked in (("--align-units", align), (given, bool(given))):
        if asked and not two:  # decision B192's line, as track's (E112: also --clock-offset's)
            raise no_waist_for_clock("run", option, session.where)
    if not two:
        return session, None
    lines: list[str] = []
    if align:
        session, alignment = align_clocks(session, lines)
    else:
        alignment = None
        if given:  # decision E111: moved by hand, then checked as the recording is (L161); B265: also the drift
            session, alignment = move_waist_clock(session, offset_s or 0.0, drift or 0.0, lines, source="given",
                                                  option=given)
        line = unit_offset_line(session, "pdrlearn run")
        lines += [line] if line else []
    for line in lines:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.name, line)
    return session, alignment


def run(
    bundle_dir: Path = typer.Argument(..., help="Bundle folder written by 'pdrlearn export'."),
    session_dir: Path = typer.Argument(None, help="PLASYS session folder to replay (omit with --protocol)."),
    out: Path = typer.Option(None, "--out", "-o", help="Folder for steps.csv, trajectory.csv, bouts.csv, turns.csv, "
                             "path.png, summary.json (the files and columns of `pdrlearn track`)."),
    protocol: str = typer.Option(None, "--protocol", help="Bluetooth text-protocol capture to read instead "
                                 "of a session ('-' = stdin)."),
    protocol_rate: float = typer.Option(None, "--protocol-rate", metavar="HZ", help="Sampling rate of the "
                                        "--protocol capture's sets (the protocol carries no time, decision D5; "
                                        "default: the bundle's, the thesis unit's 20 Hz); a foot rhythm outside the "
                                        "walking range at it is warned about (decision E90)."),
    chunk_s: float = typer.Option(1.0, help="Replay chunk length (s)."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON summary object."),
    resample: bool = typer.Option(False, "--resample", help="Resample data at another rate than the bundle's "
                                  "(+-5 %) causally to the bundle's rate (decision E22); default: track it at "
                                  "its own rate, as `pdrlearn track --streaming`."),
    no_resample: bool = typer.Option(False, "--no-resample", help="Refuse data at another rate than the "
                                     "bundle's (+-5 %) (decision E3)."),
    rules: str = typer.Option(None, "--rules", help="Class rules: bayes or thesis (default: the bundle's: "
                              "bayes = offline M3's rule since decision L41, thesis in bundles exported "
                              "before it; decision E25)."),
    min_confidence: float = typer.Option(None, "--min-confidence", min=0.0, max=1.0,
                                         help="Apply a class rule only when the model's probability of the class "
                                         "reaches this (default: the bundle's, 0.95 since decision L41; 0 = always, "
                                         "as the thesis; 0.95 with --rules bayes, 0 with --rules thesis)."),
    units: str = typer.Option(None, "--units", help="Body units to track with: foot, or foot,waist (default: "
                              "the bundle's; the foot alone when the data have no waist unit, with a warning). "
                              "foot = a two-unit bundle on a foot-only session or a failed waist (decision E26)."),
    start: str = typer.Option(None, "--start", help=START_HELP),
    storey_height: float = storey_height_option(),
    bout_rule: str = _track.BOUT_RULE_OPT,
    bout_break_s: float = _track.BOUT_BREAK_OPT,
    bout_min_strides: int = _track.BOUT_MIN_STRIDES_OPT,
    initial_heading: float = typer.Option(None, "--initial-heading", metavar="DEG",
                                          help=INITIAL_HEADING_HELP.split(" For a relative")[0]
                                          + " (the runtime's heading is relative: gyroscopes only)."),
    dpi: int = typer.Option(None, "--dpi", min=20, max=600, help=DPI_HELP),
    no_plot: bool = _track.NO_PLOT_OPT,  # decision L533, as track's
    method: str = typer.Option(None, "--method", metavar="[TASK=]METHOD[/UNIT],...",
                               help="Classify with another exported model than the bundle's chosen one: e.g. svm "
                               "(every task; its chosen unit, else its only one), svm/foot, or terrain=dtw/foot "
                               "(one task). The bundle must hold it (`pdrlearn export --methods`); decision E52."),
    contacts: bool = typer.Option(False, "--contacts", help="Each stride's initial contact (force onset, else the "
                                  "accelerometer impact) and so stride_time_s, cadence_spm, speed_mps and the "
                                  "summary's stride medians (decisions E49-E51; as `track --streaming --contacts`)."),
    drop_neighbour: bool = typer.Option(False, "--drop-neighbour", help="A stride across dropped foot samples over "
                                        "0.25 s (under 1 s) takes the length and height change of the stride before "
                                        "it (decision L167, not the default; E101; as `track --streaming "
                                        "--drop-neighbour`)."),
    altitude: str = typer.Option("foot", "--altitude", metavar="foot|fused",
                                 help="A foot-unit bundle's altitude: the strides' own height (foot, the default, "
                                 "as `track`'s) or fused with the session's waist barometer as it streams (fused: "
                                 "`track --altitude fused`'s filter, L154; slopes and hills read; each row waits "
                                 "~1 s for the barometer; decision E339; docs/deploying.md)."),
    no_cycling: bool = typer.Option(False, "--no-cycling", help="An activity without bicycles (dance, a clinic): no "
                                    "stride is judged pedalling (L611) and none is held for that verdict, which "
                                    "holds a short turning stride up to 3 later strides (decision E304; as `track "
                                    "--no-cycling`)."),
    warn_out_of_domain: float = _track.warn_ood_option(
        "A bundle exported since decision E105 (it stores the training ranges; an older one checks nothing): ",
        "bundle's model"),
    align_units: bool = typer.Option(False, "--align-units", help="A foot + waist session: move the waist unit's "
                                     "clock onto the foot's by the steps both detect, before the replay (offset and "
                                     "drift over the whole recording, as `track --align-units`; decision L170). "
                                     "Without it, the units' steps over 0.2 s apart are warned about (L161)."),
    clock_offset: float = _track.CLOCK_OFFSET_OPT,
    clock_drift_ppm: float = _track.CLOCK_DRIFT_OPT,
    common_span: bool = typer.Option(False, "--common-span", help="A session whose units (or one unit's files) "
                                     "cover different times: replay only the time all the files cover, with one "
                                     "warning naming the seconds dropped from each file (decisions B81, B83, B230; "
                                     "as `track --common-span`)."),
    drop_partial_row: bool = _track.DROP_PARTIAL_ROW_OPT,
    redact_paths: bool = _track.REDACT_PATHS_OPT,  # decision E176, as track's
    stair_rise: float = _track.STAIR_RISE_OPT,  # decision L432, as track's (review R3 finding 6)
    stair_grade: float = _track.STAIR_GRADE_OPT,  # decision L469, as track's
    sides: bool = typer.Option(False, "--sides", help="A waist-only bundle: each step's foot, steps.csv column "
                               "side (left / right, empty when undecided) as `track --pipeline waist-pendulum` "
                               "names it, from the streamed contacts (W138's causal side, not the offline W129 "
                               "one: 79 of 80 agree where both decide on HA001, E103; decision E110)."),
    length_reference: str = typer.Option("model", "--length-reference", metavar="model|session",
                                         help="session: a flat, forward, straight stride's length_class from its "
                                         "length against 0.8 / 1.2 x the median of the session's such strides so "
                                         "far, after 10 (thesis ch.6.3's per-pedestrian classes; decision C117, not "
                                         "the default: C118); the distance is unchanged."),
    gait_other: Path = typer.Option(None, "--gait", metavar="OTHER_FOOT_SESSION",
                                    help="The other foot's session of the same walk: also `pdrlearn gait`'s tables "
                                    "and summary (gait_summary.json, gait_steps.csv, gait_cycles.csv, "
                                    "gait_bouts.csv with --out) of the two feet's streamed strides, each foot "
                                    "replayed foot-only with contacts and L73's toe-off (decision E311); the sides "
                                    "from meta.json's foot, else SESSION_DIR is the left."),
    heading_source: str = typer.Option("auto", "--heading-source", metavar="auto|foot|waist-gyro",
                                       help="What turns the streamed heading (the Tracker's heading_source, decision "
                                       "E6): auto = the waist gyroscope when the waist unit streams, else the foot; "
                                       "foot = the foot's attitude change from rest to rest; waist-gyro = the waist "
                                       "gyroscope always, on a vertical carried by it (decision E289). On "
                                       "stop-and-turn sessions (VR, rehab) try foot too (docs/deploying.md)."),
    at_times: str = typer.Option(None, "--at-times", metavar="FILE|T1,T2,...",
                                 help="Checkpoint times: a CSV with a column t_s (or t: seconds on the session's "
                                 "clock; or time: ISO 8601) or a comma list of seconds, in increasing order: "
                                 "OUT/at_times.csv gives the position the live track showed at each - the streamed "
                                 "row of the last stride the replay's pushes had returned by then (--chunk-s "
                                 "apart; decision E344), not interpolated (x, y, z, pos_sigma_m, floor when known; "
                                 "decision E332). Needs --out and SESSION_DIR."),
) -> None:
    """Replay a recorded session (or a Bluetooth capture) through the streaming runtime.

    Examples:

        pdrlearn run out/bundle/u1 out/sim/D_u1 --out out/run_D --json

        cat capture.txt | pdrlearn run out/bundle/u1 --protocol - --out out/live

        pdrlearn run out/bundle/u1 out/sim/D_u1 --units foot --out out/run_foot

        pdrlearn run out/bundle/u1 out/sim/D_u1 --start 41.178,-8.608,12.5 --out out/run_geo

        pdrlearn run out/bundle/u1 out/sim/D_u1 --initial-heading 90 --out out/run_north   # sets off north

        pdrlearn run out/bundle/u1 out/sim/D_u1 --clock-offset 0.3 --out out/run_clock   # waist clock 0.3 s late

        pdrlearn run out/bundle_u1_all out/sim/D_u1 --method svm --out out/run_svm   # an exported non-chosen method

        pdrlearn run wbundle out/sim/D_u1 --sides --out out/run_sides   # a waist bundle: each step's foot

        pdrlearn run out/bundle/u1 walks/D --redact-paths --out out/run_share   # no folder path in any output (E176)

        pdrlearn run out/bundle/u1 out/sim/D_u1 --stair-rise 0.181 --out out/run_stairs   # stairs.csv n_stairs (L432)

        pdrlearn run out/bundle/u1 out/sim/D_u1 --length-reference session --out out/run_rel   # C117's length class

        pdrlearn run out/bundle/u1 out/sim/D_u1 --no-plot --out out/run_tables   # no path.png (L533)

        pdrlearn run out/bundle/u1 out/sim/D_u1 --no-cycling --out out/run_dance   # no pedalling hold (E304)

        pdrlearn run out/bundle/u1 out/sim/D_u1 --altitude fused --out out/run_hill   # the barometer's altitude (E339)
    """
    # decision L122: every option as given (defaults included) and the start, for OUT/run.json, as track's
    record = _run_json(dict(locals()), time.perf_counter(), time.process_time())
    from pdrlearn.cli.provenance import redaction

    redact = redaction(dict(locals()))  # decision E176
    from pdrlearn.warning_lines import captured_warnings

    with captured_warnings(echo=True) as logged:  # decision E154: every warning also in summary.json / --json
        from pdrlearn.errors import DataError
        from pdrlearn.io.resample import resample_mode  # decision B113: one check of the two flags, as track's
        from pdrlearn.runtime import load_bundle
        from pdrlearn.runtime.replay import replay_chunks  # decision E28, shared with the lean command (E76)
        from pdrlearn.runtime.tracker import Tracker

        if protocol is not None and session_dir is not None:
            raise DataError(f"run: give a SESSION_DIR ({session_dir}) or --protocol {protocol}, not both")
        if protocol_rate is not None and protocol is None:
            raise DataError(f"run: --protocol-rate {protocol_rate:g} is the rate of a --protocol capture; a session "
                            "folder has timestamps (drop --protocol-rate, or give --protocol FILE)")
        if protocol_rate is not None and not (0 < protocol_rate < float("inf")):
            raise DataError(f"--protocol-rate {protocol_rate:g}: give the capture's sampling rate in Hz (> 0, e.g. 52)")
        if not (chunk_s > 0 and chunk_s < float("inf")):
            raise DataError(f"--chunk-s {chunk_s}: give the replay chunk length in seconds (> 0, e.g. 1)")
        start_ll, start_alt = start_option(start)  # decision L56, as `pdrlearn track`
        from pdrlearn.kernels.geodetic import start_has_altitude

        start_ele = start_has_altitude(start)  # decision L362: track.gpx's <ele> only from a given altitude
        heading0 = initial_heading_option(initial_heading)  # decision L98, as `pdrlearn track`
        clock_offset = _track.clock_offset_value(clock_offset, align_units, "run")  # decision E112, as `track`
        clock_drift = _track.clock_drift_value(clock_drift_ppm, align_units, "run")  # decision B265, as `track`
        from pdrlearn.track.bouts import bout_rule as read_bout_rule
        from pdrlearn.track.bouts import track_bouts

        bouts = read_bout_rule(bout_break_s, bout_min_strides, bout_rule)  # L124, L130, L163: as `track`, first
        from pdrlearn.track.stair_flights import stair_rise as check_stair_rise

        stair_rise_m = check_stair_rise(stair_rise)  # decision B348, as `track`: before any output
        from pdrlearn.kernels.relative_length import check_length_reference

        check_length_reference(length_reference)  # decision C117: before any output
        from pdrlearn.runtime.baro_fusion import check_altitude

        check_altitude(altitude, "run")  # decision E339: track's values, before any output (E357: the lean's check)
        from pdrlearn.track.grade import check_stair_grade, record_stair_grade

        stair_grade_pct = check_stair_grade(stair_grade)  # decision L469, as `track`: before any output
        plot = check_no_plot("run", no_plot, dpi)  # decisions L533, B413: before any output
        at_table = at_label = None
        if at_times is not None:  # decision E332: checked before any output or replay
            if out is None:
                raise DataError(f"run: --at-times {at_times} writes OUT/at_times.csv, which only --out writes; add "
                                "--out FOLDER")
            if protocol is not None:
                raise DataError(f"run: --at-times {at_times} needs a session's clock, known before the replay; the "
                                f"--protocol capture {protocol} has none: replay a session folder (SESSION_DIR)")
            from pdrlearn.track.at_times import times_argument

            at_table, at_label = times_argument(at_times)
        if dpi is not None and out is None:  # decision L70: it would be ignored
            raise DataError(f"run: --dpi {dpi} sets the resolution of path.png, which only --out writes; add --out "
                            "FOLDER or drop --dpi")
        from pdrlearn.kernels.stride import HEADING_SOURCES

        if heading_source not in HEADING_SOURCES:  # decision E285: run exposes the Tracker's heading_source
            raise DataError(f"run: --heading-source {heading_source!r} is not one of {', '.join(HEADING_SOURCES)} "
                            "(auto: the waist gyroscope when the waist unit streams, else the foot)")
        if out is not None:
            out_folder(out, "run", force=force, inputs=(bundle_dir, session_dir))
        from pdrlearn.runtime.bundle import WAIST_SCHEMA_NAME, bundle_kind

        if bundle_kind(bundle_dir) == WAIST_SCHEMA_NAME:  # decision E57: a waist-only bundle
            given = [o for o, v in (("--protocol", protocol), ("--units", units), ("--method", method),
                                    ("--rules", rules), ("--min-confidence", min_confidence))
                     if v is not None] + [o for o, v in (("--contacts", contacts), ("--resample", resample),
                                                         ("--no-resample", no_resample), ("--align-units", align_units),
                                                         ("--clock-offset", clock_offset is not None),
                                                         ("--clock-drift-ppm", clock_drift is not None),
                                                         ("--common-span", common_span),
                                                         ("--warn-out-of-domain", warn_out_of_domain is not None),
                                                         ("--drop-neighbour", drop_neighbour),
                                                         ("--no-cycling", no_cycling),  # decision E304
                                                         ("--altitude", altitude != "foot"),  # E339 (E106: read)
                                                         ("--stair-rise", stair_rise is not None),
                                                         ("--length-reference", length_reference != "model"),
                                                         ("--heading-source", heading_source != "auto"),  # E285
                                                         ("--stair-grade", stair_grade is not None),
                                                         ("--gait", gait_other is not None),  # decision E311
                                                         ("--at-times", at_times is not None))  # decision E332
                                          if v]
            if given:
                raise DataError(f"run: {', '.join(given)} is for a foot-unit bundle; {bundle_dir} is a waist-only "
                                "bundle (give SESSION_DIR, and --start / --initial-heading / --chunk-s / --sides / "
                                "--out / --json)")
            return _run_waist(bundle_dir, session_dir, out, chunk_s, as_json, heading0, dpi, record, bouts,
                              storey_height, start_ll, start_alt, sides=sides,  # decision L142: as the foot bundle's
                              plot=plot,  # decision L533
                              start_ele=start_ele,  # decision L363
                              logged=logged,  # decision E154
                              drop_partial_row=drop_partial_row,  # decision B276
                              redact=redact)  # decision E176
        if sides:  # decision E110: W138's side is the lower-back contact's; a foot bundle tracks one foot's strides
            raise DataError(f"run: --sides gives a waist-only bundle's steps their foot; {bundle_dir} is a foot-unit "
                            "bundle, whose steps are the strides of the one foot it tracks: drop --sides")
        from pdrlearn.track.bouts import check_bout_unit

        check_bout_unit(bouts, "foot")  # decision W495 (amended): a foot bundle's strides, refused before the replay
        bundle = load_bundle(bundle_dir)  # verified before any output
        methods = bundle.choose_methods(method) if method is not None else None  # decision E52, before any work
        steps, lat, protocol_stats, session = [], [], None, None  # session: ground truth (a capture has none)
        at_t = None  # decision E332: --at-times in session seconds
        from pdrlearn.runtime.latency import DataLatency

        data_lat = DataLatency()  # decision E288: the steps' data latency (a capture's pushes: not measured)
        returned = []  # decision E344: per step, the time of the last sample of the push that returned it (s)
        if gait_other is not None and session_dir is None:  # decision E311: gait pairs two session folders
            raise DataError(f"run: --gait {gait_other} pairs SESSION_DIR with the other foot's session; "
                            + ("a --protocol capture is no session folder: " if protocol is not None else "")
                            + "give the two feet's session folders (pdrlearn run BUNDLE LEFT --gait RIGHT)")
        if protocol is not None and altitude != "foot":  # decision E339: the capture has no waist barometer
            raise DataError(f"run: --altitude {altitude} fuses the waist barometer; the --protocol capture "
                            f"{protocol} carries the foot unit only: drop --altitude, or replay a session folder "
                            "with wBarometer.csv")
        if protocol is not None and common_span:  # decision B230: a capture has one unit's streams, on one clock
            raise DataError(f"run: --common-span cuts a session's files to the time all of them cover; the --protocol "
                            f"capture {protocol} has no files: drop --common-span")
        if protocol is not None and drop_partial_row:  # decision B276: as B230's --common-span
            raise DataError(f"run: --drop-partial-row drops a session file's cut last row; the --protocol capture "
                            f"{protocol} has no files: drop --drop-partial-row")
        for option, asked in (("--align-units", align_units), ("--clock-offset", clock_offset is not None),
                              ("--clock-drift-ppm", clock_drift is not None)):
            if protocol is not None and asked:  # decisions L170, E112
                raise DataError(f"run: {option} moves the waist unit's clock onto the foot's; the --protocol capture "
                                f"{protocol} carries the foot unit only (one clock): drop {option}")
        alignment = None  # decision L170: the clock offset and drift --align-units applied
        cut_s = 0.0  # decision B267: the seconds a common-span cut took from the replayed unit (a capture: none)
        if protocol is not None:
            from pdrlearn.io import THESIS_FOOT_FRAME, BluetoothParser

            parser = BluetoothParser(rate_hz=bundle.rate_hz if protocol_rate is None else protocol_rate)  # E90
            use, _ = _units_for(bundle, units, None, f"protocol {protocol}")
            need = [s for s in bundle.sensors_of(use)[0] if not s.startswith("f")]
            if need:
                raise DataError(f"bundle {bundle.path} needs {', '.join(need)}, which the foot unit's "
                                "Bluetooth protocol does not carry; replay the foot unit alone (--units foot)")
            tracker = Tracker(bundle, heading_source=heading_source,  # decision E285
                              frames={**bundle.manifest["frames"], "foot": THESIS_FOOT_FRAME.to_dict()},
                              resample=resample_mode(resample, no_resample), rules=rules, min_confidence=min_confidence,
                              units=use, start=(0.0, 0.0, start_alt), contacts=contacts, heading_rad=heading0,
                              methods=methods, drop_neighbour=drop_neighbour,  # E101
                              cycling=not no_cycling,  # decision E304
                              length_reference=length_reference,  # decision C117
                              check_domain=True, warn_out_of_domain=warn_out_of_domain)  # decision E105
            if protocol == "-":
                stream = sys.stdin
            else:
                p = Path(protocol)
                if not p.is_file():
                    raise DataError(f"{p}: protocol capture not found")
                stream = p.open()
            with stream:
                for line in stream:
                    t0 = time.perf_counter()
                    new = tracker.push(parser.feed(line))
                    if new:
                        lat.append((time.perf_counter() - t0) / len(new))
                    steps += new
                steps += tracker.push(parser.close())
                steps += tracker.flush()
            if not parser.stats.measurements:  # decision B193: an empty capture had tracked "0 steps, 0.00 m", exit 0
                raise DataError(f"protocol {protocol}: no measurement sets ('$1 ax ay az$2 gx gy gz...' lines, "
                                f"thesis ch.4.2.3; {parser.stats.corrupted} corrupted line(s)) in the capture; check "
                                "the file or the serial port it was read from")
            source = f"protocol {protocol}"
            protocol_stats = {**parser.stats.to_dict(), "rate_hz": parser.rate_hz}
            from pdrlearn.io.protocol import protocol_rate_line

            rate_line = protocol_rate_line(parser.streams(), parser.rate_hz, f"protocol {protocol}")  # decision E90
            if rate_line:
                import logging

                logging.getLogger("pdrlearn.cli").warning("%s", rate_line)
            if parser.stats.corrupted:
                import logging  # printed as one "warning:" line by the CLI, like every warning (decision B13)

                logging.getLogger(__name__).warning(
                    "%s: %d corrupted line(s) skipped (e.g. line %d: %r; decision B432: a value beyond any "
                    "sensor's range is one too) of %d set(s) read", protocol, parser.stats.corrupted,
                    parser.stats.first_line, parser.stats.examples[0], parser.stats.sets)
            if parser.stats.lost:  # decision E91: only numbered sets show a loss
                import logging

                logging.getLogger(__name__).warning(
                    "%s: %d set(s) lost (%.1f %% of %d; the sets' sequence numbers skip them, decision E91): the clock "
                    "leaves their time empty, as a recording's gap", protocol, parser.stats.lost,
                    100.0 * parser.stats.lost / (parser.stats.lost + parser.stats.sets),
                    parser.stats.sets + parser.stats.lost)
        else:
            if session_dir is None:
                raise DataError("run: give a SESSION_DIR or --protocol FILE")
            from pdrlearn.errors import shell_quote
            from pdrlearn.io import read_session

            if gait_other is not None:  # decision E311: the two feet's pair checked before any replay
                from pdrlearn.cli.run_gait import gait_pair

                pair = gait_pair(session_dir, gait_other)
            run_command = f"pdrlearn run {shell_quote(bundle_dir)} {shell_quote(session_dir)}"  # B274, B279
            # decision L77: its drops warning; B230: --common-span as track's (B81 / B83's cut)
            session = read_session(session_dir, streamed=True, spans="common" if common_span else "refuse",
                                   drop_partial_row=drop_partial_row,  # decision B276: track's option, one mechanism
                                   command=run_command)  # decision B279: a cut last row names `run`'s option
            from pdrlearn.track.belt import check_belt_keys, session_where

            check_belt_keys(session.meta, session_where(session))  # decisions L454, B365: as track, before tracking
            if at_table is not None:  # decision E332: the times inside the recording, in order, before the replay
                from pdrlearn.track.at_times import check_forward, times_in_session
                from pdrlearn.track.clock import recording_start

                at_t = check_forward(times_in_session(at_table, at_label, session,
                                                      recording_start(session.meta, session.where)), at_label)
            from pdrlearn.io.plasys import unit_ends

            ends_read = session._unit_ends_uncut or unit_ends(session.streams)  # decision B267: before any cut
            rates = {n: st.rate_hz for n, st in session.streams.items()}
            where = f"session '{session.name}'"
            use, said = _units_for(bundle, units, set(session.streams), where)
            required, optional = bundle.sensors_of(use)
            rates = {n: r for n, r in rates.items() if n[0] in {u[0] for u in use}}  # a foot-only replay: no waist
            bundle.check_streams(rates if no_resample else {n: float("nan") for n in rates}, where=where, units=use)
            from pdrlearn.classify.force_scale import bundle_force, force_scale_line

            # decision C153: the bundle's training force against the session's (B398: none in an older bundle)
            line = force_scale_line(bundle_force(bundle.manifest), session)
            if line and "foot" in use:
                import logging

                logging.getLogger("pdrlearn.cli").warning(line)
            from pdrlearn.track.plasys import require_stride_cover

            # decisions L161, L170, E111: as track's; B230: a clock moved by --clock-offset / --align-units before B21's
            # cover check (a waist clock 2 s late covers the foot's time once moved; an overhang is cut, L162)
            moved = align_units or clock_offset is not None or clock_drift is not None  # B265: also the drift
            if moved:
                session, alignment = _unit_clocks(session, use, align_units, clock_offset, clock_drift)
            from pdrlearn.track.units import check_tracked_span, span_cut_s

            if "foot" in use and "waist" in use:  # decisions B274, B278: track's span check (B126, B264), before B21's
                check_tracked_span(session, "foot", run_command, alone="foot")  # the runtime needs the foot unit (E26)
            require_stride_cover(session, [*required, *optional], "pdrlearn run")  # decision B21; B230: names run's
            # decisions B267, B273: the seconds of the walk the replay does not cover (a moved waist clock mapped first)
            cut_s = span_cut_s(ends_read, session, "foot" if "foot" in use else "waist", alignment if moved else None)
            if "foot" in use:
                _foot_checks(session)  # decisions B201, B203, as `track`
            if not moved:  # L161's check on clocks the recording's cover check accepted
                session, alignment = _unit_clocks(session, use, align_units, clock_offset, clock_drift)
            # gaps: the runtime warns once per gap and moves a stride across a foot gap over 1 s 0 m (decision E30)
            # the session's rates (median interval, the rates check_streams judged) and where each stream ends:
            # the runtime resamples at these rates and announces it in one line; a stream behind the others
            # before its end is in a gap, which the steps wait for (E22/E23: chunk sizes give the same steps)
            # decision L177: run checked the clocks on the recording above (L170), the same numbers: no second line
            # decision E230: run said the intervals of dropped samples when it read the session (L77): not again
            from pdrlearn.runtime.baro_fusion import replay_altitude

            # decision E339, as track's L154: no waist barometer tracked (E357: the lean replay's rule too); E363: the
            # session's file is missing, so its folder is named (as track's L154), not the bundle's
            fuse = replay_altitude(altitude, use, units, "run", session.where)
            if fuse == "fused" and not (session.has("wBarometer") and len(session["wBarometer"])):
                import logging

                from pdrlearn.kernels.barometer import FUSED_WITHOUT_BAROMETER

                logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, FUSED_WITHOUT_BAROMETER)
                fuse = "foot"
            if fuse == "fused":
                from pdrlearn.kernels.barometer import FUSED_EFFECT
                from pdrlearn.track.barometer import usable_barometer

                baro_lines: list[str] = []  # decision B188, as track's L154: an impossible pressure is not fused
                if usable_barometer(session, baro_lines, FUSED_EFFECT) is None:
                    import logging

                    fuse = "foot"
                    for line in baro_lines:
                        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
            tracker = Tracker(bundle, heading_source=heading_source,  # decision E285
                              frames=frames_of(session, bundle, use), clock_check=False, stream_checks=False,
                              resample=resample_mode(resample, no_resample), rules=rules, min_confidence=min_confidence,
                              input_rates_hz=rates, units=use,
                              sensors=[n for n, st in session.streams.items() if len(st)],
                              start=(0.0, 0.0, start_alt), contacts=contacts, heading_rad=heading0, methods=methods,
                              stream_ends_s={n: float(st.t[-1]) for n, st in session.streams.items() if len(st)},
                              max_gap_s=math.inf,  # B141: a recording's gaps are its own (its clock checked: B73)
                              drop_neighbour=drop_neighbour,  # E101
                              cycling=not no_cycling,  # decision E304
                              length_reference=length_reference,  # decision C117
                              altitude=fuse,  # decision E339
                              check_domain=True, warn_out_of_domain=warn_out_of_domain)  # decision E105
            from pdrlearn.classify.users import bundle_own_user

            tracker.domain_user = bundle_own_user(bundle, session)  # decision C227
            dropped = "waist" in bundle.body_units and "waist" not in tracker.units  # --units foot (E26)
            if tracker.heading_source == "auto" and not said and (dropped or not (
                    session.has("wAccelerometer", "wGyroscope") and "waist" in tracker.forward)):  # as track says (B17)
                import logging

                from pdrlearn.track.plasys import NO_WAIST_HEADING, no_waist_heading

                line = no_waist_heading(session)  # decision B153: an incomplete waist unit names its missing file
                if dropped and any(n.startswith("w") and len(st) for n, st in session.streams.items()):
                    # decision E45: the session has a waist unit --units foot leaves out; not "no waist unit"
                    line = "waist unit not used (--units foot): " + NO_WAIST_HEADING.removeprefix("no waist unit: ")
                logging.getLogger("pdrlearn.cli").warning("%s: %s", session.name, line)
            if "waist" in tracker.units:  # decision W125: W105's check on the waist gyroscope the heading turns by
                from pdrlearn.waist.plausibility import waist_bias_line

                line = waist_bias_line(session)
                if line:
                    import logging

                    logging.getLogger("pdrlearn.cli").warning("%s: %s", session.name, line)
            bounds = [float(st.t[i]) for st in session.streams.values() if len(st) for i in (0, -1)]
            # decision E131: the recording's seconds replayed and the time left, on a terminal (not with --json)
            with GapLines(session.name), clock_progress(f"run {session.name}", min(bounds, default=0.0),
                                                        max(bounds, default=0.0),
                                                        enabled=not as_json) as reached:
                for chunk in replay_chunks({n: (st.t, st.values) for n, st in session.streams.items()}, chunk_s):
                    t0 = time.perf_counter()
                    new = tracker.push(chunk)
                    if new:
                        lat.append((time.perf_counter() - t0) / len(new))
                    steps += new
                    data_s = max((float(t[-1]) for t, _ in chunk.values() if len(t)), default=0.0)
                    data_lat.add(new, data_s)  # decision E288
                    returned += [data_s] * len(new)  # decision E344
                    reached(data_s)
                tail = tracker.flush()
                steps += tail
                returned += [max(bounds, default=0.0)] * len(tail)  # decision E344: the flush, at the recording's end
            _warn_short_streams(session, tracker, steps)
            source = f"session {session.name}"
        result = streamed_result(steps, start_ll, start_alt)
        if tracker.foot_altitude_change_m is not None:  # decision E339: as track's L154 info (L145 / L127 read it)
            result.info["altitude_source"] = "fused"
            result.info["foot_altitude_change_m"] = tracker.foot_altitude_change_m
        if session is not None and "foot" in tracker.units:  # decision E293: track's rides (L378, L624), rides.csv
            from pdrlearn.track.rides import foot_rides
            from pdrlearn.track.units import with_left_out_units

            foot_rides(result, with_left_out_units(session))  # L615's vibration reading on, as track's default
        _side_class_lines(result.steps, bundle, source if session is None else session.name)  # decision E287
        from pdrlearn.track.position_sigma import add_position_sigma, sigma_params

        # decisions L128/L150, as `track --streaming`: the waist gyroscope's heading when the tracker uses the waist
        # unit; decision E342: its offset term by the tracker's cycle_yaw (E336), as track --streaming's info says
        regime = "plasys-streaming" if "waist" in tracker.units else "plasys-foot-streaming"
        add_position_sigma(result, session, regime,
                           params=sigma_params(regime, {**result.info, "cycle_yaw": tracker.cycle_yaw}))
        as_written(result)  # decision E157: the summary from the tables as written, whatever the chunk size
        if heading0 is not None:  # decision L98: recorded; path.png draws the track in ENU
            result.info["initial_heading_rad"] = heading0
        # L170, E111, B265: as track's info (L162); None: the steps did not align
        if align_units or clock_offset is not None or clock_drift is not None:
            result.info["unit_alignment"] = alignment
        result.info.update(written_floats(tracker.height_checks()))  # decision E47: track's L69 / C28 checks; E157
        # decision E105: track's C16 report (flush warned C61's); E157: at the CSVs' digits
        result.info["out_of_domain"] = written_floats(tracker.domain_report())
        if session is not None:  # decision B456: the clipped share of each IMU file, as track's info
            from pdrlearn.io.plasys import clipped_shares

            result.info["clipped_share"] = clipped_shares(session)
        if stair_rise_m is not None:  # decision L432: stairs.csv's n_stairs, as track's info
            result.info["stair_rise_m"] = stair_rise_m
        record_stair_grade(result, stair_grade_pct)  # decision L469: the summary's and stairs.csv's grade
        # E73: bouts.csv and n_bouts at once; L195: each bout's walking range scaled to the walker's leg
        table = track_bouts(result, session, bouts)  # decision W480
        from pdrlearn.track.periods import bout_floors

        # decision L458: each bout's floors by the summary's climbs, as track's bouts.csv (L450)
        table = bout_floors(table, result.steps, result.info, storey_height)
        summary = _summary(steps, tracker, lat, source, result, session, storey_height, bouts, table)
        summary["common_span_cut_s"] = cut_s  # decision B267, as track's
        summary["steady_trim"] = 0  # decision L415, as track's key (B14): `run` has no --steady-trim
        if protocol_stats is not None:  # the README's "corrupted measurements are skipped and counted"
            summary["protocol"] = protocol_stats
        keep_warnings(summary, logged, session)  # decision E154
        gait = None
        if gait_other is not None:  # decision E311: gait's result of the two feet's streamed strides
            from pdrlearn.cli.run_gait import run_gait

            gait = run_gait(bundle, pair, chunk_s=chunk_s, said=logged, methods=methods, rules=rules,
                            min_confidence=min_confidence, resample=resample_mode(resample, no_resample),
                            drop_neighbour=drop_neighbour, cycling=not no_cycling, length_reference=length_reference)
        if out is not None:  # decision E157: the push times in run.json, not summary.json
            _write(out, result, summary, session, source, dpi=dpi, record=record(latency_ms_per_step=_latency(lat),
                   data_latency_ms=data_lat.report(None if protocol is not None else chunk_s)),  # decision E288
                   bouts=table, with_ele=start_ele, redact=redact, plot=plot, gait=gait,  # decision L533
                   at_times=at_t, returned_s=returned)  # decisions E332, E344
        if as_json:
            shown = redacted(json_safe(summary), redact)
            if gait is not None:  # decision E311: gait_summary.json's object, not in summary.json
                from pdrlearn.redact import GAIT_SUMMARY_FIELDS, redact_json

                shown["gait"] = redact_json(_gait_summary(gait), redact, fields=GAIT_SUMMARY_FIELDS) if redact \
                    else _gait_summary(gait)
            print_json(shown)
        else:
            err = summary.get("distance_error_pct")
            from pdrlearn.track.evaluate import floors_phrase  # decisions L64, L127 (numpy: lazily)

            typer.echo(f"{source}: {count_phrase(summary)}, {summary['distance_m']:.2f} m"
                       + _track.distance_error_phrase({"distance_error_pct": err,  # decision L743, as track's
                                                       "distance_ref_m": summary.get("distance_ref_m")})
                       + ", final position "
                       f"{[round(summary['final_position'][k], 2) for k in 'xyz']}"
                       + _track.position_error_phrase(summary)  # decision E206: as track's line
                       # L64: the storeys climbed and descended, when the track changed floors
                       + floors_phrase(summary)
                       + (f" -> {out}" if out else ""))
            if summary.get("gait_speed_mps") is not None:  # decisions E48 / E51: track's L79 line, what run can give
                typer.echo(gait_line(summary, streamed=True))  # decision L204: no cadence without --contacts
            flights = _track.flights_line(summary)  # decision L432: as track's line (review R3 finding 6)
            if flights:
                typer.echo(flights)
            ramps = _track.written_ramps_line(summary, out)  # decision L571: as track's line
            if ramps:
                typer.echo(ramps)
            if gait is not None:  # decision E311: gait's lines of the streamed strides
                from pdrlearn.cli.gait import result_lines

                for line in result_lines(gait, "replayed"):
                    typer.echo(line)


def _gait_summary(gait: dict) -> dict:
    """Decision E311: gait_summary.json's object of ``run --gait``'s pair (``gait``'s own, json-safe)."""
    from pdrlearn.cli.gait import summary_json

    return json_safe(summary_json(gait))


def _foot_checks(session) -> None:
    """Decisions B203 (refused: force sensors that step beside a foot IMU that never moves), B201 (warned: the
    foot accelerometer's rest |acc| off 1 g) and L406 (warned: insoles that disagree with the foot IMU, L365's
    check), as ``track`` does, before the replay."""
    import logging

    from pdrlearn.displace.force_check import streamed_insole_line
    from pdrlearn.errors import DataError
    from pdrlearn.track.foot_rest import foot_rest_stats, foot_scale_warning, frozen_foot_imu

    frozen = frozen_foot_imu(session)
    if frozen:
        raise DataError(frozen)
    line = foot_scale_warning(foot_rest_stats(session), session.where)
    if line:
        logging.getLogger("pdrlearn.cli").warning("%s", line)
    insole = streamed_insole_line(session, "pdrlearn run")
    if insole:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, insole)


def redacted(obj, redact: tuple[str, ...] | None):
    """Decision E176: ``--json``'s object with ``redact``'s paths as <redacted> (unchanged without the option)."""
    from pdrlearn.redact import redact_json

    return redact_json(obj, redact) if redact else obj


def _run_json(arguments: dict, wall0: float, cpu0: float):
    """Decision L122: ``run``'s OUT/run.json (``pdrlearn.cli.provenance``, as ``track``'s and ``track-all``'s): the
    bundle as given with its manifest's SHA-256 (= its manifest.sha256), the session or capture as given, every
    option, and the wall and CPU time from ``wall0`` / ``cpu0`` to when the record is made (a function: called when
    the outputs are written)."""
    from pdrlearn.cli.provenance import given_options, model_record, run_record

    options = given_options(arguments, leave_out=("bundle_dir", "session_dir", "out", "force", "as_json"))
    session = arguments.get("session_dir")

    def record(**times) -> dict:  # decision E157: the push times (latency_ms_per_step) with the others, here
        return run_record("run", options, session=None if session is None else str(session),
                          bundle=model_record(arguments["bundle_dir"]),
                          track_time_s=round(time.perf_counter() - wall0, 2),
                          cpu_time_s=round(time.process_time() - cpu0, 2), **times)

    return record


def _calibration_gait_warning(params, steps, warnings: list[str], where: str) -> None:
    """Decisions W140, W141, W211, E142, as ``track``: a bundle calibrated on walks of another cadence than this run's
    steps warns in one line (logged and appended to ``warnings``): W140's with the option ``gait_check`` in the
    calibration's PARAMS.json, else W211's speed line (option ``speed_check``, on unless the PARAMS.json sets it
    false) outside the calibration's cadence range (``gait.cadence_range_spm``; a bundle exported from a calibration
    before W211: its ``median_cadence_spm`` for both ends, as ``track`` reads such a file) +-10 %. A bundle without the
    calibration's ``gait`` (exported before W140) is not judged."""
    import logging

    from pdrlearn.waist.lengths import step_frequency
    from pdrlearn.waist.plausibility import calibration_line, median_cadence

    if getattr(params, "source", None) != "calibrated" or not len(steps):
        return
    line = calibration_line(getattr(params, "gait", None), *median_cadence(step_frequency(steps)),
                            getattr(params, "pipeline", None) or "waist-pendulum",
                            gait_check=bool(getattr(params, "gait_check", False)),
                            speed_check=bool(getattr(params, "speed_check", True)))
    if line:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", where, line)
        warnings.append(line)


def _run_waist(bundle_dir: Path, session_dir: Path | None, out: Path | None, chunk_s: float, as_json: bool,
               heading0: float | None, dpi: int | None, record, bouts=None, storey_height_m: float = 3.0,
               start_ll=None, start_alt: float = 0.0, sides: bool = False, drop_partial_row: bool = False,
               start_ele: bool = False, logged: list[str] | None = None,
               redact: tuple[str, ...] | None = None, plot: bool = True) -> None:
    """``pdrlearn run WAIST_BUNDLE SESSION`` (decision E57): the session's lower-back accelerometer and gyroscope
    pushed in ``chunk_s`` slices through :class:`pdrlearn.runtime.WaistTracker` (the gyroscope read at the
    accelerometer's times, as ``track``'s ``body_data``). The frame is the session's declared one (warned when the
    bundle records another), else the bundle's, else inferred from the data (D8). Writes and prints what ``run``
    does for a foot bundle, with ``track``'s waist step columns; the floor counts in storeys of ``storey_height_m``
    (``--storey-height``, decision L142: it had been left at 3 m). ``--start LAT,LON[,ALT]`` (``start_ll``,
    ``start_alt``): the tracker's lat/lon of each step (decision W147) and z at ALT, as the foot bundle's run.
    ``sides`` (``--sides``, decision E110): the runtime's causal side of each step (E103) in steps.csv's ``side``
    column, the offline lower-back track's name and values (``left`` / ``right`` / empty when undecided).
    ``logged``: the warnings ``run`` caught so far, added to the summary's (decision E154). ``redact``: the paths
    ``--redact-paths`` writes as <redacted> (decision E176)."""
    import numpy as np
    import pandas as pd

    from pdrlearn.errors import DataError, MissingSensorError
    from pdrlearn.io import read_session
    from pdrlearn.runtime.waist import WAIST_SENSORS, WaistTracker, load_waist_bundle
    from pdrlearn.signal import interp_rows
    from pdrlearn.track.base import TrackResult
    from pdrlearn.track.bouts import session_ids, track_bouts
    from pdrlearn.track.evaluate import evaluate_track, floors_phrase, summary_info

    bundle = load_waist_bundle(bundle_dir)  # verified before any output
    if session_dir is None:
        raise DataError("run: give a SESSION_DIR")
    from pdrlearn.errors import shell_quote

    session = read_session(session_dir, streamed=True, drop_partial_row=drop_partial_row,  # decision B276
                           command=f"pdrlearn run {shell_quote(bundle_dir)} {shell_quote(session_dir)}")  # B279
    from pdrlearn.track.belt import check_belt_keys, session_where

    check_belt_keys(session.meta, session_where(session))  # decisions L454, B365: as track, before tracking
    missing = [n for n in WAIST_SENSORS if not session.has(n)]
    if missing:
        raise MissingSensorError(f"session '{session.name}' ({session_dir}) has no {', '.join(missing)}, which the "
                                 f"waist bundle {bundle_dir} tracks; record the lower-back accelerometer and gyroscope")
    a, g = session["wAccelerometer"], session["wGyroscope"]
    gyr = g.values if len(g) == len(a) and np.allclose(g.t, a.t, atol=1e-6) else interp_rows(a.t, g.t, g.values)
    declared = session.frames.get("waist")  # as the foot run's frames: the session's declared frame first
    frame = None
    if declared is not None:  # checked against the data once, as the foot run's frames (D10, with its warning)
        frame = session.require_frame("waist").matrix()
        if bundle.rotation is not None and not np.allclose(frame, bundle.rotation):
            import logging

            logging.getLogger("pdrlearn.cli").warning(
                "%s: the session declares the waist frame %s, the bundle records %s; using the session's",
                session.name, declared.to_dict(), bundle.manifest["frames"].get("waist"))
    elif bundle.rotation is None:
        frame = session.require_frame("waist").matrix()  # inferred from the data (D8, with its warning)
    tracker = WaistTracker(bundle, fs=a.rate_hz, heading_rad=heading0 or 0.0, frame=frame, sides=bool(sides),  # E110
                           start_latlon=None if start_ll is None else (*start_ll, start_alt))  # decision W147
    from pdrlearn.track.barometer import usable_barometer
    from pdrlearn.track.waist import NO_BAROMETER

    baro_lines: list[str] = []
    baro = usable_barometer(session, baro_lines)  # decision E106: the offline track's barometer (B188's check)
    if baro is None and not baro_lines:
        baro_lines.append(NO_BAROMETER)  # decision W90's line, as track's
    for line in baro_lines:
        import logging

        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.name, line)
        tracker.warnings.append(line)
    steps, lat = [], []
    k = np.floor((a.t - a.t[0]) / chunk_s).astype(np.int64)  # decision E28's chunks, counted from the first sample
    kb = None if baro is None else np.floor((baro.t - a.t[0]) / chunk_s).astype(np.int64)
    jb = 0  # the barometer samples pushed so far
    with clock_progress(f"run {session.name}", a.t[0], a.t[-1], enabled=not as_json) as reached:  # decision E131
        for c in np.unique(k):
            i = np.flatnonzero(k == c)
            if kb is not None:  # E106: the barometer up to the chunk's end, before its motion samples
                j1 = int(np.searchsorted(kb, c, side="right"))
                tracker.push_barometer(baro.t[jb:j1], baro.values[jb:j1, 0])
                jb = max(jb, j1)
            t0 = time.perf_counter()
            new = tracker.push(a.t[i], a.values[i], gyr[i])
            if new:
                lat.append((time.perf_counter() - t0) / len(new))
            steps += new
            reached(a.t[i[-1]])
    if kb is not None and jb < len(kb):  # the barometer's samples after the motion's last chunk
        tracker.push_barometer(baro.t[jb:], baro.values[jb:, 0])
    steps += tracker.flush()
    cols = ["start_s", "end_s", "event_s", "length_m", "heading_rad", "dz_m", "pause_dz_m", "stairs", "unit",
            "has_next", "merged", "turning"]
    df = pd.DataFrame([{"start_s": s.t, "end_s": s.end_s, "event_s": s.t, "length_m": s.length_m,
                        "heading_rad": s.heading_rad, "dz_m": s.dz_m if s.dz_m is not None else 0.0,
                        "pause_dz_m": s.pause_dz_m if s.pause_dz_m is not None else 0.0,  # W158, as track's
                        "stairs": bool(s.stairs), "unit": "waist",  # E106/E107: W91's test, as track's column
                        "has_next": s.has_next, "merged": s.merged, "turning": s.turning} for s in steps], columns=cols)
    if sides:  # decision E110: after stairs, as the offline track's columns (W129); "" = undecided, as offline
        df.insert(cols.index("stairs") + 1, "side", pd.Series([s.side or "" for s in steps], dtype=object))
    traj = pd.DataFrame({"t": [float(a.t[0])] + [s.end_s for s in steps],
                         "x": [0.0] + [s.x for s in steps], "y": [0.0] + [s.y for s in steps]})
    # decision L56: z starts at --start's ALT; E106: the barometric altitude of each step (W89), as track's
    traj["z"] = float(start_alt) + np.concatenate([[0.0], np.cumsum(df["dz_m"].to_numpy(float)
                                                                     + df["pause_dz_m"].to_numpy(float))])
    if start_ll is not None:  # decision W147: the live tracker's lat/lon of each step
        traj["lat"] = [start_ll[0]] + [s.lat for s in steps]
        traj["lon"] = [start_ll[1]] + [s.lon for s in steps]
    from pdrlearn.kernels.barometer import step_jump_line, step_jumps
    from pdrlearn.track.freezes import lower_back_freezes

    jumps = None
    if baro is not None:  # decision E148: W230's line, as track's (the live tracker does not hold such steps)
        jumps = int(step_jumps(df["dz_m"].to_numpy(float)).sum())
        line = step_jump_line(df["dz_m"].to_numpy(float), df["end_s"].to_numpy(float), hold=False, live=True)
        if line:
            import logging

            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.name, line)
            tracker.warnings.append(line)
    result = TrackResult(steps=df, trajectory=traj, info={"pipeline": "runtime-waist",
                                                          "warnings": list(tracker.warnings),
                                                          "barometer_jump_steps": jumps,  # W230 (E148), as track's
                                                          # decision L309: the rests L296 corrected live (L306)
                                                          "rest_bias_rests": None if tracker.rest_bias_rests is None
                                                          else [list(r) for r in tracker.rest_bias_rests],
                                                          # decision W216: as track's, opt-in by the options
                                                          "freezes": lower_back_freezes(
                                                              session, "runtime-waist", bundle.options)})
    _calibration_gait_warning(bundle.params, df, result.info["warnings"], session.name)  # W140, W211 (E142)
    from pdrlearn.track.position_sigma import add_position_sigma

    add_position_sigma(result, session, "waist")  # decision L128, as track's lower-back pipelines
    as_written(result)  # decision E157: the summary from the tables as written, whatever the chunk size
    # L124, E73: one detection (L165: key; L195: the leg-scaled range)
    table = track_bouts(result, session, bouts)  # decision W480
    from pdrlearn.track.periods import bout_floors

    # decision L458: each bout's floors by the summary's climbs, as track's bouts.csv (L450)
    table = bout_floors(table, result.steps, result.info, storey_height_m)
    summary = {"source": f"session {session.name}", **evaluate_track(result, session, bouts=bouts, bout_table=table,
                                                                       storey_height_m=storey_height_m),
               "session": session.name, **session_ids(session),  # decision C100, as track's
               "pipeline": "runtime", "bundle_kind": "waist", "info": summary_info(result.info),  # E141
               "final_position": {"x": written_floats(float(tracker.position[0])),  # decision E157
                                  "y": written_floats(float(tracker.position[1])), "z": float(traj["z"].iloc[-1]),
                                  **({} if start_ll is None else {k: float(traj[k].iloc[-1]) for k in ("lat", "lon")})}}
    from pdrlearn.track.evaluate import add_gait_range_flag
    from pdrlearn.waist.plausibility import withhold_step_count

    withhold_step_count(summary)  # decision W476, as track's summary (a live waist run judges no W442: null)
    add_gait_range_flag(summary)  # decision L195: the flag as track's summary has it (this path warns no L95 line)
    keep_warnings(summary, logged or [], session)  # decision E154
    if out is not None:  # decision E157: the push times in run.json, not summary.json
        _write(out, result, summary, session, summary["source"], dpi=dpi,
               record=record(latency_ms_per_step=_latency(lat)), bouts=table, with_ele=start_ele, redact=redact,
               plot=plot)  # decision L533
    if as_json:
        print_json(redacted(json_safe(summary), redact))  # decision E176
        return
    err = summary.get("distance_error_pct")
    typer.echo(f"{summary['source']}: {count_phrase(summary)}, {summary['distance_m']:.2f} m"
               + _track.distance_error_phrase({"distance_error_pct": err,  # decision L743, as track's
                                               "distance_ref_m": summary.get("distance_ref_m")})
               + ", final position "
               f"{[round(summary['final_position'][k], 2) for k in 'xyz']}"
               + _track.position_error_phrase(summary)  # decision E206: as track's line
               + floors_phrase(summary)  # decisions L64, E106: the storeys the barometer climbed, as track's line
               + (f" -> {out}" if out else ""))


def streamed_result(steps, start_ll=None, start_alt: float = 0.0):
    """The runtime's steps as a :class:`~pdrlearn.track.base.TrackResult` with the columns of ``track``:
    the length class column is ``length_class`` (decisions B14, B142: ``Step.to_dict``'s), ``unit`` is ``foot``,
    ``heading_rad`` wrapped to [-pi, pi) as ``track`` writes it (the runtime's heading is unwrapped), the
    trajectory has ``t, x, y, z, lat, lon`` (lat/lon from ``start_ll`` = ``--start LAT,LON`` by ``track``'s
    geodetic update, else empty; z from ``start_alt``, the altitude the Tracker started at, decision L56)."""
    import pandas as pd

    from pdrlearn.orient import wrap_angle
    from pdrlearn.runtime.replay import STEP_COLUMNS
    from pdrlearn.track.base import TrackResult
    from pdrlearn.track.gait import streamed_gait_columns
    from pdrlearn.track.geodetic import geodetic_track

    df = pd.DataFrame([st.to_dict() for st in steps])  # the length class is length_class (B14, B142)
    if df.empty:
        df = pd.DataFrame(columns=["start_s", "end_s", "event_s", "length_m", "heading_rad", "dz_m", "impossible",
                                   "gap_s", "sideways"])  # L243
    first = [c for c in STEP_COLUMNS if c in df.columns]
    df = df[first + [c for c in df.columns if c not in first]]
    heading = df["heading_rad"].to_numpy(float)
    df["heading_rad"] = wrap_angle(heading)
    # every runtime step is a stride of the foot unit (the Tracker needs it); track's `unit` column also lets
    # evaluate_track score the strides (step_f1, decision L36) as it does for `track`
    df["unit"] = "foot"
    df = streamed_gait_columns(df)  # decision E50: stride time, cadence, speed from the runtime's contacts (E49)
    traj = [{"t": steps[0].start_s, "x": 0.0, "y": 0.0, "z": float(start_alt)}] if steps else []
    traj += [{"t": st.end_s, "x": st.x, "y": st.y, "z": st.z} for st in steps]
    traj = pd.DataFrame(traj, columns=["t", "x", "y", "z"]).assign(lat=float("nan"), lon=float("nan"))
    if start_ll is not None and len(traj):  # as track_streaming: eq. 56/57 along each step's direction
        ll = geodetic_track(tuple(start_ll), df["length_m"].to_numpy(float), heading)
        traj["lat"], traj["lon"] = ll[:, 0], ll[:, 1]
    return TrackResult(steps=df, trajectory=traj, info={"pipeline": "runtime"})


def _summary(steps, tracker, lat, source, result, session, storey_height_m: float = 3.0, bouts=None,
             bout_table=None) -> dict:
    """The keys of ``track``'s summary.json for the same content (``distance_m``, ``n_steps``,
    ``final_position`` {x, y, z}, ``session``, ``pipeline``, ``info``, ``frames_inferred`` when a frame was
    taken from the data and, replaying a session with ground truth, its errors), plus the runtime's
    ``source``, ``methods``, ``classes`` and latency."""
    import numpy as np

    from pdrlearn.track.evaluate import domain_fraction, evaluate_track

    counts = {t: {} for t in tracker.classifiers}
    for st in steps:
        for t, c in st.classes.items():
            counts[t][c] = counts[t].get(c, 0) + 1
    out = {"source": source, **evaluate_track(result, session, bouts=bouts, bout_table=bout_table,
                                              storey_height_m=storey_height_m),
           **domain_fraction(result)}  # decision E105: as track's summary (C16)
    from pdrlearn.track.periods import time_accounting

    out.update(time_accounting(result, session))  # decision L275, as track's summary (B14)
    # lat/lon with --start, as track's summary (without it track has none: no NaN keys either)
    geo = {k: v for k, v in out["final_position"].items() if k in ("lat", "lon") and np.isfinite(v)}
    pos = [float(v) for v in tracker.position]
    if tracker.foot_altitude_change_m is not None and len(result.trajectory):  # decision E339: the fused z, not the
        pos[2] = float(result.trajectory["z"].iloc[-1])  # tracker's own (the foot's height)
    out["final_position"] = {**dict(zip("xyz", written_floats(pos), strict=True)),
                             **geo}  # decision E157: at the CSVs' digits
    if session is not None:
        from pdrlearn.track.bouts import session_ids
        from pdrlearn.track.clinical import contact_timing

        out.update(contact_timing(session, result.steps))  # decision L116, as track's summary
        out["session"] = session.name
        out.update(session_ids(session))  # decision C100: meta.json's subject and visit, as track's
        # cohort C13: the folder tracked, as track's summary.json (copies of a session share its name)
        out["input_dir"] = str(session.folder.resolve()) if session.folder is not None else None
    out["pipeline"] = "runtime"
    from pdrlearn import __version__
    from pdrlearn.track.evaluate import tracked_rate_hz

    out["rate_hz"] = tracked_rate_hz(session, "runtime") if session is not None else None  # as track's (C19)
    out["pdrlearn_version"] = __version__  # decision C18
    from pdrlearn.track.evaluate import summary_info

    out["info"] = summary_info(result.info)  # decision E141: what track's summary.json leaves out, one list
    from pdrlearn.waist.plausibility import withhold_step_count

    withhold_step_count(out)  # decision W476, as track's summary (the runtime judges no W442: the key is null)
    from pdrlearn.track.evaluate import add_gait_range_flag

    add_gait_range_flag(out)  # decision L195, as track's summary
    if session is not None:  # decisions L95 / L113, as track's summary: gait range, withheld stride-time CV
        import logging

        from pdrlearn.io.validate import foot_accel_clip_g
        from pdrlearn.track.evaluate import summary_warnings

        for line in summary_warnings(out, foot_clip_g=foot_accel_clip_g(session)):  # decision L688
            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.name, line)
            out["info"] = {**out["info"], "warnings": [*out["info"].get("warnings", []), line]}
    if session is not None:  # decision C142: each unit's frame status, as track's summary.json
        out.update({f"frame_{p}": session.frame_status(p) for p in ("foot", "waist")})
    if session is not None and session.frames_inferred:  # D8, as track's summary.json gives them
        out["frames_inferred"] = session.frames_inferred
    out.update({
        "methods": {**{t: f"{c.method}/{c.unit}" for t, c in tracker.classifiers.items()},
                    **{t: "none" for t in getattr(tracker, "unclassified", {})}},  # E26 amended, as track's
        "classes": counts,
    })
    return out


def keep_warnings(summary: dict, logged: list[str], session=None) -> None:
    """Decision E154: the warnings ``run`` logged (its reading, the runtime's, the summary's checks) added to the
    summary's ``info["warnings"]``, each once, without the session folder or name that starts them on stderr; E155:
    with their codes and the summary's ``schema_version``, as ``track``'s."""
    from pdrlearn.warning_lines import machine_summary

    machine_summary(summary, logged, [] if session is None else [session.where, session.name])


def _side_class_lines(steps, bundle, name: str) -> None:
    """Decision E287: ``track --streaming``'s C137 / L578 lines (side-step and turn-on-the-spot strides the direction
    model classed backward, :func:`pdrlearn.track.travel.side_class_warning`) on run's steps table, logged as run's
    other warnings (so also in summary.json, E154); C161's count of trained side steps from the bundle's manifest."""
    import logging

    from pdrlearn.classify.uncovered import trained_side_strides
    from pdrlearn.track.travel import side_class_warning

    lines: list[str] = []
    side_class_warning(steps, lines, trained_side_strides(bundle))
    for line in lines:
        logging.getLogger("pdrlearn.cli").warning("%s: %s", name, line)


def _latency(lat: list[float]) -> dict:
    """``latency_ms_per_step`` of a run's run.json (decision E157; a foot or a waist bundle's): the median and 99th
    percentile (ms) of the per-step push times ``lat`` (s), None without a step."""
    import numpy as np

    return {q: float(np.percentile(lat, n) * 1e3) if lat else None for q, n in (("p50", 50), ("p99", 99))}


def written_floats(value):
    """Decision E157: ``value`` (a float, or a dict / list of them, nested) with each float at the digits the CSV files
    hold (:data:`CSV_FLOAT_FORMAT`); other values unchanged. The runtime's floats differ in their last bits with the
    replay's chunk size (``--chunk-s 1`` vs ``7.3``: distance_m 89.95196841195369 vs ...381, trial T2), the written
    tables do not."""
    if isinstance(value, float):
        return float(CSV_FLOAT_FORMAT % value) if math.isfinite(value) else value
    if isinstance(value, dict):
        return {k: written_floats(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return type(value)(written_floats(v) for v in value)
    return value


def as_written(result) -> None:
    """Decision E157, in place: every float column of ``result``'s steps and trajectory at the digits the CSV files
    write (:data:`CSV_FLOAT_FORMAT`), so that ``run``'s summary, computed from them, is the summary of the tables as
    written and so the same for any ``--chunk-s`` (the CSV files are unchanged: they held these digits). Times (``t``,
    ``*_s``) are left as they are: they are the samples' own, the same for every chunk size, and 10 digits of an epoch
    time in seconds would be whole seconds."""
    import numpy as np

    for df in (result.steps, result.trajectory):
        for c in df.columns:
            if df[c].dtype.kind == "f" and c != "t" and not c.endswith("_s"):
                v = np.array(df[c], dtype=float)
                ok = np.isfinite(v)
                v[ok] = np.char.mod(CSV_FLOAT_FORMAT, v[ok]).astype(float)
                df[c] = v


def _write(out: Path, result, summary, session=None, source: str = "", *, dpi: int | None = None,
           record: dict, bouts, with_ele: bool = False, redact: tuple[str, ...] | None = None,
           plot: bool = True, gait: dict | None = None, at_times=None, returned_s=None) -> None:
    """steps.csv, trajectory.csv, bouts.csv (L124), turns.csv (L200), path.png (not with ``plot`` false: ``--no-plot``,
    decision L533), summary.json and run.json
    (``record``, decision L122) as ``track`` writes them (same names, columns, number format, ``track``'s figure),
    atomically: all seven or none, and ``--force`` keeps the old run until then. ``session``: the replayed session
    (its ground truth in path.png; None for a capture). Decision E144: a replayed session whose meta.json gives its
    recording start gets track's clock columns and summary ``recording_start`` (L298); a capture has no meta.json and
    no clock start, so none. Decision L363: with lat/lon (``--start``) also track's track.gpx and track.geojson
    (``with_ele``: ``--start LAT,LON,ALT`` gave the altitude). ``redact``: decision E176's paths, written as
    <redacted> in every text file before the folder is moved into place. ``at_times`` (decision E332): session
    seconds whose live positions (:func:`pdrlearn.track.at_times.live_positions` of the written trajectory, each
    stride row shown from ``returned_s``, the time of the push that returned it: decision E344) go to at_times.csv."""
    import json

    from pdrlearn.atomic import atomic_directory
    from pdrlearn.cli.provenance import write_run_json
    from pdrlearn.track.clock import clock_texts, recording_start
    from pdrlearn.track.folder import event_tables
    from pdrlearn.track.plots import plot_paths

    start = recording_start(session.meta, session.where) if session is not None else None  # E144
    if start is not None:  # decision L298: the clock time of the recording's first sample
        summary["recording_start"] = clock_texts(start, [session.t_recording_start])[0]
    was = existed(out)
    with atomic_directory(out) as tmp:
        from pdrlearn.track.evaluate import with_reference_columns

        steps = with_reference_columns(result, session)  # decision E135: the reference pairs, as track
        write_table_csv(steps, tmp / "steps.csv")  # decision E164: an epoch time keeps its decimals
        from pdrlearn.track.floor_column import with_floor_columns

        traj = with_floor_columns(result.trajectory, result, summary.get("storey_height_m"))  # L630, L631
        from pdrlearn.track.rides import with_ride_column

        traj = with_ride_column(traj, result.info)  # decisions L623, E293: as track's trajectory.csv
        write_table_csv(traj, tmp / "trajectory.csv")
        if at_times is not None:  # decision E332: the position the live track showed at each checkpoint time
            from pdrlearn.track.at_times import live_positions

            # decision E344: a stride's row from the time its push returned it, not from its end
            write_table_csv(live_positions(traj, at_times, start, returned_s=returned_s), tmp / "at_times.csv")
        # L124 (E98), L200, L202: bouts.csv, turns.csv ... as track; E144: its clock columns
        tables = event_tables(result, bouts, start=start)
        for name, table in tables.items():
            write_table_csv(table, tmp / name)
        if plot:  # decision L533
            plot_paths({"runtime": result}, tmp / "path.png", session=session, title=f"{source}: pdrlearn run",
                       dpi=dpi)
        (tmp / "summary.json").write_text(json.dumps(json_safe(summary), indent=2) + "\n")
        from pdrlearn.track.geoexport import write_geo_files
        from pdrlearn.track.ramp_audit import route_features

        write_geo_files(tmp, traj, session=summary.get("session") or source,  # decision L363, as track
                        pipeline=summary.get("pipeline"), distance_m=summary.get("distance_m"), start=start,
                        with_ele=with_ele, features=route_features(tables))  # decision L570: ramps, flights
        write_run_json(tmp, record)
        if gait is not None:  # decision E311: gait's four files of the streamed strides, in the same folder
            from pdrlearn.cli.gait import write_gait_files

            write_gait_files(tmp, gait, _gait_summary(gait))
        if redact:  # decision E176
            from pdrlearn.redact import redact_folder

            redact_folder(tmp, redact)
    replaced(out, was)


def register(app: typer.Typer) -> None:
    app.command("export")(export)
    app.command("run")(run)
