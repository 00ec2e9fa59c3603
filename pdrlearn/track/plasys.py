"""The PLASYS tracking pipeline (thesis ch.7): methods M1, M2, M3 on a foot (+ waist) session.

- **M1** (accelerometer): accelerometer step detection, attitude from the accelerometer at each stride
  start, gyroscope integration without offset correction, double integration with the velocity reset at
  each stride start only; heading from the foot's own yaw (foot unit only, as thesis ch.7.3.2).
- **M2** (accelerometer + force): force-sensor stance (ZUPT at every stance sample, ZARU attitude reset),
  setup-standstill gyroscope offset, the 2-state angle Kalman filter, the white-noise-jerk Kalman filter
  (Sw = 1.8, R = 0.01) with ZUPT updates; heading: the foot's stride yaw aligned to the waist
  complementary-filter heading ("fused", decision L17; ``heading="waist"`` is the thesis' choice).
- **M3** (PLASYS): M2 plus the step classes (model or ``oracle`` labels): terrain picks the distance
  (horizontal for flat/up, 3-axis norm for down), direction fixes the sign, the length class clamps the
  distance, stairs give the altitude change (thesis ch.7.2.2).

``streaming=True`` (M2/M3) runs the stride-local kernel of the streaming runtime instead
(:mod:`pdrlearn.kernels.stride`: online stance segmentation, per-stride ZUPT on the levelled foot
acceleration, the M3 rules, heading from the integrated vertical rate), so that
``pdrlearn.runtime.Tracker`` reproduces the track (issue 7; docs/deploying.md "Streamable tracking").
"""

from __future__ import annotations

import logging
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

from pdrlearn.classify.uncovered import trained_side_strides
from pdrlearn.displace import (
    PRE_L41_CALIBRATION,
    FootDisplacement,
    StepRules,
    inertial_stance,
    model_distance_calibration,
    model_length_bounds,
    parse_bounds,
    predates_streaming_calibration,
    stance_runs,
    streaming_calibration,
)
from pdrlearn.displace.foot import check_settings as check_foot_settings
from pdrlearn.displace.force_channels import live_force
from pdrlearn.displace.force_check import (
    checked_stance,
    imu_strides_in,
    reads_force_refusal,
    streamed_insole_line,
    tared,
)
from pdrlearn.displace.force_clock import force_events, offset_check, toe_offs_in
from pdrlearn.errors import DataError, InternalError, MissingSensorError, ModelError, NoStridesError, VerticalAxisError
from pdrlearn.io.resample import recorded_rate
from pdrlearn.io.session import Session
from pdrlearn.kernels import carried_yaw as KCY
from pdrlearn.kernels import distance as KD
from pdrlearn.kernels import sideways as KSW
from pdrlearn.kernels import stop_bias as KSB
from pdrlearn.kernels import stride as SK
from pdrlearn.kernels import turn_length as KT
from pdrlearn.kernels.altitude_check import (
    integrated_altitude_check,
    judged_terrain,
    steep_stride_check,
    terrain_dz_check,
    zeroed_climb_check,
)
from pdrlearn.kernels.backward import signed_chord
from pdrlearn.kernels.bayes import DEFAULT_MIN_CONFIDENCE, DEFAULT_MODEL_RULES, SIGMA_REL, check_rules
from pdrlearn.kernels.contact import force_at, stride_cap_s, stride_contact
from pdrlearn.kernels.distance import (
    applicable_calibration,
    apply_level_gain,
    calibrated_stride_sd,
    classifier_rate_warning,
    level_dz,
    unclassed_level_dz,
)
from pdrlearn.kernels.first_walk import FirstWalk
from pdrlearn.kernels.foot_rhythm import foot_period
from pdrlearn.kernels.gap_compass import GapCompass
from pdrlearn.kernels.lull import join_lulls
from pdrlearn.kernels.pedal import closed_loop_strides, pedal_line, ride_strides, seated_strides, unrested_strides
from pdrlearn.kernels.spin import foot_gap_start, spin_line, spin_turn, turns_in_place
from pdrlearn.kernels.window import (
    BRIDGE_GAP_S,
    GAP_TOL_S,
    GROUP_STREAMS,
    TASK_COLUMNS,
    PitchReference,
    available_groups,
    hole_stride_dz,
    levelled_units,
    posture_warning,
    stride_hole,
    stride_hole_line,
)
from pdrlearn.orient import WaistHeading, unit_data, wrap_angle
from pdrlearn.orient._kernels import fit_horizontal_hard_iron, level_axes
from pdrlearn.signal import lowpass
from pdrlearn.track.accel_clip import clip_noise_default
from pdrlearn.track.altitude import apply_altitude, check_altitude, set_strides_dz
from pdrlearn.track.base import TrackResult, check_keywords, keyword_names, register_pipeline
from pdrlearn.track.evaluate import match_by_overlap
from pdrlearn.track.foot_rest import foot_rest_gravity, slow_rhythm_line
from pdrlearn.track.gait import (
    STRAIGHT_MAX_RAD,
    add_gait_columns,
    contact_cadence_spm,
    streamed_gait_columns,
    stride_rows,
    turn_rows,
)
from pdrlearn.track.gap_turns import add_waist_gap_turns, setup_rest_bias
from pdrlearn.track.gaps import (
    FOOT_IMU,
    drop_steps_across_gaps,
    drop_stride_disp,
    drop_stride_warning,
    drop_strides,
    gap_heading_clause,
    gap_rows,
    long_gaps,
    longest_gap_in,
    neighbour_heights,
    overlaps_any,
    overlaps_gaps,
    unit_gap_warnings,
)
from pdrlearn.track.geodetic import geodetic_track, heading_in_radians, start_coordinate
from pdrlearn.track.gyro_clip import (
    applied_settings,
    clipped_foot_line,
    clipped_foot_settings,
    clipping_acts,
    foot_gyro_clipped,
)
from pdrlearn.track.rides import foot_rides
from pdrlearn.track.sim_rocker import hermite_contact_line
from pdrlearn.track.travel import side_class_warning
from pdrlearn.track.trunk_tug import add_trunk_transfers
from pdrlearn.track.turn_reference import turn_reference_warning
from pdrlearn.waist.plausibility import bias_removed, foot_drift_line, waist_bias_check, waist_bias_line
from pdrlearn.warning_lines import coded

log = logging.getLogger(__name__)

#: Warning when a foot-only session (no waist accelerometer + gyroscope, or no waist frame) is headed by the
#: foot's own yaw: offline M2/M3 and the streamed path (decision B17), and `pdrlearn run`.
NO_WAIST_HEADING = coded("no waist unit: heading from the foot's own integrated yaw (relative to the start)",
                         "no-waist-unit")  # decision E170: the code E168 reads from its text


def no_waist_heading(session) -> str:
    """Decision B153: the warning of a session headed by the foot's yaw for want of the waist unit:
    :data:`NO_WAIST_HEADING`, or, when the session holds some waist files but not the waist accelerometer and
    gyroscope (an incomplete upload), the same consequence naming the missing and the present files."""
    from pdrlearn.io.sensors import SENSORS, UNIT_IMU

    present = [s.filename for n, s in SENSORS.items() if s.placement == "waist" and session.has(n)]
    missing = [SENSORS[n].filename for n in UNIT_IMU["waist"] if not session.has(n)]
    if not present or not missing:
        return NO_WAIST_HEADING
    return coded(f"waist unit incomplete: {' and '.join(missing)} missing ({', '.join(present)} present): "
                 f"{NO_WAIST_HEADING.removeprefix('no waist unit: ')}; add {' and '.join(missing)} to head by the "
                 "waist unit (decision B153)", "B153")  # decision E170

# decision L627: M2 / M3 start each stride from the accelerometer's tilt at rest (thesis eq. 38/39), not the angle
# filter's (L5, thesis eq. 40-43), whose swing propagation leaves ~1 deg at the stride starts
_M2 = {"detector": "AccelForceStepDetector", "integrator": "kalman", "zupt_end": True,
       "gyro_bias": "standstill", "attitude": "accel", "heading": "fused", "rules": False, "force": True}
METHODS: dict[str, dict] = {
    "M1": {"detector": "AccelStepDetector", "integrator": "integration", "zupt_end": False,
           "gyro_bias": "none", "attitude": "accel", "heading": "foot", "rules": False, "force": False},
    "M2": _M2,
    "M3": {**_M2, "rules": True},
}


#: decision B177: what to pass for the step classes, as the parameter and the CLI flag (the line fits both)
MODEL_NEEDED = ("{what}: pass model= a trained UserModel or its directory (CLI --model DIR; `pdrlearn train`) or "
                "model='oracle' (--model oracle) for labelled sessions")
NO_MODEL_WARNING = coded("no model: the M3 engine (ZUPT/Kalman strides) without the class rules (terrain filter, "
                         "sign, length bounds; a stride under 0.10 m of height change is level, L39); pass model= a "
                         "trained model (CLI --model DIR; `pdrlearn train`) or model='oracle' (--model oracle, "
                         "labelled sessions) for M3 (decision E153)", "E153")  # decision E170
#: decision L586: ``fused_climb`` with a model that classes terrain (offline and streamed): said, not refused (the same
#: PARAMS.json serves tracks with and without a model, and the track is right without the option)
FUSED_CLIMB_DROPPED = ("fused_climb applies to a track without a terrain model: the model's terrain classes set the "
                       "strides' heights, so it was dropped; track without --model (or with a model without terrain "
                       "classes) for it, or drop fused_climb from the --params file (decisions L565, L586)")
#: decision E170: the line of a foot unit without force sensors, with its code (E168's lead phrase)
NO_FORCE_STANCE = coded("no force sensors: stance from the accelerometer/gyroscope detector", "no-force-sensors")


def coded_altitude_check(dz, **options) -> tuple[str | None, dict]:
    """:func:`pdrlearn.kernels.altitude_check.integrated_altitude_check` (decision L69) with its line coded where
    it is made (decision E170; the kernel stays numpy-only for the runtime)."""
    msg, info = integrated_altitude_check(dz, **options)
    return (coded(msg, "L69") if msg else msg), info


def stance_strides(t: np.ndarray, stance: np.ndarray, *, max_rest_s: float = 0.3,
                   min_swing_s: float = 0.2) -> pd.DataFrame:
    """Strides of the foot unit from rest to rest: one row between consecutive stance runs (runs closer
    than 0.1 s merged; a swing shorter than ``min_swing_s`` s is not a stride). A stride starts at the
    middle of the previous stance (at most ``max_rest_s`` before the swing) and ends at the middle of
    the next stance (at most ``max_rest_s`` after it)."""
    rr = stance_runs(t, stance)
    rows = []
    for (a0, b0), (a1, b1) in zip(rr[:-1], rr[1:], strict=True):
        if t[a1] - t[b0 - 1] < min_swing_s:
            continue
        start = max(0.5 * (t[a0] + t[b0 - 1]), t[b0 - 1] - max_rest_s)
        end = min(0.5 * (t[a1] + t[b1 - 1]), t[a1] + max_rest_s)
        rows.append((start, end, t[a1], 1.0))
    df = pd.DataFrame(rows, columns=["start_s", "end_s", "event_s", "confidence"])
    df["unit"] = "foot"
    df.attrs["detector"] = "stance"
    return df


#: where track_plasys's strides come from (its ``steps`` option)
STEP_SOURCES = ("detector", "stance", "labels")


def _detect_strides(session: Session, kind: str, steps, t: np.ndarray, stance: np.ndarray,
                    warnings: list[str], seen: dict | None = None) -> pd.DataFrame:
    """Stride windows of the foot unit: ``steps`` = "detector" | "stance" | "labels", a registered foot detector's
    name, a :class:`~pdrlearn.steps.StepDetector` or a steps table (decision L149). ``seen``: a dict that receives
    the table of the default ``kind`` detector when it ran without an error, for reuse (steps decision 55)."""
    custom = _custom_strides(session, steps)
    if custom is not None:
        return custom
    if steps == "labels":
        if session.steps is None or not len(session.steps):
            raise DataError(f"session '{session.name}': steps='labels' but the session has no steps.csv")
        df = session.steps[["start_s", "end_s"]].copy()
        df["event_s"] = session.steps["ic_s"] if "ic_s" in session.steps else df["end_s"]
        df["confidence"] = 1.0
        df["unit"] = "foot"
        return df
    if steps == "detector":
        try:
            import pdrlearn.steps as steps_mod

            det = getattr(steps_mod, kind)()
            df = det.detect(session)
            if seen is not None:
                seen[kind] = df.copy()
            if len(df) and {"start_s", "end_s"} <= set(df.columns):
                return df.reset_index(drop=True)
            warnings.append(f"{kind} found no steps; using the stance segmentation")
        except (ImportError, AttributeError):
            warnings.append(f"pdrlearn.steps.{kind} not available; strides from the stance segmentation")
        except MissingSensorError:
            raise
        except DataError as exc:
            warnings.append(f"{kind} failed ({exc}); strides from the stance segmentation")
    elif steps != "stance":
        from pdrlearn.steps import DETECTORS

        raise DataError(f"plasys: steps='{steps}' is not detector, stance, labels, a foot detector's name "
                        f"({', '.join(n for n in DETECTORS if DETECTORS[n].unit == 'foot')}), a StepDetector or a "
                        "steps table")
    return stance_strides(t, stance)


def _detector_name(steps: str) -> str:
    """The detector name of ``steps="NAME"`` or ``"NAME:key=value,..."`` (decision E94, the CLI's form)."""
    from pdrlearn.plugins import parse_spec

    return parse_spec(steps, "step detector")[0] if ":" in steps else steps


def _check_steps_arg(steps) -> None:
    """Decisions B173 / L149: ``steps`` is a mode string, a registered foot detector's name, a
    :class:`~pdrlearn.steps.StepDetector` or a steps table; anything else is one :class:`DataError` line."""
    import pdrlearn.steps as steps_mod

    if isinstance(steps, (pd.DataFrame, steps_mod.StepDetector)):
        return
    if isinstance(steps, str) and (steps in STEP_SOURCES or _detector_name(steps) in steps_mod.DETECTORS):
        return
    what = repr(steps) if isinstance(steps, str) else f"a {type(steps).__name__}"
    raise DataError(f"plasys: steps={what} is not {', '.join(STEP_SOURCES)}, a foot detector's name "
                    f"({', '.join(n for n in steps_mod.DETECTORS if steps_mod.DETECTORS[n].unit == 'foot')}), a "
                    "StepDetector or a steps table with start_s, end_s in s (docs/extending.md)")


def _custom_strides(session: Session, steps) -> pd.DataFrame | None:
    """Decision L149: the strides of a user's foot detector (a :class:`StepDetector` or a registered name) or
    table (``start_s``, ``end_s`` in s, optional ``event_s``, ``confidence``); None for the built-in modes. A
    detector that finds nothing or a table without strides is an error (it was asked for: no stance fallback)."""
    import pdrlearn.steps as steps_mod

    if isinstance(steps, str):
        if steps in ("detector", "stance", "labels") or _detector_name(steps) not in steps_mod.DETECTORS:
            return None
        steps = steps_mod.get_detector(steps)  # decision E94: "NAME:key=value,..." sets its settings
    if isinstance(steps, steps_mod.StepDetector):
        if steps.unit != "foot":
            raise DataError(f"plasys: steps={steps!r} is a {steps.unit} detector; the plasys pipeline integrates "
                            "the foot unit's strides: give a foot detector (unit = 'foot')")
        df = steps.detect(session)
        what = f"steps={steps!r}"
    elif isinstance(steps, pd.DataFrame):
        df, what = steps.copy(), "the steps table"
        missing = [c for c in ("start_s", "end_s") if c not in df]
        if missing:
            raise DataError(f"plasys: {what} has no {', '.join(missing)} column; give each stride's start_s and "
                            "end_s in s on the session's clock (docs/extending.md)")
        df["event_s"] = df["event_s"] if "event_s" in df else df["end_s"]
        df["confidence"] = df["confidence"] if "confidence" in df else 1.0
        df["unit"] = "foot"
        df.attrs.setdefault("detector", "table")
    else:
        return None
    if not len(df):
        raise DataError(f"session '{session.name}': {what} gave no strides")
    return df.reset_index(drop=True)


#: Decision L38: an offline stride is classified on the streaming segmenter's stride when the two cover the same
#: stride (IoU at least this; 0.1 s moved at each end of a 1 s stride still gives 0.82).
WINDOW_MIN_IOU = 0.8


def classification_windows(session: Session, strides: pd.DataFrame) -> pd.DataFrame:
    """Decision L38: the step windows M3 classifies the offline ``strides`` on, ``start_s``/``end_s`` (s).

    A model's step windows are cut at stance-to-stance boundaries in the middle of the foot's rest (the
    labelled steps it was trained on; ``track --streaming`` and the runtime cut at the strides of
    :class:`~pdrlearn.kernels.stride.StanceSegmenter` on the foot gyroscope). The offline strides' own
    rest-to-rest bounds come from the ZUPT stance (force sensors or the accelerometer + gyroscope test, on the
    upsampled grid) and sit ~30 ms later at 20 Hz (sim: +33 ms median against the labels, streaming +7 ms),
    enough to change the length class of a third of the strides. So each offline stride is classified on the
    segmenter's stride that covers it (IoU >= :data:`WINDOW_MIN_IOU`), and on its own bounds when none does."""
    out = strides[["start_s", "end_s"]].reset_index(drop=True).copy()
    out.attrs["segmenter_windows"] = 0
    gyro = session.streams.get("fGyroscope")
    if gyro is None or not len(out):
        return out
    seg = SK.stance_strides(gyro.t, gyro.values)  # the streaming default segmenter (track --streaming, runtime)
    if not len(seg):
        return out
    pairs = match_by_overlap(out, pd.DataFrame({"start_s": seg[:, 0], "end_s": seg[:, 1]}), min_iou=WINDOW_MIN_IOU)
    if pairs:
        oi, si = (np.array(v) for v in zip(*pairs, strict=True))
        out.loc[oi, "start_s"], out.loc[oi, "end_s"] = seg[si, 0], seg[si, 1]
        out.attrs["segmenter_windows"] = len(pairs)
    return out


def model_windows(session: Session, steps: pd.DataFrame) -> pd.DataFrame:
    """Decision C51: the window a trained model classifies each row of a detected ``steps`` table on, as
    ``track --method M3`` does: the row made a rest-to-rest stride of the foot unit (the stance of the force
    sensors, else of the accelerometer + gyroscope, on :class:`~pdrlearn.displace.FootDisplacement`'s grid,
    :func:`~pdrlearn.displace.foot.rest_to_rest`), then re-cut on the streaming segmenter's stride that covers
    it (:func:`classification_windows`, decision L38). A detector's swing or contact-to-contact window is not
    the rest-to-rest window a model is trained on (scenario D: 63 of 68 strides 'up' on the detector's own
    bounds). One row per row of ``steps`` (``start_s``/``end_s``, s); a row in no stride keeps its own bounds,
    a row spanning several strides (missed steps, which ``track`` splits) gets their whole span; both are
    counted in ``attrs`` (``own_bounds``, ``several_strides``). Without the foot unit: the rows' own bounds."""
    out = steps[["start_s", "end_s"]].astype(float).reset_index(drop=True)
    own, several = 0, 0
    if len(out) and session.has("fAccelerometer", "fGyroscope"):
        foot = unit_data(session, "foot", purpose="the model's step windows")
        stance = checked_stance(session, foot)[0]  # as M3: the force sensors' stance, checked (L365)
        s0, s1, rows = FootDisplacement().stride_bounds(foot, out, stance=stance)
        by = pd.DataFrame({"start_s": s0, "end_s": s1, "row": rows}).groupby("row")
        lo, hi = by["start_s"].min(), by["end_s"].max()
        out.loc[lo.index, "start_s"], out.loc[hi.index, "end_s"] = lo.to_numpy(), hi.to_numpy()
        own, several = len(out) - len(lo), int((by.size() > 1).sum())
    win = classification_windows(session, out)
    win.attrs.update(own_bounds=own, several_strides=several)
    return win


def classes_and_bounds(model, session: Session, steps: pd.DataFrame) -> tuple[pd.DataFrame, object]:
    """M3's step classes and the user's stride-length class bounds, from a trained model or, with
    ``model="oracle"``, from the session's own labels and ``meta.json`` (one place for the offline and the
    streaming paths)."""
    if isinstance(model, str) and model == "oracle":
        bounds = next((session.meta[k] for k in ("length_class_bounds_m", "length_bounds_m")
                       if session.meta.get(k) is not None), None)
        classes = oracle_classes(session, steps)
        classes.attrs["label_warnings"] = oracle_label_warnings(session)
        return classes, bounds
    return _model_classes(model, session, steps)


def oracle_label_warnings(session: Session) -> list[str]:
    """Decision B209: ``evaluate``'s line (C33) for each task whose labels in the session's steps.csv are not all
    classes, for ``model="oracle"``, whose strides take those labels as their classes (every terrain 'lava' had
    tracked without a word, no stride up or down)."""
    from pdrlearn.classify.labels import label_warnings

    if session.steps is None:
        return []
    return [f"{ln}; model='oracle' takes the labels as the strides' classes, so those strides get no class rule: "
            "fix the labels" for ln in label_warnings(session, session.steps, "steps.csv")]


