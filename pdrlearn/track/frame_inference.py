"""Axis frames inferred from the data, for sessions whose ``meta.json`` declares none (decision D8).

A unit's :class:`~pdrlearn.io.frames.AxisFrame` maps each sensor axis to the nearest signed body
direction; the pipelines level with gravity themselves, so a pitched or rolled mount needs only that
nearest mapping (the foot filters take the tilt from the rest specific force, the waist AHRS from its
mean). What the data fixes:

- **foot**: up = the mean specific force at rest (stance); forward = the mean direction of the ZUPT stride
  displacements (:func:`stride_displacements`; a session of back-and-forth strides is refused), accepted
  only when the foot pitches toes-down in swing (push-off) clearly further than toes-up relative to that
  direction (:func:`swing_pitch_extremes`, decision D9): mostly backward walking is refused, not given a
  reversed frame; left = up x forward, cross-checked against the principal
  axis of the angular rate (the foot rotates in the sagittal plane; unsigned; the sign of the swing peak
  was measured and not adopted, decision D8). A pitched
  mount (an instep sensor is pitched toes-down by ~50 deg) is mapped by the mounting prior
  :data:`FOOT_PITCH_WINDOW_DEG`: the forward axis is the sagittal sensor axis pitched between 30 deg
  toes-up and 60 deg toes-down (foot mounts slope toes-down: laces, instep).
- **waist**: up = the mean specific force; forward = the horizontal axis with the strongest acceleration
  at step frequency (the anterior-posterior oscillation is at step frequency, the medio-lateral sway at
  stride frequency), signed by the W2 phase rule (the forward acceleration leads the vertical one by
  0-90 deg at step frequency; seed 003 sec. 3.1); left = up x forward.

The module sits in ``track``, after the stages it uses (the ZUPT stride integration of ``displace``, the W2
rule of ``waist``; the data flow of docs/architecture.md); :meth:`pdrlearn.io.Session.require_frame` imports it
lazily, when a method first asks for an undeclared frame.

Every check that can fail raises :class:`FrameInferenceError` (a :class:`DataError`) with the reason;
:meth:`pdrlearn.io.Session.require_frame` adds the file and the ``frames`` entry to declare instead.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.frames import _DIRECTIONS, AxisFrame
from pdrlearn.io.sensors import UNIT_IMU

#: Largest angle (deg) between a body direction found in the data and the sensor axis it is snapped to
#: (up, medio-lateral, waist forward). 45 deg would be a coin toss; beyond 35 deg the mount is too oblique
#: for a nearest-axis frame and the session must declare one.
MAX_SNAP_DEG = 35.0
#: Foot mounting prior (deg, toes-down positive): the forward sensor axis is the one whose pitch lies in
#: this 90 deg window. Shoe-top and instep mounts pitch toes-down (gaitmap instep units 45-51 deg, shoe
#: mounts 0-4 deg, ``rest_acc_mean_mps2`` of their meta.json); a toes-up pitch beyond 30 deg is not a
#: foot-top mount. Within :data:`PITCH_MARGIN_DEG` of either end the choice is refused as ambiguous.
FOOT_PITCH_WINDOW_DEG = (-30.0, 60.0)
PITCH_MARGIN_DEG = 5.0
#: Foot: least total rest (s) for up; least strides longer than MIN_STRIDE_M (m, horizontal) and least mean
#: resultant length of their unit directions (1 = all strides point the same way in the unit's frame).
MIN_REST_S = 0.5
MIN_STRIDES = 4
MIN_STRIDE_M = 0.2
MIN_RESULTANT = 0.5
#: Foot: least asymmetry (down - up) / (down + up) of the strides' median toes-down and toes-up swing pitch
#: (:func:`swing_pitch_extremes`) about the left of their mean direction: forward walking pushes off toes-down.
#: The 11 real foot recordings (all forward, incl. stairs and the MS patient) 0.40-1.00, simulated forward
#: walking 0.44-1.00, simulated backward walking 0.05-0.09: the middle of the gap (decision D9).
MIN_SWING_ASYMMETRY = 0.25
#: Waist: least walking (s).
MIN_WALK_S = 4.0
#: decision W333: a 4 s window whose mean yaw rate about up reaches this (rad/s) turns, and is no straight walking the
#: waist frame is judged on (steps decision 28's turning test, 0.45: the turning component of W7's mixture)
TURNING_WINDOW_RPS = 0.45
#: Waist: the forward axis must carry this factor more step-frequency power than the lateral one, and the
#: forward/vertical phase (W2) must be this many degrees away from the +-90 deg of 45 deg boundary.
MIN_AP_POWER_RATIO = 1.5
MIN_PHASE_MARGIN_DEG = 15.0
#: decision W540 (measured, not adopted: ``infer_waist_frame(..., push_lead_deg=)``'s value): a waist forward lead
#: (deg) up to 60 deg past W2's forward half (-45 to 135 deg): pole jolts turned a forward walk's lead from 54 to 171
#: deg (trial T2 F3); real forward lower-back walks read 80-112 deg, reversed units their lead + 180 (234-292 deg)
PUSH_LEAD_DEG = (135.0, 195.0)
#: Waist: walking is rhythmic. The autocorrelation of the vertical acceleration over the walking windows
#: must peak at a lag of RHYTHM_LAG_S (a step or a stride period: 0.3-1.0 s) at least MIN_RHYTHM_SIGMA white-
#: noise standard deviations (1/sqrt(N (n - L) / n) at lag L, Bartlett; decision W226) above zero: a significance
#: level, not fitted to data
#: (gravity + N(0, 1.5) m/s^2 white noise, 10-300 s at 20-100 Hz: at most 4.2 in 2250 recordings; the 9
#: mobgap lower-back sessions 12.7-24.8, simulated scenarios 17.6-78; docs/frames.md).
RHYTHM_LAG_S = (0.3, 1.0)
#: decision W226: without a step rhythm, the lags searched for a stride rhythm alone (s): a hemiparetic walker's
#: steps alternate short / long, so the signal repeats at the stride only; up to 2 s = 60 steps/min (under L95's
#: 70 steps/min floor) and half the 4 s window. Such a walk is named, not axis-checked: the test reads the step
#: frequency (a simulated A 0.75 walk with a realistic pelvis read forward 74 deg off)
STRIDE_ONLY_LAG_S = (1.0, 2.0)
MIN_RHYTHM_SIGMA = 8.0
#: decision W452 (measured, rule written first): below LOW_RATE_HZ the rhythm test needs this many noise SDs: a 20 Hz
#: recording has a fifth of a 100 Hz one's samples, so the same correlation reads sqrt(5) = 2.2x fewer SDs; white
#: noise at 20 / 25 Hz (500 recordings each, 10-300 s) read at most 3.52 / 3.12, and slow simulated walkers (users
#: 10924-10935) were inferred 4 / 5 of 12 (0 wrong) instead of 0
MIN_RHYTHM_SIGMA_LOW_RATE = 5.0
LOW_RATE_HZ = 40.0
#: A declared (or source_project) frame contradicts the data (decision D10) when one of its body directions
#: lies more than this many degrees from the direction measured in the data. A nearest-axis declaration is
#: at most 45 deg off (a unit mounted half-way between two axes may be declared either way) and the foot's
#: pitch window accepts up to 60 deg toes-down (FOOT_PITCH_WINDOW_DEG); a wrong 90-degree turn is 90 deg off
#: (less the mount's tilt), an upside-down unit 180. Geometry, not fitted to a recording.
MAX_DECLARED_OFF_DEG = 60.0
#: Decision D22: a declared up or forward more than this many degrees from the measured one is reversed, not a
#: mount between two axes (a nearest-axis declaration is at most 45 deg off, the foot pitch window reaches 60 deg,
#: a wrong 90-degree turn is ~90 deg less the tilt): the data contradict it even when they do not fix which sensor
#: axis is forward (the strides' direction sign is fixed by the push-off, D9; up by gravity at rest). Geometry:
#: midway between a 90-degree turn and the 180-degree one, not fitted to a recording.
OPPOSED_DEG = 120.0
#: the units whose reversed forward is refused (decision D23 as amended in session 21): the foot's is its strides'
#: integrated direction; the waist's is W2's forward/vertical phase cue, a gait-phase inference that a correct frame
#: can fail (the test helpers' synthetic waist reads backward by it), so a waist keeps D10's warning
REFUSE_REVERSED = ("foot",)
#: Decision D22: the declared forward's heading is compared only when it is at least this far from vertical
#: (deg): a trial's foot unit pitched 64 deg from its declared forward still walked every stride backward.
MIN_FORWARD_ELEVATION_DEG = 15.0
#: Decision D28: a declared foot forward whose heading lies more than this many degrees from the strides' direction
#: is turned, not a nearest-axis declaration: a unit yawed 45 deg on the shoe (the most a nearest-axis declaration is
#: off) and pitched toes-down by the 60 deg end of FOOT_PITCH_WINDOW_DEG projects to atan(tan 45 / cos 60) = 63.4 deg
#: from above; a declared lateral axis to 90 deg; midway, 76.7 deg. Geometry, not fitted to a recording.
MISDECLARED_DEG = (float(np.degrees(np.arctan(1.0 / np.cos(np.radians(FOOT_PITCH_WINDOW_DEG[1]))))) + 90.0) / 2.0


class FrameInferenceError(DataError):
    """The data does not fix the unit's axes with confidence (no walking, no rest, ambiguous axes).
    ``walk_s``: the seconds of walking found when there were too few to infer a waist frame (decision W61),
    else None. ``up`` and ``forward``: the directions measured before the inference gave up (unit vectors in
    sensor axes; up from gravity, forward the strides' signed horizontal direction), else None (decision D22)."""

    walk_s: float | None = None
    up: np.ndarray | None = None
    forward: np.ndarray | None = None
    #: a waist unit refused for its tilt: the nearest axis assignment its walking gives (an AxisFrame), else None
    nearest = None
    #: decision D23 amended (L223): the foot strides the forward was measured from and their mean resultant
    n_strides: int | None = None
    resultant: float | None = None
    #: decision W435: a waist forward's step-frequency power ratio (forward over lateral), else None
    ap_power_ratio: float | None = None


def _refuse(msg: str, up: np.ndarray | None = None, forward: np.ndarray | None = None,
            evidence: tuple[int, float] | None = None) -> FrameInferenceError:
    """A :class:`FrameInferenceError` carrying what was measured before giving up (decision D22; L223: the
    strides and resultant the forward came from)."""
    err = FrameInferenceError(msg)
    err.up, err.forward = up, forward
    if evidence is not None:
        err.n_strides, err.resultant = evidence
    return err


@dataclass
class InferredFrame:
    """An inferred frame and what it was found from (``evidence``: the numbers the warning prints)."""

    placement: str
    frame: AxisFrame
    evidence: dict = field(default_factory=dict)
    #: the measured up and forward directions (unit vectors in sensor axes) the frame was snapped from
    up: np.ndarray | None = None
    forward: np.ndarray | None = None
    #: decision D23 amended (L223): the foot strides the forward was measured from and their mean resultant
    n_strides: int | None = None
    resultant: float | None = None
    #: decision W435: a waist forward's step-frequency power ratio (forward over lateral), else None
    ap_power_ratio: float | None = None

    def describe(self) -> str:
        return ", ".join(f"{k} {v}" for k, v in self.evidence.items())


def _unit(v: np.ndarray) -> np.ndarray:
    n = float(np.linalg.norm(v))
    return v / n if n > 0 else v


def _angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.degrees(np.arccos(np.clip(abs(float(_unit(a) @ _unit(b))), -1.0, 1.0))))


