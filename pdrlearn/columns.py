"""Cohort decision C35: the data dictionary of track-all's tables - every column of sessions.csv, groups.csv,
subjects.csv, each session's bouts.csv and a lower-back session's steps.csv (W129) and a foot session's (E137), and
`pdrlearn gait`'s gait_steps.csv / gait_cycles.csv / gait_bouts.csv (L287), with its unit, type and meaning.
The one source of ``pdrlearn columns``
and docs/columns.md (written from it: ``pdrlearn columns > docs/columns.md``); a test tracks a batch and checks that
every column written is here. Meanings follow docs/localization.md's table of summary.json keys (decisions L103, L104).
"""

from __future__ import annotations

from pdrlearn.classify.cv_report import CLASS_COLUMN, CV_COLUMNS, LOUO_COLUMNS
from pdrlearn.cohort import GROUP_METRICS
from pdrlearn.repeated import POOLED_MEASURES, pooled_kinds
from pdrlearn.table_names import TABLE_NAMES
from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG
from pdrlearn.track.clock import CLOCK_COLUMNS

#: (column, unit, type, meaning); ``{measure}`` in a name stands for each of :data:`GROUP_METRICS`
Column = tuple[str, str, str, str]

_ID = "-"
#: decision L298: when the clock columns are written
_WITH_START = ("only when the session gives its recording start (meta.json recording_start, a date-time "
               "`pdrlearn import`, a Mobilise-D start; L298)")


def _clock(of: str) -> Column:
    """Decision L298: the clock column of instant column ``of`` (start_s -> start_time, ...)."""
    return (CLOCK_COLUMNS[of], "date-time", "text", f"{of} as a clock time: ISO 8601 with milliseconds at the "
            f"recording start's own offset (never the machine's zone); {_WITH_START}")


def _clocks(*of: str) -> tuple[Column, ...]:
    return tuple(_clock(c) for c in of)


def _ends(start: str, end: str) -> tuple[Column, ...]:
    """Decisions L570, L585: the x / y and lat / lon columns of an event's two ends (trajectory.csv at its times;
    the start at the row at or before it, where the walker stood until the first stride ended)."""
    return tuple((f"{e}_{c}", u, "number", f"{w}: trajectory.csv's {c.removesuffix('_m')} {at}"
                  + ("" if c.endswith("_m") else "; empty without a geodetic start (--start LAT,LON)"))
                 for e, w, at in (("start", start, "at the row at or before that time (where the walker stood; "
                                                   "L570, L585)"),
                                  ("end", end, "at that time (L570)"))
                 for c, u in (("x_m", "m"), ("y_m", "m"), ("lat", "deg"), ("lon", "deg")))


