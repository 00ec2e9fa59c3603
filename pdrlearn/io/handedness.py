"""Is a unit's gyroscope right-handed with respect to its accelerometer? (decision D11, amends D10)

In a right-handed sensor frame a fixed world vector seen by the sensor turns against the angular rate,
d(g_b)/dt = -omega x g_b; data mirrored in one axis (the same column negated in the accelerometer and the
gyroscope, e.g. left-foot data mirrored to look like a right foot) obey d(g_b)/dt = +omega x g_b instead,
because the angular rate is a pseudovector. So the data can say which sign fits: the gyroscope turned
the right way (``+omega``) or reversed (``-omega``, what mirrored data look like to a right-handed model).
The comparison is made where the motion makes it decisive and the linear acceleration cannot mask it:

- **foot**: every rest-to-rest stride is integrated as the ZUPT stride integration does (levelled by the
  start rest, attitude from the gyroscope, gravity removed); the velocity at the end rest must be zero.
  A reversed attitude leaks gravity into it through the whole swing (the foot pitches 50-80 deg).
  Per stride: log(|v_end(-omega)| / |v_end(+omega)|).
- **waist**: windows of :data:`WAIST_WINDOW_S`; in each, the same integration from the window start, and
  the velocity after removing a straight line (gravity's projection and the start attitude's error give
  a constant acceleration): walking keeps it within the velocity's within-stride swing, a reversed
  attitude adds the leaked gravity. Per window: log(E(-omega) / E(+omega)), E the residual's mean square.
  Only windows in which the unit moves (:data:`WAIST_MIN_ACC_SD`) count.

Positive = right-handed. The check takes the median over the strides / windows of the first
:data:`~pdrlearn.track.frame_inference.CHECK_SPAN_S` seconds and warns only below
:data:`MIN_LOG_RATIO` with at least :data:`MIN_SEGMENTS` of them (docs/frames.md, the measurement).
A declared frame (D8/D10) says where the axes point; this says whether the two sensors agree on the
sense of rotation, which no frame entry can fix: the data have to be un-mirrored.

**Axis agreement (D11 amendment)**: the foot test generalizes from {as recorded, reversed} to the 48 signed
permutations of the gyroscope's axes (24 rotations, 24 with a reflection; reversed = ``-I`` is one of them):
a gyroscope whose chip axes differ from the accelerometer's (a 90-degree turn, swapped columns) fits
neither sign. On at most :data:`AXES_STRIDES` strides averaged to about :data:`AXES_RATE_HZ` (cost),
every permutation P is integrated in one batch; per P the median over the strides of
log(|v_end(as recorded)| / |v_end(P omega)|) (> 0: P fits better). The best P other than the identity
is confirmed on all the strides at the full rate and reported when that median exceeds
:data:`AXES_MIN_LOG_RATIO` (:func:`foot_axes`, :attr:`Handedness.axes`).
"""

from __future__ import annotations

import itertools
import json
from dataclasses import dataclass

import numpy as np

from pdrlearn.kernels.handedness import (  # decision B129: the test's numpy core, shared with the runtime
    MIN_LOG_RATIO,
    MIN_SEGMENTS,
    end_speeds,
    log_ratio,
    mirrored_pair_line,
)
from pdrlearn.kernels.handedness import mirrored as _mirrored

