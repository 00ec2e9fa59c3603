"""``pdrlearn calibrate``: per-user step-length (and gyro-bias) parameters of the waist pipelines."""
# ruff: noqa: B008  (typer declares options as call defaults)

from __future__ import annotations

import math
from pathlib import Path

import typer

from pdrlearn.cli.common import FORCE_HELP, existed, json_safe, out_file, print_json, replaced
from pdrlearn.cli.registry_help import DETECTOR_NAMES
from pdrlearn.cli.track import REDACT_PATHS_OPT
from pdrlearn.errors import DataError


def register(app: typer.Typer) -> None:
    @app.command("calibrate")
    def calibrate_cmd(
        dirs: list[Path] = typer.Argument(..., help="Calibration session folder(s) of one user."),
        pipeline: str = typer.Option("waist-pendulum", "--pipeline", "-p",
                                     help="waist-pendulum (the pipeline `pdrlearn track` takes for a lower-back "
                                          "recording) or waist-pll."),
        distance: list[float] = typer.Option(None, "--distance", "-d",
                                             help="Known walked length (m), one per folder; every detected step "
                                                  "counts, first to last heel strike. A start-to-stop walkway "
                                                  "(stand, walk L m, stand): give L to read whole walks like it, "
                                                  "or the first-to-last heel strike length to compare with "
                                                  "IC-to-IC references (walkway mats, bouts); calibrate and "
                                                  "compare on one of the two (W212). Default: the folder's "
                                                  "reference bouts."),
        turns: float = typer.Option(None, "--turns",
                                    help="Signed full turns walked (+1 = one left 360), to fit the gyro "
                                         "bias (seed 003 eq. 2)."),
        fit_turns: bool = typer.Option(False, "--fit-turns",
                                       help="Also fit seed 003's straight/turning GMM on the walks' strides "
                                            "(needs >= 20 strides with turns; decision W14)."),
        shrink: bool = typer.Option(False, "--shrink",
                                    help="waist-pendulum: shrink the calibrated K toward the population K by its "
                                         "standard error (decision W48; measured, not the default)."),
        start: list[float] = typer.Option(None, "--start",
                                          help="With --distance: count only the steps after this time (s from "
                                               "the recording's start), one per folder or one for all "
                                               "(decision W61)."),
        end: list[float] = typer.Option(None, "--end",
                                        help="With --distance: count only the steps before this time (s from "
                                             "the recording's start), one per folder or one for all."),
        belt: bool = typer.Option(False, "--belt",
                                  help="Treadmill walks: each walk's distance is its meta.json belt_speed_mps x "
                                       "the span of its counted contacts, first to last (with --start/--end: "
                                       "inside them); instead of --distance (decision W378)."),
        length_model: str = typer.Option(None, "--length-model",
                                         help="Also fit this gain model's linear gain (weinberg, or a plug-in that "
                                              "declares gain_param; NAME:key=value,... sets its other settings) on "
                                              "the same walks and counted steps; written to PARAMS.json's "
                                              "length_models, which `track --length-model NAME --params` reads "
                                              "(decision W460)."),
        detector: str = typer.Option(None, "--detector",
                                     help=f"The walks' contacts from this step detector instead of the pipeline's "
                                          f"own, as `track --detector` takes them: {DETECTOR_NAMES} (a waist one, "
                                          "unit 'waist'; a registered / installed plug-in too, docs/extending.md; "
                                          "NAME:key=value,... sets its settings). Both fits (the pipeline's model "
                                          "and --length-model's gain) use them; PARAMS.json records it and `track` "
                                          "says when it tracks with another detector (decision W471)."),
        out: Path = typer.Option(..., "--out", "-o", help="PARAMS.json to write (an existing file only with --force)."),
        redact_paths: bool = REDACT_PATHS_OPT,  # decision E176: "fit" holds the folders as typed
        force: bool = typer.Option(False, "--force", help=FORCE_HELP),
        as_json: bool = typer.Option(False, "--json", help="Print the parameters as JSON."),
    ):
        """Fit per-user waist step-length parameters from walks of known length.

        Examples:

          pdrlearn calibrate datasets/real/mobgap_HA001_Test5_Trial1 -p waist-pendulum -o p.json

          pdrlearn calibrate walk1 walk2 --pipeline waist-pll -d 40 -d 60 --out p.json

          pdrlearn calibrate loop --pipeline waist-pendulum -d 35 --turns 1 --out p.json

          pdrlearn calibrate walk1 -d 40 --shrink --out p.json   (K shrunk toward the population K, W48)

          pdrlearn calibrate walk1 -d 5.01 --start 5.0 --end 11.6 --out p.json   (the measured stretch only)

          pdrlearn calibrate walks/D -d 30 --redact-paths --out p.json   (its "fit" folders as <redacted>, E176)

          pdrlearn calibrate walk1 -d 30 --length-model weinberg --out p.json   (also the gain k of weinberg,
          W460; then track with --length-model weinberg --params p.json)

          pdrlearn calibrate walk1 -d 30 --detector pll --length-model weinberg --out p.json   (on a waist
          detector's contacts, W471; then track with --detector pll --length-model weinberg --params p.json)

          A treadmill walk with meta.json belt_speed_mps: calibrate DIR --belt --start 20 --end 50 -o p.json
          (distance = belt speed x the contacts' span, W378)

        Then: pdrlearn track DIR --pipeline waist-pendulum --params p.json --out OUT
        """
        from pdrlearn.io import read_session
        from pdrlearn.waist.calibration import calibrate

        out_file(out, (".json",), "params", force=force)
        was = existed(out)
        if length_model is not None:  # decision W460: one line before any session is read or tracked
            from pdrlearn.waist.calibration import gain_model

            gain_model(length_model)
        if detector is not None:  # decision W471: an unknown or foot detector is one line before any session is read
            from pdrlearn.waist.calibration import calibration_detector

            calibration_detector(detector)
        if turns is not None and not math.isfinite(turns):
            raise DataError(f"--turns {turns}: give the signed number of full turns walked, e.g. 1 or -2")
        for dm in distance or []:  # one error line before any session is read or tracked (no track warning first)
            if not (math.isfinite(dm) and dm > 0):
                raise DataError(f"calibrate: --distance {dm} must be a positive number of metres")
        sessions = [read_session(d) for d in dirs]
        for d, s in zip(dirs, sessions, strict=True):
            if not s.has("wAccelerometer"):  # decision B28: say what calibrate is for, not "choose a method"
                have = ", ".join(s.streams) or "none"
                raise DataError(f"{d}: calibrate fits the lower-back step length of --pipeline waist-pendulum / "
                                f"waist-pll and needs the waist unit (wAccelerometer, wGyroscope), which session "
                                f"'{s.name}' lacks (it has {have}); give a session with the waist unit -- the foot "
                                "pipeline (plasys) takes no calibrate file: its distance calibration comes with "
                                "`pdrlearn train` (decision L26)")
        spans = None
        if start or end:  # decision W61: the measured stretch of each recording
            n = max(len(start or []), len(end or []))
            if (start and len(start) != n) or (end and len(end) != n):
                raise DataError(f"calibrate: {len(start or [])} --start and {len(end or [])} --end values; give "
                                "as many of each (or only one of the two)")
            spans = [((start or [None] * n)[k], (end or [None] * n)[k]) for k in range(n)]
        params = calibrate(sessions, pipeline, distances=list(distance) if distance else None, turns=turns,
                           fit_turns=fit_turns, shrink=shrink, spans=spans, belt=belt, length_model=length_model,
                           detector=detector)
        fit: dict = {"fit": [str(d) for d in dirs]}
        if redact_paths:  # decision E176: the folders fitted on as <redacted>, said in the file
            from pdrlearn.redact import path_forms, redact_json

            fit = {"fit": redact_json(fit["fit"], path_forms(dirs), paths=True), "paths_redacted": True}
        from pdrlearn.export.waist import declared_frame

        frame = declared_frame(sessions)
        if frame is not None:  # decision E367: the walks' waist frame, for `export` without --frame
            fit["frames"] = {"waist": frame}
        params.save(out, extra=fit)
        replaced(out, was)
        d = params.to_dict()
        if as_json:
            from pdrlearn import __version__

            print_json(json_safe({"out": str(out), "pipeline": pipeline, **d, "pdrlearn_version": __version__}))  # E136
        else:
            typer.echo(f"wrote {out}")
            if pipeline == "waist-pendulum":
                typer.echo(f"  fitted: K = {params.k:.4f}, F = {params.f_m:.3f} m (step = K 2 sqrt(2 L h - h^2) + F, "
                           f"L = {params.leg_m:.3f} m)")
            else:
                typer.echo(f"  fitted: step length = {params.a_walk:.4f} f - {params.b_walk:.4f} m (walking)")
            if params.detector is not None:  # decision W471
                typer.echo(f"  on the contacts of --detector {params.detector} (track with --detector "
                           f"{params.detector} --params {out})")
            for name, gains in (params.length_models or {}).items():  # decision W460
                typer.echo(f"  fitted: {name} " + ", ".join(f"{k} = {v:.4f}" for k, v in gains.items())
                           + f" (track --length-model {name} --params {out})")
            for n in d["notes"]:
                typer.echo(f"  {n}")