SESSIONS: tuple[Column, ...] = (
    ("path", _ID, "text", "the session folder relative to ROOT (the row's key)"),
    ("group", _ID, "text", "the first --group-depth folder levels of path (siteA)"),
    ("subject", _ID, "text", "meta.json subject (or user, when a name; a whole number as its text, C99); empty "
                             "when not given (C22; also a track's summary.json, C100)"),
    ("visit", _ID, "text", "the visit as changes.csv and subjects.csv name it (C82): meta.json visit, --visit-map "
                           "applied and spellings of one visit made one (C28, C29); empty when not given (C22)"),
    ("visit_as_written", _ID, "text", "meta.json visit as written (C82)"),
    ("test", _ID, "text", "meta.json test (mobgap's Test5, Test11): the column only when a session names one, "
                          "then after visit_as_written; empty for a session that names none (C170)"),
    ("trial", _ID, "text", "meta.json trial (mobgap's Trial1, Trial2), as test (C170)"),
    ("status", _ID, "text", "ok (tracked), failed, or skipped (a split part with no stride, all at rest: B389)"),
    ("error", _ID, "text", "a failed session's one-line error (a skipped one's with B389's note); empty when ok"),
    ("session", _ID, "text", "meta.json's session name"),
    ("input_dir", _ID, "text", "the folder tracked, relative to ROOT (= path, C18)"),
    ("pipeline", _ID, "text", "the pipeline used: plasys (foot) or waist-pendulum / waist-pll (lower back)"),
    ("method", _ID, "text", "the pipeline's method (M1, M2, M3 on the foot; lower back detector/step-length "
                            "model/heading, the model with the settings the user set, e.g. alvarez-offline/"
                            "weinberg:k=0.6/gyro, W462)"),
    ("rate_hz", "Hz", "number", "the tracked unit's accelerometer rate"),
    ("n_steps", "count", "integer", "rows of steps.csv: strides of the tracked foot (foot) or steps (lower back)"),
    ("n_steps_counts", _ID, "text", "what n_steps counts: 'strides of the tracked foot' or 'steps of both feet'"),
    ("n_strides_one_foot", "count", "integer", "foot: the tracked foot's strides (gap rows left out); empty on the "
                                               "lower back"),
    ("n_steps_both_feet", "count", "integer", "lower back: detected steps; foot: 2 x n_strides_one_foot (estimate)"),
    ("distance_m", "m", "number", "tracked distance"),
    ("distance_ref_m", "m", "number", "reference distance (meta.json or labels); empty without one"),
    ("distance_error_pct", "%", "number", "100 x (distance_compared_m - distance_ref_m) / distance_ref_m; "
                                          "distance_compared_m is distance_m when distance_error_scope is 'whole "
                                          "track', distance_in_ref_bouts_m when it is 'reference bouts' (W71, W459): "
                                          "a gain fitted by hand is distance_ref_m / distance_compared_m"),
    ("final_position_error_m", "m", "number", "horizontal distance of the last tracked position from the true one"),
    ("loop_closure_m", "m", "number", "horizontal distance of the last tracked position from the first (L771): "
                                      "the closure error of a walk that returns to its start, no truth needed"),
    ("loop_closure_pct", "%", "number", "100 x loop_closure_m / distance_m (L771); meaningful only when the walk "
                                        "returns to its start"),
    ("walking_time_s", "s", "number", "time walking (stops over 3 s and data gaps left out, L79); with --window "
                                      "the window's strides' (0 when it holds none, L276)"),
    ("gait_speed_mps", "m/s", "number", "distance_m / walking_time_s: rest to rest, with gait initiation and "
                                       "termination and ~0.3 s of standing (L250); on a walkway (first to last "
                                       "IC) read median_speed_straight_mps"),
    ("median_cadence_spm", "steps/min", "number", "median steps per minute: 120 / the median stride time (a stride "
                                                  "holds a step of each foot, so alternating short / long steps "
                                                  "do not bias it; lower back since W225)"),
    ("median_stride_length_m", "m", "number", "foot: median stride length (gap rows and impossible strides left "
                                              "out); lower back: median of two consecutive steps' lengths summed, "
                                              "bouts.csv's strides (W537)"),
    ("median_stride_time_s", "s", "number", "median initial contact to the same foot's next"),
    ("median_speed_mps", "m/s", "number", "median per-stride speed (lower back: two consecutive steps over their "
                                         "stride time, W225)"),
    ("n_warnings", "count", "integer", "warnings the session raised"),
    ("warnings", _ID, "text", "those warnings, separated by ' | '"),
    ("content_id", _ID, "text", "fingerprint of the sensor data (B87): equal for copies of one recording"),
    ("duplicate_of", _ID, "text", "the first folder holding the same sensor data and meta.json settings (C20)"),
    ("same_sensor_data_as", _ID, "text", "the first folder holding the same sensor data with other meta.json "
                                         "settings: not a duplicate (L137)"),
    ("params_file", _ID, "text", "--params-dir only: the calibration file used (C26)"),
    ("altitude_change_m", "m", "number", "tracked z change, last minus first"),
    ("altitude_change_rides_m", "m", "number", "altitude_change_m with the rides a foot track's z leaves out "
                                               "(rides.csv dz_m of 1.5 m or more: a lift, an escalator; L630): "
                                               "trajectory.csv z_rides' change; final_altitude_error_m compares "
                                               "it; = altitude_change_m on the lower back (barometric z)"),
    ("altitude_change_ref_m", "m", "number", "reference z change"),
    ("altitude_ref_source", _ID, "text", "where altitude_change_ref_m comes from"),
    ("altitude_error_pct", "%", "number", "altitude change error against the reference"),
    ("barometer_unused", _ID, "true/false", "the session has wBarometer.csv that a foot track's altitude does not read "
     "(L127; false with --altitude fused, L154); its rides are read (L378)"),
    ("barometer_altitude_change_m", "m", "number", "foot tracks with wBarometer.csv: the barometer's altitude change "
                                                   "over the track (L145)"),
    ("barometer_disagree_limit_m", "m", "number", "how far altitude_change_m may differ from it before a warning "
                                                  "(L145)"),
    ("barometer_climb_change_m", "m", "number", "foot tracks with wBarometer.csv: the barometer's climbs, its change "
                                                "without slow drift, which L145's warning compares (L172)"),
    ("barometer_ascent_m", "m", "number", "foot tracks with wBarometer.csv: the barometer's ascent (0.5 m crossed "
                                          "within 60 s, L172), compared with ascent_m (L180)"),
    ("barometer_descent_m", "m", "number", "foot tracks with wBarometer.csv: the barometer's descent, compared with "
                                           "descent_m (L180)"),
    ("barometer_drift_m", "m", "number", "foot tracks with wBarometer.csv: the barometer's slow drift (the weather) "
                                         "over the track, recorded minus climbs (L172)"),
    ("ascent_m", "m", "number", "cumulative climb (foot: strides' dz; barometric z - lower back, --altitude fused: "
                                "0.5 m crossed within 60 s, the weather's drift dropped; L146, L172); empty on a "
                                "lower-back track without a barometer (no altitude, L575)"),
    ("descent_m", "m", "number", "cumulative descent, >= 0 (ascent_m - descent_m = altitude_change_m; barometric z: "
                                 "minus altitude_drift_m; L146, L172); empty as ascent_m (L575)"),
    ("altitude_drift_m", "m", "number", "barometric z (lower back, --altitude fused): the slow change that "
                                        "ascent_m / descent_m and the floors leave out (L172); not the weather's "
                                        "drift during climbs, which they include (weather_drift_m, L464)"),
    ("altitude_drift_limit_m", "m", "number", "the most the fastest weather (2 hPa/h) changes the barometric z in "
                                              "the track's span; a larger altitude_drift_m is warned about (W371)"),
    ("ramps_stairs_ascent_m", "m", "number", "barometric z (lower back, --altitude fused): the summed rise of "
                                             "ramps.csv rise_m and stairs.csv height_m up; an ascent_m more than "
                                             "0.13 m below it is warned about (L566)"),
    ("ramps_stairs_descent_m", "m", "number", "barometric z: the summed drop of ramps.csv and stairs.csv down, >= 0; "
                                              "a descent_m more than 0.13 m below it is warned about (L566)"),
    ("weather_drift_rate_m_per_h", "m/h", "number", "foot tracks with wBarometer.csv: the barometric altitude's "
                                                    "slope over standstills of 60 s or more (the weather; L464)"),
    ("weather_drift_standstill_s", "s", "number", "the standstill seconds weather_drift_rate_m_per_h was read on "
                                                  "(L464)"),
    ("weather_drift_m", "m", "number", "weather_drift_rate_m_per_h over the strides' span: what the weather added to "
                                       "the barometer's net change and climbs; over 1 m warned with --altitude "
                                       "fused (L464)"),
    ("bouts_distance_m", "m", "number", "bouts.csv's distance summed (C25)"),
    ("bouts_time_s", "s", "number", "bouts.csv's durations summed (C25)"),
    ("bouts_n_steps", "count", "integer", "bouts.csv's steps summed (C25)"),
    ("bouts_n_strides", "count", "integer", "bouts.csv's strides summed (C25)"),
    ("bouts_contact_span_s", "s", "number", "bouts.csv's contact_span_s summed (L164)"),
    ("bouts_n_step_intervals", "count", "integer", "bouts.csv's n_step_intervals summed (L164)"),
    ("bout_distance_m", "m", "number", "lower back: tracked distance inside the reference walking bouts"),
    ("bout_reference_m", "m", "number", "lower back: reference distance of those bouts"),
    ("bout_distance_error_median_pct", "%", "number", "lower back: median of |per-bout distance error|, unsigned "
                                                      "(L251; the bias: bout_distance_error_median_signed_pct)"),
    ("bout_distance_error_median_signed_pct", "%", "number", "lower back: median of the signed per-bout errors, "
                                                             "100 x (tracked - reference) / reference (L251)"),
    ("bout_reference_strides_m", "m", "number", "lower back: reference stride lengths summed over the bouts"),
    # decision W493: WB detection and per-WB DMOs against the reference WBs (wb_scores.csv; mobgap's matching)
    ("wb_overlap_threshold", "fraction", "number", "W493: the overlap (of both the WB's and the bout's duration) a "
                                                   "detected bout needs to match a reference WB (mobgap's "
                                                   "categorize_intervals, 0.8); empty without reference WBs"),
    ("n_wb_reference", "count", "integer", "W493: reference walking bouts (bouts.csv level wb) = n_wb_tp + n_wb_fn"),
    ("n_wb_tp", "count", "integer", "W493: reference WBs matched by a detected bout (bouts.csv, under the track's "
                                    "bout rule)"),
    ("n_wb_fp", "count", "integer", "W493: detected bouts matched to no reference WB"),
    ("n_wb_fn", "count", "integer", "W493: reference WBs matched by no detected bout"),
    ("wb_precision", "fraction", "number", "W493: n_wb_tp / (n_wb_tp + n_wb_fp); empty without a detected bout"),
    ("wb_recall", "fraction", "number", "W493: n_wb_tp / n_wb_reference"),
    ("wb_f1", "fraction", "number", "W493: harmonic mean of wb_precision and wb_recall"),
    *((f"wb_{name}_error_median{sign}_pct", "%", "number",
       f"W493: median over the matched WBs of the {'signed' if sign else 'absolute'} relative {what} error, 100 x "
       f"(bout - reference) / reference ({'a bias' if sign else 'unsigned'}; wb_scores.csv's {name}_error_pct, "
       "mobgap's rel_error); empty without a matched WB")
      for name, what in (("cadence", "cadence"), ("stride_length", "stride length"), ("speed", "walking speed"))
      for sign in ("", "_signed")),
    ("bout_distance_error_strides_median_pct", "%", "number", "lower back: median of |per-bout error| against "
                                                              "the summed reference strides (unsigned, L251)"),
    ("class_agreement_strides", "count", "integer", "tracked strides matched to a labelled one (L53)"),
    ("contact_timing", _ID, "text", "contacts on 'whole samples' or 'between samples' (L116)"),
    ("direction_agreement", "fraction", "number", "matched strides whose direction class is the label's (L53)"),
    ("distance_compared_m", "m", "number", "the tracked distance distance_error_pct compares with distance_ref_m: "
                                           "distance_m or, in scope 'reference bouts', distance_in_ref_bouts_m "
                                           "(W459)"),
    ("distance_error_scope", _ID, "text", "what distance_error_pct compares (W71, L82): 'whole track' "
                                          "(distance_m) or 'reference bouts' (distance_in_ref_bouts_m)"),
    ("distance_error_strides_pct", "%", "number", "distance error against the summed reference strides"),
    ("distance_in_ref_bouts_m", "m", "number", "tracked distance inside the reference bouts (L82)"),
    ("distance_matched_error_pct", "%", "number", "foot: distance error over the strides matched to labels"),
    ("distance_matched_m", "m", "number", "foot: summed length of the tracked strides matched to labels (L419)"),
    ("distance_matched_ref_m", "m", "number", "foot: summed length of the labelled strides they match (L419)"),
    ("distance_ref_source", _ID, "text", "where distance_ref_m comes from"),
    ("reference_travel_m", "m", "number", "set when trajectory.csv stays put while the track walks (a treadmill "
                                          "in the lab frame): its largest distance from its start (L319)"),
    ("final_altitude_error_m", "m", "number", "z error of the last position"),
    ("final_position_error_3d_m", "m", "number", "3-D distance of the last position from the true one"),
    ("final_position_sigma_m", "m", "number", "modelled 1-sigma radius of the last position (L128; none with fixes)"),
    ("max_position_sigma_m", "m", "number", "largest modelled 1-sigma position radius of the track (L128)"),
    ("final_x_m", "m", "number", "last tracked position, x (east, or the start heading's axis)"),
    ("final_y_m", "m", "number", "last tracked position, y"),
    ("final_z_m", "m", "number", "last tracked position, z (up)"),
    ("floors_down", "count", "integer", "storeys descended (3.0 m or --storey-height; L127)"),
    ("floors_down_ref", "count", "integer", "storeys descended in the reference; empty without a reference "
                                            "altitude track (C103)"),
    ("floors_up", "count", "integer", "storeys climbed"),
    ("floors_up_stairs", "count", "integer", "floors_up's storeys of climbs on stairs (L302: rise over run 20 % or "
                                             "more, walked; a foot track's with --stair-grade PCT, e.g. 30 on "
                                             "trails, L469); floors_up = stairs + ramps + rides"),
    ("floors_up_ramps", "count", "integer", "floors_up's storeys of climbs walked under 20 % or --stair-grade (a "
                                            "ramp or a hill; L302); on a barometric or fused altitude a ramp's "
                                            "whole rise (L337)"),
    ("floors_up_rides", "count", "integer", "floors_up's storeys ridden: lift and escalator rides (a standstill change "
                                            "of 1.5 m or more, W158's pause_dz_m, each a climb of its own: L375; a "
                                            "ride of kind other counts none: L376); L302"),
    ("floors_down_stairs", "count", "integer", "floors_down's storeys on stairs (L302)"),
    ("floors_down_ramps", "count", "integer", "floors_down's storeys walked under 20 % or --stair-grade (L302, L469)"),
    ("floors_down_rides", "count", "integer", "floors_down's storeys ridden (L302)"),
    ("grade_source", _ID, "text", "where grade_pct and the ramps come from: fused (foot, --altitude fused) or "
                                  "barometer (lower back); empty: a foot track's own altitude, which L39 levels "
                                  "(L300)"),
    ("distance_along_slope_m", "m", "number", "distance along the walked surface, sum of sqrt(length^2 + dz^2); "
                                              "empty without a grade_source (L300)"),
    ("n_ramps", "count", "integer", "rows of ramps.csv (L301); empty without a ramp_source"),
    ("ramp_source", _ID, "text", "where ramps.csv's ramps come from: grade_source's, or foot (the option foot_ramps: "
                                 "a foot track's own heights, L39's strides of 0.10 m or more, no terrain classes, "
                                 "L717); empty: none"),
    ("ramps_rise_m", "m", "number", "what ramps.csv's ramps up climb, their rise_m summed (L717); empty without a "
                                    "ramp_source"),
    ("ramps_drop_m", "m", "number", "what ramps.csv's ramps down descend, their -rise_m summed, positive (L717); "
                                    "empty without a ramp_source"),
    ("max_ramp_grade_pct", "%", "number", "the steepest ramp run's grade in size, ramps.csv's largest "
                                          "|max_run_grade_pct| (L572); empty without a ramp or a ramp_source"),
    ("n_rides", "count", "integer", "rows of rides.csv: rides while standing, lift / escalator / vehicle / other "
                                    "(L377, L616; a foot track's from the waist barometer, L378, or without one its "
                                    "vehicle rides from the foot's vibration, L624); empty without a barometer on the "
                                    "lower back, or with the foot's ride_vibration off and no barometer"),
    ("floors_up_ref", "count", "integer", "storeys climbed in the reference; empty when the reference has no "
                                          "altitude track (0: it has one, and no storey was climbed; C103)"),
    ("frames_inferred", _ID, "text", "units whose frame was inferred from the data (D8)"),
    ("frame_foot", _ID, "text", "how the foot unit's axis frame was had (C142): declared (meta.json or "
                                "source_project, not contradicted), inferred (from the data, D8), contradicted "
                                "(declared, used with D10's warning naming the frame the data give), forced "
                                "(declared, rejected by the data, kept by \"force_frame\", D23); empty when the "
                                "track did not use the unit"),
    ("frame_waist", _ID, "text", "the lower-back unit's, as frame_foot (C142)"),
    ("ic_timing_mean_ms", "ms", "number", "lower back: mean initial-contact time error against the reference"),
    ("ic_timing_sd_ms", "ms", "number", "lower back: SD of that error"),
    ("ic_timing_stereo_mean_ms", "ms", "number", "lower back: mean contact time error, both feet matched"),
    ("ic_timing_stereo_sd_ms", "ms", "number", "lower back: SD of that error"),
    ("gait_out_of_range", _ID, "true/false", "L95's walking-range warning fired: the session's median cadence or "
                                             "speed outside the (leg-scaled) range, above OR below it, or a bout of "
                                             "5+ strides above it (L195); empty when nothing could be judged (no "
                                             "cadence, no judged speed: L222). Slow walking is judged here only: "
                                             "bouts.csv's gait_out_of_range is the fast side alone (L248)"),
    ("leg_length_m", "m", "number", "the walker's leg length from meta.json, by which L95's range is scaled (L148)"),
    ("leg_length_source", _ID, "text", "the meta.json key leg_length_m came from (L148)"),
    ("length_class_agreement", "fraction", "number", "matched strides whose length class is the label's (L53)"),
    ("longest_pause_s", "s", "number", "the longest pause (L104)"),
    ("belt_speed_mps", "m/s", "number", "a declared treadmill's belt speed (meta.json belt_speed_mps; L321)"),
    ("belt_speed_error_pct", "%", "number", "100 x (median_speed_belt_mps - belt_speed_mps) / belt_speed_mps "
                                            "(L321); empty under 5 belt strides (L441)"),
    ("stride_time_cv_direction", _ID, "text", "forward, or backward when the CVs are a backward walk's (fewer than "
                                              "10 steady forward strides, L444); empty without CV strides"),
    ("belt_incline_pct", "%", "number", "a declared treadmill's incline (meta.json belt_incline_pct; L442)"),
    ("floors_note", _ID, "text", "why the floors are 0: a declared inclined treadmill belt climbs no storeys (L442)"),
    ("n_belt_strides", "count", "integer", "a declared treadmill: the steady straight strides at the belt's grade, "
                                           "level or inclined, that the belt check reads (L441)"),
    ("median_speed_belt_mps", "m/s", "number", "median speed along the belt of the n_belt_strides (L441)"),
    ("belt_check_note", _ID, "text", "why there is no belt_speed_error_pct on a declared treadmill (L441)"),
    ("median_speed_straight_mps", "m/s", "number", "median speed of the level strides turning under 15 deg "
                                              "(stair strides left out, L179; side steps, L228, and backward "
                                              "strides, L580)"),
    ("median_stance_pct", "%", "number", "--toe-off only: median stance share of the stride (L73)"),
    ("median_stance_time_s", "s", "number", "--toe-off only: median stance time"),
    ("median_step_time_s", "s", "number", "lower back: median contact to the next of either foot; empty on a foot "
                                          "track"),
    ("median_swing_time_s", "s", "number", "--toe-off only: median swing time"),
    ("n_bouts", "count", "integer", "rows of bouts.csv under the bout rule (L124): THE bout count to report "
                                    "(L217)"),
    ("n_bouts_out_of_range", "count", "integer", "bouts of bouts.csv whose gait_out_of_range is true: bouts ABOVE "
                                                 "the walking range (L195); 0 on a slow session (L248)"),
    ("n_backward_strides", "count", "integer", "foot: strides whose raw length is negative, turning under 30 deg "
                                               "(backward travel, with or without a model; a replay: strides classed "
                                               "backward; L203); side steps excluded (L270); empty on the lower "
                                               "back"),
    ("median_backward_stride_length_m", "m", "number", "foot: median |length_m| of the strides n_backward_strides "
                                                       "counts (L326); empty without one or on the lower back"),
    ("median_backward_speed_mps", "m/s", "number", "foot: median speed_mps of the strides n_backward_strides counts "
                                                   "(L326); empty without one or on the lower back"),
    ("n_cv_strides", "count", "integer", "steady straight level forward strides stride_time_cv_pct and "
                                         "stride_length_cv_pct are computed over (L104, L212)"),
    ("n_cv_segments", "count", "integer", "foot: straight stretches (runs of 5 or more consecutive CV strides "
                                          "between turns and stops) stride_length_cv_within_segments_pct is "
                                          "taken over (L380)"),
    ("n_detected", "count", "integer", "lower back: detected contacts scored"),
    ("n_pauses", "count", "integer", "stands of about 1 s or more inside the walk (L104)"),
    ("n_reference", "count", "integer", "lower back: reference contacts"),
    ("n_reference_strides", "count", "integer", "reference strides stride_length_mae_m compares"),
    ("n_stance_times", "count", "integer", "--toe-off only: strides with a stance time"),
    ("toe_contact_share_pct", "%", "number", "offline foot track: 100 x the steady strides (steps.csv steady) whose "
                                             "contact is forefoot / those with a contact type: a toe walker's "
                                             "share of toe contacts; empty under 5 such strides (L756)"),
    ("n_contact_strides", "count", "integer", "offline foot track: the steady strides toe_contact_share_pct is "
                                              "taken over (L756)"),
    ("n_stereo_matched", "count", "integer", "lower back: contacts matched with both feet"),
    ("n_side_strides", "count", "integer", "foot: strides of side-stepping runs (L219 / L228's sideways rows), "
                                           "not counted as backward (L270); empty on the lower back"),
    ("forward_distance_m", "m", "number", "foot: distance_m less backward_distance_m and side_distance_m: forward "
                                          "strides, turns on the spot and shuffles (L484); the three sum to "
                                          "distance_m; empty on the lower back"),
    ("backward_distance_m", "m", "number", "foot: summed |length_m| of the strides n_backward_strides counts (L484); "
                                           "empty on the lower back"),
    ("side_distance_m", "m", "number", "foot: summed |length_m| of the strides n_side_strides counts (L484); empty "
                                       "on the lower back"),
    ("n_flight_phases", "count", "integer", "runs of the tracked unit's accelerometer (foot; lower back: the "
                                            "waist's, W416) under 0.3 g for more than 0.1 s (first to last low "
                                            "sample 0.1 s or more, W409; both feet off the ground: jumps, running; "
                                            "W363); the lower back's only of 0.2 s or more or at a step period under "
                                            "0.4 s (W538: a brisk walker's bounce is no flight). The unit's own free "
                                            "fall: a foot swinging through a running stride's flight reads well "
                                            "over 0.3 g, so a foot-tracked run counts 0 (jumps count); running's "
                                            "flights per cycle are gait's n_flight_cycles (two feet; C269)"),
    ("flight_time_s", "s", "number", "the flight phases' time in all (W363, W416): the tracked unit's own free fall "
                                     "(C269)"),
    ("direction_changes", "count", "integer", "foot: changes of travel direction (steps.csv travel: forward / "
                                              "backward / left / right, turn and empty rows skipped; "
                                              "direction_changes.csv's rows, L412); a turn is not one; empty on "
                                              "the lower back"),
    ("n_stair_strides", "count", "integer", "strides climbing or descending 0.10 m or more (L179), a ramp's or "
                                            "hill's included (the gait-range guards' count, L179 / L435): since "
                                            "L705 no longer n_stair_strides_up + _down, which leave the ramps out"),
    ("n_stair_strides_up", "count", "integer", "stair strides that climb, outside ramps.csv's ramps (L432, L705: "
                                               "before L705 a ramp's strides counted too); lower back: steps inside "
                                               "a barometric climb up (W108, W526) and steps outside one rising "
                                               "0.10 m (W527), outside ramps.csv's ramps"),
    ("n_stair_strides_down", "count", "integer", "as n_stair_strides_up, descending (L432, W527, L705)"),
    ("n_ramp_strides_up", "count", "integer", "strides (lower back: steps) inside ramps.csv's up ramps (L705); 0 "
                                              "without a ramp_source (L717)"),
    ("n_ramp_strides_down", "count", "integer", "strides (lower back: steps) inside ramps.csv's down ramps (L705)"),
    ("n_flights_up", "count", "integer", "foot: stair flights up, stairs.csv's rows (L432); empty on the lower back"),
    ("n_flights_down", "count", "integer", "foot: stair flights down (L432); empty on the lower back"),
    ("flights_rise_m", "m", "number", "foot: what the stair flights up climb, stairs.csv's height_m summed (L602); "
                                      "empty on the lower back"),
    ("flights_drop_m", "m", "number", "foot: what the stair flights down descend, stairs.csv's height_m summed "
                                      "(positive; L602); empty on the lower back"),
    ("n_steps_left", "count", "integer", "lower back: steps whose side (W129's pelvis sway) is the left foot "
                                         "(W228); empty on a foot track (n_strides_one_foot)"),
    ("n_steps_right", "count", "integer", "lower back: steps of the right foot (W228); empty on a foot track"),
    ("n_steps_side_undecided", "count", "integer", "lower back: steps whose side was undecided (W228; left + right "
                                                   "+ undecided = n_steps); empty on a foot track"),
    ("n_step_time_asymmetry_steps", "count", "integer", "lower back: step times step_time_asymmetry_raw_pct is "
                                                        "computed over (L121, W228); a foot track with the "
                                                        "lower-back unit too: 2 x the strides L416's index is taken "
                                                        "over; 0 on a foot track alone"),
    ("n_straight_strides", "count", "integer", "level strides turning under 15 deg, side steps and "
                                               "backward strides left out (L179, L228, L580)"),
    ("n_stride_times", "count", "integer", "strides with a stride time"),
    ("step_time_asymmetry_pct", "%", "number", "lower back: step-time symmetry index 100 x |a - b| / (0.5 x (a + b)) "
                                               "of the alternating steps, given only from 20 % (L121, L216; the size "
                                               "is misread, mostly over); empty under it and on a foot track (W228) "
                                               "- but for a foot track of a session with the lower-back unit too "
                                               "(>= 50 Hz): the foot's contacts label the lower back's, the index "
                                               "of the two step times (L416); empty when the foot's median step is "
                                               "under 0.45 s, a child's (W532: pdrlearn gait with two feet)"),
    ("step_time_asymmetry_raw_pct", "%", "number", "lower back: that index however small; under 20 % no finding "
                                                   "either way (symmetric simulated walkers read up to 18.8 %, L121)"),
    ("step_time_asymmetry_reason", _ID, "text", "why step_time_asymmetry_pct is given or empty (L121, L216, W228)"),
    ("step_time_asymmetry_se_points", "points", "number", "a foot track with the lower-back unit too: the standard "
                                                          "error of step_time_asymmetry_pct (L490; counting the lower "
                                                          "back's lag, L677); an index under "
                                                          "1.96 x it is within noise (L671); empty otherwise"),
    ("step_time_asymmetry_uncertain", _ID, "true/false", "a foot track with the lower-back unit too: true when "
                                                          "step_time_asymmetry_pct is within noise (under 1.96 x "
                                                          "step_time_asymmetry_se_points, L671) or its standard error "
                                                          "is over 3 points (L490): not to be read as a measurement; a "
                                                          "unit on each foot (pdrlearn gait) times it (C271); empty "
                                                          "without an index"),
    ("step_time_s_left", "s", "number", "lower back: mean step time onto the left foot (the step ending at a left "
                                        "contact, W129's side; as gait's step_time_s_left; W250; turning steps "
                                        "and steps over 1.5 median steps left out, W512); a foot track with the "
                                        "lower-back unit too and meta.json's foot: L416's step onto the left foot "
                                        "(L671); else empty on a foot track"),
    ("step_time_s_right", "s", "number", "lower back: mean step time onto the right foot (W250, W512); a foot track "
                                         "with the lower-back unit too: as step_time_s_left (L671)"),
    ("step_time_s_ratio", "ratio", "number", "lower back: step_time_s_left / step_time_s_right, > 1 the left steps "
                                             "longer (gait's ratio L/R; W250); no finding where "
                                             "step_time_asymmetry_pct is empty"),
    ("n_turns", "count", "integer", "reference turns compared (turns.csv only, L42)"),
    ("n_turns_signed", "count", "integer", "reference turns of 45 deg or more whose sign is compared (L42)"),
    ("n_unscored", "count", "integer", "lower back: contacts outside the scored span"),
    ("n_walking_bouts", "count", "integer", "walking bouts = n_pauses + 1 + foot-data gaps over 1 s (L104's pauses, "
                                            "L269's gaps, whatever --bout-rule): "
                                            "equals n_bouts under the default rule; under --bout-rule mobgap or "
                                            "--bout-min-strides report n_bouts (L217)"),
    ("out_of_domain_fraction", "fraction", "number",
     "with a model (track --model, run): strides outside its training range (C16, C63)"),
    ("pause_time_s", "s", "number", "total pause time (L104): the pauses between consecutive steps beyond the walk's "
                                    "rhythm; with --window only those between the window's steps. Not a share of "
                                    "the session's time: see time_between_steps_s (L275). With the posture known "
                                    "(lower back) the standing time only (C248)"),
    ("pause_seated_lying_s", "s", "number", "lower back: the sitting and lying seconds between steps left out of the "
                                            "pauses (C248); empty without the posture"),
    ("per_s", "s", "number", "--per only: the period of periods.csv (L277)"),
    ("corridor_m", "m", "number", "--corridor only: the corridor walk test's course length (L383)"),
    ("n_laps", "count", "integer", "--corridor only: the corridor lengths walked between cone turns (laps.csv's "
                                   "corridor_laps summed; a missed turn counts 2, L384; the walker's turns only, "
                                   "not L622's carried, C181)"),
    ("walk_test_distance_m", "m", "number", "--corridor only: n_laps x corridor_m + the final partial lap (its tracked "
                                            "distance x the last lap's corridor / tracked ratio, at most corridor_m; "
                                            "ATS 2002 as recalled, L383)"),
    ("walk_test_duration_s", "s", "number", "--corridor only: the span walk_test_distance_m covers (--walk-test-"
                                            "duration's from walk_test_start_s, L516, up to the recording's end at "
                                            "most, L644; --window's; else the first step's start to the last step's "
                                            "end); a note when it is over 7 minutes without either (L462)"),
    ("walk_test_distance_per_minute_m", "m", "number", "--corridor only, summary.json only (a list): the corridor "
                                                     "distance in each full minute from the test's start, up to "
                                                     "walk_test_stopped_s when given (L383, L644); empty when the "
                                                     "laps track under half the corridor (L646)"),
    ("fatigue_index", "ratio", "number", "--corridor only: the last full minute's distance / the first minute's "
                                         "(our choice, L383; the minutes walked, L644); empty under 2 full minutes "
                                         "or with the per-minute distances withheld (L646)"),
    ("walk_test_start_s", "s", "number", "--walk-test-duration only: the test's start ('go', session clock): "
                                         "--walk-test-start, meta.json walk_test_start_s, else the first step after "
                                         "a standstill before the first full lap, else the first step (L642)"),
    ("walk_test_protocol_s", "s", "number", "--walk-test-duration only: the test's duration asked (120: 2MWT, 360: "
                                            "6MWT; the label clinical.md gives it, L644)"),
    ("walk_test_stopped_s", "s", "number", "--walk-test-duration only: the last step's end after walk_test_start_s "
                                           "when the walking ended over 10 s before the test's end (stopped early, "
                                           "L644); empty otherwise"),
    ("walk_test_n_rests", "count", "integer", "--walk-test-duration only: the rests inside the test's window "
                                              "(L647's rests: gaps between walking bouts less turns, cut to the "
                                              "window, at least 1 s inside it; C217); the recording's own are "
                                              "n_pauses"),
    ("walk_test_rest_time_s", "s", "number", "--walk-test-duration only: those rests' seconds inside the window "
                                             "(C217)"),
    ("walk_test_rests", "s", "number", "--walk-test-duration only, summary.json only (a list): [start from "
                                       "walk_test_start_s, seconds] of each of those rests (C217)"),
    ("walk_test_scale", "ratio", "number", "--corridor on the lower back only: corridor_m / (the median tracked "
                                           "lap between two cone turns less C181's cone arc): the corridor's scale "
                                           "of the step lengths (W562); empty with under 2 such laps or the "
                                           "minutes withheld (L646)"),
    ("gait_speed_corridor_mps", "m/s", "number", "--corridor on the lower back only: gait_speed_mps x "
                                                 "walk_test_scale, the recording's gait speed on the corridor's "
                                                 "scale (W562)"),
    ("walk_test_note", _ID, "text", "--corridor only: why no walk test was scored (not a corridor, L643) or why the "
                                    "per-minute distances and fatigue index are withheld (L646); empty otherwise"),
    ("splits_m", "m", "number", "--splits only, summary.json only (a list): the distance marks given (L411); "
                                "with --splits every:STEP each STEP on the path, then the path's end (L553)"),
    ("split_times_s", "s", "number", "--splits only, summary.json only (a list): each mark's time from the first "
                                     "step's start (splits.csv's time_s); empty for a mark beyond the path (L411)"),
    ("per_align", _ID, "text", "--per-align clock or first-step only: clock (periods.csv cut at the clock's whole "
                               "periods, L299) or first-step (from the first tracked step, L381; the default with "
                               "--walk-test-duration, C178)"),
    ("per_start_s", "s", "number", "--per only: the periods' grid origin, where the first period's edge lies (the "
                                   "recording's or --window's start, or the first step's with --per-align "
                                   "first-step; L381); after a --common-span cut periods.csv's first row starts later, "
                                   "at the first held sample (C185 amended, D54)"),
    ("recording_start", "date-time", "text", "the clock time of the recording's first sample, ISO 8601 at its own "
                                             f"offset; {_WITH_START}"),
    ("pdrlearn_version", _ID, "text", "the pdrlearn version that wrote the row (run.json names the commit, L136)"),
    ("schema_version", _ID, "integer", "the version of summary.json's keys (E155): raised when a key is renamed, "
                                       "removed or changes meaning, not when one is added"),
    ("step_f1", "fraction", "number", "tracked strides / steps against the reference contacts, F1 (L36)"),
    ("step_f1_all", "fraction", "number", "lower back: F1 over every reference contact"),
    ("step_f1_same_foot_gaps_scored", "fraction", "number", "lower back: F1 with same-foot gaps scored"),
    ("step_precision", "fraction", "number", "precision of the tracked steps / strides"),
    ("step_recall", "fraction", "number", "recall of the tracked steps / strides"),
    ("stereo_recall", "fraction", "number", "lower back: recall with both feet matched"),
    ("storey_height_m", "m", "number", "the storey height floors are counted in"),
    ("storeys_changed", "count", "integer", "net storeys (up minus down)"),
    ("storeys_changed_ref", "count", "integer", "net storeys in the reference; empty without a reference altitude "
                                                "track (C103)"),
    ("stride_length_bias_m", "m", "number", "lower back: mean stride length error"),
    ("stride_length_composed", "count", "integer", "foot: labelled strides tiled by several tracked pieces"),
    ("stride_length_cv_pct", "%", "number", "foot: 100 x SD / mean of the lengths of the strides of "
                                            "stride_time_cv_pct (L212; given with 10 of them, even when L113 "
                                            "withholds the time CV); empty on the lower back"),
    ("stride_length_cv_within_segments_pct", "%", "number", "foot: the CV strides' lengths about their own "
                                                            "straight stretch's mean (L380); stride_length_cv_pct "
                                                            "over twice this warns that it pools a change of pace"),
    ("stride_length_mae_m", "m", "number", "mean absolute stride length error"),
    ("stride_length_mae_pct", "%", "number", "mean over the pairs of 100 x |error| / reference length (each stride "
                                             "weighted alike, not mean |error| / mean reference; L252); foot: every "
                                             "pair of steps.csv's ref_match (E135), the first stride from standing, "
                                             "turns and composed strides included"),
    ("stride_length_mae_pct_straight", "%", "number", "the same over strides the labels do not mark turn (the "
                                                      "initiation stride included)"),
    ("stride_length_mae_pct_steady", "%", "number", "foot: the same over strides the labels mark steady (simulated "
                                                    "walks: no initiation, termination or turn stride; L252)"),
    ("stride_length_mae_pct_turns", "%", "number", "the same over turning strides"),
    ("stride_length_matched", "count", "integer", "foot: tracked strides matched to labelled ones"),
    ("stride_time_cv_pct", "%", "number", "foot: 100 x SD / mean of steady level forward strides' times (L104, L188)"),
    ("step_count_withheld", _ID, "text", "lower back: why there is no step count - the waist contacts are over 1.5 x "
                                         "the pelvic-gyro detector's steps (W442): median_cadence_spm, "
                                         "median_step_time_s and median_stride_time_s are empty, n_steps counts "
                                         "contacts, and the text names the pelvic gyro's count and cadence (W476); "
                                         "empty otherwise"),
    ("stride_time_cv_withheld", _ID, "text", "why there is no stride-time CV; summary.json only (an object: cause "
                                             "lower_back (L104), too_few_strides (L215: with the straight strides "
                                             "the level criterion dropped) or contact_scatter (L113, an option), "
                                             "and a reason; L214; on the lower back also jitter_free_cv_pct, the "
                                             "stride-time CV with the contacts' timing jitter taken out, from 181 "
                                             "stride intervals t[k+2] - t[k] of steady straight runs (W598: no turn, "
                                             "no extra or missed contact; about 187 steps in one run), and "
                                             "n_jitter_free_strides, those intervals, W558); empty in sessions.csv"),
    ("stride_time_cv_withheld_cause", _ID, "text", "stride_time_cv_withheld's cause: lower_back, too_few_strides or "
                                                   "contact_scatter; empty when the CV is given (L230)"),
    ("stride_time_cv_within_bouts_pct", "%", "number", "foot: when the CV pools walking bouts of different rhythm "
                                                       "(L196), the CV of the strides about their own bout's mean; "
                                                       "empty otherwise"),
    ("terrain_agreement", "fraction", "number", "matched strides whose terrain class is the label's (L53)"),
    ("time_between_steps_s", "s", "number", "from the first to the last step counted (L105's rule), the time "
                                            "neither walking nor without data: standing (or sitting) between steps "
                                            "(L275; a lower-back track splits it and time_no_steps_s by "
                                            "posture: standing_time_s / sitting_time_s / lying_time_s, W222)"),
    ("time_no_data_s", "s", "number", "the tracked unit's data gaps over 1 s (the warned ones, B11) (L275)"),
    ("time_no_steps_s", "s", "number", "before the first step counted and after the last: no step bounds it (the "
                                       "time before the walk, a seated stretch at a window's edge) (L275)"),
    ("time_span_s", "s", "number", "the recording of the tracked unit from the session start (after --common-span "
                                   "the cut's start, C185), or the --window: time_walking_s + "
                                   "time_between_steps_s + time_no_steps_s + time_no_data_s (L275)"),
    ("steady_trim", "count", "integer", "--steady-trim: the strides left out at each end of each walking bout from "
                                        "steady_gait_speed_mps, cadence, the stride medians and the CVs (L415; "
                                        "0: none); distance_m, walking_time_s and gait_speed_mps keep every "
                                        "stride (L426)"),
    ("steady_distance_m", "m", "number", "--steady-trim N > 0: the distance of the strides left in (each bout's "
                                         "first / last N out); empty at 0 (L426)"),
    ("steady_time_s", "s", "number", "--steady-trim N > 0: the walking time of the strides left in; empty at 0 "
                                     "(L426)"),
    ("steady_gait_speed_mps", "m/s", "number", "steady_distance_m / steady_time_s (--steady-trim N > 0; empty at "
                                               "0, L426)"),
    ("common_span_cut_s", "s", "number", "the seconds of the walk the track does not cover: both units' "
                                         "recordings together (when they start or stop over 1 s apart) less the "
                                         "tracked span - a cut to the time both units (or every file) cover "
                                         "(--common-span, B81, B83; a moved waist clock's overhang, L162) and the "
                                         "time the other unit recorded on after the tracked one stopped (either "
                                         "unit's dead battery, or a clock drift not given); 0 when nothing was "
                                         "lost - a march cut short by a dead unit shows here, not only in the "
                                         "warnings (B267, B273)"),
    ("time_walking_s", "s", "number", "the whole session's walking pieces (walking_time_s's, L79) inside the span, "
                                      "data gaps left out: = walking_time_s for a whole session, and windows add up "
                                      "to it (L275)"),
    ("standing_time_s", "s", "number", "lower back: the span's time standing still, outside walking and data gaps "
                                       "(trunk tilt from the walking upright under 8 deg, W248, or a chair transfer's "
                                       "standing side, W222); empty for a foot track and for "
                                       "`run` of a waist bundle (E145)"),
    ("sitting_time_s", "s", "number", "lower back: the time seated (between a stand-to-sit and a sit-to-stand, or "
                                      "tilt 8-60 deg without a transfer to go by, W222 / W248); empty for a foot track "
                                      "and for `run` of a waist bundle (E145)"),
    ("lying_time_s", "s", "number", "lower back: the time lying (trunk tilt >= 60 deg from the walking upright, "
                                    "W222); empty for a foot track and for `run` of a waist bundle (E145)"),
    ("unknown_time_s", "s", "number", "lower back: the rest, data gaps and time without a walking upright; "
                                      "time_walking_s + standing + sitting + lying + unknown = time_span_s (W222); "
                                      "empty for a foot track and for `run` of a waist bundle (E145)"),
    ("timing_resolution_s", "s", "number", "one sample period of the stream the contacts come from (L116)"),
    ("turn_angle_mae_deg", "deg", "number", "mean absolute error of the reference turns' angles (L42)"),
    ("turn_count", "count", "integer",
     f"turns of >= {TURN_COUNT_MIN_DEG:g} deg, with their same-direction edge rows (L104, L181); a lower-back "
     "track's: turns.csv's rows (L231, L232) not marked carried (L622: a turn made seated or in a ride, W488, "
     "is the seat's or the vehicle's)"),
    ("turn_count_min_deg", "deg", "number", "the smallest turn turn_count counts"),
    ("median_turn_duration_s", "s", "number", "median duration of turns.csv's turns (L200); empty without a turn"),
    ("median_turn_angle_deg", "deg", "number", "median absolute angle of turns.csv's turns (L200)"),
    ("median_turn_peak_rate_dps", "deg/s", "number", "median peak turning rate of turns.csv's turns (L200, L229)"),
    ("turn_time_s", "s", "number", "turns.csv's durations summed (L200)"),
    ("median_turn_mean_rate_dps", "deg/s", "number", "median mean turning rate of turns.csv's turns (L209; foot: "
                                                     "90 % of the angle over its 5-95 % timing, lower back: the whole "
                                                     "angle over its yaw-rate timing, L229)"),
    ("n_sit_to_stand", "count", "integer", "lower back: sit-to-stand transfers (transfers.csv, W182); empty on a foot "
                                           "track (a foot unit does not see the trunk)"),
    ("n_stand_to_sit", "count", "integer", "lower back: stand-to-sit transfers (W182); empty on a foot track"),
    ("median_sit_to_stand_s", "s", "number", "lower back: median sit-to-stand duration (W182)"),
    ("median_stand_to_sit_s", "s", "number", "lower back: median stand-to-sit duration (W182)"),
    ("n_lie_down", "count", "integer", "lower back: transfers into lying, sit-to-lie and stand-to-lie (transfers.csv, "
                                       "W245, W258); empty on a foot track"),
    ("n_get_up", "count", "integer", "lower back: transfers out of lying, lie-to-sit and lie-to-stand (W245, W258); "
                                     "empty on a foot track"),
    ("tug_time_s", "s", "number", "lower back, a session that starts and ends seated (one rise before the first "
                                  "step, one sit after the last, a step between them: W340): the rise's start to "
                                  "the sit's end (W183)"),
    ("tug_time_note", _ID, "text", "lower back: why there is no tug_time_s although a sit-to-stand is followed by "
                                   "a stand-to-sit (not starting and ending seated, several trials, steps outside; "
                                   "W282; no step between: a chair stand, W340), pointing at --window - or, with "
                                   "TUG trials found, that each is timed in tug_trials.csv (W325), or that the "
                                   "seat-to-seat walks are chair-to-chair walks (W445); or that a walk of at most "
                                   "120 s has a rise before it and no sit after it, or the reverse: a slow transfer "
                                   "missed (L648); empty otherwise"),
    ("n_tug_trials", "count", "integer", "lower back: TUG trials, W183's seat-to-seat rule applied to each "
                                         "sit-to-stand directly followed by a stand-to-sit with walking between "
                                         "(tug_trials.csv, W325) that looks like a TUG: at most 120 s and back "
                                         "to the chair it rose from (W445), an about-turn (180 +- 45 deg) as its "
                                         "first turn and at most 9 m out and back (W490); empty on a foot track"),
    ("tug_trials_median_s", "s", "number", "lower back: the median of tug_trials.csv's tug_time_s (W325); empty "
                                           "without a trial"),
    ("n_chair_walks", "count", "integer", "lower back: seat-to-seat walks (W325's pattern) that do not look like a "
                                          "TUG - longer than 120 s, not back to the chair (W445), no about-turn first "
                                          "or over 9 m out or back (W490): daily walks, not timed; empty on a foot "
                                          "track"),
    ("tug_steps_source", _ID, "text", "with a TUG: the unit tug_trials.csv's n_steps is counted on, foot (a foot "
                                      "+ waist session's default track, W418 / W419) or waist; empty otherwise "
                                      "(W427)"),
    ("tug_turns_source", _ID, "text", "with a TUG: the unit whose turns time the TUG's turn phases, foot or "
                                      "waist (W419); empty otherwise (W427)"),
    ("sts5_time_s", "s", "number", "lower back, a five-times sit-to-stand: the first rise's start to the last sit's "
                                   "end when the transfers are exactly 5 rises and 5 sits alternating from a rise, "
                                   "none flagged, no walking between (W279)"),
    ("n_transfers_flagged", "count", "integer", "lower back: transfers.csv's rows with a flag (W278: not "
                                                "alternating, walking on both sides); empty on a foot track"),
    ("tug_sit_to_stand_s", "s", "number", "lower back, with a tug_time_s: the TUG's sit-to-stand (tug_phases.csv, "
                                          "W293); summary.json's tug_phases has each phase's start, end and "
                                          "duration"),
    ("tug_walk_out_s", "s", "number", "TUG: the first step after the rise to the first turn's start (W293)"),
    ("tug_turn_s", "s", "number", "TUG: the first turn between the rise and the sit (turns.csv's timing, ~1 s longer "
                                  "than a 5-95 % turn, L346; W293)"),
    ("tug_walk_back_s", "s", "number", "TUG: the turn's end to the turn-to-sit's start, without one to the last step "
                                       "before the sit (W293)"),
    ("tug_turn_to_sit_s", "s", "number", "TUG: the last of two or more turns before the sit (W293), else the last "
                                         "yaw-rate turn of 80 deg or more after the first (W307); empty without"),
    ("tug_stand_to_sit_s", "s", "number", "TUG: the stand-to-sit (W293)"),
    ("ten_m_walk_time_s", "s", "number", "10 m walk test: the time the path takes over the timed metres of "
                                         "ten_m_walk_zones_m (default 2 m to 12 m) of the first walking bout "
                                         "reaching the walkway's length, straight (L312, L522, L531); empty on a "
                                         "shorter or turning walk (L313) and on the lower back unless calibrated "
                                         "with an acceleration zone (L649)"),
    ("ten_m_walk_speed_mps", "m/s", "number", "the timed metres of ten_m_walk_zones_m (default 10 m) / "
                                              "ten_m_walk_time_s (L312, L531)"),
    ("ten_m_walk_note", _ID, "text", "why there is no ten_m_walk_time_s (L313); with one, the walking bouts that "
                                     "tracked under RUN_OUT_M short of the walkway and so are no trial (L524); "
                                     "else empty"),
    ("n_ten_m_walk_trials", "count", "integer", "10 m walk test: the walking bouts timed as the first "
                                                "(ten_m_walk_trials.csv, L524): a self-selected and a fast trial "
                                                "are 2"),
    ("ten_m_walk_max_speed_mps", "m/s", "number", "the fastest of ten_m_walk_trials.csv's speed_mps (the fast "
                                                  "trial, L524); empty without a trial"),
    ("ten_m_walk_zones_m", "m", "number", "summary.json only (a list): the walkway the 10 m walk keys were timed on, "
                                          "acceleration zone, timed metres, deceleration zone (2, 10, 2; track "
                                          "--ten-m-walk, L522)"),
    ("ten_m_walk_timed_m", "m", "number", "sessions.csv only: the timed metres of ten_m_walk_zones_m (10 without "
                                          "it, L312) when there is a ten_m_walk_speed_mps; changes.csv compares that "
                                          "speed only between visits with the same (C211)"),
    ("ten_m_walk_declared", _ID, "true/false", "true when track --ten-m-walk declared the walkway; false: the 10 m "
                                               "walk and T25FW were found in free walking, no test declared, and "
                                               "the console and clinical.md say so (L679)"),
    ("t25fw_time_s", "s", "number", "timed 25-foot walk: the time from a walking bout's start (standing; the body's "
                                    "first step, one step before a foot's first full stride, C250) to where its "
                                    "path passes 7.62 m, straight (L387); the mean of the first two trials when "
                                    "two were timed (C251); empty on a shorter or turning "
                                    "walk and on the lower back, calibrated or not (L313, L649), and on a timed "
                                    "corridor walk test's recording (C249); a flying 25-foot "
                                    "walk (track --ten-m-walk 1,7.62,3.38) is ten_m_walk_time_s, not this (C206)"),
    ("t25fw_speed_mps", "m/s", "number", "7.62 m / t25fw_time_s (L387)"),
    ("t25fw_note", _ID, "text", "why there is no t25fw_time_s (L387; C249); with two trials timed, that it is their "
                                "mean (C251)"),
    ("n_t25fw_trials", "count", "integer", "timed 25-foot walk: the walking bouts from standing timed as the first "
                                           "(C251); t25fw_time_s is the mean of the first two"),
    ("t25fw_trial_times_s", "s", "number", "summary.json only (a list): each T25FW trial's time, in order (C251)"),
    ("n_freezes", "count", "integer", "freeze episodes of the tracked unit (freezes.csv): freeze index over 3 with "
                                      "band power, 1 s or longer (W213); null on a lower-back track without the "
                                      "freeze_index option (W216: not measured)"),
    ("freeze_time_s", "s", "number", "freezes.csv's durations summed (W213)"),
    ("stepless_turns", "count", "integer", "a lower-back track's turns.csv turns whose 5-95 % span holds no detected "
                                           "step although it lasts 2 or more of the walk's step times: a turn on the "
                                           "spot the motion gate read as standing (W331); null on a foot track or "
                                           "without 4 step intervals"),
    ("turn_steps_missed", "count", "integer", "the steps the stepless_turns imply (each turn's 5-95 % duration over "
                                              "the walk's median step time, W283), not in n_steps (W331)"),
    ("n_steps_with_turns", "count", "integer", "n_steps + turn_steps_missed: the detected steps and the turning steps "
                                               "on the spot W331 estimates (W603); null where turn_steps_missed is "
                                               "(a foot track) or the step count is withheld (W476)"),
    ("turn_sign_agreement", "fraction", "number", "reference turns whose tracked turn has the same sign (L42)"),
    ("walking_speed_mps", "m/s", "number", "distance / walking time without the pauses (L110)"),
    ("walking_time_no_pauses_s", "s", "number", "walking time without the pauses inside it (L110)"),
    ("window_start_s", "s", "number", "--window only: the window's start, from the session start (L108)"),
    ("window_end_s", "s", "number", "--window only: the window's end (L108)"),
)

