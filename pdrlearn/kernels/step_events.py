"""Pure numerical kernels of the step detectors, numpy only (moved from ``pdrlearn.steps._kernels``, which
re-exports them, so that the lean runtime's clock check runs the same detectors: decision L177).

Each kernel has the form ``kernel(t, x..., state, params) -> (events, state)``: it consumes one chunk of
samples, returns the events that became final in this chunk and the new state. Feeding a signal in one
chunk or in many gives the same events (the detectors' online == offline guarantee), because every
decision depends only on samples already seen plus a bounded look-ahead that is carried in the state.

An event is a tuple ``(event_s, start_s, end_s, confidence, extra)`` with ``extra`` a dict of
detector-specific columns. Times in seconds, accelerations in m/s^2, angular rates in rad/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

# decision E50: the force detector's kernel lives with the streamed IC (numpy only); re-exported here
from pdrlearn.kernels.contact import (  # noqa: F401
    ForceParams,
    ForceState,
    TareState,
    bump_peaks,
    force_kernel,
    impact_peak,
    last_impact,
    peak_time,
    rhythm_cutoff_hz,
    running_tare,
    short_stride,
)
from pdrlearn.kernels.dsp import magnitude
from pdrlearn.kernels.samples import values

Event = tuple[float, float, float, float, dict]


# ---------------------------------------------------------------------------------------------------
# trailing-window statistics with carried history (chunk-invariant)
def trailing_window_std(x: np.ndarray, tail: np.ndarray, w: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mean and standard deviation of the last ``w`` samples at each sample of ``x``.

    ``tail`` holds the ``w - 1`` samples before ``x`` (from the previous chunk, or the first sample
    repeated at the start). Returns ``(mean, std, new_tail)``; each window is computed on its own, so
    the result does not depend on how the signal is chunked.
    """
    xp = np.concatenate([tail, x])
    win = sliding_window_view(xp, w)
    return win.mean(axis=1), win.std(axis=1), xp[len(xp) - (w - 1):] if w > 1 else xp[:0]


# ---------------------------------------------------------------------------------------------------
# swing bursts between still periods (foot accelerometer detector, thesis ch.5.1)
@dataclass
class BurstParams:
    """Settings of :func:`burst_kernel` in samples (converted from seconds by the detector)."""

    amp: float  # minimum max-min of the filtered magnitude inside a swing (m/s^2; thesis 1.7)
    min_still_n: int  # still samples that end a swing
    min_dur_s: float  # shortest swing (s)
    max_dur_s: float  # longest swing (s); longer bursts are not steps (the thesis' 20-sample window)
    min_stride_s: float  # two events closer than this are one stride (s)
    rest: float  # rest level of the filtered magnitude (m/s^2, gravity)
    peak_frac: float  # the event is the last local maximum reaching this fraction of the largest rise
    # adaptive still time (decision 14): a still run must last quiet_frac x the longest of the last
    # ``history`` still runs, between min_still_n and max_still_n samples; quiet_frac = 0: min_still_n
    max_still_n: int = 0
    quiet_frac: float = 0.0
    history: int = 4
    window_n: int = 1  # samples of the trailing still window (a run of k still samples = k + window_n - 1 quiet)
    cap_n: int = 0  # still runs are counted up to this many quiet samples (standing is not a stance)
    # decision 16: the still time follows the quiet_rank-th longest rest of the history (1 = the longest);
    # rests_only: only still runs of at least min_still_n samples (long enough to end a swing) enter it
    quiet_rank: int = 1
    rests_only: bool = False
    subsample: bool = False  # steps decision 32: each peak's time at the vertex of its parabola
    prominence: float = 0.0  # steps decision 89: maxima grouped into bumps by this dip (m/s^2; 0: every maximum)
    # steps decisions 87, 88: a swing whose event comes less than short_period_s after the last accepted stride's
    # event takes it again from the raw magnitude ``m`` low-passed at the rhythm's cutoff (contact.rhythm_cutoff_hz
    # of event_cutoff_hz, fast_period_s, fast_cutoff_hz), as the streamed contact does, over the swing and the pre_n
    # samples before it; event_delay_s (the event signal's group delay, which the processor subtracts from every
    # event) is added back. 0: ``e`` only
    short_period_s: float = 0.0
    fast_period_s: float = 0.0
    fast_cutoff_hz: float = 0.0
    event_cutoff_hz: float = 0.0
    event_delay_s: float = 0.0
    pre_n: int = 0
    cluster_s: float = 0.0  # steps decision 91: at the rhythm's cutoff the head of a split impact (contact.split_head)
    max_amp: float = 0.0  # steps decision 94: a swing spanning more than this keeps the 8 Hz impact (0: none)
    power: bool = False  # steps decision 97: the re-take on the RMS envelope (contact.event_envelope)


@dataclass
class BurstState:
    active: bool = False
    i0_t: float = 0.0
    mx: float = -math.inf
    mx_t: float = 0.0
    mn: float = math.inf
    still_count: int = 0
    last_t: float = math.nan
    prev_a: float = math.nan
    prev_t: float = math.nan
    prev2_a: float = math.nan  # the sample before prev (decision 32's parabola)
    prev2_t: float = math.nan
    rising: bool = False
    emx: float = -math.inf
    peaks: list = field(default_factory=list)  # local maxima (t, a, dip before it) of the current swing
    low: float = math.inf  # steps decision 89: the lowest event value since the swing's last local maximum
    raw: list = field(default_factory=list)  # steps decision 88: (t, |acc|) of the swing and the pre_n before it
    last_ic: float = math.nan  # steps decision 87: the held (pending) stride's event, and the one before it
    before_ic: float = math.nan
    pending: Event | None = None  # last accepted stride, held back until min_stride_s has passed
    pending_amp: float = 0.0
    pending_emx: float = -math.inf
    quiet: list = field(default_factory=list)  # quiet samples of the last still runs (at most p.history)
    need_n: int = -1  # still samples that end a swing now (-1: p.min_still_n)


