"""Per-stride displacement of the foot unit (thesis ch.7.2.1): stance, ZUPT/ZARU, attitude,
gravity removal and integration (equations of motion or the white-noise-jerk Kalman filter)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
from scipy.ndimage import uniform_filter1d

from pdrlearn.displace import _kernels as K
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels import stride as SK
from pdrlearn.kernels.clip_noise import clip_variance
from pdrlearn.kernels.frozen_foot import FORCE_LOAD_LEVEL
from pdrlearn.kernels.turn import unwrapped_turn, unwrapped_twists
from pdrlearn.orient import FootAttitude, UnitData
from pdrlearn.settings import Rule, annotation_words, broken, broken_line
from pdrlearn.signal import standstill_mask
from pdrlearn.signal.conditioning import runs

log = logging.getLogger(__name__)


def force_stance(session: Session, t: np.ndarray, gyr: np.ndarray | None = None, *, level: float = FORCE_LOAD_LEVEL,
                 gyr_tol: float = 0.4, window_s: float = 0.1) -> np.ndarray | None:
    """Zero-velocity samples from the force sensors: the foot is loaded (heel fForceA or toe fForceB above
    ``level`` x its own 95th percentile; N or normalised units) and, when ``gyr`` (n, 3) is given, not
    rotating (mean |gyro| over ``window_s`` below ``gyr_tol`` rad/s: the unit moves while the foot
    rolls over heel or toe). Returns None when the session has no usable force sensor.
    """
    names = [n for n in ("fForceA", "fForceB") if n in session.streams and len(session.streams[n]) >= 2]
    if not names:
        return None
    acc = session.streams.get("fAccelerometer")
    if acc is not None and acc.t.shape == np.shape(t) and np.array_equal(acc.t, t):  # B21: on its clock
        session.require_cover("fAccelerometer", *names)
    loaded = np.zeros(t.shape[0], dtype=bool)
    for n in names:
        s = session.streams[n]
        f = np.interp(t, s.t, s.values[:, 0])
        ref = float(np.percentile(f, 95))
        if not np.isfinite(ref) or ref <= 0:
            return None
        loaded |= f > level * ref
    if gyr is None:
        return loaded
    fs = 1.0 / float(np.median(np.diff(t)))
    w = max(1, int(round(window_s * fs)))
    calm = uniform_filter1d(np.linalg.norm(gyr, axis=1), w, mode="nearest") < gyr_tol
    return loaded & calm


#: steps decision 61: the window (s) of the offline rest's L27 floor (the streamed segmenter keeps
#: ``STANCE_L27_DEFAULTS["stance_floor_window_s"]``, its trailing window)
OFFLINE_FLOOR_WINDOW_S = SK.STANCE_L27_DEFAULTS["stance_floor_window_s"]


def inertial_stance(acc: np.ndarray, gyr: np.ndarray, fs: float, *, window_s: float = 0.1,
                    acc_tol: float = 1.5, gyr_tol: float = 0.4,
                    floor_factor: float = SK.STANCE_L27_DEFAULTS["stance_floor_factor"],
                    floor_window_s: float | None = None,
                    gyr_max: float = SK.STANCE_L27_DEFAULTS["stance_gyro_max_rad_s"],
                    rhythm_frac: float | None = None) -> np.ndarray:
    """Foot-flat samples from accelerometer + gyroscope (short window, looser tolerances than
    :func:`pdrlearn.signal.standstill_mask`, whose test this reuses).

    Decision L27: the gyro tolerance follows the walker's own stance rotation: ``floor_factor`` x the
    lowest ``window_s`` mean of |w| within ``floor_window_s`` around the sample, never below ``gyr_tol``
    nor above ``gyr_max`` (a foot that never quite rests: instep mounts rolling with the foot, short
    foot-flats); ``floor_factor=0`` = the fixed ``gyr_tol``.

    Decisions L596/L597: a rest shorter than ``rhythm_frac`` x the foot's own stride period
    (:func:`pdrlearn.kernels.foot_rhythm.stride_period`) is a slow swing's lull, not a rest, where that asks more
    than ``window_s`` (a slow rhythm; None: ``RHYTHM_FRAC``, 0: keep every run).
    """
    window_s = max(window_s, 2.5 / fs)
    floor_window_s = OFFLINE_FLOOR_WINDOW_S if floor_window_s is None else floor_window_s
    tol = gyr_tol
    if floor_factor > 0 and len(gyr):
        floor = SK.stance_floor(np.linalg.norm(np.asarray(gyr, dtype=float), axis=1), fs, mean_s=window_s,
                                window_s=floor_window_s)
        tol = SK.stance_gyro_threshold(floor, gyr_tol, factor=floor_factor, cap=gyr_max)
    rest = standstill_mask(acc, gyr, fs, window_s=window_s, acc_tol=acc_tol, gyr_tol=tol)
    rhythm_frac = FR.RHYTHM_FRAC if rhythm_frac is None else rhythm_frac
    if rhythm_frac > 0 and len(gyr):
        min_rest_s = FR.min_rest_s(FR.foot_period(gyr, fs, window_s), window_s, rhythm_frac)
        if min_rest_s > 0:  # decision L597: shorter rests are the window test's own to decide
            rest = FR.drop_short_rests(rest, int(np.floor(min_rest_s * fs)))
    return rest


def stance_runs(t: np.ndarray, stance: np.ndarray, *, merge_s: float = SK.STANCE_MERGE_S) -> np.ndarray:
    """(k, 2) start/stop indices (stop exclusive) of stance runs, runs closer than ``merge_s`` merged."""
    merged: list[list[int]] = []
    for a, b in runs(stance):
        if merged and t[a] - t[merged[-1][1] - 1] <= merge_s:
            merged[-1][1] = b
        else:
            merged.append([a, b])
    return np.array(merged, dtype=np.int64).reshape(-1, 2)


def rest_to_rest(t: np.ndarray, stance: np.ndarray, starts: np.ndarray, ends: np.ndarray, *,
                 max_rest_s: float = 0.3, tol_s: float = 0.2, all_rows: bool = False, events=None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Turn detected step windows into rest-to-rest strides of the foot unit.

    A detector may report the swing (toe-off to contact) or a stance-to-stance window; either way the
    stride used for integration runs from the middle of the stance before the window start to the middle
    of the stance after the window end (at most ``max_rest_s`` into a longer rest). A window spanning
    several stances (the detector missed steps) is split at each of them; windows whose start and end
    fall in the same stance, and duplicates, are dropped.

    Returns
    -------
    i0, i1 : sample indices of the stride boundaries;  keep : indices of the input rows used
    (``all_rows``: every (stride, row) pair before duplicates are dropped). Of several rows that make the same
    stride the first is kept, or with ``events`` (one per input row, s) the one with the latest event (the landing
    just before the rest that ends the stride: steps decision 34, localization L675)
    """
    rr = stance_runs(t, stance)
    if len(rr) < 2:
        i0 = np.clip(np.searchsorted(t, starts), 0, len(t) - 1)
        i1 = np.clip(np.searchsorted(t, ends), 0, len(t) - 1)
        keep = np.flatnonzero(i1 > i0 + 1)
        return i0[keep], i1[keep], keep
    rs, re = t[rr[:, 0]], t[rr[:, 1] - 1]
    mid = np.clip((rr[:, 0] + rr[:, 1] - 1) // 2, 0, len(t) - 1)
    n_rest = int(round(max_rest_s / float(np.median(np.diff(t)))))
    # before: the last run starting before start + tol; after: the first run ending after end - tol
    k0 = np.searchsorted(rs, np.asarray(starts) + tol_s, side="right") - 1
    k1 = np.searchsorted(re, np.asarray(ends) - tol_s, side="left")
    ok = (k0 >= 0) & (k1 < len(rr)) & (k1 > k0)
    keep = np.flatnonzero(ok)
    span = k1[keep] - k0[keep]
    keep = np.repeat(keep, span)  # one stride per pair of consecutive stances inside the window
    k0 = k0[keep] + (np.arange(len(keep)) - np.repeat(np.cumsum(span) - span, span))
    k1 = k0 + 1
    i0 = np.maximum(mid[k0], rr[k0, 1] - 1 - n_rest)
    i1 = np.minimum(mid[k1], rr[k1, 0] + n_rest)
    if all_rows:
        return i0, i1, keep
    if events is not None:  # decision L675: steps decision 34's pick, the latest event of the stride
        first = np.sort(_latest_per_stride(i0, i1, np.asarray(events, dtype=float)[keep]))
    else:
        _, first = np.unique(np.column_stack([i0, i1]), axis=0, return_index=True)
        first = np.sort(first)
    return i0[first], i1[first], keep[first]


def _latest_per_stride(i0: np.ndarray, i1: np.ndarray, ev: np.ndarray) -> np.ndarray:
    """Steps decision 34 / localization L675: of the (stride, row) pairs ``i0``, ``i1`` with events ``ev`` (NaN = no
    event, taken as the earliest), the positions of one pair per stride, the one with the latest event; of equal
    events (several rows without one) the first row, as :func:`rest_to_rest` keeps without events."""
    first_last = -np.arange(len(ev))  # ties: the first row sorts last, so it is the one kept
    order = np.lexsort((first_last, np.nan_to_num(ev, nan=-np.inf), i1, i0))  # by stride, the latest event last
    pair = np.column_stack([i0, i1])[order]
    last = np.r_[np.any(pair[1:] != pair[:-1], axis=1), True]
    return order[last]


def one_per_rest_stride(t: np.ndarray, stance: np.ndarray, starts, ends, events, *,
                        count_strides: bool = False) -> np.ndarray | tuple[np.ndarray, int]:
    """Decision steps 34: the rows of a foot detector's table that :func:`rest_to_rest` makes strides (what
    ``pdrlearn track`` integrates), one per rest-to-rest stride: of several detections between the same two
    rests (a slow stride's toe-off and landing both detected) the one with the latest ``events`` (the landing
    just before the rest that ends the stride); detections in one rest are dropped. Sorted row indices; with
    ``count_strides`` also the number of rest-to-rest strides they cover (more than the rows when a detection
    spans several strides, which ``track`` splits at the rests, L96; steps decision 38)."""
    i0, i1, rows = rest_to_rest(t, stance, np.asarray(starts, float), np.asarray(ends, float), all_rows=True)
    if not len(rows):
        return (np.zeros(0, dtype=int), 0) if count_strides else np.zeros(0, dtype=int)
    pick = _latest_per_stride(i0, i1, np.asarray(events, dtype=float)[rows])
    kept = np.unique(rows[pick])
    return (kept, len(pick)) if count_strides else kept


def twist_yaw(q_start: np.ndarray, q_end: np.ndarray) -> np.ndarray:
    """Decision L30: heading change (rad, CCW, in (-pi, pi]) of attitudes ``q_start`` -> ``q_end`` ((B, 4)
    quaternions [w, x, y, z], body -> navigation frame, z up): the angle about the vertical of the relative
    rotation q_end q_start^-1 (its twist in a swing-twist decomposition). Unlike the heading of a body axis,
    it does not depend on how far the mount tilts that axis, nor on the foot's tilt at either rest."""
    w1, x1, y1, z1 = np.moveaxis(np.asarray(q_end, dtype=float), -1, 0)
    w2, x2, y2, z2 = np.moveaxis(np.asarray(q_start, dtype=float), -1, 0)
    w = w1 * w2 + x1 * x2 + y1 * y2 + z1 * z2  # q_end * conj(q_start): scalar and z components
    z = -w1 * z2 - x1 * y2 + y1 * x2 + z1 * w2
    return 2.0 * np.arctan2(z * np.sign(np.where(w == 0, 1.0, w)), np.abs(w))


#: The points a foot track can follow (``reference_point``; ``pdrlearn track --reference-point``, decision L72)
REFERENCE_POINTS = ("sensor", "heel")
# Options of FootDisplacement, off by default (decision L584: keywords, no module switch):
# ``timestamps`` (decision L83): the foot strides are integrated on the sample timestamps.
# ``upsample_runs`` (decision L87): at 20 Hz each evenly spaced run (between dropped samples) is upsampled on its own
# (with ``timestamps`` the long interval of a drop keeps its length). Off: its rule failed at 20 Hz (worst walk
# +3.851 pp at 3 % drops; the spline's free run ends ring after an impact; experiments/results/drops_runs_43-54.md).
# ``rest_bias`` (decision L476): after a rest longer than L296's ``REST_BIAS_MIN_S`` between two strides, the foot
# gyroscope's bias (``gyro_bias="standstill"``) is re-read from the rest's still samples; decision L477: not adopted
# (two sessions grew by more than 0.3 m), opt-in.
# ``rest_drift`` (decision L712): the foot gyroscope's bias interpolated in time through the set-up standstill's and
# every stand over ``FOOT_REST_DRIFT_MIN_S``'s still-block reads (L711: the bias walks during the walking bouts).

#: decision L712: a rest (lead-in, gap between strides, tail) longer than this (s) gives the foot's bias reads of
#: ``rest_drift`` (L711: a 45 s stop's 30 s block reads within 0.031 deg/s; shorter stands are common inside a walk)
FOOT_REST_DRIFT_MIN_S = 30.0
#: decision L731: the rests ``rest_drift`` reads: ``"gap"`` (L712) the rests between the strides over
#: :data:`FOOT_REST_DRIFT_MIN_S`, ``"stand"`` the foot's own still runs (the set-up standstill's detector) of that
#: long or more
REST_DRIFT_BY = ("gap", "stand")

#: decision L628: below this foot rate (Hz) the strides are integrated on L24's x5 histospline by default (L24 took
#: it below 50 Hz, the 20 Hz firmware means); at 100 Hz L626's coning term leaves +0.0020 deg per stride of a
#: swinging foot's heading on the unit's own grid (~0.3 deg over a 200 m straight), on the x5 grid -0.0001
#: (experiments/foot_coning_l626.py, docs/decisions/localization.md L626 / L628); at 204.8 Hz the own grid is kept
FINE_GRID_BELOW_HZ = 150.0

#: decision B206: the ranges of :class:`FootDisplacement`'s numeric settings (their types come from its signature's
#: annotations: a bool is JSON true / false, an int a whole number); windows and durations in s, rates, noise terms
SETTING_BOUNDS = {"sw": {"low": 0, "open_low": True}, "r": {"low": 0, "open_low": True},
                  "max_rest_s": {"low": 0}, "rest_s": {"low": 0, "open_low": True},
                  "zupt_erode": {"low": 0, "high": 0.5},  # a fraction cut at both ends of a stance run
                  "zupt_erode_max_s": {"low": 0}, "upsample": {"low": 1}, "max_stride_s": {"low": 0, "open_low": True},
                  "accel_scale_error": {"low": 0}, "min_rocker_samples": {"low": 1}, "zaru_gyro_rad_s": {"low": 0},
                  "toe_offset_m": {"low": 0}}  # decision L795


def setting_rules() -> dict[str, Rule]:
    """Decision B206: a :class:`~pdrlearn.settings.Rule` per true / false or numeric setting of
    :class:`FootDisplacement`, from its annotations and :data:`SETTING_BOUNDS` (the text settings keep the
    class's own lines)."""
    import inspect

    rules = {}
    for name, p in inspect.signature(FootDisplacement).parameters.items():
        words = annotation_words(p.annotation)
        rule = None if words is None else Rule.from_annotation(words, **SETTING_BOUNDS.get(name, {}))
        if rule is not None:
            rules[name] = rule
    return rules


def check_settings(params, where: str = "plasys params") -> dict:
    """Decisions B206 / B207: ``params`` (the foot pipeline's ``--params`` JSON, or keywords of
    :class:`FootDisplacement`) as a dict, or one :class:`DataError` line naming ``where``: not a JSON object, an unknown
    key, or a value of the wrong type or range (``"timestamps": "no"`` had been read as true, ``"rest_s": "abc"`` a
    TypeError, ``"rest_s": -1`` accepted)."""
    import inspect

    if params is None:
        return {}
    if not isinstance(params, dict):
        raise DataError(f"{where}: parameters must be a JSON object (e.g. {{\"rest_s\": 0.05}}), not "
                        f"{type(params).__name__} {params!r:.40}")
    allowed = set(inspect.signature(FootDisplacement).parameters)
    unknown = sorted(set(params) - allowed, key=str)
    if unknown:
        raise DataError(f"{where}: unknown parameter(s) {', '.join(map(str, unknown))}; the plasys pipeline "
                        f"takes FootDisplacement settings: {', '.join(sorted(allowed))}")
    bad = broken(params, setting_rules())
    if bad:
        raise DataError(f"{where}: {broken_line(bad)}; fix the key(s) (JSON true / false and numbers, no quotes)")
    return dict(params)


class FootDisplacement:
    """Displacement of each stride of the foot unit between two rests.

    Parameters
    ----------
    integrator : ``"kalman"`` (white-noise-jerk filter with ZUPT + RTS smoothing, thesis eq. 44-55) or
        ``"integration"`` (double integration, equations of motion)
    zupt_end : remove the velocity found at the stride end (ZUPT drift correction); ``False`` only
        resets the velocity at each stride start (the traditional accelerometer method, M1)
    gyro_bias : gyroscope offset removed: ``"standstill"`` (the thesis' setup standstill, ch.7.2.1; none
        found -> no correction), ``"stance"`` (mean rate of the stance run before each stride) or ``"none"``.
        The attitude itself is re-initialised from gravity at every stride start (ZARU).
    attitude : ``"accel"`` (default, decision L627) -> initial roll/pitch of each stride from the accelerometer
        at rest (thesis eq. 38/39: the mean specific force over +-``rest_s``); ``"kalman"`` -> from the 2-state
        angle Kalman filter (thesis eq. 40-43; its swing propagation leaves ~1 deg at the stride starts, L627)
    sw, r : white-noise-jerk filter settings (thesis ch.7.2.1: Sw = 1.8, R = 0.01)
    max_rest_s : a stride starts/ends at the middle of the adjacent stance, at most this far (s) into a
        longer rest (see :func:`rest_to_rest`)
    rest_s : half-width (s) of the window averaged for gravity at a stride boundary
    zupt_erode : fraction of each stance run dropped at both ends before it is used for ZUPT (the foot
        rolls over heel and toe at the edges of stance)
    zupt_erode_max_s : at most this much (s) is dropped at each end of a stance run: the heel and toe roll
        lasts well under it, and a long rest (a 10-min stand) keeps its middle for ZUPT and the attitude
        filter instead of losing 25 % at each end (stances up to 4 x this long are cut as before)
    max_stride_s : strides longer than this (s) are flagged in ``warnings_`` (a missed stance)
    accel_scale_error : relative accelerometer error proportional to the acceleration (scale factor,
        non-linearity, bandwidth, clipped impacts; default 1 %): the ZUPT drift correction attributes the
        velocity error found at a stance to the samples in proportion to ``r + (accel_scale_error |a|)^2``
        instead of evenly in time (decision L21); 0 = evenly in time
    reference_point : ``"sensor"`` (the unit's own displacement) or ``"heel"``: the displacement of the heel
        contact point, with the sensor-to-heel lever arm estimated from the heel rocker of all strides
        (decision L22; matters in turns, where the foot rotates between the two rests)
    min_rocker_samples : fewest heel-rocker samples for the lever-arm estimate (else it stays at the sensor)
    gap_yaw : add the turn of a foot pivoting between two strides that do not touch (a rest longer than
        2 x ``max_rest_s``) to the foot heading (decision L28); samples with |w| < ``zaru_gyro_rad_s``
        count as still (ZARU: no heading change)
    upsample : strapdown on a ``k`` times finer grid (block-mean preserving spline); default 5 below
        :data:`FINE_GRID_BELOW_HZ` = 150 Hz (decision L628; L24: below 50 Hz, the 20 Hz firmware means), else 1
    yaw : a stride's heading change: ``"twist"`` (default, decision L30) = the rotation about the vertical
        of the foot's attitude change from rest to rest (swing-twist decomposition), or ``"x-axis"`` = the
        heading of the unit's x axis at the stride end (the former rule; ill-conditioned when the mount
        pitches the x axis far from horizontal)
    tilt_dedrift : decision L68: remove the tilt error found at each stride end (gravity measured where the foot
        rests again) along the stride, linearly in ``tilt_clock`` ("rotation": accumulated |w|, the choice of L68,
        or "time"), as the ZUPT removes the velocity error; False (default; L68: not adopted) = the attitude of
        the gyroscope alone
    timestamps : decision L83: integrate each stride step over its own sample interval t_k - t_(k-1)
        (dropped samples lengthen it; an interval over B11's 1 s gap counts one period, as the stride
        across it is zeroed); a clock uniform to 1e-6 uses the fixed ``1 / rate`` bit for bit.
        False = the fixed ``1 / rate`` everywhere (the former rule)
    clip_noise : decision B454: the accelerometer's clipped samples (B77 / B311) carry the velocity error the ZUPT
        finds at the next rest (:func:`pdrlearn.kernels.clip_noise.clip_variance`; the Kalman integrator's, M2 /
        M3: M1's integration has no end ZUPT to attribute); False (the class's default) = L21 alone; decision B470:
        the offline track (``track.plasys``) sets it when the foot accelerometer clips
    upsample_runs : decision L87: with ``upsample`` > 1, split the samples where an interval exceeds 1.5 periods
        (a dropped sample) and upsample each run on its own, so no block mean is widened across the drop
        (L24's spline puts the block edges halfway between neighbours); meant with ``timestamps`` (the drop's
        interval then keeps its length). A clock without a drop is unchanged bit for bit. False (default;
        L87: not adopted, the free spline ends of the runs ring after an impact)
    rest_bias : decision L476: with ``gyro_bias="standstill"``, the strides after a rest longer than 60 s
        between two strides (L296's ``REST_BIAS_MIN_S``) remove the bias read from that rest's still samples
        (L296's 30 s blocks; the last one's mean, as the setup standstill's, thesis ch.4 / ch.7.2.1) instead of
        the setup standstill's: the gyroscope's bias drifts over minutes (warm-up, temperature). Walks without
        such a rest are unchanged bit for bit
    rest_drift : decision L712: with ``gyro_bias="standstill"`` (and ``rest_bias`` false), every rest longer than
        :data:`FOOT_REST_DRIFT_MIN_S` (the lead-in, a gap between strides, the tail) gives L296's 30 s still-block
        bias reads; each stride removes the bias interpolated in time at its middle through the set-up standstill's
        read and those (the nearest read held outside them): offline both ends of a walking bout are known, so the
        bias's walk during the bout is followed, not lagged (L711). Walks without such a rest are unchanged bit for
        bit
    rest_drift_by : decision L731: which rests ``rest_drift`` reads. ``"gap"`` (default, L712): the lead-in, the
        gaps between strides and the tail over :data:`FOOT_REST_DRIFT_MIN_S`. ``"stand"``: every run of the foot's
        still samples (``standstill_mask``, the set-up standstill's detector) whose own length, first still sample
        to last, is :data:`FOOT_REST_DRIFT_MIN_S` or more - a 30 s stand leaves a stride gap under 30 s (each stride
        takes up to ``max_rest_s`` of it) but a still run over 30 s
    toe_offset_m : decision L795: the sensor-to-toe distance (m) along the foot's forward axis, for ``toe_height_m_``
        and :meth:`min_toe_clearance` (default 0.14 m, the project's own: a 0.25 m adult foot, the unit on the instep
        ~45 % of its length from the heel; the rigid-foot toe point of Mariani et al. 2012)

    Attributes
    ----------
    disp_ : (B, 3) displacement (m) in each stride's level frame (x = foot forward at the start, z up)
    yaw_change_ : (B,) foot heading change over each stride (rad, CCW)
    start_idx_, end_idx_ : (B,) sample indices of the stride boundaries used; start_s_, end_s_ their times
    lever_arm_ : (3,) heel contact - sensor in the body frame (m) with ``reference_point="heel"``, else None;
        lever_fit_ : fraction of the heel-rocker velocity variance the rotation about it explains
    heel_lift_m_ : (B,) with ``reference_point="heel"`` and a lever arm, the heel contact point's highest point above
        the line joining its two rests (m, decision L721), else None;
    lift_m_ : (B,) the sensor's highest point above the line joining its two rests (m, decision L421);
        sole_pitch_deg_ (B, L) the sole angle of every stride sample (:meth:`sole_angle` reads it at a time);
        toe_height_m_ (B, L) the toe point's height above the line joining its rests (decision L795,
        :meth:`min_toe_clearance` reads it)
    rows_ : (B,) rows of the input steps table the strides come from (dropped rows: no swing between)
    stance_ : (n,) bool stance mask;  stance_source_ : "force" or "inertial"
    """

    def __init__(self, *, integrator: str = "kalman", zupt_end: bool = True, gyro_bias: str = "standstill",
                 attitude: str = "accel", sw: float = 1.8, r: float = 0.01, max_rest_s: float = 0.3,
                 rest_s: float = 0.05, zupt_erode: float = 0.25, zupt_erode_max_s: float = 0.5,
                 upsample: int | None = None,
                 max_stride_s: float = 3.0, accel_scale_error: float = 0.01,
                 reference_point: str = "sensor", min_rocker_samples: int = 20, gap_yaw: bool = True,
                 zaru_gyro_rad_s: float = 0.4, yaw: str = "twist", tilt_dedrift: bool = False,
                 tilt_clock: str = "rotation", timestamps: bool = False,
                 upsample_runs: bool = False, rest_bias: bool = False, clip_noise: bool = False,
                 rest_drift: bool = False, rest_drift_by: str = "gap", toe_offset_m: float = 0.14):
        check_settings({k: v for k, v in locals().items() if k != "self"}, "FootDisplacement")  # decision B206
        if tilt_clock not in ("time", "rotation"):
            raise DataError(f"FootDisplacement: tilt_clock '{tilt_clock}' is not 'time' or 'rotation'")
        self.tilt_dedrift, self.tilt_clock = bool(tilt_dedrift), tilt_clock
        self.timestamps = bool(timestamps)
        self.upsample_runs = bool(upsample_runs)
        self.rest_bias = bool(rest_bias)
        self.rest_drift = bool(rest_drift)
        if rest_drift_by not in REST_DRIFT_BY:
            raise DataError(f"FootDisplacement: rest_drift_by '{rest_drift_by}' is not one of "
                            f"{', '.join(REST_DRIFT_BY)}")
        self.rest_drift_by = rest_drift_by
        self.toe_offset_m = float(toe_offset_m)  # decision L795
        self.clip_noise = bool(clip_noise)
        if yaw not in ("twist", "x-axis"):
            raise DataError(f"FootDisplacement: yaw '{yaw}' is not 'twist' or 'x-axis'")
        self.yaw = yaw
        if reference_point not in REFERENCE_POINTS:
            raise DataError(f"FootDisplacement: reference_point '{reference_point}' is not 'sensor' or 'heel'")
        self.reference_point = reference_point
        self.gap_yaw = bool(gap_yaw)
        self.zaru_gyro_rad_s = float(zaru_gyro_rad_s)
        self.min_rocker_samples = int(min_rocker_samples)
        if integrator not in ("kalman", "integration"):
            raise DataError(f"FootDisplacement: integrator '{integrator}' is not 'kalman' or 'integration'")
        if attitude not in ("kalman", "accel"):
            raise DataError(f"FootDisplacement: attitude '{attitude}' is not 'kalman' or 'accel'")
        self.integrator = integrator
        self.zupt_end = zupt_end
        if gyro_bias not in ("standstill", "stance", "none"):
            raise DataError(f"FootDisplacement: gyro_bias '{gyro_bias}' is not standstill, stance or none")
        self.gyro_bias = gyro_bias
        self.attitude = attitude
        self.sw = sw  # thesis ch.7.2.1: Sw = 1.8
        self.r = r  # thesis eq. 55: R = 0.01
        self.max_rest_s = max_rest_s
        self.rest_s = rest_s
        self.zupt_erode = zupt_erode
        if not np.isfinite(zupt_erode_max_s) or zupt_erode_max_s < 0:
            raise DataError(f"FootDisplacement: zupt_erode_max_s {zupt_erode_max_s!r} must be >= 0 (e.g. 0.5)")
        self.zupt_erode_max_s = float(zupt_erode_max_s)
        self.upsample = upsample
        self.max_stride_s = max_stride_s
        if not np.isfinite(accel_scale_error) or accel_scale_error < 0:
            raise DataError(f"FootDisplacement: accel_scale_error {accel_scale_error!r} must be >= 0 (e.g. 0.01)")
        self.accel_scale_error = float(accel_scale_error)

    def _grid(self, unit: UnitData) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, int]:
        """``(t, acc, gyr, fs, k)``: the integration grid, the unit's samples upsampled ``k`` times below
        :data:`FINE_GRID_BELOW_HZ` (decision L628)."""
        fs0 = unit.fs
        k = self.upsample if self.upsample is not None else (5 if fs0 < FINE_GRID_BELOW_HZ else 1)
        if k <= 1:
            return unit.t, unit.acc, unit.gyr, fs0, 1
        both = np.hstack([unit.acc, unit.gyr])
        t, both = (K.upsample_runs(unit.t, both, k, 1.0 / fs0) if self.upsample_runs  # decision L87
                   else K.upsample_block_means(unit.t, both, k))
        return t, both[:, :3], both[:, 3:], fs0 * k, k

    def stride_bounds(self, unit: UnitData, steps: pd.DataFrame, *,
                      stance: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Decision C51: the rest-to-rest bounds :meth:`estimate` gives the rows of ``steps`` (the same grid and
        :func:`rest_to_rest`), without integrating: ``(start_s, end_s, rows)`` for every (stride, input row)
        pair, so a row a detector repeated maps to its stride too; rows in no stride are absent."""
        t, _, _, _, k = self._grid(unit)
        i0, i1, rows = rest_to_rest(t, np.repeat(np.asarray(stance, dtype=bool), k),
                                    steps["start_s"].to_numpy(dtype=float), steps["end_s"].to_numpy(dtype=float),
                                    max_rest_s=self.max_rest_s, all_rows=True)
        return t[i0], t[i1], rows

    def estimate(self, unit: UnitData, steps: pd.DataFrame, *,
                 stance: np.ndarray | None = None) -> FootDisplacement:
        """Estimate the displacement of each row (``start_s``, ``end_s``) of ``steps``.

        ``stance`` (n,) bool on ``unit.t``; default: the inertial stance detector.
        """
        from scipy.spatial.transform import Rotation

        self.warnings_: list[str] = []
        fs0 = unit.fs
        stance0 = (inertial_stance(unit.acc, unit.gyr, fs0) if stance is None
                   else np.asarray(stance, dtype=bool))
        self.stance_source_ = "inertial" if stance is None else "given"
        zupt0 = K.erode_runs(stance0, self.zupt_erode, max_cut=int(round(self.zupt_erode_max_s * fs0)))
        t, acc, gyr, fs, k = self._grid(unit)
        self.t_ = t
        clip_var = clip_variance(unit.acc, k, 1.0 / (fs0 * k)) if self.clip_noise else None  # decision B454
        self.stance_ = np.repeat(stance0, k)
        zupt_stance = np.repeat(zupt0, k)
        period = 1.0 / fs
        st = steps["start_s"].to_numpy(dtype=float)
        en = steps["end_s"].to_numpy(dtype=float)
        ev = steps["event_s"].to_numpy(dtype=float) if "event_s" in steps else None  # decision L675
        i0, i1, self.rows_ = rest_to_rest(t, self.stance_, st, en, max_rest_s=self.max_rest_s, events=ev)
        self.start_idx_, self.end_idx_ = i0, i1
        self.start_s_, self.end_s_ = t[i0], t[i1]
        long = (self.end_s_ - self.start_s_) > self.max_stride_s
        if long.any():
            self.warnings_.append(f"{int(long.sum())} stride(s) longer than {self.max_stride_s:g} s (no "
                                  "stance detected between steps): their displacement is unreliable")
        B = len(i0)
        w = max(1, int(round(self.rest_s * fs)))
        csum = np.concatenate([np.zeros((1, 3)), np.cumsum(acc, axis=0)])
        lo = np.clip(i0 - w, 0, len(t))
        hi = np.clip(i0 + w + 1, 0, len(t))
        g_body = (csum[hi] - csum[lo]) / (hi - lo)[:, None]
        del csum  # decision L663: (n, 3) on L628's x5 grid, not kept through the strides
        init = None
        if self.attitude == "kalman" and B:
            # the angle filter runs at the native rate; its angles at the stride starts set the attitude
            # the angle filter needs no more than ~50 Hz: faster streams are block-averaged first
            m = max(1, int(fs0 // 50.0))
            n_m = (len(unit.t) // m) * m
            if m > 1:
                a_m = unit.acc[:n_m].reshape(-1, m, 3).mean(axis=1)
                g_m = unit.gyr[:n_m].reshape(-1, m, 3).mean(axis=1)
                z_m = zupt0[:n_m].reshape(-1, m).all(axis=1)
            else:
                a_m, g_m, z_m = unit.acc, unit.gyr, zupt0
            att = FootAttitude().estimate(a_m, g_m, fs0 / m, z_m)
            self.attitude_ = att
            j0 = np.clip(i0 // (k * m), 0, len(att.roll_) - 1)
            init = Rotation.from_euler("YX", np.column_stack([att.pitch_[j0], att.roll_[j0]]))  # Ry(p) Rx(r)
        bias = None
        if self.gyro_bias == "stance" and B:
            bias = self._zaru_bias(gyr, i0, fs)
        elif self.gyro_bias == "standstill" and B:
            still0 = standstill_mask(unit.acc, unit.gyr, fs0)
            bias = np.tile(self._standstill_bias(unit.gyr, fs0, still0), (B, 1))
        self.rest_bias_rests_: list[tuple[float, float]] = []  # decisions L476 / L712: the rests a bias was read from
        if self.gyro_bias == "standstill" and self.rest_bias and B:
            bias = self._rest_biases(unit, still0, bias)
        elif self.gyro_bias == "standstill" and self.rest_drift and B:
            bias = self._drift_biases(unit, still0, bias)
        idx, mask = K.stride_index(i0, i1)
        dt, tclock, weight = self._intervals(t, period, idx, mask)
        q = K.stride_attitude(gyr, dt, idx, mask, g_body, bias, init) if B else None
        if self.tilt_dedrift and B:  # decision L68: the tilt found at the stride end, removed along the stride
            clock = None
            if self.tilt_clock == "rotation":
                clock = np.cumsum(np.where(mask, np.linalg.norm(gyr[idx], axis=2), 0.0), axis=1)
            elif np.ndim(dt):  # decision L83: the time fraction on the timestamps
                clock = K.step_clock(dt, B, idx.shape[1])
            q = K.dedrift_tilt(q, acc, idx, mask, w, clock=clock)
        a_nav, self.yaw_change_ = K.strapdown(acc, gyr, dt, idx, mask, g_body, bias, init, q=q)
        if self.yaw == "twist" and B:
            self.yaw_change_ = twist_yaw(q[:, 0], q[np.arange(B), mask.sum(axis=1) - 1])
        if B:  # decision L690: a spin of 180-360 deg inside a stride is itself (the twist unwrapped along the stride)
            self.yaw_change_ = unwrapped_turn(self.yaw_change_, unwrapped_twists(twist_yaw(q[:, :1], q))[:, -1])
        self.gap_yaw_ = self._gap_yaw(acc, gyr, tclock, i0, i1, bias) if self.gap_yaw else np.zeros(B)
        zm = K.zupt_mask(zupt_stance, idx, mask)
        heel = self.reference_point == "heel" and B
        gyr_b = gyr[idx] if heel else None
        del acc, gyr  # decision L663: the grid's samples are not read again (L628's x5 grid at 100 Hz: 86 MB an hour)
        s2 = self.accel_scale_error ** 2
        if self.integrator == "kalman":
            # decision L21: velocity errors proportional to |a| (scale, bandwidth, clipped impacts)
            dts = dt if np.ndim(dt) == 0 else np.concatenate([np.zeros((B, 1)), dt], axis=1)
            q_vel = s2 * np.sum(a_nav ** 2, axis=2) * dts * dts if s2 > 0 else None
            if clip_var is not None:  # decision B454: the clipped impacts' missing acceleration
                q_clip = np.where(mask, clip_var[idx], 0.0)
                q_vel = q_clip if q_vel is None else q_vel + q_clip
            self.disp_ = K.wnj_displacement(a_nav, mask, dt, sw=self.sw, r=self.r, zupt=self.zupt_end,
                                            zupt_at=zm, q_vel=q_vel)
        else:
            clock = (K.error_clock(a_nav, mask, r=self.r, scale_error=self.accel_scale_error, weight=weight)
                     if s2 > 0 else None)
            self.disp_ = K.double_integrate(a_nav, mask, dt, zupt_end=self.zupt_end, zupt=zm, clock=clock)
        self._swing_measures(a_nav, mask, dt, zm, q, idx, weight)  # decision L421
        self.lever_arm_ = self.heel_lift_m_ = None
        if heel:
            self._to_heel(a_nav, mask, dt, zm, q, gyr_b, self.stance_[idx], period, weight)
        return self

    def _swing_measures(self, a_nav, mask, dt, zm, q, idx, weight) -> None:
        """Decision L421: ``lift_m_`` (B,) the sensor's highest point above the line joining its two rests (the
        ZUPT-corrected velocity of thesis ch.7.2.1, L21's error clock, integrated once) and ``sole_pitch_deg_``
        (B, L) the sole angle of every stride sample (gaitmap's convention), read at a time by :meth:`sole_angle`."""
        from pdrlearn.kernels.clearance import max_lift, sole_pitch_deg, toe_height

        self.idx_, self.mask_ = idx, mask
        if not len(idx):
            self.lift_m_, self.sole_pitch_deg_ = np.zeros(0), np.zeros((0, idx.shape[1]))
            self.toe_height_m_ = np.zeros((0, idx.shape[1]))
            return
        clock = (K.error_clock(a_nav, mask, r=self.r, scale_error=self.accel_scale_error, weight=weight)
                 if self.accel_scale_error > 0 else None)
        pos = K._cumtrapz(K.zupt_velocity(a_nav, mask, dt, zupt_end=self.zupt_end, zupt=zm, clock=clock), dt)
        self.lift_m_ = max_lift(pos, mask)
        self.toe_height_m_ = toe_height(pos, q, mask, self.toe_offset_m)  # decision L795
        del pos
        self.sole_pitch_deg_ = sole_pitch_deg(q)

    def sole_angle(self, times) -> np.ndarray:
        """Decision L421: (B,) the sole angle (deg, positive toes up, 0 at the starting rest) of each stride at
        ``times`` (B,) s (its initial contact or toe-off); NaN where a time is NaN or outside the stride."""
        from pdrlearn.kernels.clearance import value_at

        return value_at(self.t_, self.idx_, self.mask_, self.sole_pitch_deg_, np.asarray(times, dtype=float))

    def min_toe_clearance(self, tc_times, ic_times) -> np.ndarray:
        """Decision L795: (B,) m, each stride's minimum toe clearance (:func:`pdrlearn.kernels.clearance.min_clearance`
        of ``toe_height_m_``) between its toe-off ``tc_times`` (B,) s (NaN: not known) and its initial contact
        ``ic_times`` (B,) s; NaN without a contact inside the stride."""
        from pdrlearn.kernels.clearance import min_clearance, sample_at

        if not len(self.idx_):
            return np.zeros(0)
        i_to = sample_at(self.t_, self.idx_, self.mask_, np.asarray(ic_times, dtype=float))
        i_from = sample_at(self.t_, self.idx_, self.mask_, np.asarray(tc_times, dtype=float))
        i_from = np.where((i_from >= 0) & (i_from < i_to), i_from, -1)
        return min_clearance(self.toe_height_m_, i_from, i_to)

    def _intervals(self, t: np.ndarray, period: float, idx: np.ndarray, mask: np.ndarray):
        """Decision L83: the sample intervals the strides are integrated over. Returns ``dt`` (``period``, or
        (B, L - 1) s per stride step from the timestamps), the clock (n,) s of every sample (on a uniform clock the
        period, which :meth:`_gap_yaw` reads as the sample clock; decision L663) and the interval of every stride
        sample in periods (B, L) (None on a uniform clock)."""
        from pdrlearn.track.gaps import MIN_GAP_S  # B11's gap (imported here: pdrlearn.track imports this module)

        d = np.diff(np.asarray(t, dtype=float))
        d = np.where(d > MIN_GAP_S, period, d)  # B11's gap: one period, as before (its stride is zeroed)
        if not self.timestamps or not len(d) or np.all(np.abs(d - period) <= 1e-6 * period):
            return period, period, None
        dt = np.where(mask[:, 1:], d[np.minimum(idx[:, :-1], len(d) - 1)], 0.0)
        weight = np.concatenate([np.ones((len(idx), 1)), dt / period], axis=1)
        return dt, np.concatenate([[0.0], np.cumsum(d)]), weight

    def _to_heel(self, a_nav, mask, dt, zm, q, gyr_b, stance_b, period, weight) -> None:
        """Decision L22: move the displacement from the sensor to the heel, the point strides are measured
        at in gait analysis: heel = sensor + R(t) r, r = heel contact - sensor (body frame), estimated from
        the heel rocker (the foot rolls about the heel contact between heel strike and foot flat)."""
        clock = K.error_clock(a_nav, mask, r=self.r, scale_error=self.accel_scale_error, weight=weight)
        v = K.zupt_velocity(a_nav, mask, dt, zupt_end=True, zupt=zm, clock=clock)
        sel = K.heel_rocker_samples(a_nav, gyr_b, stance_b, mask, period)
        n_sel = int(sel.sum())
        if n_sel < self.min_rocker_samples:
            self.warnings_.append(f"heel reference: only {n_sel} heel-rocker samples (< "
                                  f"{self.min_rocker_samples}); displacement left at the sensor")
            return
        qs = q[sel]
        v_b = K._qrotate(qs * np.array([1.0, -1.0, -1.0, -1.0]), v[sel])
        rho, fit = K.rotation_pivot(v_b, gyr_b[sel])
        r = -rho
        self.lever_arm_, self.lever_fit_ = r, fit
        self.disp_ = K.move_reference(self.disp_, q[:, 0], q[np.arange(len(q)), mask.sum(axis=1) - 1], r)
        self.heel_lift_m_ = heel_lift(K._cumtrapz(v, dt), q, mask, r)  # decision L721


    def _rest_biases(self, unit: UnitData, still: np.ndarray, bias: np.ndarray) -> np.ndarray:
        """Decision L476: ``bias`` (B, 3) with every stride from the end of a rest longer than L296's
        ``REST_BIAS_MIN_S`` between two strides (the previous stride's end to the stride's start) up to the next
        such rest taking the bias of that rest: L296's :func:`~pdrlearn.kernels.rest_heading.block_bias` of the
        unit's still samples (``still``, native clock), the block nearest the rest's end (thesis ch.4 / ch.7.2.1
        read the offsets from a standstill; a rest is one). A rest without a block of still samples keeps the bias
        before it."""
        from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S, block_bias

        out = bias.copy()
        for k in range(1, len(out)):
            t0, t1 = float(self.end_s_[k - 1]), float(self.start_s_[k])
            if t1 - t0 <= REST_BIAS_MIN_S:
                continue
            a, b = int(np.searchsorted(unit.t, t0, side="left")), int(np.searchsorted(unit.t, t1, side="right"))
            blocks = block_bias(unit.t[a:b], unit.gyr[a:b], still[a:b])
            if blocks is None:
                continue
            centres, rates = blocks
            out[k:] = rates[int(np.argmax(centres))]  # the block nearest the strides that follow
            self.rest_bias_rests_.append((t0, t1))
        return out

    def _drift_biases(self, unit: UnitData, still: np.ndarray, bias: np.ndarray) -> np.ndarray:
        """Decision L712: ``bias`` (B, 3), the set-up standstill's, interpolated in time at every stride's middle
        through that read (at the middle of its still run) and the L296 still-block reads
        (:func:`~pdrlearn.kernels.rest_heading.block_bias`) of every rest longer than :data:`FOOT_REST_DRIFT_MIN_S`:
        the lead-in, the gaps between strides and the tail (thesis ch.4 / ch.7.2.1 read the offsets from a
        standstill; a stand is one). No such read: ``bias`` unchanged."""
        from pdrlearn.kernels.rest_heading import block_bias

        t = unit.t
        times, reads = [], []
        for t0, t1 in self._drift_rests(t, still):
            a, b = int(np.searchsorted(t, t0, side="left")), int(np.searchsorted(t, t1, side="right"))
            blocks = block_bias(t[a:b], unit.gyr[a:b], still[a:b])
            if blocks is None:
                continue
            times.append(blocks[0])
            reads.append(blocks[1])
            self.rest_bias_rests_.append((t0, t1))
        if not reads or self.setup_run_ is None:
            return bias
        times = np.concatenate([[0.5 * (t[self.setup_run_[0]] + t[self.setup_run_[1]])], *times])
        reads = np.vstack([bias[:1], *reads])
        order = np.argsort(times, kind="stable")
        mid = 0.5 * (self.start_s_ + self.end_s_)
        return np.column_stack([np.interp(mid, times[order], reads[order, j]) for j in range(reads.shape[1])])

    def _drift_rests(self, t: np.ndarray, still: np.ndarray) -> list[tuple[float, float]]:
        """The rests ``(t0, t1)`` (s) :meth:`_drift_biases` reads: ``rest_drift_by="gap"`` (decision L712) the lead-in,
        the gaps between strides and the tail longer than :data:`FOOT_REST_DRIFT_MIN_S`; ``"stand"`` (decision L731)
        every run of ``still`` samples (the set-up standstill's detector, thesis ch.7.2.1) whose own length, first
        still sample to last, is that long or more: a stride takes up to ``max_rest_s`` of a stand at both ends, so a
        30 s stand leaves a gap of 29.9 s and a still run of 30.3 s (L731's scratch)."""
        if self.rest_drift_by == "stand":
            return [(float(t[a]), float(t[b - 1])) for a, b in runs(still)
                    if t[b - 1] - t[a] >= FOOT_REST_DRIFT_MIN_S]
        edges = [(float(t[0]), float(self.start_s_[0]))]
        edges += [(float(a), float(b)) for a, b in zip(self.end_s_[:-1], self.start_s_[1:], strict=True)]
        edges.append((float(self.end_s_[-1]), float(t[-1])))
        return [(t0, t1) for t0, t1 in edges if t1 - t0 > FOOT_REST_DRIFT_MIN_S]

    def _standstill_bias(self, gyr: np.ndarray, fs: float, still: np.ndarray,
                         min_s: float = 1.0) -> np.ndarray:
        """Gyroscope offset (rad/s) over the first standstill of >= ``min_s`` s (thesis ch.7.2.1 setup) of the
        still samples ``still`` (``standstill_mask``); ``setup_run_`` that run's (first, last) sample (decision
        L712's interpolation reads it at its middle), None when there is none."""
        self.setup_run_ = None
        for a, b in runs(still):
            if (b - a) / fs >= min_s:
                self.setup_run_ = (int(a), int(b) - 1)
                return gyr[a:b].mean(axis=0)
        self.warnings_.append("no standstill of 1 s: gyroscope offset not removed")
        return np.zeros(3)

    def _zaru_bias(self, gyr: np.ndarray, i0: np.ndarray, fs: float) -> np.ndarray:
        """Mean rate over the stance run around each stride start (ZARU: the foot does not turn at rest);
        falls back to a +-rest_s window when the start is not in a detected stance run."""
        bias = np.zeros((len(i0), 3))
        run_of = np.full(len(gyr), -1)
        rr = runs(self.stance_)
        for k, (a, b) in enumerate(rr):
            run_of[a:b] = k
        w = max(1, int(round(self.rest_s * fs)))
        for s, i in enumerate(i0):
            k = run_of[i]
            a, b = rr[k] if k >= 0 else (max(i - w, 0), min(i + w + 1, len(gyr)))
            bias[s] = gyr[a:b].mean(axis=0)
        return bias

    def _gap_yaw(self, acc: np.ndarray, gyr: np.ndarray, t: float | np.ndarray, i0: np.ndarray, i1: np.ndarray,
                 bias: np.ndarray | None) -> np.ndarray:
        """Decision L28: heading change (rad, CCW) between the end of the previous stride and the start of
        each stride (0 for the first and for contiguous strides): the rate about gravity (the mean specific
        force over the gap; the foot is loaded) integrated over the samples that are not still by the fixed
        rule (|w| >= ``zaru_gyro_rad_s``): a foot pivoting on the ground turns, a still foot does not (ZARU)."""
        out = np.zeros(len(i0))
        if np.ndim(t) == 0:  # a sample period: the sample clock; else the clock (n,) s (decision L83)
            t = np.arange(len(gyr)) * float(t)
        for k in range(1, len(i0)):
            a, b = int(i1[k - 1]), int(i0[k])
            if b - a < 2:
                continue
            w = gyr[a:b] - (0.0 if bias is None else bias[k])
            out[k] = SK.pivot_yaw(t[a:b], w, acc[a:b].mean(axis=0), still_rad_s=self.zaru_gyro_rad_s)
        return out

    def foot_heading(self, initial: float = 0.0) -> np.ndarray:
        """Foot heading (rad, ENU) at each stride start: the stride yaw changes accumulated, plus the turn of
        a foot pivoting between two strides (decision L28; ZARU: no change while the foot is still)."""
        if not len(self.yaw_change_):
            return np.zeros(0)
        gap = getattr(self, "gap_yaw_", np.zeros(len(self.yaw_change_)))
        return initial + np.concatenate([[0.0], np.cumsum(self.yaw_change_)[:-1]]) + np.cumsum(gap)




def heel_lift(pos: np.ndarray, q: np.ndarray, mask: np.ndarray, r_body: np.ndarray) -> np.ndarray:
    """Decision L721: (B,) m, the highest point of the point at ``r_body`` (3,) m from the sensor (body frame; L22's
    heel contact) above the line joining its two rests, from the sensor's stride positions ``pos`` (B, L, 3) and
    attitudes ``q`` (B, L, 4) [w, x, y, z]: that point is at pos + R(t) r (L22), through L421's ``max_lift``."""
    from pdrlearn.kernels.clearance import max_lift

    q = np.where(mask[..., None], q, np.array([1.0, 0.0, 0.0, 0.0]))  # padding samples: any valid attitude
    rb = np.broadcast_to(np.asarray(r_body, dtype=float), pos.shape)
    return max_lift(pos + K._qrotate(q, rb), mask)