GROUPS: tuple[Column, ...] = (
    ("group", _ID, "text", "the group (sessions.csv group)"),
    ("n_tracked", "count", "integer", "sessions of the group tracked"),
    ("n_failed", "count", "integer", "sessions of the group that failed (a skipped split part is not, B389)"),
    ("{measure}_n", "count", "integer", "sessions with a value of the measure (the sessions.csv column; the four "
                                        "measures, then each track-all --metrics measure, C256)"),
    ("{measure}_mean", "as the measure", "number", "mean over those sessions (every session of every subject "
                                                   "and visit counted alike: descriptive only)"),
    ("{measure}_sd", "as the measure", "number", "sample standard deviation"),
    ("{measure}_median", "as the measure", "number", "median"),
    ("{measure}_ci95_low", "as the measure", "number", "95 % t-interval of the mean, lower end (sessions taken "
                                                       "as independent)"),
    ("{measure}_ci95_high", "as the measure", "number", "95 % t-interval of the mean, upper end"),
)

SUBJECTS: tuple[Column, ...] = (
    ("subject", _ID, "text", "meta.json subject (C25)"),
    ("visit", _ID, "text", "the visit as changes.csv names it (C40, C82)"),
    ("test", _ID, "text", "track-all --group-by test only: meta.json test, a row per subject, visit and test "
                          "(empty: the subject's sessions naming none; C171)"),
    ("group", _ID, "text", "the group(s) of the subject's sessions"),
    ("n_tracked", "count", "integer", "the subject's sessions of that visit tracked"),
    ("n_failed", "count", "integer", "those that failed"),
    ("paths", _ID, "text", "the session folders"),
    ("distance_m", "m", "number", "the tracks' distances summed over the sessions"),
    ("n_bouts", "count", "integer", "walking bouts"),
    ("walking_time_s", "s", "number", "sessions.csv's walking_time_s summed (the summary's: stops over 3 s left "
                                      "out, L79; W447)"),
    ("n_steps", "count", "integer", "bouts' steps summed"),
    ("n_strides", "count", "integer", "bouts' strides summed"),
    ("bouts_distance_m", "m", "number", "the walking bouts' distance summed (bouts.csv)"),
    ("gait_speed_mps", "m/s", "number", "distance_m / walking_time_s, the sessions pooled: sessions.csv's and "
                                        "summary.json's definition, equal to them for one session (W447)"),
    ("cadence_spm", "steps/min", "number", "60 x the bouts' steps between first and last contact / their contact "
                                           "spans (bouts.csv's cadence terms, pooled; L164; lower back: inner steps, "
                                           "W602)"),
    ("visit_as_written", _ID, "text", "meta.json visit(s) as written, ; -separated (C82)"),
    ("floors_up", "count", "integer", "sessions.csv's floors_up summed over the tracked sessions (a day in parts "
                                      "adds up); empty when one of them has none (C108)"),
    ("floors_down", "count", "integer", "sessions.csv's floors_down summed (C108)"),
    ("time_no_data_s", "s", "number", "sessions.csv's time_no_data_s (data gaps over 1 s) summed (C108)"),
    ("standing_time_s", "s", "number", "lower back: sessions.csv's standing_time_s summed; empty when one of the "
                                       "sessions has none (a foot track: a partial sum is not the day's, C108)"),
    ("sitting_time_s", "s", "number", "lower back: sitting_time_s summed; empty as standing_time_s (C108)"),
    ("lying_time_s", "s", "number", "lower back: lying_time_s summed; empty as standing_time_s (C108)"),
    ("n_sit_to_stand", "count", "integer", "lower back: sit-to-stand transfers summed; empty as standing_time_s "
                                           "(C108)"),
    ("n_stand_to_sit", "count", "integer", "lower back: stand-to-sit transfers summed; empty as standing_time_s "
                                           "(C108)"),
    ("bouts_time_s", "s", "number", "the walking bouts' durations summed (bouts.csv, the batch's --bout-* rule)"),
    ("bouts_gait_speed_mps", "m/s", "number", "bouts_distance_m / bouts_time_s (pooled, not a mean of bouts; C25's "
                                              "gait speed, named apart by W447)"),
    ("pooled_n_sessions", "count", "integer", "the row's sessions with foot strides, pooled in the pooled_* columns "
                                              "(C146)"),
    ("pooled_n_strides", "count", "integer", "foot strides pooled over those sessions (median_stride_length_m's "
                                             "strides: no gap row, no zeroed stride; C146)"),
    ("pooled_median_stride_length_m", "m", "number", "median stride length of the pooled foot strides (C146)"),
    ("pooled_n_cv_sessions", "count", "integer", "sessions with at least 2 CV strides (steps.csv steady rows with a "
                                                 "stride time), pooled in the CV (C146)"),
    ("pooled_n_cv_strides", "count", "integer", "their CV strides (C146)"),
    ("pooled_stride_time_cv_pct", "%", "number", "stride-time CV within sessions, pooled: each stride time about its "
                                                 "own session's mean, no stride across two sessions; empty under 9 "
                                                 "degrees of freedom (strides less sessions; C146)"),
    ("pooled_stride_time_cv_reason", _ID, "text", "why pooled_stride_time_cv_pct is empty (C146)"),
)

#: decision C257: ``track-all --repeated``'s subjects_pooled.csv, one row per subject over all its sessions
SUBJECTS_POOLED: tuple[Column, ...] = (
    ("subject", _ID, "text", "meta.json subject (C257)"),
    ("group", _ID, "text", "the group(s) of the subject's sessions, ; -separated"),
    ("n_tracked", "count", "integer", "the subject's sessions tracked and pooled (a copy of another counted once)"),
    ("n_failed", "count", "integer", "its sessions that failed (pooled nowhere)"),
    ("visits", _ID, "text", "its visits (shifts, days) as changes.csv would name them, ; -separated"),
    ("paths", _ID, "text", "the session folders"),
    ("hours_recorded", "h", "number", "the tracked sessions' time_span_s less time_no_data_s, summed: worn time "
                                      "with data (L275)"),
    *(col for m in POOLED_MEASURES for col in (
        (pooled_kinds(m)[0], "as the measure", "number", f"sessions.csv's {m}, the mean over the tracked sessions "
                                                         "with a value"),
        (pooled_kinds(m)[1], "measure / h", "number", f"{m} of those sessions summed / their hours_recorded (a "
                                                      "ratio of totals)"))),
    ("reason", _ID, "text", "a measure only some sessions have, a copy counted once, a failed session (C257)"),
)

#: decision C258: ``track-all --repeated``'s groups_pooled.csv, one row per group, the subject as the unit
GROUPS_POOLED: tuple[Column, ...] = (
    ("group", _ID, "text", "subjects_pooled.csv's group"),
    ("n_subjects", "count", "integer", "the group's subjects"),
    *(col for c in ("hours_recorded", *(k for m in POOLED_MEASURES for k in pooled_kinds(m))) for col in (
        (f"{c}_n", "count", "integer", f"subjects with a value of subjects_pooled.csv's {c}"),
        (f"{c}_mean", "as the column", "number", "mean over those subjects (each subject once, C258)"),
        (f"{c}_sd", "as the column", "number", "sample standard deviation over the subjects"),
        (f"{c}_median", "as the column", "number", "median over the subjects"),
        (f"{c}_ci95_low", "as the column", "number", "95 % t-interval of the mean, lower end (C20)"),
        (f"{c}_ci95_high", "as the column", "number", "95 % t-interval of the mean, upper end"))),
)

#: decisions C22, C81-C83: track-all's changes.csv, one row per subject and later visit (and test, C174);
#: ``{measure}`` stands for each measure compared (groups.csv's, or --metrics)
CHANGES: tuple[Column, ...] = (
    ("subject", _ID, "text", "meta.json subject (C22)"),
    ("group", _ID, "text", "the subject's group"),
    ("baseline_visit", _ID, "text", "the subject's baseline visit (C24, C28), as sessions.csv's visit (C82)"),
    ("visit", _ID, "text", "the later visit compared with it"),
    ("test", _ID, "text", "track-all --group-by test only: meta.json test, each test's visits paired on their own, a "
                          "row per subject, test and later visit (empty: the sessions naming none; C174)"),
    ("baseline_visit_as_written", _ID, "text", "meta.json's name(s) of the baseline visit (C82)"),
    ("visit_as_written", _ID, "text", "meta.json's name(s) of the later visit (C82)"),
    ("status", _ID, "text", "ok (paired), missing, failed, pipelines (C30) or duplicate (C31); several: before C83"),
    ("reason", _ID, "text", "why a row is not ok, or what an ok row's means left out (C83)"),
    ("baseline_n_trials", "count", "integer", "tracked sessions of the baseline visit averaged (repeated trials, C83)"),
    ("n_trials", "count", "integer", "tracked sessions of the later visit averaged (C83)"),
    ("baseline_path", _ID, "text", "the baseline session(s), ; -separated"),
    ("path", _ID, "text", "the later visit's session(s), ; -separated"),
    ("baseline_duplicate_of", _ID, "text", "other sessions holding the baseline's recording (C31)"),
    ("duplicate_of", _ID, "text", "other sessions holding the later visit's recording (C31)"),
    ("{measure}_baseline", "as the measure", "number", "the baseline visit's value (its trials' mean, C83)"),
    ("{measure}_change", "as the measure", "number", "later visit minus baseline (C22)"),
    ("{measure}_change_pct", "%", "number", "100 x change / |baseline|: the dual-task cost when the visits are "
                                            "single and dual (C81); empty when the baseline is 0; not written "
                                            "for a percent error, distance_error_pct or any *error*_pct / *mae*_pct "
                                            "(its change is in points, C101)"),
    ("step_time_asymmetry_pct_change_se", "points", "number", "with step_time_asymmetry_pct compared: the "
                                                              "change's standard error, the two visits' "
                                                              "step_time_asymmetry_se_points in quadrature (C271)"),
    ("step_time_asymmetry_pct_change_uncertain", _ID, "true/false", "with step_time_asymmetry_pct compared: true "
                                                                    "when the change is under 1.96 x its standard "
                                                                    "error or that is over 3 points: no change can "
                                                                    "be read from one foot + the lower back; two "
                                                                    "foot units (gait-all) time it (C271)"),
)

#: cohort C242: gait-all's gait_changes.csv, changes.csv's columns (no test) over the pairs' gait_summary.json walks;
#: ``{measure}`` stands for each walk measure compared (pdrlearn.track.gait_changes.GAIT_CHANGE_MEASURES)
_GAIT_CHANGE_TEXT = {"group": "the pair's first folder under ROOT (track-all's --group-depth 1)",
                     "baseline_path": "the baseline visit's folder(s) under ROOT (gait_pairs.csv path), ; -separated",
                     "path": "the later visit's folder(s) under ROOT, ; -separated (a visit's walks averaged, C83)"}