def _still_need(s: BurstState, p: BurstParams) -> int:
    if p.quiet_frac <= 0 or not s.quiet:
        return p.min_still_n
    ranked = sorted(s.quiet, reverse=True)
    n = int(round(p.quiet_frac * ranked[min(p.quiet_rank, len(ranked)) - 1])) - (p.window_n - 1)
    return min(max(n, p.min_still_n), max(p.max_still_n, p.min_still_n))


def burst_kernel(t: np.ndarray, a: np.ndarray, still: np.ndarray, state: BurstState,
                 p: BurstParams, e: np.ndarray | None = None,
                 m: np.ndarray | None = None) -> tuple[list[Event], BurstState]:
    """Swing detection: a swing starts at the first non-still sample and ends after ``min_still_n``
    still samples; it is a stride when the filtered magnitude ``a`` spans more than ``p.amp`` (thesis
    ch.5.1 max - current > 1.7 m/s^2) and it lasts ``min_dur_s``..``max_dur_s``. The event is the
    initial contact, the last impact of the swing: the last local maximum of ``a`` that rises at least
    ``peak_frac`` of the swing's largest rise above ``rest`` (push-off and impact peaks change order
    between feet, mountings and speeds; the impact is always the last one). Strides closer than
    ``min_stride_s`` are merged, keeping the larger one. ``e`` (default ``a``) is the signal whose peaks
    locate the event (a less smoothed magnitude keeps the impact apart from the push-off). With
    ``p.subsample`` a peak's time is the vertex of the parabola through it and its neighbours (steps decision 32;
    its value, and so the choice of the peak, stays the sample's). Steps decisions 87, 88: with the raw
    magnitude ``m`` and ``p.short_period_s``, a swing whose event comes within ``short_period_s`` of the last accepted
    stride's event takes it again from ``m`` low-passed at the rhythm's cutoff (decision 3's stride time, as the
    streamed contact reads it; :func:`pdrlearn.kernels.contact.impact_peak`, the streamed rule).
    """
    out: list[Event] = []
    s = state
    tl, al, sl = values(t), values(a), values(still)  # decision E195: no whole-session lists
    el = al if e is None else values(e)  # a memoryview / list iterates afresh in zip
    short = m is not None and p.short_period_s > 0  # steps decisions 87, 88
    ml = values(m) if short else el
    for ti, ai, si, ei, mi in zip(tl, al, sl, el, ml, strict=True):
        s.last_t = ti
        if s.pending is not None and ti - s.pending[0] >= p.min_stride_s and not (
                s.active and s.i0_t - s.pending[0] < p.min_stride_s):
            out.append(s.pending)
            s.pending = None
        if si:
            s.still_count += 1
        elif s.still_count:
            if p.quiet_frac > 0 and (not p.rests_only or s.still_count >= p.min_still_n):
                q = s.still_count + p.window_n - 1
                s.quiet = (s.quiet + [min(q, p.cap_n) if p.cap_n else q])[-p.history:]
                s.need_n = _still_need(s, p)
            s.still_count = 0
        was_rising, prev_a, prev_t, prev2_a, prev2_t = s.rising, s.prev_a, s.prev_t, s.prev2_a, s.prev2_t
        s.rising = ei > prev_a if prev_a == prev_a else False
        s.prev2_a, s.prev2_t, s.prev_a, s.prev_t = prev_a, prev_t, ei, ti
        if short:  # steps decision 88: the swing's raw magnitude, and the pre_n samples before it
            s.raw.append((ti, mi))
            if not s.active and len(s.raw) > p.pre_n:
                del s.raw[:len(s.raw) - p.pre_n]
        if not s.active:
            if not si:
                s.active, s.i0_t, s.mx, s.mx_t, s.mn = True, ti, ai, ti, ai
                s.peaks, s.emx, s.low = [], ei, ei
            continue
        if was_rising and ei <= prev_a:  # a rise into prev: prev2 is a sample too
            s.peaks.append((peak_time(prev2_t, prev_t, ti, prev2_a, prev_a, ei) if p.subsample else prev_t, prev_a,
                            s.low))
            s.low = ei
        elif ei < s.low:
            s.low = ei
        if ei > s.emx:
            s.emx = ei
        if ai > s.mx:
            s.mx, s.mx_t = ai, ti
        if ai < s.mn:
            s.mn = ai
        if s.still_count >= (s.need_n if s.need_n >= 0 else p.min_still_n):
            s.active = False
            dur = ti - s.i0_t
            span = s.mx - s.mn
            bumps = [s.peaks[j] for j in bump_peaks([pa for _, pa, _ in s.peaks], [d for _, _, d in s.peaks],
                                                     p.prominence)]  # steps decision 89
            emx = s.emx
            k = last_impact([pa for _, pa, _ in bumps], emx, p.rest, p.peak_frac)  # E49: the streamed IC's rule
            t_ev, e_ev = bumps[k][:2] if k >= 0 else (s.mx_t, emx)
            # steps decision 87: the rhythm from the stride before; a piece of the held stride (merged below) reads
            # it from the stride before that one
            merging = s.pending is not None and t_ev - s.pending[0] < p.min_stride_s
            period = t_ev - (s.before_ic if merging else s.last_ic)
            if short and short_stride(period, p.short_period_s, span, p.max_amp):  # steps decisions 88, 93
                f = rhythm_cutoff_hz(period, p.event_cutoff_hz, p.short_period_s, p.fast_period_s, p.fast_cutoff_hz)
                rt, rm = zip(*s.raw, strict=True)
                ic, e_f, emx_f = impact_peak(np.array(rt), np.array(rm), p.rest, p.peak_frac, f, p.subsample,
                                             p.prominence, p.cluster_s, p.power)  # steps decisions 91, 97
                if ic == ic:
                    t_ev, e_ev, emx = ic + p.event_delay_s, e_f, emx_f
            if short:
                del s.raw[:len(s.raw) - p.pre_n]
            if s.pending is not None and t_ev - s.pending[0] < p.min_stride_s and span > p.amp:
                # the same swing split by a brief false rest: merge; the event stays the last impact
                # (a wobble below the threshold while standing is ignored, it never moves the event)
                pe = s.pending
                s.pending_emx = max(s.pending_emx, emx)
                amp = max(s.pending_amp, span)
                conf = min(1.0, amp / (2.0 * p.amp))
                merged_level = p.rest + p.peak_frac * (s.pending_emx - p.rest)
                t_m = t_ev if e_ev >= merged_level else pe[0]
                s.pending, s.pending_amp = (t_m, pe[1], ti, conf, {"amplitude": amp}), amp
                s.last_ic = t_m  # steps decision 87
            elif span > p.amp and p.min_dur_s <= dur <= p.max_dur_s:
                if s.pending is not None:
                    out.append(s.pending)
                s.before_ic, s.last_ic = s.last_ic, t_ev  # steps decision 87
                conf = min(1.0, span / (2.0 * p.amp))
                s.pending, s.pending_amp, s.pending_emx = (t_ev, s.i0_t, ti, conf, {"amplitude": span}), span, emx
    return out, s


