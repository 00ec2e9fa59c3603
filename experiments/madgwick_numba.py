"""A numba-compiled Madgwick kernel against the library's Python-float kernel (decision W67, decisions/waist.md).

For the 9 mobgap lower-back sessions (datasets/real + datasets/external) and 3 simulated waist sessions, every call
of the library's ``madgwick_imu`` (the W43 kernel on Python floats) made by ``waist_imu`` (offline AHRS),
``waist-ic`` offline and ``waist-ic`` streaming
(``delay_s=1.75``, whole and in 25-sample chunks: one kernel call per chunk) is answered by the candidate
:func:`madgwick_imu_numba` (the same statements compiled with ``numba.njit``, no fastmath) and, on the same
arguments, by the library kernel; the quaternions are compared bit for bit (``np.array_equal``, max |difference|).
numba is no dependency of pdrlearn (W67: measured, not adopted): run it in a venv that has it, e.g.

  python3.11 -m venv .venv-try && .venv-try/bin/pip install torch==2.13.0 && .venv-try/bin/pip install -e '.[dev]' numba
  PYTHONPATH=. .venv-try/bin/python experiments/madgwick_numba.py
"""

from __future__ import annotations

import functools
import math
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def madgwick_imu_numba(q0, gyr: np.ndarray, acc: np.ndarray, dt: float, *, gain: float) -> np.ndarray:
    """The candidate: :func:`pdrlearn.orient._kernels.madgwick_imu` with its loop compiled (W67, not adopted)."""
    qw, qx, qy, qz = (float(v) for v in q0)
    gyr = np.ascontiguousarray(gyr, dtype=float).reshape(-1, 3)
    acc = np.ascontiguousarray(acc, dtype=float).reshape(-1, 3)
    out = np.empty((len(gyr), 4))
    _loop()(qw, qx, qy, qz, gyr, acc, 0.5 * dt, float(gain), out)
    return out


@functools.cache
def _loop():
    from numba import njit  # not a dependency of pdrlearn: this script needs a venv with numba

    @njit(cache=False)  # the library candidate had cache=True; no fastmath
    def loop(qw, qx, qy, qz, gyr, acc, hd, gain, out):  # the W43 kernel's statements, one sample per row
        sqrt = math.sqrt
        for i in range(gyr.shape[0]):
            gx, gy, gz = gyr[i, 0], gyr[i, 1], gyr[i, 2]
            ax, ay, az = acc[i, 0], acc[i, 1], acc[i, 2]
            n = sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
            qw, qx, qy, qz = qw / n, qx / n, qy / n, qz / n
            if gx == 0.0 and gy == 0.0 and gz == 0.0:
                out[i, 0], out[i, 1], out[i, 2], out[i, 3] = qw, qx, qy, qz
                continue
            dw = -qx * gx - qy * gy - qz * gz  # Madgwick eq. 12
            dx = qw * gx + qy * gz - qz * gy
            dy = qw * gy - qx * gz + qz * gx
            dz = qw * gz + qx * gy - qy * gx
            na = sqrt(ax * ax + ay * ay + az * az)
            if na > 0.0:
                ax, ay, az = ax / na, ay / na, az / na
                n = sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
                w, x, y, z = qw / n, qx / n, qy / n, qz / n
                f0 = 2.0 * (x * z - w * y) - ax  # Madgwick eq. 25
                f1 = 2.0 * (w * x + y * z) - ay
                f2 = 2.0 * (0.5 - x * x - y * y) - az
                if f0 != 0.0 or f1 != 0.0 or f2 != 0.0:
                    g0 = -2.0 * y * f0 + 2.0 * x * f1  # Madgwick eq. 26/34
                    g1 = 2.0 * z * f0 + 2.0 * w * f1 - 4.0 * x * f2
                    g2 = -2.0 * w * f0 + 2.0 * z * f1 - 4.0 * y * f2
                    g3 = 2.0 * x * f0 + 2.0 * y * f1
                    ng = sqrt(g0 * g0 + g1 * g1 + g2 * g2 + g3 * g3)
                    if ng > 0.0:
                        b = 2.0 * gain / ng  # Madgwick eq. 33
                        dw -= b * g0
                        dx -= b * g1
                        dy -= b * g2
                        dz -= b * g3
            qw, qx, qy, qz = qw + hd * dw, qx + hd * dx, qy + hd * dy, qz + hd * dz  # Madgwick eq. 13
            n = sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
            qw, qx, qy, qz = qw / n, qx / n, qy / n, qz / n
            out[i, 0], out[i, 1], out[i, 2], out[i, 3] = qw, qx, qy, qz

    return loop