#: Units whose test may warn. The waist test is measured but not adopted (docs/frames.md, decision D11): truthful
#: simulated waist units score -0.25 to -0.64 (the simulated pelvis rolls against its lateral acceleration at
#: the stride frequency, the real lower backs with it; both are right-handed: docs/decisions/simulator.md S26;
#: real +0.18 to +2.26), so its sign is set by the motion and is not a confident verdict, and at
#: a threshold that spares them it catches only the long real recordings' mirrored versions.
WARN_PLACEMENTS = ("foot",)
#: Units whose axis-agreement test (D11 amendment) may warn: foot (48 permutations), waist (turning axis).
AXES_PLACEMENTS = ("foot", "waist")
#: Waist window length and hop (s): about one stride (0.8-1.4 s at 1.4-2.4 steps/s) to two.
WAIST_WINDOW_S = 2.0
WAIST_HOP_S = 1.0
#: A waist window counts when the standard deviation of |specific force| in it exceeds this (m/s^2):
#: walking at the lower back swings it by 1-3 m/s^2 (trunk accelerations: seed 003 Fig. 1), standing by
#: less than 0.2.
WAIST_MIN_ACC_SD = 0.5
#: Axis agreement (D11 amendment): strides (at most, evenly spaced) on which all 48 permutations are tried,
#: and the rate (Hz) they are block-averaged to (not below it): 8 strides at ~30 Hz add 0.04-1.31 times D11's
#: CPU time on the real foot recordings (12 at ~50 Hz added 0.11-2.51 times; docs/decisions.md, D11
#: amendment; the simulated 20 Hz units are used as they are).
AXES_STRIDES = 8
AXES_RATE_HZ = 30.0
#: Report another permutation when it fits e times better than the axes as recorded in the median stride
#: (confirmed on all strides): the same margin as D11's MIN_LOG_RATIO. Measured (experiments/axes_check.py):
#: see docs/decisions.md, D11 amendment.
AXES_MIN_LOG_RATIO = 1.0
#: Waist axis agreement (D11 amendment): a turn window is :data:`TURN_WINDOW_S` (hop :data:`TURN_HOP_S`) over
#: which the integrated angular rate exceeds :data:`TURN_MIN_DEG` (the pelvis's walking oscillations of a few
#: degrees cancel over a stride, a turn accumulates); the principal axis of those windows' rotation vectors
#: is the turning (yaw) axis, which must lie along gravity (the accelerometer's mean) within
#: :data:`TURN_MAX_DEG` when at least :data:`TURN_MIN_WINDOWS` windows turn. Measured (experiments/axes_check.py).
TURN_WINDOW_S = 2.0
TURN_HOP_S = 0.5
TURN_MIN_DEG = 30.0
TURN_MIN_WINDOWS = 3
TURN_MAX_DEG = 30.0
#: Decision B263: turn windows within this many seconds of a window in which the unit lies (its gravity at W222's
#: 60 deg or more from the walking upright) are left out: W249's SIDE_WINDOW_S, the span before a lying run that
#: holds its way into bed (a sit on the bed's edge, the lying down)
LYING_GUARD_S = 10.0
#: Decision W280: a turn window whose accelerometer gravity (its first and last quarters' means) turns by this
#: fraction of the window's net rotation or more is the unit tilting (a trunk pitching in a chair rise), not a walker
#: turning about gravity; our choice, set before measuring
TILT_WITH_TURN = 0.5
#: The accelerometer's mean must measure gravity for the waist test: at least half of g (m/s^2). Gravity-removed
#: ("linear") acceleration averages to about 0 and points anywhere (the new-user trial's ph_linacc sessions
#: scored 84-86 deg: a wrong "axes differ" without this).
TURN_MIN_GRAVITY = 0.5 * 9.80665
#: Mirrored foot data (decision L71): the axis to negate back is named when the gyroscope's principal axis
#: (the foot's pitch axis in walking: the sagittal rotation dominates the foot's angular rate) lies within
#: this of one sensor axis. Measured (experiments/pitch_axis.py, docs/decisions/localization.md L71): 2.0-26.3
#: deg on the 11 gaitmap foot recordings and the trial's export, 9.0-9.3 deg on simulated A and D (always the
#: declared lateral axis); 54.7 deg is the most the nearest axis can be off.
PITCH_AXIS_MAX_DEG = 35.0


def signed_permutations() -> np.ndarray:
    """The 48 signed permutation matrices (48, 3, 3), the identity first (``-I`` is the eighth)."""
    out = []
    for p in itertools.permutations(range(3)):
        for s in itertools.product((1.0, -1.0), repeat=3):
            P = np.zeros((3, 3))
            P[np.arange(3), p] = s
            out.append(P)
    return np.array(out)


PERMUTATIONS = signed_permutations()


def _index(P: np.ndarray) -> int:
    return int(np.flatnonzero((PERMUTATIONS == np.asarray(P)).all(axis=(1, 2)))[0])


def axes_label(P: np.ndarray) -> str:
    """How the gyroscope's recorded (x, y, z) read in the accelerometer's axes when ``P`` @ recorded =
    the rate in the accelerometer's axes: ``"(z, y, -x)"`` = the gyroscope's x is the accelerometer's z,
    its y the accelerometer's y, its z the accelerometer's -x."""
    Q = np.asarray(P).T
    return "(" + ", ".join(("-" if Q[i].sum() < 0 else "") + "xyz"[int(np.flatnonzero(Q[i])[0])]
                           for i in range(3)) + ")"


def axes_fix(P: np.ndarray) -> str:
    """The column rewrite of the gyroscope file that gives the accelerometer's axes: ``x = -z, y = y, z = x``."""
    P = np.asarray(P)
    return ", ".join(f"{'xyz'[i]} = " + ("-" if P[i].sum() < 0 else "") + "xyz"[int(np.flatnonzero(P[i])[0])]
                     for i in range(3))


def axes_fix_acc(P: np.ndarray) -> tuple[str, bool]:
    """The other fix of :func:`axes_fix`: the column rewrite of the accelerometer file that gives the
    gyroscope's axes (the inverse, ``P^T``), and whether the gyroscope's three columns must be negated too.
    The test cannot see the sign of all three accelerometer columns (their ZUPT errors are identical: the
    trial's session D scored +3.15 with both), so of ``P^T`` and ``-P^T`` the one with fewer negations is
    given: a plain column-order mistake needs none (trial 2, finding 8: ``--acc acc_y_g,acc_x_g,acc_z_g``
    gave ``P`` = (-y, -x, -z) and the accelerometer fix ``x = y, y = x, z = z``). When ``P`` is improper
    (mirrored and permuted), rewriting the accelerometer alone leaves a mirrored pair: the gyroscope's
    columns must be negated as well."""
    Q = np.asarray(P).T
    if (Q < 0).sum() > 1:  # Q has three nonzero entries: -Q has fewer negations when Q has two or three
        Q = -Q
    return axes_fix(Q), bool(np.linalg.det(np.asarray(P)) < 0)


