"""Decision L141's measurement of L132's candidate (``stride_upsample`` 5) under L132's adoption rule.

Per user (``--work``/u<user>, made beforehand: ``calib/{terrain,direction,length}`` simulated with ``--user-seed``,
``model`` = ``pdrlearn train calib``, ``bundle`` = ``pdrlearn export model``, ``stairs`` = L132's route with its
up-and-down part twice, ``level`` = ``stand:10, straight:30, turn:180, straight:30, stand:10``, ``--seed`` = user):

* ``track`` (offline) and ``run`` with the exported bundle (the stride kernel at 20 Hz, its own L41 gain) and with a
  bundle re-exported with ``stride_upsample`` 5 and the streamed gain recalibrated with that kernel
  (:func:`pdrlearn.displace.calibration.calibrate_streaming` on the user's calibration sessions);
* the per-stride height ratio of each track's steps.csv (``dz_m`` / the true change of the simulator's
  ``foot_trajectory.csv`` z between the stride's start and end) over the strides whose true change is over 0.1 m
  up / down, pooled over the users (median); the level walk's streamed distance (summary) with each kernel;
* ``--truth`` (decision L152's rule): no offline ``track``; each level walk's ``run`` lengths against the truth (the
  simulator's foot displacement over each tracked stride), pooled and per walk, and the stairs against the truth;
* rule (e): ``track --streaming`` (M2) of the real gaitmap stair recordings with ``stride_upsample`` 1 and 5:
  the strides' heights must be equal bit for bit (204.8 Hz), hence the floor counts.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/stream_stair_fine.py --users 680-699 --work /tmp/s23st
    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/stream_stair_fine.py --users 1400-1415 --work W --truth
"""

from __future__ import annotations

import argparse
import json
import logging
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.displace.calibration import calibrate_streaming
from pdrlearn.export.from_model import export_model
from pdrlearn.io.plasys import read_session
from pdrlearn.kernels.stride import STRIDE_UPSAMPLE_KEY, STRIDE_UPSAMPLE_OPTION
from pdrlearn.track.evaluate import count_floors_by_climb
from pdrlearn.track.plasys import track_plasys

REAL = ("gaitmap_stairs_up_left", "gaitmap_stairs_up_right", "gaitmap_stairs_down_left", "gaitmap_stairs_down_right")


def cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True)


def stride_ratios(session: Path, out: Path) -> tuple[np.ndarray, np.ndarray]:
    """(ratios of the up strides, of the down strides): steps.csv dz_m / the true z change over the stride."""
    ft = pd.read_csv(session / "foot_trajectory.csv")
    tt, z = ft["t_ms"].to_numpy(float) / 1000.0, ft["z"].to_numpy(float)
    st = pd.read_csv(out / "steps.csv")
    truth = np.interp(st["end_s"].to_numpy(float), tt, z) - np.interp(st["start_s"].to_numpy(float), tt, z)
    dz = st["dz_m"].to_numpy(float)
    up, down = truth > 0.1, truth < -0.1
    return dz[up] / truth[up], dz[down] / truth[down]


def distance(out: Path) -> float:
    return float(json.loads((out / "summary.json").read_text())["distance_m"])


def level_lengths(session: Path, out: Path) -> tuple[float, float]:
    """Decision L152: (sum of steps.csv ``length_m``, sum of the true stride lengths: the horizontal displacement of
    the simulator's ``foot_trajectory.csv`` between each tracked stride's start and end)."""
    ft = pd.read_csv(session / "foot_trajectory.csv")
    tt = ft["t_ms"].to_numpy(float) / 1000.0
    st = pd.read_csv(out / "steps.csv")
    a, b = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    dx, dy = (np.interp(b, tt, ft[c].to_numpy(float)) - np.interp(a, tt, ft[c].to_numpy(float)) for c in ("x", "y"))
    return float(st["length_m"].sum()), float(np.hypot(dx, dy).sum())


def l152_checks(pooled: dict, walks: list[tuple[tuple[float, float], tuple[float, float]]]) -> None:
    """Decision L152's rule (a)-(c), printed: ``walks`` = per level walk ((run1 length, truth), (run5 length,
    truth)); ``pooled`` = the per-stride height ratios."""
    d1, d5 = sum(w[0][0] for w in walks), sum(w[1][0] for w in walks)
    e1 = np.array([100 * (w[0][0] / w[0][1] - 1) for w in walks])
    e5 = np.array([100 * (w[1][0] / w[1][1] - 1) for w in walks])
    worse = np.abs(e5) - np.abs(e1)
    change = 100 * (d5 / d1 - 1)
    print(f"L152 (a) pooled level distance change {change:+.3f} % (|.| < 0.1: {abs(change) < 0.1}); pooled error vs "
          f"truth run1 {100 * (d1 / sum(w[0][1] for w in walks) - 1):+.3f} %, run5 "
          f"{100 * (d5 / sum(w[1][1] for w in walks) - 1):+.3f} %")
    print(f"L152 (b) per-walk error vs truth, |e5| - |e1| points: max {worse.max():+.3f}, min {worse.min():+.3f}, "
          f"mean {worse.mean():+.3f} (all <= 0.3: {bool((worse <= 0.3).all())}); mean |e1| {np.abs(e1).mean():.3f}, "
          f"mean |e5| {np.abs(e5).mean():.3f}")
    med = [float(np.median(np.concatenate(v))) for v in pooled["run5"]]
    print(f"L152 (c) run5 pooled median height ratio up {med[0]:.4f} down {med[1]:.4f} "
          f"(within 1 % of 1: {all(abs(m - 1) <= 0.01 for m in med)})")


