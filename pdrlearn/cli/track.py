"""``pdrlearn track``: session -> trajectory.csv, steps.csv, path.png, summary.json."""
# ruff: noqa: B008  (typer options are declared as defaults)

from __future__ import annotations

import json
from pathlib import Path

import typer

from pdrlearn.cli.common import (
    DPI_HELP,
    FORCE_HELP,
    INITIAL_HEADING_HELP,
    NO_PLOT_HELP,
    PICKLE_HELP,
    START_HELP,
    check_no_plot,
    count_phrase,
    existed,
    gait_line,
    initial_heading_option,
    posture_line,
    print_json,
    replaced,
    resample_options,
    start_option,
    storey_height_option,
    transfer_line,
    walk_line,
)
from pdrlearn.cli.registry_help import LENGTH_NAMES
from pdrlearn.errors import DataError, NoStridesError
from pdrlearn.textfile import is_inline_json, read_json

#: The tracking options, shared by ``track`` and ``track-all`` (one declaration each, so the two commands
#: cannot drift apart). ``--gnss``/``--fixes`` are per-recording files and belong to ``track`` only.
PIPELINE_OPT = typer.Option("auto", help="Tracking pipeline: plasys, waist-pll, waist-pendulum; auto = plasys "
                            "for a session with a foot unit, else waist-pendulum, or the lower-back pipeline a "
                            "--params calibration was made for (W407).")
METHOD_OPT = typer.Option("auto", help="PLASYS method: M1 (accelerometer), M2 (+ force), M3 (+ classes); "
                          "auto = M3 with --model, else the M3 engine without the class rules (warned).")
MODEL_OPT = typer.Option(None, "--model", help=f"Trained model directory (M3; {PICKLE_HELP}); 'oracle' = the "
                         "session's own step labels.")
RULES_OPT = typer.Option(None, "--rules", help="M3 class rules: thesis (classes prevail) or bayes "
                         "(class probabilities weighed against the estimate); default bayes with a "
                         "model, thesis with --model oracle, offline and --streaming (decisions L40, L41).")
MIN_CONFIDENCE_OPT = typer.Option(None, "--min-confidence", min=0.0, max=1.0,
                                  help="M3: apply a class rule only when the model's probability of the "
                                  "class reaches this (default 0.95; 0 = always, as the thesis).")
LENGTH_BOUNDS_OPT = typer.Option(None, "--length-bounds", help="M3 stride-length class edges "
                                 "SHORT_MAX,NORMAL_MAX in m (default: the model's, else thesis x 2).")
LENGTH_REFERENCE_OPT = typer.Option("model", "--length-reference", metavar="model|session", help="M3, offline: "
                                    "session = after tracking, a flat, forward, straight stride's length_class from "
                                    "its length against 0.8 / 1.2 x the median of ALL the session's such strides, "
                                    "unless the model calls half or more of them short or long (decision C126; "
                                    "lengths unchanged). Default model: the classifier's.")


def warn_ood_option(when: str = "With --model: ", model: str = "model"):
    """C16's ``--warn-out-of-domain`` of ``track`` (``track-all``) and ``run`` (decision E105), one text."""
    return typer.Option(None, "--warn-out-of-domain", help=f"{when}warn (one line, naming the classifier and the "
                        "feature most often off) when at least this fraction of the strides lie outside the "
                        f"{model}'s training range, e.g. 0.25 (without it: a short line only when more than half are, "
                        "decision C61; the fraction is always in summary.json as out_of_domain_fraction, decision "
                        "C16).")


WARN_OOD_OPT = warn_ood_option()
START_OPT = typer.Option(None, "--start", help=START_HELP)
PARAMS_OPT = typer.Option(None, "--params", help="Per-user calibration JSON passed to the pipeline: a file, or the "
                          "JSON object itself in quotes, e.g. '{\"clip_noise\": true}' (B466).")
#: decision E176: track's, run's, track-all's and calibrate's option (one declaration, E93)
REDACT_PATHS_OPT = typer.Option(False, "--redact-paths", help="Write every folder the command was given, and the "
                                "working directory, as <redacted> in its outputs (summary.json input_dir; run.json "
                                "cwd, argv, session, root, options; warnings; track-all's hidden per-session record); "
                                "run.json says paths_redacted. Names below ROOT, the session and subject names stay "
                                "(docs/deploying.md, What each output holds). Decision E176.")
STREAMING_OPT = typer.Option(False, "--streaming", help="plasys M2/M3 with the stride-local kernel of "
                             "the streaming runtime: the trajectory `pdrlearn run` reproduces to 1 mm. Its strides "
                             "have no initial contact, so no stride time or cadence (summary median_cadence_spm None), "
                             "unless --contacts (decisions E51, L204).")
REALTIME_OPT = typer.Option(False, "--realtime", help="waist-pendulum: the causal initial-contact "
                            "detector (each contact decided < 2 s after it, decision W31) instead of the "
                            "zero-lag offline one; = \"options\": {\"realtime\": true} in --params.")
FREEZE_INDEX_OPT = typer.Option(False, "--freeze-index", help="Lower back: the freeze index's episodes "
                                "(freezes.csv, n_freezes; decision W213), off by default there: it also reads daily "
                                "activities and slow walks as freezing (decision W216); = \"options\": "
                                "{\"freeze_index\": true} in --params. Foot tracks always have it.")
GAIT_QUALITY_OPT = typer.Option(False, "--gait-quality", help="Lower back: fill bouts.csv's gait-quality columns "
                                "(harmonic ratios, regularity, symmetry, RMS; decision W350) and summary.json's "
                                "gait_quality; off by default: not validated on real recordings (W352).")
REFERENCE_POINT_OPT = typer.Option(None, "--reference-point", help="plasys: the point whose path is "
                                   "tracked: sensor (the unit, default) or heel (the heel contact, lever arm "
                                   "estimated from the recording, decision L22; = \"reference_point\" in "
                                   "--params); heel also adds the heel's own lift max_heel_lift_m to steps.csv "
                                   "(L721).")
TOE_OFF_OPT = typer.Option(False, "--toe-off", help="plasys, offline: add the toe-off tc_s and "
                           "stance_time_s, swing_time_s, stance_pct, cycle_start_s (the IC whose stance it is, "
                           "L672) to steps.csv (decision L73: an option, not the default - its toe-off runs ~21 ms "
                           "early against mocap, so stance reads ~37-43 ms short and swing as much long, L672; see "
                           "docs/localization.md). With labels giving tc_ms, steps.csv gets ref_tc_s / "
                           "ref_stance_time_s / ref_swing_time_s (D52).")
IGNORE_FORCE_OPT = typer.Option(False, "--ignore-force", help="plasys, offline: the stance and strides from the foot "
                                "IMU alone, the force sensors (fForceA/fForceB) left out (decision L366); without "
                                "it they are checked against the IMU and replaced where they disagree (L365).")
DETECTOR_OPT = typer.Option(None, "--detector", help="The steps from this step detector (a built-in or a registered "
                            "/ installed plug-in, docs/extending.md): a foot detector gives plasys its strides "
                            "(decision L149), a waist one (unit 'waist') gives the lower-back pipeline its contacts "
                            "(decision E85); NAME:key=value,... sets its settings, e.g. pll:loop_hz=1.5 (decision "
                            "E94, as --length-model). Default: the pipeline's own.")
GATE_OPT = typer.Option(False, "--gate", help="With a waist --detector: keep only its contacts where the lower-back "
                        "pipelines' walking gate is open (2 s SD of the vertical acceleration >= 0.5 m/s^2 or W76's "
                        "session threshold, as waist-ic's; decision W473), so it is compared with waist-ic on equal "
                        "terms. Default: its contacts as they are.")
LENGTH_MODEL_OPT = typer.Option(None, "--length-model", help="Lower-back pipelines: the step-length model "
                                f"({LENGTH_NAMES}, or a plug-in; NAME:key=value,... sets its settings; "
                                "decision E84; a gain model without its gain takes the one `calibrate "
                                "--length-model NAME` wrote to --params, W460). Default: the pipeline's own.")
CONTACTS_OPT = typer.Option(False, "--contacts", help="plasys --streaming: each stride's initial contact "
                            "(force onset, else the accelerometer impact) and so stride_time_s, cadence_spm, "
                            "speed_mps (decisions E49-E51; `pdrlearn run --contacts` gives the same).")
DROP_NEIGHBOUR_OPT = typer.Option(False, "--drop-neighbour", help="plasys --streaming: a stride across dropped foot "
                                  "samples over 0.25 s (under 1 s) takes the length and height change of the stride "
                                  "before it (decision L167, measured and not the default: it kept the distance "
                                  "under burst loss, not the altitude; E101; `pdrlearn run --drop-neighbour` gives "
                                  "the same).")
NO_CYCLING_OPT = typer.Option(False, "--no-cycling", help="plasys: an activity without bicycles (dance, a clinic): "
                              "no foot stride is judged pedalling and removed (L611; decision E304; `pdrlearn run "
                              "--no-cycling` gives the same, without L611's hold of short turning strides).")
ALTITUDE_OPT = typer.Option(None, "--altitude", help="plasys: the altitude from the foot's strides alone (foot, "
                            "the default) or fused with the session's waist barometer (fused: slopes and hills "
                            "read; an option, decision L154 - the barometer's wander moves a level walk by up to "
                            "~0.4 m and a stair climb by a few cm; docs/localization.md).")
#: decision L545: ``--compass``'s values: auto = L182's check and L226's fallback to the waist gyroscope when it
#: warns (the default); keep = the fused heading keeps the compass (L17) even when the check warns; decision L657:
#: off = the session tracked as without its waist magnetometer (the gyroscopes' relative heading, L98)
COMPASS_CHOICES = ("auto", "keep", "off")
#: decision L556: ``--compass keep`` (L657: or off) on a session without the waist magnetometer (it reads no compass)
COMPASS_UNUSED = ("--compass {value} chooses the fused heading's compass, but the session has no waist magnetometer "
                  "(wMagneticField.csv), so the heading reads no compass and --compass {value} changes nothing "
                  "(decision L556)")
COMPASS_OPT = typer.Option("auto", "--compass", help="plasys, offline, foot + waist (the fused heading): auto = "
                           "when the compass check warns (decision L182), follow the waist gyroscope turned to the "
                           "compass (L226); keep = keep the compass (L17) all the same, e.g. outdoors, away from "
                           "steel, where the compass is trusted (decision L545); off = read no compass, as if the "
                           "session had no wMagneticField.csv: the waist and foot gyroscopes' heading, relative, "
                           "so --initial-heading DEG sets its start direction, e.g. indoors near steel or VR gear "
                           "(decision L657).")
DPI_OPT = typer.Option(None, "--dpi", min=20, max=600, help=DPI_HELP)
NO_PLOT_OPT = typer.Option(False, "--no-plot", help=NO_PLOT_HELP)  # decision L533
COMMON_SPAN_OPT = typer.Option(False, "--common-span", help="A sensor file of a unit is over 1 s shorter than the "
                               "unit's others (cut short, refused by B72): track only the time all of them cover, "
                               "every file and label table cut to it, with one warning naming the seconds dropped "
                               "from each file (decision B81).")
DROP_PARTIAL_ROW_OPT = typer.Option(False, "--drop-partial-row", help="A sensor file whose last line has no line "
                                    "break (a row cut when a unit's battery died; refused by B128 when the cut "
                                    "leaves a cell empty or not a number, while a cut inside the last number is read "
                                    "as that shorter number without a word, B270): drop that last line, with one "
                                    "warning; a file then shorter than its unit's others is still refused (B72; "
                                    "decision B266). A last row without a line break is treated as cut even when its "
                                    "values look whole, so it is dropped too (decision B276).")
ALIGN_UNITS_OPT = typer.Option(False, "--align-units", help="plasys, offline, foot + waist: move the waist unit's "
                               "clock onto the foot's by the steps both detect (offset and drift, "
                               "pdrlearn.steps.align_units; reliable for offsets under half a step period, about "
                               "0.25 s: a larger one can be read one step period off; decision L162; an estimate "
                               "that cannot be trusted, as a long recording's drift past half a step, is not applied "
                               "and one line says so: give --clock-offset / --clock-drift-ppm, decision L446).")
CLOCK_OFFSET_OPT = typer.Option(None, "--clock-offset", metavar="SECONDS", help="plasys, foot + waist: the waist "
                                "unit's clock offset, known by hand (t_waist = t_foot + SECONDS: 0.3 when the waist "
                                "clock reads 0.3 s late), removed before tracking, offline or streamed; instead of "
                                "--align-units' estimate; recorded as info.unit_alignment in summary.json "
                                "(decisions E111, E112).")
CLOCK_DRIFT_OPT = typer.Option(None, "--clock-drift-ppm", metavar="PPM", help="plasys, foot + waist: the waist "
                               "unit's clock drift, known by hand (ppm, as `simulate --clock-drift-ppm`: t_waist = "
                               "t_foot x (1 + PPM/1e6) + --clock-offset; 200 when the waist clock gains 0.72 s an "
                               "hour), removed before tracking with --clock-offset's mechanism; the refusal of "
                               "units whose ends drift apart names it (decisions B264, B265).")
RESAMPLE_OPT, NO_RESAMPLE_OPT = resample_options("tracked", "with --model: ")


def clock_offset_value(clock_offset: float | None, align_units: bool, command: str) -> float | None:
    """``--clock-offset`` checked (decision E112): a finite number of seconds, not with ``--align-units`` (which
    estimates the offset the option gives); one line naming the fix otherwise."""
    import math

    if clock_offset is None:
        return None
    if not math.isfinite(clock_offset):
        raise DataError(f"{command}: --clock-offset {clock_offset}: give the waist unit's clock offset in seconds, a "
                        "finite number (t_waist = t_foot + SECONDS), e.g. --clock-offset 0.3")
    if align_units:
        raise DataError(f"{command}: --clock-offset {clock_offset:g} gives the waist clock's offset and "
                        "--align-units estimates it from the steps: drop one of them")
    return float(clock_offset)


