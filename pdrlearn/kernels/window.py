"""One step's window: levelled, heading-aligned, gravity-removed, resampled (numpy only).

The construction shared by :func:`pdrlearn.features.step_windows` (training) and
:func:`pdrlearn.runtime.features.step_window` (streaming); see :mod:`pdrlearn.features.windows` for the
step frame (x forward horizontal, y left, z up) and docs/features.md.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Collection, Mapping

import numpy as np

from pdrlearn.errors import DataError, VerticalAxisError
from pdrlearn.kernels.rotation import gravity_rotation, vec_norm
from pdrlearn.kernels.stats import (
    heading_rotation,
    levelled_vectors,
    principal_horizontal_axis,
    rest_index,
    rest_score,
    row_norm,
)
from pdrlearn.kernels.strapdown import CONING_COEF  # decision L35 (L626: shared with the offline strapdown)
from pdrlearn.kernels.turn import integrated_yaw, unwrapped_turn  # decision L690
from pdrlearn.kernels.units import STANDARD_GRAVITY  # thesis ch.4.2.1.1

#: Sensor groups and their channels, in the order of :data:`CHANNELS` (after ``t_s``).
GROUPS: dict[str, tuple[str, ...]] = {
    "foot_acc": ("foot_acc_x", "foot_acc_y", "foot_acc_z", "foot_acc_norm"),  # m/s^2, z gravity removed
    "foot_gyr": ("foot_gyr_x", "foot_gyr_y", "foot_gyr_z"),  # rad/s about forward/left/up
    "force": ("force_a", "force_b"),  # heel (fForceA), toe (fForceB); sensor units (N or normalised)
    "waist_acc": ("waist_acc_x", "waist_acc_y", "waist_acc_z"),  # m/s^2, z gravity removed
    "waist_gyr": ("waist_gyr_x", "waist_gyr_y", "waist_gyr_z"),  # rad/s about forward/left/up
    "waist_baro": ("waist_baro",),  # hPa relative to the step's first sample
}

#: Fixed channel layout of a window array (axis 1). ``t_s`` = time since the step start (s).
CHANNELS: tuple[str, ...] = ("t_s",) + tuple(c for group in GROUPS.values() for c in group)
CHANNEL_INDEX: dict[str, int] = {c: i for i, c in enumerate(CHANNELS)}

#: Source streams of each sensor group (the PLASYS file names, thesis ch. 4.3.3).
GROUP_STREAMS: dict[str, tuple[str, ...]] = {
    "foot_acc": ("fAccelerometer",),
    "foot_gyr": ("fGyroscope",),
    "force": ("fForceA", "fForceB"),
    "waist_acc": ("wAccelerometer",),
    "waist_gyr": ("wGyroscope",),
    "waist_baro": ("wBarometer",),
}

Streams = Mapping[str, tuple[np.ndarray, np.ndarray]]  # sensor name -> (t (n,) s, values (n, k))

try:  # the compiled routine np.interp calls for real data (its Python wrapper costs ~0.6 us per call,
    from numpy._core.multiarray import interp as _compiled_interp  # a third of it; decision E13)
except ImportError:  # pragma: no cover - numpy < 2
    from numpy.core.multiarray import interp as _compiled_interp


def interp(x, xp: np.ndarray, fp: np.ndarray) -> np.ndarray:
    """``np.interp(x, xp, fp)`` for real ``fp``: the same compiled routine, bit-identical results."""
    return _compiled_interp(x, xp, fp, None, None)


def col_mean(v: np.ndarray) -> np.ndarray:
    """``v.mean(axis=0)`` of an ``(n >= 1, k)`` array: the same sum divided by n, without its wrapper."""
    return np.add.reduce(v, axis=0) / v.shape[0]


#: Decision E35: time comparisons against a window length or a limit are decided as in exact arithmetic. On a
#: clock that is an exact multiple of the window (20 Hz: 0.1 s = 2 samples, 100 Hz: 0.03 s = 3 samples) the
#: difference of two float times lands on either side of the limit by rounding (1e-14 s near 100 s, 1e-7 s on
#: an epoch clock), so a shift of the clock by 1e-13 s changed which samples a window held and moved a stride
#: boundary by a sample. Differences within ``TIE_S`` of the limit count as equal to it: far below any sample
#: interval (1 ms at 1 kHz), far above the rounding.
TIE_S = 1e-6


def cover(t: np.ndarray, t0: float, t1: float) -> tuple[int, int]:
    """Indices ``i0, i1`` of the samples covering [t0, t1]: the last sample at or before ``t0`` to the first
    at or after ``t1`` (one sample on each side when an edge falls between samples); a sample within
    ``TIE_S`` of an edge is on it (decision E35), so the cut does not depend on the clock's rounding."""
    i0 = max(int(t.searchsorted(t0 + TIE_S, side="right")) - 1, 0)
    i1 = min(int(t.searchsorted(t1 - TIE_S, side="left")) + 1, len(t))
    return i0, i1


