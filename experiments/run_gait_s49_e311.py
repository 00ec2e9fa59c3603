"""Decision E311 (session 49, I1): offline `gait` against `run --gait`'s streamed pair.

    python experiments/run_gait_s49_e311.py 16200 16220 > users.txt      # fresh simulated users 16200-16219
    python experiments/run_gait_s49_e311.py 0 0 real > real.txt           # the gaitmap level pair only (a check)

Sessions are simulated into $OUT (default /tmp/e311); the shipped bundle models/plasys-sim-default. Steps are
matched by side and IC (|dIC| <= 20 ms), cycles by side and start."""

import json
import logging
import os
import sys
from pathlib import Path

import numpy as np

from pdrlearn.cli import main
from pdrlearn.cli.run_gait import streamed_foot_track
from pdrlearn.runtime import load_bundle
from pdrlearn.track.bilateral import pair_sessions

REAL = Path("/work/shared/data")
TOL_S = 0.020


def _stride_length(w: dict) -> float:
    return float(np.nanmean([np.nan if w[k] is None else w[k] for k in ("stride_length_m_left",
                                                                          "stride_length_m_right")]))


def compare(tag: str, left: Path, right: Path, bundle, pool: dict) -> dict:
    off = pair_sessions(left, right)
    st = pair_sessions(left, right, streamed=True, track_foot=streamed_foot_track(bundle))
    a, b = off["steps"], st["steps"]
    n_match = 0
    for _, r in a.iterrows():
        same = b[(b["side"] == r["side"]) & ((b["ic_s"] - r["ic_s"]).abs() <= TOL_S)]
        if len(same):
            n_match += 1
            pool["dstep"].append(same.iloc[0]["step_time_s"] - r["step_time_s"])
            pool["dswing"].append(same.iloc[0]["swing_time_s"] - r["swing_time_s"])
    for _, r in off["cycles"].iterrows():
        cb = st["cycles"]
        same = cb[(cb["side"] == r["side"]) & ((cb["start_s"] - r["start_s"]).abs() <= TOL_S)]
        if len(same):
            pool["dstride"].append(same.iloc[0]["stride_time_s"] - r["stride_time_s"])
            pool["dstance"].append(same.iloc[0]["stance_time_s"] - r["stance_time_s"])
    pool["n_off"] += len(a)
    pool["n_match"] += n_match
    wa, wb = off["walk"], st["walk"]
    row = {"tag": tag, "steps_off": len(a), "steps_stream": len(b), "matched": n_match,
           "d_stride_length_pct": round(100 * (_stride_length(wb) - _stride_length(wa)) / _stride_length(wa), 3),
           "ds_off": wa["double_support_pct"], "ds_stream": wb["double_support_pct"],
           "cad_off": wa["cadence_spm"], "cad_stream": wb["cadence_spm"]}
    print(json.dumps(row), flush=True)
    return row


def _med_ms(x) -> float:
    return round(1000 * float(np.nanmedian(np.abs(x))), 3) if len(x) else float("nan")


def _max_ms(x) -> float:
    return round(1000 * float(np.nanmax(np.abs(x))), 3) if len(x) else float("nan")


def run(first: int, stop: int, real: bool) -> None:
    logging.disable(logging.WARNING)
    bundle = load_bundle(Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default")
    root = Path(os.environ.get("OUT", "/tmp/e311"))
    pool = {"n_off": 0, "n_match": 0, "dstep": [], "dswing": [], "dstride": [], "dstance": []}
    rows = []
    for u in range(first, stop):
        for f in ("left", "right"):
            d = root / f"u{u}_{f}"
            if not d.exists():
                assert main(["simulate", "--route", "stand:2, straight:20, stand:2", "--rate", "50", "--seed", "1",
                             "--foot", f, "--user-seed", str(u), "--out", str(d)]) == 0
        rows.append(compare(f"user {u}", root / f"u{u}_left", root / f"u{u}_right", bundle, pool))
    if real:
        rows.append(compare("gaitmap_level", REAL / "gaitmap_level_left", REAL / "gaitmap_level_right", bundle, pool))
    print("matched", pool["n_match"], "of", pool["n_off"], "offline steps,",
          round(100 * pool["n_match"] / max(pool["n_off"], 1), 2), "%")
    print("median |d step time| ms", _med_ms(pool["dstep"]), "max", _max_ms(pool["dstep"]))
    print("median |d swing time| ms", _med_ms(pool["dswing"]), "max", _max_ms(pool["dswing"]))
    print("median |d stride time| ms", _med_ms(pool["dstride"]))
    print("median |d stance time| ms", _med_ms(pool["dstance"]), "mean d",
          round(1000 * float(np.nanmean(pool["dstance"])), 3))
    sim = [r["d_stride_length_pct"] for r in rows if r["tag"].startswith("user")]
    if sim:
        print("median over users |d walk stride length| %", round(float(np.median(np.abs(sim))), 3),
              "max", round(float(np.max(np.abs(sim))), 3))
        ds = [r["ds_stream"] - r["ds_off"] for r in rows if r["tag"].startswith("user")]
        print("d double support (pp) median", round(float(np.median(ds)), 3), "min", round(min(ds), 3),
              "max", round(max(ds), 3))


if __name__ == "__main__":
    run(int(sys.argv[1]), int(sys.argv[2]), len(sys.argv) > 3)
