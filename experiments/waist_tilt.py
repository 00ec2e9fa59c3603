"""Decision W102's measurement: the trunk-tilt gate (`max_tilt_deg`) on the real lower-back recordings and fresh
simulated users, with and without the gate (docs/decisions/waist.md W102 gives the adoption rule).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_tilt.py real   # (a), (b)
     OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_tilt.py sim    # (c), users 540-559
"""
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.evaluate import waist_metrics
from pdrlearn.waist.posture import MAX_TILT_DEG

logging.disable(logging.WARNING)



def outside(steps, folder):
    """Detected contacts outside every reference walking bout (bouts.csv level wb, [start, end])."""
    b = pd.read_csv(folder / "bouts.csv")
    b = b[b["level"] == "wb"]
    e = steps["event_s"].to_numpy(float)
    inside = np.zeros(e.size, bool)
    for s0, s1 in zip(b.start_ms / 1000, b.end_ms / 1000, strict=True):
        inside |= (e >= s0) & (e <= s1)
    return int((~inside).sum())



def main() -> None:
    if sys.argv[1:] == ["real"]:
        dirs = sorted(Path("datasets/external").glob("mobgap_*")) + sorted(Path("/work/shared/data").glob("mobgap_*"))
        tot = {None: 0, MAX_TILT_DEG: 0}
        for d in dirs:
            s = read_session(d)
            if not (d / "bouts.csv").exists() or not (d / "ics.csv").exists():
                print(f"{d}: no reference (bouts.csv / ics.csv), skipped")
                continue
            r = {}
            for g in (None, MAX_TILT_DEG):
                res = track_waist(s, pipeline="waist-pendulum", max_tilt_deg=g)
                m = waist_metrics(res.steps, s)
                r[g] = (m["step_f1"], m.get("step_f1_all"), len(res.steps), outside(res.steps, d),
                        res.info["n_tilted_contacts"])
                tot[g] += r[g][3]
            a, b = r[None], r[MAX_TILT_DEG]
            print(f"{d}: F1 {a[0]:.4f} -> {b[0]:.4f} (diff {b[0]-a[0]:+.4f}); F1_all {a[1]:.4f} -> {b[1]:.4f}; "
                  f"contacts {a[2]} -> {b[2]} (tilted {b[4]}); outside bouts {a[3]} -> {b[3]}", flush=True)
        change = 100 * (tot[MAX_TILT_DEG] - tot[None]) / max(tot[None], 1)
        print(f"pooled outside bouts {tot[None]} -> {tot[MAX_TILT_DEG]} ({change:+.1f} %)")
    else:
        from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

        route = [Stand(3.0), Straight(14.0), Stand(3.0)]
        diff = 0
        for u in range(540, 560):
            user = UserProfile.from_seed(u)
            for sp in ("slow", "normal", "fast"):
                s = simulate_path(route, user, speed=sp, rate_hz=100, seed=u, bounce="constant")
                n0 = len(track_waist(s, pipeline="waist-pendulum").steps)
                r1 = track_waist(s, pipeline="waist-pendulum", max_tilt_deg=MAX_TILT_DEG)
                n1 = len(r1.steps)
                diff += n0 != n1
                print(f"user {u} {sp}: steps {n0} -> {n1} (tilted {r1.info['n_tilted_contacts']})", flush=True)
        print(f"sim walks with a changed step count: {diff} of 60")


if __name__ == "__main__":
    main()
