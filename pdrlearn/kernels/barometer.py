"""Pressure and altitude, numpy only: the barometric formula of the simulator's barometer and its inverse,
the relative altitude of a barometer stream (decision W89 in docs/decisions/waist.md).

The thesis uses the barometer "in differential mode": the altitude is the change of the pressure from a
reference point, not an absolute height, because the sea-level pressure drifts with the weather by more than
four storeys over a month (thesis ch.4.3.1.4, Figure 44, Table 18). :func:`relative_altitude` is that
differential altitude, from the international barometric formula (:func:`pressure_hpa`, the formula the
simulator writes ``wBarometer`` with, docs/simulator.md). :func:`fuse_altitude` fuses it with a foot track's
strides (decision L154, an option).
"""

from __future__ import annotations

import numpy as np

#: international barometric formula: p = P0 (1 - C h)^E (h in m, p and P0 in hPa); ICAO standard atmosphere
BARO_C_PER_M = 2.25577e-5
BARO_EXPONENT = 5.25588
#: standard sea-level pressure (hPa): the reference of :func:`altitude_m` (the differential altitude of
#: :func:`relative_altitude` depends on it by under 0.2 % between 950 and 1050 hPa)
STANDARD_P0_HPA = 1013.25
#: decision W89: the barometer is averaged over this centred window (s) before its altitude is read: the
#: BMP280's 0.0157 hPa noise (thesis Table 18) is 0.13 m of altitude per sample, a 3 m storey is 0.36 hPa
ALTITUDE_SMOOTH_S = 1.0


def pressure_hpa(altitude_m: np.ndarray, p0_hpa: float) -> np.ndarray:
    """International barometric formula: pressure (hPa) at ``altitude_m`` for sea-level ``p0_hpa``."""
    return p0_hpa * (1.0 - BARO_C_PER_M * np.asarray(altitude_m, dtype=float)) ** BARO_EXPONENT


def altitude_m(p_hpa: np.ndarray, p0_hpa: float = STANDARD_P0_HPA) -> np.ndarray:
    """The inverse of :func:`pressure_hpa`: altitude (m) above the level where the pressure is ``p0_hpa``."""
    return (1.0 - (np.asarray(p_hpa, dtype=float) / p0_hpa) ** (1.0 / BARO_EXPONENT)) / BARO_C_PER_M


def relative_altitude(t: np.ndarray, p_hpa: np.ndarray, at: np.ndarray,
                      smooth_s: float = ALTITUDE_SMOOTH_S, *, noise_window: bool = True,
                      smoothing: tuple[float, float | None] | None = None) -> np.ndarray:
    """Altitude (m) at the times ``at`` relative to the first of them, from a barometer ``(t, p_hpa)``
    (s, hPa): the pressure averaged over a centred ``smooth_s`` window (fewer samples at the ends), converted
    with :func:`altitude_m` and interpolated (held beyond the stream's ends). Thesis ch.4.3.1.4: the
    differential of the pressure from a reference point. Non-finite samples are skipped; with none finite
    the altitude is 0 throughout. ``noise_window`` (decision W621): the window is :func:`noise_window_s`'s, at
    least ``smooth_s`` and longer for a barometer whose noise per second is higher (a phone's 1 Hz samples), read
    as :func:`noise_smoothing` says; ``smoothing``: that pair given (the live tracker's, read on its first samples)."""
    at = np.asarray(at, dtype=float).ravel()
    if smoothing is None:
        smoothing = noise_smoothing(t, p_hpa, smooth_s) if noise_window else (float(smooth_s), None)
    t, h = _altitude_series(t, p_hpa, smoothing)
    if not len(t) or not len(at):
        return np.zeros(len(at))
    h = np.interp(at, t, h)
    return h - h[0]


def held_altitude(t: np.ndarray, p_hpa: np.ndarray, at: np.ndarray, windows,
                  smooth_s: float = ALTITUDE_SMOOTH_S) -> tuple[np.ndarray, np.ndarray]:
    """:func:`relative_altitude` at the times ``at``, and the same with the change inside each ``(a, b)`` window
    (s) taken out: the altitude held through it (decision W174: a sit-to-stand's rise is the transfer's, not a
    climb). Overlapping windows are merged. Returns ``(held, raw)``, both relative to ``at[0]``."""
    at = np.asarray(at, dtype=float).ravel()
    n = len(at)
    merged: list[list[float]] = []
    for a, b in sorted((float(a), float(b)) for a, b in windows):
        if merged and a <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], b)
        else:
            merged.append([a, b])
    w = np.asarray(merged, dtype=float).reshape(-1, 2)
    h = relative_altitude(t, p_hpa, np.concatenate([at, *(np.clip(at, a, b) for a, b in w), w[:, 0]]), smooth_s)
    raw = h[:n]
    held = raw.copy()
    for k in range(len(w)):  # less the change from the window's start to min(time, its end), after its start
        held -= h[n * (k + 1):n * (k + 2)] - h[n * (len(w) + 1) + k]
    return (held - held[0] if n else held), raw


def altitude_noise(t: np.ndarray, p_hpa: np.ndarray, *, first_n: int = 64) -> tuple[float, float]:
    """Decision W621: ``(sigma, dt)``: the white noise (m, 1 SD) of one sample of a barometer's altitude and its
    median sample interval (s), from its first ``first_n`` finite samples: each inner sample's difference from the
    line through its two neighbours (a climb at a steady rate, the weather's drift, cancel), scaled to one sample's
    noise, its median absolute value as a robust SD (1.4826 MAD: a ride's start or a door's transient is a few
    outliers). ``(0, 0)`` with under 8 such samples or times that do not increase."""
    t, p = np.asarray(t, dtype=float).ravel(), np.asarray(p_hpa, dtype=float).ravel()
    ok = np.isfinite(t) & np.isfinite(p)
    t, h = t[ok][:first_n], altitude_m(p[ok][:first_n])
    dt = np.diff(t)
    if len(t) < 10 or not np.all(dt > 0):
        return 0.0, 0.0
    a = dt[:-1] / (dt[:-1] + dt[1:])  # the middle sample's place between its neighbours
    r = (h[1:-1] - (1.0 - a) * h[:-2] - a * h[2:]) / np.sqrt(1.0 + a * a + (1.0 - a) ** 2)
    return float(1.4826 * np.median(np.abs(r))), float(np.median(dt))


def noise_window_s(t: np.ndarray, p_hpa: np.ndarray, smooth_s: float = ALTITUDE_SMOOTH_S, *, sds: float = 3.0,
                   first_n: int = 64, max_s: float = 12.0) -> float:
    """Decision W621: the window (s) W89's centred mean averages a barometer over: ``smooth_s``, or longer where the
    barometer's noise density ``n = sigma sqrt(dt)`` (m s^0.5, :func:`altitude_noise`) would leave W91's rise (the
    change of that mean over :data:`STAIRS_RATE_WINDOW_S`, D) a noise SD over 1 / ``sds`` of its threshold
    ``STAIRS_RATE_MPS * D``. A window W's mean has noise SD ``n / sqrt(W)``; two of them D apart differ by SD
    ``n sqrt(2 / W)`` (W <= D, disjoint) or ``n sqrt(2 D) / W`` (W >= D, overlapping): the least W meeting the bound.
    Its seconds follow the noise, not the sample rate: the simulator's 50 Hz barometer (W89's BMP280, n ~0.03) keeps
    1 s; a phone's 1 Hz samples of ~0.27 m (n ~0.27) are averaged over ~8 s - one sample a second read as the altitude
    made every second level step a stair (trial s53t2). Decision W627: at most ``max_s`` (12 s; W621's phones needed
    4.3-9.1 s at 1 Hz): a barometer sampled every 5 s read a 17.5 s window, whose median flattened a lift ride's
    storeys (L374's user 7222: 3 floors down read as 2).
    """
    sigma, dt = altitude_noise(t, p_hpa, first_n=first_n)
    d = STAIRS_RATE_WINDOW_S
    x = sds * sigma * np.sqrt(dt) / (STAIRS_RATE_MPS * d)  # the rise's SD bound is STAIRS_RATE_MPS * D / sds
    need = 2.0 * x * x if 2.0 * x * x <= d else x * np.sqrt(2.0 * d)
    return float(max(smooth_s, min(need, max_s)))  # decision W627: the cap


