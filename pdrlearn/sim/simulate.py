"""Simulate a PLASYS session (foot + waist unit) with ground truth, from a path or a thesis scenario."""

from __future__ import annotations

import dataclasses
import logging
import math
import zlib
from dataclasses import asdict

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.io.frames import THESIS_FOOT_FRAME, THESIS_WAIST_FRAME
from pdrlearn.io.session import Session, Stream
from pdrlearn.kernels.barometer import STANDARD_P0_HPA, pressure_hpa  # one formula: simulator and tracker (W89)
from pdrlearn.sim import sensors as sn
from pdrlearn.sim.body import (
    BOUNCE_MODES,
    CONTACT_MODES,
    HEEL_OFF_FRACTION,
    LOAD_FRACTION,
    PELVIS_MODES,
    ROCKER_MODES,
    STANCE_TIME_ASYMMETRY_MAX,
    STEP_TIME_ASYMMETRY_MAX,
    TRUNK_ACC_SD,
    TRUNK_RATE_SD,
    Events,
    foot_loads,
    foot_pose,
    pelvis_knots,
    pelvis_pose,
    realistic_pelvis,
    schedule,
    step_heights,
    step_lengths,
    trunk_vibration_source,
)
from pdrlearn.sim.cycle import cycle_foot, cycle_loads, cycle_pelvis
from pdrlearn.sim.freeze import FreezeEpisode, freeze_foot, freeze_loads, freeze_pelvis, freeze_table
from pdrlearn.sim.kernels import (
    angular_rate_body,
    block_mean,
    earth_field_enu,
    specific_force_body,
)
from pdrlearn.sim.lying import LyingEpisode, lying_angles, lying_rotation, lying_table, roll_table
from pdrlearn.sim.path import Footstep, Segment, Stairs, plan_footsteps
from pdrlearn.sim.ride import Ride, ride_offset, ride_table
from pdrlearn.sim.scenarios import SCENARIOS
from pdrlearn.sim.spin import SpinEpisode, spin_carry, spin_table
from pdrlearn.sim.transfer import (
    TRANSFER_S,
    TRANSFER_TIME_RANGE_S,
    session_sit_starts,
    session_sits,
    transfer_motion,
    transfer_starts,
    transfer_table,
)
from pdrlearn.sim.trunk_jerks import JERK_DEG, JERK_M, check_jerk_options, draw_jerks, jerk_pose, jerk_table
from pdrlearn.sim.user import PROSTHETIC_FOOT_FIELDS, SPEEDS, UserProfile, side_foot
from pdrlearn.sim.vehicle import VehicleRide, vehicle_carry

log = logging.getLogger(__name__)

INTERNAL_RATE_HZ = 100.0  # sensor output data rate (thesis ch.4.2.1.1-2)
OVERSAMPLE = 5  # pose grid at 500 Hz, averaged to the 100 Hz samples
#: decision S44: the 500 Hz poses are built in parts of this many samples (~2 min; a part's poses ~60 MB at most)
FINE_CHUNK = 60_000
STAND_MARGIN_S = 0.2  # added to the standstills so that they last at least ``stand_s`` in every sensor
#: decision S42: ``step_length_asymmetry`` must be below this (symmetry ratio 2, as S35's step times): beyond, the
#: short step is less than a third of the stride (2 / (1 + r) < 2 / 3)
STEP_LENGTH_ASYMMETRY_MAX = 1.0
TERRAIN_DZ_M = 0.08  # |height change| of a stride above which it is a stair stride (about half a rise)

#: Realism knobs of :func:`simulate` / :func:`simulate_path` and their defaults.
KNOBS: dict[str, object] = {
    "variability": 1.0,  # scale of the user's stride-to-stride variability (0 = identical strides)
    "irregular_rate": 0.0,  # fraction of irregular (short, slow, low-clearance) steps
    "clock_offset_s": 0.0,  # waist clock = foot clock * (1 + drift) + offset
    "clock_drift_ppm": 0.0,
    "drop_rate": 0.0,  # fraction of foot-unit packets lost on the Bluetooth link
    "noise": True,  # sensor noise, biases, quantisation (False: exact physics)
    "stand_s": 5.0,  # standstill before the first and after the last movement (thesis ch.8: 5 s)
    "heading0_deg": 0.0,  # initial heading, ENU (0 = east, counter-clockwise)
    "mag_field_ut": 45.0,  # Earth field magnitude (uT)
    "mag_inclination_deg": 55.0,
    "mag_declination_deg": 0.0,
    "mag_disturbance_ut": 3.0,  # sd of the indoor field disturbances
    "baro_drift_hpa_per_h": 0.3,  # sd of the weather drift slope
    "length_m": 1000.0,  # scenario "walk" only: path length
    "foot_mount_pitch_deg": 0.0,  # extra toes-down tilt of the foot unit (e.g. 50 for an instep mount)
    # decision S113: a sideways tilt of the foot unit about the foot's forward axis (deg; + lifts its left edge)
    "foot_mount_roll_deg": 0.0,
    # the waist unit turned on the belt: a rotation vector (deg) about the body's forward, left and up axes, on top
    # of the user's few-degree misalignment; meta.json's frame stays the belt's (decision S34)
    "waist_mount_deg": (0.0, 0.0, 0.0),
    # decision S117: the mount at the last sample (a rotation vector, deg, as waist_mount_deg): the unit turns at a
    # constant rate from waist_mount_deg at the first sample; None: a fixed mount
    "waist_mount_end_deg": None,
    # decision S123: the waist unit re-clipped at once: (t_s, rotation vector deg as waist_mount_deg) - at t_s (foot
    # clock) the unit turns within 0.5 s from waist_mount_deg to the new mount; None: no re-clip
    "waist_reclip": None,
    # decision S121: a slope's steps shortened / lengthened and slowed by its grade (Tobler 1993; False: level steps)
    "graded_slopes": False,
    # decision S122: the cadence falls linearly over the session's steps by this percent (0-50; 0: none)
    "fatigue_pct": 0.0,
    "device_errors": True,  # accelerometer scale factors per unit (the user's own), not per session (S22)
    "pelvis": "model",  # "realistic": roll toward the stance side and a smaller sway, drawn per user (S27)
    "bounce": "constant",  # "pendulum": the pelvis bounce scales with the step length (S29); "population": S74
    # decision W612: the gait oscillations' envelope over a bout - "step" (fading in and out across the edge steps) or
    # "contact" (full amplitude from the bout's first contact to its last, as the real lower back, W611)
    "bout_envelope": "step",
    "rocker": "hermite",  # "smooth": a heel rocker that comes to rest gradually, no second |acc| peak (S31)
    "contact": "heel",  # "forefoot": level steps land on the forefoot, no heel rocker (a toe walker, S108)
    # decision S109: the foot unit's distance from the heel as a share of the foot length (None: the user's own draw,
    # 25-50 %; up to 0.85 for a unit on the forefoot dorsum)
    "foot_sensor_pos": None,
    # decision S112: the foot unit's height above the sole (m; None: the user's own draw, 0.03-0.07)
    "foot_sensor_height_m": None,
    # decision S109: crouch-like pelvis - the waist unit's standing height (m; None: the user's, 0.55-0.6 x height)
    # and a factor on the user's pelvis bounce (1 = the user's; under 1 damped)
    "pelvis_height_m": None,
    "bounce_scale": 1.0,
    # hemiparetic gait: the steps onto the left foot are 1 + this times the right foot's, same cadence (S35)
    "step_time_asymmetry": 0.0,
    # step-length asymmetry: the steps onto the left foot are 1 + this times the right's, same stride length (S42)
    "step_length_asymmetry": 0.0,
    # decision S94: the paretic_side foot's stance fraction is the user's / (1 + this), the step times unchanged
    "stance_time_asymmetry": 0.0,
    # the session starts seated this long (s), then stands up; and / or ends seated after sitting down (S43)
    "sit_start_s": 0.0,
    "sit_end_s": 0.0,
    # the foot that carries the foot unit: "right" (S1) or "left" - the same walk, the other foot (S54)
    "instrumented_foot": "right",
    # the foot whose steps the two asymmetries lengthen: "left" (S35, S42) or "right" (S55)
    "paretic_side": "left",
    # decision S120: the foot whose stance stance_time_asymmetry leaves the longer (None: the one not paretic_side)
    "longer_stance_side": None,
    # decision S119: a one-sided (prosthetic) foot, "left" or "right", with its own toe-off pitch (deg), heel-strike
    # pitch (deg) and impact speed (m/s) in place of the user's (None: the user's; sim.user.PROSTHETIC_FOOT_FIELDS)
    "prosthetic_side": None,
    "prosthetic_toe_off_pitch_deg": None,
    "prosthetic_heel_strike_pitch_deg": None,
    "prosthetic_impact_speed_mps": None,
    # decision S83: data gaps (a battery swap): (unit, start_s, duration_s) per gap, unit foot, waist or both
    "gaps": (),
    # decision S95: the range (s) of each sit-down's / stand-up's duration (sim.transfer.TRANSFER_S by default)
    "transfer_s": TRANSFER_S,
    # decision S110: the gyroscopes' bias drift a first-order Gauss-Markov process of this correlation time (s),
    # bounded; None: S12's unbounded random walk
    "gyro_bias_tau_s": None,
    # decision S114: involuntary trunk jerks (chorea-like) of the waist unit: jerks per second, peak tilt range (deg)
    # and vertical bump range (m); 0 = none (sim.trunk_jerks)
    "trunk_jerk_rate_hz": 0.0,
    "trunk_jerk_deg": JERK_DEG,
    "trunk_jerk_m": JERK_M,
}
#: decision S83: the units a gap may name
GAP_UNITS = ("foot", "waist", "both")
#: knobs meta.json records only when set (default sessions' meta.json as before they existed: S27, S29, S31, S34, S35)
META_ONLY_WHEN_SET = ("pelvis", "bounce", "waist_mount_deg", "waist_mount_end_deg", "rocker", "contact",
                      "bout_envelope",  # decision W612
                      "waist_reclip", "graded_slopes", "fatigue_pct",  # decisions S121-S123
                      "foot_sensor_pos", "foot_sensor_height_m", "foot_mount_roll_deg",
                      "pelvis_height_m", "bounce_scale", "step_time_asymmetry", "step_length_asymmetry",
                      "stance_time_asymmetry", "sit_start_s", "sit_end_s", "instrumented_foot", "paretic_side", "gaps",
                      "longer_stance_side", "prosthetic_side", *PROSTHETIC_FOOT_FIELDS,  # decisions S119, S120
                      "transfer_s", "gyro_bias_tau_s", "trunk_jerk_rate_hz", "trunk_jerk_deg", "trunk_jerk_m")
