"""``pdrlearn gait LEFT_DIR RIGHT_DIR``: bilateral gait from two foot units of one walk (decisions L259-L263);
``pdrlearn gait-all ROOT``: every visit folder's pair (decision C110)."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from pdrlearn.cli.common import FORCE_HELP
from pdrlearn.decision_refs import decision_ref

#: the files ``gait --out`` writes (decision L260); the output-folder kind ``gait`` is recognised by them
GAIT_FILES = ("gait_summary.json", "gait_steps.csv", "gait_cycles.csv", "gait_bouts.csv")
#: the files ``gait-all --out`` writes (decision C110); the folder kind ``gait-all`` is recognised by gait_pairs.csv
GAIT_ALL_FILES = ("gait_pairs.csv", "gait_steps.csv", "gait_cycles.csv", "gait_bouts.csv")


#: cohort C245: the help of gait's and gait-all's --affected-side
AFFECTED_HELP = ("left or right: the affected side (a prosthesis, a paretic or operated leg). gait_summary.json "
                 "records it (affected_side) and `report --clinical` words the sides affected / unaffected ('right "
                 "longer' reads 'unaffected longer'); the measures keep their left / right names (decision C245).")


def _fmt(v, spec: str) -> str:
    return "-" if v is None else format(v, spec)


def gait_lines(summary: dict, by_kind: dict | None = None) -> list[str]:
    """The printed lines of one :func:`pdrlearn.track.bilateral.bilateral_gait` measures dict (``walk``); its
    ``by_kind`` names the level steps' counts when the headline took all steps (decision L608)."""
    w = summary
    lines = [f"steps left/right {w['n_steps_left']}/{w['n_steps_right']}{_basis(w, by_kind)}: step time "
             f"{_fmt(w['step_time_s_left'], '.3f')} / {_fmt(w['step_time_s_right'], '.3f')} s, symmetry index "
             f"{_fmt(w['step_time_s_si_pct'], '.1f')} %, ratio L/R {_fmt(w['step_time_s_ratio'], '.3f')}",
             f"stride length left/right {_fmt(w['stride_length_m_left'], '.3f')} / "
             f"{_fmt(w['stride_length_m_right'], '.3f')} m, symmetry index {_fmt(w['stride_length_m_si_pct'], '.1f')} %"
             f" (stride time {_fmt(w['stride_time_s_left'], '.3f')} / {_fmt(w['stride_time_s_right'], '.3f')} s)"]
    if w.get("step_length_m_left") is not None or w.get("step_length_m_right") is not None:  # decision L310
        scale = w.get("step_length_scale_pct")
        lines.append(f"step length left/right {_fmt(w['step_length_m_left'], '.3f')} / "
                     f"{_fmt(w['step_length_m_right'], '.3f')} m, symmetry index "
                     f"{_fmt(w['step_length_m_si_pct'], '.1f')} %, ratio L/R {_fmt(w['step_length_m_ratio'], '.3f')} "
                     + (f"({w['n_step_lengths']} straight steps; the closing step took out a "
                        f"{_fmt(scale, '+.2f')} % relative scale of the two tracks, L310)" if scale is not None else
                        f"({w['n_step_lengths']} steps; the labels' own step lengths, ics.csv, L540)"))
    if w.get("swing_time_s_left") is not None or w.get("swing_time_s_right") is not None:  # decision L284
        swing = (f"swing time left/right {_fmt(w['swing_time_s_left'], '.3f')} / "
                 f"{_fmt(w['swing_time_s_right'], '.3f')} s, symmetry index {_fmt(w['swing_time_s_si_pct'], '.1f')} %")
        from pdrlearn.track.bilateral import clock_offset_pattern  # here: `pdrlearn --help` loads no numpy

        if clock_offset_pattern(w):  # decision L328: only where L284's pattern is seen, not on every pair
            swing += (f"; double support before the left / right swing differs by {2000 * w['clock_offset_s']:+.0f} "
                      "ms (step times asymmetric, swing times not: a clock offset or one foot's late contacts, "
                      "L284, L318)")
        lines.append(swing)
    if w.get("stance_time_s_left") is not None or w.get("stance_time_s_right") is not None:  # decision L327
        lines.append(f"stance time left/right {_fmt(w['stance_time_s_left'], '.3f')} / "
                     f"{_fmt(w['stance_time_s_right'], '.3f')} s, symmetry index "
                     f"{_fmt(w['stance_time_s_si_pct'], '.1f')} %, ratio L/R {_fmt(w['stance_time_s_ratio'], '.3f')}")
    if w["double_support_pct"] is not None:
        lines.append(f"double support {w['double_support_pct']:.1f} % of the gait cycle, single support left/right "
                     f"{_fmt(w['single_support_pct_left'], '.1f')} / {_fmt(w['single_support_pct_right'], '.1f')} % "
                     f"({w['n_support_cycles']} cycles)")
    if w.get("n_flight_cycles"):  # decision L729: cycles with a toe-off before the other foot's contact
        lines.append(f"flight (a loss of contact, or a clock offset between the units) in {w['n_flight_cycles']} "
                     f"cycles, {1000 * w['flight_time_s']:.0f} ms per gait cycle on average (its two flights "
                     f"summed), {1000 * w['flight_time_s'] / 2:.0f} ms per step (L729, C268)")
    if w.get("cadence_spm") is not None:  # decision L539
        lines.append(pace_line(w))
    angles = foot_angle_text(w)
    if angles:  # cohort C244
        lines.append(angles)
    from pdrlearn.track.affected_side import toe_clearance_text

    clearance = toe_clearance_text(w)
    if clearance:  # decision L795
        lines.append(clearance)
    return lines


