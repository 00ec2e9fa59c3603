"""Decision L723's adoption rule (docs/decisions/localization.md): L712's ``rest_drift`` (the foot gyroscope's bias
interpolated in time between the stands over 30 s) against false (= main) on walks simulated at RATE Hz, where the
strides carry no rate-dependent yaw (L716), on fresh users 16020-16059.

``python experiments/foot_rest_drift_l723.py RATE [--no-checks]``: (a) / (b) / (f1) / (f2) on L712's long route,
(c) on its short walk at the same rate, (d) / (e) (the real gaitmap recordings, scenario D) unless ``--no-checks``.
"""

from __future__ import annotations

import sys

import numpy as np

from foot_rest_drift_l712 import heading_growth, measure, real_and_demo_checks

USERS = range(16020, 16060)
F2_MAX_M = 10.0  # L723 (f2): a session on the same fused path grows by at most this (m)


def fused_path(result) -> str:
    """Which of the fused heading's paths ran: L17's fusion, L226's waist-gyroscope fallback or D25's mount one."""
    if (result.info.get("compass_mount") or {}).get("fallback"):
        return "mount"
    return "fallback" if (result.info.get("compass_check") or {}).get("gyro_fallback") else "fusion"


def report(rate: float, users, extra: dict | None = None, checks: bool = True) -> np.ndarray:
    """L723's clauses at ``rate`` Hz on ``users``: every session's line, (a) / (b) / (c) / (f1) / (f2), the switched
    fused paths, and (d) / (e) when ``checks``; ``extra``: more foot settings with ``rest_drift`` on (L731). Returns
    :func:`measure`'s rows."""
    rows, paths = [], []
    for user in users:
        row, (fo, fn) = measure(user, rate, extra)
        rows.append(row)
        paths.append((fused_path(fo), fused_path(fn)))
        _, h0, h1, p0, p1, f0, f1, c = row
        print(f"u{user} {rate:g} Hz: foot heading final error {h0:+.2f} -> {h1:+.2f} deg, final position {p0:.2f} -> "
              f"{p1:.2f} m; fused final position {f0:.2f} -> {f1:.2f} m ({paths[-1][0]} -> {paths[-1][1]}); short "
              f"walk max stride change {c:.3g}", flush=True)
    r = np.array(rows)
    mh0, mh1, grow, worst = heading_growth(r)
    print(f"{rate:g} Hz (a) mean |final heading error| {mh0:.2f} -> {mh1:.2f} deg ({100 * (mh1 / mh0 - 1):+.1f} %); "
          f"mean signed {np.mean(r[:, 1]):+.2f} -> {np.mean(r[:, 2]):+.2f}; mean final position error "
          f"{np.mean(r[:, 3]):.2f} -> {np.mean(r[:, 4]):.2f} m; heading better on {int(np.sum(grow < 0))} of {len(r)}",
          flush=True)
    print(f"{rate:g} Hz (b) largest |final heading error| growth {grow[worst]:+.2f} deg (u{int(r[worst, 0])}); "
          f"sessions grown > 20 deg: {int(np.sum(grow > 20))}", flush=True)
    print(f"{rate:g} Hz (c) short walks: largest stride change {np.max(r[:, 7]):.3g}", flush=True)
    print(f"{rate:g} Hz (f1) fused mean final position error {np.mean(r[:, 5]):.3f} -> {np.mean(r[:, 6]):.3f} m "
          f"({100 * (np.mean(r[:, 6]) / np.mean(r[:, 5]) - 1):+.2f} %); worse on {int(np.sum(r[:, 6] > r[:, 5]))} of "
          f"{len(r)}", flush=True)
    same = np.array([a == b for a, b in paths])
    fg = r[:, 6] - r[:, 5]
    if same.any():
        k = int(np.flatnonzero(same)[np.argmax(fg[same])])
        print(f"{rate:g} Hz (f2) same fused path on {int(same.sum())} sessions: largest final position growth "
              f"{fg[k]:+.2f} m (u{int(r[k, 0])}); grown > {F2_MAX_M:g} m: {int(np.sum(fg[same] > F2_MAX_M))}",
              flush=True)
    for i in np.flatnonzero(~same):
        print(f"{rate:g} Hz (f) path switched u{int(r[i, 0])}: {paths[i][0]} -> {paths[i][1]}, final position "
              f"{r[i, 5]:.2f} -> {r[i, 6]:.2f} m ({fg[i]:+.2f})", flush=True)
    if checks:
        real_and_demo_checks(extra)
    return r


def main() -> None:
    report(float(sys.argv[1]), USERS, checks="--no-checks" not in sys.argv)


if __name__ == "__main__":
    sys.exit(main())