def sessions():
    from pdrlearn.io import read_session
    from pdrlearn.sim import simulate

    dirs = sorted({d.name: d for root in (ROOT / "datasets" / "real", ROOT / "datasets" / "external")
                   for d in root.glob("mobgap_*") if (d / "meta.json").exists()}.values())
    for d in dirs:
        yield d.name, read_session(d)
    for args, kw in [(("A", 0, "normal"), {"rate_hz": 100.0}), (("D", 3, "fast"), {"rate_hz": 100.0}),
                     (("walk", 7, "slow"), {"rate_hz": 20.0, "seed": 2})]:
        s = simulate(*args, **kw)
        yield f"{s.name} ({kw['rate_hz']:.0f} Hz)", s


def main() -> None:
    import pdrlearn.orient._kernels as K
    import pdrlearn.waist.ahrs as A
    from pdrlearn.steps.waist_ic import WaistICStepDetector

    python = K.madgwick_imu
    calls: list[tuple[int, bool, float]] = []

    def both(q0, gyr, acc, dt, *, gain):
        q = madgwick_imu_numba(q0, gyr, acc, dt, gain=gain)
        ref = python(q0, gyr, acc, dt, gain=gain)
        calls.append((len(q), np.array_equal(q, ref), float(np.max(np.abs(q - ref), initial=0.0))))
        return q

    K.madgwick_imu = A.madgwick_imu = both
    try:
        n_all = 0
        for name, s in sessions():
            calls.clear()
            A.waist_imu(s)
            WaistICStepDetector().detect(s)
            rt = WaistICStepDetector(delay_s=1.75)
            rt.detect(s)
            t, v, ctx = rt._inputs(s)  # the streaming detector fed 25-sample chunks: one kernel call per chunk
            online = rt.online(1.0 / np.median(np.diff(t)), **ctx)
            for i in range(0, len(t), 25):
                online.push(t[i:i + 25], v[i:i + 25])
            online.flush()
            n = sum(c[0] for c in calls)
            ok = all(c[1] for c in calls)
            n_all += not ok
            print(f"{name:44s} kernel calls {len(calls):4d}, samples {n:7d}: "
                  f"{'bit-identical' if ok else 'DIFFERENT'} (max |dq| {max(c[2] for c in calls):.3g})")
    finally:
        K.madgwick_imu = A.madgwick_imu = python
    print("all bit-identical" if n_all == 0 else f"{n_all} sessions DIFFER")
    # speed of the kernel alone on the longest real recording (CPU, min of 5)
    from pdrlearn.io import read_session
    from pdrlearn.waist.ahrs import body_data

    t, acc, gyr = body_data(read_session(ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"))
    for label, fn in [("python", python), ("numba", madgwick_imu_numba)]:
        best = math.inf
        for _ in range(5):
            c0 = time.process_time()
            fn([1.0, 0, 0, 0], gyr, acc, 0.01, gain=0.033)
            best = min(best, time.process_time() - c0)
        print(f"kernel alone, {label}: {best * 1e6 / len(t):.3f} us per sample (CPU, min of 5, {len(t)} samples)")


if __name__ == "__main__":
    main()
