"""Stride-local displacement, PLASYS rules and position update, numpy only (thesis ch.7.2).

The one kernel behind both the streaming runtime (:class:`pdrlearn.runtime.tracker.Tracker`) and the
streamable variant of the ``plasys`` pipeline (``pdrlearn track --streaming``), so that a streamed
trajectory equals the offline one (issue 7, decision E6 in docs/decisions/export.md):

- :class:`StanceSegmenter` - online step detection on the foot gyroscope, stance to stance (decision E7),
  the stance threshold relative to the walker's own stance rotation (decision L27 in
  docs/decisions/localization.md; :func:`stance_floor`/:func:`stance_gyro_threshold` are the offline side);
- :func:`stride_motion` - the stride's foot signals levelled by :func:`pdrlearn.kernels.window.levelled_units`
  (the step-window construction, at the unit's own rate) integrated twice with a zero-velocity update
  at both stances, and the stride's heading change;
- :func:`apply_stride_rules` - the M3 rules (terrain -> distance, direction -> sign, length class ->
  clamp, stairs -> altitude change; thesis ch.7.2.2) on per-stride displacements;
- :func:`advance` - heading and ENU position after a stride.

Units: s, m, rad, m/s^2, rad/s.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Mapping

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels import bayes as B
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels.backward import on_the_spot
from pdrlearn.kernels.contact import MAX_STRIDE_S
from pdrlearn.kernels.histospline import upsample_block_means
from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S, rest_rotation
from pdrlearn.kernels.stop_bias import vertical_rate
from pdrlearn.kernels.turn_length import STRAIGHT_MAX_RAD
from pdrlearn.kernels.window import BRIDGE_GAP_S, TIE_S, Levelled, foot_levelled, interp, resample, segment

# -- length-class bounds -------------------------------------------------------------------------------
#: Decision L59 (docs/decisions/localization.md): the ``length_bounds_source`` an export wrote before L59 when
#: the model had no bounds of its own, beside the thesis step bounds x 2 (ch.6.3) stored as if they were the
#: user's. L50: those bounds clamp a typical 1.3 m stride to 0.90 / 0.60 m, so the runtime reads a bundle with
#: this source as one without bounds, as a bundle exported since (``length_bounds_source`` "none").
THESIS_FALLBACK_SOURCE = "thesis ch.6.3 step bounds x 2 (stride)"
#: the bounds those exports wrote (thesis ch.6.3 step bounds x 2 per stride; ch.7.2.2: long from 0.46 m per
#: step); an export before the source field (commit 8e1520d) wrote them into every bundle, with no source
THESIS_FALLBACK_BOUNDS = {"short": (0.0, 0.60), "normal": (0.60, 0.90), "long": (0.92, 20.0)}
#: the ``length_bounds_source`` of a bundle exported since L59 from a model without bounds
NO_BOUNDS_SOURCE = "none"


def pre_l59_fallback(displacement: Mapping) -> bool:
    """Decision L59: a bundle's ``displacement`` holds the thesis fallback an export before L59 stored as the
    user's bounds: its ``length_bounds_source`` says so, or (exported before that field) it has no source and
    exactly those bounds."""
    b, src = displacement.get("length_bounds_m"), displacement.get("length_bounds_source")
    if b is None:
        return False
    if src is not None:
        return src == THESIS_FALLBACK_SOURCE
    try:
        return {str(k): (float(v[0]), float(v[1])) for k, v in b.items()} == THESIS_FALLBACK_BOUNDS
    except (AttributeError, TypeError, ValueError, IndexError):
        return False


def no_length_bounds_warning(subject: str = "the model", effect: str = "") -> str:
    """Decision L59: the one line ``pdrlearn track`` (offline and ``--streaming``), ``pdrlearn export`` and the
    runtime print when a model / bundle that classifies stride length has no length-class bounds: the length
    rule (thesis clamp or bayes weighing, L14) is skipped and each stride keeps its measured length; the fix."""
    effect = effect or ("the length rule is skipped (each stride keeps its measured length; the thesis step "
                        "bounds x 2 would clamp typical strides, L50)")
    return (f"{subject} carries no length-class bounds (length_bounds_m): {effect}; train with the user's "
            "lengths (length_m labels on the length exercise, or the calibration walk's meta.json "
            "length_class_bounds_m) or give --length-bounds SHORT_NORMAL,NORMAL_LONG (track, export)")


# -- stride detection ---------------------------------------------------------------------------------
#: Decision L27 (docs/decisions/localization.md): the stance threshold follows the walker's own stance
#: rotation. ``stance_floor_factor`` x the floor (the lowest ``min_stance_s`` mean of |w| within
#: ``stance_floor_window_s``), never below the fixed threshold, never above ``stance_gyro_max_rad_s``;
#: factor 0 = the fixed threshold alone (decision E7). ``stance_gap_s``: a stance survives shorter runs of
#: samples above the threshold (one-sample spikes split the 0.12-0.19 s foot-flats of the MS recording).
#: Decision L29: ``stance_mean_min_s`` > 0 also counts a sample as still when the ``min_stance_s`` mean of
#: |w| centred on it is below the threshold (the offline rule of ``inertial_stance``), and a stance then
#: needs to last ``stance_mean_min_s`` (not ``min_stance_s``); 0 = L27 alone. Decision L120: a stance also
#: survives motion shorter than ``stance_gap_swing_frac`` x the swing before it (the motion from the previous
#: stance's end to its start), at most ``stance_gap_max_s``: a slow walker's terminal swing passes under the
#: threshold for ~0.1 s before the heel strike, and the heel rocker after it (0.2-0.3 s) must not end that stance
#: (offline drops a swing under 0.2 s, ``track.plasys.stance_strides``); 0 (the default) = the fixed
#: ``stance_gap_s`` alone.
STANCE_L27_DEFAULTS = {"stance_floor_factor": 2.0, "stance_floor_window_s": 1.0, "stance_gyro_max_rad_s": 2.0,
                       "stance_gap_s": 0.03, "stance_mean_min_s": 0.07,
                       "stance_gap_swing_frac": 0.0, "stance_gap_max_s": 0.5}
#: decision L120's option (not adopted as the default: its rule failed on the 0.1 m/s walks): give
#: ``{"stance_gap_swing_frac": STANCE_GAP_SWING_FRAC_OPTION}`` (bundle ``displacement``, ``track --streaming --params``)
STANCE_GAP_SWING_FRAC_OPTION = 0.35
#: Offline's stance runs closer than this (s) are one stance (``displace.foot.stance_runs``; L27 notes it): decision
#: L667's cap of L120's gap in :data:`STANCE_SIDE_STEP_OPTION`
STANCE_MERGE_S = 0.1
#: decision L667's option (measured, not adopted: a real instep walk's streamed distance moved 1.28 %, over its
#: rule's 1 %): L120's swing-relative gap capped at offline's merge, which keeps a side step's landing (a still
#: terminal swing, the impact, the foot-flat) in one stance; give it as ``track --streaming --params`` or a bundle's
#: ``displacement``
STANCE_SIDE_STEP_OPTION = {"stance_gap_swing_frac": STANCE_GAP_SWING_FRAC_OPTION, "stance_gap_max_s": STANCE_MERGE_S}


def stance_gyro_threshold(floor: np.ndarray | float, base: float, *, factor: float = 2.0,
                          cap: float = 2.0) -> np.ndarray:
    """Decision L27: the stance gyro threshold (rad/s) from the stance floor (rad/s, the lowest short-time
    mean of |w| around the sample): ``factor`` x floor, within ``base`` (the fixed threshold) .. ``cap``.
    A non-finite floor (no sample to estimate it) gives ``base``."""
    f = np.asarray(floor, dtype=float)
    return np.minimum(np.maximum(factor * np.where(np.isfinite(f), f, 0.0), base), max(cap, base))


def stance_floor(w: np.ndarray, fs: float, *, mean_s: float, window_s: float) -> np.ndarray:
    """Offline (centred) stance floor (rad/s) of a whole recording of |w| ``(n,)`` at ``fs`` Hz (decision
    L27): the mean of |w| over ``mean_s`` around each sample, its minimum within ``window_s`` around it.
    The streaming :class:`StanceSegmenter` uses the trailing window."""
    from scipy.ndimage import minimum_filter1d, uniform_filter1d

    w = np.asarray(w, dtype=float)
    if not len(w):
        return np.zeros(0)
    m = uniform_filter1d(w, max(1, int(round(mean_s * fs))), mode="nearest")
    return minimum_filter1d(m, max(1, int(round(window_s * fs))), mode="nearest")


def _param_number(key: str, value) -> float:
    """Decision B459 (review R2): a segmenter parameter (a bundle's or ``track --streaming --params``') as a float,
    or a one-line :class:`DataError` naming the key: not a number, or not finite."""
    try:
        x = float(value) if not isinstance(value, bool) else math.nan
    except (TypeError, ValueError):
        x = math.nan
    if not math.isfinite(x):
        raise DataError(f"StanceSegmenter: parameter {key} = {value!r} is not a finite number; give it as a number "
                        "(in the --params JSON file, or the bundle's displacement parameters)")
    return x


class StanceSegmenter:
    """Online stance-to-stance stride detection on the foot gyroscope (decisions E7, L27, L29).

    A stance is a run of samples with ``|w|`` below the stance threshold lasting ``min_stance_s``. The
    threshold is ``stance_gyro_rad_s``, raised to ``stance_floor_factor`` x the walker's stance floor (the
    lowest ``min_stance_s`` mean of |w| in the last ``stance_floor_window_s``) when the foot never quite
    rests (a rolling instep mount, short foot-flats), at most ``stance_gyro_max_rad_s`` (decision L27).
    Decision L29 (``stance_mean_min_s`` > 0): a sample is also still when the ``min_stance_s`` mean of |w|
    centred on it is below the threshold (the offline stance test), and a run of still samples is a stance
    when it lasts ``stance_mean_min_s``; samples are then judged half a mean window late (~0.05 s).
    Its boundary is its middle, but at most ``stance_half_s`` from its start (closing the stride before)
    and from its end (opening the next), so standing still neither delays a stride nor stretches it.
    Strides lasting ``min_step_s``..``max_step_s`` are returned by :meth:`update` as ``(start_s, end_s)``.
    Decision L684 (L597's rule, shared with the offline rest through
    :func:`pdrlearn.kernels.foot_rhythm.min_rest_s`): where L597's rule finds the foot's own stride period slow (0.06 x
    the period asks more than the minimum run), a stance must also last ``stance_rhythm_frac`` x the period (a slow
    swing's lull before the heel strike is not a stance); the period is read when a stance starts, from the last
    :data:`~pdrlearn.kernels.foot_rhythm.TRAILING_WINDOW_S` of the |w| means (0: no such rule; the default 0.1
    since L696). Decision L696: the means are the walk's - a standing stance's samples (after it closed its stride
    early) join them only while no stride was returned in that window (a stand between walking bouts would make the
    bouts' repetition read as the period; a stand before the walk gives its first seconds their span); L697 / L698:
    the period is the first autocorrelation peak near the highest, read after the last foot gap (L715's candidate, not
    adopted: after the foot's own last gap, :attr:`foot_gap_end`, not the hole a stand leaves in the means).
    """

    def __init__(self, *, stance_gyro_rad_s: float = 0.8, min_stance_s: float = 0.1, stance_half_s: float = 0.3,
                 min_step_s: float = 0.3, max_step_s: float = 3.0,
                 stance_floor_factor: float = STANCE_L27_DEFAULTS["stance_floor_factor"],
                 stance_floor_window_s: float = STANCE_L27_DEFAULTS["stance_floor_window_s"],
                 stance_gyro_max_rad_s: float = STANCE_L27_DEFAULTS["stance_gyro_max_rad_s"],
                 stance_gap_s: float = STANCE_L27_DEFAULTS["stance_gap_s"],
                 stance_mean_min_s: float = STANCE_L27_DEFAULTS["stance_mean_min_s"],
                 stance_gap_swing_frac: float = STANCE_L27_DEFAULTS["stance_gap_swing_frac"],
                 stance_gap_max_s: float = STANCE_L27_DEFAULTS["stance_gap_max_s"],
                 stance_rhythm_frac: float = FR.STREAMED_RHYTHM_FRAC, foot_gap_cut: bool = False,
                 lull_join: bool = False):
        self.thr = float(stance_gyro_rad_s)
        #: decision E345 (an option, not adopted by E347's rule): True (``{"stance_lull_join": 1}``) makes the callers
        #: (``track --streaming``, the runtime) join two strides cut at a swing lull (:mod:`pdrlearn.kernels.lull`)
        self.lull_join = bool(lull_join)
        self.foot_gap_cut = bool(foot_gap_cut)  # decision L715 (not adopted): the rhythm cut at the foot's own gap
        self.min_stance_s = float(min_stance_s)
        self.half = float(stance_half_s)
        self.min_step_s, self.max_step_s = float(min_step_s), float(max_step_s)
        self.factor = float(stance_floor_factor)
        self.floor_window_s = float(stance_floor_window_s)
        self.cap = max(float(stance_gyro_max_rad_s), self.thr)
        self.gap = float(stance_gap_s)
        self.mean_min = float(stance_mean_min_s)
        self.swing_frac, self.gap_max = float(stance_gap_swing_frac), float(stance_gap_max_s)
        if not (self.swing_frac >= 0 and self.gap_max >= 0):
            raise DataError(f"StanceSegmenter: stance_gap_swing_frac {stance_gap_swing_frac!r} and stance_gap_max_s "
                            f"{stance_gap_max_s!r} must be >= 0 (decision L120; 0 = the fixed stance_gap_s)")
        if not (self.factor >= 0 and self.floor_window_s > 0 and self.gap >= 0 and self.mean_min >= 0):
            raise DataError(f"StanceSegmenter: stance_floor_factor {stance_floor_factor!r}, stance_gap_s "
                            f"{stance_gap_s!r} and stance_mean_min_s {stance_mean_min_s!r} must be >= 0, "
                            f"stance_floor_window_s {stance_floor_window_s!r} > 0 (decisions L27, L29; all "
                            "three 0 = the fixed rule E7)")
        self.rhythm_frac = float(stance_rhythm_frac)
        if not 0 <= self.rhythm_frac < 1:  # decision B459: a stance lasting the whole stride period is no stride
            raise DataError(f"StanceSegmenter: stance_rhythm_frac {stance_rhythm_frac!r} must be >= 0 and under 1, "
                            "the fraction of the foot's stride period a stance must last (decision L684; 0 = no "
                            "rhythm rule, the default 0.1; B459)")
        # decision L684: trailing (t, |w| mean) to read the foot's period (L695: in a numpy buffer)
        self._rhythm = FR.TrailingSeries(FR.TRAILING_WINDOW_S, TIE_S)
        self.rest_s = 0.0  # decision L684: the rhythm's shortest stance (s), read when the stance in progress started
        self.stance_start: float | None = None
        self.last_still = -np.inf
        self.closed = False
        self.open_s: float | None = None  # start (s) of the stride in progress
        self.last_boundary: float | None = None
        self.walked_s = -np.inf  # decision L696: the end (s) of the last stride returned
        self.last_t = -np.inf  # decision L715: the last sample's time (s)
        self.foot_gap_end = -np.inf  # decision L715: the first sample (s) after the foot's last gap over 0.5 s
        self.prev_stance_end: float | None = None  # decision L120: the last stance's last still sample (s)
        self.moved = False  # decision L120: a sample since the last still one was not still
        self.run_start = -np.inf  # decision L120: the start (s) of the stance's current still run
        self.best_run: tuple[float, float] | None = None  # and its longest earlier run
        # decision L27: trailing min_stance_s window of [t, |w|, threshold] (running sum of |w|) and the
        # trailing minimum of its mean (monotonic deque)
        self._mean_q: deque = deque()
        self._mean_sum = 0.0
        self._min_q: deque = deque()

    @classmethod
    def from_params(cls, params: Mapping) -> StanceSegmenter:
        """From a bundle's ``displacement`` parameters (unknown keys ignored; decision B459: a value that is not a
        finite number refused in one line naming its key)."""
        keys = ("stance_gyro_rad_s", "min_stance_s", "stance_half_s", "min_step_s", "max_step_s",
                "stance_rhythm_frac", *STANCE_L27_DEFAULTS)  # L684; L120: stance_gap_swing_frac, stance_gap_max_s
        kw = {k: _param_number(k, params[k]) for k in keys if k in params}
        if "stance_lull_join" in params:  # decision E345's switch: true / false or 1 / 0
            v = params["stance_lull_join"]
            kw["lull_join"] = bool(v) if isinstance(v, bool) else _param_number("stance_lull_join", v) != 0
        return cls(**kw)

    def _gap_now(self) -> float:
        """Decision L120: the motion (s) the stance in progress survives: ``stance_gap_s``, or
        ``stance_gap_swing_frac`` x the swing before it (previous stance's end to this one's start) when
        longer, at most ``stance_gap_max_s``, while the stance has not closed the stride (a stance lasting
        2 ``stance_half_s`` closes it early: a slow walker's foot-flat; the swing after it may dip under the
        threshold and must end it) and none of its still runs has lasted ``stance_half_s`` (a foot-flat: an
        instep mount's fragmented stances must end on the fixed gap, or swing dips chain strides together)."""
        if self.prev_stance_end is None or self.stance_start is None or self.closed:
            return self.gap  # a stance that closed its stride (a long foot-flat) ends on the fixed gap
        s0, s1 = self._stance_run()
        if s1 - s0 >= self.half - TIE_S:  # a still run of stance_half_s is a foot-flat, no terminal-swing moment
            return self.gap
        swing = self.stance_start - self.prev_stance_end
        return max(self.gap, min(self.swing_frac * swing, self.gap_max))

    def _push(self, ti: float, wi: float) -> tuple[float, float]:
        """Add one sample to the trailing window; its mean of |w| and the sample's stance threshold (decision
        L27: trailing floor; state carried across calls, so nothing depends on how the stream is chunked)."""
        if ti - self.last_t > FR.PERIOD_RANGE_S[0]:  # L715's candidate: a hole in the foot's own samples (L698's 0.5 s)
            self.foot_gap_end = ti
        self.last_t = ti
        mq = self._mean_q
        mq.append([ti, wi, self.thr])
        self._mean_sum += wi
        while mq[0][0] <= ti - self.min_stance_s + TIE_S:
            self._mean_sum -= mq.popleft()[1]
        m = self._mean_sum / len(mq)
        if self.rhythm_frac > 0 and not self._standing_in_walk(ti):  # L684: the means the period is read from
            self._rhythm.append(ti, m)
        if self.factor == 0:
            return m, self.thr
        nq = self._min_q
        while nq and nq[-1][1] >= m:
            nq.pop()
        nq.append((ti, m))
        while nq[0][0] <= ti - self.floor_window_s + TIE_S:
            nq.popleft()
        th = min(max(self.factor * nq[0][1], self.thr), self.cap)
        mq[-1][2] = th
        return m, th

    def _standing_in_walk(self, ti: float) -> bool:
        """Decision L696: the stance in progress has closed its stride early (standing) and a stride was returned in
        the last ``TRAILING_WINDOW_S``: its samples stay out of the rhythm's means."""
        return self.stance_start is not None and self.closed and ti - self.walked_s <= FR.TRAILING_WINDOW_S

    def _thresholds(self, t: list[float], w: list[float]) -> list[float]:
        """Decision L27: the stance threshold at each new sample (advances the state)."""
        return [self._push(ti, wi)[1] for ti, wi in zip(t, w, strict=True)]

    def update(self, t: np.ndarray, gyr: np.ndarray) -> list[tuple[float, float]]:
        """Feed new foot-gyroscope samples ``t (n,)`` s, ``gyr (n, 3)`` rad/s; return the strides they close."""
        gyr = np.asarray(gyr, dtype=np.float64)  # |w| = np.linalg.norm(gyr, axis=1)'s own arithmetic without its
        w = np.sqrt(np.add.reduce(gyr * gyr, axis=1)).tolist()  # Python wrapper (~1 us per push, decision E16)
        return self.update_norms(np.asarray(t, dtype=np.float64).tolist(), w)

    def update_norms(self, tl: list[float], w: list[float]) -> list[tuple[float, float]]:
        """:meth:`update` with the samples' times (s) and |w| (rad/s) given as Python floats (the runtime's
        push-time levelling has |w| already: decision E17). ``math.sqrt(x*x + y*y + z*z)`` is the same
        arithmetic as :meth:`update`'s ``np.linalg.norm`` ufuncs (left to right, one correctly rounded
        square root), so both entries give the same strides."""
        out: list[tuple[float, float]] = []
        if not math.isfinite(sum(w)):  # a NaN would stay in the L27 running sum: no stance for the rest of the stream
            raise DataError("StanceSegmenter: foot gyroscope samples contain NaN/inf; drop those samples first")
        mean_rule = self.mean_min > 0
        min_run = self.mean_min if mean_rule else self.min_stance_s
        mq = self._mean_q
        for tn, wn in zip(tl, w, strict=True):
            m, th = self._push(tn, wn)
            if mean_rule:  # L29: judge the sample at the window's centre (its older middle: E7 dates kept)
                ti, wi, thi = mq[(len(mq) - 1) // 2]
                still = wi < thi or m < thi  # L32: the centred mean against the centre's threshold (offline)
            else:
                ti, still = tn, wn < th
            if still:
                if self.stance_start is None:
                    self.stance_start, self.run_start, self.best_run, self.closed = ti, ti, None, False
                    self.rest_s = self._rhythm_rest(min_run)
                elif self.swing_frac > 0 and self.moved and ti - self.last_still > self.gap + TIE_S:
                    self._keep_run()  # L120: a new still run after motion only L120's gap bridged
                    self.run_start = ti
                self.last_still, self.moved = ti, False
                if not self.closed and ti - self.run_start >= max(2 * self.half, min_run) - TIE_S:
                    self._close(self.run_start + self.half, out)  # long stance: close the stride now
                continue
            self.moved = True
            if self.stance_start is not None and ti - self.last_still > self._gap_now() + TIE_S:  # L27, L120
                s0, s1 = self._stance_run()
                if s1 - s0 >= max(min_run, self.rest_s) - TIE_S:  # L684: and the rhythm's shortest stance
                    mid = 0.5 * (s0 + s1)
                    if not self.closed:
                        self._close(mid, out)
                    self.open_s = max(mid, s1 - self.half)
                    self.prev_stance_end = self.last_still
                self.stance_start = None
        return out

    def closing_stride(self) -> tuple[float, float] | None:
        """The stride ``(start_s, end_s)`` that :meth:`update` is likely to return for the next sample it
        judges (read-only; the runtime computes that stride ahead, decision E24), or None.

        A stance in progress ends when a judged sample is not still (``ti - last_still > stance_gap_s``; at
        20 Hz the first sample judged after the stance, 0.05 s > 0.03 s), closing the stride at the stance's
        middle, exactly :meth:`update`'s ``0.5 * (s0 + s1)``; a stance that reaches ``2 stance_half_s``
        closes it at ``s0 + stance_half_s`` while still (standing). With the L29 mean rule a sample is judged
        at the centre of the trailing window, and one whose own |w| is below its threshold is still whatever
        comes after it; so: the early close when the next sample to judge is still for certain and old enough,
        None when it is still for certain otherwise or within ``stance_gap_s`` of the last still sample (at
        204.8 Hz the 6 samples after a stance), else the middle. None also when no stride would close (no
        stance of the minimum length, already closed, no stride open, out of ``min_step_s``..``max_step_s``).
        The sample judged next is taken to be the one after the last centre; irregular clocks may judge
        another first: a likely stride, never a certain one."""
        start = self.open_s
        if self.stance_start is None or start is None or self.closed:
            return None
        s0, s1 = self._stance_run()
        mean_rule = self.mean_min > 0
        min_run = self.mean_min if mean_rule else self.min_stance_s
        mq = self._mean_q
        if mean_rule and len(mq) > (len(mq) - 1) // 2 + 1:
            # the sample judged next: usually the one after the last centre (with a steady clock)
            tn, wn, thn = mq[(len(mq) - 1) // 2 + 1]
            if wn < thn:  # still for certain: no stance ends there, but a long one may close early
                if tn - self.run_start < max(2 * self.half, min_run) - TIE_S:
                    return None
                end = self.run_start + self.half  # update's long-stance close
                return (start, end) if self._step_ok(end - start) else None
            if tn - self.last_still <= self._gap_now() + TIE_S:  # within the gap (L27, L120): ends no stance
                return None
        if s1 - s0 < max(min_run, self.rest_s) - TIE_S:  # L684: and the rhythm's shortest stance
            return None
        end = 0.5 * (s0 + s1)
        return (start, end) if self._step_ok(end - start) else None

    def may_open_at(self, start_s: float) -> bool:
        """Decision E345: whether a stride starting at ``start_s`` (s, the end of a returned stride) may still be
        returned: the stride in progress starts there, or the stance that ended the returned stride is still in
        progress (it sets the next start when it ends)."""
        return self.open_s == start_s or (self.open_s is None and self.last_boundary == start_s
                                          and self.stance_start is not None)

    def _rhythm_rest(self, min_run: float) -> float:
        """Decision L684: the shortest stance (s) the foot's period asks, read from the trailing |w| means:
        ``stance_rhythm_frac`` x the period where L597's rule (:func:`pdrlearn.kernels.foot_rhythm.min_rest_s` against
        the stance's own minimum run) finds it slow; 0 = none."""
        if self.rhythm_frac == 0:
            return 0.0
        t, m = self._rhythm.arrays()
        if len(t) < 3:
            return 0.0
        since = self.foot_gap_end if self.foot_gap_cut else None  # L715's candidate: the foot's own gap
        period = FR.trailing_period(t, m, since)
        return self.rhythm_frac * period if FR.min_rest_s(period, min_run) > 0 else 0.0  # where L597 acts

    def _keep_run(self) -> None:
        """Decision L120: remember the still run that just ended inside a bridged stance when it is the longest."""
        cur = (self.run_start, self.last_still)
        if self.best_run is None or cur[1] - cur[0] > self.best_run[1] - self.best_run[0]:
            self.best_run = cur

    def _stance_run(self) -> tuple[float, float]:
        """Decision L120: the still run ``(start, end)`` (s) whose middle bounds the strides - the stance's longest
        (a slow walker's foot-flat, not the terminal swing's moment under the threshold before it, nor a blip
        after a short real foot-flat); the stance's only run without L120."""
        cur = (self.run_start, self.last_still)
        best = self.best_run
        return best if best is not None and best[1] - best[0] > cur[1] - cur[0] else cur

    def _step_ok(self, duration: float) -> bool:
        return self.min_step_s - TIE_S <= duration <= self.max_step_s + TIE_S

    def _close(self, end: float, out: list) -> None:
        self.closed = True
        start, self.open_s = self.open_s, None
        self.last_boundary = end
        if start is not None and self._step_ok(end - start):
            out.append((start, end))
            self.walked_s = end


def stance_strides(t: np.ndarray, gyr: np.ndarray, params: Mapping | None = None) -> np.ndarray:
    """All strides ``(n, 2)`` (start, end s) of a whole foot-gyroscope recording, as streamed."""
    seg = StanceSegmenter.from_params(params or {})
    return np.array(seg.update(np.asarray(t, float), np.asarray(gyr, float)), dtype=float).reshape(-1, 2)


# -- stride displacement ------------------------------------------------------------------------------
def zupt_displacement(t: np.ndarray, acc: np.ndarray) -> np.ndarray:
    """Displacement (3,) m of a stance-to-stance stride from its levelled, gravity-removed acceleration.

    Trapezoidal velocity; the velocity drift is removed linearly in time so that v = 0 at both stances
    (zero-velocity update, thesis ch.7.2); trapezoidal position.
    """
    if len(t) < 2 or not t[-1] > t[0]:
        return np.zeros(3)  # no sample interval inside the stride: no measured motion
    # The velocity v_j = sum_{k<j} u_k (u_k = (a_k + a_{k+1}) dt_k / 2), less its drift s_j v_end
    # (s_j = (t_j - t_0) / T), integrated by the trapezoid rule, is linear in the u_k: the position weight of
    # u_k is sum_{j>k} w_j - T/2 = t_c - m_k (w_j the trapezoid weights, t_c the stride's middle time, m_k the
    # middle of interval k; the drift term sums to v_end T / 2 exactly). One product instead of the cumulative
    # sums (decision E17; the same displacement to rounding, within 5e-15 relative up to 615 samples).
    tr = t - t[0]  # times from the stride's start (no cancellation of large clock values)
    lo, hi = tr[:-1], tr[1:]
    # 0.5 (t_c - m_k) dt_k = (T - (lo + hi)) dt_k / 4 with T = t_end - t_0: the factors 1/2 are powers of two,
    # so moving them out is exact (E17's values bit for bit; two numpy calls less, runtime decision E20);
    # ndarray.dot: @'s BLAS product without its dispatch (E20)
    return 0.25 * ((tr[-1].item() - (lo + hi)) * (hi - lo)).dot(acc[1:] + acc[:-1])


def yaw_change(t: np.ndarray, rate_z: np.ndarray, t0: float = -np.inf, t1: float = np.inf) -> float:
    """Heading change (rad) over ``[t0, t1]`` (s): trapezoidal integral of the levelled vertical rate
    (rad/s) linearly interpolated at ``t0``/``t1``, so that consecutive strides do not share samples."""
    tt = np.minimum(np.maximum(t, t0), t1)  # clipped to [t0, t1]
    r = interp(tt, t, rate_z)
    return 0.5 * float((r[1:] + r[:-1]).dot(tt[1:] - tt[:-1]))  # trapezoid (one product, E17; .dot: E20)


def end_phase_yaw(t: np.ndarray, rate_z: np.ndarray, t0: float, t1: float, *, with_turn: bool = False):
    """Decision E336: the yaw (rad, CCW) of the stride ``[t0, t1]`` (s)'s ends over its mean yaw, ``psi = (Y(t0) +
    Y(t1)) / 2 - mean Y`` with ``Y`` the vertical rate ``rate_z`` (rad/s) integrated from ``t0`` (the trapezoid of
    :func:`yaw_change`, the mean by the trapezoid over ``[t0, t1]``). A gait cycle's mean pelvis yaw is the walking
    direction; its yaw at the cycle's ends (the foot's rest) is that plus the pelvic rotation's value at that phase
    (psi). 0 for a constant rate (a steady turn), fewer than 2 samples or ``t1 <= t0``. ``with_turn``: ``(psi,
    Y(t1))``, the stride's turn too (decision E338)."""
    if not t1 > t0 or len(t) < 2:
        return (0.0, 0.0) if with_turn else 0.0
    tt = np.minimum(np.maximum(t, t0), t1)
    r = interp(tt, t, rate_z)
    dt = tt[1:] - tt[:-1]
    y = np.concatenate(([0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * dt)))
    mean = 0.5 * float((y[1:] + y[:-1]).dot(dt)) / (float(t1) - float(t0))
    psi = 0.5 * float(y[-1]) - mean
    return (psi, float(y[-1])) if with_turn else psi


class CyclePhase:
    """Decision E338: E336's end-phase yaw read on straight strides only (the waist's turn over the stride under L79's
    :data:`~pdrlearn.kernels.turn_length.STRAIGHT_MAX_RAD`); a turning stride, whose yaw is no steady ramp where a
    curve starts or ends, takes the last straight stride's (the same gait phase), or its own before any."""

    def __init__(self) -> None:
        self.psi: float | None = None

    def stride(self, psi: float, turn: float) -> float:
        if abs(turn) < STRAIGHT_MAX_RAD:
            self.psi = psi
        return psi if self.psi is None else self.psi


def waist_phase_turn(levelled: Levelled, t0: float, t1: float) -> tuple[float, float] | None:
    """Decision E336 / E338: ``(psi, turn)`` of :func:`end_phase_yaw` on the stride's levelled waist vertical rate (the
    rate :func:`stride_motion` integrates for a waist-headed stride); None without the waist's gyroscope. Kept per
    stride by ``track --streaming``, which feeds :class:`CyclePhase` only once L611 has judged the strides (decision
    E343: a pedalling stride, which the runtime never places, sets no held phase)."""
    w = levelled.get("waist")
    if w is None or w[0] is None or w[2] is None:
        return None
    return end_phase_yaw(w[0], np.asarray(w[2], dtype=float)[:, 2], float(t0), float(t1), with_turn=True)


def waist_end_phase_yaw(levelled: Levelled, t0: float, t1: float, phase: CyclePhase | None = None) -> float:
    """Decision E336: :func:`end_phase_yaw` of the stride's levelled waist vertical rate (:func:`waist_phase_turn`);
    0 without the waist's gyroscope. ``phase`` (decision E338): the stream's :class:`CyclePhase`, which holds it over
    turning strides."""
    return held_phase_yaw(waist_phase_turn(levelled, t0, t1), phase)


def held_phase_yaw(raw: tuple[float, float] | None, phase: CyclePhase | None = None) -> float:
    """Decision E338: the yaw a stride of :func:`waist_phase_turn`'s ``raw`` is placed off by: its own psi without
    ``phase``, else the phase's held one; 0 (the phase untouched) without the waist's gyroscope."""
    if raw is None:
        return 0.0
    return raw[0] if phase is None else phase.stride(*raw)


def pivot_yaw(t: np.ndarray, gyr: np.ndarray, up: np.ndarray, *, still_rad_s: float = 0.4,
              max_dt_s: float | None = None) -> float:
    """Decision L28: heading change (rad, CCW) of a foot between two strides, samples ``t (n,)`` s, ``gyr
    (n, 3)`` rad/s (offset removed): the rate about ``up`` (the mean specific force over the gap: the foot
    is loaded) integrated (trapezoid) over the samples that are not still (|w| >= ``still_rad_s``, the fixed
    stance threshold below L27's floor): a foot pivoting on the ground turns, a still one does not (ZARU).
    ``max_dt_s`` (decision E348): an interval between two samples longer than this adds nothing (no straight line
    of the rate across a gap of the gyroscope); None: every interval counts."""
    n = float(math.sqrt(float(np.dot(up, up))))
    if len(t) < 2 or not n > 0:
        return 0.0
    w = np.asarray(gyr, dtype=float)
    rate = np.where(np.sqrt(np.add.reduce(w * w, axis=1)) >= still_rad_s, w @ (np.asarray(up, float) / n), 0.0)
    dt = t[1:] - t[:-1]
    if max_dt_s is not None:  # decision E348: the gyroscope's own gap counts 0
        dt = np.where(dt > max_dt_s, 0.0, dt)
    return float(np.add.reduce(0.5 * (rate[1:] + rate[:-1]) * dt))


#: Decision L31: the streamed gap yaw looks back at most this far (s) from a stride's start (the runtime
#: keeps one second of samples before the stride it is measuring).
GAP_YAW_MAX_S = 1.0


def gap_yaw(t_gyr: np.ndarray, gyr: np.ndarray, t_acc: np.ndarray, acc: np.ndarray, t0: float, t1: float,
            *, still_rad_s: float = 0.4, max_s: float = GAP_YAW_MAX_S, max_dt_s: float | None = None) -> float:
    """Decision L31: :func:`pivot_yaw` of a streamed foot between the end ``t0`` of one stride and the start
    ``t1`` of the next (s), over the gyroscope samples from the first one at or after ``max(t0, t1 - max_s)``
    to the first one at or after ``t1`` (0 when the strides touch or no accelerometer sample falls in the
    gap). A stride's own turn runs from its first sample at or after its start to the first at or after its
    end (L33, :func:`pdrlearn.kernels.window.start_index`), so strides and the gaps between them chain
    without a sample interval counted by neither (before, the interval holding ``t1`` was lost). ``max_dt_s``:
    :func:`pivot_yaw`'s (decision E348)."""
    lo = max(float(t0), float(t1) - max_s)
    if not t1 > lo:
        return 0.0
    edges = [lo - TIE_S, t1 - TIE_S]  # a sample within TIE_S of an edge is on it (decision E35)
    i0, i1 = (int(i) for i in np.searchsorted(t_gyr, edges, side="left"))
    j0, j1 = (int(i) for i in np.searchsorted(t_acc, edges, side="left"))
    i1, j1 = min(i1 + 1, len(t_gyr)), min(j1 + 1, len(t_acc))  # to the next stride's first sample
    if i1 - i0 < 2 or j1 <= j0:
        return 0.0
    return pivot_yaw(t_gyr[i0:i1], gyr[i0:i1], np.add.reduce(acc[j0:j1], axis=0) / (j1 - j0), still_rad_s=still_rad_s,
                     max_dt_s=max_dt_s)


#: Decision L61: the waist's turn between strides is integrated ungated (the waist-gyro heading inside a
#: stride integrates every sample; L31's 0.4 rad/s gate is a still foot's rule)
WAIST_GAP_STILL_RAD_S = 0.0


def waist_gap_max_s(prev_end: float, t0: float) -> float:
    """Decision L498: how far back (s) the waist's gap yaw looks from a stride's start ``t0``: the whole gap since
    ``prev_end`` up to ``rest_heading.REST_BIAS_MIN_S`` (60 s, L296 / W72: the offline waist integrates such a stop
    whole; the pelvis turns back into its rest early in a stop), else L31's :data:`GAP_YAW_MAX_S` (W413: no
    switch back to L31's last second alone)."""
    gap = float(t0) - float(prev_end)
    return gap if gap <= REST_BIAS_MIN_S else GAP_YAW_MAX_S


def waist_gap_from(prev_end: float | None, t0: float, waist: bool = True) -> float:
    """Decision E272: where the waist's gap yaw before the stride starting at ``t0`` begins (s; :func:`stride_gap_yaw`
    with ``waist``: L498's look-back from ``t0``), or ``t0`` when it adds none: the span a gyroscope bias turns it
    by."""
    if not waist or prev_end is None or not t0 > prev_end:
        return float(t0)
    return max(float(prev_end), float(t0) - waist_gap_max_s(prev_end, t0))


def long_stop_span(prev_end: float | None, t0: float, *, max_stop_s: float = 600.0) -> tuple[float, float] | None:
    """Decision E324: the part ``(a, b)`` (s) of the stop between a stride's end ``prev_end`` and the next one's start
    ``t0`` that :func:`long_stop_turn` measures: a stop over L296's ``REST_BIAS_MIN_S`` (60 s; L498's gap yaw then
    reads only its last ``GAP_YAW_MAX_S`` = 1 s, L31) from its start, or from ``max_stop_s`` before ``t0`` when longer
    (the live Tracker keeps that much of the waist's samples: 600 s, 60000 samples a ring at 100 Hz), to that last
    second; None for a shorter stop (L498 integrates it whole) or none."""
    if prev_end is None or not float(t0) - float(prev_end) > REST_BIAS_MIN_S:
        return None
    return max(float(prev_end), float(t0) - max_stop_s), float(t0) - GAP_YAW_MAX_S


def long_stop_turn(stream: Callable[[str], tuple[np.ndarray, np.ndarray]], prev_end: float | None, t0: float, *,
                   still_margin_s: float = 1.0) -> float:
    """Decision E324: the waist's turn (rad, CCW) over :func:`long_stop_span` (0 when None, or without waist samples):
    L296's :func:`~pdrlearn.kernels.rest_heading.rest_rotation` of the vertical rate
    (:func:`~pdrlearn.kernels.stop_bias.vertical_rate`): the still
    samples add nothing, the moving ones (a turn on the spot, standing up) their rate less the bias of the still blocks
    around them, as the offline waist track integrates a rest (W72 / L296), a still sample within ``still_margin_s``
    of a moving one counted as moving. Before E324 a turn made on the spot more
    than a second before the first stride after a stop over 60 s was lost (trial s50t1 F1: 15.20 m off on 20 m)."""
    span = long_stop_span(prev_end, t0)
    if span is None:
        return 0.0
    read = vertical_rate(stream, *span)
    if read is None:
        return 0.0
    t, w, still = read
    # a still sample within still_margin_s of a moving one is moving: a turn's slow start and end (under the still
    # test's 0.25 rad/s) is turn, not bias (without it trial s50t1's 90 deg spin after 90 s came out 74 deg).
    # Decision E334: "within" by time (+ half the median interval: the sample count's window on a regular clock),
    # so a waist dropout (fewer samples than the window) no longer breaks it (review s51r1 F1: a ValueError)
    moving = t[~still]
    reach = still_margin_s + 0.5 * float(np.median(np.diff(t)))
    j = np.searchsorted(moving, t - reach, side="left")  # the first moving sample not before t - reach
    near = (j < len(moving)) & (moving[np.minimum(j, len(moving) - 1)] <= t + reach) if len(moving) else ~still
    # decision E334: a gap in the waist samples over WAIST_GAP_S adds nothing (each side by its own samples)
    return rest_rotation(t, w, still & ~near, *span, max_dt_s=WAIST_GAP_S)


def stride_gap_yaw(levelled: Levelled, heading_source: str, stream: Callable[[str], tuple[np.ndarray, np.ndarray]],
                   prev_end: float | None, t0: float, *, foot: bool = True, waist: bool = False,
                   stop_turn: float | None = None) -> float:
    """Decisions L31 / L61: the turn (rad) in the gap between the previous stride's end ``prev_end`` and this
    stride's start ``t0`` (s), by the unit that heads the stride (:func:`stride_motion`): the foot's pivot
    (:func:`gap_yaw` of ``fGyroscope`` / ``fAccelerometer``, L31) when ``foot`` and the stride is headed by the
    foot; the waist's turn (the same :func:`gap_yaw` of ``wGyroscope`` / ``wAccelerometer``, not gated:
    :data:`WAIST_GAP_STILL_RAD_S`, L61) when ``waist`` and the stride is headed by the waist gyroscope; else 0.
    ``stream(name)`` -> ``(t, values)`` of a whole buffered stream (offline: the session's; the runtime: its
    ring buffer), so ``track --streaming`` and ``pdrlearn run`` call the same code. ``stop_turn``: E324's
    :func:`long_stop_turn` when the caller has it (decision E335: read once per stride), else read here."""
    if prev_end is None or not t0 > prev_end:
        return 0.0
    if headed_by_foot(levelled, heading_source):
        return gap_yaw(*stream("fGyroscope"), *stream("fAccelerometer"), prev_end, t0) if foot else 0.0
    if not waist:
        return 0.0
    return gap_yaw(*stream("wGyroscope"), *stream("wAccelerometer"), prev_end, t0, still_rad_s=WAIST_GAP_STILL_RAD_S,
                   max_s=waist_gap_max_s(prev_end, t0)) + (  # decisions L498, E324
        long_stop_turn(stream, prev_end, t0) if stop_turn is None else stop_turn)


def waist_bridge_yaw(stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float, *,
                     gap_line: bool = True) -> float:
    """Decision L91: the waist's turn (rad, CCW) over ``[t0, t1]`` (s), an interval the foot gyroscope did not
    record (it overlaps a foot gap over 1 s, B11): :func:`gap_yaw` of ``wGyroscope`` / ``wAccelerometer`` over the
    whole interval, ungated as L61 (:data:`WAIST_GAP_STILL_RAD_S`); 0 when ``t1 <= t0``. Across the waist
    gyroscope's own gap the trapezoid draws a straight line of the rate between the samples around it (W389, E299).
    ``gap_line=False`` (decision E348's candidate, measured and not adopted: straight walks median |error| 30.77 ->
    1.98 deg, but gaps inside a curve 14.84 -> 57.46 deg): an interval over :data:`WAIST_GAP_S` adds no turn."""
    if not t1 > t0:
        return 0.0
    return gap_yaw(*stream("wGyroscope"), *stream("wAccelerometer"), float(t0), float(t1),
                   still_rad_s=WAIST_GAP_STILL_RAD_S, max_s=float(t1) - float(t0),
                   max_dt_s=None if gap_line else WAIST_GAP_S)


def waist_gap_s(stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float) -> float:
    """Decision E354: the total (s) of the waist gyroscope's sample intervals over :data:`WAIST_GAP_S` among the
    samples :func:`waist_bridge_yaw` integrates over ``[t0, t1]`` (as :func:`gap_yaw` picks them): the waist's own
    gap inside the bridged span; 0 without one or without waist gyroscope samples."""
    if not t1 > t0:
        return 0.0
    try:
        t = stream("wGyroscope")[0]
    except KeyError:
        return 0.0
    i0, i1 = (int(i) for i in np.searchsorted(t, [float(t0) - TIE_S, float(t1) - TIE_S], side="left"))
    dt = np.diff(t[i0:min(i1 + 1, len(t))])
    return float(np.sum(dt[dt > WAIST_GAP_S]))


def stride_mean_rate(stream: Callable[[str], tuple[np.ndarray, np.ndarray]], s0: float, s1: float) -> float:
    """Decision E354: the waist's mean vertical rate (rad/s, CCW) over the stride ``[s0, s1]`` (s): the bridge
    kernel's ungated turn over it (its own waist gap counting 0, E348's keyword) over its duration. A whole gait cycle
    cancels the pelvis' zero-mean yaw oscillation and keeps a steady curve's rate; 0 when ``s1 <= s0``."""
    if not s1 > s0:
        return 0.0
    return waist_bridge_yaw(stream, s0, s1, gap_line=False) / (float(s1) - float(s0))


class CycleGapLine:
    """Decision E354: the turn across the waist gyroscope's own gap inside L91's bridge as the straight line between
    the gait-cycle mean rates either side (:func:`stride_mean_rate` of the last stride measured before and of the
    first stride measured after), ``0.5 * (before + after) * D`` (``D``: :func:`waist_gap_s`). :meth:`note` at each
    measured stride (decision E365: its rate recorded as it is placed, never read back from a trimmed buffer),
    :meth:`hold` at a bridged stride or pause (whose own bridge then counts the gap 0, ``gap_line=False``), :meth:`take`
    at the next measured stride (its turn gets the gap's). ``limit_after`` (decision E364): the rate after enters the
    line limited to the size of the rate before (a turn seen only after the gap is not drawn back into it). The live
    ``Tracker`` and ``track --streaming`` share it."""

    def __init__(self, *, limit_after: bool = True) -> None:
        self.limit_after = bool(limit_after)  # decision E364
        self.gap_s, self.before = 0.0, None  # the gaps held (s), the mean rate before the first of them (rad/s)
        self.last: float | None = None  # decision E365: the mean rate of the last stride measured (rad/s)
        #: decision E361: after :meth:`take`, the line's spread (rad) when it took a gap (half the difference of the
        #: mean rates either side times the gaps' length), else None
        self.spread: float | None = None

    def note(self, stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float) -> None:
        """Decision E365: the stride ``[t0, t1]`` (s) is measured: record its mean rate (the rate before a next gap)."""
        self.last = stride_mean_rate(stream, t0, t1)

    def hold(self, stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float) -> None:
        """The bridged span ``[t0, t1]`` (s); the rate before it: the last :meth:`note`'s (None before any)."""
        d = waist_gap_s(stream, t0, t1)
        if d > 0:
            if not self.gap_s:
                self.before = self.last
            self.gap_s += d

    def take(self, stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float) -> float:
        """The held gaps' turn (rad, CCW) with the stride ``[t0, t1]`` (s) after them; 0 when none is held."""
        self.spread = None
        if not self.gap_s:
            return 0.0
        after = stride_mean_rate(stream, t0, t1)
        before = after if self.before is None else self.before
        # decision E364: a rate seen only after the gap is measured from its first stride on, not drawn into the gap
        line_after = min(max(after, -abs(before)), abs(before)) if self.limit_after else after
        turn = 0.5 * (before + line_after) * self.gap_s
        self.spread = 0.5 * abs(before - after) * self.gap_s  # decision E361
        self.gap_s, self.before = 0.0, None
        return turn


#: Heading sources of a streamed stride: the foot's attitude change from rest to rest, the waist's
#: levelled vertical rate integrated over the stride, or "auto" (the waist when the stride has waist
#: samples, else the foot).
HEADING_SOURCES = ("auto", "foot", "waist-gyro")


#: Decision L141 (L132's candidate): the stride kernel's displacement is integrated on L24's histospline
#: ``stride_upsample`` times finer (1 = at the unit's own rate) when the foot's rate is below
#: :data:`FINE_BELOW_HZ`, the spline fitted on the stride's samples and :data:`FINE_PAD_S` either side; the
#: bundle's ``displacement`` / ``track --streaming --params`` key, default :data:`STRIDE_UPSAMPLE_DEFAULT`
STRIDE_UPSAMPLE_KEY = "stride_upsample"
STRIDE_UPSAMPLE_DEFAULT = 1
#: decision L141: offline ``FootDisplacement``'s factor (L16, L24; offline below 150 Hz since L628), and the padding
#: L132 measured (without it the spline's free ends ring: down strides 0.93-0.95 of their height)
STRIDE_UPSAMPLE_OPTION = 5
FINE_BELOW_HZ = 50.0
FINE_PAD_S = 0.5
#: decision E83: a live step on the fine kernel waits this much past its padding (one 20 Hz sample), so its samples
#: are all buffered one push before the push that returns it, which then finds it computed (E24)
FINE_AHEAD_S = 0.05


def stride_upsample(params: Mapping | None, where: str = "params") -> int:
    """Decision L141: the stride kernel's upsampling factor from a bundle's ``displacement`` / the streamed
    ``params`` (an integer >= 1; one clear line naming ``where`` otherwise)."""
    v = (params or {}).get(STRIDE_UPSAMPLE_KEY, STRIDE_UPSAMPLE_DEFAULT)
    # B176: NaN / Infinity (JSON accepts them) fail the finiteness test before int() would raise
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v != int(v) or int(v) < 1:
        raise DataError(f"{where}: {STRIDE_UPSAMPLE_KEY} {v!r} must be an integer >= 1 (1 = the unit's own rate, "
                        f"{STRIDE_UPSAMPLE_OPTION} = decision L141's block-mean spline below {FINE_BELOW_HZ:g} Hz)")
    return int(v)


def fine_spec(params: Mapping | None, stream: Callable[[str], tuple[np.ndarray, np.ndarray]],
              forward: Mapping[str, np.ndarray], *, rest_search_s: float, heading: str,
              where: str = "params") -> dict | None:
    """Decision L141: :func:`stride_motion`'s ``fine`` keywords for the streamed settings ``params`` (the bundle's
    ``displacement``, ``track --streaming --params``), or None when the stride kernel stays at the unit's rate
    (``stride_upsample`` 1, or no declared foot frame). ``track --streaming`` and the runtime call this."""
    factor = stride_upsample(params, where)
    if factor <= 1 or "foot" not in forward:
        return None
    return {"stream": stream, "forward_s": forward["foot"], "rest_search_s": float(rest_search_s),
            "heading": heading, "factor": factor}


def fine_stride_displacement(stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float,
                             forward_s: np.ndarray, *, rest_search_s: float, heading: str, factor: int,
                             pad_s: float = FINE_PAD_S) -> np.ndarray | None:
    """Decision L141: the stride ``[t0, t1]`` (s)'s displacement (3,) m in the step frame, levelled and integrated on
    L24's block-mean histospline ``factor`` times finer (:func:`pdrlearn.kernels.histospline.upsample_block_means`,
    fitted on the foot's samples from ``t0 - pad_s`` to ``t1 + pad_s``, the gyroscope on the accelerometer's clock,
    then cut to the stride): a 20 Hz sample is a 50 ms block mean, within which the swinging foot pitches by ~0.5
    rad, so one attitude per block leaves part of gravity in the vertical (L132: stair strides 2-4 % short).
    ``stream(name)`` -> ``(t, values)`` of a buffered stream (``track --streaming``: the session's; the runtime:
    its ring buffer, which holds ``pad_s`` past the stride before the step is measured). None (the caller keeps
    the native-rate displacement) when ``factor`` is 1, the foot's median rate there is ``FINE_BELOW_HZ`` or more
    (offline does not upsample either), the foot gyroscope is missing, fewer than 3 samples, or an interval over
    1.5 median intervals (a dropped sample: the block would widen across it, L87)."""
    if factor <= 1:
        return None
    try:
        ta, acc = segment(*stream("fAccelerometer"), t0 - pad_s, t1 + pad_s)
        tg, gyr = segment(*stream("fGyroscope"), t0 - pad_s, t1 + pad_s)
    except KeyError:
        return None
    if len(ta) < 3 or len(tg) < 2:
        return None
    d = np.diff(ta)
    period = float(np.median(d))
    if not period > 0 or 1.0 / period >= FINE_BELOW_HZ or float(d.max()) > 1.5 * period:
        return None
    tf, v = upsample_block_means(ta, np.hstack([acc[:, :3], resample(ta, tg, gyr[:, :3]).T]), factor)
    ts, vs = segment(tf, v, t0, t1)
    a = foot_levelled(ts, vs[:, :3], vs[:, 3:], forward_s, rest_search_s=rest_search_s, heading=heading, t0=t0)[0]
    return zupt_displacement(ts, a)


def stride_motion(levelled: Levelled, heading_source: str = "auto", *, t0: float = -np.inf,
                  t1: float = np.inf, fine: Mapping | None = None) -> tuple[np.ndarray, float]:
    """Displacement (3,) m in the step frame (foot, ZUPT at both stances) and heading change (rad) of
    the stride ``[t0, t1]`` (s) from :func:`pdrlearn.kernels.window.levelled_units`. ``fine`` (decision L141):
    the keywords of :func:`fine_stride_displacement` but the times (``stream``, ``forward_s``, ``rest_search_s``,
    ``heading``, ``factor``): the displacement on the histospline below 50 Hz (the heading change stays the
    native rate's)."""
    if "foot" not in levelled:
        raise DataError("stride displacement needs the foot unit's accelerometer and its declared frame")
    ta, a, g, _, dpsi = levelled["foot"][:5]
    fine_disp = None if fine is None else fine_stride_displacement(t0=t0, t1=t1, **fine)
    disp = zupt_displacement(ta, a) if fine_disp is None else fine_disp
    src = heading_source
    if src == "auto":
        src = "waist-gyro" if waist_heads(levelled) else "foot"
    if src == "waist-gyro":
        if "waist" not in levelled or levelled["waist"][2] is None:
            raise DataError("heading 'waist-gyro' needs the waist unit's accelerometer and gyroscope")
        tw, _, gw, _, _ = levelled["waist"]
        return disp, yaw_change(tw, gw[:, 2], t0, t1)
    if src != "foot":
        raise DataError(f"stride heading source {heading_source!r} is not one of {', '.join(HEADING_SOURCES)}")
    return disp, dpsi  # the foot's attitude change from rest to rest (the rate's vertical integral is not)


def placement_offset(levelled: Levelled, heading_source: str, disp: np.ndarray) -> float:
    """Decision L34: the direction (rad) a stride is placed along, relative to the heading after it. A
    stride headed by the foot goes along the foot's heading at its start (the heading after it less its own
    turn) plus the direction of its displacement relative to the foot there (offline's ``foot_heading +
    lateral``), not along the heading after a turn it made on the way; a stride headed by the waist keeps
    the heading after it (0). ``disp`` (3,) in the step frame (:func:`stride_motion`); the lateral angle is
    signed with the stride's x, like the length's sign."""
    if not headed_by_foot(levelled, heading_source):
        return 0.0
    foot = levelled["foot"]
    direction = foot[5] if len(foot) > 5 else 0.0
    dx, dy = float(disp[0]), float(disp[1])
    lateral = math.atan2(dy, abs(dx)) * (-1.0 if dx < 0 else 1.0)
    return direction + lateral - float(foot[4])


def reversed_by_rules(foot_headed: bool, dx: float, length: float) -> float:
    """Decision L37: pi when the rules gave a stride headed by the foot (:func:`headed_by_foot`) a length
    whose sign is against its measured x (a turning stride whose step frame points backwards, classed
    forward), else 0. Added to :func:`placement_offset`, the stride goes along its measured displacement, as
    offline's does, instead of ~160 deg the wrong way; a stride headed by the waist keeps the thesis sign
    rule (0)."""
    if not foot_headed or length == 0.0 or (length < 0.0) == (dx < 0.0):
        return 0.0
    return math.pi


def waist_forward_flip(foot_headed: bool, direction, length: float, side_offset: float = 0.0) -> float:
    """Decision E216: pi when a stride headed by the waist (not ``foot_headed``) has the reported direction class
    ``"forward"``, a negative ``length`` and no E124 side placement (``side_offset`` 0); else 0 (measured and adopted,
    docs/decisions/export.md; the rule itself, no module switch, W413). Added to the stride's direction, it moves
    |length| along the waist heading (the walker's facing), where a forward stride travels."""
    if foot_headed or direction != "forward" or not length < 0.0 or side_offset != 0.0:
        return 0.0
    return math.pi


def travel_sign_one(length: float, heading: float, measured_x: float = math.nan, sideways: bool = False,
                    turn_rad: float = math.nan) -> tuple[float, float]:
    """Decision L654 (amends L65): the ``(length_m, heading_rad)`` a stride is REPORTED with - the same displacement
    (``advance``), so apply it after the position update - whose sign is the stride's measured travel: ``length_m``
    is negative exactly when the stride travels backward, its measured x (``measured_x``, the displacement along the
    foot's forward axis; steps.csv ``raw_length_m``'s sign) negative, and ``heading_rad`` is then the facing the
    stride went back from; otherwise positive along the direction it moved (a negative length becomes its magnitude
    along the heading turned by pi, and a positive one the thesis' class rule signed against its measured x the
    other way). So the sign of ``length_m`` says what steps.csv ``backward_travel`` / ``travel`` say, whatever the
    model's ``direction`` class (T2 F10: a backward stride classed forward read +0.46 m; F3: a forward stride
    classed backward read -1.41 m with oracle classes). A NaN ``measured_x`` (a gap row) is no backward travel.
    Decision C137: a ``sideways`` stride (L219 / L486's side step) is no backward travel (L270), so it keeps no
    negative length; decision L578: nor does a stride turning ``turn_rad`` (its own turn) through
    ``BACKWARD_MAX_TURN_DEG`` or more (travel = turn: a pivot's or a turnaround's chord points anywhere, L65's
    -1.3 m turnaround stride) on a chord under ``SPOT_MAX_CHORD_M`` (decision L692: |``measured_x``|, the signed
    chord of :func:`pdrlearn.kernels.backward.signed_chord`, judged against the mid-stride facing)."""
    back = bool(measured_x < 0.0) and not sideways and not bool(on_the_spot([turn_rad], [measured_x])[0])
    if length != 0.0 and (length < 0.0) != back:
        return -length, heading + math.pi
    return length, heading


def travel_sign(length: np.ndarray, heading: np.ndarray, measured_x=None,
                sideways=None, turn_rad=None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`travel_sign_one` on arrays (``measured_x``: (n,) each stride's signed chord, L692's
    :func:`pdrlearn.kernels.backward.signed_chord`, or None: no stride travels backward; ``sideways``: (n,) bool,
    decision C137, or None: none; ``turn_rad``: (n,) each stride's own turn, decision L578, or None: none)."""
    length = np.asarray(length, dtype=float)
    heading = np.asarray(heading, dtype=float)
    with np.errstate(invalid="ignore"):
        back = (np.zeros(len(length), dtype=bool) if measured_x is None
                else np.asarray(measured_x, dtype=float) < 0.0)  # decision L654: the measured travel
    if sideways is not None:
        back &= ~np.asarray(sideways, dtype=bool)  # decision C137: a side step keeps no negative length
    if turn_rad is not None:  # decisions L578, L692: nor does a turn on the spot (a short chord)
        back &= ~on_the_spot(turn_rad, np.nan if measured_x is None else measured_x)
    flip = (length != 0.0) & ((length < 0.0) != back)
    return np.where(flip, -length, length), np.where(flip, heading + math.pi, heading)


def headed_by_foot(levelled: Levelled, heading_source: str) -> bool:
    """Whether :func:`stride_motion` takes this stride's heading from the foot (decision L31: only then is
    the foot's pivot before the stride added)."""
    return heading_source == "foot" or (heading_source == "auto" and not waist_heads(levelled))


#: decision E114: heading auto leaves the waist gyroscope for a stride whose waist samples leave a gap over this
#: (s) inside it or at its ends (B11's 1 s, ``GAP_LONG_S``)
WAIST_GAP_S = 1.0


def waist_heads(levelled: Levelled) -> bool:
    """Decision E114: whether heading auto takes the stride's turn from the waist gyroscope: the waist unit's
    accelerometer and gyroscope are levelled, and their samples cover the stride,
    from the foot's first to its last sample, without an interval over :data:`WAIST_GAP_S`. A waist dropout's rate
    interpolated across the gap is not a turn, and a live Tracker's held waist has no sample after the stride."""
    if "waist" not in levelled or levelled["waist"][2] is None:
        return False
    if "foot" not in levelled:
        return True
    tw, tf = levelled["waist"][0], levelled["foot"][0]
    if tw is None or tf is None:  # no times to judge (a caller's stand-in): the waist heads, as before E114
        return True
    if not len(tw) or not len(tf):
        return False
    # the waist's samples of the stride (one either side, ``segment``) reach the foot's within E36's 0.25 s (a live
    # Tracker's held waist stops short of the stride's end) and leave no interval over WAIST_GAP_S (a recording's
    # gap, whose far side a replay holds)
    return (float(tw[0]) <= float(tf[0]) + BRIDGE_GAP_S and float(tw[-1]) >= float(tf[-1]) - BRIDGE_GAP_S
            and (len(tw) < 2 or float(np.max(np.diff(tw))) <= WAIST_GAP_S))


# -- rules (thesis ch.7.2.2) --------------------------------------------------------------------------
#: decision L178: every path's default down-stride rule - the thesis' 3-axis norm (eq. 61) is the stride's path
#: length and its horizontal part moves x/y (L51's "projected"); "norm3" places the norm itself horizontally
DEFAULT_DOWN_MODE = "projected"


def terrain_distance(disp: np.ndarray, terrain: np.ndarray, *, down_mode: str = DEFAULT_DOWN_MODE) -> np.ndarray:
    """Unsigned distance (m) of each stride from its displacement (B, 3) according to its terrain class.

    flat/up: the displacement along the direction of travel (horizontal, the thesis' "x-axis" filter);
    down: the norm of the three axes, thesis eq. 61 (``down_mode="horizontal"`` uses the flat rule; under
    ``"projected"`` the norm is the path length whose horizontal part :func:`horizontal_part` gives, L51).
    """
    horiz = np.hypot(disp[:, 0], disp[:, 1])
    if down_mode == "horizontal":
        return horiz
    norm3 = np.sqrt(np.add.reduce(disp * disp, axis=1))  # thesis eq. 61 (= np.linalg.norm(disp, axis=1))
    return np.where(np.asarray(terrain) == "down", norm3, horiz)


#: the down-stride rules: "norm3" (thesis eq. 61, the norm moves x/y), "projected" (decision L51: the norm is
#: the path length, its horizontal part moves x/y), "horizontal" (the flat/up rule)
DOWN_MODES = ("norm3", "projected", "horizontal")


def horizontal_part(length, dz, terrain, *, down_mode: str = DEFAULT_DOWN_MODE):
    """Decision L51 (``down_mode="projected"``, the default since L178): the signed horizontal length that moves x/y. A
    stride classed down has the thesis' 3-axis norm (eq. 61) as its path length ``length``; its horizontal part
    is sign(length) * sqrt(max(length^2 - dz^2, 0)), ``dz`` the altitude change the rules give the stride.
    Other modes and other strides: ``length`` as it is. Arrays or Python floats (the runtime, decision E17)."""
    if isinstance(length, float):  # the runtime's one stride (decision E17: Python floats)
        if down_mode != "projected" or terrain != "down":
            return length
        h = math.sqrt(max(length * length - dz * dz, 0.0))
        return -h if length < 0 else h
    length = np.asarray(length, dtype=float)
    if down_mode != "projected":
        return length
    dz = np.asarray(dz, dtype=float)
    h = np.sqrt(np.maximum(length * length - dz * dz, 0.0))
    return np.where(np.asarray(terrain, dtype=object) == "down", np.where(length < 0, -h, h), length)


def apply_direction(distance: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Sign of each distance set by its direction class; the class prevails (thesis ch.7.2.2)."""
    d = np.abs(np.asarray(distance, dtype=float))
    return np.where(np.asarray(direction) == "backward", -d, d)


def clamp_length(distance: np.ndarray, length_class: np.ndarray,
                 bounds: Mapping[str, tuple[float, float]]) -> np.ndarray:
    """Clamp |distance| into the bounds of its length class, keeping the sign (thesis ch.7.2.2).

    ``bounds`` maps a class to (min, max) in metres; unknown classes are left unchanged.
    """
    d = np.asarray(distance, dtype=float)
    cls = np.asarray(length_class)
    mag = np.abs(d)
    out = mag.copy()
    for name in bounds.keys() & set(cls.ravel().tolist()):  # the classes present (masks are disjoint)
        lo, hi = bounds[name]
        sel = cls == name
        out[sel] = np.minimum(np.maximum(mag[sel], lo), hi)
    return np.where(d < 0, -out, out)


def altitude_change(dz: np.ndarray, terrain: np.ndarray) -> np.ndarray:
    """Altitude change (m) per stride: 0 on flat terrain, +|dz| up, -|dz| down (thesis ch.7.2.2)."""
    t = np.asarray(terrain)
    a = np.abs(np.asarray(dz, dtype=float))
    return np.where(t == "up", a, np.where(t == "down", -a, 0.0))


def _known_one(v) -> bool:
    return v is not None and v == v and v != ""  # v == v: not NaN


def _known(x: np.ndarray) -> np.ndarray:
    return np.array([_known_one(v) for v in x], dtype=bool)


def apply_stride_rules(disp: np.ndarray, terrain=None, direction=None, length_class=None, *,
                       bounds: Mapping[str, tuple[float, float]] | None = None,
                       down_mode: str = DEFAULT_DOWN_MODE, rules: str = "thesis", length_proba=None,
                       sigma_rel: float = B.SIGMA_REL, sigma_min: float = B.SIGMA_MIN, dz_min: float = B.DZ_MIN
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The M3 rules (thesis ch.7.2.2) on displacements ``disp (B, 3)``: signed length and altitude change.

    A missing class (None) means "no rule": horizontal distance and the estimated vertical change / the
    sign of the estimate / no clamp. ``rules="bayes"`` (decisions L14, L40): see :func:`stride_rules_one`;
    ``length_proba`` = one mapping (length class -> probability) or None per stride.
    """
    disp = np.asarray(disp, dtype=float).reshape(-1, 3)
    n = len(disp)
    if rules == "bayes" or n == 1:  # one stride (the streaming runtime), or bayes: the scalar kernel per stride
        cols = [[None] * n if c is None else list(c) for c in (terrain, direction, length_class)]
        lp = [None] * n if length_proba is None else list(length_proba)
        out = [stride_rules_one(*d, t, r, c, bounds=bounds, down_mode=down_mode, rules=rules, length_proba=p,
                                sigma_rel=sigma_rel, sigma_min=sigma_min, dz_min=dz_min)
               for d, t, r, c, p in zip(disp.tolist(), *cols, lp, strict=True)]
        return np.array([o[0] for o in out], dtype=float), np.array([o[1] for o in out], dtype=float)
    none = np.full(n, None, dtype=object)
    terrain = none if terrain is None else np.asarray(terrain, dtype=object)
    direction = none if direction is None else np.asarray(direction, dtype=object)
    length_class = none if length_class is None else np.asarray(length_class, dtype=object)
    length = terrain_distance(disp, terrain, down_mode=down_mode) * np.where(disp[:, 0] < 0, -1.0, 1.0)
    has_dir = _known(direction)
    length = np.where(has_dir, apply_direction(length, np.where(has_dir, direction, "forward")), length)
    if bounds is not None:
        has_lc = _known(length_class)
        length = clamp_length(length, np.where(has_lc, length_class, ""), bounds)
    has_t = _known(terrain)
    dz = np.where(has_t, altitude_change(disp[:, 2], np.where(has_t, terrain, "flat")), disp[:, 2])
    return horizontal_part(length, dz, terrain, down_mode=down_mode), dz  # decision L51


def stride_rules_one(dx: float, dy: float, dz: float, terrain=None, direction=None, length_class=None, *,
                     bounds: Mapping[str, tuple[float, float]] | None = None,
                     down_mode: str = DEFAULT_DOWN_MODE,
                     rules: str = "thesis", length_proba: Mapping[str, float] | None = None,
                     sigma_rel: float = B.SIGMA_REL, sigma_min: float = B.SIGMA_MIN, dz_min: float = B.DZ_MIN
                     ) -> tuple[float, float]:
    """:func:`apply_stride_rules` of one stride given and returned as Python floats (signed length m, altitude
    change m): the runtime's call, without the arrays (decision E17).

    ``rules="thesis"``: the class prevails (sign, clamp into the class bounds, altitude from the terrain).
    ``rules="bayes"`` (decision L14, as :class:`pdrlearn.displace.StepRules`; streamed since L40): with
    sigma = max(``sigma_rel`` |L|, ``sigma_min``), the direction class decides only an ambiguous sign (|L| <
    2 sigma), the length is the posterior mean given the length-class probabilities ``length_proba`` (class
    -> p; None: one-hot of ``length_class``), :func:`pdrlearn.kernels.bayes.bayes_length_one`, and a height
    change above ``dz_min`` keeps its measured sign whatever the terrain class. Gate the classes first
    (:func:`pdrlearn.kernels.bayes.confident_one`, decision L18): a class set to None has no rule."""
    if down_mode != "horizontal" and terrain == "down":
        dist = math.sqrt(dx * dx + dy * dy + dz * dz)  # thesis eq. 61
    else:
        dist = float(np.hypot(dx, dy))  # terrain_distance: the flat/up rule (numpy's hypot, as the array path)
    length = -dist if dx < 0 else dist
    bayes = rules == "bayes"
    sigma = max(sigma_rel * dist, sigma_min) if bayes else 0.0  # L14: the estimate's sd
    if _known_one(direction) and (not bayes or dist < 2 * sigma):  # apply_direction: the class prevails
        length = -abs(length) if direction == "backward" else abs(length)
    if bayes and bounds is not None and _known_one(length_class):  # L14: posterior mean over the classes
        mag = B.bayes_length_one(dist, B.class_proba_one(length_proba, bounds, length_class),  # names = keys
                                 list(bounds.values()), sigma)
        length = mag if length > 0 else -mag if length < 0 else 0.0 * mag  # np.sign(length) * mag
    elif bounds is not None and _known_one(length_class) and length_class in bounds:  # clamp_length
        lo, hi = bounds[length_class]
        mag = min(max(abs(length), lo), hi)
        length = -mag if length < 0 else mag
    if _known_one(terrain) and not (bayes and abs(dz) > dz_min):  # altitude_change (L14: a clear dz stays)
        dz = abs(dz) if terrain == "up" else -abs(dz) if terrain == "down" else 0.0
    return horizontal_part(float(length), dz, terrain, down_mode=down_mode), dz  # decision L51


# -- position -----------------------------------------------------------------------------------------
def advance(position: np.ndarray, heading_rad: float, length_m: float, dz_m: float) -> np.ndarray:
    """ENU position (3,) m after a stride of signed ``length_m`` along ``heading_rad`` and ``dz_m`` up."""
    x, y, z = np.asarray(position, dtype=np.float64).reshape(3).tolist()  # Python floats: math.cos/sin
    return np.array(advance_xyz(x, y, z, heading_rad, length_m, dz_m))


def advance_xyz(x: float, y: float, z: float, heading_rad: float, length_m: float, dz_m: float
                ) -> tuple[float, float, float]:
    """:func:`advance` on Python floats (the runtime keeps its position as floats, decision E17)."""
    return x + length_m * math.cos(heading_rad), y + length_m * math.sin(heading_rad), z + dz_m


# -- last-line guard (decision L94) --------------------------------------------------------------------------
#: A stride's displacement over its time above this speed (m/s) is physically impossible: strides tile the walk
#: stance to stance (one gait cycle each), so |displacement| / duration is the walker's mean speed over the cycle,
#: and no human has run faster than ~12.4 m/s (the 100 m world record's fastest 20 m split, Berlin 2009). Running
#: is out of the validated range (decision L95) but must not be dropped here: a 4.5 m/s run is a third of it.
MAX_STRIDE_SPEED_MPS = 12.5


def impossible_stride_one(length_m: float, dz_m: float, duration_s: float) -> bool:
    """Decision L94: True when the stride's finite 3-D displacement (``length_m``, ``dz_m``, m) exceeds
    :data:`MAX_STRIDE_SPEED_MPS` x ``duration_s`` (s). Python floats (the runtime's step). A non-finite value is
    not "impossible" but a bug (:func:`non_finite_stride_error`, as decision E38)."""
    d = math.hypot(length_m, dz_m)
    return math.isfinite(d) and d > MAX_STRIDE_SPEED_MPS * max(duration_s, 0.0)


def impossible_strides(length_m: np.ndarray, dz_m: np.ndarray, duration_s: np.ndarray) -> np.ndarray:
    """:func:`impossible_stride_one` of B strides (arrays of one shape) -> bool (B,)."""
    d = np.hypot(np.asarray(length_m, dtype=float), np.asarray(dz_m, dtype=float))
    with np.errstate(invalid="ignore"):
        return np.isfinite(d) & (d > MAX_STRIDE_SPEED_MPS * np.maximum(np.asarray(duration_s, dtype=float), 0.0))


def impossible_stride_warning(n: int, t0: float, t1: float, length_m: float, dz_m: float) -> str:
    """Decision L94's one line (offline, ``track --streaming``, the runtime): ``n`` strides moved 0 m, the first
    at ``t0``-``t1`` s with the rules' ``length_m`` / ``dz_m``. Decision B132: its cause by the first stride's time:
    longer than :data:`~pdrlearn.kernels.contact.MAX_STRIDE_S` (no rest of the foot inside) the input is not
    walking there (crawling, kneeling: integrated without a zero-velocity update); a stride of walking length
    that fast is a sensor fault or a bug."""
    if t1 - t0 > MAX_STRIDE_S:
        cause = (f"the foot did not rest for {t1 - t0:.1f} s (over {MAX_STRIDE_S:g} s: non-walking motion such as "
                 "crawling or kneeling, or a unit that is never still), so it was integrated without a zero-velocity "
                 "update: the input is not walking there, not a bug (decision B132)")
    else:
        cause = ("a stride of walking length this fast means an accelerometer fault (spikes, clipping, wrong units) "
                 "or a bug in pdrlearn: if the foot accelerometer looks sane there, please report it (decision B132)")
    return (f"{n} stride(s) gave a physically impossible displacement (first {t0:.3f}-{t1:.3f} s: length "
            f"{length_m:.6g} m, height {dz_m:.6g} m in {t1 - t0:.3f} s; the bound is {MAX_STRIDE_SPEED_MPS:g} m/s "
            "x the stride's time, faster than any human sprint) and moved 0 m, as a gap, left out of the distance "
            "and of the gait parameters (stride time, cadence, speed, walking time; column impossible in "
            f"steps.csv) (decision L94, L97): {cause}")


def non_finite_stride_error(where: str, t0: float, t1: float, length_m: float, dz_m: float) -> str:
    """Decision L94 (E38's rule for the offline paths): a non-finite stride length or height from data that
    passed every input check is pdrlearn's fault; the message of the :class:`InternalError` raised."""
    return (f"internal error in {where}: the stride {t0:.3f}-{t1:.3f} s gave a non-finite length ({length_m:.6g} "
            f"m) or height change ({dz_m:.6g} m) from finite samples; this is a bug, not bad data - please report it")
