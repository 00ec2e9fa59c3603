"""Streaming input stage of the tracker: causal resampling to the bundle's rate and the stream-lag check
(decisions E22 and E23 in docs/decisions/export.md; numpy only, like the rest of :mod:`pdrlearn.runtime`).

* :class:`StreamResampler` — one sensor stream resampled causally onto the grid ``k / rate_out`` (s) with
  bounded state. Downsampling first low-passes the input with a linear-phase windowed-sinc FIR whose delay
  is compensated in the timestamps (each filtered sample keeps the time of its centre tap; it is emitted
  ``(n_taps - 1) / 2`` input samples late), then interpolates linearly; upsampling interpolates linearly.
  Every output sample is computed from the same input samples with the same operations in the same order
  whatever the chunking, so pushes of any sizes give the output of one big push, bit for bit.
* :class:`InputStage` — per sensor: its input rate is the caller's declared one (``Tracker(input_rates_hz=...)``,
  ``pdrlearn run`` gives the session's) or else learned from its first samples (median interval of the
  first :data:`RATE_PROBE` samples or :data:`RATE_PROBE_S` s); then the stream passes through (rate within
  the bundle's tolerance), is resampled, or refused (``resample=False``: the rate ``DataError`` of E3). A
  stream the bundle does not use is ignored from its first sample.
* :func:`stopped_message` — the one line of decision E23 for a stream that stopped.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from pdrlearn.errors import DataError, message_number
from pdrlearn.kernels.distance import classifier_rate_warning
from pdrlearn.kernels.order import first_out_of_order

#: a stream's rate, when the caller does not declare it, is the median interval of its first RATE_PROBE samples,
#: or of those in its first RATE_PROBE_S s when that comes first (at least RATE_PROBE_MIN samples): a few
#: irregular samples at the start (a burst, a late first sample) do not decide it (decision E22, amended)
RATE_PROBE = 32
#: decision E239 (ours): a resampled stream's raw input times kept this many seconds back from its newest, so that a
#: packet sent again is found whole by ``Tracker(drop_duplicate_timestamps=True)`` (its buffer holds the output grid)
RECENT_RAW_S = 5.0
RATE_PROBE_S = 1.0
RATE_PROBE_MIN = 5
#: decision E29: a stream whose rate is more than this factor away from the bundle's is refused rather than
#: tracked: its timestamps are not in seconds (in ms a 20 Hz stream reads as 0.02 Hz and gives no step; real
#: accelerometer and gyroscope rates, 10-1000 Hz, stay within it of every bundle rate, 20-100 Hz; judged on
#: those streams only, a barometer may run at 1 Hz)
RATE_UNIT_FACTOR = 100.0
#: decision B452: a barometer's timestamps are judged by this least rate (Hz; one sample per 10 s) instead: the
#: slowest barometer documented here is E39's 0.2 Hz, and ms timestamps of a 1-100 Hz barometer give 0.001-0.1 Hz
#: (0.1 Hz itself refused: ``<=``, session 45, FM, review R3 F4)
#: (before, the barometer was not judged at all: trial T2's one-sample barometer packets in ms passed, F8)
BARO_MIN_HZ = 0.1
#: centres filtered together in one block of :meth:`StreamResampler._filter_at` (bounds its memory)
_BLOCK = 64
#: input intervals longer than this (s) are not bridged: the resampler ends the segment and restarts at the
#: next sample (decision B11's gap length; shorter gaps are interpolated, as ``resample_stream`` does)
GAP_S = 1.0
#: anti-alias FIR (decision E22): pass band up to PASS x the output Nyquist rate, stop band from the output
#: Nyquist rate, cut-off in the middle; Hamming window, whose transition width is 3.3 / n_taps of the input
#: rate and whose stop band is >= 53 dB (Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed.,
#: Table 7.2; Smith, The Scientist and Engineer's Guide to DSP, ch. 16)
PASS = 0.8
HAMMING_WIDTH = 3.3


def lowpass_taps(rate_in: float, rate_out: float) -> np.ndarray:
    """Linear-phase low-pass FIR (odd length, unit DC gain) for resampling ``rate_in`` -> ``rate_out`` Hz
    (``rate_out < rate_in``): Hamming-windowed sinc, cut-off ``(1 + PASS) / 2`` x the output Nyquist rate,
    transition band ``PASS`` .. 1 x the output Nyquist rate (decision E22)."""
    nyq = 0.5 * rate_out
    fc = 0.5 * (1.0 + PASS) * nyq / rate_in  # cut-off in cycles per input sample
    width = (1.0 - PASS) * nyq / rate_in  # transition width in cycles per input sample
    n = int(math.ceil(HAMMING_WIDTH / width)) | 1  # odd: a centre tap, an integer delay
    m = np.arange(n) - (n - 1) // 2
    h = 2.0 * fc * np.sinc(2.0 * fc * m) * np.hamming(n)
    return h / h.sum()


def native_message(rates: dict[str, float], rate_hz: float) -> str:
    """The one line that says streams at another rate are tracked at their own rate (E22 amended); decision E304:
    it names the delay ``--resample``'s low-pass filter would add (the longest of the streams', ``latency_s``)."""
    what = ", ".join(f"{n} {r:.4g} Hz" for n, r in rates.items())
    delay = max((StreamResampler(r, rate_hz).latency_s for r in rates.values() if r > rate_hz), default=0.0)
    added = f" (its low-pass filter delays every step by {delay * 1e3:.0f} ms more)" if delay else ""
    return (f"{what}: not the bundle's {rate_hz:.4g} Hz; tracked at the data's own rate, as `pdrlearn track "
            "--streaming` does (the features are defined in seconds); `--resample` resamples to the bundle's "
            f"rate instead{added}, `--no-resample` refuses")


class StreamResampler:
    """Causal resampling of one stream (``(t (n,), values (n, k))`` pushes) onto ``k / rate_out`` (s).

    State: the last ``n_taps - 1`` input samples (downsampling) and the last filtered sample, so bounded.
    ``push`` returns the output samples that the inputs so far determine; ``flush`` the rest (the FIR's
    last ``(n_taps - 1) / 2`` samples, computed with the last input repeated, as the first ones are
    computed with the first input repeated).
    """

    def __init__(self, rate_in: float, rate_out: float):
        self.rate_in, self.rate_out = float(rate_in), float(rate_out)
        self.taps = lowpass_taps(rate_in, rate_out) if rate_in > rate_out else None
        self.delay = 0 if self.taps is None else (len(self.taps) - 1) // 2  # input samples
        self._ht = np.empty(0)  # raw input samples not yet past the filter's centre (times, values)
        self._hv: np.ndarray | None = None
        self._pt: float | None = None  # the last filtered sample (interpolation's left node)
        self._pv: np.ndarray | None = None
        self._k: int | None = None  # next output grid index
        self._last_in: float | None = None  # time of the last input sample (s)

    @property
    def last_in(self) -> float | None:
        """Time (s) of the last input sample of the current segment (None at the start of one)."""
        return self._last_in

    @property
    def latency_s(self) -> float:
        """Delay of the output behind the input (s): the FIR's half length plus one input interval."""
        return (self.delay + 1) / self.rate_in

    def push(self, t: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t = np.asarray(t, dtype=np.float64).reshape(-1)
        v = np.asarray(v, dtype=np.float64)
        if not len(t):
            return _cat([], v.shape[-1] if v.ndim == 2 else 1)
        v = v.reshape(len(t), -1)
        outs = []
        prev = self._last_in if self._last_in is not None else t[0]
        gaps = np.flatnonzero(np.diff(t, prepend=prev) > GAP_S)
        i = 0
        for g in gaps.tolist():  # a long gap ends the segment: nothing is made up inside it (B11)
            if g > i:
                outs.append(self._feed(t[i:g], v[i:g]))
            outs.append(self.flush())
            i = g
        outs.append(self._feed(t[i:], v[i:]))
        self._last_in = float(t[-1])
        return _cat(outs, v.shape[1])

    def flush(self) -> tuple[np.ndarray, np.ndarray]:
        """The output samples still held by the filter (end of a segment or of the recording); the next
        push starts a new segment."""
        if self._hv is None or self.delay == 0 or not len(self._ht):
            out = _cat([], 0 if self._hv is None else self._hv.shape[1])
        else:
            d = self.delay
            pad_t = self._ht[-1] + (np.arange(1, d + 1) / self.rate_in)  # times of the repeated last sample
            out = self._centres(np.concatenate([self._ht, pad_t]),
                                np.concatenate([self._hv, np.repeat(self._hv[-1:], d, axis=0)]), len(self._ht) - d)
        self._ht, self._hv, self._pt, self._pv, self._k, self._last_in = np.empty(0), None, None, None, None, None
        return out

    def _feed(self, t: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        d = self.delay
        if self._hv is None:  # a new segment: the first sample repeated d times before it
            self._ht = t[0] - np.arange(d, 0, -1) / self.rate_in
            self._hv = np.repeat(v[:1], d, axis=0)
        ht, hv = np.concatenate([self._ht, t]), np.concatenate([self._hv, v])
        if d == 0:
            self._ht, self._hv = ht[-1:], hv[-1:]  # nothing to filter: the last sample only marks the segment
            return self._interp(t, v)
        n = len(ht) - 2 * d  # centres (from index d) with their whole support
        if n <= (self._pt is not None):  # nothing new (the first centre is the last push's right node)
            self._ht, self._hv = ht, hv
            return _cat([], v.shape[1])
        out = self._centres(ht, hv, n)
        self._ht, self._hv = ht[n - 1:], hv[n - 1:]  # from the support of the last centre (the next left node)
        return out

    def _centres(self, ht: np.ndarray, hv: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """The output grid samples up to the ``n``-th centre (``ht[d:d + n]``; the first one is the last
        push's right node when the segment goes on). Only the centres that bracket an output time are
        filtered (decision E22: ~2 per output sample, not one per input sample), each by the same sum."""
        d = self.delay
        ct = ht[d:d + n]
        if self._pt is None:  # a new segment: the grid from its first centre
            self._k = math.ceil(float(ct[0]) * self.rate_out)
            while self._k / self.rate_out < ct[0]:  # rounding of the product
                self._k += 1
        self._pt = float(ct[-1])
        tg = _grid(self._k, float(ct[-1]), self.rate_out)
        if not len(tg):
            return _cat([], hv.shape[1])
        self._k += len(tg)
        i = np.searchsorted(ct, tg, side="right") - 1  # left node of each output time (ct[i] <= tg)
        need = np.unique(np.concatenate([i, np.minimum(i + 1, n - 1)]))
        y = self._filter_at(hv, need)
        out = np.empty((len(tg), hv.shape[1]))
        for j in range(hv.shape[1]):
            out[:, j] = np.interp(tg, ct[need], y[:, j])
        return tg, out

    def _filter_at(self, hv: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """FIR output at the centres ``idx`` (their support ``hv[idx:idx + n_taps]``): products, then a
        running sum in tap order (``np.add.accumulate`` is sequential), so a centre's value has the same
        bits whichever push or block computes it."""
        if len(idx) * hv.shape[1] >= _BLOCK * 4:  # many centres (a long push): tap by tap over their span,
            lo, hi = int(idx[0]), int(idx[-1]) + 1  # the same products and running sums, fewer numpy calls
            h = self.taps.tolist()
            acc = h[0] * hv[lo:hi]
            for j in range(1, len(h)):
                acc += h[j] * hv[lo + j:hi + j]
            return acc[idx - lo]
        taps = self.taps[None, :, None]
        k = np.arange(len(self.taps))
        out = np.empty((len(idx), hv.shape[1]))
        for b in range(0, len(idx), _BLOCK):
            w = hv[idx[b:b + _BLOCK, None] + k]  # (block, taps, channels)
            out[b:b + _BLOCK] = np.add.accumulate(taps * w, axis=1)[:, -1]
        return out

    def _interp(self, t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Output grid samples up to ``t[-1]`` by linear interpolation between consecutive filtered samples
        (the left node of the first interval is the previous push's last sample)."""
        if self._pt is None:
            xt, xv = t, y
            self._k = math.ceil(float(t[0]) * self.rate_out)
            while self._k / self.rate_out < t[0]:  # rounding of the product
                self._k += 1
        else:
            xt, xv = np.concatenate([[self._pt], t]), np.concatenate([self._pv, y])
        self._pt, self._pv = float(t[-1]), y[-1:].copy()
        tg = _grid(self._k, float(xt[-1]), self.rate_out)
        if not len(tg):
            return _cat([], y.shape[1])
        self._k += len(tg)
        out = np.empty((len(tg), y.shape[1]))
        for j in range(y.shape[1]):
            out[:, j] = np.interp(tg, xt, xv[:, j])
        return tg, out


def _grid(k: int, t_max: float, rate: float) -> np.ndarray:
    """Output times ``j / rate`` (s) for ``j = k, k + 1, ...`` up to ``t_max``."""
    k1 = int(math.floor(t_max * rate)) + 2
    tg = np.arange(k, max(k1, k)) / rate
    return tg[tg <= t_max]


def probe_rate(t: np.ndarray) -> float:
    """A stream's rate (Hz) from its first samples: the median interval (decision E22)."""
    return 1.0 / float(np.median(np.diff(t)))


def _checked(name: str, t, v, last: float | None) -> tuple[np.ndarray, np.ndarray]:
    """The tracker's own input errors (decision E3's wording) for a stream about to be resampled: the
    resampler would spread a NaN over its taps and interpolate garbage between unordered times."""
    t = np.asarray(t, dtype=np.float64).reshape(-1)
    if not len(t):
        return t, np.asarray(v, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64).reshape(len(t), -1)
    if not (np.isfinite(t).all() and np.isfinite(v).all()):
        raise DataError(f"{name}: pushed samples contain NaN/inf; clean the stream before tracking")
    i = first_out_of_order(t, -math.inf if last is None else last)
    if i is not None:
        raise DataError(f"{name}: pushed timestamps are not increasing (at {t[i]:.3f} s); push samples in time "
                        "order")
    return t, v


def _cat(parts, k: int) -> tuple[np.ndarray, np.ndarray]:
    parts = [p for p in parts if len(p[0])]
    if not parts:
        return np.empty(0), np.empty((0, k))
    if len(parts) == 1:
        return parts[0]
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


#: decision B382: the timestamp unit whose factor to seconds is nearest (in decades) to the rate ratio, and its fix
_UNIT_HINTS = ((1e3, "are they in ms? push t in seconds (t_ms / 1000)"),
               (1e6, "are they in us? push t in seconds (t_us / 1e6)"),
               (1e9, "are they in ns (an Android event timestamp)? push t in seconds (t_ns / 1e9)"))


def _unit_hint(ratio: float) -> str:
    """Decision B382: the hint of :data:`_UNIT_HINTS` whose factor is nearest to ``ratio`` on a log scale."""
    return min(_UNIT_HINTS, key=lambda h: abs(math.log10(ratio) - math.log10(h[0])))[1]


def check_rate_unit(name: str, rate_hz: float, nominal_hz: float, nominal_what: str = "") -> None:
    """Decision E29: a one-line :class:`DataError` when pushed timestamps give a rate more than
    :data:`RATE_UNIT_FACTOR` away from the nominal one: they are not in seconds. ``name`` opens the message;
    ``nominal_what`` names the nominal rate (e.g. ``"the bundle's "``, ``"fs="``); decision B424: the factor as
    :func:`pdrlearn.errors.message_number` writes it."""
    num = message_number
    f = rate_hz / nominal_hz
    if f < 1.0 / RATE_UNIT_FACTOR:
        raise DataError(f"{name}: the pushed timestamps give {rate_hz:.3g} Hz, {num(1.0 / f, 0)}x below {nominal_what}"
                        f"{nominal_hz:g} Hz: {_unit_hint(1.0 / f)}")
    if f > RATE_UNIT_FACTOR:
        raise DataError(f"{name}: the pushed timestamps give {rate_hz:.3g} Hz, {num(f, 0)}x above {nominal_what}"
                        f"{nominal_hz:g} Hz: push t in seconds")


class InputStage:
    """The tracker's input side for streams whose rate may differ from the bundle's (decision E22).

    ``push(samples)`` takes ``{sensor: (t, values)}`` and returns the samples to buffer: unchanged for a
    stream at the bundle's rate (within its tolerance), resampled to it for another rate (``resample``)
    or, without ``resample``, the rate ``DataError`` of decision E3. A stream's rate is ``rates_hz[name]``
    when the caller declares it (a recording knows its rates), else learned from its first samples (held
    until then, :func:`probe_rate`). A stream the bundle does not use is ignored (``ignored``, logged once).
    """

    def __init__(self, bundle, *, resample: bool | str = "native", rates_hz: dict[str, float] | None = None,
                 used=None):
        self.bundle = bundle
        self.rate_hz = float(bundle.rate_hz)
        #: the sensors read (default: the bundle's; a foot-only tracker's, decision E26)
        self.used = frozenset(bundle.used_sensors if used is None else used)
        if resample not in (True, False, "native"):
            raise ValueError(f"resample must be True, False or 'native', not {resample!r}")
        #: "native" (default): a stream at another rate is tracked at its own rate, as `pdrlearn track
        #: --streaming` does (E22 amended); True: resampled to the bundle's rate; False: refused (E3)
        self.resample = resample
        #: sensor -> its input rate (Hz): declared, or learned from its first samples
        self.input_rates_hz: dict[str, float] = {}
        #: sensor -> its resampler (only the streams at another rate)
        self.resamplers: dict[str, StreamResampler] = {}
        self._probe: dict[str, tuple[list, list]] = {}
        self._last_raw: dict[str, float] = {}  # resampled streams: time of the last input sample (s)
        self._recent: dict[str, np.ndarray] = {}  # resampled streams: their last RECENT_RAW_S of input times (E239)
        self.passed: set[str] = set()  # streams at the bundle's rate, passed through unchanged
        #: sensor -> why its samples are dropped (the bundle does not use it; an optional stream that stopped)
        self.ignored: dict[str, str] = {}
        #: (logging level, line) for the caller to report once: the resampling (warning level, one line per
        #: call that finds streams to resample, decision E22); each ignored stream (debug level: logged once,
        #: not a warning, as the sensors a recording carries beyond the bundle's are normal)
        self.messages: list[tuple[int, str]] = []
        declared = {n: float(r) for n, r in (rates_hz or {}).items()
                    if n in self.used and math.isfinite(r) and r > 0}
        if declared:
            self._decide(declared, where="declared rates")

    def unit_check(self, rates: dict[str, float]) -> None:
        """Decision E29: a one-line :class:`DataError` for a stream whose rate (Hz) is more than
        :data:`RATE_UNIT_FACTOR` away from the bundle's (a barometer's: under :data:`BARO_MIN_HZ`, decision
        B452): its timestamps are not in seconds."""
        for n, r in rates.items():
            if n.endswith("Barometer"):  # decision B452: a barometer may run at 1 Hz or slower, not at 0.1 Hz
                if r <= BARO_MIN_HZ:  # B452 amended (review R3 F4): a 100 Hz barometer in ms reads as 0.1 Hz
                    raise DataError(f"{n}: the pushed timestamps give {r:.3g} Hz, under any barometer's rate "
                                    f"({BARO_MIN_HZ:g} Hz, one sample per 10 s; decision B452): "
                                    f"{_unit_hint(10.0 / r)}")  # the hint for a 10 Hz barometer
                continue
            check_rate_unit(n, r, self.rate_hz, "the bundle's ")  # B452: every stream at the IMUs' rates

    def check_rate(self, name: str, t: np.ndarray) -> None:
        """:meth:`refuse` the rate a push of ``t`` (s) would teach for a stream whose rate is being learned,
        before any state changes (decision E29); nothing for a stream whose rate is known."""
        if name in self.input_rates_hz or name not in self.used:
            return
        p = self._probe.get(name)
        tt = np.concatenate([*p[0], t]) if p and p[0] else t
        if len(tt) < RATE_PROBE and not (len(tt) >= RATE_PROBE_MIN and tt[-1] - tt[0] >= RATE_PROBE_S):
            return
        self.refuse({name: probe_rate(tt[:RATE_PROBE])}, where="pushed " + name)

    def refuse(self, rates: dict[str, float], where: str) -> dict[str, float]:
        """The one-line :class:`DataError` of a stream whose rate (sensor -> Hz) is refused: timestamps not in
        seconds (:meth:`unit_check`) or, with ``resample=False``, a rate off the bundle's; else the off-rate
        streams (decision E29: :meth:`check_rate` asks it before a push changes anything, :meth:`_decide` after)."""
        self.unit_check(rates)
        off = self.bundle.off_rate(rates)
        if off and self.resample is False:
            self.bundle.check_rates(off, where=where)
        return off

    def _decide(self, rates: dict[str, float], where: str) -> None:
        """Pass, resample or refuse the streams of ``rates`` (sensor -> input rate, Hz)."""
        off = self.refuse(rates, where)
        self.input_rates_hz.update(rates)
        if self.resample == "native":  # E22 amended: the data's own rate, as track --streaming
            self.passed.update(rates)
            if off:
                self.messages.append((logging.WARNING, native_message(off, self.rate_hz)))
                units = {u: {"trained_hz": self.rate_hz, "session_hz": off[f"{u[0]}Accelerometer"]}
                         for u in ("foot", "waist") if f"{u[0]}Accelerometer" in off}
                if units and self.bundle.tasks:  # decision C18 amended: the classifiers' rate, as track says
                    self.messages.append((logging.WARNING, classifier_rate_warning(units)))
            return
        self.passed.update(n for n in rates if n not in off)
        for n, fs in off.items():
            self.resamplers[n] = StreamResampler(fs, self.rate_hz)
        if off:
            self.messages.append((logging.WARNING, resample_message({n: self.resamplers[n] for n in off},
                                                                    self.rate_hz)))

    def ignore(self, name: str, why: str) -> None:
        """Drop ``name``'s samples from now on."""
        self.ignored[name] = why
        self.passed.discard(name)
        self.resamplers.pop(name, None)
        self._probe.pop(name, None)
        self._recent.pop(name, None)

    def last_in(self, name: str) -> float | None:
        """Time (s) of the newest sample received of a stream that is resampled or whose rate is being
        learned (None otherwise: its buffer's last sample is)."""
        if name in self._last_raw:
            return self._last_raw[name]
        p = self._probe.get(name)
        return float(p[0][-1][-1]) if p and p[0] else None

    def raw_times(self, name: str) -> np.ndarray:
        """Decision E239: the input times (s, increasing) of ``name`` held here: a resampled stream's last
        :data:`RECENT_RAW_S` s, a stream still probed for its rate all of its probe; empty otherwise (its buffer
        holds them)."""
        if name in self._recent:
            return self._recent[name]
        p = self._probe.get(name)
        return np.concatenate(p[0]) if p and p[0] else np.empty(0)

    def _took_raw(self, name: str, t: np.ndarray) -> None:
        """Decision E239: note the input times ``t`` of the resampled stream ``name`` (its last RECENT_RAW_S s)."""
        tt = np.concatenate([self._recent.get(name, np.empty(0)), np.asarray(t, dtype=np.float64)])
        self._recent[name] = tt[tt >= tt[-1] - RECENT_RAW_S]
        self._last_raw[name] = float(tt[-1])

    def push(self, samples: dict) -> dict:
        if self.passed.issuperset(samples):  # every stream known and at the bundle's rate
            return samples
        out, learned = {}, {}
        for name, (t, v) in samples.items():
            if name in self.passed:
                out[name] = (t, v)
                continue
            r = self.resamplers.get(name)
            if r is not None:
                t, v = _checked(name, t, v, self._last_raw.get(name))
                if len(t):
                    out[name] = r.push(t, v)
                    self._took_raw(name, t)
                continue
            if name in self.ignored:
                continue
            if name not in self.used:
                self.ignore(name, "the bundle does not use it")
                self.messages.append((logging.DEBUG, f"{name}: the bundle does not use it; its samples are ignored"))
                continue
            pt, pv = self._probe.setdefault(name, ([], []))
            t, v = _checked(name, t, v, float(pt[-1][-1]) if pt else None)  # the errors now, not samples later
            if not len(t):
                continue
            pt.append(t)
            pv.append(v)
            tt = np.concatenate(pt)
            if len(tt) < RATE_PROBE and not (len(tt) >= RATE_PROBE_MIN and tt[-1] - tt[0] >= RATE_PROBE_S):
                continue
            del self._probe[name]
            learned[name] = (tt, np.concatenate(pv))
        if learned:  # the streams whose rate this push told: one announcement for them
            self._decide({n: probe_rate(tt[:RATE_PROBE]) for n, (tt, _) in learned.items()},
                         where="pushed " + ", ".join(learned))
            for name, (tt, vv) in learned.items():
                if name in self.passed:
                    out[name] = (tt, vv)
                else:
                    out[name] = self.resamplers[name].push(tt, vv)
                    self._took_raw(name, tt)
        return {n: tv for n, tv in out.items() if len(tv[0])}

    def flush(self) -> dict:
        """The samples still held: probes of streams that never reached their rate probe and each
        resampler's filter tail (end of the recording)."""
        out = {n: (np.concatenate(pt), np.concatenate(pv)) for n, (pt, pv) in self._probe.items()}
        self._probe.clear()
        for name, r in self.resamplers.items():
            t, v = r.flush()
            if len(t):
                out[name] = (t, v)
        return out


def resampled_text(resamplers: dict[str, StreamResampler], *, latency: bool = True) -> str:
    """The resampled streams grouped by input rate, each group with its filter (and its delay, ``latency``):
    ``fAccelerometer, fGyroscope sampled at 100 Hz (83-tap linear-phase low-pass + linear interpolation, 420 ms
    delay)``; shared by :func:`resample_message` and the offline ``--resample`` line (decision B113)."""
    groups: dict[float, list[str]] = {}
    for n, r in resamplers.items():
        groups.setdefault(r.rate_in, []).append(n)
    parts = []
    for rate_in, names in groups.items():
        r = resamplers[names[0]]
        how = ("linear interpolation" if r.taps is None
               else f"{len(r.taps)}-tap linear-phase low-pass + linear interpolation")
        delay = f", {r.latency_s * 1e3:.0f} ms delay" if latency else ""
        parts.append(f"{', '.join(names)} sampled at {rate_in:.4g} Hz ({how}{delay})")
    return "; ".join(parts)


def resample_message(resamplers: dict[str, StreamResampler], rate_out: float) -> str:
    """The one line that announces the resampled streams (decision E22), grouped by input rate."""
    return (f"{resampled_text(resamplers)}, the bundle at {rate_out:.4g} Hz: resampling to {rate_out:.4g} Hz as "
            "the samples stream in; the resampled windows are not the ones the classifiers were trained on, and on "
            "simulated 50 Hz walks into a 20 Hz bundle most strides came out backward (E22): prefer the default, which "
            "tracks the data at its own rate as `pdrlearn track --streaming` does; --no-resample / "
            "Tracker(resample=False) refuses instead")


def stopped_message(name: str, t: float | None, first_s: float, newest: float, max_lag_s: float, grace_s: float,
                    required: bool, cause: str = "") -> str:
    """Decision E23's line for a stream that sent nothing while the others moved on by more than
    ``max_lag_s`` + ``grace_s`` (its own delivery interval, s); ``t`` = its newest sample (None: never). ``cause``:
    what the lag is instead of a stopped sensor (decision E223: the units' clocks apart from the start)."""
    what = (f"no samples since {t:.2f} s" if t is not None
            else f"no samples at all since the first sample at {first_s:.2f} s")
    behind = f"max_lag_s = {max_lag_s:g} s" + (f" + {grace_s:.2f} s of its own delivery interval" if grace_s else "")
    if cause:
        return (f"{name}: {what} while the other sensors are at {newest:.2f} s (more than {behind} behind): {cause}"
                + ("; the push is refused and the tracker unchanged" if required else
                   "; ignored from now on, the steps no longer wait for it"))
    if required and t is None and name.startswith("w"):  # E32: a foot-only stream, most likely; the fix first
        return (f"{name}: {what} while other sensors are at {newest:.2f} s (more than {behind} behind): for a "
                "foot-only stream pass units=('foot',) to Tracker (or sensors= without the waist sensors; "
                "pdrlearn run --units foot, decision E26); else connect the waist unit and start a new Tracker")
    if required:
        return (f"{name}: {what} while other sensors are at {newest:.2f} s (more than {behind} behind; the sensor "
                "stopped or its link dropped): the push is refused and the tracker unchanged; when its samples return "
                "the same Tracker goes on (a stride across a foot gap over 1 s is a 0 m gap row, E46; a pod that "
                "reconnected with its clock restarted: tracker.rebase_clock, decision E227); a sensor that is gone: "
                "track without it with a "
                + ("foot-only Tracker (units=('foot',); pdrlearn run --units foot, decision E26)"
                   if name.startswith("w") else "bundle that does not need it"))
    return (f"{name} (optional): {what} while the others are at {newest:.2f} s (more than {behind} behind): "
            "ignored from now on; the steps no longer wait for it and are measured without it")
