"""Pure numerical kernels of the waist-only dead-reckoning pipelines (seeds 000, 001, 003).

Every function is side-effect free, takes arrays along axis 0 = time, rates in Hz, windows in seconds,
and returns new arrays. The classes in :mod:`pdrlearn.waist` hold parameters and results and call these.
numpy only (the filters are :mod:`pdrlearn.kernels.dsp`), so the lean runtime's waist tracker runs the same
functions as ``pdrlearn track`` (decision W92; imported as ``pdrlearn.waist._kernels`` too).
"""

from __future__ import annotations

import functools

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError
from pdrlearn.kernels import dsp
from pdrlearn.kernels.nearest import nearest_distance

# --------------------------------------------------------------------------------------------------
# motion gate (seed 000 sec. II-B)
# --------------------------------------------------------------------------------------------------
GATE_WINDOW_S = 2.0  # seed 000 sec. II-B: standard deviation over the last two seconds
RUN_THRESHOLD_MPS2 = 5.0  # seed 000 sec. II-B: walking/running threshold on sigma_z


def rolling_std(x: np.ndarray, fs: float, *, window_s: float = GATE_WINDOW_S,
                causal: bool = True) -> np.ndarray:
    """Standard deviation of ``x`` over a sliding window of ``window_s`` seconds.

    ``causal=True`` uses the last ``window_s`` seconds (seed 000 sec. II-B, the real-time buffer);
    ``False`` centres the window (offline).
    """
    x = np.asarray(x, dtype=np.float64)
    w = max(3, int(round(window_s * fs)) | 1)  # odd length
    origin = (w - 1) // 2 if causal else 0  # output[i] uses x[i - w + 1 .. i]
    m = dsp.uniform_filter1d(x, w, origin=origin)
    m2 = dsp.uniform_filter1d(x * x, w, origin=origin)
    return np.sqrt(np.maximum(m2 - m * m, 0.0))