GAIT_CHANGES: tuple[Column, ...] = tuple((name, unit, kind, _GAIT_CHANGE_TEXT.get(name, text))
                                         for name, unit, kind, text in CHANGES
                                         if name != "test" and not name.startswith("step_time_asymmetry_pct_"))

#: decisions C23, C81, C85: track-all's changes_summary.csv, one row per later visit, baseline (test, C174) and measure
CHANGES_SUMMARY: tuple[Column, ...] = (
    ("visit", _ID, "text", "the later visit (changes.csv's visit, C82)"),
    ("baseline_visit", _ID, "text", "the baseline it is compared with (subjects of other baselines apart, C28)"),
    ("test", _ID, "text", "track-all --group-by test only: changes.csv's test, a row per visit, baseline, test and "
                          "measure (C174)"),
    ("measure", _ID, "text", "the measure (groups.csv's, or a --metrics name, C81)"),
    ("n_subjects", "count", "integer", "subjects with a change: both visits tracked and the measure at both (C23)"),
    ("mean_change", "as the measure", "number", "the mean of the subjects' changes (C23)"),
    ("sd_change", "as the measure", "number", "their standard deviation (n - 1)"),
    ("ci95_low", "as the measure", "number", "the paired 95 % t-interval of the mean change, low; empty under two "
                                             "subjects (C23)"),
    ("ci95_high", "as the measure", "number", "its high end"),
    ("n_pct_subjects", "count", "integer", "subjects with a percent change: n_subjects less those whose baseline is "
                                           "0 (C85)"),
    ("mean_pct_change", "%", "number", "the mean of the subjects' percent changes, 100 x change / |baseline| "
                                       "(the mean dual-task cost; C81); empty for a percent error (C101)"),
    ("sd_pct_change", "%", "number", "their standard deviation (n - 1)"),
    ("pct_ci95_low", "%", "number", "the paired 95 % t-interval of the mean percent change, low (C81)"),
    ("pct_ci95_high", "%", "number", "its high end"),
    ("n_not_paired", "count", "integer", "subjects of the visit whose changes.csv row is not ok (C23)"),
    ("not_paired", _ID, "text", "those subjects, ; -separated"),
    ("n_uncertain", "count", "integer", "step_time_asymmetry_pct only: subjects whose change is uncertain "
                                        "(changes.csv step_time_asymmetry_pct_change_uncertain, C271); the printed "
                                        "change says 'k of n uncertain'; empty for the other measures"),
)

BOUTS: tuple[Column, ...] = (
    ("path", _ID, "text", "track-all's OUT/bouts.csv only: the session's path, sessions.csv's key (L165)"),
    ("visit", _ID, "text", "a track's bouts.csv: meta.json's visit, empty when not given (C100); track-all's "
                           "OUT/bouts.csv: the session's visit as sessions.csv names it (L165, C82)"),
    ("session", _ID, "text", "the session's name (meta.json's session, else the folder; L165)"),
    ("subject", _ID, "text", "meta.json subject (or user; a whole number as its text, C99); empty when not given "
                             "(L165)"),
    ("bout", "index", "integer", "the bout's number in the session, from 1"),
    ("start_s", "s", "number", "start (first step's start), on the session's clock"),
    ("end_s", "s", "number", "end (last step's end), on the session's clock"),
    ("duration_s", "s", "number", "end_s - start_s: the slower first and last steps included"),
    ("n_steps", "count", "integer", "steps of both feet in the bout (L103; on a foot track an estimate from the "
                                    "tracked foot's strides)"),
    ("n_strides", "count", "integer", "foot: strides of the tracked foot; lower back: n_steps - 2 (strides "
                                      "contact k to k + 2, as mobgap forms them)"),
    ("distance_m", "m", "number", "tracked distance in the bout"),
    ("speed_mps", "m/s", "number", "distance_m / duration_s (speed_m_s before E98)"),
    ("stride_length_m", "m", "number", "mean stride length: foot distance_m / n_strides; lower back 2 x "
                                       "distance_m / (n_steps - 1), 2 x the mean step (L166)"),
    ("contact_span_s", "s", "number", "first initial contact to the last (L164); on the lower back from the second "
                                      "contact to the last-but-one (W602: its edge contacts are read inward; under "
                                      "4 contacts 0); with --corridor less the gaps its stepless cone turns fill "
                                      "(C182: their steps were not detected, W331) and, on the lower back, the "
                                      "steps beside them"),
    ("n_step_intervals", "count", "integer", "steps between those contacts: contacts - 1 (foot: 2 per stride; L164; "
                                             "lower back: contacts - 3, W602); with --corridor less the cone turns' "
                                             "gaps (C182)"),
    ("cadence_spm", "steps/min", "number", "60 x n_step_intervals / contact_span_s (L164); empty on a lower-back "
                                           "track whose contacts are no step count (step_count_withheld, W480) and "
                                           "on a lower-back bout of under 4 contacts (W602)"),
    ("longest_contact_gap_s", "s", "number", "longest time between two consecutive contacts in the bout; may "
                                             "exceed --bout-break-s under --bout-rule pdrlearn (L163; with "
                                             "--corridor a stepless cone turn's gap, which ends no bout: C182), "
                                             "and on a foot track (one foot's contacts) under mobgap by one "
                                             "step time (L676)"),
    ("data_gap_s", "s", "number", "foot-data gaps (L67's gap rows) inside the bout, summed; a gap longer than "
                                  "--bout-break-s ends the bout instead (L269)"),
    ("n_turns", "count", "integer", f"turns of >= {TURN_COUNT_MIN_DEG:g} deg in the bout (L104)"),
    ("direction", _ID, "text", "foot: forward (no stride of the bout travels backward or sideways), backward (all "
                               "travel backward), side (all are side steps, L581) or mixed, by each stride's "
                               "travelled direction (steps.csv backward_travel, L203, and sideways), not the "
                               "model's class; empty on the lower back (L331)"),
    ("backward_fraction", "fraction", "number", "foot: the bout's strides that travel backward (backward_travel) / "
                                                "n_strides; empty on the lower back (L331)"),
    ("n_backward_strides", "count", "integer", "foot: the bout's strides that travel backward (backward_travel); "
                                               "empty on the lower back (L581)"),
    ("n_side_strides", "count", "integer", "foot: the bout's strides of side-stepping runs (sideways, L270); empty "
                                           "on the lower back (L581)"),
    ("altitude_change_m", "m", "number", "z change over the bout"),
    ("altitude_change_before_m", "m", "number", "lower back: z change while standing before the bout (a lift or "
                                                "escalator ride; W158; of a pause over 30 s only the 1.5 m "
                                                "within 30 s rides, W231), 0 for foot tracks"),
    ("floors_up", "count", "integer", "storeys of the summary's floor climbs (L127, L374-L376) whose last stair "
                                      "stride lies in the bout (L450; `run` too, L458); empty when the floors come "
                                      "from the altitude (L64)"),
    ("floors_down", "count", "integer", "the same, down (L450)"),
    ("ascent_m", "m", "number", "the summary's ascent_m rule on the trajectory from start_s to end_s (L467)"),
    ("descent_m", "m", "number", "the same, descent (L467)"),
    ("freeze_time_s", "s", "number", "when the freeze index ran (foot tracks; lower back with --freeze-index): the "
                                     "seconds of freezes.csv's episodes inside the bout (W397); absent otherwise"),
    ("gait_out_of_range", _ID, "true/false", "the bout's cadence_spm or speed_mps is ABOVE L95's walking range "
                                             "(leg-scaled, L148; bouts of 5+ strides; L195): running or short fast "
                                             "steps. Never true for a slow bout (a bout's speed includes its start, "
                                             "stop and turns): a filter on it keeps slow bouts; slow walking is the "
                                             "session's gait_out_of_range in summary.json / sessions.csv with L95's "
                                             "line (L248)"),
    ("n_cv_strides", "count", "integer", "the bout's strides among the session's CV strides (steady straight level "
                                         "forward, L104 / L188); 0 on the lower back (L212)"),
    ("stride_time_cv_pct", "%", "number", "foot: 100 x SD / mean of those strides' times, with 5 or more of them "
                                          "(L196's minimum); empty otherwise (L212)"),
    ("stride_length_cv_pct", "%", "number", "foot: the same of their lengths (L212); complete strides only, unlike "
                                            "stride_length_m"),
    # decision W350: the lower back's gait quality, bouts of 10+ strides; empty on a foot track and shorter bouts, and
    # without track --gait-quality (W352)
    ("hr_ap", _ID, "number", "lower back, 10+ strides, only with track --gait-quality (W352, opt-in): "
                             "anteroposterior harmonic ratio, even / odd of the first 20 "
                             "stride harmonics, mean over strides (Menz et al. 2003; W350)"),
    ("hr_v", _ID, "number", "lower back: the vertical harmonic ratio, even / odd (W350)"),
    ("hr_ml", _ID, "number", "lower back: the mediolateral harmonic ratio, odd / even (W350)"),
    ("step_regularity_v", _ID, "number", "lower back: peak of the vertical acceleration's unbiased autocorrelation "
                                         "near one step (Moe-Nilssen & Helbostad 2004; W350)"),
    ("stride_regularity_v", _ID, "number", "lower back: the same near one stride (W350)"),
    ("step_symmetry_v", _ID, "number", "lower back: step_regularity_v / stride_regularity_v; 1 = both steps alike "
                                       "(W350)"),
    ("step_regularity_ap", _ID, "number", "lower back: step regularity of the anteroposterior acceleration (W350)"),
    ("stride_regularity_ap", _ID, "number", "lower back: stride regularity of the anteroposterior acceleration "
                                            "(W350)"),
    ("step_symmetry_ap", _ID, "number", "lower back: step_regularity_ap / stride_regularity_ap (W350)"),
    *((f"rms_{axis}_mps2", "m/s^2", "number", f"lower back: RMS of the {name} acceleration, linearly detrended over "
                                              "the bout (W350)")
      for axis, name in (("ap", "anteroposterior"), ("ml", "mediolateral"), ("v", "vertical"))),
    ("rms_ml_ratio", _ID, "number", "lower back: rms_ml_mps2 over the RMS of the acceleration vector: sideways sway "
                                    "(Sekine et al. 2013; W350)"),
    *_clocks("start_s", "end_s"),
    ("visit_as_written", _ID, "text", "track-all's OUT/bouts.csv only: meta.json visit as written (C82)"),
    ("speed_m_s", "m/s", "number", "deprecated (E98): speed_mps under its old name, kept last until a later release"),
)

#: decision L200: a track's turns.csv, one row per turn of at least turn_count_min_deg (foot and lower back)
TURNS: tuple[Column, ...] = (
    ("turn", "index", "integer", "the turn's number in the session, from 1"),
    ("start_s", "s", "number", "where the turn's heading, each row's change spread over the row's span, has gone 5 % "
                               "of its angle (L208, L209), on the session's clock; a lower-back track's turn matched "
                               "by a turn of its yaw rate: that turn's start, last sample under 5 deg/s (L210, L211)"),
    ("end_s", "s", "number", "where that heading has gone 95 % of the angle (L208, L209); a lower-back turn matched by "
                             "a yaw-rate turn: its end, first sample under 5 deg/s after it (L210, L211)"),
    ("duration_s", "s", "number", "end_s - start_s; a lower-back turn timed by its yaw rate reads longer than its "
                                  "5-95 % turn: about +1 s on a 180 deg turn, +0.65 s on a 90 deg one (L346), +1.4 s "
                                  "on a 360 deg turn on the spot (W328: +1.40 s waist-pendulum, 20 simulated turns); a "
                                  "foot turn on the spot about +0.25 s (L371)"),
    ("angle_deg", "deg", "number", "signed heading change, + = left (counter-clockwise), as turn_count's (L104, L181); "
                                   "a lower-back turn matched by a yaw-rate turn: that turn's angle, the yaw rate "
                                   "integrated over it (W328; L231's whole turns before); a turn ends where the "
                                   "heading turns the other way (foot, L371) or between two opposite yaw-rate turns "
                                   "(lower back, W328)"),
    ("peak_rate_dps", "deg/s", "number", "largest rate of the turn's heading with each row's change spread over "
                                         "that row's span, the heading start_s / end_s are read on (L229; a "
                                         "foot turn's mean rate is never above it); a lower-back turn timed by its "
                                         "yaw rate (L210): that yaw-rate turn's peak, El-Gohary's 0.5 Hz low-passed "
                                         "|yaw rate| (L235, L236)"),
    ("n_rows", "count", "integer", "rows of steps.csv the turn spans; 0: a yaw-rate turn no step row holds: on the "
                                   "lower back a full turn on the spot whose steps were missed (L255 / L256: the "
                                   "rows' heading over it is on another branch), or any such turn with the option "
                                   "of L233; on a two-unit foot track a turn in a rest gap between strides (a turn "
                                   "on the spot without a stride of the tracked foot), timed by the lower back "
                                   "(L701, L702)"),
    ("bout", "index", "integer", "the bouts.csv bout holding the turn; empty outside every bout"),
    ("mean_rate_dps", "deg/s", "number", "the heading change from start_s to end_s / duration_s (L209); per unit "
                                         "(L229): a foot track's turn (5-95 % heading timing, L208) 90 % of "
                                         "|angle_deg|; a lower-back turn timed by its yaw rate (L210) all of "
                                         "|angle_deg| over that span, longer than a 5-95 % one, so it reads lower "
                                         "than a foot track's for the same turn (about 20 % under the 5-95 % "
                                         "mean rate, L346); empty for a turn of no duration"),
    ("carried", _ID, "true/false", "lower back: the turn is one the pelvis made seated or in a ride (W488: inside "
                                      "a seated span, a span of contacts W336 / W486 name a ride, or with the foot "
                                      "unit at rest), the seat's or the vehicle's, not the walker's; kept here, left "
                                      "out of turn_count, the turn medians and periods.csv's n_turns (L622); false on "
                                      "a foot track"),
    ("turn_steps", "count", "integer", "the steps of both feet inside the turn, the clinical steps per turn, unlike "
                                       "n_rows: lower back, its detected contacts (event_s) from start_s to end_s "
                                       "(W398); a foot track with a lower-back unit, that unit's contacts inside "
                                       "the turn widened to the waist's own yaw-rate turn; a foot alone, 2 x the "
                                       "foot's strides whose contact lies in the turn, an estimate (L749); empty "
                                       "without contact times (pdrlearn run's foot strides)"),
    ("turn_steps_source", _ID, "text", "what turn_steps counts (L749): waist (the lower back's "
                                                  "contacts) or foot_x2 (the foot's strides x 2, an estimate: the "
                                                  "other foot assumed to alternate); empty without a count"),
    *_clocks("start_s", "end_s"),
)

#: decision L277: a track's periods.csv (``track --per``), one row per period of the whole session's track
PERIODS: tuple[Column, ...] = (
    ("session", _ID, "text", "meta.json's session name (bouts.csv's key, L165)"),
    ("subject", _ID, "text", "meta.json's subject; empty when not given"),
    ("visit", _ID, "text", "meta.json's visit, empty when not given (C100); track-all's OUT/periods.csv: "
                           "sessions.csv's visit (C82)"),
    ("period", "index", "integer", "the period's number, from 1"),
    ("start_s", "s", "number", "the period's start on the session's clock (the recording's start + k x --per; "
                               "--per-align clock: the clock's whole periods, L299)"),
    ("end_s", "s", "number", "its end; the last period ends with the tracked unit's recording"),
    ("duration_s", "s", "number", "end_s - start_s"),
    ("partial", _ID, "true/false", "a period shorter than --per: the last one; with --per-align clock also the first "
                                   "(from the recording's start to the clock's next whole period, L299)"),
    ("distance_m", "m", "number", "distance of the steps whose middle lies in the period (L105's rule); the periods "
                                  "sum to the summary's distance_m (L278)"),
    ("n_steps", "count", "integer", "those steps (rows of steps.csv, as the summary's n_steps): strides of the "
                                    "tracked foot on a foot track, steps of both feet on the lower back "
                                    "(n_steps_counts)"),
    ("n_steps_counts", _ID, "text", "what n_steps counts: 'strides of the tracked foot' or 'steps of both feet' (the "
                                    "summary's, L103, L320)"),
    ("n_steps_both_feet", "count", "integer", "steps of both feet in the period, whatever the unit (L449): the lower "
                                              "back's steps; a foot track's 2 per stride of the tracked foot (gap rows "
                                              "left out; an estimate, as the summary's); sums to that"),
    ("median_stride_time_s", "s", "number", "median stride time of the period's steps, by the summary's default rule "
                                            "(L320); empty without a stride time (a streamed track, E51)"),
    ("median_cadence_spm", "steps/min", "number", "median cadence of the period's steps, by the summary's default "
                                                  "rule (L176, W225; L320)"),
    ("median_stride_length_m", "m", "number", "the period's median stride length, the summary's rule (foot: gap "
                                              "rows and impossible strides left out, C19; L340; lower back: two "
                                              "consecutive steps summed, W537)"),
    ("median_speed_mps", "m/s", "number", "the period's median per-stride speed, the summary's rule (L340)"),
    ("stride_time_cv_pct", "%", "number", "foot: the summary's stride-time CV on the period's steady straight level "
                                          "forward strides (L104, L340); empty under 10 of them or when withheld "
                                          "(L113)"),
    ("stride_length_cv_pct", "%", "number", "foot: the CV of the same strides' lengths (L212, L340); empty under 10"),
    ("n_cv_strides", "count", "integer", "foot: the period's strides the two CVs are computed over (L340); empty "
                                         "on the lower back"),
    ("time_walking_s", "s", "number", "the session's walking time inside the period; sums to walking_time_s (L275)"),
    ("time_between_steps_s", "s", "number", "first to last step of the period: neither walking nor no data "
                                            "(L275); with time_no_steps_s it sums to the summary's two"),
    ("time_no_steps_s", "s", "number", "before the period's first step and after its last (a stop across the "
                                       "period's edge is here in both periods, L275)"),
    ("time_no_data_s", "s", "number", "the tracked unit's data gaps over 1 s inside the period (L275)"),
    ("standing_time_s", "s", "number", "lower back: time standing in the period, outside walking and gaps (W222); "
                                       "the periods sum to the summary's; empty for a foot track and for `run` of "
                                       "a waist bundle (E145)"),
    ("sitting_time_s", "s", "number", "lower back: time seated in the period (W222); empty for a foot track and "
                                      "for `run` of a waist bundle (E145)"),
    ("lying_time_s", "s", "number", "lower back: time lying in the period (W222); empty for a foot track and for "
                                    "`run` of a waist bundle (E145)"),
    ("unknown_time_s", "s", "number", "lower back: the period's data gaps and time without a walking upright; with "
                                      "time_walking_s and the three postures it sums to duration_s (W222); "
                                      "empty for a foot track and for `run` of a waist bundle (E145)"),
    ("floors_up", "count", "integer", "storeys of the climbs (L127) whose last stair stride lies in the period; "
                                      "empty when the floors come from the altitude (L64)"),
    ("floors_down", "count", "integer", "the same, down"),
    ("ascent_m", "m", "number", "the summary's ascent_m rule on the trajectory inside the period (L467)"),
    ("descent_m", "m", "number", "the same, descent (L467)"),
    ("n_bouts", "count", "integer", "bouts.csv's bouts that start in the period (sums to n_bouts)"),
    ("n_turns", "count", "integer", "turns.csv's turns not marked carried (L622) that start in the period (sums to "
                                    "turn_count)"),
    ("n_backward_strides", "count", "integer", "foot: the summary's backward strides whose middle lies in the period "
                                               "(sums to n_backward_strides, L484); empty on the lower back"),
    ("n_side_strides", "count", "integer", "foot: the summary's side strides whose middle lies in the period (sums "
                                           "to n_side_strides, L484); empty on the lower back"),
    ("data_gap", _ID, "true/false", "time_no_data_s > 0: a data gap inside the period"),
    ("position_sigma_end_m", "m", "number", "the position's 1-sigma at the period's end (trajectory.csv pos_sigma_m, "
                                            "L128); empty for an aided track"),
    ("start_x_m", "m", "number", "the track's x (trajectory.csv) at the period's start: at the end of the last step "
                                 "distance_m counts before it (its middle before the start), at the first step's start "
                                 "when none is (L514, L528)"),
    ("start_y_m", "m", "number", "the track's y at the period's start (L514, L528)"),
    ("end_x_m", "m", "number", "the track's x at the period's end: at the end of the last step counted up to it, so "
                               "|(dx_m, dy_m)| <= distance_m (L514, L528)"),
    ("end_y_m", "m", "number", "the track's y at the period's end (L514, L528)"),
    ("dx_m", "m", "number", "end_x_m - start_x_m: the period's net displacement along x (distance_m is the path "
                            "length; L514)"),
    ("dy_m", "m", "number", "end_y_m - start_y_m (L514)"),
    ("n_sit_to_stand", "count", "integer", "lower back: sit-to-stand transfers (transfers.csv) starting in the "
                                           "period; empty on a foot track (W448)"),
    ("n_turns_left", "count", "integer", "the period's n_turns that turn left (turns.csv angle_deg > 0; L691)"),
    ("n_turns_right", "count", "integer", "the period's n_turns that turn right (angle_deg < 0); with n_turns_left "
                                          "it sums to n_turns (L691)"),
    ("net_rotation_deg", "deg", "number", "the signed sum of those turns' angle_deg, left + (a 360 deg spin "
                                          "reads 360, L690; L691); 0 without a turn"),
    ("median_stance_pct", "%", "number", "--toe-off only: the period's median stance share of the stride, the "
                                         "summary's rule (L73; L725); empty without toe-off columns"),
    ("n_steps_with_turns", "count", "integer", "n_steps + the steps of W331's stepless turns whose midpoint lies in "
                                               "the period (W603; sums to the summary's); empty on a foot track or "
                                               "where the step count is withheld (W476)"),
    ("distance_corridor_m", "m", "number", "--corridor on the lower back only: distance_m x the summary's "
                                           "walk_test_scale, the step lengths put on the corridor's scale (W563); "
                                           "the walked path, cone arcs included, so a little over the corridor's "
                                           "own per-minute distances"),
    ("speed_corridor_mps", "m/s", "number", "--corridor on the lower back only: distance_corridor_m / "
                                           "time_walking_s (W563); empty without walking"),
    *_clocks("start_s", "end_s"),
)

