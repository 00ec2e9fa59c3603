"""The lower-back heading across lying in bed: the yaw of the trunk's long axis about gravity, not the vertical rate
(decision W269 in docs/decisions/waist.md), numpy only.

W72's ``integrate_stops`` carries the vertical rate (the rate about gravity) of a stop into the heading. Lying, the
trunk's long axis is near horizontal and turning over in bed is a roll about it (S59): no turn of the walking body.
But the long axis is not exactly horizontal (S58: 85-95 deg from the vertical), so each 90 deg roll has a vertical
component of some degrees, and sitting up while the roll unwinds (S59) is a closed path of attitudes whose vertical
rate does not integrate to zero (users 6440 / 6442: 5-10 deg a 90 deg roll, 33-42 deg over the sit-up; a lying
night's heading ended 11-22 deg off). The body's heading is the azimuth of its long axis (the walking upright, W102);
its rate about gravity, with ``z`` the up direction and ``u`` the long axis in the body frame and ``w`` the body
rate, is ``(w.z - (u.z)(w.u)) / (1 - (u.z)^2)``: a roll about ``u`` gives 0, a turn about ``z`` its own rate
(the time derivative of ``atan2`` of the long axis's horizontal part; no seed has it).
"""

from __future__ import annotations

import numpy as np

#: decision W269: the long axis's rate is read only where it is at least this far (deg) from the vertical; nearer,
#: its azimuth is undefined (the rate 0 there). W222's lying is 60 deg or more, so this only guards the edges
MIN_AXIS_TILT_DEG = 30.0


def long_axis_yaw_rate(up_body: np.ndarray, gyr_body: np.ndarray, long_axis: np.ndarray) -> np.ndarray:
    """Per sample: the rate (rad/s) of the azimuth about gravity of ``long_axis`` (a unit vector in the body frame,
    W102's walking upright) for the AHRS's up direction ``up_body`` (n, 3) and body rate ``gyr_body`` (n, 3); 0 where
    the axis is within :data:`MIN_AXIS_TILT_DEG` of the vertical (module docstring)."""
    z = np.asarray(up_body, dtype=np.float64)
    z = z / np.linalg.norm(z, axis=1, keepdims=True)
    u = np.asarray(long_axis, dtype=np.float64)
    u = u / np.linalg.norm(u)
    w = np.asarray(gyr_body, dtype=np.float64)
    uz = z @ u
    horiz = 1.0 - uz ** 2
    ok = horiz >= np.sin(np.radians(MIN_AXIS_TILT_DEG)) ** 2
    rate = (np.einsum("ij,ij->i", w, z) - uz * (w @ u)) / np.where(ok, horiz, 1.0)
    return np.where(ok, rate, 0.0)


def stop_pieces(t0: float, t1: float, spans) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Decision W269: a stop ``[t0, t1]`` cut by the lying episodes ``spans`` ((start, lying, rise, end) s each: the
    lying-down movement's start, the lying run's start and end, the getting-up movement's end): ``(upright, lying)``,
    the pieces outside every episode (the vertical rate counts there) and each episode's lying run inside the stop
    (the long axis's yaw counts there); the lying-down and getting-up movements count nothing."""
    upright: list[tuple[float, float]] = []
    lying: list[tuple[float, float]] = []
    at = t0
    for s, a, b, e in sorted(spans):
        if e <= t0 or s >= t1:
            continue
        if s > at:
            upright.append((at, s))
        lo, hi = max(a, t0), min(b, t1)
        if hi > lo:
            lying.append((lo, hi))
        at = max(at, e)
    if t1 > at:
        upright.append((at, t1))
    return upright, lying