def clock_drift_value(clock_drift_ppm: float | None, align_units: bool, command: str) -> float | None:
    """``--clock-drift-ppm`` checked (decision B265, as E112's ``--clock-offset``): a finite number of ppm within
    ``apply_alignment``'s 10 % (100000 ppm), not with ``--align-units`` (which estimates the drift); returned as a
    fraction (200 ppm -> 2e-4). One line naming the fix otherwise."""
    import math

    if clock_drift_ppm is None:
        return None
    from pdrlearn.kernels.align import MAX_CLOCK_DRIFT

    if not math.isfinite(clock_drift_ppm) or abs(clock_drift_ppm) > MAX_CLOCK_DRIFT * 1e6:
        raise DataError(f"{command}: --clock-drift-ppm {clock_drift_ppm}: give the waist clock's drift in ppm, a "
                        "finite number within +-100000 (t_waist = t_foot x (1 + PPM/1e6)), e.g. --clock-drift-ppm "
                        "200")
    if align_units:
        raise DataError(f"{command}: --clock-drift-ppm {clock_drift_ppm:g} gives the waist clock's drift and "
                        "--align-units estimates it from the steps: drop one of them")
    return float(clock_drift_ppm) * 1e-6


def given_clock_options(offset_s: float | None, drift: float | None) -> str:
    """The options that gave the waist clock by hand (decisions E111, B265), for the lines that name them."""
    return " and ".join(o for o, v in (("--clock-offset", offset_s), ("--clock-drift-ppm", drift)) if v is not None)


def no_waist_for_clock(command: str, option: str, where: str) -> DataError:
    """Decision B192's line (E112: also for ``--clock-offset``): the option moves the waist clock of a session
    without a waist unit, or whose waist unit ``--units`` leaves out."""
    return DataError(f"{command}: {option} moves the waist unit's clock onto the foot's, but {where} has no waist "
                     f"unit (wAccelerometer.csv + wGyroscope.csv) or --units leaves it out; drop {option}")
MOUNT_FRAME_OPT = typer.Option("declared", "--mount-frame", help="declared (default): a unit's meta.json frame is "
                               "used even when its data contradict it (D10's warning); inferred: the frame the data "
                               "give is used then (a unit clipped turned on its mount, e.g. a lower-back unit at the "
                               "side of the waistband), one line saying so (decision W607).")
UNITS_OPT = typer.Option(None, "--units", help="Body units to track with: foot (the waist files left out, as "
                         "`pdrlearn run --units foot`), waist, or foot,waist (default: every unit the session has; "
                         "decision B127), e.g. to keep the foot outcome of a session whose waist unit stopped early.")
INITIAL_HEADING_OPT = typer.Option(None, "--initial-heading", metavar="DEG", help=INITIAL_HEADING_HELP)
TURN_TO_HEADING_OPT = typer.Option(False, "--turn-to-heading", help="With --initial-heading DEG on a track whose "
                                   "heading is absolute (the default offline track with the waist compass): turn the "
                                   "whole track about its start so that its first straight strides head DEG, taking "
                                   "out the compass's constant offset (decision L635; an option, not the default: "
                                   "measured, it helped on 2 of 4 courses).")
AT_TIMES_OPT = typer.Option(None, "--at-times", metavar="FILE", help="A CSV of times, column t (seconds from the "
                            "session's start) or time (ISO 8601, with a recording start): OUT/at_times.csv gives the "
                            "track's x, y, z (and its other columns) at each, interpolated; the start pose before "
                            "the first stride (decision L638). A time outside the recording is one error line.")
START_XY_OPT = typer.Option(None, "--start-xy", metavar="X,Y", help="The start in local metres (x east, y north; "
                            "decision L637): trajectory.csv starts there, and --fixes in local x, y are in the same "
                            "frame. Not with --start (a geodetic start) or --gnss.")
BOUT_RULE_OPT = typer.Option(None, "--bout-rule", help="Walking bouts (OUT/bouts.csv, decision L163): pdrlearn "
                              "(default: a pause of --bout-break-s beyond the walker's rhythm, a turn across it "
                              "taking its time first) or mobgap (Mobilise-D's rule as mobgap implements it: a new "
                              "bout when two contacts are more than 3 s apart, at least 4 strides; --bout-break-s "
                              "and --bout-min-strides override its numbers) or mobgap-indip (mobgap's bouts, each "
                              "lower-back bout from its second contact to its last-but-one, nearer INDIP's WB "
                              "edges; decision W495).")
BOUT_BREAK_OPT = typer.Option(None, "--bout-break-s", help="Walking bouts (OUT/bouts.csv, decision L124): a pause "
                               "of at least S seconds beyond the walker's rhythm ends a bout (with --bout-rule "
                               "mobgap: a contact gap over S s). Default 1 (L104); 3 with --bout-rule mobgap. "
                               "Not mobgap's rule by itself: see --bout-rule.")
BOUT_MIN_STRIDES_OPT = typer.Option(None, "--bout-min-strides", help="Walking bouts (OUT/bouts.csv, decision "
                                    "L124): a bout needs at least N strides, shorter ones are left out of the "
                                    "table. Default 0 (every bout); mobgap's Mobilise-D rule: 4.")
WINDOW_OPT = typer.Option(None, "--window", help="START,END in seconds from the session start (track-all: from "
                          "each session's start): track the whole session, then keep the steps whose middle lies "
                          "inside (e.g. 0,120: a 2-minute walk; decisions L105, L108). The summary, steps.csv and "
                          "trajectory.csv are the window's; its references are cut the same way. An END past "
                          "the recording is clipped to its end, with one warning line (decision B242). Clock times "
                          "(02:10,02:20 or two ISO 8601 date-times) when the session gives its start (meta.json "
                          "recording_start or a date-time import; decision L299).")
WINDOW_MARGIN_OPT = typer.Option(None, "--window-margin", metavar="SECONDS", help="With --window: track only the "
                                 "window and SECONDS before and after it (e.g. 60: a fused heading's +-60 s), not the "
                                 "whole recording - a window of a long shift then costs the window. The positions "
                                 "start at the margin's start (not where the whole track was); decision L792 gives "
                                 "what else differs. Default: the whole recording is tracked.")

PER_OPT = typer.Option(None, "--per", help="Totals per period in OUT/periods.csv (e.g. 1h, 30min, 90s, 900; 'm' is "
                       "refused as it reads as metres: write min for minutes, decision B305; 0.1 s at least, B329): "
                       "the whole session's "
                       "track cut into periods from the recording's start, the last one shorter and marked partial; "
                       "distance, steps, walking / between-steps / no-step / no-data time, floors, bouts, "
                       "turns, the position sigma at the period's end (decisions L275, L277). With --window: the "
                       "window cut into periods from its start (decision L381).")
PER_ALIGN_OPT = typer.Option(None, "--per-align", help="Where --per's periods begin: start (default: at the "
                             "recording's start, or the --window's), first-step (at the first tracked step, decision "
                             "L381; with --walk-test-duration at the walk test's 'go', walk_test_start_s: the test's "
                             "minutes; the default with --walk-test-duration, decision C178) or clock (at whole "
                             "multiples of the period on the recording's clock, 1h = the clock hours; the first and "
                             "last periods partial). clock needs the session's start (meta.json recording_start or a "
                             "date-time import; decision L299).")
SEGMENTS_OPT = typer.Option(None, "--segments", metavar="LEGS.csv", help="Totals per trip leg in OUT/segments.csv "
                            "from one track: LEGS.csv has columns start_s,end_s (seconds from the session start, as "
                            "--window takes them) and an optional label, one leg a row, sorted and not overlapping; "
                            "each row has periods.csv's totals (steps, distance, walking time, bouts, ...) over its "
                            "leg. A bad LEGS.csv is one error line before any tracking (decisions L618, L619).")
STEADY_TRIM_OPT = typer.Option(None, "--steady-trim", metavar="N", help="A steady-state rule: leave the first "
                               "and last N strides of each walking bout out of gait speed, cadence, the stride "
                               "time / length / speed medians and the CVs (decision L415; default 0: none, each bout's "
                               "first two and last stride are never CV strides anyway). steps.csv's steady column "
                               "marks the CV strides.")
CORRIDOR_OPT = typer.Option(None, "--corridor", metavar="METRES", help="A corridor walk test (6MWT / 2MWT) up "
                            "and down a course of METRES (e.g. 30, the ATS 2002 6MWT's): OUT/laps.csv (the laps "
                            "between cone turns of >= 135 deg) and the summary's walk_test_distance_m = laps x "
                            "METRES + the final partial lap, n_laps, distance per minute from the first step, "
                            "fatigue_index (decisions L383, L384). A 6MWT inside a longer "
                            "recording: with --window T0,T0+360.")
WALK_TEST_DURATION_OPT = typer.Option(None, "--walk-test-duration", metavar="SECONDS", help="With --corridor: "
                                      "the test lasts SECONDS from 'go' (--walk-test-start; 360 for a 6MWT, 120 for "
                                      "a 2MWT, the ATS 2002 protocol); walking after it (back to a chair) is not "
                                      "scored (decision L516); a recording or walk that ends early is said "
                                      "(walk_test_stopped_s, L644).")
WALK_TEST_START_OPT = typer.Option("auto", "--walk-test-start", metavar="auto|first-step|SECONDS", help="With "
                                   "--walk-test-duration: the test's 'go'. auto (default): the first step after the "
                                   "last standstill of 5 s or more before the first full lap (a walk to the start "
                                   "line and a wait), else the first step; a session's meta.json walk_test_start_s "
                                   "gives its own 'go' (s); first-step: the first step; SECONDS: that time on every "
                                   "session's clock (decision L642).")
SPLITS_OPT = typer.Option(None, "--splits", metavar="METRES", help="Split times at distances along the tracked path "
                          "(e.g. 5,10,20: a sprint's marks, metres from the first step; every:1000: a mark every "
                          "1000 m and the final partial split at the path's end, L553): OUT/splits.csv (each mark's "
                          "time from the first step's start, interpolated within the stride that crosses it, the "
                          "split time, mean speed and pace in min/km since the previous mark, L554) and a summary "
                          "line; marks beyond the path are named in one warning (decision L411).")
TEN_M_WALK_OPT = typer.Option(None, "--ten-m-walk", metavar="ACCEL,TIMED,DECEL", help="The 10 m walk test's "
                              "walkway in metres: an acceleration zone, the timed distance and a deceleration zone "
                              "(default 2,10,2 on 14 m, L312; e.g. 2,6,2: a 10 m walkway's middle 6 m). Every "
                              "straight walking bout that long is timed (one tracked at most 2 % short that passed "
                              "the timed stretch too, C193): the summary's ten_m_walk_* keys (the first "
                              "trial), n_ten_m_walk_trials and OUT/ten_m_walk_trials.csv (decisions L522, L524); a "
                              "test not timed says why on the console and in clinical.md (C194).")

STAIR_RISE_OPT = typer.Option(None, "--stair-rise", metavar="METRES", help="The stairs' rise (e.g. 0.17): "
                              "OUT/stairs.csv (one row per stair flight of a foot track) gets n_stairs = "
                              "round(|height| / METRES) and stairs_per_min; the count comes from the height because a "
                              "stride holds 2 stairs step-over-step and 1 step-to-step (decision L432). A lower-back "
                              "track has no stair flights: no stairs.csv, and one warning says the option is not "
                              "used (L440).")
STAIR_GRADE_OPT = typer.Option(None, "--stair-grade", metavar="PCT", help="The rise over run (%, in (0, 100]) from "
                               "which a foot track's climb is a stair, not a ramp (stairs.csv, floors_*_stairs / "
                               "_ramps, ramps.csv). Default 20 (decision L301); --stair-grade 30 for a trail walk, "
                               "whose 20-30 % slopes then stay ramps (decisions L463, L469). A foot track reads real "
                               "stairs at about 34-39 %, so a grade near that loses stair flights. The lower back "
                               "keeps 20 % (one warning says so).")


def flights_line(summary: dict) -> str | None:
    """Decision L432: the printed line of a foot track's stair flights (``track`` and ``run``), None without one;
    decision L705: its stair strides are the flights' own (a hill's are the ramps line's)."""
    if not (summary.get("n_flights_up") or summary.get("n_flights_down")):
        return None
    return (f"stair flights {summary['n_flights_up']} up / {summary['n_flights_down']} down "
            f"({summary.get('n_stair_strides_up', 0)} / {summary.get('n_stair_strides_down', 0)} stair "
            "strides; stairs.csv" + ("" if (summary.get("info") or {}).get("stair_rise_m") else
                                     ", n_stairs with --stair-rise METRES") + ")")


def written_ramps_line(summary: dict, out: Path | None) -> str | None:
    """Decision L571: the printed ramps line of a track (``track`` and ``run``) from its written ramps.csv in
    ``out``; None without a ramp."""
    if out is None or not summary.get("n_ramps") or not (Path(out) / "ramps.csv").is_file():
        return None
    import pandas as pd

    from pdrlearn.track.ramp_audit import ramps_line

    strides = (summary.get("n_ramp_strides_up"), summary.get("n_ramp_strides_down"))  # decision L705
    return ramps_line(pd.read_csv(Path(out) / "ramps.csv"), strides if None not in strides else None)


