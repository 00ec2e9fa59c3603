"""The foot's initial contact (IC) of one stride: the accelerometer detector's impact rule (decision E49).

Offline, :class:`pdrlearn.steps.AccelStepDetector` (thesis ch.5.1, steps decision 14) puts a stride's IC at the
last local maximum of the causally low-passed acceleration magnitude (2nd-order Butterworth, 8 Hz) that rises at
least ``peak_frac`` of the swing's largest rise above gravity, moved back by the filter's group delay at 1 Hz.
:func:`last_impact` is that selection (``steps._kernels.burst_kernel`` calls it); :func:`impact_time` applies the
whole rule to the samples of one streamed stride (``pdrlearn run``, ``track --streaming``, E49). The filter is the
closed-form bilinear 2nd-order Butterworth (equal to ``scipy.signal.butter(2, ...)`` to rounding, pinned by
``tests/test_streamed_contacts.py``), so the runtime needs numpy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pdrlearn.kernels.samples import values

#: standard gravity (m/s^2), the rest level of |acc| (thesis ch.4.2.1.1)
GRAVITY = 9.80665
#: the impact's low-pass cutoff (Hz) and order: AccelStepDetector's ``event_cutoff_hz`` (steps decision 14)
EVENT_CUTOFF_HZ = 8.0
#: steps decisions 87, 88: a stride whose impact at 8 Hz comes less than this (s) after the previous stride's IC (a
#: child's 126 steps/min) takes its impact on |acc| low-passed at the stride's own cutoff (:func:`rhythm_cutoff_hz`):
#: at 8 Hz its terminal-swing deceleration and impact merge into one peak, the deceleration's, 60-88 ms early
SHORT_PERIOD_S = 0.95
#: steps decision 88: at this IC-to-IC time (s) and shorter the cutoff is :data:`FAST_EVENT_CUTOFF_HZ` (a child's
#: 0.34 s steps; u14906's 60 ms gap needed 20 Hz, steps 87)
FAST_PERIOD_S = 0.68
#: steps decision 88: the cap of the rhythm's cutoff (Hz, 2nd order, its own group delay)
FAST_EVENT_CUTOFF_HZ = 20.0
#: steps decision 93: the rhythm's re-take only at a foot rate (Hz) of at least this (0: at every rate): at 50 Hz its
#: 20 Hz cutoff is capped at 0.45 x the rate only and hardly smooths (trial R2-F1); steps 91 was measured at 100 Hz
SHORT_MIN_RATE_HZ = 0.0
#: steps decision 94: a swing whose |acc| low-passed at 3 Hz spans more than this (m/s^2; AccelStepDetector's
#: ``amplitude``) keeps decision 3's 8 Hz impact (0: none): development race walkers 16060-16065 (0.9-1.05 m steps
#: in 0.27-0.33 s, trial R2-F2) spanned 80-147, children 16070-16073 22-52, and their IC-to-IC strides overlap
#: (0.53-0.69 s against 0.61-0.86 s), so the stride time cannot part them
SHORT_MAX_AMP = 65.0
#: steps decision 94: the streamed stride's span is read on |acc| low-passed at this (Hz; AccelStepDetector's
#: ``cutoff_hz``, thesis ch.5.1; :func:`swing_span`)
AMP_CUTOFF_HZ = 3.0
#: steps decision 91: at the rhythm's cutoff the impact is looked for among the last peak reaching the level and the
#: peaks up to this long (s) before it (:func:`split_head`): at 20 Hz a child's impact splits into the contact and a
#: tail 30-50 ms later (steps 88), which the last-peak rule took. 0: the last peak (steps 88)
IMPACT_CLUSTER_S = 0.05
#: steps decision 91: an earlier peak of that cluster is the impact when the later one is under this share of it (the
#: split tails of development children 14900-14911 / 15200-15219 were 0.43-0.70 of their impact 40-50 ms before; an
#: impact 40-50 ms after the deceleration peak was 0.76 of it or more)
IMPACT_SPLIT_RATIO = 0.75
#: the impact must rise at least this fraction of the swing's largest rise (AccelStepDetector ``peak_frac``)
PEAK_FRAC = 0.3
#: steps decision 89 (not adopted: 0, every local maximum in samples): a local maximum whose dip from the bump before
#: it (the lowest filtered value between them) stays less than this (m/s^2) below the lower of the two is a ripple of
#: that bump; AccelStepDetector's ``peak_prominence`` option (1.7 keeps an up-sampled gaitmap walk's ICs, 89)
PEAK_PROMINENCE = 0.0
#: a cutoff is kept below this fraction of the sampling rate (``steps.detectors._cutoff``)
MAX_CUTOFF_FRAC = 0.45
#: two strides touch when the first ends within this of the second's start (s; both are samples of one clock)
TOUCH_S = 1e-6
#: longest IC-to-IC time that is a stride (s): Mobilise-D stride selection, mobgap StrideSelection mobilised
#: default (duration <= 3 s, pdrlearn.waist.gait_rules.MAX_STRIDE_S); also the longest rest inside a walk
#: (mobgap WbAssembly MaxBreakCriteria(max_break_s=3)) for ``walking_time_s`` (decisions L79, L80)
MAX_STRIDE_S = 3.0
#: decision L605: a foot's stride cap is at least this many of its own stride periods (a stride time may hold half
#: a stride more than the walker's rhythm, a short stop, before it is a stop); at a normal period (<= 1.45 s) it
#: stays under :data:`MAX_STRIDE_S`, so L80's 3 s holds there
RHYTHM_CAP_PERIODS = 1.5
#: decision L605: ... only when the foot's strides (their median rest-to-rest window) fill at least this fraction of
#: the period: shorter strides are normal strides with stands between them, whose walk-and-stand cycle is no stride
#: (an order picker's 1.4 s strides in a 3.42 s cycle: 0.41; slow continuous walks 0.70-0.88)
RHYTHM_CAP_MIN_FILL = 0.5
#: steps decision 32: the foot contacts' times between the samples (the impact peak's parabola, the force crossing's
#: line) when True; whole samples when False. The detectors' ``subsample=None`` and the streamed contacts read it
SUBSAMPLE = True


def butter2(cutoff_hz: float, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """(b, a) of the 2nd-order Butterworth low-pass at ``cutoff_hz`` (Hz) for rate ``fs`` (Hz): the bilinear
    transform with pre-warping, as ``scipy.signal.butter(2, cutoff_hz / (fs / 2))``."""
    k = math.tan(math.pi * cutoff_hz / fs)
    n = 1.0 / (1.0 + math.sqrt(2.0) * k + k * k)
    b0 = k * k * n
    a = np.array([1.0, 2.0 * (k * k - 1.0) * n, (1.0 - math.sqrt(2.0) * k + k * k) * n])
    return np.array([b0, 2.0 * b0, b0]), a


def group_delay_s(b: np.ndarray, a: np.ndarray, fs: float, at_hz: float = 1.0) -> float:
    """Group delay (s) of the filter ``(b, a)`` at ``at_hz``: Re(sum k c_k z^-k / sum c_k z^-k) of b less that
    of a, z = exp(j 2 pi at_hz / fs) (as ``pdrlearn.signal.lowpass_delay_s``, decision E49)."""
    z = np.exp(-1j * 2.0 * np.pi * at_hz / fs * np.arange(max(len(b), len(a))))

    def tau(c):
        c = np.asarray(c, dtype=float)
        zc = z[:len(c)]
        return float(np.real(np.sum(np.arange(len(c)) * c * zc) / np.sum(c * zc)))

    return (tau(b) - tau(a)) / fs


def lowpass2(x: np.ndarray, b: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Causal biquad ``(b, a)`` over ``x`` (n,), started at the steady state of ``x[0]`` (a constant passes
    unchanged, as ``pdrlearn.signal.lowpass(causal=True)``)."""
    x = np.asarray(x, dtype=float)
    y = np.empty_like(x)
    if not len(x):
        return y
    b0, b1, b2 = (float(v) for v in b)
    _, a1, a2 = (float(v) for v in a)
    x1 = x2 = float(x[0])
    y1 = y2 = float(x[0]) * (b0 + b1 + b2) / (1.0 + a1 + a2)
    for i, xi in enumerate(x.tolist()):
        yi = b0 * xi + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2
        y[i] = yi
        x2, x1, y2, y1 = x1, xi, y1, yi
    return y


