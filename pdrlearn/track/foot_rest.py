"""What the foot unit's rests say about its sensor and its placement (decisions B133, B134).

- B133: at foot-flat the accelerometer reads gravity alone, so the median |acc| over the detected rests (the
  ZUPT's own inertial test, :func:`pdrlearn.displace.foot.inertial_stance`) over standard gravity is the
  accelerometer's scale: shown by ``pdrlearn info`` (a display); B133's warning candidate (2 % off 1 g) was not adopted
  (``experiments/foot_rest_scale_b133.py``: real correctly scaled feet read 0.967-1.008 g).
- B134: a foot unit swings forward at several hundred deg/s every stride; a unit in the foot files that walks
  (its |acc| varies, B37) but never swings (B91's 99th percentile of |gyro| under ``FOOT_NO_SWING``) is not on
  the foot (waist, pocket): its "rests" are not foot-flats and its ZUPT track is meaningless (trial `placement`
  finding 4: 8.99 m for 89.5 m, warned only as running).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.displace.foot import inertial_stance
from pdrlearn.io.sensors import UNIT_IMU
from pdrlearn.kernels.units import FOOT_NO_SWING, STANDARD_GRAVITY, WALKING_ACC_STD, swing_rate
from pdrlearn.signal import interp_rows

#: fewer rest samples than this: no figure (nothing to judge)
MIN_REST_SAMPLES = 20


def foot_rest_stats(session) -> dict | None:
    """The foot unit's rest figures: ``rest_acc_g`` (median |acc| over the detected foot-flat samples, in g;
    None with fewer than :data:`MIN_REST_SAMPLES`), ``rest_fraction``, ``swing_rad_s`` (B91's statistic) and
    ``walking`` (B37's sd of |acc| over :data:`WALKING_ACC_STD`). None without both foot IMU streams. |acc| and
    |gyro| do not depend on the axes, so no frame is needed."""
    acc_n, gyr_n = UNIT_IMU["foot"]
    if not session.has(acc_n, gyr_n):
        return None
    acc_s, gyr_s = session.streams[acc_n], session.streams[gyr_n]
    if len(acc_s) < 4 or len(gyr_s) < 4:
        return None
    acc = np.asarray(acc_s.values, dtype=float)
    gyr = interp_rows(acc_s.t, gyr_s.t, np.asarray(gyr_s.values, dtype=float))
    norm = np.linalg.norm(acc, axis=1)
    rest = inertial_stance(acc, gyr, float(acc_s.rate_hz))
    ok = np.isfinite(norm) & rest
    return {"rest_acc_g": float(np.median(norm[ok]) / STANDARD_GRAVITY) if ok.sum() >= MIN_REST_SAMPLES else None,
            "rest_fraction": float(rest.mean()), "swing_rad_s": swing_rate(gyr_s.values),
            "walking": bool(np.nanstd(norm) > WALKING_ACC_STD)}


def foot_placement_warning(stats: dict | None, where: str) -> str | None:
    """Decision B134: one line when the foot unit walks but never swings like a foot."""
    if not stats or not stats["walking"] or not stats["swing_rad_s"] < FOOT_NO_SWING:
        return None
    return (f"{where}: no foot-flat rests found: the foot unit (fAccelerometer.csv, fGyroscope.csv) walks but never "
            f"swings like a foot (at most {np.degrees(stats['swing_rad_s']):.0f} deg/s, 99th percentile of |gyro|; a "
            f"walking foot exceeds {np.degrees(FOOT_NO_SWING):.0f}), so the rests its ZUPT finds are not foot-flats "
            "and its distance is meaningless: is this unit on the foot? (pocket/waist/shank placements are not "
            "supported for the foot unit: mount it on the shoe, instep, heel or side; a lower-back unit's data go "
            "in the w* files; decision B134)")
