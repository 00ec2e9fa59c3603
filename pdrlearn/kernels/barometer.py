"""Pressure and altitude, numpy only: the barometric formula of the simulator's barometer and its inverse,
the relative altitude of a barometer stream (decision W89 in docs/decisions/waist.md).

The thesis uses the barometer "in differential mode": the altitude is the change of the pressure from a
reference point, not an absolute height, because the sea-level pressure drifts with the weather by more than
four storeys over a month (thesis ch.4.3.1.4, Figure 44, Table 18). :func:`relative_altitude` is that
differential altitude, from the international barometric formula (:func:`pressure_hpa`, the formula the
simulator writes ``wBarometer`` with, docs/simulator.md).
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
                      smooth_s: float = ALTITUDE_SMOOTH_S) -> np.ndarray:
    """Altitude (m) at the times ``at`` relative to the first of them, from a barometer ``(t, p_hpa)``
    (s, hPa): the pressure averaged over a centred ``smooth_s`` window (fewer samples at the ends), converted
    with :func:`altitude_m` and interpolated (held beyond the stream's ends). Thesis ch.4.3.1.4: the
    differential of the pressure from a reference point. Non-finite samples are skipped; with none finite
    the altitude is 0 throughout."""
    t, p = np.asarray(t, dtype=float).ravel(), np.asarray(p_hpa, dtype=float).ravel()
    at = np.asarray(at, dtype=float).ravel()
    ok = np.isfinite(t) & np.isfinite(p)
    t, p = t[ok], p[ok]
    if not len(t) or not len(at):
        return np.zeros(len(at))
    cs = np.concatenate([[0.0], np.cumsum(p)])
    lo = np.searchsorted(t, t - 0.5 * smooth_s, side="left")
    hi = np.searchsorted(t, t + 0.5 * smooth_s, side="right")
    mean = (cs[hi] - cs[lo]) / (hi - lo)
    h = np.interp(at, t, altitude_m(mean))
    return h - h[0]


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


def climb_mask(proposed: np.ndarray, start_h: np.ndarray, end_h: np.ndarray, noise_sd: float) -> np.ndarray:
    """Decision W108: the steps of a climb. ``proposed`` is each step's signed proposal (+1 up, -1 down, 0 none;
    W91's rate test), ``start_h`` / ``end_h`` the altitude (m) at each step's start / end. A maximal run of
    consecutive steps proposed with one sign is a climb when its height (``end_h`` of its last step minus
    ``start_h`` of its first) has that sign and is at least ``max(STAIR_CLIMB_MIN_M, CLIMB_NOISE_SDS *
    noise_sd)``."""
    s = np.asarray(proposed, dtype=int).ravel()
    out = np.zeros(len(s), dtype=bool)
    need = max(STAIR_CLIMB_MIN_M, CLIMB_NOISE_SDS * float(noise_sd))
    edges = np.flatnonzero(np.diff(np.concatenate([[0], s, [0]])) != 0)  # every change of the proposal
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        if s[a] != 0 and s[a] * (end_h[b - 1] - start_h[a]) >= need:
            out[a:b] = True
    return out