def _nearest_axis(v: np.ndarray, exclude: tuple[int, ...] = ()) -> tuple[int, float, float]:
    """(sensor axis index, sign, angle deg) of the signed sensor axis nearest the direction ``v``."""
    v = _unit(v)
    cand = [i for i in range(3) if i not in exclude]
    i = max(cand, key=lambda k: abs(v[k]))
    sub = np.array([v[k] for k in cand])
    cos = min(1.0, abs(v[i]) / max(float(np.linalg.norm(sub)), 1e-12))
    return i, float(np.sign(v[i]) or 1.0), float(np.degrees(np.arccos(cos)))


def frame_from_axes(forward: tuple[int, float], left: tuple[int, float], up: tuple[int, float]) -> AxisFrame:
    """The :class:`AxisFrame` of sensor axes (index, sign) pointing forward, left and up."""
    names = {}
    for (i, s), (pos, neg) in zip((forward, left, up), (("forward", "backward"), ("left", "right"),
                                                       ("up", "down")), strict=True):
        names["xyz"[i]] = pos if s > 0 else neg
    return AxisFrame(**names)


#: decision D9: a stride at 20-150 strides/min lasts 0.4-3 s
MIN_STRIDE_S, MAX_STRIDE_S = 0.4, 3.0


def _rests(stance: np.ndarray, fs: float) -> np.ndarray | None:
    from pdrlearn.displace.foot import stance_runs

    rr = stance_runs(np.arange(len(stance)) / fs, stance)
    return rr if len(rr) >= 2 else None


