"""``pdrlearn info`` and ``pdrlearn plot``: inspect a session folder."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from pdrlearn.cli.common import DPI_HELP, FORCE_HELP, console, existed, json_safe, out_file, print_json, replaced
from pdrlearn.decision_refs import decision_ref
from pdrlearn.textfile import read_json


def info(
    session_dir: Path = typer.Argument(..., help="PLASYS session folder (fAccelerometer.csv, ...)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Show sensors, rates, duration, gaps and labels of a session, and check each IMU unit's axes.

    The axis checks are those every command runs when it needs a unit's frame: a declared frame against
    the data (decision D10) or the frame inferred from them (D8), and the mirrored-data test of the
    accelerometer and gyroscope (D11); their warnings go to stderr, the results to the table or --json.

    Examples:

        pdrlearn info datasets/real/gaitmap_level_left

        pdrlearn info out/sim/D_u1 --json
    """
    from pdrlearn.io import read_session

    # the gaps as recorded (decision B64); a stream cut short is shown and warned about, not refused (B72)
    s = read_session(session_dir, bridge_drops=False, spans="warn")
    summary = s.summary()
    summary["frame_checks"] = s.frame_checks()  # warnings are logged (stderr) once, by the checks themselves
    from pdrlearn.track.foot_rest import foot_placement_line, foot_rest_stats, foot_scale_warning

    summary["foot_rests"] = foot_rest_stats(s)  # decisions B133 (rest |acc| in g, a display), B134
    from pdrlearn.displace.force_channels import live_force
    from pdrlearn.io.meta_keys import unknown_keys_line
    from pdrlearn.track.units import units_apart_line

    dead = live_force(s)[1]  # steps decision 74: a dead force channel (or a lone forefoot, 75) named
    for line in (foot_placement_line(s, summary["foot_rests"], s.where),  # B134 (W415: not on side drills)
                 dead and f"{s.where}: {dead}",
                 foot_scale_warning(summary["foot_rests"], s.where),  # decision B201: a rest |acc| off 1 g
                 unknown_keys_line(s.meta, s.where),  # decision B262: meta.json keys pdrlearn does not read
                 units_apart_line(s)):  # decision B267: the units' spans differ (what track refuses or cuts)
        if line:
            import logging

            logging.getLogger("pdrlearn.info").warning("%s", line)
    # decision B64: what the other commands do with the short intervals of dropped samples: none is bridged (B64
    # not adopted; read_session(bridge_drops=True) is the API's option, decision E251)
    summary["dropped_samples_bridged"] = {n: 0 for n, st in s.streams.items() if st.gaps()}
    if s.has("wAccelerometer"):  # decision B155: which meta.json value the waist pipelines' pendulum uses
        from pdrlearn.waist.params import leg_length_note

        summary["waist_leg_length"] = leg_length_note(s.meta or {})
    if as_json:
        print_json(json_safe(summary))
        return
    from rich.table import Table

    c = console()
    c.print(f"session {summary['name']} — {summary['duration_s']:.1f} s", markup=False)
    t = Table()
    for col in ("sensor", "placement", "rate (Hz)", "samples", "duration (s)", "gaps", "longest gap (s)",
                "resolution"):  # decision B406
        # names whole (the sensor was cut to "fAccelero…" at 80 columns); the other headers wrap instead
        t.add_column(col, min_width={"sensor": 14, "placement": 9, "resolution": 10}.get(col))
    for name, d in summary["sensors"].items():
        res = "-" if d["resolution"] is None else f"{d['resolution']:.3g} {d['unit']}"  # decision B412: off a grid
        t.add_row(name, d["placement"], f"{d['rate_hz']}", str(d["samples"]), f"{d['duration_s']:.2f}",
                  str(d["gaps"]), f"{d['longest_gap_s']:.3f}", res)
    c.print(t)
    gz = [d["file"] for d in summary["sensors"].values() if str(d.get("file", "")).endswith(".gz")]
    if gz:  # decision B369: read in place
        c.print(f"gzip-compressed, read in place: {', '.join(gz)}", markup=False)
    # as meta.json writes it (JSON, pasteable); an undeclared frame is inferred when a command needs it (D8)
    frames = (json.dumps(summary["frames"]) if summary["frames"]
              else "not declared (inferred from the data when a command needs it, decision D8)")
    c.print(f"frames: {frames}", markup=False)
    for p, chk in summary["frame_checks"].items():
        frame = json.dumps(chk["frame"]) if chk["frame"] else "none"
        # decision D22: "not contradicted" only when the check ran; a refusal and an unchecked frame in words
        check = {"ok": f"not contradicted by the data ({decision_ref('D10', topic='data-model')})",  # D49
                 "warned": "see the warning",
                 "refused": f"refused by the commands that need it: {chk['check']}"}.get(chk["status"], chk["check"])
        h = chk["handedness"]
        # frame_checks lists only units with both sensors: no result = too short or non-finite data
        hand = "not run (under 16 samples or non-finite values)" if h is None else (
            f"{h['verdict']} (log ratio {h['log_ratio'] if h['log_ratio'] is not None else 'n/a'} over "
            f"{h['segments']} {'strides' if p == 'foot' else 'moving windows'}"
            + (f"; best other gyroscope axes {h['axes']['gyroscope']}, log ratio {h['axes']['log_ratio']}"
               if h.get("axes") else "")
            # as Handedness.describe: no turning-axis clause without a turn window (no "None deg")
            + (f"; turning axis {_deg(h['turn_axis']['angle_deg'])} from gravity over "
               f"{h['turn_axis']['turn_windows']} turn windows"
               if h.get("turn_axis") and h["turn_axis"]["turn_windows"] else "") + ")")
        # no frame: "foot axes: no frame declared or inferred (...)", not "none frame none" (trial 2, finding 10)
        axes = f"{chk['source']} frame {frame}, {check}" if chk["frame"] else f"no frame declared or inferred ({check})"
        c.print(f"{p} axes: {axes}; handedness ({decision_ref('D11', topic='data-model')}): {hand}", markup=False)
    rests = summary["foot_rests"]
    if rests:
        g = rests["rest_acc_g"]
        c.print("foot rests: " + (f"|acc| {g:.3f} g at the detected foot-flats" if g is not None else
                                  "too few foot-flat samples for an |acc|")
                + f" ({100 * rests['rest_fraction']:.0f} % of the samples; at rest an accelerometer reads 1 g, so "
                f"the difference is its scale error, {decision_ref('B133')}); swing "
                f"{rests['swing_rad_s'] * 57.29577951308232:.0f} deg/s (99th percentile of |gyro|, largest 10 s "
                f"block, {decision_ref('B91', 'B253')})", markup=False)  # decision D49
    if summary.get("waist_leg_length"):  # decision B155
        c.print(f"waist step length: {summary['waist_leg_length']}", markup=False)
    c.print(f"labels: {json.dumps(json_safe(summary['labels']))}", markup=False)  # JSON, like the frames line