def foot_angle_text(w: dict) -> str | None:
    """Cohort C244: the walk's per-side median sole angles at contact and toe-off (steps.csv's ic_angle_deg /
    tc_angle_deg, L421: + toes up), "left/right a / b deg"; None without any."""
    names = (("ic_angle_deg", "at contact"), ("tc_angle_deg", "at toe-off"))
    if all(w.get(f"{k}_{s}") is None for k, _ in names for s in ("left", "right")):
        return None
    return ("foot (sole) angle left/right, + toes up, medians: " + ", ".join(
        f"{what} {_fmt(w.get(f'{k}_left'), '.1f')} / {_fmt(w.get(f'{k}_right'), '.1f')} deg" for k, what in names)
        + " (L421, C244)")


def _basis(w: dict, by_kind: dict | None = None) -> str:
    """Decisions L538, L608: what the headline's steps are, after the counts; with all steps, how many level
    straight steps each side had (``by_kind["level"]``, none without)."""
    if w.get("headline_steps") == "level":
        return (f" (level straight steps, of {w['n_steps_all_left']}/{w['n_steps_all_right']}: no stairs, turns, "
                "starts, stops, backward or ramp strides; L538, L746, L775)")
    if w.get("headline_steps") == "all":
        from pdrlearn.track.bilateral import HEADLINE_MIN_LEVEL_STEPS

        level = (by_kind or {}).get("level") or {}
        return (f" (all steps: {level.get('n_steps_left', 0)}/{level.get('n_steps_right', 0)} level straight "
                f"steps, under {HEADLINE_MIN_LEVEL_STEPS} a side; L538, L608)")
    return ""


def pace_line(w: dict) -> str:
    """Decision L539: the walk's (a bout's, a kind's) gait speed, cadence and distance line."""
    return (f"gait speed {_fmt(w.get('gait_speed_mps'), '.2f')} m/s, cadence {_fmt(w['cadence_spm'], '.1f')} "
            f"steps/min, distance {_fmt(w.get('distance_m'), '.2f')} m in {_fmt(w.get('walking_time_s'), '.1f')} s "
            "(all steps; the two feet's strides averaged, L539)")


#: decision L538: the printed name of each step kind's row
KIND_NAMES = {"level": "level", "stairs_up": "stairs up", "stairs_down": "stairs down", "turn": "turn",
              "start_stop": "start / stop", "backward": "backward", "ramp": "ramp"}  # decisions L746, L775


def kind_lines(by_kind: dict) -> list[str]:
    """Decision L538: one line per step kind (gait_summary.json ``by_kind``): steps, step time and its symmetry
    index, stance time and stride length left / right."""
    lines = []
    for kind, w in by_kind.items():
        lines.append(f"{KIND_NAMES.get(kind, kind)}: steps {w['n_steps_left']}/{w['n_steps_right']}, step time "
                     f"{_fmt(w['step_time_s_left'], '.3f')} / {_fmt(w['step_time_s_right'], '.3f')} s (SI "
                     f"{_fmt(w['step_time_s_si_pct'], '.1f')} %), stance {_fmt(w['stance_time_s_left'], '.3f')} / "
                     f"{_fmt(w['stance_time_s_right'], '.3f')} s, stride length "
                     f"{_fmt(w['stride_length_m_left'], '.3f')} / {_fmt(w['stride_length_m_right'], '.3f')} m")
    return lines