def _segments() -> tuple[Column, ...]:
    """Decision L619: segments.csv's columns, :func:`pdrlearn.track.segments.segment_columns`'s order: the leg's key,
    then periods.csv's totals (their meanings, each over the leg instead of the period)."""
    periods = {c[0]: c for c in PERIODS}
    own = {"segment": ("segment", "index", "integer", "the leg's number, from 1 (LEGS.csv's row order)"),
           "label": ("label", _ID, "text", "LEGS.csv's label (the leg's mode or place), empty when not given"),
           "start_s": ("start_s", "s", "number", "the leg's start on the session's clock (LEGS.csv's start_s, seconds "
                                                 "from the session's start as --window's)"),
           "end_s": ("end_s", "s", "number", "the leg's end (LEGS.csv's end_s); a leg holds its end unless the "
                                             "next leg starts there (L619)")}
    from pdrlearn.track.segments import segment_columns

    return (*(own.get(n) or periods[n] for n in segment_columns()), *_clocks("start_s", "end_s"))


#: decision L619: a track's segments.csv (``track --segments LEGS.csv``), one row per leg of the whole session's track
SEGMENTS: tuple[Column, ...] = _segments()

#: decision W182: a lower-back track's transfers.csv (a foot track writes none)
TRANSFERS: tuple[Column, ...] = (
    ("transfer", "index", "integer", "the transfer's number in the session, from 1"),
    ("kind", _ID, "text", "sit-to-stand (the pelvis rises 0.20 m or more) or stand-to-sit (it lowers as much); "
                          "sit-to-lie, stand-to-lie, lie-to-sit or lie-to-stand: the trunk's tilt crosses 60 deg "
                          "into or out of lying, the sit / stand side from the posture split (W245)"),
    ("start_s", "s", "number", "the trunk starts to flex (its tilt rate reaches 10 deg/s; a lying kind: to move "
                               "toward or away from lying), on the session's clock"),
    ("end_s", "s", "number", "the trunk is still again after straightening (a lying kind: after the tilt stops "
                             "moving at 10 deg/s)"),
    ("duration_s", "s", "number", "end_s - start_s"),
    ("peak_s", "s", "number", "the trunk's largest tilt from the walking upright (a lying kind: the tilt passes "
                              "60 deg)"),
    ("peak_tilt_deg", "deg", "number", "the largest tilt (W104's flexion events exceed 25 deg; a lying kind: in the "
                                       "movement)"),
    ("height_change_m", "m", "number", "the pelvis's height change from start_s to end_s (+ up)"),
    ("flag", _ID, "text", "why the row cannot be taken as read, else empty: 'not alternating' (the posture it comes "
                          "from is not the one the row before went to, or the one it goes to not the next's), "
                          "'walking on both sides' (walking contacts within 2 s before and after it); flagged rows "
                          "are still counted (W278)"),
    *_clocks("start_s", "end_s", "peak_s"),
)

#: decision W293: a lower-back track's tug_phases.csv (only with a tug_time_s)
TUG_PHASE_TABLE: tuple[Column, ...] = (
    ("phase", _ID, "text", "sit_to_stand, walk_out, turn, walk_back, turn_to_sit, stand_to_sit, in time order; a phase "
                           "the track cannot place has no row (turn_to_sit without a second turn, W307; the walks and "
                           "the turn without a turn)"),
    ("start_s", "s", "number", "sit_to_stand / stand_to_sit: its transfers.csv row's; walk_out: the first step "
                               "after the rise; turn, turn_to_sit: their turns.csv row's (turn_to_sit: else its "
                               "yaw-rate turn's, W307); walk_back: the turn's end"),
    ("end_s", "s", "number", "walk_out: the turn's start; walk_back: the turn-to-sit's start, else the last step "
                             "before the sit; the others: their row's end_s"),
    ("duration_s", "s", "number", "end_s - start_s; the phases do not tile the TUG (standing before the first step "
                                  "or before the sit is in none)"),
    *_clocks("start_s", "end_s"),
)

#: decision L524: a foot track's ten_m_walk_trials.csv (only with a timed 10 m walk)
TEN_M_WALK_TRIAL_TABLE: tuple[Column, ...] = (
    ("trial", "count", "integer", "1, 2, ... in time order: each walking bout long enough (acceleration zone + timed "
                                  "+ deceleration zone, 2 + 10 + 2 m or track --ten-m-walk's, L522), straight and "
                                  "level (L312, L313, L524)"),
    ("start_s", "s", "number", "when the path passes the end of the acceleration zone (the timed stretch's start)"),
    ("end_s", "s", "number", "when the path passes the end of the timed stretch"),
    ("time_s", "s", "number", "end_s - start_s (the first trial's is the summary's ten_m_walk_time_s)"),
    ("speed_mps", "m/s", "number", "the timed metres / time_s"),
    *_clocks("start_s", "end_s"),
)

#: decision W325: a lower-back track's tug_trials.csv (only with a TUG trial)
TUG_TRIAL_TABLE: tuple[Column, ...] = (
    ("trial", "count", "integer", "1, 2, ... in time order: each sit-to-stand directly followed by a stand-to-sit "
                                  "with walking between, seated before and after, neither flagged (W183's rule per "
                                  "segment, W325)"),
    ("start_s", "s", "number", "the trial's sit-to-stand's start (transfers.csv)"),
    ("end_s", "s", "number", "the trial's stand-to-sit's end (transfers.csv)"),
    ("tug_time_s", "s", "number", "end_s - start_s (W183's TUG time of this trial; a one-trial recording's "
                                  "summary tug_time_s)"),
    ("tug_sit_to_stand_s", "s", "number", "W293's phases cut on this trial (as tug_phases.csv; W307's yaw-rate "
                                          "turn-to-sit); empty for a phase the track cannot place"),
    ("tug_walk_out_s", "s", "number", "the trial's walk out (W293)"),
    ("tug_turn_s", "s", "number", "the trial's first turn (W293)"),
    ("tug_walk_back_s", "s", "number", "the trial's walk back (W293)"),
    ("tug_turn_to_sit_s", "s", "number", "the trial's turn-to-sit (W293, W307)"),
    ("tug_stand_to_sit_s", "s", "number", "the trial's stand-to-sit (W293)"),
    ("n_steps", "count", "integer", "steps of both feet from start_s to end_s: a lower-back track's steps.csv rows "
                                    "(turns on the spot hold none, W331); a foot + waist session's default track: "
                                    "2 x the foot's strides (W419); steps_source says which"),
    ("n_turns", "count", "integer", "turns.csv rows whose midpoint lies between the rise's end and the sit's start"),
    ("steps_source", _ID, "text", "the unit n_steps is counted on: foot (a foot + waist session's default track, "
                                  "W419) or waist (a lower-back track: misses the steps of turns on the spot)"),
    ("turns_source", _ID, "text", "the unit whose turns.csv times the turns and n_turns: foot or waist (W419; the "
                                  "lower back's turns read about 1 s longer, W293)"),
    *_clocks("start_s", "end_s"),
)

#: decision W213: a track's freezes.csv (foot or lower back: the tracked unit's freeze index)
FREEZES: tuple[Column, ...] = (
    ("freeze", "index", "integer", "the episode's number in the session, from 1"),
    ("start_s", "s", "number", "the first freezing window's centre less 0.25 s, on the session's clock"),
    ("end_s", "s", "number", "the last freezing window's centre plus 0.25 s"),
    ("duration_s", "s", "number", "end_s - start_s"),
    ("peak_fi", "ratio", "number", "the largest freeze index (3-8 Hz / 0.5-3 Hz power, Moore 2008) of its 4 s "
                                   "windows"),
    *_clocks("start_s", "end_s"),
)

#: decision W417: a track's flights.csv, one row per flight phase of either unit (W363's test, W409's rule, W416)
FLIGHTS: tuple[Column, ...] = (
    ("unit", _ID, "text", "foot or waist: the accelerometer (fAccelerometer.csv / wAccelerometer.csv) that read it"),
    ("start_s", "s", "number", "its first sample under 0.3 g, on the session's clock"),
    ("end_s", "s", "number", "its last sample under 0.3 g plus one sample interval"),
    ("flight_time_s", "s", "number", "end_s - start_s (first to last low sample 0.1 s or more apart, W409)"),
    ("jump_height_m", "m", "number", "g x flight_time_s^2 / 8, the flight-time method (W417): assumes take-off and "
                                     "landing in the same posture and the unit in free fall from take-off to "
                                     "touch-down; a landing on bent knees overstates it; the sample interval limits "
                                     "flight_time_s (+-0.05 s at 20 Hz: +-0.05 m at a 0.4 s flight)"),
    *_clocks("start_s", "end_s"),
)

#: decision L300: steps.csv's grade column, foot and lower back
_GRADE_PCT: Column = ("grade_pct", "%", "number", "100 x dz_m / |length_m|, + up (L300); empty unless the altitude "
                      "is barometric (grade_source), on a row under 0.2 m, a gap row or an impossible stride")

#: a lower-back track's steps.csv (``TrackResult.steps`` of waist-pendulum / waist-pll), one row per contact of either
#: foot; a foot track's steps.csv (strides of one foot) has other columns
WAIST_STEPS: tuple[Column, ...] = (
    ("start_s", "s", "number", "the contact (initial contact), on the session's clock"),
    ("end_s", "s", "number", "the next contact of the walking sequence; = start_s when the contact closes it"),
    ("event_s", "s", "number", "the contact (= start_s)"),
    ("unit", _ID, "text", "the unit tracked: waist"),
    ("confidence", "fraction", "number", "1 for a step to a next contact, 0.5 for a sequence-closing contact"),
    ("fc_s", "s", "number", "the final contact after it (waist-pendulum); empty for the PLL's steps"),
    ("has_next", _ID, "true/false", "a next contact follows within 1.5 s: the row is a step with a length"),
    ("still_before_s", "s", "number", "seconds the pelvis was still (L296's still samples) since the contact before: "
                                      "standing, which the pause rule gives no turn (L372)"),
    ("h_m", "m", "number", "waist-pendulum: the pelvis's vertical excursion during the step (seed 003)"),
    ("g_m", "m", "number", "waist-pendulum: the pendulum chord 2 sqrt(2 L h - h^2) before K and F"),
    ("merged", _ID, "true/false", "waist-pendulum: a fragment whose length its neighbour carries (W27)"),
    ("pause_factor", "fraction", "number", "waist-pendulum, offline and realtime (pause_steps, default since W134, "
                                           "realtime W165): the factor the step's length was scaled by (W111, W122, "
                                           "W134)"),
    ("pivot_factor", "fraction", "number", "waist, option pivot_steps (W150): the share of the step's length kept by "
                                           "the pivot cap (1 unless the pelvis turned 45 deg or more in the step)"),
    ("cadence_factor", "fraction", "number", "waist-pendulum, option cadence_law (W240): the calibrated step's factor "
                                             "sqrt(SL(f) / SL(f_cal)) of seed 000's walking line; with \"steady\" "
                                             "(W261) 1 on a step outside steady walking"),
    ("length_m", "m", "number", "step length (0 for a sequence-closing contact): the pelvis's advance from this "
                                "contact to the next, valid summed or as a walk's typical step; NOT valid as a "
                                "per-side step length - grouped by side it does not give each leg's step (not "
                                "validated; a simulated walker stepping 0.604 / 0.749 m onto the left / right foot "
                                "read 0.602 / 0.564 m by side; W251)"),
    ("gap_bridged_m", "m", "number", "waist-pendulum / waist-pll offline, option gap_bridge: the metres of the "
                                     "closing contact's row across a data gap of at most 5 s inside walking, walked "
                                     "at the mean pace of the 3 steps either side (its end_s the next contact; W625); "
                                     "0 elsewhere, absent when no gap is bridged"),
    ("frequency_hz", "Hz", "number", "1 / the step's duration"),
    ("dyaw_rad", "rad", "number", "vertical-gyro rotation during the step"),
    ("heading_rad", "rad", "number", "the step's heading (ENU, counter-clockwise from east)"),
    ("turning", _ID, "integer", "gyro heading: 1 = a turning stride (seed 003's classifier), else 0"),
    ("mean_rate_rps", "rad/s", "number", "the stride's mean vertical rate (MRZ, seed 003 sec. 3.3)"),
    ("stairs", _ID, "true/false", "the barometric altitude changes by 0.1 m/s or more around the step (W91)"),
    ("side", _ID, "text", "left / right foot of the contact, empty when undecided: the pelvis's lateral velocity at "
                          "it (W20, W129; 99 % agree with INDIP's foot where decided); empty with --realtime; "
                          "`run WAIST_BUNDLE --sides`: the streamed contact's causal side (W138, E103, E110)"),
    ("climb", _ID, "true/false", "the step is inside a barometric climb of 1.5 m or more (W108: the steps its \"on "
                                  "stairs\" warning counts); with the PARAMS.json option `climb_veto` true, no ramp "
                                  "and no ramp climb is made of such steps (L314; opt-in since L330: a ramp walked at "
                                  "a normal pace is such a climb)"),
    ("ride", _ID, "text", "the kind of the ride in the standstill before the step: lift, escalator or other (L376; "
                          "a pause_dz_m of 1.5 m or more, L375); empty: none; rides.csv has one row each"),
    ("dz_m", "m", "number", "barometric altitude change over the step (W89; 0 without a usable barometer)"),
    ("pause_dz_m", "m", "number", "barometric altitude change while standing before the step (a lift ride; W158; "
                                  "of a pause over 30 s only the 1.5 m within 30 s rides, W231), "
                                  "0 inside a walking sequence"),
    _GRADE_PCT,
    ("transfer_dz_m", "m", "number", "barometric altitude change inside a sit-to-stand or stand-to-sit (a trunk "
                                     "flexion over 25 deg, W104) since the previous row: the transfer's, not in "
                                     "z, ascent or floors (W174)"),
)

#: decision E137: a foot track's steps.csv (``pdrlearn track`` / ``run`` of a foot recording, plasys), one row per
#: stride of the tracked foot; docs/localization.md's "steps.csv columns" in full
FOOT_STEPS: tuple[Column, ...] = (
    ("start_s", "s", "number", "the stride's start: the middle of the foot's rest before it (at most 0.3 s into a "
                               "longer rest), on the session's clock"),
    ("end_s", "s", "number", "the stride's end: the middle of the rest after it"),
    ("event_s", "s", "number", "the step detector's initial contact (IC) in the stride (--streaming: empty, or the "
                               "streamed IC with --contacts; E49-E51)"),
    ("length_m", "m", "number", "horizontal distance the stride moved after the class rules; negative exactly when "
                                "the stride travelled backward (backward_travel: raw_length_m < 0, no side step nor "
                                "turn on the spot), whatever the direction class (L654, amending L65; C137, L578); 0 "
                                "for a gap row or an impossible stride"),
    ("raw_length_m", "m", "number", "the estimate before the rules, signed with the foot's forward axis at the "
                                    "stride start (< 0: it moved backwards in that frame); a stride turning 30 deg or "
                                    "more against its mid-stride facing (< 0: within 60 deg of straight back, L692)"),
    ("heading_rad", "rad", "number", "the direction the stride is placed along (ENU, 0 = east or the start "
                                     "direction, counter-clockwise)"),
    ("dz_m", "m", "number", "the stride's height change"),
    ("raw_dz_m", "m", "number", "offline: the stride's integrated height change before L39's level rule or a "
                                "terrain class (a 1:12 ramp's ~0.09 m stride is 0 in dz_m); empty on a gap row or an "
                                "impossible stride; gait's ramps keyword reads it (L775, off by default)"),
    ("pause_dz_m", "m", "number", "with a waist barometer (wBarometer.csv): its ride of 1.5 m or more in the "
                                  "standstill before the stride (L378, W231's rule), else 0; not in dz_m nor z, "
                                  "counted in the floors (L375)"),
    ("ride", _ID, "text", "with a waist barometer: that ride's kind, lift / escalator / other / vehicle (L376, "
                          "L378, L616); without one (L624): vehicle only, from the foot's vibration, and no "
                          "pause_dz_m; empty: none"),
    _GRADE_PCT,
    ("terrain", _ID, "text", "M3's terrain class (empty without a model; L18)"),
    ("terrain_dz", _ID, "text", "offline: up / down / flat from dz_m by L39's 0.10 m, with or without a model "
                                "(not a class; empty on a gap row; L424)"),
    ("direction", _ID, "text", "M3's direction class, the model's (empty without a model; L224); on a side step "
                               "(sideways) a guess, its travel says the side (C137); on a stride turning on the "
                               "spot (travel turn) too (L578)"),
    ("backward_travel", _ID, "true/false", "the stride travelled backward, as n_backward_strides counts (L203, "
                                           "L224)"),
    ("travel", _ID, "text", "the stride's travel direction from the foot's facing (L412): forward, backward (as "
                            "backward_travel), left / right (a side-stepping run's stride, sideways; streamed by "
                            "the sign of lateral_m since E319, side without it), turn (the foot turned 30 deg or "
                            "more on a chord under 0.6 m: on the spot, "
                            "L692), empty (a gap, impossible or under "
                            "0.15 m); model-free, unlike direction"),
    ("length_class", _ID, "text", "M3's length class (empty without a model)"),
    ("confidence", "fraction", "number", "the class confidence (1 without a model)"),
    ("p_<task>_<class>", "fraction", "number", "with a model: the class probabilities (one column each)"),
    ("ood_*", _ID, "number", "with a model: the stride's out-of-training-range scores (C16)"),
    ("method_<task>", _ID, "text", "with a model: the classifier (method/unit, e.g. nn/combined) that classed the "
                                   "stride, none when none could; offline since L583, streamed before"),
    ("speed_out_of_range", _ID, "true/false", "offline with a model trained since L474: speed_mps more than 10 % "
                                              "outside the model's training strides' 1-99 % speeds (its classes "
                                              "can be wrong with a high confidence; L474); since L481 only level, "
                                              "straight, forward strides of a continuous walk are compared (a "
                                              "start, a stop, a turn, a stair stride is false)"),
    ("stride_time_out_of_range", _ID, "true/false", "offline with a model trained since C191: stride_time_s more "
                                                    "than 10 % outside the model's training strides' 1-99 % stride "
                                                    "times (a tempo the calibration did not walk; the same strides "
                                                    "as speed_out_of_range are compared; C191)"),
    ("window_start_s", "s", "number", "with a model: the window the classes come from (L38)"),
    ("window_end_s", "s", "number", "the same window's end"),
    ("sideways", _ID, "true/false", "a side step of L219's sideways run: no steady or straight stride (L228); a "
                                    "streamed track (track --streaming, run, Tracker) flags a run from its third "
                                    "stride, as decided live (L243)"),
    ("lateral_m", "m", "number", "streamed (track --streaming, run, the lean runtime, Tracker): the stride's "
                                 "displacement to the left of the foot's facing at its start, negative to the right "
                                 "(empty on a gap row); a side step's travel left / right by its sign (E319)"),
    ("steady", _ID, "true/false", "a CV stride: n_cv_strides counts these rows and stride_time_cv_pct / "
                                  "stride_length_cv_pct are the CVs (SD with n - 1) of their stride_time_s / "
                                  "|length_m| (steady straight level forward, L104; --steady-trim's bout ends out, "
                                  "L415)"),
    ("in_freeze", _ID, "true/false", "when the freeze index ran: the stride's contact (event_s) lies inside an "
                                     "episode of freezes.csv (W397; with the lower back's W396 unreliable episodes "
                                     "too); absent otherwise"),
    ("contact_source", _ID, "text", "a stitched track only (L365's partial fallback): force or imu, the detector "
                                    "that timed the stride's IC (L405)"),
    ("pivot_rad", "rad", "number", "streamed tracks (--streaming, run): the heading change not in the stride's own "
                                   "turn: the turn between strides, and on a foot + lower-back stride the lower "
                                   "back's lag behind the foot's turn (E51, L106, L699)"),
    ("stride_time_s", "s", "number", "IC to IC: this event_s minus the previous stride's (empty at the first "
                                     "stride, after a stop over 3 s, a gap row, or a missing IC; L66, L80)"),
    ("cadence_spm", "steps/min", "number", "120 / stride_time_s (two steps per stride of one foot)"),
    ("speed_mps", "m/s", "number", "|length_m| / stride_time_s: the first stride after a stop under 3 s reads low "
                                   "(its IC-to-IC holds the stop) and the first stride has none; the opt-in "
                                   "gait.add_gait_columns(rest_speed=True) takes the shorter of its own and the "
                                   "next stride's time (L509, L512)"),
    ("turn_angle_rad", "rad", "number", "the foot's own heading change from rest to rest over the stride, left + "
                                        "(not wrapped: a spin of 180-360 deg inside one stride is itself, L690)"),
    ("tc_s", "s", "number", "--toe-off only: the toe-off inside the stride, the one ending the stance of the contact "
                            "at cycle_start_s (foot gyroscope push-off peak; L73); against gaitmap's mocap ~21 ms "
                            "early (L672)"),
    ("stance_time_s", "s", "number", "--toe-off only: the stance of the contact at cycle_start_s (the previous "
                                     "row's event_s), tc_s - cycle_start_s - not of this row's event_s (L672); "
                                     "against gaitmap's mocap (straight strides) -36.9 / -42.8 ms left / right"),
    ("swing_time_s", "s", "number", "--toe-off only: tc_s to this row's event_s (the next IC); against gaitmap's "
                                    "mocap +36.3 / +39.9 ms left / right (L672)"),
    ("stance_pct", "%", "number", "--toe-off only: 100 x stance_time_s / stride_time_s; against gaitmap's mocap "
                                  "-3.3 / -3.8 points left / right (L672); it moves with the unit's height and place "
                                  "on the foot, not its tilt (simulated: +2 cm -0.53 points; L720, "
                                  "docs/robustness.md)"),
    ("cycle_start_s", "s", "number", "--toe-off only: the IC opening the gait cycle stance_time_s / swing_time_s "
                                     "split, event_s - stride_time_s (the previous row's event_s; empty without a "
                                     "stride time): pair a walkway's footfall (heel strike) with this, not event_s "
                                     "(L672)"),
    ("max_sensor_lift_m", "m", "number", "offline foot track: the sensor's highest point above the line joining its "
                                         "two rests (gaitmap's max_sensor_lift on level ground; L421): the unit's "
                                         "own lift, so a higher or farther-forward mount reads another value for "
                                         "the same foot motion; --reference-point heel leaves it as it is and adds "
                                         "max_heel_lift_m (L721)"),
    ("min_toe_clearance_m", "m", "number", "offline foot track: the minimum toe clearance - the toe point's (the "
                                           "sensor + R(t) x toe_offset_m forward, 0.14 m unless --params sets it) "
                                           "lowest height above the line joining its rests after its first peak of "
                                           "the swing, up to event_s (Mariani et al. 2012; L795)"),
    ("max_heel_lift_m", "m", "number", "offline foot track with --reference-point heel: the heel contact point's "
                                       "highest point above the line joining its two rests (L22's lever arm from "
                                       "the recording; the same for any mount of the unit; L721)"),
    ("ic_angle_deg", "deg", "number", "offline foot track: the sole angle at event_s, + toes up, 0 at the starting "
                                      "rest (gaitmap's ic_angle; L421)"),
    ("tc_angle_deg", "deg", "number", "offline foot track with a toe-off (--toe-off): the sole angle at tc_s "
                                      "(gaitmap's tc_angle; L421)"),
    ("contact", _ID, "text", "offline foot track: the contact type from ic_angle_deg - forefoot below -3 deg "
                             "(toes down: a toe walker), heel above +3 deg (the heel rocker), flat in between "
                             "(L756)"),
    ("impossible", _ID, "true/false", "the last-line guard (L94) moved the stride 0 m: no gait values (L97)"),
    ("trunk_pause_s", "s", "number", "offline, with the lower-back unit: the pause before the stride, its time "
                                     "from the previous stride's start beyond the walker's stride (two of the lower "
                                     "back's median contact intervals, or the foot's median movement window when "
                                     "shorter) when 1 s or more, else 0 (n_pauses counts these; the stride is left "
                                     "out of the median cadence; L687); absent where the lower back's contacts are "
                                     "too dense to judge (the foot's own rule)"),
    ("gap_s", "s", "number", "the longest foot-data gap inside the stride; > 0: a 0 m gap row (L67)"),
    ("unit", _ID, "text", "the unit tracked: foot"),
    ("x", "m", "number", "pdrlearn run: the position east at the stride's end"),
    ("y", "m", "number", "pdrlearn run: the position north"),
    ("z", "m", "number", "pdrlearn run: the height"),
    ("ref_match", "index", "integer", "where the session labels stride lengths (E135; or toe-offs on a --toe-off "
                                      "track, D52): the labelled stride paired "
                                      "with this row, its row in the session's steps.csv from 0; empty: unpaired"),
    ("ref_length_m", "m", "number", "that labelled stride's length_m"),
    ("ref_stride_time_s", "s", "number", "its stride time: ic - pre_ic, or the IC of the labelled stride ending "
                                         "where it starts (E135); empty otherwise, and on ref_composed rows (steps "
                                         "98: the labelled stride spans the tiles; so are the ref_tc_s ... columns)"),
    ("ref_composed", _ID, "true/false", "the row is one of two or more tracked rows tiling one labelled stride"),
    ("pair_length_m", "m", "number", "the pair's estimated length: |length_m|, or the tiles' vector sum on each "
                                     "tile; stride_length_mae_* = these pairs, one per ref_match (L252)"),
    ("ref_tc_s", "s", "number", "--toe-off, labels with tc_ms (D52): the paired labelled stride's toe-off (between its "
                                "pre_ic and ic); without labelled lengths ref_match / ref_stride_time_s come from "
                                "these pairs"),
    ("ref_stance_time_s", "s", "number", "--toe-off, labels with tc_ms: ref_tc_s - the labelled stride's opening IC "
                                         "(pre_ic), beside stance_time_s (D52)"),
    ("ref_swing_time_s", "s", "number", "--toe-off, labels with tc_ms: the labelled ic - ref_tc_s, beside "
                                        "swing_time_s (D52)"),
    ("ref_stance_pct", "%", "number", "--toe-off, labels with tc_ms: 100 x ref_stance_time_s / ref_stride_time_s "
                                      "(D52)"),
)