def last_impact(peak_values, emx: float, rest: float, peak_frac: float) -> int:
    """Index of the last of the swing's local maxima ``peak_values`` that reaches ``rest + peak_frac (emx - rest)``
    (``emx`` the swing's largest value), -1 when none does (AccelStepDetector's IC, steps decision 14)."""
    level = rest + peak_frac * (emx - rest)
    for i in range(len(peak_values) - 1, -1, -1):
        if peak_values[i] >= level:
            return i
    return -1


def bump_peaks(peak_values, dips, prominence: float) -> list[int]:
    """Steps decision 89: indices into the swing's local maxima ``peak_values`` of its bumps' highest maxima, in
    time order. ``dips[k]`` is the lowest filtered value between maximum ``k - 1`` and maximum ``k`` (``dips[0]`` is
    not read). A maximum whose lowest value since the current bump's highest one stays less than ``prominence``
    below the lower of the two joins that bump, which keeps the higher; else it opens a bump. With ``prominence``
    0 every maximum is a bump (a dip is never above the maxima beside it), as before decision 89."""
    out: list[int] = []
    low = math.inf
    for k, v in enumerate(peak_values):
        if out:
            low = min(low, float(dips[k]))
            top = peak_values[out[-1]]
            if min(top, v) - low < prominence:
                if v > top:
                    out[-1], low = k, math.inf
                continue
        out.append(k)
        low = math.inf
    return out