#: decisions S54, S55: the values of the two foot-side knobs
FEET = ("left", "right")


#: decision S76 (amended after review R1): the largest variability scale - 10x the user's own stride-to-stride CV
#: (2-3.5 % at 1, so 20-35 %: beyond the step-time CVs of pathological gait); at 100 a 20 m route walked 36.6 m and
#: 1e9 overflowed and hung (R1)
VARIABILITY_MAX = 10.0


NON_NEGATIVE_KNOBS = (
    "variability",
    "irregular_rate",
    "drop_rate",
    "stand_s",
    "mag_disturbance_ut",
    "length_m",
    "baro_drift_hpa_per_h",
    "sit_start_s",
    "sit_end_s",
)


def _rng(*parts: object) -> np.random.Generator:
    ints = [p if isinstance(p, int) else zlib.crc32(str(p).encode()) for p in parts]
    return np.random.default_rng(ints)


def check_gaps(gaps, *, option: str | None = None) -> tuple[tuple[str, float, float], ...]:
    """Decisions S83, B370: ``gaps`` as ``((unit, start_s, duration_s), ...)``, each unit foot, waist or both, a start
    > 0 and a duration > 0 (s, finite), sorted by start; one line naming the bad one and the fix. ``option``: the
    CLI option (``--gap``) whose ``UNIT:START:DURATION`` texts, split at ``:``, the gaps are; the line names the
    option's text and form (the CLI parses only the syntax: one message, this one)."""
    if not isinstance(gaps, list | tuple) and gaps is not None:  # gaps=5 was a TypeError traceback (review R4)
        raise DataError(f"simulate: gaps={gaps!r}: give a list of (unit, start_s, duration_s), e.g. "
                        "[('foot', 600, 120)] (decision B370)")
    shape = (f"UNIT:START:DURATION, e.g. {option} foot:600:120" if option else
             "(unit, start_s, duration_s), e.g. ('foot', 600, 120)")
    out = []
    for g in gaps or ():
        try:
            name = f"{option} {':'.join(map(str, g))!r}" if option else f"gap {g!r}"
        except TypeError:  # not a sequence (review R1 of session 37)
            name = f"{option} {g!r}" if option else f"gap {g!r}"
        try:
            unit, start, dur = g
            start, dur = float(start), float(dur)
        except (TypeError, ValueError):
            raise DataError(f"simulate: {name}: give {shape} (decision B370)") from None
        if unit not in GAP_UNITS or not (math.isfinite(start) and start > 0) or not (math.isfinite(dur) and dur > 0):
            raise DataError(f"simulate: {name}: the unit must be one of {', '.join(GAP_UNITS)}, the start a time > "
                            f"0 s and the duration > 0 s{f'; give {shape}' if option else ''} (decision B370)")  # B384
        out.append((str(unit), start, dur))
    return tuple(sorted(out, key=lambda g: g[1]))


def check_gaps_inside(t: np.ndarray, gaps) -> None:
    """Decisions B370, L548: every gap leaves samples (times ``t``, s, the output grid) before and after it, else one
    line - checked as soon as the recording's length is known, before the sensors are simulated (a 107 min march
    had said so only after 1 min 40 s). A gap that runs to the end is a unit that stops for good: the line says
    how to make one."""
    for g_unit, start, dur in gaps or ():
        if not (t[0] < start and start + dur < t[-1]):
            stops = t[0] < start < t[-1] <= start + dur
            raise DataError(f"simulate: gap {g_unit}:{start:g}:{dur:g} does not lie inside the recording (0-"
                            f"{t[-1]:.1f} s) with samples before and after it; start it later or shorten it "
                            "(decision B370)" + (
                                "; for a unit that stops for good (a battery that dies) simulate without the gap "
                                "and cut that unit's sensor files at the time (docs/localization.md, \"A unit that "
                                "stops early\", decision L548)" if stops else ""))


def _gap_keep(t: np.ndarray, gaps, unit: str) -> np.ndarray:
    """Decision S83: the samples (times ``t`` on the foot clock) of ``unit`` outside its gaps; a gap must leave
    samples before and after it (one line, decision B370; :func:`check_gaps_inside`)."""
    keep = np.ones(len(t), dtype=bool)
    check_gaps_inside(t, gaps)
    for g_unit, start, dur in gaps:
        if g_unit not in (unit, "both"):
            continue
        keep &= ~((t >= start - 1e-9) & (t < start + dur - 1e-9))  # start <= t < end, t's rounding aside
    return keep


