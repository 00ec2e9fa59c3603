"""Waist-only dead-reckoning pipelines ``waist-pll`` (seed 000/001) and ``waist-pendulum`` (seed 003).

Both share the AHRS (:mod:`pdrlearn.waist.ahrs`), the motion gate and the evaluation; they differ in
the step events, the step length model and the heading:

=================  ======================================  =========================================
                   waist-pll (Basso 2017/2021)             waist-pendulum (Alvarez 2012)
=================  ======================================  =========================================
step events        PLL on vertical acceleration            IC from AP + vertical acceleration (FIR)
step length        ``a f - b`` (piecewise linear in f)     ``K 2 sqrt(2 L h - h^2) + F``
heading            A-HE tip-to-tail (or ellipse closed     vertical gyro, integrated on turning
                   form) of the planar acceleration        strides (GMM on |MRZ|), bias removed
=================  ======================================  =========================================
"""

from __future__ import annotations

import copy
import functools
import json
import logging

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io import Session
from pdrlearn.kernels.barometer import (  # decision W91's constants and test, shared with the live trackers (E107)
    ALTITUDE_SMOOTH_S,
    STAIR_TREAD_M,
    STAIRS_RATE_MPS,  # noqa: F401 (re-exported)
    STAIRS_RATE_WINDOW_S,
    STEP_TO_STEP_MAX_RISE_M,
    runs_mask,
    stairs_rate_test,
    step_to_step_mask,
)
from pdrlearn.kernels.freeze import inside_episodes
from pdrlearn.kernels.lying_heading import long_axis_yaw_rate, stop_pieces  # decision W269
from pdrlearn.kernels.rest_heading import rest_rotation  # decision L296
from pdrlearn.kernels.step_events import EDGE_LOCK_VALUES  # decision W358
from pdrlearn.kernels.waist import (  # decisions W543, W544, W384, W475
    GENTLE_DEFAULTS,
    TURN_BRIDGE_SIDE,
    gentle_rest_rate,
    pll_slow_band,
)
from pdrlearn.runtime.detector_line import OWN_DETECTOR  # decision W479 (W483: shared with the runtime)
from pdrlearn.settings import Rule, broken, broken_line
from pdrlearn.steps import PLLStepDetector
from pdrlearn.track.barometer import usable_barometer
from pdrlearn.track.base import TrackResult, check_keywords, keyword_names, register_pipeline
from pdrlearn.track.frame_inference import foot_swing_strides
from pdrlearn.track.freezes import (
    freeze_caveat_message,
    freeze_hint,
    lower_back_freezes,
    session_freezes,
    unreliable_mask,
    unreliable_message,
)
from pdrlearn.track.gait import waist_step_times
from pdrlearn.track.gaps import cut_steps_at_gaps, gap_warnings, long_gaps
from pdrlearn.track.geodetic import heading_in_radians, start_coordinate
from pdrlearn.track.sideways import sideways_warnings
from pdrlearn.track.units import unit_span, with_left_out_units
from pdrlearn.waist import _kernels as K
from pdrlearn.waist import mount_drift as _mount_drift
from pdrlearn.waist import reclip as _reclip
from pdrlearn.waist.ahrs import WaistIMU, waist_imu
from pdrlearn.waist.backward import backward_warnings
from pdrlearn.waist.contact_model import CONTACT_MODEL_VALUES, rescore_contacts
from pdrlearn.waist.events import (
    FAST_FILL_OUTSIDE_FREEZE,
    InitialContactDetector,
    gate_threshold,
    refine_to_contacts,
    steps_from_events,
    walking_gate,
)
from pdrlearn.waist.foot_rest import foot_rest_keep, foot_rest_message, foot_rest_runs, strideless_spans
from pdrlearn.waist.heading import (
    HARMONIC_METHODS,
    UNTRACKED_TURN_WARN_DEG,
    TurnClassifier,
    average_two,
    gyro_headings,
    harmonic_directions,
    untracked_turn,
    untracked_turn_message,
    yaw_turns,
)
from pdrlearn.waist.lengths import (
    PAUSE_STEPS_VALUES,  # noqa: F401  (the pause_steps option's values, here since W122)
    StepLengthModel,
    check_length_smoothing,
    check_lengths,
    check_pause_steps,
    get_step_length,
    model_spec,
    pause_scaled_count,
    pause_scaled_message,
    step_frequency,
    walking_sequences,
)
from pdrlearn.waist.lying import postures_and_transfers, session_lying
from pdrlearn.waist.params import NO_CALIBRATION, NO_SENSOR_HEIGHT, WaistParams, resolve_params, subject_height
from pdrlearn.waist.pelvic_rhythm import (
    RHYTHM_SLOW,
    SLOW_PERIOD_S,
    median_step_period,
    merge_dropped,
    pelvic_step_period_s,
    read_once,
    rhythm_keep,
    slow_shortest_step_s,
)
from pdrlearn.waist.plausibility import (
    ALTERNATION_MIN,
    PLAUSIBILITY_MIN_PAIRS,
    SHORT_STEP_CAUSE,
    WALK_RATIO_ADVICE,
    WALK_RATIO_NEED,
    calibration_covers,
    calibration_line,
    contact_alternation,
    contact_lateral_velocity,
    contact_sides,
    count_mismatch_message,
    median_cadence,
    micro_bout_message,
    micro_bouts,
    not_alternating_message,
    pll_excess,
    pll_missed_steps_message,
    pll_model_message,
    pll_slow_excess_message,
    running_cadence,
    short_step_message,
    short_walker_message,
    step_count_withheld_reason,
    step_counts,
    steps_uncountable,
    still_yaw_rate,
    still_yaw_rate_message,
    walk_ratio,
    walk_ratio_advice,
    walk_ratio_message,
)
from pdrlearn.waist.pll_calibration import edge_lock_mismatch_line, recorded_keys
from pdrlearn.waist.posture import (
    drop_contacts,
    sit_veto_hint,
    sit_veto_keywords,
    tilt_gate,
    transfer_veto,
    transfer_windows,
)
from pdrlearn.waist.posture import stand_veto as drop_weak_runs
from pdrlearn.waist.posture import vault_veto as drop_unvaulted
from pdrlearn.waist.rhythm import arrhythmic_message, arrhythmic_sequences
from pdrlearn.waist.ride_runs import ride_message, ride_runs, ride_spans
from pdrlearn.waist.sit_causal import causal_transfer_veto
from pdrlearn.waist.steplength import CADENCE_LAW_STEADY, cadence_law_factor, calibration_cadence_hz, steady_steps
from pdrlearn.waist.transfers import (
    chair_transfers_upright,
    flag_message,
    flag_transfers,
    seated_spans,
    unmatched_message,
    unmatched_posture_changes,
    upright_message,
)
from pdrlearn.waist.trunk_rhythm import arrhythmic_line, rhythm_keep_mask
from pdrlearn.waist.turn_steps import mark_carried

log = logging.getLogger(__name__)

MAX_STEP_S = 1.5  # contacts further apart end a walking sequence (slow gait: steps up to ~1 s)


def _sequences(steps: pd.DataFrame) -> list[np.ndarray]:
    """Row indices of each walking sequence: consecutive rows with a next contact plus the closing row."""
    return walking_sequences(steps["has_next"].to_numpy(bool))


def _pll_steps(session: Session, imu: WaistIMU, walk_threshold: float, *, refine_ic: bool = True,
               rhythm: bool = True, edge_lock: bool | str = False,
               followed: tuple[pd.DataFrame, float] | None = None) -> pd.DataFrame:
    """Step events of seed 000: the peaks of :class:`pdrlearn.steps.PLLStepDetector` while walking,
    moved to the initial contact next to them when ``refine_ic`` (decision W11); ``edge_lock``: the detector's
    W356 option (a gated run's first / last peak only when the loop is locked at them; W358's "trailing": its last only;
    W367's "walk-end": its last only where the walk ends; W372's "walk-edges": also its first where it starts).
    ``followed`` (decision W504, the option ``pll_slow_follow``): :func:`slow_follow_pll`'s peaks and walking-sequence
    bound instead of the PLL's own at W117's range and the track's gate (None: those)."""
    if followed is not None:
        st, max_step_s = followed
    else:  # the PLL's own gate is a variance; use the same threshold as our motion gate (W4)
        st = PLLStepDetector(gate_var=walk_threshold ** 2, relative_gate=False,  # the gate is track's
                             edge_lock=edge_lock, slow_band=False).detect(session)  # W475: not on this path (measured)
        max_step_s = MAX_STEP_S
    ev = np.sort(st["event_s"].to_numpy(float)) if len(st) else np.zeros(0)
    idx = np.clip(np.searchsorted(imu.t, ev), 0, len(imu.t) - 1)
    idx = idx[walking_gate(imu, walk_threshold=walk_threshold)[idx]]
    if refine_ic:
        idx = refine_to_contacts(imu, idx, walk_threshold=walk_threshold, rhythm=rhythm)
    return steps_from_events(imu.t, idx, max_step_s=max_step_s, detector="pll+ic" if refine_ic else "pll")


def slow_follow_pll(session: Session, walk_threshold: float, edge_lock: bool | str, gyro_s: np.ndarray | None
                    ) -> tuple[pd.DataFrame, float] | None:
    """Decision W504: where W475's band applies (:func:`pdrlearn.kernels.waist.pll_slow_band` of the session's
    pelvic-gyro step period: a rhythm under 70 steps/min), the PLL's peaks with that band and the detector's own gate
    (W481's events) and the walking-sequence bound ``max(MAX_STEP_S, 1.5 T)``, T the median of the PLL's own locked
    period (1 / ``step_freq_hz``; 1.5 periods: L605's ``RHYTHM_CAP_PERIODS``); None elsewhere. ``gyro_s``: the
    session's pelvic-gyro steps (:func:`pdrlearn.waist.pelvic_rhythm.read_once`; None: no waist gyroscope)."""
    if gyro_s is None or pll_slow_band(pelvic_step_period_s(session, gyro_s)) is None:
        return None
    st = PLLStepDetector(gate_var=walk_threshold ** 2, edge_lock=edge_lock).detect(session)  # W475's band, own gate
    f = st["step_freq_hz"].to_numpy(float) if len(st) else np.zeros(0)
    f = f[np.isfinite(f) & (f > 0)]
    period = float(np.median(1.0 / f)) if f.size else 0.0
    return st, max(MAX_STEP_S, SLOW_FOLLOW_PERIODS * period)


#: decision W504: a slow walker's walking sequence ends after this many of the PLL's locked periods (L605's
#: ``RHYTHM_CAP_PERIODS`` for the foot: half a step more than the rhythm before it is a stop)
SLOW_FOLLOW_PERIODS = 1.5
#: decision W505: waist-pll's contacts over this many times W504's count at a slow rhythm get one line (W99 / W208's
#: 30 % count disagreement)
SLOW_FOLLOW_EXCESS = 1.3


def slow_harmonic_line(steps: pd.DataFrame, followed: pd.DataFrame) -> str | None:
    """Decision W505: one line when waist-pll's own contacts (``steps``) are over :data:`SLOW_FOLLOW_EXCESS` x the
    ones W504's option gives (``followed``, where W475's slow band applies), else None."""
    if not len(steps) > SLOW_FOLLOW_EXCESS * len(followed):
        return None
    return (f"waist-pll counted {len(steps)} contacts where its PLL locked at this walker's slow rhythm (pelvic "
            f"rhythm under 70 steps/min) counts {len(followed)}: its own PLL follows a harmonic here, so its step "
            "count and distance read long; track with --params holding {\"options\": {\"pll_slow_follow\": true}} to "
            "count with the locked rhythm (its step length, seed 000's line below its validated 1.5 Hz, may read "
            "short; waist-pendulum adds contacts at this gait too) (decisions W504, W505)")


def _start(start, initial_heading: float) -> tuple[float, float, float, tuple[float, float] | None, float]:
    """``(x0, y0, heading0, latlon, alt)`` from ``start``: None, a dict ``x``/``y``/``heading_rad`` (m, rad)
    or ``(lat, lon[, alt])`` in degrees (alt in m; the ``pdrlearn track --start`` form, one check for both:
    :func:`~pdrlearn.track.geodetic.start_coordinate`, decision L157). Headings are checked to be radians
    (:func:`heading_in_radians`, decision W81)."""
    initial_heading = heading_in_radians(initial_heading, "initial_heading")
    if isinstance(start, dict) and isinstance(start.get("heading_rad"), int | float):
        start = {**start, "heading_rad": heading_in_radians(start["heading_rad"], "start heading_rad")}
    if isinstance(start, dict):
        try:
            return (float(start.get("x", 0.0)), float(start.get("y", 0.0)),
                    float(start.get("heading_rad", initial_heading)), None, 0.0)
        except (TypeError, ValueError):
            raise DataError(f"start {start!r}: x, y, heading_rad must be numbers") from None
    latlon, alt = start_coordinate(start)
    return 0.0, 0.0, initial_heading, latlon, alt


def _result(steps: pd.DataFrame, start, initial_heading: float, info: dict, t0: float,
            z: np.ndarray | None = None, z_start: np.ndarray | None = None,
            z_raw: np.ndarray | None = None) -> TrackResult:
    """TrackResult from a steps table with ``length_m`` and navigation-frame ``heading_rad``: headings
    rotated by the start heading (ENU), trajectory = cumulative positions (plus lat/lon). ``z``: the altitude
    (m) at ``t0`` and at each step's end (decision W89; None: 0 throughout). Decision W158: ``z_start``, the
    altitude at each step's start (None: the previous end's); a step's ``dz_m`` is the change from its start to its
    end, ``pause_dz_m`` the change while the unit stood before it (from the previous row's end, or ``t0``, to its
    start: a lift or escalator ride, 0 inside a walking sequence), so ``dz_m + pause_dz_m`` sum to ``z``. Decision
    W174: ``z_raw``, the barometric altitude at ``t0`` and each step's end without W174's transfer windows held (None:
    ``z``); ``transfer_dz_m`` is each row's change inside them, so ``dz_m + pause_dz_m + transfer_dz_m`` sum to it."""
    from pdrlearn.track.geodetic import geodetic_track

    x0, y0, h0, latlon, alt = _start(start, initial_heading)
    out = steps.copy()
    lengths = out["length_m"].to_numpy(float)
    head = np.angle(np.exp(1j * (out["heading_rad"].to_numpy(float) + h0)))
    out["heading_rad"] = head
    z = np.zeros(len(out) + 1) if z is None else np.asarray(z, dtype=float)
    zs = z[:-1] if z_start is None else np.asarray(z_start, dtype=float)
    out["dz_m"] = z[1:] - zs
    out["pause_dz_m"] = zs - z[:-1]  # W158: the standstill's altitude change before the step, not the step's
    out["transfer_dz_m"] = np.zeros(len(out)) if z_raw is None else np.diff(z_raw) - np.diff(z)  # W174
    z = z + alt  # decision L157: start=(lat, lon, alt) starts z at alt, as --start LAT,LON,ALT
    traj = pd.DataFrame({"t": np.concatenate([[t0], out["end_s"].to_numpy(float)]),
                         "x": x0 + np.concatenate([[0.0], np.cumsum(lengths * np.cos(head))]),
                         "y": y0 + np.concatenate([[0.0], np.cumsum(lengths * np.sin(head))]),
                         "z": z})
    if latlon is not None:
        ll = geodetic_track(latlon, lengths, head)
        traj["lat"], traj["lon"] = ll[:, 0], ll[:, 1]
    return TrackResult(steps=out, trajectory=traj, info=info)


#: decision W90: the one line of a lower-back track without a barometer
NO_BAROMETER = ("no barometer (wBarometer.csv): a lower-back track has no altitude - z stays 0 and no floors "
                "are counted, also on stairs")