def peak_time(t0: float, t1: float, t2: float, e0: float, e1: float, e2: float) -> float:
    """Steps decision 32: the time (s) of the vertex of the parabola through the samples ``(t0, e0)``, ``(t1, e1)``,
    ``(t2, e2)`` around a local maximum at ``t1`` (Press et al., Numerical Recipes, 3rd ed., eq. 10.3.1), kept within
    half an interval of ``t1``; ``t1`` when the three points lie on a line."""
    a, c = t1 - t0, t1 - t2
    den = a * (e1 - e2) - c * (e1 - e0)
    if not den:
        return t1
    t = t1 - 0.5 * (a * a * (e1 - e2) - c * c * (e1 - e0)) / den  # Numerical Recipes eq. 10.3.1
    return min(max(t, t1 - 0.5 * a), t1 - 0.5 * c)


def crossing_time(t0: float, t1: float, f0: float, f1: float, level: float) -> float:
    """Steps decision 32: the time (s) at which the line from ``(t0, f0)`` to ``(t1, f1)`` reaches ``level`` (a
    threshold crossing between two samples, ``f0 <= level < f1``), kept within ``[t0, t1]``; ``t1`` when
    ``f1 <= f0``."""
    if not f1 > f0:
        return t1
    return min(max(t0 + (level - f0) / (f1 - f0) * (t1 - t0), t0), t1)


def local_maxima(e: np.ndarray) -> np.ndarray:
    """Indices ``i`` where ``e`` rose into sample ``i`` and does not rise after it (``e[i-1] < e[i] >= e[i+1]``):
    the peaks ``burst_kernel`` collects."""
    e = np.asarray(e, dtype=float)
    if len(e) < 3:
        return np.zeros(0, dtype=int)
    return np.flatnonzero((e[1:-1] > e[:-2]) & (e[2:] <= e[1:-1])) + 1


def short_stride(period_s: float, short_period_s: float = SHORT_PERIOD_S, amp: float = 0.0,
                 max_amp: float = SHORT_MAX_AMP) -> bool:
    """Steps decision 87: True when a stride whose 8 Hz impact comes ``period_s`` (s) after the previous stride's IC
    takes its impact on the rhythm's cutoff (under ``short_period_s``; NaN, no previous contact: False); steps
    decision 94: not when its swing's ``amp`` (m/s^2) is over ``max_amp`` > 0 (a race walker's long, quick swing)."""
    return bool(period_s < short_period_s) and not (max_amp > 0 and amp > max_amp)


