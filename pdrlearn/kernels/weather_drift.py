"""Decision L464: the weather's barometric drift rate read where the walker stands still - pure kernels.

On a hike the weather's drift happens during the climbs and L172's band counts it into them (trial T3: a closed
loop's barometer drifted +3.70 m in 35 min while ``altitude_drift_m``, the slow change L172 dropped, read 0.23 m).
A standstill (a viewpoint pause, the stands at either end) has no climb, so the barometric altitude's slope over
it is the weather's (plus noise); that rate times the track's span is the drift the climbs and the net change took
in."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.rests import between_rows

#: decision L464: a standstill read for the drift lasts at least this (s) after trimming: L172's climb window (a
#: storey is climbed in well under a minute), so a shorter pause between two climbs is not read as weather
STANDSTILL_MIN_S = 60.0
#: decision L464: seconds trimmed from each end of a standstill: the barometer's 1 s smoothing (kernels.barometer
#: ALTITUDE_SMOOTH_S) and the last and first step's height change, with margin
STANDSTILL_TRIM_S = 5.0


def standstills(start, end, t_first: float, t_last: float, min_s: float = STANDSTILL_MIN_S,
                trim_s: float = STANDSTILL_TRIM_S) -> list[tuple[float, float]]:
    """The standstills (s, s) of a walk whose steps span ``start`` to ``end`` (any order) within a recording from
    ``t_first`` to ``t_last``: the times before the first step, between steps and after the last, each trimmed by
    ``trim_s`` at both ends and kept when at least ``min_s`` long."""
    s = np.asarray(start, dtype=float).ravel()
    e = np.asarray(end, dtype=float).ravel()
    keep = np.isfinite(s) & np.isfinite(e)
    s, e = s[keep], e[keep]
    order = np.argsort(s, kind="stable")
    # an overlapping step keeps the walk going (carry); a recording without steps is one standstill
    lo, hi = between_rows(s[order], e[order], edges=(t_first, t_last), carry=True)
    return [(float(a + trim_s), float(b - trim_s)) for a, b in zip(lo, hi, strict=True) if b - a - 2 * trim_s >= min_s]


def drift_rate(t, z, intervals) -> tuple[float | None, float]:
    """The pooled least-squares slope (m/s) of the altitudes ``z`` at the times ``t`` over the ``intervals``, each
    with its own level (a climb between two standstills moves the level, not the slope), and the seconds read;
    (None, 0.0) without two finite samples in any interval."""
    t = np.asarray(t, dtype=float).ravel()
    z = np.asarray(z, dtype=float).ravel()
    ok = np.isfinite(t) & np.isfinite(z)
    t, z = t[ok], z[ok]
    sxy = sxx = seconds = 0.0
    for a, b in intervals:
        m = (t >= a) & (t <= b)
        if np.count_nonzero(m) < 2:
            continue
        dt, dz = t[m] - t[m].mean(), z[m] - z[m].mean()
        sxy, sxx, seconds = sxy + float(dt @ dz), sxx + float(dt @ dt), seconds + float(b - a)
    return (sxy / sxx, seconds) if sxx > 0 else (None, 0.0)