def rest_to_rest(stance: np.ndarray, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """Start and end sample of every rest-to-rest stride: a stance-run middle to the next stance-run middle,
    0.4-3 s long (a stride at 20-150 strides/min)."""
    rr = _rests(stance, fs)
    if rr is None:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    mid = (rr[:, 0] + rr[:, 1] - 1) // 2
    i0, i1 = mid[:-1], mid[1:]
    dur = (i1 - i0) / fs
    ok = (dur >= MIN_STRIDE_S) & (dur <= MAX_STRIDE_S)
    return i0[ok], i1[ok]


def rest_swings(stance: np.ndarray, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """Start and end sample of every swing: the last sample of a stance run to the first of the next, at most
    :data:`MAX_STRIDE_S` long (decision W342: a swing is part of a stride, D9's slowest stride bounds it). Unlike
    :func:`rest_to_rest`, a long rest before or after does not lengthen it: a bout's first and last strides next to
    a rest of 2 s or more are over 3 s from rest middle to rest middle, so a 2-stride bout had no rest-to-rest
    stride at all."""
    rr = _rests(stance, fs)
    if rr is None:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    i0, i1 = rr[:-1, 1] - 1, rr[1:, 0]
    ok = (i1 - i0) / fs <= MAX_STRIDE_S
    return i0[ok], i1[ok]


def stride_displacements(acc: np.ndarray, gyr: np.ndarray, fs: float, stance: np.ndarray) -> np.ndarray:
    """ZUPT displacement (k, 3) m of every rest-to-rest stride (:func:`stride_motion`'s first value)."""
    return stride_motion(acc, gyr, fs, stance)[0]


def stride_motion(acc: np.ndarray, gyr: np.ndarray, fs: float, stance: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """ZUPT displacement (k, 3) m of every rest-to-rest stride (:func:`rest_to_rest`), in the sensor frame
    of its start rest.

    The project's stride integration (:func:`pdrlearn.displace._kernels.strapdown`: levelled by the start
    rest's specific force, attitude from the gyroscope; :func:`double_integrate` with the ZUPT at both
    rests), rotated back from the levelled frame into the sensor axes; and the foot's heading change over each
    stride (rad, CCW; the strapdown's, decision L400)."""
    from pdrlearn.displace._kernels import double_integrate, level_rotation, strapdown, stride_index

    i0, i1 = rest_to_rest(stance, fs)
    if not len(i0):
        return np.zeros((0, 3)), np.zeros(0)
    idx, mask = stride_index(i0, i1)
    g_body = acc[i0]
    # the lead's amendment of L626: a check at the unit's native rate keeps the former rule (no coning term: at 20 Hz
    # a swinging foot turns ~15 deg a sample, outside the term's small-angle range; the track integrates on L628's grid)
    a_nav, yaw = strapdown(acc, gyr, 1.0 / fs, idx, mask, g_body, coning=0.0)
    disp = double_integrate(a_nav, mask, 1.0 / fs)
    return level_rotation(g_body).inv().apply(disp), np.asarray(yaw, float)


def swing_pitch_extremes(gyr: np.ndarray, fs: float, i0: np.ndarray, i1: np.ndarray,
                         left: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Largest toes-down and toes-up pitch (rad, both >= 0) of each stride ``i0[k]:i1[k]``: the angular rate
    about ``left`` (sensor frame; right-hand rule, so positive = toes-down) integrated from the stride's start
    rest. Forward walking pitches toes-down at push-off (51-82 deg in the real foot recordings) much further
    than toes-up before heel strike (0-35 deg); this does not depend on which way the strides point in the
    unit's frame, only on whether the foot walks toes first."""
    down, up = np.zeros(len(i0)), np.zeros(len(i0))
    w = gyr @ left
    for k, (a, b) in enumerate(zip(i0, i1, strict=True)):
        th = np.cumsum(w[a:b]) / fs
        down[k], up[k] = max(float(th.max(initial=0.0)), 0.0), max(-float(th.min(initial=0.0)), 0.0)
    return down, up


def _declared_foot(session, *, need_frame: bool = True, span: tuple[float, float] | None = None,
                   rhythm_frac: float | None = None):
    """The session's foot unit with its declared frame, for :func:`foot_push_off` and :func:`foot_travel_angles`:
    ``(t, acc, gyr, fs, frame, stance)`` (the accelerometer's clock, the gyro resampled onto it, the ZUPT stance
    mask); None without a foot unit, a declared foot frame (``need_frame=False``: frame None allowed, decision
    W336's frame-free read), enough finite samples or a rate. ``span`` (s): only the samples inside it (W415).
    ``rhythm_frac``: :func:`pdrlearn.displace.foot.inertial_stance`'s (None: L596's default; 0: every rest, W548)."""
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.signal.filters import interp_rows

    acc_n, gyr_n = UNIT_STREAMS["foot"]
    frame = session.frames.get("foot")
    if (frame is None and need_frame) or acc_n not in session.streams or gyr_n not in session.streams:
        return None
    acc_s, gyr_s = session.streams[acc_n], session.streams[gyr_n]
    if len(acc_s) < 8 or len(gyr_s) < 2 or not np.isfinite(acc_s.rate_hz):
        return None
    t, acc = acc_s.t, acc_s.values
    if span is not None:  # decision W415: the waist check's span only
        keep = (t >= span[0]) & (t <= span[1])
        if keep.sum() < 8:
            return None
        t, acc = t[keep], acc[keep]
    gyr, fs = interp_rows(t, gyr_s.t, gyr_s.values), float(acc_s.rate_hz)
    if not (np.isfinite(acc).all() and np.isfinite(gyr).all()):
        return None
    return t, acc, gyr, fs, frame, inertial_stance(acc, gyr, fs, rhythm_frac=rhythm_frac)


def foot_push_off(session) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Start and end time (s) and swing-pitch asymmetry (toes-down minus toes-up over their sum, D9's measure of
    :func:`infer_foot_frame`, here per stride) of each rest-to-rest stride of the session's foot unit, about the
    left axis of its declared frame (decision W173: a forward stride pushes off toes-down, a backward one does not);
    None without a foot unit or a declared foot frame (an inferred one assumes forward walking)."""
    foot = _declared_foot(session)
    if foot is None:
        return None
    t, acc, gyr, fs, frame, stance = foot
    i0, i1 = rest_to_rest(stance, fs)
    down, toes_up = swing_pitch_extremes(gyr, fs, i0, i1, _unit(frame.matrix()[1]))
    asym = (down - toes_up) / np.maximum(down + toes_up, 1e-9)
    return t[i0], t[i1], asym


def foot_swing_strides(session) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Start and end time (s) and total rotation (rad, the integral of |w|) of each swing between two rests of the
    session's foot unit (:func:`rest_swings`, decision W342; W336 took rest-to-rest strides), in any frame (decision
    W336: a walking stride swings the foot, a vehicle's vibration breaking the rest does not); None without a foot
    unit. Decision W548: the stance without L596's rhythm rule (W336 asks whether the foot swung, not how long it
    rested: a race walker's 0.08-0.15 s rests are under L596's 6 % of a period read at six strides)."""
    foot = _declared_foot(session, need_frame=False, rhythm_frac=0.0)
    if foot is None:
        return None
    t, _acc, gyr, fs, _frame, stance = foot
    i0, i1 = rest_swings(stance, fs)
    turn = np.concatenate([[0.0], np.cumsum(np.linalg.norm(gyr, axis=1)) / fs])
    return t[i0], t[i1], turn[i1] - turn[i0]


def foot_travel_angles(session, span: tuple[float, float] | None = None
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """Start and end time (s), travel angle (rad from the foot's facing, left +), horizontal length (m) and the
    foot's heading change (rad, L400) of each rest-to-rest ZUPT stride of the session's foot unit
    (:func:`stride_motion`), in its declared frame's
    forward / left axes (decision L219: a side step travels about 90 deg from the facing); None without a foot unit
    or a declared foot frame (an inferred one assumes forward walking). ``span`` (s): the strides inside it (W415)."""
    foot = _declared_foot(session, span=span)
    if foot is None:
        return None
    t, acc, gyr, fs, frame, stance = foot
    i0, i1 = rest_to_rest(stance, fs)
    disp, yaw = stride_motion(acc, gyr, fs, stance)
    m = frame.matrix()
    fwd, left = disp @ _unit(m[0]), disp @ _unit(m[1])
    return t[i0], t[i1], np.arctan2(left, fwd), np.hypot(fwd, left), yaw


#: decision B418: a foot refused for its rotation axis whose swing pitches toes-down less than this (deg) is named a
#: foot of little sagittal rotation: trial s40 T1 finding 6's prosthetic-like feet pitched 15 deg (refused, axis 48
#: deg off) and 25-52 deg (inferred; axis 13-25 deg off); the simulator's anatomical foot ~50 deg
LITTLE_PITCH_DEG = 30.0


def little_pitch_words(down_deg: float) -> str:
    """Decision B418: what the foot rotation-axis refusal adds when the swing's toes-down pitch ``down_deg`` is under
    :data:`LITTLE_PITCH_DEG` (else ""): the likely cause (a stiff or prosthetic foot, a shuffling gait) and the fix
    (declare the axes)."""
    if not down_deg < LITTLE_PITCH_DEG:
        return ""
    return (f"; in swing it pitches toes-down only {down_deg:.0f} deg: little sagittal rotation, as a stiff or "
            "prosthetic foot or a shuffling gait makes, lets its roll and yaw decide the axis; declare the unit's "
            "axes - pdrlearn import --frames x=...,y=...,z=... or a \"frames\" entry in meta.json (docs/frames.md, "
            "prosthetic feet; decision B418) - and it tracks")


def infer_foot_frame(acc: np.ndarray, gyr: np.ndarray, fs: float) -> InferredFrame:
    """Frame of a foot unit from its specific force (m/s^2) and angular rate (rad/s) on one clock (fs Hz).

    Raises :class:`FrameInferenceError` when the recording has too little rest or walking, or an axis is
    ambiguous (see the module docstring for the rules and thresholds).
    """
    from pdrlearn.displace.foot import inertial_stance

    acc = np.asarray(acc, dtype=float)
    gyr = np.asarray(gyr, dtype=float)
    stance = inertial_stance(acc, gyr, fs)
    if stance.sum() < MIN_REST_S * fs:
        raise FrameInferenceError(f"the foot unit is never still for {MIN_REST_S:g} s in total (no stance to "
                                  "find up from)")
    up = _unit(acc[stance].mean(axis=0))
    disp = stride_displacements(acc, gyr, fs, stance)
    hor = disp - np.outer(disp @ up, up)
    length = np.linalg.norm(hor, axis=1)
    walked = length > MIN_STRIDE_M
    hor = hor[walked] / length[walked, None]
    if len(hor) < MIN_STRIDES:
        raise _refuse(f"{len(hor)} strides of more than {MIN_STRIDE_M:g} m between two rests of the "
                                  f"foot unit (at least {MIN_STRIDES} walking strides are needed)", up)
    mean = hor.mean(axis=0)
    resultant = float(np.linalg.norm(mean))
    if resultant < MIN_RESULTANT:
        raise _refuse(f"the strides point in no common direction of the unit (mean resultant "
                      f"{resultant:.2f} < {MIN_RESULTANT:g}; walking back and forth?)", up)
    fwd = _unit(mean)
    left = np.cross(up, fwd)
    # forward walking, not backward: the strides' direction is forward only when the foot pitches toes-down
    # (about the left of that direction) further than toes-up in swing: the push-off plantarflexion
    down, toes_up = swing_pitch_extremes(gyr, fs, *(i[walked] for i in rest_to_rest(stance, fs)), left)
    asym = float((np.median(down) - np.median(toes_up)) / max(float(np.median(down) + np.median(toes_up)), 1e-9))
    if asym < MIN_SWING_ASYMMETRY:
        raise _refuse(
            f"in swing the foot pitches toes-down {np.degrees(np.median(down)):.0f} deg and toes-up "
            f"{np.degrees(np.median(toes_up)):.0f} deg relative to its strides' direction (asymmetry {asym:.2f} < "
            f"{MIN_SWING_ASYMMETRY:g}): no forward push-off, so the strides' direction is not forward ("
            # simulated backward walking gives 0.05-0.09 (D9); a clear toes-up "push-off" is what data mirrored
            # in one axis (a left-handed export, a left foot mirrored to look like a right one) give (B29)
            + ("data mirrored in one axis, e.g. a left-handed export, or backward walking?)"
               if asym < -MIN_SWING_ASYMMETRY
               else "mostly backward walking, or data mirrored in one axis, e.g. a left-handed export?)"), up)
    # cross-check: the foot rotates about its medio-lateral axis (principal axis of the angular rate)
    moving = ~stance
    w, v = np.linalg.eigh(gyr[moving].T @ gyr[moving] / max(int(moving.sum()), 1))
    ang_rot = _angle_deg(v[:, 2], left)
    if ang_rot > MAX_SNAP_DEG:
        raise _refuse(f"the foot's main rotation axis is {ang_rot:.0f} deg from the medio-lateral "
                      f"direction of its strides (more than {MAX_SNAP_DEG:g})" + little_pitch_words(
                          float(np.degrees(np.median(down)))), up, fwd, (len(hor), resultant))
    i_ml, s_ml, ang_ml = _nearest_axis(left)
    if ang_ml > MAX_SNAP_DEG:
        raise _refuse(f"the medio-lateral direction is {ang_ml:.0f} deg from every sensor axis "
                      f"(more than {MAX_SNAP_DEG:g}; a yawed mount)", up, fwd, (len(hor), resultant))
    sag = [i for i in range(3) if i != i_ml]
    lo_w, hi_w = FOOT_PITCH_WINDOW_DEG
    cand = [(i, s, float(np.degrees(np.arctan2(-s * up[i], s * fwd[i])))) for i in sag for s in (1.0, -1.0)]
    inside = [c for c in cand if lo_w < c[2] <= hi_w]  # pitch toes-down positive
    # one of the four signed sagittal axes lies in the 90 deg window when they are 90 deg apart; a yawed or
    # rolled mount skews their projections, so near an edge none or two may: ambiguous, as the margin says
    if len(inside) != 1:
        pitch = min((c[2] for c in cand), key=lambda p: min(abs(p - lo_w), abs(p - hi_w)))
        raise _refuse(f"the mount is pitched {pitch:.0f} deg, at the edge of the {lo_w:g}..{hi_w:g} "
                      f"deg window that decides which axis is forward ({len(inside)} sagittal axes in it)", up, fwd,
                      (len(hor), resultant))
    i_f, s_f, pitch = inside[0]
    if min(abs(pitch - lo_w), abs(pitch - hi_w)) < PITCH_MARGIN_DEG:
        raise _refuse(f"the mount is pitched {pitch:.0f} deg, at the edge of the {lo_w:g}..{hi_w:g} "
                      "deg window that decides which axis is forward", up, fwd, (len(hor), resultant))
    i_u = next(i for i in sag if i != i_f)
    s_u = float(np.sign(up[i_u]) or 1.0)
    frame = frame_from_axes((i_f, s_f), (i_ml, s_ml), (i_u, s_u))
    return InferredFrame("foot", frame, up=up, forward=fwd, n_strides=len(hor), resultant=resultant, evidence={
        "up": f"{'xyz'[i_u]}{'+' if s_u > 0 else '-'} (pitch {abs(pitch):.0f} deg "
              f"{'toes-down' if pitch >= 0 else 'toes-up'}, {ang_ml:.0f} deg roll/yaw)",
        "forward": f"{'xyz'[i_f]}{'+' if s_f > 0 else '-'} from {len(hor)} strides (resultant {resultant:.2f}; "
                   "the sign assumes the walker mostly walks forward)",
        "rotation axis": f"{ang_rot:.0f} deg from medio-lateral",
        "swing pitch": f"toes-down {np.degrees(np.median(down)):.0f} deg, toes-up {np.degrees(np.median(toes_up)):.0f} "
                       f"deg (asymmetry {asym:.2f})",
    })


#: decision B79: the band the waist test takes the step frequency from is 1.2-3.0 Hz (cadence 72-180 steps/min);
#: above it (running, 220 steps/min) its vertical peak in the band is the stride frequency, where the
#: medio-lateral sway dominates, and the lateral axis looked forward. A window whose vertical peak over
#: 1.2-:data:`FAST_BAND_HZ` Hz lies above 3.0 Hz is "fast"; more than :data:`MAX_FAST_FRACTION` of the walking
#: windows fast: no waist inference (real lower-back recordings: at most 15 of 49 windows, MS001 Test11).
FAST_BAND_HZ, MAX_FAST_FRACTION = 4.5, 0.5


def _lag_sigma(ac: np.ndarray, n_covered: int, fs: float, lag_s: tuple[float, float]) -> tuple[float, float | None]:
    """``(sigma, lag_s)``: the highest normalised unbiased autocorrelation ``ac`` (summed over windows of ``len(ac)``
    samples covering ``n_covered``) at a lag within ``lag_s`` (s), in units of its white-noise standard deviation
    there, and that lag; decision W226: at lag L the unbiased estimate rests on N (n - L) / n sample pairs, so its
    noise is 1/sqrt(N (n - L) / n) (Bartlett), and a long lag is no easier to pass. ``(0.0, None)`` without any."""
    n = len(ac)
    lags = np.arange(n)
    sel = (lags >= lag_s[0] * fs) & (lags <= lag_s[1] * fs) & (lags < n)
    if not (ac[0] > 0 and sel.any()):
        return 0.0, None
    sig = ac[sel] / ac[0] * n / (n - lags[sel]) * np.sqrt(n_covered * (n - lags[sel]) / n)
    k = int(np.argmax(sig))
    return float(sig[k]), float(lags[sel][k] / fs)


def _step_spectra(acc_v: np.ndarray, acc_h: np.ndarray, fs: float, *, window_s: float = 4.0,
                  walk_std: float = 0.5, fast_out: list | None = None,
                  stride_out: list | None = None, yaw_rate: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Summed cross-spectra at step frequency over walking windows, and their gait rhythm.

    Returns ``C`` (2, 2) real horizontal cross-power and ``z`` (2,) complex horizontal x vertical
    cross-spectra, both at each window's step frequency (the vertical peak in 1.2-3.0 Hz), the time (s)
    the walking windows cover (vertical std over ``walk_std`` m/s^2, the W4 motion gate), and the rhythm
    significance: the highest autocorrelation of the vertical acceleration (summed over the walking
    windows, normalised, unbiased) at a lag of :data:`RHYTHM_LAG_S`, in units of its white-noise standard
    deviation 1/sqrt(N) (Bartlett), N the samples the walking windows cover. ``fast_out`` (a list) receives the
    fraction of the walking windows whose vertical peak over 1.2-:data:`FAST_BAND_HZ` Hz lies above the band
    (decision B79). ``yaw_rate`` (rad/s about up, decision W333): a window whose mean reaches
    :data:`TURNING_WINDOW_RPS` turns on the spot or round a corner and is left out (no straight walking)."""
    n = max(int(round(window_s * fs)), 8)
    hop = n // 2
    hann = np.hanning(n)
    freqs = np.fft.rfftfreq(n, 1.0 / fs)
    band = (freqs >= 1.2) & (freqs <= min(3.0, 0.45 * fs))  # cadence 72-180 steps/min
    wide = (freqs >= 1.2) & (freqs <= min(FAST_BAND_HZ, 0.45 * fs))  # B79: cadence up to 270 steps/min
    n_walk = n_fast = 0
    C = np.zeros((2, 2))
    z = np.zeros(2, dtype=complex)
    ac = np.zeros(n)
    covered = np.zeros(len(acc_v), dtype=bool)
    for a in range(0, len(acc_v) - n + 1, hop):
        v = acc_v[a:a + n]
        if np.std(v) < walk_std:
            continue
        if yaw_rate is not None and abs(float(np.mean(yaw_rate[a:a + n]))) >= TURNING_WINDOW_RPS:  # W333
            continue
        F = np.fft.rfft(v - v.mean(), 2 * n)
        ac += np.fft.irfft(F * np.conj(F), 2 * n)[:n]
        V = np.fft.rfft((v - v.mean()) * hann)
        if not band.any():
            break
        n_walk += 1
        n_fast += bool(freqs[wide][np.argmax(np.abs(V[wide]))] > 3.0)
        k = int(np.flatnonzero(band)[np.argmax(np.abs(V[band]))])
        H = np.fft.rfft((acc_h[a:a + n] - acc_h[a:a + n].mean(0)) * hann[:, None], axis=0)[k]
        C += np.real(np.outer(H, np.conj(H)))
        z += H * np.conj(V[k])
        covered[a:a + n] = True
    rhythm = _lag_sigma(ac, covered.sum(), fs, RHYTHM_LAG_S)[0]
    if stride_out is not None:  # decision W226: the stride rhythm alone, and its lag (s)
        stride_out.append(_lag_sigma(ac, covered.sum(), fs, STRIDE_ONLY_LAG_S))
    if fast_out is not None:
        fast_out.append((n_fast, n_walk))
    return C, z, float(covered.sum()) / fs, rhythm


def _walking_mean(acc: np.ndarray, fs: float, *, window_s: float = 4.0, walk_std: float = 0.5) -> np.ndarray:
    """Mean specific force over the 4 s windows whose |a| varies by more than ``walk_std`` m/s^2 (the W4
    motion gate on the norm, which needs no axis): the unit's up while walking, not while sitting or lying;
    the whole recording's mean when no window walks."""
    n = max(int(round(window_s * fs)), 8)
    norm = np.linalg.norm(acc, axis=1)
    sums, count = np.zeros(3), 0
    for a in range(0, len(acc) - n + 1, n):
        if np.std(norm[a:a + n]) >= walk_std:
            sums += acc[a:a + n].sum(axis=0)
            count += n
    return sums / count if count else acc.mean(axis=0)


#: decision W394 (trial T1's finding 10): a waist unit whose gravity or forward is beyond MAX_SNAP_DEG of every axis is
#: refused, and the refusal suggests the nearest axis assignment its walking gives, found with both snap checks opened
#: to this (deg)
NEAREST_SNAP_DEG = 90.0


def _with_nearest(err: FrameInferenceError, acc, gyr, fs: float, max_snap_deg: float) -> FrameInferenceError:
    """Decision W394: ``err`` (a snap refusal) carrying ``nearest``, the frame :func:`infer_waist_frame` gives
    with the snap checks opened (:data:`NEAREST_SNAP_DEG`), when this was not already that inference."""
    if max_snap_deg < NEAREST_SNAP_DEG:
        try:
            err.nearest = infer_waist_frame(acc, gyr, fs, max_snap_deg=NEAREST_SNAP_DEG).frame
        except FrameInferenceError:
            pass
    return err


#: decision W435: a waist forward measured with a step-frequency power ratio (forward over lateral) under this is said
#: to be possibly turned by the gait (D25's line, the axis refusal): an asymmetric gait's lateral sway puts power at the
#: step frequency and turns the measured forward by up to ~50 deg (trial s40 T1 finding 3: x4.7-x7.0 at step-time
#: asymmetry 0.2-0.45, 53 deg off); a symmetric simulated walk reads ~x85 and the real straight lower-back walks
#: x12.8-x228 (mobgap Test5); a project choice between the two. Not adopted: not judging D25 (b) under it (W435)
MIN_JUDGED_POWER_RATIO = 10.0


def asymmetric_forward_words(ratio: float | None) -> str:
    """Decision W435: the words a waist forward measurement with a low step-frequency power ``ratio`` adds to what it
    says ("" when the ratio is :data:`MIN_JUDGED_POWER_RATIO` or more, or None)."""
    if ratio is None or ratio >= MIN_JUDGED_POWER_RATIO:
        return ""
    return (f"; its step-frequency power ratio is only x{ratio:.1f} (under x{MIN_JUDGED_POWER_RATIO:g}): a strongly "
            "asymmetric gait (a prosthesis, a hemiparesis) or much turning puts lateral sway at the step frequency and "
            "can turn the measured forward by up to ~50 deg (decision W435)")


def infer_waist_frame(acc: np.ndarray, gyr: np.ndarray, fs: float, *,
                      max_snap_deg: float = MAX_SNAP_DEG,
                      push_lead_deg: tuple[float, float] | None = None) -> InferredFrame:
    """Frame of a waist (lower-back, belt) unit from its specific force (m/s^2) on one clock (fs Hz).

    ``gyr`` (rad/s, same samples; or None) leaves out the windows that turn (decision W333: the yaw rate about up,
    :data:`TURNING_WINDOW_RPS`). Raises :class:`FrameInferenceError` when there is too little (straight) walking or
    the axes are ambiguous. Gravity or forward more than ``max_snap_deg`` from every axis is refused; the refusal
    carries ``nearest``, the frame inferred with the snap checks opened (:data:`NEAREST_SNAP_DEG`), or None (decision
    W394: the fix suggested is that frame, not the thesis mounting). ``push_lead_deg`` (decision W540, measured and
    not adopted, an option; None: none, :data:`PUSH_LEAD_DEG` its measured range): a W2 forward lead in that range
    (deg) is refused as not telling forward from backward (pole plants' forward push; but also a side shuffle's).
    """
    from pdrlearn.waist._kernels import forward_sign

    acc = np.asarray(acc, dtype=float)
    up = _unit(_walking_mean(acc, fs))
    i_u, s_u, ang_u = _nearest_axis(up)
    if ang_u > max_snap_deg:  # W394: the nearest assignment the walking gives, as the suggested entry
        raise _with_nearest(_refuse(f"gravity is {ang_u:.0f} deg from every sensor axis (more than "
                                    f"{max_snap_deg:g})", up), acc, gyr, fs, max_snap_deg)
    hor = [i for i in range(3) if i != i_u]
    e = np.eye(3)
    # horizontal basis: the two other sensor axes made orthogonal to up (the unit's tilt removed)
    b = [_unit(e[i] - (e[i] @ up) * up) for i in hor]
    b[1] = _unit(b[1] - (b[1] @ b[0]) * b[0])
    B = np.column_stack(b)
    fast: list = []
    stride: list = []
    yaw = None if gyr is None or np.shape(gyr) != acc.shape else np.asarray(gyr, dtype=float) @ up  # W333
    C, z, walk_s, rhythm = _step_spectra(acc @ up, acc @ B, fs, fast_out=fast, stride_out=stride, yaw_rate=yaw)
    # half a sample of tolerance: one 4 s window of walking covers 400 samples, which at a rate of 100.000000000001 Hz
    # (a clock in ms read back) are 3.99999999999996 s; it was refused as "less than 4 s" (review of W61)
    if walk_s < MIN_WALK_S - 0.5 / fs:
        err = FrameInferenceError(f"less than {MIN_WALK_S:g} s of walking (vertical acceleration std over 0.5 "
                                  "m/s^2 in 4 s windows" + (", turning windows left out: W333)" if yaw is not None
                                                            else ")"))
        err.walk_s = walk_s  # W61: a waist track of such a recording has no steps to place
        raise err
    min_sigma = MIN_RHYTHM_SIGMA_LOW_RATE if fs < LOW_RATE_HZ else MIN_RHYTHM_SIGMA  # decision W452
    if rhythm < min_sigma and stride and stride[0][0] >= min_sigma:  # decision W226
        raise FrameInferenceError(f"the vertical acceleration of the {walk_s:.0f} s that move repeats at a stride of "
                                  f"{stride[0][1]:.2f} s (autocorrelation {stride[0][0]:.1f} noise standard "
                                  f"deviations) but at no step period of {RHYTHM_LAG_S[0]:g}-{RHYTHM_LAG_S[1]:g} s "
                                  f"({rhythm:.1f} < {min_sigma:g}): alternating short and long steps (an "
                                  "asymmetric gait) or very slow walking, on which this test, which reads the step "
                                  "frequency, is not validated (decision W226)")
    if rhythm < min_sigma:
        raise FrameInferenceError(f"no walking rhythm: the vertical acceleration of the {walk_s:.0f} s that move "
                                  f"repeats at no step or stride period of {RHYTHM_LAG_S[0]:g}-{RHYTHM_LAG_S[1]:g} s "
                                  f"(autocorrelation {rhythm:.1f} < {min_sigma:g} noise standard deviations"
                                  + (f" at {fs:g} Hz, W452" if fs < LOW_RATE_HZ else "") + ")"
                                  + (f" nor at a stride of {STRIDE_ONLY_LAG_S[0]:g}-{STRIDE_ONLY_LAG_S[1]:g} s "
                                     f"({stride[0][0]:.1f}; decision W226)" if stride else ""))
    n_fast, n_walk = fast[0]  # after the rhythm check: noise has no rhythm, and no step band
    if n_walk and n_fast > MAX_FAST_FRACTION * n_walk:  # decision B79
        raise FrameInferenceError(f"the vertical acceleration peaks above 3 Hz (over 180 steps/min) in {n_fast} of "
                                  f"{n_walk} walking windows: faster than the 72-180 steps/min the waist axis test "
                                  "reads (running is not supported, L95)")
    w, vecs = np.linalg.eigh(C)
    ratio = float(w[1] / max(w[0], 1e-12))
    if ratio < MIN_AP_POWER_RATIO:
        raise FrameInferenceError(f"no horizontal axis dominates at step frequency (power ratio {ratio:.2f} < "
                                  f"{MIN_AP_POWER_RATIO:g}): forward and lateral are ambiguous")
    ap = B @ vecs[:, 1]
    zc = complex(vecs[:, 1] @ z)
    lead = float(np.degrees(np.angle(zc)))
    margin = 90.0 - abs(((lead - 45.0 + 180.0) % 360.0) - 180.0)
    if abs(margin) < MIN_PHASE_MARGIN_DEG:
        raise FrameInferenceError(f"the forward/vertical phase at step frequency ({lead:.0f} deg) does not tell "
                                  "forward from backward")
    if push_lead_deg is not None and push_lead_deg[0] <= lead % 360.0 <= push_lead_deg[1]:  # decision W540
        raise FrameInferenceError(f"the forward/vertical phase at step frequency ({lead:.0f} deg) does not tell "
                                  f"forward from backward: up to {push_lead_deg[1] - push_lead_deg[0]:.0f} deg past "
                                  "the forward half, where an impulsive forward push at each step (Nordic-walking "
                                  "pole plants) puts a forward walker's lead (decision W540)")
    # decision W2: forward when the lead lies within +-90 deg of 45 deg (the one rule, shared with the heading)
    fwd = ap * forward_sign(np.array([1.0]), np.array([zc.real]), np.array([-zc.imag]), 1.0, 0.0)
    i_f, s_f, ang_f = _nearest_axis(fwd, exclude=(i_u,))
    if ang_f > max_snap_deg:  # W394, as for gravity
        err = _refuse(f"the forward direction is {ang_f:.0f} deg from both horizontal sensor axes "
                      f"(more than {max_snap_deg:g})" + asymmetric_forward_words(ratio), up,
                      _unit(fwd - (fwd @ up) * up))
        err.ap_power_ratio = ratio  # decision W435
        raise _with_nearest(err, acc, gyr, fs, max_snap_deg)
    left = np.cross(e[i_u] * s_u, e[i_f] * s_f)
    i_l = int(np.argmax(np.abs(left)))
    frame = frame_from_axes((i_f, s_f), (i_l, float(np.sign(left[i_l]))), (i_u, s_u))
    return InferredFrame("waist", frame, up=up, forward=_unit(fwd - (fwd @ up) * up), ap_power_ratio=ratio, evidence={
        "up": f"{'xyz'[i_u]}{'+' if s_u > 0 else '-'} ({ang_u:.0f} deg tilt)",
        "forward": f"{'xyz'[i_f]}{'+' if s_f > 0 else '-'} ({ang_f:.0f} deg off, step-frequency power x{ratio:.1f})",
        "forward lead": f"{lead:.0f} deg over {walk_s:.0f} s of walking (rhythm {rhythm:.0f} sigma; the sign "
                        "assumes the walker mostly walks forward)",
    })


INFER = {"foot": infer_foot_frame, "waist": infer_waist_frame}
#: Accelerometer and gyroscope streams of each unit.
UNIT_STREAMS = UNIT_IMU


#: The D10 check of a declared frame reads at most this much of a recording from its first walk (s, decision B252's
#: :func:`check_span`; from its start before B252): minutes of
#: walking fix the axes as well as an hour does, and a 1 h track must not pay a second pass over its data.
CHECK_SPAN_S = 300.0
#: decision L223 (amends D23): D23 refuses a reversed foot forward only when the check measured it from at least
#: this many strides (> MIN_STRIDE_M) with at least this mean resultant: the smallest count and resultant (rounded
#: down to 0.05) of the validated-range walks of selection users 4110-4114 (scenario A: 11 strides; scenario C: 0.89)
#: and the gaitmap foot recordings (walk4x10_left: 0.86) (experiments/frame_check_evidence.py); the 40 steps/min
#: crawls that read reversed: 5 strides / 0.54 (the trial's), 10 / 0.62 (user 4115)
REFUSE_MIN_STRIDES = 11
REFUSE_MIN_RESULTANT = 0.85


#: decision B252: the check span starts this long (s) before the first walking window, one W4 window: the foot's
#: rest before its first stride, and the waist's first steps, are in it
SPAN_LEAD_S = 4.0


def check_span(t: np.ndarray, acc: np.ndarray, max_s: float, *, window_s: float = 4.0,
               walk_std: float = 0.5) -> tuple[int, int]:
    """Decision B252: the sample range ``[i0, i1)`` of the ``max_s`` seconds a check reads: from
    :data:`SPAN_LEAD_S` before the first window of ``window_s`` (on a grid from ``t[0]``) whose |acc| varies by more
    than ``walk_std`` m/s^2 (the W4 motion gate of :func:`_walking_mean`), else from the start. A night starting
    with an hour in bed has no walking in its first 300 s; its first walk does."""
    t = np.asarray(t, dtype=float)
    if len(t) == 0:
        return 0, 0
    norm = np.linalg.norm(np.asarray(acc, dtype=float), axis=1)
    idx = np.floor((t - t[0]) / window_s).astype(np.int64)
    cnt = np.bincount(idx)
    s1, s2 = np.bincount(idx, norm), np.bincount(idx, norm * norm)
    with np.errstate(invalid="ignore", divide="ignore"):
        m = s1 / cnt
        sd = np.sqrt(np.maximum(s2 / cnt - m * m, 0.0))
    moving = np.flatnonzero((cnt >= 8) & (sd >= walk_std))
    start = t[0] if moving.size == 0 else max(t[0], t[0] + moving[0] * window_s - SPAN_LEAD_S)
    i0 = int(np.searchsorted(t, start, side="left"))
    return i0, int(np.searchsorted(t, start + max_s, side="right"))


def infer_session_frame(session, placement: str, *, max_s: float | None = None) -> InferredFrame:
    """Infer the ``placement`` unit's frame from a :class:`~pdrlearn.io.Session` (the gyroscope on the
    accelerometer's clock), from ``max_s`` seconds when given, from its first walk (:func:`check_span`, decision
    B252; default: all of it). Raises :class:`FrameInferenceError` (a :class:`DataError`) with the reason."""
    from pdrlearn.signal.filters import interp_rows

    if placement not in INFER:
        raise FrameInferenceError(f"no inference for a '{placement}' unit")
    acc_n, gyr_n = UNIT_STREAMS[placement]
    missing = [n for n in (acc_n, gyr_n) if n not in session.streams]
    if missing:
        raise FrameInferenceError(f"it has no {' or '.join(missing)} to infer it from")
    acc_s, gyr_s = session.streams[acc_n], session.streams[gyr_n]
    if len(acc_s) < 8 or len(gyr_s) < 2 or not np.isfinite(acc_s.rate_hz):
        raise FrameInferenceError("too few samples")
    i0, n = (0, len(acc_s)) if max_s is None else check_span(acc_s.t, acc_s.values, max_s)  # decision B252
    acc, gyr = acc_s.values[i0:n], interp_rows(acc_s.t[i0:n], gyr_s.t, gyr_s.values)
    if not (np.isfinite(acc).all() and np.isfinite(gyr).all()):
        raise FrameInferenceError("NaN or infinite values")
    return INFER[placement](acc, gyr, float(acc_s.rate_hz))

def frame_disagreement(declared: AxisFrame, found: InferredFrame) -> dict[str, float]:
    """Body directions (``up``, ``forward``, ``left``) for which the ``declared`` frame's sensor direction
    lies more than :data:`MAX_DECLARED_OFF_DEG` from the direction measured in the data (``found.up``,
    ``found.forward``, left = up x forward), with the angle in degrees; ``{}`` when the declared frame is
    a possible nearest-axis declaration of what the data show (decision D10)."""
    return directions_off(declared, found.up, found.forward, MAX_DECLARED_OFF_DEG)


def directions_off(declared: AxisFrame, up: np.ndarray | None, forward: np.ndarray | None,
                   limit: float) -> dict[str, float]:
    """The declared frame's body directions more than ``limit`` deg from the measured ``up`` / ``forward``
    (sensor axes; either may be ``None``: not measured) and left = up x forward, with their angles (deg)."""
    R = declared.matrix()  # sensor -> body; its rows are the body directions in sensor axes
    measured = {"up": up, "forward": forward,
                "left": None if up is None or forward is None else np.cross(up, forward)}
    body = {"forward": R[0], "left": R[1], "up": R[2]}
    out = {}
    for name in ("up", "forward", "left"):
        if measured[name] is None:
            continue
        ang = float(np.degrees(np.arccos(np.clip(float(_unit(body[name]) @ _unit(measured[name])), -1.0, 1.0))))
        if ang > limit:
            out[name] = ang
    return out


def forward_reversal_deg(declared: AxisFrame, up: np.ndarray | None, forward: np.ndarray | None) -> float | None:
    """Decision D22: the angle (deg) between the horizontal part of the declared forward (its sensor direction
    with the measured ``up`` removed: the heading a track levelled by gravity walks) and the measured horizontal
    ``forward``; ``None`` when either is not measured, or the declared forward is within
    :data:`MIN_FORWARD_ELEVATION_DEG` of vertical (no heading to compare)."""
    if up is None or forward is None:
        return None
    f = declared.matrix()[0]
    u = _unit(up)
    h = f - (f @ u) * u
    if float(np.linalg.norm(h)) < np.sin(np.radians(MIN_FORWARD_ELEVATION_DEG)):
        return None
    fw = _unit(forward - (forward @ u) * u)
    return float(np.degrees(np.arccos(np.clip(float(_unit(h) @ fw), -1.0, 1.0))))


def forward_yaw_deg(declared: AxisFrame, up: np.ndarray | None, forward: np.ndarray | None) -> float | None:
    """Decision L796: :func:`forward_reversal_deg`'s angle signed, about the measured ``up`` (deg, + = the measured
    walking direction lies counter-clockwise, to the left, of the declared forward seen from above): what a compass
    reading the declared forward's heading is to be turned by to read the walking direction (a unit yawed on its
    belt); ``None`` as :func:`forward_reversal_deg`."""
    mag = forward_reversal_deg(declared, up, forward)
    if mag is None:
        return None
    u = _unit(up)
    h = declared.matrix()[0]
    h = h - (h @ u) * u
    return mag if float(np.cross(h, forward) @ u) >= 0.0 else -mag


@dataclass
class DeclaredCheck:
    """What the data say of a declared frame (decisions D10, D22): ``message`` the warning or refusal text
    (without the ``meta.json`` location; ``None``: nothing to say), ``refuse`` True when the declared forward
    is reversed against the data, ``unchecked`` why the data could not judge it (the inference's reason;
    ``None`` when it ran), ``compared`` the directions the data could still compare when it gave up,
    ``forward_deg`` the horizontal angle (deg) between the declared forward and the measured walking direction
    (``None``: not measured; decision D25 reads it for the waist compass)."""

    message: str | None = None
    refuse: bool = False
    unchecked: str | None = None
    compared: tuple[str, ...] = ()
    forward_deg: float | None = None
    #: decision C142: a frame the data reject (D23, D28, D30) kept by ``"force_frame"``
    forced: bool = False
    #: decision W415: not judged, the foot unit's strides mostly travel sideways or backward (``unchecked`` says so)
    side_drill: bool = False
    #: decision W435: the waist forward measurement's step-frequency power ratio (None: not measured or a foot)
    forward_power_ratio: float | None = None
    #: decision W607: the frame the data give, used instead of the declared one (``mount_frame="inferred"``); None:
    #: the declared frame is used
    used_found: AxisFrame | None = None
    #: decision L796: the signed angle (deg) from the used frame's forward to the measured walking direction
    #: (:func:`forward_yaw_deg`; None: not measured)
    forward_yaw_deg: float | None = None

    def summary(self) -> str:
        """``info``'s words for a check that raised nothing (decision D22: never "not contradicted" unchecked)."""
        if self.unchecked is None:
            return "not contradicted by the data (D10)"
        if self.compared:
            return (f"its {' and '.join(self.compared)} not reversed by the data; which axis is which not checked "
                    f"({self.unchecked})")
        return f"not checked ({self.unchecked})"


def _span_check(session, placement: str, declared: AxisFrame, max_s: float | None) -> tuple:
    """D10 / D22's inference for :func:`check_declared_frame` over ``max_s`` seconds from the first walk (None: the
    whole recording): ``(found, unchecked, off, evidence, up, forward, compared, ratio)`` (ratio: W435's forward
    power ratio)."""
    unchecked, compared, up, fwd, ratio = None, (), None, None, None
    try:
        found = infer_session_frame(session, placement, max_s=max_s)
    except FrameInferenceError as exc:
        found, unchecked, off = None, str(exc), {}
        evidence, ratio = (exc.n_strides, exc.resultant), exc.ap_power_ratio
        if exc.forward is not None:  # gave up after measuring the strides' signed direction (past D9's push-off)
            up, fwd, compared = exc.up, exc.forward, ("up", "forward")
            off = directions_off(declared, up, None, OPPOSED_DEG)  # up only: which axis is forward is unknown
    except DataError as exc:
        found, unchecked, off = None, str(exc), {}
        evidence = (None, None)
    else:
        up, fwd = found.up, found.forward
        off = frame_disagreement(declared, found)
        evidence, ratio = (found.n_strides, found.resultant), found.ap_power_ratio
    return found, unchecked, off, evidence, up, fwd, compared, ratio


def check_declared_frame(session, placement: str, declared: AxisFrame, *, side_words: bool = False,
                         mount_frame: str = "declared", command: str | None = None) -> DeclaredCheck:
    """The data's word on a declared or ``source_project`` frame: a warning (without the ``meta.json``
    location) when it is left-handed or the data contradict it with confidence (decision D10); a refusal when
    its forward is reversed against the data (decision D22), also when the inference gives up on which
    axis is forward but measured the strides' direction and gravity (:class:`FrameInferenceError` ``up`` /
    ``forward``; a reversed up alone is D10's warning). The inference runs once here, on the first
    :data:`CHECK_SPAN_S` seconds; decision W453: a waist frame they contradict, again on the whole recording, whose
    answer (when it fixes the axes) is the one judged. Decision W415: a waist frame is not judged when the foot
    unit's strides in that span mostly travel sideways or backward
    (:func:`pdrlearn.track.stride_kinds.not_judged`). ``side_words`` (decision W416 (b), not adopted: its rule's
    waist-only backpedal, user 10022, reads forward, so there is no line to word; opt-in, False = D10's line as
    before): a waist line without a foot unit leads with :func:`side_travel_words`. ``mount_frame`` (decision W607):
    ``"inferred"`` uses the frame the data give when they contradict the declared one with confidence (a unit clipped
    turned on its mount: a side-clipped lower back), one line saying so, never a refusal; ``"declared"`` (the
    default) keeps the declared frame with D10's line, naming the option when ``command`` (decision W615: ``track`` or
    ``track-all``, the commands that have it) reads the session."""
    if isinstance(session.meta.get("frames"), dict):
        origin = 'declared in "frames"'
    else:
        origin = f"implied by source_project {json.dumps(str(session.meta.get('source_project', '')))}"
    found, unchecked, off, evidence, up, fwd, compared, ratio = _span_check(session, placement, declared, CHECK_SPAN_S)
    if placement == "waist" and off:
        # decision W453: a waist frame the first CHECK_SPAN_S contradict is judged on the whole recording (B252's
        # cost paid only then): a night's span from its first movement held the bed's, not the later walk
        whole = _span_check(session, placement, declared, None)
        if whole[1] is None:
            found, unchecked, off, evidence, up, fwd, compared, ratio = whole
    rev = forward_reversal_deg(declared, up, fwd)
    yaw = forward_yaw_deg(declared, up, fwd)  # decision L796 (read by the compass-headed track)
    reverse = rev is not None and rev > OPPOSED_DEG
    if reverse and "forward" not in off:  # the heading reversed though the axis is pitched (D22)
        off["forward"] = rev
    how = misdeclared(declared, found, rev)  # decisions D28, D30: turned, or the vertical axis declared forward
    if how is not None and "forward" not in off:
        off["forward"] = directions_off(declared, None, found.forward, 0.0)["forward"]
    reverse = reverse or how is not None
    skip = _waist_not_judged(session) if placement == "waist" else None
    if skip is not None:  # decision W415: no line but a left-handed one; D25 still reads the measured offset
        return DeclaredCheck(declared_frame_warning(placement, declared, None, origin, off={}), False, skip,
                             compared, rev, side_drill=True, forward_power_ratio=ratio)  # L796: a drill's yaw is none
    if mount_frame == "inferred" and off and found is not None:  # decision W607: the data's frame, said once
        msg = declared_frame_warning(placement, declared, found, origin, off=off, data_used=True)
        return DeclaredCheck(msg, False, unchecked, compared, rev, forward_power_ratio=ratio, used_found=found.frame,
                             forward_yaw_deg=forward_yaw_deg(found.frame, up, fwd))  # L796: the frame used
    forced = reverse and session.frame_forced(placement)  # decision D23's override
    refuse = reverse and not forced and placement in REFUSE_REVERSED  # D23 amended: the foot only
    used = 'the meta.json frame ("force_frame", decision D23)' if forced else "the meta.json frame"
    if refuse and weak_reversal(*evidence):  # decision L223: too little evidence to refuse
        return DeclaredCheck(weak_reversal_warning(placement, declared, origin, rev, *evidence, how=how), False,
                             unchecked, compared, rev, forward_power_ratio=ratio, forward_yaw_deg=yaw)
    msg = declared_frame_warning(placement, declared, found, origin, used, off=off, refuse=refuse,
                                 unchecked=unchecked, how=how, command=command)  # decision W615
    if side_words and msg and placement == "waist" and UNIT_STREAMS["foot"][0] not in session.streams:
        msg = side_travel_words(rev) + msg if side_travel_words(rev) else msg  # decision W416
    return DeclaredCheck(msg, refuse, unchecked, compared, rev, forced=forced, forward_power_ratio=ratio,
                         forward_yaw_deg=yaw)


#: decision W416 (b): D10's waist line on a session without a foot unit leads with side or backward travel when the
#: measured walking direction is more than this (deg) from the declared forward (L219's side window's edge)
SIDE_FROM_DEG = 60.0

def side_travel_words(rev: float | None) -> str:
    """Decision W416 (b): the words that lead D10's waist line on a session without a foot unit when the measured
    walking direction lies ``rev`` deg (over :data:`SIDE_FROM_DEG`) from the declared forward: side or backward
    movement, which the lower-back pipelines place forward, named before a wrong frame; "" otherwise."""
    if rev is None or rev <= SIDE_FROM_DEG:
        return ""
    return (f"the waist unit's measured walking direction is {rev:.0f} deg from its declared forward: side or "
            "backward movement (side shuffles, backpedals) reads so with a right frame, and the lower-back pipelines "
            "place it forward (the distance counts it as forward walking; a foot unit tells the way each stride "
            "went; decision W416) - write the \"frames\" entry below only if the walker walked forward. D10: ")


def _waist_not_judged(session) -> str | None:
    """Decision W415: why the waist unit's declared frame is not judged over D10's check span (B252's first walk, up to
    :data:`CHECK_SPAN_S` s): the foot unit's strides there mostly travel sideways or backward; None: judge it."""
    from pdrlearn.track.stride_kinds import foot_stride_kinds, not_judged

    acc_s = session.streams.get(UNIT_STREAMS["waist"][0])
    if acc_s is None or len(acc_s) < 8:
        return None
    i0, n = check_span(acc_s.t, acc_s.values, CHECK_SPAN_S)
    if n <= i0:
        return None
    return not_judged(foot_stride_kinds(session, (float(acc_s.t[i0]), float(acc_s.t[n - 1]))))


def misdeclared(declared: AxisFrame, found: InferredFrame | None, rev: float | None) -> str | None:
    """Decisions D28, D30: how a declared frame's forward is wrong though not reversed (D22's ``rev`` at most
    :data:`OPPOSED_DEG`), when the data fix the frame (``found``): ``"turned by N deg"`` beyond
    :data:`MISDECLARED_DEG`, ``"the unit's vertical axis"`` when the declared forward lies within
    :data:`MIN_FORWARD_ELEVATION_DEG` of the measured up (``rev`` None); else ``None``."""
    if found is None or found.up is None or found.forward is None:
        return None
    if rev is None:  # D30: no heading to compare, the declared forward is (near) vertical
        return "the unit's vertical axis, decision D30"
    if MISDECLARED_DEG < rev <= OPPOSED_DEG:  # D28
        return f"turned by {rev:.0f} deg, decision D28"
    return None


def weak_reversal(n_strides: int | None, resultant: float | None) -> bool:
    """Decision L223: a foot forward measured from fewer than :data:`REFUSE_MIN_STRIDES` strides or with a
    resultant under :data:`REFUSE_MIN_RESULTANT` is too little evidence for D23's refusal."""
    if n_strides is None or resultant is None:
        return False
    return n_strides < REFUSE_MIN_STRIDES or resultant < REFUSE_MIN_RESULTANT


def weak_reversal_warning(placement: str, declared: AxisFrame, origin: str, rev: float | None, n_strides: int,
                          resultant: float, *, how: str | None = None) -> str:
    """Decision L223: the line for a declared foot frame that reads reversed (``how``: or turned, or its vertical
    axis declared forward, D28/D30) on too little evidence: the frame is used, no other frame is suggested, and the
    likely cause (a walk slower than L95's range) is named."""
    reads = (f"reads reversed against its data (forward {rev:.0f} deg from the strides' direction)"
             if how is None else f"reads wrong against its data (its forward is {how})")
    return (f"the {placement} unit's frame {json.dumps(declared.to_dict())} ({origin}) {reads}, "
            f"but on too little evidence to refuse it "
            f"(the strides' direction from {n_strides} strides of more than {MIN_STRIDE_M:g} m, resultant "
            f"{resultant:.2f}; decision L223 refuses on at least {REFUSE_MIN_STRIDES} strides and a resultant of "
            f"{REFUSE_MIN_RESULTANT:g}): the meta.json frame is still used. Few long strides with a common direction "
            f"in the first {CHECK_SPAN_S:.0f} s is what a walk slower than the walking the pipelines are validated "
            "on gives (70-160 steps/min, 0.5-2.5 m/s, decision L95): the track is then not reliable")


def _turned(declared: AxisFrame, names: set[str]) -> AxisFrame:
    """The ``declared`` frame with the body directions ``names`` (two of forward, left, up) reversed: turned
    180 deg about the third, still right-handed when the declared one is."""
    opp = {"forward": "backward", "backward": "forward", "left": "right", "right": "left", "up": "down",
           "down": "up"}
    base = {"backward": "forward", "right": "left", "down": "up"}
    return AxisFrame(**{a: opp[d] if base.get(d, d) in names else d for a, d in declared.to_dict().items()})


def declared_frame_warning(placement: str, declared: AxisFrame, found: InferredFrame | None, origin: str,
                           used: str = "the meta.json frame", *, off: dict[str, float] | None = None,
                           refuse: bool = False, unchecked: str | None = None, how: str | None = None,
                           data_used: bool = False, command: str | None = None) -> str | None:
    """Decision D10's warning for a ``declared`` frame (``origin``: where it was declared) against the frame
    ``found`` in the data (``None``: the data did not fix it), or ``None`` when there is nothing to say. Shared by
    :func:`check_declared_frame` (offline) and the live ``WaistTracker`` (decision B108, ``used``: what it keeps).
    ``off`` (default: D10's disagreement with ``found``) may come from the directions measured when the
    inference gave up (``unchecked``: its reason); ``refuse`` words it as D22's refusal (``how``: D28/D30's words
    for a forward turned or vertical, :func:`misdeclared`; None: reversed). ``data_used`` (decision W607): the frame
    ``found`` is used instead (``mount_frame="inferred"``), said so. ``command`` (decision W615): the command reading
    the session that takes ``--mount-frame`` (``track``, ``track-all``), named in the line's fix; None (every other
    command, the live tracker, a notebook): the option is not named."""
    if off is None:
        off = frame_disagreement(declared, found) if found is not None else {}
    left_handed = not declared.right_handed
    if not off and not left_handed:
        return None
    what = f"the {placement} unit's frame {json.dumps(declared.to_dict())} ({origin})"
    issues = []
    if left_handed:
        issues.append("is left-handed (IMU axes are right-handed: one axis is probably reversed)")
    angles = ", ".join(f"{k} {v:.0f} deg from the declared {k}" for k, v in off.items())
    if off and found is not None:
        issues.append(f"contradicts its data, which give {json.dumps(found.frame.to_dict())} ({angles}; "
                      f"{found.describe()})")
    elif off:  # D22: the inference gave up on which axis is which, but the reversal is unambiguous
        measured = " and ".join("the strides' direction" if k == "forward" else "gravity" for k in off)
        issues.append(f"is reversed against its data ({angles}, measured from {measured}; the data do not fix "
                      f"which axis is which: {unchecked})")
    if off and found is not None:
        fix = f'if the data are right, write "frames": {json.dumps({placement: found.frame.to_dict()})} in meta.json'
        if not refuse and command is not None:  # W607: a batch need not be edited one by one; W615: if it has it
            fix += f" (or run {command} with --mount-frame inferred, decision W607)"
    elif off:
        flip = set(off) if len(off) == 2 else {*off, "left"}  # turned 180 deg about the direction that agrees
        fix = (f'if the data are right, write "frames": {json.dumps({placement: _turned(declared, flip).to_dict()})} '
               "in meta.json (the declared frame turned 180 deg)")
    else:
        fix = "declare the device's right-handed frame in meta.json"
    if set(off) == {"left"}:  # up and forward agree, left reversed: a wrong entry, or mirrored data
        fix = (f"{fix}; but if the declared axes are right, the data are mirrored (one axis column negated, "
               "e.g. by a left-handed export): negate that column in the CSV files instead")
    if {"up", "forward"} <= set(off) and min(off["up"], off["forward"]) > 150.0:  # B48: turned 180 deg about left
        acc_n = UNIT_STREAMS[placement][0]
        fix = (f"{fix}; but if the declared axes are right, the accelerometer reports gravity as -1 g (iOS Core "
               f"Motion exports do): negate all three columns of {acc_n}.csv (pdrlearn import --acc=-X,-Y,-Z) "
               "instead, since writing the data's frame would mirror every turn")
    if data_used and off and found is not None:  # decision W607: mount_frame "inferred"
        return (f"{what} {' and '.join(issues)}; the frame the data give is used instead (mount_frame \"inferred\", "
                f"decision W607): to declare it, write \"frames\": {json.dumps({placement: found.frame.to_dict()})} in "
                "meta.json")
    if refuse:  # decision D22: a reversed track is never what is meant (D28, D30: nor a turned one)
        tracked = ("reversed" if how is None else f"turned (the declared forward is {how})")
        return (f"{what} {' and '.join(issues)}; every stride would be tracked {tracked}, so it is not used "
                f"(decision D23): {fix}; or, to use it anyway, add \"force_frame\": true to meta.json")
    return f"{what} {' and '.join(issues)}; {used} is still used (decision D8): {fix}"


def frame_after_negating(session, placement: str, axis: str) -> AxisFrame | None:
    """Decision D30: the frame the data give (:func:`infer_session_frame`, the first :data:`CHECK_SPAN_S` s) once the
    ``placement`` unit's ``axis`` ("x", "y" or "z") is negated in all its streams (D11's fix of a mirrored pair);
    ``None`` when the data do not fix it."""
    R = np.diag([-1.0 if a == axis else 1.0 for a in "xyz"])
    try:
        return infer_session_frame(remount(session, placement, R), placement, max_s=CHECK_SPAN_S).frame
    except DataError:
        return None


def remount(session, placement: str, rotation: np.ndarray):
    """A copy of ``session`` with the ``placement`` unit's 3-axis streams (accelerometer, gyroscope,
    magnetometer) expressed in a remounted sensor frame: ``v_new = rotation @ v_old``. A declared frame
    follows (``M rotation^T``) when that is still a signed permutation, else it is dropped (a yaw of 45 deg
    cannot be declared). For tests and experiments: every orientation of a unit from one recording."""
    from pdrlearn.io.session import Stream

    R = np.asarray(rotation, dtype=float)
    out = session.copy()
    out._inferred = {}
    out._checked = {}
    for name, st in session.streams.items():
        if st.placement == placement and st.values.ndim == 2 and st.values.shape[1] == 3:
            out.streams[name] = Stream(name, st.t.copy(), st.values @ R.T)
    if placement in out.frames:
        M = np.round(out.frames[placement].matrix() @ R.T, 9)
        names = {}
        for j, axis in enumerate("xyz"):
            hit = [d for d, v in _DIRECTIONS.items() if np.allclose(M[:, j], v)]
            if not hit:
                del out.frames[placement]
                break
            names[axis] = hit[0]
        else:
            out.frames[placement] = AxisFrame(**names)
    return out


def right_handed_orientations() -> list[np.ndarray]:
    """The 24 signed permutation matrices with determinant +1 (every 90-degree mounting of a unit)."""
    import itertools

    out = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1.0, -1.0), repeat=3):
            P = np.zeros((3, 3))
            P[[0, 1, 2], list(perm)] = signs
            if np.linalg.det(P) > 0:
                out.append(P)
    return out


__all__ = ["FrameInferenceError", "InferredFrame", "infer_foot_frame", "infer_waist_frame", "frame_from_axes",
           "infer_session_frame", "frame_disagreement", "check_declared_frame", "declared_frame_warning",
           "DeclaredCheck", "directions_off", "forward_reversal_deg", "forward_yaw_deg", "OPPOSED_DEG",
           "MISDECLARED_DEG", "misdeclared",
           "rest_to_rest", "rest_swings", "stride_displacements", "swing_pitch_extremes", "remount",
           "frame_after_negating", "right_handed_orientations", "INFER", "UNIT_STREAMS"]