def fine_bundle(w: Path) -> Path:
    """The user's bundle re-exported with ``stride_upsample`` 5 and the streamed gain of that kernel."""
    b5 = w / "bundle5"
    if (b5 / "manifest.json").exists():
        return b5
    sessions = [read_session(str(w / "calib" / sc)) for sc in ("terrain", "direction", "length")]
    rec = calibrate_streaming(sessions, params={STRIDE_UPSAMPLE_KEY: STRIDE_UPSAMPLE_OPTION})
    ok = rec.get("reason") is None
    print(f"  {w.name}: streamed gain with stride_upsample 5: {rec['gain']:.4f} ({rec['n_strides']} strides)",
          flush=True)
    export_model(w / "model", b5, displacement={
        STRIDE_UPSAMPLE_KEY: STRIDE_UPSAMPLE_OPTION, "streaming_distance_gain": float(rec["gain"]),
        "streaming_stride_sigma_rel": float(rec["stride_sd"]) if ok and rec.get("stride_sd") else None,
        "streaming_distance_calibration_reason": rec.get("reason")})
    return b5


def real_check(work: Path) -> None:
    """Rule (e), printed once per ``work`` folder (cached in ``work/real_check.txt``)."""
    cache = work / "real_check.txt"
    if cache.exists():
        print(cache.read_text(), end="", flush=True)
        return
    lines = []
    for name in REAL:
        d = next((p for p in (Path("datasets/real") / name, Path("datasets/external") / name) if p.exists()), None)
        if d is None:
            print(f"{name}: not found", flush=True)
            continue
        ses = read_session(str(d))
        dz = [track_plasys(ses, method="M2", streaming=True, params={STRIDE_UPSAMPLE_KEY: k},
                           distance_gain=1.0).steps["dz_m"].to_numpy(float) for k in (1, STRIDE_UPSAMPLE_OPTION)]
        same = len(dz[0]) == len(dz[1]) and bool((dz[0] == dz[1]).all())
        lines.append(f"{name}: {len(dz[0])} strides, dz bit for bit equal: {same}, floors (up, down) "
                     f"{count_floors_by_climb(dz[0])[:2]} / {count_floors_by_climb(dz[1])[:2]}")
        print(lines[-1], flush=True)
    cache.write_text("".join(f"{ln}\n" for ln in lines))


def main() -> None:
    logging.disable(logging.WARNING)
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="680-699")
    ap.add_argument("--work", type=Path, required=True)
    ap.add_argument("--truth", action="store_true", help="decision L152's rule: run1 / run5 against the simulated "
                    "truth (no offline track)")
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    pooled: dict[str, list] = {m: [[], []] for m in (("run1", "run5") if a.truth else ("track", "run1", "run5"))}
    level, walks = [], []
    for u in range(lo, hi + 1):
        w = a.work / f"u{u}"
        b5 = fine_bundle(w)
        for mode in pooled:
            for kind in ("stairs", "level"):
                out = w / f"{mode}_{kind}"
                if (out / "steps.csv").exists():
                    continue
                if mode == "track":
                    cli("track", str(w / kind), "--model", str(w / "model"), "--out", str(out))
                else:
                    cli("run", str(w / "bundle" if mode == "run1" else b5), str(w / kind), "--out", str(out))
            up, down = stride_ratios(w / "stairs", w / f"{mode}_stairs")
            pooled[mode][0].append(up)
            pooled[mode][1].append(down)
        d1, d5 = distance(w / "run1_level"), distance(w / "run5_level")
        level.append((d1, d5))
        walks.append(tuple(level_lengths(w / "level", w / f"{m}_level") for m in ("run1", "run5")))
        (l1, tr1), (l5, tr5) = walks[-1]
        print(f"u{u}: " + "; ".join(f"{m} up {np.median(pooled[m][0][-1]):.4f} down {np.median(pooled[m][1][-1]):.4f}"
                                    for m in pooled)
              + f"; level run distance {d1:.3f} -> {d5:.3f} m ({100 * (d5 / d1 - 1):+.3f} %); error vs truth "
              f"{100 * (l1 / tr1 - 1):+.3f} -> {100 * (l5 / tr5 - 1):+.3f} %", flush=True)
    med = {m: [float(np.median(np.concatenate(v))) for v in pooled[m]] for m in pooled}
    n = {m: [len(np.concatenate(v)) for v in pooled[m]] for m in pooled}
    for m in pooled:
        print(f"pooled {m}: up {med[m][0]:.4f} (n={n[m][0]}) down {med[m][1]:.4f} (n={n[m][1]})")
    for m in ("run1", "run5") if "track" in pooled else ():
        print(f"(a) {m} - track: up {med[m][0] - med['track'][0]:+.4f}, down {med[m][1] - med['track'][1]:+.4f}")
    ch = np.array([100 * (d5 / d1 - 1) for d1, d5 in level])
    print(f"(b) level walk distance change %: max |.| {np.abs(ch).max():.3f}, mean {ch.mean():+.3f}, "
          f"total {100 * (sum(d5 for _, d5 in level) / sum(d1 for d1, _ in level) - 1):+.3f}")
    if a.truth:
        l152_checks(pooled, walks)
    real_check(a.work)


if __name__ == "__main__":
    main()