def burst_flush(state: BurstState) -> list[Event]:
    """Events still held back at the end of the signal (a swing still open is dropped)."""
    out = [state.pending] if state.pending is not None else []
    state.pending = None
    return out


# ---------------------------------------------------------------------------------------------------
# force-gated stance detector (thesis ch.5.2): ForceParams, ForceState, force_kernel live in
# pdrlearn.kernels.contact (decision E50) and are imported above
# ---------------------------------------------------------------------------------------------------
# pelvic rotation lobes (thesis ch.5.3, eq. 27)
@dataclass
class PelvicParams:
    threshold: float  # possible step above this yaw rate (rad/s; thesis ch.5.3: 0.11)
    peak_window_s: float  # the peak is searched this long after the threshold crossing
    amp_ref: float  # amplitude for P(A) = 100 % (rad/s; thesis: 0.20)
    length_ref_s: float  # signal length for P(L) = 100 %
    d1_s: float  # first delta taken this long after the peak
    d1_ref: float  # rad/s (thesis: 0.05)
    d2_s: float
    d2_ref: float  # rad/s (thesis: 0.10)
    weights: tuple[float, float, float, float]  # thesis eq. 27: 0.25, 0.10, 0.40, 0.25
    p_min: float  # thesis: 75 %
    max_lobe_s: float  # a lobe is closed after this long even without a sign change


@dataclass
class PelvicState:
    active: bool = False
    sign: float = 0.0
    t_cross: float = 0.0
    peak: float = 0.0
    t_peak: float = 0.0
    pending: list = field(default_factory=list)  # [t_cross, t_end, sign, peak, t_peak, v_d1, v_d2]
    last_t: float = -math.inf


def _prob(value: float, ref: float) -> float:
    return max(0.0, min(1.0, value / ref)) if ref > 0 else 1.0


def pelvic_score(amp: float, length_s: float, d1: float, d2: float, p: PelvicParams) -> float:
    """Thesis eq. 27: P(S) = 0.25 P(A) + 0.10 P(L) + 0.40 P(D1) + 0.25 P(D2), each P = min(1, x/x_ref)."""
    wa, wl, w1, w2 = p.weights
    return (wa * _prob(amp, p.amp_ref) + wl * _prob(length_s, p.length_ref_s)
            + w1 * _prob(d1, p.d1_ref) + w2 * _prob(d2, p.d2_ref))


def pelvic_kernel(t: np.ndarray, w: np.ndarray, state: PelvicState,
                  p: PelvicParams) -> tuple[list[Event], PelvicState]:
    """Lobes of the filtered vertical (yaw) rate ``w``: a lobe opens when ``|w|`` exceeds the threshold,
    its peak is the largest ``sign * w`` within ``peak_window_s`` of the crossing, and it closes at the
    sign change (or ``max_lobe_s``). Once ``d2_s`` has passed after the peak its features are scored
    with eq. 27 and the lobe is a step when P(S) > ``p_min``. Event = the peak time; the ``side`` column
    is ``left`` for positive and ``right`` for negative lobes (thesis ch.5.3)."""
    out: list[Event] = []
    s = state
    for ti, wi in zip(values(t), values(w), strict=True):  # decision E195
        s.last_t = ti
        # fill the delta samples of lobes waiting for their look-ahead
        for c in s.pending:
            if c[5] is None and ti >= c[4] + p.d1_s:
                c[5] = c[2] * wi
            if c[6] is None and ti >= c[4] + p.d2_s:
                c[6] = c[2] * wi
        while s.pending and s.pending[0][6] is not None and s.pending[0][1] is not None:
            out.extend(_pelvic_decide(s.pending.pop(0), p))
        if s.active:
            v = s.sign * wi
            if v > s.peak and ti - s.t_cross <= p.peak_window_s:
                s.peak, s.t_peak = v, ti
                s.pending[-1][3], s.pending[-1][4] = v, ti
                s.pending[-1][5] = s.pending[-1][6] = None
            if v <= 0 or ti - s.t_cross >= p.max_lobe_s:
                s.active = False
                s.pending[-1][1] = ti
        if not s.active and abs(wi) > p.threshold:
            s.active, s.sign, s.t_cross = True, (1.0 if wi > 0 else -1.0), ti
            s.peak, s.t_peak = abs(wi), ti
            s.pending.append([ti, None, s.sign, abs(wi), ti, None, None])
    return out, s


def _pelvic_decide(c: list, p: PelvicParams) -> list[Event]:
    t_cross, t_end, sign, peak, t_peak, v1, v2 = c
    if t_end is None:
        t_end = t_peak
    d1 = peak - v1 if v1 is not None else 0.0
    d2 = peak - v2 if v2 is not None else 0.0
    prob = pelvic_score(peak, t_end - t_cross, d1, d2, p)
    if prob > p.p_min:
        side = "left" if sign > 0 else "right"
        return [(t_peak, t_cross, t_end, prob, {"side": side, "amplitude": peak})]
    return []