def rhythm_cutoff_hz(period_s: float, cutoff_hz: float = EVENT_CUTOFF_HZ, short_period_s: float = SHORT_PERIOD_S,
                     fast_period_s: float = FAST_PERIOD_S, fast_cutoff_hz: float = FAST_EVENT_CUTOFF_HZ) -> float:
    """Steps decision 88: the impact's cutoff (Hz) of a stride whose 8 Hz impact comes ``period_s`` (s) after the
    previous stride's IC: ``cutoff_hz`` from ``short_period_s`` up (and without a previous IC), rising linearly to
    ``fast_cutoff_hz`` at ``fast_period_s`` and held there below (the filter's span follows the closing gap between the
    terminal-swing deceleration and the impact)."""
    if not short_stride(period_s, short_period_s, max_amp=0.0):
        return float(cutoff_hz)
    share = min(1.0, (short_period_s - period_s) / max(short_period_s - fast_period_s, 1e-9))
    return float(cutoff_hz + share * (max(fast_cutoff_hz, cutoff_hz) - cutoff_hz))


def swing_span(m: np.ndarray, fs: float) -> float:
    """Steps decision 93 / 94: the span (m/s^2) of the magnitude ``m`` (n,) at ``fs`` Hz low-passed as
    AccelStepDetector's ``amplitude`` (3rd-order Butterworth at :data:`AMP_CUTOFF_HZ`, thesis ch.5.1; causal, started
    at its steady state on the first sample): the streamed stride's counterpart of the offline swing's span."""
    from pdrlearn.kernels import dsp

    sos = dsp.butter_sos(3, min(AMP_CUTOFF_HZ, MAX_CUTOFF_FRAC * fs), fs, "low")
    e = dsp.sosfilt(sos, np.asarray(m, dtype=float), dsp.sosfilt_zi(sos) * float(m[0]))[0]
    return float(e.max() - e.min())


def split_head(peak_t, peak_values, k: int, cluster_s: float, ratio: float = IMPACT_SPLIT_RATIO) -> int:
    """Steps decision 91: the impact among the peaks ``peak_values`` (times ``peak_t``, s, in order) when peak ``k`` is
    the last one reaching the impact level: going back from ``k`` over the peaks up to ``cluster_s`` (s) before it, an
    earlier peak takes the choice when the chosen one is under ``ratio`` of it (a split impact's tail: the impact
    stays the larger head; the terminal-swing deceleration lies further back or is not that much larger). ``k``
    itself when ``cluster_s`` is 0."""
    best = k
    for j in range(k - 1, -1, -1):
        if peak_t[j] < peak_t[k] - cluster_s:
            break
        if peak_values[best] < ratio * peak_values[j]:
            best = j
    return best


def event_envelope(m: np.ndarray, b: np.ndarray, a: np.ndarray, power: bool = False) -> np.ndarray:
    """The impact's event signal of the magnitude ``m`` (n,): ``m`` low-passed by the biquad ``(b, a)``
    (:func:`lowpass2`, decision E49); steps decision 97 with ``power``: the RMS envelope sqrt(low-pass(m^2)), whose
    input, the squared magnitude, is band-limited to twice the axes' band and so reads alike on every sample grid
    that resolves the axes (|acc|, a square root, is not band-limited: its rectified ringing folds into the low band
    differently at each rate)."""
    m = np.asarray(m, dtype=float)
    if not power:
        return lowpass2(m, b, a)
    return np.sqrt(np.maximum(lowpass2(m * m, b, a), 0.0))


