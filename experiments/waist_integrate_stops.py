"""Decision W58: is ``integrate_stops=True`` (yaw turned while standing kept in the gyro heading) a better default
for the waist pipelines? Measures the three parts of W58's adoption rule (written before this ran):

1. simulated users 1-3, scenarios A-D (experiments/waist.py protocol), waist-pendulum offline and realtime;
2. the real Test11 recordings with turns.csv (mobgap HA001, HA002, MS001), uncalibrated waist-pendulum: L42 turn
   metrics;
3. the trial-12 fragility cases: final position change from a 7 ms gyroscope clock offset and from 100 -> 50 Hz
   (anti-aliased) resampling.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_integrate_stops.py [--external datasets/external] [--sim-users 3]
"""

from __future__ import annotations

import argparse
import json
import logging
import shutil
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]


def _sim(users: list[int]) -> pd.DataFrame:
    import waist as W

    rows = []
    for integ in (False, True):
        configs = [("waist-pendulum", "waist-pendulum", {"integrate_stops": integ}),
                   ("waist-pendulum realtime", "waist-pendulum", {"realtime": True, "integrate_stops": integ})]
        s = W.summarize_sim(W.simulated(users, configs))
        s.insert(1, "integrate_stops", integ)
        rows.append(s)
    return pd.concat(rows, ignore_index=True)


def _track(session_dir: Path, integ: bool) -> dict:
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import evaluate_track

    s = read_session(session_dir)
    res = get_pipeline("waist-pendulum")(s, integrate_stops=integ)
    ev = evaluate_track(res, s)
    tr = res.trajectory
    return {"steps": len(res.steps), "x": float(tr["x"].iloc[-1]), "y": float(tr["y"].iloc[-1]),
            "turn_mae": ev.get("turn_angle_mae_deg"), "turn_sign": ev.get("turn_sign_agreement"),
            "n_turns": ev.get("n_turns")}


def _variant(src: Path, dst: Path, kind: str) -> Path:
    """A copy of ``src`` with the gyroscope clock shifted 7 ms (``shift7``) or both waist files at 50 Hz (``50hz``)."""
    from scipy.signal import resample_poly

    shutil.copytree(src, dst)
    meta = json.loads((dst / "meta.json").read_text())
    for f in ("wAccelerometer.csv", "wGyroscope.csv", "wMagneticField.csv", "wBarometer.csv"):
        p = dst / f
        if not p.exists():
            continue
        t = pd.read_csv(p)
        if kind == "shift7" and f == "wGyroscope.csv":
            t["timestamp"] = t["timestamp"] + 7.0
        elif kind == "50hz":
            cols = [c for c in t.columns if c != "timestamp"]
            v = resample_poly(t[cols].to_numpy(float), 1, 2, axis=0, padtype="line")
            t = pd.DataFrame(v, columns=cols)
            t.insert(0, "timestamp", float(pd.read_csv(p)["timestamp"].iloc[0]) + 20.0 * np.arange(len(v)))
        t.to_csv(p, index=False)
    if kind == "50hz":
        meta["rate_hz"] = 50.0
        (dst / "meta.json").write_text(json.dumps(meta, indent=2))
    return dst


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets/external")
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    pd.set_option("display.width", 200)
    print("## 2. real Test11 turns (uncalibrated waist-pendulum)")
    rows = []
    for name in ("mobgap_HA001_Test11_Trial1", "mobgap_HA002_Test11_Trial1", "mobgap_MS001_Test11_Trial1"):
        for integ in (False, True):
            rows.append({"session": name, "integrate_stops": integ, **_track(args.external / name, integ)})
    real = pd.DataFrame(rows)
    print(real.to_string(index=False, float_format="%.3f"))
    print("## 3. fragility: final position change vs the original recording (m)")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test11_Trial1", "mobgap_MS001_Test11_Trial1"):
            for kind in ("shift7", "50hz"):
                d = _variant(args.external / name, Path(tmp) / f"{name}_{kind}", kind)
                for integ in (False, True):
                    a, b = _track(args.external / name, integ), _track(d, integ)
                    rows.append({"session": name, "case": kind, "integrate_stops": integ,
                                 "final_orig": f"({a['x']:.1f},{a['y']:.1f})",
                                 "final_variant": f"({b['x']:.1f},{b['y']:.1f})",
                                 "moved_m": float(np.hypot(a["x"] - b["x"], a["y"] - b["y"]))})
    frag = pd.DataFrame(rows)
    print(frag.to_string(index=False, float_format="%.2f"))
    if args.sim_users:
        print(f"## 1. simulated users 1..{args.sim_users}, scenarios A-D")
        print(_sim(list(range(1, args.sim_users + 1))).to_string(index=False, float_format="%.3f"))


if __name__ == "__main__":
    main()
