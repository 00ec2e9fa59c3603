"""Decision L318: are the two feet's detected contacts comparable? (session 31 prosthesis trial, finding 1)

A foot whose impact is soft (a prosthetic carbon foot, a cushioned shoe, a unit mounted on a damping part or a
low-passed accelerometer) has no heel-strike spike: the contact detector fires later in the loading response on that
foot only, so every step time ending on it reads long, the other foot's short, and stance / double support shift
too. One foot's track cannot tell; two feet can: each foot's **impact sharpness** is the median, over its detected
initial contacts, of the largest rate of change of the accelerometer norm (m/s^3) within
:data:`IMPACT_WINDOW_S` of the contact. Pure functions (arrays in, numbers / a line out).
"""

from __future__ import annotations

import numpy as np

#: decision L318: half-width (s) of the window around a detected IC searched for the impact: a contact detected up to
#: 0.1 s late still has its impact inside; ~the loading response (0-10 % of a ~1.1 s cycle, Perry & Burnfield 2010,
#: Gait Analysis ch. 1)
IMPACT_WINDOW_S = 0.1
#: decision L318: the largest ratio of the two feet's impact sharpness (sharper / softer) taken as comparable
#: contacts. Measured (experiments in L318's text): normal feet 1.00-1.53 (gaitmap's real level pair 1.15, simulated
#: symmetric and asymmetric walkers, with and without force sensors), one foot low-passed at 15 / 8 / 5 / 3 Hz
#: 7.2-40; 3 sits twice above the normal feet's largest and under half the softened feet's smallest
SHARPNESS_RATIO_MAX = 3.0


def impact_sharpness(t: np.ndarray, acc: np.ndarray, ic_s: np.ndarray) -> float | None:
    """Decision L318: the median over the contacts ``ic_s`` (s) of the largest |d|a|/dt| (m/s^3) of the
    accelerometer ``acc`` ((n, 3), m/s^2, timestamps ``t``) within :data:`IMPACT_WINDOW_S` of the contact; None
    without a contact whose window holds three samples."""
    t, acc = np.asarray(t, float), np.asarray(acc, float)
    if len(t) < 3:
        return None
    jerk = np.abs(np.gradient(np.linalg.norm(acc, axis=1), t))
    peaks = []
    for ic in np.asarray(ic_s, float):
        if not np.isfinite(ic):
            continue
        a, b = np.searchsorted(t, [ic - IMPACT_WINDOW_S, ic + IMPACT_WINDOW_S], side="left")
        if b - a >= 3:
            peaks.append(jerk[a:b].max())
    return float(np.median(peaks)) if peaks else None


def comparability_warning(left: float | None, right: float | None) -> str | None:
    """Decision L318: one line when the two feet's :func:`impact_sharpness` differ by more than
    :data:`SHARPNESS_RATIO_MAX` times (the step times, stance and double support are not comparable), else None."""
    if left is None or right is None or min(left, right) <= 0:
        return None
    ratio = max(left, right) / min(left, right)
    if ratio <= SHARPNESS_RATIO_MAX:
        return None
    soft, sharp = ("left", "right") if left < right else ("right", "left")
    return (f"bilateral gait: the {soft} foot's contacts are {ratio:.1f} x less sharp than the {sharp} foot's (median "
            f"impact {left:.0f} / {right:.0f} m/s^3 left/right; over {SHARPNESS_RATIO_MAX:.0f} x, decision L318): a "
            "soft impact (a prosthetic or cushioned foot, a damped mount, a low-passed accelerometer) makes that "
            "foot's contacts read late, so the step times, their asymmetry, stance, swing and double support are "
            "not comparable between the feet - do not report them; each foot's stride times and lengths are")