def axes_fix_text(P: np.ndarray, acc_n: str, gyr_n: str) -> str:
    """The two rewrites that fix a unit whose gyroscope reads the accelerometer's axes permuted by ``P``
    (decision D11 amendment): the test finds how the two files disagree, not which one is wrong."""
    acc_fix, negate = axes_fix_acc(P)
    also = f" and negate all three columns of {gyr_n}.csv" if negate else ""
    return (f"the test cannot tell which file is wrong: if {gyr_n}.csv is, rewrite its columns as {axes_fix(P)}; "
            f"if {acc_n}.csv is (e.g. its columns were given in the wrong order), rewrite its columns as "
            f"{acc_fix}{also} (or re-export both sensors in one frame); a \"frames\" entry cannot fix this")


@dataclass
class Handedness:
    """Result of a handedness test: ``log_ratio`` the median over ``segments`` strides / windows of
    log(error with the gyroscope reversed / error as recorded) (> 0: right-handed), NaN when none."""

    placement: str
    log_ratio: float
    segments: int
    #: Axis agreement (foot, D11 amendment): the best signed permutation other than the identity (3, 3),
    #: P @ recorded gyroscope = rate in the accelerometer's axes, and its confirmed median log ratio
    #: (> 0: it fits better than the axes as recorded; on the subset of :func:`foot_axes`, on all the
    #: strides when above :data:`AXES_MIN_LOG_RATIO` on the subset); None / NaN when not computed.
    axes: np.ndarray | None = None
    axes_log_ratio: float = float("nan")
    #: Waist axis agreement (D11 amendment, :func:`turn_axis`): the angle (deg) between the gyroscope's
    #: turning axis and gravity, the number of turn windows, the gyroscope axis nearest the turning axis and
    #: the accelerometer axis nearest gravity (0-2, -1 when unknown).
    turn_deg: float = float("nan")
    turn_windows: int = 0
    turn_axes: tuple[int, int] = (-1, -1)
    #: Foot (decision L71, :func:`pitch_axis`): the sensor axis (0-2, -1 unknown) nearest the gyroscope's
    #: principal axis, the foot's medio-lateral pitch axis, and the angle (deg) between them.
    pitch_axis: int = -1
    pitch_deg: float = float("nan")

    @property
    def mirror_axis(self) -> str | None:
        """The axis ("x", "y" or "z") a left/right mirror negates, when the data show it (decision L71): the
        medio-lateral axis the foot pitches about, within :data:`PITCH_AXIS_MAX_DEG`; else None."""
        if self.pitch_axis < 0 or not self.pitch_deg <= PITCH_AXIS_MAX_DEG:
            return None
        return "xyz"[self.pitch_axis]

    @property
    def axes_differ(self) -> bool:
        """True when the gyroscope's axes disagree with the accelerometer's with confidence (D11 amendment):
        foot, another signed permutation than the identity and the reversal (``-I``, :attr:`mirrored`) fits
        the strides; waist, the gyroscope turns about an axis far from gravity."""
        if self.placement not in AXES_PLACEMENTS:
            return False
        if self.placement == "waist":
            return self.turn_windows >= TURN_MIN_WINDOWS and bool(self.turn_deg > TURN_MAX_DEG)
        return (self.axes is not None and self.segments >= MIN_SEGMENTS
                and not np.array_equal(self.axes, -np.eye(3)) and bool(self.axes_log_ratio > AXES_MIN_LOG_RATIO))

    @property
    def mirrored(self) -> bool:
        """True when the data say with confidence that the pair is left-handed (mirrored); always False
        for a unit outside :data:`WARN_PLACEMENTS`."""
        return self.placement in WARN_PLACEMENTS and _mirrored(self.log_ratio, self.segments)

    @property
    def verdict(self) -> str:
        """``mirrored``, ``right-handed``, ``unsure`` (too few segments or between the thresholds) or
        ``not tested`` (a unit whose test is not adopted: the ratio is informative only)."""
        if self.axes_differ:
            return "axes differ"
        if self.placement not in WARN_PLACEMENTS:
            return "not tested"
        if self.segments < MIN_SEGMENTS:
            return "unsure"
        return "mirrored" if self.mirrored else "right-handed" if self.log_ratio > -MIN_LOG_RATIO else "unsure"

    def describe(self) -> str:
        what = "strides" if self.placement == "foot" else "moving windows"
        ratio = "no" if not np.isfinite(self.log_ratio) else f"{self.log_ratio:+.2f}"
        axes = (f"; best other gyroscope axes {axes_label(self.axes)}, log ratio {self.axes_log_ratio:+.2f}"
                if self.axes is not None and np.isfinite(self.axes_log_ratio) else "")
        if self.turn_windows:
            axes += f"; turning axis {self.turn_deg:.0f} deg from gravity over {self.turn_windows} turn windows"
        return f"{self.verdict} (log ratio {ratio} over {self.segments} {what}{axes}; decision D11)"

    def to_dict(self) -> dict:
        out = {"log_ratio": None if not np.isfinite(self.log_ratio) else round(float(self.log_ratio), 3),
               "segments": int(self.segments), "verdict": self.verdict}
        if self.axes is not None:
            out["axes"] = {"gyroscope": axes_label(self.axes), "fix": axes_fix(self.axes),
                           "fix_accelerometer": axes_fix_acc(self.axes)[0] + (
                               " and negate the gyroscope" if axes_fix_acc(self.axes)[1] else ""),
                           "log_ratio": (None if not np.isfinite(self.axes_log_ratio)
                                         else round(float(self.axes_log_ratio), 3))}
        if self.placement == "waist":
            out["turn_axis"] = {"angle_deg": None if not np.isfinite(self.turn_deg) else round(float(self.turn_deg), 1),
                                "turn_windows": int(self.turn_windows)}
        return out