def noise_smoothing(t: np.ndarray, p_hpa: np.ndarray, smooth_s: float = ALTITUDE_SMOOTH_S, *,
                    first_n: int = 64) -> tuple[float, float | None]:
    """Decision W621: ``(window_s, mean_s)``: :func:`noise_window_s`'s window and, where it is longer than
    ``smooth_s``, the short mean of :func:`median_altitude` (over W91's rise window, :data:`STAIRS_RATE_WINDOW_S`);
    else ``(smooth_s, None)``: W89's plain mean, as before W621."""
    w = noise_window_s(t, p_hpa, smooth_s, first_n=first_n)
    return (w, STAIRS_RATE_WINDOW_S) if w > smooth_s else (float(smooth_s), None)


def _altitude_series(t: np.ndarray, p_hpa: np.ndarray, smoothing: tuple[float, float | None]
                     ) -> tuple[np.ndarray, np.ndarray]:
    """``(t, h)`` before interpolation for a ``smoothing`` of :func:`noise_smoothing`: W89's mean, or W621's running
    median over ``pi / 2`` times the window (the median's Gaussian efficiency is 2 / pi) and the short mean."""
    w, mean_s = smoothing
    return _smoothed_altitude(t, p_hpa, w) if mean_s is None else median_altitude(t, p_hpa, 0.5 * np.pi * w, mean_s)


def median_altitude(t: np.ndarray, p_hpa: np.ndarray, window_s: float, mean_s: float,
                    chunk: int = 2048) -> tuple[np.ndarray, np.ndarray]:
    """Decision W621: ``(t, h)``: the finite samples' times and the altitude's running median over a centred
    ``window_s`` (fewer samples at the ends), then its mean over a centred ``mean_s``. A long window's mean would
    spread a lift ride's rise (5 m in a few seconds) over the steps walked ``window_s / 2`` either side of it, and a
    flight's ends; a median keeps a monotone noiseless signal as it is (its window's middle sample) and averages
    a level's noise (its Gaussian efficiency 2 / pi: over ``pi / 2`` times a mean's window, the mean's noise); on
    a ramp it holds about one sample's noise, which the short mean takes down."""
    t, p = np.asarray(t, dtype=float).ravel(), np.asarray(p_hpa, dtype=float).ravel()
    ok = np.isfinite(t) & np.isfinite(p)
    t, h = t[ok], altitude_m(p[ok])
    if not len(t):
        return t, h
    lo = np.searchsorted(t, t - 0.5 * window_s, side="left")
    hi = np.searchsorted(t, t + 0.5 * window_s, side="right")
    med = np.empty(len(t))
    for a in range(0, len(t), chunk):  # rows of a padded (samples x window) table, a chunk at a time
        b = min(a + chunk, len(t))
        idx = lo[a:b, None] + np.arange(int((hi[a:b] - lo[a:b]).max()))[None, :]
        med[a:b] = np.nanmedian(np.where(idx < hi[a:b, None], h[np.minimum(idx, len(t) - 1)], np.nan), axis=1)
    cs = np.concatenate([[0.0], np.cumsum(med)])
    lo = np.searchsorted(t, t - 0.5 * mean_s, side="left")
    hi = np.searchsorted(t, t + 0.5 * mean_s, side="right")
    return t, (cs[hi] - cs[lo]) / (hi - lo)


def _smoothed_altitude(t: np.ndarray, p_hpa: np.ndarray, smooth_s: float) -> tuple[np.ndarray, np.ndarray]:
    """``(t, h)``: the finite samples' times and the altitude (m, :func:`altitude_m`) of their pressure averaged
    over a centred ``smooth_s`` window (fewer samples at the ends; W89's smoothing)."""
    t, p = np.asarray(t, dtype=float).ravel(), np.asarray(p_hpa, dtype=float).ravel()
    ok = np.isfinite(t) & np.isfinite(p)
    t, p = t[ok], p[ok]
    if not len(t):
        return t, p
    cs = np.concatenate([[0.0], np.cumsum(p)])
    lo = np.searchsorted(t, t - 0.5 * smooth_s, side="left")
    hi = np.searchsorted(t, t + 0.5 * smooth_s, side="right")
    return t, altitude_m((cs[hi] - cs[lo]) / (hi - lo))