def _check_knobs(knobs: dict) -> dict:
    """Merge ``knobs`` with the defaults, failing with one line on unknown names or bad values."""
    unknown = sorted(set(knobs) - set(KNOBS))
    if unknown:
        raise DataError(f"simulate: unknown option(s) {', '.join(unknown)}; valid: {', '.join(KNOBS)}")
    out = {**KNOBS, **knobs}
    for k in ("noise", "device_errors", "graded_slopes"):  # S121
        if not isinstance(out[k], bool | np.bool_):
            raise DataError(f"simulate: {k}={out[k]!r} must be True or False")
    if out["pelvis"] not in PELVIS_MODES:
        raise DataError(f"simulate: pelvis={out['pelvis']!r} must be one of {', '.join(PELVIS_MODES)}")
    if out["bounce"] not in BOUNCE_MODES:
        raise DataError(f"simulate: bounce={out['bounce']!r} must be one of {', '.join(BOUNCE_MODES)}")
    for k in ("instrumented_foot", "paretic_side", "longer_stance_side", "prosthetic_side"):  # S54, S55, S119, S120
        if out[k] not in FEET and (out[k] is not None or k in ("instrumented_foot", "paretic_side")):
            raise DataError(f"simulate: {k}={out[k]!r} must be 'left' or 'right'")
    check_prosthetic_foot(out)  # decision S119
    if out["bout_envelope"] not in ("step", "contact"):  # decision W612
        raise DataError(f"simulate: bout_envelope={out['bout_envelope']!r} must be 'step' or 'contact'")
    if out["rocker"] not in ROCKER_MODES:
        raise DataError(f"simulate: rocker={out['rocker']!r} must be one of {', '.join(ROCKER_MODES)}")
    if out["contact"] not in CONTACT_MODES:  # decision S108
        raise DataError(f"simulate: contact={out['contact']!r} must be one of {', '.join(CONTACT_MODES)}")
    tau = out["gyro_bias_tau_s"]  # decision S110
    if tau is not None and (isinstance(tau, bool) or not isinstance(tau, int | float | np.number)
                            or not math.isfinite(tau) or tau <= 0):
        raise DataError(f"simulate: gyro_bias_tau_s={tau!r} must be a positive number of seconds (the bias drift's "
                        "correlation time), or None for S12's random walk")
    out["foot_sensor_pos"] = check_foot_sensor_pos(out["foot_sensor_pos"])  # decision S109
    out["foot_sensor_height_m"] = check_foot_sensor_height(out["foot_sensor_height_m"])  # decision S112
    if not (isinstance(out["foot_mount_roll_deg"], int | float) and -90 <= out["foot_mount_roll_deg"] <= 90):  # S113
        raise DataError(f"simulate: foot_mount_roll_deg={out['foot_mount_roll_deg']!r} must be -90 to 90 degrees (a "
                        "sideways tilt of the foot unit; beyond 90 it would lie on its side upside down)")
    ph = out["pelvis_height_m"]  # decision S109: checked against the user's leg in simulate_path
    if ph is not None and (isinstance(ph, bool) or not isinstance(ph, int | float | np.number)
                           or not math.isfinite(ph) or ph <= 0):
        raise DataError(f"simulate: pelvis_height_m={ph!r} must be a positive number of metres (the waist unit's "
                        "standing height), or None for the user's own")
    if isinstance(out["bounce_scale"], int | float) and not isinstance(out["bounce_scale"], bool) and not (
            0.0 <= out["bounce_scale"] <= BOUNCE_SCALE_MAX):
        raise DataError(f"simulate: bounce_scale={out['bounce_scale']!r} must be 0 to {BOUNCE_SCALE_MAX:g} (1 = the "
                        "user's own pelvis bounce, 0.5 = half of it)")
    out["waist_mount_deg"] = _check_rotvec("waist_mount_deg", out["waist_mount_deg"])
    if out["waist_mount_end_deg"] is not None:  # decision S117
        out["waist_mount_end_deg"] = _check_rotvec("waist_mount_end_deg", out["waist_mount_end_deg"])
    out["waist_reclip"] = check_reclip(out["waist_reclip"], out["waist_mount_end_deg"])  # decision S123
    fat = out["fatigue_pct"]  # decision S122
    if isinstance(fat, bool) or not isinstance(fat, int | float | np.number) or not 0 <= fat <= 50:
        raise DataError(f"simulate: fatigue_pct={fat!r} must be 0 to 50 (the percent the walking speed falls by over "
                        "the session; decision S122)")
    out["gaps"] = check_gaps(out["gaps"])  # decisions S83, B370
    out["transfer_s"] = check_transfer_s(out["transfer_s"])  # decision S95
    out["trunk_jerk_rate_hz"], out["trunk_jerk_deg"], out["trunk_jerk_m"] = check_jerk_options(  # decision S114
        out["trunk_jerk_rate_hz"], out["trunk_jerk_deg"], out["trunk_jerk_m"])
    for k, default in KNOBS.items():
        v = out[k]
        if isinstance(default, bool | str | tuple) or default is None:  # None: checked above (S109, S112)
            continue
        if isinstance(v, bool) or not isinstance(v, int | float | np.number) or not math.isfinite(v):
            raise DataError(f"simulate: {k}={v!r} must be a finite number")
        if k in NON_NEGATIVE_KNOBS and v < 0:
            raise DataError(f"simulate: {k}={v!r} must be >= 0")
    if out["variability"] > VARIABILITY_MAX:  # decision S76 (R1)
        raise DataError(f"simulate: variability={out['variability']!r} must be <= {VARIABILITY_MAX:g} (1 = the "
                        "user's own stride-to-stride variability)")
    if out["irregular_rate"] > 1 or out["drop_rate"] >= 0.5:
        raise DataError("simulate: irregular_rate must be <= 1 and drop_rate < 0.5")
    if not 0 < out["mag_field_ut"] < 1000 or not -90 <= out["mag_inclination_deg"] <= 90:
        raise DataError("simulate: mag_field_ut must be in (0, 1000) uT and mag_inclination_deg in [-90, 90]")
    if not 0 <= out["step_time_asymmetry"] < STEP_TIME_ASYMMETRY_MAX:  # decision S35
        raise DataError(f"simulate: step_time_asymmetry={out['step_time_asymmetry']!r} must be >= 0 and < "
                        f"{STEP_TIME_ASYMMETRY_MAX:g} (0.39 = the left foot's steps 39 % longer than the right's; "
                        "paretic_side='right' for the right foot's)")
    if not 0 <= out["stance_time_asymmetry"] < STANCE_TIME_ASYMMETRY_MAX:  # decision S94
        raise DataError(f"simulate: stance_time_asymmetry={out['stance_time_asymmetry']!r} must be >= 0 and < "
                        f"{STANCE_TIME_ASYMMETRY_MAX:g} (0.1: the paretic_side foot's stance fraction / 1.1)")
    if not 0 <= out["step_length_asymmetry"] < STEP_LENGTH_ASYMMETRY_MAX:  # decision S42
        raise DataError(f"simulate: step_length_asymmetry={out['step_length_asymmetry']!r} must be >= 0 and < "
                        f"{STEP_LENGTH_ASYMMETRY_MAX:g} (0.1 = the left foot's steps 10 % longer)")
    return out


def check_prosthetic_foot(opt: dict, *, options: dict | None = None) -> None:
    """Decision S119: the one-sided foot's knobs (:data:`pdrlearn.sim.user.PROSTHETIC_FOOT_FIELDS`) each None or a
    finite number in its range, given with ``prosthetic_side`` and ``prosthetic_side`` with at least one of them;
    one line otherwise. ``options``: knob -> the CLI option to name in the line (the knob's name without it)."""
    def name(k: str) -> str:
        return (options or {}).get(k, k)

    given = [k for k in PROSTHETIC_FOOT_FIELDS if opt.get(k) is not None]
    for k in given:
        lo, hi = PROSTHETIC_FOOT_FIELDS[k][1]
        v = opt[k]
        if isinstance(v, bool) or not isinstance(v, int | float | np.number) or not (
                math.isfinite(v) and lo <= v <= hi):
            raise DataError(f"simulate: {name(k)} {v!r}: give a number from {lo:g} to {hi:g} (decision S119)")
    if given and opt.get("prosthetic_side") is None:
        raise DataError(f"simulate: {name(given[0])} sets one foot's own value: give the foot with "
                        f"{name('prosthetic_side')} left or right (decision S119)")
    if opt.get("prosthetic_side") is not None and not given:
        raise DataError(f"simulate: {name('prosthetic_side')} {opt['prosthetic_side']} names a foot with no value of "
                        f"its own: give {', '.join(name(k) for k in PROSTHETIC_FOOT_FIELDS)} (decision S119)")


def _check_rotvec(name: str, mount) -> tuple[float, float, float]:
    """Decisions S34, S117: a mount knob as three finite floats (a rotation vector, deg); one line otherwise."""
    try:
        ok = len(mount) == 3 and all(math.isfinite(float(v)) and not isinstance(v, bool) for v in mount)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise DataError(f"simulate: {name}={mount!r} must be three finite numbers (a rotation vector, deg)")
    return tuple(float(v) for v in mount)


#: decision S109: the foot unit's position range, a share of the foot length from the heel: the user draws 0.25-0.50
#: (the instep / mid-dorsum, S1); a forefoot-dorsum unit sits over the metatarsals, short of the ball's 0.72 and the
#: toes (ours: past 0.85 the strap would be on the toes, which bend at push-off and the rigid foot does not model)
FOOT_SENSOR_POS_RANGE = (0.05, 0.85)
#: decision S112: the foot unit's height above the sole (m) a session may give: the user draws 0.03-0.07 (S19, beside
#: the heel to the instep); from a unit in the insole (0.01) to a strap at the top of a high shoe (0.15; ours, no
#: value from a document)
FOOT_SENSOR_HEIGHT_RANGE_M = (0.01, 0.15)


#: decision S109: the waist unit's standing height a session may give, as a share of the user's leg length (ours):
#: a drawn user stands it at 1.04-1.13 legs (0.55-0.6 x height over a 0.53 x height leg); crouch lowers it, and
#: under half a leg is a squat, not a walk
PELVIS_HEIGHT_LEGS = (0.5, 1.2)
#: decision S109: the largest bounce_scale (ours: 3 x a 3-4.5 cm bounce is 9-13.5 cm, past any walking bounce)
BOUNCE_SCALE_MAX = 3.0


def body_placement(user: UserProfile, opt: dict) -> UserProfile:
    """Decisions S109, S112: the user with the session's ``foot_sensor_pos``, ``foot_sensor_height_m``,
    ``pelvis_height_m`` and ``bounce_scale``
    (each when set), so meta.json's ``user`` records the body simulated; one ``DataError`` line for a pelvis height
    outside :data:`PELVIS_HEIGHT_LEGS` of the leg."""
    changes = {}
    if opt["foot_sensor_pos"] is not None:
        changes["foot_sensor_x_frac"] = round(float(opt["foot_sensor_pos"]), 4)
    if opt.get("foot_sensor_height_m") is not None:  # decision S112
        changes["foot_sensor_height_m"] = round(float(opt["foot_sensor_height_m"]), 4)
    if opt["pelvis_height_m"] is not None:
        lo, hi = (k * user.leg_length_m for k in PELVIS_HEIGHT_LEGS)
        if not lo <= float(opt["pelvis_height_m"]) <= hi:
            raise DataError(f"simulate: pelvis_height_m={opt['pelvis_height_m']!r} must be {lo:.2f}-{hi:.2f} m: "
                            f"{PELVIS_HEIGHT_LEGS[0]:g}-{PELVIS_HEIGHT_LEGS[1]:g} x this user's "
                            f"{user.leg_length_m:.2f} m leg (the user's own: {user.sensor_height_m:.2f} m)")
        changes["sensor_height_m"] = round(float(opt["pelvis_height_m"]), 4)
    if float(opt["bounce_scale"]) != 1.0:
        changes["pelvis_bounce_m"] = round(user.pelvis_bounce_m * float(opt["bounce_scale"]), 5)
    return dataclasses.replace(user, **changes) if changes else user