def pitch_axis(gyr: np.ndarray) -> tuple[int, float]:
    """The sensor axis (0-2) nearest the principal axis of the angular rate ``gyr`` (n, 3) and the angle
    (deg) between them; ``(-1, nan)`` without rotation. On a walking foot it is the medio-lateral axis the
    foot pitches about (decision L71). Pure function."""
    g = np.asarray(gyr, dtype=float)
    m = g.T @ g if len(g) else np.zeros((3, 3))
    if not (np.isfinite(m).all() and np.trace(m) > 0):
        return -1, float("nan")
    u = np.linalg.eigh(m)[1][:, -1]
    k = int(np.argmax(np.abs(u)))
    return k, float(np.degrees(np.arccos(min(1.0, abs(float(u[k]))))))


def mirror_fix_text(h: Handedness, acc_n: str, gyr_n: str, *, how=None) -> str:
    """The fix of a mirrored (left-handed) pair, naming the axis when the data show it (decision L71): the
    medio-lateral axis :attr:`Handedness.mirror_axis`, which a left/right mirror negates. Negating any one
    axis in both files makes the pair right-handed; the data cannot say which one the export negated, so
    the text says so. ``how(axis)``: where to negate ``axis`` ("x"/"y"/"z", None when unknown); default in
    both files (``pdrlearn import`` gives its own ``--acc``/``--gyro`` options). The one wording of ``info``,
    ``track`` and ``import``."""
    ax = h.mirror_axis
    where = (how(ax) if how is not None else None) or f"in both {acc_n}.csv and {gyr_n}.csv"
    if ax is None:
        return (f"negate the mirrored axis back {where} (the data do not show which axis: the foot's pitch axis "
                "is not near one sensor axis; or re-export without mirroring)")
    how = where
    return (f"negate the {ax} axis back {how}: the foot pitches about its {ax} axis (the gyroscope's main "
            f"rotation axis is {h.pitch_deg:.0f} deg from it), "
            f"the medio-lateral axis a left/right mirror negates (negating any one axis makes the pair "
            f"right-handed; if the export negated another one, negate that one instead, or re-export without "
            f"mirroring)")


def foot_handedness(acc: np.ndarray, gyr: np.ndarray, fs: float) -> Handedness:
    """Handedness test of a foot unit: specific force (n, 3) m/s^2 and angular rate (n, 3) rad/s on one
    clock of ``fs`` Hz. Pure function (the stance detector and stride integration of ``displace``)."""
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.track.frame_inference import rest_to_rest

    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    i0, i1 = rest_to_rest(inertial_stance(acc, gyr, fs), fs)
    pk, pdeg = pitch_axis(gyr)
    if not len(i0):
        return Handedness("foot", float("nan"), 0, pitch_axis=pk, pitch_deg=pdeg)
    vp, vm = end_speeds(acc, gyr, 1.0 / fs, i0, i1)
    r = log_ratio(vm, vp)
    P, ra = foot_axes(acc, gyr, fs, i0, i1)
    r_axes = float(ra[_index(P)])
    if np.array_equal(P, -np.eye(3)):
        r_axes = -float(np.median(r))
    elif r_axes > AXES_MIN_LOG_RATIO:  # a candidate: confirmed on every stride at the full rate
        va = end_speeds(acc, gyr @ P.T, 1.0 / fs, i0, i1, signs=(1.0,))[0]
        r_axes = float(np.median(log_ratio(vp, va)))
    return Handedness("foot", float(np.median(r)), int(len(r)), P, r_axes, pitch_axis=pk, pitch_deg=pdeg)