def pelvic_flush(state: PelvicState, p: PelvicParams) -> list[Event]:
    """Score lobes still waiting at the end of the signal with the samples available."""
    out: list[Event] = []
    for c in state.pending:
        if c[1] is None:
            c[1] = state.last_t
        out.extend(_pelvic_decide(c, p))
    state.pending = []
    return out


# ---------------------------------------------------------------------------------------------------
# phase-locked loop on vertical acceleration (seed 000 Sec. II-C, seed 001 Sec. 2.2.2)
#: decision W356: a gated run's first / last PLL peak counts only within this phase error (deg) when ``edge_lock`` is
#: on -- W345's printed split (97 % of the walk's matched contacts within it, 5 % of its trailing edge extras)
EDGE_LOCK_DEG = 45.0
#: decision W358: the values of the detector's ``edge_lock`` (``pll_edge_lock``): off, both edges of a gated run judged
#: (True, the same as "both"; W356), or only its trailing edge, its last peak (W345: 5 % of the trailing edge extras
#: locked, but true first contacts often unlocked); W367: "walk-end", the trailing edge dropped only where the walk
#: ends; W372: "walk-edges", "walk-end" plus the leading edge dropped only where the walk starts after it
EDGE_LOCK_VALUES = (False, True, "both", "trailing", "walk-end", "walk-edges")


@dataclass
class PLLParams:
    f0_hz: float  # free-running frequency (seed 000/001: 1.8 Hz)
    kp: float  # proportional gain (rad/s per unit phase-detector output)
    ki: float  # integral gain (rad/s^2 per unit)
    f_min_hz: float
    f_max_hz: float
    agc_tau_s: float  # time constant of the amplitude normalisation
    gate_window_s: float  # activity window, centred on each peak (seed 001: 4 s)
    gate_var: float  # minimum variance of vertical acceleration (m^2/s^4; seed 001: 1.5)
    refine_frac: float  # event = largest vertical acceleration within +- refine_frac periods of the peak
    # decision W356: a gated run's first / last peak is kept only when |phase error| <= edge_lock_deg (0: off)
    edge_lock_deg: float = 0.0
    # decision W358: False judges only a run's last peak (its trailing edge), its first is kept as without edge lock
    edge_lock_leading: bool = True
    # decision W367: an unlocked last peak is kept when the variance over the stride after it reaches this (0: off)
    walk_end_var: float = 0.0
    # decision W372: an unlocked first peak is kept when the variance over the stride before it reaches this (0: off)
    walk_start_var: float = 0.0


@dataclass
class PLLState:
    theta: float = 0.0
    integ: float = 0.0
    power: float = math.nan
    last_t: float = math.nan
    last_peak_t: float = math.nan
    buf_t: np.ndarray = field(default_factory=lambda: np.zeros(0))
    buf_v: np.ndarray = field(default_factory=lambda: np.zeros(0))
    pending: list = field(default_factory=list)  # [t_peak, freq_hz, previous peak, phase error deg]
    iq: tuple = (0.0, 0.0)  # W345: in-phase / quadrature sums since the last peak
    prev_gated: bool = False  # W356: the last decided peak passed the activity gate
    held: tuple | None = None  # W356: (event, first of its run, kept as first, kept as last), waiting for the next gate


def pll_kernel(t: np.ndarray, v: np.ndarray, state: PLLState, p: PLLParams) -> tuple[list[Event], PLLState]:
    """Second-order PLL (multiplier phase detector + PI loop filter) locked on the vertical acceleration
    ``v`` (gravity removed, m/s^2). Output ``cos(theta)``; a step is each peak of the output
    (theta wraps past 2 pi), accepted when the variance of ``v`` over ``gate_window_s`` centred on the
    peak exceeds ``gate_var`` (seed 001's activity gate). The step frequency is 1 / (time since the
    previous peak) (seed 000: f_k = 1/T_k), or the loop frequency for the first peak."""
    s = state
    if t.size == 0:
        return [], s
    # amplitude normalisation: running mean power, exponential with time constant agc_tau_s
    dt = np.diff(t, prepend=t[0] if s.last_t != s.last_t else s.last_t)
    alpha = np.exp(-dt / p.agc_tau_s)
    vv = v * v
    pw = s.power if s.power == s.power else float(vv[0])
    # decision L177: the recursion in numpy (it was scipy's lfilter([1 - a], [1, -a]) for uniform sampling, the
    # same products and sums: bitwise equal, tests/test_runtime_clocks.py)
    power = np.empty_like(v)
    for i, (ai, qi) in enumerate(zip(alpha.tolist(), vv.tolist(), strict=True)):
        pw = ai * pw + (1.0 - ai) * qi
        power[i] = pw
    s.power = float(power[-1])
    x = np.clip(np.where(power > 1e-12, v / np.sqrt(np.maximum(power, 1e-300)), 0.0), -3.0, 3.0)
    w_min, w_max = 2 * math.pi * p.f_min_hz, 2 * math.pi * p.f_max_hz
    w0 = 2 * math.pi * p.f0_hz
    i_lo, i_hi = w_min - w0, w_max - w0
    two_pi = 2 * math.pi
    theta, integ, last_peak = s.theta, s.integ, s.last_peak_t
    kp, ki = p.kp, p.ki
    sin, cos = math.sin, math.cos
    acc_i, acc_q = s.iq
    for ti, xi, di in zip(values(t), values(x), values(dt), strict=True):  # decision E195
        sth = sin(theta)
        pd = -xi * sth
        acc_i += xi * cos(theta) * di  # decision W345: the period's in-phase / quadrature sums
        acc_q += xi * sth * di
        integ += ki * pd * di
        if integ < i_lo:
            integ = i_lo
        elif integ > i_hi:
            integ = i_hi
        omega = w0 + kp * pd + integ
        if omega < w_min:
            omega = w_min
        elif omega > w_max:
            omega = w_max
        th_prev = theta
        theta += omega * di
        if theta >= two_pi:
            theta -= two_pi
            step = omega * di
            tp = ti - di + ((two_pi - th_prev) / step) * di if step > 0 else ti
            freq = 1.0 / (tp - last_peak) if last_peak == last_peak else omega / two_pi
            s.pending.append([tp, freq, last_peak, phase_error_deg(acc_i, acc_q)])
            acc_i = acc_q = 0.0
            last_peak = tp
    s.theta, s.integ, s.last_peak_t, s.last_t = theta, integ, last_peak, float(t[-1])
    s.iq = (acc_i, acc_q)
    # activity gate and event refinement need the samples up to half a gate window after each peak
    s.buf_t = np.concatenate([np.asarray(s.buf_t, dtype=float), t])
    s.buf_v = np.concatenate([np.asarray(s.buf_v, dtype=float), v])
    half = 0.5 * p.gate_window_s
    n_ready = 0
    while n_ready < len(s.pending) and s.last_t >= s.pending[n_ready][0] + half:
        n_ready += 1
    out = _pll_decide_many(s, s.pending[:n_ready], p)
    del s.pending[:n_ready]
    keep_from = min(s.pending[0][0] if s.pending else s.last_t, s.last_t) - half - 1.0
    k = int(np.searchsorted(s.buf_t, keep_from))
    s.buf_t, s.buf_v = s.buf_t[k:], s.buf_v[k:]
    return out, s