class LiveAltitude:
    """Decision E106: W89's altitude (:func:`relative_altitude`: the pressure averaged over a centred ``smooth_s``
    window, :func:`altitude_m`, interpolated) for a live tracker fed barometer samples as they come. ``push(t, p)``
    holds them; ``at(ts)`` is the altitude at ``ts`` relative to the ``origin_s`` given by :meth:`set_origin` (the
    track's first sample, as ``track_waist``'s ``imu.t[0]``), read on the samples held then; ``trim(before)`` drops
    what no later ``at(ts >= before)`` reads. Equal to the offline altitude wherever the samples up to ``ts +
    smooth_s`` were pushed before ``at(ts)`` (the window's right half; else the window is shorter: causal).
    :attr:`implausible` is B188's finding (:func:`implausible_pressure` on the held samples) once one was seen, after
    which ``at`` returns None (the offline track reads no part of such a barometer). ``noise_window`` (decision
    W621, as :func:`relative_altitude`'s): the window is :func:`noise_window_s`'s, read on the first samples pushed
    (:attr:`window_s`; the offline one once they number ``first_n``, which the origin's altitude waits for)."""

    def __init__(self, smooth_s: float = ALTITUDE_SMOOTH_S, *, noise_window: bool = True, first_n: int = 64):
        self.smooth_s = float(smooth_s)
        self.noise_window, self.first_n = bool(noise_window), int(first_n)
        self._head_t: list[float] = []  # W621: the first first_n finite samples, for the noise window
        self._head_p: list[float] = []
        self._smoothing: tuple[float, float | None] | None = None  # W621's, once read on first_n samples
        self._t = np.zeros(0)
        self._p = np.zeros(0)
        self._origin_s: float | None = None
        self._ref: float | None = None  # the altitude at the origin, once its window is complete
        self.implausible: tuple[float, float, float, float, float] | None = None
        self._watch = PlausibleWatch(self.smooth_s)  # B188's check, incremental (same answers)

    def push(self, t: np.ndarray, p_hpa: np.ndarray):
        """Hold samples ``(t, p_hpa)`` (s increasing past the held ones, hPa); B188's finding when they make the
        held barometer implausible (the first time), else None."""
        t, p = np.asarray(t, dtype=float).ravel(), np.asarray(p_hpa, dtype=float).ravel()
        self._t = np.concatenate([self._t, t])
        self._p = np.concatenate([self._p, p])
        if self._smoothing is None and self.noise_window:
            ok = np.isfinite(t) & np.isfinite(p)
            room = self.first_n - len(self._head_t)
            self._head_t += t[ok][:room].tolist()
            self._head_p += p[ok][:room].tolist()
            if len(self._head_t) >= self.first_n:
                self._smoothing = self._noise_smoothing()
        if self.implausible is None:
            if not self._watch.push(t, p):
                found = implausible_pressure(self._t, self._p, self.smooth_s)
                if found is not None:
                    self.implausible = found
                    return found
        return None

    def _noise_smoothing(self) -> tuple[float, float | None]:
        return noise_smoothing(np.array(self._head_t), np.array(self._head_p), self.smooth_s, first_n=self.first_n)

    @property
    def smoothing(self) -> tuple[float, float | None]:
        """Decision W621: :func:`noise_smoothing`'s ``(window_s, mean_s)`` (W89's ``(smooth_s, None)`` without
        ``noise_window``; before ``first_n`` samples, read on those pushed so far)."""
        if not self.noise_window:
            return self.smooth_s, None
        return self._smoothing if self._smoothing is not None else self._noise_smoothing()

    @property
    def window_s(self) -> float:
        """Decision W621: the window (s) the altitude is averaged over (:attr:`smoothing`'s)."""
        return self.smoothing[0]

    @property
    def times(self) -> np.ndarray:
        """The held samples' times (s; decision E339's holder reads how far the barometer was pushed)."""
        return self._t

    def set_origin(self, t0: float) -> None:
        """The time the altitude is relative to (once)."""
        if self._origin_s is None:
            self._origin_s = float(t0)

    def _h(self, at: np.ndarray, upto: float | None = None) -> np.ndarray | None:
        k = self._t.size if upto is None else int(np.searchsorted(self._t, upto, side="right"))
        t, h = _altitude_series(self._t[:k], self._p[:k], self.smoothing)
        return np.interp(at, t, h) if len(t) else None

    def at(self, ts: float, *, upto: float | None = None) -> float | None:
        """The altitude (m) at ``ts`` relative to the origin; None without a usable sample or origin. ``upto``
        (decision W622): read on the samples held up to that time only (a rise's earlier end on a window cut on
        its right as its later end's: both lag alike)."""
        if self.implausible is not None or self._origin_s is None:
            return None
        h = self._h(np.array([self._origin_s]))
        if h is None:
            return None
        hs = self._h(np.array([float(ts)]), upto)
        if hs is None:
            return None
        h = np.array([h[0], hs[0]])
        ref = self._ref if self._ref is not None else float(h[0])
        final = self._smoothing is not None or not self.noise_window  # W621: the window is the offline one
        if self._ref is None and final and self._t[-1] >= self._origin_s + self.window_s:
            self._ref = ref  # its window is complete: the offline value, kept when older samples are trimmed
        return float(h[1] - ref)

    def trim(self, before: float) -> None:
        """Drop the samples no ``at(ts)`` with ``ts >= before`` reads (kept while the origin's altitude is open)."""
        if self._ref is None or not self._t.size:
            return
        drop = int(np.searchsorted(self._t, float(before) - 2.0 * self.window_s))
        drop = min(drop, self._t.size - 2)  # the last two samples stay: interpolation past the end holds
        if drop > 0:
            self._watch.trim(int(np.count_nonzero(np.isfinite(self._t[:drop]) & np.isfinite(self._p[:drop]))))
            self._t, self._p = self._t[drop:], self._p[drop:]

    def ride(self, a: float, b: float) -> float | None:
        """Decision E146: W231's ride (m) of the pause from ``a`` to ``b`` (s)
        (:func:`pdrlearn.kernels.pause_ride.pause_ride_dz`) on the held samples (the live tracker holds them across
        its pauses); None where :meth:`at` is None."""
        if self.implausible is not None or self._origin_s is None or not self._t.size:
            return None
        from pdrlearn.kernels.pause_ride import pause_ride_dz

        return pause_ride_dz(self._t, self._p, float(a), float(b), smoothing=self.smoothing)[0]

    def size(self) -> int:
        return int(self._t.size + self._p.size)

    def state(self) -> dict:
        """Decision E356: what :meth:`from_state` needs to go on as this holder (plain numbers and lists)."""
        return {"t": self._t.tolist(), "p": self._p.tolist(), "origin_s": self._origin_s, "ref": self._ref,
                "implausible": None if self.implausible is None else list(self.implausible)}

    @classmethod
    def from_state(cls, state: dict, smooth_s: float = ALTITUDE_SMOOTH_S) -> LiveAltitude:
        """Decision E356: a holder that goes on as the one :meth:`state` was taken of: its held samples (B188's
        incremental check rebuilt on them: the same answers, :class:`PlausibleWatch`), origin, reference and finding."""
        alt = cls(smooth_s)
        found = None if state["implausible"] is None else tuple(float(v) for v in state["implausible"])
        if found is None:
            alt.push(np.asarray(state["t"], float), np.asarray(state["p"], float))
        else:  # read no further (B188): the samples are kept for their size only
            alt._t, alt._p, alt.implausible = np.asarray(state["t"], float), np.asarray(state["p"], float), found
        alt._origin_s = None if state["origin_s"] is None else float(state["origin_s"])
        alt._ref = None if state["ref"] is None else float(state["ref"])
        return alt


#: decision B188: the fastest a wearer travels vertically (m/s): the fastest passenger elevators run 18-21 m/s
#: (Shanghai Tower 18 m/s, CTF Finance Centre Guangzhou 21 m/s); near sea level ~2.4 hPa/s (0.12 hPa per m)
MAX_VERTICAL_SPEED_MPS = 20.0


def implausible_pressure(t: np.ndarray, p_hpa: np.ndarray, smooth_s: float = ALTITUDE_SMOOTH_S,
                         max_speed_mps: float = MAX_VERTICAL_SPEED_MPS
                         ) -> tuple[float, float, float, float, float] | None:
    """Decision B188: ``(speed, t_a, p_a, t_b, p_b)`` when the barometer's altitude (its pressure averaged over
    ``smooth_s`` as :func:`relative_altitude` reads it) changes faster than ``max_speed_mps`` between samples
    ``smooth_s`` apart (the averaging keeps the sensor's noise, 0.13 m a sample (W89), far under it): ``speed`` the
    largest such rate (m/s) and the largest sample-to-sample pressure jump around it, from ``p_a`` (hPa) at ``t_a``
    to ``p_b`` at ``t_b`` (s); None when the barometer is plausible (or has under two finite samples)."""
    t_s, h = _smoothed_altitude(t, p_hpa, smooth_s)
    if len(t_s) < 2:
        return None
    j = np.searchsorted(t_s, t_s + smooth_s, side="left")
    i = np.flatnonzero(j < len(t_s))
    if not i.size:  # a stream shorter than smooth_s: its two ends
        i, j = np.array([0]), np.array([len(t_s) - 1])
    else:
        j = j[i]
    speed = np.abs(h[j] - h[i]) / np.maximum(t_s[j] - t_s[i], 1e-9)
    k = int(np.argmax(speed))
    if not speed[k] > max_speed_mps:
        return None
    tt = np.asarray(t, dtype=float).ravel()
    pp = np.asarray(p_hpa, dtype=float).ravel()
    ok = np.isfinite(tt) & np.isfinite(pp)
    tt, pp = tt[ok], pp[ok]
    a, b = np.searchsorted(tt, [t_s[i[k]] - smooth_s, t_s[j[k]] + smooth_s])
    a, b = max(0, int(a) - 1), min(len(tt), int(b) + 1)
    m = a + int(np.argmax(np.abs(np.diff(pp[a:b]))))
    return float(speed[k]), float(tt[m]), float(pp[m]), float(tt[m + 1]), float(pp[m + 1])