def foot_axes(acc: np.ndarray, gyr: np.ndarray, fs: float, i0: np.ndarray, i1: np.ndarray,
              *, strides: int | None = None, rate_hz: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Axis agreement on a foot unit's rest-to-rest strides ``i0[b]..i1[b]`` (D11 amendment): the best
    signed permutation P (3, 3) other than the identity (P @ recorded = rate in the accelerometer's axes)
    and the median log ratio (48,) of every :data:`PERMUTATIONS` entry (> 0: fits better than as recorded),
    on at most ``strides`` evenly spaced strides block-averaged to about ``rate_hz`` (default
    :data:`AXES_STRIDES`, :data:`AXES_RATE_HZ`). Pure function."""
    from pdrlearn.displace._kernels import strapdown, stride_index, zupt_velocity

    strides = AXES_STRIDES if strides is None else strides
    rate_hz = AXES_RATE_HZ if rate_hz is None else rate_hz

    sel = np.unique(np.linspace(0, len(i0) - 1, min(strides, len(i0))).round().astype(np.int64))
    k = max(1, int(fs // rate_hz))
    a_parts, g_parts = [], []
    for b in sel:
        m = (i1[b] + 1 - i0[b]) // k * k
        a_parts.append(acc[i0[b]:i0[b] + m].reshape(-1, k, 3).mean(axis=1))
        g_parts.append(gyr[i0[b]:i0[b] + m].reshape(-1, k, 3).mean(axis=1))
    lens = np.array([len(a) for a in a_parts])
    A, G = np.concatenate(a_parts), np.concatenate(g_parts)
    n_p = len(PERMUTATIONS)
    starts = (np.arange(n_p)[:, None] * len(A) + np.concatenate([[0], np.cumsum(lens)[:-1]])[None, :]).ravel()
    ends = starts + np.tile(lens - 1, n_p)
    AA = np.tile(A, (n_p, 1))
    GG = np.einsum("pij,nj->pni", PERMUTATIONS, G).reshape(-1, 3)  # every permutation of every sample
    idx, mask = stride_index(starts, ends)
    a_nav, _ = strapdown(AA, GG, k / fs, idx, mask, AA[starts], coning=0.0)  # the lead's amendment of L626
    v = zupt_velocity(a_nav, mask, k / fs, zupt_end=False)
    e = np.log(np.maximum(np.linalg.norm(v[np.arange(len(starts)), mask.sum(axis=1) - 1], axis=1), 1e-9))
    e = e.reshape(n_p, len(sel))
    r = np.median(e[0][None, :] - e, axis=1)
    return PERMUTATIONS[1 + int(np.argmax(r[1:]))], r


def _detrended_energy(a_nav: np.ndarray, mask: np.ndarray, fs: float) -> np.ndarray:
    """Mean square (B,) of each window's velocity minus its least-squares straight line."""
    from pdrlearn.displace._kernels import zupt_velocity

    v = zupt_velocity(a_nav, mask, 1.0 / fs, zupt_end=False)
    L = v.shape[1]
    tt = np.arange(L) / fs
    A = np.stack([np.ones(L), tt - tt.mean()], axis=1)  # all windows have the same length
    coef = np.linalg.lstsq(A, v.transpose(1, 0, 2).reshape(L, -1), rcond=None)[0]
    r = v.transpose(1, 0, 2).reshape(L, -1) - A @ coef
    return (r.reshape(L, v.shape[0], 3) ** 2).sum(axis=2).mean(axis=0)


def waist_handedness(acc: np.ndarray, gyr: np.ndarray, fs: float, *, ratio: bool = True) -> Handedness:
    """Handedness test of a waist unit (arguments as :func:`foot_handedness`) with its axis agreement
    (:func:`turn_axis`); ``ratio=False`` skips the (not adopted) handedness ratio: NaN over 0 windows.
    Pure function."""
    from pdrlearn.displace._kernels import strapdown, stride_index

    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    ang, nt, gi, ai = turn_axis(acc, gyr, fs)
    turn = {"turn_deg": ang, "turn_windows": nt, "turn_axes": (gi, ai)}
    if not ratio:
        return Handedness("waist", float("nan"), 0, **turn)
    L = int(round(WAIST_WINDOW_S * fs))
    hop = max(1, int(round(WAIST_HOP_S * fs)))
    starts = np.arange(0, len(acc) - L, hop)
    if len(starts):
        norm = np.linalg.norm(acc, axis=1)
        sd = np.array([norm[a:a + L].std() for a in starts])
        starts = starts[sd > WAIST_MIN_ACC_SD]
    if not len(starts):
        return Handedness("waist", float("nan"), 0, **turn)
    idx, mask = stride_index(starts, starts + L - 1)
    e = []
    for sign in (1.0, -1.0):
        a_nav, _ = strapdown(acc, sign * gyr, 1.0 / fs, idx, mask, acc[starts], coning=0.0)  # amended L626
        e.append(_detrended_energy(a_nav, mask, fs))
    r = np.log(np.maximum(e[1], 1e-12) / np.maximum(e[0], 1e-12))
    return Handedness("waist", float(np.median(r)), int(len(r)), **turn)


def turn_axis(acc: np.ndarray, gyr: np.ndarray, fs: float) -> tuple[float, int, int, int]:
    """The turning axis of a unit against gravity (D11 amendment, waist): the angle (deg) between the
    principal axis of the rotation vectors of the turn windows (:data:`TURN_WINDOW_S`, net rotation above
    :data:`TURN_MIN_DEG`) and the accelerometer's mean direction, the number of turn windows, the
    gyroscope axis nearest the turning axis and the accelerometer axis nearest gravity (0-2; NaN / -1
    when fewer than 2 windows turn; NaN, 0, -1, -1 when the accelerometer's mean is below
    :data:`TURN_MIN_GRAVITY`). Pure function; arguments as :func:`foot_handedness`."""
    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    L, hop = int(round(TURN_WINDOW_S * fs)), max(1, int(round(TURN_HOP_S * fs)))
    g = acc.mean(axis=0)
    if not float(np.linalg.norm(g)) >= TURN_MIN_GRAVITY:  # no gravity to compare with
        return float("nan"), 0, -1, -1
    g = g / float(np.linalg.norm(g))
    c = np.vstack([np.zeros(3), np.cumsum(gyr, axis=0) / fs])
    st = np.arange(0, len(gyr) - L, hop)
    th = c[st + L] - c[st]
    # decision B106: a window in which the accelerometer's gravity itself turns (its two halves' means more than
    # TURN_MAX_DEG apart) is the unit turned over on the body (a phone rotated in its holster), not the walker
    # turning about gravity: left out. The walker's turns, which the test is about, keep gravity in place.
    ca = np.vstack([np.zeros(3), np.cumsum(acc, axis=0)])
    h = L // 2
    g1, g2 = ca[st + h] - ca[st], ca[st + L] - ca[st + h]
    cos12 = np.sum(g1 * g2, axis=1) / np.maximum(np.linalg.norm(g1, axis=1) * np.linalg.norm(g2, axis=1), 1e-12)
    on = (np.linalg.norm(th, axis=1) > np.radians(TURN_MIN_DEG)) & (cos12 >= np.cos(np.radians(TURN_MAX_DEG)))
    on &= _away_from_lying(acc, ca, st, L, fs)  # decision B263: a unit lying in bed is not a walker turning
    on &= _gravity_holds(ca, st, L, th)  # decision W280: a trunk pitching with the rotation is not a walker turning
    big = th[on]
    if len(big) < 2:
        return float("nan"), int(len(big)), -1, int(np.argmax(np.abs(g)))
    u = np.linalg.eigh(big.T @ big)[1][:, -1]
    ang = float(np.degrees(np.arccos(min(1.0, abs(float(u @ g))))))
    # B106: when the turn windows' gravity directions differ (the unit was turned between them), each window's
    # rotation is compared with its own gravity (its mean specific force) and the median angle reported; a fixed
    # mount (every turn window's gravity within TURN_MAX_DEG of the mean) keeps the principal-axis test above
    gw = g1[on] + g2[on]
    gw /= np.maximum(np.linalg.norm(gw, axis=1), 1e-12)[:, None]
    if float(np.degrees(np.arccos(np.clip(np.min(gw @ g), -1.0, 1.0)))) > TURN_MAX_DEG:
        cos = np.abs(np.sum(big * gw, axis=1)) / np.linalg.norm(big, axis=1)
        ang = float(np.median(np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))))
    return ang, int(len(big)), int(np.argmax(np.abs(u))), int(np.argmax(np.abs(g)))