def _deg(v) -> str:
    return "n/a" if v is None else f"{v} deg"


def plot(
    session_dir: Path = typer.Argument(..., help="PLASYS session folder."),
    out: Path = typer.Option(..., "--out", "-o", help="Figure file to write: .png, .pdf or .svg."),
    start: float = typer.Option(None, help="First second to show (default: whole session)."),
    end: float = typer.Option(None, help="Last second to show."),
    steps: str = typer.Option("labels", "--steps", help="Steps to shade: labels (the session's steps.csv), "
                              "detected (found by `pdrlearn steps`' default detector), or a steps table "
                              "(`pdrlearn steps --out`, a track's steps.csv) or a `track`/`run` output folder "
                              "(a lower-back track's transfers.csv is drawn too, W296)."),
    shade: str = typer.Option("terrain", "--shade", help="What the steps' shading shows: terrain (flat / up / "
                              "down) or travel (a foot track's steps.csv travel: forward / backward / left / right "
                              "/ side / turn, decision L655; give --steps a track's output folder or steps.csv)."),
    dpi: int = typer.Option(None, "--dpi", min=20, max=600, help=DPI_HELP),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
) -> None:
    """Plot every sensor stream with the labelled (or detected) steps shaded.

    Examples:

        pdrlearn plot datasets/real/gaitmap_stairs_up_left --out out/stairs.png --start 5 --end 12

        pdrlearn plot datasets/real/gaitmap_level_left --out out/level.pdf --steps detected

        pdrlearn plot datasets/real/gaitmap_level_right --out out/right.svg --steps out/track_right --dpi 200

        pdrlearn plot out/sim/D_u1 --out out/D_travel.png --steps out/track/D_M3 --shade travel
    """
    from pdrlearn.errors import DataError
    from pdrlearn.io import read_session
    from pdrlearn.plots import FIGURE_SUFFIXES, SHADE_COLOURS, check_window, plot_session

    if shade not in SHADE_COLOURS:  # decision L655
        raise DataError(f"--shade {shade}: give one of {', '.join(SHADE_COLOURS)}")
    out = out_file(out, FIGURE_SUFFIXES, "plot", force=force)
    was = existed(out)
    s = read_session(session_dir)
    check_window(start, end, s.t_end - s.t_start, str(session_dir))
    table, what = _steps_to_shade(steps, s)
    if shade != "terrain" and (table is None or shade not in table):  # decision L655: before anything is written
        raise DataError(f"--shade {shade}: the steps shaded ({what or 'the labelled steps'}) have no {shade} column; "
                        f"give --steps a foot track's output folder or steps.csv (`pdrlearn track`, `run`)")
    plot_session(s, out, start=start, end=end, steps=table, steps_what=what, dpi=dpi,
                 transfers=_transfers_to_draw(steps), shade=shade)  # decision W296
    replaced(out, was)
    typer.echo(str(out))