class PlausibleWatch:
    """:func:`implausible_pressure`'s None, decided incrementally for :class:`LiveAltitude` (same answers): ``push``
    the samples as they come and ``trim(k)`` when the first ``k`` finite ones are dropped; :meth:`push` returns True
    only when the full check on the finite samples held would certainly return None (else the caller runs it). Each
    pair ``(i, j)`` the full check compares (``j`` the first sample ``smooth_s`` after ``i``) keeps an upper bound of
    its speed, recomputed only where a push or a trim changes its windows (the last ``~2 smooth_s`` before the new
    samples, the first ``~smooth_s`` after the dropped ones): first the pressure range over those windows (both
    means lie in it), and where that is not under the limit each pair's own speed on a slice of the samples. The
    bounds cover the floating-point difference between a cumsum over a slice and the full check's over every sample
    held (:meth:`_err_m`). It does not decide pressures outside 100-2000 hPa (from then on), times that decrease, a
    stream shorter than ``smooth_s``, nor a speed within that floating-point bound of the limit."""

    #: the pressures (hPa) the error bound holds for; |d altitude_m / dp| <= 60 m/hPa above 100 hPa (8.3 at 1013)
    P_MIN_HPA, P_MAX_HPA, SLOPE_M_PER_HPA = 100.0, 2000.0, 60.0
    _U = float(np.finfo(float).eps)

    def __init__(self, smooth_s: float = ALTITUDE_SMOOTH_S, max_speed_mps: float = MAX_VERTICAL_SPEED_MPS):
        self.smooth_s, self.max_speed_mps = float(smooth_s), float(max_speed_mps)
        self._buf = np.zeros((4, 64))  # rows t, p (the finite samples held), ub, inv; live columns [_a, _b)
        self._a = self._b = 0
        # ub: per sample i the bound of its pair's speed (m/s; -inf without a pair); inv: (1 + 8u) / the pair's time
        # apart (a bound of it), what the full check's own rounding (:meth:`_err_m`) is divided by
        self._front = 0  # samples [0, _front) to recompute (their windows lost dropped samples)
        self._done = 0  # samples [0, _done) were bounded (those after are new since)
        self._exact = True  # False: inputs the bound does not cover (the full check decides)

    @property
    def _t(self) -> np.ndarray:
        return self._buf[0, self._a:self._b]

    @property
    def _ub(self) -> np.ndarray:
        return self._buf[2, self._a:self._b]

    @property
    def _inv(self) -> np.ndarray:
        return self._buf[3, self._a:self._b]

    def _err_m(self, n: int) -> float:
        """Bound (m) of an altitude difference's floating-point error, windows' sums from an n-sample cumsum."""
        mean_err = 4.0 * self._U * (n * n + n + 1.0) * self.P_MAX_HPA  # sequential cumsum, difference, division
        return 2.0 * (self.SLOPE_M_PER_HPA * mean_err + 1e-9)  # two altitudes (+ altitude_m's own rounding)

    def push(self, t: np.ndarray, p: np.ndarray) -> bool:
        """Hold samples; True when the full check on all held would certainly return None."""
        ok = np.isfinite(t) & np.isfinite(p)
        if not ok.all():
            t, p = t[ok], p[ok]
        m = t.size
        if self._exact and m and (
                not (self.P_MIN_HPA <= p.min() and p.max() <= self.P_MAX_HPA) or (m > 1 and np.any(np.diff(t) < 0))
                or (self._b > self._a and t[0] < self._buf[0, self._b - 1])):
            self._exact = False
            self._buf, self._a, self._b = np.zeros((4, 0)), 0, 0
        if not self._exact:
            return False
        if m:
            if self._b + m > self._buf.shape[1]:  # compact, and grow when over half full
                live = self._buf[:, self._a:self._b]
                if 2 * (live.shape[1] + m) > self._buf.shape[1]:
                    self._buf = np.zeros((4, 2 * (live.shape[1] + m)))
                self._buf[:, :live.shape[1]] = live  # live is a copy-safe slice when the buffer was replaced
                self._a, self._b = 0, live.shape[1]
            self._buf[0, self._b:self._b + m], self._buf[1, self._b:self._b + m] = t, p
            self._buf[2, self._b:self._b + m], self._buf[3, self._b:self._b + m] = -np.inf, 0.0
            self._b += m
        T, n, s = self._t, self._b - self._a, self.smooth_s
        if n < 2 or not T[-1] >= T[0] + s:
            return False  # no pair (the full check compares the two ends): it decides
        slack = 0.25 * s + 1e-9 * (1.0 + abs(float(T[-1])) + abs(float(T[0])))
        n_old, i_s = min(self._done, n), n
        if n_old < n:  # the windows reaching the new samples, and the pairs reading them or new pairs
            k = min(int(np.searchsorted(T, T[n_old] - 0.5 * s - slack, side="left")), n_old)
            i_s = 0 if k == 0 else int(np.searchsorted(T, T[k - 1] - s - slack, side="left"))
        front = min(self._front, n)
        if front >= i_s:
            self._bound(0, n)
        else:
            if front:
                self._bound(0, front)
            if i_s < n:
                self._bound(i_s, n)
        self._front, self._done = 0, n
        return bool(np.max(self._ub + self._err_m(n) * self._inv) < self.max_speed_mps)

    def _bound(self, i0: int, i1: int) -> None:
        """The speed bounds of the pairs from samples i0..i1-1: the pressure range over all their windows, else the
        full check's windows and pairs, its arithmetic on a slice."""
        T, P, n, s = self._t, self._buf[1, self._a:self._b], self._b - self._a, self.smooth_s
        ub, inv = self._ub, self._inv
        a0 = int(np.searchsorted(T, T[i0] - 0.5 * s - 0.25 * s, side="left"))  # every window from i0 on (slack)
        dt_min = s - 4.0 * self._U * (abs(float(T[0])) + abs(float(T[-1])) + s)  # t_j >= fl(t_i + s)
        if dt_min > 0.5 * s:
            grow = 1.0 + 8.0 * self._U
            rise = float(altitude_m(P[a0:].min()) - altitude_m(P[a0:].max()))  # both means lie in the range
            c = (rise + self._err_m(0)) / dt_min * grow
            if c + self._err_m(n) * grow / dt_min < self.max_speed_mps:
                ub[i0:i1], inv[i0:i1] = c, grow / dt_min
                return
        j = np.searchsorted(T, T[i0:i1] + s, side="left")  # as implausible_pressure
        ub[i0:i1], inv[i0:i1] = -np.inf, 0.0
        has = j < n
        if not has.any():
            return
        ii, jj = np.arange(i0, i1)[has], j[has]
        tk = T[i0:int(jj.max()) + 1]
        lo = np.searchsorted(T, tk - 0.5 * s, side="left")  # as _smoothed_altitude
        hi = np.searchsorted(T, tk + 0.5 * s, side="right")
        a, b = int(lo.min()), int(hi.max())
        cs = np.concatenate([[0.0], np.cumsum(P[a:b])])
        h = altitude_m((cs[hi - a] - cs[lo - a]) / (hi - lo))
        dt = np.maximum(T[jj] - T[ii], 1e-9)
        grow = 1.0 + 8.0 * self._U
        ub[ii] = (np.abs(h[jj - i0] - h[ii - i0]) / dt + self._err_m(b - a) / dt) * grow
        inv[ii] = grow / dt

    def trim(self, k: int) -> None:
        """The first ``k`` finite samples were dropped."""
        if not self._exact or k <= 0:
            return
        k = min(k, self._b - self._a)
        last = float(self._buf[0, self._a + k - 1])
        self._a += k
        slack = 0.25 * self.smooth_s + 1e-9 * (1.0 + abs(last))
        f = int(np.searchsorted(self._t, last + 0.5 * self.smooth_s + slack, side="right"))
        self._front, self._done = max(self._front - k, f), max(self._done - k, 0)


#: what an unread barometer means for a lower-back track (W89) and for a foot track (L145)
WAIST_EFFECT = "z stays 0 with no floors counted"
FOOT_EFFECT = "the foot altitude is not compared with it (L145)"
FUSED_EFFECT = "the altitude is the foot's own, not fused with it (L154)"
#: decision L154: the altitude sources of a foot track (``track --altitude``; E339: ``run --altitude``, the
#: ``Tracker``'s ``altitude``): the strides' own height (the default) or fused with the waist barometer
ALTITUDES = ("foot", "fused")
def fused_without_barometer(lacks: str = "this session lacks") -> str:
    """Decision L154's line for ``altitude="fused"`` without the waist barometer; ``lacks`` says what lacks it
    (decision E363: the live ``Tracker``'s declared streams, not a session it never saw)."""
    return (f"altitude \"fused\" needs the waist barometer (wBarometer.csv), which {lacks}: the altitude is the "
            "foot's own (L39 / the terrain classes)")