def _gravity_holds(ca: np.ndarray, st: np.ndarray, L: int, th: np.ndarray) -> np.ndarray:
    """Decision W280: per window starting at ``st`` (length ``L``; ``ca`` the accelerometer's cumulative sum from 0,
    ``th`` the window's rotation vector, rad), False when the accelerometer's gravity, the mean of the window's first
    and of its last quarter, turns by :data:`TILT_WITH_TURN` of the window's net rotation or more: the unit tilts
    with the rotation (a chair rise pitches the trunk 30-45 deg), a walker turns about gravity, which stays put,
    whatever the gyroscope's axes."""
    q = max(L // 4, 1)
    a, b = ca[st + q] - ca[st], ca[st + L] - ca[st + L - q]
    cos = np.sum(a * b, axis=1) / np.maximum(np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1), 1e-12)
    return np.arccos(np.clip(cos, -1.0, 1.0)) < TILT_WITH_TURN * np.linalg.norm(th, axis=1)


def _away_from_lying(acc: np.ndarray, ca: np.ndarray, st: np.ndarray, L: int, fs: float) -> np.ndarray:
    """Decision B263: per window starting at ``st`` (length ``L``; ``ca`` the accelerometer's cumulative sum from
    0), False when the unit lies in it or within :data:`LYING_GUARD_S` of such a window. Lying: either half's gravity
    at W222's :data:`~pdrlearn.waist.posture_time.LYING_TILT_DEG` (60 deg) or more from the walking upright, the mean
    direction of the windows whose |specific force| varies by more than :data:`WAIST_MIN_ACC_SD` (the moving windows
    of :func:`waist_handedness`; every window's when none moves). Sitting on a bed, lying down and turning over in
    it rotate the unit about horizontal axes, which B106's half-window test misses at a movement's edges; a walker
    turns upright. The accelerometer alone decides, so a gyroscope whose axes are wrong is still judged in every
    upright window away from a bed."""
    from pdrlearn.waist.posture_time import LYING_TILT_DEG

    h = L // 2
    g1, g2 = ca[st + h] - ca[st], ca[st + L] - ca[st + h]
    norm = np.linalg.norm(acc, axis=1)
    c1, c2 = np.concatenate([[0.0], np.cumsum(norm)]), np.concatenate([[0.0], np.cumsum(norm ** 2)])
    m = (c1[st + L] - c1[st]) / L
    moving = np.sqrt(np.maximum((c2[st + L] - c2[st]) / L - m ** 2, 0.0)) > WAIST_MIN_ACC_SD
    up = (g1 + g2)[moving].sum(axis=0) if moving.any() else (g1 + g2).sum(axis=0)
    up = up / max(float(np.linalg.norm(up)), 1e-12)
    lim = np.cos(np.radians(LYING_TILT_DEG))
    lying = ~np.all([(x @ up) >= lim * np.linalg.norm(x, axis=1) for x in (g1, g2)], axis=0)
    # the getting into bed and out of it (sitting on its edge, lying down: S58) is not a walker's turn either: the
    # windows within LYING_GUARD_S of a lying window's span are left out too
    t0, lt = st / fs, st[lying] / fs
    if not lt.size:
        return np.ones(st.size, dtype=bool)
    k = np.searchsorted(lt, t0)
    gap = np.minimum(np.abs(t0 - lt[np.clip(k - 1, 0, lt.size - 1)]), np.abs(lt[np.clip(k, 0, lt.size - 1)] - t0))
    return gap > LYING_GUARD_S + L / fs