def _hold_jumps(steps: pd.DataFrame, z: np.ndarray, z_start: np.ndarray, z_raw: np.ndarray, warnings: list[str],
                hold: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Decision W230: one line naming the steps whose barometric change exceeds
    :data:`~pdrlearn.kernels.barometer.MAX_STEP_DZ_M`; with ``hold`` (option ``step_bound``) they are held level
    (:func:`~pdrlearn.kernels.barometer.hold_step_jumps`; ``z_raw``, W174's, shifted alike). Returns ``(z, z_start,
    z_raw, number of such steps)``."""
    from pdrlearn.kernels.barometer import hold_step_jumps, step_jump_line

    z2, zs2, jumped = hold_step_jumps(z, z_start)
    if not jumped.any():
        return z, z_start, z_raw, 0
    warnings.append(step_jump_line(z[1:] - z_start, steps["end_s"].to_numpy(float), hold=hold))
    if not hold:
        return z, z_start, z_raw, int(jumped.sum())
    return z2, zs2, z_raw - (z - z2), int(jumped.sum())


def _altitude(session: Session, baro, t: np.ndarray, warnings: list[str], held=()
              ) -> tuple[np.ndarray, np.ndarray] | None:
    """Decision W89: the altitude (m, relative to ``t[0]``) at the times ``t`` from the waist barometer ``baro``
    (:func:`pdrlearn.track.barometer.usable_barometer`; :func:`pdrlearn.kernels.barometer.relative_altitude`), held
    through the ``held`` windows (decision W174's transfers), and the raw one: ``(held, raw)``; None when ``baro`` is
    None, with :data:`NO_BAROMETER` added to ``warnings`` (W90) when the session has none (an implausible one has
    B188's line already)."""
    from pdrlearn.kernels.barometer import held_altitude

    if baro is None:
        if not session.has("wBarometer") or not len(session["wBarometer"]):
            warnings.append(NO_BAROMETER)
        return None
    return held_altitude(baro.t, baro.values[:, 0], t, held)


def _pause_rides(baro, steps: pd.DataFrame, t0: float, z: np.ndarray, z_start: np.ndarray, z_raw: np.ndarray | None,
                 warnings: list[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Decision W231: each pause's (W158's ``pause_dz_m``: from the previous step's end, or ``t0``, to the step's
    start) barometric change counts only where it is a ride (:func:`pdrlearn.kernels.pause_ride.pause_ride_dz`);
    the rest, drift across a long rest, is taken out of ``z``, ``z_start`` and ``z_raw`` (W174's ``transfer_dz_m``
    unchanged), with one warning (:func:`~pdrlearn.kernels.pause_ride.drift_line`)."""
    from pdrlearn.kernels.pause_ride import RIDE_WINDOW_S, drift_line, pause_ride_dz

    ends = np.concatenate([[t0], steps["end_s"].to_numpy(float)[:-1]])
    starts = steps["start_s"].to_numpy(float)
    drop = np.zeros(len(starts))
    for j in np.flatnonzero(starts - ends > RIDE_WINDOW_S):  # a short pause counts whole (W158)
        ride, _ = pause_ride_dz(baro.t, baro.values[:, 0], float(ends[j]), float(starts[j]))
        drop[j] = (z_start[j] - z[j]) - ride  # the pause's own change (W174's transfers held) less its ride
    if not drop.any():
        return z, z_start, z_raw
    cum = np.concatenate([[0.0], np.cumsum(drop)])  # removed up to each step's end
    z, z_start = z - cum, z_start - cum[1:]
    z_raw = None if z_raw is None else z_raw - cum
    line = drift_line(drop, ends, starts)  # shared with the live tracker (decision E146)
    if line:
        warnings.append(line)
    return z, z_start, z_raw


def _stairs_steps(baro, steps: pd.DataFrame, climb: bool) -> np.ndarray:
    """Decision W91: the steps proposed as on stairs - the barometric altitude changes by :data:`STAIRS_RATE_MPS`
    or more over :data:`STAIRS_RATE_WINDOW_S` centred on the step's middle (all False without a usable barometer
    ``baro``, B188).
    ``climb`` (decision W108): only the proposed steps of a climb higher than the barometer's own still-period
    noise allows (:func:`pdrlearn.kernels.barometer.climb_mask`)."""
    if baro is None or not len(steps):
        return np.zeros(len(steps), dtype=bool)
    return runs_mask(len(steps), _climb_runs(baro, steps)) if climb else _stair_proposals(baro, steps)[0]


def _stair_proposals(baro, steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Decision W91's proposals (a mask), each step's 2 s rise and its altitude at its start and end (m)."""
    from pdrlearn.kernels.barometer import relative_altitude

    t0, t1 = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    mid = 0.5 * (t0 + t1)
    half = 0.5 * STAIRS_RATE_WINDOW_S
    n = len(mid)
    h = relative_altitude(baro.t, baro.values[:, 0], np.concatenate([mid - half, mid + half, t0, t1]))
    rise = h[n:2 * n] - h[:n]
    return stairs_rate_test(rise), rise, h[2 * n:3 * n], h[3 * n:]


def _climb_runs(baro, steps: pd.DataFrame) -> list[tuple[int, int, float]]:
    """Decision W108's climbs (:func:`pdrlearn.kernels.barometer.climb_runs`: first row, stop row, height); none
    without a usable barometer ``baro`` (B188) or steps."""
    from pdrlearn.kernels.barometer import climb_runs, still_altitude_sd

    if baro is None or not len(steps):
        return []
    proposed, rise, start_h, end_h = _stair_proposals(baro, steps)
    sd = still_altitude_sd(baro.t, baro.values[:, 0], float(steps["start_s"].min()), float(steps["end_s"].max()))
    return climb_runs(np.where(proposed, np.sign(rise), 0), start_h, end_h, sd)


#: decision W155: at least this many steps inside W108's climbs warn that ``stairs_length`` is off (a storey of the
#: simulator's 0.17 m risers, 3 m, is ~18 steps; W108's shortest climb, 1.5 m, ~9)
STAIRS_WARN_MIN_STEPS = 8


def stairs_length_message(climbs: np.ndarray, length_m: np.ndarray, tread_m: np.ndarray | None = None) -> str | None:
    """Decision W155's one warning line of a track whose steps ``climbs`` (W108's climb mask: steps inside a
    barometric climb of at least half a storey) are :data:`STAIRS_WARN_MIN_STEPS` or more while the option
    ``stairs_length`` is off: their lengths ``length_m`` are read as level steps (the trial's two storeys up and down:
    +64 % distance on waist-pendulum, +90 % on waist-pll, calibrated; +3.9 % with the option). ``tread_m``: each
    step's bound (decision W433: half the tread on a step-to-step climb; None: :data:`STAIR_TREAD_M` everywhere),
    and the line names the step-to-step steps. None otherwise. Decision W596: the barometer cannot tell a trail's
    slope from stairs (three candidates measured, none adopted), so the line says to leave the option off on a walk
    up trail slopes (trial s51t1: a hike's -0.57 % read -31.10 % with it)."""
    c = np.asarray(climbs, dtype=bool)
    n = int(c.sum())
    if n < STAIRS_WARN_MIN_STEPS:
        return None
    tread = np.full(len(c), STAIR_TREAD_M) if tread_m is None else np.asarray(tread_m, dtype=float)
    read = float(np.abs(np.asarray(length_m, dtype=float)[c]).sum())
    capped = float(np.minimum(np.abs(np.asarray(length_m, dtype=float)[c]), tread[c]).sum())
    halves = int((c & (tread < STAIR_TREAD_M)).sum())
    return (f"{n} steps are on stairs (barometric climbs of 1.5 m or more, decision W108) and read {read:.1f} m "
            "horizontally as level steps: the waist step-length models measure the body's step, not the tread, so "
            "these steps read long (two storeys up and down, calibrated, simulated: +64 % waist-pendulum, +90 % "
            "waist-pll; an uncalibrated track whose level steps read short may still read short in total: "
            "calibrate first, pdrlearn calibrate)"
            + (f"; {halves} of them climb under {STEP_TO_STEP_MAX_RISE_M:.2f} m per step, half a riser: a "
               "step-to-step climb (both feet on each stair, as with a prosthesis or a painful knee), whose steps "
               "move half a tread each, so they read about double again, and its climbs may be listed as ramps "
               "(decision W433)" if halves else "")
            + "; the option stairs_length bounds a stair step by the "
            f"{STAIR_TREAD_M:.2f} m tread " + ("(half of it step to step) " if halves else "") +
            "(decision W91): \"options\": {\"stairs_length\": \"climbs\"} in the PARAMS.json (--params), or "
            f"stairs_length=\"climbs\", bounds these steps ({capped:.1f} m here; decision W156), true also the "
            "steps of shorter barometric changes (decision W155); but if the walk climbed trail slopes, not "
            "stairs, these climbs are slopes walked at full step length, which the barometer cannot tell from "
            "stairs, and the option would cut them to the tread (trial hikes: -0.6 % -> -31 %): leave it off there "
            "(decision W596)")


def _fill_nan_headings(h: np.ndarray, fallback: float) -> np.ndarray:
    out = h.copy()
    last = fallback
    for i, v in enumerate(out):
        if np.isfinite(v):
            last = v
        else:
            out[i] = last
    return out


def _step_lengths(steps: pd.DataFrame, imu: WaistIMU, p: WaistParams, model: StepLengthModel, thr: float, *,
                  turn_factor: bool = False, pivot_steps: bool = False,
                  cadence_law: bool | str = False) -> pd.DataFrame:
    """Steps table with ``length_m`` from the step-length ``model`` (decision E84; 0 for sequence-closing
    contacts, plus the model's own columns: the pendulum's ``h_m``, ``g_m``, ``merged``, ``pause_factor``),
    ``frequency_hz`` and ``dyaw_rad`` (vertical-gyro rotation during the step). ``thr``: the motion gate the steps
    were found with (``steps.attrs["walk_threshold_mps2"]``, the frequency model's running state).
    ``turn_factor`` scales each length by :func:`~pdrlearn.waist._kernels.turning_step_factor` (W19); a W27
    fragment window of the pendulum gives its owner the rotation of the whole merged step. ``pivot_steps`` (decision
    W150's candidate) then keeps a step turning 45 deg or more at most the chord of its turn
    (:func:`~pdrlearn.waist._kernels.pivot_step_factor`; column ``pivot_factor``). ``cadence_law`` (decision W240's
    candidate) multiplies a calibrated pendulum step by :func:`~pdrlearn.waist.steplength.cadence_law_factor` about
    the calibration cadence, after W19 and before W150 (column ``cadence_factor``); ``"steady"`` (decision W261) only
    on the steps :func:`~pdrlearn.waist.steplength.steady_steps` calls steady (factor 1 elsewhere)."""
    n = len(steps)
    has_next = steps["has_next"].to_numpy(bool)
    freq = step_frequency(steps)
    ev = steps["event_s"].to_numpy(float)
    end = steps["end_s"].to_numpy(float)
    steps = steps.copy()
    steps.attrs["walk_threshold_mps2"] = float(thr)
    out = model.transform(steps, imu, p)
    if not isinstance(out, pd.DataFrame) or len(out) != n or "length_m" not in out:
        raise DataError(f"step-length model {model.name}: transform must return the steps table with length_m "
                        "(one row per step); implement predict only (docs/extending.md)")
    lengths = check_lengths(out["length_m"], out, model.name)
    win: dict[int, tuple[int, int]] = out.attrs.get("fragment_windows") or {}
    dyaw = np.where(has_next, K.integrate_rate(imu.t, imu.w_z - p.gyro_bias_rps, ev, end), 0.0)
    for i, (a, b) in win.items():  # W27: the owner's turn factor over the merged step; the fragment keeps
        total = float(np.sum(dyaw[a:b + 1]))  # none, so that the column sums to the walk's turn
        dyaw[a:b + 1] = 0.0
        dyaw[i] = total
    if turn_factor:
        lengths = lengths * K.turning_step_factor(dyaw)
    if cadence_law and "g_m" in out:  # W240: the pendulum's steps only (waist-pll's length is the line itself)
        cfac = np.where(has_next, cadence_law_factor(freq, calibration_cadence_hz(p), p), 1.0)
        if cadence_law == CADENCE_LAW_STEADY:  # W261: steady walking steps only (a trailing window: causal)
            cfac = np.where(steady_steps(1.0 / freq, has_next, frequency_scale=p.frequency_scale()), cfac, 1.0)
        lengths = lengths * cfac
        out = out.assign(cadence_factor=cfac)
    if pivot_steps:  # W150: a pivot step keeps at most the chord of its turn (after W19)
        factor = K.pivot_step_factor(lengths, dyaw)
        lengths = lengths * factor
        out = out.assign(pivot_factor=factor)
    return out.assign(length_m=lengths, frequency_hz=freq, dyaw_rad=dyaw)


def _step_headings(steps: pd.DataFrame, imu: WaistIMU, p: WaistParams, method: str, *,
                   resolve_signs: bool, integrate_stops: bool = False, slow_turn_rps: float = 0.0,
                   gentle_curves: bool = False, gentle_bias_rps: float = 0.0,
                   integrate_end: bool = False, rest_bias: bool = False, lying=None,
                   rest_frame: bool = False, still_mask=None) -> pd.DataFrame:
    """Steps table with ``heading_rad`` (navigation frame, before the start rotation), ``turning``
    (gyro method) and ``mean_rate_rps`` (stride mean vertical rate, MRZ of seed 003 sec. 3.3). Headings
    carry over between walking sequences; a sequence-closing contact keeps the last heading, except the last one
    with the gyro method, ``integrate_stops`` and ``integrate_end`` (decision W187): it adds the rotation from its
    contact to the end of the recording (a turn on the spot after the last step). ``rest_bias`` (decision L296): a
    stop over a minute long adds its moving samples' rate less the bias of its still ones
    (:func:`pdrlearn.kernels.rest_heading.rest_rotation`), not its whole integral. ``lying`` (decision W269):
    ``(episodes, long_axis_rate, still)`` - inside a stop, each lying episode's movements add nothing and its lying
    run adds the yaw of the trunk's long axis (:func:`_stop_rotation`); None: the vertical rate throughout.
    ``rest_frame`` (decision W285, harmonic headings): each step's direction less the AHRS frame's turn over the rests
    over a minute before it (:func:`_rest_frame_drifts`). ``gentle_bias_rps``: W544's rate at rest, taken from
    W543's gentle-curve test (:func:`pdrlearn.kernels.waist.gyro_headings`). ``still_mask``: :func:`_still_samples`'
    zero-argument source of L296's still samples, computed once per track and shared by L296, W269 and W285 (None:
    computed here)."""
    n = len(steps)
    headings = np.full(n, np.nan)
    turning = np.zeros(n, dtype=int)
    seqs = _sequences(steps)
    ev_all = steps["event_s"].to_numpy(float)
    mean_rate = np.full(n, np.nan)
    w = imu.w_z - p.gyro_bias_rps
    cum = K.rate_integral(imu.t, w)  # once for every sequence (W43)
    for seq in seqs:
        if len(seq) > 1:
            mean_rate[seq[:-1]] = K.mean_rate_per_stride(imu.t, w, ev_all[seq], cum=cum)
    removed: list[tuple[float, float]] = []  # decision L296: (end of a long rest, the bias integral left out)
    rests: list[tuple[float, float]] | None = None  # decision L306: the (start, end) of the rests L296 corrected
    if method == "gyro":
        clf = TurnClassifier(**(p.turn_gmm or {}))
        per_seq = []
        current = 0.0
        still = (_rest_still(imu, seqs, ev_all, still_mask) if integrate_stops and rest_bias  # decision L296
                 else None)
        rests = [] if integrate_stops and rest_bias else None
        for j, seq in enumerate(seqs):
            if integrate_stops and j > 0:  # turns made while standing between walking sequences
                t_a, t_b = ev_all[seqs[j - 1][-1]], ev_all[seq[0]]
                whole = K.integrate_rate(imu.t, w, t_a, t_b, cum=cum)
                turned = _stop_rotation(imu, w, still, t_a, t_b, cum, lying)
                if turned != whole:  # L296 (W269): the bias (the lying) left out, for W74's comparison with the yaw
                    removed.append((float(t_b), whole - turned))
                    if rests is not None:
                        rests.append((float(t_a), float(t_b)))  # decision L306: what L297's clock may skip
                current += turned
            if len(seq) > 1:
                hd, tr = gyro_headings(imu, ev_all[seq], classifier=clf, bias_rps=p.gyro_bias_rps,
                                       heading0=current, cum=cum, slow_turn_rps=slow_turn_rps,
                                       gentle_curves=gentle_curves, gentle_bias_rps=gentle_bias_rps)
                turning[seq[:-1]] = tr
                current = float(hd[-1])
                per_seq.append(hd)
            else:
                per_seq.append(np.zeros(0))
        gyro_end = current  # W187: the gyro heading at the last contact, with every stop before it integrated
    else:
        raw = np.full(n, np.nan)
        for seq in seqs:
            if len(seq) > 1:
                raw[seq[:-1]] = harmonic_directions(imu, ev_all[seq], method=method)
        if resolve_signs:  # decision W13: one yaw offset per worn unit fixes 180-degree sign errors
            mid = 0.5 * (steps["start_s"].to_numpy(float) + steps["end_s"].to_numpy(float))
            raw = K.resolve_axis_signs(raw, np.interp(mid, imu.t, imu.yaw))
        if rest_frame:  # decision W285: the frame's turn over a long rest (the bias) is no turn of the walk
            raw = raw - _rest_frame_drifts(imu, seqs, ev_all, still_mask)
        per_seq = [average_two(raw[seq[:-1]]) for seq in seqs]
    current = 0.0
    for seq, hd in zip(seqs, per_seq, strict=True):
        if len(hd):
            hd = _fill_nan_headings(hd, current)
            headings[seq[:-1]] = hd
            current = float(hd[-1])
        headings[seq[-1]] = current
    if method == "gyro" and integrate_stops and integrate_end and seqs:  # W187: W72's integral over the final stop
        last = seqs[-1][-1]  # (a lone last contact, too: its stop's rotation is in gyro_end, not in ``current``)
        headings[last] = gyro_end + (K.integrate_rate(imu.t, w, ev_all[last], float(imu.t[-1]), cum=cum)
                                     if lying is None else  # decision W269: a lying night after the last step
                                     _stop_rotation(imu, w, None, ev_all[last], float(imu.t[-1]), cum, lying))
    out = steps.assign(heading_rad=_fill_nan_headings(headings, 0.0), turning=turning, mean_rate_rps=mean_rate)
    out.attrs["rest_bias_removed"] = removed
    out.attrs["rest_bias_rests"] = rests  # None: L296 not in force (not the gyro heading, or an option off)
    return out


def _stop_rotation(imu: WaistIMU, w: np.ndarray, still: np.ndarray | None, t_a: float, t_b: float,
                   cum: np.ndarray, lying) -> float:
    """The heading's rotation over a stop ``[t_a, t_b]``: W72's integral of the vertical rate ``w``, or L296's
    :func:`rest_rotation` with ``still``; with ``lying`` (decision W269, ``(episodes, long_axis_rate, still)``) only
    over the stop's pieces outside its lying episodes, and over each lying run the long axis's yaw
    (:func:`pdrlearn.kernels.lying_heading.long_axis_yaw_rate`) as L296 reads a rest: its still samples add nothing."""
    def rotation(rate, mask, a, b, c=None):
        return K.integrate_rate(imu.t, rate, a, b, cum=c) if mask is None else rest_rotation(imu.t, rate, mask, a, b,
                                                                                             cum=c)
    if lying is None or not lying[0]:
        return rotation(w, still, t_a, t_b, cum)
    upright, lying_runs = stop_pieces(t_a, t_b, lying[0])
    if not lying_runs and upright == [(t_a, t_b)]:
        return rotation(w, still, t_a, t_b, cum)
    return (sum(rotation(w, still, a, b, cum) for a, b in upright)
            + sum(rotation(lying[1], lying[2], a, b) for a, b in lying_runs))


def _still_samples(imu: WaistIMU, still_mask=None) -> np.ndarray:
    """L296's still samples of the waist (``standstill_mask`` on the navigation-frame IMU, its defaults):
    ``still_mask()`` when given (:func:`track_waist`'s, shared by L296, W269 and W285), else the IMU's own mask
    (:func:`~pdrlearn.waist.ahrs.nav_still`: computed once per IMU object and shared with W122's step lengths,
    decision W354)."""
    if still_mask is not None:
        return still_mask()
    from pdrlearn.waist.ahrs import nav_still

    return nav_still(imu)


def _with_still_before(steps: pd.DataFrame, imu: WaistIMU, still: np.ndarray) -> pd.DataFrame:
    """Decision L372: ``steps`` with ``still_before_s``, the seconds of L296's still samples ``still`` between each
    contact (``event_s``, else ``start_s``) and the one before it in time (0 for the first): standing, which the pause
    rule does not give a turn (L119)."""
    if not len(steps):
        return steps.assign(still_before_s=np.zeros(0))
    ev = steps["event_s"].to_numpy(float) if "event_s" in steps else steps["start_s"].to_numpy(float)
    ev = np.where(np.isfinite(ev), ev, steps["start_s"].to_numpy(float))
    cum = np.r_[0.0, np.cumsum(np.asarray(still, dtype=float))] / imu.fs  # still seconds before each sample
    at = cum[np.clip(np.searchsorted(imu.t, ev), 0, len(imu.t))]
    order = np.argsort(ev, kind="stable")
    out = np.zeros(len(ev))
    out[order[1:]] = np.maximum(np.diff(at[order]), 0.0)
    return steps.assign(still_before_s=out)


def _rest_frame_drifts(imu: WaistIMU, seqs, ev_all: np.ndarray, still_mask=None) -> np.ndarray:
    """Decision W285: per step (``ev_all``'s order), the AHRS frame's turn (rad) about the vertical over the rests
    before it that its body did not make (:func:`pdrlearn.kernels.rest_heading.rest_frame_drift`): the lead-in from
    the recording's start to the first contact and each stop between walking sequences, the rests over
    ``REST_BIAS_MIN_S`` only (L296's bound); zeros when there is none."""
    from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S, rest_frame_drift

    out = np.zeros(len(ev_all))
    if not seqs:
        return out
    rests = [(float(imu.t[0]), float(ev_all[seqs[0][0]]), int(seqs[0][0]))]
    rests += [(float(ev_all[a[-1]]), float(ev_all[b[0]]), int(b[0])) for a, b in zip(seqs[:-1], seqs[1:], strict=True)]
    if max(b - a for a, b, _ in rests) <= REST_BIAS_MIN_S:
        return out
    still = _still_samples(imu, still_mask)  # L296's still samples
    cum = K.rate_integral(imu.t, imu.w_z)  # the raw rate: the AHRS integrates the gyroscope as it is (W5)
    for a, b, k in rests:
        out[k:] += rest_frame_drift(imu.t, imu.w_z, still, a, b, cum=cum)
    return out


def _lying_heading(imu: WaistIMU, steps: pd.DataFrame, chair: pd.DataFrame, still_mask=None):
    """Decision W269: ``(episodes, long_axis_rate, still)`` for :func:`_stop_rotation` - the lying episodes of
    :func:`pdrlearn.waist.lying.session_lying`, the yaw rate of W102's walking upright about gravity and L296's still
    samples (:func:`_still_samples`) - or None when the track has no lying episode (or no upright or body rate)."""
    episodes, upright = session_lying(imu, steps, chair)
    if not episodes or upright is None or imu.gyr_body is None:
        return None
    return (episodes, long_axis_yaw_rate(imu.up_body, imu.gyr_body, upright),
            _still_samples(imu, still_mask))


def _rest_still(imu: WaistIMU, seqs, ev_all: np.ndarray, still_mask=None) -> np.ndarray | None:
    """Decision L296: the waist's still samples (``standstill_mask`` on the navigation-frame IMU), when some stop
    between walking sequences lasts over :data:`~pdrlearn.kernels.rest_heading.REST_BIAS_MIN_S`; else None."""
    from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S

    gaps = [ev_all[b[0]] - ev_all[a[-1]] for a, b in zip(seqs[:-1], seqs[1:], strict=True)]
    if not gaps or max(gaps) <= REST_BIAS_MIN_S:
        return None
    return _still_samples(imu, still_mask)


def _untracked_turn_warning(steps: pd.DataFrame, imu: WaistIMU, p: WaistParams, method: str,
                            integrate_stops: bool, warnings: list[str], removed=()) -> float | None:
    """Decision W74: the gyro heading's largest shortfall against the waist's integrated yaw (deg, over the steps
    that carry a length), and one warning when it reaches :data:`UNTRACKED_TURN_WARN_DEG`; None for the
    harmonic headings (absolute directions, nothing is dropped between steps)."""
    if method != "gyro" or not len(steps):
        return None
    moving = steps["has_next"].to_numpy(bool) & (steps["length_m"].to_numpy(float) > 0)
    if not moving.any():
        return 0.0
    ends = steps["end_s"].to_numpy(float)[moving]
    heads = steps["heading_rad"].to_numpy(float)[moving]
    for t_b, r in removed:  # decision L296: the long rests' bias the heading left out is the yaw's, not a turn
        heads = heads + np.where(ends >= t_b, r, 0.0)
    diff, t_end = untracked_turn(imu, steps["event_s"].to_numpy(float)[:1], ends, heads, bias_rps=p.gyro_bias_rps)
    deg = float(np.degrees(diff))
    if abs(deg) >= UNTRACKED_TURN_WARN_DEG:
        warnings.append(untracked_turn_message(deg, t_end, integrate_stops))
    return deg


#: pipeline options a PARAMS.json may set under "options" (so ``pdrlearn track --params`` reaches them)
OPTION_DEFAULTS = {"realtime": False, "heading": None, "refine_ic": True, "initial_heading": 0.0,
                   "resolve_signs": True, "integrate_stops": True, "turn_factor": True, "rhythm": True,
                   "merge_fragments": True, "length_smoothing": "none", "relative_gate": True,
                   "stairs_length": False, "stairs_climb": False, "slow_turn_rps": 0.0, "max_tilt_deg": None,
                   "gentle_curves": GENTLE_DEFAULTS["gentle_curves"],  # W543
                   "gentle_rest_bias": GENTLE_DEFAULTS["gentle_rest_bias"],  # W544: offline only
                   "sit_veto": "opposite", "pause_steps": "standing", "vault_veto": False, "contact_shift": True,
                   "gait_check": False, "pll_check": False, "weak_fill": False,  # pll_check: W186
                   "pll_slow_check": False,  # W289: uncalibrated waist-pll over 1.25 x the pendulum at a slow gait
                   "pll_slow_cadence_check": True,  # W313 / W314 (adopted): the same, the slow gait by the cadence
                   "pivot_steps": False, "parity_fill": "within",  # pause_steps: W134, pivot_steps: W150, parity: W152
                   "cadence_law": False,  # W240
                   "realtime_contact_shift": False,  # W166: measured, not adopted; sit_veto: W185, offline only
                   "integrate_end": False,  # W187
                   "stand_veto": "walking",  # W189; W199's "adjacent" withdrawn by W217; W218 / W219: "walking"
                   "contact_model": False,  # W203
                   "realtime_sit_veto": False,  # W200: the causal sit veto of realtime tracks
                   "short_step_check": False,  # W207: measured, not adopted for waist-pendulum (W208: pll always)
                   "freeze_veto": False,  # W214
                   "pll_slow_follow": False,  # W504: measured, not adopted (distance short); W505's line names it
                   "pll_edge_lock": "walk-edges",  # W356 / W367 / W372: waist-pll's edge peaks where the walk ends
                   # (starts) only when the loop is locked at them; W368: "walk-end" adopted; W373: "walk-edges"
                   "foot_rest_veto": True,  # W336: the contacts while the foot unit makes no stride (W337 adopted)
                   "pelvic_rhythm_veto": False,  # W440: measured, not adopted (Test11's step F1 fell); an option
                   # W591: the shortest step from the pelvic gyro's step below 70 steps/min; W592's rule was met,
                   # W593 withdrew the default (a turn's closing step lost on L647's walk): an option
                   "slow_min_step": False,
                   "rhythm_warning": False,  # W338: phone-only stride-rhythm warning; W339: not met, opt-in
                   "trunk_rhythm_veto": False,  # W550: runs without a step rhythm (trunk jerks); measured, not adopted
                   # W565 / W566: a sliding belt unit said and corrected; W571: not on the walking upright alone;
                   # W577: adopted with W576's check, the quiet standing before and after moved with it ("standing")
                   "mount_drift": "standing",
                   # W623: a unit re-clipped mid-walk: its walking frames either side, the data after it turned back
                   # (true); W624: W623's rule not met (errors 0.68 / 0.77 of before, not half), the line alone
                   "reclip": "line",
                   "side_at_contact": False,  # W235: the sequence rules' sides at the contact (offline pendulum)
                   "fast_fill": False,  # W242: a merged step's 5 Hz maximum (offline pendulum)
                   "ap_above_mean": False,  # W265: W29's IC, the last AP maximum above the AP mean (offline pendulum)
                   "turn_bridge": TURN_BRIDGE_SIDE,  # W374: the gate open over a yaw-rate turn inside a walk
                   # (offline pendulum); W384 / W385: adopted as "side", its added contacts where the side alternates
                   "speed_check": True,  # W211
                   "step_bound": False,  # W230: measured, not adopted (a transient's return is a climb)
                   "freeze_index": False,  # W216: the lower back's freeze index is opt-in (freeze_veto implies it)
                   "pause_ride": True,  # W231: a long pause's barometric change counts only where it is a ride
                   "rest_bias": True,  # L296: a long rest's rotation less the bias of its still samples
                   "lying_heading": True,  # W269, W271 (adopted by W270): lying turns it by the long axis's yaw only
                   "rest_frame": False,  # W285: harmonic headings less the AHRS frame's turn over a long rest
                   "climb_veto": False,  # L314's ramp veto from W108's climbs: opt-in (decision L330)
                   "ride_vibration": False,  # L402: a vibrating ride is a vehicle's; L403: not met, opt-in
                   "walked_ride": False,  # W609: a ride shaking like walking is stairs; not met, opt-in
                   # E358: stairs_length "climbs" applied live by holding an open run's steps until it is decided
                   # ("hold"); false: the live trackers do not apply "climbs" (E107's line names it)
                   "live_climbs": False,
                   # W625: a waist gap of at most 5 s inside walking bridged at the pace either side (offline)
                   "gap_bridge": False}
#: decision W193: options that act on one pipeline / mode only - where each applies (said when it is set and does
#: nothing) and the test of whether it acts: ``(pipeline, realtime, heading method, detector given, integrate_stops)``
SCOPED_OPTIONS = {
    "integrate_end": ("the offline gyro heading with integrate_stops (waist-pendulum's default heading; W187)",
                      lambda pl, rt, m, det, stops: m == "gyro" and stops and not rt),
    "lying_heading": ("the offline gyro heading with integrate_stops (waist-pendulum's default heading; W269)",
                      lambda pl, rt, m, det, stops: m == "gyro" and stops and not rt),
    "rest_frame": ("the harmonic headings (ahe, ellipse, ellipse-stride: waist-pll's default heading; W285)",
                   lambda pl, rt, m, det, stops: m in HARMONIC_METHODS),
    "stand_veto": ("the offline waist-pendulum with its own contact detector (W189)",
                   lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "contact_model": ("the offline waist-pendulum with its own contact detector (W203)",
                      lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "side_at_contact": ("the offline waist-pendulum with its own contact detector (W235)",
                        lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "fast_fill": ("the offline waist-pendulum with its own contact detector (W242)",
                  lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "ap_above_mean": ("the offline waist-pendulum with its own contact detector (W29, W265)",
                      lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "turn_bridge": ("the offline waist-pendulum with its own contact detector (W374, W384)",
                    lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "freeze_veto": ("the offline waist tracks (W214: the freeze index's window looks 2 s ahead)",
                    lambda pl, rt, m, det, stops: not rt),
    "pelvic_rhythm_veto": ("the offline waist tracks (W440: the pelvic rhythm is read over the whole recording)",
                           lambda pl, rt, m, det, stops: not rt),
    "slow_min_step": ("the offline waist-pendulum with its own contact detector (W591: the pelvic rhythm is read over "
                      "the whole recording)",
                      lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt and not det),
    "trunk_rhythm_veto": ("the offline waist tracks (W550: a run is judged after its last contact)",
                          lambda pl, rt, m, det, stops: not rt),
    "mount_drift": ("the offline waist tracks (W565 / W566: the bouts' uprights are read over the whole recording)",
                    lambda pl, rt, m, det, stops: not rt),
    "reclip": ("the offline waist tracks (W623: the walking frames before and after each time are compared)",
               lambda pl, rt, m, det, stops: not rt),
    "pll_edge_lock": ("waist-pll with its own PLL detector (W356)",
                      lambda pl, rt, m, det, stops: pl == "waist-pll" and not det),
    "pll_slow_follow": ("the offline waist-pll with its own PLL detector (W504)",
                        lambda pl, rt, m, det, stops: pl == "waist-pll" and not det and not rt),
    "vault_veto": ("the offline waist-pendulum (W119)",
                   lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt),
    "realtime_sit_veto": ("realtime tracks (offline tracks apply the sit veto on the whole recording; W200)",
                          lambda pl, rt, m, det, stops: rt),
    "cadence_law": ("calibrated waist-pendulum tracks (W240)", lambda pl, rt, m, det, stops: pl == "waist-pendulum"),
    "short_step_check": ("the offline waist-pendulum (W207; an uncalibrated offline waist-pll track is judged so by "
                         "default, W208)", lambda pl, rt, m, det, stops: pl == "waist-pendulum" and not rt),
    "live_climbs": ("realtime tracks and the live trackers, with stairs_length \"climbs\" (E358)",
                    lambda pl, rt, m, det, stops: rt),
}


def ignored_options_line(o: dict, pipeline: str, realtime: bool, method: str, detector: bool,
                         integrate_stops: bool, explicit=()) -> str | None:
    """Decision W193: one line naming the resolved options ``o`` set away from :data:`OPTION_DEFAULTS` -- or given
    explicitly (``explicit``: the PARAMS.json's ``"options"`` keys, decision W301) -- that do nothing for this track
    (:data:`SCOPED_OPTIONS`) and where each applies, else None (the live trackers' E107 line says the same of the
    options they do not apply). W301: ``lying_heading``, true by default (W271), is named only where the PARAMS.json
    gives it true, not on every ``--realtime`` / ``waist-pll`` track."""
    off = [k for k, (_, acts) in SCOPED_OPTIONS.items()  # an option set off (false) does nothing anywhere (W199)
           if o.get(k) not in (None, False) and (o.get(k) != OPTION_DEFAULTS[k] or k in explicit)
           and not acts(pipeline, realtime, method, detector, integrate_stops)]
    if not off:
        return None
    here = ", ".join([pipeline] + (["--realtime"] if realtime else []) + [f"heading {method}"]
                     + (["a detector plug-in"] if detector else []) + ([] if integrate_stops else
                                                                       ["integrate_stops off"]))
    named = "; ".join(f"{k}={json.dumps(o[k])} applies to {SCOPED_OPTIONS[k][0]}" for k in off)
    return (f"option{'s' if len(off) > 1 else ''} ignored by this track ({here}): {named} (decision W193)")


#: decision W165: the ``pause_steps`` value the realtime detector and the live trackers apply too -- W134's test
#: (a stand of half the local period, not a walk's edge) is decided once the three steps after it are known
CAUSAL_PAUSE_STEPS = "standing"
#: decision B199: the options that are true or false (``sit_veto``, ``pause_steps``, ``vault_veto`` take more values,
#: checked by their own lines)
FLAG_OPTIONS = tuple(k for k, v in OPTION_DEFAULTS.items()
                     if isinstance(v, bool) and k not in ("sit_veto", "pause_steps", "vault_veto", "stairs_length",
                                                          "parity_fill", "stand_veto", "contact_model", "fast_fill",
                                                          "cadence_law", "pll_edge_lock", "turn_bridge",
                                                          "pelvic_rhythm_veto", "mount_drift", "slow_min_step",
                                                          "live_climbs", "reclip"))
FLAG_RULES = {k: Rule("flag", ints=True) for k in FLAG_OPTIONS}  # B199: 0 / 1 pass (B206's shared check)
#: the values of the ``sit_veto`` option: off, W104's veto, W109's veto sparing left/right step pairs, W180's
#: sparing also an undecided contact between two same-side contacts of its sequence, W184's sparing instead an
#: undecided contact between two opposite-side contacts of its sequence
SIT_VETO_VALUES = (False, True, "rhythm", "alternation", "opposite")
#: decision W156: ``stairs_length`` - False (no bound), True (W91's proposed steps, W108's under ``stairs_climb``) or
#: "climbs" (only the steps inside W108's climbs)
STAIRS_LENGTH_VALUES = (False, True, "climbs")
#: decision W159: ``parity_fill`` - False, True (W152's contacts) or "within" (only inside a walking sequence)
PARITY_FILL_VALUES = (False, True, "within")
#: the values of the ``vault_veto`` option: off, W119's veto, W127's veto sparing turning steps
VAULT_VETO_VALUES = (False, True, "turns")
#: the values of the ``stand_veto`` option: off, W189's veto, W191's veto sparing a run with a turning step, W196's
#: sparing a run whose decided sides alternate, W198's sparing a run with walking within 3 s before and after it,
#: W218's "adjacent" judged against the walking stretches' bounce, the stretches never dropped
STAND_VETO_VALUES = (False, True, "turns", "alternation", "adjacent", "walking")
#: decision W255: ``fast_fill`` - False, True (W242's contacts) or "outside_freeze" (none inside a freeze episode)
FAST_FILL_VALUES = (False, True, FAST_FILL_OUTSIDE_FREEZE)
#: decision W261: ``cadence_law`` - False, True (W240's factor on every calibrated pendulum step) or "steady" (only on
#: steady walking steps)
CADENCE_LAW_VALUES = (False, True, CADENCE_LAW_STEADY)
#: decision W384: ``turn_bridge`` - False, True (W374's bridge) or "side" (its contacts only where the side alternates)
TURN_BRIDGE_VALUES = (False, True, TURN_BRIDGE_SIDE)
#: decision W440: ``pelvic_rhythm_veto`` - False, True (at every cadence) or "slow" (below 70 steps/min only)
PELVIC_RHYTHM_VALUES = (False, True, RHYTHM_SLOW)
#: decision W591: ``slow_min_step`` - False or "slow" (the shortest step from the pelvic gyro's step below 70 steps/min)
SLOW_MIN_STEP_VALUES = (False, RHYTHM_SLOW)
#: the options with more than two values and the decisions that define them (one refusal line for each)
CHOICE_OPTIONS = {"sit_veto": (SIT_VETO_VALUES, "W104, W109, W180, W184"),
                  "vault_veto": (VAULT_VETO_VALUES, "W119, W127"),
                  "stairs_length": (STAIRS_LENGTH_VALUES, "W91, W156"),
                  "parity_fill": (PARITY_FILL_VALUES, "W152, W159"),
                  "stand_veto": (STAND_VETO_VALUES, "W189, W191, W196, W198, W218"),
                  "contact_model": (CONTACT_MODEL_VALUES, "W203"),
                  "fast_fill": (FAST_FILL_VALUES, "W242, W255"),
                  "cadence_law": (CADENCE_LAW_VALUES, "W240, W261"),
                  "pll_edge_lock": (EDGE_LOCK_VALUES, "W356, W358, W367, W372"),
                  "turn_bridge": (TURN_BRIDGE_VALUES, "W374, W384"),
                  "pelvic_rhythm_veto": (PELVIC_RHYTHM_VALUES, "W440"),
                  "slow_min_step": (SLOW_MIN_STEP_VALUES, "W591"),
                  # W576: "standing", the line only when the quiet standing moved with the walking upright
                  "mount_drift": ((False, True, "standing"), "W565, W571, W576"),
                  # W623 / W624: true, the line and the correction; "line", the line alone; false, neither
                  "reclip": ((False, True, "line"), "W623, W624"),
                  "live_climbs": ((False, "hold"), "E358")}


def resolve_options(p: WaistParams, given: dict) -> dict:
    """The pipeline options: each of ``given`` that is not None, else ``p.options``' value, else
    :data:`OPTION_DEFAULTS` (shared by :func:`track_waist` and :class:`pdrlearn.waist.live.WaistTracker`)."""
    unknown = sorted(set(p.options or {}) - set(OPTION_DEFAULTS))
    if unknown:
        raise DataError(f"params options: unknown {', '.join(unknown)}; use some of {', '.join(OPTION_DEFAULTS)}")
    o = {k: (v if v is not None else (p.options or {}).get(k, OPTION_DEFAULTS[k])) for k, v in given.items()}
    bad = broken(o, FLAG_RULES)
    if bad:  # decision B199: "false" in a PARAMS.json had been read as true
        raise DataError(f"params options: {broken_line(bad)}; fix the option or the PARAMS.json "
                        "\"options\" (JSON true / false, no quotes)")
    return o


def _postures_transfers(imu: WaistIMU, steps: pd.DataFrame, transfers: pd.DataFrame, upright_source: str,
                        fixed_up, o: dict, warnings: list[str]) -> tuple[list, pd.DataFrame | None]:
    """The posture runs and the final chair transfers of a lower-back track (``track_waist``'s and, decision W428,
    :func:`trunk_events`'): ``transfers`` (W182's rows) with W245's lying transfers, W277's empty answer without an
    upright, W278's flags (their line appended to ``warnings``)."""
    # decisions W222, W245: the posture runs (from the chair transfers) and the lying transfers added to them
    postures, transfers = postures_and_transfers(imu, steps, transfers, fixed_up)
    if upright_source == "none":  # decision W277: no upright, no transfer and no posture to judge: left empty
        return [], None
    # decision W278: rows that cannot be taken as read (not alternating, walking on both sides) flagged, one line
    # decision W311: W278's walking test reads the contacts after the offline sit veto even when the track
    # applied none (realtime): a rise's own false contacts are no walking on both sides
    transfers = flag_transfers(transfers, steps if bool(o["sit_veto"]) else transfer_veto(
        steps, imu, **sit_veto_keywords(OPTION_DEFAULTS["sit_veto"]),
        **({} if fixed_up is None else {"upright": fixed_up})))
    line = flag_message(transfers)
    if line:
        warnings.append(line)
    line = unmatched_message(unmatched_posture_changes(postures, transfers))  # decision W451
    if line:
        warnings.append(line)
    return postures, transfers


def track_waist(session: Session, *, pipeline: str, params=None, start=None, realtime: bool | None = None,
                heading: str | None = None, refine_ic: bool | None = None, initial_heading: float | None = None,
                resolve_signs: bool | None = None, integrate_stops: bool | None = None,
                turn_factor: bool | None = None, rhythm: bool | None = None,
                merge_fragments: bool | None = None, length_smoothing: str | None = None,
                relative_gate: bool | None = None, stairs_length: bool | None = None, stairs_climb: bool | None = None,
                slow_turn_rps: float | None = None, max_tilt_deg: float | None = None,
                gentle_curves: bool | None = None, gentle_rest_bias: bool | None = None,
                sit_veto: bool | str | None = None, pause_steps: bool | str | None = None,
                vault_veto: bool | str | None = None, contact_shift: bool | None = None,
                gait_check: bool | None = None, speed_check: bool | None = None, pll_check: bool | None = None,
                weak_fill: bool | None = None,
                pivot_steps: bool | None = None, parity_fill: bool | str | None = None, pause_ride: bool | None = None,
                cadence_law: bool | str | None = None,
                rest_bias: bool | None = None,
                realtime_contact_shift: bool | None = None, integrate_end: bool | None = None,
                stand_veto: bool | str | None = None, contact_model: bool | str | None = None,
                realtime_sit_veto: bool | None = None, short_step_check: bool | None = None, detector=None,
                length_model=None, freeze_veto: bool | None = None,
                freeze_index: bool | None = None, side_at_contact: bool | None = None,
                fast_fill: bool | str | None = None, ap_above_mean: bool | None = None,
                foot_rest_veto: bool | None = None, pll_edge_lock: bool | str | None = None,
                turn_bridge: bool | str | None = None, pelvic_rhythm_veto: bool | str | None = None,
                slow_min_step: bool | str | None = None, gate: bool = False) -> TrackResult:
    """Run a waist pipeline (``"waist-pll"`` or ``"waist-pendulum"``) on ``session``.

    Parameters
    ----------
    params : PARAMS.json path, dict or :class:`WaistParams` from ``pdrlearn calibrate`` (None: defaults
        from meta.json, with a warning)
    start : ``(lat, lon)`` degrees (adds ``lat``/``lon`` columns) or a dict ``x``, ``y`` (m),
        ``heading_rad`` (rad, ENU; 0 = east); default: origin
    initial_heading : ENU heading (rad, |value| <= 2 pi, else refused: W81) given to the unit's initial facing
        direction (no magnetometer)
    realtime : pendulum only: the causal IC detector instead of the zero-lag offline one
    refine_ic : PLL only: report each step at the initial contact next to its PLL peak (W11)
    heading : ``"ahe"`` (default of waist-pll, seed 000), ``"ellipse"`` (seed 001 closed form on the
        step), ``"ellipse-stride"`` (the closed form on the stride's step-frequency harmonic, W12) or
        ``"gyro"`` (default of waist-pendulum, seed 003)
    resolve_signs : harmonic headings: fix 180-degree sign errors with the unit's yaw (W13)
    integrate_stops : gyro heading: also integrate the rate between walking sequences (turns made while
        standing or during undetected steps); default True since decision W73 (seed 003 integrates only during
        walking: ``False``)
    integrate_end : with ``integrate_stops``, gyro heading, offline: the last closing contact also takes the rotation
        from it to the end of the recording (a turn on the spot after the last step; decision W187)
    turn_factor : shorten steps during which the pelvis turns, ``x cos(turn)`` (decision W19; the papers'
        models assume straight steps); default True
    rhythm : offline IC detector (pendulum, and the PLL's IC refinement): complete walking sequences at
        the gait rhythm (decision W18); default True
    merge_fragments : pendulum: a step shorter than half its walking sequence's median step is a piece of
        a step split by a spurious contact; its neighbour's length covers both (decision W27); default True
    length_smoothing : pendulum, offline detector: ``"none"`` (default), ``"mobgap"`` (mobgap SlZijlstra's
        Hampel + per-second smoothing of the step lengths, decision W56), ``"hampel"`` or ``"seconds"`` (its two
        parts alone)
    relative_gate : offline, when the params do not set ``walk_threshold_mps2``: the motion gate's threshold is
        ``min(0.5, max(0.15, 0.5 x P90))`` of the session's own 2 s vertical SD (decision W76,
        :func:`~pdrlearn.waist._kernels.relative_walk_threshold`); default True since W76's rule held (False:
        W4's 0.5)
    stairs_length : a step on stairs (the barometric altitude changes by 0.1 m/s or more) is at most the
        0.30 m tread long (decision W91's candidate; default False); ``"climbs"``: only the steps inside W108's
        climbs (decision W156's candidate)
    step_bound : (PARAMS.json option) a step whose barometric change exceeds 0.5 m is held level (decision W230's
        candidate; default False: HA002 Test11's transient returns and then reads as a climb); such steps are
        named in a warning either way
    stairs_climb : a step is on stairs (column ``stairs``) only inside a climb of at least 1.5 m and 3 sqrt(2)
        still-period altitude SDs, and the altitude changes only on such steps (decision W108's candidate;
        default False: it failed its rule on one real level recording)
    slow_turn_rps : gyro heading: also integrate the strides whose 5-stride mean vertical rate reaches this (rad/s),
        so gentle curves are kept (decision W82; 0.035 tested, not the default: it failed its rule on sharp turns
        by 0.01 m); 0 (default) = seed 003's classifier alone
    gentle_curves : gyro heading: a step in a run of three strides whose mean vertical rate keeps its sign and
        reaches 1.5 deg/s, and that seed 003 leaves out, adds its stride's mean rate over the step (decision W543;
        default True, adopted by its rule; False = seed 003's classifier alone)
    gentle_rest_bias : offline gyro heading: W543's run test and its gentle steps read each stride's mean rate less
        W105's reading over the recording's first standstill (a gyroscope bias at rest; decision W544); no
        standstill, ``realtime`` or live: no change
    max_tilt_deg : a contact made while the trunk is tilted more than this (deg) from the session's walking upright is
        no step, and the step before it ends its sequence (decision W102, :mod:`pdrlearn.waist.posture`; sit-to-stand,
        bending); None (default) = no tilt gate
    sit_veto : ``True``: drop the contacts within 1 s of a trunk-flexion peak of more than 25 deg from the walking
        upright (a sit-to-stand or bend event; decision W104, :func:`pdrlearn.waist.posture.transfer_veto`);
        ``"rhythm"``: the same, sparing the contacts that alternate left/right with a neighbour of their walking
        sequence (decision W109); ``"alternation"``: as ``"rhythm"``, sparing also an undecided contact (no W20 side)
        between two same-side contacts of its sequence (decision W180); ``"opposite"`` (the default of offline
        tracks since W185): as ``"rhythm"``, sparing also an undecided contact between two opposite-side contacts of
        its sequence (decision W184); ``False``: no veto (the default with ``realtime`` unless ``realtime_sit_veto``)
    realtime_sit_veto : with ``realtime``: apply ``sit_veto`` (``"opposite"`` unless set) causally, each contact decided
        3.25 s after it on the samples up to then, the upright from the walking contacts so far (decision W200,
        :func:`pdrlearn.waist.sit_causal.causal_transfer_veto`); default False: a realtime track keeps no veto unless
        ``sit_veto`` is set, and then its veto reads the whole recording (W185)
    realtime_contact_shift : pendulum, realtime: W131's ``contact_shift`` inside each W31 decision window too (no added
        latency; decision W166: measured, not adopted -- Test11's pooled calibrated bout median vs the strides rose
        13.280 -> 13.556 %); default False. The live trackers read it from the PARAMS.json / bundle options
    pause_steps : pendulum (the realtime detector applies only ``"standing"``, decision W165; it ignores the other
        values): a step
        longer than 1.5 local periods spans a pause (the stop before a turn on the spot, the restart after it) and
        keeps one period's length (decision W111); ``"progression"``: a step during which the unit stands still
        (``standstill_mask``) keeps at most the trunk's horizontal travel over it, integrated from zero velocity in
        the standstill (decision W122); ``"standing"`` (default, decision W134): W122's travel only for a step whose
        longest still run lasts half its local step period and that is neither the first nor the last of its walk;
        False: off
    vault_veto : pendulum, offline detector (the realtime one ignores it: it looks three steps ahead): drop a contact
        whose step vaults the pelvis by less than a quarter of its neighbours' (a weight shift while standing, no
        step; decision W119, :func:`pdrlearn.waist.posture.vault_veto`); ``"turns"``: the same, sparing a contact whose
        step turns the pelvis by more than 15 deg (a turn on the spot vaults little; decision W127); default False
    stand_veto : pendulum, offline detector (the realtime one and ``waist-pll`` ignore it): drop a whole walking run
        (contacts chained by ``has_next``) whose median vertical bounce is under a third of the recording's median
        contact bounce: standing sway, no walking (decision W189, :func:`pdrlearn.waist.posture.stand_veto`);
        ``"turns"``: the same, sparing a run with a step that turns the pelvis by more than 15 deg (W127's test; a
        slow turn on the spot bounces little; decision W191); ``"alternation"``: sparing a run whose decided W20
        sides alternate left/right, at least two decided (decision W196); ``"adjacent"``: sparing a run with walking
        strides within Mobilise-D's 3 s bout break before and after it (inside one walk; decision W198; the default
        of W199, withdrawn by W217); ``"walking"`` (the default, decisions W218 / W219): ``"adjacent"`` judged against
        the median bounce of the walking stretches (at least 4 regular strides on decided, alternating W20 sides) and
        the walk of a stretch never dropped (a freeze's trembling chained to it, a long standing recording);
        False: no stand veto
    freeze_veto : offline (the realtime detector ignores it): drop the contacts inside a freeze episode of the lower
        back's freeze index (freezes.csv, :mod:`pdrlearn.track.freezes`, decision W213): trembling in place is no
        step (decision W214); the step before a dropped contact ends its sequence; default False; implies
        ``freeze_index``
    foot_rest_veto : with a foot unit in the session: drop each run of 4 or more lower-back contacts none within 1 s
        of a foot stride that swings the foot (a standing passenger's bounce in a vehicle; decision W336,
        :mod:`pdrlearn.waist.foot_rest`; such runs are always named in one warning line each); default True
        (decision W337), False keeps and names them
    pelvic_rhythm_veto : offline: drop a contact sooner after the previous one of its walking sequence than 0.6 x the
        local step period of the pelvic-gyro detector (the one of the pair farther from a pelvic-gyro step; the step
        before it extends over it; decision W440, :mod:`pdrlearn.waist.pelvic_rhythm`): a very slow gait's extra
        contacts (W79); ``"slow"``: only where that period is slower than 70 steps/min (L95's range); True: at
        every cadence (lowered the real daily-activity recordings' step F1, W440)
    slow_min_step : offline waist-pendulum with its own detector: ``"slow"`` = where the session's pelvic-gyro median
        step (W475) is slower than 70 steps/min and counts at least 10 steps, the contact detector's shortest step is
        0.75 x that step instead of W113's (at most 0.3 s): a slow gait's second vertical maximum inside a step is no
        contact (decisions W590, W591, :func:`pdrlearn.waist.pelvic_rhythm.slow_shortest_step_s`); default False
        (W593: W592 met W591's rule, but the closing step before a slow walker's turn was lost and a bout split)
    pll_edge_lock : waist-pll with its own detector (the live tracker ignores it): the first and the last PLL peak of
        a run of peaks that pass the activity gate count only when the loop is locked at them (phase error within
        45 deg over the period ending at the peak; decision W356, W345's diagnosis: a free-running peak at a bout's
        edge; True / ``"both"``: W357 measured it, not adopted -- fewer extra contacts, but true edge contacts lost);
        ``"trailing"`` judges only the run's last peak and keeps its first (decision W358, not adopted, W366);
        ``"walk-end"`` (decision W368) judges a run's last peak only where the walk ends (the stride after it under
        W76's 0.15 m/s^2 SD; decision W367); ``"walk-edges"`` (the default, decision W373) also its first peak only
        where the walk starts after it (the stride before it that quiet; decision W372); False keeps every gated peak
    freeze_index : the lower back's freeze index (decision W213): freezes.csv and ``n_freezes`` / ``freeze_time_s``;
        default False (decision W216: on the lower back it also reads daily activities and slow walks as freezing),
        ``info["freezes"]`` None and the summary keys null (not measured)
    contact_model : pendulum, offline detector (the realtime one and ``waist-pll`` ignore it): ``"learned"`` keeps
        only the contacts whose calibrated probability from W203's learned re-scorer
        (:func:`pdrlearn.waist.contact_model.rescore_contacts`) is at least 0.5, before the stand and sit vetoes;
        default False (decision W203)
    contact_shift : pendulum, offline detector: every kept contact judged once more by W23's weight-shift test with the
        side read at the contact, turns spared (decision W131, :class:`~pdrlearn.waist.events.InitialContactDetector`'s
        ``contact_shift``); default True, ``False`` restores the detector before W131
    gait_check : with calibrated params that record their walks' gait: one warning line when this walk's median
        cadence is outside x0.75-x1.33 of the calibration's (decision W140: an option, its adoption rule was not met;
        ``info["calibration_cadence_ratio"]`` carries the ratio either way); default False
    speed_check : with calibrated params that record their walks' gait: one warning line when this walk's median
        cadence is more than 10 % outside the calibration walks' cadence range (decision W211: another walking speed
        biases the calibrated step length; with ``gait_check`` W140's line is given instead when both fire);
        default True
    pll_check : offline, uncalibrated waist-pll: one warning line when its distance is over 1.5 x the pendulum model's
        reading of the same session (decision W186: an option, its adoption rule was not met - fast plain walks
        warned too; ``info["pll_pendulum_ratio"]`` carries the ratio either way); default False
    short_step_check : offline, uncalibrated waist-pendulum: one warning line when the median step is under half the
        comfortable step of the stature (0.5 x 0.415 x height): a shuffling gait the pendulum model reads long
        (decision W207: an option, its adoption rule was not met - a real daily-activity recording warned; an
        uncalibrated offline waist-pll track is judged so on the pendulum's reading by default, W208); default False
    weak_fill : pendulum, offline detector: a weak step on the decided alternating side where the alternation and the
        local rhythm ask for one (decision W148, :class:`~pdrlearn.waist.events.InitialContactDetector`'s
        ``weak_fill``; measured and not adopted); default False
    pivot_steps : a step whose pelvis turns 45 deg or more from its contact to the next keeps at most the chord of its
        turn on a 0.2 m radius, after ``turn_factor`` (decision W150's candidate, both pipelines, offline and realtime;
        steps column ``pivot_factor``; measured and not adopted); default False
    cadence_law : a calibrated waist-pendulum step is multiplied by ``sqrt(SL(f) / SL(f_cal))``, seed 000's walking
        line at the step's and the calibration walks' median step frequency (1.5-2.2 Hz): the geometric mean of the
        pendulum and the cadence law (decision W240's candidate, offline and realtime; steps column
        ``cadence_factor``); ``"steady"``: only on a step that closes four steps of one walking sequence whose stride
        times vary by at most 10 % (CV) at a median cadence inside 1.5-2.2 Hz (decision W261); default False
    parity_fill : pendulum, offline detector: a contact without a vertical maximum between two kept contacts of one
        decided side about two local periods apart (decision W152, ``InitialContactDetector``'s ``parity_fill``);
        ``"within"``: only where it lies inside one walking sequence of the other contacts (decision W159's
        candidate); default False
    side_at_contact : pendulum, offline detector: the sequence rules read each candidate's W20 side at its initial
        contact instead of at its vertical maximum (decision W235, ``InitialContactDetector``'s ``side_at_contact``);
        default False
    fast_fill : pendulum, offline detector: one contact where a gap between two kept contacts has room for exactly
        one step and the vertical acceleration low-passed at twice the cut-off (5 Hz) has a maximum of its own there
        (decision W242, ``InitialContactDetector``'s ``fast_fill``); ``"outside_freeze"``: none inside an episode of
        the lower back's freeze index (W213; decision W255); default False
    ap_above_mean : pendulum, offline detector: the IC is the last local AP maximum in W3's window above the AP
        acceleration's 2 s mean, if there is one (decision W29, ``InitialContactDetector``'s ``ap_above_mean``; a
        track option by decision W265); default False
    turn_bridge : pendulum, offline detector: the motion gate is also open over a yaw-rate turn with walking on both
        sides (decision W374, ``InitialContactDetector``'s ``turn_bridge``); ``"side"`` (the default, decisions W384 /
        W385): the contacts without the bridge and those the bridge adds where their W20 side is decided and
        alternates

    detector : the contacts from this step detector instead of the pipeline's own (decision E85): a registered
        name (``pdrlearn.steps.DETECTORS``) or a :class:`~pdrlearn.steps.StepDetector` with ``unit = "waist"``; its
        ``event_s`` are used as they are (no motion gate, no IC refinement); offline only (not with ``realtime``)
    gate : with ``detector``: keep only its contacts where the pipeline's walking gate (W4, W76's threshold or
        PARAMS.json's ``walk_threshold_mps2``) is open (decision W473, :func:`pdrlearn.waist.events.gate_contacts`);
        the steps' detector then reads ``NAME+gate``. Default False (the contacts as they are)
    length_model : the step length from this model instead of the pipeline's (decision E84): a registered name
        (``pdrlearn.waist.lengths.STEP_LENGTHS``: the built-ins and plug-ins, ``list(STEP_LENGTHS)``), a
        ``"name:key=value"`` string or a :class:`~pdrlearn.waist.lengths.StepLengthModel`; None: ``pendulum``
        (waist-pendulum) or ``frequency`` (waist-pll). A model given by name takes the options named like its
        settings (``merge_fragments``, ``length_smoothing``, ``pause_steps``)

    The altitude (trajectory ``z``, steps ``dz_m``) is the waist barometer's, relative to the start (decision
    W89); without a barometer it stays 0 with one warning (W90).

    Options left at ``None`` take the value of ``params.options`` (a PARAMS.json ``"options"`` object)
    and else :data:`OPTION_DEFAULTS`.
    """
    given = {"realtime": realtime, "heading": heading, "refine_ic": refine_ic,
             "initial_heading": initial_heading, "resolve_signs": resolve_signs,
             "integrate_stops": integrate_stops, "turn_factor": turn_factor, "rhythm": rhythm,
             "merge_fragments": merge_fragments, "length_smoothing": length_smoothing,
             "relative_gate": relative_gate, "stairs_length": stairs_length, "stairs_climb": stairs_climb,
             "slow_turn_rps": slow_turn_rps, "gentle_curves": gentle_curves, "gentle_rest_bias": gentle_rest_bias,
             "max_tilt_deg": max_tilt_deg, "sit_veto": sit_veto, "pause_steps": pause_steps,
             "vault_veto": vault_veto, "contact_shift": contact_shift, "gait_check": gait_check, "pll_check": pll_check,
             "short_step_check": short_step_check,
             "speed_check": speed_check,
             "weak_fill": weak_fill, "pivot_steps": pivot_steps, "parity_fill": parity_fill, "cadence_law": cadence_law,
             "realtime_contact_shift": realtime_contact_shift, "integrate_end": integrate_end,
             "stand_veto": stand_veto, "contact_model": contact_model, "realtime_sit_veto": realtime_sit_veto,
             "freeze_veto": freeze_veto, "freeze_index": freeze_index, "pause_ride": pause_ride,
             "foot_rest_veto": foot_rest_veto,  # W336
             "pelvic_rhythm_veto": pelvic_rhythm_veto,  # W440
             "slow_min_step": slow_min_step,  # W591
             "pll_edge_lock": pll_edge_lock,  # W356
             "rhythm_warning": None,  # W338 / W339: a PARAMS.json option only
             "trunk_rhythm_veto": None,  # W550: a PARAMS.json option only
             "mount_drift": None,  # W565 / W566 / W571: a PARAMS.json option only
             "reclip": None,  # W623: a PARAMS.json option only
             "rest_bias": rest_bias, "step_bound": None,  # W230: a PARAMS.json option only
             "climb_veto": None,  # L330: a PARAMS.json option only
             "ride_vibration": None,  # L402 / L403: a PARAMS.json option only
             "walked_ride": None,  # W609: a PARAMS.json option only
             "gap_bridge": None,  # W625: a PARAMS.json option only
             "live_climbs": None,  # E358: a PARAMS.json option only
             "lying_heading": None,  # W269: a PARAMS.json option only
             "rest_frame": None,  # W285: a PARAMS.json option only
             "pll_slow_check": None,  # W289: a PARAMS.json option only
             "pll_slow_cadence_check": None,  # W313: a PARAMS.json option only
             "pll_slow_follow": None,  # W504: a PARAMS.json option only
             "side_at_contact": side_at_contact, "fast_fill": fast_fill, "ap_above_mean": ap_above_mean,
             "turn_bridge": turn_bridge}
    return _track_waist(session, pipeline, params, start, given, detector, length_model, gate=gate)


def _track_waist(session: Session, pipeline: str, params, start, given: dict, detector, length_model, *,
                 trunk_only: bool = False, gate: bool = False) -> TrackResult:
    """:func:`track_waist`'s body, its keyword options in ``given`` (each None: PARAMS.json's, else the default).
    ``trunk_only`` (decision W428, :func:`trunk_events`): stop after the contacts' vetoes and the gap cut, with the
    chair transfers, the contacts and the yaw-rate turns only."""
    if pipeline not in ("waist-pll", "waist-pendulum"):
        raise DataError(f"unknown waist pipeline '{pipeline}'; choose waist-pll or waist-pendulum")
    if not isinstance(gate, bool | np.bool_):  # review R1 finding 3: "no" or 1.0 gated (W473's option)
        raise DataError(f"gate={gate!r} is not True or False (decision W473: the walking gate on a detector's "
                        "contacts); pass gate=True or gate=False")
    p, warnings = resolve_params(session, params)
    spec = length_model if length_model is not None else ("pendulum" if pipeline == "waist-pendulum" else
                                                          "frequency")
    unused = unused_length_models_line(p, length_model, pipeline)
    if unused:
        warnings = [*warnings, unused]
    # decision W468: an instance is the caller's: configured on a copy, so PARAMS.json's gain (W460) stays this track's
    model = copy.deepcopy(spec) if isinstance(spec, StepLengthModel) else get_step_length(spec)  # E84
    if not model.uses_leg_length:  # e.g. the frequency model (waist-pll's) has no leg length (W62)
        warnings = [w for w in warnings if not w.startswith(NO_SENSOR_HEIGHT)]
    det = None if detector is None else waist_detector(detector, given["realtime"])  # E85
    if gate and det is None:  # decision W473
        raise DataError("gate applies the walking gate to a detector's contacts; the pipeline's own contacts are "
                        "gated already: give a waist detector (detector=NAME, --detector NAME) or drop the gate")
    o = resolve_options(p, given)
    realtime, heading, refine_ic = bool(o["realtime"]), o["heading"], bool(o["refine_ic"])
    causal_veto = realtime and bool(o["realtime_sit_veto"])  # W200: the sit veto decided causally
    if realtime and not causal_veto and given["sit_veto"] is None and (p.options or {}).get("sit_veto") is None:
        # decision W185: no veto - W184's rule adopted the whole-recording veto ("opposite") for offline tracks only
        # (decision W472: the rule, no module constant ``REALTIME_SIT_VETO``)
        o["sit_veto"] = False
    initial_heading, resolve_signs = float(o["initial_heading"]), bool(o["resolve_signs"])
    integrate_stops = bool(o["integrate_stops"])
    smoothing = check_length_smoothing(o["length_smoothing"])  # W56
    for key, (values, decisions) in CHOICE_OPTIONS.items():  # one line per option with more than two values
        if o[key] not in values:
            raise DataError(f"{key} {o[key]!r} is not one of {', '.join(json.dumps(v) for v in values)} (decisions "
                            f"{decisions}); fix the option or the PARAMS.json \"options\"")
    check_pause_steps(o["pause_steps"])  # W111, W122, W134
    if smoothing != "none" and realtime:
        raise DataError(f"length_smoothing '{smoothing}' looks up to 1 s ahead and the realtime detector does not "
                        "(decision W56); drop realtime or set length_smoothing to none")
    _configure_model(model, None if isinstance(spec, StepLengthModel) else spec, realtime,
                     _model_options(o, realtime))
    # decision W411: another pipeline's calibration leaves this one's step length on its defaults too
    own_calibration = p.source == "calibrated" and p.pipeline in (None, pipeline)
    gain_source = _calibrated_gain(model, spec, p, own_calibration)  # decision W460
    if not model.uses_profile:  # decision W461: calibrate's K / lines do not change this model; its own gain may
        warnings = [w for w in warnings if not w.startswith(NO_CALIBRATION)]
        warnings[:0] = [default_gain_line(model)] if gain_source == "default" else []
    if own_calibration and (model.uses_profile or gain_source == "params"):  # decision W471
        line = calibrated_detector_line(p.detector, det, pipeline)
        if line:
            warnings.append(line)
    if p.source == "calibrated" and not own_calibration and model.uses_profile:
        warnings.append(f"the parameters were calibrated for {p.pipeline}: the {pipeline} step length "
                        "keeps its defaults (run 'pdrlearn calibrate --pipeline " + pipeline + "')")
    try:
        imu = waist_imu(session)
    except DataError as exc:  # W61: no frame declared and too little walking to infer one: nothing to track
        if getattr(exc, "walk_s", None) is None:
            raise
        return _no_walking(session, pipeline, p, o, warnings, float(exc.walk_s), start, initial_heading)
    if o["reclip"] and not realtime:  # decision W623: a unit re-clipped mid-walk, its turn no heading turn
        imu, lines = _reclip.reclipped_imu(session, imu, correct=o["reclip"] != "line")  # W624: "line", the line alone
        warnings += lines
    # the W4 gate's threshold and signal (offline: centred); W76's relative gate (not realtime); steps 35
    thr, sigma, gate_source = gate_threshold(imu, p.walk_threshold_mps2,
                                             relative=bool(o["relative_gate"]) and not realtime)
    det_given = det is not None
    pelvic = None  # waist-pll's own PLL: [the pelvic-gyro steps], read once (W485, W504)
    if det is not None:  # E85: a waist detector's contacts, as they are
        steps = detector_steps(det, session, imu, thr if gate else None)  # W473: gated at the track's threshold
        method = heading or ("gyro" if pipeline == "waist-pendulum" else "ahe")
    elif pipeline == "waist-pendulum":
        min_step = None
        if o["slow_min_step"] and not realtime:  # decision W591: the pelvic gyro's slow step, read once (W485)
            pelvic = [read_once(None, session)]
            min_step = slow_shortest_step_s(pelvic[0])
        det = _contact_detector(o, thr, realtime, min_step_s=min_step).detect(imu)
        steps = det.steps_
        method = heading or "gyro"
    else:
        pelvic = None if realtime else [read_once(None, session)]  # W485: read once (W440, W441 below)
        followed = None if realtime else slow_follow_pll(session, thr, o["pll_edge_lock"], pelvic[0])  # W504
        own = functools.partial(_pll_steps, session, imu, thr, refine_ic=refine_ic, rhythm=bool(o["rhythm"]),
                                edge_lock=o["pll_edge_lock"])
        steps = own(followed=followed if o["pll_slow_follow"] else None)
        if followed is not None and not o["pll_slow_follow"]:  # decision W505
            line = slow_harmonic_line(steps, own(followed=followed))
            warnings += [line] if line else []
        method = heading or "ahe"
    if method not in (*HARMONIC_METHODS, "gyro"):
        raise DataError(f"heading method '{method}' is not one of {', '.join((*HARMONIC_METHODS, 'gyro'))}")
    line = ignored_options_line(o, pipeline, realtime, method, det_given, integrate_stops,  # decision W193
                                explicit={k for k, v in (p.options or {}).items() if v is not None}  # W301
                                - recorded_keys(p))  # W369: a calibration's own record is no user's choice
    warnings += [line] if line else []
    line = None if det_given else edge_lock_mismatch_line(p, pipeline, o["pll_edge_lock"])  # decision W369
    warnings += [line] if line else []
    n_rescored = 0
    if o["contact_model"] and pipeline == "waist-pendulum" and not realtime and detector is None:  # W203
        steps = rescore_contacts(steps, imu, thr, sigma, gyro_bias_rps=p.gyro_bias_rps)
        n_rescored = steps.attrs["n_rescored"]
    n_weak_run = 0
    if o["stand_veto"] and pipeline == "waist-pendulum" and not realtime and detector is None:  # W189
        steps = drop_weak_runs(steps, imu, spare_turns=o["stand_veto"] == "turns", gyro_bias_rps=p.gyro_bias_rps,
                               spare_alternation=o["stand_veto"] == "alternation",
                               spare_adjacent=o["stand_veto"] in ("adjacent", "walking"),
                               walking_reference=o["stand_veto"] == "walking")  # W218: + the walking reference
        n_weak_run = steps.attrs["n_weak_run"]
    if not realtime and len(steps):  # decision W550: runs of contacts without a step rhythm (trunk jerks)
        rhythmic = rhythm_keep_mask(steps["event_s"].to_numpy(float), steps["has_next"].to_numpy(bool))
        line = arrhythmic_line(int((~rhythmic).sum()), len(steps), bool(o["trunk_rhythm_veto"]))
        warnings += [line] if line else []
        if o["trunk_rhythm_veto"]:
            steps = drop_contacts(steps, rhythmic, "n_arrhythmic")
    n_tilted = 0
    pimu = imu  # decisions W565 / W566: the IMU the posture code reads (a drifting mount's turned up direction)
    if o["mount_drift"] and not realtime and len(steps) and "has_next" in steps:  # W571: an opt-in
        pimu, line = _mount_drift.drift_imu(imu, steps["event_s"].to_numpy(float), steps["has_next"].to_numpy(bool),
                                            standing=o["mount_drift"] == "standing")  # W576
        warnings += [line] if line else []
    if o["max_tilt_deg"] is not None:  # W102: a contact made with the trunk far from its walking upright is no step
        steps = tilt_gate(steps, pimu, float(o["max_tilt_deg"]))
        n_tilted = steps.attrs["n_tilted"]
    # decision W182: each sit-to-stand / stand-to-sit (W104's events); W277: without walking, from the still standing
    transfers, upright, upright_source = chair_transfers_upright(pimu, steps)
    fixed_up = upright if upright_source == "still" else None  # W277: the veto and the postures read it too
    if upright_source != "walking":
        warnings.append(upright_message(upright_source, len(transfers)))
    n_vetoed, sit_hint_s = 0, None
    if bool(o["sit_veto"]):  # W104: no step around a sit-to-stand's trunk-flexion peak; W109: step pairs kept;
        # W180: and an undecided contact inside an alternating sequence; W184: or inside a left/right pair
        veto = causal_transfer_veto if causal_veto else transfer_veto  # W200: realtime_sit_veto, the causal form
        steps = veto(steps, pimu, **sit_veto_keywords(o["sit_veto"]),
                     **({} if causal_veto or fixed_up is None else {"upright": fixed_up}))
        n_vetoed = steps.attrs["n_vetoed"]
        if not causal_veto and len(steps):  # decision W487: and every contact of a seated span (nobody walks seated)
            steps = drop_contacts(steps, ~inside_episodes(steps["event_s"].to_numpy(float), seated_spans(transfers)),
                                  "n_seated")
            n_vetoed += steps.attrs["n_seated"]
    else:  # W146: the contacts W104's veto would drop (a TUG's chair rises), named below (W343: if still counted)
        ev_sit = steps["event_s"].to_numpy(float)
        sit_hint_s = ev_sit[~np.isin(ev_sit, transfer_veto(steps, pimu)["event_s"].to_numpy(float))]
    n_unvaulted = 0
    if o["vault_veto"] and pipeline == "waist-pendulum" and not realtime:  # W119: no vault, no step
        steps = drop_unvaulted(steps, imu, spare_turns=o["vault_veto"] == "turns", gyro_bias_rps=p.gyro_bias_rps)
        n_unvaulted = steps.attrs["n_unvaulted"]
    freezes = lower_back_freezes(session, pipeline, o)  # decisions W213, W216: freezes.csv's episodes, opt-in
    shaky = unreliable_mask(freezes, steps)  # W396: an episode covering most of its bout is no freeze to veto
    if freezes:  # decision W215: on the lower back the index is a screening one; say what else it reads
        warnings.append(freeze_caveat_message(len(freezes), sum(r["duration_s"] for r in freezes),
                                              bool(o["freeze_veto"]) and not realtime and not shaky.all()))
    n_frozen = 0
    if shaky.any():
        warnings.append(unreliable_message([r for r, b in zip(freezes, shaky, strict=True) if b],
                                           bool(o["freeze_veto"]) and not realtime))
    if o["freeze_veto"] and not realtime and len(steps):  # W214: a contact inside a freeze is trembling, no step
        steps = drop_contacts(steps, ~inside_episodes(steps["event_s"].to_numpy(float),
                                                      [(r["start_s"], r["end_s"]) for r, b
                                                       in zip(freezes or [], shaky, strict=True) if not b]),
                              "n_frozen")
        n_frozen = steps.attrs["n_frozen"]
    elif freezes is None and not realtime:  # W395: the index off, a one-line hint when steps lie in its episodes
        line = freeze_hint(session_freezes(session, pipeline), steps)
        if line:
            warnings.append(line)
    # W336's foot strides (None: no foot unit); decision W547: of the tracked session only - a foot unit --units left
    # out changes no step (W253's put-back read is for the lines that only name: W173, L219)
    strides = foot_swing_strides(session)
    foot_runs = foot_rest_runs(steps, session, strides)  # W336: contacts while the foot rests
    warnings.extend(foot_rest_message(steps, a, b, bool(o["foot_rest_veto"])) for a, b in foot_runs)
    # decision W488: where the pelvis turned with a seat or a vehicle (seated; the foot unit at rest; a ride's contacts)
    yaw = yaw_turns(imu, p.gyro_bias_rps)  # decision L210: El-Gohary's turns, read once
    turn_spans = [(y["start_s"] if y.get("start_5_s") is None else y["start_5_s"],
                   y["end_s"] if y.get("end_95_s") is None else y["end_95_s"]) for y in yaw]
    carried = seated_spans(transfers) + strideless_spans(turn_spans, strides, unit_span(session, "foot"))  # W547
    n_foot_rest = 0
    if foot_runs and o["foot_rest_veto"]:
        carried += ride_spans(steps["event_s"].to_numpy(float), foot_runs)
        steps = drop_contacts(steps, foot_rest_keep(len(steps), foot_runs), "n_foot_rest")
        n_foot_rest = steps.attrs["n_foot_rest"]
    # W440, W441: read once, offline; W485: the ones --detector pll read for its band, if it did
    gyro_s = functools.cache(lambda: None if realtime else pelvic[0] if pelvic else read_once(det, session))
    n_ride = 0
    if not realtime and len(steps) and gyro_s() is not None:  # decision W486: no pelvic rhythm, a vibration: a ride?
        ev_ride = steps["event_s"].to_numpy(float)  # named, not dropped (W486's drop rule was not met)
        found = ride_runs(ev_ride, gyro_s(), imu.t, imu.acc_v, imu.fs)
        if found:
            warnings.append(ride_message(ev_ride, found))
            carried += ride_spans(ev_ride, found)
            n_ride = sum(b - a + 1 for a, b, _ in found)
    n_rhythm = 0
    if o["pelvic_rhythm_veto"] and not realtime and len(steps) and gyro_s() is not None:  # decision W440
        steps = merge_dropped(steps, rhythm_keep(steps["event_s"].to_numpy(float), steps["has_next"].to_numpy(bool),
                                                 gyro_s(), min_period_s=SLOW_PERIOD_S
                                                 if o["pelvic_rhythm_veto"] == RHYTHM_SLOW else 0.0), "n_rhythm")
        n_rhythm = steps.attrs["n_rhythm"]
    if sit_hint_s is not None:  # W146's line; W343: not for the contacts a later veto (W336's foot rest) dropped
        warnings.extend(sit_veto_hint(int(np.isin(sit_hint_s, steps["event_s"].to_numpy(float)).sum()),
                                      realtime=realtime))
    gaps = long_gaps(session, ("wAccelerometer", "wGyroscope"))  # decision B11
    warnings.extend(gap_warnings(gaps))
    steps = cut_steps_at_gaps(steps, gaps)
    if trunk_only:  # decision W428: what W418's TUG reads; the rest of the track (lengths, headings, altitude) is not
        postures, transfers = _postures_transfers(pimu, steps, transfers, upright_source, fixed_up, o, warnings)
        return TrackResult(steps=steps[["start_s", "end_s", "event_s"]].copy(), trajectory=pd.DataFrame(),
                           info={"transfers": None if transfers is None else transfers.to_dict("records"),
                                 "postures": postures,  # decision W586: the two-unit track's posture split
                                 "yaw_turns": mark_carried(yaw, carried)})  # decisions L210, W488, as below
    # W338: phone only (W336 reads a foot unit; W547: not one --units left out); W339: measured, an opt-in option
    if o["rhythm_warning"] and not session.placement_streams("foot"):
        warnings.extend(arrhythmic_message(steps, a, b, r)
                        for a, b, r in arrhythmic_sequences(steps, imu.t, imu.acc_v, imu.fs))
    steps = _step_lengths(steps, imu, p, model, thr, turn_factor=bool(o["turn_factor"]),
                          pivot_steps=bool(o["pivot_steps"]),
                          cadence_law=(o["cadence_law"] if o["cadence_law"] == CADENCE_LAW_STEADY
                                       else bool(o["cadence_law"])))  # W240, W261
    baro = usable_barometer(session, warnings)  # decision B188: an impossible pressure change is not read
    runs = _climb_runs(baro, steps)  # W108's climbs (W433: a single unproposed step inside bridged), for W155
    climbs = runs_mask(len(steps), runs)
    stairs = climbs if bool(o["stairs_climb"]) else _stairs_steps(baro, steps, False)
    tread = np.where(step_to_step_mask(len(steps), runs), 0.5 * STAIR_TREAD_M, STAIR_TREAD_M)  # W433: half a tread
    if not bool(o["stairs_length"]):  # W155: a counted stair climb read at level-walking step lengths says so
        line = stairs_length_message(climbs, steps["length_m"].to_numpy(float), tread)
        if line:
            warnings.append(line)
    if bool(o["stairs_length"]):  # W91's candidate: the horizontal length of a stair step is at most the tread
        bounded = climbs if o["stairs_length"] == "climbs" else stairs  # W156: only W108's climbs
        if o["stairs_length"] == "climbs" and realtime and o["live_climbs"] == "hold" and baro is not None:
            from pdrlearn.kernels.barometer import live_climb_bounds

            proposed, rise, start_h, end_h = _stair_proposals(baro, steps)  # E358: the live trackers' climbs
            tread, _ = live_climb_bounds(np.where(proposed, np.sign(rise), 0).astype(int), start_h, end_h)
            bounded = np.isfinite(tread)
        steps = steps.assign(length_m=np.where(bounded, np.minimum(steps["length_m"].to_numpy(float), tread),
                                               steps["length_m"].to_numpy(float)))
    still_mask = functools.cache(lambda: _still_samples(imu))  # L296's still samples: the IMU's own (W285, W354)
    lying = (_lying_heading(imu, steps, transfers, still_mask) if bool(o["lying_heading"]) and method == "gyro"
             and integrate_stops and not realtime else None)  # decision W269: offline (W222's lying reads ahead)
    at_rest = still_yaw_rate(imu.t, imu.acc_nav, imu.gyr_nav, imu.fs, p.gyro_bias_rps,
                             still=imu.still())  # decisions W105, W354 (and W544)
    steps = _step_headings(steps, imu, p, method, resolve_signs=resolve_signs, integrate_stops=integrate_stops,
                           slow_turn_rps=float(o["slow_turn_rps"] or 0.0),
                           gentle_curves=bool(o["gentle_curves"]),  # decision W543
                           gentle_bias_rps=gentle_rest_rate(at_rest, bool(o["gentle_rest_bias"]) and not realtime),
                           integrate_end=bool(o["integrate_end"]) and not realtime,  # W187: offline only
                           rest_bias=bool(o["rest_bias"]), lying=lying,  # decisions L296, W269
                           rest_frame=bool(o["rest_frame"]), still_mask=still_mask)  # decision W285
    rest_removed = steps.attrs.get("rest_bias_removed", [])
    rest_spans = steps.attrs.get("rest_bias_rests")  # decision L306
    steps = steps.assign(stairs=stairs)
    foot_cues = with_left_out_units(session)  # decision W253: a foot unit that --units left out still warns
    warnings.extend(backward_warnings(steps, foot_cues))  # decision W173: backward steps are counted forward
    ev_s, len_s = steps["event_s"].to_numpy(float), steps["length_m"].to_numpy(float)
    warnings.extend(sideways_warnings(foot_cues, lambda a, b: (  # decision L219: side steps are counted forward
        "the lower-back pipelines count every step as forward distance, so the track's "
        f"{np.nansum(len_s[(ev_s >= a) & (ev_s <= b)]):.1f} m of steps over this span go along its heading, not "
        "sideways")))
    n_st = len(steps)
    held = transfer_windows(imu, steps["event_s"].to_numpy(float), steps["has_next"].to_numpy(bool),
                            0.5 * ALTITUDE_SMOOTH_S, fixed_up)  # W174: a transfer's height change is the transfer's
    zz = _altitude(session, baro, np.concatenate([[imu.t[0]], steps["end_s"].to_numpy(float),
                                                  steps["start_s"].to_numpy(float)]), warnings, held)
    z, z_start, z_raw = (None, None, None) if zz is None else (zz[0][:n_st + 1], zz[0][n_st + 1:], zz[1][:n_st + 1])
    if z is not None and bool(o["pause_ride"]) and not bool(o["stairs_climb"]):  # decision W231
        z, z_start, z_raw = _pause_rides(baro, steps, float(imu.t[0]), z, z_start, z_raw, warnings)
    jumps = None
    if z is not None:  # decision W230: a step cannot climb more than MAX_STEP_DZ_M; a larger change is the air's
        z, z_start, z_raw, jumps = _hold_jumps(steps, z, z_start, z_raw, warnings, bool(o["step_bound"]))
    if z is not None and bool(o["stairs_climb"]):  # W108: a step off stairs is on a level floor (pauses too)
        z = np.concatenate([[0.0], np.cumsum(np.where(stairs, np.diff(z), 0.0))])
        z_start, z_raw = z[:-1], None  # W174's transfer_dz_m: 0 (every change off the stairs is left out here)
    untracked = _untracked_turn_warning(steps, imu, p, method, integrate_stops, warnings, rest_removed)
    # decision W76: never 0 steps without a word; W312: but not on a chair test W277 read without walking (its line
    # says so), and the isolated contacts a headline counts are named
    if not steps["has_next"].to_numpy(bool).any() and not (upright_source == "still" and len(transfers)):
        warnings.append(no_steps_message(thr, sigma, gate_source, n_contacts=len(steps)) + (
            f"; freeze_veto (decision W214) dropped {n_frozen} contact(s) inside freeze episodes: track without it "
            "(decision W396)" if n_frozen else "") + (
            f"; foot_rest_veto (decision W336) dropped {n_foot_rest} contact(s) made while the foot unit took no "
            "swinging stride: if the walker walked, track the lower back alone with --units waist, or set "
            "{\"options\": {\"foot_rest_veto\": false}} (decision W547)" if n_foot_rest else ""))
    elif not steps["has_next"].to_numpy(bool).any() and len(steps):
        warnings.append(f"the {len(steps)} contact(s) counted are isolated, none followed by another within "
                        f"{MAX_STEP_S:g} s: the chair transfers' own movement, no step and no distance (decision W312)")
    bias_line = still_yaw_rate_message(at_rest)  # decisions W105, W354
    if bias_line:
        warnings.append(bias_line)
    note = relative_heading_note(start, o["initial_heading"], "wMagneticField" in session, method)
    if note:
        warnings.append(note)
    ev = steps["event_s"].to_numpy(float)
    v_at = contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, ev)  # W20's cue, read once for W98 and W129
    alternation, pairs = contact_alternation(imu.t, imu.acc_ml, imu.fs, ev, steps["has_next"].to_numpy(bool),
                                             v_at=v_at)  # decision W98
    # decision W129: each contact's side; realtime: empty (W20's velocity is zero-phase over the whole recording)
    steps = steps.assign(side=np.full(len(steps), "", dtype=object) if realtime
                         else contact_sides(imu.t, imu.acc_ml, imu.fs, ev, v_at=v_at))
    steps = steps.assign(climb=climbs)  # decision L314: W108's stair climbs, which no ramp is made of (grade.py)
    rides: list[dict] | None = None  # None: no barometer read (n_rides empty, no rides.csv)
    if z is not None:  # decisions L375-L377: each ride's kind (steps.csv ride), rides.csv and their lines
        from pdrlearn.track.rides import ride_accelerometer, ride_lines, ride_rows

        ride_kinds, rides = ride_rows(baro.t, baro.values[:, 0], steps, float(imu.t[0]), z, z_start,
                                      t_end=float(imu.t[-1]), acc=ride_accelerometer(session),  # L394, L402
                                      vibration_kind=bool(o["ride_vibration"]),  # L403: opt-in
                                      walked_kind=bool(o["walked_ride"]))  # W609: opt-in
        steps = steps.assign(ride=ride_kinds)
        warnings.extend(ride_lines(rides))
    # decisions W114, W441: the pelvic gyro's count beside the contacts' (offline), both ways
    counts = None if realtime else step_counts(session, steps["event_s"].to_numpy(float), gyro_s=gyro_s(),
                                               has_next=steps["has_next"].to_numpy(bool))
    not_alternating = (not realtime and alternation is not None and pairs >= PLAUSIBILITY_MIN_PAIRS
                       and alternation < ALTERNATION_MIN)  # decision W98
    uncountable = not_alternating and steps_uncountable(counts)  # decision W442
    if not_alternating:
        warnings.append(not_alternating_message(alternation, pairs, counts))  # W114, W442 in its line
    elif count_mismatch_message(counts):  # decision W441; W486: naming the ride's contacts it also counted
        warnings.append(count_mismatch_message(counts) + (
            f"; {n_ride} of the contacts lie in the runs named vehicle / ride? (decision W486)" if n_ride else ""))
    pendulum = functools.cache(lambda: _pendulum_steps(imu, p, thr, o))  # W139 and W186 read it once
    height_m, no_height = subject_height(session.meta)
    ratio, ratio_line = _walk_ratio(steps, p, pipeline, realtime, height_m,  # W100, W116
                                    pendulum=pendulum, short_step=bool(o["short_step_check"]),  # W139, W207
                                    stairs=lambda st: _stairs_steps(baro, st, bool(o["stairs_climb"])),  # W155
                                    height_known=no_height is None,  # decision L492
                                    gyro_count=None if realtime else lambda st: _gyro_count(session, st, gyro_s()),
                                    pendulum_kept=lambda: trunk_events(session).steps["event_s"].to_numpy(float),
                                    advice=walk_ratio_advice(model.name, uses_profile=model.uses_profile,
                                                             gain_param=model.gain_param))  # decision W461
    if ratio_line:
        warnings.append(ratio_line)
    excess = None
    if pipeline == "waist-pll" and not realtime and p.source == "defaults" and not ratio_line:  # decision W186
        excess, excess_line = pll_excess(steps["length_m"].to_numpy(float), steps["frequency_hz"].to_numpy(float),
                                         pendulum()["length_m"].to_numpy(float))
        pll_lines = []
        if excess_line and bool(o["pll_check"]):  # W186's line: an option (its adoption rule was not met)
            pll_lines = [excess_line]
        elif bool(o["pll_slow_check"]) or bool(o["pll_slow_cadence_check"]):  # decisions W289, W313: at a slow gait
            pend = pendulum()  # W186's ratio over 1.25 warns (the slow gait judged by the pendulum's speed / cadence)
            _, n_pend, pend_length, pend_cadence = walk_ratio(pend["length_m"].to_numpy(float),
                                                              waist_step_times(pend)[0])
            slow_lines = [pll_slow_excess_message(excess, float(np.nansum(np.abs(steps["length_m"].to_numpy(float)))),
                                                  float(np.nansum(np.abs(pend["length_m"].to_numpy(float)))),
                                                  pend_length, pend_cadence, n_pend, judge=judge)
                          for judge, key in (("speed", "pll_slow_check"), ("cadence", "pll_slow_cadence_check"))
                          if bool(o[key])]
            pll_lines = [line for line in slow_lines if line][:1]  # one line when both judges are on
        if not pll_lines:  # decision W491: no earlier line: the population-model line over 1.25 x at any gait
            pll_lines = [line for line in [pll_model_message(
                excess, float(np.nansum(np.abs(steps["length_m"].to_numpy(float)))),
                float(np.nansum(np.abs(pendulum()["length_m"].to_numpy(float)))))] if line]
        warnings += pll_lines
    if length_model is None and not own_calibration:  # decisions W405, W533, W534: a child's uncalibrated distance
        step_s = waist_step_times(steps)[0]
        short = short_walker_message(session.meta, pipeline,
                                     float(np.nanmedian(step_s)) if np.isfinite(step_s).any() else None)
        if short:
            warnings.append(short)
    micro_line = micro_bout_message(*micro_bouts(steps["length_m"].to_numpy(float),  # decision W157
                                                 steps["has_next"].to_numpy(bool)))
    if micro_line:
        warnings.append(micro_line)
    pause_line = pause_scaled_message(*pause_scaled_count(steps), o["pause_steps"])  # decision W514
    if pause_line:
        warnings.append(pause_line)
    # decisions W140 (gait_check: an option, its adoption rule was not met), W211 (speed_check: on); one line
    pelvic = _pelvic_cadence(counts, gyro_s()) if uncountable else None  # decision W579
    judged = not uncountable or pelvic is not None  # W579: contacts that are no steps judge no calibration
    cadence_ratio, calibration, covers = _calibration_gait(steps, p, pipeline, bool(o["gait_check"]) and judged,
                                                           bool(o["speed_check"]) and judged, pelvic=pelvic)
    if calibration:
        warnings.append(calibration)
    n = len(steps)
    # decision W462: the model with the settings the user set (info["methods"]["length"] keeps its name)
    length_model = model_spec(model, None if isinstance(spec, StepLengthModel) else spec, gain_source == "params")
    postures, transfers = _postures_transfers(pimu, steps, transfers, upright_source, fixed_up, o, warnings)
    steps = _with_still_before(steps, imu, still_mask())  # decision L372: the pauses' still time
    info = {
        "pipeline": pipeline,
        "method": f"{steps.attrs.get('detector', '')}/{length_model}/{method}",
        "methods": {"steps": steps.attrs.get("detector", ""), "length": model.name, "heading": method},
        "params": p.to_dict(),
        "params_source": p.source,
        "options": o,
        "warnings": warnings,
        "n_contacts": int(n),
        "rate_hz": imu.fs,
        "untracked_turn_deg": untracked,
        "walk_threshold_mps2": float(thr),
        "alternation_index": alternation,
        "alternation_pairs": pairs,
        "walk_ratio": ratio,
        "pll_pendulum_ratio": excess,  # decision W186
        "calibration_cadence_ratio": cadence_ratio,
        "calibration_covers_cadence": covers,  # decision W227: L95's slow line names a calibration at this gait
        "n_tilted_contacts": n_tilted,
        "n_vetoed_contacts": n_vetoed,
        "n_unvaulted_contacts": n_unvaulted,
        "n_weak_run_contacts": n_weak_run,
        "n_rescored_contacts": n_rescored,  # decision W203
        "n_frozen_contacts": n_frozen,  # decision W214
        "n_rhythm_contacts": n_rhythm,  # decision W440
        "n_foot_rest_contacts": n_foot_rest,  # decision W336 (C198: track-all names a track they emptied)
        "n_ride_contacts": n_ride,  # decision W486: the contacts its line names (still counted)
        "n_pelvic_gyro_steps": None if counts is None else counts[1],  # decision W441: over the contacts' span
        "step_count_unusable": bool(uncountable),  # decision W442: L95's line names no fast gait then
        # decision W476: why summary.json withholds the cadence and step times (None: W442 did not fire)
        "step_count_withheld": (step_count_withheld_reason(counts, median_step_period(gyro_s()))
                                if uncountable else None),
        "barometer_jump_steps": jumps,  # decision W230: steps held level (a pressure transient); None: no altitude
        "freezes": freezes,  # decision W213: freezes.csv (not written to summary.json)
        # decisions W182, W245: transfers.csv (not in summary.json); W277: None when no upright could be had
        "transfers": None if transfers is None else transfers.to_dict("records"),
        "postures": postures,  # decision W222: the posture runs (not in summary.json)
        # decision L306: the rests whose bias L296 took out (L297's sigma clock skips these only); None: L296 not
        # in force on this heading (not in summary.json)
        "rest_bias_rests": None if rest_spans is None else [[a, b] for a, b in rest_spans],
        # decision L210: El-Gohary's turns, turns.csv's timing; W488: those made seated or riding marked "carried"
        "yaw_turns": mark_carried(yaw, carried),
        "rides": rides,  # decision L377: rides.csv (not in summary.json)
    }
    from pdrlearn.waist import turn_steps

    # W283's missed-steps warning is not printed (W284: not adopted; turn_steps.turn_steps_warning is the API's)
    if "event_s" in steps:  # decision W331 (W332: adopted): turns on the spot with no step
        line = turn_steps.stepless_turns_warning(steps["event_s"], info["yaw_turns"])
        if line:
            warnings.append(line)
    if o["gap_bridge"] and not realtime:  # decision W625: a short gap inside walking walked at the pace either side
        steps = _bridge_gaps(steps, gaps, warnings)
    for w in warnings:
        log.warning("%s: %s", session.where, w)
    return _result(steps, start, initial_heading, info, float(imu.t[0]), z, z_start, z_raw)


def _bridge_gaps(steps: pd.DataFrame, gaps: dict[str, list[tuple[float, float]]], warnings: list[str]) -> pd.DataFrame:
    """Decision W625: ``steps`` with each B11 gap inside walking that :func:`pdrlearn.kernels.gap_bridge.pace_bridge`
    bridges walked at the pace either side (the closing contact's row: ``length_m``, ``end_s`` the next contact,
    ``gap_bridged_m``), and one line in ``warnings`` saying so. Unchanged (no column) when none is bridged."""
    from pdrlearn.decision_refs import decision_ref
    from pdrlearn.kernels.gap_bridge import pace_bridge

    if not gaps or not len(steps):
        return steps
    bridged, end = pace_bridge(steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float),
                               steps["has_next"].to_numpy(bool), steps["length_m"].to_numpy(float), gaps)
    on = bridged > 0
    if not on.any():
        return steps
    out = steps.assign(length_m=np.where(on, bridged, steps["length_m"].to_numpy(float)),
                       end_s=np.where(on, end, steps["end_s"].to_numpy(float)), gap_bridged_m=bridged)
    out.attrs = dict(steps.attrs)
    said = set(gap_warnings(gaps))  # B11's lines: each now says what the bridge did
    told = gap_warnings(gaps, f"{int(on.sum())} of them inside walking (at most 5 s) bridged at the pace of the steps "
                              f"either side, {bridged.sum():.1f} m in all (steps.csv gap_bridged_m; the heading held "
                              f"across them, a turn inside one is missed; {decision_ref('W625')}); no displacement is "
                              "counted inside the others")
    at = next((k for k, w in enumerate(warnings) if w in said), len(warnings))
    warnings[:] = [w for w in warnings[:at] if w not in said] + told + [w for w in warnings[at:] if w not in said]
    return out


def _calibrated_gain(model: StepLengthModel, spec, p: WaistParams, own_calibration: bool) -> str | None:
    """Decision W460: where ``model``'s :attr:`~pdrlearn.waist.lengths.StepLengthModel.gain_param` comes from, and set
    it from PARAMS.json's ``length_models`` when the user did not: ``"spec"`` (the spec names it, or an instance's is
    not None), ``"params"`` (the file's, calibrated for this pipeline), ``"default"`` (the model's default gain);
    None for a model without a gain. A gain that is still None is one line naming both ways to set it."""
    from pdrlearn.plugins import parse_spec

    gain = model.gain_param
    if not gain:
        return None
    value = model.get_params().get(gain)
    if (gain in parse_spec(spec, "step-length model")[1]) if isinstance(spec, str) else value is not None:
        return "spec"
    fitted = ((p.length_models or {}).get(model.name) or {}).get(gain) if own_calibration else None
    if fitted is not None:
        model.set_params(**{gain: float(fitted)})
        return "params"
    if value is not None:
        return "default"
    where = _length_models_where(model.name, gain, p, own_calibration)  # decision W469
    raise DataError(f"step-length model {model.name}: set its gain {gain}{where}: give it "
                    f"(--length-model {model.name}:{gain}=VALUE) or fit it on a walk of known length: 'pdrlearn "
                    f"calibrate DIR --distance M --length-model {model.name} --out PARAMS.json', then track with "
                    f"--length-model {model.name} --params PARAMS.json (decisions W460, W470)")


def unused_length_models_line(p: WaistParams, length_model, pipeline: str) -> str:
    """Decision W470: the note of a track whose PARAMS.json, calibrated for this ``pipeline``, holds ``length_models``
    gains (``calibrate --length-model NAME``, W460) that no --length-model uses (they apply only to the model named);
    "" otherwise (another pipeline's file is said by its own lines)."""
    models = p.length_models or {}
    if length_model is not None or not models or p.pipeline not in (None, pipeline):
        return ""
    names = ", ".join(models)
    first = next(iter(models))
    return (f"the --params file holds step-length model {names}'s gain (calibrate --length-model), which this track "
            f"does not use (it takes the pipeline's own model): add --length-model {first} to use it (decision W470)")


def _length_models_where(name: str, gain: str, p: WaistParams, own_calibration: bool) -> str:
    """Decision W469: why PARAMS.json's ``length_models`` gave model ``name`` no gain ``gain`` (the bracket of
    :func:`_calibrated_gain`'s line): another pipeline's calibration, an entry without ``gain`` (a mistyped setting),
    or entries for other names only (a mistyped model name); "" when the file has no ``length_models``."""
    models = p.length_models or {}
    if not models:
        return ""
    entry = models.get(name)
    if entry is None:  # e.g. a misspelt name
        return f" (the --params file's length_models has no {name!r}, only {', '.join(map(repr, models))})"
    if not own_calibration:
        return f" (the --params file was calibrated for {p.pipeline}, not this pipeline)"
    return (f" (the --params file's length_models {name!r} holds {', '.join(map(repr, entry))}, not {gain!r}: "
            f"rename it {gain})")


def default_gain_line(model: StepLengthModel) -> str:
    """Decision W461: the "no per-user calibration" line of a gain model tracked on its default gain."""
    g = model.gain_param
    return (f"{NO_CALIBRATION}: step-length model {model.name}'s gain {g} = {model.get_params()[g]:g} is its default; "
            f"fit it on this walker's walk of known length ('pdrlearn calibrate DIR --distance M --length-model "
            f"{model.name} --out PARAMS.json', then track with --length-model {model.name} --params PARAMS.json) or "
            f"set {model.name}:{g}=VALUE (decisions W460, W461, W470)")


def _configure_model(model: StepLengthModel, spec, realtime: bool, options: dict) -> None:
    """Decision E84: a model named by the pipeline or the user (``spec``: its name or ``"name:key=value,..."``;
    None for an instance, which keeps its own settings) takes the pipeline's options named like its settings,
    except those the spec sets itself (``--length-model pendulum:merge_fragments=false`` was overwritten by the
    option's default). The realtime detector refuses a setting that looks ahead (W56's smoothing, W111 / W122's
    pause steps; the options are ignored or refused there already)."""
    from pdrlearn.plugins import parse_spec

    own = parse_spec(spec, "step-length model")[1] if isinstance(spec, str) else {}
    if spec is not None:
        model.set_params(**{k: v for k, v in options.items() if k in model.get_params() and k not in own})
    if not realtime:
        return
    mine = model.get_params()
    if "causal_stands" in mine:  # decision W529: W516's share over the steps so far, as the live tracker counts it
        model.set_params(causal_stands=True)
    if str(mine.get("length_smoothing", "none")) != "none":
        raise DataError(f"step-length model {model.name}: length_smoothing '{mine['length_smoothing']}' looks up to "
                        "1 s ahead and the realtime detector does not (decision W56); drop realtime or the setting")
    if mine.get("pause_steps") and mine.get("pause_steps") != CAUSAL_PAUSE_STEPS:  # W165: "standing" is causal
        raise DataError(f"step-length model {model.name}: pause_steps {mine['pause_steps']!r} looks three steps "
                        "ahead and the realtime detector does not apply it (decisions W111, W122; W165: only "
                        "\"standing\" is); drop realtime or the setting")


def waist_detector(detector, realtime: bool):
    """Decision E85: the :class:`~pdrlearn.steps.StepDetector` a waist pipeline takes its contacts from - a
    registered name or an instance whose declared unit is ``"waist"``; one line otherwise."""
    from pdrlearn.steps import StepDetector, get_detector

    det = get_detector(detector) if isinstance(detector, str) else detector
    if not isinstance(det, StepDetector):
        raise DataError(f"detector {detector!r}: pass a registered step detector's name or a StepDetector instance "
                        "(docs/extending.md)")
    if det.unit != "waist":
        raise DataError(f"detector {det.name} declares unit {det.unit!r}; a lower-back pipeline integrates every "
                        "step of both feet: choose a detector with unit 'waist' (pll, waist-ic, pelvic-gyro or a "
                        "plug-in), or track a foot session with the plasys pipeline")
    if realtime:
        raise DataError(f"detector {det.name}: realtime chooses the pipeline's own causal contact detector "
                        "(decision W31); drop realtime or the detector")
    return det


def detector_spec(det) -> str | None:
    """Decision W471: the waist detector ``det`` (a :class:`~pdrlearn.steps.StepDetector`, None: the pipeline's own)
    as PARAMS.json's ``detector`` records it: ``NAME:key=value,...`` with the settings that differ from its defaults
    (the form ``--detector`` reads back)."""
    from pdrlearn.plugins import spec_text

    return None if det is None else spec_text(det.name, det.changed_params())


def calibrated_detector_line(recorded: str | None, det, pipeline: str | None = None, *,
                             live: bool = False) -> str | None:
    """Decision W471: one line when PARAMS.json's step length was calibrated on the contacts of another detector
    (``recorded``, its ``detector``; None: the pipeline's own) than the one this track takes them from (``det``, None:
    the pipeline's own); None when they are the same detector with the same settings. Decision W479: on
    ``pipeline``, its :data:`OWN_DETECTOR` with its default settings counts as the pipeline's own (either side);
    ``live``: the live tracker's line, which cannot take another detector's contacts (its advice is to recalibrate)."""
    from pdrlearn.plugins import parse_spec
    from pdrlearn.runtime.detector_line import live_detector_line, recorded_own

    if live:  # decision W479: the live tracker takes the pipeline's own contacts only (W483: its words shared with
        return live_detector_line(recorded, pipeline)  # the lean runtime's WaistTracker)
    own = (OWN_DETECTOR.get(pipeline), {})
    if det is not None and (det.name, det.changed_params()) == own:
        det = None  # decision W479
    if recorded is not None:
        if recorded_own(recorded, pipeline):
            recorded = None  # decision W479
        else:
            try:
                spec = parse_spec(recorded, "step detector")
            except DataError:
                spec = None  # an unreadable record is another detector
            if det is not None and spec == (det.name, det.changed_params()):
                return None
    if recorded is None and det is None:
        return None
    now = detector_spec(det)
    was = "the pipeline's own contacts" if recorded is None else f"the contacts of --detector {recorded}"
    track = "track without --detector" if recorded is None else f"track with --detector {recorded}"
    return (f"the parameters were calibrated on {was}; this track takes "
            + ("the pipeline's own" if now is None else f"--detector {now}'s") +
            ": another detector's contacts split the walk into other steps, so the calibrated step length may not "
            f"fit them ({track}, or calibrate with the detector you track with: 'pdrlearn calibrate DIR -d METRES "
            + ("" if now is None else f"--detector {now} ") + "--out PARAMS.json'; decision W471)")


def detector_steps(det, session: Session, imu: WaistIMU, gate_mps2: float | None = None) -> pd.DataFrame:
    """Decision E85: the waist steps table (``has_next``; ``fc_s`` NaN: the pendulum reads IC to IC, W10) of a
    detector's contacts on the AHRS's samples (the nearest sample of each
    ``event_s``; contacts further apart than :data:`MAX_STEP_S` end a sequence). Decision W473: with ``gate_mps2``
    only the contacts the walking gate at that threshold lets through (:func:`~pdrlearn.waist.events.gate_contacts`),
    the detector named ``NAME+gate``."""
    table = det.detect(session)
    if gate_mps2 is None:
        return contact_steps(table, imu, det.name)
    from pdrlearn.waist.events import gate_contacts

    return contact_steps(gate_contacts(table, imu, walk_threshold=gate_mps2), imu, f"{det.name}+gate")


def transfer_contacts(table: pd.DataFrame, session: Session) -> tuple[np.ndarray, pd.DataFrame]:
    """Decision W297: of a lower-back detector's contacts (``table``'s ``event_s``, as `pdrlearn steps` prints
    them), the times (s, on the AHRS's samples) that an offline `track`'s default sit veto drops (W104 / W185's
    :func:`~pdrlearn.waist.posture.transfer_veto` with :data:`OPTION_DEFAULTS`' ``sit_veto``, against W277's
    upright as `track` reads it), and W182 / W277's transfers.csv rows found with them."""
    imu = waist_imu(session)
    steps = contact_steps(table, imu)
    transfers, upright, source = chair_transfers_upright(imu, steps)
    kept = transfer_veto(steps, imu, **sit_veto_keywords(OPTION_DEFAULTS["sit_veto"]),
                         **({"upright": upright} if source == "still" else {}))  # as `track`'s fixed_up (W277)
    dropped = np.setdiff1d(steps["event_s"].to_numpy(float), kept["event_s"].to_numpy(float))
    return dropped, transfers


def contact_steps(table: pd.DataFrame, imu: WaistIMU, name: str = "") -> pd.DataFrame:
    """Decision E85: :func:`detector_steps`' table of the contacts ``table`` (``event_s``)."""
    ev = np.sort(table["event_s"].to_numpy(float)) if len(table) else np.zeros(0)
    idx = np.unique(np.clip(np.round((ev - imu.t[0]) * imu.fs).astype(int), 0, len(imu.t) - 1))
    return steps_from_events(imu.t, idx, max_step_s=MAX_STEP_S, detector=name)


def _walk_ratio(steps: pd.DataFrame, p: WaistParams, pipeline: str, realtime: bool,
                height_m: float, pendulum=None, stairs=None, short_step: bool = False, height_known: bool = True,
                advice: str = WALK_RATIO_ADVICE, gyro_count=None,
                pendulum_kept=None) -> tuple[float | None, str | None]:
    """Decision W100: the walk ratio of an offline, uncalibrated ``waist-pendulum`` track (None otherwise) and its
    warning line (None inside the healthy band of a walker ``height_m`` tall, W116, or with too few steps).
    Decision W139: an offline, uncalibrated ``waist-pll`` track is judged on the steps ``pendulum()`` returns (the
    pendulum model's reading of the same session, :func:`_pendulum_steps`); ``walk_ratio`` is then theirs.
    Decision W155: the steps ``stairs(steps)`` marks as on stairs (W91 / W108) are left out: a stair step is no
    level gait (under ``stairs_length`` its length is the tread's, and read as a shuffle).
    Decision W207: with ``short_step`` (the option ``short_step_check``; always for waist-pll, W208), inside W100's
    band, a median pendulum step under half the comfortable step for the stature warns
    (:func:`~pdrlearn.waist.plausibility.short_step_message`; not at a running cadence, W177). Decision W208: a pll
    track with far fewer contacts than the pendulum reading says it misses steps instead of W139's line. Decision
    W461: ``advice`` ends W100's line (:func:`~pdrlearn.waist.plausibility.walk_ratio_advice`: what applies to the
    track's step-length model); a model other than the pipeline's (another advice) gets no W207 line, which is about
    the pendulum's reading. Decision W477: ``gyro_count(steps)``, the pelvic-gyro steps over the pendulum reading's
    walking sequences, judges W208's line's advice (None: not read). Decision W489: ``pendulum_kept()``, the
    contact times the default waist-pendulum track keeps after its vetoes (W428's :func:`trunk_events`), is what
    W208's line compares with (None: the raw reading)."""
    if realtime or p.source != "defaults" or not len(steps):
        return None, None
    pll_length = pll_m = pendulum_m = None
    missed = None
    if pipeline == "waist-pll" and pendulum is not None:
        level = ~stairs(steps) if stairs is not None else np.ones(len(steps), dtype=bool)
        own = steps["length_m"].to_numpy(float)[(waist_step_times(steps)[0] > 0) & level]
        pll_length = float(np.median(np.abs(own))) if own.size else None
        pll_m = float(np.nansum(np.abs(steps["length_m"].to_numpy(float))))
        n_pll = len(steps)
        steps = pendulum()
        pendulum_m = float(np.nansum(np.abs(steps["length_m"].to_numpy(float))))
        missed = pll_missed_steps_message(n_pll, len(steps), pll_m, pendulum_m)  # decision W208
        if missed and pendulum_kept is not None:  # decision W489: judged on the pendulum track's kept contacts
            kept = _kept_reading(steps, pendulum_kept())
            missed = pll_missed_steps_message(n_pll, len(kept), pll_m,
                                              float(np.nansum(np.abs(kept["length_m"].to_numpy(float)))),
                                              n_gyro=gyro_count(kept) if gyro_count else None)  # W477
        elif missed:
            missed = pll_missed_steps_message(n_pll, len(steps), pll_m, pendulum_m,
                                              n_gyro=gyro_count(steps) if gyro_count else None)  # W477
    elif pipeline != "waist-pendulum":
        return None, None
    step_s = waist_step_times(steps)[0]
    if stairs is not None:  # W155: stair steps are not judged (NaN step time: left out of walk_ratio)
        step_s = np.where(stairs(steps), np.nan, step_s)
    ratio, n, length, cadence = walk_ratio(steps["length_m"].to_numpy(float), step_s)
    # W208: a pll track that misses steps says so first (W139's line would call its short reading long)
    line = missed or walk_ratio_message(ratio, n, length, cadence, height_m, pll_length=pll_length,
                                        pll_m=pll_m, pendulum_m=pendulum_m, height_known=height_known,
                                        advice=advice)
    if (line is None and (short_step or pll_m is not None) and advice == WALK_RATIO_ADVICE
            and not running_cadence(length, cadence, height_m)):
        line = short_step_message(length, n, height_m, pll_m=pll_m, pendulum_m=pendulum_m)  # decision W207
    return ratio, line


def _kept_reading(steps: pd.DataFrame, kept_s: np.ndarray, tol_s: float = 0.05) -> pd.DataFrame:
    """Decision W489: W139's raw pendulum reading ``steps`` without the contacts that the pendulum track did not keep
    (no contact of ``kept_s`` within ``tol_s``; a dropped contact ends its walking sequence, as the vetoes do)."""
    ev = steps["event_s"].to_numpy(float)
    k = np.sort(np.asarray(kept_s, dtype=float))
    if not k.size:
        return drop_contacts(steps, np.zeros(len(steps), dtype=bool), "n_unkept")
    j = np.clip(np.searchsorted(k, ev), 1, max(k.size - 1, 1))
    near = np.minimum(np.abs(ev - k[j - 1]), np.abs(k[np.minimum(j, k.size - 1)] - ev))
    return drop_contacts(steps, near <= tol_s, "n_unkept")


def _gyro_count(session: Session, steps: pd.DataFrame, gyro_s: np.ndarray | None) -> int | None:
    """Decision W477: the pelvic-gyro steps over the walking sequences of ``steps`` (W441's :func:`step_counts`);
    None without a waist gyroscope or contacts."""
    if gyro_s is None or len(steps) < 2:
        return None
    counts = step_counts(session, steps["event_s"].to_numpy(float), gyro_s=gyro_s,
                         has_next=steps["has_next"].to_numpy(bool))
    return None if counts is None else counts[1]


def _pelvic_cadence(counts: tuple[int, int], gyro_s: np.ndarray | None) -> tuple[float, int] | None:
    """Decision W579: the pelvic-gyro detector's cadence (60 / its median step interval, as W476's reason) and its
    count; None without a finite interval."""
    period = median_step_period(gyro_s)
    return (60.0 / period, int(counts[1])) if np.isfinite(period) and period > 0 else None


def _calibration_gait(steps: pd.DataFrame, p: WaistParams, pipeline: str, gait_check: bool,
                      speed_check: bool, *, pelvic: tuple[float, int] | None = None
                      ) -> tuple[float | None, str | None, bool | None]:
    """Decision W140: ``(ratio, line, covers)``, this track's median cadence over its calibration walks' (None: not
    calibrated, a params file without ``gait``, or fewer than ten steps), the one calibration line under the options
    (:func:`~pdrlearn.waist.plausibility.calibration_line`: W140's, else W211's; None: neither fires) and W227's
    verdict whether the calibration's cadence range covers this walk
    (:func:`~pdrlearn.waist.plausibility.calibration_covers`; None: not judged). Decision W594: with ``pelvic``
    (W579: the contacts are no step count) the ratio and W227's verdict read the pelvic gyro's cadence and count too,
    as W211's line does."""
    ref = (p.gait or {}).get("median_cadence_spm") if p.source == "calibrated" else None
    cadence, n = median_cadence(steps["frequency_hz"].to_numpy(float)) if pelvic is None else pelvic  # W594
    if not ref or cadence is None or n < PLAUSIBILITY_MIN_PAIRS:
        return None, None, None
    line = calibration_line(p.gait, cadence, n, p.pipeline or pipeline, gait_check=gait_check,
                            speed_check=speed_check, pelvic=pelvic)  # decision W579
    return cadence / float(ref), line, calibration_covers(p.gait, cadence, n)


def _contact_detector(o: dict, thr: float, realtime: bool, *, min_step_s: float | None = None
                      ) -> InitialContactDetector:
    """The waist-pendulum pipeline's contact detector under the track's options ``o`` and motion-gate threshold
    ``thr`` (one construction for the track and W139's pendulum reading, so an option cannot be left out: E102);
    ``min_step_s``: the shortest step (None: W113's; W591's ``slow_min_step`` gives the pelvic gyro's)."""
    return InitialContactDetector(realtime=realtime, walk_threshold=thr, max_step_s=MAX_STEP_S, min_step_s=min_step_s,
                                  rhythm=bool(o["rhythm"]), contact_shift=bool(o["contact_shift"]),
                                  realtime_shift=bool(o["realtime_contact_shift"]),  # W166: an option
                                  weak_fill=bool(o["weak_fill"]), side_at_contact=bool(o["side_at_contact"]),  # W235
                                  fast_fill=o["fast_fill"] if o["fast_fill"] == FAST_FILL_OUTSIDE_FREEZE
                                  else bool(o["fast_fill"]),  # W242, W255
                                  ap_above_mean=bool(o["ap_above_mean"]) and not realtime,  # W29, W265: offline
                                  turn_bridge=not realtime and (TURN_BRIDGE_SIDE  # W374: offline; W384
                                                                if o["turn_bridge"] == TURN_BRIDGE_SIDE
                                                                else bool(o["turn_bridge"])),
                                  parity_fill="within" if o["parity_fill"] == "within" else bool(o["parity_fill"]))


def _model_options(o: dict, realtime: bool) -> dict:
    """The step-length model's options from the track's options ``o`` (W111 / W122's ``pause_steps`` off in
    realtime; W134's ``"standing"`` applied there too, decision W165; W56's smoothing checked)."""
    return {"merge_fragments": bool(o["merge_fragments"]),
            "length_smoothing": check_length_smoothing(o["length_smoothing"]),
            "pause_steps": o["pause_steps"] if not realtime or o["pause_steps"] == CAUSAL_PAUSE_STEPS else False}


def _pendulum_steps(imu: WaistIMU, p: WaistParams, thr: float, o: dict) -> pd.DataFrame:
    """Decision W139: the steps ``waist-pendulum`` would read from ``imu`` with the parameters ``p`` (its offline
    contact detector and the pendulum step length, seed 003 eq. 1) under the track's options ``o`` and motion gate
    ``thr``; the vetoes and gap cuts of a pendulum track are not applied (a plausibility reading, not a track)."""
    det = _contact_detector(o, thr, False).detect(imu)  # E102: the track's options, W131's among them
    model = get_step_length("pendulum")
    _configure_model(model, "pendulum", False, _model_options(o, False))
    return _step_lengths(det.steps_, imu, p, model, thr)


RELATIVE_HEADING = "waist heading relative to the start"


class _NoHeadingNote(logging.Filter):
    """Drops W83's line from this module's log: a calibration tracks walks for their distance, not their heading;
    W155's, which advises a track's option (a calibration walk's stairs are the calibration's to judge); and the
    "no per-user calibration" line (B241: it is the calibration being made); decision W455: W100's walk-ratio line
    and W207's short-step line, whose advice (calibrate on this walker's own walk) is the calibration being made."""

    def filter(self, record: logging.LogRecord) -> bool:
        msg = record.getMessage()
        return not any(mark in msg for mark in (RELATIVE_HEADING, "(decision W155)", NO_CALIBRATION,
                                                WALK_RATIO_NEED, SHORT_STEP_CAUSE))


def without_heading_note():
    """Context manager: :func:`track_waist` calls inside it do not log W83's or W155's line (``calibrate``'s
    walks)."""
    from contextlib import contextmanager

    @contextmanager
    def ctx():
        f = _NoHeadingNote()
        log.addFilter(f)
        try:
            yield
        finally:
            log.removeFilter(f)
    return ctx()


def relative_heading_note(start, initial_heading: float, has_magnetometer: bool, method: str = "gyro") -> str | None:
    """Decision W83: the one line saying a waist track's heading is relative to the start (no compass: W5), when
    the start direction was not given, and that a recorded wMagneticField.csv is not used; None otherwise.
    Decision W390: it names the reference of the heading ``method``: the gyro heading's 0 is the first walk's
    direction; a harmonic heading's (``ahe``, waist-pll's default) the unit's initial facing."""
    given = bool(initial_heading) or (isinstance(start, dict) and "heading_rad" in start)
    if given and not has_magnetometer:
        return None
    if method == "gyro":
        zero = "0 = the direction of the first walk"
    else:  # W390: a yawed unit (a phone on the belt, in a pocket) turns the whole path
        zero = ("0 = the unit's initial facing, not the walking direction: the harmonic heading turns the whole "
                "path by the unit's yaw on the body, where waist-pendulum's gyro heading starts at the first walk's "
                "direction (decision W390)")
    line = (f"{RELATIVE_HEADING} ({zero}, drawn as east); give the start direction with "
            "--initial-heading DEG (initial_heading= rad in Python)" if not given else
            f"{RELATIVE_HEADING}, turned by the start direction given")
    if has_magnetometer:
        line += ("; wMagneticField.csv is not used: the waist pipelines have no compass heading (decision W5), "
                 "so take the start direction from the phone's compass yourself")
    return line


def no_steps_message(thr: float, sigma: np.ndarray, source: str, fix: str | None = None, n_contacts: int = 0) -> str:
    """Decision W76: the one line of a waist track that found no step - the motion gate (threshold and where it
    comes from), the largest 2 s SD of the vertical acceleration the data reached, and the fix (``fix``: the
    caller's own first remedy instead of the params JSON, e.g. the ``pll`` step detector's option, steps 48).
    ``n_contacts``: the isolated contacts a track's headline counts (decision W312: named, so that "N steps" and
    "no steps found" do not contradict)."""
    top = float(np.nanmax(sigma)) if np.size(sigma) else 0.0
    opened = "never opened" if top < thr else "opened but no step was found in it"
    suggest = max(K.RELATIVE_GATE_FLOOR_MPS2, round(0.5 * top, 2))
    src = {"params": "the params' walk_threshold_mps2", "relative": "decision W76's session-relative gate"}.get(
        source, "decision W4's fixed gate")
    lone = (f" (the {n_contacts} contact(s) counted are isolated, none followed by another within {MAX_STEP_S:g} s:"
            " no step between them and no distance)" if n_contacts else "")
    return (f"no steps found{lone}: the walking gate (2 s SD of the vertical acceleration >= {thr:.2f} m/s^2, {src}) "
            f"{opened}; the data's largest 2 s SD is {top:.2f} m/s^2. If the person walked with little trunk "
            f"movement (walking aid, rollator, very slow), "
            + (fix or f"pass a params JSON with {{\"walk_threshold_mps2\": {suggest:.2f}}} ('pdrlearn track DIR "
               "--params P.json'; docs/waist.md)") + ", or try 'pdrlearn steps DIR --detector pelvic-gyro'")


#: the columns of a waist steps table (the pendulum's; the PLL's lacks h_m and merged)
_STEP_COLUMNS = {"start_s": float, "end_s": float, "event_s": float, "unit": "string", "confidence": float,
                 "fc_s": float, "has_next": bool, "h_m": float, "merged": bool, "length_m": float,
                 "frequency_hz": float, "dyaw_rad": float, "heading_rad": float, "turning": "int64",
                 "mean_rate_rps": float, "stairs": bool}


def no_walking_message(walk_s: float, outcome: str) -> str:
    """The one warning line of decision W61 (a waist unit without a declared frame that walks less than the
    frame inference needs); ``outcome`` says what the command reports instead (e.g. "0 steps, 0 m")."""
    from pdrlearn.track.frame_inference import MIN_WALK_S

    return (f"no walking to track: {walk_s:.0f} s of walking (under {MIN_WALK_S:g} s, too little to infer the axis "
            f"frame): {outcome}; if the recording does walk, add the waist \"frames\" entry to meta.json (or "
            "'pdrlearn import --frames')")


def _no_walking(session: Session, pipeline: str, p: WaistParams, o: dict, warnings: list[str], walk_s: float,
                start, initial_heading: float) -> TrackResult:
    """Decision W61: a recording without a declared waist frame whose data walks less than the frame inference
    needs (``walk_s`` < 4 s): an empty track (0 steps, 0 m) with one warning, instead of an error asking for the
    frame of a recording with nothing to track."""

    cols = {k: v for k, v in _STEP_COLUMNS.items() if pipeline == "waist-pendulum" or k not in ("h_m", "merged")}
    steps = pd.DataFrame({k: pd.Series(dtype=v) for k, v in cols.items()})
    acc = session.require("wAccelerometer", purpose="a lower-back track")
    warnings = [*warnings, no_walking_message(walk_s, "0 steps, 0 m")]
    info = {"pipeline": pipeline, "method": "", "methods": {}, "params": p.to_dict(), "params_source": p.source,
            "options": o, "warnings": warnings, "n_contacts": 0, "rate_hz": float(acc.rate_hz),
            "no_walking": True, "freezes": lower_back_freezes(session, pipeline, o),  # W216: opt-in
            "postures": []}  # decision W222: no walking upright, so every instant's posture is unknown
    for w in warnings:
        log.warning("%s: %s", session.where, w)
    return _result(steps, start, initial_heading, info, float(acc.t[0]))


def trunk_events(session: Session) -> TrackResult:
    """Decision W428: what W418's two-unit TUG reads of ``session``'s lower-back unit, as the default offline
    waist-pendulum track (``get_pipeline("waist-pendulum")(session)``, its defaults and PARAMS.json-free options)
    reads it: ``info["transfers"]`` (W182 / W245 / W278's rows, None without an upright: W277), ``info["postures"]``
    (W222's runs, the same track's; W586: the two-unit track's posture split), ``info["yaw_turns"]`` (L210) and
    ``steps``' ``start_s``, ``end_s``, ``event_s`` (the contacts after every veto and B11's gap cut).
    The same :func:`track_waist` code stopped there: no step length, heading, altitude, ride or plausibility check
    is computed, no trajectory is made, and the track's own warning lines are not logged (W418 keeps none of the inner
    track's)."""
    return _track_waist(session, "waist-pendulum", None, None, dict.fromkeys(OPTION_DEFAULTS), None, None,
                        trunk_only=True)


def _check_waist_keywords(pipeline: str, opts: dict) -> None:
    """A misspelled keyword is a TypeError naming the closest valid one (decision L43)."""
    if opts:
        check_keywords(pipeline, opts, ["model", "start", "params",
                                        *keyword_names(track_waist, exclude=("pipeline", "params", "start"))])


@register_pipeline("waist-pll")
def waist_pll(session: Session, *, model=None, start=None, params=None, **opts) -> TrackResult:
    """Seed 000 pipeline: PLL steps, step length linear in frequency, A-HE heading (``heading="ellipse"``
    for the seed 001 closed form). ``model`` is unused (no step classifier). Other keyword arguments: those of
    :func:`track_waist`."""
    _check_waist_keywords("waist-pll", opts)
    return track_waist(session, pipeline="waist-pll", params=params, start=start, **opts)


@register_pipeline("waist-pendulum")
def waist_pendulum(session: Session, *, model=None, start=None, params=None, **opts) -> TrackResult:
    """Seed 003 pipeline: IC/FC from waist acceleration (``realtime=True`` for the causal variant),
    inverted-pendulum step length, gyroscope heading on turning strides. ``model`` is unused (no step
    classifier). Other keyword arguments: those of :func:`track_waist`."""
    _check_waist_keywords("waist-pendulum", opts)
    return track_waist(session, pipeline="waist-pendulum", params=params, start=start, **opts)


__all__ = ["track_waist", "waist_pll", "waist_pendulum", "WaistParams"]