def impact_peak(t: np.ndarray, m: np.ndarray, rest: float, peak_frac: float, cutoff_hz: float,
                subsample: bool, prominence: float = PEAK_PROMINENCE,
                cluster_s: float = 0.0, power: bool = False) -> tuple[float, float, float]:
    """Decision E49's rule on the magnitude ``m`` (n,) at times ``t`` (n,) s at one cutoff (Hz, below 0.45 x the
    rate): (IC (s) less the filter's group delay at 1 Hz, the peak's filtered value, the largest filtered value);
    the IC is NaN with fewer than 3 samples or no peak reaching ``peak_frac`` of the largest rise above ``rest``.
    Steps decision 91: with ``cluster_s`` > 0 the peak is the head of a split impact among the last one reaching the
    level and those up to ``cluster_s`` (s) before it (:func:`split_head`). Steps decision 97: ``power`` reads the
    RMS envelope (:func:`event_envelope`). :func:`impact_time` and the offline detector's rhythm cutoff (steps
    decision 88) share it."""
    t = np.asarray(t, dtype=float)
    if len(t) < 3:
        return math.nan, math.nan, math.nan
    fs = 1.0 / float(np.median(np.diff(t)))
    b, a = butter2(min(cutoff_hz, MAX_CUTOFF_FRAC * fs), fs)
    e = event_envelope(m, b, a, power)  # steps decision 97
    pk = local_maxima(e)
    dips = [math.inf] + [float(e[i + 1:j + 1].min()) for i, j in zip(pk[:-1], pk[1:], strict=True)]
    pk = pk[bump_peaks(e[pk], dips, prominence)]  # steps decision 89
    emx = float(e.max())
    k = last_impact(e[pk], emx, rest, peak_frac)
    if k < 0:
        return math.nan, math.nan, emx
    i = int(pk[split_head(t[pk], e[pk], k, cluster_s)])  # steps decision 91
    tp = peak_time(*(float(v) for v in (*t[i - 1:i + 2], *e[i - 1:i + 2]))) if subsample else float(t[i])
    return tp - group_delay_s(b, a, fs), float(e[i]), emx


def impact_time(t: np.ndarray, acc: np.ndarray, *, rest: float = GRAVITY, peak_frac: float = PEAK_FRAC,
                cutoff_hz: float = EVENT_CUTOFF_HZ, prominence: float = PEAK_PROMINENCE, prev_ic_s: float = math.nan,
                short_period_s: float = SHORT_PERIOD_S, fast_period_s: float = FAST_PERIOD_S,
                fast_cutoff_hz: float = FAST_EVENT_CUTOFF_HZ, cluster_s: float = IMPACT_CLUSTER_S,
                min_rate_hz: float = SHORT_MIN_RATE_HZ, max_amp: float = SHORT_MAX_AMP, power: bool = False) -> float:
    """Decision E49: the IC (s) of one stride from its foot accelerometer samples ``t`` (n,) s, ``acc`` (n, 3)
    m/s^2 (stance to stance): |acc| low-passed by :func:`butter2` (cutoff below 0.45 x the rate), the last bump
    (steps decision 89: local maxima grouped by ``prominence``, :func:`bump_peaks`) reaching ``peak_frac`` of the
    largest rise above ``rest`` (:func:`last_impact`), less the filter's group delay at 1 Hz (:func:`impact_peak`).
    NaN with fewer than 3 samples, no such peak, or an IC before ``t[0]``. Steps decisions 87, 88: re-taken at the
    rhythm's cutoff (:func:`rhythm_cutoff_hz`) when it comes less than ``short_period_s`` after ``prev_ic_s``, the
    previous stride's contact; steps decision 91: there the head of a split impact (:func:`split_head`); steps
    decision 93: only at a rate of ``min_rate_hz`` and up; steps decision 94: only when the stride's
    :func:`swing_span` is at most ``max_amp``; steps decision 97: ``power`` dates it on the RMS envelope
    (:func:`event_envelope`)."""
    t = np.asarray(t, dtype=float)
    if len(t) < 3:
        return math.nan
    acc = np.asarray(acc, dtype=float)
    m = np.sqrt(np.einsum("ij,ij->i", acc, acc))
    ic = impact_peak(t, m, rest, peak_frac, cutoff_hz, SUBSAMPLE, prominence, power=power)[0]
    fs = 1.0 / float(np.median(np.diff(t)))
    if fs < min_rate_hz:  # steps decision 93: only at the rate the re-take was measured at
        short_period_s = 0.0
    f = rhythm_cutoff_hz(ic - prev_ic_s, cutoff_hz, short_period_s, fast_period_s, fast_cutoff_hz)
    if f != cutoff_hz and max_amp > 0:  # steps decision 94: a race walker's swing keeps the 8 Hz impact
        f = f if short_stride(0.0, 1.0, swing_span(m, fs), max_amp) else cutoff_hz
    if f != cutoff_hz:  # steps decision 88 (no peak at the rhythm's cutoff: the 8 Hz one stays, as offline)
        ic2 = impact_peak(t, m, rest, peak_frac, f, SUBSAMPLE, prominence, cluster_s, power)[0]
        ic = ic2 if ic2 == ic2 else ic
    return ic if ic >= t[0] else math.nan


