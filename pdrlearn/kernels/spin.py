"""A turn on the spot without a step: the foot rotates about the vertical only (decision L742).

A walker turning on the planted foot (S106's ``spin``) rotates the foot unit about gravity at up to several rad/s,
over the stance threshold (L27's cap 2.0 rad/s), so the stance segmenter (streamed) and the step detectors (offline)
saw a "swing" and a stride came out of it. A real swing tilts the foot (toe-off and heel strike pitch it by tens of
degrees at several rad/s) and accelerates it; a turn in place does neither. :func:`turn_in_place` is the one rule
offline ``track``, ``track --streaming`` and the runtime apply to a stride window before measuring it.

Units: s, m/s^2, rad/s. Numpy only (the lean runtime imports it).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.units import STANDARD_GRAVITY

#: decision L742: a turn in place tilts the foot at most this fast (rad/s): the peak rate across the window's mean
#: specific force (trial s49t2 spins 0.10-0.36; real strides, stepping turns and side steps included, >= 2.78);
#: 0.6, not FE's 1.0: a 0.4 m/s patient's small turn step at 20 Hz (7 cm, 5 cm lift) peaked at 0.927 (the lead,
#: at the merge: tests/test_clinical_summary.py's patient walk)
SPIN_TILT_MAX_RAD_S = 0.6
#: decision L742: nor moves |specific force| further than this from g (m/s^2; a pivot 0.15 m off the unit at 3 rad/s
#: adds 1.4; trial s49t2 spins 0.12-0.18, real strides >= 12)
SPIN_ACC_DEV_MAX = 3.0


def _inside(t: np.ndarray, t0: float, t1: float) -> slice:
    return slice(int(np.searchsorted(t, t0, side="left")), int(np.searchsorted(t, t1, side="right")))


def turn_rates(t_acc, acc, t_gyr, gyr, t0: float, t1: float) -> tuple[float, float]:
    """Decision L742's two statistics of the foot window ``[t0, t1]`` (s; sensor axes as :func:`turn_in_place`'s):
    ``(peak rate across the window's mean specific force (rad/s), peak | |acc| - g | (m/s^2))``; NaN when the window
    has under two samples of either or no mean specific force."""
    t_acc, t_gyr = np.asarray(t_acc, dtype=float), np.asarray(t_gyr, dtype=float)
    a = np.asarray(acc, dtype=float)[_inside(t_acc, t0, t1)]
    w = np.asarray(gyr, dtype=float)[_inside(t_gyr, t0, t1)]
    if len(a) < 2 or len(w) < 2:
        return float("nan"), float("nan")
    dev = float(np.nanmax(np.abs(np.sqrt(np.add.reduce(a * a, axis=1)) - STANDARD_GRAVITY)))
    up = np.nanmean(a, axis=0)
    n = float(np.sqrt(up.dot(up)))
    if not n > 0:
        return float("nan"), dev
    up = up / n
    across = w - np.outer(w @ up, up)
    return float(np.nanmax(np.sqrt(np.add.reduce(across * across, axis=1)))), dev


def turn_in_place(t_acc, acc, t_gyr, gyr, t0: float, t1: float) -> bool:
    """Decision L742: whether the foot window ``[t0, t1]`` (s) is a turn on the spot, no stride: its samples'
    (sensor axes; ``t_acc`` (n,), ``acc`` (n, 3) m/s^2, ``t_gyr`` (m,), ``gyr`` (m, 3) rad/s) peak rate across the
    window's mean specific force is under :data:`SPIN_TILT_MAX_RAD_S` and their peak | |acc| - g | under
    :data:`SPIN_ACC_DEV_MAX` (:func:`turn_rates`). False when the window has under two samples of either."""
    tilt, dev = turn_rates(t_acc, acc, t_gyr, gyr, t0, t1)
    return bool(dev < SPIN_ACC_DEV_MAX and tilt < SPIN_TILT_MAX_RAD_S)


def turns_in_place(t_acc, acc, t_gyr, gyr, start_s, end_s) -> np.ndarray:
    """Decision L742: :func:`turn_in_place` of each window ``[start_s[i], end_s[i]]``, a (k,) bool array."""
    return np.array([turn_in_place(t_acc, acc, t_gyr, gyr, float(a), float(b))
                     for a, b in zip(np.asarray(start_s, float), np.asarray(end_s, float), strict=True)], dtype=bool)


def spin_line(n: int | None = None) -> str:
    """Decision L742: the warning line when ``n`` foot windows (None: one or more, streamed) were left out as turns
    on the spot."""
    from pdrlearn.decision_refs import decision_ref

    return (f"{'' if n is None else f'{n} '}turn(s) on the spot without a step left out of the strides: the foot "
            f"rotated about the vertical only (no tilt, no acceleration), which is no stride ({decision_ref('L742')})")


def spin_turn(stream, t0: float, t1: float) -> float:
    """Decision L742: the foot's turn (rad, CCW) over a window ``[t0, t1]`` left out as a turn in place: L31's pivot
    (:func:`pdrlearn.kernels.stride.gap_yaw` of ``fGyroscope`` / ``fAccelerometer`` over the whole window), which
    the next foot-headed stride adds to its heading change (before L742 the spurious stride carried it).
    ``stream(name)`` -> ``(t, values)``, as :func:`~pdrlearn.kernels.stride.stride_gap_yaw`'s."""
    from pdrlearn.kernels.stride import gap_yaw

    return gap_yaw(*stream("fGyroscope"), *stream("fAccelerometer"), float(t0), float(t1),
                   max_s=float(t1) - float(t0))


def foot_gap_start(prev_end: float | None, spun: tuple[float, float] | None) -> float | None:
    """Decision L742: where the foot's L31 gap yaw before a stride starts: after the last window left out as a turn
    in place (``spun`` = (its turn, its end)) when one lies after ``prev_end``, else ``prev_end``."""
    if spun is None or prev_end is None:
        return prev_end
    return max(float(prev_end), float(spun[1]))