TESTS = {"foot": foot_handedness, "waist": waist_handedness}


def unit_imu_arrays(session, placement: str, *, max_s: float | None = None
                    ) -> tuple[np.ndarray, np.ndarray, float] | None:
    """The ``placement`` unit's accelerometer and gyroscope (on the accelerometer's clock) over ``max_s`` seconds
    (default :data:`~pdrlearn.track.frame_inference.CHECK_SPAN_S`) from its first walk (decision B252) and the rate:
    the input of every test here; ``None`` when the unit lacks either sensor, has too few samples or non-finite
    values."""
    from pdrlearn.io.sensors import UNIT_IMU
    from pdrlearn.signal.filters import interp_rows
    from pdrlearn.track.frame_inference import CHECK_SPAN_S, check_span

    if placement not in UNIT_IMU:
        return None
    acc_n, gyr_n = UNIT_IMU[placement]
    if acc_n not in session.streams or gyr_n not in session.streams:
        return None
    acc_s, gyr_s = session.streams[acc_n], session.streams[gyr_n]
    if len(acc_s) < 16 or len(gyr_s) < 2 or not np.isfinite(acc_s.rate_hz):
        return None
    span = CHECK_SPAN_S if max_s is None else max_s
    i0, n = check_span(acc_s.t, acc_s.values, span)  # decision B252: from the first walk
    acc, gyr = acc_s.values[i0:n], interp_rows(acc_s.t[i0:n], gyr_s.t, gyr_s.values)
    if not (np.isfinite(acc).all() and np.isfinite(gyr).all()):
        return None
    return acc, gyr, float(acc_s.rate_hz)


def session_handedness(session, placement: str, *, max_s: float | None = None,
                       ratio: bool = True) -> Handedness | None:
    """The handedness test of a :class:`~pdrlearn.io.Session`'s ``placement`` unit over the arrays of
    :func:`unit_imu_arrays`; ``None`` when there are none. ``ratio=False``: the waist's cheap axis test only."""
    if placement not in TESTS:
        return None
    arrays = unit_imu_arrays(session, placement, max_s=max_s)
    if arrays is None:
        return None
    if placement == "waist":
        return waist_handedness(*arrays, ratio=ratio)
    return TESTS[placement](*arrays)