def stride_cap_s(period_s: float, window_s: float) -> float:
    """Decision L605: the longest IC-to-IC time (s) that is a stride of a foot whose stride period is ``period_s``
    (s; :func:`pdrlearn.kernels.foot_rhythm.foot_period`) and whose strides' median rest-to-rest window is
    ``window_s`` (s): L80's :data:`MAX_STRIDE_S`, or :data:`RHYTHM_CAP_PERIODS` periods when that is longer (a slow
    walker's 3.5-5 s strides) and the strides fill :data:`RHYTHM_CAP_MIN_FILL` of the period; a non-finite value =
    :data:`MAX_STRIDE_S`."""
    if not (math.isfinite(period_s) and math.isfinite(window_s)) or window_s < RHYTHM_CAP_MIN_FILL * period_s:
        return MAX_STRIDE_S
    return max(MAX_STRIDE_S, RHYTHM_CAP_PERIODS * float(period_s))


def stride_times(start_s, end_s, event_s, valid=None, *, max_s: float = MAX_STRIDE_S) -> np.ndarray:
    """(B,) s: ``event_s[i] - event_s[i-1]`` where stride ``i-1`` ends no later than stride ``i`` starts, both
    events lie inside their own windows, both strides are ``valid`` (not across a gap: a gap row between two
    strides is an invalid row, L67) and the difference is positive and at most ``max_s``; else NaN
    (decision L66: initial contact to initial contact, the gait-lab stride time; decision L80: a rest between
    the strides shorter than a stop keeps it - L66 required the strides to touch)."""
    st, en, ev = (np.asarray(v, dtype=float) for v in (start_s, end_s, event_s))
    n = len(st)
    out = np.full(n, np.nan)
    if n < 2:
        return out
    ok = (ev >= st) & (ev <= en) & np.isfinite(ev)
    if valid is not None:
        ok &= np.asarray(valid, dtype=bool)
    follows = st[1:] >= en[:-1] - TOUCH_S  # the next stride of the foot, not an overlapping window
    d = ev[1:] - ev[:-1]
    good = follows & ok[1:] & ok[:-1] & (d > 0) & (d <= max_s + 1e-9)
    out[1:] = np.where(good, d, np.nan)
    return out


# force-gated stance detector (thesis ch.5.2), shared by AccelForceStepDetector and the streamed IC (E50)
@dataclass
class ForceParams:
    amp: float  # max - min of the filtered acceleration during the swing (m/s^2; thesis ch.5.2: 1)
    on_frac: float  # combined force above this fraction of its running maximum = stance
    off_frac: float  # below this fraction = swing (hysteresis)
    min_swing_s: float  # shortest swing (s)
    subsample: bool = False  # steps decision 32: the onset between the samples, by the crossing's line
    ref_stances: int = 0  # steps decision 53: levels from the median peak of this many last stances (0: running max)
    confirm: bool = False  # steps decision 54: an onset holds for the next sample too (a one-sample spike is none)


@dataclass
class ForceState:
    fmax: float = 0.0
    stance: bool = True
    swing_t0: float = math.nan
    mx: float = -math.inf
    mn: float = math.inf
    last_event_t: float = math.nan
    prev_t: float = math.nan  # the previous sample (decision 32's crossing)
    prev_f: float = math.nan
    peak: float = 0.0  # steps decision 53: the current stance's largest force
    peaks: tuple = ()  # ... and the last completed stances' (at most ForceParams.ref_stances)
    peak_median: float = math.nan  # ... and their median
    pending: tuple = ()  # steps decision 54: (t before, f before, t, f) of an onset waiting for the next sample