def _check_in_range(name: str, value, bounds: tuple[float, float], what: str) -> float | None:
    """A placement knob (decisions S109, S112): None (the user's own) or a finite number in ``bounds``; one
    ``DataError`` line naming ``name`` and ``what`` it must be otherwise."""
    if value is None:
        return None
    lo, hi = bounds
    ok = isinstance(value, int | float | np.number) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or not lo <= float(value) <= hi:
        raise DataError(f"simulate: {name}={value!r} must be {what} in [{lo:g}, {hi:g}] "
                        f"{_PLACEMENT_EXAMPLES[name]}; leave it out for the user's own")
    return float(value)


_PLACEMENT_EXAMPLES = {"foot_sensor_pos": "(0.45 mid-dorsum, 0.70 forefoot dorsum)",
                       "foot_sensor_height_m": "(0.06 on the instep, 0.08 on a raised strap)"}


def check_foot_sensor_pos(value) -> float | None:
    """Decision S109: ``foot_sensor_pos`` as a share of the foot length in :data:`FOOT_SENSOR_POS_RANGE`, or None
    (the user's own); one ``DataError`` line otherwise."""
    return _check_in_range("foot_sensor_pos", value, FOOT_SENSOR_POS_RANGE, "a share of the foot length from the heel")


def check_foot_sensor_height(value) -> float | None:
    """Decision S112: ``foot_sensor_height_m``, the foot unit's height above the sole (m) in
    :data:`FOOT_SENSOR_HEIGHT_RANGE_M`, or None (the user's own); one ``DataError`` line otherwise."""
    return _check_in_range("foot_sensor_height_m", value, FOOT_SENSOR_HEIGHT_RANGE_M,
                           "the foot unit's height above the sole in metres")


def check_transfer_s(value) -> tuple[float, float]:
    """Decision S95: ``transfer_s`` as ``(lo, hi)`` seconds, ``lo <= hi``, both in
    :data:`~pdrlearn.sim.transfer.TRANSFER_TIME_RANGE_S`; one ``DataError`` line otherwise."""
    lo_ok, hi_ok = TRANSFER_TIME_RANGE_S
    try:
        lo, hi = (float(v) for v in value)
        ok = not any(isinstance(v, bool) for v in value) and lo_ok <= lo <= hi <= hi_ok
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise DataError(f"simulate: transfer_s={value!r} must be two durations LO <= HI in seconds, {lo_ok:g} to "
                        f"{hi_ok:g} (e.g. (3, 6) for a frail person's sit-to-stand; default {TRANSFER_S})")
    return lo, hi


def _output_factor(rate_hz: float) -> int:
    k = INTERNAL_RATE_HZ / float(rate_hz) if rate_hz and rate_hz > 0 else float("nan")
    if not math.isfinite(k) or abs(k - round(k)) > 1e-9 or round(k) < 1:
        raise DataError(
            f"rate {rate_hz!r} Hz: the simulator averages 100 Hz samples in whole blocks; "
            "use 100 Hz divided by an integer (100, 50, 25, 20, 10 ...)"
        )
    return int(round(k))


def _misalignment(deg: list[float]) -> np.ndarray:
    return Rotation.from_rotvec(np.radians(deg)).as_matrix()


def check_reclip(reclip, mount_end) -> tuple[float, tuple[float, float, float]] | None:
    """Decision S123: ``waist_reclip`` as ``(t_s, (x, y, z) deg)`` (a time > 0 s and a rotation vector as
    ``waist_mount_deg``), or None; one line on a bad value or with ``waist_mount_end_deg`` (S117's slide)."""
    if reclip is None:
        return None
    try:
        t_s, rot = reclip
        t_s = float(t_s)
    except (TypeError, ValueError):
        raise DataError(f"simulate: waist_reclip={reclip!r}: give (t_s, (x, y, z) deg), e.g. (600, (0, 20, 0)) "
                        "(decision S123)") from None
    if not (math.isfinite(t_s) and t_s > 0):
        raise DataError(f"simulate: waist_reclip's time {t_s!r} must be a time > 0 s (decision S123)")
    if mount_end is not None:
        raise DataError("simulate: waist_reclip (an abrupt re-clip) and waist_mount_end_deg (a slow slide) cannot be "
                        "combined; give one (decisions S117, S123)")
    return t_s, _check_rotvec("waist_reclip", rot)