#: decision C110: ``pdrlearn gait-all``'s gait_pairs.csv, one row per visit folder
GAIT_PAIRS: tuple[Column, ...] = (
    ("path", _ID, "text", "the visit folder relative to ROOT (the pooled gait tables' path)"),
    ("status", _ID, "text", "ok (paired and measured), failed (gait refused the pair) or no_pair (not one left "
                            "and one right foot session by meta.json foot)"),
    ("reason", _ID, "text", "a failed or no_pair row's one line; empty when ok"),
    ("session_left", _ID, "text", "as gait_steps.csv (C109); empty unless ok"),
    ("session_right", _ID, "text", "as gait_steps.csv (C109)"),
    ("subject", _ID, "text", "as gait_steps.csv (C109)"),
    ("visit", _ID, "text", "as gait_steps.csv (C109)"),
    ("n_bouts", "count", "integer", "the pair's walking bouts: its rows of gait_bouts.csv"),
    ("n_steps", "count", "integer", "the pair's steps of both feet: its rows of gait_steps.csv"),
    ("clock_right_minus_left_s", "s", "number", "the right session's absolute start minus the left's when both "
                                                "were imported from absolute timestamps and aligned on them (L537, "
                                                "gait_summary.json clock_alignment); empty: paired on their t = 0"),
    ("warnings", _ID, "text", "the pair's warning lines as gait_summary.json's warnings (each foot's track lines "
                              "prefixed `left foot:` / `right foot:`, L461), ` | `-joined; empty when none"),
)


#: cohort C242: gait-all's gait_changes_summary.csv, changes_summary.csv's columns (no test) of gait_changes.csv
GAIT_CHANGES_SUMMARY: tuple[Column, ...] = tuple(c for c in CHANGES_SUMMARY if c[0] != "test")


def _pair(name: str, unit: str, what: str) -> tuple[Column, ...]:
    """Decision L287: a left / right measure of ``pdrlearn gait`` and its two asymmetry columns (L259)."""
    return ((f"{name}_left", unit, "number", f"the left foot's mean {what}"),
            (f"{name}_right", unit, "number", f"the right foot's mean {what}"),
            (f"{name}_si_pct", "%", "number", "symmetry index of the two means, 100 x abs(L - R) / (0.5 x (L + R)) "
                                              "(Robinson 1987; L259)"),
            (f"{name}_ratio", "ratio", "number", "left / right (Patterson et al. 2010; L259)"))


#: decision C109: the id columns leading each of ``pdrlearn gait``'s tables
_GAIT_IDS: tuple[Column, ...] = (
    ("path", _ID, "text", "gait-all only: the visit folder relative to ROOT (gait_pairs.csv's key; C110)"),
    ("session_left", _ID, "text", "the left foot's session name (meta.json session, else its folder; C109)"),
    ("session_right", _ID, "text", "the right foot's session name (C109)"),
    ("subject", _ID, "text", "meta.json subject of the two feet (as track-all's; both, ; -separated, when they "
                             "differ; empty when not given; C109)"),
    ("visit", _ID, "text", "meta.json visit of the two feet, as written (C109)"),
)
_FOOT: Column = ("foot", _ID, "text", "= side: strides.csv's name for it (C109; side kept for existing readers)")

#: ``pdrlearn gait``'s gait_steps.csv (decisions L259, L284, L287): one row per step of the merged contacts
GAIT_STEPS: tuple[Column, ...] = (
    *_GAIT_IDS,
    ("side", _ID, "text", "the foot the step lands on (left / right)"),
    _FOOT,
    ("bout", "index", "integer", "the walking bout of the pair (L261), from 1"),
    ("start_s", "s", "number", "the other foot's initial contact that starts the step, on the pair's clock"),
    ("ic_s", "s", "number", "the landing foot's initial contact that ends it"),
    ("step_time_s", "s", "number", "ic_s - start_s (L259)"),
    ("swing_time_s", "s", "number", "the landing foot's toe-off before ic_s to ic_s, one unit's clock (L284); "
                                    "empty without a toe-off"),
    ("step_length_m", "m", "number", "the two feet's tracked rest positions at start_s and ic_s differenced along "
                                     "the walking direction (L310); empty in a turn, off the walk's first axis, at "
                                     "the closing step and for labelled contacts"),
    ("contact_source", _ID, "text", "the detector that timed the landing foot's contacts (steps 72): force "
                                    "(accel-force), imu (the accelerometer detector) or force+imu (a stitched track, "
                                    "L405); both feet imu when only one had force sensors or with --ignore-force; "
                                    "also gait_summary.json's contact_source {left, right}"),
    ("kind", _ID, "text", "level, stairs_up, stairs_down, turn, start_stop or backward: the kind of the two strides "
                          "into start_s and ic_s (a stair stride, |dz| >= 0.10 m, over a turn of 15 deg or more over a "
                          "bout's first or last contact over a stride travelling backward, L203 / L746; L538); the "
                          "walk's headline is its level steps' "
                          "(gait_summary.json walk headline_steps), each kind's in by_kind"),
)
#: ``pdrlearn gait``'s gait_cycles.csv (decisions L262, L287): one row per gait cycle of either foot
GAIT_CYCLES: tuple[Column, ...] = (
    *_GAIT_IDS,
    ("side", _ID, "text", "the foot whose cycle it is (its IC to its next IC)"),
    _FOOT,
    ("bout", "index", "integer", "the walking bout of the pair (L261)"),
    ("start_s", "s", "number", "the cycle's first initial contact"),
    ("end_s", "s", "number", "the foot's next initial contact"),
    ("stride_time_s", "s", "number", "end_s - start_s"),
    ("stance_time_s", "s", "number", "the foot's toe-off inside the cycle - start_s, one unit's clock (L327); empty "
                                     "without a toe-off"),
    ("double_support_pct", "%", "number", "both double-support periods of the cycle, % of it (L262; reads low from "
                                          "foot units, L285, by gait_summary.json reason's points of this walk's "
                                          "cycle; no known sign for IMU-only contacts under a 0.95 s cycle, L703); "
                                          "0 where a toe-off falls on the other foot's contact (L736); empty "
                                          "without both toe-offs or with a flight (L729)"),
    ("single_support_pct", "%", "number", "the other foot's swing, % of the cycle (L262)"),
    ("flight_time_s", "s", "number", "the time with neither foot on the ground in the cycle: both of its flights "
                                     "(a toe-off before the other foot's contact: a loss of contact, running, or a "
                                     "clock offset between the units; L729) summed - two steps' worth; per step: "
                                     "half (C268); 0 in walking order, empty without both toe-offs"),
    ("flight_after", _ID, "text", "the foot whose toe-off started the cycle's flight, or both (flights after one "
                                  "foot's only: a clock offset's pattern; L729); empty without a flight"),
    ("kind", _ID, "text", "as gait_steps.csv's kind, of the cycle's two contacts after start_s (L538)"),
)
#: ``pdrlearn gait``'s gait_bouts.csv (decisions L259-L262, L284, L287): one row per walking bout of the pair; the same
#: keys are gait_summary.json's ``walk``
GAIT_BOUTS: tuple[Column, ...] = (
    *_GAIT_IDS,
    ("bout", "index", "integer", "the walking bout of the pair (L261), from 1"),
    ("start_s", "s", "number", "its first initial contact (either foot)"),
    ("end_s", "s", "number", "its last initial contact"),
    ("n_steps_left", "count", "integer", "steps landing on the left foot"),
    ("n_steps_right", "count", "integer", "steps landing on the right foot"),
    *_pair("step_time_s", "s", "step time (the other foot's IC to this foot's)"),
    *_pair("stride_time_s", "s", "stride time (IC to IC, alternating cycles)"),
    *_pair("stride_length_m", "m", "stride length (the foot track's length_m)"),
    *_pair("swing_time_s", "s", "swing time (toe-off to IC, one unit's clock; L284)"),
    *_pair("stance_time_s", "s", "stance time (IC to toe-off, one unit's clock; L327)"),
    *_pair("step_length_m", "m", "step length (the other foot's contact to this foot's, along the walk; L310)"),
    ("n_step_lengths", "count", "integer", "steps with a step_length_m (L310)"),
    ("step_length_scale_pct", "%", "number", "gait_summary.json walk only: the left track's length scale against "
                                             "the right's that the closing step implied, taken out (L310); empty "
                                             "without a closing step"),
    ("step_length_passes", "count", "integer", "gait_summary.json walk only: the passes of a walk with turns whose "
                                               "step lengths were re-anchored at their own closing steps (L760); "
                                               "empty for a one-pass walk (L310's scale)"),
    ("step_length_si_drift_pct", "%", "number", "gait_summary.json walk only, with bilateral_gait(si_drift=True) "
                                                "(L761, not adopted): the points the step-length symmetry index may "
                                                "be off by from the two foot tracks' drift"),
    ("si_withheld", _ID, "text", "why this bout's (in gait_summary.json's walk: the walk's) symmetry indices and "
                                 "ratios are empty (fewer than 10 steps on a side, L461); empty when given"),
    ("clock_offset_s", "s", "number", "((left step - left swing) - (right step - right swing)) / 2: the left clock's "
                                      "offset the steps imply, plus half the walker's own double-support imbalance "
                                      "(L284; > 0 = the left unit's times late)"),
    *((f"{a}_{s}", "deg", "number", f"gait_summary.json walk only, foot tracks: the {s} foot's median sole angle "
       f"{what} (+ toes up) over the headline's steps (steps.csv {a}, L421; C244)")
      for a, what in (("ic_angle_deg", "at its contact"), ("tc_angle_deg", "at the toe-off before it"))
      for s in ("left", "right")),
    *((f"min_toe_clearance_m_{s}", "m", "number", f"gait_summary.json walk only, foot tracks: the {s} foot's "
       "median minimum toe clearance over the headline's steps (steps.csv min_toe_clearance_m, L795)")
      for s in ("left", "right")),
    ("toe_clearance_lower", _ID, "text", "gait_summary.json walk only: left / right, the side whose median toe "
                                         "clearance is clearly lower (at least 0.005 m below the other's, L795); "
                                         "empty otherwise"),
    ("impact_sharpness_left", "m/s^3", "number", "gait_summary.json walk only, foot tracks: the left foot's median "
                                                 "largest |d|a|/dt| within 0.1 s of its contacts (L318)"),
    ("impact_sharpness_right", "m/s^3", "number", "gait_summary.json walk only: the same of the right foot; over 3 x "
                                                  "apart, the feet's contacts are not comparable (L318)"),
    ("n_support_cycles", "count", "integer", "cycles with a double support, 0 % counted (L736); with "
                                             "n_flight_cycles every cycle with both toe-offs"),
    ("n_flight_cycles", "count", "integer", "cycles with a flight: a toe-off before the other foot's contact (a loss "
                                            "of contact, or a clock offset; no double support; L729)"),
    ("flight_time_s", "s", "number", "the mean flight time per gait cycle of those cycles, each cycle's two "
                                     "flights summed (gait_cycles.csv's flight_time_s; L729, C268); empty without "
                                     "one"),
    ("step_flight_time_s", "s", "number", "the mean flight time per step: half of flight_time_s (a gait cycle holds "
                                          "two steps; what runners call flight time; C268); empty without one"),
    ("double_support_pct", "%", "number", "mean double support, % of the gait cycle (L262; reads low, L285; by how "
                                          "much in this walk: reason, L703)"),
    *_pair("single_support_pct", "%", "single support (the other foot's swing), % of the gait cycle (L262)"),
    ("distance_m", "m", "number", "the mean of the two feet's summed stride lengths, every step of the bout (L539)"),
    ("walking_time_s", "s", "number", "the mean of the two feet's summed stride times, rest to rest (L539)"),
    ("gait_speed_mps", "m/s", "number", "distance_m / walking_time_s (L539)"),
    ("cadence_spm", "steps/min", "number", "60 x the bout's steps (both feet) / their summed step times (L539)"),
    ("headline_steps", _ID, "text", "gait_summary.json walk only: level (the measures above the pace are of the "
                                    "walk's level straight steps, gait_steps.csv kind level; under 10 a side: "
                                    "their indices withheld, L461) or all (under 3 level straight steps on a side, "
                                    "L608); a "
                                    "bout's measures take the walk's choice (L538)"),
    ("n_steps_all_left", "count", "integer", "gait_summary.json walk only: every step landing on the left foot, "
                                             "of any kind (L538)"),
    ("n_steps_all_right", "count", "integer", "gait_summary.json walk only: the same on the right foot (L538)"),
)


#: decision L301: ``ramps.csv`` (``track`` / ``run``), one row per ramp: runs of consistent grade and their landings
RAMPS: tuple[Column, ...] = (
    ("path", _ID, "text", "track-all's OUT/ramps.csv only: the session's path, sessions.csv's key (L572)"),
    ("visit", _ID, "text", "track-all's OUT/ramps.csv only: sessions.csv's visit (C82; L572)"),
    ("ramp", "index", "integer", "the ramp's number, from 1 in walking order"),
    ("start_s", "s", "number", "its first row's start_s"),
    ("end_s", "s", "number", "its last row's end_s"),
    ("direction", _ID, "text", "up or down"),
    ("n_runs", "count", "integer", "runs of 2 m or more whose rows' grade is 3 % to the stair grade (20 %; a "
                                   "foot track's --stair-grade, L301, L469) of one sign"),
    ("landings", "count", "integer", "level stretches of at most 3.5 m between two runs (n_runs - 1); a single "
                                     "stride reading under 3 % inside a steady slope counts as one"),
    ("horizontal_run_m", "m", "number", "horizontal length of the runs (landings left out)"),
    ("landing_m", "m", "number", "horizontal length of the landings"),
    ("along_slope_m", "m", "number", "length of the runs along the surface, sum of sqrt(length^2 + dz^2)"),
    ("rise_m", "m", "number", "the runs' height change (signed)"),
    ("mean_grade_pct", "%", "number", "100 x rise_m / horizontal_run_m"),
    ("max_run_grade_pct", "%", "number", "the steepest run's own mean grade"),
    ("n_steps", "count", "integer", "rows of steps.csv from the first run's first to the last run's last: on a foot "
                                    "track strides of the tracked foot (one foot: about half as many as bouts.csv's "
                                    "n_steps, which counts both feet, L449), on the lower back steps of both feet "
                                    "(C186)"),
    ("duration_s", "s", "number", "end_s - start_s (L467)"),
    ("speed_mps", "m/s", "number", "along_slope_m over duration_s: the runs' length along the surface over the "
                                   "ramp's time, landings' time included (L467)"),
    ("max_run_rise_m", "m", "number", "the largest rise of one run (signed; L569)"),
    ("over_1_12", _ID, "true/false", "the steepest run's grade |max_run_grade_pct| is over 1:12 = 8.33 % (ADA 2010 "
                                     "sec. 405.2; L569); a grade read 0.5-1 point off can decide it"),
    ("over_1_20", _ID, "true/false", "|max_run_grade_pct| is over 1:20 = 5 % (steeper than a walking surface, ADA "
                                     "2010 sec. 403.3; L569)"),
    ("run_rise_over_0_76", _ID, "true/false", "|max_run_rise_m| is over 0.76 m, a run's largest rise (ADA 2010 sec. "
                                              "405.6; L569)"),
    ("near_limit", _ID, "true/false", "max_run_grade_pct within 1 point of 8.33 % or 5 %, or max_run_rise_m within "
                                      "0.07 m of 0.76 m: a stride more or less can flip a flag, measure it (L588)"),
    *_ends("its first row's start", "its last row's end"),
    *_clocks("start_s", "end_s"),
)

#: decision L568: ``ramp_runs.csv`` (``track`` / ``run``), one row per run and per landing of each ramps.csv ramp
RAMP_RUNS: tuple[Column, ...] = (
    ("ramp", "index", "integer", "ramps.csv's ramp the row belongs to"),
    ("part", "index", "integer", "the run's or landing's number within the ramp, from 1 in walking order"),
    ("kind", _ID, "text", "run (rows of one grade sign, 3 % up to the stair grade, 2 m or more; L301) or landing "
                          "(the rows between two runs)"),
    ("start_s", "s", "number", "its first row's start_s"),
    ("end_s", "s", "number", "its last row's end_s"),
    ("horizontal_m", "m", "number", "the rows' horizontal length; a landing's in whole strides, resolved to one "
                                    "stride (a 1.0 m landing can read 1.7 m)"),
    ("rise_m", "m", "number", "the rows' summed dz_m (signed, + up)"),
    ("grade_pct", "%", "number", "100 x rise_m / horizontal_m"),
    ("n_steps", "count", "integer", "rows of steps.csv: strides of the tracked foot on a foot track (not both "
                                    "feet's steps, as bouts.csv's n_steps), steps on the lower back (C186)"),
    ("over_1_12", _ID, "true/false", "a run's |grade_pct| over 1:12 = 8.33 % (ADA 2010 sec. 405.2; L569); empty "
                                     "on a landing"),
    ("over_1_20", _ID, "true/false", "a run's |grade_pct| over 1:20 = 5 % (L569); empty on a landing"),
    ("run_rise_over_0_76", _ID, "true/false", "a run's |rise_m| over 0.76 m (ADA 2010 sec. 405.6; L569); empty on "
                                              "a landing"),
    ("near_limit", _ID, "true/false", "a run's grade_pct within 1 point of 8.33 % or 5 %, or its rise_m within "
                                      "0.07 m of 0.76 m: a stride more or less can flip a flag (L588); empty on a "
                                      "landing"),
    *_ends("its first row's start", "its last row's end"),
    *_clocks("start_s", "end_s"),
)

