"""Steps decision 61 (session 35): the offline foot rest's L27 floor window, 1.0 s (before) against 2.0 s (the
candidate), by the rule written in docs/decisions/steps.md before this ran. Nothing tuned.

Simulated: fresh users 8450-8469, 100 Hz, the default foot track (``plasys``, no model, the simulated force files kept),
trial T3's stairs route up and down and a level route at a 1.2 s step (``--speed slow``), and the level and the up
route at the user's own normal step. Real: the gaitmap foot recordings in datasets/real and datasets/external.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/stance_window_61.py [--users 8450-8469]
Output: experiments/results/stance_window_61.txt
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

import numpy as np

import pdrlearn.displace.foot as foot
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.track.base import get_pipeline

UP = "stand:3, straight:2, up:12:0.17:0.29, straight:2, stand:3"
ROUTES = {"slow up": (UP, "slow", 1.2), "slow down": (UP.replace("up:", "down:"), "slow", 1.2),
          "slow level": ("stand:3, straight:20, stand:3", "slow", 1.2),
          "normal level": ("stand:3, straight:20, stand:3", "normal", None), "normal up": (UP, "normal", None)}
WINDOWS = (1.0, 2.0)


def _track(session, window: float) -> dict:
    foot.OFFLINE_FLOOR_WINDOW_S = window
    r = get_pipeline("plasys")(session)
    return r, r.summary(session)


def _contact_sd(session, steps) -> float:
    ic = session.steps["ic_s"].dropna().to_numpy(float)
    ev = steps["event_s"].to_numpy(float)
    err = np.array([e - ic[np.argmin(np.abs(ic - e))] for e in ev])
    return float(1000 * np.std(err[np.abs(err) < 0.25]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="8450-8469")
    ap.add_argument("--external", default="datasets/external")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    print("real feet (window 1.0 s | 2.0 s)")
    real = sorted(Path("datasets/real").glob("gaitmap_*")) + sorted(Path(args.external).glob("gaitmap_*"))
    for d in real:
        s = read_session(d)
        cells = []
        for w in WINDOWS:
            r, m = _track(s, w)
            cell = f"strides {m['n_steps']}"
            if m.get("step_f1") is not None and m.get("stride_length_mae_m") is not None and "ic_s" in s.steps:
                cell += (f", F1 {m['step_f1']:.3f}, stride MAE {m['stride_length_mae_m']:.4f} m, contact SD "
                         f"{_contact_sd(s, r.steps):.1f} ms, CV {m['stride_time_cv_pct']:.2f} %")
            cells.append(cell)
        print(f"  {d.name:28s} {' | '.join(cells)}", flush=True)
    lo, hi = (int(x) for x in args.users.split("-"))
    res = {(k, w): {"count": [], "alt": [], "dist": []} for k in ROUTES for w in WINDOWS}
    for u in range(lo, hi + 1):
        for name, (route, speed, step_s) in ROUTES.items():
            user = UserProfile.from_seed(u)
            if step_s is not None:
                user = dataclasses.replace(user, step_time_s=step_s / SPEED_FACTORS[speed][1])
            s = simulate_path(parse_route(route), user, speed=speed, rate_hz=100.0)
            true_n = len(s.steps)
            cells = []
            for w in WINDOWS:
                _, m = _track(s, w)
                c = int(m["n_steps"]) - true_n
                alt = float(m.get("altitude_change_m") or 0.0) - float(m.get("altitude_change_ref_m") or 0.0)
                dist = float(m["distance_error_pct"])
                res[(name, w)]["count"].append(c)
                res[(name, w)]["alt"].append(alt)
                res[(name, w)]["dist"].append(dist)
                cells.append(f"strides {c:+d}, altitude {alt:+.2f} m, distance {dist:+.1f} %")
            print(f"  user {u} {name:12s} {' | '.join(cells)}", flush=True)
    print("summary (window 1.0 s | 2.0 s)")
    for name in ROUTES:
        cells = []
        for w in WINDOWS:
            v = res[(name, w)]
            cells.append(f"median |stride error| {np.median(np.abs(v['count'])):.1f}, users with an error "
                         f"{int(np.sum(np.array(v['count']) != 0))}, median |altitude error| "
                         f"{np.median(np.abs(v['alt'])):.2f} m, median |distance error| "
                         f"{np.median(np.abs(v['dist'])):.1f} %")
        print(f"  {name:12s} {' | '.join(cells)}")


if __name__ == "__main__":
    main()
