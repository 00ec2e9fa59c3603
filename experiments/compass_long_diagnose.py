"""Diagnosis of the offline two-unit track on long looped multi-storey routes (session 28, decision L226; the
navigation trial's findings 4 and 9, L182's measurement). Per session against the simulator's truth (trajectory.csv
``heading_rad``, x, y, z): the per-stride heading error of the raw waist compass, of the foot's relative heading
(aligned at the first stride) and of the default fused heading; whether the compass error is place-dependent (the
same place walked in the same direction on later laps as on the first: correlation and median difference); and the
final position error of the fused track for L17's window ``fused_tau_s`` 60 s (default), 300 s and a constant
offset. A measurement; nothing is changed.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_long_diagnose.py SESSION_DIR [...]``
"""

from __future__ import annotations

import logging
import sys

import numpy as np
import pandas as pd
from scipy.spatial import cKDTree

from pdrlearn.io.plasys import read_session
from pdrlearn.orient.filters import WaistHeading
from pdrlearn.track.plasys import track_plasys


def wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def stride_mean(t, ang, s, e):
    lo, hi = np.searchsorted(t, s), np.searchsorted(t, e)
    c, sn = (np.concatenate([[0.0], np.cumsum(f(ang))]) for f in (np.cos, np.sin))
    return np.arctan2(sn[hi] - sn[lo], c[hi] - c[lo])


def diagnose(d: str) -> None:
    s = read_session(d)
    tr = pd.read_csv(f"{d}/trajectory.csv")
    tt = tr["timestamp"].to_numpy(float) / 1000
    fused = track_plasys(s)
    st = fused.steps
    S, E = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    M = 0.5 * (S + E)
    truth = np.interp(M, tt, np.unwrap(tr["heading_rad"].to_numpy(float)))
    xyz = np.column_stack([np.interp(M, tt, tr[k].to_numpy(float)) for k in "xyz"])
    wh = WaistHeading().fit_session(s)
    foot = track_plasys(s, heading="foot").steps["heading_rad"].to_numpy(float)
    err = {"compass": np.degrees(wrap(stride_mean(wh.t_, wh.compass_, S, E) - truth)),
           "foot": np.degrees(wrap(foot - truth - (foot[0] - truth[0]))),
           "fused": np.degrees(wrap(st["heading_rad"].to_numpy(float) - truth))}
    q = len(M) // 4
    print(f"{d}: {len(M)} strides, {M[-1] / 60:.1f} min")
    for k, e in err.items():
        quarters = " ".join(f"{np.median(e[i * q:(i + 1) * q]):+6.1f}" for i in range(4))
        p90 = np.percentile(np.abs(e), 90)
        print(f"  {k:8s} heading error median |e| {np.median(np.abs(e)):5.1f} deg, p90 {p90:5.1f}"
              f", median by quarter {quarters}")
    first = M < M[-1] / 4  # the first lap of R1 x4
    dist, j = cKDTree(xyz[first]).query(xyz[~first])
    same = (dist < 1.0) & (np.cos(truth[~first] - truth[first][j]) > 0.9)
    a, b = err["compass"][~first][same], err["compass"][first][j[same]]
    print(f"  compass error at the same place and direction as lap 1 ({int(same.sum())} strides): correlation "
          f"{np.corrcoef(a, b)[0, 1]:+.2f}, median |difference| {np.median(np.abs(a - b)):.1f} deg")
    fpe = [track_plasys(s, fused_tau_s=t).summary(s)["final_position_error_m"] for t in (60.0, 300.0, 1e6)]
    fpe_str = track_plasys(s, streaming=True).summary(s)["final_position_error_m"]
    print(f"  final error fused tau 60 s (default) {fpe[0]:.2f} m, 300 s {fpe[1]:.2f} m, constant offset "
          f"{fpe[2]:.2f} m; streamed (waist gyroscope) {fpe_str:.2f} m", flush=True)


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    for folder in sys.argv[1:]:
        diagnose(folder)