#: decision L432: ``stairs.csv`` (``track`` / ``run``), one row per stair flight of a foot track
STAIRS: tuple[Column, ...] = (
    ("flight", "index", "integer", "the flight's number, from 1 in walking order"),
    ("start_s", "s", "number", "its first stride's start_s"),
    ("end_s", "s", "number", "its last stride's end_s"),
    ("direction", _ID, "text", "up or down"),
    ("n_strides", "count", "integer", "consecutive stair strides of the tracked foot (|dz_m| >= 0.10 m, L179) of one "
                                      "direction, 2 or more (L438); a level stride (a landing, a level turn on one), "
                                      "a pause of 1 s or more, a data gap or a reversal ends the flight (L432)"),
    ("height_m", "m", "number", "the strides' summed dz_m (signed, + up)"),
    ("time_s", "s", "number", "end_s - start_s"),
    ("cadence_spm", "steps/min", "number", "2 steps per stride of the tracked foot over time_s (L176)"),
    ("vertical_speed_mps", "m/s", "number", "|height_m| / time_s"),
    ("median_stride_dz_m", "m", "number", "median |dz_m| of the flight's strides"),
    ("stride_dz_cv_pct", "%", "number", "100 x SD / mean of the strides' |dz_m| (L104's CV; empty for 1 stride)"),
    ("n_stairs", "count", "integer", "round(|height_m| / --stair-rise); empty without it: a stride holds 2 stairs "
                                     "step-over-step, 1 step-to-step, so strides do not count stairs (L432)"),
    ("stairs_per_min", "1/min", "number", "60 x n_stairs / time_s; empty without --stair-rise"),
    *_ends("its first stride's start", "its last stride's end"),
    *_clocks("start_s", "end_s"),
)

#: decision L573: ``curbs.csv`` (``track`` / ``run``), one row per single level change (a curb) of a foot track
CURBS: tuple[Column, ...] = (
    ("curb", "index", "integer", "the level change's number, from 1 in walking order"),
    ("start_s", "s", "number", "the stride's start_s"),
    ("end_s", "s", "number", "the stride's end_s"),
    ("direction", _ID, "text", "up or down"),
    ("dz_m", "m", "number", "the stride's height change (signed, + up): |dz_m| >= 0.10 m (L179) in one stride "
                            "outside stairs.csv's flights, ramps.csv's ramps and ramp climbs of 2+ strides (L573); "
                            "a curb ramp (under 2 m) is in no table"),
    ("length_m", "m", "number", "the stride's horizontal length"),
    ("x_m", "m", "number", "trajectory.csv's x halfway through the stride (the curb is within half a stride)"),
    ("y_m", "m", "number", "trajectory.csv's y halfway through the stride"),
    *_clocks("start_s", "end_s"),
)

#: decision L383: a track's laps.csv (``track --corridor``), one row per stretch between cone turns
LAPS: tuple[Column, ...] = (
    ("lap", "index", "integer", "the stretch's number, from 1 (the last one the final, partial lap)"),
    ("start_s", "s", "number", "the first step's start (L399, also with --window) or the middle of the cone turn "
                               "(>= 135 deg, turns.csv) before"),
    ("end_s", "s", "number", "the middle of the cone turn that ends it; the final lap: the last step's end (L399, "
                             "also with --window: standing after the test is no lap's time)"),
    ("duration_s", "s", "number", "end_s - start_s, rests included (L384)"),
    ("corridor_laps", "count", "integer", "corridor lengths it counts: round(tracked_m / the median stretch); 2 or "
                                          "more a missed turn, 0 the final partial lap or a last lap that turned "
                                          "back short (L384, L517); 1 a final lap scaled to 95 % of the corridor "
                                          "or more (it reached the cone, L645)"),
    ("tracked_m", "m", "number", "the track's distance over it (steps.csv's lengths)"),
    ("distance_m", "m", "number", "corridor_laps x corridor_m, or the final lap's scaled tracked distance (L383)"),
    ("distance_source", _ID, "text", "corridor, tracked x scale (the final lap or a last lap that turned back "
                                     "short, L517: x the last lap's corridor / tracked ratio) or tracked (no lap "
                                     "completed)"),
    ("speed_mps", "m/s", "number", "distance_m / duration_s (E98's name, as bouts.csv)"),
    ("rest_s", "s", "number", "its time outside bouts.csv's walking bouts (a rest at a cone stays in its lap, L384) "
                              "and outside turns.csv's turns widened by a step interval, a gap's leftover under 1 s "
                              "no rest (L647: a stepless cone turn is no rest)"),
    ("n_steps", "count", "integer", "steps of both feet whose contact lies in it (as bouts.csv's n_steps)"),
    *_clocks("start_s", "end_s"),
)

#: decision L411: a track's splits.csv (``track --splits``), one row per distance mark the tracked path reaches
SPLITS: tuple[Column, ...] = (
    ("split", "index", "integer", "the mark's number, from 1"),
    ("distance_m", "m", "number", "the mark: metres along the tracked path from the first step (--splits)"),
    ("time_s", "s", "number", "when the path passes it, from the first step's start (interpolated within the stride "
                              "that crosses it; a rest adds no distance, L411)"),
    ("split_time_s", "s", "number", "time_s minus the previous mark's (the first: time_s)"),
    ("speed_mps", "m/s", "number", "the metres since the previous mark / split_time_s"),
    ("pace_min_per_km", "min/km", "number", "split_time_s in minutes / the kilometres since the previous mark (L554)"),
    ("n_steps", "count", "integer", "rows of steps.csv whose middle lies between the previous mark's time and this "
                                    "one's (the last split holds its end; segments.csv's rule): strides of the "
                                    "tracked foot on a foot track, steps on the lower back (L725)"),
    ("median_cadence_spm", "steps/min", "number", "median cadence of the split's steps, by the summary's default rule "
                                                  "(as segments.csv's, L320; L725)"),
    ("median_stride_length_m", "m", "number", "the split's median stride length, the summary's rule (as "
                                              "segments.csv's, L340; L725)"),
    ("median_stance_pct", "%", "number", "--toe-off only: the split's median stance share of the stride (L73; "
                                         "L725); empty without toe-off columns"),
)

#: decision L412: a foot track's direction_changes.csv, one row per change of travel direction
DIRECTION_CHANGES: tuple[Column, ...] = (
    ("change", "index", "integer", "the change's number, from 1"),
    ("start_s", "s", "number", "the start of the first stride of the new travel direction"),
    ("from_travel", _ID, "text", "the previous labelled stride's travel (steps.csv travel: forward, backward, left, "
                                 "right, side)"),
    ("to_travel", _ID, "text", "this stride's travel"),
    ("row", "index", "integer", "its row of steps.csv, from 0"),
    *_clocks("start_s"),
)


#: decision L377: ``rides.csv`` (``track`` of a lower-back unit), one row per ride while standing
RIDES: tuple[Column, ...] = (
    ("ride", "index", "integer", "the ride's number, from 1 in time order"),
    ("start_s", "s", "number", "when the altitude had moved 10 % of the ride's change (L376)"),
    ("end_s", "s", "number", "when it had moved 90 %"),
    ("kind", _ID, "text", "lift (0.5 m/s or more vertically), escalator (0.15-0.5 m/s, at most 45 s), vehicle (it "
                          "vibrates at 0.15 m/s^2 or more, climbing or level: a standstill of 20 s or more; L615, "
                          "L616), other (a slow long climb) or stairs (it shook like walking: steps missed; the "
                          "lower back's opt-in walked_ride, W609); vehicle and other count no floors (L376)"),
    ("dz_m", "m", "number", "the altitude change while standing (steps.csv pause_dz_m of the next step; a vehicle "
                            "row of a standstill under 1.5 m of change, L616: the barometer's change over it, not in "
                            "pause_dz_m); empty: a foot track without a barometer (L624: its vehicle rows are read "
                            "from the foot's vibration alone)"),
    ("duration_s", "s", "number", "(end_s - start_s) / 0.8: the ride's duration (L376)"),
    ("vertical_rate_mps", "m/s", "number", "|dz_m| / duration_s; empty without dz_m (L624)"),
    ("vibration_mps2", "m/s^2", "number", "the median over 1 s windows of the detrended |specific force|'s SD during "
                                          "the ride (a lower-back track: the waist accelerometer, else the foot's; a "
                                          "foot track: the foot's first, L615); 0.15 or more is a vehicle (L402) on "
                                          "a foot track by default (L615), on the lower back with the PARAMS.json "
                                          "option ride_vibration (L403: opt-in); empty: no accelerometer"),
    ("horizontal_est_m", "m", "number", "escalator only, an estimate: |dz_m| / tan(30 deg), the horizontal travel the "
                                        "track leaves out (a 35 deg escalator travels 18 % less); empty otherwise "
                                        "(L377)"),
    *_clocks("start_s", "end_s"),
)

#: decision W493: a track's wb_scores.csv (a session with reference walking bouts, bouts.csv level wb): one row per
#: reference WB (tp / fn) and per detected bout matched to none (fp)
_WB_DMO = {"cadence": ("spm", "steps/min", "cadence_spm"), "stride_length": ("m", "m", "avg_stride_length_m"),
           "speed": ("mps", "m/s", "speed_mps")}
WB_SCORES: tuple[Column, ...] = (
    ("match", _ID, "text", "tp: the reference WB and a detected bout overlap by at least wb_overlap_threshold (0.8) "
                           "of both their durations (mobgap's categorize_intervals); fn: a WB no bout matches; fp: a "
                           "detected bout that matches no WB"),
    ("ref_wb", "index", "integer", "the reference WB's wb_id (bouts.csv); empty on an fp row"),
    ("ref_start_s", "s", "number", "the reference WB's start (its first contact), on the session's clock"),
    ("ref_end_s", "s", "number", "the reference WB's end (its last contact)"),
    ("bout", "index", "integer", "the detected bout (bouts.csv's bout) matched; on an fn row the one overlapping the "
                                 "WB most (empty when none overlaps)"),
    ("bout_start_s", "s", "number", "that bout's start_s (bouts.csv)"),
    ("bout_end_s", "s", "number", "that bout's end_s"),
    ("overlap_s", "s", "number", "the time the WB and the bout share"),
    ("overlap_ref_frac", "fraction", "number", "overlap_s / the WB's duration"),
    ("overlap_bout_frac", "fraction", "number", "overlap_s / the bout's duration"),
    ("start_diff_s", "s", "number", "bout_start_s - ref_start_s: negative = the bout starts before the WB (W495)"),
    ("end_diff_s", "s", "number", "bout_end_s - ref_end_s: positive = the bout ends after the WB (W495)"),
    *(c for name, (u, unit, ref_col) in _WB_DMO.items() for c in (
        (f"ref_{name}_{u}", unit, "number", f"the reference WB's {name.replace('_', ' ')} (bouts.csv {ref_col}: "
                                            "INDIP's)"),
        (f"{name}_{u}", unit, "number", f"the bout's {name.replace('_', ' ')} (bouts.csv "
                                        f"{'stride_length_m' if name == 'stride_length' else ref_col})"),
        (f"{name}_error_pct", "%", "number", f"100 x ({name}_{u} - ref_{name}_{u}) / ref_{name}_{u} (mobgap's "
                                             "rel_error); summary.json's medians take the tp rows only"))),
)


#: decision E163: track-all's ``strides.csv``, every tracked session's steps.csv rows led by these columns
STRIDES: tuple[Column, ...] = (
    ("path", _ID, "text", "the session's sessions.csv path (its key)"),
    ("visit", _ID, "text", "sessions.csv's visit (C82)"),
    ("session", _ID, "text", "the session's name (summary.json session)"),
    ("subject", _ID, "text", "sessions.csv's subject (C100)"),
    ("foot", _ID, "text", "left or right from the session's meta.json (foot / instrumented_foot, L260); empty where "
                          "not known"),
    ("turn_deg", "deg", "number", "a foot row's turn_angle_rad in degrees (left +); empty on a lower-back row"),
    ("is_turn", _ID, "true/false", "the row overlaps one of the session's turns.csv turns (>= 80 deg) by half its own "
                                   "span or half the turn's (L422)"),
)


#: decision B309: the trajectory every track and run writes (trajectory.csv of the output folder; not the session's
#: input trajectory.csv, the path reference with ``timestamp`` in ms, D1)
TRAJECTORY: tuple[Column, ...] = (
    ("t", "s", "number", "the time of the position: the start, then each step's (stride's) end, on the session's "
                         "clock"),
    ("x", "m", "number", "east of the start (ENU; a track with a relative heading sets off along x unless "
                         "--initial-heading turns it, L98)"),
    ("y", "m", "number", "north of the start (ENU)"),
    ("z", "m", "number", "up from the start (--start LAT,LON,ALT: the altitude, L56)"),
    ("lat", "deg", "number", "latitude (WGS-84); empty without --start or geodetic fixes"),
    ("lon", "deg", "number", "longitude (WGS-84); empty without --start or geodetic fixes"),
    ("pos_sigma_m", "m", "number", "the modelled 1-sigma radius of the horizontal position (L128); not with fixes"),
    ("z_rides", "m", "number", "z with the rides a foot track's z leaves out (rides.csv dz_m of 1.5 m or more - a "
                               "lift, an escalator - from the first row at or after the ride's end; L630): the "
                               "walker's altitude, track.gpx / track.geojson's elevation; = z on the lower back "
                               "(its barometric z holds them) and without a ride"),
    ("floor", "storeys", "integer", "the storey the row is on, from the start's (0): the summary's climbs and rides "
                                    "(L127, L375) summed up to the row (inside a stair climb: the storeys climbed so "
                                    "far, rounded), so the last row's is the end floor (storeys_changed; a ride after "
                                    "the last stride, L394, only there); storeys of --storey-height, without it L64's "
                                    "assumed 3.0 m - set it to the building's (L631)"),
    ("ride", "index", "integer", "only when rides.csv has a row: the rides.csv ride the line from the row before to "
                                 "this one crosses - not walked (the first stride after a ride starts where the "
                                 "walker boarded: the vehicle's travel is not in the track), so do not draw it as a "
                                 "path (path.png draws it dotted grey); empty elsewhere (L623)"),
    ("time", "date-time", "text", "t as a clock time, ISO 8601 with milliseconds at the recording start's own offset; "
                                  "only when the session gives its recording start (meta.json recording_start, a "
                                  "date-time or epoch-number `pdrlearn import`; B447, B448), the last column"),
)

#: decision L638: `track --at-times FILE`, the trajectory's columns at the given times
AT_TIMES: tuple[Column, ...] = (
    ("t", "s", "number", "the given time on the session's clock (a time column of the file: less the recording "
                         "start), in the file's order"),
    ("stride_end_s", "s", "number", "`run --at-times` only (decision E332), the second column: the time of the "
                                    "streamed trajectory.csv row held at t - the end of the last stride the live "
                                    "track had returned by t (returned_s; decision E344); x, y, z, pos_sigma_m, "
                                    "z_rides and floor are that row's, not interpolated; empty while the start row "
                                    "is shown (before the first stride is returned)"),
    ("returned_s", "s", "number", "`run --at-times` only (decision E344), the third column: when that stride "
                                  "reached the device - the last sample of the replay's push that returned it "
                                  "(--chunk-s apart, E288's data latency; the final flush: the recording's last "
                                  "sample); empty while the start row is shown"),
    ("x", "m", "number", "trajectory.csv's x at t: linear between its rows; the start's before its first row (the "
                         "standstill before the first stride), its last row's after its last (`run --at-times`: "
                         "the row at stride_end_s, the last returned by t, E332, E344)"),
    ("y", "m", "number", "trajectory.csv's y at t, as x"),
    ("z", "m", "number", "trajectory.csv's z at t, as x"),
    ("lat", "deg", "number", "trajectory.csv's lat at t, as x; only when the track has lat/lon"),
    ("lon", "deg", "number", "trajectory.csv's lon at t, as x; only when the track has lat/lon"),
    ("pos_sigma_m", "m", "number", "trajectory.csv's pos_sigma_m at t, as x; not with fixes"),
    ("z_rides", "m", "number", "z at t plus the rides ended by t (decision L630; computed at t, not held from a "
                               "row: review R1 F2)"),
    ("floor", "storeys", "integer", "the storey at t: the summary's climbs and rides ended by t (decision L631; the "
                                    "lead's merge of L638 with L631, session 44; computed at t: review R1 F2)"),
    ("x_pdr", "m", "number", "with fixes: the PDR-only x at t (trajectory.csv's x_pdr)"),
    ("y_pdr", "m", "number", "with fixes: the PDR-only y at t"),
    ("x_rt", "m", "number", "with fixes: the causal (real-time) x at t (trajectory.csv's x_rt)"),
    ("y_rt", "m", "number", "with fixes: the causal (real-time) y at t"),
    ("time", "date-time", "text", "t as a clock time (as trajectory.csv's); only with a recording start"),
)


#: decision steps 59 (trial T2 finding 9): `pdrlearn steps --out` (also score-steps' input): one row per detection
DETECTIONS: tuple[Column, ...] = (
    ("start_s", "s", "number", "the detection's span starts (a foot detector: the swing's start; s since the "
                               "session's first sample, as every time below)"),
    ("end_s", "s", "number", "the span ends (a foot detector: the rest after the swing)"),
    ("event_s", "s", "number", "the detected event: the initial contact (scored against the reference's ic_ms)"),
    ("unit", _ID, "text", "foot (strides of the instrumented foot) or waist (steps of both feet)"),
    ("confidence", "0-1", "number", "the detector's confidence (accel / accel-force: the swing's amplitude over "
                                    "twice the threshold, capped at 1)"),
    ("amplitude", "m/s^2 or rad/s", "number", "accel, accel-force: the swing's span (max - min) of the low-passed "
                                              "acceleration magnitude, m/s^2 (thesis ch.5.1: > 1.7 m/s^2 makes a "
                                              "stride); pelvic-gyro: the peak pelvic rotation rate, rad/s"),
    ("side", _ID, "text", "pelvic-gyro: left or right, from the sign of the rotation peak"),
    ("step_freq_hz", "Hz", "number", "pll: 1 / the time since the previous step (seed 000)"),
    ("fc_s", "s", "number", "waist-ic: the final contact (toe-off) after the initial contact"),
    ("tc_s", "s", "number", "a track's steps.csv with --toe-off: the toe-off, scored against steps.csv tc_ms "
                            "(steps 59)"),
    ("pedalling", _ID, "true/false", "steps --keep-pedalling with a foot detector: the stride is one L611 calls "
                                     "pedalling (track removes it); without the option those rows are left out "
                                     "(L625)"),
)
#: decision steps 59: `pdrlearn steps / score-steps --events-out`
EVENTS: tuple[Column, ...] = (
    ("event", _ID, "text", "ic (initial contact) or tc (toe-off)"),
    ("foot", _ID, "text", "left / right: the reference event's foot (ics.csv foot; of a foot unit meta.json foot "
                          "or instrumented_foot, else steps.csv's one foot, B357), else the detection's; empty when "
                          "unknown"),
    ("detected_s", "s", "number", "the detection's time on the session's clock (with steps --time-origin export: "
                                  "the export's, as --out; steps 59); empty for a missed reference event"),
    ("reference_s", "s", "number", "the reference event's time on the session's clock (after --ref-offset; with "
                                   "--time-origin export: the export's); empty for a false positive"),
    ("error_s", "s", "number", "detected_s - reference_s (positive: the detection is late); matched pairs only"),
    ("match", _ID, "text", "matched (within the tolerance, one-to-one, closest first), false_positive (a scored "
                           "detection matching nothing) or missed (a reference event no detection matches)"),
)
#: decision steps 59 (trial T2 finding 9): the keys of `pdrlearn steps --json` / `score-steps --json`
STEPS_JSON: tuple[Column, ...] = (
    ("session", _ID, "text", "meta.json's session name"),
    ("detector", _ID, "text", "the detector (score-steps: the detections file's name)"),
    ("unit", _ID, "text", "foot or waist"),
    ("count", "count", "integer", "every detection (a foot table: one per rest-to-rest stride, steps 34)"),
    ("total_count", "count", "integer", "= count (its old alias)"),
    ("scored_count", "count", "integer", "detections scored: inside the labelled intervals, less the unscored ones"),
    ("reference", _ID, "text", "where the reference events come from (steps.ic_s, extras['ics'].ic_s ...)"),
    ("reference_count", "count", "integer", "reference events"),
    ("true_positives", "count", "integer", "matched pairs (|detected - reference| <= tolerance, one-to-one)"),
    ("false_positives", "count", "integer", "scored detections matching no reference event"),
    ("false_negatives", "count", "integer", "reference events matching no detection"),
    ("precision", "0-1", "number", "true_positives / scored_count"),
    ("recall", "0-1", "number", "true_positives / reference_count"),
    ("f1", "0-1", "number", "2 true_positives / (scored_count + reference_count)"),
    ("count_error_pct", "%", "number", "100 |scored_count - reference_count| / reference_count"),
    ("timing_error_mean_s", "s", "number", "mean of detected - reference over the matched pairs (positive: "
                                           "detections late); printed as the value before +-"),
    ("timing_error_sd_s", "s", "number", "SD (n - 1) of detected - reference over the matched pairs; printed after "
                                         "+-; null with one pair"),
    ("timing_error_median_s", "s", "number", "median of detected - reference over the matched pairs"),
    ("timing_error_abs_mean_s", "s", "number", "mean |detected - reference| over the matched pairs"),
    ("tolerance_s", "s", "number", "the matching tolerance (--tolerance)"),
    ("ground_truth", _ID, "true/false", "false for a detected segmentation (source=detected): no timing error"),
    ("outside_labels", "count", "integer", "detections outside the labelled intervals (not scored)"),
    ("unscored_untimed", "count", "integer", "detections standing for reference contacts without a time (steps 19)"),
    ("unscored_same_foot_gap", "count", "integer", "detections in same-foot reference gaps (steps 20)"),
    ("f1_same_foot_gaps_scored", "0-1", "number", "F1 with those counted as false positives"),
    ("one_foot", _ID, "text", "a lower-back detector against one foot's strides: that foot (W96; recall only)"),
    ("ref_offset_s", "s", "number", "--ref-offset: the reference clock minus the IMU clock (steps 56)"),
    ("ref_offset_estimate_s", "s", "number", "the --ref-offset that puts the median timing error at 0, from sliding "
                                             "the reference over +-10 s (it includes the detector's own bias; "
                                             "steps 56)"),
    ("ref_offset_suspect", _ID, "true/false", "true when the estimate names an offset (the warning of steps 56)"),
    ("tight_window_s", "s", "number", "a quarter of the tolerance: the window of the two counts below"),
    ("tight_matches_as_given", "count", "integer", "reference events with a detection within tight_window_s"),
    ("tight_matches_at_estimate", "count", "integer", "the same with the reference moved to the estimate"),
    ("reference_span_only", _ID, "true/false", "ics.csv without bouts.csv: first to last contact is scored, pauses "
                                            "included (steps 57)"),
    ("reference_start_s", "s", "number", "the first reference contact (with reference_span_only)"),
    ("reference_end_s", "s", "number", "the last reference contact (with reference_span_only)"),
    ("reference_pauses", "count", "integer", "gaps between reference contacts longer than 3 s"),
    ("pause_detections", "count", "integer", "scored detections inside those gaps (false positives)"),
    ("tc_*", "-", "number", "the toe-offs' scores when the detections have tc_s and steps.csv tc_ms (count, "
                                "reference_count, true_positives, false_positives, false_negatives, precision, "
                                "recall, f1, timing_error_mean_s, timing_error_sd_s; steps 59)"),
    ("merged_detections", "count", "integer", "foot: detections dropped between the same two rests (steps 34)"),
    ("rest_strides", "count", "integer", "foot: rest-to-rest strides the kept detections cover (steps 38)"),
    ("foot_swing_strides", "count", "integer", "foot: the foot's own rest-and-swing strides, when more (steps 47)"),
    ("pedalling_strides", "count", "integer", "steps with a foot detector: strides L611 calls pedalling (a closed "
                                              "loop: cycling?), left out of count (with --keep-pedalling: counted, "
                                              "marked in --out's pedalling column); 0: none (L625)"),
    ("not_scored", _ID, "text", "why a foot table was not scored (steps 58)"),
    ("out", _ID, "text", "--out's path"),
    ("events_out", _ID, "text", "--events-out's path"),
)