def _transfers_to_draw(source: str):
    """Decision W296: a lower-back track's transfers.csv when ``plot --steps`` names its output folder (None
    otherwise: a foot track writes none); a transfers.csv without its columns is one line naming it."""
    import pandas as pd

    from pdrlearn.errors import DataError

    path = Path(source) / "transfers.csv"
    if source in ("labels", "detected") or not path.is_file():
        return None
    try:
        table = pd.read_csv(path)
    except (OSError, ValueError) as exc:
        raise DataError(f"{path}: cannot read it as a track's transfers.csv ({type(exc).__name__}); re-run "
                        "`pdrlearn track` to rewrite it, or remove it to plot the steps alone") from None
    missing = [c for c in ("kind", "start_s", "end_s") if c not in table]
    if missing:
        raise DataError(f"{path}: no {' or '.join(missing)} column; re-run `pdrlearn track` to rewrite it, or remove "
                        "it to plot the steps alone")
    bad = bad_transfer_row(table)  # decision B280: a row that cannot be drawn as written is named, not dropped
    if bad:
        raise DataError(f"{path}: {bad}; re-run `pdrlearn track` to rewrite it, or remove it to plot the steps alone")
    return table.astype({"start_s": float, "end_s": float})


def bad_transfer_row(table) -> str:
    """Decision B280: ``""`` or why the first bad row of a transfers.csv ``table`` cannot be drawn (its line in
    the file, header = line 1): a kind that is none of transfers.csv's, a start_s / end_s that is not a finite
    number, or an end before its start."""
    import numpy as np
    import pandas as pd

    from pdrlearn.waist.transfers import GET_UP_KINDS, LIE_DOWN_KINDS, SIT_TO_STAND, STAND_TO_SIT

    kinds = (SIT_TO_STAND, STAND_TO_SIT, *LIE_DOWN_KINDS, *GET_UP_KINDS)
    a = pd.to_numeric(table["start_s"], errors="coerce").to_numpy(float)
    b = pd.to_numeric(table["end_s"], errors="coerce").to_numpy(float)
    for i, (k, x, y) in enumerate(zip(table["kind"], a, b, strict=True)):
        row = f"line {i + 2} ({k}, {table['start_s'].iloc[i]}, {table['end_s'].iloc[i]})"
        if k not in kinds:
            return f"{row}: kind is not one of {', '.join(kinds)}"
        if not (np.isfinite(x) and np.isfinite(y)):
            return f"{row}: start_s and end_s must be numbers (s)"
        if y < x:
            return f"{row}: end_s is before start_s"
    return ""