#: decision L154's line for ``altitude="fused"`` on a session without the waist barometer (E339: also ``run``'s)
FUSED_WITHOUT_BAROMETER = fused_without_barometer()


def implausible_barometer_message(found: tuple[float, float, float, float, float],
                                  effect: str = WAIST_EFFECT) -> str:
    """Decision B188's one line: the file, the jump and its time, and the fix (the caller's log line names the
    session folder)."""
    speed, t_a, p_a, t_b, p_b = found
    # the barometric formula's slope at sea level, |dp/dh| = P0 C E (pressure_hpa's derivative at h = 0)
    hpa_per_s = MAX_VERTICAL_SPEED_MPS * STANDARD_P0_HPA * BARO_C_PER_M * BARO_EXPONENT
    return (f"wBarometer.csv is not used: its pressure goes from {p_a:.2f} to {p_b:.2f} hPa between "
            f"{t_a:.3f} and {t_b:.3f} s, an altitude change of {speed:.0f} m/s - faster than any person travels "
            f"vertically (the fastest elevators, {MAX_VERTICAL_SPEED_MPS:g} m/s ~ {hpa_per_s:.1f} hPa/s; decision "
            "B188), so it "
            f"is an artefact (a resampling filter's zero padding, a glitch), and {effect}; fix the file (resample "
            "without zero padding, e.g. scipy resample_poly(..., padtype='line'), or drop the bad samples) or delete "
            "wBarometer.csv")


#: decision W91 (candidate, option ``stairs_length``): a step is on stairs when the barometric altitude changes
#: by at least this rate (m/s) over :data:`STAIRS_RATE_WINDOW_S` centred on it: half the rate of a 0.17 m riser
#: (the simulator's stair) climbed at 1.2 steps/s, a slow climb; level walking changes no altitude
STAIRS_RATE_MPS = 0.1
STAIRS_RATE_WINDOW_S = 2.0
#: decision W91: the horizontal length of a step on stairs is at most the tread, "about 30cm" (thesis
#: ch.7.3.2.1, scenario D's stairs)
STAIR_TREAD_M = 0.30


def stairs_rate_test(rise_m: np.ndarray) -> np.ndarray:
    """Decision W91: whether a step is proposed as on stairs from ``rise_m``, the altitude change (m) over
    :data:`STAIRS_RATE_WINDOW_S` centred on the step's middle (its rate at least :data:`STAIRS_RATE_MPS`)."""
    return np.abs(np.asarray(rise_m, dtype=float)) / STAIRS_RATE_WINDOW_S >= STAIRS_RATE_MPS

#: decision W108: the least barometric height of a climb, half of L64's 3 m storey (a flight between two landings)
STAIR_CLIMB_MIN_M = 1.5
#: decision W108: a climb's height is at least this many SDs of a difference of two still-period altitudes
CLIMB_NOISE_SDS = 3.0 * np.sqrt(2.0)
#: decision W108: still barometer samples this far (s) from the walk's first / last step, at least
#: :data:`STILL_MIN_S` of them, give the session's altitude noise
STILL_MARGIN_S = 0.5
STILL_MIN_S = 1.0


def still_altitude_sd(t: np.ndarray, p_hpa: np.ndarray, walk_start_s: float, walk_end_s: float,
                      smooth_s: float = ALTITUDE_SMOOTH_S) -> float:
    """Decision W108: the SD (m) of the ``smooth_s``-averaged altitude over the barometer samples more than
    :data:`STILL_MARGIN_S` before ``walk_start_s`` or after ``walk_end_s`` (the session's own still periods),
    each period about its own mean (the walk may have changed floors between them); 0 when they span under
    :data:`STILL_MIN_S`."""
    t = np.asarray(t, dtype=float).ravel()
    h = relative_altitude(t, p_hpa, t, smooth_s)
    ok = np.isfinite(t) & np.isfinite(h)
    periods = [m for m in (ok & (t < walk_start_s - STILL_MARGIN_S), ok & (t > walk_end_s + STILL_MARGIN_S))
               if m.sum() > 1]
    if sum(float(np.ptp(t[m])) for m in periods) < STILL_MIN_S:
        return 0.0
    dev = np.concatenate([h[m] - h[m].mean() for m in periods])
    return float(np.sqrt(np.mean(dev ** 2)))


def bridge_single_gaps(proposed: np.ndarray) -> np.ndarray:
    """Decision W433: ``proposed`` (+1 / -1 / 0 per step) with every single unproposed step between two proposed
    steps of one sign given that sign - a step-to-step flight's closing steps keep its 2 s rate near W91's 0.1 m/s
    and one of them dips under it (trial s40 T1 F2: a 1.7 m flight split into 1.0 m + 0.7 m runs, no climb)."""
    s = np.asarray(proposed, dtype=int).ravel().copy()
    if len(s) >= 3:
        gap = (s[1:-1] == 0) & (s[:-2] != 0) & (s[:-2] == s[2:])
        s[1:-1][gap] = s[:-2][gap]
    return s


def climb_runs(proposed: np.ndarray, start_h: np.ndarray, end_h: np.ndarray,
               noise_sd: float) -> list[tuple[int, int, float]]:
    """Decision W108: the climbs, ``(first, stop, height)`` per climb (rows ``first:stop``, height in m, signed).
    ``proposed`` is each step's signed proposal (+1 up, -1 down, 0 none; W91's rate test), ``start_h`` / ``end_h``
    the altitude (m) at each step's start / end. A maximal run of consecutive steps proposed with one sign (a single
    unproposed step between two of one sign bridged, decision W433) is a climb when its height (``end_h`` of its
    last step minus ``start_h`` of its first) has that sign and is at least ``max(STAIR_CLIMB_MIN_M,
    CLIMB_NOISE_SDS * noise_sd)``."""
    s = bridge_single_gaps(proposed)
    need = max(STAIR_CLIMB_MIN_M, CLIMB_NOISE_SDS * float(noise_sd))
    edges = np.flatnonzero(np.diff(np.concatenate([[0], s, [0]])) != 0)  # every change of the proposal
    return [(int(a), int(b), float(end_h[b - 1] - start_h[a])) for a, b in zip(edges[:-1], edges[1:], strict=True)
            if s[a] != 0 and s[a] * (end_h[b - 1] - start_h[a]) >= need]


def climb_turn_pieces(dz: np.ndarray, min_turn_m: float = STAIR_CLIMB_MIN_M) -> list[tuple[int, int]]:
    """Decision W526: a run of climb rows of walking height change ``dz`` (m per row) cut at its turns, as
    ``(first, stop)`` pieces covering every row. The height is cumulated from the run's start; where it reaches an
    extreme - at least ``min_turn_m`` (W108's least climb) from the piece's start - and then returns by at least
    ``min_turn_m``, the piece ends after that extreme's row and the rest is read the same way. An up flight and the
    down flight after it whose rows are adjacent (a stand and a turn at the top hold no step) are two pieces."""
    dz = np.nan_to_num(np.asarray(dz, dtype=float).ravel())
    c = np.concatenate([[0.0], np.cumsum(dz)])  # the height at each row boundary
    n, s, out = len(dz), 0, []
    hi = lo = 0
    j = 1
    while j <= n:
        hi = j if c[j] > c[hi] else hi
        lo = j if c[j] < c[lo] else lo
        k = (hi if c[hi] - c[s] >= min_turn_m and c[hi] - c[j] >= min_turn_m else
             lo if c[s] - c[lo] >= min_turn_m and c[j] - c[lo] >= min_turn_m else None)
        if k is None:
            j += 1
            continue
        out.append((s, k))
        s = hi = lo = k
        j = k + 1
    out.append((s, n))
    return [(a, b) for a, b in out if b > a]


def climb_mask(proposed: np.ndarray, start_h: np.ndarray, end_h: np.ndarray, noise_sd: float) -> np.ndarray:
    """Decision W108: the steps of a climb (:func:`climb_runs`), a mask over the steps."""
    return runs_mask(len(np.asarray(proposed).ravel()), climb_runs(proposed, start_h, end_h, noise_sd))


