"""Decisions E330 / E331 (session 51, I4): the streamed position radius's coverage on indoor missions and walks.

    python experiments/streamed_sigma_s51_e330.py 17870 17880 mission > e330_missions.txt
    python experiments/streamed_sigma_s51_e330.py 17880 17884 walk > e330_walks.txt
    python experiments/streamed_sigma_s51_e330.py 17870 17884 offset > e331_delta.txt    # E331's delta
    python experiments/streamed_sigma_s51_e330.py 17890 17904 mission two DELTA > e331_missions.txt
    python experiments/streamed_sigma_s51_e330.py 17904 17910 walk two DELTA > e331_walks.txt

Each user is simulated into $OUT (default /tmp/e330) and replayed with `pdrlearn run models/plasys-sim-default`,
with both units (``two``) and ``--units foot`` (``foot``). Per run: the share of trajectory.csv rows (after the
start) whose horizontal error against the simulator's trajectory.csv is within 2 ``pos_sigma_m`` (position_sigma's
``errors``), the median sigma over the RMS error, the RMS and the final error. Missions: E330's route with three
stops drawn from 30-180 s per user (numpy's generator seeded with the user id)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import position_sigma  # experiments/position_sigma.py: errors(), cli()

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
OUT = Path(os.environ.get("OUT", "/tmp/e330"))
WALK = "stand:5, straight:60, turn:90, straight:40, turn:-90, straight:30, stand:5"


def mission(u: int) -> str:
    """E330's mission route with user ``u``'s three stops (30-180 s)."""
    s1, s2, s3 = np.random.default_rng(u).integers(30, 181, 3)
    return (f"stand:10, straight:20, turn:90, straight:10, up:16, curve:180:0.8, up:16, turn:90, straight:15, "
            f"stand:{s1}, straight:12, turn:-90, down:16, curve:-180:0.8, down:16, straight:10, turn:-90, "
            f"straight:27.6, stand:{s2}, straight:15, turn:90, straight:20, turn:90, straight:10, stand:{s3}, "
            f"turn:180, straight:10, stand:10")


def runs(u: int, kind: str, sets=("two", "foot")):
    sim = OUT / f"{kind}_u{u}"
    if not sim.exists():
        position_sigma.cli("simulate", "--route", mission(u) if kind == "mission" else WALK, "--user-seed", str(u),
                           "--seed", str(u), "--out", str(sim))
    for units in sets:
        out = OUT / f"{kind}_u{u}_{units}"
        if not out.exists():
            position_sigma.cli("run", str(BUNDLE), str(sim), "--out", str(out),
                               *(("--units", "foot") if units == "foot" else ()))
        yield units, sim, out


def radius(out: Path, offset_rad: float | None) -> np.ndarray:
    """E331: trajectory.csv's pos_sigma_m recomputed from steps.csv as ``add_position_sigma`` does for `run`'s
    two-unit regime (E205's rests), with ``heading_offset_rad`` = ``offset_rad`` (None: the regime as it is)."""
    from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S
    from pdrlearn.track.position_sigma import sigma_params, sigma_per_row, streamed_rests

    steps, t = pd.read_csv(out / "steps.csv"), pd.read_csv(out / "trajectory.csv")["t"].to_numpy(float)
    params = sigma_params("plasys-streaming")
    if offset_rad is not None:
        params["heading_offset_rad"] = offset_rad
    return sigma_per_row(steps, t, params, REST_BIAS_MIN_S, streamed_rests(steps, REST_BIAS_MIN_S))


def first_offset(sim: Path, out: Path, reach_m: float = 15.0) -> float:
    """E331: the angle (rad) between the track's and the truth's displacement from the start at the first row whose
    true position is ``reach_m`` or more from the start."""

    tr, gt = pd.read_csv(out / "trajectory.csv"), pd.read_csv(sim / "trajectory.csv")
    t = tr["t"].to_numpy(float)
    true = np.stack([np.interp(t, gt["timestamp"].to_numpy(float) / 1000.0, gt[c].to_numpy(float)) for c in "xy"], 1)
    true, est = true - true[0], tr[["x", "y"]].to_numpy(float) - tr[["x", "y"]].to_numpy(float)[0]
    k = int(np.flatnonzero(np.hypot(true[:, 0], true[:, 1]) >= reach_m)[0])
    d = np.arctan2(est[k, 1], est[k, 0]) - np.arctan2(true[k, 1], true[k, 0])
    return float((d + np.pi) % (2 * np.pi) - np.pi)


def row(sim: Path, out: Path, sigma: np.ndarray | None = None) -> dict:
    tr, e = position_sigma.errors(sim, out)
    e = np.hypot(e[:, 0], e[:, 1])
    s = tr["pos_sigma_m"].to_numpy(float) if sigma is None else sigma[1:]
    ok = np.isfinite(s)
    rms = float(np.sqrt(np.mean(e[ok] ** 2)))
    return {"share": float(np.mean(e[ok] <= 2 * s[ok])), "sigma_rms": float(np.median(s[ok]) / rms), "rms": rms,
            "final": float(e[-1]), "final_sigma": float(s[-1]), "t_end": float(tr["t"].iloc[-1])}


def offsets(a: int, b: int) -> None:
    """E331's delta: the RMS of :func:`first_offset` over E330's two-unit runs of users a..b-1 (missions, walks)."""
    got = []
    for u in range(a, b):
        for kind in ("mission", "walk"):
            sim, out = OUT / f"{kind}_u{u}", OUT / f"{kind}_u{u}_two"
            if (out / "trajectory.csv").is_file():
                got.append(first_offset(sim, out))
                print(f"{kind}_u{u} two: first-leg heading offset {np.degrees(got[-1]):+.2f} deg", flush=True)
    print(f"{len(got)} runs: RMS offset {np.sqrt(np.mean(np.square(got))):.5f} rad "
          f"({np.degrees(np.sqrt(np.mean(np.square(got)))):.2f} deg)")


if __name__ == "__main__":
    a, b, kind = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    if kind == "offset":
        offsets(a, b)
        sys.exit(0)
    sets = tuple(sys.argv[4].split(",")) if len(sys.argv) > 4 else ("two", "foot")
    delta = float(sys.argv[5]) if len(sys.argv) > 5 else None  # E331: the candidate's heading_offset_rad
    pooled: dict[str, list] = {"two": [], "foot": [], "two old": []}
    for u in range(a, b):
        for units, sim, out in runs(u, kind, sets):
            if delta is not None:  # E331: the old radius recomputed (checked against the written one), then the new
                old = radius(out, None)
                written = pd.read_csv(out / "trajectory.csv")["pos_sigma_m"].to_numpy(float)
                assert np.allclose(old, written, rtol=1e-6, atol=1e-6, equal_nan=True), "recomputed != written"
                r = row(sim, out, old)
                pooled["two old"].append(r)
                print(f"{kind}_u{u} {units} old: within 2 sigma {r['share']:.3f}, median sigma / RMS "
                      f"{r['sigma_rms']:.2f}, final sigma {r['final_sigma']:.2f} m", flush=True)
            r = row(sim, out, None if delta is None else radius(out, delta))
            pooled[units].append(r)
            print(f"{kind}_u{u} {units}: within 2 sigma {r['share']:.3f}, median sigma / RMS {r['sigma_rms']:.2f}, "
                  f"RMS {r['rms']:.2f} m, final {r['final']:.2f} m at sigma {r['final_sigma']:.2f} m, "
                  f"{r['t_end']:.0f} s", flush=True)
    for units, rs in pooled.items():
        if rs:
            share = [r["share"] for r in rs]
            ratio, rms = np.median([r["sigma_rms"] for r in rs]), np.median([r["rms"] for r in rs])
            print(f"{kind} {units}: mean share {np.mean(share):.3f}, min {np.min(share):.3f}, median sigma / RMS "
                  f"{ratio:.2f}, median RMS {rms:.2f} m")