def stair_lines(flights: list[dict]) -> list[str]:
    """Decision L561: one line per stair flight (gait_summary.json ``stairs``): its pattern and leading foot."""
    from pdrlearn.track.stair_lead import flight_line

    return [f"stairs (L561): {flight_line(f)}" for f in flights]


def summary_json(res: dict) -> dict:
    """gait_summary.json's object of :func:`pdrlearn.track.bilateral.pair_sessions`'s ``res`` (gait --out; gait-all
    writes one per pair, decision W437)."""
    out = {k: res[k] for k in ("walk", "bouts", "by_kind", "stairs", "toe_off", "reason", "warnings", "sessions",
                               "contact_source", "clock_alignment")}  # L561: stairs
    out["affected_side"] = res.get("affected_side")  # cohort C245
    ref = res.get("reference")
    out["reference"] = None if ref is None else {k: ref[k] for k in ("walk", "bouts", "by_kind", "stairs", "toe_off",
                                                                     "reason")}
    return out


def write_gait_files(folder: Path, res: dict, summary: dict | None = None) -> None:
    """Decisions L260, C109: ``gait --out``'s four files of :func:`pdrlearn.track.bilateral.pair_sessions`'s ``res``
    into ``folder`` (gait_summary.json: ``summary``, default :func:`summary_json` of ``res``); ``run --gait`` writes
    the same (decision E311)."""
    from pdrlearn.io.plasys import json_safe
    from pdrlearn.table_csv import write_table_csv
    from pdrlearn.track.gait_tables import gait_tables

    summary = json_safe(summary_json(res)) if summary is None else summary
    (folder / "gait_summary.json").write_text(json.dumps(summary, indent=2, allow_nan=False) + "\n")
    for name, table in gait_tables(res).items():  # decision C109: ids in front, foot beside side
        write_table_csv(table, folder / name)  # decision C103: as gait-all writes them (review R4)


def result_lines(res: dict, how: str) -> list[str]:
    """The printed lines of one pair's ``res`` (``gait``'s; ``run --gait``'s with ``how`` = "replayed", E311): the
    sessions' strides and bouts, the clock alignment (L537), the headline measures, one line per kind of step (L538),
    the stair flights (L561) and the reason support measures are missing or biased."""
    s = res["sessions"]
    lines = [f"{s['left']['session']} + {s['right']['session']}: {s['left']['n_strides']} left and "
             f"{s['right']['n_strides']} right strides {how}, {len(res['bouts'])} walking bout(s)"]
    from pdrlearn.track.bilateral import alignment_line

    aligned = alignment_line(res["clock_alignment"])  # decision L537
    if aligned is not None:
        lines.append(aligned)
    lines += gait_lines(res["walk"], res["by_kind"])
    if res.get("affected_side"):  # cohort C245
        lines.append(f"affected side: {res['affected_side']} (--affected-side; clinical.md words the sides "
                     "affected / unaffected, C245)")
    if len(res["by_kind"]) > 1:  # decision L538: a walk of one kind has its rows in the headline
        lines.append(f"by kind of step ({decision_ref('L538')}):")  # decision D49
        lines += ["  " + line for line in kind_lines(res["by_kind"])]
    lines += stair_lines(res["stairs"])  # decision L561
    if res["reason"]:
        lines.append(res["reason"])
    return lines


