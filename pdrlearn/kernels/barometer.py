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