def _segment_sums(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Sum of ``x[lo_i:hi_i]`` for possibly overlapping segments (each reduced on its own)."""
    idx = np.empty(2 * lo.size, dtype=np.intp)
    idx[0::2], idx[1::2] = lo, hi
    xp = np.append(x, 0.0)  # hi may equal len(x)
    return np.add.reduceat(xp, idx)[0::2]


def centred_variance(bt: np.ndarray, bv: np.ndarray, centres: np.ndarray,
                     half: float) -> tuple[np.ndarray, np.ndarray]:
    """Variance of ``bv`` over ``[c - half, c + half]`` for each centre ``c`` (times ``bt``, sorted).

    Returns ``(ok, var)``; ``ok`` is False where the window holds fewer than two samples. Each window is
    reduced on its own, so the result does not depend on how the buffer was filled.
    """
    lo = np.searchsorted(bt, centres - half, side="left")
    hi = np.searchsorted(bt, centres + half, side="right")
    n = hi - lo
    ok = n >= 2
    lo, hi, n = np.where(ok, lo, 0), np.where(ok, hi, 1), np.maximum(n, 1)
    mean = _segment_sums(bv, lo, hi) / n
    return ok, np.maximum(_segment_sums(bv * bv, lo, hi) / n - mean * mean, 0.0)


# ---------------------------------------------------------------------------------------------------
# waist motion gate for events of another detector (decision 23 of docs/decisions/steps.md)
@dataclass
class GateState:
    buf_t: np.ndarray = field(default_factory=lambda: np.zeros(0))
    buf_v: np.ndarray = field(default_factory=lambda: np.zeros(0))
    pending: list = field(default_factory=list)  # events waiting for half a window of samples after them
    last_t: float = -math.inf


def motion_gate_kernel(t: np.ndarray, v: np.ndarray, events: list, state: GateState, window_s: float,
                       var_min: float) -> tuple[list[Event], GateState]:
    """Keep an event when the variance of ``v`` (gravity-removed vertical acceleration) over ``window_s``
    centred on it reaches ``var_min`` (the waist motion gate, seed 000 sec. II-B; decisions 18 and W4).

    ``events`` are the detector's events of this chunk; each is decided once ``window_s / 2`` of samples
    after it has arrived, so chunking does not change the result (``motion_gate_flush`` decides the rest).
    """
    s = state
    if len(t):
        s.buf_t = np.concatenate([s.buf_t, t])
        s.buf_v = np.concatenate([s.buf_v, v])
        s.last_t = float(t[-1])
    s.pending.extend(events)
    half = 0.5 * window_s
    n_ready = 0
    while n_ready < len(s.pending) and s.last_t >= s.pending[n_ready][0] + half:
        n_ready += 1
    out = _gate_decide(s, s.pending[:n_ready], half, var_min)
    del s.pending[:n_ready]
    keep_from = min(min((e[0] for e in s.pending), default=s.last_t), s.last_t) - half - 1.0
    k = int(np.searchsorted(s.buf_t, keep_from))
    s.buf_t, s.buf_v = s.buf_t[k:], s.buf_v[k:]
    return out, s


def _gate_decide(s: GateState, events: list, half: float, var_min: float) -> list[Event]:
    if not events:
        return []
    ok, var = centred_variance(s.buf_t, s.buf_v, np.array([e[0] for e in events]), half)
    return [e for e, good, vi in zip(events, ok.tolist(), var.tolist(), strict=True) if good and vi >= var_min]


def motion_gate_flush(state: GateState, window_s: float, var_min: float) -> list[Event]:
    """Decide the events still waiting for their look-ahead with the samples available."""
    out = _gate_decide(state, sorted(state.pending, key=lambda e: e[0]), 0.5 * window_s, var_min)
    state.pending = []
    return out


def phase_error_deg(i_sum: float, q_sum: float) -> float:
    """Decision W345: the loop's phase error (deg) over one period, ``atan2(Q, I)`` of the sums of its AGC'd input
    times the output's sine (Q) and cosine (I); 0 deg = the output's peak on the input's, the loop locked (seed 000
    Sec. II-C: "the PLL can lock the raw acceleration data a_z"). NaN (never locked) when both sums are 0: a period
    of no input (the AGC's zero below its power floor) has no phase."""
    return math.degrees(math.atan2(q_sum, i_sum)) if (i_sum or q_sum) else math.nan


def _pll_release(s: PLLState, last_of_run: bool, p: PLLParams) -> list[Event]:
    """Decision W356: the held gated peak, kept unless it is the first (W358: only when ``p.edge_lock_leading``) or
    the last of its gated run and unlocked."""
    if s.held is None:
        return []
    ev, first, keep_first, keep_last = s.held
    s.held = None
    return [] if (first and p.edge_lock_leading and not keep_first) or (last_of_run and not keep_last) else [ev]


def walk_goes_on(bt: np.ndarray, bv: np.ndarray, peak: float, freq: float, p: PLLParams, *,
                 before: bool = False) -> bool:
    """Decision W367: the walk goes on after the PLL ``peak``: the variance of ``bv`` over the stride after it,
    ``[peak, peak + min(2 / f, gate_window_s / 2)]`` (one stride = two steps, W47; at most the look-ahead the activity
    gate already waits for, so every chunking has delivered it), reaches ``p.walk_end_var``. W372 (``before``): the
    walk was already going before it, the stride ``[peak - min(2 / f, gate_window_s / 2), peak]`` (within the half
    window the gate reads back) reaching ``p.walk_start_var``. False when off (0)."""
    var_min = p.walk_start_var if before else p.walk_end_var
    if var_min <= 0:
        return False
    w = min(2.0 / max(freq, p.f_min_hz), 0.5 * p.gate_window_s)
    ok, var = centred_variance(bt, bv, np.array([peak - 0.5 * w if before else peak + 0.5 * w]), 0.5 * w)
    return bool(ok[0] and var[0] >= var_min)


def _pll_decide_many(s: PLLState, cands: list, p: PLLParams) -> list[Event]:
    """Activity gate (variance of ``v`` over the window centred on each peak) and event refinement; with
    ``p.edge_lock_deg`` (decision W356) each gated peak waits for the next peak's gate, so that a run's first and
    last peaks are kept only when the loop is locked at them."""
    if not cands:
        return []
    bt, bv = s.buf_t, s.buf_v
    ok, var = centred_variance(bt, bv, np.array([c[0] for c in cands]), 0.5 * p.gate_window_s)
    out: list[Event] = []
    lock = p.edge_lock_deg > 0
    for c, good, vi in zip(cands, ok.tolist(), var.tolist(), strict=True):
        gated = good and vi >= p.gate_var
        if lock:
            out += _pll_release(s, not gated, p)
        first, s.prev_gated = not s.prev_gated, gated
        if not gated:
            continue
        tp, freq, prev, phase = c
        peak = tp
        if p.refine_frac > 0:
            r = p.refine_frac / max(freq, p.f_min_hz)
            a, b = np.searchsorted(bt, tp - r, side="left"), np.searchsorted(bt, tp + r, side="right")
            if b > a:
                tp = float(bt[a + int(np.argmax(bv[a:b]))])
        start = prev if prev == prev and tp - prev < 2.0 / p.f_min_hz else tp - 1.0 / max(freq, p.f_min_hz)
        ev = (tp, start, tp, min(1.0, vi / (2 * p.gate_var)),
              {"step_freq_hz": freq, "pll_peak_s": peak, "phase_err_deg": phase})
        if lock:  # W367 / W372: an unlocked last (first) peak inside a walk that goes on (went on) counts as locked
            locked = abs(phase) <= p.edge_lock_deg
            s.held = (ev, first, locked or walk_goes_on(bt, bv, peak, freq, p, before=True),
                      locked or walk_goes_on(bt, bv, peak, freq, p))
        else:
            out.append(ev)
    return out


def pll_flush(state: PLLState, p: PLLParams) -> list[Event]:
    """Decide the peaks still waiting for their look-ahead with the samples available (W356: the held peak ends its
    run)."""
    out = _pll_decide_many(state, state.pending, p)
    state.pending = []
    return out + _pll_release(state, True, p)


# ---------------------------------------------------------------------------------------------------
# the online processors of the accel, accel-force and PLL detectors (``pdrlearn.steps.detectors``), numpy only
# given their low-pass (decision L177: offline passes scipy's, the lean runtime's clock check :class:`NumpyLowpass`)
class NumpyLowpass:
    """Streaming Butterworth low-pass with state, as :class:`pdrlearn.signal.filters.CausalLowpass` (its sections
    and its steady-state start on the first sample) with :mod:`pdrlearn.kernels.dsp`'s numpy filter (equal to
    rounding: the sections are computed in numpy, the recursion is scipy's)."""

    def __init__(self, cutoff_hz: float, fs: float, *, order: int = 3):
        from pdrlearn.kernels import dsp

        self.sos = dsp.butter_sos(order, cutoff_hz, fs, "low")
        self._zi: list[np.ndarray] | None = None

    def push(self, x: np.ndarray) -> np.ndarray:
        from pdrlearn.kernels import dsp

        a = np.asarray(x, dtype=np.float64)
        if a.shape[0] == 0:
            return a.copy()
        cols = a.reshape(a.shape[0], -1)
        if self._zi is None:
            zi = dsp.sosfilt_zi(self.sos)
            self._zi = [zi * c0 for c0 in cols[0].tolist()]
        out = np.empty_like(cols)
        for j in range(cols.shape[1]):
            out[:, j], self._zi[j] = dsp.sosfilt(self.sos, cols[:, j], self._zi[j])
        return out.reshape(a.shape)


def numpy_delay_s(cutoff_hz: float, fs: float, *, order: int = 3, at_hz: float = 1.0) -> float:
    """Group delay (s) of :class:`NumpyLowpass` at ``at_hz``, as :func:`pdrlearn.signal.filters.lowpass_delay_s`."""
    from pdrlearn.kernels import dsp
    from pdrlearn.kernels.contact import group_delay_s

    b, a = np.ones(1), np.ones(1)
    for sec in dsp.butter_sos(order, cutoff_hz, fs, "low"):
        b, a = np.convolve(b, sec[:3]), np.convolve(a, sec[3:])
    return group_delay_s(b, a, fs, at_hz)


def cutoff_below(cutoff_hz: float, fs: float) -> float:
    """Keep a low-pass cutoff below 0.45 fs so that every detector also runs on low-rate streams."""
    return min(cutoff_hz, 0.45 * fs)


def subsample_of(det) -> bool:
    """Steps decision 32: the detector's ``subsample``, or the module default when None."""
    from pdrlearn.kernels import contact as _contact

    return bool(_contact.SUBSAMPLE if det.subsample is None else det.subsample)


def shift_events(events: list, delay: float) -> list:
    """Move event times back by the causal filter's group delay (start/end windows unchanged)."""
    if not delay:
        return events
    return [(e[0] - delay, e[1], e[2], e[3], e[4]) for e in events]


class GravityTracker:
    """Causal gravity direction from a slow low-pass of the accelerometer (works in any sensor frame)."""

    def __init__(self, fs: float, cutoff_hz: float, lowpass=NumpyLowpass):
        self.lp = lowpass(cutoff_below(cutoff_hz, fs), fs, order=2)

    def push(self, acc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        g = self.lp.push(acc)
        n = magnitude(g)
        n = np.where(n > 1e-6, n, 1.0)
        return g / n[:, None], n


#: a still period that ends a swing needs at least this many samples, whatever min_still_s gives: at
#: 20 Hz one quiet sample in the middle of a slow swing split strides in two (docs/decisions/steps.md)
MIN_STILL_SAMPLES = 2
#: a standard deviation over fewer than 3 samples is no estimate (decision 14)
MIN_STILL_WINDOW_SAMPLES = 3
#: steps decision 37: detections closer than this (s) are one stride of the foot; 0.6 s (decision 3) merged the
#: strides of children at 200+ steps/min (experiments/results/child_strides.md)
MIN_STRIDE_S = 0.4
#: steps decision 88: the offline rhythm cutoff filters the swing's raw |acc| from this long (s) before its first moving
#: sample (a rest; the filter started at its steady state has settled there, as the streamed stride's from its start)
PRE_SWING_S = 0.2


class AccelProcessor:
    """:class:`pdrlearn.steps.AccelStepDetector`'s online detection (thesis ch.5.1) of the settings ``det``."""

    def __init__(self, det, fs: float, lowpass=NumpyLowpass, delay=numpy_delay_s):
        self.det = det
        self.lp = lowpass(cutoff_below(det.cutoff_hz, fs), fs, order=det.order)
        self.lp_event = lowpass(cutoff_below(det.event_cutoff_hz, fs), fs, order=2)
        self.delay = delay(cutoff_below(det.event_cutoff_hz, fs), fs, order=2)
        self.w = max(MIN_STILL_WINDOW_SAMPLES, int(round(det.still_window_s * fs)))
        self.tail: np.ndarray | None = None
        self.state = BurstState()
        # still samples for a quiet time of q seconds: the window's first w - 1 samples are quiet too
        def need(q: float) -> int:
            return max(MIN_STILL_SAMPLES, int(round(q * fs)) - (self.w - 1))
        self.params = BurstParams(
            amp=det.threshold, min_still_n=need(det.min_quiet_s),
            min_dur_s=det.min_swing_s, max_dur_s=det.max_swing_s, min_stride_s=det.min_stride_s,
            rest=det.gravity, peak_frac=det.peak_frac, max_still_n=need(det.max_quiet_s),
            quiet_frac=det.quiet_frac, history=4, window_n=self.w, cap_n=int(round(0.6 * fs)),
            quiet_rank=det.quiet_rank, rests_only=det.rests_only, subsample=subsample_of(det),
            prominence=float(det.peak_prominence),
            short_period_s=det.short_period_s if fs >= det.short_min_rate_hz else 0.0,  # steps decisions 87, 88, 93
            fast_period_s=det.fast_period_s,
            fast_cutoff_hz=det.fast_event_cutoff_hz, event_cutoff_hz=det.event_cutoff_hz, event_delay_s=self.delay,
            pre_n=int(round(PRE_SWING_S * fs)), cluster_s=det.impact_cluster_s,  # steps decision 91
            # steps decision 97: a bundle's detector settings saved before it have no event_power (off)
            max_amp=det.short_max_amp, power=bool(getattr(det, "event_power", False)))  # steps decisions 94, 97
        self.state.need_n = self.params.max_still_n if det.quiet_frac > 0 else self.params.min_still_n

    def process(self, t: np.ndarray, v: np.ndarray) -> list:
        m = magnitude(v)
        a = self.lp.push(m)
        if self.tail is None:
            self.tail = np.full(self.w - 1, m[0])
        mean, std, self.tail = trailing_window_std(m, self.tail, self.w)
        still = (std < self.det.still_std) & (np.abs(mean - self.det.gravity) < self.det.still_level_tol)
        if self.params.power:  # steps decision 97: the RMS envelope, sqrt(low-pass(|acc|^2))
            e = np.sqrt(np.maximum(self.lp_event.push(m * m), 0.0))
        else:
            e = self.lp_event.push(m)
        ev, self.state = burst_kernel(t, a, still, self.state, self.params, e=e, m=m)
        return shift_events(ev, self.delay)

    def flush(self) -> list:
        return shift_events(burst_flush(self.state), self.delay)


class ForceProcessor:
    """:class:`pdrlearn.steps.AccelForceStepDetector`'s online detection (thesis ch.5.2): ``v`` (n, 5) is the
    acceleration and the two forces at its times."""

    def __init__(self, det, fs: float, lowpass=NumpyLowpass, delay=None, tare: bool = True):
        self.det = det
        self.lp = lowpass(cutoff_below(det.cutoff_hz, fs), fs, order=det.order)
        self.state = ForceState()
        self.tare = TareState() if tare else None  # steps decision 73: B284's tare, causal
        self.offset_ = (0.0, 0.0)  # steps decision 73: the largest offsets subtracted so far (heel, toe)
        self.params = ForceParams(amp=det.threshold, on_frac=det.force_on_frac, off_frac=det.force_off_frac,
                                  min_swing_s=det.min_swing_s, subsample=subsample_of(det),
                                  ref_stances=int(getattr(det, "ref_stances", 0)),
                                  confirm=bool(getattr(det, "confirm", False)))

    def process(self, t: np.ndarray, v: np.ndarray) -> list:
        a = self.lp.push(magnitude(v[:, :3]))
        forces = v[:, 3:5]
        if self.tare is not None:  # steps decision 73: an unloaded offset (raw ADC counts) subtracted
            forces, self.tare = running_tare(t, a, forces, self.tare, amp=self.params.amp,
                                             off_frac=self.params.off_frac)
            self.offset_ = tuple(map(max, self.offset_, self.tare.offset))
        f = forces[:, 0] + forces[:, 1]
        ev, self.state = force_kernel(t, a, f, self.state, self.params)
        return ev

    def flush(self) -> list:
        return []


def pll_params(det, period_s: float = float("nan"), gate_var: float | None = None,
               pelvic_period_s: float = float("nan")) -> PLLParams:
    """The PLL's loop parameters of the settings ``det`` (:meth:`pdrlearn.steps.PLLStepDetector.loop_params`); with
    ``f_max_hz=None`` (decision W117) its free-running frequency and upper clamp from the step period ``period_s``
    (:func:`pdrlearn.kernels.waist.pll_range`; NaN: ``f0_hz`` and 3.2 Hz). ``gate_var``: the activity gate's
    variance when not ``det.gate_var`` (decision steps 48: the session-relative gate found offline).
    ``pelvic_period_s``: the session's pelvic-gyro step period (decision W475: with ``f_max_hz=None``, a walker slower
    than 70 steps/min gets :func:`pdrlearn.kernels.waist.pll_slow_band`'s band instead)."""
    from pdrlearn.kernels.waist import PLL_F0_HZ, pll_range, pll_slow_band

    kd = 1.0 / math.sqrt(2.0)
    wn = 2 * math.pi * det.loop_hz
    f0, f_min, f_max = det.f0_hz, det.f_min_hz, det.f_max_hz
    slow = pll_slow_band(pelvic_period_s) if f_max is None else None
    if slow is not None:  # decision W475
        f0, f_min, f_max = slow[0], min(f_min, slow[1]), slow[2]
    elif f_max is None:
        f0_r, f_max = pll_range(period_s)
        f0 = f0 if f0_r == PLL_F0_HZ else f0_r
    return PLLParams(f0_hz=f0, kp=2 * det.damping * wn / kd, ki=wn * wn / kd,
                     f_min_hz=f_min, f_max_hz=f_max, agc_tau_s=det.agc_tau_s,
                     gate_window_s=det.gate_window_s, gate_var=det.gate_var if gate_var is None else gate_var,
                     refine_frac=det.refine_frac,
                     **edge_lock_params(getattr(det, "edge_lock", False)))


def edge_lock_params(mode) -> dict:
    """:class:`PLLParams`' edge-lock fields of the detector's ``edge_lock`` ``mode`` (one of :data:`EDGE_LOCK_VALUES`;
    decisions W356 / W358 / W367 / W372): True or "both" judges a gated run's first and last peak, "trailing" its last
    only, "walk-end" its last only where the walk ends (the stride after it quieter than W76's floor, W367),
    "walk-edges" also its first only where the walk starts after it (the stride before it that quiet, W372)."""
    if mode not in EDGE_LOCK_VALUES:
        from pdrlearn.errors import DataError

        raise DataError(f"pll edge_lock {mode!r} is not one of false, true, \"both\", \"trailing\", \"walk-end\", "
                        "\"walk-edges\" (decisions W356, W358, W367, W372); fix the detector setting or the "
                        "PARAMS.json option pll_edge_lock")
    from pdrlearn.kernels.waist import RELATIVE_GATE_FLOOR_MPS2  # W367: W76's floor, no gate takes less for walking

    floor = RELATIVE_GATE_FLOOR_MPS2 ** 2
    return {"edge_lock_deg": EDGE_LOCK_DEG if mode else 0.0, "edge_lock_leading": mode not in ("trailing", "walk-end"),
            "walk_end_var": floor if mode in ("walk-end", "walk-edges") else 0.0,
            "walk_start_var": floor if mode == "walk-edges" else 0.0}  # W372: the same floor before the first peak


class PLLProcessor:
    """:class:`pdrlearn.steps.PLLStepDetector`'s online detection (seed 000 Sec. II-C) of the settings ``det``."""

    def __init__(self, det, fs: float, period_s: float = float("nan"), lowpass=NumpyLowpass, delay=numpy_delay_s,
                 gate_var: float | None = None, pelvic_period_s: float = float("nan")):
        self.det = det
        self.grav = GravityTracker(fs, det.gravity_cutoff_hz, lowpass)
        self.lp = lowpass(cutoff_below(det.cutoff_hz, fs), fs, order=2)
        self.delay = delay(cutoff_below(det.cutoff_hz, fs), fs, order=2) if det.refine_frac > 0 else 0.0
        self.state = PLLState()
        self.params = pll_params(det, period_s, gate_var, pelvic_period_s)  # W475: a slow walker's band

    def process(self, t: np.ndarray, v: np.ndarray) -> list:
        up, gnorm = self.grav.push(v)
        vert = self.lp.push(np.einsum("ij,ij->i", v, up) - gnorm)
        ev, self.state = pll_kernel(t, vert, self.state, self.params)
        return shift_events(ev, self.delay)

    def flush(self) -> list:
        return shift_events(pll_flush(self.state, self.params), self.delay)