def runs_mask(n: int, runs: list[tuple[int, int, float]]) -> np.ndarray:
    """The mask over ``n`` steps of the rows ``first:stop`` of ``runs`` (:func:`climb_runs`)."""
    out = np.zeros(int(n), dtype=bool)
    for a, b, _ in runs:
        out[a:b] = True
    return out


#: decision W433: a climb whose barometric rise per step is under this (m) is climbed step to step (both feet on
#: each stair, every second step a closing step): half of L39's highest riser (0.18 m) is 0.09 m, L39's lowest riser
#: 0.15 m - a step-over-step climb rises one riser per step - and this lies between the two
STEP_TO_STEP_MAX_RISE_M = 0.12


def step_to_step(height_m: float, n_steps: int) -> bool:
    """Decision W433: whether a climb of ``height_m`` (m, signed) over ``n_steps`` steps is climbed step to step (its
    |height| per step under :data:`STEP_TO_STEP_MAX_RISE_M`)."""
    return abs(float(height_m)) / max(int(n_steps), 1) < STEP_TO_STEP_MAX_RISE_M


def step_to_step_mask(n: int, climbs: list[tuple[int, int, float]]) -> np.ndarray:
    """Decision W433: the steps of the ``climbs`` (:func:`climb_runs` over ``n`` steps) whose |height| per step is
    under :data:`STEP_TO_STEP_MAX_RISE_M`: a step-to-step climb, whose steps move half a tread each."""
    return runs_mask(n, [r for r in climbs if step_to_step(r[2], r[1] - r[0])])


def climb_tread(height_m: float, n_steps: int) -> float:
    """Decisions W91, W433: the most a step of a climb of ``height_m`` (m) over ``n_steps`` steps moves horizontally:
    the tread (:data:`STAIR_TREAD_M`, thesis ch.7.3.2.1), half of it step to step (:func:`step_to_step`)."""
    return 0.5 * STAIR_TREAD_M if step_to_step(height_m, n_steps) else STAIR_TREAD_M


class LiveClimbHold:
    """Decision E358: W108's climbs (:func:`climb_runs`) read causally for the live waist tracker's
    ``stairs_length="climbs"`` with the option ``live_climbs="hold"``: the steps of an OPEN run of W91's proposals
    are held until the run is decided, then released in order with their bound (m, :func:`climb_tread`), or None
    (unbounded). A run is consecutive steps proposed with one sign, a single unproposed step inside bridged (W433:
    held while the run may go on); it is decided as a climb once its height from its first step's start to the
    step's end has its sign and reaches ``min_height_m`` (W108's :data:`STAIR_CLIMB_MIN_M`, without its still-period
    noise term: the still period after the walk is not known live) - its held steps and every later step of it are
    released bounded by the run so far - or as no climb when it ends (another sign, two unproposed steps, a step
    without altitude, :meth:`flush`): its held steps released unbounded. A step outside any run is released at once,
    so level walking is never delayed. :meth:`push` / :meth:`flush` return ``[(key, bound or None), ...]``."""

    def __init__(self, *, min_height_m: float = STAIR_CLIMB_MIN_M):
        self.min_height_m = float(min_height_m)
        self._run: list | None = None  # [sign, start height (m), steps, climbing]
        self._held: list = []  # the open run's steps not released yet
        self._gap = None  # the unproposed step after the run, held: W433 bridges it if the run goes on

    def size(self) -> int:
        """The steps held now."""
        return len(self._held) + (self._gap is not None)

    def flush(self) -> list[tuple[object, float | None]]:
        """End of the run (and of the stream): the held steps, unbounded (a climb has released its own)."""
        out = [(k, None) for k in self._held] + ([] if self._gap is None else [(self._gap, None)])
        self._run, self._held, self._gap = None, [], None
        return out

    def push(self, key, sign: int, start_h: float | None, end_h: float | None) -> list[tuple[object, float | None]]:
        """The step ``key`` with its W91 proposal ``sign`` (+1 up, -1 down, 0 none) and its altitude (m) at its start
        / end (None: unknown, which ends the run): the steps released by it, in order."""
        if start_h is None or end_h is None or not (np.isfinite(start_h) and np.isfinite(end_h)):
            return self.flush() + [(key, None)]
        run = self._run
        if sign == 0:
            if run is None:
                return [(key, None)]
            if self._gap is None:  # W433: bridged if the next step goes on with the run's sign
                self._gap = key
                return []
            return self.flush() + [(key, None)]  # two unproposed steps: the run has ended
        out = []
        if run is not None and run[0] == sign:
            if self._gap is not None:
                self._held.append(self._gap)
                self._gap, run[2] = None, run[2] + 1
            run[2] += 1
        else:
            out = self.flush()
            run = self._run = [int(sign), float(start_h), 1, False]
        self._held.append(key)
        height = float(end_h) - run[1]
        if run[3] or sign * height >= self.min_height_m:  # W108: a climb of at least 1.5 m, decided now
            run[3] = True
            tread = climb_tread(height, run[2])  # W433: half the tread step to step
            out += [(k, tread) for k in self._held]
            self._held = []
        return out


def live_climb_bounds(proposed: np.ndarray, start_h: np.ndarray, end_h: np.ndarray, *,
                      min_height_m: float = STAIR_CLIMB_MIN_M) -> tuple[np.ndarray, np.ndarray]:
    """Decision E358: :class:`LiveClimbHold` over a whole track's steps in order (``track_waist(realtime=True)``'s
    reference of the live tracker): each step's bound (m; inf: unbounded) and the step whose report released it
    (its own index when not held; ``n`` at the end of the stream)."""
    n = len(proposed)
    bound, released = np.full(n, np.inf), np.full(n, n, dtype=int)
    hold = LiveClimbHold(min_height_m=min_height_m)
    for i in range(n + 1):
        out = hold.flush() if i == n else hold.push(i, int(proposed[i]), float(start_h[i]), float(end_h[i]))
        for k, b in out:
            bound[k], released[k] = np.inf if b is None else b, i
    return bound, released


#: Decision W230: the largest barometric height change (m) one walking step can make. A step climbs one riser
#: (0.15-0.18 m, L39; the simulator's 0.17 m), two at a time ~0.36 m; 0.5 m is ~3 risers and L146's whole ascent
#: band in one step. A larger change inside a step (HA002 Test11's level floor: -1.28 and -1.19 m at 141-142 s,
#: W108's pressure transient) is the air, not the walker; rides happen while standing (W158's pause_dz_m).
MAX_STEP_DZ_M = 0.5


def step_jumps(dz: np.ndarray, max_dz: float = MAX_STEP_DZ_M) -> np.ndarray:
    """Decision W230: the mask of the steps whose barometric change ``dz`` (m, end minus start) exceeds ``max_dz``."""
    return np.abs(np.nan_to_num(np.asarray(dz, dtype=float))) > max_dz


def step_jump_line(dz: np.ndarray, end_s: np.ndarray, *, hold: bool, live: bool = False) -> str | None:
    """Decision W230's one line naming the steps of :func:`step_jumps` (their change ``dz``, m, and end ``end_s``,
    s), None without one: ``hold`` says they were held level (option ``step_bound``); ``live`` (decision E148:
    ``pdrlearn run`` of a waist bundle, whose live tracker does not hold them) names offline ``track`` as where the
    option acts.
    Shared by the offline lower-back track and ``run``."""
    dz, end_s = np.asarray(dz, dtype=float), np.asarray(end_s, dtype=float)
    jumped = step_jumps(dz)
    if not jumped.any():
        return None
    dz, at = dz[jumped], end_s[jumped]
    shown = ", ".join(f"{d:+.2f} m at {a:.1f} s" for d, a in zip(dz[:5], at[:5], strict=True))
    if hold:
        done = "held level (option step_bound): their change is left out of the altitude, the floors and the ascent"
    elif live:
        done = ("the altitude, floors and ascent include it; offline `pdrlearn track` with the option step_bound "
                "(PARAMS.json \"options\") holds such steps level, though the pressure's return then reads as a climb")
    else:
        done = ("the altitude, floors and ascent include it; the option step_bound (PARAMS.json \"options\") holds "
                "such steps level, though the pressure's return then reads as a climb")
    return (f"{int(jumped.sum())} step(s) changed the barometric altitude by more than {MAX_STEP_DZ_M:.1f} m "
            f"each ({shown}{', ...' if len(dz) > 5 else ''}), {float(dz.sum()):+.2f} m in all: a walking "
            "step climbs a riser or two (0.15-0.18 m each), so these are pressure transients (a door, a "
            f"draught, wind), not climbs; {done} (decision W230)")