def track(
    session_dir: Path = typer.Argument(..., help="Session folder (PLASYS format)."),
    out: Path = typer.Option(..., "--out", "-o", help="Output folder (created; an existing track only with --force)."),
    pipeline: str = PIPELINE_OPT,
    method: str = METHOD_OPT,
    model: str = MODEL_OPT,
    rules: str = RULES_OPT,
    min_confidence: float = MIN_CONFIDENCE_OPT,
    length_bounds: str = LENGTH_BOUNDS_OPT,
    length_reference: str = LENGTH_REFERENCE_OPT,
    warn_out_of_domain: float = WARN_OOD_OPT,
    start: str = START_OPT,
    initial_heading: float = INITIAL_HEADING_OPT,
    start_xy: str = START_XY_OPT,
    turn_to_heading: bool = TURN_TO_HEADING_OPT,
    at_times: Path = AT_TIMES_OPT,
    storey_height: float = storey_height_option(),
    params: Path = PARAMS_OPT,
    gnss: Path = typer.Option(None, "--gnss", help="GNSS fixes (NMEA, GPX or CSV) for aiding."),
    gnss_period: float = typer.Option(None, "--gnss-period", help="Use a GNSS fix every S seconds."),
    gnss_time_offset: float = typer.Option(None, "--gnss-time-offset", help="Seconds after the session start of the "
                                           "--gnss log's first fix, when meta.json gives no recording_start with a "
                                           "UTC offset (decision D38)."),
    fixes: Path = typer.Option(None, "--fixes", help="Sporadic absolute fixes CSV for aiding."),
    fix_period: float = typer.Option(None, "--fix-period", help="Query the --fixes stream every S seconds while "
                                     "walking (seed 004; thins a dense stream). Default: every fix is used."),
    streaming: bool = STREAMING_OPT,
    realtime: bool = REALTIME_OPT,
    freeze_index: bool = FREEZE_INDEX_OPT,
    gait_quality: bool = GAIT_QUALITY_OPT,
    reference_point: str = REFERENCE_POINT_OPT,
    toe_off: bool = TOE_OFF_OPT,
    ignore_force: bool = IGNORE_FORCE_OPT,
    contacts: bool = CONTACTS_OPT,
    drop_neighbour: bool = DROP_NEIGHBOUR_OPT,
    no_cycling: bool = NO_CYCLING_OPT,
    detector: str = DETECTOR_OPT,
    gate: bool = GATE_OPT,
    length_model: str = LENGTH_MODEL_OPT,
    altitude: str = ALTITUDE_OPT,
    compass: str = COMPASS_OPT,
    dpi: int = DPI_OPT,
    no_plot: bool = NO_PLOT_OPT,
    common_span: bool = COMMON_SPAN_OPT,
    drop_partial_row: bool = DROP_PARTIAL_ROW_OPT,
    align_units: bool = ALIGN_UNITS_OPT,
    clock_offset: float = CLOCK_OFFSET_OPT,
    clock_drift_ppm: float = CLOCK_DRIFT_OPT,
    units: str = UNITS_OPT,
    mount_frame: str = MOUNT_FRAME_OPT,
    window: str = WINDOW_OPT,
    window_margin: float = WINDOW_MARGIN_OPT,
    per: str = PER_OPT,
    per_align: str = PER_ALIGN_OPT,
    segments: Path = SEGMENTS_OPT,
    corridor: float = CORRIDOR_OPT,
    walk_test_duration: float = WALK_TEST_DURATION_OPT,
    walk_test_start: str = WALK_TEST_START_OPT,
    splits: str = SPLITS_OPT,
    ten_m_walk: str = TEN_M_WALK_OPT,
    stair_rise: float = STAIR_RISE_OPT,
    stair_grade: float = STAIR_GRADE_OPT,
    bout_rule: str = BOUT_RULE_OPT,
    bout_break_s: float = BOUT_BREAK_OPT,
    bout_min_strides: int = BOUT_MIN_STRIDES_OPT,
    steady_trim: int = STEADY_TRIM_OPT,
    resample: bool = RESAMPLE_OPT,
    no_resample: bool = NO_RESAMPLE_OPT,
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    redact_paths: bool = REDACT_PATHS_OPT,
    as_json: bool = typer.Option(False, "--json", help="Print the summary as one JSON object."),
    strict: bool = typer.Option(False, "--strict", help="Exit with code 3 when the track gave any warning (the "
                                "outputs are still written; summary.json info.warnings lists them; decision E156). "
                                "Without it: exit 4 when the session holds no stride (B318), 2 on bad input."),
) -> None:
    """Track a session: per-step table, trajectory, path figure and summary (errors vs ground truth).

    Examples:

        pdrlearn track datasets/real/gaitmap_level_right --out out/track_right   # no model: no classes

        pdrlearn track datasets/real/gaitmap_level_right --method M3 --model oracle --out out/track_oracle

        pdrlearn track out/sim/D_u1 --method M2 --start 41.178,-8.608 --out out/D   # + track.gpx, track.geojson

        pdrlearn track out/sim/D_u1 --start 41.178,-8.608,12.5 --out out/D_alt   # z starts at 12.5 m

        pdrlearn track out/sim/D_u1 --streaming --initial-heading 90 --out out/D_north   # sets off north

        pdrlearn track out/sim/D_u1 --method M3 --model out/models/u1 --rules bayes --out out/D3 --json

        pdrlearn track out/sim/D_u1 --method M3 --model out/models/u1 --streaming --out out/D3s   # = pdrlearn run

        pdrlearn track out/sim/D_u1 --model out/models/u1 --length-reference session --out out/D3r   # C126

        pdrlearn track datasets/real/gaitmap_level_left --model out/models/u1 --warn-out-of-domain 0.25 --out out/L

        pdrlearn track datasets/real/mobgap_HA001_Test5_Trial1 --pipeline waist-pendulum --realtime --out out/W

        pdrlearn track out/sim/A_u1 --window 5,15 --out out/A_middle   # the steps between 5 s and 15 s

        pdrlearn track out/sim/A_u1 --per 10s --out out/A_per   # OUT/periods.csv: totals every 10 s

        pdrlearn track night --per 1h --per-align clock --out out/night_h   # clock hours (an imported night)

        pdrlearn track out/sim/A_u1 --per 60 --per-align first-step --out out/A_min   # minutes from the first step

        pdrlearn track day/ --segments legs.csv --out out/day_legs   # OUT/segments.csv: totals per leg (L619)

        pdrlearn track out/sim/D_u1 --corridor 30 --out out/D_laps   # a 6MWT: OUT/laps.csv, laps x 30 m (L383)

        pdrlearn track clinic/6mwt --corridor 30 --walk-test-duration 360 --out out/6mwt   # 6 min from 'go'

        pdrlearn track out/sim/A_u1 --splits 5,10,20 --out out/A_splits   # OUT/splits.csv: times at 5, 10, 20 m

        pdrlearn track march/ --splits every:1000 --out out/march   # every km and the last partial km (L553)

        pdrlearn track out/sim/A_u1 --ten-m-walk 2,6,2 --out out/A_10mwt   # a 10 m walkway's middle 6 m (L522)

        pdrlearn track out/sim/D_u1 --stair-rise 0.181 --out out/D_stairs   # stairs.csv: 1 flight (D's turns climb)

        pdrlearn track out/sim/D_u1 --altitude fused --stair-grade 30 --out out/D_trail   # 20-30 % slopes: ramps

        pdrlearn track out/sim/A_u1 --steady-trim 3 --out out/A_steady   # each bout's first / last 3 strides out

        pdrlearn track out/sim/D_u1 --clock-offset 0.3 --out out/D_clock   # its waist clock known to read 0.3 s late

        pdrlearn track out/sim/D_u1 --clock-drift-ppm 200 --out out/D_drift   # its waist clock gains 200 ppm

        pdrlearn track out/sim/D_u1 --model oracle --strict --json --out out/D_qa   # exit 3 on any warning (E156)

        pdrlearn track walks/D --redact-paths --out out/D_share   # no folder path in any output (E176)

        pdrlearn track out/sim/D_u1 --no-plot --out out/D_tables   # no path.png: the tables alone, faster (L533)

    Many sessions at once: pdrlearn track-all ROOT --out OUTDIR (docs/cohort.md).
    """
    arguments = dict(locals())  # decision L122: every option as given, defaults included (before any other name)
    import time

    from pdrlearn.atomic import atomic_directory
    from pdrlearn.cli.common import out_folder, progress
    from pdrlearn.cli.provenance import given_options, input_hashes, model_record, redaction, run_record, write_run_json

    options = given_options(arguments, leave_out=("session_dir", "out", "force", "as_json"))  # for OUT/run.json
    forms = redaction(arguments)  # decision E176
    out_folder(out, "track", force=force, inputs=(session_dir, params, gnss, fixes, segments))  # L618: LEGS.csv too
    settings = settings_of(arguments, "track")  # decision E93: every tracking option, as track-all passes them
    was = existed(out)
    wall, cpu = time.perf_counter(), time.process_time()
    # decision E131: on a terminal, the stage (tracking, then writing) and the time spent; the offline pipelines
    # run each recording as one call, so no time left is known
    with progress(f"track {session_dir.name}", 2, enabled=not as_json) as advance:
        tracked = track_session(session_dir, settings)  # bad input fails here, before any folder is made
        advance()
        with atomic_directory(out) as tmp:  # all five files or none; --force keeps the old track until then
            summary, aided = write_track(tmp, tracked)
            # decision L122: the session as given (not resolved), the model and its checksum, the pipeline and
            # method used; the times only here (summary.json and the tables stay the same run to run)
            write_run_json(tmp, run_record(
                "track", options, session=str(session_dir), input_sha256=input_hashes(session_dir),  # L136
                model=model_record(model),
                pipeline=summary.get("pipeline"), method=summary.get("info", {}).get("method"),
                track_time_s=round(time.perf_counter() - wall, 2), cpu_time_s=round(time.process_time() - cpu, 2)))
            if forms:  # decision E176: inside the temporary folder, so no unredacted file is ever in place
                from pdrlearn.cli.common import json_default
                from pdrlearn.redact import redact_folder, redact_json

                redact_folder(tmp, forms)
                summary = redact_json(summary, forms, default=json_default)
        advance()
    replaced(out, was)
    if as_json:
        print_json(summary)
    else:
        from pdrlearn.textfile import session_csv

        _print_summary(summary, out, aided, waist_unit=session_csv(session_dir, "wAccelerometer").is_file(),  # L316
                       plot=settings["plot"],  # decision L533
                       tug_from_waist="trunk_contacts" in tracked["result"].info)  # W431: whether the track read it
    warned = summary.get("info", {}).get("warnings") or []
    if strict and warned:  # decision E156: the outputs are written; the exit code says the track warned
        typer.echo(f"strict: {len(warned)} warning(s) (summary.json info.warnings); exit code {STRICT_EXIT}", err=True)
        raise typer.Exit(STRICT_EXIT)


#: decision E156: ``track --strict``'s exit code when the track gave a warning (0 ok, 1 some sessions / users
#: failed, 2 bad input, nothing written, 3 written with warnings)
STRICT_EXIT = 3


#: decision E93: ``track``'s options that ``track-all`` does not take, and why (tests/test_track_all_options_e93.py
#: checks that every other option of ``track`` is one of ``track-all``, declared by the same object)
NOT_IN_TRACK_ALL = {
    "--gnss": "a per-recording fix file", "--gnss-period": "thins --gnss", "--fixes": "a per-recording fix file",
    "--gnss-time-offset": "places one --gnss log's times",
    "--fix-period": "thins --fixes",
    "--segments": "one recording's table of legs (its seconds are that session's clock)",
    "--start-xy": "one recording's start in its building's metres (L637)",
    "--at-times": "one recording's times (its seconds are that session's clock, L638)",
    "--strict": "track-all's exit code 1 names failed sessions; sessions.csv's n_warnings counts each one's (E156)",
}


def settings_of(arguments: dict, command: str = "track") -> dict:
    """:func:`track_settings` of a command's options as given (``dict(locals())`` of ``track`` / ``track-all``):
    every keyword of it that the command has, so that an option one command declares cannot be left out of its
    call (decision E93: ``track-all`` had dropped --detector, --length-model and --align-units). ``command``: ``track``
    or ``track-all`` (decision W615: D10's line names its ``--mount-frame``)."""
    import inspect

    names = inspect.signature(track_settings).parameters
    return track_settings(**{k: v for k, v in arguments.items() if k in names and k != "command"}, command=command)