#: cohort C92: `evaluate-all --per-method`'s tables (pdrlearn.cohort_methods); accuracies are fractions (0-1)
_EVAL = "as `pdrlearn evaluate --json` scores it (tasks.<task>.methods.<method>.units.<unit>)"
COHORT_METHODS: tuple[Column, ...] = (
    ("user", _ID, "text", "the user's folder in the cohort (cohort_summary.csv's user)"),
    ("task", _ID, "text", "terrain, direction or length"),
    ("method", _ID, "text", "the classifier method (heuristic, dtw, svm, nn, fusion, ensemble or a plug-in)"),
    ("unit", _ID, "text", "the unit it classifies from: foot, waist, fused (soft vote) or combined (both units' "
                          "features)"),
    ("chosen", _ID, "true/false", "whether it is the task's chosen model (evaluate's tasks.<task>.chosen), the one "
                               "track --model and the runtime use"),
    ("accuracy_labelled", "fraction", "number", f"accuracy on the held-out steps cut at the labelled boundaries, "
                                                f"{_EVAL}"),
    ("balanced_accuracy_labelled", "fraction", "number", "mean recall over the classes present, on the labelled "
                                                         "boundaries"),
    ("n_steps_labelled", "count", "integer", "labelled steps the model classified"),
    ("accuracy_detected", "fraction", "number", "accuracy of this model on the strides the runtime detects (C49), "
                                                "every row (classifiers C97); empty when it cannot run on the units"),
    ("balanced_accuracy_detected", "fraction", "number", "balanced accuracy on the detected strides (C97)"),
    ("n_steps_detected", "count", "integer", "labelled steps matched to a detected stride and classified by this "
                                             "model (C97)"),
)
COHORT_METHODS_SUMMARY: tuple[Column, ...] = (
    ("task", _ID, "text", "as cohort_methods.csv"),
    ("method", _ID, "text", "as cohort_methods.csv"),
    ("unit", _ID, "text", "as cohort_methods.csv"),
    ("n_users", "count", "integer", "users whose evaluation scored this task x method x unit"),
    ("accuracy_labelled_mean", "fraction", "number", "mean over those users of accuracy_labelled"),
    ("accuracy_labelled_sd", "fraction", "number", "sample SD (n - 1) of accuracy_labelled; empty for one user"),
    ("balanced_accuracy_labelled_mean", "fraction", "number", "mean over those users of balanced_accuracy_labelled"),
    ("balanced_accuracy_labelled_sd", "fraction", "number", "sample SD (n - 1) of balanced_accuracy_labelled; "
                                                            "empty for one user"),
    ("n_steps_labelled", "count", "integer", "labelled steps summed over those users"),
    ("n_chosen", "count", "integer", "users whose chosen model it is"),
    ("accuracy_detected_mean", "fraction", "number", "mean accuracy_detected over the users it was scored for "
                                                     "(every user since classifiers C97)"),
)


def _named(names: tuple[str, ...], meanings: dict[str, tuple[str, str, str]]) -> tuple[Column, ...]:
    """Classifiers C150: a table's columns in the order its writer names them (``names``, the writer's one list),
    each with its entry of ``meanings``; a name without a meaning, or a meaning of no column, fails at import."""
    if set(names) != set(meanings):
        raise KeyError(f"columns: {sorted(set(names) ^ set(meanings))} named by the writer or the dictionary only")
    return tuple((n, *meanings[n]) for n in names)


#: classifiers C143: `train --report`'s tables (pdrlearn.classify.cv_report); accuracies are percentages; the names
#: and their order are cv_report's CV_COLUMNS / LOUO_COLUMNS (C150)
TRAIN_CV: tuple[Column, ...] = (*_named(CV_COLUMNS, {
    "task": (_ID, "text", "terrain, direction or length"),
    "method": (_ID, "text", "as cohort_methods.csv"),
    "unit": (_ID, "text", "as cohort_methods.csv"),
    "chosen": (_ID, "true/false", "whether it is the task's chosen model (train's choice, C8), the one track --model "
                                  "uses"),
    "cv": (_ID, "text", "the cross-validation: '10-fold CV accuracy', 'leave-one-user-out CV accuracy (3 users)', ..."),
    "n_steps": ("count", "integer", "labelled strides of one foot the CV scored (C69: every session's, pooled)"),
    "accuracy_pct": ("%", "number", "out-of-fold accuracy over the pooled steps"),
    "balanced_accuracy_pct": ("%", "number", "mean of the class recalls (C60; what train ranks by, C36)"),
    "ci95_low_pct": ("%", "number", "exact binomial (Clopper-Pearson) 95 % interval of accuracy_pct, low end (C58)"),
    "ci95_high_pct": ("%", "number", "its high end"),
    "folds_mean_pct": ("%", "number", "mean of the folds' accuracies (C41)"),
    "folds_sd_pct": ("%", "number", "their sample SD; empty with one fold"),
    "thesis_pct": ("%", "number", "the thesis' figure of the row: mean of its per-class accuracies in Tables "
                                  "27/28/33 (C144); empty where the thesis has no row (soft votes, ensemble)"),
}), (CLASS_COLUMN, "%", "number", "recall of each class (thesis Tables 27/28/33's per-class accuracy)"))
TRAIN_LOUO: tuple[Column, ...] = _named(LOUO_COLUMNS, {
    "task": (_ID, "text", "as cv.csv"),
    "method": (_ID, "text", "as cv.csv"),
    "unit": (_ID, "text", "as cv.csv"),
    "chosen": (_ID, "true/false", "as cv.csv"),
    "held_out": (_ID, "text", "the user (session, C59) the fold held out, as meta.json names it"),
    "n_steps": ("count", "integer", "that user's labelled steps"),
    "accuracy_pct": ("%", "number", "accuracy on that user's steps, trained on the others"),
    "balanced_accuracy_pct": ("%", "number", "mean recall over the classes that user's steps hold"),
})


#: cohort C106: the classifier tasks cohort_summary.csv has columns of (pdrlearn.classify.training.TASKS, not imported
#: here: it loads scikit-learn)
COHORT_TASKS = ("terrain", "direction", "length")


def _per_task(name: str, unit: str, kind: str, meaning: str) -> tuple[Column, ...]:
    """Cohort C106: one cohort_summary.csv column per task of :data:`COHORT_TASKS` (``<task>`` in ``name``)."""
    return tuple((name.replace("<task>", t), unit, kind, meaning) for t in COHORT_TASKS)


#: cohort C106: `train-all`'s and `evaluate-all`'s cohort_summary.csv (pdrlearn.cli.cohort); one row per user
COHORT_SUMMARY: tuple[Column, ...] = (
    ("user", _ID, "text", "the user's folder in COHORT (and the model's folder in MODELS): the row's key"),
    ("subject", _ID, "text", "the subject the user's sessions' meta.json name, as track-all's sessions.csv subject "
                             "(C22); '; '-joined when several; empty when none is named or the user failed (C107)"),
    ("status", _ID, "text", "ok or failed"),
    ("seconds", "s", "number", "wall time of the user's job"),
    ("cpu_seconds", "s", "number", "CPU time of the process that ran the job, while it ran"),
    ("error", _ID, "text", "a failed user's one-line error; empty when ok (the column only when some user failed)"),
    ("sessions", "count", "integer", "sessions read (train-all: train/; evaluate-all: test/)"),
    ("skipped_sessions", "count", "integer", "sessions --skip-bad-sessions left out (C11; only with the option)"),
    ("skipped", _ID, "text", "those sessions, 'name: error; ...' (C11; only with the option)"),
    ("rate_hz", "Hz", "number", "train-all: the rate the model was trained at (foot accelerometer's, else the "
                                "waist's; C62)"),
    ("recorded_hz", _ID, "text", "train-all --resample: the rates the sessions were recorded at, '20 / 100' (C62)"),
    ("skipped_tasks", "count", "integer", "train-all: tasks asked for that training skipped (C87)"),
    ("skipped_task_names", _ID, "text", "the tasks skipped (train-all) or not scored (evaluate-all), '; '-joined "
                                        "(C87)"),
    *_per_task("<task>_method", _ID, "text", "train-all: the task's chosen model, method/unit (heuristic/foot)"),
    *_per_task("<task>_cv_accuracy", "fraction", "number", "train-all: the chosen model's cross-validated accuracy"),
    *_per_task("<task>_n_steps", "count", "integer", "train-all: labelled steps the task was trained on"),
    *_per_task("<task>_accuracy_detected", "fraction", "number", "evaluate-all: the chosen model's accuracy on the "
                                                                 "strides the runtime detects (C49, C87)"),
    *_per_task("<task>_n_steps_detected", "count", "integer", "evaluate-all: labelled steps matched to a detected "
                                                              "stride"),
    *_per_task("<task>_accuracy_labelled", "fraction", "number", "evaluate-all: accuracy on the held-out steps cut "
                                                                 "at the labelled boundaries"),
    *_per_task("<task>_n_steps_labelled", "count", "integer", "evaluate-all: labelled steps scored"),
    *_per_task("<task>_classes_absent", _ID, "text", "evaluate-all: the task's classes the test steps hold none of, "
                                                     "'; '-joined (classifiers C64): the accuracies do not cover "
                                                     "them; empty when every class is present (C105)"),
)


#: every table of the dictionary, in the order shown (named by :data:`pdrlearn.table_names.TABLE_NAMES`, E152)
TABLES: dict[str, tuple[Column, ...]] = dict(zip(TABLE_NAMES, (
    SESSIONS, GROUPS, SUBJECTS, CHANGES, CHANGES_SUMMARY, SUBJECTS_POOLED, GROUPS_POOLED, BOUTS, STRIDES, TURNS,
    PERIODS, SEGMENTS, LAPS,
    SPLITS,
    DIRECTION_CHANGES, TRANSFERS, TUG_PHASE_TABLE, TUG_TRIAL_TABLE, TEN_M_WALK_TRIAL_TABLE,
    FREEZES, FLIGHTS, RAMPS, RAMP_RUNS, STAIRS, CURBS, RIDES, WB_SCORES, WAIST_STEPS,
    FOOT_STEPS, TRAJECTORY, AT_TIMES, GAIT_STEPS, GAIT_CYCLES, GAIT_BOUTS, GAIT_PAIRS,
    GAIT_CHANGES, GAIT_CHANGES_SUMMARY, DETECTIONS, EVENTS, STEPS_JSON,
    COHORT_SUMMARY, COHORT_METHODS, COHORT_METHODS_SUMMARY, TRAIN_CV, TRAIN_LOUO), strict=True))

#: a line under a table's heading (decision W129: steps.csv is documented for lower-back tracks)
NOTES = {"steps.csv": "Lower-back tracks (waist-pendulum, waist-pll): one row per contact of either foot. A foot "
                      "track's steps.csv (strides of the tracked foot) has other columns: steps.csv (foot), below.",
         "steps.csv (foot)": "Foot tracks (plasys; `pdrlearn track`, `run`): one row per stride of the tracked foot "
                             "(E137); an empty cell is a value the stride cannot have. Columns marked with an option "
                             "or a model appear only with it.",
         "bouts.csv": "Two column orders (decision C113; read the columns by name): a single `track` / `run` writes "
                      "`session, subject, visit, bout, ...`; `track-all`'s OUT/bouts.csv leads with sessions.csv's "
                      "key, `path, visit, session, subject, bout, ...` (L165), as listed below, and adds "
                      "`visit_as_written` (C82).",
         "periods.csv": "Two column orders (decision C113; read the columns by name): a single `track` / `run --per` "
                        "writes `session, subject, visit, period, ...`, as listed below; `track-all --per`'s "
                        "OUT/periods.csv leads with sessions.csv's key, `path, visit, session, subject, period, ...` "
                        "(L277; `path`: the session folder relative to ROOT).",
         "segments.csv": "`pdrlearn track DIR --segments LEGS.csv` (decisions L618, L619): one row per leg of "
                         "LEGS.csv (start_s, end_s: seconds from the session's start; an optional label), each with "
                         "periods.csv's totals over the leg, from one track of the whole session.",
         "strides.csv": "`pdrlearn track-all` (decision E163): every tracked session's steps.csv in one table, in "
                        "sessions.csv's order; the columns below lead, then the session's own steps.csv columns "
                        "(steps.csv / steps.csv (foot)).",
         "trajectory.csv": "Every track and run (decision B309): the output's trajectory, one row per position. A "
                           "session's own trajectory.csv (its path reference, `timestamp` in ms) is an input of "
                           "another layout (README, Data format).",
         "at_times.csv": "`pdrlearn track DIR --at-times FILE` (decision L638): one row per time of FILE (a CSV "
                         "with a column t, seconds from the session's start, or time, ISO 8601), in its order: "
                         "trajectory.csv's numeric columns there (a floor column: its row at or before t). "
                         "`pdrlearn run ... --at-times FILE|T1,T2,...` (decision E332; a column t_s or t, or a comma "
                         "list, in increasing order): the streamed row at or before each time, held, with "
                         "stride_end_s.",
         "detections.csv": "`pdrlearn steps --out FILE` (any name): one row per detection, times in s since the "
                           "session's first sample; the columns after confidence depend on the detector; "
                           "`score-steps` reads the same layout (event_s, and start_s / end_s for a foot table).",
         "events.csv": "`pdrlearn steps` / `score-steps --events-out FILE` (decision steps 59): one row per scored "
                       "event, for Bland-Altman plots (error_s against the mean of detected_s and reference_s); "
                       "sorted by event, then reference time.",
         "steps.json": "The keys of `pdrlearn steps --json` and `score-steps --json` (decisions steps 41, 56-59); "
                       "the scores appear only when the session has a reference, NaN is written as null. Timing "
                       "error = detected - reference (s): positive means the detector is late; `+-` in the text "
                       "output is the SD over the matched pairs only.",
         "cohort_summary.csv": "`pdrlearn train-all COHORT --out MODELS` (MODELS/cohort_summary.csv) and "
                               "`pdrlearn evaluate-all MODELS COHORT` (OUT/cohort_summary.csv), decision C106: one "
                               "row per user; train-all writes the train-all columns, evaluate-all the evaluate-all "
                               "ones, each task's only when some user trained or scored it. Join to track-all's "
                               "tables on subject (C107).",
         "cohort_methods.csv": "`pdrlearn evaluate-all MODELS COHORT --per-method` (cohort decision C92): one row "
                               "per user, task, method and unit; cohort_methods_summary.csv|md: the means over users.",
         "cv.csv": "`pdrlearn train ... --report DIR` (classifiers C143; `to_dataframe(model)` is the same table): "
                   "one row per task, method and unit of the model's cross-validation, in thesis Tables 27/28/33's "
                   "order; confusion_<task>.png beside it, report.md the same tables.",
         "louo.csv": "`pdrlearn train ... --cv-groups user --report DIR` (C143): one row per task, method, unit and "
                     "held-out user; written only when the folds held out whole users.",
         "gait_steps.csv": "`pdrlearn gait LEFT RIGHT --out DIR` (decisions L259-L263, L283-L287): the two feet's "
                           "contacts merged on their shared clock; gait_summary.json's `walk` has gait_bouts.csv's "
                           "keys for the whole walk (its level straight steps', L538), `by_kind` the same keys "
                           "for each step kind, `clock_alignment` how the two feet were put on one clock (L537), "
                           "its `warnings` the B245 / L284 / L285 lines. `pdrlearn gait-all ROOT --out DIR` (C110) "
                           "stacks every visit folder's pair, each row led by `path`; `pdrlearn run BUNDLE "
                           "SESSION --gait OTHER_FOOT --out DIR` writes the same files of the two feet's streamed "
                           "strides (E311)."}


def expanded(table: str) -> dict[str, Column]:
    """``table``'s columns by name, ``{measure}`` entries expanded to each of :data:`GROUP_METRICS`."""
    out: dict[str, Column] = {}
    for col in TABLES[table]:
        names = [col[0].format(measure=m) for m in GROUP_METRICS] if "{measure}" in col[0] else [col[0]]
        out.update({n: (n, *col[1:]) for n in names})
    return out


def undocumented(table: str, columns) -> list[str]:
    """The ``columns`` of a written ``table`` that the dictionary lacks (a test keeps this empty, C35)."""
    known = expanded(table)
    if table == "strides.csv":  # decision E163: the sessions' own steps.csv columns follow the lead ones
        known = {**expanded("steps.csv"), **expanded("steps.csv (foot)"), **known}
    if table == "groups.csv":  # decision C256: any sessions.csv number column can be a --metrics measure
        known.update({f"{name}_{k}": ("", "", "", "") for name, _, kind, _ in SESSIONS if kind in ("number", "integer")
                      for k in ("n", "mean", "sd", "median", "ci95_low", "ci95_high")})
    if table in ("changes.csv", "gait_changes.csv"):  # decision C81: any sessions.csv number column can be a
        # --metrics measure; cohort C242: gait_changes.csv's, the gait walk's
        from pdrlearn.track.gait_changes import GAIT_CHANGE_MEASURES

        measures = (GAIT_CHANGE_MEASURES if table == "gait_changes.csv" else
                    [name for name, _, kind, _ in SESSIONS if kind in ("number", "integer")])
        known.update({f"{m}_{k}": ("", "", "", "") for m in measures for k in ("baseline", "change", "change_pct")})
    # decision E137: "p_<task>_<class>" / "ood_*" name a family of columns by its prefix
    prefixes = tuple(k.split("<")[0].rstrip("*") for k in known if "<" in k or k.endswith("*"))
    return [c for c in columns if c not in known and not (prefixes and c.startswith(prefixes))]


#: decision L449: which step count is which, one line at the top of docs/columns.md
STEP_COUNT_LINE = ("Step counts (L449): `n_steps` is the rows of steps.csv - strides of the tracked foot on a foot "
                   "track, steps of both feet on the lower back (summary, sessions.csv, periods.csv; "
                   "`n_steps_counts` says which); `n_steps_both_feet` (summary, sessions.csv, periods.csv) and "
                   "bouts.csv's and subjects.csv's `n_steps` always count the steps of both feet (on a foot track "
                   "2 per stride, an estimate); ramps.csv's and ramp_runs.csv's `n_steps` are rows of steps.csv "
                   "again - a foot track's strides (C186).")


def markdown(tables: list[str] | None = None) -> str:
    """The dictionary as Markdown, one section per table (docs/columns.md is this text); the heading names the
    ``tables`` asked for (decision W306: ``pdrlearn columns periods`` had "track-all's tables", a track's file)."""
    title = ("pdrlearn's tables (track, track-all, run, steps, gait)" if tables is None
             else ", ".join(dict.fromkeys(t.split(" ")[0] for t in tables)))
    lines = [f"# Columns of {title}", "",
             "Generated by `pdrlearn columns` from `pdrlearn/columns.py` (cohort decision C35); `{measure}` stands "
             f"for each of {', '.join(GROUP_METRICS)} (changes.csv: or each `track-all --metrics` measure, C81; "
             "by default also the clinical tests' walk_test_distance_m, fatigue_index, tug_time_s, "
             "ten_m_walk_speed_mps, t25fw_time_s where a session has them, first, C177). "
             "Empty cell = not measured for that session (a failed "
             "session, another pipeline, no reference). The gait events (initial contact, toe-off, mid-stance) "
             "and each temporal and spatial column's window: docs/gait-definitions.md.", "", STEP_COUNT_LINE, ""]
    for name in tables or list(TABLES):
        lines += [f"## {name}", ""] + ([NOTES[name], ""] if name in NOTES else [])
        lines += ["| column | unit | type | meaning |", "|---|---|---|---|"]
        lines += [f"| `{c}` | {u} | {t} | {m} |" for c, u, t, m in TABLES[name]]
        lines.append("")
    return "\n".join(lines)
