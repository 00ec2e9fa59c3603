"""Decisions E330 / E331 (session 51, I4): the streamed position radius's coverage on indoor missions and walks.

    python experiments/streamed_sigma_s51_e330.py 17870 17880 mission > e330_missions.txt
    python experiments/streamed_sigma_s51_e330.py 17880 17884 walk > e330_walks.txt

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


def runs(u: int, kind: str):
    sim = OUT / f"{kind}_u{u}"
    if not sim.exists():
        position_sigma.cli("simulate", "--route", mission(u) if kind == "mission" else WALK, "--user-seed", str(u),
                           "--seed", str(u), "--out", str(sim))
    for units in ("two", "foot"):
        out = OUT / f"{kind}_u{u}_{units}"
        if not out.exists():
            position_sigma.cli("run", str(BUNDLE), str(sim), "--out", str(out),
                               *(("--units", "foot") if units == "foot" else ()))
        yield units, sim, out


def row(sim: Path, out: Path) -> dict:
    tr, e = position_sigma.errors(sim, out)
    e = np.hypot(e[:, 0], e[:, 1])
    s = tr["pos_sigma_m"].to_numpy(float)
    ok = np.isfinite(s)
    rms = float(np.sqrt(np.mean(e[ok] ** 2)))
    return {"share": float(np.mean(e[ok] <= 2 * s[ok])), "sigma_rms": float(np.median(s[ok]) / rms), "rms": rms,
            "final": float(e[-1]), "final_sigma": float(s[-1]), "t_end": float(tr["t"].iloc[-1])}


if __name__ == "__main__":
    a, b, kind = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    pooled: dict[str, list] = {"two": [], "foot": []}
    for u in range(a, b):
        for units, sim, out in runs(u, kind):
            r = row(sim, out)
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