def force_kernel(t: np.ndarray, a: np.ndarray, f: np.ndarray, state: ForceState,
                 p: ForceParams) -> tuple[list, ForceState]:
    """Thesis ch.5.2: while the combined heel+toe force is ~0 (swing) keep the max and min of the
    filtered acceleration; at the stance onset count a step when max - min > ``p.amp``. The event is
    the stance onset (initial contact), with ``p.subsample`` the time the line from the sample before reaches the
    on level (steps decision 32); the window runs from the swing start to the stance onset sample. The levels are
    fractions of the running maximum, or with ``p.ref_stances`` > 0 of the median peak of the last that many
    completed stances (steps decision 53: one spike cannot move them; the running maximum until one has ended)."""
    out: list = []
    s = state
    for ti, ai, fi in zip(values(t), values(a), values(f), strict=True):  # decision E195: no whole-session lists
        prev_t, prev_f, s.prev_t, s.prev_f = s.prev_t, s.prev_f, ti, fi
        if fi > s.fmax:
            s.fmax = fi
        ref = s.peak_median if p.ref_stances > 0 and s.peaks else s.fmax
        if s.stance:
            s.peak = max(s.peak, fi)
            if ref > 0 and fi < p.off_frac * ref:
                if p.ref_stances > 0:  # steps decision 53
                    s.peaks, s.peak = (*s.peaks, s.peak)[-p.ref_stances:], 0.0
                    s.peak_median = float(np.median(s.peaks))
                s.stance, s.swing_t0, s.mx, s.mn = False, ti, ai, ai
        else:
            above = fi > p.on_frac * ref
            if s.pending:  # steps decision 54: the onset of the sample before holds, or was a spike
                onset, s.pending = s.pending, ()
                if above:
                    _force_onset(s, p, *onset, ref, out)
                    s.peak = max(s.peak, fi)
                    continue
            if ai > s.mx:
                s.mx = ai
            if ai < s.mn:
                s.mn = ai
            if above:
                if p.confirm:
                    s.pending = (prev_t, prev_f, ti, fi)
                else:
                    _force_onset(s, p, prev_t, prev_f, ti, fi, ref, out)
    return out, s


def _force_onset(s: ForceState, p: ForceParams, prev_t: float, prev_f: float, ti: float, fi: float, ref: float,
                 out: list) -> None:
    """:func:`force_kernel`'s stance onset at sample ``ti`` (``prev_t`` the one before): a step when the swing's
    acceleration spans ``p.amp`` and the swing lasted ``p.min_swing_s``."""
    s.stance, s.peak = True, fi
    span = s.mx - s.mn
    if span > p.amp and ti - s.swing_t0 >= p.min_swing_s:
        ic = (crossing_time(prev_t, ti, prev_f, fi, p.on_frac * ref)
              if p.subsample and prev_f == prev_f else ti)
        out.append((ic, s.swing_t0, ti, min(1.0, span / (2.0 * p.amp)), {"amplitude": span}))
        s.last_event_t = ti


#: AccelForceStepDetector's settings (thesis ch.5.2): stance when the combined force exceeds FORCE_ON_FRAC of its
#: running maximum, swing below FORCE_OFF_FRAC; the swing's |acc| must span FORCE_AMP m/s^2 and last FORCE_MIN_SWING_S
FORCE_ON_FRAC, FORCE_OFF_FRAC, FORCE_AMP, FORCE_MIN_SWING_S = 0.10, 0.05, 1.0, 0.15
#: steps decisions 53/54 (adopted with 54's confirmed onset): the levels' reference = the median peak of the last this
#: many stances (AccelForceStepDetector's default; the streamed contacts of E50 keep the stride's running maximum)
FORCE_REF_STANCES = 5


@dataclass
class TareState:
    """Steps decision 73: :func:`running_tare`'s state - the filtered |acc|'s extremes since the start, the time the
    foot first swung (NaN: not yet), each force channel's running minimum and maximum, and the offsets last
    subtracted (0: none)."""
    amn: float = math.inf
    amx: float = -math.inf
    swung_t: float = math.nan
    fmn: tuple = (math.inf, math.inf)
    fmx: tuple = (-math.inf, -math.inf)
    offset: tuple = (0.0, 0.0)