def register(app: typer.Typer) -> None:
    register_all(app)

    @app.command("gait")
    def gait_cmd(
        left_dir: Path = typer.Argument(..., help="The LEFT foot's session folder."),
        right_dir: Path = typer.Argument(..., help="The RIGHT foot's session folder of the same walk (same clock)."),
        out: Path = typer.Option(None, "--out", "-o", help="Folder for gait_summary.json, gait_steps.csv, "
                                 "gait_cycles.csv and gait_bouts.csv (default: print only)."),
        force: bool = typer.Option(False, "--force", help=FORCE_HELP),
        as_json: bool = typer.Option(False, "--json", help="Print gait_summary.json's object."),
        ignore_force: bool = typer.Option(False, "--ignore-force", help="Time both feet's contacts and toe-offs with "
                                          "the foot IMU's detector, the force sensors left out (as track's, L366). "
                                          "Without it a pair whose feet would be timed by different detectors (force "
                                          "on one foot only) is timed by the IMU on both, with one line (steps 72)."),
        affected_side: str = typer.Option(None, "--affected-side", help=AFFECTED_HELP),
    ):
        """Bilateral gait of one walk recorded with a unit on each foot: step time (one foot's initial contact
        to the other's next), step length (the two feet's tracked positions along the walk, straight steps,
        decision L310), step-time / step-length / stride-time / stride-length asymmetry (symmetry index and L/R ratio),
        double and single support (% of the gait cycle, from the toe-off of track --toe-off), per walk and per
        walking bout. Each folder is tracked offline with --toe-off; with labelled IC / TC events in both folders
        (gaitmap's mocap) the same measures of the labels are given as the reference (with ics.csv's step lengths,
        L540). The headline measures are the level straight steps' (no stairs, turns, starts, stops or backward
        strides, L746; all steps with none on a side), with a row per kind of step and gait_steps.csv /
        gait_cycles.csv's kind (L538), and the walk's gait speed, cadence and distance (L539). The two recordings
        must share one clock:
        two sessions imported from absolute (epoch or date-time) timestamps are aligned on their meta.json
        imported.time.origin_s (the later one moved by the difference, one line, gait_summary.json's
        clock_alignment; L537); any other pair must share t = 0 (as gaitmap's left / right folders). gait
        refuses contacts that do not overlap in time (decision L260) and two sessions whose meta.json names different
        activities, and warns when under 80 % of the merged contacts alternate feet (decision B245). Two sessions
        whose meta.json clock_id differ are refused (decision L283); a step-time asymmetry that the swing times do not
        share - what a clock offset or one foot's late contacts give - is warned about with the offset's size (L284),
        a tracked stance under 55 % of the cycle (an early toe-off or a late contact) too (L285), two feet whose
        impacts differ over 3 x in sharpness (a soft, e.g. prosthetic, foot: its step times, stance and double
        support are not comparable, L318), a backward walk (L329) and two feet whose stair ascent or descent
        disagree beyond their per-stride height spread (L436, L437); the warnings are in gait_summary.json's
        "warnings". Stride lengths leave out the half strides that start and end each walking bout (L317); stance
        time per foot is given with its asymmetry (L327). A pair whose meta.json "foot" (import --foot) contradicts
        the LEFT / RIGHT order is refused (B321), as are two feet whose rates differ by over 10 % or whose spans
        overlap for under 50 % of the shorter (B322); with no "foot" recorded one warning says the side is taken from
        the argument order. Both feet are timed by one detector (steps 72): with force sensors on one foot only, or
        with --ignore-force, both by the IMU's; gait_steps.csv's and gait_summary.json's contact_source say which.
        The walk also gives each side's median foot (sole) angle at contact and at toe-off (the tracks' L421
        angles, + toes up; C244); --affected-side left|right names the affected side (a prosthesis, a paretic leg):
        gait_summary.json's affected_side, and `report --clinical` words the sides affected / unaffected (C245).

        Examples:

          pdrlearn gait datasets/real/gaitmap_level_left datasets/real/gaitmap_level_right

          pdrlearn gait LEFT RIGHT --out gait_out --json

          pdrlearn gait LEFT RIGHT --ignore-force   # both feet timed by the IMU, the insoles left out

          pdrlearn gait LEFT RIGHT --out G --affected-side left   # a left prosthesis (C245)
        """
        from pdrlearn.atomic import atomic_directory
        from pdrlearn.cli.common import existed, out_folder, print_json, refused_output, replaced
        from pdrlearn.io.plasys import json_safe
        from pdrlearn.track.affected_side import check_affected_side
        from pdrlearn.track.bilateral import pair_sessions

        affected_side = check_affected_side(affected_side)  # cohort C245: before any tracking
        if out is not None:
            out_folder(out, "gait", force=force, inputs=(left_dir, right_dir))
        # bad input fails here, before any folder is made
        res = pair_sessions(left_dir, right_dir, ignore_force=ignore_force)
        res["affected_side"] = affected_side
        summary = json_safe(summary_json(res))
        if out is not None:
            was = existed(out)
            with refused_output(out), atomic_directory(out) as tmp:  # all four files or none (B151)
                write_gait_files(tmp, res, summary)
            replaced(out, was)
        if as_json:
            print_json(summary)
            return
        for line in result_lines(res, "tracked"):
            typer.echo(line)
        ref = res.get("reference")
        if ref is not None:
            typer.echo("reference (the sessions' labelled contacts):")
            for line in gait_lines(ref["walk"], ref["by_kind"]):
                typer.echo("  " + line)
            if len(ref["by_kind"]) > 1:  # decision L538
                for line in kind_lines(ref["by_kind"]):
                    typer.echo("    " + line)
            for line in stair_lines(ref["stairs"]):  # decision L561
                typer.echo("  " + line)
            if ref["reason"]:
                typer.echo("  " + ref["reason"])
        if out is not None:
            typer.echo(f"wrote {out}/" + ", ".join(GAIT_FILES))