def track_settings(*, pipeline: str = "auto", method: str = "auto", model: str | None = None,
                   rules: str | None = None, min_confidence: float | None = None, length_bounds: str | None = None,
                   warn_out_of_domain: float | None = None, start: str | None = None, params: Path | None = None,
                   gnss: Path | None = None, gnss_period: float | None = None, fixes: Path | None = None,
                   fix_period: float | None = None, gnss_time_offset: float | None = None, streaming: bool = False,
                   realtime: bool = False,
                   freeze_index: bool = False, gait_quality: bool = False,
                   reference_point: str | None = None, toe_off: bool = False, ignore_force: bool = False,
                   contacts: bool = False,
                   drop_neighbour: bool = False, no_cycling: bool = False, dpi: int | None = None,
                   no_plot: bool = False,
                   initial_heading: float | None = None, start_xy: str | None = None,
                   turn_to_heading: bool = False, at_times: Path | None = None,
                   common_span: bool = False, window: str | None = None, window_margin: float | None = None,
                   per: str | None = None,
                   per_align: str | None = None, segments: Path | None = None, corridor: float | None = None,
                   splits: str | None = None,
                   walk_test_duration: float | None = None, walk_test_start: str = "auto",
                   ten_m_walk: str | None = None,
                   stair_rise: float | None = None, stair_grade: float | None = None, resample: bool = False,
                   no_resample: bool = False, units: str | None = None, bout_break_s: float | None = None,
                   bout_min_strides: int | None = None, storey_height: float = 3.0,
                   detector: str | None = None, gate: bool = False, length_model: str | None = None,
                   altitude: str | None = None, align_units: bool = False, compass: str = "auto",
                   bout_rule: str | None = None, clock_offset: float | None = None,
                   clock_drift_ppm: float | None = None, drop_partial_row: bool = False,
                   steady_trim: int | None = None, length_reference: str = "model",
                   mount_frame: str = "declared", command: str | None = None) -> dict:
    """The tracking options as one plain dict, with what does not depend on the session checked and read
    once (fix files exist, ``--start``, ``--initial-heading`` and ``--window`` parsed, ``--params`` JSON read):
    a batch checks them before its first session, and the dict travels to a Dask worker as it is
    (``track-all --jobs``). What depends on the session (a window inside its recording, L105; a relative
    heading for ``--initial-heading``, L98) is checked per session in :func:`track_session` (decision L108)."""
    from pdrlearn.io.resample import resample_mode
    from pdrlearn.track.bouts import bout_rule as read_bout_rule
    from pdrlearn.track.bouts import check_bout_unit
    from pdrlearn.track.steady import check_steady_trim
    from pdrlearn.track.units import parse_units
    from pdrlearn.track.window import parse_window

    rate_mode = resample_mode(resample, no_resample)  # decision B113
    plot = check_no_plot("track", no_plot, dpi)  # decisions L533, B413: before any session
    bouts = read_bout_rule(bout_break_s, bout_min_strides, bout_rule)  # L124, L163: checked before any session
    if pipeline == "plasys":  # decision W495 (amended): a foot track's trim refused before any session
        check_bout_unit(bouts, "foot")
    if rate_mode != "native" and model is None:
        raise DataError(f"track: {'--resample' if resample else '--no-resample'} compares the session's rate with "
                        "the model's: pass --model DIR, or drop it (without a model nothing depends on the rate)")
    start_ll, start_alt = start_option(start)
    from pdrlearn.kernels.geodetic import start_has_altitude

    heading0 = initial_heading_option(initial_heading)  # decision L98: degrees ENU -> rad
    win = parse_window(window)  # decision L105: a bad window is one line before any tracking
    from pdrlearn.track.window import check_margin

    margin_s = check_margin(window_margin, win)  # decision L792: before any tracking
    from pdrlearn.track.periods import parse_per

    per_s = parse_per(per)  # decision L277
    from pdrlearn.track.clock import PER_ALIGNS

    # decision C178: with --walk-test-duration the periods are the test's minutes, from its first step ("go")
    per_align_auto = per_align is None
    if per_align_auto:
        per_align = "first-step" if walk_test_duration is not None and per_s is not None else "start"
    if per_align not in PER_ALIGNS:  # decision L299
        raise DataError(f"--per-align {per_align!r}: give start (periods from the recording's start), first-step "
                        "(from the first tracked step) or clock (on the clock's whole periods)")
    if per_align != "start" and per_s is None:
        raise DataError(f"track: --per-align {per_align} places --per's periods; give --per (e.g. --per 1h) or drop "
                        "it")
    from pdrlearn.track.segments import read_legs

    legs = read_legs(segments)  # decision L618: a bad LEGS.csv is one line before any session
    if legs is not None and win is not None:
        raise DataError(f"track: --segments {segments} gives the legs to total on the session's clock; --window "
                        "would cut the track they are totalled from: drop --window (or make it a leg)")
    from pdrlearn.track.corridor import corridor_length

    corridor_m = corridor_length(corridor)  # decision B293: before any session
    from pdrlearn.track.bouts import corridor_rule

    bouts = corridor_rule(bouts, corridor_m)  # decision C182: a corridor test's cone turns end no walking bout
    from pdrlearn.track.corridor import walk_test_duration as check_walk_test_duration

    walk_test_s = check_walk_test_duration(walk_test_duration, corridor_m)  # decision B396: before any session
    from pdrlearn.track.corridor import walk_test_start as check_walk_test_start

    go = check_walk_test_start(walk_test_start, walk_test_s)  # decision L642: before any session
    from pdrlearn.track.splits import parse_splits

    splits_m = parse_splits(splits)  # decision B307: before any session
    from pdrlearn.track.walk_test import parse_ten_m_walk

    ten_m_walk_m = parse_ten_m_walk(ten_m_walk)  # decision L522: before any session
    from pdrlearn.track.stair_flights import stair_rise as check_stair_rise

    stair_rise_m = check_stair_rise(stair_rise)  # decision B348: before any session
    from pdrlearn.track.grade import check_stair_grade

    stair_grade_pct = check_stair_grade(stair_grade)  # decision L469: before any session
    if heading0 is not None and gnss is not None:  # L98: known before any tracking (L637: --fixes take it)
        raise DataError("track: --initial-heading sets the start direction of the track, but --gnss gives the "
                        "track its direction; drop --initial-heading")
    if turn_to_heading and heading0 is None:  # decision L635
        raise DataError("track: --turn-to-heading turns the track to the start heading of --initial-heading DEG, "
                        "which is not given; add --initial-heading DEG or drop --turn-to-heading")
    at_times_file, at_times_rows = None, None
    if at_times is not None:  # decision L638: the times file read once, before any session
        from pdrlearn.track.at_times import read_times

        at_times_file, at_times_rows = str(at_times), read_times(at_times)
    from pdrlearn.track.start_pose import parse_start_xy

    xy0 = parse_start_xy(start_xy)  # decision L637: before any session
    if xy0 is not None and (start is not None or gnss is not None):
        other = "--start gives it as latitude, longitude" if start is not None else "--gnss fixes are geodetic"
        raise DataError(f"track: --start-xy {start_xy} gives the start in local metres; {other}: drop one of them")
    if gnss_time_offset is not None and gnss is None:  # decision D38
        raise DataError(f"track: --gnss-time-offset {gnss_time_offset:g} places the times of a --gnss log, which is "
                        "not given; pass --gnss FILE or drop --gnss-time-offset")
    from pdrlearn.aid.track import check_time_offset

    gnss_time_offset = check_time_offset(gnss_time_offset)  # decision D42: a finite number, before any session
    for fix_file in (gnss, fixes):  # before the tracking, which warned and worked first
        if fix_file is not None and not Path(fix_file).is_file():
            raise DataError(f"{fix_file}: no such fix file; pass an NMEA log (.nmea/.txt), a GPX track (.gpx) or a "
                            "CSV (t, lat, lon, accuracy_m)")
    from pdrlearn.kernels.relative_length import check_length_reference

    if check_length_reference(length_reference) != "model" and (model is None or str(model) == "oracle"):  # C126
        raise DataError(f"track: --length-reference {length_reference} replaces a trained model's length classes "
                        f"({'oracle classes are the labels' if model is not None else 'no --model given'}); add "
                        "--model DIR, or drop --length-reference")
    if model is not None and str(model) != "oracle":  # decision B128: a bad --model fails once, before any session
        from pdrlearn.classify.model_dir import refuse_pickle, verify_model_dir

        refuse_pickle(model)  # decision E260: PDRLEARN_NO_PICKLE=1, once before any session
        verify_model_dir(model)
    if rate_mode != "native":  # B113: oracle or a model without rates, once before a batch's first session
        from pdrlearn.classify.model_dir import read_manifest
        from pdrlearn.io.resample import positive_rates, require_rates

        rates = {} if str(model) == "oracle" else positive_rates(read_manifest(model).get("sampling_rate_hz") or {})
        require_rates(str(model), rates, rate_mode, command="track")
    par = None if params is None else read_params(params)
    if isinstance(par, dict) and "stride_upsample" in par:  # B176: checked once, naming the file (L141's line)
        from pdrlearn.kernels.stride import stride_upsample

        stride_upsample(par, str(params))
    detector_unit = None
    if detector is not None:  # decisions L149, E85: an unknown detector fails once, before any session
        from pdrlearn.steps import get_detector

        detector_unit = get_detector(detector).unit
        if detector_unit == "foot" and pipeline not in ("auto", "plasys"):
            raise DataError(f"track: --detector {detector} detects the foot's strides; --pipeline {pipeline} "
                            "integrates lower-back steps: choose a detector with unit 'waist' (pll, waist-ic, "
                            "pelvic-gyro or a plug-in), or --pipeline plasys")
        if detector_unit == "waist" and pipeline == "plasys":
            raise DataError(f"track: --detector {detector} detects lower-back steps; the plasys pipeline integrates "
                            "the foot's strides: choose a foot detector (accel, accel-force or a plug-in with "
                            "unit 'foot'), or a lower-back --pipeline")
        if detector_unit == "waist" and realtime:
            raise DataError(f"track: --detector {detector}: --realtime chooses the pipeline's own causal contact "
                            "detector (decision W31); drop one of them")
        refusal = None
        if ignore_force:  # decision B299: before any session
            from pdrlearn.displace.force_check import reads_force_refusal

            refusal = reads_force_refusal(detector)
        if refusal:
            raise DataError(f"track: {refusal}")
        if streaming:
            raise DataError("track: --detector chooses the offline strides; the --streaming kernel segments its "
                            "own - drop one of them")
    if gate and detector_unit != "waist":  # decision W473: before any session
        raise DataError("track: --gate applies the lower-back walking gate to a waist --detector's contacts"
                        + (f"; --detector {detector} detects the foot's strides" if detector_unit == "foot" else
                           " (the pipelines' own contacts are gated already)")
                        + ": give --detector NAME of a detector with unit 'waist', or drop --gate")
    clock_offset_s = clock_offset_value(clock_offset, align_units, "track")  # decision E112: before any session
    clock_drift = clock_drift_value(clock_drift_ppm, align_units, "track")  # decision B265, as E112
    if align_units and streaming:  # decision L162 (E93: once, before a batch's first session)
        raise DataError("track: --align-units moves the waist clock by the steps of the whole recording; the "
                        "--streaming kernel cannot - drop --streaming or --align-units")
    if length_model is not None:  # decision E84: an unknown model or setting fails once, before any session
        from pdrlearn.waist.lengths import get_step_length

        get_step_length(length_model)
        if pipeline == "plasys":
            raise DataError("track: --length-model sets the lower-back pipelines' step length; plasys takes its "
                            "stride length from the foot: drop --length-model or choose a lower-back --pipeline")
    if altitude is not None:  # decision L154: an unknown source is one line before any session
        from pdrlearn.track.altitude import check_altitude

        if check_altitude(altitude) == "fused" and "waist" not in (parse_units(units) or ("waist",)):
            raise DataError(f"track: --altitude fused reads the waist barometer (wBarometer.csv), which --units "
                            f"{units} leaves out: add waist to --units (--units foot,waist) or drop --altitude")
    from pdrlearn.io.frames import MOUNT_FRAMES

    if mount_frame not in MOUNT_FRAMES:  # decision W607: before any session
        raise DataError(f"--mount-frame {mount_frame}: give declared (the meta.json frame, the default) or inferred "
                        "(the frame the data give when they contradict it, decision W607)")
    if compass not in COMPASS_CHOICES:  # decision L545: before any session
        raise DataError(f"--compass {compass}: give auto (fall back to the waist gyroscope when the compass check "
                        "warns, the default), keep (keep the compass) or off (read no compass, decision L657)")
    if compass != "auto" and streaming:
        raise DataError(f"track: --compass {compass} chooses the offline fused heading's source; the --streaming "
                        "kernel heads by the waist gyroscope and reads no compass: drop --streaming or --compass")
    if compass != "auto" and "waist" not in (parse_units(units) or ("waist",)):  # decision L556, as --altitude fused
        raise DataError(f"track: --compass {compass} chooses the fused heading's source, the waist unit's "
                        f"compass, which --units {units} leaves out: add waist to --units (--units foot,waist) or "
                        "drop --compass")
    if length_bounds is not None:
        from pdrlearn.cli.common import parse_length_bounds

        bounds = parse_length_bounds(length_bounds)
    else:
        bounds = None
    return {"pipeline": pipeline, "method": method, "model": model, "rules": rules,
            "min_confidence": min_confidence, "bounds": bounds, "length_bounds_given": length_bounds is not None,
            "warn_out_of_domain": warn_out_of_domain, "start_ll": start_ll, "start_alt": start_alt,
            "start_ele": start_has_altitude(start),  # decision L362: track.gpx's <ele> only from a given altitude
            "params": params, "par": par, "gnss": gnss, "gnss_period": gnss_period, "fixes": fixes,
            "gnss_time_offset": gnss_time_offset,
            "fix_period": fix_period, "streaming": streaming, "realtime": realtime,
            "freeze_index": freeze_index, "gait_quality": gait_quality,
            "reference_point": reference_point, "toe_off": toe_off, "ignore_force": ignore_force,
            "contacts": contacts,
            "drop_neighbour": drop_neighbour, "no_cycling": no_cycling, "dpi": dpi, "plot": plot,
            "initial_heading_rad": heading0, "start_xy": xy0, "turn_to_heading": turn_to_heading,  # L635, L637
            "at_times": at_times_file, "at_times_table": at_times_rows,  # decision L638
            "common_span": common_span, "window": win, "window_margin_s": margin_s, "per_s": per_s,
            "per_align": per_align, "per_align_auto": per_align_auto,  # decision C178
            "legs": legs, "segments": segments,  # decision L618
            "corridor_m": corridor_m, "walk_test_s": walk_test_s, "walk_test_start": go, "splits_m": splits_m,
            "ten_m_walk_m": ten_m_walk_m,
            "stair_rise_m": stair_rise_m, "stair_grade_pct": stair_grade_pct,
            "resample": rate_mode,
            "units": parse_units(units), "bouts": bouts, "storey_height_m": storey_height,
            "detector": detector, "detector_unit": detector_unit, "gate": gate, "length_model": length_model,
            "altitude": altitude, "align_units": align_units, "compass": compass, "clock_offset_s": clock_offset_s,
            "clock_drift": clock_drift, "drop_partial_row": drop_partial_row,
            "steady_trim": None if steady_trim is None else check_steady_trim(steady_trim),  # decision L415
            "length_reference": length_reference,  # decision C126
            "mount_frame": mount_frame,  # decision W607
            "command": command}  # decision W615: track or track-all, the command whose options these are


