"""Streaming input stage of the tracker: causal resampling to the bundle's rate and the stream-lag check
(decisions E22 and E23 in docs/decisions/export.md; numpy only, like the rest of :mod:`pdrlearn.runtime`).

* :class:`StreamResampler` — one sensor stream resampled causally onto the grid ``k / rate_out`` (s) with
  bounded state. Downsampling first low-passes the input with a linear-phase windowed-sinc FIR whose delay
  is compensated in the timestamps (each filtered sample keeps the time of its centre tap; it is emitted
  ``(n_taps - 1) / 2`` input samples late), then interpolates linearly; upsampling interpolates linearly.
  Every output sample is computed from the same input samples with the same operations in the same order
  whatever the chunking, so pushes of any sizes give the output of one big push, bit for bit.
* :class:`InputStage` — per sensor: learns the input rate from the first :data:`RATE_PROBE` samples
  (median interval, the tracker's own rate check), then passes the stream through (rate within the
  bundle's tolerance), resamples it, or refuses it (``resample=False``: the rate ``DataError`` of E3).
* :func:`stopped_stream` — the stream that has fallen more than ``max_lag_s`` behind the newest one.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import DataError

#: samples of a stream used to learn its rate (the tracker's rate check reads as many, decision E3)
RATE_PROBE = 5
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
            n_real = len(self._ht) - d  # samples after the left padding / history whose centre is pending
            pad_t = self._ht[-1] + (np.arange(1, d + 1) / self.rate_in)  # times of the repeated last sample
            out = self._filter(np.concatenate([self._ht, pad_t]),
                               np.concatenate([self._hv, np.repeat(self._hv[-1:], d, axis=0)]), n_real)
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
        n_ready = len(ht) - 2 * d  # centres with their whole support
        if n_ready <= 0:
            self._ht, self._hv = ht, hv
            return _cat([], v.shape[1])
        out = self._filter(ht, hv, n_ready)
        self._ht, self._hv = ht[n_ready:], hv[n_ready:]
        return out

    def _filter(self, ht: np.ndarray, hv: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """The first ``n`` centres of ``hv`` filtered (tap by tap, in one fixed order: the same sums for
        every chunking) and interpolated onto the output grid."""
        h, d = self.taps.tolist(), self.delay
        acc = h[0] * hv[0:n]
        for j in range(1, len(h)):
            acc += h[j] * hv[j:j + n]
        return self._interp(ht[d:d + n], acc)

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
        k1 = int(math.floor(float(xt[-1]) * self.rate_out)) + 2
        tg = np.arange(self._k, max(k1, self._k)) / self.rate_out
        tg = tg[tg <= xt[-1]]
        if not len(tg):
            return _cat([], y.shape[1])
        self._k += len(tg)
        out = np.empty((len(tg), y.shape[1]))
        for j in range(y.shape[1]):
            out[:, j] = np.interp(tg, xt, xv[:, j])
        return tg, out


def _checked(name: str, t, v, last: float | None) -> tuple[np.ndarray, np.ndarray]:
    """The tracker's own input errors (decision E3's wording) for a stream about to be resampled: the
    resampler would spread a NaN over its taps and interpolate garbage between unordered times."""
    t = np.asarray(t, dtype=np.float64).reshape(-1)
    if not len(t):
        return t, np.asarray(v, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64).reshape(len(t), -1)
    if not (np.isfinite(t).all() and np.isfinite(v).all()):
        raise DataError(f"{name}: pushed samples contain NaN/inf; clean the stream before tracking")
    d = np.diff(t, prepend=-np.inf if last is None else last)
    if not (d > 0).all():
        i = int(np.argmin(d > 0))
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


class InputStage:
    """The tracker's input side for streams whose rate may differ from the bundle's (decision E22).

    ``push(samples)`` takes ``{sensor: (t, values)}`` and returns the samples to buffer: unchanged for a
    stream at the bundle's rate (within its tolerance), resampled to it for another rate (``resample``)
    or, without ``resample``, the rate ``DataError`` of decision E3. The first :data:`RATE_PROBE` samples
    of each stream are held until its rate is known.
    """

    def __init__(self, bundle, *, resample: bool = True):
        self.bundle = bundle
        self.rate_hz = float(bundle.rate_hz)
        self.tol = float(bundle.manifest["sampling"].get("rate_tolerance", 0.05))
        s = bundle.manifest["sensors"]
        self.used = set(s.get("required", [])) | set(s.get("optional", []))
        self.resample = bool(resample)
        #: sensor -> its input rate (Hz), learned from its first samples
        self.input_rates_hz: dict[str, float] = {}
        #: sensor -> its resampler (only the streams at another rate)
        self.resamplers: dict[str, StreamResampler] = {}
        self._probe: dict[str, tuple[list, list]] = {}
        self.passed: set[str] = set()  # streams at the bundle's rate, passed through unchanged
        self.messages: list[str] = []  # one line per resampled stream (decision E22)

    def push(self, samples: dict) -> dict:
        if self.passed.issuperset(samples):  # every stream known and at the bundle's rate
            return samples
        out = {}
        for name, (t, v) in samples.items():
            if name in self.passed:
                out[name] = (t, v)
                continue
            r = self.resamplers.get(name)
            if r is not None:
                out[name] = r.push(*_checked(name, t, v, r.last_in))
                continue
            pt, pv = self._probe.setdefault(name, ([], []))
            t, v = _checked(name, t, v, float(pt[-1][-1]) if pt else None)  # the errors now, not 5 samples later
            if not len(t):
                continue
            pt.append(t)
            pv.append(v)
            tt = np.concatenate(pt)
            if len(tt) < RATE_PROBE:
                continue
            del self._probe[name]
            vv = np.concatenate(pv)
            fs = 1.0 / float(np.median(np.diff(tt[:RATE_PROBE])))
            self.input_rates_hz[name] = fs
            if name not in self.used or abs(fs - self.rate_hz) <= self.tol * self.rate_hz:
                self.passed.add(name)
                out[name] = (tt, vv)
                continue
            if not self.resample:
                self.bundle.check_rates({name: fs}, where=f"pushed {name}")
            r = self.resamplers[name] = StreamResampler(fs, self.rate_hz)
            self.messages.append(resample_message(name, fs, self.rate_hz, r))
            out[name] = r.push(tt, vv)
        return {n: tv for n, tv in out.items() if len(tv[0])}

    def flush(self) -> dict:
        """The samples still held: probes of streams that never reached :data:`RATE_PROBE` samples and
        each resampler's filter tail (end of the recording)."""
        out = {n: (np.concatenate(pt), np.concatenate(pv)) for n, (pt, pv) in self._probe.items()}
        self._probe.clear()
        for name, r in self.resamplers.items():
            t, v = r.flush()
            if len(t):
                out[name] = (t, v)
        return out