def _steps_to_shade(source: str, session):
    """``plot --steps`` (decision L70): ``(table or None, what)``; None = the session's labelled steps."""
    import pandas as pd

    from pdrlearn.errors import DataError

    if source == "labels":
        return None, None
    if source == "detected":
        from pdrlearn.cli.steps import auto_detector

        det = auto_detector(session)
        table = det.detect(session)
        return table, f"detected {'stride' if det.unit == 'foot' else 'step'}(s) ({det.name})"
    path = Path(source)
    if path.is_dir():
        table_path = path / "steps.csv"
        if not table_path.is_file():
            raise DataError(f"--steps {source}: a folder without steps.csv; give labels, detected, a steps table "
                            "or a `pdrlearn track`/`run` output folder")
        summary = path / "summary.json"
        try:
            made_from = read_json(summary).get("session") if summary.is_file() else None
        except (OSError, ValueError, AttributeError):
            made_from = None
        if isinstance(made_from, str) and made_from != session.name:
            import logging

            logging.getLogger("pdrlearn.cli").warning("%s: tracked from session '%s', not '%s'; its strides are "
                                                      "shaded on this session's clock", path, made_from, session.name)
    elif path.is_file():
        table_path = path
    else:
        raise DataError(f"--steps {source}: not labels, detected, a steps table or a track output folder "
                        "(no such file or folder)")
    try:
        table = pd.read_csv(table_path)
    except (OSError, ValueError) as exc:
        raise DataError(f"{table_path}: cannot read it as a steps table ({type(exc).__name__}); give a CSV with "
                        "start_s and end_s columns (`pdrlearn steps --out`, a track's steps.csv)") from None
    missing = [c for c in ("start_s", "end_s") if c not in table]
    if missing:
        raise DataError(f"{table_path}: no {' or '.join(missing)} column; give a steps table with start_s and end_s "
                        "in s (`pdrlearn steps --out`, a track's steps.csv)")
    table = table[pd.to_numeric(table["start_s"], errors="coerce").notna()
                  & pd.to_numeric(table["end_s"], errors="coerce").notna()].astype({"start_s": float, "end_s": float})
    if len(table) and (table["end_s"].max() < session.t_start or table["start_s"].min() > session.t_end):
        raise DataError(f"{table_path}: its steps ({table['start_s'].min():.1f}-{table['end_s'].max():.1f} s) lie "
                        f"outside session '{session.name}' ({session.t_start:.1f}-{session.t_end:.1f} s); was it "
                        "made from another session?")
    return table, f"step(s) of {table_path}"


def fetch(
    source: str = typer.Argument(..., help="Dataset source: mobgap or gaitmap (their example data), hapt "
                                           "(UCI HAPT, a phone on a belt)."),
    out: Path = typer.Option(Path("datasets/external"), "--out", "-o",
                             help="Folder that receives one session folder per recording."),
    cache: Path = typer.Option(None, "--cache", help="Download cache (default ~/.cache/pdrlearn/external)."),
    from_dir: Path = typer.Option(None, "--from", metavar="DIR",
                                  help="mobgap only: convert the Mobilise-D data.mat files under DIR "
                                       "(<cohort>/<id>/data.mat or <cohort>/<id>/Laboratory/data.mat, or the "
                                       "unpacked mobgap sdist) instead of downloading; no network."),
) -> None:
    """Download a public gait dataset (pinned PyPI sdist, sha256-checked) and convert it to sessions.

    The sessions have the layout of datasets/real (same file names, units and label files); every
    meta.json says where each file came from and what is missing. Needs the network once; with --from,
    mobgap's converter reads your own Mobilise-D lab data.mat files (the participant from the
    infoForAlgo.mat beside each) and needs no network.

    Examples:

        pdrlearn fetch mobgap --out datasets/external

        pdrlearn fetch mobgap --from ~/MobiliseD_TVS --out datasets/tvs

        pdrlearn fetch gaitmap --out datasets/external

        pdrlearn fetch hapt --out datasets/hapt
    """
    from pdrlearn.io.external import fetch as fetch_source

    made = fetch_source(source, out, cache_dir=cache, progress=lambda m: typer.echo(m, err=True),
                        from_dir=from_dir)  # decision C173
    for p in made:
        typer.echo(str(p))
    typer.echo(f"{len(made)} session(s) under {out}", err=True)


def register(app: typer.Typer) -> None:
    app.command("info")(info)
    app.command("plot")(plot)
    app.command("fetch")(fetch)