def read_params(params: Path):
    """The parsed ``--params`` JSON (a calibration file of ``pdrlearn calibrate`` or plasys settings), read once per
    file; one error line naming the file when it cannot be read. Decision B466: a value that is no file and starts
    with ``{`` is the JSON object itself (``--params '{"clip_noise": true}'``)."""
    try:
        text = str(params).strip()
        if is_inline_json(params):  # decision B466: the JSON itself, inline
            try:
                par = json.loads(text)
            except json.JSONDecodeError as exc:
                raise DataError(f"--params {text}: not a file, and not a JSON object either ({exc.msg} at "
                                f"character {exc.pos}); pass a file, or quote the JSON: "
                                "--params '{\"clip_noise\": true}'") from None
        else:
            par = read_json(Path(params))
    except (OSError, json.JSONDecodeError) as exc:
        why = exc.msg if isinstance(exc, json.JSONDecodeError) and not exc.pos else type(exc).__name__  # B423
        raise DataError(f"{params}: cannot read the parameters JSON ({why}); "
                        "pass the file written by `pdrlearn calibrate`") from None
    if not isinstance(par, dict):  # decision B207: a list had been a TypeError, a string "unknown parameter(s) e, h"
        raise DataError(f"{params}: parameters must be a JSON object ({{\"key\": value, ...}}), not a JSON "
                        f"{'list' if isinstance(par, list) else 'string' if isinstance(par, str) else 'value'}; "
                        "pass the file written by `pdrlearn calibrate`, or foot settings such as {\"rest_s\": 0.05}")
    return par


def _refuse_foot_options_without_foot(pipeline: str, o: dict, session) -> None:
    """Decision W254: ``--units waist`` left a foot unit out, and the foot pipeline was asked for (``--pipeline
    plasys``, or a PLASYS option: ``--model``, ``--method`` ...): one line naming both ways out, instead of "no
    fAccelerometer" about a folder that has it (trial 31 finding 8)."""
    if not any(s.placement == "foot" for s in session._left_out.values()):
        return
    asked = _foot_options_asked(pipeline, o)
    if pipeline == "plasys":
        what = " and ".join(asked) or "the foot pipeline"
        raise DataError(f"track: {session.where}: {what} needs the foot unit (PLASYS tracks the foot), which --units "
                        f"{_kept_units(session)} leaves out; drop "
                        f"{' and '.join(asked) or '--pipeline plasys'} for a lower-back track, or drop --units "
                        "(decision W254)")


def _foot_options_asked(pipeline: str, o: dict) -> list[str]:
    """The options that chose (or name) the foot pipeline, as the user gave them (decisions W254, C163)."""
    return [name for name, on in (
        ("--pipeline plasys", pipeline == "plasys" and o.get("pipeline") == "plasys"),
        ("--model", o.get("model") is not None), ("--method", str(o.get("method", "auto")).lower() != "auto"),
        ("--streaming", bool(o.get("streaming"))), ("--toe-off", bool(o.get("toe_off"))),
        ("--ignore-force", bool(o.get("ignore_force"))),
        ("--contacts", bool(o.get("contacts"))), ("--detector", o.get("detector") is not None),
        ("--altitude", o.get("altitude") is not None)) if on]


def _refuse_foot_options_on_a_lower_back_session(pipeline: str, o: dict, session) -> None:
    """Decision C163 (session 41, trial T1 finding 9): a lower-back-only recording tracked with a foot option
    (``--model``, ``--method``, ``--streaming`` ...) had said "no foot unit ... track it with --pipeline
    waist-pendulum", and that command then refused the same option (two errors in a row). One line now names the
    option, why no lower-back pipeline reads it and the command that works. Decision C164: a per-user model's waist
    direction classifier is not read by a lower-back track either (it failed its adoption rule)."""
    if pipeline != "plasys" or session.has("fAccelerometer") or not session.has("wAccelerometer"):
        return
    asked = [a for a in _foot_options_asked(pipeline, o) if a != "--pipeline plasys"]
    if not asked:  # a bare --pipeline plasys: plasys's own line (decision E182) names the waist pipeline
        return
    drop = " and ".join((["--pipeline plasys"] if o.get("pipeline") == "plasys" else []) + asked)
    one = len(asked) == 1
    classes = (" (they have no step classes: a lower-back track counts backward steps as forward, decision C164)"
               if "--model" in asked else "")
    named = "" if Path(session.where).name == session.name else f" (session '{session.name}')"  # as E182 named it
    raise DataError(f"track: {session.where}{named} has no foot unit (fAccelerometer.csv), and {', '.join(asked)} "
                    f"{'is a foot-pipeline (PLASYS) option' if one else 'are foot-pipeline (PLASYS) options'} that "
                    f"no lower-back pipeline reads{classes}; drop {drop} to track the lower back (--pipeline auto "
                    "chooses waist-pendulum), or give a session with a foot unit (decision C163)")


def _kept_units(session) -> str:
    """The placements ``--units`` kept (decisions W254, W260: the lines name them as given)."""
    return ",".join(sorted({s.placement for s in session.streams.values()}))


def _refuse_waist_pipeline_without_waist(pipeline: str, session) -> None:
    """Decision W260, W254's mirror: ``--units foot`` left the lower-back unit out and a waist pipeline was named:
    one line naming both ways out, instead of "has no wAccelerometer ... record that sensor" about a folder that
    has it (session 31 review, F3)."""
    if (pipeline.startswith("waist") and session._left_out and not session.has("wAccelerometer", "wGyroscope")
            and any(s.placement == "waist" for s in session._left_out.values())):
        raise DataError(f"track: {session.where}: --pipeline {pipeline} needs the lower-back unit, which --units "
                        f"{_kept_units(session)} leaves out; drop --pipeline {pipeline} for a foot track, or drop "
                        "--units (decision W260)")


def refuse_incomplete_foot(pipeline: str, o: dict, session) -> None:
    """Decision C266 (trial s52t3, F7): a PLASYS track of a session whose foot unit lacks its accelerometer or
    gyroscope while the lower-back unit has both is refused in one line naming ``--units waist``, the way to the
    track the session holds ("has no fGyroscope ... choose a method that does not need it" named no method that
    does). Still refused (exit 2): the foot pipeline is not swapped for the lower back's silently."""
    missing = [n for n in ("fAccelerometer", "fGyroscope") if not session.has(n)]
    if pipeline != "plasys" or not missing or not session.has("wAccelerometer", "wGyroscope") or o.get("units"):
        return
    from pdrlearn.decision_refs import decision_ref
    from pdrlearn.errors import MissingSensorError

    given = " (drop --pipeline plasys)" if o.get("pipeline") == "plasys" else ""
    raise MissingSensorError(
        f"track: {session.where}: the foot unit has no {' or '.join(f'{n}.csv' for n in missing)}, which every "
        f"PLASYS method needs; the lower-back unit is complete (wAccelerometer, wGyroscope): track it with "
        f"--units waist{given}, or record the foot's {' and '.join(n[1:].lower() for n in missing)} "
        f"({decision_ref('C266', topic='cohort')})")


def track_session(session_dir: Path, settings: dict) -> dict:
    """Read and track one session with :func:`track_settings`'s options; return what :func:`write_track`
    writes (the session, the result, its summary.json dict, the pipeline, whether it was aided). Decision E154:
    every warning logged on the way (reading, tracking, the summary's checks) is in the summary's
    ``info["warnings"]`` (and the result's), each once, as ``track-all``'s sessions.csv gives them; E155: with their
    codes and the summary's ``schema_version``. Decision L415: the measures are computed under ``--steady-trim``
    (:func:`pdrlearn.track.steady.steady_trim_set`)."""
    from pdrlearn.track.belt import incline_scope
    from pdrlearn.track.grade import stair_grade_set
    from pdrlearn.track.steady import steady_trim_set
    from pdrlearn.warning_lines import captured_warnings, machine_summary

    # decision L442: _track_session declares the session's belt incline inside this scope; L469: --stair-grade
    with captured_warnings(echo=True) as logged, steady_trim_set(settings.get("steady_trim")), incline_scope(), \
            stair_grade_set(settings.get("stair_grade_pct")):
        tracked = _track_session(session_dir, settings)
    # decisions E154, E155; B359 (R1): a zip's session (folder None) names itself `session 'NAME'` in later lines
    where = [str(session_dir), *getattr(tracked.get("session"), "wheres", [])]
    summary = machine_summary(tracked["summary"], logged, where)
    tracked["result"].info["warnings"] = list(summary["info"]["warnings"])
    return tracked


def pseudonymous(session, names: dict[str, str]):
    """Decision C86: ``session`` under ``track-all --subject-map``'s pseudonyms: its name and meta.json's ``subject``
    / ``user`` (a name) replaced where the map lists them (the figure titles, summary and bouts.csv read these)."""
    session.name = names.get(session.name, session.name)
    for key in ("subject", "user"):
        if isinstance(session.meta, dict) and isinstance(session.meta.get(key), str):
            session.meta[key] = names.get(session.meta[key], session.meta[key])
    return session


