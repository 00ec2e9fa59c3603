"""Decision B454: where a clipped foot accelerometer's missing acceleration lies (a kernel on B77 / B311's test).

A sensor at its full scale reads the rail while the true acceleration is beyond it by an unknown amount: at 100 Hz a
simulated heel strike of 43-72 m/s^2 reads 39.2 m/s^2 on a +-4 g unit, in one sample between neighbours of 11 and
-16 m/s^2, so the neighbours cannot tell the peak (the cubic declipping of trial T3, B454's first candidate, changed
nothing at slow and normal speed). The missing part lies only at the clipped samples, and the ZUPT at the next rest
measures its sum as a velocity error. The foot's white-noise-jerk filter (thesis eq. 44-60) is told so: each clipped
sample adds velocity process noise (full scale x dt)^2, a missing acceleration the size of the full scale (1 SD), so
the smoother puts the velocity error at the impact instead of spreading it over the swing (L21's noise is 1e-4 |a|^2
dt^2, four orders smaller at the rail).
"""
from __future__ import annotations

import numpy as np


def clip_variance(acc: np.ndarray, k: int, dt: float) -> np.ndarray | None:
    """Decision B454: (n * k,) extra velocity process noise (m/s)^2 per sample of the integration grid (``k`` fine
    samples per sample of ``acc``, interval ``dt`` s) from the accelerometer samples ``acc`` (n, 3) that B77 / B311
    call clipped on some axis (:func:`pdrlearn.io.validate.clipped_axes`): (full scale x ``dt``)^2 at them, 0
    elsewhere; None when nothing is clipped (the track is then exactly L21's)."""
    from pdrlearn.io.validate import clipped_axes

    hit, top = clipped_axes(acc, "accelerometer")
    if not hit.size or not hit.any():
        return None
    return np.repeat(np.where(hit.any(axis=1), (top * dt) ** 2, 0.0), k)