def oracle_classes(session: Session, steps: pd.DataFrame) -> pd.DataFrame:
    """Classes of each stride from the session's own labels (matched by time overlap)."""
    lab = session.steps
    if lab is None or not any(c in lab for c in ("terrain", "direction", "length_class")):
        raise DataError(f"session '{session.name}': model='oracle' needs labelled steps "
                        "(steps.csv with terrain/direction/length_class)")
    out = pd.DataFrame(index=range(len(steps)), columns=["terrain", "direction", "length_class"],
                       dtype=object)
    pairs = match_by_overlap(steps, lab.reset_index(drop=True), min_iou=0.3)
    if pairs:
        ei, ri = (np.array(v) for v in zip(*pairs, strict=True))
        for c in out.columns:
            if c in lab:
                col = out[c].to_numpy(dtype=object, copy=True)
                col[ei] = lab[c].to_numpy(dtype=object)[ri]
                out[c] = col
    out["confidence"] = 1.0
    return out


def _model_classes(model, session: Session, steps: pd.DataFrame) -> tuple[pd.DataFrame, dict | None]:
    """Classes from a trained model (object or model directory) and its length-class bounds, if any."""
    if isinstance(model, str | Path):
        from pdrlearn.classify import load_model

        model = load_model(model)
    # decision C51: the strides are cut already; C18's rate line is the tracker's own warning (rate_check)
    from pdrlearn.classify import UserModel

    # decision C71: no joint domain score (it failed its adoption rule; predict_steps' option, C162)
    pred = (model.predict_steps(session, steps, windows="given", warn_rate=False)
            if isinstance(model, UserModel)
            else model.predict_steps(session, steps)).reset_index(drop=True)
    if len(pred) != len(steps):
        raise ModelError(f"model predicted {len(pred)} rows for {len(steps)} strides")
    bounds = model_length_bounds(model)
    if "confidence" not in pred:
        maxima = [pred[[c for c in pred.columns if c.startswith(f"p_{task}_")]].max(axis=1)
                  for task in TASK_COLUMNS if any(c.startswith(f"p_{task}_") for c in pred.columns)]
        pred["confidence"] = np.min(np.column_stack(maxima), axis=1) if maxima else 1.0
    return pred, bounds


def domain_check(model, classes: pd.DataFrame, warnings: list[str], warn_at: float | None = None,
                 session=None) -> dict | None:
    """Decision C16: how many strides lie outside the trained model's training range (the range of each
    classifier's own inputs); one warning line appended when the fraction reaches ``warn_at`` (opt-in) or, without
    it, when more than half the strides are out (decision C61, :func:`~pdrlearn.classify.domain.session_warning_line`).
    ``None`` for oracle labels; for a model saved before C16 a note (no check)."""
    if model is None or isinstance(model, str | Path) or not hasattr(model, "domain_report") or not model.tasks:
        return None  # C17: a model without a classifier (level walks only) classifies nothing to check
    from pdrlearn.classify.domain import NO_RANGES_NOTE, session_warning_line

    if not model.has_domain:
        log.info(NO_RANGES_NOTE)
        return {"out_of_domain_fraction": None, "note": NO_RANGES_NOTE}
    report = model.domain_report(classes, warn_at=warn_at)
    from pdrlearn.classify.training import own_user

    # decision C227: the advice for a per-user model on its own user's session (``session``) is its calibration
    line = session_warning_line(report, what="strides", user=None if session is None else own_user(model, session))
    if line:
        warnings.append(line)
    return report


def rate_check(model, session: Session, classes: pd.DataFrame, warnings: list[str]) -> dict | None:
    """Decision C18: one warning line when a unit whose classifiers classified the strides runs at a rate
    other than the one the model was trained at (:func:`pdrlearn.classify.training.rate_mismatch`, shared with
    ``UserModel.predict_steps`` and ``evaluate``, decision C52): the step windows then hold other signals (a
    20 Hz simulator model on a 100 Hz real foot classified 28 of 32 level strides 'up'). Returns unit ->
    ``{"trained_hz", "session_hz"}`` of the units that differ (None: none, or oracle labels / a model
    without rates). Decision C138: also one line when the per-user model was fitted on another user than the
    session's meta.json names."""
    if isinstance(model, str | Path):
        return None
    from pdrlearn.classify.training import other_user_line, rate_mismatch

    off = rate_mismatch(model, session, classes)
    if off:
        warnings.append(classifier_rate_warning(off, resample_hint=True))
    line = other_user_line(model, [session], "track")  # decision C138: a per-user model on another user
    if line:
        warnings.append(line)
    from pdrlearn.classify.force_scale import force_scale_line, model_force

    line = force_scale_line(model_force(model), session)  # decision C153: force in another unit than the training's
    if line:
        warnings.append(line)
    return off


#: decision W431: a streamed two-unit track's ``trunk_note`` (summary ``tug_time_note``): W418's TUG is offline only
STREAMED_TRUNK_NOTE = ("no chair transfers and no TUG in a --streaming track (W418 reads them offline only): "
                       "pdrlearn track {where} without --streaming (W431)")


def align_clocks(session: Session, warnings: list[str], *, force_table=None) -> tuple[Session, dict | None]:
    """Waist streams moved onto the foot clock with the steps detected by both units (thesis ch.7.2.2:
    the gyroscope-detected steps align the units); the session unchanged when that fails. ``track --align-units``
    (L162) and ``run --align-units`` (L170) share it. Decision L186: an estimate that did not lock (L183's
    :func:`~pdrlearn.kernels.align.offset_locked`) is not applied: the session unchanged and one line why.
    ``force_table``: :func:`~pdrlearn.steps.align.align_estimate`'s (steps decision 55)."""
    try:
        from pdrlearn.kernels.align import twin_line, unlocked_message, untrusted_message
        from pdrlearn.steps.align import align_estimate

        est = align_estimate(session, force_table=force_table)
        # decision L186: an unlocked estimate tells no offset (L183); L446: nor does one that cannot be trusted
        line = unlocked_message(est) or untrusted_message(est)
        if line is not None:
            warnings.append(line)
            return session, None
        moved = move_waist_clock(session, est["offset_s"], est["drift"], warnings, source="estimated",
                                 ref_s=est["ref_s"])  # decision L198: the offset holds at ref_s
        if (line := twin_line(est)) is not None:  # decision E228: applied, and its twin a step away named
            warnings.append(line)
        return moved
    except (ImportError, AttributeError):
        warnings.append("pdrlearn.steps.align_units not available: unit clocks not aligned")
    except DataError as exc:
        warnings.append(f"unit clocks not aligned ({exc})")
    return session, None


#: the option that moved the waist clock, by ``source`` of :func:`move_waist_clock` (the lines name it)
CLOCK_OPTIONS = {"estimated": "--align-units", "given": "--clock-offset"}


def move_waist_clock(session: Session, offset_s: float, drift: float, warnings: list[str], *,
                     source: str, ref_s: float | None = None, option: str | None = None) -> tuple[Session, dict]:
    """The waist streams moved onto the foot clock, ``t_foot = ref_s + (t_waist - offset_s - ref_s) / (1 + drift)``
    (:func:`pdrlearn.steps.align.apply_alignment`; ``offset_s`` is the offset at foot-clock time ``ref_s``, decision
    L198; None: 0, a given drift-free offset), and what was applied: ``{"offset_s", "drift", "source"}`` (+ ``ref_s``
    when given: an estimate's)
    (``source`` ``"estimated"``: ``--align-units``' estimate, L162; ``"given"``: ``--clock-offset``, E111), with
    ``common_span_s`` when the moved clock left the units apart and the time both cover was kept (B83's cut,
    one line in ``warnings`` naming the option: ``option``, else the source's, :data:`CLOCK_OPTIONS`)."""
    from pdrlearn.io.plasys import cut_to_common_span
    from pdrlearn.steps.align import apply_alignment

    aligned = apply_alignment(session, offset_s, drift, 0.0 if ref_s is None else ref_s)
    info = {"offset_s": float(offset_s), "drift": float(drift), "source": source}
    if ref_s is not None:  # decision L198: the foot-clock time the estimated offset holds at
        info["ref_s"] = float(ref_s)
    # decision L162: the moved waist clock may leave the units apart (B83): the time both cover is kept
    cut = cut_to_common_span(aligned.streams, session.folder or Path(session.name))
    if cut is not None:
        info["common_span_s"] = [float(cut[0]), float(cut[1])]
        warnings.append(f"{option or CLOCK_OPTIONS[source]} moved the waist clock by {-offset_s:+.2f} s (drift "
                        f"{drift * 1e6:+.0f} ppm); tracked {cut[0]:.2f}-{cut[1]:.2f} s, where both units have data: "
                        f"dropped {cut[2]} (decision L162)")
    return aligned, info


from pdrlearn.kernels.align import UNIT_OFFSET_WARN_S  # noqa: E402, F401 (decision L161; shared with the runtime, L177)


def unit_offset_line(session: Session, command: str = "pdrlearn track", *, force_table=None) -> str | None:
    """Decision L161: the warning line when :func:`pdrlearn.steps.align_units` finds the waist unit's steps over
    :data:`UNIT_OFFSET_WARN_S` from the foot's; None when under it or when the steps do not align (too few).
    ``command``: the one whose ``--align-units`` the line names (``pdrlearn run``, decision L170); ``force_table``:
    :func:`~pdrlearn.steps.align.align_estimate`'s (steps decision 55)."""
    from pdrlearn.kernels.align import unit_offset_message
    from pdrlearn.steps.align import align_estimate

    try:
        est = align_estimate(session, force_table=force_table)
    except DataError:
        return None
    from pdrlearn.kernels.align import offset_locked, untrusted_message

    if offset_locked(est) and (line := untrusted_message(est, None)) is not None:  # decision L446: no offset named
        return line
    return unit_offset_message(est["offset_s"], est["drift"], command, estimate=est)  # L183: locked estimates only