def _track_session(session_dir: Path, settings: dict) -> dict:
    """:func:`track_session` without E154's capture and L415's setting."""
    from pdrlearn.io import read_session
    from pdrlearn.track.base import (
        calibrated_pipeline,
        get_pipeline,
        lower_back_choice,
        lower_back_params,
        resolve_pipeline,
    )
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.units import check_tracked_span, keep_units, tracked_unit, without_streams

    o = settings
    pipeline, method, model, streaming, toe_off = o["pipeline"], o["method"], o["model"], o["streaming"], o["toe_off"]
    contacts = o["contacts"]
    params, par, gnss, fixes, dpi = o["params"], o["par"], o["gnss"], o["fixes"], o["dpi"]
    # L77: the drops warning of its path; B81: a unit's file cut short, tracked over the time all its files cover
    session = read_session(session_dir, streamed=streaming, spans="common" if o.get("common_span") else "refuse",
                           drop_partial_row=bool(o.get("drop_partial_row")))  # decision B266
    session.mount_frame = o.get("mount_frame", "declared")  # decision W607
    session.mount_frame_command = o.get("command")  # decision W615: D10's line names the option of this command
    if o.get("names"):  # decision C86: track-all --subject-map; the name the tables, figures and summary carry
        session = pseudonymous(session, o["names"])
    from pdrlearn.io.plasys import unit_ends

    ends_read = session._unit_ends_uncut or unit_ends(session.streams)  # decision B267: before any cut
    from pdrlearn.io.external.hapt import activities_line

    labels = activities_line(session_dir)  # decision H8: HAPT's activity labels are not read; said once
    if labels:
        import logging

        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, labels)
    from pdrlearn.io.meta_keys import unknown_keys_line
    from pdrlearn.track.evaluate import belt_summary

    belt_summary(session.meta, {}, session.where)  # decision L321: a bad belt speed refused before tracking
    from pdrlearn.track.belt import incline_value, set_incline

    set_incline(incline_value(session.meta, session.where))  # decision L442 (B365: a bad value refused here)
    unknown = unknown_keys_line(session.meta, session.where)  # decision B262: meta.json keys pdrlearn does not read
    if unknown:
        import logging

        logging.getLogger("pdrlearn.cli").warning("%s", unknown)
    content_id = session.content_id()  # decision C20: track-all names two sessions holding the same recording
    session = keep_units(session, o.get("units"))  # decision B127: --units foot leaves the waist files out
    compass_lines = []
    if o.get("compass", "auto") in ("keep", "off") and not session.has("wMagneticField"):  # decision L556: said
        compass_lines.append(COMPASS_UNUSED.format(value=o["compass"]))
    if o.get("compass", "auto") == "off":  # decision L657: tracked as without wMagneticField.csv
        session = without_streams(session, ("wMagneticField",))
    # decision W474: a lower-back parameters file (on a session with a waist unit) asks for the lower back as well,
    # unless a foot-only option asks for the foot (W478: then one line naming both)
    waist_file = lower_back_params(session, par)
    waist_asked = o.get("detector_unit") == "waist" or o.get("length_model") is not None  # E84, E85
    plasys_given = _plasys_options_given(o, method, model, streaming, toe_off, contacts)
    if pipeline == "auto" and waist_file and not waist_asked:
        _refuse_foot_options_with_waist_params(params, plasys_given, o.get("detector"))  # decision W478
    chosen_by = None  # the option that chose the pipeline, for the lines that name it
    if pipeline == "auto" and (waist_asked or waist_file):
        # a lower-back detector, step-length model or parameters file: the user means the lower back, with the
        # pipeline the file was calibrated for (W407), else waist-pendulum (W474)
        chosen_by = (f"--detector {o['detector']}" if o.get("detector_unit") == "waist" else
                     f"--length-model {o['length_model']}" if o.get("length_model") is not None else
                     f"--params {params}")
        pipeline = lower_back_choice(session, par, chosen_by)  # W478: the one rule get_pipeline("auto") shares
    if waist_asked and not session.has("wAccelerometer"):
        asked = (f"--detector {o['detector']} detects lower-back steps" if o.get("detector_unit") == "waist" else
                 f"--length-model {o['length_model']} sets the lower-back step length")
        raise DataError(f"track: {asked}, but {session.where} has no lower-back unit (wAccelerometer.csv); choose a "
                        "foot detector (accel, accel-force or a plug-in with unit 'foot'), or a session with a waist "
                        "unit")
    if pipeline == "auto" and (method.lower() != "auto" or model is not None or streaming or toe_off or contacts
                               or o.get("ignore_force")
                               or o.get("detector") is not None or o.get("altitude") is not None):
        pipeline = "plasys"  # --method / --model / --streaming are PLASYS options: the user means the foot
    if pipeline in ("plasys", "auto") and session._left_out and not session.has("fAccelerometer"):
        _refuse_foot_options_without_foot(pipeline, o, session)  # decision W254
    _refuse_foot_options_on_a_lower_back_session(pipeline, o, session)  # decision C163
    _refuse_waist_pipeline_without_waist(pipeline, session)  # decision W260
    auto = pipeline == "auto"
    pipeline = resolve_pipeline(pipeline, session)
    refuse_incomplete_foot(pipeline, o, session)  # decision C266
    calibrated = calibrated_pipeline(pipeline, par) if auto else pipeline  # decision W407: the calibration's pipeline
    if calibrated != pipeline:
        pipeline = calibrated
        import logging

        logging.getLogger("pdrlearn.cli").info("--pipeline auto: %s, the pipeline %s was calibrated for (decision "
                                               "W407)", pipeline, params)
    from pdrlearn.track.bouts import check_bout_unit

    check_bout_unit(o.get("bouts"), tracked_unit(pipeline))  # decision W495 (amended): before tracking the session
    given_clock, clock_lines = None, []
    # decision E111: the waist clock moved by hand, before anything reads it; B230: before B126's span check (a
    # waist clock 2 s late covers the foot's time once moved); another pipeline is refused below (B27)
    given = given_clock_options(o.get("clock_offset_s"), o.get("clock_drift"))  # E111; B265: also the drift
    if given and pipeline == "plasys":
        if not session.has("wAccelerometer", "wGyroscope"):
            raise no_waist_for_clock("track", given, session.where)
        from pdrlearn.track.plasys import move_waist_clock

        session, given_clock = move_waist_clock(session, o.get("clock_offset_s") or 0.0, o.get("clock_drift") or 0.0,
                                                clock_lines, source="given", option=given)
    check_tracked_span(session, tracked_unit(pipeline))  # decision B126: the tracked unit covers the walk
    from pdrlearn.track.units import span_cut_s

    # decisions B267, B273: the seconds of the walk the track does not cover (a waist clock moved by hand mapped first)
    cut_s = span_cut_s(ends_read, session, tracked_unit(pipeline), given_clock)
    from pdrlearn.track.clock import clock_texts, recording_start, require_start

    start = recording_start(session.meta, session.where)  # decision L298 (B254: a bad one refused before tracking)
    at_t = None
    if o.get("at_times_table") is not None:  # decision L638: the times in session seconds, checked before tracking
        from pdrlearn.track.at_times import times_in_session

        at_t = times_in_session(o["at_times_table"], o["at_times"], session, start)
    clock = (require_start(session.meta, session.where, "--per-align clock")  # decisions L299, B254
             if o.get("per_s") is not None and o.get("per_align") == "clock" else None)
    win = None
    if o.get("window") is not None:  # decision L105: inside the recording, checked before tracking
        from pdrlearn.track.window import check_window

        win = check_window(o["window"], session, tracked_unit(pipeline))  # B126: the tracked unit's recording
        if at_t is not None:  # review R1 F4: the track covers the window only; a time outside it is not placed
            from pdrlearn.track.at_times import check_span

            at_t = check_span(at_t, win, o["at_times"], "the --window as tracked")
    legs = None
    if o.get("legs") is not None:  # decision L618: the legs inside the tracked unit's recording, before tracking
        from pdrlearn.track.segments import check_legs

        legs = check_legs(o["legs"], session, tracked_unit(pipeline), o.get("segments"))
    fn = get_pipeline(pipeline)
    if o["realtime"] and pipeline != "waist-pendulum":  # decision W60: the flag the docs named
        raise DataError(f"track: --realtime applies to the waist-pendulum pipeline only (got --pipeline {pipeline}, "
                        "which has no causal variant); add --pipeline waist-pendulum on a session with a waist "
                        "unit, or drop --realtime")
    _refuse_ignored_options(pipeline, method, plasys_given,
                            gnss=gnss, gnss_period=o["gnss_period"], fixes=fixes, fix_period=o["fix_period"],
                            chosen_by=chosen_by)
    track_keys = {}
    if pipeline == "plasys" and isinstance(par, dict):
        _refuse_waist_params(par, params, session)
        par, track_keys = _track_params(par, params, streaming)  # decision W422
        if not streaming:  # decisions B206 / B207: the foot settings' types and ranges, in a line naming the file
            from pdrlearn.displace.foot import check_settings

            check_settings(par, str(params))
    if o.get("resample", "native") != "native":  # decision B113: the session at the model's rate, or refused
        from pdrlearn.classify import load_model
        from pdrlearn.io.resample import at_model_rate

        if model != "oracle":
            model = load_model(model)
        session = at_model_rate(session, model, o["resample"], command="track")
    if o["reference_point"] is not None:  # decision L72
        par = _reference_point(o["reference_point"], par, params, pipeline, streaming)
    # waist pipelines read the file themselves, so that their errors name it
    kw = {"model": model, "start": o["start_ll"],
          "params": par if pipeline == "plasys" or par is None else str(params)}
    if o["realtime"]:
        kw["realtime"] = True
    if o.get("freeze_index") and pipeline in ("waist-pll", "waist-pendulum"):  # W216; a foot track's index is on
        kw["freeze_index"] = True
    if pipeline != "plasys":  # decisions E84, E85: the lower-back pipelines' detector and step-length model
        if o.get("detector") is not None:
            kw["detector"] = o["detector"]
        if o.get("gate"):  # decision W473
            kw["gate"] = True
        if o.get("length_model") is not None:
            kw["length_model"] = o["length_model"]
    heading0 = o.get("initial_heading_rad")
    if heading0 is not None:  # decision L98: every pipeline's API takes it (ENU rad)
        kw["initial_heading"] = heading0
    if pipeline == "plasys":
        kw["method"] = method
        if streaming:
            kw["streaming"] = True
        if contacts:  # decisions E49-E51
            if not streaming:
                raise DataError("track: --contacts gives the --streaming kernel initial contacts; offline track "
                                "has its detector's contacts already - add --streaming or drop --contacts")
            kw["contacts"] = True
        if o.get("drop_neighbour"):  # decisions L167, E101
            if not streaming:
                raise DataError("track: --drop-neighbour is for the --streaming strides (decision L167); offline, "
                                "strides across dropped samples take their neighbours' height change (L160) - add "
                                "--streaming or drop --drop-neighbour")
            kw["drop_neighbour"] = True
        if o.get("no_cycling"):  # decision E304: an activity without bicycles
            kw["cycling"] = False
        if o.get("detector") is not None:  # decision L149
            kw["steps"] = o["detector"]
        if o.get("align_units"):  # decision L162
            if not session.has("wAccelerometer", "wGyroscope"):  # decision B192: it had been ignored silently
                raise no_waist_for_clock("track", "--align-units", session.where)
            kw["align"] = True  # with --streaming refused by track_settings, before any session
        if o.get("compass", "auto") == "keep":  # decision L545
            kw["compass_fallback"] = False
        if o.get("ignore_force"):  # decision L366 (offline only: plasys refuses it with streaming=True)
            kw["ignore_force"] = True
        if toe_off:  # decision L73
            if streaming:
                raise DataError("track: --toe-off needs the offline tracker's initial contacts; the --streaming "
                                "kernel (and `pdrlearn run`) has none - drop --streaming or --toe-off")
            kw["toe_off"] = True
        for k in ("rules", "min_confidence", "warn_out_of_domain", "bounds", "altitude"):
            if o.get(k) is not None:
                kw[k] = o[k]
        kw.update(track_keys)  # decision W422: track_plasys options given in --params
    # decision W352: the gait quality (W350) only when asked for; W353: it reads the track's own AHRS
    gait_quality = tracked_unit(pipeline) == "waist" and bool(o.get("gait_quality"))
    tracked_in = session
    if win is not None and o.get("window_margin_s") is not None:  # decision L792: the window and its margin only
        from pdrlearn.track.window import margin_session

        tracked_in = margin_session(session, *win, o["window_margin_s"])
    try:
        result, imus = _run_pipeline(fn, tracked_in, kw, gait_quality)
    except NoStridesError:
        if tracked_in is session:
            raise
        # decision E363 (amends L792): no stride in the window and its margin is L105's empty window, not a session
        # without strides: the whole session tracked, as without --window-margin (its note, exit 0)
        result, imus = _run_pipeline(fn, session, kw, gait_quality)
    if o.get("length_reference", "model") != "model" and pipeline == "plasys":  # decision C126: the whole session's
        from pdrlearn.track.session_length import whole_session_length  # strides, before a window keeps some

        result.steps = whole_session_length(result.steps, source=str(session.where))
    if given_clock is not None:  # decision E111: recorded as --align-units' estimate is (L162)
        import logging

        result.info["unit_alignment"] = given_clock
        result.info["warnings"] = [*clock_lines, *result.info.get("warnings", [])]
        for line in clock_lines:
            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    if compass_lines:  # decision L556
        import logging

        result.info["warnings"] = [*result.info.get("warnings", []), *compass_lines]
        for line in compass_lines:
            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    aided = gnss is not None or fixes is not None
    if heading0 is not None:
        result = _apply_start_heading(result, session, heading0, o["start_ll"], bool(o.get("turn_to_heading")))
    if o.get("start_xy") is not None:  # decision L637: the start in local metres, before the fixes' fusion
        from pdrlearn.track.start_pose import shift_to_start_xy

        result = shift_to_start_xy(result, o["start_xy"])
    if aided:
        try:
            from pdrlearn.aid import aid_track
        except ImportError:
            raise DataError("aiding (--gnss/--fixes) needs pdrlearn.aid.aid_track, which is not installed "
                            "in this version; run without those options") from None
        result = aid_track(result, session, gnss_path=gnss, gnss_period_s=o["gnss_period"], fixes_path=fixes,
                           fix_period_s=o["fix_period"], start=o["start_ll"],
                           gnss_time_offset_s=o.get("gnss_time_offset"))
    if o["start_alt"]:  # decision L56: the z column starts at the given altitude (as Tracker(start=(x, y, ALT)))
        result.trajectory["z"] = result.trajectory["z"] + o["start_alt"]
    if o.get("ten_m_walk_m") is not None:  # decision L522: the walkway of the 10 m walk test's keys and trials
        result.info["ten_m_walk_m"] = o["ten_m_walk_m"]
    if o.get("stair_rise_m") is not None:  # decision L432: stairs.csv's n_stairs (clinical_tables reads it)
        result.info["stair_rise_m"] = o["stair_rise_m"]
        import logging

        from pdrlearn.track.stair_flights import lower_back_rise_line

        line = lower_back_rise_line(result.steps)  # decision L440: said, not ignored silently
        if line:
            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    if o.get("stair_grade_pct") is not None:  # decision L469: the summary's and the tables' stair grade
        import logging

        from pdrlearn.track.grade import record_stair_grade

        line = record_stair_grade(result, o["stair_grade_pct"])
        if line:
            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
    tracked_session, whole = session, result  # decisions L275 / L277: the whole session's track
    if win is not None:  # decision L105: the whole session tracked, then the window's steps kept
        from pdrlearn.track.window import window_track

        result, tracked_session = window_track(result, session, *win)
    from pdrlearn.track.position_sigma import add_position_sigma, drop_position_sigma

    if aided:  # decision L128: fixes reset the error; the dead-reckoning model does not apply
        drop_position_sigma(result)
    elif win is not None:  # L128: a window's uncertainty grows from its own first position
        add_position_sigma(result, tracked_session)
    from pdrlearn.track.bouts import track_bouts

    # decision L124: OUT/bouts.csv, the detected walking bouts; L165: keyed by the session and its subject
    bouts = track_bouts(result, session, o.get("bouts"))  # decision W480
    # decision W352: without --gait-quality its bouts.csv columns stay empty
    if gait_quality and len(bouts):  # decision W350: the lower back's gait quality per bout
        from pdrlearn.waist.ahrs import kept_imu
        from pdrlearn.waist.gait_quality import add_bout_quality

        bouts = add_bout_quality(bouts, result.steps, kept_imu(imus, session))  # W353: the track's AHRS
    from pdrlearn.track.periods import bout_ascent, bout_floors

    bouts = bout_floors(bouts, result.steps, result.info, o.get("storey_height_m", 3.0))  # decision L450
    bouts = bout_ascent(bouts, result)  # decision L467
    # C13, C14: the API's TrackResult.summary; L124: n_bouts under the given bout definition (E73: of the table
    # above, detected once); L64, L127: storeys
    summary = track_summary(result, tracked_session, pipeline=pipeline, bouts=o.get("bouts"), bout_table=bouts,
                            storey_height_m=o.get("storey_height_m", 3.0))
    from pdrlearn.track.steady import add_steady_column

    add_steady_column(result.steps)  # decision L415: steps.csv says which strides the CVs are taken over
    from pdrlearn.track.freezes import add_freeze_columns

    bouts = add_freeze_columns(bouts, result.steps, result.info.get("freezes"))  # decision W397
    from pdrlearn.track.periods import time_accounting

    unit = tracked_unit(pipeline)
    summary.update(time_accounting(whole, session, unit, win))  # decision L275: where the time went
    summary["common_span_cut_s"] = cut_s  # decisions B267, B273: the seconds of the walk the track does not cover
    if gait_quality:  # decision W350: the bouts' medians (W352: no key without --gait-quality, nor on a foot track)
        from pdrlearn.waist.gait_quality import NOT_VALIDATED, quality_medians

        summary["gait_quality"] = quality_medians(bouts)
        import logging

        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, NOT_VALIDATED)
        info = summary.setdefault("info", {})
        info["warnings"] = [*info.get("warnings", []), NOT_VALIDATED]
    elif o.get("gait_quality"):  # W352 amended: a foot track computes none; say so instead of nothing
        import logging

        line = (f"--gait-quality: the gait-quality measures are the lower back's (W350) and a {pipeline} track of the "
                "foot computes none; track the lower-back unit for them: --pipeline waist-pendulum")
        logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
        info = summary.setdefault("info", {})
        info["warnings"] = [*info.get("warnings", []), line]
    if win is not None:
        # decision B242: the window as tracked (an END past the recording clipped to it, info["window"])
        summary["window_start_s"], summary["window_end_s"] = (float(result.info["window"][k])
                                                              for k in ("start_s", "end_s"))
        if not len(result.steps):  # decision L276: a window without a step walked 0 s (not "unknown")
            summary["walking_time_s"] = 0.0
        for line in result.info.get("notes", []):
            typer.echo(f"note: {session.where}: {line}; {summary['time_no_steps_s']:.1f} s without a step, "
                       f"{summary['time_no_data_s']:.1f} s without data", err=True)
    if start is not None:  # decision L298: the clock time of the recording's first sample
        summary["recording_start"] = clock_texts(start, [session.t_recording_start])[0]
    at_times_out = None
    if at_t is not None:  # decision L638: the track's position at the given times
        from pdrlearn.track.at_times import at_times_table
        from pdrlearn.track.floor_column import with_floor_columns

        traj = with_floor_columns(result.trajectory, result, summary.get("storey_height_m"))  # L630, L631: the floor
        at_times_out = at_times_table(traj, at_t, start, result.steps, result, summary.get("storey_height_m"))
    laps = None  # before periods.csv: C178 starts the test's minutes at its go (L642)
    if o.get("corridor_m") is not None:  # decisions L383, L384: the corridor walk test of the track (or its window)
        from pdrlearn.track.corridor import corridor_laps
        from pdrlearn.track.folder import clinical_tables

        span = (summary["window_start_s"], summary["window_end_s"]) if win is not None else None  # L383: the test's
        from pdrlearn.track.corridor import session_go
        from pdrlearn.track.periods import session_span

        laps, keys, lines = corridor_laps(result.steps, clinical_tables(result, bouts)["turns.csv"], o["corridor_m"],
                                          bouts, span=span, duration_s=o.get("walk_test_s"),  # L516
                                          start=session_go(o.get("walk_test_start", "auto"), session),  # L642
                                          data_end=session_span(session, unit)[1])  # L644
        summary.update(keys)
        from pdrlearn.track.own_test import is_walk_test_recording, own_test

        laps, own_lines = own_test(summary, laps)  # decision C249: each recording scored for its own test only
        lines = [*lines, *own_lines]
        if is_walk_test_recording(summary):  # C249: no ten_m_walk_trials.csv from a 6MWT's passes
            result.info["walk_test_recording"] = True
        if summary.get("walk_test_scale") is not None:  # decision W562: the lower back's gait speed, corridor's scale
            from pdrlearn.track.corridor import corridor_gait_speed

            summary["gait_speed_corridor_mps"] = corridor_gait_speed(summary)
        if lines:
            import logging

            for line in lines:
                logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
            summary["info"]["warnings"] = [*summary["info"].get("warnings", []), *lines]
    periods = None
    if o.get("per_s") is not None:  # decision L277: periods.csv, from the whole session's track
        from pdrlearn.track.folder import clinical_tables
        from pdrlearn.track.periods import period_span, period_table

        # decision L381: the window's span (its first step's with first-step), else the recording's
        first_step = o.get("per_align") == "first-step"
        in_window = (summary["window_start_s"], summary["window_end_s"]) if win is not None else None
        go = summary.get("walk_test_start_s") if first_step else None
        try:
            if go is not None:  # the lead's merge of C178 with L642: the test's minutes from its go, not its first step
                # (C178 amended, review R2 finding 5: an explicit --per-align first-step too)
                whole_span = period_span(whole, session, unit, in_window)
                span = (max(whole_span[0], float(go)), whole_span[1])
            else:
                span = period_span(whole, session, unit, in_window, first_step=first_step)
        except DataError:
            if not o.get("per_align_auto"):
                raise
            # decision C178: the walk test's default, without a step to start from: the span's start (as before)
            first_step = False
            span = period_span(whole, session, unit, in_window)
        periods = period_table(whole, session, o["per_s"], unit=unit, bouts=bouts,
                               turns=clinical_tables(whole, bouts)["turns.csv"],
                               storey_height_m=o.get("storey_height_m", 3.0), clock=clock, span=span)
        if summary.get("walk_test_scale") is not None:  # decision W563: the periods on the corridor's scale too
            from pdrlearn.track.periods import with_corridor_scale

            periods = with_corridor_scale(periods, summary["walk_test_scale"])
        summary["per_s"] = float(o["per_s"])
        summary["per_start_s"] = float(span[0])
        if first_step:
            summary["per_align"] = "first-step"
        from pdrlearn.track.periods import constant_bounce_line

        bounce = constant_bounce_line(session.meta, summary.get("info") or {})  # decision S69
        if bounce:
            import logging

            logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, bounce)
            summary["info"]["warnings"] = [*summary["info"].get("warnings", []), bounce]
        if clock is not None:
            summary["per_align"] = "clock"
    segments = None
    if legs is not None:  # decision L619: segments.csv, from the whole session's track (one track for every leg)
        from pdrlearn.track.folder import clinical_tables
        from pdrlearn.track.segments import segment_table

        segments = segment_table(whole, session, legs, unit=unit, bouts=bouts,
                                 turns=clinical_tables(whole, bouts)["turns.csv"],
                                 storey_height_m=o.get("storey_height_m", 3.0))
    splits = None
    if o.get("splits_m"):  # decision L411: times at distance marks from the track's (or window's) first step
        from pdrlearn.track.splits import split_table

        splits, keys, lines = split_table(result.steps, o["splits_m"])
        summary.update(keys)
        if lines:
            import logging

            for line in lines:
                logging.getLogger("pdrlearn.cli").warning("%s: %s", session.where, line)
            summary["info"]["warnings"] = [*summary["info"].get("warnings", []), *lines]
    # L105: the window's session (its reference cut alike) for path.png / aided.png, as for the summary
    return {"session": tracked_session, "result": result, "summary": summary, "pipeline": pipeline, "aided": aided,
            "dpi": dpi, "plot": o["plot"], "content_id": content_id, "bouts": bouts, "periods": periods, "laps": laps,
            "start": start, "splits": splits, "segments": segments, "at_times": at_times_out,
            "start_ele": bool(o.get("start_ele"))}