def resample_message(name: str, rate_in: float, rate_out: float, r: StreamResampler | None = None) -> str:
    """The one line that announces a resampled stream (decision E22)."""
    how = ("linear interpolation" if r is None or r.taps is None
           else f"{len(r.taps)}-tap linear-phase low-pass + linear interpolation")
    lat = f", {r.latency_s * 1e3:.0f} ms delay" if r is not None else ""
    return (f"{name} is sampled at {rate_in:.4g} Hz, the bundle at {rate_out:.4g} Hz: resampling it to "
            f"{rate_out:.4g} Hz ({how}{lat}); pass --no-resample / Tracker(resample=False) to refuse instead")


def stopped_stream(last_s: dict[str, float], sensors: dict, first_s: float, max_lag_s: float
                   ) -> tuple[str | None, str | None]:
    """Decision E23: the stream furthest behind the newest one, when that is more than ``max_lag_s`` (s).

    ``last_s``: sensor -> time (s) of its newest sample; ``sensors``: the bundle's ``{"required": [...],
    "optional": [...]}``; a required sensor without any sample counts from ``first_s`` (the first sample of
    any stream). A stream the bundle uses raises a one-line :class:`DataError` naming it (its steps would be
    made of held values); for a stream it does not use, returns ``(name, warning)`` (the caller drops it);
    ``(None, None)`` when no stream is that far behind.
    """
    required = list(sensors.get("required", []))
    last = dict(last_s)
    for n in required:
        last.setdefault(n, first_s)
    if not last:
        return None, None
    newest = max(last.values())
    name, t = min(last.items(), key=lambda kv: kv[1])
    if not newest - t > max_lag_s:
        return None, None
    if name in required or name in sensors.get("optional", []):
        what = (f"no samples since {t:.2f} s" if name in last_s
                else f"no samples at all since the first sample at {t:.2f} s")
        raise DataError(
            f"{name}: {what} while other sensors are at {newest:.2f} s (more than max_lag_s = {max_lag_s:g} s "
            "behind; the sensor stopped or its link dropped); reconnect it and start a new Tracker, or track "
            "without it with a bundle that does not need it")
    return name, (f"{name} stopped at {t:.2f} s (the others are at {newest:.2f} s); the bundle does not use it: "
                  "dropped, the steps no longer wait for it")