def running_tare(t: np.ndarray, a: np.ndarray, f: np.ndarray, state: TareState, amp: float = FORCE_AMP,
                 off_frac: float = FORCE_OFF_FRAC, wait_s: float = MAX_STRIDE_S) -> tuple[np.ndarray, TareState]:
    """Steps decision 73: decision B284's tare, causal, for the online accel-force detector (which sees no gyroscope).
    The foot has swung once the filtered |acc| ``a`` has spanned ``amp`` since the start (thesis ch.5.2's swing test);
    ``wait_s`` (the longest stride) later every channel that reaches ~0 unloaded has done so. From then on a force
    channel (``f`` (n, 2), heel and toe, at times ``t``) whose running minimum stays above ``off_frac`` of its running
    maximum (B284's test: the detector could never see a swing) has that minimum (its unloaded reading) subtracted,
    clipped at 0. A channel that reaches ~0 in the swings is returned bit for bit."""
    t, a = np.asarray(t, dtype=float), np.asarray(a, dtype=float)
    f = np.asarray(f, dtype=float).reshape(len(a), 2)
    if not len(a):
        return f, state
    amx = np.maximum.accumulate(np.concatenate([[state.amx], a]))[1:]
    amn = np.minimum.accumulate(np.concatenate([[state.amn], a]))[1:]
    fmn = np.minimum.accumulate(np.vstack([state.fmn, f]), axis=0)[1:]
    fmx = np.maximum.accumulate(np.vstack([state.fmx, f]), axis=0)[1:]
    swung_t = state.swung_t
    if swung_t != swung_t and ((amx - amn) > amp).any():
        swung_t = float(t[np.argmax((amx - amn) > amp)])
    due = t >= swung_t + wait_s  # all False while swung_t is NaN
    off = np.where(due[:, None] & (fmn > off_frac * fmx), fmn, 0.0)
    out = np.where(off > 0, np.maximum(f - off, 0.0), f)
    return out, TareState(float(amn[-1]), float(amx[-1]), swung_t, tuple(map(float, fmn[-1])),
                          tuple(map(float, fmx[-1])), tuple(map(float, off[-1])))


def force_onset(t: np.ndarray, acc: np.ndarray, force: np.ndarray) -> float:
    """Decision E50: the last stance onset (s) in one stride's samples by :func:`force_kernel` (a fresh state: the
    running maximum is the stride's), ``force`` (n, 2) heel and toe at the times ``t`` of ``acc`` (n, 3); the swing
    check on the raw |acc|. NaN without one."""
    acc = np.asarray(acc, dtype=float)
    f = np.asarray(force, dtype=float)
    if len(t) < 3 or f.ndim != 2 or f.shape[1] < 2:
        return math.nan
    ev, _ = force_kernel(np.asarray(t, dtype=float), np.sqrt(np.einsum("ij,ij->i", acc, acc)), f[:, 0] + f[:, 1],
                         ForceState(), ForceParams(amp=FORCE_AMP, on_frac=FORCE_ON_FRAC, off_frac=FORCE_OFF_FRAC,
                                                   min_swing_s=FORCE_MIN_SWING_S, subsample=SUBSAMPLE))
    return float(ev[-1][0]) if ev else math.nan


def stride_contact(t: np.ndarray, acc: np.ndarray, force: np.ndarray | None = None,
                   prev_ic_s: float = math.nan) -> float:
    """Decisions E49 / E50: the initial contact (s) of one streamed stride (stance to stance; ``t`` (n,) s, foot
    ``acc`` (n, 3) m/s^2, ``force`` (n, 2) heel and toe at ``t`` or None): offline's source - the force sensors'
    stance onset (:func:`force_onset`) when given and found, else the accelerometer impact (:func:`impact_time`;
    ``prev_ic_s`` the previous stride's contact, steps decision 87)."""
    if force is not None:
        ic = force_onset(t, acc, force)
        if math.isfinite(ic):
            return ic
    return impact_time(t, acc, prev_ic_s=prev_ic_s)


def force_at(t: np.ndarray, streams) -> np.ndarray | None:
    """(n, 2) heel and toe force at the times ``t``, linearly interpolated (offline's ``stream_on``) from
    ``streams`` = ((tA, vA), (tB, vB)); None when either has fewer than 2 samples."""
    out = []
    for ts, vs in streams:
        if len(ts) < 2:
            return None
        out.append(np.interp(t, ts, np.asarray(vs, dtype=float).reshape(len(ts), -1)[:, 0]))
    return np.column_stack(out)