def _apply_start_heading(result, session, heading0: float, start_ll, turn: bool = False):
    """Decision L98: ``--initial-heading`` sets the start direction of a relative heading (the pipelines took it);
    a track whose heading is absolute (the waist compass's; position fixes by GNSS are refused before tracking, in
    :func:`track_settings`) would ignore it - one error line (B27's rule) instead, naming ``--turn-to-heading``.
    Decision L635: with ``turn``, an absolute track is turned about its start so that its first straight strides
    head the given way (the compass's constant offset taken out); one note line and ``info["start_heading"]``.
    Given and used, it is recorded in ``info`` (``initial_heading_rad``), and path.png draws the track in ENU."""
    from pdrlearn.track.plots import heading_is_absolute

    if heading_is_absolute(result.info, session):
        if not turn:
            raise DataError(f"track: --initial-heading sets the start direction of a relative heading, but this "
                            f"track's heading is absolute ({result.info.get('heading_source')} heading with the "
                            "waist magnetometer of the session); add --turn-to-heading to turn the track to it "
                            "(L635), drop --initial-heading, or track with --streaming (gyroscope heading)")
        from pdrlearn.track.start_pose import turn_to_start_heading

        result = turn_to_start_heading(result, heading0, start=start_ll)
        rec = result.info["start_heading"]
        if rec["turn_deg"] is not None:
            line = (f"--turn-to-heading: the {result.info.get('heading_source')} (compass) track turned by "
                    f"{rec['turn_deg']:+.1f} deg about its start, so that its first {rec['n_strides']} straight "
                    f"strides head {rec['given_deg']:g} deg (they headed {rec['track_deg']:.1f} deg; decision L635)")
            typer.echo(f"note: {session.where}: {line}", err=True)  # asked for: a note, not a warning (--strict)
    elif turn:
        typer.echo(f"note: {session.where}: --turn-to-heading: this track's heading is relative; --initial-heading "
                   "set its start direction, nothing to turn (L635)", err=True)
    result.info["initial_heading_rad"] = heading0
    return result


def write_track(dest: Path, tracked: dict) -> tuple[dict, bool]:
    """Write :func:`track_session`'s track into the existing folder ``dest`` (the caller's temporary folder): the
    library's :func:`pdrlearn.track.folder.write_folder` (decision E169), imported when used (numpy)."""
    from pdrlearn.track.folder import write_folder

    return write_folder(dest, tracked)


def distance_error_phrase(summary: dict) -> str:
    """The summary line's distance error. Decision L419 (session 34, trial T5 finding 6): when labelled strides cover
    part of the walk (gaitmap's mocap volume: 28 of 32 strides), the like-with-like number leads - the matched
    tracked strides against their labelled strides - and the whole-track ``distance_error_pct`` (every tracked
    stride against the labelled strides' sum) follows with the spans it compares; otherwise as before."""
    err = summary.get("distance_error_pct")
    if err is None:
        return ""
    from pdrlearn.track.evaluate import distance_error_text  # decision L743 (numpy: lazily)

    matched, n = summary.get("stride_length_matched"), summary.get("n_steps")
    if summary.get("distance_matched_error_pct") is None or matched is None or n is None or matched >= n:
        return f", distance error {distance_error_text(err, summary.get('distance_ref_m'))}"
    spans = (f" ({summary['distance_matched_m']:.2f} m tracked vs {summary['distance_matched_ref_m']:.2f} m labelled)"
             if summary.get("distance_matched_m") is not None and summary.get("distance_matched_ref_m") is not None
             else "")
    ref = summary.get("distance_ref_m")
    whole = (f"all {n} tracked strides {summary['distance_m']:.2f} m vs the labelled strides' {ref:.2f} m: "
             if ref is not None else f"all {n} tracked strides: ")
    return (f", distance error {summary['distance_matched_error_pct']:+.2f} % over the {matched} strides matched to "
            f"labels{spans}; whole track {distance_error_text(err, ref)} ({whole}strides outside the labelled span "
            "count against it, L419)")


def position_error_phrase(summary: dict) -> str:
    """The one-line summaries' final position error (``track``; ``run`` too since decision E206): ", final position
    error E m horizontal" when the session has a reference, else ""."""
    err = summary.get("final_position_error_m")
    return f", final position error {err:.2f} m horizontal" if err is not None else ""


def _print_summary(summary: dict, out: Path, aided: bool, waist_unit: bool = False, plot: bool = True,
                   tug_from_waist: bool = True) -> None:
    name = summary["session"]
    if summary.get("window_start_s") is not None:  # decision L105
        name += f" [{summary['window_start_s']:g}-{summary['window_end_s']:g} s]"
    err = summary.get("distance_error_pct")
    bouts = err is not None and "bout_distance_m" in summary and "bout_reference_m" in summary
    from pdrlearn.track.evaluate import floors_phrase  # decisions L64, L127 (numpy: lazily)
    from pdrlearn.track.floor_column import rides_altitude_phrase

    typer.echo(f"{name}: {count_phrase(summary)}, {summary['distance_m']:.2f} m"
               # W21: the lower-back error counts the reference bouts only; say so before the number
               + (f"; inside the reference bouts {summary['bout_distance_m']:.2f} m vs "
                  f"{summary['bout_reference_m']:.2f} m" if bouts else "")
               + distance_error_phrase(summary)
               + position_error_phrase(summary)
               # L52: the altitude change, with its reference when the session has one
               + (f", altitude change {summary['altitude_change_m']:+.2f} m" if "altitude_change_m" in summary else "")
               + (f" (reference {summary['altitude_change_ref_m']:+.2f} m)" if "altitude_change_ref_m" in summary
                  else "")
               + rides_altitude_phrase(summary)  # decision L630
               # L64: the storeys climbed and descended, when the track changed floors
               + floors_phrase(summary)
               # decision C16: how much of the walk the model's training data covered
               + (f"; {100 * summary['out_of_domain_fraction']:.0f} % of the strides outside the model's "
                  "training range" if summary.get("out_of_domain_fraction") is not None else ""))
    if summary.get("gait_speed_mps") is not None:  # decisions L79 / W70: the clinical walking speed
        typer.echo(gait_line(summary))
    if aided:  # decision D48: how the GNSS fixes were used, in one line
        from pdrlearn.aid.track import gnss_line

        fused = gnss_line(((summary.get("info") or {}).get("aid") or {}).get("gnss") or {})
        if fused:
            typer.echo(fused)
    from pdrlearn.track.evaluate import belt_line

    belt = belt_line(summary)  # decision L321: a declared treadmill
    if belt:
        typer.echo(belt)
    if summary.get("gait_speed_mps") is not None:
        walk = walk_line(summary)  # decision L104
        if walk:
            typer.echo(walk)
    timed = transfer_line(summary)  # decisions L200, W183; W277: also without walking (a sit-to-stand test)
    if timed:
        typer.echo(timed)
    from pdrlearn.waist.tug_phases import tug_phase_line, tug_trials_line

    phased = tug_phase_line(summary)  # decision W293
    if phased:
        typer.echo(phased)
    if summary.get("n_tug_trials") and (out / "tug_trials.csv").is_file():  # decision W325: several trials
        import pandas as pd

        trials = tug_trials_line(summary, pd.read_csv(out / "tug_trials.csv"))
        if trials:
            typer.echo(trials)
    if summary.get("corridor_m") is not None:  # decision L383: the corridor walk test
        from pdrlearn.track.corridor import corridor_line

        typer.echo(corridor_line(summary))
    from pdrlearn.track.travel import travel_line

    travel = travel_line(summary)  # decisions L412, L484: backward / side strides, changes of travel direction
    if travel:
        typer.echo(travel)
    if summary.get("splits_m"):  # decision L411: the split times
        from pdrlearn.track.splits import splits_line

        typer.echo(splits_line(summary))
    flights = flights_line(summary)  # decision L432: the stair flights
    if flights:
        typer.echo(flights)
    ramps = written_ramps_line(summary, out)  # decision L571: the ramps, beside the stair flights
    if ramps:
        typer.echo(ramps)
    if summary.get("time_span_s") is not None:  # decision L275: where the time went, summing to the span
        typer.echo(f"time {summary['time_span_s']:.1f} s: walking {summary['time_walking_s']:.1f} s, between steps "
                   f"{summary['time_between_steps_s']:.1f} s, no steps {summary['time_no_steps_s']:.1f} s, no data "
                   f"{summary['time_no_data_s']:.1f} s")
        # decisions W222, L316: the time that is not walking, by posture
        typer.echo(posture_line(summary, waist_unit and summary.get("pipeline") == "plasys", tug_from_waist))
    from pdrlearn.track.geoexport import GEO_FILES

    typer.echo(f"wrote {out}/trajectory.csv, steps.csv, bouts.csv, turns.csv, ramps.csv, ramp_runs.csv, "
               # decision L440: no stairs.csv on the lower back
               f"{'stairs.csv, ' if (out / 'stairs.csv').is_file() else ''}"
               f"{'curbs.csv, ' if (out / 'curbs.csv').is_file() else ''}"  # decision L573
               f"{'transfers.csv, ' if summary.get('n_sit_to_stand') is not None else ''}"
               f"{'tug_phases.csv, ' if summary.get('tug_phases') else ''}"
               f"{'tug_trials.csv, ' if summary.get('n_tug_trials') else ''}"
               f"{'ten_m_walk_trials.csv, ' if summary.get('n_ten_m_walk_trials') else ''}"  # decision L524
               f"{'freezes.csv, ' if summary.get('n_freezes') is not None else ''}"
               f"{'flights.csv, ' if (out / 'flights.csv').is_file() else ''}"
               f"{'rides.csv, ' if summary.get('n_rides') is not None else ''}"
               f"{'wb_scores.csv, ' if summary.get('n_wb_reference') is not None else ''}"  # decision W493
               f"{'laps.csv, ' if summary.get('corridor_m') is not None else ''}"
               f"{'splits.csv, ' if summary.get('splits_m') else ''}"
               f"{'direction_changes.csv, ' if summary.get('direction_changes') is not None else ''}"
               f"{'periods.csv, ' if summary.get('per_s') else ''}"
               f"{'segments.csv, ' if (out / 'segments.csv').is_file() else ''}"  # decision L619
               f"{'at_times.csv, ' if (out / 'at_times.csv').is_file() else ''}"  # decision L638
               f"{'path.png, ' if plot else ''}"  # decision L533: no figure with --no-plot
               f"{'aided.png, ' if aided and plot else ''}summary.json, run.json"
               # decision L363: the map files, written when the track has lat/lon (--start)
               + "".join(f", {n}" for n in GEO_FILES if (out / n).is_file()))