def drifting_axes(t: np.ndarray, start_deg, end_deg, inner: np.ndarray, *, window: tuple[float, float] | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Decision S117: a unit whose mount turns at a constant rate from the rotation vector ``start_deg`` (deg, at
    ``t[0]``) to ``end_deg`` (at ``t[-1]``), both about the body axes as ``waist_mount_deg``, on top of ``inner``
    (the user's misalignment @ the declared frame). Returns the per-sample axes ``(n, 3, 3)`` (columns: the unit's
    axes in body coordinates, :func:`_to_sensor`'s ``mis @ frame``) and the turn's own angular rate in the unit's
    axes (rad/s, constant), which its gyroscope adds to the body's: with ``A = R(t) M`` and
    ``R(t) = R0 exp(s(t) [w]x)``, ``A^T dA/dt = [M^T w ds/dt]x``.

    ``window`` (decision S123): the turn runs from ``window[0]`` to ``window[1]`` (s) only - the mount fixed before
    and after - and the rate returned is per sample ``(n, 3)``, zero outside the window (an abrupt re-clip)."""
    r0 = Rotation.from_rotvec(np.radians(start_deg))
    w = (r0.inv() * Rotation.from_rotvec(np.radians(end_deg))).as_rotvec()  # the turn, in the start mount's axes
    t0, t1 = (float(t[0]), float(t[-1])) if window is None else window
    span = t1 - t0 if len(t) > 1 and t1 > t0 else 1.0
    s = np.clip((np.asarray(t, float) - t0) / span, 0.0, 1.0)
    axes = (r0 * Rotation.from_rotvec(s[:, None] * w[None, :])).as_matrix() @ inner
    rate = (w / span) @ inner
    if window is not None:
        rate = rate[None, :] * ((t >= t0) & (t < t1))[:, None]
    return axes, rate


def _to_sensor(v_body: np.ndarray, frame_matrix: np.ndarray, mis: np.ndarray) -> np.ndarray:
    """Body FLU vectors (n, 3) -> sensor axes of a unit declared with ``frame_matrix`` and rotated by ``mis``."""
    axes = mis @ frame_matrix  # columns: the sensor axes in body coordinates
    return v_body @ axes


def _stride_table(
    steps: list[Footstep], ev: Events, initial: dict, user: UserProfile, r_sensor: np.ndarray, foot: str = "right"
) -> pd.DataFrame:
    """One row per stride of ``foot``: mid-stance to mid-stance around each swing."""
    idx = [k for k, s in enumerate(steps) if s.foot == foot]
    rows = []
    h_a, y_a = initial[foot]
    prev_ff = None
    for j, k in enumerate(idx):
        st = steps[k]
        T = 2.0 * ev.step_s[k]
        gap = 0.5 * (HEEL_OFF_FRACTION - LOAD_FRACTION) * T  # half the foot-flat period of a steady cycle
        ho = ev.ho[k]
        start = 0.5 * (prev_ff + ho) if prev_ff is not None and ho - prev_ff < 2 * gap + 0.3 else ho - gap
        nxt = idx[j + 1] if j + 1 < len(idx) else None
        ff = ev.ff[k]
        end = 0.5 * (ff + ev.ho[nxt]) if nxt is not None and ev.ho[nxt] - ff < 2 * gap + 0.3 else ff + gap
        p_a = np.asarray(h_a) + _rz(y_a) @ r_sensor
        p_b = np.asarray(st.heel) + _rz(st.yaw) @ r_sensor
        length = float(np.hypot(*(p_b - p_a)[:2]))
        # decision S49: the sideways part of the travel (> 0 = left of the heading at the stride's start)
        lateral = float(-(p_b - p_a)[0] * math.sin(y_a) + (p_b - p_a)[1] * math.cos(y_a))
        dz = float(p_b[2] - p_a[2])
        rows.append(
            {
                "start_s": start,
                "end_s": end,
                "ic_s": ev.ic[k],
                "tc_s": ev.to[k],
                "terrain": "up" if dz > TERRAIN_DZ_M else ("down" if dz < -TERRAIN_DZ_M else "flat"),
                "direction": st.direction,
                "length_m": round(length, 6),
                "height_m": round(dz, 6),
                "length_class": user.length_class(length),
                "heading_change_deg": round(math.degrees(st.yaw - y_a), 4),
                "foot": foot,
                "kind": st.kind,
                "gait": st.gait,
                "irregular": st.irregular,
                "lateral_m": round(lateral, 6),
            }
        )
        rows[-1]["steady"] = bool(
            st.kind in ("walk", "stairs_up", "stairs_down", "backward")
            and not ev.bout_start[k]
            and steps[k - 1].kind == st.kind
            and k + 1 < len(steps)
            and steps[k + 1].kind == st.kind
            and not ev.bout_start[k + 1]
        )
        h_a, y_a, prev_ff = st.heel, st.yaw, ff
    df = pd.DataFrame(rows)
    if not any(s.kind == "side" for s in steps):  # decision S49: only sessions with side steps have the column
        df = df.drop(columns="lateral_m", errors="ignore")
    df.attrs["time_columns"] = ["start_s", "end_s", "ic_s", "tc_s"]
    return df


def _rz(psi: float) -> np.ndarray:
    c, s = math.cos(psi), math.sin(psi)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _drawn_user(user: UserProfile) -> bool:
    """Whether ``user`` is :meth:`UserProfile.from_seed` of its own seed, unchanged."""
    try:
        return user == UserProfile.from_seed(user.seed)
    except (DataError, TypeError, ValueError):
        return False


def simulate_path(
    segments: list[Segment],
    user: UserProfile,
    *,
    speed: str = "normal",
    rate_hz: float = 20.0,
    seed: int | None = 0,
    name: str | None = None,
    scenario: str = "custom",
    **knobs,
) -> Session:
    """Simulate walking ``segments`` (see :mod:`pdrlearn.sim.path`) by ``user``.

    Parameters
    ----------
    segments : path segments (Straight, Curve, Stairs, Backward, Turn, Stand, Sit)
    user : the pedestrian (:meth:`UserProfile.from_seed`)
    speed : "slow", "normal" or "fast"
    rate_hz : output rate (Hz); 100 Hz divided by an integer. 20 Hz = the PLASYS firmware (5-sample mean).
    seed : randomness of this walk (gait variability, noise, biases)
    name : the session's name (meta.json ``session``, the name in messages); default
        ``sim_u{user.seed}_{speed}_s{seed}`` (``sim_{scenario}_...`` for another ``scenario`` than "custom"),
        ``_custom_user`` added for a user changed from
        ``UserProfile.from_seed(user.seed)`` (e.g. by ``dataclasses.replace``; decision S30: every session was "sim")
    **knobs : see :data:`KNOBS`

    Returns
    -------
    Session with the eight PLASYS streams, ``steps`` (strides of the instrumented foot: the right, or the left with
    ``instrumented_foot="left"``, S54), ``trajectory`` (waist
    unit, ENU), ``extras["ics"]`` (initial contacts of both feet), ``extras["foot_trajectory"]`` and, for a
    path with :class:`~pdrlearn.sim.path.Sit`, ``extras["transfers"]`` (sit-down start to stand-up end, S36); for a
    path with :class:`~pdrlearn.sim.path.Lie` also ``extras["lying"]`` and ``extras["rolls"]`` (S58, S59).
    """
    if speed not in SPEEDS:
        raise DataError(f"speed {speed!r}: must be one of {', '.join(SPEEDS)}")
    k_out = _output_factor(rate_hz)
    opt = _check_knobs(knobs)
    seed = 0 if seed is None else seed
    if not isinstance(seed, int | np.integer) or isinstance(seed, bool) or seed < 0:
        raise DataError(f"seed {seed!r}: must be a non-negative integer")
    foot = str(opt["instrumented_foot"])  # decision S54
    if name is None:  # decision S30
        name = ("sim" if scenario == "custom" else f"sim_{scenario}") + f"_u{user.seed}_{speed}_s{seed}" + (
            "" if _drawn_user(user) else "_custom_user")
        name += "" if foot == "right" else "_left"  # decision S54: the left foot's folder of the same walk
    user = body_placement(user, opt)  # decision S109: meta.json's user records the unit and pelvis simulated
    noise = bool(opt["noise"])
    rng = _rng(user.seed, int(seed), scenario, speed, "walk")
    steps, initial, end_pause, transfers = plan_footsteps(
        segments,
        user,
        speed=speed,
        rng=rng,
        heading0_rad=math.radians(float(opt["heading0_deg"])),
        irregular_rate=float(opt["irregular_rate"]),
        variability=float(opt["variability"]),
        step_length_asymmetry=float(opt["step_length_asymmetry"]),
        paretic_side=str(opt["paretic_side"]),
        transfer_s=opt["transfer_s"],  # decision S95
        graded_slopes=bool(opt["graded_slopes"]),  # decision S121
    )
    rides = [e for e in transfers if isinstance(e, Ride | VehicleRide)]  # decisions S45 (lifts, escalators), S71
    freezes = [e for e in transfers if isinstance(e, FreezeEpisode)]  # decision S51: trembling in place
    lyings = [e for e in transfers if isinstance(e, LyingEpisode)]  # decision S58: lying inside a bed-edge sit
    spins = [e for e in transfers if isinstance(e, SpinEpisode)]  # decision S106: a stepless turn on the spot
    transfers = [e for e in transfers
                 if not isinstance(e, Ride | VehicleRide | FreezeEpisode | LyingEpisode | SpinEpisode)]
    stand = float(opt["stand_s"]) + (STAND_MARGIN_S if steps else 0.0)
    # decision S43: seated at the start (then a stand-up before the standstill) and / or at the end (own stream)
    sit0, sit1 = ((None, None) if not (opt["sit_start_s"] or opt["sit_end_s"]) else session_sits(
        float(opt["sit_start_s"]), float(opt["sit_end_s"]), _rng(user.seed, int(seed), scenario, speed, "sit"),
        opt["transfer_s"]))
    lead = float(opt["sit_start_s"]) + sit0.up_s if sit0 else 0.0
    if not steps and 2 * stand + end_pause + lead + float(opt["sit_end_s"]) < 1.0:
        raise DataError("simulate: nothing to simulate (no steps and stand_s < 1 s); add segments or stand longer")
    side = side_foot(user, opt)  # decision S119: the prosthetic_side foot's own pitches and impact
    longer = opt["longer_stance_side"]  # decision S120: the stance shortened is the other foot's
    ev = schedule(steps, user, speed=speed, rng=rng, stand_s=lead + stand, variability=float(opt["variability"]),
                  rocker=str(opt["rocker"]), contact=str(opt["contact"]),
                  step_time_asymmetry=float(opt["step_time_asymmetry"]),
                  affected=str(opt["paretic_side"]), stance_time_asymmetry=float(opt["stance_time_asymmetry"]),
                  feet=None if side is None else {str(opt["prosthetic_side"]): side},
                  short_stance=None if longer is None else next(f for f in FEET if f != longer),
                  fatigue_pct=float(opt["fatigue_pct"]))  # decision S122
    total_s = (max(ev.end_s, lead + stand) if steps else lead + stand) + end_pause + stand
    sit_starts = transfer_starts(transfers, ev.rest, lead + stand)  # decision S36
    ride_starts = transfer_starts(rides, ev.rest, lead + stand)  # decision S45: as a transfer's
    freeze_starts = transfer_starts(freezes, ev.rest, lead + stand)  # decision S51: as a transfer's
    lying_starts = transfer_starts(lyings, ev.rest, lead + stand)  # decision S58: as a transfer's
    spin_starts = transfer_starts(spins, ev.rest, lead + stand)  # decision S106: as a transfer's
    if sit0 or sit1:  # decision S43
        ends = session_sit_starts(sit0, sit1, total_s)
        transfers = [*([sit0] if sit0 else []), *transfers, *([sit1] if sit1 else [])]
        sit_starts = np.concatenate([ends[:1] if sit0 else [], sit_starts, ends[-1:] if sit1 else []])
        total_s += sit1.down_s + float(opt["sit_end_s"]) if sit1 else 0.0
    k_fine = OVERSAMPLE * k_out
    fine_rate = INTERNAL_RATE_HZ * OVERSAMPLE
    n_out = int(math.floor(total_s * rate_hz)) + 1
    # decision S62: the 500 Hz grid is never held whole: its parts are made where they are used (same values)
    t = _FineGrid(n_out * k_fine, 0.5 * (k_fine - 1), fine_rate)
    dt = 1.0 / fine_rate
    t100 = t.block_means(OVERSAMPLE)
    t_out = block_mean(t100, k_out)
    check_gaps_inside(t_out, opt["gaps"])  # decision L548: before the sensors are simulated

    cycling = any(r.kind == "cycle" for r in rides)  # decision S99
    # -- foot unit (the right foot, S1, or the left, S54) --
    # per-user mount: from beside the heel to the instep (decisions S19)
    r_sensor = np.array([user.foot_sensor_x_frac * user.foot_length_m, 0.0, user.foot_sensor_height_m])
    carry = _Carry(rides, ride_starts, spins, spin_starts, foot, r_sensor)  # decisions S45, S71, S106

    def foot_unit(tt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        heel, rot = foot_pose(tt, foot, steps, ev, initial, user, vibration=1.0 if noise else 0.0)
        moved = [freeze_foot(tt, freezes, freeze_starts)] if freezes else []  # decision S51: the trembling foot
        if cycling:  # decision S99: the foot on the pedal, going round the crank
            moved.append(cycle_foot(tt, rides, ride_starts))
        for dp, pitch in moved:  # pitching about the unit, moving fore-aft and up
            c, s_ = np.cos(pitch), np.sin(pitch)
            ry = np.zeros((tt.size, 3, 3))
            ry[:, 0, 0], ry[:, 0, 2], ry[:, 1, 1], ry[:, 2, 0], ry[:, 2, 2] = c, s_, 1.0, -s_, c
            heel = heel + rot @ r_sensor - (rot @ ry) @ r_sensor + dp
            rot = rot @ ry
        # decision S45: the ride carries the standing walker (S71: a vehicle turns them too; S106: a spin)
        return carry(tt, heel + rot @ r_sensor, rot)

    # decision S44: in parts of the 500 Hz grid; S62: the foot's pose kept at the output samples only
    f_body, w_body, pf_out, Rf_out = _unit_motion(t, foot_unit, dt, pose_every=k_out)
    # mounting: the user's few-degree misalignment, optionally on top of a deliberate toes-down tilt
    # (an instep mount like the real gaitmap stair recordings is pitched ~50 deg)
    mount_f = (_misalignment([float(opt["foot_mount_roll_deg"]), 0.0, 0.0])  # decision S113: rolled after the pitch
               @ _misalignment([0.0, float(opt["foot_mount_pitch_deg"]), 0.0]))
    mis_f = mount_f @ _misalignment(user.foot_misalignment_deg)
    foot_mis_deg = [round(float(v), 9) for v in np.degrees(Rotation.from_matrix(mis_f).as_rotvec())]
    foot_m = THESIS_FOOT_FRAME.matrix()
    s_rng = _rng(user.seed, int(seed), scenario, speed, "sensors")

    def unit(name: str) -> np.random.Generator | None:  # the user's own device (decisions S22)
        return _rng(user.seed, "device", name) if opt["device_errors"] else None

    # decision S54: the left unit is another device with its own session errors; the right unit's draws are still
    # taken from the session's stream (same shapes, values unused) so that the waist unit's are the right session's
    f_rng = s_rng if foot == "right" else _rng(user.seed, int(seed), scenario, speed, "sensors", "left")
    f_dev = "" if foot == "right" else "left "
    acc_f, e_af = sn.imu_readout(
        _to_sensor(f_body, foot_m, mis_f), sn.FOOT_ACC, f_rng, noise=noise, device_rng=unit(f_dev + "fAccelerometer")
    )
    tau = opt["gyro_bias_tau_s"]  # decision S110
    gyr_f, e_gf = sn.imu_readout(_to_sensor(w_body, foot_m, mis_f), sn.FOOT_GYR, f_rng, noise=noise, bias_tau_s=tau)
    load_h, load_t = foot_loads(t100, foot, steps, ev, user)
    if freezes:  # decision S51: the heel and forefoot loads alternate while trembling
        load_h, load_t = freeze_loads(t100, load_h, load_t, freezes, freeze_starts)
    if cycling:  # decision S99: the heel off the pedal, the forefoot pressing on the downstroke
        load_h, load_t = cycle_loads(t100, load_h, load_t, rides, ride_starts)
    force_a = sn.force_readout(load_h, f_rng, noise=noise)
    force_b = sn.force_readout(load_t, f_rng, noise=noise)
    if foot != "right":  # decision S54: advance the session stream past the right unit's draws
        sn.imu_readout(np.zeros_like(f_body), sn.FOOT_ACC, s_rng, noise=noise, device_rng=unit("fAccelerometer"))
        sn.imu_readout(np.zeros_like(w_body), sn.FOOT_GYR, s_rng, noise=noise)
        sn.force_readout(np.zeros_like(load_h), s_rng, noise=noise)
        sn.force_readout(np.zeros_like(load_t), s_rng, noise=noise)

    def out(x: np.ndarray) -> np.ndarray:  # the output rate
        return block_mean(x, k_out)

    # decision S62: each 100 Hz reading goes to the output rate as soon as it is drawn (same values, the draws in
    # the same order), so the 100 Hz arrays of one unit are freed before the next unit's are made
    acc_f, gyr_f, force_a, force_b = out(acc_f), out(gyr_f), out(force_a), out(force_b)
    del f_body, w_body, load_h, load_t

    # -- waist unit (front of the belt) --
    r_waist = np.array([0.12, 0.0, 0.0])
    trunk = float(opt["variability"]) if noise else 0.0  # exact physics (noise=False): no trunk vibration
    pelvis = realistic_pelvis(user) if opt["pelvis"] == "realistic" else None
    trunk_rng = _rng(user.seed, int(seed), scenario, speed, "trunk")
    span = (float(t[0]), float(t[-1]))
    # decision S44: the trunk vibration is drawn once over the whole grid, then each part interpolates it
    vib_source = (trunk_vibration_source(*span, trunk_rng, TRUNK_ACC_SD + TRUNK_RATE_SD) if trunk > 0 else None)
    # decision S114: the trunk jerks, drawn from their own stream (the other draws unchanged)
    jerks = draw_jerks(*span, float(opt["trunk_jerk_rate_hz"]), opt["trunk_jerk_deg"], opt["trunk_jerk_m"],
                       _rng(user.seed, int(seed), scenario, speed, "trunk_jerks"))

    knots = pelvis_knots(steps, ev, initial, user, *span)  # decision S125: once, for every part of the grid

    def waist_unit(tt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        p_pel, rot, _ = pelvis_pose(
            tt,
            steps,
            ev,
            initial,
            user,
            rng=trunk_rng,
            trunk_noise=trunk,
            pelvis=pelvis,
            bounce_mode=str(opt["bounce"]),
            bout_envelope=str(opt["bout_envelope"]),  # decision W612
            transfer_offsets=transfer_motion(tt, transfers, sit_starts) if transfers else None,
            span=span,
            vibration_source=vib_source,
            knots=knots,
        )
        if freezes:  # decision S51: the pelvis trembles with the legs
            p_pel = p_pel + freeze_pelvis(tt, freezes, freeze_starts)
        if jerks:  # decision S114: the trunk tilts and bumps in its own frame
            p_pel, rot = jerk_pose(tt, p_pel, rot, jerks)
        if lyings:  # decisions S58, S59: lying down on the bed, turning over, sitting up (body frame)
            p_pel, rot = _lie_down(tt, p_pel, rot, lyings, lying_starts)
        if cycling:  # decision S99: seated on the saddle, tilted forward, rocking with the crank (body frame)
            rot = rot @ cycle_pelvis(tt, rides, ride_starts)
        # decision S45: the ride, and the standing passenger's small sway (with the trunk's vibration; S71, S106)
        return carry(tt, p_pel + rot @ r_waist, rot, sway=trunk > 0)

    fw_body, ww_body, p_w100, R_p100 = _unit_motion(t, waist_unit, dt)  # decision S44
    heading_out = _yaw_of(R_p100[k_out // 2 :: k_out][:n_out])
    mis_w = _misalignment(list(opt["waist_mount_deg"])) @ _misalignment(user.waist_misalignment_deg)  # S34
    waist_mis_deg = (user.waist_misalignment_deg if not any(opt["waist_mount_deg"]) else
                     [round(float(v), 9) for v in np.degrees(Rotation.from_matrix(mis_w).as_rotvec())])
    waist_m = THESIS_WAIST_FRAME.matrix()
    if opt["waist_mount_end_deg"] is None and opt["waist_reclip"] is None:
        def to_waist(v: np.ndarray) -> np.ndarray:
            return _to_sensor(v, waist_m, mis_w)
        turn_rate = None
    else:  # decisions S117, S123: the unit turns on the belt during the session, or at once when re-clipped
        reclip = opt["waist_reclip"]
        axes_w, turn_rate = drifting_axes(
            t100, opt["waist_mount_deg"], opt["waist_mount_end_deg"] if reclip is None else reclip[1],
            _misalignment(user.waist_misalignment_deg) @ waist_m,
            window=None if reclip is None else (reclip[0], reclip[0] + 0.5))  # S123: a hand's re-clip, 0.5 s (ours)
        if reclip is not None and not reclip[0] + 0.5 < t100[-1]:
            raise DataError(f"simulate: waist_reclip at {reclip[0]:g} s does not lie inside the recording (0-"
                            f"{t100[-1]:.1f} s); re-clip earlier (decision S123)")

        def to_waist(v: np.ndarray) -> np.ndarray:
            return np.einsum("ni,nij->nj", v, axes_w)
    acc_w, e_aw = sn.imu_readout(
        to_waist(fw_body), sn.WAIST_ACC, s_rng, noise=noise, device_rng=unit("wAccelerometer")
    )
    gyr_w, e_gw = sn.imu_readout(to_waist(ww_body) if turn_rate is None else to_waist(ww_body) + turn_rate,
                                 sn.WAIST_GYR, s_rng, noise=noise, bias_tau_s=tau)  # decisions S110, S117
    acc_w, gyr_w = out(acc_w), out(gyr_w)  # decision S62
    del fw_body, ww_body
    b_enu = earth_field_enu(
        float(opt["mag_field_ut"]), float(opt["mag_inclination_deg"]), float(opt["mag_declination_deg"])
    )
    env_rng = _rng(user.seed, int(seed), scenario, speed, "environment")
    dist = 0.0
    if noise:  # the disturbance varies smoothly in space: evaluate at 10 Hz and interpolate
        coarse = sn.field_disturbance(p_w100[::10], env_rng, float(opt["mag_disturbance_ut"]))
        dist = np.column_stack([np.interp(t100, t100[::10], coarse[:, j]) for j in range(3)])
    b_body = np.einsum("nji,nj->ni", R_p100, b_enu[None, :] + dist)
    del R_p100, dist  # decision S62
    mag_w, e_m = sn.magnetometer_readout(to_waist(b_body), s_rng, noise=noise)
    mag_w = out(mag_w)
    del b_body
    p0 = float(env_rng.uniform(*sn.BARO_P0_RANGE)) if noise else STANDARD_P0_HPA
    baro, e_b = sn.barometer_readout(
        pressure_hpa(sn.BUILDING_ALTITUDE_M + p_w100[:, 2], p0),
        t100,
        s_rng,
        noise=noise,
        drift_hpa_per_h=float(opt["baro_drift_hpa_per_h"]),
    )
    baro, pw_out = out(baro), block_mean(p_w100, k_out)  # decision S62
    del p_w100

    # -- output rate, clocks, dropped packets --
    foot_keep = np.ones(n_out, dtype=bool)
    drop_rate = float(opt["drop_rate"])
    if drop_rate > 0:
        foot_keep = _rng(user.seed, int(seed), scenario, speed, "drops").random(n_out) >= drop_rate
        foot_keep[[0, -1]] = True
    drift = float(opt["clock_drift_ppm"]) * 1e-6
    t_waist = t_out * (1.0 + drift) + float(opt["clock_offset_s"])
    waist_keep = np.ones(n_out, dtype=bool)
    if opt["gaps"]:  # decision S83: a battery swap removes the unit's samples; the truth files stay the walk's
        foot_keep &= _gap_keep(t_out, opt["gaps"], "foot")
        waist_keep = _gap_keep(t_out, opt["gaps"], "waist")  # on the foot clock, as meta.json's gaps
        t_waist, acc_w, gyr_w, mag_w, baro = (a[waist_keep] for a in (t_waist, acc_w, gyr_w, mag_w, baro))
    streams = {
        "fAccelerometer": Stream("fAccelerometer", t_out[foot_keep], acc_f[foot_keep]),
        "fGyroscope": Stream("fGyroscope", t_out[foot_keep], gyr_f[foot_keep]),
        "fForceA": Stream("fForceA", t_out[foot_keep], force_a[foot_keep]),
        "fForceB": Stream("fForceB", t_out[foot_keep], force_b[foot_keep]),
        "wAccelerometer": Stream("wAccelerometer", t_waist, acc_w),
        "wGyroscope": Stream("wGyroscope", t_waist, gyr_w),
        "wMagneticField": Stream("wMagneticField", t_waist, mag_w),
        "wBarometer": Stream("wBarometer", t_waist, baro),
    }

    # -- ground truth --
    trajectory = pd.DataFrame(
        {"t": t_out, "x": pw_out[:, 0], "y": pw_out[:, 1], "z": pw_out[:, 2], "heading_rad": heading_out}
    )
    q = Rotation.from_matrix(Rf_out[:n_out]).as_quat()  # x, y, z, w
    pf_out = pf_out[:n_out]
    foot_traj = pd.DataFrame(
        {
            "t_s": t_out,
            "x": pf_out[:, 0],
            "y": pf_out[:, 1],
            "z": pf_out[:, 2],
            "qw": q[:, 3],
            "qx": q[:, 0],
            "qy": q[:, 1],
            "qz": q[:, 2],
        }
    )
    foot_traj.attrs["time_columns"] = ["t_s"]
    ics = pd.DataFrame({"ic_s": ev.ic, "foot": [s.foot for s in steps], "kind": [s.kind for s in steps]})
    if opt["step_length_asymmetry"]:  # decision S42: the per-step lengths (steps.csv's strides sum two of them)
        ics["step_length_m"] = step_lengths(steps, initial)
    if any(isinstance(seg, Stairs) and seg.step_to_step for seg in segments):
        # decision S101: each step's rise; a step-to flight's alternate one stair and 0 (the trail onto the same stair)
        ics["height_m"] = np.round(step_heights(steps, initial), 6)
    ics.attrs["time_columns"] = ["ic_s"]
    strides = _stride_table(steps, ev, initial, user, r_sensor, foot)
    extras = {"ics": ics, "foot_trajectory": foot_traj}
    if transfers:  # decision S36: only sessions with a sit have the table (default label files unchanged)
        extras["transfers"] = pd.DataFrame(transfer_table(transfers, sit_starts))
        if sit0 or sit1:  # decision S43: the seated start / end clipped to the recording
            tcols = ["start_s", "seated_s", "rise_s", "end_s"]
            extras["transfers"][tcols] = extras["transfers"][tcols].clip(0.0, float(t_out[-1]))
        extras["transfers"].attrs["time_columns"] = ["start_s", "seated_s", "rise_s", "end_s"]
    if rides:  # decision S45: only sessions with a lift or an escalator have the table
        extras["rides"] = pd.DataFrame(ride_table(rides, ride_starts))
        extras["rides"].attrs["time_columns"] = ["start_s", "end_s"]
    if spins:  # decision S106: only sessions with a spin have the table
        extras["spins"] = pd.DataFrame(spin_table(spins, spin_starts))
        extras["spins"].attrs["time_columns"] = ["start_s", "end_s"]
    if freezes:  # decision S51: only sessions with a freeze have the table
        extras["freezes"] = pd.DataFrame(freeze_table(freezes, freeze_starts))
        extras["freezes"].attrs["time_columns"] = ["start_s", "end_s"]
    if jerks:  # decision S114: only sessions with trunk jerks have the table
        extras["trunk_jerks"] = pd.DataFrame(jerk_table(jerks), columns=["start_s", "end_s", "peak_deg", "bump_m"])
        extras["trunk_jerks"].attrs["time_columns"] = ["start_s", "end_s"]
    if lyings:  # decision S58: only sessions with a lie have lying.csv and rolls.csv (S59)
        extras["lying"] = pd.DataFrame(lying_table(lyings, lying_starts))
        extras["lying"].attrs["time_columns"] = ["start_s", "lying_s", "rise_s", "end_s"]
        extras["rolls"] = pd.DataFrame(roll_table(lyings, lying_starts),
                                       columns=["start_s", "end_s", "from_posture", "to_posture", "angle_deg"])
        extras["rolls"].attrs["time_columns"] = ["start_s", "end_s"]

    meta = {
        "session": name,
        "source_project": "pdrlearn.sim",
        "scenario": scenario,
        "speed": speed,
        "seed": int(seed),
        "user_seed": user.seed,
        "user": user.to_dict(),
        "rate_hz": float(rate_hz),
        "internal_rate_hz": INTERNAL_RATE_HZ,
        "sensor_height_m": user.sensor_height_m,
        "leg_length_m": user.leg_length_m,
        "height_m": user.height_m,
        "length_class_bounds_m": list(user.length_class_bounds_m),
        "length_m_definition": "horizontal displacement of the foot unit between the mid-stance instants",
        "instrumented_foot": foot,
        "clock_offset_s": float(opt["clock_offset_s"]),
        "clock_drift_ppm": float(opt["clock_drift_ppm"]),
        "time_base": "foot unit clock; labels and trajectory use it; waist = foot * (1 + drift) + offset",
        "dropped_samples": int((~foot_keep).sum()),
        "misalignment_deg": {"foot": foot_mis_deg, "waist": waist_mis_deg},
        "sensor_errors": {
            "fAccelerometer": e_af,
            "fGyroscope": e_gf,
            "wAccelerometer": e_aw,
            "wGyroscope": e_gw,
            "wMagneticField": e_m,
            "wBarometer": {**e_b, "p0_hpa": p0},
        },
        "earth_field_enu_ut": [float(v) for v in b_enu],
        # the default pelvis is left out so that default sessions (and their meta.json) are as before S27
        "knobs": {k: (list(v) if isinstance(v, tuple) else v) for k, v in opt.items()
                  if k not in META_ONLY_WHEN_SET or v != KNOBS[k]},
        "n_steps": len(steps),
        "n_strides": int(len(strides)),
        "distance_m": float(strides["length_m"].sum()) if len(strides) else 0.0,
        "units": {"fForceA": "N (heel)", "fForceB": "N (forefoot)"},
    }
    if pelvis is not None:
        meta["pelvis"] = asdict(pelvis)
    frames = {"foot": THESIS_FOOT_FRAME, "waist": THESIS_WAIST_FRAME}
    return Session(
        name=name,
        streams=streams,
        steps=strides if len(strides) else None,
        trajectory=trajectory,
        extras=extras,
        meta=meta,
        frames=frames,
    )


class _Carry:
    """The episodes that carry or turn the standing walker as a whole, applied to a unit's planned pose: S45's lifts
    and escalators, S71's / S99's vehicles and bicycles and S106's spins.

    Without a spin, exactly the rides' carry as before S106 (:func:`vehicle_carry`, then :func:`ride_offset`).
    Decision S106: with a spin, each episode is a rigid motion laid out in the planner's frame, which knows nothing of
    the episodes before it, so the pose is carried by the episodes from the last to the first (a ride after a spin
    is turned by it; a spin after a ride is moved by it). A spin turns about the vertical through the instrumented
    ``foot``'s unit (``r_sensor`` from its heel) where it stands in the planner's frame."""

    def __init__(self, rides: list, ride_starts: np.ndarray, spins: list[SpinEpisode], spin_starts: np.ndarray,
                 foot: str, r_sensor: np.ndarray):
        self.rides, self.ride_starts = rides, ride_starts
        episodes = [(float(t0), 0, i, r) for i, (r, t0) in enumerate(zip(rides, ride_starts, strict=True))]
        for i, (sp, t0) in enumerate(zip(spins, spin_starts, strict=True)):
            heel, yaw = sp.foot(foot)
            episodes.append((float(t0), 1, i, (sp, heel + (_rz(yaw) @ r_sensor)[:2])))
        self.spun = sorted(episodes, key=lambda e: (e[0], e[1], e[2]))[::-1] if spins else None

    def __call__(self, tt: np.ndarray, pos: np.ndarray, rot: np.ndarray, *, sway: bool = False
                 ) -> tuple[np.ndarray, np.ndarray]:
        if self.spun is None:
            if not self.rides:
                return pos, rot
            pos, rot = vehicle_carry(tt, pos, rot, self.rides, self.ride_starts)  # S71
            return pos + ride_offset(tt, self.rides, self.ride_starts, sway=sway), rot
        for t0, is_spin, _, ep in self.spun:  # decision S106: the last episode first
            if is_spin:
                pos, rot = spin_carry(tt, pos, rot, ep[0], t0, ep[1])
            else:
                pos, rot = vehicle_carry(tt, pos, rot, [ep], np.array([t0]))
                pos = pos + ride_offset(tt, [ep], np.array([t0]), sway=sway)
        return pos, rot


class _FineGrid:
    """Decision S62: the 500 Hz time grid ``(arange(n) - offset) / rate`` without holding it: ``grid[lo:hi]`` makes a
    part (the same float64 values as the whole array's slice: the same elementwise arithmetic)."""

    def __init__(self, n: int, offset: float, rate: float):
        self.size, self.offset, self.rate = int(n), float(offset), float(rate)

    def __getitem__(self, key):
        if isinstance(key, slice):
            lo, hi, step = key.indices(self.size)
            return (np.arange(lo, hi, step) - self.offset) / self.rate
        i = range(self.size)[key]
        return float((np.arange(i, i + 1) - self.offset)[0] / self.rate)

    def block_means(self, k: int, chunk: int = 1_000_000) -> np.ndarray:
        """:func:`block_mean` of the whole grid, made in parts of whole blocks (each block's mean is its own)."""
        n = self.size // k * k
        size = max(chunk // k, 1) * k
        return np.concatenate([block_mean(self[a:min(a + size, n)], k) for a in range(0, n, size)])


def _unit_motion(t: _FineGrid, pose, dt: float, chunk: int | None = None,
                 pose_every: int = 1) -> tuple[np.ndarray, ...]:
    """Decision S44: a unit's 100 Hz specific force and angular rate (block means of the 500 Hz ones), and its
    position and orientation at the middle of each 100 Hz block, from ``pose(times) -> (positions (n, 3),
    rotations (n, 3, 3))`` evaluated on parts of :data:`FINE_CHUNK` samples of the 500 Hz grid ``t`` (one more
    sample on each inner side for the differences), so that the grid's poses are never all held at once. Every value
    is the one the whole grid gives: the kernels are pointwise but for the differences, whose edge samples are
    dropped (``tests/test_sim_memory.py``).

    Decision S62: the outputs are filled in place (no list of parts and a concatenated copy), and ``pose_every = k``
    keeps the pose only at the 100 Hz samples ``k // 2, k // 2 + k, ...`` (the middle of each output block: the
    foot's ground truth needs no more)."""
    n, size = t.size, (chunk or FINE_CHUNK) // OVERSAMPLE * OVERSAMPLE
    n100 = n // OVERSAMPLE
    n_pose = len(range(pose_every // 2, n100, pose_every))
    force, rate = np.empty((n100, 3)), np.empty((n100, 3))
    where, turn = np.empty((n_pose, 3)), np.empty((n_pose, 3, 3))
    for a in range(0, n, size):
        b = min(a + size, n)
        lo, hi = max(a - 1, 0), min(b + 1, n)
        pos, rot = pose(t[lo:hi])
        keep = slice(a - lo, a - lo + b - a)
        i0, i1 = a // OVERSAMPLE, b // OVERSAMPLE
        force[i0:i1] = block_mean(specific_force_body(pos, rot, dt)[keep], OVERSAMPLE)
        rate[i0:i1] = block_mean(angular_rate_body(rot, dt)[keep], OVERSAMPLE)
        first = i0 + (pose_every // 2 - i0) % pose_every  # the first kept 100 Hz sample of this part
        mid = slice(a - lo + (first - i0) * OVERSAMPLE + OVERSAMPLE // 2, a - lo + b - a, OVERSAMPLE * pose_every)
        j0 = (first - pose_every // 2) // pose_every
        m = len(range(first, i1, pose_every))
        where[j0:j0 + m] = pos[mid]
        turn[j0:j0 + m] = rot[mid]
    return force, rate, where, turn


def _lie_down(t: np.ndarray, p_pel: np.ndarray, rot: np.ndarray, lyings: list, starts: np.ndarray):
    """Decision S58: the seated pelvis ``(p_pel, rot)`` lain down: rotated in its own frame by
    :func:`~pdrlearn.sim.lying.lying_rotation` and slid back onto the bed along the walker's heading."""
    unrecline, yaw, pitch, roll, back = lying_angles(t, lyings, starts)
    moving = (unrecline != 0) | (yaw != 0) | (pitch != 0) | (roll != 0) | (back != 0)
    if not moving.any():
        return p_pel, rot
    rot, p_pel = rot.copy(), p_pel.copy()
    rot[moving] = rot[moving] @ lying_rotation(unrecline[moving], yaw[moving], pitch[moving], roll[moving])
    heading = np.zeros_like(t)
    for ep, t0 in zip(lyings, starts, strict=True):
        heading[(t >= t0) & (t <= t0 + ep.total_s)] = ep.heading_rad
    p_pel[:, 0] -= back * np.cos(heading)
    p_pel[:, 1] -= back * np.sin(heading)
    return p_pel, rot


def _yaw_of(R: np.ndarray) -> np.ndarray:
    return np.arctan2(R[:, 1, 0], R[:, 0, 0])


def simulate(
    scenario: str, user_seed: int | UserProfile, speed: str = "normal", *, rate_hz: float = 20.0,
    seed: int | None = None, **knobs
) -> Session:
    """Simulate one of the thesis scenarios or calibration exercises.

    Parameters
    ----------
    scenario : "A", "B", "C", "D" (thesis ch.7.3.2.1), "terrain", "direction", "length" (calibration
        exercises, ch.7.2.2), "standstill" (60 s, Table 34), "rotations" (Table 35), "walk" (knob ``length_m``)
    user_seed : non-negative integer selecting the user (:meth:`UserProfile.from_seed`), or the
        :class:`UserProfile` itself (decision S39: a custom profile such as ``UserProfile.from_seed(1).scaled(0.95)``
        walks the same scenario, with the random draws of its seed)
    speed : "slow", "normal" or "fast"
    rate_hz : output rate (Hz), 100 Hz divided by an integer; 20 Hz as the PLASYS firmware
    seed : randomness of the walk and sensors (default 0); same arguments -> identical session
    **knobs : realism options, see :data:`KNOBS`
    """
    if scenario not in SCENARIOS:
        raise DataError(f"scenario {scenario!r}: must be one of {', '.join(SCENARIOS)}")
    if speed not in SPEEDS:
        raise DataError(f"speed {speed!r}: must be one of {', '.join(SPEEDS)}")
    seed = 0 if seed is None else seed
    if not isinstance(seed, int | np.integer) or seed < 0:
        raise DataError(f"seed {seed!r}: must be a non-negative integer")
    user = user_seed if isinstance(user_seed, UserProfile) else UserProfile.from_seed(user_seed)  # decision S39
    opt = _check_knobs(knobs)
    path_rng = _rng(user.seed, int(seed), scenario, speed, "path")
    segments = SCENARIOS[scenario](user, speed, path_rng, length_m=float(opt["length_m"]))
    if scenario == "standstill":
        knobs = {**knobs, "stand_s": 30.0}
    name = f"sim_{scenario}_u{user.seed}_{speed}_s{seed}" + ("" if _drawn_user(user) else "_custom_user")
    name += "_left" if opt["instrumented_foot"] == "left" else ""  # decision S54
    return simulate_path(
        segments, user, speed=speed, rate_hz=rate_hz, seed=int(seed), name=name, scenario=scenario, **knobs
    )