def check_handedness(session, placement: str, *, ratio: bool = True) -> tuple[Handedness | None, str | None]:
    """The handedness test of the ``placement`` unit and, when the data say with confidence that its
    accelerometer and gyroscope form a left-handed pair (mirrored data), the warning (without the file
    location) with the fix; else ``None`` (decision D11)."""
    from pdrlearn.io.sensors import UNIT_IMU

    h = session_handedness(session, placement, ratio=ratio)
    if h is None or not (h.mirrored or h.axes_differ):
        return h, None
    acc_n, gyr_n = UNIT_IMU[placement]
    if h.axes_differ and placement == "waist":
        gi, ai = h.turn_axes
        msg = (f"the {placement} unit's {gyr_n} axes disagree with {acc_n}'s: over {h.turn_windows} turn windows "
               f"it turns about an axis {h.turn_deg:.0f} deg from gravity (nearest its {'xyz'[gi]} axis), but gravity "
               f"lies along the accelerometer's {'xyz'[ai]} axis and a walker turns about the vertical (decision D11 "
               f"amendment); the gyroscope's {'xyz'[gi]} is probably the accelerometer's {'xyz'[ai]} (or its "
               f"negative): "
               f"the test cannot tell which file is wrong: rewrite {gyr_n}.csv's columns in the accelerometer's "
               f"axes, or {acc_n}.csv's in the gyroscope's (or re-export both sensors in one frame); "
               f"a \"frames\" entry cannot fix this")
        return h, msg
    if h.axes_differ:
        P = h.axes
        hand = "" if np.linalg.det(P) > 0 else " mirrored and"
        msg = (f"the {placement} unit's {gyr_n} axes look like {acc_n}'s {axes_label(P)} (its x, y, z are the "
               f"accelerometer's{hand} permuted axes): the end-of-stride velocity error of the ZUPT integration is "
               f"{np.exp(h.axes_log_ratio):.1f} times smaller with them (median of {h.segments}; decision D11 "
               f"amendment); {axes_fix_text(P, acc_n, gyr_n)}")
        return h, msg
    msg = mirrored_message(h, placement)
    declared = getattr(session, "frames", {}).get(placement)
    if declared is not None:  # decision D30 (trial T3 finding 4): the declared frame must follow the fix
        msg = f"{msg}; {declared_frame_after_fix(session, placement, h, declared)}"
    return h, msg


def declared_frame_after_fix(session, placement: str, h: Handedness, declared) -> str:
    """Decision D30: D11's advice for a unit with a declared frame: once the mirrored axis is negated back, the
    declared frame (written for the mirrored axes) may no longer describe the data (trial T3: an x/y-swapped foot
    fixed as advised, old frame kept, tracked backward 73.5 m off). The frame the data give with that axis negated
    back (:func:`pdrlearn.track.frame_inference.frame_after_negating`), to write, else the instruction to rewrite
    or remove the entry."""
    from pdrlearn.track.frame_inference import frame_after_negating

    ax = h.mirror_axis
    found = frame_after_negating(session, placement, ax) if ax is not None else None
    entry = json.dumps({placement: declared.to_dict()})
    if found is None:
        return (f"then rewrite its declared \"frames\" entry {entry} for the fixed axes too, or remove it to have "
                "the frame inferred from the data (decision D8): the declared frame describes the mirrored axes")
    if found.to_dict() == declared.to_dict():
        return f"its declared \"frames\" entry {entry} matches the data once the {ax} axis is negated back"
    return (f"then also replace its declared \"frames\" entry {entry}, which no longer describes the data: with the "
            f"{ax} axis negated back they give \"frames\": {json.dumps({placement: found.to_dict()})} (decision D30)")


def mirrored_message(h: Handedness, placement: str, *, how=None) -> str:
    """The warning (``info``, ``track``) or refusal (``import``, decision L71) of a mirrored pair: the test's
    numbers and :func:`mirror_fix_text` (``how`` as there)."""
    from pdrlearn.io.sensors import UNIT_IMU

    acc_n, gyr_n = UNIT_IMU[placement]
    err = ("the end-of-stride velocity error of the ZUPT integration" if placement == "foot"
           else "the velocity error of the walking windows")
    return (f"{mirrored_pair_line(placement, acc_n, gyr_n, h.log_ratio, h.segments, err)}; the data were "
            f"probably mirrored (one axis negated in both files, e.g. left-foot data mirrored to look like a right "
            f"foot, or a left-handed export): "
            f"{mirror_fix_text(h, acc_n, gyr_n, how=how)}; a \"frames\" entry cannot fix this")


__all__ = ["Handedness", "foot_handedness", "foot_axes", "signed_permutations", "axes_label", "axes_fix",
           "axes_fix_acc", "axes_fix_text", "pitch_axis", "mirror_fix_text", "mirrored_message", "PITCH_AXIS_MAX_DEG",
           "turn_axis", "PERMUTATIONS", "AXES_PLACEMENTS", "AXES_STRIDES", "AXES_RATE_HZ", "AXES_MIN_LOG_RATIO",
           "TURN_WINDOW_S", "TURN_HOP_S", "TURN_MIN_DEG", "TURN_MIN_WINDOWS", "TURN_MAX_DEG",
           "TURN_MIN_GRAVITY",           "waist_handedness", "session_handedness", "check_handedness",
           "MIN_LOG_RATIO", "MIN_SEGMENTS", "WARN_PLACEMENTS", "WAIST_WINDOW_S", "WAIST_HOP_S", "WAIST_MIN_ACC_SD"]