#: Options only the plasys pipeline reads (decision B27); the waist pipelines have no step classifier
_PLASYS_OPTIONS = ("--method", "--model", "--rules", "--min-confidence", "--length-bounds", "--length-reference",
                   "--streaming",
                   "--toe-off", "--ignore-force", "--contacts", "--drop-neighbour", "--no-cycling", "--detector",
                   "--altitude",
                   "--align-units", "--compass",
                   "--clock-offset", "--clock-drift-ppm")
#: Options only plasys M3 reads: the step classes and their rules (M1/M2 move every stride the same way)
_M3_OPTIONS = ("--model", "--rules", "--min-confidence", "--length-bounds", "--length-reference")


def _plasys_options_given(o: dict, method: str, model, streaming: bool, toe_off: bool, contacts) -> dict[str, bool]:
    """Each option of :data:`_PLASYS_OPTIONS` and whether ``track``'s settings ``o`` give it (decisions B27, W478)."""
    return {"--method": method.lower() != "auto", "--model": model is not None, "--rules": o["rules"] is not None,
            "--min-confidence": o["min_confidence"] is not None, "--length-bounds": o["length_bounds_given"],
            "--length-reference": o.get("length_reference", "model") != "model", "--streaming": streaming,
            "--toe-off": toe_off, "--ignore-force": bool(o.get("ignore_force")), "--contacts": contacts,
            "--drop-neighbour": bool(o.get("drop_neighbour")), "--no-cycling": bool(o.get("no_cycling")),
            "--detector": o.get("detector_unit") == "foot",
            "--altitude": o.get("altitude") is not None, "--align-units": bool(o.get("align_units")),
            "--compass": o.get("compass", "auto") != "auto", "--clock-offset": o.get("clock_offset_s") is not None,
            "--clock-drift-ppm": o.get("clock_drift") is not None}


def _refuse_foot_options_with_waist_params(params: Path, given: dict[str, bool], detector: str | None) -> None:
    """Decision W478: under --pipeline auto, a lower-back ``--params`` file and an option only the foot pipeline
    takes ask for both units: one line naming both (W474 would choose the lower back, and the foot option would then
    be refused with advice that refuses the file)."""
    asked = [f"--detector {detector}" if o == "--detector" else o for o in _PLASYS_OPTIONS if given.get(o)]
    if asked:
        raise DataError(f"track: --params {params} is a lower-back parameters file (`pdrlearn calibrate`), but "
                        f"{', '.join(asked)} appl{'ies' if len(asked) == 1 else 'y'} to the plasys foot pipeline "
                        "only; drop the option to track the lower back with the file, or drop --params to track "
                        "the foot (decision W478)")


def _refuse_ignored_options(pipeline: str, method: str, given: dict[str, bool], *, gnss, gnss_period, fixes,
                            fix_period, chosen_by: str | None = None) -> None:
    """One error line for an option the chosen pipeline (or PLASYS method, or missing companion option)
    would ignore (decision B27): `track --pipeline waist-pendulum --method M3 --model X` tracked without
    the model and exited 0. ``chosen_by``: the option that chose the pipeline when no --pipeline was given
    (decision B191)."""
    asked = [o for o in _PLASYS_OPTIONS if given.get(o)]
    if pipeline != "plasys" and asked:
        one = len(asked) == 1
        it = "it" if one else "them"
        got = f"got --pipeline {pipeline}" if chosen_by is None else f"{chosen_by} chose --pipeline {pipeline}"
        raise DataError(f"{', '.join(asked)} appl{'ies' if one else 'y'} to the plasys pipeline only ({got}, "
                        f"a lower-back pipeline without step classes, which ignores {it}); drop {it}, "
                        "or track the foot unit with --pipeline plasys")
    m = method.upper()
    asked = [o for o in _M3_OPTIONS if given.get(o)]
    if m in ("M1", "M2") and asked:
        one = len(asked) == 1
        raise DataError(f"track: {', '.join(asked)}: M3 step-class option{'' if one else 's'}, which --method {m} "
                        "ignores (it uses no step classes); use --method M3 (or leave --method out), or drop "
                        f"{'it' if one else 'them'}")
    for period, name, source, src_name in ((gnss_period, "--gnss-period", gnss, "--gnss"),
                                           (fix_period, "--fix-period", fixes, "--fixes")):
        if period is not None and source is None:
            raise DataError(f"track: {name} {period:g} thins the fixes of {src_name} FILE, which is not given; "
                            f"pass {src_name} FILE or drop {name}")


def _reference_point(point: str, par, params: Path | None, pipeline: str, streaming: bool) -> dict:
    """``--reference-point`` (decision L72) as the ``reference_point`` setting of ``--params``: the plasys
    offline pipeline only (the streaming kernel and the runtime track the sensor); one that contradicts the
    --params file is an error (which one was meant?)."""
    from pdrlearn.displace.foot import REFERENCE_POINTS

    if point not in REFERENCE_POINTS:
        raise DataError(f"--reference-point {point}: not one of {', '.join(REFERENCE_POINTS)}")
    if pipeline != "plasys":
        raise DataError(f"--reference-point applies to the plasys (foot) pipeline only (got --pipeline {pipeline}, "
                        "whose lower-back step length has no reference point); drop it, or track the foot unit "
                        "with --pipeline plasys")
    if streaming:
        raise DataError("track: --reference-point: the --streaming kernel (and `pdrlearn run`) track the sensor "
                        "point only; drop --streaming to track the heel, or drop --reference-point")
    par = {} if par is None else par
    if not isinstance(par, dict):
        raise DataError(f"{params}: the parameters JSON is not an object; pass a file such as "
                        "{\"reference_point\": \"heel\"}")
    if par.get("reference_point", point) != point:
        raise DataError(f"track: --reference-point {point} contradicts \"reference_point\": "
                        f"\"{par['reference_point']}\" in {params}; give one of them")
    return {**par, "reference_point": point}


#: decision W422: ``--params`` keys of the plasys pipeline that are ``track_plasys`` options, not FootDisplacement
#: settings (W126's waist-gyroscope rest-bias removal: the API had it, the CLI refused the key, trial T2 finding 5)
#: decision L565: ``fused_climb`` (L564's one height source inside a barometric climb, an option), offline and streamed
#: decision L636: ``hard_iron_fit`` (L84's fit of the waist compass's hard-iron offset on the walk, an option that is
#: not the default), offline only
#: decision L717: ``foot_ramps`` (ramps.csv from a foot track's own L39 heights, an option: its rule failed)
#: decision L770: ``compass_sinusoid`` (the waist compass's direction sinusoid off before the fused window), offline
#: decision L796: ``forward_yaw`` (the waist compass turned by D10's measured mount yaw; on by default), offline
#: decision L801: ``forward_yaw_gate`` (not when W435's power ratio or W434's force_frame distrusts it; on by default
#: since L803), offline
TRACK_PARAM_KEYS = ("waist_bias", "fused_climb", "hard_iron_fit", "foot_ramps", "compass_sinusoid", "forward_yaw",
                    "forward_yaw_gate")
#: decision L615: the lower-back PARAMS ``options`` (``{"options": {...}}``) the plasys pipeline reads as well
PLASYS_OPTION_KEYS = ("ride_vibration",)


def _run_pipeline(fn, session, kw: dict, gait_quality: bool):
    """(the pipeline ``fn``'s result on ``session``, the waist AHRS states W353's gait quality keeps, or None)."""
    if not gait_quality:
        return fn(session, **kw), None
    from pdrlearn.waist.ahrs import kept_imus

    with kept_imus() as imus:
        return fn(session, **kw), imus


def _track_params(par: dict, path: Path, streaming: bool) -> tuple[dict, dict]:
    """Decision W422: ``par`` split into the FootDisplacement settings and the :data:`TRACK_PARAM_KEYS` (JSON true /
    false), or one line naming the file: a non-boolean value, or ``waist_bias`` with ``--streaming`` (the streamed
    heading has no W126 removal: it removes the bias read at each stop, causally, decision E272)."""
    keys = {k: par[k] for k in TRACK_PARAM_KEYS if k in par}
    for k, v in keys.items():
        if not isinstance(v, bool):
            raise DataError(f"{path}: \"{k}\" must be true or false (JSON, no quotes), not {v!r:.40}; fix the key")
    if "waist_bias" in keys and streaming:
        raise DataError(f"{path}: \"waist_bias\" removes the waist gyroscope bias from the offline two-unit heading "
                        "(decisions W126, W422); the --streaming kernel removes instead, always, the bias read at "
                        "each stop of 10 s or more (decision E272): drop --streaming or the key")
    for key, codes in (("hard_iron_fit", "L84, L636"), ("compass_sinusoid", "L770"), ("forward_yaw", "L796"),
                       ("forward_yaw_gate", "L801")):
        if key in keys and streaming:  # decisions L636, L770
            raise DataError(f"{path}: \"{key}\" fits the waist compass of the offline fused heading (decisions "
                            f"{codes}); the --streaming kernel heads by the gyroscopes and reads no compass: drop "
                            "--streaming or the key")
    keys.update(_plasys_options(par.get("options"), path, streaming) if "options" in par else {})
    return {k: v for k, v in par.items() if k not in TRACK_PARAM_KEYS and k != "options"}, keys


def _plasys_options(opts, path: Path, streaming: bool) -> dict:
    """Decision L615: ``--params``' ``"options"`` for the plasys pipeline: :data:`PLASYS_OPTION_KEYS` (JSON true /
    false) as ``track_plasys`` keywords, or one line naming the file: not an object, a lower-back-only option, a
    non-boolean value, or the option with ``--streaming`` (the streamed track reads no rides)."""
    if not isinstance(opts, dict):
        raise DataError(f"{path}: \"options\" must be a JSON object such as {{\"ride_vibration\": true}}, not "
                        f"{opts!r:.40}; fix the key")
    other = sorted(set(opts) - set(PLASYS_OPTION_KEYS), key=str)
    if other:
        raise DataError(f"{path}: option(s) {', '.join(map(str, other))} are lower-back options (--pipeline "
                        f"waist-pendulum or waist-pll); the plasys pipeline reads only "
                        f"{', '.join(PLASYS_OPTION_KEYS)} there (decision L615): drop them or track the lower back")
    for k, v in opts.items():
        if not isinstance(v, bool):
            raise DataError(f"{path}: \"options\": \"{k}\" must be true or false (JSON, no quotes), not {v!r:.40}; "
                            "fix the key")
    if streaming:
        raise DataError(f"{path}: \"options\": \"ride_vibration\" tells the offline foot track's rides (decision "
                        "L615); the --streaming kernel reads no rides: drop --streaming or the option")
    return dict(opts)


def _refuse_waist_params(par: dict, path: Path, session) -> None:
    """A lower-back parameters file given to the foot pipeline: say what it is and where it belongs (the
    plasys pipeline would list its keys as unknown FootDisplacement settings)."""
    from pdrlearn.track.base import waist_params_file

    is_waist, for_ = waist_params_file(par)
    if not is_waist:
        return
    use = f"--pipeline {for_}" if for_ else "--pipeline waist-pendulum or waist-pll"
    unit = "" if session.has("wAccelerometer") else f" (session '{session.name}' has no waist unit)"
    raise DataError(f"{path}: a {for_ or 'waist-pendulum/waist-pll'} parameters file (lower-back step length, "
                    f"`pdrlearn calibrate`), not settings of the plasys foot pipeline; use it with {use} on a "
                    f"session with a waist unit{unit}, or track the foot without --params")


def register(app: typer.Typer) -> None:
    app.command("track")(track)