def register_all(app: typer.Typer) -> None:
    @app.command("gait-all")
    def gait_all_cmd(
        root: Path = typer.Argument(..., help="A folder of visit folders, each holding the left and the right "
                                    "foot's session of one walk (meta.json \"foot\", as import --foot writes)."),
        out: Path = typer.Option(..., "--out", "-o", help="Folder for gait_pairs.csv and the pooled "
                                 "gait_steps.csv, gait_cycles.csv, gait_bouts.csv, and each paired visit folder's "
                                 "gait_summary.json at OUT/PATH/gait_summary.json (as gait --out's; decision W437), "
                                 "which `pdrlearn report OUT [--clinical]` reads."),
        force: bool = typer.Option(False, "--force", help=FORCE_HELP),
        jobs: int = typer.Option(1, "--jobs", "-j", min=1, help="Pairs tracked at once: 1 = one after the other in "
                                 "this process (default); N > 1 = a Dask LocalCluster of N single-threaded worker "
                                 "processes, as track-all --jobs (decision C115); the same output."),
        resume: bool = typer.Option(False, "--resume", help="Reuse the pairs an interrupted (killed, Ctrl-C) or "
                                    "earlier run into OUT paired from the same input files and code, and pair the "
                                    "others (a failed pair again); the tables are those an uninterrupted run writes "
                                    "(decision C116). OUT is replaced as with --force."),
        affected_side: str = typer.Option(None, "--affected-side", help=AFFECTED_HELP),
    ):
        """Bilateral gait of every visit folder under ROOT (decision C110): the session folders are found as
        track-all finds them, grouped by the folder holding them, and each folder's one left and one right foot
        session (by meta.json "foot") is given to `pdrlearn gait`. The pooled tables stack gait's tables, each
        row led by `path` (the visit folder relative to ROOT) and the pair's ids (session_left, session_right,
        subject, visit; C109); gait_pairs.csv has one row per visit folder with its status (ok, failed, no_pair)
        and reason. A visit folder without exactly one session of each foot is one line and a no_pair row; a
        pair that gait refuses is one line and a failed row (exit code 1), the others go on; no pair anywhere is
        one error line, nothing written (exit 2). Pairs are tracked one after another, with a line each, or N at a
        time with --jobs N (C115). --resume goes on from an interrupted or earlier run: each paired visit folder's
        result is recorded in OUT (a hidden .gait-all-pairs folder) with its input files' SHA-256, and reused while
        they and pdrlearn's code are unchanged; a changed pair is paired again, its line saying what changed (C116).
        With two or more visits of a subject (meta.json visit), gait_changes.csv and gait_changes_summary.csv pair
        them as track-all's changes.csv does (C22 baseline, C83 a visit's walks averaged) over each walk's symmetry
        indices, each side's means, support, pace and foot angles (C242). --affected-side names one affected side
        for every pair under ROOT (C245; run gait-all per side otherwise).

        Examples:

          pdrlearn gait-all study/ --out gait_study

          pdrlearn gait-all study/ --out gait_study --jobs 2 --force

          pdrlearn gait-all study/ --out gait_study --resume   # after a kill or Ctrl-C: the finished pairs reused

          pdrlearn gait-all study/ --out gait_study --affected-side left   # every patient's left leg affected (C245)
        """
        from pdrlearn.cli.gait_batch import gait_all
        from pdrlearn.track.affected_side import check_affected_side

        code = gait_all(root, out, force, jobs=jobs, resume=resume,
                        affected_side=check_affected_side(affected_side))  # cohort C245: before any pairing
        if code:
            raise typer.Exit(code)