def hold_step_jumps(z: np.ndarray, z_start: np.ndarray, max_dz: float = MAX_STEP_DZ_M
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Decision W230: ``z`` (n+1,) the altitude at the track's start and each step's end, ``z_start`` (n,) at each
    step's start (W158). A step whose change (end minus start) exceeds ``max_dz`` in size is held level: its
    change is taken out of it and of every later altitude (the pauses' changes, W158, are kept). Returns
    ``(z, z_start, jumped)`` with ``jumped`` the (n,) mask of the steps held."""
    z = np.asarray(z, dtype=float)
    zs = np.asarray(z_start, dtype=float)
    dz = z[1:] - zs
    jumped = step_jumps(dz, max_dz)
    cut = np.cumsum(np.where(jumped, dz, 0.0))
    return z - np.concatenate([[0.0], cut]), zs - np.concatenate([[0.0], cut[:-1]]), jumped


#: decision L154: the fused altitude's model of the barometer's wander, a first-order Gauss-Markov error of this SD
#: (m; W108: the real belt barometer wanders ~0.3 m on level walks, its still-period SD 0.06-0.65 m) and
BARO_WANDER_SD_M = 0.3
#: this correlation time (s): a change that outlasts it is a climb, a shorter one the barometer's wander
BARO_WANDER_TAU_S = 10.0
#: decision L154: the white noise of the 1 s-averaged altitude (m): one BMP280 sample's 0.13 m (0.0157 hPa, thesis
#: Table 18; W89), not reduced by the averaging (conservative)
BARO_NOISE_M = 0.13
#: decision L154: the foot's per-stride height error (m, 1 SD) on a stride that keeps its height (stairs; L39's
#: measured stair error, |error| mean 0.05 m over 3.8 m of ~24 strides: ~0.01 m per stride) and on a stride the
#: rules call level (|dz| under L39's 0.10 m), whose missed height is also the slope state's:
FOOT_STRIDE_SD_M = 0.01
#: the height a level stride misses on a slope (m per stride) changes by this much per stride (1 SD): a slope of
#: up to ~7 % (0.10 m per 1.4 m stride, which L39 reads level) is reached within ~5 strides
SLOPE_STEP_SD_M = 0.02
#: decision L154: a barometer change this many SDs away from the filter's prediction within one stride is a pressure
#: transient (W108: 1.98 m in 2.4 s on a level floor, HA002 Test11), not a climb the foot missed: the barometer is
#: re-referenced by it (the thesis' differential mode from a new reference point, ch.4.3.1.4) and the height kept
BARO_JUMP_SDS = 4.0
#: decision L478 (a project choice, not from the thesis): a climbing stride's (|dz| >= L39's 0.10 m) height carries a
#: bias b (m per stride) the foot repeats over a climb (trial T3: +30.99 m read for a 30 m trail climb, +0.0045 m per
#: stride), a state with this prior SD (m; L154's FOOT_STRIDE_SD_M, a stride's whole error budget) that
FOOT_CLIMB_BIAS_SD_M = 0.01
#: walks by this SD per climbing stride (m), so a later climb (a descent, stairs) may carry another bias; a level
#: stride neither moves nor uses it, so the barometer's disagreement over a climb is the climb's, not the level
#: strides' slope after it
FOOT_CLIMB_BIAS_STEP_SD_M = 0.001
#: decision L502 (L503: "scale" adopted): the climb bias's forms, :func:`fuse_altitude`'s ``bias_mode``
BIAS_MODES = ("one", "split", "scale")
#: decision L502: "scale"'s prior and random walk are L478's per-stride budgets at the smallest climbing stride (L39)
SCALE_REF_DZ_M = 0.10


#: decision L564 (a project choice): a stride is read inside a barometric climb over the span from this many seconds
#: before its start to as many after its end - about four strides each side, so a ramp's first and last strides are in
CLIMB_SPAN_S = 5.0
#: decision L564: ... when the barometer changes over that span by at least this grade (%) of the horizontal length
#: walked in it: L301's RAMP_MIN_GRADE_PCT, the grade that makes a ramp row (above ADA 2010's 1:48 level bound)
CLIMB_MIN_GRADE_PCT = 3.0


def barometric_climb(start_s: np.ndarray, end_s: np.ndarray, length_m: np.ndarray, baro_t: np.ndarray,
                     baro_hpa: np.ndarray, span_s: float = CLIMB_SPAN_S,
                     min_grade_pct: float = CLIMB_MIN_GRADE_PCT) -> np.ndarray:
    """Decision L564: boolean per stride (walking order; ``start_s`` / ``end_s`` on the barometer's clock,
    ``length_m`` horizontal), True inside a barometric climb: :func:`relative_altitude` changes from ``span_s`` before
    the stride's start to ``span_s`` after its end by at least ``min_grade_pct`` % of the summed length of the strides
    that overlap that span. Centred (it reads the barometer after the stride): the fusion runs after the track.
    Non-finite lengths count as 0."""
    t0, t1 = np.asarray(start_s, dtype=float).ravel(), np.asarray(end_s, dtype=float).ravel()
    n = len(t0)
    if not n:
        return np.zeros(0, dtype=bool)
    length = np.abs(np.nan_to_num(np.asarray(length_m, dtype=float).ravel()))
    a, b = t0 - span_s, t1 + span_s
    h = relative_altitude(baro_t, baro_hpa, np.concatenate([a, b]))
    rise = np.abs(h[n:] - h[:n])
    order = np.argsort(t1, kind="stable")
    walked = np.concatenate([[0.0], np.cumsum(length[order])])
    # strides overlapping [a, b]: ending after a and starting before b (walking order: end times sorted)
    lo = np.searchsorted(t1[order], a, side="right")
    hi = np.searchsorted(np.sort(t0), b, side="left")
    run = walked[np.maximum(hi, lo)] - walked[lo]
    return (run > 0) & (rise >= min_grade_pct / 100.0 * run)


def without_stair_climbs(climbing: np.ndarray, raw_dz: np.ndarray, length_m: np.ndarray,
                         stair_grade_pct: float) -> np.ndarray:
    """Decision L591's candidate (L565's "next candidate"): ``climbing`` (:func:`barometric_climb`) with every run of
    climbing strides cleared that holds a stair stride - a stride whose own |``raw_dz``| over its horizontal
    |``length_m``| is at least ``stair_grade_pct`` (L301's stair grade): a stair climb keeps L39's level heights
    (its landing and turn strides' integrated heights cost L565's stairs 0.11 m). A pure kernel."""
    out = np.asarray(climbing, dtype=bool).ravel().copy()
    raw = np.abs(np.nan_to_num(np.asarray(raw_dz, dtype=float).ravel()))
    length = np.abs(np.nan_to_num(np.asarray(length_m, dtype=float).ravel()))
    stair = raw >= stair_grade_pct / 100.0 * length
    stair &= raw > 0
    from pdrlearn.signal import runs

    for a, b in runs(out.copy()):
        if stair[a:b].any():
            out[a:b] = False
    return out


class AltitudeFusion:
    """Decision L154's filter over the strides, one stride at a time (decision E339: shared by :func:`fuse_altitude`
    and the live :class:`~pdrlearn.runtime.Tracker`'s ``altitude="fused"``): :meth:`start` with the barometer's
    altitude at the first stride's start, then :meth:`stride` per stride in walking order with its height change, its
    end time and the barometer's altitude there (both relative to the first start, :func:`relative_altitude`); each
    returns the fused height change. The model, the states and the options are :func:`fuse_altitude`'s."""

    def __init__(self, *, level_dz_m: float = 0.10, climb_bias: bool = True, bias_mode: str = "scale"):
        if bias_mode not in BIAS_MODES:
            raise ValueError(f"bias_mode {bias_mode!r}: one of 'one', 'split', 'scale' (decision L502)")
        self.level_dz_m, self.mode = float(level_dz_m), bias_mode
        per = SCALE_REF_DZ_M if bias_mode == "scale" else 1.0  # L502: k's budgets are b's at a 0.10 m stride
        self._bias_sd = FOOT_CLIMB_BIAS_SD_M / per if climb_bias else 0.0
        self._step_sd = FOOT_CLIMB_BIAS_STEP_SD_M / per
        # h = 0 and no slope at the start, w its prior, b (L478; L502: b_up or k) and L502's b_down their priors
        # (0: off)
        self.x = np.zeros(5)
        self.p = np.diag([0.0, 0.0, BARO_WANDER_SD_M ** 2, self._bias_sd ** 2,
                          self._bias_sd ** 2 * (bias_mode == "split")])
        self.ref = 0.0  # the barometer's reference, moved by each transient
        self.t_prev: float | None = None

    _OBS = np.array([1.0, 0.0, 1.0, 0.0, 0.0])

    def state(self) -> dict:
        """Decision E356: the filter's state (its options are the constructor's): ``x``, ``p``, ``ref``, ``t_prev``."""
        return {"x": self.x.tolist(), "p": self.p.tolist(), "ref": float(self.ref), "t_prev": self.t_prev}

    def set_state(self, state: dict) -> None:
        """Decision E356: go on from :meth:`state` of a filter with the same options."""
        self.x = np.asarray(state["x"], float).reshape(5)
        self.p = np.asarray(state["p"], float).reshape(5, 5)
        self.ref = float(state["ref"])
        self.t_prev = None if state["t_prev"] is None else float(state["t_prev"])

    def _update(self, z: float) -> None:
        obs, x, p = self._OBS, self.x, self.p
        s = obs @ p @ obs + BARO_NOISE_M ** 2
        if abs(z - self.ref - obs @ x) > BARO_JUMP_SDS * np.sqrt(s):  # L154: a transient re-references the barometer
            self.ref = z - obs @ x
            return
        k = p @ obs / s
        self.x, self.p = x + k * (z - self.ref - obs @ x), p - np.outer(k, obs @ p)

    def start(self, t0: float, b0: float) -> None:
        """The first stride's start ``t0`` (s) and the barometer's altitude there ``b0`` (m)."""
        self._update(b0)
        self.t_prev = float(t0)

    def stride(self, d: float, t1: float, b: float, climbing: bool = False) -> float:
        """One stride: its height change ``d`` (m, after L39 / the class rules; non-finite as 0), its end ``t1`` (s)
        and the barometer's altitude there ``b`` (m); ``climbing`` (L564): not level whatever its |d|. Returns its
        fused height change (m)."""
        d = float(np.nan_to_num(d))
        level = abs(d) < self.level_dz_m and not climbing
        mode = self.mode
        a = np.exp(-max(float(t1 - self.t_prev), 0.0) / BARO_WANDER_TAU_S)  # the wander decorrelates
        climb = float(not level and self._bias_sd > 0.0)
        down = climb * float(mode == "split" and d < 0.0)  # L502: a descending stride's own bias
        up = climb - down
        f = np.eye(5)
        f[0, 1], f[2, 2], f[0, 4] = float(level), a, down
        f[0, 3] = up * d if mode == "scale" else up  # L502: dz (1 + k) flips the correction with dz's sign
        h0 = self.x[0]
        self.x = f @ self.x + np.array([d, 0.0, 0.0, 0.0, 0.0])
        self.p = f @ self.p @ f.T + np.diag([FOOT_STRIDE_SD_M ** 2, SLOPE_STEP_SD_M ** 2 * level,
                                             BARO_WANDER_SD_M ** 2 * (1.0 - a * a), self._step_sd ** 2 * up,
                                             self._step_sd ** 2 * down])
        self._update(b)
        self.t_prev = float(t1)
        return float(self.x[0] - h0)


def fuse_altitude(dz: np.ndarray, start_s: np.ndarray, end_s: np.ndarray, baro_t: np.ndarray,
                  baro_hpa: np.ndarray, *, level_dz_m: float = 0.10, climb_bias: bool = True,
                  bias_mode: str = "scale", climbing: np.ndarray | None = None) -> np.ndarray:
    """Decision L154: the strides' height changes ``dz`` (m, after L39 / the class rules) fused with a barometer
    ``(baro_t, baro_hpa)`` (s, hPa) by a Kalman filter over the strides (causal: each stride's height uses the
    barometer up to its end; ``start_s`` / ``end_s`` the strides' times on the barometer's clock).

    State: the height h, the slope s (the height a level stride misses) and the barometer's error w (measured:
    b = h + w + noise). A stride moves h by its dz (+ s when |dz| < ``level_dz_m``: a stride the rules call
    level) with the foot's error :data:`FOOT_STRIDE_SD_M`; s is a random walk of :data:`SLOPE_STEP_SD_M` per level
    stride; h does not move between strides; w is a first-order Gauss-Markov process (:data:`BARO_WANDER_SD_M`,
    :data:`BARO_WANDER_TAU_S`), so a barometer change that outlasts the wander's time becomes a slope and a short
    one does not. The measurement is :func:`relative_altitude` (W89's 1 s mean; the thesis' "differential mode",
    ch.4.3.1.4) at each stride's end, with :data:`BARO_NOISE_M`; a measurement :data:`BARO_JUMP_SDS` SDs from its
    prediction moves the barometer's reference, not the height. ``climb_bias`` (decision L478; on by default
    since L479, whose rule was met: false ramps 5 -> 0; W413: a keyword, no module switch) adds a fourth state, the
    climbing strides' bias b (:data:`FOOT_CLIMB_BIAS_SD_M`, a random walk of :data:`FOOT_CLIMB_BIAS_STEP_SD_M` per
    climbing stride): a climbing stride moves h by dz + b. ``bias_mode`` (decision L502, one of :data:`BIAS_MODES`;
    L503 adopted "scale"): "one" that state; "split" b for climbing and a fifth state for descending strides;
    "scale" the state is a scale k, a climbing stride moves h by dz (1 + k). ``climbing`` (decision L564, a boolean
    per stride, :func:`barometric_climb`): those strides are climbing strides whatever their |dz| (the caller gives
    them the foot's un-levelled height: one height source inside a barometric climb). Returns the fused per-stride
    height changes (their sum is the fused altitude change); non-finite dz count as 0."""
    d = np.nan_to_num(np.asarray(dz, dtype=float).ravel())
    t0, t1 = np.asarray(start_s, dtype=float).ravel(), np.asarray(end_s, dtype=float).ravel()
    if not len(d):
        return d
    b = relative_altitude(baro_t, baro_hpa, np.concatenate([[t0[0]], t1]))
    climb = np.zeros(len(d), dtype=bool) if climbing is None else np.asarray(climbing, dtype=bool).ravel()
    kf = AltitudeFusion(level_dz_m=level_dz_m, climb_bias=climb_bias, bias_mode=bias_mode)  # decision E339: shared
    h = np.zeros(len(d) + 1)
    kf.start(t0[0], b[0])
    for i in range(len(d)):
        kf.stride(d[i], t1[i], b[i + 1], bool(climb[i]))
        h[i + 1] = kf.x[0]
    return np.diff(h)