def segment(t: np.ndarray, v: np.ndarray, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
    """Samples covering [t0, t1] plus one sample on each side (for interpolation at the edges; :func:`cover`)."""
    i0, i1 = cover(t, t0, t1)
    return t[i0:i1], v[i0:i1]


def box_filter(v: np.ndarray, width: int) -> np.ndarray:
    """Centred moving mean of odd ``width`` samples along axis 0, edges repeated (like scipy's
    ``uniform_filter1d(mode="nearest")``)."""
    h = width // 2
    p = np.concatenate([np.repeat(v[:1], h, axis=0), v, np.repeat(v[-1:], h, axis=0)], axis=0)
    c = np.concatenate([np.zeros((1,) + v.shape[1:]), np.cumsum(p, axis=0)], axis=0)
    return (c[width:] - c[:-width]) / width


def resample(t_new: np.ndarray, t: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Resample the columns of ``v`` (n, k) at ``t_new`` -> (k, len(t_new)); when downsampling, each output
    sample is the mean over its own interval first (box anti-alias filter, like the PLASYS firmware's
    5-sample averaging, thesis ch. 4.2.3), so impact peaks do not alias and 20/100/204.8 Hz data agree."""
    width = 1
    if len(t_new) > 1 and len(t) > 2:
        width = int(round((t_new[1] - t_new[0]) * (len(t) - 1) / float(t[-1] - t[0])))  # mean spacing
        width = 2 * (width // 2) + 1  # odd: a centred box, no half-sample delay
        if width > 1:
            v = box_filter(v, width)
    if width == 1 and len(t_new) == len(t) and (t_new == t).all():  # same clock (e.g. acc and gyro of a unit)
        return v.T.copy()  # = np.interp at its own nodes, exactly
    out = np.empty((v.shape[1], len(t_new)))
    for j in range(v.shape[1]):
        out[j] = interp(t_new, t, v[:, j])
    return out


#: Step-boundary modes of step windows (decision 13 in docs/decisions/features.md): ``"given"`` cuts at the
#: step table's times, ``"rest"`` moves each boundary to the middle of the foot's rest (:func:`rest_boundaries`).
BOUNDARIES = ("given", "rest")
#: task -> its class column in a steps table (labels' ``steps.csv``, ``predict_steps``, ``pdrlearn track``'s and
#: ``run``'s steps.csv, ``Step.to_dict()`` since decision B142): the length class is ``length_class``
TASK_COLUMNS: dict[str, str] = {"terrain": "terrain", "direction": "direction", "length": "length_class"}

#: How a foot step window's forward axis is found (:func:`foot_levelled`): ``"pca"``, the principal horizontal
#: axis of the acceleration, or ``"declared"``, the mounting's declared axis; a bundle's ``features.heading``
#: is one of them (decision B138).
WINDOW_HEADINGS = ("pca", "declared")


def rest_boundaries(t: np.ndarray, gyr: np.ndarray, start: np.ndarray, end: np.ndarray, *,
                    search_s: float = 0.3, smooth_s: float = 0.05, rest_tol_rad_s: float = 0.1
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Move each step boundary to the middle of the foot's rest nearby (rest-to-rest step windows).

    Motion score = angular-rate norm (rad/s; rotation-invariant, so the same for any mounting),
    box-smoothed over ``smooth_s`` seconds. Within ``search_s`` seconds of the given boundary (at most a
    quarter of the step inward, so a window keeps at least half of its given span) the rest is the run of
    samples around the score's minimum that stay within ``rest_tol_rad_s`` of it; the boundary becomes
    that run's middle (``rest_tol_rad_s=0``: the minimum itself, which jitters by the noise inside a long
    rest). Step labels from other sources (motion-capture mid-stance events, a converter's swing
    detection, manual cuts) start at different gait phases; cut at the middle of the foot's rest, every
    step runs rest to rest whatever the source, mounting or rate, like the runtime's stance-middle
    segmentation (decision 13 in docs/decisions/features.md).

    Parameters
    ----------
    t : (n,) s, increasing;  gyr : (n, 3) rad/s foot angular rate on ``t``
    start, end : (m,) step boundaries (s), ``end > start``
    search_s, smooth_s : search half-width and smoothing window (s), converted with the stream's rate
    rest_tol_rad_s : rate above the local minimum still counted as rest (rad/s; 0.1 rad/s = 6 deg/s, a
        foot flat on the ground vs. heel strike / heel-off, whose rates pass it within a few samples)

    Returns
    -------
    new_start, new_end : (m,) s (``new_end > new_start``); the rest's edges are interpolated between
        samples, so 20 Hz and 204.8 Hz streams of the same walk give boundaries a few ms apart
    """
    t = np.asarray(t, dtype=float)
    start = np.asarray(start, dtype=float)
    end = np.asarray(end, dtype=float)
    if len(t) < 2:
        return start.copy(), end.copy()
    fs = (len(t) - 1) / float(t[-1] - t[0])
    w = 2 * (max(1, int(round(smooth_s * fs))) // 2) + 1  # odd: a centred box
    score = np.sqrt(np.einsum("ij,ij->i", gyr, gyr))
    if w > 1:
        score = box_filter(score, w)
    quarter = 0.25 * (end - start)

    def quietest(lo: np.ndarray, hi: np.ndarray, given: np.ndarray) -> np.ndarray:
        i0 = np.searchsorted(t, lo, side="left")
        i1 = np.searchsorted(t, hi, side="right")
        out = given.copy()
        for k in range(len(given)):  # a few samples per boundary; steps are not equally long
            if i1[k] > i0[k]:
                seg, ts = score[i0[k]:i1[k]], t[i0[k]:i1[k]]
                j = int(np.argmin(seg))
                out[k] = ts[j]
                if rest_tol_rad_s > 0:  # middle of the quiet run around the minimum
                    thr = seg[j] + rest_tol_rad_s
                    a, b = j, j
                    while a > 0 and seg[a - 1] <= thr:
                        a -= 1
                    while b < len(seg) - 1 and seg[b + 1] <= thr:
                        b += 1
                    # run edges where the score crosses thr, interpolated between samples, so the middle
                    # does not move by whole sample periods at low rates (20 Hz: 50 ms)
                    left = ts[a] if a == 0 else float(np.interp(thr, [seg[a], seg[a - 1]], [ts[a], ts[a - 1]]))
                    right = ts[b] if b == len(seg) - 1 else float(
                        np.interp(thr, [seg[b], seg[b + 1]], [ts[b], ts[b + 1]]))
                    out[k] = 0.5 * (left + right)
        return out

    new_start = quietest(start - search_s, start + np.minimum(search_s, quarter), start)
    new_end = quietest(end - np.minimum(search_s, quarter), end + search_s, end)
    return new_start, new_end


def posture_warning(n: int, t0: float, t1: float) -> str:
    """Decision B131: the line for ``n`` strides in ``t0``-``t1`` s skipped because the foot rested with its declared
    forward axis (nearly) vertical after strides whose frame was level (a posture, not a wrong meta.json)."""
    return (f"{n} stride(s) in {t0:.2f}-{t1:.2f} s skipped: the foot rested with its declared forward axis (nearly) "
            "vertical (kneeling, crawling or a foot pitched far from level; the strides before had a level frame): "
            "no displacement is counted there and the position holds (decision B131)")


def rest_half_width(t: np.ndarray) -> tuple[float, int]:
    """A foot window's mean rate (Hz; 1 for a single sample) and the half width (samples) of the +-20 ms its rest
    specific force and rate are averaged over (:func:`window_rests`, :func:`rest_pitch_deg`; decisions: rest
    reference, B474)."""
    n = len(t)
    fs = (n - 1) / float(t[-1] - t[0]) if n > 1 else 1.0  # mean rate over the step
    return fs, max(0, int(round(0.02 * fs)))


def window_rests(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray | None, *, rest_search_s: float) -> tuple:
    """The rests of a stride's foot window (:func:`foot_levelled`'s reading): ``(|acc|, k0, k1, g0, g1)``, the
    quietest sample within ``rest_search_s`` of the window's start and of its end and the specific force averaged
    over +-20 ms around each (decisions: rest reference)."""
    n = acc.shape[0]
    fs, h = rest_half_width(t)
    m = max(2, min(int(round(rest_search_s * fs)), n // 4 + 1))
    an = row_norm(acc)
    # rest |acc| from the quietest samples, the whole +-h neighbourhood quiet (decisions: rest reference)
    score = rest_score(an, None if gyr is None else row_norm(gyr), half_width=h)
    k0 = rest_index(acc, gyr, 0, m, score=score)
    k1 = rest_index(acc, gyr, n - m, n, score=score)
    return an, k0, k1, col_mean(acc[max(k0 - h, 0): k0 + h + 1]), col_mean(acc[max(k1 - h, 0): k1 + h + 1])


def rest_pitch_deg(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray | None, forward_s: np.ndarray, *,
                   rest_search_s: float, still_rad_s: float = 0.25, still_acc: float = 0.3) -> float:
    """Decisions B473 / B474: how far (deg) the declared forward axis ``forward_s`` points from horizontal at the foot
    window's first rest (:func:`window_rests`; B131's test in :func:`foot_levelled` is over 84.3 deg, a horizontal
    part under 0.1); NaN for a window of under 2 samples or no specific force, and (B474 amended, session 50 FM)
    when that rest is no rest: its +-20 ms mean rate over ``still_rad_s`` or its specific force further than
    ``still_acc`` (m/s^2) from 1 g (L296's still test's 0.25 rad/s and 0.3 m/s^2): a window starting mid-swing (a
    limp's first fragment) or on a turning pedal is no posture."""
    if acc.shape[0] < 2:
        return math.nan
    _, k0, _, g0, _ = window_rests(t, acc, gyr, rest_search_s=rest_search_s)
    if abs(vec_norm(g0) - STANDARD_GRAVITY) > still_acc:  # decision B474 (amended): not at rest (L296's 0.3 m/s^2)
        return math.nan
    if gyr is not None:  # decision B474 (amended): L296's 0.25 rad/s over the rest's +-20 ms
        h = rest_half_width(t)[1]
        if float(row_norm(gyr[max(k0 - h, 0): k0 + h + 1]).mean()) > still_rad_s:
            return math.nan
    f = np.asarray(forward_s, dtype=float)
    den = vec_norm(g0) * vec_norm(f)
    return math.degrees(math.asin(min(1.0, abs(float(np.dot(g0, f))) / den))) if den > 0 else math.nan


def pitched_from(pitch_deg: float, ref_deg: float | None, *, max_change_deg: float = 45.0) -> bool:
    """Decision B474: whether a stride's first rest pitch ``pitch_deg`` (:func:`rest_pitch_deg`) is more than
    ``max_change_deg`` further from horizontal than ``ref_deg``, the most level rest of the strides tracked so far
    (:func:`level_reference`; the first one's frame B131 judges): B131's posture (kneeling, crawling: a boot pitched
    60-90 deg from its walking rest). One-sided, so a walk after a session's kneeling start is tracked. B473's absolute
    60 deg was not adopted: a real instep mount rests 50 deg pitched on the level and 72 deg on a stair going down
    (gaitmap; at most 29.5 deg from its most level rest in the real foot recordings)."""
    return ref_deg is not None and math.isfinite(pitch_deg) and pitch_deg - ref_deg > max_change_deg


def level_reference(ref_deg: float | None, pitch_deg: float) -> float | None:
    """Decision B474: :func:`pitched_from`'s reference after a tracked stride whose rest pitch is ``pitch_deg``: the
    most level one so far (NaN changes nothing)."""
    if not math.isfinite(pitch_deg):
        return ref_deg
    return pitch_deg if ref_deg is None else min(ref_deg, pitch_deg)


class PitchReference:
    """Decisions B474 / B475: the most level first-rest pitch (deg) of the strides tracked so far, and the test of
    each new stride against it, one mechanism for the live ``Tracker`` and ``track --streaming``. :meth:`pitched`
    reads the stride's pitch (:func:`stride_rest_pitch`): True when it is more than ``max_change_deg`` further from
    level than :attr:`deg` (:func:`pitched_from`: B131's posture); else the stride updates :attr:`deg`
    (:func:`level_reference`; None before the first, whose frame B131 judges)."""

    def __init__(self, *, max_change_deg: float = 45.0) -> None:
        self.max_change_deg = max_change_deg
        self.deg: float | None = None

    def pitched(self, stream, forward_s: np.ndarray, t0: float, t1: float, *, rest_search_s: float) -> bool:
        pitch = stride_rest_pitch(stream, forward_s, t0, t1, rest_search_s=rest_search_s)
        if pitched_from(pitch, self.deg, max_change_deg=self.max_change_deg):
            return True
        self.deg = level_reference(self.deg, pitch)
        return False


def foot_levelled(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray | None, forward_s: np.ndarray, *,
                  rest_search_s: float, heading: str, t0: float | None = None, frame: bool = False
                  ) -> tuple:
    """Foot acc (n, 3; gravity removed), gyro (n, 3) in the step frame, |acc| (n,), and the heading
    change (rad, + = left) of the foot from the first sample at or after ``t0`` (the stride's start; None =
    the first sample) to the last sample (0 without a gyroscope), from the propagated attitude (decisions
    L30, L33: the twist about the vertical, chained without a hole between consecutive strides).

    Tilt from the rest specific force near the window's start, attitude propagated with the gyroscope,
    the tilt seen at the rest near the end spread over the step; forward = principal horizontal axis of
    the acceleration (``heading="pca"``) or the declared axis (``"declared"``), signed by ``forward_s``.
    ``frame=True`` adds a fifth value: the direction (rad, + = left) of the step frame's forward axis
    relative to the foot's heading at the stride's first sample (decision L34, :func:`step_direction`;
    0 without a gyroscope).
    """
    n = acc.shape[0]
    an, k0, k1, g0, g1 = window_rests(t, acc, gyr, rest_search_s=rest_search_s)
    r0 = gravity_rotation(g0)
    ref = (r0 @ forward_s)[:2]  # the attitude at k0 is r0 exactly
    if vec_norm(ref) < 0.1:
        raise VerticalAxisError("foot unit: the declared forward axis points (nearly) vertically at rest; "
                        "check the declared foot frame (meta.json or the bundle's frames)")
    ref = ref / vec_norm(ref)
    if gyr is not None:
        # acc, gyro and the forward axis rotated together by the propagated, tilt-corrected attitude
        # (one stack of products instead of the (n, 3, 3) attitude and two einsums, decision E13)
        X = np.empty((n, 3, 3))  # per sample the rows acc, gyro, forward axis
        X[:, 0] = acc
        X[:, 1] = gyr
        X[:, 2] = forward_s
        Y = levelled_vectors(gyr, t[1:] - t[:-1], k0, k1, r0, g1, X)
        s0 = start_index(t, t0)
        dpsi = stride_dpsi(forward_s, acc, Y, s0, t)  # decisions L30, L33, L35 (before gravity is removed)
        psi0 = start_heading(forward_s, acc[s0], Y[s0]) if frame else 0.0  # decision L34 (idem)
        a_lev = Y[:, 0]
    else:
        a_lev = acc @ r0.T
    a_lev[:, 2] -= vec_norm(g0)
    axis = principal_horizontal_axis(a_lev, ref) if heading == "pca" else ref
    yaw = heading_rotation(axis)
    if gyr is None:
        return (a_lev @ yaw.T, None, an, 0.0) + ((0.0,) if frame else ())
    out = (Y.reshape(-1, 3) @ yaw.T).reshape(n, 3, 3)  # acc and gyro about the step's forward axis
    if frame:  # decision L34, from the attitude at the stride's first sample
        return out[:, 0], out[:, 1], an, dpsi, step_direction(axis, psi0)
    return out[:, 0], out[:, 1], an, dpsi


def twist_dpsi(r0: np.ndarray, e1: np.ndarray, e2: np.ndarray, f1: np.ndarray, f2: np.ndarray) -> float:
    """Decision L30: heading change (rad, + = left) of a foot from its start-rest attitude ``r0`` (3, 3) to
    the attitude that carries the body vectors ``e1``, ``e2`` (not parallel; e.g. the forward axis and the
    last specific force) to ``f1``, ``f2``: the twist about the vertical of R_rel = R_end r0^T. Unlike the
    heading of the forward axis it does not depend on how far the mount tilts that axis (pitched instep
    mounts) nor on the foot's tilt at either rest."""
    frame = _frame3
    # 3-vectors on Python floats: a dozen numpy calls on (3,) arrays cost ~10x more per step (runtime E16)
    (a0, a1, a2), (b0, b1, b2), (c0, c1, c2) = r0.tolist()
    x, y = np.asarray(e1, dtype=float).tolist(), np.asarray(e2, dtype=float).tolist()
    s = [a0 * x[0] + a1 * x[1] + a2 * x[2], b0 * x[0] + b1 * x[1] + b2 * x[2], c0 * x[0] + c1 * x[1] + c2 * x[2]]
    f = np.asarray(f1, dtype=float).tolist()
    S = frame(s, [a0 * y[0] + a1 * y[1] + a2 * y[2], b0 * y[0] + b1 * y[1] + b2 * y[2],
                  c0 * y[0] + c1 * y[1] + c2 * y[2]])
    V = frame(f, np.asarray(f2, dtype=float).tolist())
    if S is None or V is None:  # e2 zero (a zeroed sample) or along e1: the heading of the e1 axis (pre-L30 rule)
        return math.atan2(s[0] * f[1] - s[1] * f[0], s[0] * f[0] + s[1] * f[1])
    (s1, s2, s3), (v1, v2, v3) = S, V
    R = [[v1[i] * s1[j] + v2[i] * s2[j] + v3[i] * s3[j] for j in range(3)] for i in range(3)]
    return twist_about_z(R)


def start_index(t: np.ndarray, t0: float | None) -> int:
    """Decision L33: index of the first sample at or after ``t0`` (s) in a stride's samples ``t`` as cut by
    :func:`segment` (one sample before ``t0`` when ``t0`` falls between two samples): 0 or 1. The stride's
    last sample is the first at or after its end, so consecutive strides chain their heading changes
    sample to sample, no interval counted twice or left out."""
    return 1 if t0 is not None and len(t) > 2 and float(t[0]) < t0 - TIE_S else 0  # E35: within TIE_S = at t0


def stride_dpsi(forward_s: np.ndarray, acc: np.ndarray, Y: np.ndarray, s: int = 0,
                t: np.ndarray | None = None) -> float:
    """Decisions L30/L33: heading change (rad, + = left) of the foot from sample ``s`` to the last sample of
    a stride: the twist about the vertical of R_end R_s^T, each attitude given by the body vectors (declared
    forward axis ``forward_s``, the sample's specific force ``acc[k]``) and their levelled images ``Y[k, 2]``,
    ``Y[k, 0]`` (rows of :func:`pdrlearn.kernels.stats.levelled_vectors`: acc, gyro, forward axis).

    The attitude at the start rest's quietest sample (the tilt reference ``r0``) is not the stride's start:
    the foot still turns in the ~0.1 s between the middle of the stance and that sample (the gaitmap level
    walks: 0.015 rad per stride, always the same sign, a heading drift of ~0.9 deg/s), so the heading is
    measured from the stride's own first sample, which is the previous stride's last one (decision L33).

    ``t`` (the samples' times, s) given, the coning term the mean-rate attitude misses is added
    (:func:`coning_yaw`, decision L35) and the twist is unwrapped on the levelled vertical rate's integral (decision
    L690: a spin of 180-360 deg inside the stride); the levelled rows ``Y`` (the step window's signals) are not
    changed."""
    if s == 0 and len(Y) == 1:
        return 0.0
    fwd = np.asarray(forward_s, dtype=float).tolist()  # Python floats, each row fetched once (runtime E17)
    ys = np.asarray(Y[s], dtype=float).tolist()  # rows acc, gyro, fwd
    d = _dpsi(fwd, acc, Y, ys, _attitude(fwd, np.asarray(acc[s], dtype=float).tolist(), ys[2], ys[0]))
    return d if t is None else _unwrapped(d + coning_yaw(t, Y, s), t, Y, s)


def stride_headings(forward_s: np.ndarray, acc: np.ndarray, Y: np.ndarray, s: int = 0,
                    t: np.ndarray | None = None) -> tuple[float, float]:
    """``(stride_dpsi(forward_s, acc, Y, s, t), start_heading(forward_s, acc[s], Y[s]))`` with the attitude at
    sample ``s`` computed once (both need it; the same values bit for bit, runtime decision E17)."""
    fwd = _floats(forward_s)  # a list as it is: the runtime converts its declared axis once (runtime E20)
    ys = Y[s].tolist()  # float arrays: np.asarray(., dtype=float).tolist() without the asarray (E20)
    Rs = _attitude(fwd, acc[s].tolist(), ys[2], ys[0])
    psi0 = math.atan2(ys[2][1], ys[2][0]) if Rs is None else twist_about_z(Rs)
    if s == 0 and len(Y) == 1:
        return 0.0, psi0
    d = _dpsi(fwd, acc, Y, ys, Rs)
    return (d if t is None else _unwrapped(d + coning_yaw(t, Y, s), t, Y, s)), psi0


def _unwrapped(d: float, t: np.ndarray, Y: np.ndarray, s: int) -> float:
    """Decision L690: the twist ``d`` (rad, modulo 2 pi) on the branch of the levelled vertical rate (``Y[k, 1, 2]``)
    integrated from sample ``s`` to the stride's last: a spin of 180-360 deg inside one stride is itself."""
    return unwrapped_turn(d, integrated_yaw(t[s:], Y[s:, 1, 2]))




def coning_yaw(t: np.ndarray, Y: np.ndarray, s: int = 0) -> float:
    """Decision L35: the heading change (rad, + = left) from sample ``s`` to the last sample that the attitude
    from the mean rate of each sample interval misses: (5/24) sum_k dt_k^2 (w_k x w_k+1)_z, with ``w_k``
    the levelled angular rate (``Y[k, 1]``, rad/s, rows of :func:`pdrlearn.kernels.stats.levelled_vectors`)
    and ``dt_k`` the sample intervals (s, from ``t``). Without it the simulated 20 Hz foot's heading drifts
    +0.023 rad per stride (one sign on every stride: the swing's pitch and roll do not commute); the term
    scales with dt^2 (25x smaller at 100 Hz, 100x at 204.8 Hz). Only the heading chain takes it: the
    levelled step windows (training features) stay as they are."""
    w = Y[s:, 1, :2]  # the rate's x, y (one index, E20)
    if w.shape[0] < 2:
        return 0.0
    dt = t[s + 1:] - t[s:-1]
    dt *= dt
    # sum dt^2 (x_k y_k+1 - y_k x_k+1) as the two sums of [x_k y_k+1, y_k x_k+1] (fewer calls per step)
    p, q = (dt @ (w[:-1] * w[1:, ::-1])).tolist()
    return CONING_COEF * (p - q)


def _dpsi(fwd: list[float], acc: np.ndarray, Y: np.ndarray, ys: list, Rs: list | None) -> float:
    """:func:`stride_dpsi` given the start sample's levelled rows ``ys`` and attitude ``Rs``."""
    ye = Y[-1].tolist()  # float arrays (E20)
    Re = _attitude(fwd, acc[-1].tolist(), ye[2], ye[0])
    if Rs is None or Re is None:  # a zeroed sample or the specific force along the forward axis: the
        f, g = ys[2], ye[2]  # forward axis's heading change (pre-L30)
        return math.atan2(f[0] * g[1] - f[1] * g[0], f[0] * g[0] + f[1] * g[1])
    # R_end R_s^T on Python floats (3x3: cheaper than numpy calls, runtime E16), each entry the sum
    # 0 + p0 + p1 + p2 (as sum() of the three products), written out (runtime E17)
    (a0, a1, a2), (a3, a4, a5), (a6, a7, a8) = Re
    (b0, b1, b2), (b3, b4, b5), (b6, b7, b8) = Rs
    R = [[0 + a0 * b0 + a1 * b1 + a2 * b2, 0 + a0 * b3 + a1 * b4 + a2 * b5, 0 + a0 * b6 + a1 * b7 + a2 * b8],
         [0 + a3 * b0 + a4 * b1 + a5 * b2, 0 + a3 * b3 + a4 * b4 + a5 * b5, 0 + a3 * b6 + a4 * b7 + a5 * b8],
         [0 + a6 * b0 + a7 * b1 + a8 * b2, 0 + a6 * b3 + a7 * b4 + a8 * b5, 0 + a6 * b6 + a7 * b7 + a8 * b8]]
    return twist_about_z(R)


def start_heading(forward_s: np.ndarray, acc_s: np.ndarray, Y_s: np.ndarray) -> float:
    """Decision L34: the foot's heading (rad, in the levelled frame of the stride) at the sample whose body
    vectors ``forward_s``, ``acc_s`` (specific force, gravity included) are levelled to ``Y_s[2]``,
    ``Y_s[0]`` (a row of :func:`pdrlearn.kernels.stats.levelled_vectors` before gravity is removed): the
    twist about the vertical of that attitude (the heading the stride chain of L30/L33 carries forward), not
    the heading of the declared forward axis, which a pitched instep mount makes depend on the roll (L30).
    A degenerate attitude gives the heading of the levelled forward axis."""
    ys = np.asarray(Y_s, dtype=float).tolist()
    R = _attitude(forward_s, acc_s, ys[2], ys[0])
    if R is None:
        return math.atan2(ys[2][1], ys[2][0])
    return twist_about_z(R)


def step_direction(axis: np.ndarray, heading0: float) -> float:
    """Decision L34: direction (rad, + = left, in (-pi, pi]) of the step frame's forward axis ``axis``
    (levelled, (2,) or (3,)) relative to the foot's heading ``heading0`` (:func:`start_heading`)."""
    d = math.atan2(float(axis[1]), float(axis[0])) - heading0
    return math.atan2(math.sin(d), math.cos(d))


def _frame3(a: list[float], b: list[float]) -> tuple[list[float], list[float], list[float]] | None:
    """Orthonormal frame (u, v, u x v) from ``a`` and the part of ``b`` normal to it; None when ``a`` is
    zero or ``b`` (nearly) along it."""
    a0, a1, a2 = a  # each entry read once (the same arithmetic; fewer list lookups, runtime decision E18)
    b0, b1, b2 = b
    na = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    if not na > 0:
        return None
    u0, u1, u2 = a0 / na, a1 / na, a2 / na
    d = u0 * b0 + u1 * b1 + u2 * b2
    v0, v1, v2 = b0 - d * u0, b1 - d * u1, b2 - d * u2
    nv = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    if not nv > 1e-9 * math.sqrt(b0 * b0 + b1 * b1 + b2 * b2):
        return None
    v0, v1, v2 = v0 / nv, v1 / nv, v2 / nv
    return [u0, u1, u2], [v0, v1, v2], [u1 * v2 - u2 * v1, u2 * v0 - u0 * v2, u0 * v1 - u1 * v0]


def _attitude(e1, e2, f1, f2) -> list[list[float]] | None:
    """The rotation (3x3 nested lists) carrying the body vectors ``e1``, ``e2`` to ``f1``, ``f2`` (frames of
    :func:`_frame3`); None when a frame is degenerate."""
    S = _frame3(e1 if type(e1) is list else _floats(e1), e2 if type(e2) is list else _floats(e2))  # lists as
    V = _frame3(f1 if type(f1) is list else _floats(f1), f2 if type(f2) is list else _floats(f2))  # they are
    if S is None or V is None:
        return None
    (s1, s2, s3), (v1, v2, v3) = S, V
    x1, y1, z1 = s1  # V S^T, entry (i, j) = v1[i] s1[j] + v2[i] s2[j] + v3[i] s3[j] (written out, E17)
    x2, y2, z2 = s2
    x3, y3, z3 = s3
    return [[p * x1 + q * x2 + r * x3, p * y1 + q * y2 + r * y3, p * z1 + q * z2 + r * z3]
            for p, q, r in zip(v1, v2, v3, strict=True)]


def _floats(v) -> list[float]:
    """A 3-vector as a list of Python floats (lists of floats as they are)."""
    return v if type(v) is list else np.asarray(v, dtype=float).tolist()


def twist_about_z(R: np.ndarray | list) -> float:
    """Angle (rad, in (-pi, pi]) about the vertical of the rotation ``R`` (3, 3): 2 atan2(q_z, q_w) of its
    quaternion (swing-twist decomposition), the quaternion taken from the largest of its four squares
    (Shepperd), so that a half-turn stride (q_w near 0) keeps full precision."""
    (a, b, c), (d, e, f), (g, h, i) = R.tolist() if isinstance(R, np.ndarray) else R
    # 4 q_w^2, 4 q_x^2, ...; the first largest, as max(range(4), key=sq.__getitem__) without its calls (E20)
    k, best = 0, 1.0 + a + e + i
    sq = 1.0 + a - e - i
    if sq > best:
        k, best = 1, sq
    sq = 1.0 - a + e - i
    if sq > best:
        k, best = 2, sq
    sq = 1.0 - a - e + i
    if sq > best:
        k, best = 3, sq
    m = 2.0 * math.sqrt(best)  # 4 q_k
    if k == 0:
        qw, qz = 0.25 * m, (d - b) / m
    elif k == 1:
        qw, qz = (h - f) / m, (c + g) / m
    elif k == 2:
        qw, qz = (c - g) / m, (f + h) / m
    else:
        qw, qz = (d - b) / m, 0.25 * m
    return 2.0 * math.atan2(qz if qw >= 0 else -qz, abs(qw))


def waist_levelled(acc: np.ndarray, gyr: np.ndarray | None, forward_s: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray | None]:
    """Waist acc (gravity removed) and rate in the step frame: tilt from the mean specific force over
    the step (the pelvis never rests while walking), forward = the declared axis made horizontal."""
    g = col_mean(acc)
    r = gravity_rotation(g)
    ref = (r @ forward_s)[:2]
    if vec_norm(ref) < 0.1:
        raise DataError("waist unit: the declared forward axis points (nearly) vertically; "
                        "check the declared waist frame (meta.json or the bundle's frames)")
    rr = heading_rotation(ref / vec_norm(ref)) @ r
    a = acc @ rr.T
    a[:, 2] -= vec_norm(g)
    return a, (None if gyr is None else gyr @ rr.T)


def available_groups(streams: Streams) -> tuple[str, ...]:
    """Sensor groups (keys of :data:`GROUPS`) whose every source stream is in ``streams``."""
    return tuple(g for g, names in GROUP_STREAMS.items() if all(nm in streams for nm in names))


Levelled = dict[str, tuple[np.ndarray, np.ndarray, "np.ndarray | None", "np.ndarray | None", float]]


#: Decision E36: an interval between two foot-accelerometer samples of a stride longer than this (s) is a gap:
#: the runtime's warned gap (``GAP_WARN_S``, decision E30; shorter ones cannot hide a stance)
BRIDGE_GAP_S = 0.25
#: decision E230: an interval is over :data:`BRIDGE_GAP_S` only by more than this (s): float rounding of the timestamps
#: (a lost 4-sample packet at 20 Hz: ``32.2 - 31.95`` = 0.25000000000000355 s, ``31.2 - 30.95`` = 0.25 s) must not
#: decide whether the same loss is a gap (far under any sample interval: 1e-6 s is 0.1 % of a 1 kHz one)
GAP_TOL_S = 1e-6


def gap_clock(t: np.ndarray, gap_s: float = BRIDGE_GAP_S) -> np.ndarray:
    """Decision E36: a stride's sample times ``t`` (s) with each interval longer than ``gap_s`` counted as one
    sample interval (the median of the other intervals), the later samples moved earlier by the difference:
    the clock offline ``pdrlearn track`` integrates a stride on (``FootDisplacement``: dt = 1 / fs per sample,
    so a gap bridged by B11 counts as one interval). ``t`` itself when it has no such interval (the same
    numbers, bit for bit)."""
    if len(t) < 2:
        return t
    d = t[1:] - t[:-1]
    big = d > gap_s + GAP_TOL_S  # decision E230: not by float rounding
    if not big.any():
        return t
    small = d[~big]
    nominal = float(np.median(small)) if len(small) else float(gap_s)  # no regular interval: the gap limit
    shift = np.concatenate(([0.0], np.cumsum(np.where(big, d - nominal, 0.0))))
    return t - shift


#: Decision L674: a stride whose foot accelerometer / gyroscope samples have an interval longer than this many of
#: their own median interval in the stride (two samples lost or more) has a hole in it: no classes and no height
#: change (trial T2 F6: a 120 ms hole at 100 Hz gave a confident "down" stride with dz -0.46 m on flat ground)
SWING_GAP_INTERVALS = 2.5
#: decision L674 amended (session 45, FM, review R3 F2): the limit is raised by this many robust standard deviations
#: (1.4826 x MAD) of the stride's intervals, so timestamp jitter (4 ms at 100 Hz flagged 9 of 15 complete strides)
#: is not read as a hole; a clean clock's MAD is 0 and the limit is L674's
HOLE_JITTER_MADS = 3.0


def stride_hole(t: np.ndarray, t0: float, t1: float) -> float:
    """Decision L674: the longest interval (s) between the samples ``t`` (rising) that lie in or cover the stride
    ``[t0, t1]`` (:func:`cover`'s) when it is over :data:`SWING_GAP_INTERVALS` of their median interval (plus
    :data:`HOLE_JITTER_MADS` robust deviations of the intervals, R3 F2, and :data:`GAP_TOL_S`, E230), else 0.0
    (also with fewer than three samples)."""
    a, b = cover(t, t0, t1)
    if b - a < 3:
        return 0.0
    d = np.diff(t[a:b])
    longest = float(d.max())
    med = float(np.median(d))
    jitter = HOLE_JITTER_MADS * 1.4826 * float(np.median(np.abs(d - med)))  # L674 amended (R3 F2): the intervals'
    return longest if longest > SWING_GAP_INTERVALS * med + jitter + GAP_TOL_S else 0.0  # own spread, robust (MAD)


def hole_stride_dz(ref) -> float:
    """Decision L674 amended (session 45, FM, review R3 F1): the height change (m) of a stride with a hole, that of
    the nearest clean stride before it (``ref``: ``((dx, dy, dz), duration_s)``, L167's neighbour, or None: 0.0).
    L674's 0 m flattened real stairs (two stairs a stride, 0.34 m: a 17-stair flight with a 0.12 s hole every 3 s
    climbed 1.86 of 2.86 m); on level ground the neighbour's height is ~0, as L674's was."""
    return 0.0 if ref is None else float(ref[0][2])


def stride_hole_line(hole_s: float, t0: float, t1: float) -> str:
    """Decision L674: the one line for the first stride with a hole (the runtime's and ``track --streaming``'s)."""
    return (f"foot accelerometer / gyroscope samples missing for {hole_s:.2f} s inside the stride at "
            f"{t0:.2f}-{t1:.2f} s (over {SWING_GAP_INTERVALS:g} of their sample intervals): strides with such a hole "
            "have no classes and the height change of the clean stride before them, their length kept (decision L674; "
            "said once)")


def levelled_units(streams: Streams, t0: float, t1: float, *, available: tuple[str, ...],
                   forward: Mapping[str, np.ndarray], rest_search_s: float, heading: str,
                   bridge_gaps: bool = False) -> Levelled:
    """Each unit's samples of the step ``[t0, t1]`` at the unit's own rate, in the step frame.

    Returns placement -> ``(t (n,) s, acc (n, 3) m/s^2 gravity removed, gyr (n, 3) rad/s or None,
    |acc| (n,) or None, heading change (rad) of the foot's attitude or nan)`` for ``foot``
    (:func:`foot_levelled`; the foot's tuple has a sixth value, the step frame's direction relative to
    the foot's heading at the stride's start, decision L34) and ``waist`` (:func:`waist_levelled`)
    when their accelerometer is available and their forward axis is declared.

    ``bridge_gaps`` (decision E36, the stride kernel's callers): the foot is levelled on :func:`gap_clock` of its
    times, which it returns as its times (what the displacement is integrated on): a gap in the foot
    accelerometer inside the stride counts as one sample interval, as offline (the step window's training side
    keeps the real clock).
    """
    out: Levelled = {}
    if "foot_acc" in available and "foot" in forward:
        ta, acc = segment(*streams["fAccelerometer"], t0, t1)
        gyr = resample(ta, *segment(*streams["fGyroscope"], t0, t1)).T if "foot_gyr" in available else None
        tf, s0 = (gap_clock(ta) if bridge_gaps else ta), t0
        if tf is not ta:  # the stride's start on the same sample of the moved clock (start_index: 0 or 1)
            s0 = float(tf[1]) if start_index(ta, t0) else t0
            ta = tf
        a, g, an, dpsi, direction = foot_levelled(ta, acc, gyr, forward["foot"], rest_search_s=rest_search_s,
                                                  heading=heading, t0=s0, frame=True)
        out["foot"] = (ta, a, g, an, dpsi, direction)
    if "waist_acc" in available and "waist" in forward:
        tw, wacc = segment(*streams["wAccelerometer"], t0, t1)
        wgyr = resample(tw, *segment(*streams["wGyroscope"], t0, t1)).T if "waist_gyr" in available else None
        a, g = waist_levelled(wacc, wgyr, forward["waist"])
        out["waist"] = (tw, a, g, None, float("nan"))
    return out


def stride_rest_pitch(stream, forward_s: np.ndarray, t0: float, t1: float, *, rest_search_s: float) -> float:
    """Decisions B473 / B474: :func:`rest_pitch_deg` of the foot samples of the stride ``[t0, t1]`` (s) read as
    :func:`levelled_units` reads them; ``stream(name)`` -> ``(t, values)`` of a buffered stream (the runtime's ring,
    ``track --streaming``'s session), so both judge a stride alike. NaN without foot samples."""
    try:
        ta, acc = segment(*stream("fAccelerometer"), t0, t1)
        gyr = resample(ta, *segment(*stream("fGyroscope"), t0, t1)).T
    except KeyError:
        return math.nan
    return rest_pitch_deg(ta, acc, gyr, forward_s, rest_search_s=rest_search_s)


@functools.lru_cache(maxsize=8)
def _unit_grid(n_samples: int) -> np.ndarray:
    g = np.linspace(0.0, 1.0, n_samples)
    g.flags.writeable = False
    return g


def fill_step_window(Xi: np.ndarray, streams: Streams, t0: float, t1: float, *, channel_index: Mapping[str, int],
                     available: tuple[str, ...], forward: Mapping[str, np.ndarray], rest_search_s: float,
                     heading: str, channels: Collection[str] | None = None) -> Levelled:
    """Write one step's channels ``(len(channel_index), n_samples)`` into ``Xi`` (in place).

    Parameters
    ----------
    Xi : NaN-filled output; row ``channel_index["t_s"]`` gets the time since ``t0`` (s).
    streams : sensor name -> ``(t (n,) s, values (n, k))`` covering ``[t0, t1]``.
    t0, t1 : step start and end (s).
    available : sensor groups to fill (the others stay NaN).
    forward : placement (``foot``/``waist``) -> sensor-frame vector pointing body-forward.
    channels : only these channels are resampled, the others stay NaN (the streaming runtime asks for
        the channels its step graph reads, decision E13); None = every channel. A written channel has the
        same values either way (the resampling is column by column).

    Returns
    -------
    The units' levelled samples at their own rate (:func:`levelled_units`), for the stride kernels.
    """
    ci = channel_index
    n_samples = Xi.shape[1]
    tg = t0 + (t1 - t0) * _unit_grid(n_samples)
    Xi[ci["t_s"]] = tg - t0
    lev = levelled_units(streams, t0, t1, available=available, forward=forward, rest_search_s=rest_search_s,
                         heading=heading)
    if channels is not None:
        _fill_channels(Xi, streams, t0, t1, tg, lev, ci, available, set(channels))
        return lev
    if "foot" in lev:  # one resampling call for all of a unit's channels (same numbers, fewer calls)
        ta, a, g, an = lev["foot"][:4]
        r = resample(tg, ta, np.column_stack([a, an] if g is None else [a, an, g]))
        c = ci["foot_acc_x"]
        Xi[c:c + 3] = r[:3]
        Xi[ci["foot_acc_norm"]] = r[3]
        if g is not None:
            c = ci["foot_gyr_x"]
            Xi[c:c + 3] = r[4:7]
    if "force" in available:
        _fill_force(Xi, streams, t0, t1, tg, ci)
    if "waist" in lev:
        tw, a, g, _, _ = lev["waist"]
        r = resample(tg, tw, a if g is None else np.column_stack([a, g]))
        c = ci["waist_acc_x"]
        Xi[c:c + 3] = r[:3]
        if g is not None:
            c = ci["waist_gyr_x"]
            Xi[c:c + 3] = r[3:6]
    if "waist_baro" in available:
        tb, b = segment(*streams["wBarometer"], t0, t1)
        Xi[ci["waist_baro"]] = interp(tg, tb, b[:, 0]) - interp(t0, tb, b[:, 0])
    return lev


def _fill_force(Xi: np.ndarray, streams: Streams, t0: float, t1: float, tg: np.ndarray,
                ci: Mapping[str, int]) -> None:
    """Resample the two force sensors of the window onto ``tg`` (rows ``force_a`` / ``force_b`` of ``Xi``)."""
    (ta_, fa), (tb_, fb) = (segment(*streams[name], t0, t1) for name in ("fForceA", "fForceB"))
    if len(ta_) == len(tb_) and (ta_ == tb_).all():  # one clock: one resampling call for both sensors
        Xi[[ci["force_a"], ci["force_b"]]] = resample(tg, ta_, np.column_stack([fa[:, 0], fb[:, 0]]))
    else:
        Xi[ci["force_a"]] = resample(tg, ta_, fa)[0]
        Xi[ci["force_b"]] = resample(tg, tb_, fb)[0]


def _fill_channels(Xi: np.ndarray, streams: Streams, t0: float, t1: float, tg: np.ndarray, lev: Levelled,
                   ci: Mapping[str, int], available: tuple[str, ...], need: set[str]) -> None:
    """:func:`fill_step_window`'s resampling for the channels in ``need`` only (one call per unit)."""
    units = []
    if "foot" in lev:
        ta, a, g, an = lev["foot"][:4]
        cols = {"foot_acc_x": a[:, 0], "foot_acc_y": a[:, 1], "foot_acc_z": a[:, 2], "foot_acc_norm": an}
        if g is not None:
            cols.update(foot_gyr_x=g[:, 0], foot_gyr_y=g[:, 1], foot_gyr_z=g[:, 2])
        units.append((ta, cols))
    if "waist" in lev:
        tw, a, g, _, _ = lev["waist"]  # a is None when no needed channel reads it (runtime, decision E17)
        cols = {} if a is None else {"waist_acc_x": a[:, 0], "waist_acc_y": a[:, 1], "waist_acc_z": a[:, 2]}
        if g is not None:
            cols.update(waist_gyr_x=g[:, 0], waist_gyr_y=g[:, 1], waist_gyr_z=g[:, 2])
        units.append((tw, cols))
    for t, cols in units:
        names = [c for c in cols if c in need]
        if names:
            Xi[[ci[c] for c in names]] = resample(tg, t, np.column_stack([cols[c] for c in names]))
    if "force" in available and need & {"force_a", "force_b"}:
        _fill_force(Xi, streams, t0, t1, tg, ci)
    if "waist_baro" in available and "waist_baro" in need:
        tb, b = segment(*streams["wBarometer"], t0, t1)
        Xi[ci["waist_baro"]] = interp(tg, tb, b[:, 0]) - interp(t0, tb, b[:, 0])