def fuse_heading(relative: np.ndarray, absolute: np.ndarray, t: np.ndarray, *, tau_s: float = 60.0,
                 keep: np.ndarray | None = None) -> np.ndarray:
    """Relative foot heading (accurate turns, slow drift) aligned to the absolute waist heading (noisy,
    magnetically disturbed) by a slowly varying offset: the circular mean of ``absolute - relative``
    over a +-``tau_s`` window of strides (rad). ``keep`` (decision L589): the strides the mean counts (the straight
    ones: a foot pivoting on the spot travels about 90 deg off the facing the waist reads); a window without a kept
    stride counts all its strides. None = all."""
    if len(relative) == 0:
        return relative
    d = wrap_angle(np.asarray(absolute) - np.asarray(relative))
    lo = np.searchsorted(t, t - tau_s, side="left")
    hi = np.searchsorted(t, t + tau_s, side="right")

    def window_sums(w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        cc, cs, cn = (np.concatenate([[0.0], np.cumsum(v)]) for v in (w * np.cos(d), w * np.sin(d), w))
        return cc[hi] - cc[lo], cs[hi] - cs[lo], cn[hi] - cn[lo]

    c, s, _ = window_sums(np.ones(len(d)))
    if keep is not None:  # decision L589: the offset from the straight strides where the window has any
        ck, sk, nk = window_sums(np.asarray(keep, float))
        c, s = np.where(nk > 0, ck, c), np.where(nk > 0, sk, s)
    return np.asarray(relative) + np.arctan2(s, c)


#: decision L471 (adopted by its rule; docs/decisions/localization.md): the fused heading's +-``tau_s`` window is
#: measured on :func:`walking_clock` (a stop between strides counts L79's 3 s at most); False = L17's clock time
FUSED_WALKING_CLOCK = True


def walking_clock(start_s: np.ndarray, end_s: np.ndarray, *, max_stop_s: float | None = None) -> np.ndarray:
    """Decision L471: the strides' end times ``end_s`` (s, sorted) with every interval from one stride's end to the
    next one's start that is longer than ``max_stop_s`` (None = L79's 3 s, ``kernels.contact.MAX_STRIDE_S``)
    shortened to ``max_stop_s``: the time in which the foot's relative heading can drift (at rest its ZUPT/ZARU
    holds it), so L17's window does not split a walk at a long rest."""
    from pdrlearn.kernels.contact import MAX_STRIDE_S

    cap = MAX_STRIDE_S if max_stop_s is None else float(max_stop_s)
    start_s, end_s = np.asarray(start_s, float), np.asarray(end_s, float)
    if len(end_s) < 2:
        return end_s.copy()
    excess = np.clip(start_s[1:] - end_s[:-1] - cap, 0.0, None)
    return end_s - np.concatenate([[0.0], np.cumsum(excess)])


def fuse_with_drift(relative: np.ndarray, absolute: np.ndarray, t: np.ndarray, *,
                    min_span_s: float | None = None) -> np.ndarray:
    """Decision L266: ``relative`` (a gyroscope heading whose rate bias was not removed: its error grows with time)
    turned to ``absolute`` by an offset that drifts linearly in ``t`` (s): the least-squares line of the wrapped
    difference ``absolute - relative`` about its circular mean (rad). A constant offset (L226) is the mean of a
    drifting difference, wrong at both ends of a long recording by half the drift; a line takes the gyroscope's
    constant rate bias out and leaves a place-dependent compass error unfollowed (it averages over the stretch).
    ``min_span_s`` (decision L280): a stretch spanning less than this gets one constant offset (L226) - over a short
    stretch a line fits the compass's place-dependent error, not the gyroscope's drift."""
    relative, absolute, t = (np.asarray(a, dtype=float) for a in (relative, absolute, t))
    if len(relative) < 2 or not np.ptp(t) > 0 or (min_span_s is not None and np.ptp(t) < min_span_s):
        return fuse_heading(relative, absolute, t, tau_s=np.inf)
    from pdrlearn.orient._kernels import drift_line

    return relative + drift_line(wrap_angle(absolute - relative), t)


#: decision L84: "fused" fits the waist magnetometer's horizontal hard-iron offset from the walk (not adopted:
#: the rule's measurement is in docs/decisions/localization.md); ``track_plasys(hard_iron_fit=True)`` turns it on
HARD_IRON_FIT = False
#: decision L219 (adopted by its rule): with the waist / fused heading, a sideways run's travel angle (minus the
#: foot's usual offset) is added after the waist heading instead of fused into it; False = before L219
SIDE_TRAVEL_HEADING = True
#: L84's gates, fixed before measuring: the walk's stride headings spread enough (resultant length), enough
#: strides, and an offset no larger than the fitted horizontal field
HARD_IRON_MAX_RESULTANT = 0.5
HARD_IRON_MIN_STRIDES = 8


def stride_level_field(session: Session, strides: pd.DataFrame,
                       keep: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Per kept stride the waist magnetometer's mean level-forward / level-left field (uT, thesis eq. 33/34) over
    the stride's window, and the kept mask (strides with samples and ``keep``); None without a waist magnetometer
    (decisions L84, L182)."""
    u = unit_data(session, "waist", purpose="waist heading")
    if u.mag is None:
        return None
    _, fwd, left = level_axes(lowpass(u.acc, min(1.0, 0.4 * u.fs), u.fs))
    m_f, m_l = np.einsum("ij,ij->i", u.mag, fwd), np.einsum("ij,ij->i", u.mag, left)
    s = strides["start_s"].to_numpy(float)
    e = strides["end_s"].to_numpy(float)
    lo, hi = np.searchsorted(u.t, s, side="left"), np.searchsorted(u.t, e, side="right")
    ok = (hi > lo) & (np.ones(len(s), bool) if keep is None else np.asarray(keep, bool))
    cf, cl = np.concatenate([[0.0], np.cumsum(m_f)]), np.concatenate([[0.0], np.cumsum(m_l)])
    n = np.maximum(hi - lo, 1)
    return ((cf[hi] - cf[lo]) / n)[ok], ((cl[hi] - cl[lo]) / n)[ok], ok


def fit_waist_hard_iron(session: Session, strides: pd.DataFrame, psi: np.ndarray,
                        keep: np.ndarray | None = None) -> tuple[np.ndarray | None, dict]:
    """The waist magnetometer's horizontal hard-iron offset (uT, body FLU, z = 0) fitted on the walk itself
    (decision L84): per kept stride the mean level-forward / level-left field (thesis eq. 33/34) over its
    window against the foot's relative heading ``psi`` (rad), :func:`~pdrlearn.orient._kernels.
    fit_horizontal_hard_iron`. None (with the reason in the dict) when the session has no waist magnetometer,
    the walk turns too little (resultant length of ``psi`` > :data:`HARD_IRON_MAX_RESULTANT`), has fewer than
    :data:`HARD_IRON_MIN_STRIDES` strides, or the fitted offset exceeds the fitted horizontal field."""
    level = stride_level_field(session, strides, keep)
    if level is None:
        return None, {"applied": False, "reason": "no waist magnetometer"}
    mf_i, ml_i, ok = level
    psi_i = np.asarray(psi, dtype=float)[ok]
    out = {"applied": False, "n_strides": int(ok.sum())}
    if ok.sum() < HARD_IRON_MIN_STRIDES:
        return None, {**out, "reason": f"fewer than {HARD_IRON_MIN_STRIDES} strides"}
    b, field, resultant = fit_horizontal_hard_iron(mf_i, ml_i, psi_i)
    out.update({"resultant": resultant, "field_ut": field, "offset_ut": [float(b[0]), float(b[1])]})
    if resultant > HARD_IRON_MAX_RESULTANT:
        return None, {**out, "reason": "the walk turns too little to separate the offset from the heading"}
    if float(np.hypot(*b)) > field:
        return None, {**out, "reason": "fitted offset larger than the fitted field"}
    return np.array([b[0], b[1], 0.0]), {**out, "applied": True}


#: decision L182: the median angle (deg) between the waist compass and the foot's gyroscope heading, beyond L84's
#: hard-iron model, above which an offline track that reads the compass warns: 20 deg moves a track sideways by a
#: third of the distance, 2x the medians of default (3 uT, S33) simulated sessions (up to 9.1 deg)
COMPASS_DISAGREE_DEG = 20.0
#: decision L226 (adopted by its rule, L227; docs/decisions/localization.md): when L182's check warns, the fused
#: heading's relative part is the waist gyroscope's heading (not the foot's) and its offset to the compass is one
#: constant per stretch (not L17's +-60 s window); False = L17 as before
COMPASS_GYRO_FALLBACK = True
#: decision L266 (adopted with L264 by its rule, L265): the fallback's offset to the compass drifts
#: linearly per stretch (:func:`fuse_with_drift`), taking out the waist gyroscope's rate bias that one constant leaves
#: (the heading of a 27 min shift was 75 deg off at its first stride); False = L226's one constant
FALLBACK_DRIFT = True


#: decision L264: L182's check fits its model on windows of this length (s) of straight strides, each on its own:
#: L17's +-60 s, the span over which the fused heading itself trusts the foot's relative heading against the compass;
#: a foot heading that drifts over a 30-80 min shift (stairs, turns on the spot) is then judged only over the span
#: the track relies on it, while a field that changes from place to place still disagrees inside a window
COMPASS_CHECK_WINDOW_S = 120.0
#: decision L264 (adopted by its rule, L265): True = the windowed check; False = L182's one fit
COMPASS_CHECK_WINDOWED = True
#: decision L280 (candidate; docs/decisions/localization.md): L266's line only on a fallback stretch spanning at least
#: two of L264's windows; shorter, L226's one constant: over a 2-lap loop of ~100 s the line fitted the compass's
#: place-dependent error (L265: u5197 0.91 -> 5.34 m) while the waist gyroscope's bias (thesis Table 14: sd 0.0005
#: rad/s on its yaw axis) turns its heading ~3 deg per 100 s
FALLBACK_DRIFT_MIN_S = 2 * COMPASS_CHECK_WINDOW_S
#: decision L280: L182's one fit over the whole walk also judges (OR with L264's windows) a walk whose straight
#: strides span at most this (s): the walks L182's one fit and L226's fallback were validated on (R1 x2, 6-7.5 min,
#: L227; R1 x4, 12 min, L226), under the 26-81 min shifts where it misjudged (L264)
COMPASS_ONE_FIT_MAX_S = 900.0
#: decision L280 (adopted by its rule, L281): True = the two gates above; False = L264 / L266 as adopted in L265
COMPASS_SPAN_GATES = True


def compass_windows(t: np.ndarray, window_s: float, min_n: int) -> list[np.ndarray]:
    """Decision L264: the indices of the times ``t`` (sorted, s) cut into consecutive windows of ``window_s``
    from the first; a window of fewer than ``min_n`` joins the one before it (the first, the one after it), so every
    window holds at least ``min_n`` when ``len(t) >= min_n``."""
    t = np.asarray(t, float)
    if not len(t):
        return []
    key = np.floor((t - t[0]) / window_s).astype(int)
    groups = [np.flatnonzero(key == k) for k in np.unique(key)]
    out: list[np.ndarray] = []
    for g in groups:
        if out and (len(g) < min_n or len(out[-1]) < min_n):
            out[-1] = np.concatenate([out[-1], g])
        else:
            out.append(g)
    if len(out) > 1 and len(out[-1]) < min_n:
        out[-2] = np.concatenate([out[-2], out.pop()])
    return out


def windowed_disagreement(m_fwd: np.ndarray, m_left: np.ndarray, psi: np.ndarray, t: np.ndarray, *,
                          window_s: float = COMPASS_CHECK_WINDOW_S,
                          min_n: int = HARD_IRON_MIN_STRIDES) -> np.ndarray:
    """Decision L264: :func:`~pdrlearn.orient._kernels.compass_disagreement`'s angles (rad), its model fitted on each
    :func:`compass_windows` window of the strides at times ``t`` (s) on its own; in the order of ``t``. Decisions
    L544 / L558 (adopted by L558's rule, L559): with at least two windows, no hard-iron offset in a window whose
    headings do not spread (L84's gate) and a heading offset that drifts linearly in the window (the foot
    gyroscope's drift); a walk of one window is fitted as L182's one fit."""
    from pdrlearn.orient._kernels import compass_disagreement

    ang = np.zeros(len(psi))
    groups = compass_windows(t, window_s, min_n)
    drift = len(groups) > 1  # decisions L558 / L559: one window is L182's one fit, judged exactly as before
    for g in groups:
        ang[g] = compass_disagreement(np.asarray(m_fwd, float)[g], np.asarray(m_left, float)[g],
                                      np.asarray(psi, float)[g],
                                      max_resultant=HARD_IRON_MAX_RESULTANT if drift else None,
                                      t=np.asarray(t, float)[g] if drift else None)[0]  # decision L544
    return ang


def compass_check(session: Session, strides: pd.DataFrame, psi: np.ndarray,
                  keep: np.ndarray, *, windowed: bool | None = None, lengths: np.ndarray | None = None,
                  in_place_stride_m: float | None = 0.10) -> tuple[str | None, dict | None]:
    """Decision L182: (a warning line or None, ``info.compass_check``) for a track whose heading reads the waist
    compass: the median |angle| (:func:`~pdrlearn.orient._kernels.compass_disagreement`) of the ``keep`` strides
    (straight, outside foot gaps) against the foot's relative heading ``psi`` (rad), with at least
    :data:`HARD_IRON_MIN_STRIDES` of them; (None, None) without a waist magnetometer or enough strides. Decision
    W589: a stride whose horizontal travel ``lengths`` (m) is under ``in_place_stride_m`` (L778's steps in place)
    is left out - ``psi`` is its travel direction, and a 1-3 cm shuffle's direction is no heading (None: the rule
    before W589)."""
    if lengths is not None and in_place_stride_m is not None:  # decision W589
        keep = np.asarray(keep, bool) & (np.nan_to_num(np.asarray(lengths, float)) >= in_place_stride_m)
    level = stride_level_field(session, strides, keep)
    if level is None or int(level[2].sum()) < HARD_IRON_MIN_STRIDES:
        return None, None
    mf, ml, ok = level
    psi_ok = np.asarray(psi, float)[ok]
    windowed = COMPASS_CHECK_WINDOWED if windowed is None else windowed
    t = strides["start_s"].to_numpy(float)[ok]
    angle, info = check_angle(mf, ml, psi_ok, t, windowed=windowed)
    if not angle > COMPASS_DISAGREE_DEG:
        return None, info
    over = {"windows": f" (each {COMPASS_CHECK_WINDOW_S:g} s window on its own, L264)",
            "one fit": f" (one fit over a walk of at most {COMPASS_ONE_FIT_MAX_S:g} s, L280)"}[info["by"]] \
        if windowed else ""
    return (f"the waist compass disagrees with the foot's gyroscope heading by a median {angle:.1f} deg over "
            f"{int(ok.sum())} straight strides{over}, more than a hard-iron offset explains (over "
            f"{COMPASS_DISAGREE_DEG:g} deg warns, decision L182): one of the two headings is wrong and the check "
            "cannot tell which (a magnetic disturbance turns the compass; the foot's own yaw drifts over a walk; "
            "decision L336); track with `--compass off` (the gyroscopes' heading, decision L657), `--streaming` (the "
            "waist gyroscope's) or `--units foot` (the foot's own) if it is the compass: this offline track's heading "
            "follows the compass (L17)"), info


def check_angle(mf: np.ndarray, ml: np.ndarray, psi: np.ndarray, t: np.ndarray, *, windowed: bool,
                span_gates: bool | None = None) -> tuple[float, dict]:
    """Decisions L182 / L264 / L280: the median |angle| (deg) L182's check judges, from the straight strides' level
    field ``mf`` / ``ml`` (uT), the foot's relative heading ``psi`` (rad) and their times ``t`` (s), and the
    ``info.compass_check`` dict. ``windowed``: each L264 window on its own; with ``span_gates`` (None =
    :data:`COMPASS_SPAN_GATES`) a walk spanning at most :data:`COMPASS_ONE_FIT_MAX_S` is also judged by L182's one
    fit, and the larger median judges (L280); the windows are fitted as L558 / L559 adopted."""
    from pdrlearn.orient._kernels import compass_disagreement

    gates = COMPASS_SPAN_GATES if span_gates is None else span_gates
    one = None
    if not windowed or (gates and np.ptp(t) <= COMPASS_ONE_FIT_MAX_S):  # decision L182 / L280: one fit
        one = float(np.degrees(np.median(np.abs(compass_disagreement(mf, ml, psi)[0]))))
    win = float(np.degrees(np.median(np.abs(windowed_disagreement(mf, ml, psi, t))))) if windowed else None
    angle, by = max((a, b) for a, b in ((win, "windows"), (one, "one fit")) if a is not None)
    info = {"median_deg": angle, "n_strides": int(len(psi)), "limit_deg": COMPASS_DISAGREE_DEG,
            "window_s": COMPASS_CHECK_WINDOW_S if windowed else None, "by": by,
            "median_windows_deg": win, "median_one_fit_deg": one}
    return angle, info


# decision L18: DEFAULT_MODEL_RULES ("bayes") and DEFAULT_MIN_CONFIDENCE (0.95), the default rule with a model's
# classes and its confidence gate, live in pdrlearn.kernels.bayes since L40 (the streaming runtime applies them)


#: what M3 does for each task a model does not classify: the no-model behaviour of that rule (decision C17)
_UNTRAINED_FALLBACK = {"terrain": "horizontal distance, a stride under 0.10 m of height change is level (L39)",
                       "direction": "the estimate's own sign", "length": "no length clamp"}


def untrained_tasks(classes: pd.DataFrame) -> list[str]:
    """The tasks whose classes a model gave to no stride: not trained (e.g. a model trained on level walks
    only), or not runnable on the session's sensors (decision C17)."""
    return [t for t, col in TASK_COLUMNS.items() if col not in classes or classes[col].isna().all()]


#: the streamed stride rules (``kernels.stride.apply_stride_rules``) for a class the model does not give: C17
#: changed the offline path only, so terrain keeps each stride's raw height change there (no L39)
_UNTRAINED_STREAMED = {**_UNTRAINED_FALLBACK, "terrain": "the stride's raw height change (no L39 level rule)"}


def untrained_warning(tasks: list[str], streaming: bool = False) -> str:
    """One line: which classes the model does not give and what M3 does instead (decision C17); ``streaming``:
    what the streamed stride rules do instead."""
    fallback = _UNTRAINED_STREAMED if streaming else _UNTRAINED_FALLBACK
    return (f"the model classifies no {', '.join(tasks)} (not trained, or not on this session's sensors); "
            + ("streamed: " if streaming else "as without a model: ")
            + "; ".join(f"{t}: {fallback[t]}" for t in tasks)
            + f" (decision C17; train with {', '.join(tasks)} labels for those rules)")


def _confident(classes: pd.DataFrame, min_confidence: float) -> pd.DataFrame:
    """Classes whose probability (``p_<task>_<class>`` columns) is below ``min_confidence`` set to None,
    so that their rule is not applied (0 = always apply, as the thesis does)."""
    out = classes.copy()
    if min_confidence <= 0:
        return out
    for task, col in TASK_COLUMNS.items():
        pcols = [c for c in classes.columns if c.startswith(f"p_{task}_")]
        if pcols and col in out:
            low = classes[pcols].max(axis=1).to_numpy(float) < min_confidence
            out.loc[low, col] = None
    return out


def _length_proba(classes: pd.DataFrame) -> list[dict[str, float] | None]:
    """Per stride, the model's length-class probabilities (class -> p, from ``p_length_<class>``), or None
    (oracle labels: the bayes rule takes the label as certain)."""
    cols = {c[len("p_length_"):]: c for c in classes.columns if c.startswith("p_length_")}
    if not cols:
        return [None] * len(classes)
    p = classes[list(cols.values())].to_numpy(float)
    return [dict(zip(cols, row, strict=True)) for row in p.tolist()]


def _distance_gain(requested: float | None, model, fs: float, warnings: list[str],
                   calibration: bool = True, streaming: bool = False,
                   resampled_hz: float | None = None) -> tuple[float, str, float | None]:
    """The distance gain to apply (decision L26), where it comes from, and the user's calibrated relative
    sd of one stride's length estimate (None: no applicable calibration). ``streaming``: the record of the
    streamed stride kernel when the model has one (decision L41), else the offline engine's. ``fs``: the foot's
    recorded rate, also when the session was resampled to the model's ``resampled_hz`` (decisions E22, B113:
    resampling does not restore what the recording rate lost)."""
    rec = model_distance_calibration(model) if calibration and not (model is None or isinstance(model, str)) \
        else None
    if streaming:
        rec = streaming_calibration(rec)
    rec, warning = applicable_calibration(rec, fs, resampled_hz=resampled_hz)  # the runtime's check (E14)
    if warning:
        warnings.append(warning)
    sd = calibrated_stride_sd(rec)
    if requested is not None:
        g = float(requested)
        if not np.isfinite(g) or not 0.5 < g < 2.0:
            raise DataError(f"plasys: distance_gain={requested!r} must be a finite factor between 0.5 and 2 "
                            "(1.0 = off)")
        return g, "argument", sd
    if rec is None:
        src = "none" if model is None or isinstance(model, str) else "none (no applicable calibration in the model)"
        return 1.0, src, None
    return float(rec.get("gain", 1.0)), "model", sd


def require_stride_cover(session: Session, names, command: str = "pdrlearn track") -> None:
    """Decision B21 for the stride-local kernel of the streaming runtime (``track --streaming``, ``pdrlearn
    run`` replaying a session): strides come from the foot gyroscope and each stride's samples of every other
    stream in ``names`` (foot accelerometer, force, waist, barometer) are cut and interpolated there, so each
    must cover the gyroscope's span (:meth:`~pdrlearn.io.session.Session.require_cover`): a waist
    accelerometer that stopped after 60 s of 90 s moved the sim D_u1 replay's final position by 28 m, a foot
    accelerometer that stopped there cut its distance by 31 %, without a word. ``command``: the one whose
    ``--common-span`` the refusal names (decision B230)."""
    used = {n for group in GROUP_STREAMS.values() for n in group}
    session.require_cover("fGyroscope", *(n for n in names if n in used and n != "fGyroscope" and n in session),
                          command=command)


#: decision L494 (docs/decisions/localization.md): a foot-only heading's 0 is the first walk's direction (W390's
#: circular mean of the first strides' travel headings), not the foot unit's facing, which a unit yawed on the shoe
#: turns (trial T3: 20 deg -> 13.24 m off on a 45 m route; adopted, W413: no module switch); the first walk's
#: direction is the circular mean of its first (up to) this many walking strides' headings (W390's measured count;
#: its lower-back switch was removed, W401)
WALK_REFERENCE_STRIDES = 4
#: decision E215: the streamed track's ``info["compass_mount"]``: D25's check is not needed there (measured: a waist
#: turned 90 / 180 deg on the belt or mirrored moved the streamed end by at most 0.059 m, users 9880-9884)
STREAMED_COMPASS_MOUNT = ("not needed: the streamed heading reads no compass (the waist or foot gyroscope's rate about "
                          "the vertical, which a unit's yaw on the belt does not change; decision E215)")


def foot_walk_reference(head: np.ndarray, disp: np.ndarray, lateral: np.ndarray | None = None,
                        turn: np.ndarray | None = None) -> float:
    """Decision L494: the direction (rad) of the first walk in the strides' foot-only travel headings ``head`` (rad,
    0 = the foot unit's facing at the start): the circular mean of the first :data:`WALK_REFERENCE_STRIDES` finite
    headings of the strides longer than the frame inference's walking stride (``MIN_STRIDE_M``, D8; horizontal
    displacement ``disp``, m), as W390 read a walk's direction; 0 when there is none. Decision L510: with
    ``lateral`` (each stride's travel angle from the foot's facing, rad, left +) a sideways stride (L219's
    :func:`~pdrlearn.kernels.sideways.is_sideways`, ``turn`` its foot's heading change, L400) reads the walker's
    facing, its heading less 90 deg to its side, so 0 is the walker's facing at the first walk, not a first
    shuffle's travel (a backward stride's heading is its facing already: its length carries the sign)."""
    from pdrlearn.kernels.sideways import is_sideways
    from pdrlearn.track.frame_inference import MIN_STRIDE_M

    disp = np.asarray(disp, float)
    head = np.asarray(head, float)
    hlen = np.hypot(disp[:, 0], disp[:, 1])
    if lateral is not None:  # decision L510: a side stride travels at the facing +-90 deg
        lateral = np.asarray(lateral, float)
        head = head - np.where(is_sideways(lateral, hlen, turn), np.sign(lateral) * np.pi / 2, 0.0)
    head = head[hlen > MIN_STRIDE_M]
    head = head[np.isfinite(head)][:WALK_REFERENCE_STRIDES]
    return float(np.angle(np.mean(np.exp(1j * head)))) if len(head) else 0.0


def _stride_heading(wh: WaistHeading, steps: pd.DataFrame) -> np.ndarray:
    """Mean waist heading over each stride window (rad)."""
    s = steps["start_s"].to_numpy(float)
    e = steps["end_s"].to_numpy(float)
    grid = s[:, None] + (e - s)[:, None] * np.linspace(0, 1, 9)[None, :]
    return wh.heading_at(grid.ravel()).reshape(grid.shape).mean(axis=1)


def split_events(strides: pd.DataFrame, rows: np.ndarray, t: np.ndarray, stance: np.ndarray) -> np.ndarray:
    """Decision L96: the ``event_s`` (initial contact, s) of rest-to-rest strides ``strides`` whose input rows
    ``rows`` repeat (one detected window split at the rests inside it, :func:`pdrlearn.displace.rest_to_rest`):
    each piece of a split window gets the start of the rest that ends it (the foot lands; as
    :func:`stance_strides`'s event), instead of the window's one contact repeated in every piece (which gave
    none of them a stride time). Rows used once keep their detector's event."""
    ev = strides["event_s"].to_numpy(dtype=float).copy()
    rows = np.asarray(rows)
    _, inv, counts = np.unique(rows, return_inverse=True, return_counts=True)
    split = counts[inv] > 1
    if not split.any():
        return ev
    rr = stance_runs(t, stance)
    if not len(rr):
        return np.where(split, np.nan, ev)
    rs = t[rr[:, 0]]
    st, en = strides["start_s"].to_numpy(dtype=float), strides["end_s"].to_numpy(dtype=float)
    k = np.searchsorted(rs, en, side="right") - 1  # the last rest starting by the piece's end
    land = np.where(k >= 0, rs[np.clip(k, 0, len(rs) - 1)], np.nan)
    land = np.where((land > st) & (land <= en), land, np.nan)
    return np.where(split, land, ev)


#: decision L160: a stride across dropped foot samples (an interval up to 1 s, not a B11 gap) takes its neighbours'
#: height change (the BLE trial's 5 % burst loss: a flat 400 m walk +7.96 m, all from those strides)
GAP_STRIDE_HEIGHT = True

#: Decision L184 (adopted by its rule, experiments/gated_level_dz.py): offline M3 gives L39's level rule to the
#: strides whose terrain class the confidence gate (L18) dropped, instead of their raw integrated height
GATED_LEVEL_DZ = True
#: decision B297: added to L161's unit-offset line when the insoles' own clock is off (L390): the foot's contacts it
#: compares the waist's steps with are the insoles' (trial T2 finding 8: a +150 ms insole shift blamed the waist)
INSOLE_CLOCK_NOTE = (" - but the foot's contacts here are the force insoles', whose clock is off against the foot IMU "
                     "(decision L390's line): re-align the insoles first")
#: decision L388 (not adopted: its rule was not met, so off): True = ``--toe-off`` with a force stance takes the
#: insoles' drop-off as the toe-off; False = L73's gyroscope toe-off always
FORCE_TOE_OFF = False


def _sideways_rows(lateral: np.ndarray, disp: np.ndarray, turn: np.ndarray | None = None) -> np.ndarray:
    """Decision L228: the strides of L219's sideways runs (:func:`pdrlearn.kernels.sideways.sideways_runs` over each
    stride's travel angle ``lateral`` rad from the foot's facing and its horizontal displacement ``disp``), the
    steps table's ``sideways`` column: a side step has its own rhythm and length, no steady walker's stride;
    ``turn`` the foot's heading change over each stride (rad; decision L400: a turning stride is none)."""
    from pdrlearn.kernels.sideways import sideways_runs

    side = np.zeros(len(lateral), dtype=bool)
    for a, b in sideways_runs(lateral, np.hypot(disp[:, 0], disp[:, 1]), turn):
        side[a:b + 1] = True
    return side


def _drop_impossible(length: np.ndarray, dz: np.ndarray, t0: np.ndarray, t1: np.ndarray,
                     warnings: list[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Decision L94: a stride faster than any human moves 0 m (a gap), with one warning line for the session,
    never summed into the distance; a non-finite one is an :class:`InternalError` (a bug, as the runtime's E38).
    Returns (length, dz, bad): ``bad`` (B,) the zeroed strides, which decision L97 leaves out of the gait
    parameters (steps.csv column ``impossible``)."""
    nonfinite = ~(np.isfinite(length) & np.isfinite(dz))
    if nonfinite.any():
        i = int(np.flatnonzero(nonfinite)[0])
        raise InternalError(SK.non_finite_stride_error("pdrlearn.track (plasys)", float(t0[i]), float(t1[i]),
                                                       float(length[i]), float(dz[i])))
    bad = SK.impossible_strides(length, dz, np.asarray(t1, dtype=float) - np.asarray(t0, dtype=float))
    if not bad.any():
        return length, dz, bad
    i = int(np.flatnonzero(bad)[0])
    warnings.append(SK.impossible_stride_warning(int(bad.sum()), float(t0[i]), float(t1[i]), float(length[i]),
                                                 float(dz[i])))
    return np.where(bad, 0.0, length), np.where(bad, 0.0, dz), bad


def _no_strides_hint(session) -> str:
    """Decision B268 (L611's NoStridesError too): the fix a foot track without strides names when the session has a
    lower-back unit ("" without one)."""
    if not session.has("wAccelerometer", "wGyroscope"):
        return ""
    return (" -- the session has a lower-back unit, which sees a chair test, a standing or a seated session without "
            "foot strides: track it with --units waist (decision B268)")


def _placement_clause(session) -> str:
    """B134's amendment (session 44, FM): when L611 / L612 / L639 leave no stride, B134's line ("is this unit on the
    foot?") joins the NoStridesError if it fires: a unit that walks but never swings (waist data in the foot files) and
    a crank alone both read as unrested loops and as B134's unit, so the refusal names both causes, B134's first
    ("" when B134 does not fire)."""
    from pdrlearn.track.foot_rest import foot_placement_line, foot_rest_stats

    line = foot_placement_line(session, foot_rest_stats(session), "")
    return f"{line}; or " if line else ""


def _without_pedalling(fd: FootDisplacement, fd_kw: dict, foot, strides: pd.DataFrame, stance: np.ndarray,
                       transfers, g_rest: float, foot_gaps=None,
                       cycling: bool = True) -> tuple[FootDisplacement, pd.DataFrame, list[str]]:
    """Decisions L611 / L612: the strides whose raw heights go up and down in a closed loop (cycling), or that lie in
    a span the lower-back unit's chair ``transfers`` call seated, are not walking: their detections are left out and the
    rest integrated again (nothing changes without them); ``g_rest``: the foot's rest reading (L621). Decision L639:
    so is a stride longer than ``RIDE_STRIDE_CAPS`` of the foot's stride cap (L605), with every detection inside it,
    unless it overlaps one of ``foot_gaps`` (B11's 0 m row). ``cycling=False`` (decision E304): no L611 check.
    Decision L799: L611's level strides travelling 1 m or more get a line of their own (running's, not cycling's).
    Returns (fd, strides, warning lines)."""
    from pdrlearn.track.pedalling import pedal_verdict, travelling_line

    none = np.zeros(len(fd.start_s_), dtype=bool)
    loop, going = (pedal_verdict(fd, foot, g_rest) if cycling  # decisions L611, L799 (L625: shared with `steps`)
                   else (none, none))  # decision E304: an activity without bicycles
    seated, seats = seated_strides(fd.start_s_, fd.end_s_, transfers)
    ride, cap = long_ride_strides(fd, foot, foot_gaps)  # decision L639
    if not (loop | seated | ride).any():
        return fd, strides, []
    # decision L799: L611's level strides that travel are named as running's, not as "cycling?"
    lines = [pedal_line(loop & ~going, seated, fd.start_s_, fd.end_s_, seats, ride, cap),
             travelling_line(going & ~seated & ~ride, fd)]
    lines = [x for x in lines if x]
    kept = strides.drop(index=strides.index[making_only(fd, fd_kw, foot, strides, stance, loop | seated | ride)])
    kept = kept.reset_index(drop=True)
    if not len(kept):
        return fd, kept, lines
    return FootDisplacement(**fd_kw).estimate(foot, kept, stance=stance), kept, lines


#: review R1 F6: two stride times (s) from the same ``stride_bounds`` call are the same stride within this much,
#: absolute (a relative tolerance would grow with the session clock: 0.29 s eight hours in)
SAME_STRIDE_S = 1e-6


def same_strides(s0: np.ndarray, s1: np.ndarray, g0: np.ndarray, g1: np.ndarray) -> np.ndarray:
    """Review R1 F6: for each stride ``[s0, s1]`` (s), whether it is one of the strides ``[g0, g1]``."""
    s0, s1, g0, g1 = (np.asarray(v, dtype=float) for v in (s0, s1, g0, g1))
    close = {"rtol": 0.0, "atol": SAME_STRIDE_S}
    return (np.isclose(s0[:, None], g0[None, :], **close) & np.isclose(s1[:, None], g1[None, :], **close)).any(axis=1)


def long_ride_strides(fd: FootDisplacement, foot, foot_gaps=None) -> tuple[np.ndarray, float]:
    """Decision L639: ``(ride, cap)``: (B,) bool, the strides of ``fd`` longer than ``RIDE_STRIDE_CAPS`` of the foot's
    stride cap ``cap`` (s, L605) that overlap none of ``foot_gaps`` (B11's 0 m row); shared by ``track`` and
    ``pdrlearn steps`` (review R1 F1)."""
    windows = fd.end_s_ - fd.start_s_
    cap = stride_cap_s(foot_period(foot.gyr, foot.fs), float(np.median(windows)) if len(windows) else np.nan)
    ride = ride_strides(fd.start_s_, fd.end_s_, cap) & ~overlaps_gaps(
        pd.DataFrame({"start_s": fd.start_s_, "end_s": fd.end_s_}), foot_gaps)
    return ride, cap


def making_only(fd: FootDisplacement, fd_kw: dict, foot, strides: pd.DataFrame, stance: np.ndarray,
                removed: np.ndarray) -> np.ndarray:
    """Decision L641: the rows of ``strides`` (positions) every one of whose rest-to-rest strides (C51's
    ``stride_bounds`` pairs) is one of ``fd``'s ``removed`` strides: left out, none of them makes it again (a stride
    joining several detections kept the others, L611's first mechanism); a row that also makes a kept stride stays.
    ``fd`` may be fitted on another table than ``strides`` over the same rests (review R1 F1: `pdrlearn steps`
    judges the detector's whole table and drops rows of its one-per-stride table)."""
    s0, s1, rows = FootDisplacement(**fd_kw).stride_bounds(foot, strides, stance=stance)
    hit = same_strides(s0, s1, fd.start_s_[removed], fd.end_s_[removed])
    made = np.zeros(len(strides), dtype=bool)
    made[rows] = True
    keeps = np.zeros(len(strides), dtype=bool)
    np.logical_or.at(keeps, rows[~hit], True)
    return np.flatnonzero(made & ~keeps)


def _contact_cadence(seen: dict, table: pd.DataFrame, t: np.ndarray, stance: np.ndarray) -> float | None:
    """Decision L431: the cadence of the foot's contacts as `pdrlearn steps` judges it (steps decision 44): the step
    detector's own table when the track ran one (``seen``, steps decision 55: the accel detector of an IMU stance,
    the accel-force detector of the insoles) reduced to one contact per rest-to-rest stride of the track's stance as
    `steps` reduces it (steps decision 34), before the strides were cut at the rests; else the strides' contacts."""
    from pdrlearn.displace.foot import one_per_rest_stride

    det = seen.get("AccelStepDetector", seen.get("AccelForceStepDetector"))
    if det is not None and len(det) and {"start_s", "end_s", "event_s"} <= set(det):
        rows = one_per_rest_stride(t, stance, det["start_s"], det["end_s"], det["event_s"])
        return contact_cadence_spm(det["event_s"].to_numpy(float)[rows])
    return contact_cadence_spm(table["event_s"].to_numpy(float)) if "event_s" in table else None


@register_pipeline("plasys")
def track_plasys(session: Session, *, method: str = "auto", model=None, start=None, params=None,
                 steps: str = "detector", heading: str | None = None, initial_heading: float = 0.0,
                 bounds=None, bounds_scale: float = 2.0, down_mode: str = SK.DEFAULT_DOWN_MODE,
                 min_confidence: float | None = None, align: bool = False, rules: str | None = None,
                 fused_tau_s: float = 60.0, streaming: bool = False, distance_gain: float | None = None,
                 calibration: bool = True, gap_yaw: bool | None = None, waist_gap_yaw: bool | None = None,
                 waist_bridge: bool | None = None, warn_out_of_domain: float | None = None, toe_off: bool = False,
                 hard_iron_fit: bool | None = None, contacts: bool = False, altitude: str | None = None,
                 drop_neighbour: bool = False, ignore_force: bool = False,
                 waist_bias: bool | None = None, compass_fallback: bool | None = None,
                 fallback_drift: bool | None = None, first_walk: bool = False, transfers: bool = True,
                 gated_level_dz: bool | str = False, fused_climb: bool = False,
                 fused_straight: bool = True, ride_vibration: bool = True, cycling: bool = True,
                 foot_ramps: bool = False, compass_sinusoid: bool = False, forward_yaw: bool = True,
                 forward_yaw_gate: bool = True,
                 **opts) -> TrackResult:
    """Track a foot (+ waist) session with PLASYS method M1, M2 or M3 (thesis ch.7).

    Parameters
    ----------
    method : "auto" (default, as ``pdrlearn track``; decision L44) | "M1" | "M2" | "M3". "auto" (decision
        L36): M3 when ``model`` is given; without a model the M3 engine (M2's ZUPT/Kalman strides, the stance
        from the force sensors or the inertial detector) with the class rules off, and a warning (streaming:
        M2's kernel)
    model : M3 classes source: a model directory / loaded model, or ``"oracle"`` (the session's labels)
    start : (lat, lon) or (lat, lon, alt) in degrees (alt in m; or the CLI's ``"LAT,LON[,ALT]"``) -> ``lat``/
        ``lon`` columns via thesis eq. 56/57, ``z`` from ``alt``; out of range: one error line (decision L157)
    params : optional dict overriding :class:`FootDisplacement` settings
    steps : "detector" (pdrlearn.steps detectors), "stance" (stance segmentation), "labels", or your own
        strides (decision L149): a foot detector's registered name (:func:`pdrlearn.steps.register_detector`),
        a :class:`~pdrlearn.steps.StepDetector` instance with ``unit = "foot"`` or a steps table (``start_s``,
        ``end_s``, optional ``event_s``, ``confidence``; s on the session's clock). Offline only
    heading : "waist" | "foot" | "fused" (default per method; "foot" when there is no waist unit).
        "fused": the foot's stride-by-stride yaw aligned to the waist heading by an offset averaged over
        +-``fused_tau_s`` s (decision L17), counted on the straight strides only (decisions L589, L609: the
        default, so turns on the spot do not pull it; ``fused_straight=False`` counts every stride, L17 as before)
    ride_vibration : offline, with a waist barometer: a ride (L378) or a standstill of 20 s or more whose foot unit
        vibrates at 0.15 m/s^2 or more is a ``vehicle`` ride (decisions L402, L615, L616; ``--params``' ``{"options":
        {"ride_vibration": false}}``); False: L376's vertical rate alone, and no level vehicle rides
    initial_heading : ENU heading (rad, |value| <= 2 pi, else refused as degrees: decision L158) at the start
        when the heading is relative (foot, or no magnetometer)
    bounds : length-class bounds (m) overriding the model's; default thesis step bounds x ``bounds_scale``
        (the foot unit measures strides = two steps, see docs/decisions/localization.md)
    down_mode : "projected" (the default since decision L178; L51: the thesis' eq. 61 norm L is the path length,
        its horizontal part sqrt(L^2 - dz^2) moves x/y), "norm3" (thesis eq. 61, the norm moves x/y) or
        "horizontal" for descending stairs
    rules : "thesis" (the classes prevail, ch.7.2.2) or "bayes" (class probabilities weighed against the
        estimate's uncertainty, docs/decisions/localization.md L14). Default None: "bayes" with a model's
        classes, "thesis" with ``model="oracle"`` labels (decision L18), streaming too (L40, L41)
    align : M3: align the waist clock to the foot clock from the steps both units detect (off by
        default, see docs/decisions/localization.md L13)
    min_confidence : a class rule is applied only when the model's probability of the class reaches this
        (default None = :data:`DEFAULT_MIN_CONFIDENCE` 0.95, decision L18; 0 = always, as the thesis).
        Oracle classes carry no probabilities and are always applied. ``streaming=True`` gates the same way
        (decision L40)
    streaming : M2/M3 with the streaming runtime's stride-local kernel (see :func:`track_streaming`);
        ``heading`` is then "auto" (default), "foot" or "waist-gyro"; ``params`` = stance-segmentation
        settings (:class:`pdrlearn.kernels.stride.StanceSegmenter`)
    distance_gain : factor on the horizontal displacement of the level strides (|dz| < 0.1 m), decision
        L26. Default None: M3 with a trained model uses the model's per-user distance calibration (from
        ``pdrlearn train``) when its foot rate matches the session's, else 1; a number applies it with
        any method (e.g. M2); 1.0 = off
    gap_yaw : streaming: add the foot's turn between two strides that do not touch (decision L31; None = the
        :func:`track_streaming` default); offline this is ``params={"gap_yaw": ...}`` (L28, on by default)
    waist_gap_yaw : streaming: a stride headed by the waist gyroscope adds the waist's turn between two strides
        that do not touch (decision L61; None = the :func:`track_streaming` default); offline not used (the
        waist heading filter integrates the whole session)
    waist_bridge : the turn over a foot-IMU gap (over 1 s, B11) is the waist gyroscope's, offline (the stride
        across the gap and the pause before the first stride after it; decision L91, an option) and streamed (the
        stride across it, from the foot's rest before the gap to its rest after it, and the pause before the next;
        decision L99, the streamed default). None (default): True streamed, False offline; False, or no waist
        gyroscope: 0 (L90: the foot's interpolated gyroscope is never integrated there)
    drop_neighbour : streaming: a stride across dropped foot samples over 0.25 s takes the length and height change
        of the clean stride before it (decision L167, an option; E101, L549: a keyword, False by default);
        offline such strides take their neighbours' height change (L160) and True is refused
    first_walk : streaming: a foot-headed track's heading is turned once, at the end of its first walk, by that walk's
        direction (L494's reference made causal; decision E215, not adopted as the default; E222: this keyword, as
        the runtime ``Tracker``'s); offline L494 references the first walk always and True is refused
    gated_level_dz : streaming M3: an M3 stride whose terrain class the 0.95 gate (L18) dropped gets L39's level rule,
        per stride (True, decision L189) or on the summed dz of its run of such strides (``"summed"``, L206); both
        measured and not adopted (L189, L207), so False (default: raw heights); decision L550: this keyword, as the
        runtime ``Tracker``'s. Offline M3 levels such strides already (L184) and True / "summed" are refused
    cycling : True (default): L611's pedalling check removes the foot strides that go round a closed loop (a crank);
        False (decision E304, ``track --no-cycling``, the runtime ``Tracker(cycling=False)``'s): an activity without
        bicycles, no stride judged pedalling (offline, L612's seated and L639's ride strides are still removed)
    transfers : offline two-unit session: time the chair transfers and TUG from the waist unit (W418); False skips
        that inner waist work for callers that read no TUG (the distance calibration; decision W439)
    calibration : M3 with a trained model: use the model's distance calibration (L26): its gain (unless
        ``distance_gain`` is given) and, for the bayes rules, its measured stride-length sd in place of the
        3 % default. False: neither
    warn_out_of_domain : M3 with a trained model: warn (one line) when at least this fraction of the strides
        lie outside the model's training range (decision C16; None = no warning, the default). The
        fraction is always in ``info["out_of_domain"]``
    toe_off : add the toe-off ``tc_s`` and ``stance_time_s``, ``swing_time_s``, ``stance_pct`` to every stride
        row (decision L73, ``pdrlearn.track.toeoff``; offline only)
    hard_iron_fit : heading "fused": fit the waist magnetometer's horizontal hard-iron offset on the walk when
        it turns enough (decision L84, :func:`fit_waist_hard_iron`; None = :data:`HARD_IRON_FIT`); the fit
        is in ``info["hard_iron"]``
    compass_fallback : heading "fused": when L182's compass check warns, follow the waist gyroscope's heading
        aligned to the compass by one offset per stretch (decision L226; linear in time, L266; None =
        :data:`COMPASS_GYRO_FALLBACK`); ``info["compass_check"]["gyro_fallback"]`` says whether it applied
    fallback_drift : the fallback's offset drifts linearly per stretch (decision L266; None = :data:`FALLBACK_DRIFT`)
    compass_sinusoid : heading "fused": take the waist compass's direction-dependent error (a hard-iron offset's
        sinusoid of the walking direction, fitted on the walk jointly with the foot's drift,
        :func:`pdrlearn.kernels.compass_sinusoid.direction_sinusoid`) off the waist heading before L17's window
        (decision L770; ``info["compass_sinusoid_deg"]`` its amplitude, None when the walk turns too little)
    forward_yaw : heading "waist"/"fused" with a compass: turn the waist compass's heading (its declared forward's)
        by the signed angle D10's check measured from that forward to the walking direction (a unit yawed on its
        belt by a few degrees; decision L796, adopted: fresh users 18950-18979, median final error 1.495 -> 0.932 m;
        ``info["compass_mount"]["forward_yaw_deg"]``); False: as before L796. Decision L801: one warning line when
        W435's power ratio (under x10) or W434's ``"force_frame"`` does not trust the measured yaw
    forward_yaw_gate : decision L801 (the default since L803): with ``forward_yaw``, do not turn the compass when
        W435's power ratio or W434's ``"force_frame"`` does not trust the measured yaw (review s53r1: a hemiparetic
        walker's 20.8 m final error 2.7 m again; fresh symmetric users: no run changed);
        ``info["compass_mount"]["forward_yaw_skipped"]``; False: L796's turn all the same, with L801's line
    waist_bias : heading "waist"/"fused": when W125's bias warning fires, remove the waist gyroscope's vertical-rate
        bias read at its standstills (decision W126; None = on, W423's adopted default: users 10160-10169 at 52 Hz,
        18/18 biased sessions where W105 fired improved, median 34.81 -> 3.65 m)
    contacts : streaming: give each stride its initial contact (``event_s``: the force sensors' stance onset, else
        the accelerometer impact, decisions E49/E50) and so ``stride_time_s``, ``cadence_spm``, ``speed_mps``
        and the summary's stride medians (E51; an option: E50's adoption rule was not met). Offline strides always
        have their detector's contacts
    ignore_force : offline: the stance and strides from the foot IMU alone, the force sensors (fForceA/fForceB)
        left out (decision L366, ``--ignore-force``; M2 then has no force and is refused). Without it the force
        stance is checked against the IMU's rests and swings, and replaced by the IMU's where they disagree
        (decision L365, one warning); ``info["stance_source"]`` says which
    altitude : "foot" (default, None) - the strides' own height (L39 / the terrain classes) - or "fused": fused with
        the session's waist barometer (decision L154, :func:`pdrlearn.kernels.barometer.fuse_altitude`; an option,
        its adoption rule was not met), offline and streamed; ``info["altitude_source"]`` says which
    foot_ramps : a foot track without ``altitude="fused"`` and without terrain classes: ramps.csv, ``n_ramps`` and
        the ramp strides from its own L39 heights (a 1:12 ramp's strides of 1.2 m or more; decision L717, an option,
        its rule was not met: 16 of 20 users within 2 strides, 18 asked), offline and streamed
    fused_climb : with ``altitude="fused"`` and no terrain model: a stride inside a barometric climb is fused with the
        foot's own un-levelled height instead of L39's level one (decision L564, an option: L565, its rule was not
        met - ramp ends within 0.06 s and grades steadier, but stair walks' end height up to 0.11 m worse)

    Any other keyword argument raises ``TypeError`` naming the closest valid one (decision L43). Warnings go
    to ``info["warnings"]`` and to the ``logging`` logger ``pdrlearn.track`` (not Python's ``warnings``).
    """
    from pdrlearn.classify.domain import check_warn_at

    if opts:  # decision L43: a misspelled option is an error, as in the waist pipelines (it was ignored)
        check_keywords("plasys", opts, keyword_names(track_plasys))
    if fused_climb and check_altitude(altitude) != "fused":  # decision L565: an option that would do nothing
        raise DataError("plasys: fused_climb=True reads the waist barometer's climbs, which only altitude='fused' "
                        "uses: add altitude='fused' or drop fused_climb (decision L565)")
    if not (model is None or isinstance(model, str | Path) or hasattr(model, "predict_steps")):
        raise TypeError(f"plasys: model={model!r:.40} is not a model: pass a trained model directory (str or Path), "
                        "a model from pdrlearn.classify.load_model, 'oracle' (the session's labels) or None (decision "
                        "B208)")
    if params is not None and not isinstance(params, dict):  # decision B207, streamed too
        check_foot_settings(params, "plasys params")
    raw_start = start
    start, start_alt = start_coordinate(start)  # decision L157: (lat, lon[, alt]) checked as --start
    initial_heading = heading_in_radians(initial_heading, "initial_heading")  # decision L158 (W81's check)
    check_warn_at(warn_out_of_domain)
    altitude = check_altitude(altitude)  # decision L154
    _check_steps_arg(steps)  # decision B173 (a bad value was a pandas traceback), L149 (own strides accepted)
    method = str(method).upper()
    no_classes = False
    if method == "AUTO":  # decision L36: M3 with a model; without one the M3 engine, its class rules off
        method, no_classes = ("M3", False) if model is not None else (("M2", True) if streaming else ("M3", True))
        asked = [n for n, v in (("rules (--rules)", rules), ("min_confidence (--min-confidence)", min_confidence),
                                ("bounds (--length-bounds)", bounds)) if v is not None]
        if no_classes and asked:  # they would be ignored: no classes, no rules
            raise ModelError(MODEL_NEEDED.format(
                what=f"plasys: {', '.join(asked)} set the class rules, which need the step classes"))
    if method not in METHODS:
        raise DataError(f"plasys: method '{method}' is not one of auto, M1, M2, M3")
    if not session.has("fAccelerometer") and session.has("wAccelerometer"):  # decision E182
        raise MissingSensorError(
            f"session '{session.name}' has no foot unit (fAccelerometer), which every plasys method needs, but a "
            "waist unit: track it with get_pipeline('waist-pendulum') (CLI --pipeline waist-pendulum), or "
            "get_pipeline('auto') to choose by the session as --pipeline auto does (decision E182)")
    from pdrlearn.track.foot_rest import frozen_foot_imu

    frozen = frozen_foot_imu(session)  # decision B203: force sensors that step beside a foot IMU that never moves
    if frozen:
        raise DataError(frozen)
    if down_mode not in SK.DOWN_MODES:  # decision L51: offline and streamed alike
        raise DataError(f"plasys: down_mode '{down_mode}' is not one of {', '.join(SK.DOWN_MODES)}")
    if drop_neighbour and not streaming:  # decision E101
        raise DataError("plasys drop_neighbour=True is the streamed strides' option (decision L167); offline, strides "
                        "across dropped samples take their neighbours' height change (L160): add streaming=True or "
                        "drop drop_neighbour")
    if KD.check_gated_level_dz(gated_level_dz) and not streaming:  # decision L550
        raise DataError(f"plasys gated_level_dz={gated_level_dz!r} is the streamed track's option (decisions L189, "
                        "L206); offline, M3 gives a stride whose terrain class the gate dropped L39's level rule "
                        "already (L184): add streaming=True or drop gated_level_dz")
    if first_walk and not streaming:  # decision E222
        raise DataError("plasys first_walk=True is the streamed track's option (decision E215); offline, a foot-only "
                        "heading's 0 is the first walk's direction already (L494): add streaming=True or drop "
                        "first_walk")
    if streaming:
        if ignore_force:  # decision L366: the streamed kernel's contacts read the force (E50); offline only
            raise DataError("plasys ignore_force=True (--ignore-force) is offline only: the streamed strides take "
                            "their contacts from the force sensors (decision E50); drop streaming=True or "
                            "ignore_force")
        if not (isinstance(steps, str) and steps == "detector") or align:
            raise DataError("plasys streaming=True: steps and align are not streamable; leave them at their "
                            "defaults")
        res = track_streaming(session, method=method, model=model, start=raw_start, params=params,
                              heading=heading or "auto", initial_heading=initial_heading, bounds=bounds,
                              bounds_scale=bounds_scale, down_mode=down_mode, distance_gain=distance_gain,
                              calibration=calibration, rules=rules, min_confidence=min_confidence,
                              warn_out_of_domain=warn_out_of_domain, contacts=contacts,
                              drop_neighbour=drop_neighbour,  # decision E101
                              first_walk=first_walk,  # decision E222
                              gated_level_dz=gated_level_dz,  # decision L550
                              cycling=cycling,  # decision E304
                              **({} if waist_bridge is None else {"waist_bridge": bool(waist_bridge)}),
                              **({} if gap_yaw is None else {"gap_yaw": bool(gap_yaw)}),
                              **({} if waist_gap_yaw is None else {"waist_gap_yaw": bool(waist_gap_yaw)}))
        if no_classes:
            res.info["method"] = "M3 engine, no classes"
            raw_dz = res.steps["dz_m"].to_numpy(float) if len(res.steps) else np.zeros(0)
            _level_without_classes(res)  # decision L39, as offline
            msg, res.info["altitude_check"] = coded_altitude_check(res.steps["dz_m"].to_numpy(float),
                                                                   raw_dz=raw_dz)  # L69, L145
            res.info["warnings"] = [NO_MODEL_WARNING, *res.info.get("warnings", []), *([msg] if msg else [])]
            log.warning("%s: %s", session.where, NO_MODEL_WARNING)
        if fused_climb and not no_classes:  # decision L586, as offline
            res.info["warnings"].append(FUSED_CLIMB_DROPPED)
            log.warning("%s: %s", session.where, FUSED_CLIMB_DROPPED)
        at = len(res.info["warnings"]) - 1 if no_classes and msg else None
        apply_altitude(res, session, altitude,  # decision L154 (L292: rewrites L69's line; L564: the raw heights)
                       raw_dz=raw_dz if no_classes and fused_climb else None)  # L565: an option
        if at is not None:
            log.warning("%s: %s", session.where, res.info["warnings"][at])
        insole = streamed_insole_line(session, "track --streaming")  # decision L406: L365's check, told
        if insole:
            res.info["warnings"].append(insole)
            log.warning("%s: %s", session.where, insole)
        if transfers and session.has("wAccelerometer", "wGyroscope"):  # W418's transfers are offline only (`run`
            res.info["trunk_note"] = STREAMED_TRUNK_NOTE.format(where=session.where)  # writes none); W431: say so
        from pdrlearn.track.units import with_left_out_units

        # decision E293: the rides as offline (L378, L615, L624), and as `run` reads them (E6: one computation)
        foot_rides(res, with_left_out_units(session), ride_vibration)
        return _foot_ramps_option(res, foot_ramps)  # decision L717
    refusal = reads_force_refusal(steps) if ignore_force else None  # decision B299
    if refusal:
        raise DataError(f"plasys: {refusal}")
    cfg = {**METHODS[method], "rules": False} if no_classes else METHODS[method]
    warnings: list[str] = [NO_MODEL_WARNING] if no_classes else []
    clipped = foot_gyro_clipped(session) if cfg["heading"] == "fused" else (0, 0.0, 0)  # decision L525
    clipped = clipped if clipping_acts(clipped[0], clipped[2]) else (0, 0.0, 0)  # L529: a spike is left alone
    if clipped[0]:
        waist_gyro = session.has("wAccelerometer", "wGyroscope") and session.has_frame("waist")
        heading = heading or ("waist" if waist_gyro else None)  # L525 (b): the foot's stride yaw is not trusted
        warnings.append(clipped_foot_line(clipped[0], len(session.streams["fGyroscope"]), clipped[1],
                                          heading == "waist", applied_settings(params)))
    foot = unit_data(session, "foot", purpose=f"PLASYS {method}")
    stance_source, imu_spans = "inertial", np.zeros((0, 2))
    dead_line = None  # steps decision 74
    fev, force_offset = None, None  # decisions L388 / L389: the force detector's events, the insoles' clock offset
    if cfg["force"]:
        if ignore_force and method == "M2":  # decision L366
            raise DataError("plasys: method M2 is accelerometer + force, and ignore_force=True (--ignore-force) "
                            "leaves the force out; use --method M1 or M3, or drop --ignore-force")
        if not ignore_force:  # decision B284: an unloaded offset (raw ADC counts) subtracted, with one line
            session, dead_line = live_force(session)  # steps decision 74: a dead channel named and left out
            warnings += [dead_line] if dead_line else []
            session, tare_line = tared(session, foot)
            warnings += [tare_line] if tare_line else []
        stance, stance_source, lines, imu_spans = checked_stance(session, foot, use_force=not ignore_force)  # L365/6
        warnings += lines
        if stance_source == "inertial" and not ignore_force:
            if method == "M2":
                raise MissingSensorError(
                    f"session '{session.name}' has no fForceA/fForceB needed by M2 (accelerometer + force)"
                    + (f" ({dead_line})" if dead_line else "") + "; use --method M1 or M3, or record the force sensors")
            warnings += [] if dead_line else [NO_FORCE_STANCE]  # steps 77: steps 74's line has said it
    else:
        stance = inertial_stance(foot.acc, foot.gyr, foot.fs)
    kind = cfg["detector"] if stance_source == "force" or method == "M1" else "AccelStepDetector"
    if kind == "AccelStepDetector" and isinstance(steps, str) and steps == "detector":  # decision S78
        sim_line = hermite_contact_line(session.meta)
        warnings += [sim_line] if sim_line else []
    seen: dict = {}  # steps decision 55: the accel-force detector's table, run once for the strides, L390 and L161
    strides = _detect_strides(session, kind, steps, foot.t, stance, warnings, seen).reset_index(drop=True)
    if stance_source == "force":  # decisions L388-L390: the force detector's events (onsets, drop-offs)
        fev = force_events(session, detected=seen.get("AccelForceStepDetector"))
    if cfg["force"] and len(imu_spans) and isinstance(steps, str) and steps == "detector":
        strides = imu_strides_in(session, strides, imu_spans)  # decision L365: the IMU's strides where force fails
    # decision B11: report long stream gaps; no foot stride spans a foot-IMU gap (L365: a gap of the force sensors
    # alone is bridged by the IMU's stance, and checked_stance named it; it had cut 2 s of walking as 0 m)
    foot_gaps = long_gaps(session, ("fAccelerometer", "fGyroscope"))
    bridged = bool(waist_bridge) and session.has("wGyroscope", "wAccelerometer")  # decision L91 (offline: off)
    waist_heads = (heading or cfg["heading"]) in ("waist", "fused") and session.has(
        "wAccelerometer", "wGyroscope") and session.has_frame("waist")
    how = (heading or cfg["heading"]) if waist_heads else ("bridged" if bridged else "none")  # decision L92
    warnings += unit_gap_warnings(session, foot_gaps,  # decision B231: per unit
                                  "no displacement is counted inside them: a stride across a foot gap is one row "
                                  "of 0 m with its gap_s in steps.csv (L67)" + gap_heading_clause(foot_gaps, how),
                                  (heading or cfg["heading"]) if waist_heads else "foot")
    strides = drop_steps_across_gaps(strides, foot_gaps)
    spins = turns_in_place(foot.t, foot.acc, foot.t, foot.gyr, strides["start_s"], strides["end_s"])  # L742
    strides = strides[~spins].reset_index(drop=True)
    warnings += [spin_line(int(spins.sum()))] if spins.any() else []
    if not len(strides):
        # decision B318: the session's folder (as every other error names it), and its own exit code 4
        raise NoStridesError(f"{session.where}: no strides detected; is the foot unit moving?"
                             + (f" ({spin_line(int(spins.sum()))})" if spins.any() else "")
                             + f"{_no_strides_hint(session)}")
    fd_kw = {k: cfg[k] for k in ("integrator", "zupt_end", "gyro_bias", "attitude")}
    fd_kw.update(check_foot_settings(params, "plasys params"))  # decisions B206 / B207
    if clipped[0]:  # decision L525 (a): the streamed stride's tilt correction and ZUPT clock
        fd_kw = clipped_foot_settings(fd_kw, params)
    fd_kw, clip_line = clip_noise_default(fd_kw, params, foot.acc)  # decision B470: a clipped foot accelerometer
    warnings += [clip_line] if clip_line else []
    fd = FootDisplacement(**fd_kw).estimate(foot, strides, stance=stance)
    trunk = SimpleNamespace(info={})  # decision L612: W418's transfers, read once, before the strides are final
    if transfers:
        add_trunk_transfers(trunk, session)
    fd, strides, pedal_warnings = _without_pedalling(fd, fd_kw, foot, strides, stance, trunk.info.get("transfers"),
                                                     foot_rest_gravity(session), foot_gaps,  # decisions L621, L639
                                                     cycling=cycling)  # decision E304
    if not len(strides):
        raise NoStridesError(f"{session.where}: no walking strides: {_placement_clause(session)}"
                             f"{'; '.join(pedal_warnings)}{_no_strides_hint(session)}")
    fd_warnings = list(fd.warnings_) + pedal_warnings  # decisions L611, L799
    raw_disp = disp = fd.disp_
    if len(fd.rows_) < len(strides):
        log.info("%s: %d detected step(s) without a swing between two rests dropped", session.name,
                 len(strides) - len(fd.rows_))
    source = strides.attrs.get("detector", steps if isinstance(steps, str) else "table")
    strides = strides.iloc[fd.rows_].reset_index(drop=True)
    strides["start_s"], strides["end_s"] = fd.start_s_, fd.end_s_
    if "event_s" in strides:  # decision L96: the pieces of a split detection get their own landing
        strides["event_s"] = split_events(strides, fd.rows_, fd.t_, fd.stance_)
    # decision B11: the rest-to-rest bounds may reach across a gap; such strides move 0 m
    in_gap = overlaps_gaps(strides, foot_gaps)
    if in_gap.any():
        disp = np.where(in_gap[:, None], 0.0, disp)
        # B34: a stride across a gap moves 0 m (said by the gap warning), so it is not one of the "unreliable"
        # long strides: those are counted without it (one 2 s gap gave "no steps ... inside" + "1 stride > 3 s")
        long = ((fd.end_s_ - fd.start_s_) > fd.max_stride_s) & ~in_gap
        fd_warnings = [w for w in fd_warnings if "stride(s) longer than" not in w]
        if long.any():
            fd_warnings.append(f"{int(long.sum())} stride(s) longer than {fd.max_stride_s:g} s (no stance detected "
                               "between steps): their displacement is unreliable")
    # decision L605: L80's stride cap, or 1.5 of a slow foot's own rhythm (L596) where its strides fill half of it
    windows, period = (fd.end_s_ - fd.start_s_)[~in_gap], foot_period(foot.gyr, foot.fs)
    window = float(np.median(windows)) if len(windows) else np.nan
    stride_cap = stride_cap_s(period, window)
    slow_line = slow_rhythm_line(period, stride_cap, window)  # decision L599: a rhythm over 3 s is named (L658: the
    # strides' own, filling half of it)
    if slow_line:
        fd_warnings = [w for w in fd_warnings if "stride(s) longer than" not in w] + [slow_line]
    warnings += fd_warnings
    if not len(strides):
        raise DataError(f"session '{session.name}': no stride between two rests of the foot unit")
    if GAP_STRIDE_HEIGHT:  # decision L160: a stride across dropped samples takes its neighbours' height change
        across = drop_strides(session, strides, in_gap)
        if across.any():
            disp = disp.copy()
            disp[:, 2] = neighbour_heights(disp[:, 2], across, in_gap)
            warnings.append(drop_stride_warning(int(across.sum())))

    classes = pd.DataFrame(index=range(len(strides)), columns=["terrain", "direction", "length_class"],
                           dtype=object)
    classes["confidence"] = strides.get("confidence", pd.Series(1.0, index=strides.index)).to_numpy()
    model_bounds, windows, domain, off_rate = None, None, None, None
    untrained: list[str] = []  # decision C17: the tasks a model does not classify fall back to the no-model rules
    has_waist = session.has("wAccelerometer", "wGyroscope") and session.has_frame("waist")
    work, alignment = session, None
    if align and has_waist:  # decision L162: any method the waist heads (L13 had M3 only)
        work, alignment = align_clocks(session, warnings, force_table=seen.get("AccelForceStepDetector"))
    if clipped[0] and heading == "waist":  # decision L525 (b): each stride's and pause's turn is the waist's
        bridge_foot_yaw(fd, {}, lambda n: (work.streams[n].t, work.streams[n].values), every=True)
    if cfg["rules"]:
        if model is None:
            raise ModelError(MODEL_NEEDED.format(what="M3 needs the step classes") + "; M1/M2 need no model")
        if isinstance(model, str | Path) and str(model) != "oracle":
            from pdrlearn.classify import load_model

            model = load_model(model)
        is_oracle = isinstance(model, str) and model == "oracle"
        # decision L38: a model classifies each stride on the window the streaming path (and its training) cuts
        windows = None if is_oracle else classification_windows(work, strides)
        classes, model_bounds = classes_and_bounds(model, work, strides if windows is None else windows)
        warnings += classes.attrs.get("label_warnings", [])  # decision B209
        domain = domain_check(model, classes, warnings, warn_out_of_domain, session=session)
        off_rate = rate_check(model, work, classes, warnings)  # decision C18
        if not is_oracle:
            untrained = untrained_tasks(classes)
            if untrained:
                warnings.append(untrained_warning(untrained))
    fs0, resampled_hz = recorded_rate(session, "fAccelerometer")  # decision B113: judged at the recorded rate
    gain, gain_source, stride_sd = _distance_gain(distance_gain, model if cfg["rules"] else None,
                                                  foot.fs if resampled_hz is None else fs0, warnings, calibration,
                                                  resampled_hz=resampled_hz)
    # decision L26: the user's calibration on the level strides' horizontal displacement
    disp = apply_level_gain(disp, gain)
    use_bounds = bounds if bounds is not None else model_bounds
    clamp = cfg["rules"]
    if clamp and use_bounds is None and "length" not in untrained:  # C17: no length class, nothing to clamp
        if isinstance(model, str) and model == "oracle":
            warnings.append("no length-class bounds in the session: thesis step bounds x "
                            f"{bounds_scale:g} used")
        else:
            clamp = False
            warnings.append(SK.no_length_bounds_warning("the model"))  # decision L59: one line, track and runtime
    if rules is None:  # decision L18: a model's probabilities are weighed, certain labels prevail
        rules = "thesis" if isinstance(model, str) and model == "oracle" else DEFAULT_MODEL_RULES
    # decision L26: the bayes rule weighs the classes against the user's own calibrated stride accuracy
    sigma_kw = {"sigma_rel": float(stride_sd)} if stride_sd and rules == "bayes" else {}
    step_rules = StepRules(bounds=parse_bounds(use_bounds) if use_bounds is not None else None,
                           bounds_scale=bounds_scale, down_mode=down_mode, mode=rules,
                           clamp=clamp, sign=cfg["rules"], altitude=cfg["rules"], **sigma_kw)
    if not cfg["rules"]:
        classes["terrain"] = None
    gate = DEFAULT_MIN_CONFIDENCE if min_confidence is None else float(min_confidence)
    classified_length = classes["length_class"].to_numpy(dtype=object, copy=True) \
        if "length_class" in classes else None  # decision C89 counts the classifier's own classes
    turn_rule = bool(KT.TURN_LENGTH_RULE and cfg["rules"] and use_bounds is not None
                     and classified_length is not None and not (isinstance(model, str) and model == "oracle"))
    if turn_rule:  # decisions C88 / C91: a turning stride's length class from its measured length (the runtime's)
        from pdrlearn.track.turn_classes import measured_classes_on_turns

        classes = measured_classes_on_turns(classes, np.hypot(disp[:, 0], disp[:, 1]), fd.yaw_change_,
                                            parse_bounds(use_bounds))
    rule_classes = _confident(classes, gate) if cfg["rules"] else classes.assign(terrain="flat")
    applied = step_rules.apply(disp, rule_classes)
    length = applied["length_m"].to_numpy()
    if clamp and rules == "thesis" and not (isinstance(model, str) and model == "oracle"):  # decision L325
        from pdrlearn.displace.rules import doubled_lengths_line

        keep = ~np.asarray(in_gap, bool)
        line = doubled_lengths_line(np.hypot(disp[keep, 0], disp[keep, 1]), length[keep],
                                    rule_classes["length_class"].to_numpy(dtype=object)[keep]
                                    if "length_class" in rule_classes else np.full(int(keep.sum()), None))
        warnings += [line] if line else []
    dz = applied["dz_m"].to_numpy() if cfg["rules"] else disp[:, 2]
    raw_dz = dz
    if no_classes or "terrain" in untrained:  # decision L39 (C17: also a model without terrain classes)
        dz = level_dz(dz)
    elif cfg["rules"] and GATED_LEVEL_DZ:  # decision L184: a stride whose class the gate dropped is level by L39
        dz = unclassed_level_dz(dz, [isinstance(t, str) for t in rule_classes["terrain"]])
    length, dz = np.where(in_gap, 0.0, length), np.where(in_gap, 0.0, dz)
    length, dz, impossible = _drop_impossible(length, dz, strides["start_s"].to_numpy(float),
                                              strides["end_s"].to_numpy(float), warnings)  # decision L94
    unjudged = in_gap | impossible  # decision C240: the strides no height check judges (a gap's, L94's)
    # decision L564: the heights before L39's level rule (0 where the stride has none), for the fused altitude
    leveled = no_classes or "terrain" in untrained
    climb_dz = np.where(unjudged, 0.0, raw_dz) if leveled else None
    altitude_check, terrain_check = None, None
    msg, steep_check = steep_stride_check(np.where(unjudged, 0.0, np.hypot(disp[:, 0], disp[:, 1])), dz)
    warnings += [msg] if msg else []  # decision L430: strides steeper than any stair
    if no_classes or "terrain" in untrained:  # decision L69: the altitude is the foot's integrated height
        msg, altitude_check = coded_altitude_check(  # decisions L69, L145
            dz, raw_dz=np.where(unjudged, 0.0, raw_dz))
        warnings += [msg] if msg else []
    elif cfg["rules"] and not (isinstance(model, str) and model == "oracle"):  # decision C28
        judged = judged_terrain(classes["terrain"].to_numpy(dtype=object), unjudged)  # decision C240
        msg, terrain_check = terrain_dz_check(judged, disp[:, 2], dz)
        warnings += [msg] if msg else []
        if altitude != "fused":  # decision L543: up / down strides the level rule zeroed (fused reads the barometer)
            msg, terrain_check["zeroed_climb"] = zeroed_climb_check(judged, disp[:, 2], dz)
            warnings += [msg] if msg else []

    bridge_foot_yaw(fd, foot_gaps, (lambda n: (work.streams[n].t, work.streams[n].values)) if bridged else None)
    # decision L701: a rest gap takes the lower back's turn the foot's heading missed (a stepless turn on the spot)
    bias_line, rest = waist_bias_check(work) if has_waist else (None, None)  # decisions W125, W421 (read once)
    gap_turns = add_waist_gap_turns(fd, lambda n: (work.streams[n].t, work.streams[n].values),
                                    bias_rad_s=setup_rest_bias(rest) if waist_bias is None or bool(waist_bias)
                                    else None) if has_waist else None  # decision L709 (R1 F6: --params waist_bias)
    hsrc = heading or cfg["heading"]
    hard_iron_info, compass_info, mount_info, sinus_info = None, None, None, {}
    if hsrc in ("waist", "fused") and not has_waist:
        warnings.append(no_waist_heading(session))
        hsrc = "foot"
    if hsrc == "foot" and fd.gyro_bias == "standstill":  # decision W421: the foot's bias drifting after its first rest
        warnings += [line for line in [foot_drift_line(work)] if line]
    lateral = np.arctan2(disp[:, 1], np.abs(disp[:, 0])) * np.where(disp[:, 0] < 0, -1.0, 1.0)
    side_extra = np.zeros(len(lateral))
    if hsrc in ("waist", "fused") and SIDE_TRAVEL_HEADING:  # decision L219: a sideways run's travel
        from pdrlearn.track.sideways import side_travel_extra  # angle is added after the waist heading, not fused

        side_extra = side_travel_extra(lateral, np.hypot(disp[:, 0], disp[:, 1]), fd.yaw_change_)  # L400
    relative = fd.foot_heading(0.0) + lateral - side_extra
    if hsrc in ("waist", "fused"):
        work.require_cover("fAccelerometer", "wAccelerometer")  # B21: the waist heading is read at the strides
        hard_iron = None
        if hsrc == "fused" and (HARD_IRON_FIT if hard_iron_fit is None else hard_iron_fit):  # decision L84
            hard_iron, hard_iron_info = fit_waist_hard_iron(work, strides, relative, keep=~in_gap)
        # decision L98: without a magnetometer the waist heading starts at initial_heading, as the docstring says
        yaw_bias = rest[1] if bias_line and (waist_bias is None or bool(waist_bias)) else None
        warnings += [bias_removed(bias_line) if yaw_bias is not None else bias_line] if bias_line else []  # W422
        wh = WaistHeading(hard_iron_ut=hard_iron, initial_heading=initial_heading,
                          yaw_bias=yaw_bias).fit_session(work)  # decision W126
        warnings += wh.warnings_
        # decision L161: the units' clocks checked when they were not aligned (L446: not again after --align-units
        # said why it kept them)
        if alignment is None and not align:
            offset_line = unit_offset_line(session, force_table=seen.get("AccelForceStepDetector"))
            warnings += [offset_line] if offset_line else []
        head = _stride_heading(wh, strides)
        straight = ~in_gap & (np.abs(fd.yaw_change_) < STRAIGHT_MAX_RAD)
        mount_line = None
        # decision D25 (adopted; W413: no module switch): the fused / waist heading checks the waist unit's mounting
        # (its compass's turns against the foot gyroscope's, its declared forward against the walking direction)
        if work.has("wMagneticField"):
            from pdrlearn.track.compass_mount import mount_check

            mount_line, mount_info = mount_check(work, relative, head, straight)
            warnings += [mount_line] if mount_line else []
        if (mount_info or {}).get("fallback"):  # D25 (W415: without a line): the foot gyroscope's heading
            compass_line, compass_info = None, None
            head = relative + initial_heading - foot_walk_reference(  # decisions L494, L510
                relative + side_extra, disp, lateral, fd.yaw_change_)
        else:
            if forward_yaw and mount_info is not None:  # decision L796: the compass reads the unit's forward
                from pdrlearn.track.compass_mount import trusted_forward_yaw

                yaw_deg, yaw_line = trusted_forward_yaw(work, mount_info, gate=forward_yaw_gate)  # L801
                warnings += [yaw_line] if yaw_line else []
                head = head + (np.radians(yaw_deg) if yaw_deg is not None else 0.0)
            from pdrlearn.track.stride_kinds import disp_kind_labels

            # decision L182: straight strides (L79), no foot gap; L656: none W415 classes side or backward
            kinds = disp_kind_labels(disp, fd.yaw_change_)
            compass_line, compass_info = compass_check(work, strides, relative,
                                                       straight & ~np.isin(kinds, ("side", "backward")),
                                                       lengths=np.hypot(disp[:, 0], disp[:, 1]))  # W589
        warnings += [compass_line] if compass_line else []
        fallback = (hsrc == "fused" and compass_line is not None
                    and (COMPASS_GYRO_FALLBACK if compass_fallback is None else compass_fallback))
        if compass_info is not None and hsrc == "fused":
            compass_info["gyro_fallback"] = bool(fallback)
        if fallback:  # decision L226: the compass's place-dependent error is not followed stretch by stretch
            gyro = WaistHeading(use_magnetometer=False, yaw_bias=yaw_bias).fit_session(work)
            drift = FALLBACK_DRIFT if fallback_drift is None else fallback_drift
            head = fuse_by_segment(_stride_heading(gyro, strides), head, strides["start_s"].to_numpy(float),
                                   strides["end_s"].to_numpy(float), foot_gaps, tau_s=np.inf, drift=drift)
            turned_by = "one constant offset (decision L226)"
            if drift:
                turned_by = "an offset that drifts linearly (decision L226, L266)" if not COMPASS_SPAN_GATES else (
                    f"an offset that drifts linearly on a stretch of at least {FALLBACK_DRIFT_MIN_S:g} s, one constant "
                    "on a shorter one (decision L226, L266, L280)")
            warnings[warnings.index(compass_line)] = compass_line.split("; track with")[0] + (
                f"; this track follows the waist gyroscope's heading, turned to the compass by {turned_by}")
        elif hsrc == "fused" and not (mount_info or {}).get("fallback"):  # D25 (W415: also without its line)
            sinus = _compass_sinusoid(relative, head, strides, straight, info_out=sinus_info)  # decision L770
            if compass_sinusoid:  # L770 (candidate A, an option): the compass's hard-iron sinusoid off before L17
                head = head - sinus
            else:  # L770 (candidate B, adopted): the line when its amplitude reaches 5 deg
                line = compass_sinusoid_line(sinus_info.pop("compass_sinusoid_deg"),
                                             sinus_info.pop("compass_sinusoid_residual_deg"),  # L785
                                             compass=wh.compass_ is not None)  # W616
                warnings += [line] if line else []
            head = fuse_by_segment(relative, head, strides["start_s"].to_numpy(float),
                                   strides["end_s"].to_numpy(float), foot_gaps, tau_s=fused_tau_s,
                                   walking=FUSED_WALKING_CLOCK,
                                   keep=straight if fused_straight else None)  # decisions L471, L589, L609
        head = head + side_extra  # decision L219 (0 without a sideways run)
    elif hsrc == "foot":
        head = fd.foot_heading(0.0) + lateral
        head = head + initial_heading - foot_walk_reference(head, disp, lateral, fd.yaw_change_)  # L494, L510
    else:
        raise DataError(f"plasys: heading '{hsrc}' is not waist, foot or fused")
    if hsrc in ("waist", "fused") and not SIDE_TRAVEL_HEADING:  # decision L219: a side-stepping stretch is put
        # along the body's facing
        from pdrlearn.track.sideways import sideways_warnings

        warnings += sideways_warnings(session, lambda a, b: (
            "the heading comes from the waist unit, which follows where the body faces, so the track puts these "
            "strides along the facing and can turn the walk around them"))
    if cfg["rules"] and hsrc in ("foot", "fused"):  # decision L65: offline as the streamed L37 - a stride whose
        # sign the rules turned against its measured x (a turnaround classed forward) goes along its displacement
        head = head + np.where((length != 0) & ((length < 0) != (disp[:, 0] < 0)), np.pi, 0.0)

    table = strides[["start_s", "end_s"]].copy()
    table["event_s"] = strides["event_s"] if "event_s" in strides else strides["end_s"]
    table["length_m"] = length
    table["raw_length_m"] = signed_chord(raw_disp[:, 0], raw_disp[:, 1], fd.yaw_change_)  # decision L692
    table["heading_rad"] = wrap_angle(head)
    table["dz_m"] = dz
    # decision L775: the stride's integrated height change before L39's level rule or a class (gait's ramp strides)
    table["raw_dz_m"] = np.where(unjudged, np.nan, disp[:, 2])
    for c in ("terrain", "direction", "length_class"):
        table[c] = classes[c].to_numpy() if c in classes else None
    table["confidence"] = classes["confidence"].to_numpy(float) if "confidence" in classes else 1.0
    for c in classes.columns:
        if c.startswith("p_") or (c.startswith("ood_") and not c.startswith("ood_feature_")):
            table[c] = classes[c].to_numpy(float)
    for c in classes.columns:  # decision L583: which classifier classed each stride, as the streamed table's
        if c.startswith("method_"):
            table[c] = classes[c].to_numpy(dtype=object)
    if windows is not None:  # decision L38: the windows the classes come from
        table["window_start_s"], table["window_end_s"] = (windows[c].to_numpy(float) for c in ("start_s", "end_s"))
    table["sideways"] = _sideways_rows(lateral, disp, fd.yaw_change_)  # L228: no steady / straight stride for the CVs
    if "contact_source" in strides:  # decision L405: a stitched track's contacts by detector (force / imu)
        table["contact_source"] = strides["contact_source"].to_numpy(dtype=object)
    from pdrlearn.track.travel import side_labels

    table["travel"] = side_labels(table["sideways"], disp[:, 1])  # decision L412: a side step's side (foot frame)
    table["unit"] = "foot"
    # decision L66: gait parameters (IC-to-IC stride time from event_s, swing from the stance detection, the
    # foot's own turn over the stride)
    tc, tc_gyro = None, None
    if toe_off or fev is not None:  # decision L73: toe-off from the foot gyroscope at its native rate (L390: the
        from pdrlearn.track.toeoff import toe_off_times  # insoles' clock is checked against it)

        tc_gyro = toe_off_times(foot.t, foot.gyr, table["start_s"], table["end_s"], table["event_s"])
    force_names = [n for n in ("fForceA", "fForceB") if n in session.streams]
    # decisions L389 / L390 / B297: the insoles' clock against the IMU's own events; steps 75: not on one channel,
    # whose drop-off is the heel's when it is a heel (user 10138: -210 ms against the toe-off, a false clock line)
    if fev is not None and len(force_names) == 2:
        from pdrlearn.track.stride_kinds import disp_kind_labels

        force_offset, clock_line = offset_check(session, fev, force_names, table=table, tc_gyro=tc_gyro,
                                                forward=disp_kind_labels(disp, fd.yaw_change_) == "forward")  # B449
        if clock_line:  # B297: L161's waist-vs-foot line compares with the insoles' contacts, so it says so
            warnings[:] = [w + INSOLE_CLOCK_NOTE if "decision L161" in w else w for w in warnings]
            warnings.append(clock_line)
    if toe_off:  # decision L73: the stance/swing split (the toe-off columns only with --toe-off)
        tc, toe_off_source = tc_gyro, "gyroscope"
        if fev is not None and FORCE_TOE_OFF:  # decision L388: the force drop-off where the insoles have one
            tf = toe_offs_in(fev["start_s"], table["start_s"], table["event_s"])
            toe_off_source = ("force" if np.isfinite(tf).all() else "force+gyroscope") if np.isfinite(tf).any() \
                else "gyroscope"
            tc = np.where(np.isfinite(tf), tf, tc)
    add_gait_columns(table, turn_rad=fd.yaw_change_, valid=~in_gap & ~impossible, tc_s=tc,  # L97: no stride
                     turn_valid=~in_gap, max_stride_s=stride_cap)  # L109: a zeroed stride keeps its turn
    if domain is not None and cfg["rules"]:  # decision L474: strides faster / slower than the training strides
        from pdrlearn.track import speed_domain as sd

        speed_info = sd.flag_speeds(table, sd.model_speed_range(model), warnings, sd.model_speed_strides(model))
        if speed_info is not None and isinstance(domain, dict):
            domain["speed"] = speed_info
        time_info = sd.flag_stride_times(table, model, warnings)  # decision C191: the calibration's tempo
        if time_info is not None and isinstance(domain, dict):
            domain["stride_time"] = time_info
    if cfg["rules"] and use_bounds is not None and classified_length is not None and "length" not in untrained \
            and not (isinstance(model, str) and model == "oracle"):  # decision C89: the classes on turning strides
        from pdrlearn.track.turn_classes import turning_length_disagreement, turning_length_line

        n_off, n_turn = turning_length_disagreement(classified_length, table["raw_length_m"],
                                                    table["turn_angle_rad"], parse_bounds(use_bounds),
                                                    ~in_gap & ~impossible)
        line = turning_length_line(n_off, n_turn, len(table), replaced=turn_rule)
        if line:
            warnings.append(line)
    if toe_off:  # decision L315: L285's stance bound on one foot's track
        from pdrlearn.track.bilateral import session_foot
        from pdrlearn.track.gait import stance_share_warning

        line = stance_share_warning(table, session_foot(session.meta or {}))  # decision L763: the foot named
        if line:
            warnings.append(line)
    swing_columns(table, fd, ~in_gap & ~impossible)  # decision L421: clearance and sole angles
    table["impossible"] = impossible  # decision L97: the strides L94 moved 0 m (no gait values)
    table["gap_s"] = longest_gap_in(table["start_s"], table["end_s"], foot_gaps)  # decision L67 (run's E37)
    table = table[[c for c in table.columns if c != "unit"] + ["unit"]]  # gap_s before unit, as run's steps.csv
    head = np.asarray(head, dtype=float)
    extra = gap_rows(table, foot_gaps)
    if len(extra):  # decision L67: the strides dropped at a foot gap are one row of 0 m, as `pdrlearn run`'s
        at = extra["before"].to_numpy(int)
        rows = pd.DataFrame({"start_s": extra["start_s"], "end_s": extra["end_s"], "event_s": np.nan,
                             "length_m": 0.0, "raw_length_m": np.nan,
                             "heading_rad": table["heading_rad"].to_numpy()[at - 1],
                             "dz_m": 0.0, "raw_dz_m": np.nan, "confidence": np.nan, "unit": "foot",
                             "impossible": False,
                             "sideways": False,
                             "gap_s": extra["gap_s"]})
        table = pd.concat([table, rows], ignore_index=True)
        length = np.concatenate([length, np.zeros(len(at))])
        dz = np.concatenate([dz, np.zeros(len(at))])
        head = np.concatenate([head, head[at - 1]])
        order = np.argsort(table["start_s"].to_numpy(float), kind="stable")
        table = table.iloc[order].reset_index(drop=True)
        length, dz, head = length[order], dz[order], head[order]
        climb_dz = None if climb_dz is None else np.concatenate([climb_dz, np.zeros(len(at))])[order]  # L564
        inserted = np.flatnonzero(order >= len(order) - len(at))  # the gap rows' new places
        add_gait_columns(table, turn_rad=table["turn_angle_rad"].to_numpy(float),  # the rows next to a gap row
                         valid=stride_rows(table), turn_valid=turn_rows(table),  # decisions L67, L97, L109
                         tc_s=table["tc_s"].to_numpy(float) if "tc_s" in table else None, max_stride_s=stride_cap)

    xyz = np.zeros((len(table) + 1, 3))
    xyz[1:, 0] = np.cumsum(length * np.cos(head))
    xyz[1:, 1] = np.cumsum(length * np.sin(head))
    xyz[1:, 2] = np.cumsum(dz)
    traj = pd.DataFrame({"t": np.concatenate([[table["start_s"].iloc[0]], table["end_s"].to_numpy()]),
                         "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2] + start_alt})  # L157: z from alt
    if start is not None:
        ll = geodetic_track(start, length, head)
        traj["lat"], traj["lon"] = ll[:, 0], ll[:, 1]
    # decision L654 (amends L65): length_m's sign is the measured travel (|length| along heading + pi, same path)
    rep_length, rep_head = SK.travel_sign(length, head, table["raw_length_m"].to_numpy(float),
                                          table["sideways"].to_numpy(dtype=bool),  # decision C137
                                          table["turn_angle_rad"].to_numpy(float))  # decision L578
    side_class_warning(table, warnings, trained_side_strides(model))  # decisions C137, C161
    turn_reference_warning(table, fd.reference_point, warnings)  # decision L489: many turns on the spot
    if len(extra):  # decision L76: a gap row reports the heading of the row before it (after L65's sign)
        for i in inserted[inserted > 0]:
            rep_head[i] = rep_head[i - 1]
    table["length_m"], table["heading_rad"] = rep_length, wrap_angle(rep_head)
    oracle = isinstance(model, str) and model == "oracle"
    info = {"pipeline": "plasys", "method": "M3 engine, no classes" if no_classes else method,
            "heading_source": hsrc, "stance_source": stance_source,
            **({"waist_gap_turns": gap_turns} if gap_turns else {}),  # decision L701 (turns.csv's rows)
            "force_offset_s": force_offset,  # decision L389 (None: no force stance)
            "toe_off_source": toe_off_source if toe_off else None,  # decision L388
            "hard_iron": hard_iron_info,  # decision L84 (None: the fit was not asked)
            **sinus_info,  # decision L770: compass_sinusoid_deg when compass_sinusoid was asked
            "compass_check": compass_info,  # decision L182 (None: no compass heading, or too few strides)
            "compass_mount": mount_info,  # decision D25 (None: no compass heading)
            "steps_source": source,
            "classes_source": ("oracle" if oracle else ("model" if cfg["rules"] else None)),
            # decision L38: strides classified on the streaming segmenter's window / on their own bounds
            "class_windows": (None if windows is None else
                              {"segmenter": int(windows.attrs.get("segmenter_windows", 0)),
                               "own": len(windows) - int(windows.attrs.get("segmenter_windows", 0))}),
            "unit_alignment": alignment,
            "out_of_domain": domain,  # decision C16: strides outside the model's training range
            "classifier_rate_mismatch": off_rate,  # decision C18
            "resampled": session.meta.get("resampled") or None,  # B113 amended (review): from_hz / to_hz
            "length_bounds_m": step_rules.effective_bounds() if clamp else None,
            "rules": rules if cfg["rules"] else None,
            "min_confidence": gate if cfg["rules"] else None,
            "distance_gain": gain, "distance_gain_source": gain_source,
            "stride_sigma_rel": step_rules.sigma_rel if cfg["rules"] and rules == "bayes" else None,
            "settings": {k: getattr(fd, k)
                         for k in ("integrator", "zupt_end", "gyro_bias", "attitude", "sw", "r",
                                   "accel_scale_error", "reference_point", "yaw", "rest_bias",
                                   "rest_drift", "rest_drift_by")},  # L476, L712, L731
            # decision L22: heel contact - sensor (body frame, m) when the heel is the reference point
            "lever_arm_m": None if fd.lever_arm_ is None else [round(float(v), 4) for v in fd.lever_arm_],
            "altitude_check": altitude_check, "terrain_dz_check": terrain_check,  # decisions L69, C28
            "steep_stride_check": steep_check,  # decision L430
            # decision L431: the contacts' cadence as `pdrlearn steps` judges it
            "contact_cadence_spm": _contact_cadence(seen, table, foot.t, stance),
            "warnings": warnings}
    if fused_climb and not leveled:  # decision L586: the model's terrain classes set the strides' heights
        warnings.append(FUSED_CLIMB_DROPPED)
    res = TrackResult(steps=table, trajectory=traj, info=info)
    logged = len(warnings)  # apply_altitude logs its own lines
    apply_altitude(res, session, altitude,  # decision L154 (L292: rewrites L69's line; L564 / L565: an option)
                   raw_dz=climb_dz if fused_climb else None)
    from pdrlearn.track.units import with_left_out_units

    # decision L378: the rides, from the waist barometer (streamed and `run` too since E293); L615 / L616: the foot's
    # vibration tells a vehicle; L634: `--units foot` leaves the waist's motion out, not its barometer
    foot_rides(res, with_left_out_units(session), ride_vibration)
    res.steps.insert(res.steps.columns.get_loc("terrain") + 1, "terrain_dz",  # decision L424: beside the class
                     KD.terrain_from_dz(res.steps["dz_m"], stride_rows(res.steps)))
    for w in warnings[:logged]:
        log.warning("%s: %s", session.where, w)
    if transfers and work is session:  # decision L612: read above, on this clock
        res.info.update(trunk.info)
    elif transfers:  # decision W439: callers that read no TUG (the distance calibration) skip the inner waist work
        add_trunk_transfers(res, work)  # decision W418 (W430: the waist on the aligned clock, as --clock-offset)
    from pdrlearn.track.trunk_pauses import add_trunk_pauses

    add_trunk_pauses(res)  # decision L687: the lower back's stops are the two-unit track's pauses
    return _foot_ramps_option(res, foot_ramps)  # decision L717


def _foot_ramps_option(res: TrackResult, foot_ramps: bool) -> TrackResult:
    """Decision L717: ``foot_ramps=True`` recorded in ``res.info`` (:data:`pdrlearn.track.grade.FOOT_RAMPS_KEY`), so
    the summary and the tables read the ramps of a track without terrain classes from its own L39 heights."""
    if foot_ramps:
        from pdrlearn.track.grade import FOOT_RAMPS_KEY

        res.info[FOOT_RAMPS_KEY] = True
    return res


def _compass_sinusoid(relative, head, strides: pd.DataFrame, straight, *, info_out: dict) -> np.ndarray:
    """Decision L770: the waist heading's direction sinusoid per stride (rad) on L471's walking clock, its amplitude
    (deg, or None when the gates refuse) in ``info_out["compass_sinusoid_deg"]`` and the fit's residual SD (deg,
    decision L785) in ``info_out["compass_sinusoid_residual_deg"]``."""
    from pdrlearn.kernels.compass_sinusoid import direction_sinusoid

    clock = walking_clock(strides["start_s"].to_numpy(float), strides["end_s"].to_numpy(float))
    sinus, amp, resid = direction_sinusoid(relative, head, clock, straight,  # L84's gates
                                           min_strides=HARD_IRON_MIN_STRIDES, max_resultant=HARD_IRON_MAX_RESULTANT,
                                           with_residual=True)  # L785
    info_out["compass_sinusoid_deg"] = None if amp is None else float(np.degrees(amp))
    info_out["compass_sinusoid_residual_deg"] = None if resid is None else float(np.degrees(resid))
    return sinus


def compass_sinusoid_line(amplitude_deg: float | None, residual_deg: float | None = None, *, min_deg: float = 5.0,
                          max_deg: float = 12.0, max_residual_deg: float = 6.0, compass: bool = True) -> str | None:
    """Decision L770 (candidate B, adopted by its rule): the warning of a fused track whose waist compass reads a
    heading error that follows the walking direction (:func:`_compass_sinusoid`'s amplitude ``amplitude_deg``, deg)
    of ``min_deg`` or more (L708's bound: 5 deg moves a track sideways by 8.7 % of the distance); None under it or
    when the walk turned too little to see it. Decision L785: the line advises ``compass_sinusoid`` only where L770
    measured its gain - an amplitude of at most ``max_deg`` (L770's fits: 2.4-11.5 deg) and a fit residual
    ``residual_deg`` (deg; None: not judged) of at most ``max_residual_deg`` (L770's missions 3.5-5.0 deg); else it
    says the difference is not a hard iron's sinusoid and does not advise the option (trial s51t1: a 26-75 min hike's
    foot drift read as +-57.7 / +-130.8 deg, the option 205.6 -> 1277.96 m, 82.55 -> 3276.62 m). Decision W616:
    ``compass`` False (a waist unit without a magnetometer, its heading the gyroscope's) gives None - the fit then
    reads the waist gyroscope against the foot's, no compass (trial s52t3: 6 of 6 such sessions were told of a
    compass beside "no magnetometer")."""
    if not compass or amplitude_deg is None or not amplitude_deg >= min_deg:
        return None
    from pdrlearn.decision_refs import decision_ref

    if amplitude_deg <= max_deg and (residual_deg is None or residual_deg <= max_residual_deg):
        return (f"the waist compass's heading error follows the walking direction by +-{amplitude_deg:.1f} deg (an "
                "uncalibrated hard-iron offset), and the fused heading carries it: the way out and the way back are "
                "turned differently, so a walk back to its start does not close; --params '{\"compass_sinusoid\": "
                "true}' takes it off (40 simulated 6-min missions: median final error 2.41 -> 1.40 m, the foot alone "
                "3.08 m), `--units foot` tracks the foot alone, relative to the start "
                f"({decision_ref('L707', 'L770')})")
    resid = "" if residual_deg is None else f", {residual_deg:.1f} deg left unexplained"
    return (f"the waist compass's heading differs from the foot's by more than an uncalibrated hard iron explains (a "
            f"fit of +-{amplitude_deg:.1f} deg along the walking direction{resid}; a hard iron's fit is at most "
            f"{max_deg:g} deg with at most {max_residual_deg:g} deg left): on a long walk this is mostly the foot "
            "gyroscope's own drift and the trunk's motion, which the fused heading already takes from the compass, "
            "so --params '{\"compass_sinusoid\": true}' is not advised here (it would turn the track: trial hikes "
            "205.6 -> 1277.96 m); keep the fused heading and check the position with fixes (`track --fixes`) "
            f"({decision_ref('L770', 'L785')})")


def fuse_by_segment(relative: np.ndarray, absolute: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
                    foot_gaps: dict, *, tau_s: float = 60.0, drift: bool = False,
                    walking: bool = False, keep: np.ndarray | None = None) -> np.ndarray:
    """Decision L90: :func:`fuse_heading` on each stretch of strides between two foot-IMU gaps (``fAccelerometer``
    / ``fGyroscope``, over 1 s) on its own: the foot's relative heading loses its link at such a gap (the turn
    inside it was not measured), so each stretch gets its own offset to the waist heading, from its own strides -
    the strides before a gap do not depend on anything after it, and after it the waist heading re-anchors the
    foot's. A stride belongs to the stretch after every gap that ended by its start. Without such a gap: one
    :func:`fuse_heading` call, as before. ``drift``: each stretch's offset is :func:`fuse_with_drift`'s line
    (decision L266) instead of :func:`fuse_heading`'s window. ``walking``: the window runs on
    :func:`walking_clock` (decision L471), so a long rest inside a stretch does not split it. ``keep``: the strides
    :func:`fuse_heading`'s window counts (decision L589; not the drift line's)."""
    kept = np.ones(len(relative), bool) if keep is None else np.asarray(keep, bool)

    def one(r, a, t, k):
        if not drift:
            return fuse_heading(r, a, t, tau_s=tau_s, keep=None if keep is None else k)  # L17 (L471, L589)
        return fuse_with_drift(r, a, t, min_span_s=FALLBACK_DRIFT_MIN_S if COMPASS_SPAN_GATES else None)  # L280

    clock = walking_clock(start_s, end_s) if walking and not drift else np.asarray(end_s, float)  # decision L471
    ends = sorted(b for k, g in foot_gaps.items() if k in FOOT_IMU for _, b in g)
    if not ends or not len(relative):
        return one(relative, absolute, clock, kept)
    seg = np.searchsorted(np.asarray(ends), np.asarray(start_s, float), side="right")
    out = np.empty(len(relative))
    for k in np.unique(seg):
        m = seg == k
        out[m] = one(np.asarray(relative)[m], np.asarray(absolute)[m], clock[m], kept[m])
    return out


def bridge_foot_yaw(fd: FootDisplacement, foot_gaps: dict, stream=None, *, every: bool = False) -> None:
    """Decisions L90 / L91: the foot's turn is not integrated over a foot-IMU gap (``fAccelerometer`` /
    ``fGyroscope``, over 1 s): the gyroscope there is an interpolated line (``orient.unit_data``), so the yaw of a
    stride whose bounds overlap a gap (``fd.yaw_change_``) and the pivot before a stride whose pause from the
    previous stride overlaps one (``fd.gap_yaw_``, L28) become the waist's turn over the same interval
    (:func:`~pdrlearn.kernels.stride.waist_bridge_yaw`; ``stream(name)`` -> ``(t, values)``) or, with ``stream``
    None (no waist gyroscope), 0. Strides and pauses that overlap no such gap keep their values bit for bit.
    ``every`` (decision L525: a clipped foot gyroscope's stride yaw is not trusted): every stride's turn is the
    waist's from the previous stride's end (the pause's turn folded in, as a streamed row's ``pivot_rad``, L106, so
    that a turn on the spot counts), and no pause keeps a turn of its own."""
    imu = {k: v for k, v in foot_gaps.items() if k in FOOT_IMU and v}
    if not (imu or every) or not len(fd.yaw_change_):
        return
    st, en = np.asarray(fd.start_s_, float), np.asarray(fd.end_s_, float)

    def over(a: float, b: float) -> bool:
        return overlaps_any(a, b, imu)

    def turn(a: float, b: float) -> float:
        return 0.0 if stream is None else SK.waist_bridge_yaw(stream, a, b)

    yc = np.array(fd.yaw_change_, dtype=float)
    gy = np.array(getattr(fd, "gap_yaw_", np.zeros(len(yc))), dtype=float)
    if every:
        fd.yaw_change_ = np.array([turn(min(st[k], en[k - 1]) if k else st[k], en[k]) for k in range(len(yc))])
        fd.gap_yaw_ = np.zeros(len(yc))
        return
    for k in range(len(yc)):
        if over(st[k], en[k]):
            yc[k] = turn(st[k], en[k])
        if k and en[k - 1] < st[k] and over(en[k - 1], st[k]):
            gy[k] = turn(en[k - 1], st[k])
    fd.yaw_change_, fd.gap_yaw_ = yc, gy


def swing_columns(table: pd.DataFrame, fd: FootDisplacement, valid: np.ndarray) -> None:
    """Decision L421: ``max_sensor_lift_m`` (L795: and ``min_toe_clearance_m``) and the sole angles ``ic_angle_deg``
    (at ``event_s``) and ``tc_angle_deg`` (at ``tc_s``, where the toe-off is known) of each stride row of ``table``
    (the rows of ``fd``), NaN on the rows not ``valid`` (a stride across a gap, one L94 moved 0 m)."""
    from pdrlearn.track.table_columns import place_column

    valid = np.asarray(valid, dtype=bool)
    tc = table["tc_s"].to_numpy(float) if "tc_s" in table else np.full(len(table), np.nan)
    # before the gait columns (L66) and L97's tail, which run's and track --streaming's steps.csv end with too
    place_column(table, "max_sensor_lift_m", np.where(valid, fd.lift_m_, np.nan), before=("stride_time_s",))
    ic = table["event_s"].to_numpy(float)
    place_column(table, "min_toe_clearance_m", np.where(valid, fd.min_toe_clearance(tc, ic), np.nan),
                 after=("max_sensor_lift_m",))  # decision L795
    place_column(table, "ic_angle_deg", np.where(valid, fd.sole_angle(ic), np.nan),
                 after=("min_toe_clearance_m",))
    place_column(table, "tc_angle_deg", np.where(valid, fd.sole_angle(tc), np.nan), after=("ic_angle_deg",))
    from pdrlearn.kernels.contact_type import contact_types

    # decision L756: forefoot / flat / heel from the sole angle at the contact
    place_column(table, "contact", contact_types(table["ic_angle_deg"].to_numpy(float)), after=("tc_angle_deg",))
    if getattr(fd, "heel_lift_m_", None) is not None:  # decision L721: --reference-point heel with a lever arm
        place_column(table, "max_heel_lift_m", np.where(valid, fd.heel_lift_m_, np.nan), after=("max_sensor_lift_m",))


def _level_without_classes(res: TrackResult) -> None:
    """Decision L39 on a streamed track without classes: the level strides' ``dz_m`` set to 0 and the
    trajectory's height re-accumulated (one trajectory row per stride after the start row)."""
    set_strides_dz(res, level_dz(res.steps["dz_m"].to_numpy(float)) if len(res.steps) else np.zeros(0))


def _unclassed(classes: pd.DataFrame, mask: np.ndarray) -> pd.DataFrame:
    """A copy of the streamed strides' ``classes`` with no class or probability on the strides of ``mask`` (E30's
    strides, L674's)."""
    classes = classes.copy()
    for c in [c for c in classes.columns if c in ("terrain", "direction", "length_class") or c.startswith("p_")]:
        num = pd.api.types.is_float_dtype(classes[c].dtype)
        classes[c] = classes[c].astype(float if num else object)
        classes.loc[mask, c] = np.nan if num else None
    return classes


def _one_row_per_gap(table: pd.DataFrame, traj: pd.DataFrame, in_gap: np.ndarray,
                     gaps: dict) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Decision E46: the streamed strides that touch a foot gap (``in_gap``, 0 m each) replaced by offline's
    gap rows (L67, :func:`~pdrlearn.track.gaps.gap_rows` on the other strides): one 0 m row per stretch between
    two kept strides that a foot gap overlaps, the previous row's reported heading (L76), the position it
    leaves unchanged; the runtime's ``Tracker`` emits the same rows one stride at a time."""
    keep = np.flatnonzero(~in_gap)
    if not len(keep):
        return table.iloc[:0].reset_index(drop=True), traj.iloc[:1].reset_index(drop=True)
    kt = table.iloc[keep].reset_index(drop=True)
    kj = traj.iloc[np.concatenate([[0], keep + 1])].reset_index(drop=True)
    kj.loc[0, "t"] = kt["start_s"].iloc[0]  # the gap strides dropped before the first kept one moved 0 m
    extra = gap_rows(kt, gaps)
    if not len(extra):
        return kt, kj
    at = extra["before"].to_numpy(int)
    rows = pd.DataFrame({c: [None if kt[c].dtype == object else np.nan] * len(at) for c in kt.columns})
    rows["start_s"], rows["end_s"] = extra["start_s"].to_numpy(float), extra["end_s"].to_numpy(float)
    rows["event_s"] = np.nan  # no initial contact (decision E49; offline's gap rows, L67)
    rows["length_m"], rows["raw_length_m"], rows["dz_m"] = 0.0, 0.0, 0.0
    rows["heading_rad"] = kt["heading_rad"].to_numpy(float)[at - 1]  # decision L76
    rows["gap_s"], rows["unit"] = extra["gap_s"].to_numpy(float), "foot"
    if "impossible" in rows:  # decision L97: a gap row is no zeroed stride
        rows["impossible"] = False
    if "sideways" in rows:  # decision L243: a gap row is no side step (L228's)
        rows["sideways"] = False
    prev = kj.iloc[at].reset_index(drop=True)  # the position after the kept row before (the row moves 0 m)
    prev["t"] = rows["end_s"].to_numpy(float)
    key = np.concatenate([np.arange(len(kt), dtype=float), at - 0.5])
    order = np.argsort(key, kind="stable")
    table = pd.concat([kt, rows], ignore_index=True).iloc[order].reset_index(drop=True)
    traj = pd.concat([kj.iloc[:1], pd.concat([kj.iloc[1:], prev], ignore_index=True).iloc[order]],
                     ignore_index=True)
    return table, traj


def track_streaming(session: Session, *, method: str = "M3", model=None, start=None, params=None,
                    heading: str = "auto", initial_heading: float = 0.0, bounds=None, bounds_scale: float = 2.0,
                    down_mode: str = SK.DEFAULT_DOWN_MODE, rest_search_s: float = 0.3, step_heading: str = "pca",
                    distance_gain: float | None = None, calibration: bool = True, gap_yaw: bool = True,
                    waist_gap_yaw: bool = True, waist_bridge: bool = True, rules: str | None = None,
                    min_confidence: float | None = None,
                    warn_out_of_domain: float | None = None, contacts: bool = False,
                    drop_neighbour: bool = False, first_walk: bool = False,
                    gated_level_dz: bool | str = False, cycling: bool = True,
                    cycle_yaw: bool = True, bridge_cycle: bool = True, gap_compass: bool = True) -> TrackResult:
    """PLASYS M2/M3 with the streaming runtime's stride-local kernel (issue 7 trajectory parity).

    Strides come from :class:`~pdrlearn.kernels.stride.StanceSegmenter` fed the whole foot gyroscope;
    each stride's displacement from its own samples only (:func:`~pdrlearn.kernels.stride.stride_motion`:
    levelled foot acceleration, ZUPT at both stances); M3 classes from ``model`` (directory, loaded model
    or ``"oracle"``) and the rules of :func:`~pdrlearn.kernels.stride.apply_stride_rules`; the heading is
    ``initial_heading`` + the integrated levelled vertical rate (``heading``: "auto" = waist gyroscope
    when present, else foot; "foot"; "waist-gyro"). ``Tracker(bundle)`` streaming the same session gives
    the same steps and positions (tested to 1 mm). Session-wide steps (Kalman smoother, waist heading
    filter with the magnetometer, fused heading) are not streamable and not used here. ``distance_gain`` /
    ``calibration``: as :func:`track_plasys` (decision L26): M3 with a trained model multiplies the level
    strides' horizontal displacement by the model's distance gain when its foot rate matches the session's,
    as the runtime does with a bundle's ``displacement.distance_gain`` (decision E14). ``rules`` /
    ``min_confidence``: as :func:`track_plasys` (default "bayes" on the classes the model is >= 0.95 sure of,
    "thesis" with oracle labels; decision L40: one stride at a time,
    :func:`~pdrlearn.kernels.stride.stride_rules_one`, the runtime's call), the bayes rule with the
    calibrated stride sd when the calibration applies (L26). ``gap_yaw``
    (decision L31, as the runtime): a stride headed by the foot adds the turn of the foot
    pivoting in the gap before it (:func:`~pdrlearn.kernels.stride.gap_yaw`, the streamed form of L28).
    ``waist_gap_yaw`` (decision L61, as the runtime's): a stride headed by the waist gyroscope adds the waist's
    turn in the gap before it (:func:`~pdrlearn.kernels.stride.stride_gap_yaw`). ``waist_bridge`` (decision L99,
    as the runtime's; L91's mechanism): a stride headed by the waist gyroscope across a foot-IMU gap over 1 s turns
    by the waist's turn from the previous stride's end (the foot's rest before the gap) to its own end (the rest
    after it); False: 0 (L90). ``bridge_cycle`` (decision E354, as the runtime's): across the waist gyroscope's own
    gap inside that bridge the turn is the line between the gait-cycle mean rates of the stride before and the stride
    after (:class:`~pdrlearn.kernels.stride.CycleGapLine`, added to the stride after); False: L91's line between the
    rates at the gap's edges. ``gap_compass`` (decision E361, as the runtime's): after such a gap the heading is also
    re-anchored to the waist compass, weighed against that line (:class:`~pdrlearn.kernels.gap_compass.GapCompass`);
    False: the line alone. ``drop_neighbour=True`` (decision L167, an option, as the runtime ``Tracker``'s;
    E101: a keyword, False by default, L549): a stride across dropped foot samples over 0.25 s
    (under 1 s) takes the length (scaled by the durations) and height change of the clean stride before it.
    ``first_walk=True`` (decisions E215, E222, an option, as the runtime ``Tracker``'s): a foot-headed track's
    heading is turned once, at the end of its first walk, by that walk's direction. ``gated_level_dz`` (decisions
    L189, L206, options not adopted; L550: a keyword, as the runtime ``Tracker``'s): True / ``"summed"`` give an M3
    stride whose terrain class the gate dropped L39's level rule, per stride / on its run's summed dz; False: raw.
    ``cycle_yaw`` (decision E336, as the runtime ``Tracker``'s): a stride headed by the waist gyroscope goes along its
    gait cycle's mean yaw (the heading after it less the pelvic rotation's yaw at its ends); False: the heading after
    it.
    """
    start, start_alt = start_coordinate(start)  # decision L157: (lat, lon[, alt]) checked as --start
    initial_heading = heading_in_radians(initial_heading, "initial_heading")  # decision L158 (W81's check)
    if method not in ("M2", "M3"):
        raise DataError(f"plasys streaming: method '{method}' is not streamable; use M2 or M3")
    gated_level_dz = KD.check_gated_level_dz(gated_level_dz)  # decision L550
    if heading not in SK.HEADING_SOURCES:
        raise DataError(f"plasys streaming: heading '{heading}' is not one of {', '.join(SK.HEADING_SOURCES)} "
                        "(waist/fused headings need the whole session)")
    session.require("fAccelerometer", "fGyroscope", purpose=f"PLASYS {method} (streaming)")
    from pdrlearn.features.windows import _declared_forward

    streams = {n: (s.t, s.values) for n, s in session.streams.items()}
    available = available_groups(streams)
    require_stride_cover(session, [n for g in available for n in GROUP_STREAMS[g]])
    forward = {p: _declared_forward(session, p) for p in ("foot", "waist")
               if f"{p}_acc" in available and session.has_frame(p)}
    seg_params = dict(params or {})
    fine = SK.fine_spec(seg_params, streams.__getitem__, forward, rest_search_s=rest_search_s,  # decision L141
                        heading=step_heading)
    strides = SK.stance_strides(*streams["fGyroscope"], seg_params)
    segmenter = SK.StanceSegmenter.from_params(seg_params)
    if segmenter.lull_join and "fAccelerometer" in streams:  # decision E345: a slow stair swing's lull is no stance
        strides = join_lulls(strides, *streams["fAccelerometer"], foot_rest_gravity(session), segmenter.max_step_s)
    spins = (turns_in_place(*streams["fAccelerometer"], *streams["fGyroscope"], strides[:, 0], strides[:, 1])
             if "fAccelerometer" in streams else np.zeros(len(strides), dtype=bool))  # decision L742, as the runtime
    # decision L742: each kept stride's (foot turn, end) of the turns in place left out since the stride before it
    spun = [None] * int((~spins).sum())
    for k in np.flatnonzero(spins):
        nxt = int((~spins[:k]).sum())  # the kept stride after it
        if nxt < len(spun):
            turn = spin_turn(streams.__getitem__, float(strides[k, 0]), float(strides[k, 1]))
            spun[nxt] = (turn + (spun[nxt][0] if spun[nxt] is not None else 0.0), float(strides[k, 1]))
    strides = strides[~spins]
    if not len(strides):
        raise DataError(f"session '{session.name}': no stance-to-stance stride found on the foot gyroscope"
                        + (f" ({spin_line(int(spins.sum()))})" if spins.any() else ""))
    table = pd.DataFrame({"start_s": strides[:, 0], "end_s": strides[:, 1]})
    # decision B11 / E30: as the streaming runtime (parity), a stride across a foot-stream gap over 1 s moves 0 m,
    # turns with the waist gyroscope when it heads the strides (L99; else keeps the heading, L90) and has no classes; a
    # waist gap is only warned (bridged)
    foot_gaps = long_gaps(session, ("fAccelerometer", "fGyroscope", "fForceA", "fForceB"))
    bridged = bool(waist_bridge and heading in ("auto", "waist-gyro") and "waist" in forward
                   and "waist_gyr" in available and "waist_acc" in available)  # decisions L91 / L99
    waist_how = ("foot" if heading == "foot" or not ("waist" in forward and "waist_gyr" in available)
                 else "streamed" if heading == "auto" else "waist-gyro")  # decision B231
    warnings: list[str] = unit_gap_warnings(session, foot_gaps,
                                            "no displacement is counted inside them (a stride across a foot gap "
                                            "moves 0 m, as the runtime, E30)"
                                            + gap_heading_clause(foot_gaps, "bridged" if bridged else "none",  # E365
                                                                 long_gaps(session, ("wGyroscope",)).get(
                                                                     "wGyroscope", []), bridge_cycle),
                                            waist_how)
    warnings += [spin_line(int(spins.sum()))] if spins.any() else []  # decision L742
    if heading == "auto" and not ("waist" in forward and "waist_gyr" in available):  # as offline M2/M3 say
        warnings.append(no_waist_heading(session))
    elif heading in ("auto", "waist-gyro"):  # decision W125: the waist gyroscope heads the strides, as `run`'s
        bias_line = waist_bias_line(session)
        warnings += [bias_line] if bias_line else []
    classes = pd.DataFrame(index=range(len(table)), columns=["terrain", "direction", "length_class"], dtype=object)
    model_bounds, domain, off_rate = None, None, None
    if method == "M3":
        if model is None:
            raise ModelError("M3 needs the step classes: pass a trained model directory or 'oracle'")
        if isinstance(model, str | Path) and str(model) != "oracle":
            from pdrlearn.classify import load_model

            model = load_model(model)
        classes, model_bounds = classes_and_bounds(model, session, table)
        warnings += classes.attrs.get("label_warnings", [])  # decision B209
        domain = domain_check(model, classes, warnings, warn_out_of_domain, session=session)  # decision C16
        untrained = [] if isinstance(model, str) and model == "oracle" else untrained_tasks(classes)
        if untrained:  # C17's line, with what the streamed rules do instead (they keep the raw height change)
            warnings.append(untrained_warning(untrained, streaming=True))
        off_rate = rate_check(model, session, classes, warnings)  # decision C18
    fs0, resampled_hz = recorded_rate(session, "fAccelerometer")  # decision B113: judged at the recorded rate
    gain, gain_source, stride_sd = _distance_gain(distance_gain, model if method == "M3" else None, fs0, warnings,
                                                  calibration, streaming=True,  # L41: the stride kernel's gain
                                                  resampled_hz=resampled_hz)
    # decision L41 (L40 amended): streamed, offline's default too - bayes with the 0.95 gate with a model's
    # classes, the thesis rule with oracle labels (with the stride kernel's own gain: better distance on A-D
    # and altitude on D than the thesis rule, held-out users 11-20)
    if rules is None:
        rules = "thesis" if isinstance(model, str) and model == "oracle" else DEFAULT_MODEL_RULES
        if (method == "M3" and calibration and distance_gain is None and not isinstance(model, str)
                and predates_streaming_calibration(model_distance_calibration(model))):
            rules = "thesis"  # L41: only the offline gain - the pair measured worse than thesis on C and D
            warnings.append(PRE_L41_CALIBRATION)
    rules = str(rules)
    gate = (0.0 if rules == "thesis" else DEFAULT_MIN_CONFIDENCE) if min_confidence is None else float(min_confidence)
    check_rules(rules, gate, "plasys streaming")
    # decision L26: the bayes rule weighs the classes against the user's own calibrated stride accuracy
    sigma_rel = float(stride_sd) if stride_sd and rules == "bayes" else SIGMA_REL
    use_bounds = bounds if bounds is not None else model_bounds
    rb = None
    if method == "M3":  # decision L60: the bounds as offline M3 takes them (above, L9 / L59)
        if use_bounds is not None or (isinstance(model, str) and model == "oracle"):
            rb = StepRules(bounds=parse_bounds(use_bounds) if use_bounds is not None else None,
                           bounds_scale=bounds_scale).effective_bounds()
            if use_bounds is None:  # oracle labels: L9's fallback, with offline's line
                warnings.append(f"no length-class bounds in the session: thesis step bounds x {bounds_scale:g} used")
        elif "length" not in untrained:  # a model without the user's bounds: no length rule (L59; C17: no class)
            warnings.append(SK.no_length_bounds_warning("the model"))
    disp, dyaw, place = np.zeros((len(table), 3)), np.zeros(len(table)), np.zeros(len(table))
    ic, turn = np.full(len(table), np.nan), np.full(len(table), np.nan)  # decisions E49-E51
    fa_t, fa_v = streams["fAccelerometer"]
    has_force = "fForceA" in streams and "fForceB" in streams
    foot_headed = np.zeros(len(table), dtype=bool)  # decision L37 needs only this of each stride
    phase_raw: list[tuple[float, float] | None] = [None] * len(table)  # decisions E336 / E343: (psi, turn)
    frame = np.zeros(len(table))  # decision E124: each stride's step frame from the foot's facing
    foot_turn = np.zeros(len(table))  # decision L400: the foot's heading change over each stride
    posture = np.zeros(len(table), dtype=bool)  # decision B131: strides skipped as the runtime skips them
    in_gap = overlaps_gaps(table, foot_gaps)  # decision E30: these strides move 0 m, turn 0, no classes
    hole = np.zeros(len(table))  # decision L674: each stride's hole in the foot's samples (s), 0 without one
    imu_gaps = {k: v for k, v in foot_gaps.items() if k in FOOT_IMU}
    imu_gap = overlaps_gaps(table, imu_gaps)  # decisions L90 / L91: the foot's yaw is lost over these strides
    # decision L167 (an option, drop_neighbour): a stride across dropped samples over the gap clock's limit takes the
    # length and height of the stride before it (ref: that stride's displacement and duration), as the runtime's
    across, ref = drop_strides(session, table, in_gap, min_gap_s=BRIDGE_GAP_S + GAP_TOL_S), None  # E230
    neighbour = bool(drop_neighbour)  # decisions E101, L549
    stop = KSB.StopBias() if "waist" in forward else None  # decision E272 (the runtime's: the waist unit tracked)
    pitch_ref = PitchReference()  # decisions B474 / B475: the most level rest pitch of the strides so far
    cycle_line = SK.CycleGapLine()  # decision E354
    compass = (GapCompass() if gap_compass and bridge_cycle and bridged and "wMagneticField" in streams
               else None)  # decision E361 (the runtime's)

    for i, (t0, t1) in enumerate(strides):
        prev = float(strides[i - 1, 1]) if i else None
        if in_gap[i]:  # decision L91: the waist's turn from the previous stride's end, else 0 (L90)
            if bridged and imu_gap[i]:
                lo = min(float(t0), prev if prev is not None else float(t0))
                dyaw[i] = SK.waist_bridge_yaw(streams.__getitem__, lo, float(t1), gap_line=not bridge_cycle)
                if bridge_cycle:  # decision E354: the waist gap's turn waits for the stride after it (the runtime's)
                    cycle_line.hold(streams.__getitem__, lo, float(t1))
            if compass is not None:  # decision E361: the row's turn in the compass's heading
                compass.row(dyaw[i])
            continue
        try:
            if "foot" in forward and pitch_ref.pitched(streams.__getitem__, forward["foot"], float(t0), float(t1),
                                                       rest_search_s=rest_search_s):  # decision B474 (the runtime's):
                raise VerticalAxisError("foot pitched at rest")  # far from the most level rest so far: B131's posture
            lev = levelled_units(streams, float(t0), float(t1), available=available, forward=forward,  # E36: a
                                 rest_search_s=rest_search_s, heading=step_heading, bridge_gaps=True)  # short gap
        except VerticalAxisError:  # = 1 interval; decision B131: after level strides, a posture (the runtime's)
            if i == int(posture.sum()):
                raise
            posture[i] = True
            continue
        disp[i], dyaw[i] = SK.stride_motion(lev, heading, t0=float(t0), t1=float(t1), fine=fine)
        if across[i]:
            disp[i] = drop_stride_disp(disp[i], float(t1 - t0), ref, neighbour)
        hole[i] = 0.0 if across[i] and neighbour else max(  # L167's option keeps its neighbour's height
            [stride_hole(streams[n][0], float(t0), float(t1)) for n in FOOT_IMU if n in streams], default=0.0)
        if hole[i]:  # decision L674 (the runtime's): a hole in the foot's samples, no classes and the height change
            disp[i, 2] = hole_stride_dz(ref)  # of the clean stride before it (R3 F1)
        elif not across[i]:
            ref = (disp[i].copy(), float(t1 - t0))
        turn[i] = dyaw[i]  # decision E51: the stride's own turn (the runtime's), before the pivot below
        a, b = np.searchsorted(fa_t, t0, side="left"), np.searchsorted(fa_t, t1, side="right")
        if contacts:  # decisions E49-E51 (an option): the runtime's initial contact
            force = force_at(fa_t[a:b], [streams[n] for n in ("fForceA", "fForceB")]) if has_force else None
            ic[i] = stride_contact(fa_t[a:b], fa_v[a:b, :3], force, ic[i - 1] if i else float("nan"))  # steps 87
        place[i] = SK.placement_offset(lev, heading, disp[i])  # decision L34
        frame[i] = KSW.step_frame(lev)  # decision E124: the step frame's direction from the foot's facing
        foot_turn[i] = KSW.foot_turn(lev)  # decision L400
        foot_headed[i] = SK.headed_by_foot(lev, heading)
        if cycle_yaw and not foot_headed[i]:  # decision E336: along the cycle's mean yaw (the runtime's call); the
            phase_raw[i] = SK.waist_phase_turn(lev, float(t0), float(t1))  # E338 phase is held below, after L611
        pause = bool(i and prev < t0 and overlaps_any(prev, float(t0), imu_gaps))
        stop_turn = (SK.long_stop_turn(streams.__getitem__, prev, float(t0)) if waist_gap_yaw  # decision E335: E324's
                     and not foot_headed[i] and not pause else None)  # turn read once for both calls below (runtime's)
        if pause:  # L90: no foot pivot over a foot gap;
            if bridged:  # L91: the waist's turn over the whole pause
                dyaw[i] += SK.waist_bridge_yaw(streams.__getitem__, prev, float(t0), gap_line=not bridge_cycle)
                if bridge_cycle:  # decision E354 (taken below by this stride)
                    cycle_line.hold(streams.__getitem__, prev, float(t0))
            elif not foot_headed[i]:  # L61's waist look-back is measured, kept
                dyaw[i] += SK.stride_gap_yaw(lev, heading, streams.__getitem__, prev, float(t0), foot=False,
                                             waist=waist_gap_yaw)
        elif i and spun[i] is not None and gap_yaw and foot_headed[i]:  # decision L742: the foot's turn in place
            dyaw[i] += spun[i][0] + SK.stride_gap_yaw(lev, heading, streams.__getitem__,  # before it (the runtime's)
                                                      foot_gap_start(prev, spun[i]), float(t0))
        elif i:  # decisions L31 / L61: the heading unit's turn between strides (the runtime's call)
            dyaw[i] += SK.stride_gap_yaw(lev, heading, streams.__getitem__, prev, float(t0),
                                         foot=gap_yaw, waist=waist_gap_yaw, stop_turn=stop_turn)
        if not pause:  # decision E285 (the runtime's call)
            started = KCY.carried_turn(streams.__getitem__, lev, heading, prev, float(t0), float(t1), waist_gap_yaw,
                                       stop_turn=stop_turn)
            if started is not None:
                turn[i], dyaw[i] = started
        if stop is not None and not foot_headed[i]:  # decision E272: the bias read at the last stop, as the runtime
            stop.update(streams.__getitem__, foot_gap_start(prev, spun[i]), float(t0))  # L742: after a turn in place
            lo = (prev if i and prev < t0 and bridged and overlaps_any(prev, float(t0), imu_gaps)
                  else SK.waist_gap_from(prev, float(t0), waist_gap_yaw))
            turn[i] -= stop.turn(t0, t1)
            dyaw[i] -= stop.turn(lo, t1)
        turn[i] = KSW.own_turn(lev, heading, turn[i])  # decision L699: the foot's own turn, as offline's row
        if bridge_cycle:  # decision E354: a held waist gap's turn (0 without one), the runtime's call
            dyaw[i] += cycle_line.take(streams.__getitem__, float(t0), float(t1))
            if bridged:  # decision E365: the rate before a next gap, recorded as the stride is measured
                cycle_line.note(streams.__getitem__, float(t0), float(t1))
        if compass is not None:  # decision E361 (the runtime's call)
            if foot_headed[i]:
                compass.row(dyaw[i])
            else:
                dyaw[i] += compass.stride(streams.__getitem__, float(t0), float(t1), dyaw[i], cycle_line.spread)
    if neighbour and (across & ~posture).any():
        warnings.append(drop_stride_warning(int((across & ~posture).sum()), streamed=True))
    if (hole > 0).any():  # decision L674: the runtime's line (for the first such stride) and its missing classes
        i = int(np.flatnonzero(hole > 0)[0])
        warnings.append(stride_hole_line(float(hole[i]), float(strides[i, 0]), float(strides[i, 1])))
        classes = _unclassed(classes, hole > 0)
    # decision L611 (offline's kernel): pedalling strides are skipped as B131's posture strides are (no row, 0 m)
    # (a stride across a bridged gap, L167's ``across``, is not judged: its interpolated swing is neither a height
    # reversal nor a missing rest; session 43, lead, after test_runtime_input_e29's 0.55 s gap lost 3 strides)
    unjudged = in_gap | across | posture
    pedal = closed_loop_strides(np.where(unjudged, 0.0, disp[:, 2]), strides[:, 0], strides[:, 1],
                                unrested_strides(fa_t, fa_v, strides[:, 0], strides[:, 1],
                                                 foot_rest_gravity(session)) & ~unjudged,  # decision L621
                                np.hypot(disp[:, 0], disp[:, 1]))
    pedal &= ~unjudged & bool(cycling)  # decision E304: no pedalling check (the runtime's Tracker(cycling=False))
    pedal_warning = pedal_line(pedal, np.zeros(len(pedal), dtype=bool), strides[:, 0], strides[:, 1])
    warnings += [pedal_warning] if pedal_warning else []
    if (posture | pedal).all():  # as offline: no stride is left to track (B318's exit code 4); B134 first (FM)
        raise NoStridesError(f"{session.where}: no walking strides: {_placement_clause(session)}{pedal_warning}"
                             f"{_no_strides_hint(session)}")
    skipped_posture, posture = posture, posture | pedal
    cycle_phase = SK.CyclePhase()  # decision E343: E338's held phase over the strides the runtime places (its _apply),
    for i in np.flatnonzero(~(in_gap | posture)):  # in order, after L611's mask: a crank stroke is no gait phase
        place[i] -= SK.held_phase_yaw(phase_raw[i], cycle_phase)
    raw_disp, disp = disp, apply_level_gain(disp, gain)  # decision L26 (the runtime: E14)
    if (method == "M3" and use_bounds is not None and "length_class" in classes
            and not (isinstance(model, str) and model == "oracle")):  # decision C94: C89's count, as the runtime's
        tally = KT.TurnTally()
        for i in np.flatnonzero(~posture):
            tally.add(classes["length_class"].iat[i], float(np.hypot(disp[i, 0], disp[i, 1])), float(foot_turn[i]),
                      parse_bounds(use_bounds))
        line = tally.line(replaced=KT.TURN_LENGTH_RULE)
        if line:
            warnings.append(line)
    if (KT.TURN_LENGTH_RULE and method == "M3" and use_bounds is not None and "length_class" in classes
            and not (isinstance(model, str) and model == "oracle")):  # decisions C88 / C91: as offline and the
        from pdrlearn.track.turn_classes import measured_classes_on_turns  # runtime, on the foot's turn (L400)

        classes = measured_classes_on_turns(classes, np.hypot(disp[:, 0], disp[:, 1]), foot_turn,
                                            parse_bounds(use_bounds))
    rule_classes = _confident(classes, gate) if method == "M3" else classes  # decision L18 / L40
    length, dz = SK.apply_stride_rules(disp, *(rule_classes[c].to_numpy(dtype=object)
                                               if method == "M3" and c in rule_classes else None  # length-only models
                                             for c in ("terrain", "direction", "length_class")),
                                       bounds=rb, down_mode=down_mode, rules=rules if method == "M3" else "thesis",
                                       length_proba=_length_proba(classes) if method == "M3" and rules == "bayes"
                                       else None,
                                       sigma_rel=sigma_rel)
    place += [SK.reversed_by_rules(bool(f), float(d[0]), float(L))  # decision L37
              for f, d, L in zip(foot_headed, disp, length, strict=True)]
    if method == "M3" and gated_level_dz and "terrain" not in untrained and "terrain" in rule_classes:
        # decision L189 (offline's L184, the same function) / L206 (the run's summed dz): a gated stride is level
        dz = KD.streamed_gated_level_dz(dz, [isinstance(t, str) for t in rule_classes["terrain"]],
                                        gated_level_dz)  # decision L550: the keyword
    length, dz, impossible = _drop_impossible(length, dz, strides[:, 0], strides[:, 1], warnings)  # L94, as run
    side_offset = np.zeros(len(table))
    # decisions E124 / E125 (adopted; E234: the rule is the code, no module switch): a side-stepping stretch's strides
    # headed by the waist go along their travel angle once the run is decided (the runtime's call, stride by stride)
    side = KSW.SideRun()
    for i in np.flatnonzero(~(in_gap | posture | foot_headed)):
        side_offset[i] = side.stride(float(disp[i, 0]), float(disp[i, 1]), float(length[i]), float(frame[i]),
                                     float(foot_turn[i]))  # L400
    place += side_offset
    if "direction" in classes:  # decision E216: the runtime's call, stride by stride
        place += [SK.waist_forward_flip(bool(f), c, float(L), float(o)) for f, c, L, o in
                  zip(foot_headed, classes["direction"].to_numpy(dtype=object), length, side_offset, strict=True)]
    sideways = np.zeros(len(table), dtype=bool)  # decision L243: the runtime's Step.sideways, stride by stride
    rows = KSW.SideRun()
    for i in np.flatnonzero(~(in_gap | posture)):
        rows.stride(float(disp[i, 0]), float(disp[i, 1]), float(length[i]), float(frame[i]), float(foot_turn[i]))
        sideways[i] = rows.decided
    if skipped_posture.any():  # decision B131: the runtime's one warning; the strides are dropped below
        warnings.append(posture_warning(int(skipped_posture.sum()), float(strides[skipped_posture][0, 0]),
                                        float(strides[skipped_posture][-1, 1])))
    lost = in_gap | posture
    if lost.any():  # decision E30: the runtime's Step for such a stride (0 m, no classes)
        length, dz = np.where(lost, 0.0, length), np.where(lost, 0.0, dz)
        classes = _unclassed(classes, lost)
    terrain_check, altitude_check = None, None
    if method == "M3" and "terrain" in untrained:  # decision L69 (C17): a model without terrain classes, as offline
        msg, altitude_check = coded_altitude_check(dz, levelled=False)
        warnings += [msg] if msg else []
    elif method == "M3" and not (isinstance(model, str) and model == "oracle") and "terrain" in classes:  # C28
        msg, terrain_check = terrain_dz_check(judged_terrain(classes["terrain"].to_numpy(dtype=object),
                                                             in_gap | impossible), raw_disp[:, 2], dz)  # C240
        warnings += [msg] if msg else []
    head = initial_heading + np.cumsum(dyaw) + place  # decision L34: the direction each stride is placed along
    walk_ref = FirstWalk(initial_heading, enabled=first_walk)  # decision E215: L494's first-walk direction, said once
    for i in np.flatnonzero(~(in_gap | posture)):  # (the runtime's call; the heading turned by it only with
        # first_walk=True, decision E222, else by 0.0)
        ref = walk_ref.stride(bool(foot_headed[i]), float(head[i]), float(np.hypot(disp[i, 0], disp[i, 1])))
        if ref is not None:
            head[i:] -= ref
            line = walk_ref.line(float(strides[i, 1]))
            warnings += [line] if line else []
    xyz = np.zeros((len(table) + 1, 3))
    for i in range(len(table)):  # the runtime's own position update, stride by stride
        xyz[i + 1] = SK.advance(xyz[i], float(head[i]), float(length[i]), float(dz[i]))
    table["event_s"] = ic  # decisions E49-E51 (it was the stride end; NaN without contacts)
    table["raw_length_m"] = signed_chord(raw_disp[:, 0], raw_disp[:, 1], foot_turn, frame)  # L692: the foot's
    table["dz_m"] = dz
    for c in classes.columns:
        if not c.startswith("ood_feature_"):
            table[c] = classes[c].to_numpy()
    # decision L654 (as the runtime's Step): length_m's sign is the measured travel; the path is the same
    measured = table["raw_length_m"].to_numpy(float)  # L692
    first = np.flatnonzero(~(in_gap | posture))
    if first.size:  # decisions L505, E318: the stream's first measured stride is not judged backward (the runtime's)
        measured = measured.copy()
        measured[first[0]] = abs(measured[first[0]])
    rep_length, rep_head = SK.travel_sign(length, head, measured,
                                          sideways,  # decision C137
                                          turn)  # decision L578: E51's own turn (L690: not wrapped)
    table.insert(3, "length_m", rep_length)
    table.insert(5, "heading_rad", wrap_angle(rep_head))
    table["turn_angle_rad"] = turn  # decision E51 (L690: not wrapped, as offline's L66 column)
    table["pivot_rad"] = np.angle(np.exp(1j * (dyaw - turn)))  # decision L106: the turn between strides (the runtime's)
    table["impossible"] = impossible & ~in_gap  # decision L97: the strides L94 moved 0 m (no gait values)
    table["gap_s"] = np.where(in_gap, longest_gap_in(table["start_s"], table["end_s"], foot_gaps), 0.0)  # E37, L67
    table["sideways"] = sideways  # decision L243 (L228's column, decided stride by stride as the runtime's)
    # decision E319: each measured stride's displacement to the foot's left, the runtime's Step.lateral_m
    table["lateral_m"] = np.where(in_gap | posture, np.nan, KSW.foot_frame(disp[:, 0], disp[:, 1], frame)[1])
    table["unit"] = "foot"
    traj = pd.DataFrame({"t": np.concatenate([[table["start_s"].iloc[0]], table["end_s"].to_numpy()]),
                         "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2] + start_alt})  # L157: z from alt
    if start is not None:
        ll = geodetic_track(start, length, head)
        traj["lat"], traj["lon"] = ll[:, 0], ll[:, 1]
    if posture.any():  # decision B131: no row for them, as the runtime emits none (they moved 0 m)
        table, traj, in_gap = (table[~posture].reset_index(drop=True),
                               traj[np.r_[True, ~posture]].reset_index(drop=True), in_gap[~posture])
    # decisions C137, C161, L652 (a foot table); review R2 F2: after B131's posture rows are dropped, so that E318's
    # first measured stride is the runtime's (a leading posture row is none)
    side_class_warning(table, warnings, trained_side_strides(model))
    if any(len(g) for g in foot_gaps.values()):  # decision E46: one 0 m row per stretch with a foot gap (L67)
        table, traj = _one_row_per_gap(table, traj, in_gap, foot_gaps)
    table = streamed_gait_columns(table)  # decision E51
    info = {"pipeline": "plasys", "method": method, "streaming": True, "heading_source": heading,
            "steps_source": "stance (streaming)",
            "classes_source": (None if method == "M2" else ("oracle" if isinstance(model, str)
                                                            and model == "oracle" else "model")),
            "length_bounds_m": rb, "settings": {"segmenter": seg_params, "rest_search_s": rest_search_s},
            "rules": rules if method == "M3" else None, "min_confidence": gate if method == "M3" else None,
            "stride_sigma_rel": sigma_rel if method == "M3" and rules == "bayes" else None,
            "distance_gain": gain, "distance_gain_source": gain_source, "stride_sd_calibrated": stride_sd,
            "out_of_domain": domain,  # decision C16
            "classifier_rate_mismatch": off_rate,  # decision C18
            "resampled": session.meta.get("resampled") or None,  # B113 amended (review): from_hz / to_hz
            "terrain_dz_check": terrain_check, "altitude_check": altitude_check,  # decisions C28, L69
            # decision E215: D25 guards a compass, which this never reads (W415's "not_judged" key, dict as offline)
            "compass_mount": {"fallback": False, "not_judged": STREAMED_COMPASS_MOUNT},
            "first_walk_deg": None if walk_ref.angle is None else float(np.degrees(walk_ref.angle)),  # E215
            "cycle_yaw": bool(cycle_yaw),  # decision E342: the radius's heading offset term follows it (E336 / E331)
            "warnings": warnings}
    for w in warnings:
        log.warning("%s: %s", session.where, w)
    return TrackResult(steps=table, trajectory=traj, info=info)