def rolling_mean(x: np.ndarray, fs: float, *, window_s: float = GATE_WINDOW_S, causal: bool = True) -> np.ndarray:
    """Mean of ``x`` over the sliding window of :func:`rolling_std` (same length, same causal / centred origin)."""
    x = np.asarray(x, dtype=np.float64)
    w = max(3, int(round(window_s * fs)) | 1)
    return dsp.uniform_filter1d(x, w, origin=(w - 1) // 2 if causal else 0)


def motion_gate(acc_v: np.ndarray, w_z: np.ndarray, fs: float, *, walk_threshold: float, causal: bool = False,
                turn_gate_rps: float | None = None) -> np.ndarray:
    """Samples where the motion state (seed 000 sec. II-B) is walking or running; with ``turn_gate_rps``
    (decision 28 of docs/decisions/steps.md) also where the levelled vertical rate's mean over the same window
    reaches it in absolute value (the pelvis turns: a turn on the spot bounces too little for the std)."""
    gate = motion_state(rolling_std(acc_v, fs, causal=causal), walk_threshold=walk_threshold) > 0
    if turn_gate_rps is not None:
        gate |= np.abs(rolling_mean(w_z, fs, causal=causal)) >= turn_gate_rps
    return gate


def turn_bridge_gate(gate: np.ndarray, w_z: np.ndarray, fs: float, *, max_step_s: float = 1.5) -> np.ndarray:
    """Decision W374: the motion ``gate`` (n,) bool also open over each El-Gohary yaw-rate turn of the levelled vertical
    rate ``w_z`` (n,) rad/s (:func:`pdrlearn.kernels.yaw_turns.yaw_rate_turns`, L210: a turn of at least 45 deg,
    0.5-10 s, its span from the last sample under 5 deg/s before its peak to the first one after) that lies inside a
    walk: the gate is open within ``max_step_s`` (W47's sequence gap, one step at the slowest) before the turn's start
    and within ``max_step_s`` after its end. A turn on the spot between two walks is stepped (the feet carry the
    body round, short steps with a small pelvic bounce, so the 2 s SD gate closes), a turn while standing or sitting
    has no walk on both sides. A new array; the sequence rules still decide which maxima in the span are steps.
    Offline only: the span's end and the walk after it are read ahead."""
    from pdrlearn.kernels.yaw_turns import yaw_rate_turns

    out = np.array(gate, dtype=bool)
    n = out.size
    reach = max(1, int(round(max_step_s * fs)))
    for a, b, *_ in yaw_rate_turns(np.degrees(np.asarray(w_z, dtype=np.float64)), fs):
        a, b = int(a), int(b)
        if gate[max(0, a - reach):a + 1].any() and gate[max(b - 1, 0):min(n, b + reach)].any():
            out[a:b] = True
    return out


#: decision W384: the ``turn_bridge`` value that keeps a contact of the bridged span only where its side alternates
TURN_BRIDGE_SIDE = "side"


def motion_state(sigma_z: np.ndarray, *, walk_threshold: float, run_threshold: float = RUN_THRESHOLD_MPS2
                 ) -> np.ndarray:
    """0 = stopped, 1 = walking, 2 = running from the rolling std of vertical acceleration (m/s^2)."""
    s = np.asarray(sigma_z, dtype=np.float64)
    return (s >= walk_threshold).astype(np.int8) + (s >= run_threshold).astype(np.int8)


#: decision W76 (candidate): the session-relative gate's floor (m/s^2; the rehab trial's workaround, several times
#: the standing noise), fraction of the walking level and the percentile that measures that level
RELATIVE_GATE_FLOOR_MPS2, RELATIVE_GATE_FRACTION, RELATIVE_GATE_PERCENTILE = 0.15, 0.5, 90.0


def relative_walk_threshold(sigma_z: np.ndarray, base: float) -> float:
    """Decision W76's candidate gate: ``min(base, max(floor, fraction x P90(sigma_z)))`` (m/s^2), ``sigma_z`` the
    session's centred 2 s SD of the vertical acceleration. A session walking a tenth of the time or more has its
    walking level at P90; half of it keeps the start and end steps. ``base`` (W4's 0.5) whenever P90 >= 2 base."""
    s = np.asarray(sigma_z, dtype=np.float64)
    s = s[np.isfinite(s)]
    if not s.size:
        return float(base)
    level = float(np.percentile(s, RELATIVE_GATE_PERCENTILE))
    return float(min(base, max(RELATIVE_GATE_FLOOR_MPS2, RELATIVE_GATE_FRACTION * level)))


# --------------------------------------------------------------------------------------------------
# zero-lag FIR filtering and gait events (seed 003 sec. 3.1)
# --------------------------------------------------------------------------------------------------
def fir_taps(cutoff_hz: float, fs: float, order: int) -> np.ndarray:
    """Linear-phase (Hamming) low-pass FIR of ``order`` (``order + 1`` taps, order made even)."""
    nyq = 0.5 * fs
    if not 0 < cutoff_hz < nyq:
        raise DataError(f"FIR low-pass: cutoff {cutoff_hz} Hz must lie in (0, {nyq:g}) Hz at {fs:g} Hz")
    order = max(2, int(order) + (int(order) % 2))
    return _firwin_of(order + 1, float(cutoff_hz), float(fs))


@functools.lru_cache(maxsize=64)
def _firwin_of(numtaps: int, cutoff_hz: float, fs: float) -> np.ndarray:
    """:func:`dsp.firwin_lowpass`, designed once per setting (read-only; E308: the realtime detector, W31, asks the
    same design for every 0.25 s window)."""
    taps = dsp.firwin_lowpass(numtaps, cutoff_hz, fs)
    taps.flags.writeable = False
    return taps


def fir_zero_lag(x: np.ndarray, taps: np.ndarray) -> np.ndarray:
    """Apply a symmetric FIR with its group delay removed (output aligned with the input), edges
    padded by reflection."""
    x = np.asarray(x, dtype=np.float64)
    h = len(taps) // 2
    if x.shape[0] == 0:
        return x.copy()
    xp = np.pad(x, (h, h), mode="reflect" if x.shape[0] > h else "edge")
    return np.convolve(xp, taps, mode="valid")


def fir_causal(x: np.ndarray, taps: np.ndarray) -> np.ndarray:
    """Apply an FIR causally (output delayed by ``(len(taps) - 1) / 2`` samples), started at the first
    sample's steady state."""
    x = np.asarray(x, dtype=np.float64)
    if x.shape[0] == 0:
        return x.copy()
    xp = np.concatenate([np.full(len(taps) - 1, x[0]), x])
    return np.convolve(xp, taps, mode="valid")


def peak_positions(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """Sub-sample positions (float sample indices) of the local maxima ``idx`` of ``x``: the vertex of the parabola
    through each maximum and its two neighbours (quadratic peak interpolation, J. O. Smith, Spectral Audio Signal
    Processing, "Quadratic Interpolation of Spectral Peaks": offset ``0.5 (a - c) / (a - 2b + c)``, within half a
    sample). A maximum at either end, or on a flat top, keeps its sample. Decision W107: W20's same-side pruning times
    the maxima so, to well under a sample whatever the rate (at 50 Hz a sample is 20 ms)."""
    x = np.asarray(x, dtype=np.float64)
    i = np.asarray(idx, dtype=np.int64)
    pos = i.astype(np.float64)
    inner = (i > 0) & (i < x.shape[0] - 1)
    a, b, c = x[i[inner] - 1], x[i[inner]], x[i[inner] + 1]
    den = a - 2.0 * b + c
    off = np.where(den < 0.0, 0.5 * (a - c) / np.where(den < 0.0, den, -1.0), 0.0)
    pos[inner] += np.clip(off, -0.5, 0.5)
    return pos


#: W16: the shortest step (s), and since W113 its cap: a session's own shortest step is never longer
SHORTEST_STEP_S = 0.3
#: W113: a session's shortest step is this fraction of its step period (a priori: 150 steps/min and slower keep W16)
SHORTEST_STEP_FRAC = 0.75
#: W113: the autocorrelation lags (s) searched for the step period (400 down to 40 steps/min)
STEP_PERIOD_LAGS_S = (0.15, 1.5)


def step_period_s(vf: np.ndarray, fs: float, gate: np.ndarray | None = None,
                  lags_s: tuple[float, float] = STEP_PERIOD_LAGS_S) -> float:
    """The step period (s) of a recording's filtered vertical acceleration ``vf`` (decision W113): the lag of the
    first dominant peak of its autocorrelation inside the motion ``gate`` (Moe-Nilssen & Helbostad 2004, J Biomech
    37:121-126: the first dominant peak of the vertical trunk acceleration's autocorrelation is the step, the second
    the stride), "dominant" = a local maximum at least half the largest one in :data:`STEP_PERIOD_LAGS_S`; NaN
    when there is none (no rhythmic motion). ``lags_s``: the lags searched (decision E90 reads a foot's stride
    with longer ones)."""
    x = np.asarray(vf, dtype=np.float64)
    if gate is not None:
        x = np.where(np.asarray(gate, dtype=bool), x, 0.0)
    lo, hi = (int(round(s * fs)) for s in lags_s)
    if x.size <= hi + 2 or not np.any(x):
        return float("nan")
    x = x - np.mean(x[x != 0.0])
    nfft = 1 << int(np.ceil(np.log2(2 * x.size)))
    r = np.fft.irfft(np.abs(np.fft.rfft(x, nfft)) ** 2, nfft)[:hi + 2]
    if r[0] <= 0.0:
        return float("nan")
    seg = r[lo - 1:hi + 2] / r[0]
    peaks = np.flatnonzero((seg[1:-1] > seg[:-2]) & (seg[1:-1] >= seg[2:]) & (seg[1:-1] > 0.0)) + 1
    if peaks.size == 0:
        return float("nan")
    first = peaks[seg[peaks] >= 0.5 * seg[peaks].max()][0]
    return float(lo - 1 + first) / fs


def shortest_step_s(period_s: float) -> float:
    """Decision W113: the shortest step (s) of a walk whose step period is ``period_s``: :data:`SHORTEST_STEP_FRAC`
    of it, capped at W16's :data:`SHORTEST_STEP_S` (also without a period)."""
    return min(SHORTEST_STEP_S, SHORTEST_STEP_FRAC * period_s) if np.isfinite(period_s) else SHORTEST_STEP_S


#: steps decision 6: the PLL's free-running frequency and upper clamp (Hz), today's range at an adult's rhythm
PLL_F0_HZ = 1.8
PLL_F_MAX_HZ = 3.2


def pll_range(period_s: float) -> tuple[float, float]:
    """Decision W117: the PLL's free-running frequency and upper clamp (Hz) for a session whose step period is
    ``period_s`` (:func:`step_period_s`): when the rhythm f_r = 1 / period is faster than :data:`SHORTEST_STEP_FRAC`
    x :data:`PLL_F_MAX_HZ` (2.4 Hz: the clamp leaves less than W113's 1 / 0.75 headroom) the loop free-runs at f_r,
    clamped at f_r / :data:`SHORTEST_STEP_FRAC`; otherwise (and without a period) steps decision 6's 1.8 / 3.2 Hz."""
    if not np.isfinite(period_s) or period_s <= 0.0:
        return PLL_F0_HZ, PLL_F_MAX_HZ
    f_r = 1.0 / period_s
    if f_r <= SHORTEST_STEP_FRAC * PLL_F_MAX_HZ:
        return PLL_F0_HZ, PLL_F_MAX_HZ
    return f_r, f_r / SHORTEST_STEP_FRAC


#: decision W475: a slow walker's PLL band starts here (Hz; trial T2 finding F4's ``f_min_hz``, 18 steps/min)
PLL_SLOW_F_MIN_HZ = 0.3
#: decision W475: the PLL's slow band applies below this pelvic-gyro rhythm (Hz): L95's lowest validated cadence,
#: 70 steps/min (W440's ``SLOW_PERIOD_S``)
PLL_SLOW_BELOW_HZ = 70.0 / 60.0


def pll_slow_band(pelvic_period_s: float, f_max_hz: float | None = None) -> tuple[float, float, float] | None:
    """Decision W475: the PLL's free-running frequency, lower and upper clamp (Hz) for a walker whose pelvic-gyro
    step period (:func:`pdrlearn.waist.pelvic_rhythm.pelvic_step_period_s`) is ``pelvic_period_s``: when its rhythm
    f_g is slower than :data:`PLL_SLOW_BELOW_HZ`, free-running at f_g, clamped to :data:`PLL_SLOW_F_MIN_HZ` ..
    ``f_max_hz`` (None: f_g / :data:`SHORTEST_STEP_FRAC`, so the second harmonic 2 f_g is outside); None otherwise
    (and without a period: W117's range stands)."""
    if not np.isfinite(pelvic_period_s) or pelvic_period_s <= 0.0:
        return None
    f_g = 1.0 / pelvic_period_s
    if f_g >= PLL_SLOW_BELOW_HZ:
        return None
    return f_g, PLL_SLOW_F_MIN_HZ, f_g / SHORTEST_STEP_FRAC if f_max_hz is None else f_max_hz


def mean_gravity_vertical(acc: np.ndarray) -> np.ndarray | None:
    """The vertical acceleration of a raw accelerometer recording (n, 3): its projection on the mean gravity
    direction, mean removed (any mounting frame); None for fewer than 3 samples or a zero mean."""
    a = np.asarray(acc, dtype=np.float64)
    g = a.mean(axis=0) if a.ndim == 2 and a.shape[0] else np.zeros(3)
    if a.shape[0] < 3 or not np.linalg.norm(g) > 0.0:
        return None
    v = a @ (g / np.linalg.norm(g))
    return v - v.mean()


def accel_relative_gate(acc: np.ndarray, fs: float, base: float, *, lowpass=None,
                        window_s: float = GATE_WINDOW_S) -> tuple[float, np.ndarray]:
    """Decision W76's session-relative gate (:func:`relative_walk_threshold`) of a raw accelerometer recording
    (n, 3), for the PLL step detector (decision steps 48): the threshold (m/s^2, at most ``base``) and the centred
    ``window_s`` SD it is judged on, of the mean-gravity vertical acceleration passed through ``lowpass`` (a
    callable on the (n,) signal: the PLL's own input filter, so the SD is the one its activity gate judges)."""
    v = mean_gravity_vertical(acc)
    if v is None:
        return float(base), np.zeros(0)
    sigma = rolling_std(v if lowpass is None else lowpass(v), fs, window_s=window_s, causal=False)
    return relative_walk_threshold(sigma, base), sigma


def accel_step_period_s(acc: np.ndarray, fs: float, *, gate_var: float, gate_window_s: float,
                        cutoff_hz: float = 2.5, fir_order_s: float = 0.3) -> float:
    """W113's :func:`step_period_s` of a raw accelerometer recording (n, 3) for the PLL (decision W117): the vertical
    acceleration on the mean gravity direction, W113's FIR low-pass (as :func:`ic_offline`), inside the PLL's own
    activity gate (variance over ``gate_window_s`` centred > ``gate_var``)."""
    v = mean_gravity_vertical(acc)
    if v is None:
        return float("nan")
    w = max(1, int(round(gate_window_s * fs)))
    kern = np.ones(w) / w
    var = np.convolve(v * v, kern, mode="same") - np.convolve(v, kern, mode="same") ** 2
    vf = fir_zero_lag(v, fir_taps(cutoff_hz, fs, int(round(fir_order_s * fs))))
    return step_period_s(vf, fs, var > gate_var)


def relative_min_gap(ts: np.ndarray, fs: float, max_step_s: float = 1.5) -> int:
    """Decision W113 on contacts already found (sample indices ``ts``, increasing): the shortest step in samples
    from the median spacing of the consecutive ones at most ``max_step_s`` apart (W16's when there are fewer than
    ``RHYTHM_MIN_STEPS - 1`` such spacings)."""
    d = np.diff(np.asarray(ts, dtype=np.float64))
    d = d[d <= max_step_s * fs]
    period = float(np.median(d)) / fs if d.size >= RHYTHM_MIN_STEPS - 1 else float("nan")
    return max(1, int(round(shortest_step_s(period) * fs)))


def ic_offline(acc_v: np.ndarray, acc_ap: np.ndarray, fs: float, *, gate: np.ndarray | None = None,
               cutoff_hz: float = 2.5, fir_order_s: float = 0.3, min_step_s: float | None = None,  # W16, W113
               search_s: float = 0.25, fc_search_s: float = 0.25, min_peak_mps2: float = 0.1,
               rhythm: bool = False, max_step_s: float = 1.5, acc_ml: np.ndarray | None = None,
               unshifted: bool = True, end_steps: bool = False, ap_above_mean: bool = False,
               turning: np.ndarray | None = None, contact_shift: bool = False,
               spinning: np.ndarray | None = None, weak_fill: bool = False, parity: bool | str = False,
               side_at_contact: bool = False, fast_fill: bool = False,
               frozen: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Initial / final contacts from waist acceleration, offline (seed 003 sec. 3.1).

    The vertical acceleration is low-passed with a zero-lag FIR (seed 003: order 30, 2.5 Hz, here the
    order is ``fir_order_s`` seconds of samples so the filter is the same at every rate); each maximum of
    it is one step. The IC is the maximum of the antero-posterior (AP) acceleration immediately before
    the vertical maximum (the last local maximum within ``search_s``, decision W3), the FC the minimum
    of AP acceleration just after it (within ``fc_search_s``).

    Parameters
    ----------
    acc_v : (n,) vertical acceleration without gravity (m/s^2, up positive)
    acc_ap : (n,) antero-posterior acceleration (m/s^2, forward positive)
    fs : rate (Hz)
    gate : (n,) bool, samples where the user moves; vertical maxima outside it are ignored
    min_step_s : the shortest step (s); ``None`` (default) = decision W113's: :func:`shortest_step_s` of the
        :func:`step_period_s` of the filtered vertical acceleration inside ``gate`` (W16's 0.3 s at 150 steps/min and
        slower, shorter for a faster rhythm)
    min_peak_mps2 : a vertical maximum must exceed this (filtered, m/s^2) to be a step
    rhythm : complete the walking sequences with :func:`rhythm_complete` (decision W18)
    max_step_s : maxima further apart than this (s) belong to different walking sequences (``rhythm``)
    acc_ml : (n,) medio-lateral acceleration (m/s^2); with ``rhythm`` the side of each step from it
        (:func:`step_sides`) makes the completed sequences alternate left/right (decision W20)
    unshifted : with ``acc_ml`` and ``rhythm``, drop weak maxima without a weight shift (decision W23)
    end_steps : with ``acc_ml`` and ``rhythm``, one step of gait initiation / termination beyond each
        sequence end on the alternating side (:func:`extend_alternating`, decision W28)
    ap_above_mean : the IC is the last local AP maximum above the AP signal's mean over the motion
        gate's window (``GATE_WINDOW_S``, centred), when the search window holds one (decision W29)
    turning : (n,) bool, samples where the pelvis turns; maxima there are exempt from ``unshifted``
        (decision 29 of docs/decisions/steps.md; ``None`` = none exempt)
    contact_shift : with ``acc_ml`` and ``rhythm``, judge every kept contact once more by W23's test with the side
        read at the initial contact (:func:`unshifted_contacts`, decision W131); contacts flagged in ``spinning``
        (n,) bool, samples where the pelvis turns, are not judged
    weak_fill : with ``acc_ml`` and ``rhythm``, weak steps where the alternation and the local rhythm ask for one
        (``rhythm_complete(weak_fill=True)``, decision W148; off by default)
    parity : with ``acc_ml`` and ``rhythm``, after the sequence rules a contact without a vertical maximum between
        two kept maxima of one decided side about two local periods apart (:func:`parity_fill`, decision W152; off
        by default); ``"within"``: such a contact only where it lies inside one walking sequence of the contacts
        without it (:func:`inside_sequences`, decision W159)
    side_at_contact : with ``acc_ml`` and ``rhythm``, the sequence rules read each candidate maximum's W20 side at its
        initial contact (W3's AP maximum before it, W129's cue) instead of at the maximum (decision W235; off by
        default)
    fast_fill : with ``acc_ml`` and ``rhythm``, after W152 one contact where a gap between two kept contacts has room
        for exactly one step and the vertical acceleration low-passed at twice ``cutoff_hz`` has a maximum of its own
        there (:func:`fast_band_fill`, decision W242; off by default)
    frozen : (n,) bool, samples inside a freeze episode (W213's freeze index); with ``fast_fill`` no W242 contact is
        added at such a sample (decision W255; ``None`` = none frozen)

    Returns
    -------
    ic, fc, vmax : sample indices (int arrays of equal length) of IC, FC and the vertical maximum.
    """
    v = np.asarray(acc_v, dtype=np.float64)
    ap = np.asarray(acc_ap, dtype=np.float64)
    taps = fir_taps(cutoff_hz, fs, int(round(fir_order_s * fs)))  # seed 003 sec. 3.1: order 30, 2.5 Hz
    vf = fir_zero_lag(v - np.mean(v), taps)
    if min_step_s is None:  # decision W113: the shortest step follows the session's own step rhythm
        min_step_s = shortest_step_s(step_period_s(vf, fs, gate))
    dist = max(1, int(round(min_step_s * fs)))
    ws = max(1, int(round(search_s * fs)))
    level = ap_mean_level(ap, fs) if ap_above_mean else None
    if rhythm:  # decision W18: gaps and gate-cut sequence ends completed at the local step period
        cand = dsp.find_peaks(vf, height=0.0, distance=dist)
        strong = vf[cand] >= min_peak_mps2
        if gate is not None:
            strong &= np.asarray(gate, dtype=bool)[cand]
        if not strong.any():  # no accepted maximum: W18-W28 and W148 keep none, W152 / W242 fill only between kept
            none = np.zeros(0, dtype=int)  # ones, so no contact (the result of the rules, without filtering for them)
            return none, none.copy(), cand[:0]
        vl = None if acc_ml is None else lateral_velocity_cached(acc_ml, fs)
        side = None if vl is None else candidate_sides(vl, cand, strong, ap if side_at_contact else None, ws,
                                                       level=level)
        keep = rhythm_complete(cand, vf[cand], strong, fs, min_peak=min_peak_mps2, at=peak_positions(vf, cand),
                               min_step_s=min_step_s, max_step_s=max_step_s, side=side,
                               unshifted=unshifted, end_steps=end_steps,
                               turning=None if turning is None else np.asarray(turning, dtype=bool)[cand],
                               weak_fill=weak_fill)
        peaks = cand[keep]
        if parity and side is not None:  # W152: the missing opposite step of a same-side pair, without a maximum
            added = parity_fill(cand, keep, side, vl, side_scale(vl[cand], strong), fs, max_step_s=max_step_s)
            added = np.setdiff1d(added, peaks)
            peaks = np.union1d(peaks, added)
        if fast_fill and side is not None and FAST_BAND_FACTOR * cutoff_hz < 0.5 * fs:  # W242: a merged step
            filled = _fast_fill(v, vf, cand, keep, side, peaks, vl, strong, fs, cutoff_hz=cutoff_hz,
                                fir_order_s=fir_order_s, min_gap=dist, max_step_s=max_step_s)
            if frozen is not None:  # W255: a 3 Hz trembling separates at 5 Hz; no fill inside a freeze
                filled = filled[~np.asarray(frozen, dtype=bool)[filled]]
            peaks = np.union1d(peaks, filled)
    else:
        peaks = dsp.find_peaks(vf, height=min_peak_mps2, distance=dist)
        if gate is not None:
            peaks = peaks[np.asarray(gate, dtype=bool)[peaks]]
    ic = np.array([_nearest_local_max_before(ap, p, max(0, p - ws), level=level) for p in peaks], dtype=int)
    if contact_shift and rhythm and acc_ml is not None and peaks.size:  # W131: W23 at the contact, every contact
        keep = unshifted_contacts(peaks, vf[peaks], vl[ic], fs, max_step_s=max_step_s,
                                  exempt=None if spinning is None else np.asarray(spinning, dtype=bool)[ic])
        peaks, ic = peaks[keep], ic[keep]
    if parity == "within" and rhythm and acc_ml is not None and peaks.size:  # W159: no contact across a break
        keep = inside_sequences(ic, np.isin(peaks, added), _max_gap(max_step_s, fs))
        peaks, ic = peaks[keep], ic[keep]
    return ic, fc_after(ap, peaks, fs, fc_search_s), peaks


def _fast_fill(v: np.ndarray, vf: np.ndarray, cand: np.ndarray, keep: np.ndarray, side: np.ndarray, peaks: np.ndarray,
               vl: np.ndarray, strong: np.ndarray, fs: float, *, cutoff_hz: float, fir_order_s: float,
               min_gap: int, max_step_s: float) -> np.ndarray:
    """W242 inside :func:`ic_offline`: :func:`fast_band_fill` on the kept contacts ``peaks`` (candidates and W152's
    anchors; an anchor's side read as W20 reads it, at the scale of the candidates), the second band filtered as the
    first (seed 003's FIR, the same order in seconds) at ``FAST_BAND_FACTOR`` x the cut-off. Returns the new anchors."""
    taps = fir_taps(FAST_BAND_FACTOR * cutoff_hz, fs, int(round(fir_order_s * fs)))  # W237: twice seed 003's cut-off
    vf_fast = fir_zero_lag(v - np.mean(v), taps)
    scale = side_scale(vl[cand], strong)  # W20: decided at 1/3 of the median |v| at the accepted candidates
    sd = step_sides(vl[peaks], None, scale=scale)
    is_cand = np.isin(peaks, cand)
    sd[is_cand] = np.asarray(side)[np.searchsorted(cand, peaks[is_cand])]
    ref = float(np.median(vf[cand[keep]])) if np.any(keep) else float("nan")
    added = fast_band_fill(vf_fast, cand, peaks, sd, ref, fs, min_gap=min_gap, max_step_s=max_step_s)
    return np.setdiff1d(added, peaks)


def alternating_bridged(peaks: np.ndarray, sd: np.ndarray, added: np.ndarray, max_gap: int) -> np.ndarray:
    """Decision W384: the mask of the kept contacts ``peaks`` (sample indices, increasing; ``sd`` their W20 sides,
    +1 / -1 / 0) where a contact W374's bridge ``added`` (per contact: not kept without the bridge) stays only when it
    shows the weight shift of a step (W23: a decided side) to the side opposite the previous kept contact's (W20:
    steps alternate feet) -- the previous one within ``max_gap`` samples (W47's sequence gap) and decided; else a
    decided side is enough. The contacts kept without the bridge are never dropped. No new threshold (W20's 1/3)."""
    keep = np.ones(np.asarray(peaks).shape[0], dtype=bool)
    last = -1
    for i in range(keep.size):
        if added[i]:
            near = last >= 0 and peaks[i] - peaks[last] <= max_gap and sd[last] != 0
            if sd[i] == 0 or (near and sd[i] == sd[last]):
                keep[i] = False
                continue
        last = i
    return keep


def candidate_sides(v_lat: np.ndarray, cand: np.ndarray, accepted: np.ndarray, ap: np.ndarray | None = None,
                    search: int = 0, *, level: np.ndarray | None = None) -> np.ndarray:
    """W20's side (+1 / -1 / 0, :func:`step_sides`) of each candidate vertical maximum ``cand`` (sample indices) from
    the pelvis's lateral velocity ``v_lat`` (per sample), decided against the median at the ``accepted`` ones. Read at
    the maximum (W20), or with ``ap`` (the AP acceleration) at the candidate's initial contact, the last AP maximum at
    most ``search`` samples before it (W3, as every contact's IC is found; ``level``: W29's): decision W235, where
    W129 found the side cue agrees best with the foot."""
    cand = np.asarray(cand, dtype=np.int64)
    at = cand if ap is None else np.array([_nearest_local_max_before(ap, p, max(0, p - search), level=level)
                                           for p in cand], dtype=np.int64)
    return step_sides(np.asarray(v_lat, dtype=np.float64)[at], accepted)


def unshifted_contacts(vmax: np.ndarray, height: np.ndarray, v_at_ic: np.ndarray, fs: float, *,
                       max_step_s: float = 1.5, exempt: np.ndarray | None = None) -> np.ndarray:
    """Decision W131: the mask of the kept contacts (their vertical maxima ``vmax``, sample indices, increasing, and
    filtered ``height``) that pass W23's weight-shift test (:func:`drop_unshifted`, unchanged) with the side read at
    the initial contact, as W129 reads it: :func:`step_sides` of the pelvis's lateral velocity there (``v_at_ic``),
    against its median over these contacts. Every contact is judged (W18 fills and W28 end steps too), except
    those flagged in ``exempt`` (the pelvis turns: decision 29's test). A weak bounce at a contact where the pelvis
    moves to neither side is a weight shift of standing, no step."""
    n = np.asarray(vmax).shape[0]
    every = np.ones(n, dtype=bool)
    side = step_sides(v_at_ic, every)
    return drop_unshifted(vmax, height, every, every, side, fs, max_step_s=max_step_s, exempt=exempt)


def contacts_offline(acc_v: np.ndarray, acc_ap: np.ndarray, acc_ml: np.ndarray, w_z: np.ndarray, fs: float, *,
                     walk_threshold: float, cutoff_hz: float = 2.5, fir_order_s: float = 0.3,
                     ap_cutoff_hz: float = 20.0, rhythm: bool = True, max_step_s: float = 1.5,
                     alternate: bool = True, weight_shift: bool = True, end_steps: bool = True,
                     ap_above_mean: bool = False, turn_gate_rps: float | None = None,
                     turn_shift_rps: float | None = None, min_step_s: float | None = None,
                     contact_shift: bool = False, weak_fill: bool = False, parity_fill: bool | str = False,
                     side_at_contact: bool = False, fast_fill: bool = False, frozen: np.ndarray | None = None,
                     with_ap: bool = True, turn_bridge: bool | str = False
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """The offline IC detector's rule contacts on navigation-frame arrays (the body of
    :meth:`pdrlearn.waist.events.InitialContactDetector._offline`, without the W33 learned stage): the motion gate,
    the AP acceleration low-passed at ``min(ap_cutoff_hz, 0.4 fs)`` (zero-phase third-order Butterworth, as
    :func:`pdrlearn.signal.lowpass`), then :func:`ic_offline`. Returns ``(ic, fc, vmax, ap)`` (``ap`` the filtered
    AP acceleration the learned stage reads); ``frozen`` as :func:`ic_offline`'s (decision W255). Without
    ``with_ap`` a window whose motion gate is closed throughout returns no contacts and ``ap`` None without filtering
    (:func:`ic_offline` keeps only maxima inside the gate, and its sequence rules add contacts only around kept ones:
    the same empty result, for the realtime detector's windows of a long rest, W31). ``turn_bridge``: the gate also
    open over a yaw-rate turn inside a walk (:func:`turn_bridge_gate`, decision W374; off by default); ``"side"``
    (:data:`TURN_BRIDGE_SIDE`): and a contact the bridge adds only where its W20 side is decided and alternates
    (decision W384)."""
    gate = motion_gate(acc_v, w_z, fs, walk_threshold=walk_threshold, causal=False, turn_gate_rps=turn_gate_rps)
    if turn_bridge == TURN_BRIDGE_SIDE:  # W384: the contacts without the bridge, and the bridge's that alternate
        kw = dict(walk_threshold=walk_threshold, cutoff_hz=cutoff_hz, fir_order_s=fir_order_s,
                  ap_cutoff_hz=ap_cutoff_hz, rhythm=rhythm, max_step_s=max_step_s, alternate=alternate,
                  weight_shift=weight_shift, end_steps=end_steps, ap_above_mean=ap_above_mean,
                  turn_gate_rps=turn_gate_rps, turn_shift_rps=turn_shift_rps, min_step_s=min_step_s,
                  contact_shift=contact_shift, weak_fill=weak_fill, parity_fill=parity_fill,
                  side_at_contact=side_at_contact, fast_fill=fast_fill, frozen=frozen, with_ap=with_ap)
        off = contacts_offline(acc_v, acc_ap, acc_ml, w_z, fs, **kw)
        on = contacts_offline(acc_v, acc_ap, acc_ml, w_z, fs, turn_bridge=True, **kw)
        return bridge_additions(off, on, lateral_velocity_cached(acc_ml, fs), fs, max_step_s=max_step_s,
                                min_step_s=SHORTEST_STEP_S if min_step_s is None else min_step_s)
    if turn_bridge:  # W374: a turn on the spot between two walks is stepped
        gate = turn_bridge_gate(gate, w_z, fs, max_step_s=max_step_s)
    if not with_ap and not gate.any():
        fir_taps(cutoff_hz, fs, int(round(fir_order_s * fs)))  # ic_offline's check of the cut-off, as before
        none = np.zeros(0, dtype=int)
        return none, none.copy(), none.copy(), None
    ap = dsp.lowpass(acc_ap, min(ap_cutoff_hz, 0.4 * fs), fs)
    yaw_rate = np.abs(rolling_mean(w_z, fs, causal=False)) if (turn_shift_rps is not None or contact_shift) else None
    turning = None if turn_shift_rps is None else yaw_rate >= turn_shift_rps  # decision 29: W23 off in turns
    ic, fc, vmax = ic_offline(acc_v, ap, fs, gate=gate, cutoff_hz=cutoff_hz, fir_order_s=fir_order_s, rhythm=rhythm,
                              max_step_s=max_step_s, acc_ml=acc_ml if alternate else None, unshifted=weight_shift,
                              end_steps=end_steps, ap_above_mean=ap_above_mean, turning=turning,
                              min_step_s=min_step_s, contact_shift=contact_shift,
                              spinning=None if yaw_rate is None else yaw_rate >= CONTACT_SHIFT_TURN_RPS,
                              weak_fill=weak_fill, parity=parity_fill, side_at_contact=side_at_contact,
                              fast_fill=fast_fill, frozen=frozen)
    return ic, fc, vmax, ap


def bridge_additions(off: tuple, on: tuple, v_lat: np.ndarray, fs: float, *, max_step_s: float = 1.5,
                     min_step_s: float = SHORTEST_STEP_S) -> tuple:
    """Decision W384 (``turn_bridge="side"``): the contacts ``off`` (``(ic, fc, vmax, ap)`` of
    :func:`contacts_offline` without W374's bridge) and those of ``on`` (with it) that the bridge adds -- more than
    ``min_step_s`` (W16's shortest step) from every ``off`` maximum -- and that pass :func:`alternating_bridged` in
    the merged sequence: the side read from the pelvis's lateral velocity ``v_lat`` at the vertical maximum (W20),
    at the scale of the ``off`` contacts. The bridge only adds steps; the ones it adds show the weight shift of a
    step to the other foot. Returns ``(ic, fc, vmax, ap)``, ``ap`` as ``on``'s."""
    ic0, fc0, vm0 = (np.asarray(x, dtype=int) for x in off[:3])
    ic1, fc1, vm1 = (np.asarray(x, dtype=int) for x in on[:3])
    gap = max(1, int(round(min_step_s * fs)))
    if vm0.size:
        near = nearest_distance(vm1, vm0) <= gap  # decision L546: no contacts x contacts matrix
    else:
        near = np.zeros(vm1.size, dtype=bool)
    ic = np.concatenate([ic0, ic1[~near]])
    fc = np.concatenate([fc0, fc1[~near]])
    vm = np.concatenate([vm0, vm1[~near]])
    added = np.r_[np.zeros(vm0.size, dtype=bool), np.ones(int((~near).sum()), dtype=bool)]
    order = np.argsort(vm, kind="stable")
    ic, fc, vm, added = ic[order], fc[order], vm[order], added[order]
    v = np.asarray(v_lat, dtype=np.float64)
    sd = step_sides(v[vm], ~added)  # W20: decided at 1/3 of the median |v| at the contacts found without the bridge
    keep = alternating_bridged(vm, sd, added, _max_gap(max_step_s, fs))
    return ic[keep], fc[keep], vm[keep], on[3]


def contact_rows(ts: np.ndarray, max_step_s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(end_s, has_next, confidence)`` of the contacts at times ``ts`` (s, increasing): a step ends at the next
    contact when it follows within ``max_step_s``; else the contact closes its walking sequence (``end_s`` = its
    own time, confidence 0.5); the rows of :func:`pdrlearn.waist.events.steps_from_events`."""
    ts = np.asarray(ts, dtype=np.float64)
    nxt = np.append(ts[1:], np.inf)
    has_next = (nxt - ts) <= max_step_s
    return np.where(has_next, nxt, ts), has_next, np.where(has_next, 1.0, 0.5)


def fc_after(acc_ap: np.ndarray, peaks: np.ndarray, fs: float, fc_search_s: float = 0.25) -> np.ndarray:
    """Final contacts (sample indices): the minimum of AP acceleration within ``fc_search_s`` after each
    vertical maximum in ``peaks`` (seed 003 sec. 3.1; the offline detector and its learned stage, W33)."""
    wf = max(1, int(round(fc_search_s * fs)))
    return np.array([p + int(np.argmin(acc_ap[p:min(len(acc_ap), p + wf + 1)])) for p in peaks], dtype=int)


RHYTHM_TOL = 0.35  # a filled maximum lies within +-35 % of a step period of its predicted time (W18)
RHYTHM_MIN_STEPS = 3  # a local step period needs at least this many contacts of the sequence (W18)
RHYTHM_GAP = 1.5  # an interval over this many local periods should hold a missed step (W18; W111's pause)
SIDE_BAND_HZ = (0.3, 3.0)  # W20: holds the stride frequency of walking (0.5-1.7 Hz), drops turns/drift
SIDE_MIN_FRAC = 1.0 / 3.0  # W20: a side is decided when |v_ml| >= 1/3 of its median at the steps
PRUNE_HEIGHT_FRAC = 0.5  # W20: of a same-side pair only a maximum under half the other's height goes
#: W131: a contact where the pelvis's centred 2 s mean yaw rate reaches this (rad/s) is not judged by W23 at the
#: contact -- decision 29's turning test (docs/decisions/steps.md), decision 28's turning component of W7's mixture
CONTACT_SHIFT_TURN_RPS = 0.45
#: decision W129: the side labels for W20's +1 / -1 / 0 (undecided); a priori, v > 0 (towards the left) = left foot
SIDE_LABELS = {1: "left", -1: "right", 0: ""}


def lateral_velocity(acc_ml: np.ndarray, fs: float, *, band_hz: tuple[float, float] = SIDE_BAND_HZ
                     ) -> np.ndarray:
    """Medio-lateral velocity of the pelvis (m/s; zero-phase, offline), from the ML acceleration
    band-passed to the stride band, integrated and high-passed again (integration drift removed).

    The pelvis sways towards the stance foot once per stride, so at the initial contacts its lateral
    velocity has one sign for left and the other for right steps (decision W20). Zeros for inputs too
    short to filter (< 32 samples).
    """
    a = np.asarray(acc_ml, dtype=np.float64)
    if a.shape[0] < 32:
        return np.zeros_like(a)
    lo, hi = float(band_hz[0]), float(min(band_hz[1], 0.45 * fs))
    v = np.cumsum(dsp.sosfiltfilt(_butter2(lo, hi, "bandpass", float(fs)), a)) / fs
    return dsp.sosfiltfilt(_butter2(lo, None, "high", float(fs)), v)


def lateral_velocity_cached(acc_ml: np.ndarray, fs: float) -> np.ndarray:
    """:func:`lateral_velocity` (default band) as a read-only array, kept for the last few inputs (keyed by their
    bytes: the same samples give the same floats; the same ``functools.lru_cache`` by bytes as ``dsp``'s filter
    start state). The realtime detector (W31) reads W20's velocity of a decision window inside the rules and again
    for W138's side of the contacts decided there (``waist_stream``)."""
    a = np.ascontiguousarray(acc_ml, dtype=np.float64)
    return _lateral_velocity_of(float(fs), a.shape, a.tobytes())


@functools.lru_cache(maxsize=32)
def _lateral_velocity_of(fs: float, shape: tuple, data: bytes) -> np.ndarray:
    v = lateral_velocity(np.frombuffer(data, dtype=np.float64).reshape(shape), fs)
    v.flags.writeable = False
    return v


@functools.lru_cache(maxsize=32)
def _butter2(lo: float, hi: float | None, btype: str, fs: float) -> np.ndarray:
    """Second-order Butterworth sections, designed once per setting (callers take a copy): the realtime
    detector (W31) filters a window every 0.25 s, and the design cost as much as the filtering (W43)."""
    return dsp.butter_sos(2, lo if hi is None else (lo, hi), fs, btype)


def step_sides(v_at: np.ndarray, accepted: np.ndarray | None, *, min_frac: float = SIDE_MIN_FRAC,
               scale: float | None = None) -> np.ndarray:
    """Side of each candidate step (+1 / -1; 0 = undecided) from the pelvis's lateral velocity at it
    (:func:`lateral_velocity`, decision W20). Decided where ``|v| >= min_frac`` x the median ``|v|`` of
    the ``accepted`` steps (the signal's own scale; ``scale``, when given, is that median read elsewhere - W242's
    anchors at the candidates' scale). Which sign is the left foot depends on the mounting
    and does not matter: only equal vs opposite sides are used."""
    v = np.asarray(v_at, dtype=np.float64)
    scale = side_scale(v, accepted) if scale is None else float(scale)
    if scale <= 0.0:
        return np.zeros(v.shape[0], dtype=np.int8)
    return np.where(np.abs(v) >= min_frac * scale, np.sign(v), 0.0).astype(np.int8)


def side_scale(v_at: np.ndarray, accepted: np.ndarray) -> float:
    """W20's scale of the lateral velocity: its median ``|v|`` at the ``accepted`` steps (0 when there is none)."""
    v = np.asarray(v_at, dtype=np.float64)
    acc = np.asarray(accepted, dtype=bool)
    scale = float(np.median(np.abs(v[acc]))) if acc.any() else 0.0
    return scale if np.isfinite(scale) and scale > 0.0 else 0.0


def _max_gap(max_step_s: float, fs: float) -> int:
    """Decision W32: the longest step inside a sequence in whole samples, ``round(max_step_s * fs)``
    (as W28 made the shortest one): two maxima exactly ``max_step_s`` apart stay in one sequence whether
    the rate estimate is a hair under or over its nominal value (100 Hz from timestamps: 100.000000000002)."""
    return int(round(max_step_s * fs))


def _local_period(t: np.ndarray, k: int, side: int, max_gap: float, n: int = 3) -> float:
    """Median of up to ``n`` step intervals of the sequence on ``side`` (-1 before, +1 after) of
    accepted maximum ``k`` (times ``t`` in samples, an array or a list of floats: E308, the same values);
    NaN when fewer than ``RHYTHM_MIN_STEPS - 1``."""
    iv = []
    j = k
    while len(iv) < n:
        j2 = j + side
        if j2 < 0 or j2 >= len(t) or abs(t[j2] - t[j]) > max_gap:
            break
        iv.append(abs(t[j2] - t[j]))
        j = j2
    return _median_few(iv) if len(iv) >= RHYTHM_MIN_STEPS - 1 else float("nan")


def _median_few(x: list) -> float:
    """``float(np.median(x))`` of a few numbers, without numpy's per-call cost (the rhythm rules ask it once per
    contact and side in every 0.25 s window of the realtime detector, W31): the middle one, or the mean of the two
    middle ones as numpy takes it (``(a + b) / 2``); numpy's own where one is NaN."""
    if any(v != v for v in x):
        return float(np.median(x))
    s = sorted(x)
    m = len(s) // 2
    return float(s[m]) if len(s) % 2 else float((s[m - 1] + s[m]) / 2)


def _nanmedian_few(x: list) -> float:
    """``float(np.nanmedian(x))`` of a few numbers: :func:`_median_few` of the ones that are not NaN (NaN when
    none is; E308: the rhythm rules ask it once per contact pair in every 0.25 s window of the realtime detector)."""
    v = [a for a in x if a == a]
    return _median_few(v) if v else float("nan")


def _period_around(t: np.ndarray, k: int, max_gap: float) -> float:
    """Local step period at accepted maximum ``k``: median of the periods before and after it."""
    p = [x for x in (_local_period(t, k, -1, max_gap), _local_period(t, k, +1, max_gap)) if np.isfinite(x)]
    return _median_few(p) if p else float("nan")


def _missing_steps(ratio: float, side_a: int, side_b: int) -> int:
    """Steps missing in a gap of ``ratio`` local periods between two contacts. Sides unknown (0): the
    nearest count, ``round(ratio) - 1`` (W18). Both sides known: that count only if its parity agrees
    with alternation -- odd between equal sides, even between opposite ones (W20) -- else 0 (no count
    of the right parity lies within half a period of the gap)."""
    m = int(round(ratio)) - 1
    if m < 1:
        return 0
    if side_a == 0 or side_b == 0:
        return m
    return m if (m % 2 == 1) == (side_a == side_b) else 0


def prune_same_side(cand: np.ndarray, height: np.ndarray, accepted: np.ndarray, side: np.ndarray,
                    fs: float, *, max_step_s: float = 1.5) -> np.ndarray:
    """Drop the weaker of two consecutive accepted maxima that lie on the same side and closer than
    1.5 local step periods when it is under ``PRUNE_HEIGHT_FRAC`` of the other's height (decision W20):
    steps alternate left/right, and a same-side pair too close to hold the missing opposite step between
    them contains a maximum that is no step (a pelvic bounce inside a long swing). Pairs of similar
    height (a side read wrongly is likelier) and maxima with an undecided side (0) are left alone.
    Returns the new mask."""
    cand = np.asarray(cand, dtype=np.float64)  # sample positions, whole or sub-sample (W107)
    h = np.asarray(height, dtype=np.float64)
    keep = np.asarray(accepted, dtype=bool).copy()
    acc = np.flatnonzero(keep)
    t = cand[acc].astype(np.float64)
    max_gap = _max_gap(max_step_s, fs)
    last = -1
    for k, i in enumerate(acc):
        if last >= 0 and side[i] != 0 and side[i] == side[last] and cand[i] - cand[last] <= max_gap:
            per = _period_around(t, k, max_gap)
            lo_h, hi_h = sorted((h[i], h[last]))
            if np.isfinite(per) and cand[i] - cand[last] < 1.5 * per and lo_h < PRUNE_HEIGHT_FRAC * hi_h:
                drop = i if h[i] < h[last] else last
                keep[drop] = False
                last = last if drop == i else i
                continue
        last = i
    return keep


def drop_unshifted(cand: np.ndarray, height: np.ndarray, keep: np.ndarray, accepted: np.ndarray,
                   side: np.ndarray, fs: float, *, max_step_s: float = 1.5, n_neighbours: int = 2,
                   exempt: np.ndarray | None = None) -> np.ndarray:
    """Drop a maximum that shows neither cue of a step (decision W23): accepted by the fixed height
    threshold only (not a W18 rhythm fill), no weight shift (undecided side: the pelvis's lateral velocity
    under a third of its typical value, W20), and under ``PRUNE_HEIGHT_FRAC`` of the median height of its
    walking-sequence neighbours (up to ``n_neighbours`` kept maxima on each side, consecutive maxima at
    most ``max_step_s`` apart). Every step moves the body's weight from one foot to the other, so a weak
    vertical bounce without that lateral shift is no step (a bounce inside a slow step, a postural move).
    Decided on the mask as given (order-independent). Maxima flagged in ``exempt`` are not judged (decision 29
    of docs/decisions/steps.md: the pelvis turns there). Returns the new mask."""
    cand = np.asarray(cand, dtype=np.int64)
    h = np.asarray(height, dtype=np.float64)
    keep = np.asarray(keep, dtype=bool)
    out = keep.copy()
    sel = np.flatnonzero(keep)
    t = cand[sel]
    max_gap = _max_gap(max_step_s, fs)
    for j, c in enumerate(sel):
        if side[c] != 0 or not accepted[c] or (exempt is not None and exempt[c]):
            continue
        nb = []
        for step in (-1, 1):
            i = j
            while len([x for x in nb if (x > j) == (step > 0)]) < n_neighbours:
                nxt = i + step
                if nxt < 0 or nxt >= sel.size or abs(t[nxt] - t[i]) > max_gap:
                    break
                nb.append(nxt)
                i = nxt
        if nb and h[c] < PRUNE_HEIGHT_FRAC * _median_few(h[sel[nb]].tolist()):  # E308: np.median's value
            out[c] = False
    return out


def extend_alternating(cand: np.ndarray, height: np.ndarray, keep: np.ndarray, side: np.ndarray, fs: float, *,
                       min_peak: float, max_step_s: float = 1.5, tol: float = RHYTHM_TOL,
                       weak: bool = False) -> np.ndarray:
    """One step of gait initiation / termination beyond each end of a walking sequence (decision W28).

    W18 extends a sequence by one step at its own rhythm (one local period +- ``tol``). The first and
    last steps of a walk are slower than its rhythm and fall where the 2 s motion gate is closed, so
    here the evidence is the alternation instead (W20): beyond each end of a sequence of at least
    ``RHYTHM_MIN_STEPS`` kept maxima whose end contact has a decided side, the nearest candidate of full
    height (``>= min_peak``) on the decided *opposite* side between ``1 - tol`` local periods and
    ``max_step_s`` (the longest step inside a sequence, W16) from the end is added. One step per end and
    one pass: it does not chain. With ``weak`` (decision W148), an end where no such candidate lies takes the
    highest positive candidate on the opposite side one local period (``+- tol``) beyond it instead (the height
    floor W18's interior fills use; the rhythm replaces the height as the evidence). Returns the new mask."""
    cand = np.asarray(cand, dtype=np.int64)
    h = np.asarray(height, dtype=np.float64)
    sd = np.asarray(side)
    keep = np.asarray(keep, dtype=bool)
    out = keep.copy()
    sel = np.flatnonzero(keep)
    max_gap = _max_gap(max_step_s, fs)
    breaks = np.flatnonzero(np.diff(cand[sel]) > max_gap) + 1
    for sq in np.split(sel, breaks):
        if sq.size < RHYTHM_MIN_STEPS:
            continue
        t = cand[sq].astype(np.float64)
        for end, direction in ((sq.size - 1, 1), (0, -1)):
            s_end = int(sd[sq[end]])
            per = _local_period(t, end, -direction, max_gap)
            if s_end == 0 or not np.isfinite(per):
                continue
            near, far = t[end] + direction * (1.0 - tol) * per, t[end] + direction * max_gap
            lo, hi = min(near, far), max(near, far)
            idx = [i for i in range(np.searchsorted(cand, lo), np.searchsorted(cand, hi, side="right"))
                   if not out[i] and h[i] >= min_peak and int(sd[i]) == -s_end]
            if idx:
                out[min(idx, key=lambda i: abs(cand[i] - t[end]))] = True
            elif weak:  # W148: no full-height step: a weak one on the alternating side, at the local rhythm
                i = _weak_candidate(cand, h, out, sd, -s_end, [t[end] + direction * per], per, tol)
                if i is not None:
                    out[i] = True
    return out


def _one_step_gaps(pos: np.ndarray, sd: np.ndarray, max_gap: int, tol: float, *, same_side: bool = True):
    """Decisions W148 / W152 / W242: each pair of consecutive kept contacts (``pos`` sample positions, increasing, their
    W20 sides ``sd``) at most ``max_gap`` samples apart that may miss one step between them, with the local period
    ``per`` around it (W18: the median of the pair's outer periods) and the window ``(lo, hi)`` (samples) of a step one
    period (``+- tol`` periods) after the first AND one before the second (non-empty only for a gap of about two
    periods). ``same_side``: only pairs on one decided side (W148 / W152: the alternation asks for the step); else
    every pair except one on decided opposite sides (W242: one missing step would leave both on one side).
    Yields ``(k, side, per, lo, hi)`` (``k`` the pair's first index in ``pos``, ``side`` its side)."""
    t = np.asarray(pos, dtype=np.float64)
    for k in range(t.size - 1):
        s_k, s_n = int(sd[k]), int(sd[k + 1])
        if t[k + 1] - t[k] > max_gap:
            continue
        if (s_k == 0 or s_n != s_k) if same_side else s_k * s_n < 0:
            continue
        per = _nanmedian_few([_local_period(t, k, -1, max_gap), _local_period(t, k + 1, +1, max_gap)])  # E308
        if per != per:
            continue
        a1, a2 = t[k] + per, t[k + 1] - per  # the predicted times; W18's +-tol around both
        lo, hi = max(a1, a2) - tol * per, min(a1, a2) + tol * per
        if lo <= hi:
            yield k, s_k, per, lo, hi


def _same_side_pairs(cand: np.ndarray, keep: np.ndarray, sd: np.ndarray, max_gap: int, tol: float):
    """Decisions W148 / W152: :func:`_one_step_gaps` of the kept candidates (``cand`` sample positions, ``keep``
    mask) on one decided side ``sd`` (W20: the alternation is broken, one opposite step is missing). Yields
    ``(side, per, lo, hi)``; a pair without a local period or with an empty window is skipped."""
    sel = np.flatnonzero(keep)
    for _k, s_k, per, lo, hi in _one_step_gaps(cand[sel], np.asarray(sd)[sel], max_gap, tol):
        yield s_k, per, lo, hi


def _weak_candidate(cand: np.ndarray, h: np.ndarray, keep: np.ndarray, sd: np.ndarray, want: int,
                    anchors: list[float], per: float, tol: float) -> int | None:
    """Decision W148: the highest positive (W18's interior floor) candidate not in ``keep`` whose decided side is
    ``want`` and which lies within ``tol`` local periods ``per`` of every predicted time in ``anchors`` (samples)."""
    lo, hi = max(anchors) - tol * per, min(anchors) + tol * per
    return _weak_in(cand, h, keep, sd, want, lo, hi)


def _weak_in(cand: np.ndarray, h: np.ndarray, keep: np.ndarray, sd: np.ndarray, want: int, lo: float,
             hi: float) -> int | None:
    """The highest positive candidate not in ``keep`` on decided side ``want`` with position in ``[lo, hi]``."""
    idx = [i for i in range(np.searchsorted(cand, lo), np.searchsorted(cand, hi, side="right"))
           if not keep[i] and h[i] > 0.0 and int(sd[i]) == want]
    return max(idx, key=lambda i: h[i]) if idx else None


def fill_weak_alternating(cand: np.ndarray, height: np.ndarray, keep: np.ndarray, side: np.ndarray, fs: float, *,
                          max_step_s: float = 1.5, tol: float = RHYTHM_TOL) -> np.ndarray:
    """Decision W148 inside a sequence: two consecutive kept maxima on the same decided side (W20: the alternation
    is broken, one opposite step is missing between them) get the highest positive candidate on the decided
    opposite side that lies one local period (``+- tol``, W18) after the first AND one before the second. W18
    fills such a gap only when it exceeds 1.5 local periods (and then near its centre); here the alternation and
    the rhythm are the evidence, so a weak bounce (a turning or transfer step) is enough. One pass over the kept
    pairs; a pair with no such candidate is left alone (W20's pruning has judged it). Returns the new mask."""
    cand = np.asarray(cand, dtype=np.int64)
    h = np.asarray(height, dtype=np.float64)
    sd = np.asarray(side)
    keep = np.asarray(keep, dtype=bool)
    out = keep.copy()
    for s_k, _per, lo, hi in _same_side_pairs(cand, keep, sd, _max_gap(max_step_s, fs), tol):
        i = _weak_in(cand, h, keep, sd, -s_k, lo, hi)
        if i is not None:
            out[i] = True
    return out


def parity_fill(cand: np.ndarray, keep: np.ndarray, side: np.ndarray, v_lat: np.ndarray, scale: float, fs: float, *,
                max_step_s: float = 1.5, tol: float = RHYTHM_TOL, min_frac: float = SIDE_MIN_FRAC) -> np.ndarray:
    """Decision W152: a contact WITHOUT a vertical maximum for a same-side pair of kept maxima (W148's pairs and
    window, :func:`_same_side_pairs`: one local period +-``tol`` after the first and before the second, so only a
    pair about two local periods apart has one). Where the weak bounce of the missing step merged into its
    neighbours' (W149: 15 of the 23 real Test11 misses have no vertical maximum of their own), the lateral sway
    still shows the step: W20 reads a step's side from the pelvis's lateral velocity ``v_lat`` (per sample) at its
    vertical maximum, so the missing opposite step is placed at the sample of the window where the velocity points
    most to the opposite side, provided it is decided there (``|v| >= min_frac`` x W20's ``scale``,
    :func:`side_scale`). Returns the sample positions of the placed vertical-maximum anchors (int, increasing);
    their initial contacts are found as every contact's (W3)."""
    cand = np.asarray(cand, dtype=np.int64)
    v = np.asarray(v_lat, dtype=np.float64)
    out = []
    if scale <= 0.0:
        return np.zeros(0, dtype=np.int64)
    for s_k, _per, lo, hi in _same_side_pairs(cand, np.asarray(keep, dtype=bool), np.asarray(side),
                                              _max_gap(max_step_s, fs), tol):
        a, b = max(0, int(np.ceil(lo))), min(v.size - 1, int(np.floor(hi)))
        if b < a:
            continue
        x = a + int(np.argmax(-s_k * v[a:b + 1]))  # the opposite side's sway extreme (W20's sign convention)
        if -s_k * v[x] >= min_frac * scale:  # decided on the opposite side (W20's 1/3 of the median)
            out.append(x)
    return np.asarray(sorted(set(out)), dtype=np.int64)


#: W242: the second band's cut-off is twice seed 003's 2.5 Hz (W237's read-out, the same FIR order)
FAST_BAND_FACTOR = 2.0
#: W237: a second-band maximum over 0.1 s from every 2.5 Hz candidate maximum is its own
FAST_OWN_S = 0.1
#: W237 (W23's 1/2): a second-band maximum is a cue at half the median kept 2.5 Hz height or more
FAST_HEIGHT_FRAC = 0.5


def fast_band_fill(vf_fast: np.ndarray, cand: np.ndarray, peaks: np.ndarray, side: np.ndarray, ref_height: float,
                   fs: float, *, min_gap: int, max_step_s: float = 1.5, tol: float = RHYTHM_TOL,
                   own_s: float = FAST_OWN_S, frac: float = FAST_HEIGHT_FRAC) -> np.ndarray:
    """Decision W242: one contact where the 2.5 Hz pass merged a step into a neighbour's. Between two consecutive kept
    contacts ``peaks`` (vertical-maximum samples, increasing; W20 sides ``side``, 0 undecided) of one sequence whose gap
    is consistent with one missing step -- a pair on one decided side (the alternation asks for one opposite step;
    window: the gap less the shortest step ``min_gap`` samples from each end, W16 / W113), else a pair not on
    decided opposite sides with room for exactly one step (:func:`_one_step_gaps`, W148's window: one local period
    +-``tol`` from each) -- the highest maximum of ``vf_fast`` (the vertical acceleration low-passed at
    twice the cut-off) inside the window that is its own (over ``own_s`` from every 2.5 Hz candidate maximum
    ``cand``) and at least ``frac`` x ``ref_height`` (the median kept 2.5 Hz height) high. Unlike W148 (a weaker
    2.5 Hz maximum) and W152 (the lateral sway, no vertical evidence) the evidence is a vertical bounce of its own in
    the faster band. Returns the anchors' sample positions (int, increasing); their contacts are found as every
    contact's (W3)."""
    x = np.asarray(vf_fast, dtype=np.float64)
    peaks = np.asarray(peaks, dtype=np.int64)
    cand = np.asarray(cand, dtype=np.int64)
    if not (np.isfinite(ref_height) and ref_height > 0.0) or peaks.size < 2:
        return np.zeros(0, dtype=np.int64)
    mx = dsp.find_peaks(x, height=frac * ref_height)
    if cand.size:
        i = np.searchsorted(cand, mx)  # cand[i - 1] < mx <= cand[i]
        near = np.minimum(np.abs(mx - cand[np.clip(i - 1, 0, cand.size - 1)]),
                          np.abs(mx - cand[np.clip(i, 0, cand.size - 1)]))
        mx = mx[near > own_s * fs]
    sd = np.asarray(side)
    max_gap = _max_gap(max_step_s, fs)
    win = {k: (lo, hi) for k, _s, _per, lo, hi in _one_step_gaps(peaks, sd, max_gap, tol, same_side=False)}
    for k in np.flatnonzero((sd[:-1] != 0) & (sd[:-1] == sd[1:]) & (np.diff(peaks) <= max_gap)):
        win[int(k)] = (peaks[k] + min_gap, peaks[k + 1] - min_gap)  # W20: one opposite step missing, W16 apart
    out = []
    for lo, hi in win.values():
        m = mx[(mx >= lo) & (mx <= hi)]
        if m.size:
            out.append(int(m[np.argmax(x[m])]))
    return np.asarray(sorted(set(out)), dtype=np.int64)


def inside_sequences(ic: np.ndarray, added: np.ndarray, max_gap: int) -> np.ndarray:
    """Decision W159: the mask of the contacts (initial contacts ``ic``, sample indices, increasing) that keeps every
    contact not flagged in ``added`` and an ``added`` one only where the unflagged contacts have one before it and one
    after it at most ``max_gap`` samples apart (W16's longest step in whole samples, W32): it lies inside one walking
    sequence as :func:`contact_rows` splits them, so it splits a step and never joins two sequences or extends one."""
    ic = np.asarray(ic, dtype=np.int64)
    added = np.asarray(added, dtype=bool)
    base = ic[~added]
    keep = ~added
    for i in np.flatnonzero(added):
        j = np.searchsorted(base, ic[i])  # base[j - 1] < ic[i] <= base[j]
        keep[i] = 0 < j < base.size and base[j - 1] < ic[i] < base[j] and base[j] - base[j - 1] <= max_gap
    return keep


def ap_mean_level(ap: np.ndarray, fs: float, *, window_s: float = GATE_WINDOW_S) -> np.ndarray:
    """Mean of the AP acceleration over a centred window of ``window_s`` (the motion gate's 2 s, seed 000
    sec. II-B): the level an AP *maximum* at the initial contact must exceed (decision W29)."""
    x = np.asarray(ap, dtype=np.float64)
    w = max(3, int(round(window_s * fs)) | 1)
    return dsp.uniform_filter1d(x, w)


def rhythm_complete(cand: np.ndarray, height: np.ndarray, accepted: np.ndarray, fs: float, *,
                    min_peak: float, min_step_s: float = 0.3, max_step_s: float = 1.5,
                    tol: float = RHYTHM_TOL, side: np.ndarray | None = None, unshifted: bool = True,
                    end_steps: bool = False, turning: np.ndarray | None = None,
                    at: np.ndarray | None = None, weak_fill: bool = False) -> np.ndarray:
    """Complete walking sequences of accepted vertical maxima with the gait rhythm (decision W18).

    Steps come at a regular period: (1) inside a sequence, a gap of ``m + 1`` local periods
    (``m >= 1``, gap > 1.5 periods) gets ``m`` maxima, the highest positive candidate within ``tol``
    periods of each predicted time (weak maxima of turning/shuffling steps); (2) a sequence of at least
    ``RHYTHM_MIN_STEPS`` contacts is extended by one step at each end when a candidate of full height
    (``>= min_peak``) lies one period (``+- tol``) beyond it (the 2 s motion gate lags at walk
    start/end). One step per end only, so noise while standing cannot chain.

    With ``side`` (decision W20) the sequences must alternate left/right: same-side pairs too close for
    a missing step lose their weaker maximum first (:func:`prune_same_side`); a gap between contacts of
    known sides is filled only with a step count of the right parity (:func:`_missing_steps`), only by
    candidates not on the wrong side, and only completely (all ``m`` steps found, else none); an end
    step must not lie on the side of the contact it extends. With ``side`` and ``unshifted`` (decision
    W23), an accepted maximum with an undecided side and under half its neighbours' height is dropped
    (:func:`drop_unshifted`). With ``side`` and ``end_steps`` (decision W28) each sequence end then gets
    one more step of gait initiation / termination on the alternating side (:func:`extend_alternating`).
    With ``side`` and ``weak_fill`` (decision W148, off by default) a same-side pair of kept maxima gets a weak
    opposite-side step at the local rhythm between them (:func:`fill_weak_alternating`, after W23) and an end
    where W28 finds no full-height step a weak one at the local rhythm (``extend_alternating(weak=True)``).
    The shortest step is ``round(min_step_s * fs)`` samples, the candidates' own spacing (W28: a float
    ``min_step_s * fs`` just over it dropped maxima exactly that far apart).

    Parameters
    ----------
    cand : (n,) sample indices of positive maxima of the filtered vertical acceleration, increasing
    height : (n,) their filtered values (m/s^2)
    accepted : (n,) bool, maxima accepted by the height threshold and the motion gate
    fs : rate (Hz); min_step_s, max_step_s : shortest step (s), longest step inside a sequence (s)
    side : (n,) int, +1 / -1 / 0 (undecided) step side of each candidate (:func:`step_sides`) or None
    turning : (n,) bool, candidates where the pelvis turns: W23 does not judge them (decision 29 of
        docs/decisions/steps.md: in a pivot the weight moves along the turn and the centripetal acceleration
        enters the lateral signal, so no lateral swing is no evidence against a step); None = all judged
    at : (n,) float, the candidates' sub-sample positions (:func:`peak_positions`) W20's same-side pruning
        compares (decision W107: the same decision at every rate); None = ``cand``. W18, W23 and W28 keep the whole
        samples of ``cand`` (decision W106: timing them between samples too moved real Test11 contacts at 100 Hz)

    Returns
    -------
    (n,) bool: the accepted maxima plus the completed ones.
    """
    cand = np.asarray(cand, dtype=np.int64)
    h = np.asarray(height, dtype=np.float64)
    keep = np.asarray(accepted, dtype=bool).copy()
    if cand.size == 0:
        return keep
    sd = np.zeros(cand.size, dtype=np.int8) if side is None else np.asarray(side, dtype=np.int8)
    if side is not None:  # W107: the pair's distance and local period between samples
        keep = prune_same_side(cand if at is None else at, h, keep, sd, fs, max_step_s=max_step_s)
    max_gap, min_gap = _max_gap(max_step_s, fs), max(1, int(round(min_step_s * fs)))  # as find_peaks' distance
    acc = np.flatnonzero(keep)
    t = cand[acc].astype(np.float64)
    tl = t.tolist()  # E308: _local_period on Python floats (the same values, no numpy scalar per interval)
    add: list[int] = []

    def best_near(centre: float, half: float, floor: float, want: int = 0) -> int | None:
        lo, hi = np.searchsorted(cand, centre - half), np.searchsorted(cand, centre + half, side="right")
        idx = [i for i in range(lo, hi) if not keep[i] and h[i] >= floor and sd[i] * want >= 0]
        return max(idx, key=lambda i: h[i]) if idx else None

    for k in range(t.size):
        s_k = int(sd[acc[k]])
        period_b = _local_period(tl, k, -1, max_gap)
        if k + 1 < t.size and t[k + 1] - t[k] <= max_gap:  # (1) gap inside a sequence
            period_a = _local_period(tl, k + 1, +1, max_gap)
            per = _nanmedian_few([period_b, period_a])  # E308: np.nanmedian's value
            gap = t[k + 1] - t[k]
            if np.isfinite(per) and gap > RHYTHM_GAP * per:
                s_n = int(sd[acc[k + 1]])
                m = _missing_steps(gap / per, s_k, s_n)
                fills = [best_near(t[k] + j * gap / (m + 1), tol * per, 0.0, s_k * (-1) ** j)
                         for j in range(1, m + 1)]
                found = [i for i in fills if i is not None]
                if s_k == 0 or s_n == 0 or len(found) == m:  # W20: alternation needs all of them
                    add.extend(found)
        elif np.isfinite(period_b):  # (2) sequence end: one more step where the gate closed early
            i = best_near(t[k] + period_b, tol * period_b, min_peak, -s_k)
            if i is not None:
                add.append(i)
        if (k == 0 or t[k] - t[k - 1] > max_gap):  # (2) sequence start
            period_a = _local_period(tl, k, +1, max_gap)
            if np.isfinite(period_a):
                i = best_near(t[k] - period_a, tol * period_a, min_peak, -s_k)
                if i is not None:
                    add.append(i)
    keep[np.asarray(add, dtype=np.int64)] = True
    if side is not None and unshifted:  # W23: no weight shift and a weak bounce: no step
        keep = drop_unshifted(cand, h, keep, np.asarray(accepted, dtype=bool), sd, fs, max_step_s=max_step_s,
                              exempt=turning)
    if side is not None and weak_fill:  # W148: a weak step where the alternation and the rhythm ask for one
        keep = fill_weak_alternating(cand, h, keep, sd, fs, max_step_s=max_step_s, tol=tol)
    if side is not None and end_steps:  # W28: initiation / termination step on the alternating side
        keep = extend_alternating(cand, h, keep, sd, fs, min_peak=min_peak, max_step_s=max_step_s, tol=tol,
                                  weak=weak_fill)
    # the completed set must still respect the shortest step: drop the lower of two too-close maxima
    sel = np.flatnonzero(keep)
    for a, b in zip(sel[:-1], sel[1:], strict=True):
        if keep[a] and keep[b] and cand[b] - cand[a] < min_gap:
            keep[a if h[a] < h[b] else b] = False
    return keep


def _nearest_local_max_before(x: np.ndarray, k: int, lo: int, *, level: np.ndarray | None = None) -> int:
    """Index of the last local maximum of ``x`` in ``[lo, k]`` (the global maximum there if none). With
    ``level`` (per sample), the last local maximum above it if there is one (decision W29: a ripple in an
    AP trough is no maximum of the AP signal)."""
    seg = x[lo:k + 1]
    if seg.size < 3:
        return lo + int(np.argmax(seg)) if seg.size else k
    inner = np.flatnonzero((seg[1:-1] >= seg[:-2]) & (seg[1:-1] > seg[2:])) + 1
    if level is not None and inner.size:
        above = inner[seg[inner] > level[lo + inner]]
        if above.size:
            return lo + int(above[-1])
    return lo + int(inner[-1]) if inner.size else lo + int(np.argmax(seg))


DECISION_DELAY_S = 1.75  # W31: a contact is decided 1.75 to < 2.0 s after it (thesis: realtime delay < 2 s)
DECISION_HOP_S = 0.25  # W31: decisions every 0.25 s
DECISION_HISTORY_S = 10.0  # W31: samples before the decision window the sequence rules may look at
#: W31: a contact within the shortest step of the last decided one repeats it; None (W113) = the shortest step of
#: the decision window's own contacts (:func:`relative_min_gap`; W16's 0.3 s at 150 steps/min and slower)
DECISION_MIN_STEP_S: float | None = None


class DelayedDecider:
    """The state of decision W31's decisions, fed one stretch of samples at a time.

    Decision times lie on a grid of ``hop_s`` from the first sample. At a decision time ``T`` the caller's
    ``detect(lo, T)`` runs on the samples ``[lo, T)`` only (``lo = T - span``, clipped at 0, ``span`` =
    ``history_s + delay_s + hop_s``) and returns ``(ic, fc, anchor)`` indices relative to ``lo``; the contacts
    whose IC lies in ``(T - hop_s - delay_s, T - delay_s]`` are decided there, once, and never revised. A
    contact closer than ``round(min_step_s * fs)`` samples after the last decided one is the same step seen
    again from a later window and is not repeated (``min_step_s=None``: decision W113's shortest step of the
    window's own contacts, :func:`relative_min_gap`). The end of the data is one more decision time that
    decides all remaining contacts (:meth:`decide_until` with ``end``).

    Used by :func:`delayed_decisions` (a whole recording) and by the ``waist-ic`` step detector's streaming
    mode (:mod:`pdrlearn.steps.waist_ic`, steps decision 17), which keeps only the last ``span`` samples.
    """

    def __init__(self, fs: float, *, delay_s: float = DECISION_DELAY_S, hop_s: float = DECISION_HOP_S,
                 history_s: float = DECISION_HISTORY_S, min_step_s: float | None = DECISION_MIN_STEP_S):
        self.hop = max(1, int(round(hop_s * fs)))
        self.dly = int(round(delay_s * fs))
        self.span = int(round(history_s * fs)) + self.dly + self.hop  # samples a decision's detector sees
        self.fs = fs
        self.min_gap = None if min_step_s is None else max(1, int(round(min_step_s * fs)))
        self.next_t = self.hop  # the next decision time on the grid (samples from the first one)
        self.done = -1  # contacts with an IC up to this sample are decided
        self.last: int | None = None  # the IC of the last decided contact

    def decide_until(self, n: int, detect, *, end: bool = False) -> list[tuple[int, int, int, int]]:
        """Decide at every grid time up to ``n`` samples (``end``: before ``n``, then at ``n`` itself, which
        decides every contact left: the data ends there). Returns the new ``(ic, fc, anchor, decided)``
        (absolute sample indices; ``decided`` the decision time) in increasing order."""
        out: list[tuple[int, int, int, int]] = []
        while self.next_t <= n and not (end and self.next_t == n):
            self._decide(self.next_t, self.next_t - self.dly, detect, out)
            self.next_t += self.hop
        if end:
            self._decide(n, n - 1, detect, out)
        return out

    def _decide(self, tt: int, upto: int, detect, out: list) -> None:
        if upto <= self.done:
            return
        lo = max(0, tt - self.span)
        ic, fc, an = detect(lo, tt)
        gap = relative_min_gap(ic, self.fs) if self.min_gap is None else self.min_gap  # W113
        for a, b, c in zip(np.asarray(ic) + lo, np.asarray(fc) + lo, np.asarray(an) + lo, strict=True):
            if self.done < a <= upto and (self.last is None or a - self.last >= gap):
                out.append((int(a), int(b), int(c), tt))
                self.last = int(a)
        self.done = upto


def delayed_decisions(n: int, fs: float, detect, *, delay_s: float = DECISION_DELAY_S,
                      hop_s: float = DECISION_HOP_S, history_s: float = DECISION_HISTORY_S,
                      min_step_s: float | None = DECISION_MIN_STEP_S, final: bool = True
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Causal contacts with a bounded decision delay from an offline detector (decision W31), on ``n`` samples.

    :class:`DelayedDecider` over the whole data: ``detect(lo, T)`` runs on the samples ``[lo, T)`` at each
    decision time ``T`` and the contacts whose IC lies in ``(T - hop_s - delay_s, T - delay_s]`` are decided
    there, once. A contact is thus decided at least ``delay_s`` and less than ``delay_s + hop_s`` after it
    happens (``T - ic``), with the whole-sequence rules of the offline detector (rhythm, alternation: W18,
    W20, W23, W28) seeing ``delay_s`` of what follows it. With ``final`` the end of the data is one more
    decision time that decides all remaining contacts (a stream that ends); without it the last
    ``delay_s`` stay undecided. A prefix of the data gives the same contacts as the whole data up to
    the prefix's last decision time minus ``delay_s``.

    Returns
    -------
    ic, fc, anchor, decided : sample indices (int arrays of equal length), increasing; ``decided`` is the
    decision time (the first sample the decision did not see).
    """
    rows = DelayedDecider(fs, delay_s=delay_s, hop_s=hop_s, history_s=history_s,
                          min_step_s=min_step_s).decide_until(n, detect, end=final)
    cols = np.array(rows, dtype=int).reshape(-1, 4)
    return cols[:, 0].copy(), cols[:, 1].copy(), cols[:, 2].copy(), cols[:, 3].copy()


def ic_realtime(acc_v: np.ndarray, acc_ap: np.ndarray, fs: float, *, gate: np.ndarray | None = None,
                cutoff_hz: float = 2.5, fir_order: int = 11, search_s: float = 0.25,  # windows: W16
                min_step_s: float | None = None, max_step_s: float = 1.5, lobe_ratio: float = 2.0,
                fc_search_s: float = 0.25, mean_s: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Causal initial-contact detection (seed 003 sec. 3.1, real-time variant).

    The AP acceleration passes an 11th-order causal FIR (seed 003 sec. 3.1, which gives no cut-off: the
    offline filter's 2.5 Hz is reused and the order stays in samples, decision W68); each positive-to-negative
    zero crossing of its output is an IC candidate. The positive lobe before a true crossing is about as
    long as the previous ones, a false crossing's lobe is much longer (seed 003): a candidate is rejected
    when its lobe lasts more than ``lobe_ratio`` times the running median of the accepted lobes of the
    current walking sequence (a gap over ``max_step_s`` starts a new one). The IC is the last local maximum
    of the raw AP acceleration in the ``search_s`` window before the (delay-corrected) crossing; the FC
    the minimum of AP acceleration in the ``fc_search_s`` after the IC's vertical maximum. Only samples
    up to the crossing (plus ``fc_search_s`` for the FC) are used, so the IC is known one filter delay
    after it happens. Two ICs are at least ``min_step_s`` apart; ``None`` (decision W113) = the shortest step of
    the last accepted contacts' rhythm (:func:`relative_min_gap`, W16's 0.3 s until there are three).

    Returns
    -------
    ic, fc, zc : sample indices of IC, FC and the (delayed) zero crossing that triggered the detection.
    """
    ap = np.asarray(acc_ap, dtype=np.float64)
    v = np.asarray(acc_v, dtype=np.float64)
    order = int(fir_order)
    taps = dsp.firwin_lowpass(order + 1, min(cutoff_hz, 0.45 * fs), fs)
    delay = order // 2
    # causal mean removal over the last ``mean_s`` (about a stride) keeps the filter input centred
    w = max(2, int(round(mean_s * fs)))
    w |= 1
    apc = ap - dsp.uniform_filter1d(ap, w, origin=(w - 1) // 2)
    y = fir_causal(apc, taps)
    zc = np.flatnonzero((y[:-1] > 0) & (y[1:] <= 0)) + 1
    up = np.flatnonzero((y[:-1] <= 0) & (y[1:] > 0)) + 1
    gate_arr = None if gate is None else np.asarray(gate, dtype=bool)
    lobes: list[float] = []
    ic_l, fc_l, zc_l = [], [], []
    ws = max(1, int(round(search_s * fs)))
    wf = max(1, int(round(fc_search_s * fs)))
    fixed_gap = None if min_step_s is None else int(round(min_step_s * fs))
    max_gap = int(round(max_step_s * fs))
    for z in zc:
        if gate_arr is not None and not gate_arr[z]:
            continue
        prev_up = up[up < z]
        if prev_up.size == 0:
            continue
        lobe = (z - prev_up[-1]) / fs
        if lobes and ic_l and z - zc_l[-1] > max_gap:  # a new walking sequence: forget the old lobes
            lobes.clear()
        if len(lobes) >= 3 and lobe > lobe_ratio * float(np.median(lobes[-8:])):
            continue  # seed 003: a false crossing follows a much longer positive lobe
        zr = z - delay  # crossing time corrected for the FIR delay
        ic = _nearest_local_max_before(ap, zr, max(0, zr - ws))
        min_gap = relative_min_gap(ic_l[-9:], fs, max_step_s) if fixed_gap is None else fixed_gap  # W113
        if ic_l and ic - ic_l[-1] < min_gap:
            continue
        lobes.append(lobe)
        hi = min(len(v), ic + wf + 1)
        vmax = ic + int(np.argmax(v[ic:hi])) if hi > ic else ic
        fhi = min(len(ap), vmax + wf + 1)
        fc_l.append(vmax + int(np.argmin(ap[vmax:fhi])) if fhi > vmax else vmax)
        ic_l.append(ic)
        zc_l.append(z)
    return np.array(ic_l, dtype=int), np.array(fc_l, dtype=int), np.array(zc_l, dtype=int)


# --------------------------------------------------------------------------------------------------
# step length models
# --------------------------------------------------------------------------------------------------
def pendulum_length(h: np.ndarray, leg_m: float, *, k: float = 1.0, f: float = 0.0) -> np.ndarray:
    """Modified inverted pendulum step length (seed 003 eq. 1): ``d = K * 2 sqrt(2 L h - h^2) + F``.

    Parameters
    ----------
    h : vertical excursion of the waist during the step's single stance (m), clipped to ``[0, L]``
    leg_m : leg length L (m); k : gain K (-); f : double-stance term F (m, about the foot length)
    """
    hh = np.clip(np.asarray(h, dtype=np.float64), 0.0, leg_m)
    return k * 2.0 * np.sqrt(np.maximum(2.0 * leg_m * hh - hh * hh, 0.0)) + f


# decision W56: mobgap 1.2.0 SlZijlstra's step-length smoothing (`step_length_smoothing=HampelFilter(2, 3.0)`,
# `max_interpolation_gap_s=3`, mobgap/stride_length/_sl_zijlstra.py; Zijlstra & Hof 2003 as modified by Soltani
# et al. 2021, IEEE TNSRE 29:1955-1964); its published defaults, nothing fitted here
HAMPEL_HALF_WINDOW = 2  # values either side of the current one (window of 5, truncated at the ends)
HAMPEL_SIGMAS = 3.0
MAD_TO_SD = 1.4826  # mobgap _hampel_filter_numba: MAD of a normal sample -> its standard deviation
MAX_INTERP_GAP_S = 3.0  # seconds without a contact interpolated at most (mobgap robust_step_para_to_sec)
LENGTH_SMOOTHING_MODES = ("none", "mobgap", "hampel", "seconds")


def hampel(x: np.ndarray, half_window: int = HAMPEL_HALF_WINDOW, n_sigmas: float = HAMPEL_SIGMAS) -> np.ndarray:
    """Hampel filter as mobgap's ``_hampel_filter_numba`` (decision W56): each value farther than ``n_sigmas`` x
    1.4826 x MAD from the median of its window (``half_window`` values either side, truncated at the ends; NaN
    ignored) is replaced by that median (a MAD of 0 replaces any value off the median); NaN stays NaN."""
    x = np.asarray(x, dtype=np.float64)
    out = x.copy()
    for i in range(x.size):
        w = x[max(0, i - half_window):i + half_window + 1]
        w = w[np.isfinite(w)]
        if not w.size:
            continue
        med = float(np.median(w))
        if abs(x[i] - med) > n_sigmas * MAD_TO_SD * float(np.median(np.abs(w - med))):
            out[i] = med
    return out


def per_second_means(t_ic: np.ndarray, values: np.ndarray, n_sec: int) -> np.ndarray:
    """Mean of the values of the contacts ``t_ic`` (s from the sequence's first contact, sorted) inside each
    second ``[k, k + 1]``, bounds included (mobgap ``interval_mean``, decision W56); NaN for a second without one."""
    t = np.asarray(t_ic, dtype=np.float64)
    v = np.asarray(values, dtype=np.float64)
    k = np.arange(n_sec, dtype=np.float64)
    lo, hi = np.searchsorted(t, k, side="left"), np.searchsorted(t, k + 1.0, side="right")
    out = np.full(n_sec, np.nan)
    for j, (a, b) in enumerate(zip(lo, hi, strict=True)):
        seg = v[a:b][np.isfinite(v[a:b])]
        if seg.size:
            out[j] = float(seg.mean())
    return out


def interpolate_inside(x: np.ndarray, max_gap: float = MAX_INTERP_GAP_S) -> np.ndarray:
    """NaN runs between finite values filled linearly, runs longer than ``max_gap`` values (seconds) and the
    edges left NaN (mobgap ``robust_step_para_to_sec``, decision W56)."""
    x = np.asarray(x, dtype=np.float64).copy()
    ok = np.flatnonzero(np.isfinite(x))
    for a, b in zip(ok[:-1], ok[1:], strict=True):
        if 1 < b - a <= max_gap + 1:
            x[a + 1:b] = np.interp(np.arange(a + 1, b), [a, b], [x[a], x[b]])
    return x


def smooth_step_lengths(start_s: np.ndarray, end_s: np.ndarray, lengths: np.ndarray, mode: str = "mobgap"
                        ) -> np.ndarray:
    """Step lengths of one walking sequence smoothed as mobgap's ``SlZijlstra`` does (decision W56).

    ``start_s``/``end_s``: each step's contacts (s, sorted, step i ends where i + 1 starts); ``lengths`` the
    per-step values (any unit; the result is equivariant to ``x -> a x + b``, a > 0). ``mode``:
    ``"mobgap"`` -- the last value repeated for the last contact, a Hampel filter on the per-contact values,
    the mean per second of the sequence (from its first contact), the Hampel filter on the per-second values,
    gaps of up to 3 s interpolated, and each step the mean of that piecewise-constant per-second curve over its
    own span; ``"hampel"`` -- only the first Hampel filter; ``"seconds"`` -- the per-second steps without either
    Hampel filter; ``"none"`` -- the lengths unchanged.
    """
    v = np.asarray(lengths, dtype=np.float64)
    if mode not in LENGTH_SMOOTHING_MODES:
        raise DataError(f"length_smoothing '{mode}' is not one of {', '.join(LENGTH_SMOOTHING_MODES)}")
    if mode == "none" or not v.size:
        return v.copy()
    t0 = float(start_s[0])
    s = np.asarray(start_s, dtype=np.float64) - t0
    e = np.asarray(end_s, dtype=np.float64) - t0
    per_ic = np.append(v, v[-1])  # mobgap: the last step's value also stands for the last contact
    use_hampel = mode in ("mobgap", "hampel")
    if use_hampel:
        per_ic = hampel(per_ic)
    if mode == "hampel":
        return per_ic[:-1]
    t_ic = np.append(s, e[-1])
    n_sec = int(np.floor(t_ic[-1])) + 1  # mobgap: seconds k + 0.5 of the sequence, the last contact's included
    sec = per_second_means(t_ic, per_ic, n_sec)
    if use_hampel:
        sec = hampel(sec)
    sec = interpolate_inside(sec)
    # each step: the mean of the piecewise-constant per-second curve over [start, end] (mobgap
    # naive_sec_paras_to_regions), seconds left NaN (longer gaps) not counted
    ok = np.isfinite(sec)
    knots = np.arange(n_sec + 1, dtype=np.float64)
    area = np.concatenate([[0.0], np.cumsum(np.where(ok, sec, 0.0))])
    cover = np.concatenate([[0.0], np.cumsum(ok.astype(np.float64))])
    da = np.interp(e, knots, area) - np.interp(s, knots, area)
    dc = np.interp(e, knots, cover) - np.interp(s, knots, cover)
    at = sec[np.clip(np.floor(s).astype(int), 0, n_sec - 1)]  # a step of zero duration: its second's value
    out = np.where(dc > 1e-12, da / np.where(dc > 1e-12, dc, 1.0), at)
    return np.where(np.isfinite(out), out, per_ic[:-1])  # no finite second under the step: its own value


#: decision W348: the rate (Hz) a step's vertical acceleration is integrated at, at least: a slower record is
#: upsampled first (the trapezoidal rule's double-integration gain at a 1.8 Hz step is 0.947 at 20 Hz, 0.998 at 100 Hz)
EXCURSION_MIN_RATE_HZ = 100.0


def band_limited_upsample(x: np.ndarray, factor: int) -> np.ndarray:
    """Decision W348: the samples ``x`` at ``factor`` times their rate, ``(len(x) - 1) * factor + 1`` samples from
    the first to the last, by zero-padding the FFT of ``x`` extended by its even reflection (periodic without a
    jump at the ends; the sampling theorem's interpolation of a band-limited signal). ``factor`` 1: ``x``."""
    x = np.asarray(x, dtype=np.float64)
    if factor <= 1 or x.size < 3:
        return x.copy()
    ext = np.concatenate([x, x[-2:0:-1]])
    fine = np.fft.irfft(np.fft.rfft(ext), ext.size * factor) * factor
    return fine[:(x.size - 1) * factor + 1]


def vertical_excursion(acc_v: np.ndarray, fs: float, i0: int, i1: int, *, min_rate_hz: float = 0.0) -> float:
    """Peak-to-peak vertical displacement (m) between samples ``i0`` and ``i1``.

    Double integration of the vertical acceleration (gravity removed) with zero velocity at both ends
    (seed 003 sec. 3.2: ZUPT at the IC) and equal height at both ends: the mean of the acceleration is
    removed before the first integration and the linear drift of the position after the second. Below
    ``min_rate_hz`` the step's samples (``i0`` to ``i1`` only) are first upsampled by ``ceil(min_rate_hz / fs)``
    (:func:`band_limited_upsample`, decision W348).
    """
    a = np.asarray(acc_v[i0:i1 + 1], dtype=np.float64)
    if a.size < 3:
        return 0.0
    factor = int(np.ceil(min_rate_hz / fs - 1e-9)) if min_rate_hz > fs else 1  # W348
    a = band_limited_upsample(a, factor)
    dt = 1.0 / (fs * factor)
    a = a - a.mean()
    vel = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
    vel = vel - np.linspace(vel[0], vel[-1], vel.size)
    pos = np.concatenate([[0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * dt)])
    pos = pos - np.linspace(pos[0], pos[-1], pos.size)
    return float(pos.max() - pos.min())


def turning_step_factor(dpsi_rad: np.ndarray) -> np.ndarray:
    """Share of a step's straight-ahead length kept when the pelvis turns by ``dpsi_rad`` during it
    (decision W19): ``cos(min(|dpsi|, pi/2))`` -- the component of the step along the heading held at
    both of its contacts; 1 on straight steps, 0 for a quarter turn or more in one step (turning on the
    spot)."""
    d = np.minimum(np.abs(np.asarray(dpsi_rad, dtype=np.float64)), 0.5 * np.pi)
    return np.cos(d)


#: decision W150 (candidate, option ``pivot_steps``): a step whose net pelvis rotation reaches this (deg) is a pivot
#: step -- a walked step of 0.6 m turning 45 deg lies on a 0.76 m radius, past a corner walked without pivoting
PIVOT_MIN_DEG = 45.0
#: decision W150: the radius (m) the pelvis circles the stance foot on in a pivot step: a 45 deg step moves it 0.15 m,
#: a 90 deg one 0.28 m, the 0.1-0.2 m a step of a turn on the spot moves the body (S41)
PIVOT_RADIUS_M = 0.2


def pivot_step_factor(lengths: np.ndarray, dpsi_rad: np.ndarray, *, min_deg: float = PIVOT_MIN_DEG,
                      radius_m: float = PIVOT_RADIUS_M) -> np.ndarray:
    """Decision W150: the share of each step's length kept when a step turning the pelvis by ``|dpsi_rad|`` >=
    ``min_deg`` keeps at most the chord of its turn on ``radius_m``, ``2 r sin(|dpsi| / 2)`` (plane geometry); 1 for
    the other steps and for a length already under the chord (or 0)."""
    length = np.asarray(lengths, dtype=np.float64)
    d = np.abs(np.asarray(dpsi_rad, dtype=np.float64))
    chord = 2.0 * radius_m * np.sin(0.5 * np.minimum(d, np.pi))
    pivot = (d >= np.radians(min_deg)) & (length > chord)
    return np.where(pivot, chord / np.where(pivot, length, 1.0), 1.0)


def local_medians(values: np.ndarray, use: np.ndarray, closes: np.ndarray) -> np.ndarray:
    """Per row of a steps table: W18's local median of ``values`` around the row's step, the median of the medians
    of up to three values of the steps on each side inside its walking sequence (at least ``RHYTHM_MIN_STEPS - 1``
    on a side; the row's own value not included); NaN where no side has enough. Shared by W111 (step durations:
    the local period) and W119 (step vaults). ``use``: rows that are steps (not a W27 fragment, not a
    sequence-closing contact); ``closes``: rows that end a walking sequence (no next contact)."""
    v = np.asarray(values, dtype=np.float64)
    use, closes = np.asarray(use, dtype=bool), np.asarray(closes, dtype=bool)
    out = np.full(v.size, np.nan)
    seq = np.concatenate([[0], np.cumsum(closes)[:-1]]) if v.size else np.zeros(0, int)
    for sid in np.unique(seq[use]):
        rows = np.flatnonzero(use & (seq == sid))
        c = np.concatenate([[0.0], np.cumsum(v[rows])]).tolist()  # consecutive differences are the values
        for j, r in enumerate(rows):
            side = [x for x in (_local_period(c, j, -1, np.inf), _local_period(c, j + 1, +1, np.inf))
                    if np.isfinite(x)]
            if side:
                out[r] = _median_few(side)  # E308: np.median's value
    return out


def pause_step_factor(duration_s: np.ndarray, use: np.ndarray, closes: np.ndarray) -> np.ndarray:
    """Share of a step's pendulum length kept when the step spans a pause (decision W111): a step longer than
    :data:`RHYTHM_GAP` local periods -- an interval W18 should have filled with a missed step and could not --
    keeps one period's length, ``period / duration``; 1 elsewhere. The local period is W18's:
    :func:`local_medians` of the step durations.

    ``duration_s``: IC to next IC (s) of each row; ``use``: rows that are steps with a length (not a W27 fragment,
    not a sequence-closing contact); ``closes``: rows that end a walking sequence (no next contact)."""
    dur = np.asarray(duration_s, dtype=np.float64)
    per = local_medians(dur, use, closes)
    long = np.asarray(use, dtype=bool) & np.isfinite(per) & (dur > RHYTHM_GAP * np.nan_to_num(per, nan=np.inf))
    return np.where(long, per / np.where(long, dur, 1.0), 1.0)


#: W119: a step under this share of its neighbours' vault is under half their length (pendulum h ~ s^2 / (8 L),
#: seed 003 eq. 1, Zijlstra & Hof 2003; simulator S29): W27's "half a step is no step", in vault terms
LOW_VAULT_RATIO = 0.25


def low_vault_mask(h_m: np.ndarray, use: np.ndarray, closes: np.ndarray) -> np.ndarray:
    """Rows whose step vaults the pelvis by less than :data:`LOW_VAULT_RATIO` of its local vault
    (:func:`local_medians` of ``h_m``, the steps' vertical excursions): a contact that starts no pendulum vault is
    a weight shift in place, no step (decision W119). Rows without a local vault are never flagged."""
    h = np.asarray(h_m, dtype=np.float64)
    local = local_medians(h, use, closes)
    return np.asarray(use, dtype=bool) & np.isfinite(local) & (h < LOW_VAULT_RATIO * np.nan_to_num(local))


#: W189: a walking run whose median bounce is under this fraction of the recording's median contact bounce is no
#: walking (standing sway). W20's SIDE_MIN_FRAC: a cue under a third of its typical value is undecided.
WEAK_RUN_FRAC = SIDE_MIN_FRAC
#: W189: the bounce of a contact is read over +-this many seconds around it (W16's shortest step, 0.3 s)
BOUNCE_HALF_S = 0.3
#: W189: the vertical acceleration's low-pass before its range is read (Hz; seed 003 sec. 3.1's cutoff)
BOUNCE_CUTOFF_HZ = 2.5


def contact_bounce(acc_v: np.ndarray, fs: float, idx: np.ndarray, *, half_s: float = BOUNCE_HALF_S,
                   cutoff_hz: float = BOUNCE_CUTOFF_HZ) -> np.ndarray:
    """Per contact (sample indices ``idx``): the range (max - min, m/s^2) of the vertical acceleration, low-passed at
    ``cutoff_hz`` (zero-phase third-order Butterworth), over +-``half_s`` around it -- the trunk's bounce at the
    contact (decision W189)."""
    idx = np.asarray(idx, dtype=int)
    if not idx.size:
        return np.zeros(0)
    v = dsp.lowpass(np.asarray(acc_v, dtype=np.float64), min(cutoff_hz, 0.4 * fs), fs)
    w = max(1, int(round(half_s * fs)))
    return np.array([np.ptp(v[max(0, i - w):min(len(v), i + w + 1)]) for i in idx], dtype=np.float64)


def run_ids(has_next: np.ndarray) -> np.ndarray:
    """Per contact: the index of its walking run (contacts chained by ``has_next``: a step to the next contact)."""
    h = np.asarray(has_next, dtype=bool)
    if not h.size:
        return np.zeros(0, dtype=int)
    return np.concatenate([[0], np.cumsum(~h[:-1])]).astype(int)


def weak_run_mask(bounce: np.ndarray, has_next: np.ndarray, *, frac: float = WEAK_RUN_FRAC,
                  spare: np.ndarray | None = None, reference: float | None = None,
                  keep: np.ndarray | None = None) -> np.ndarray:
    """Contacts of a walking run (:func:`run_ids`) whose median ``bounce`` is under ``frac`` times the median bounce
    of all the contacts: a run without a walker's vertical bounce is standing sway, no walking (decision W189).
    ``spare`` (per contact, optional): a run holding any spared contact is never flagged, the whole run kept
    (decision W191: a run with a step that turns the pelvis). ``reference`` (optional): the bounce the runs are
    judged against instead of the median of all the contacts (decision W218: :func:`walking_reference`); ``keep``
    (per contact, optional): contacts never flagged, the rest of their run judged as before (W218's walking
    stretches, :func:`walking_stretch_mask`)."""
    b = np.asarray(bounce, dtype=np.float64)
    if not b.size:
        return np.zeros(0, dtype=bool)
    rid = run_ids(has_next)
    run_med = np.array([np.median(b[rid == r]) for r in range(rid[-1] + 1)])
    weak = run_med[rid] < frac * (float(np.median(b)) if reference is None else float(reference))
    if spare is not None:
        spared_runs = np.zeros(rid[-1] + 1, dtype=bool)
        spared_runs[rid[np.asarray(spare, dtype=bool)]] = True
        weak &= ~spared_runs[rid]
    if keep is not None:
        weak &= ~np.asarray(keep, dtype=bool)
    return weak


def walking_stretch_mask(side: np.ndarray, has_next: np.ndarray, event_s: np.ndarray, min_strides: int, *,
                         tol: float = RHYTHM_TOL) -> np.ndarray:
    """Per contact: True inside a *walking stretch* (decision W218): at least ``min_strides`` consecutive regular
    strides (contact k to k + 2, W47) on alternating sides -- every step of them (``has_next``) between two decided,
    opposite sides (W20's :func:`step_sides`: +1 / -1; an undecided contact breaks the chain), and every stride within
    ``tol`` (W18's +-35 %) of the median stride time of its alternating chain (strides, not steps: the left / right
    asymmetry of the contact's placement cancels over a stride). The caller passes Mobilise-D's 4 strides (a bout's
    minimum, W47). Standing sway, a weight shift or a freeze's trembling (undecided sides, S51) makes none."""
    s = np.asarray(side, dtype=int)
    hn = np.asarray(has_next, dtype=bool)
    t = np.asarray(event_s, dtype=np.float64)
    out = np.zeros(s.size, dtype=bool)
    if s.size < 3:
        return out
    alt = np.append(hn[:-1] & (s[:-1] * s[1:] == -1), False)  # step i -> i + 1 alternates (W109's pair)
    i = 0
    while i < s.size:
        if not alt[i]:
            i += 1
            continue
        j = i
        while alt[j]:
            j += 1  # contacts i..j: an alternating chain
        if j - i >= 2:
            stride = t[i + 2:j + 1] - t[i:j - 1]  # stride k = contact k to k + 2, k = i..j - 2
            regular = np.abs(stride - np.median(stride)) <= tol * np.median(stride) + 1e-12
            k = 0
            while k < stride.size:  # runs of consecutive regular strides
                if not regular[k]:
                    k += 1
                    continue
                m = k
                while m + 1 < stride.size and regular[m + 1]:
                    m += 1
                if m - k + 1 >= min_strides:
                    out[i + k:i + m + 3] = True
                k = m + 1
        i = j + 1
    return out


def walk_extent_mask(event_s: np.ndarray, has_next: np.ndarray, stretch: np.ndarray, strong: np.ndarray,
                     bound_s: float) -> np.ndarray:
    """Per contact: True inside the walk of a walking ``stretch`` (decision W218): the stretch's contacts and, going
    out from it contact by contact along its own walking run (:func:`run_ids`), every contact that lies at most
    ``bound_s`` from a stretch contact or is ``strong`` (its own bounce at least the weak fraction of the reference),
    up to the first that is neither (a freeze's trembling or standing sway chained to the walk). The caller passes
    Mobilise-D's 3 s bout break."""
    t = np.asarray(event_s, dtype=np.float64)
    st = np.asarray(stretch, dtype=bool)
    ok = np.asarray(strong, dtype=bool).copy()
    out = st.copy()
    if not st.any():
        return out
    rid = run_ids(has_next)
    ts = t[st]
    ok |= nearest_distance(t, ts) <= bound_s + 1e-9  # decision L546: no contacts x contacts matrix
    for k in np.flatnonzero(st):
        for step in (-1, 1):
            j = k + step
            while 0 <= j < t.size and rid[j] == rid[k] and not out[j] and ok[j]:
                out[j] = True
                j += step
    return out


def walking_reference(bounce: np.ndarray, walking: np.ndarray) -> float:
    """Decision W218: the median ``bounce`` of the contacts of the walking stretches (:func:`walking_stretch_mask`),
    the recording's walking bounce that standing or trembling contacts cannot outnumber; W189's median of all the
    contacts when there is none."""
    b = np.asarray(bounce, dtype=np.float64)
    w = np.asarray(walking, dtype=bool)
    return float(np.median(b[w])) if w.any() else float(np.median(b)) if b.size else 0.0


def alternating_run_mask(side: np.ndarray, has_next: np.ndarray) -> np.ndarray:
    """Per contact: True when its walking run (:func:`run_ids`) holds at least two decided sides (W20's
    :func:`step_sides`: +1 / -1, 0 undecided) and every two consecutive decided sides of the run agree with a strict
    left/right alternation of all its contacts: opposite when an even number of contacts lies between them (none:
    adjacent contacts), equal when an odd number does (W180's ... L ? L ...). Real steps alternate sides; standing
    sway and weight shifts do not, or stay undecided (decision W196)."""
    s = np.asarray(side, dtype=int)
    if not s.size:
        return np.zeros(0, dtype=bool)
    rid = run_ids(has_next)
    out = np.zeros(s.size, dtype=bool)
    for r in range(rid[-1] + 1):
        members = np.flatnonzero(rid == r)
        pos = members[s[members] != 0]  # the decided contacts of the run, in order
        if pos.size < 2:
            continue
        parity = np.where((np.diff(pos) % 2) == 1, -1, 1)  # -1: adjacent positions must be on opposite sides
        out[members] = bool(np.all(s[pos[:-1]] * s[pos[1:]] == parity))
    return out


def adjacent_run_mask(event_s: np.ndarray, has_next: np.ndarray, walking: np.ndarray, bound_s: float) -> np.ndarray:
    """Per contact: True when its walking run (:func:`run_ids`) has a ``walking`` contact of another run at most
    ``bound_s`` before its first contact AND one at most ``bound_s`` after its last contact: the run lies inside
    walking, between two walking runs (a turn on the spot inside a walk), not at a walk's end or inside standing
    (decision W198; the caller passes Mobilise-D's walking-bout break, ``gait_rules.MAX_BREAK_S``)."""
    t = np.asarray(event_s, dtype=np.float64)
    if not t.size:
        return np.zeros(0, dtype=bool)
    rid = run_ids(has_next)
    w = np.asarray(walking, dtype=bool)
    n_runs = rid[-1] + 1
    first = np.array([t[rid == r][0] for r in range(n_runs)])
    last = np.array([t[rid == r][-1] for r in range(n_runs)])
    out_runs = np.zeros(n_runs, dtype=bool)
    for r in range(n_runs):
        other = w & (rid != r)
        before = other & (t < first[r]) & (t >= first[r] - bound_s - 1e-9)
        after = other & (t > last[r]) & (t <= last[r] + bound_s + 1e-9)
        out_runs[r] = bool(before.any() and after.any())
    return out_runs[rid]


#: W127: a step whose pelvis turns by more than this (deg, IC to next IC) is a turning step, which W119's veto
#: spares. The geometric middle, a factor 1.5 from each, of the largest turn of a straight step -- the pelvis's
#: whole transverse rotation, 2 x 4-5 deg (Perry & Burnfield, Gait Analysis, 2010; simulator 3-5 deg amplitude,
#: ``UserProfile.pelvis_rotation_deg``) = 10 deg -- and the smallest turn of a step of a quarter turn on the spot
#: (simulator S9: feet turned at most 60 deg a step, the pelvis at their mean: 90 deg in two steps turns it
#: 22.5, 45, 22.5 deg): sqrt(10 x 22.5) = 15 deg. Not from a recording.
TURN_STEP_DEG = 15.0


def turning_step_mask(dyaw_rad: np.ndarray) -> np.ndarray:
    """Rows whose step turns the pelvis (``dyaw_rad``: the vertical rate integrated from the step's IC to the next)
    by more than :data:`TURN_STEP_DEG` either way: a turn on the spot vaults little, like a weight shift, and is a
    step (decision W127)."""
    return np.abs(np.asarray(dyaw_rad, dtype=np.float64)) > np.radians(TURN_STEP_DEG)


def still_samples(acc: np.ndarray, gyr: np.ndarray, fs: float, *, window_s: float = 0.25, acc_tol: float = 0.3,
                  gyr_tol: float = 0.25) -> np.ndarray:
    """Samples where the unit is still (:func:`pdrlearn.signal.standstill_mask`'s test, numpy only, which that
    function calls after checking its input): over a centred window of ``window_s`` s the standard deviation of
    the acceleration magnitude is under ``acc_tol`` (m/s^2) and the mean gyroscope magnitude under ``gyr_tol``
    (rad/s) -- thesis ch.3's stance tests on magnitudes, so any frame of the same samples gives the same mask.
    The live waist trackers run it on their buffered window (decision W165)."""
    return still_from_magnitudes(dsp.magnitude(acc), dsp.magnitude(gyr), fs, window_s=window_s, acc_tol=acc_tol,
                                 gyr_tol=gyr_tol)


def still_from_magnitudes(am: np.ndarray, gm: np.ndarray, fs: float, *, window_s: float = 0.25, acc_tol: float = 0.3,
                          gyr_tol: float = 0.25) -> np.ndarray:
    """:func:`still_samples`'s test on the magnitudes ``am`` (m/s^2) and ``gm`` (rad/s) of the acceleration and rate:
    what the live waist tracker holds across a rest for L296's bias (decision L308)."""
    w = max(1, int(round(window_s * fs)))
    mean = dsp.uniform_filter1d(am, w)
    var = np.maximum(dsp.uniform_filter1d(am * am, w) - mean * mean, 0.0)
    return (np.sqrt(var) < acc_tol) & (dsp.uniform_filter1d(gm, w) < gyr_tol)


def step_still_travel(acc_h: np.ndarray, still: np.ndarray, fs: float, i0: int, i1: int) -> tuple[float, float]:
    """Decision W122 / W134 for one step from sample ``i0`` to ``i1``: the trunk's horizontal travel
    (:func:`still_displacement`, NaN without a still sample) and the duration (s) of its longest still run
    (:func:`longest_still_run`, NaN without one). Shared by the offline pendulum model and the live trackers (W165)."""
    run = longest_still_run(still, i0, i1)
    if run is None:
        return float("nan"), float("nan")
    return still_displacement(acc_h, still, fs, i0, i1), (run[1] - run[0]) / fs


def longest_still_run(still: np.ndarray, i0: int, i1: int) -> tuple[int, int] | None:
    """The longest run ``[start, end)`` (sample indices of ``still``) of consecutive still samples inside
    ``[i0, i1]``, the first of equal ones; None when none is still (decisions W122, W134)."""
    m = np.asarray(still[i0:i1 + 1], dtype=bool)
    if not m.any():
        return None
    edges = np.flatnonzero(np.diff(np.concatenate([[0], m.astype(np.int8), [0]])))
    starts, ends = edges[::2], edges[1::2]  # runs [start, end)
    j = int(np.argmax(ends - starts))
    return i0 + int(starts[j]), i0 + int(ends[j])


def still_displacement(acc_h: np.ndarray, still: np.ndarray, fs: float, i0: int, i1: int) -> float:
    """Horizontal displacement (m) of the unit between samples ``i0`` and ``i1`` when the unit stands still
    somewhere in between (decision W122); NaN when no sample of ``still`` lies in ``[i0, i1]``.

    The velocity is zero in the middle of the longest still run (the zero-velocity update of foot-mounted
    dead reckoning, thesis ch.3, moved to the trunk: a standing walker's pelvis does not travel); from there the
    horizontal acceleration ``acc_h`` (n, 2; navigation frame, m/s^2) is integrated forward and backward to the
    velocity (trapezoid) and the velocity over ``[i0, i1]`` to the displacement, whose length is returned.
    """
    run = longest_still_run(still, i0, i1)
    if run is None:
        return float("nan")
    a = np.asarray(acc_h[i0:i1 + 1], dtype=np.float64)
    k0 = (run[0] + run[1] - 1) // 2 - i0
    dv = 0.5 * (a[1:] + a[:-1]) / fs  # velocity change from sample k to k + 1
    cum = np.concatenate([np.zeros((1, a.shape[1])), np.cumsum(dv, axis=0)])
    v = cum - cum[k0]  # zero at k0, integrated both ways
    d = 0.5 * (v[1:] + v[:-1]).sum(axis=0) / fs
    return float(np.hypot(d[0], d[1]))


def progression_factor(displacement_m: np.ndarray, length_m: np.ndarray) -> np.ndarray:
    """Share of a step's length kept when the unit stood still during the step (decision W122): the trunk's
    own horizontal travel over it (:func:`still_displacement`) over the step length, at most 1; 1 for a step
    without a still sample (NaN displacement) or without a length."""
    d = np.asarray(displacement_m, dtype=np.float64)
    ln = np.asarray(length_m, dtype=np.float64)
    ok = np.isfinite(d) & (ln > 0)
    return np.where(ok, np.minimum(1.0, np.where(ok, d, 0.0) / np.where(ok, ln, 1.0)), 1.0)


#: W134: a step whose longest still run lasts at least this share of its local step period holds a stand. While
#: walking the pelvis is slowest in double support, about 10 % of the gait cycle twice per cycle (Perry & Burnfield,
#: Gait Analysis, 2010), a fifth of a step (a quarter when slow); half a step is more than twice that. Not fitted.
STANDING_SHARE = 0.5
#: decision W516: a walking sequence with more than this share of its steps read as stands has none (a real stand
#: needs a step into it and one out of it, so stops come at most every third step; a steadied trunk, trial T1: 35-54 %)
STANDS_MAX_SHARE = 0.25


def stands_within_share(n_stands: np.ndarray, n_steps: np.ndarray) -> np.ndarray:
    """Decisions W516 / W529: whether a stand step is kept when ``n_stands`` of the ``n_steps`` steps of its walking
    sequence (W516: all of them; W529, causal: those up to it, this one included) read as W134's stands: at most
    :data:`STANDS_MAX_SHARE`. The live tracker counts them step by step, the realtime model over its table (W165)."""
    return np.asarray(n_stands, dtype=np.float64) <= STANDS_MAX_SHARE * np.asarray(n_steps, dtype=np.float64)


def _sequence_ids(closes: np.ndarray) -> np.ndarray:
    """Each row's walking sequence (0, 1, ...): a sequence ends at a row that ``closes`` it."""
    closes = np.asarray(closes, dtype=bool)
    return np.concatenate([[0], np.cumsum(closes)[:-1]]) if closes.size else np.zeros(0, int)


def standing_step_mask(still_run_s: np.ndarray, duration_s: np.ndarray, use: np.ndarray,
                       closes: np.ndarray, *, causal: bool = False) -> np.ndarray:
    """Rows whose step holds a stand, not a slow phase of walking: W134's :func:`standing_candidates`, kept while
    they are rare in their walking sequence (decision W516, :func:`stands_within_share`): over the whole sequence,
    or with ``causal`` over its steps up to each one (decision W529: the realtime replay and the live tracker, which
    decide a step before the walk ends)."""
    stand = standing_candidates(still_run_s, duration_s, use, closes)
    use, closes = np.asarray(use, dtype=bool), np.asarray(closes, dtype=bool)
    seq = _sequence_ids(closes)
    for sid in np.unique(seq[use]):  # W516 / W529: stands are events of a walk, not every other step of it
        rows = np.flatnonzero(use & (seq == sid))
        if causal:
            stand[rows] &= stands_within_share(np.cumsum(stand[rows]), np.arange(1, rows.size + 1))
        else:
            stand[rows] &= stands_within_share(stand[rows].sum(), rows.size)
    return stand


def standing_candidates(still_run_s: np.ndarray, duration_s: np.ndarray, use: np.ndarray,
                        closes: np.ndarray) -> np.ndarray:
    """Rows whose step holds a stand, not a slow phase of walking (decision W134): the step's longest still run
    (``still_run_s``, s; NaN without a still sample) lasts at least :data:`STANDING_SHARE` of its local step period
    (W18's :func:`local_medians` of ``duration_s``), and the step is neither the first nor the last row of
    ``use`` in its walking sequence (a walk's first / last step starts from / ends in quiet standing, which the
    still window runs into while the pelvis still travels). Rows without a local period are never flagged.
    ``use``, ``closes``: as :func:`local_medians`."""
    run = np.asarray(still_run_s, dtype=np.float64)
    use, closes = np.asarray(use, dtype=bool), np.asarray(closes, dtype=bool)
    per = local_medians(duration_s, use, closes)
    inner = np.zeros(run.size, dtype=bool)
    seq = _sequence_ids(closes)
    for sid in np.unique(seq[use]):
        rows = np.flatnonzero(use & (seq == sid))
        inner[rows[1:-1]] = True
    ok = inner & np.isfinite(per) & np.isfinite(run)
    return ok & (np.where(ok, run, 0.0) >= STANDING_SHARE * np.where(ok, per, np.inf))


def frequency_length(f_hz: np.ndarray, a: float, b: float) -> np.ndarray:
    """Step length linear in step frequency (seed 001 eq. 23; seed 000 sec. II-D): ``SL = a f - b``."""
    return a * np.asarray(f_hz, dtype=np.float64) - b


def stride_gains(distance_m: float, g: np.ndarray, c: np.ndarray | None = None, f_m: float = 0.0) -> np.ndarray:
    """The pendulum gain each stride of a calibration walk implies if every step of the walk had the same
    length (decision W48): ``K_j = (D / sum c - F) (c_a + c_b) / (c_a g_a + c_b g_b)`` over consecutive pairs
    ``(a, b)`` of the steps that carry length (``c > 0``, finite ``g > 0``); ``D`` the walk's known length (m),
    ``g = 2 sqrt(2 L h - h^2)`` per step (seed 003 eq. 1 with K = 1, F = 0), ``c`` the tracker's per-step
    factors (W19, W27; ones when ``None``), so that ``D = sum c (K g + F)`` as the tracker sums it (W21).
    A stride (not a step) is the unit: an early contact moves length from one step to the next (W40).
    Returns an empty array for a walk of fewer than two such steps."""
    gg = np.asarray(g, dtype=np.float64)
    cc = np.ones(gg.size) if c is None else np.asarray(c, dtype=np.float64)
    if gg.size == 0 or not np.sum(cc) > 0:
        return np.zeros(0)
    mean_step = float(distance_m) / float(np.sum(cc)) - f_m
    keep = (cc > 0) & np.isfinite(gg) & (gg > 0)
    gg, cc = gg[keep], cc[keep]
    n = gg.size // 2
    ca = cc[:2 * n:2] + cc[1:2 * n:2]
    cg = cc[:2 * n:2] * gg[:2 * n:2] + cc[1:2 * n:2] * gg[1:2 * n:2]
    return mean_step * ca / cg


def shrink_gain(k_cal: float, se: float, k0: float, tau: float) -> float:
    """Precision-weighted mean of a calibrated gain and a population prior (decision W48; the normal-normal
    posterior mean, Gelman et al., Bayesian Data Analysis, 3rd ed., eq. 2.12):
    ``(k_cal / se^2 + k0 / tau^2) / (1 / se^2 + 1 / tau^2)`` = ``k0 + tau^2 / (tau^2 + se^2) (k_cal - k0)``.

    ``se`` = standard error of ``k_cal`` (``inf``: no evidence -> ``k0``); ``tau`` = between-subject spread of the
    gain about ``k0`` (``inf``: no prior -> ``k_cal``). Raises ``ValueError`` on a NaN / negative ``se`` or ``tau``
    and on ``se = tau = 0`` (no weighting defined)."""
    if not (se >= 0 and tau >= 0):
        raise ValueError(f"shrink_gain: se={se!r} and tau={tau!r} must be >= 0")
    if np.isinf(tau):
        return float(k_cal) if np.isfinite(se) else float("nan")
    if np.isinf(se):
        return float(k0)
    if se == 0 and tau == 0:
        raise ValueError("shrink_gain: se = tau = 0 gives no weighting")
    w = tau * tau / (tau * tau + se * se)
    return float(k0 + w * (k_cal - k0))


def moment_tau(k_cals: np.ndarray, ses: np.ndarray, k0: float) -> float:
    """Between-subject spread of the gain about the prior mean ``k0`` by the method of moments (decision W48):
    ``tau^2 = mean((k_cal_s - k0)^2) - mean(se_s^2)`` over subjects ``s`` (each its calibration gain and standard
    error), floored at ``mean(se_s^2)`` -- a few subjects can give a moment estimate <= 0 by chance, and the floor
    keeps a walk as long as theirs at half its weight or more. Needs at least one subject with a finite se."""
    k, s = np.asarray(k_cals, dtype=np.float64), np.asarray(ses, dtype=np.float64)
    ok = np.isfinite(k) & np.isfinite(s)
    if not ok.any():
        raise ValueError("moment_tau: no subject with a finite gain and standard error")
    s2 = float(np.mean(s[ok] ** 2))
    return float(np.sqrt(max(float(np.mean((k[ok] - k0) ** 2)) - s2, s2)))


def harmonic_mean_frequency(f_hz: np.ndarray) -> float:
    """Average step frequency of a walk, ``(mean(1/f_k))^-1`` (seed 000 eq. 1)."""
    f = np.asarray(f_hz, dtype=np.float64)
    f = f[np.isfinite(f) & (f > 0)]
    return float(1.0 / np.mean(1.0 / f)) if f.size else float("nan")


# --------------------------------------------------------------------------------------------------
# heading from the harmonics of planar acceleration (seed 000 sec. III, seed 001 sec. 2.2.3)
# --------------------------------------------------------------------------------------------------
def fourier_coefficients(t: np.ndarray, x: np.ndarray, t0: float, period: float, n_harmonics: int
                         ) -> tuple[np.ndarray, np.ndarray]:
    """Fourier coefficients over one period starting at ``t0`` (seed 000 sec. III; seed 001 eq. 8).

    ``alpha_n = 2/T int x(t) cos(2 pi n (t - t0) / T) dt`` and likewise ``beta_n`` with sine, for
    n = 1..``n_harmonics``; ``x`` may have several columns. Trapezoidal integration over the samples.

    Returns
    -------
    alpha, beta : (n_harmonics, k) arrays.
    """
    t = np.asarray(t, dtype=np.float64)
    x = np.asarray(x, dtype=np.float64).reshape(t.shape[0], -1)
    tau = t - t0
    alpha = np.empty((n_harmonics, x.shape[1]))
    beta = np.empty_like(alpha)
    for n in range(1, n_harmonics + 1):
        w = 2.0 * np.pi * n / period
        alpha[n - 1] = 2.0 / period * np.trapezoid(x * np.cos(w * tau)[:, None], t, axis=0)
        beta[n - 1] = 2.0 / period * np.trapezoid(x * np.sin(w * tau)[:, None], t, axis=0)
    return alpha, beta


def forward_sign(direction: np.ndarray, alpha_h: np.ndarray, beta_h: np.ndarray, alpha_v: float,
                 beta_v: float) -> float:
    """+1 if ``direction`` points forward, -1 if backward, from the gait's phase (decision W2).

    At step frequency the waist's forward acceleration leads its vertical acceleration by 0-90 deg
    (inverted-pendulum gait: forward acceleration while the body falls before initial contact, vertical
    maximum at the contact; seed 003 sec. 3.1: the AP maximum comes immediately before the vertical
    maximum). The complex amplitudes of the projection on ``direction`` and of the vertical component
    (``alpha - i beta``) give that lead; the direction is forward when the lead lies within +-90 deg of
    45 deg.
    """
    d = np.asarray(direction, dtype=np.float64)
    cf = complex(float(alpha_h @ d), -float(beta_h @ d))
    cv = complex(alpha_v, -beta_v)
    if abs(cf) < 1e-12 or abs(cv) < 1e-12:
        return 1.0
    lead = np.angle(cf / cv)
    return 1.0 if np.cos(lead - np.pi / 4) >= 0 else -1.0


def ellipse_axis(alpha: np.ndarray, beta: np.ndarray) -> np.ndarray:
    """Major semi-axis of the first-harmonic ellipse ``a(t) = alpha cos(wt) + beta sin(wt)``.

    Derivation (docs/decisions/waist.md W1, replacing seed 001 eq. 16-20):
    ``|a|^2 = (|alpha|^2 + |beta|^2)/2 + (|alpha|^2 - |beta|^2)/2 cos 2wt + (alpha.beta) sin 2wt``, which is
    largest at ``2wt* = atan2(alpha.beta, (|alpha|^2 - |beta|^2)/2)``; the axis is ``a(t*)``.
    Returns the (2,) vector (zero for a circle: no preferred direction).
    """
    al = np.asarray(alpha, dtype=np.float64)
    be = np.asarray(beta, dtype=np.float64)
    a_coef = 0.5 * (al @ al - be @ be)
    b_coef = float(al @ be)
    if abs(a_coef) < 1e-15 and abs(b_coef) < 1e-15:
        return np.zeros(2)
    wt = 0.5 * np.arctan2(b_coef, a_coef)
    return al * np.cos(wt) + be * np.sin(wt)


def ellipse_direction(t: np.ndarray, a_h: np.ndarray, a_v: np.ndarray, t0: float, t1: float) -> float:
    """Direction (rad, atan2(y, x) in the horizontal frame) of one step ``[t0, t1]`` from the first
    harmonic of its planar acceleration (seed 001 sec. 2.2.3, eq. 10-13, closed form of decision W1),
    the sign chosen by :func:`forward_sign`. NaN if the step has fewer than 4 samples."""
    m = (t >= t0) & (t <= t1)
    if m.sum() < 4:
        return float("nan")
    period = t1 - t0
    alpha, beta = fourier_coefficients(t[m], np.column_stack([a_h[m], a_v[m]]), t0, period, 1)
    axis = ellipse_axis(alpha[0, :2], beta[0, :2])
    if not np.any(axis):
        return float("nan")
    axis = axis * forward_sign(axis, alpha[0, :2], beta[0, :2], alpha[0, 2], beta[0, 2])
    return float(np.arctan2(axis[1], axis[0]))


def tip_to_tail_direction(t: np.ndarray, a_h: np.ndarray, a_v: np.ndarray, t0: float, t1: float,
                          t2: float, *, n_grid: int = 256) -> float:
    """Direction (rad) of the step ``[t1, t2]`` from the tip-to-tail vector of the unbiased second-order
    Fourier approximation of the planar acceleration over the stride ``[t0, t2]`` (seed 000 sec. III,
    Algorithm 1 steps a-d).

    The maxima of ``|a2(t)|`` (periodic over the stride) that lie in the step, or nearest to it, are the
    tip and the tail (the two largest when more lie inside, decision W15); the vector
    joining them is the step's line of motion, oriented forward by :func:`forward_sign` (the
    acceleration phase = tip, decision W2) using the step-frequency (second) harmonic of the stride.
    """
    m = (t >= t0) & (t <= t2)
    if m.sum() < 8 or not (t0 < t1 < t2):
        return float("nan")
    period = t2 - t0
    alpha, beta = fourier_coefficients(t[m], np.column_stack([a_h[m], a_v[m]]), t0, period, 2)
    # the approximation is periodic over the stride: find the maxima of its magnitude over the whole
    # stride (circularly), then keep the two that belong to the step [t1, t2]
    tg = t0 + period * np.arange(n_grid) / n_grid
    tau = tg - t0
    approx = np.zeros((n_grid, 2))
    for n in (1, 2):
        w = 2.0 * np.pi * n / period
        approx += np.outer(np.cos(w * tau), alpha[n - 1, :2]) + np.outer(np.sin(w * tau), beta[n - 1, :2])
    mag = np.hypot(approx[:, 0], approx[:, 1])
    peaks = np.flatnonzero((mag >= np.roll(mag, 1)) & (mag > np.roll(mag, -1)))
    if peaks.size >= 2:
        # distance (s) of each maximum from the step interval; inside = 0, ties broken by magnitude
        dist = np.maximum(t1 - tg[peaks], 0.0) + np.maximum(tg[peaks] - t2, 0.0)
        order = np.lexsort((-mag[peaks], dist))
        top = np.sort(peaks[order[:2]])
        vec = approx[top[0]] - approx[top[1]]
    else:  # degenerate: a single maximum; use the major axis of the step-frequency harmonic
        vec = ellipse_axis(alpha[1, :2], beta[1, :2])
    if not np.any(vec):
        return float("nan")
    vec = vec * forward_sign(vec, alpha[1, :2], beta[1, :2], alpha[1, 2], beta[1, 2])
    return float(np.arctan2(vec[1], vec[0]))


def stride_ellipse_direction(t: np.ndarray, a_h: np.ndarray, a_v: np.ndarray, t0: float, t2: float) -> float:
    """Direction (rad) from the major axis of the step-frequency (second) harmonic over the stride
    ``[t0, t2]``: seed 001's closed-form ellipse (decision W1) on seed 000's stride window, where the
    stride-frequency lateral sway falls in the first harmonic and does not tilt the axis (decision W12).
    Sign by :func:`forward_sign`."""
    m = (t >= t0) & (t <= t2)
    if m.sum() < 8:
        return float("nan")
    alpha, beta = fourier_coefficients(t[m], np.column_stack([a_h[m], a_v[m]]), t0, t2 - t0, 2)
    axis = ellipse_axis(alpha[1, :2], beta[1, :2])
    if not np.any(axis):
        return float("nan")
    axis = axis * forward_sign(axis, alpha[1, :2], beta[1, :2], alpha[1, 2], beta[1, 2])
    return float(np.arctan2(axis[1], axis[0]))


def resolve_axis_signs(directions: np.ndarray, yaw: np.ndarray) -> np.ndarray:
    """Fix 180-degree sign errors of per-step directions with the unit's heading (decision W13).

    A worn unit keeps its yaw offset to the walking direction, so ``direction - yaw`` is about constant;
    a step whose offset points the other way from the majority is flipped. The axis of the offsets is
    their doubled-angle mean; its sign is the one most steps (each signed by :func:`forward_sign`) agree
    on. NaN directions stay NaN.
    """
    d = np.asarray(directions, dtype=np.float64)
    off = d - np.asarray(yaw, dtype=np.float64)
    ok = np.isfinite(off)
    if ok.sum() < 3:
        return d.copy()
    axis = 0.5 * np.angle(np.sum(np.exp(2j * off[ok])))
    votes = np.cos(off[ok] - axis)
    if np.sum(votes > 0) < np.sum(votes < 0):
        axis += np.pi
    out = d.copy()
    flip = ok & (np.cos(off - axis) < 0)
    out[flip] = np.angle(np.exp(1j * (d[flip] + np.pi)))
    return out


#: two directions whose unit vectors sum to less than this have no mean (decision W44)
OPPOSITE_EPS = 1e-9


def circular_mean2(a: float, b: float) -> float:
    """Mean direction of two angles (rad); the A-HE average of two consecutive steps (seed 000 Alg. 1e).

    Two (nearly) opposite directions have no mean (the sum of their unit vectors is rounding residue,
    so its angle is arbitrary): the newer step ``b`` is taken (decision W44)."""
    if not np.isfinite(a):
        return b
    if not np.isfinite(b):
        return a
    s, c = np.sin(a) + np.sin(b), np.cos(a) + np.cos(b)
    if np.hypot(s, c) < OPPOSITE_EPS:
        return float(b)
    return float(np.arctan2(s, c))


# --------------------------------------------------------------------------------------------------
# gyroscope heading (seed 003 sec. 3.3)
# --------------------------------------------------------------------------------------------------
def gyro_bias_360(t: np.ndarray, w_z: np.ndarray, *, turns: float = 1.0) -> float:
    """Vertical gyro bias (rad/s) from a closed walk that turns ``turns`` full circles
    (seed 003 eq. 2): ``b = (int w dt - 2 pi turns) / T``; ``turns`` is signed (+ = left, CCW)."""
    t = np.asarray(t, dtype=np.float64)
    w = np.asarray(w_z, dtype=np.float64)
    if t.size < 2:
        raise DataError("gyro bias calibration: need at least two gyroscope samples")
    total = float(np.trapezoid(w, t))
    return (total - 2.0 * np.pi * turns) / float(t[-1] - t[0])


def rate_integral(t: np.ndarray, w_z: np.ndarray) -> np.ndarray:
    """Running trapezoidal integral of ``w_z`` over ``t`` (rad; 0 at ``t[0]``): pass it as ``cum`` to
    :func:`mean_rate_per_stride` / :func:`integrate_rate` to integrate one signal over many windows in
    one pass (the same values as computing it in each call)."""
    return np.concatenate([[0.0], np.cumsum(0.5 * (w_z[1:] + w_z[:-1]) * np.diff(t))])


def mean_rate_per_stride(t: np.ndarray, w_z: np.ndarray, events: np.ndarray, *,
                         cum: np.ndarray | None = None) -> np.ndarray:
    """Mean vertical rate (rad/s) over the stride around each step (seed 003 sec. 3.3, MRZ without the
    absolute value): for step ``k`` (``events[k]`` to ``events[k+1]``) the stride is
    ``[events[k-1], events[k+1]]``; the first step of a sequence takes the stride that starts with it,
    ``[events[0], events[2]]`` (decision W24: a window of one step keeps the pelvis's per-step yaw
    swing, which cancels only over a stride). One-step sequences use that step. Returns
    ``len(events) - 1`` values. ``cum``: :func:`rate_integral` of ``(t, w_z)`` if already computed."""
    ev = np.asarray(events, dtype=np.float64)
    n = len(ev) - 1
    out = np.full(max(n, 0), np.nan)
    cum = rate_integral(t, w_z) if cum is None else cum
    for k in range(n):
        a, b = (ev[k - 1], ev[k + 1]) if k > 0 else (ev[0], ev[min(2, n)])
        if b <= a:
            continue
        out[k] = (np.interp(b, t, cum) - np.interp(a, t, cum)) / (b - a)
    return out


def integrate_rate(t: np.ndarray, w_z: np.ndarray, t0, t1, *, cum: np.ndarray | None = None):
    """Integral of ``w_z`` over ``[t0, t1]`` (rad), trapezoidal with interpolated ends. ``t0``/``t1``
    may be arrays (one integral per pair, one pass over the signal); scalars give a float. ``cum``:
    :func:`rate_integral` of ``(t, w_z)`` if already computed."""
    cum = rate_integral(t, w_z) if cum is None else cum
    out = np.interp(t1, t, cum) - np.interp(t0, t, cum)
    return float(out) if np.ndim(out) == 0 else out

# --------------------------------------------------------------------------------------------------
# gyroscope heading (seed 003 sec. 3.3) and split steps (W27), shared by track_waist and the live trackers (W92)
# --------------------------------------------------------------------------------------------------
def turn_proba(x: np.ndarray, means, sds, weights) -> np.ndarray:
    """(n, 2) straight / turning probabilities of ``|x|`` (rad/s) under the two-Gaussian mixture ``means``,
    ``sds``, ``weights`` (component 0 straight; seed 003 sec. 3.3, decision W7)."""
    x = np.abs(np.asarray(x, dtype=np.float64)).reshape(-1)
    m, s, w = (np.asarray(v, dtype=np.float64) for v in (means, sds, weights))
    logp = -0.5 * ((x[:, None] - m) / s) ** 2 - np.log(s) + np.log(w)
    logp -= logp.max(axis=1, keepdims=True)
    p = np.exp(logp)
    return p / p.sum(axis=1, keepdims=True)


class TurnPrior:
    """A fixed straight / turning mixture (``pdrlearn.waist.heading.TurnClassifier`` before any fit, as the live
    trackers use it): ``predict(x)`` 1 where the turning component is the more probable."""

    def __init__(self, means, sds, weights):
        w = np.asarray(weights, dtype=np.float64)
        self.means, self.sds, self.weights = np.asarray(means, float), np.asarray(sds, float), w / w.sum()

    def predict(self, x) -> np.ndarray:
        return (turn_proba(x, self.means, self.sds, self.weights)[:, 1] > 0.5).astype(int)


#: Decision W82: the ``slow_turn_rps`` the W74 line suggests for gentle curves (rad/s, 2 deg/s): a straight-called
#: stride is integrated too when the mean rate of the strides k-3..k+1 (within the sequence) reaches it. An option,
#: not the default: it failed its adoption rule on sharp turns by 0.01 m
SLOW_TURN_RPS = 0.035
#: strides before / after stride k in its window: one after, because the live tracker (W64) knows stride k+1 but not
#: always k+2 when it reports k
SLOW_TURN_WINDOW = (3, 1)


def slow_turn_strides(mrz: np.ndarray, threshold_rps: float | None) -> np.ndarray:
    """Decision W82: strides inside a gentle curve, whose 5-stride (:data:`SLOW_TURN_WINDOW`) mean rate reaches
    ``threshold_rps``."""
    x = np.nan_to_num(np.asarray(mrz, np.float64))
    if not threshold_rps or x.size == 0:
        return np.zeros(x.shape, dtype=bool)
    c = np.concatenate([[0.0], np.cumsum(x)])
    k = np.arange(x.size)
    lo = np.maximum(k - SLOW_TURN_WINDOW[0], 0)
    hi = np.minimum(k + SLOW_TURN_WINDOW[1] + 1, x.size)
    return np.abs((c[hi] - c[lo]) / (hi - lo)) >= threshold_rps


#: Decision W543: a gentle curve is a run of at least this many consecutive strides of a sequence whose stride mean
#: vertical rate (MRZ, seed 003 sec. 3.3) keeps its sign and reaches :data:`GENTLE_RPS` in magnitude
GENTLE_RUN = 3
#: Decision W543: the least |MRZ| (rad/s, 1.5 deg/s) of a gentle-curve stride: under seed 003's straight class
#: (W7 prior N(0.03, 0.04), boundary 0.136 rad/s), a 50 m radius walked at 1.3 m/s
GENTLE_RPS = 0.026
#: Decision W543: the gyro heading keeps gentle curves by default (adopted by its rule: users 15580-15619, gentle
#: curves' mean final error 86.536 -> 7.866 m, sharp turns and straight walks unchanged, a 0.5 deg/s bias +0.103 m)
#: Decision W544: W543's run test reads each stride's mean rate less W105's reading at rest (offline); adopted by its
#: rule (users 16140-16159: route C with a 2 deg/s bias 54.379 -> 14.830 m, gentle curves 7.415 -> 7.491 m).
#: The options' defaults (W413: an adopted rule is the code; its off switch a keyword option, not a module boolean)
GENTLE_DEFAULTS = {"gentle_curves": True, "gentle_rest_bias": True}


def gentle_rest_rate(at_rest: tuple[float, float, float] | None, on: bool = True) -> float:
    """Decision W544: the rate (rad/s) W543's gentle-curve test takes from each stride's MRZ: W105's reading over the
    first standstill (``still_yaw_rate``'s ``(rate, t0, t1)``, at any level) when ``on``; 0 without one."""
    return float(at_rest[0]) if on and at_rest is not None and np.isfinite(at_rest[0]) else 0.0


def gentle_curve_strides(mrz: np.ndarray, integrated: np.ndarray, *, run: int = GENTLE_RUN,
                         rps: float = GENTLE_RPS) -> np.ndarray:
    """Decision W543: the steps of a gentle curve that seed 003's integration leaves out. Step ``k`` qualifies when
    it is not ``integrated``, neither is the other step of its stride window (step ``k-1``; step 1 for the first,
    W24), and a run of ``run`` consecutive strides holding ``k`` and ending at ``k`` or ``k+1`` (one stride of
    look-ahead, as W82's window: the live tracker knows it, W64) all have ``|mrz| >= rps`` with ``mrz[k]``'s sign."""
    x = np.nan_to_num(np.asarray(mrz, np.float64))
    done = np.asarray(integrated, dtype=bool)
    n = x.size
    q = np.where(np.abs(x) >= rps, np.sign(x), 0.0)
    out = np.zeros(n, dtype=bool)
    for k in range(n):
        other = k - 1 if k > 0 else 1
        if q[k] == 0 or done[k] or (other < n and done[other]):
            continue
        for a in (k - run + 1, k - run + 2):  # the windows holding k that end at k or k + 1
            b = a + run
            if a >= 0 and b <= n and np.all(q[a:b] == q[k]):
                out[k] = True
                break
    return out


def gyro_headings(t: np.ndarray, w_z: np.ndarray, events: np.ndarray, *, predict,
                  bias_rps: float = 0.0, heading0: float = 0.0, cum: np.ndarray | None = None,
                  slow_turn_rps: float = 0.0, gentle_curves: bool = False,
                  gentle_bias_rps: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Per-step heading from the vertical gyroscope, integrated only over turning strides
    (seed 003 sec. 3.3).

    Each step's stride mean rate is classified (``predict``: |MRZ| (m,) -> 0/1, e.g.
    :meth:`TurnPrior.predict`); the rate (minus ``bias_rps``, seed 003 eq. 2) is
    integrated over the steps classified as turning and over the step before and after each of them
    (seed 003: "integrate two straight steps occurring before and after a curved walking step"), and over
    the strides of a gentle curve when ``slow_turn_rps`` > 0 (:func:`slow_turn_strides`, decision W82).
    ``gentle_curves`` (decision W543): the steps of a run of same-sign strides (:func:`gentle_curve_strides`) that
    are not integrated add their stride's mean rate times their duration (the stride mean holds no pelvic swing).
    ``gentle_bias_rps`` (decision W544): a rate at rest (W105's reading) taken from MRZ before that run test and
    that sum only (seed 003's integration keeps ``w_z - bias_rps``). ``cum``: :func:`rate_integral` of
    ``(t, w_z - bias_rps)`` when the caller integrates the same rate over many sequences (one pass over the
    recording, W43).

    Returns
    -------
    headings : (m - 1,) heading during each step (rad); turning : (m - 1,) 0/1 classification.
    """
    ev = np.asarray(events, dtype=np.float64)
    n = len(ev) - 1
    if n <= 0:
        return np.zeros(0), np.zeros(0, dtype=int)
    w = w_z - bias_rps
    cum = rate_integral(t, w) if cum is None else cum
    mrz = mean_rate_per_stride(t, w, ev, cum=cum)
    turning = np.asarray(predict(np.nan_to_num(mrz)))
    integrate = turning.astype(bool).copy()
    integrate[1:] |= turning[:-1].astype(bool)
    integrate[:-1] |= turning[1:].astype(bool)
    mrz_g = mrz - gentle_bias_rps  # W544: W543's curves judged on the rate less the reading at rest
    gentle = gentle_curve_strides(mrz_g, integrate) if gentle_curves else np.zeros(n, dtype=bool)  # W543
    integrate |= slow_turn_strides(mrz, slow_turn_rps)  # W82, off by default
    dpsi = integrate_rate(t, w, ev[:-1], ev[1:], cum=cum)
    gentle_dpsi = np.nan_to_num(mrz_g) * np.diff(ev)  # W543: the stride's mean rate over the step
    heading = np.empty(n)
    h = heading0
    for k in range(n):
        if integrate[k]:
            h += dpsi[k]
        elif gentle[k]:
            h += gentle_dpsi[k]
        heading[k] = h
    return heading, turning


#: Decision W74: a gyro-headed waist track warns when the waist's own yaw, integrated from the first contact to the
#: end of a step, and that step's heading differ by this much (deg) at some step: a turn the headings dropped
UNTRACKED_TURN_WARN_DEG = 60.0


def turn_gap(gyro_yaw, heading):
    """Decision W80: gyroscope yaw minus step heading (rad) as a direction difference, wrapped to (-pi, pi]: either
    may be wrapped, and a wrapped U-turn must not read as a missed full turn."""
    return np.angle(np.exp(1j * (np.asarray(gyro_yaw, np.float64) - np.asarray(heading, np.float64))))


def untracked_turn_message(diff_deg: float, t_s: float, integrate_stops: bool) -> str:
    """The one warning line of decision W74 (shared with :class:`pdrlearn.waist.live.WaistTracker`)."""
    cause = ("turns made during undetected steps or while standing are dropped with integrate_stops off: set "
             "\"options\": {\"integrate_stops\": true} in the PARAMS.json (or integrate_stops=True)"
             if not integrate_stops else
             "a turn on strides the turn classifier called straight (a gentle curve under 8 deg/s that no run of "
             f"strides over 1.5 deg/s kept: {decision_ref('W82', 'W543')}) "
             "or a gyroscope bias; for curves set \"options\": {\"slow_turn_rps\": 0.035} (live too) or "
             "{\"heading\": \"ellipse\"} in the PARAMS.json, or use '--pipeline waist-pll'; for a bias calibrate "
             "on a walk with a full turn ('pdrlearn calibrate --turns 1 --fit-turns')")
    return (f"the step headings miss {diff_deg:+.0f} deg of the waist gyroscope's turn by {t_s:.1f} s "
            f"(decision W74): the positions after it are off; {cause}")


FRAGMENT_FRAC = 0.5
MIN_FRAGMENT_SEQ = 3  # steps a sequence needs for its median step to judge fragments by


def fragment_windows(start_s: np.ndarray, end_s: np.ndarray, has_next: np.ndarray) -> dict[int, tuple[int, int]]:
    """Steps that carry a split step's length (decision W27): ``{owner: (first_row, last_row)}``.

    In a walking sequence (consecutive rows with ``has_next``, closed by a row without) of at least
    :data:`MIN_FRAGMENT_SEQ` steps, a step (IC to next IC) shorter than :data:`FRAGMENT_FRAC` x the
    sequence's median step is a fragment: it is merged with the neighbouring non-fragment step of the
    sequence that makes the merged duration closest to the median, and that neighbour (the owner) spans
    rows ``first_row .. last_row`` (its pendulum h is taken over the merged window); the fragment carries
    no length. Rows not in the result keep their own window. A fragment without a non-fragment neighbour
    is left alone.
    """
    t0, t1 = np.asarray(start_s, dtype=np.float64), np.asarray(end_s, dtype=np.float64)
    hn = np.asarray(has_next, dtype=bool)
    dur = t1 - t0
    out: dict[int, tuple[int, int]] = {}
    seq: list[int] = []
    for i in range(hn.size + 1):
        if i < hn.size and hn[i]:
            seq.append(i)
            continue
        if len(seq) >= MIN_FRAGMENT_SEQ:
            med = float(np.median(dur[seq]))
            frag = {j for j in seq if dur[j] < FRAGMENT_FRAC * med}
            for j in sorted(frag):
                nbs = [k for k in (j - 1, j + 1) if k in seq and k not in frag]
                if not nbs:
                    continue
                k = min(nbs, key=lambda q: abs(dur[q] + dur[j] - med))
                a, b = out.get(k, (k, k))
                out[k] = (min(a, j), max(b, j))
        seq = []
    return out


#: decision W87: a calibrated step length applied more than this fraction off its calibration rate warns
RATE_MISMATCH = 0.1


def rate_mismatch_line(calibrated_hz: float, rate_hz: float, where: str) -> str | None:
    """Decision W87's warning when a step length calibrated at ``calibrated_hz`` is applied at ``rate_hz`` more
    than :data:`RATE_MISMATCH` away and the lower of the two is under B465's ``RATE_MATTERS_HZ``, else None (also
    for an unknown calibration rate, NaN)."""
    from pdrlearn.kernels.distance import RATE_MATTERS_HZ, rate_matters

    if (not np.isfinite(calibrated_hz) or abs(rate_hz - calibrated_hz) <= RATE_MISMATCH * calibrated_hz
            or not rate_matters(calibrated_hz, rate_hz)):  # B465
        return None
    return (f"{where}: step length calibrated at {calibrated_hz:.4g} Hz, applied to a {rate_hz:.4g} Hz recording: "
            f"under {RATE_MATTERS_HZ:g} Hz the calibrated factor depends on the rate (K moved 3.2-5.1 % from 25 Hz to "
            "50-1000 Hz, at most 0.72 % among 50-1000 Hz; decisions W87, B465); re-calibrate on a walk "
            f"recorded at {rate_hz:.4g} Hz: pdrlearn calibrate WALK --distance METERS --out PARAMS.json")
