"""Decisions L192 / L193: L145 / L180's barometer lines and the foot / waist tracks on simulated lift and escalator
routes (decision S45), against a standstill of the same length and a plain two-storey stairs route.

    .venv/bin/python experiments/sim_rides.py [--users 3330-3359]

Seed = user, 20 Hz, offline, no model; foot = ``track_plasys``, waist = ``track_waist(pipeline="waist-pendulum")``
(uncalibrated). Errors are against trajectory.csv between the track's first and last times (the ride included).
Prints one JSON line per user and route, then a summary per route.
"""

from __future__ import annotations

import argparse
import collections
import json
import warnings

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import barometer_warning, track_summary
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.waist import track_waist

ROUTES = {
    "lift_up": "straight:10, lift:+9, straight:10",
    "lift_updown": "straight:10, lift:+9, straight:10, lift:-9, straight:10",
    "esc_up": "straight:10, escalator:+6, straight:10",
    "esc_updown": "straight:10, escalator:+6, straight:5, turn:180, escalator:-6, straight:10",
    "stand_ctrl": "straight:10, stand:12, straight:10",
    "stairs": "straight:5, up:17, turn:180, up:17, straight:5, turn:180, down:17, turn:180, down:17, straight:5",
}


def one(user: int, name: str) -> dict:
    s = simulate_path(parse_route(ROUTES[name]), UserProfile.from_seed(user), seed=user, scenario="route")
    gt = s.trajectory
    row: dict = {"user": user, "route": name}
    for pipe in ("foot", "waist"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = track_plasys(s) if pipe == "foot" else track_waist(s, pipeline="waist-pendulum")
            m = track_summary(res, s, pipeline=None if pipe == "foot" else "waist-pendulum")
        tr = res.trajectory
        ta, tb = float(tr["t"].iloc[0]), float(tr["t"].iloc[-1])
        true = np.array([np.interp(tb, gt["t"], gt[c]) - np.interp(ta, gt["t"], gt[c]) for c in "xyz"])
        est = tr[["x", "y", "z"]].to_numpy(float)[-1] - tr[["x", "y", "z"]].to_numpy(float)[0]
        row[pipe] = {"horiz_err_m": round(float(np.hypot(*(est[:2] - true[:2]))), 3),
                     "alt_est_m": round(float(m["altitude_change_m"]), 3), "alt_true_m": round(float(true[2]), 3),
                     "dist_err_pct": round(float(m.get("distance_error_pct", np.nan)), 2),
                     "floors": [m.get("floors_up"), m.get("floors_down")]}
        if pipe == "foot":
            w = barometer_warning(m)
            row[pipe]["warn"] = None if w is None else ("climb" if "L180" in w else "net")
    return row


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="3330-3359")
    a, b = (int(v) for v in ap.parse_args().users.split("-"))
    by = collections.defaultdict(list)
    for u in range(a, b + 1):
        for name in ROUTES:
            row = one(u, name)
            print(json.dumps(row), flush=True)
            by[name].append(row)
    for name, rs in by.items():
        def stat(p: str, k: str, rs=rs) -> str:
            v = np.array([r[p][k] for r in rs], float)
            return f"median {np.median(v):.2f} [{v.min():.2f}, {v.max():.2f}]"

        def alt(p: str, rs=rs) -> str:
            v = np.array([abs(r[p]["alt_est_m"] - r[p]["alt_true_m"]) for r in rs])
            return f"median {np.median(v):.2f} max {v.max():.2f}"

        lines = dict(collections.Counter(str(r["foot"]["warn"]) for r in rs))
        print(f"{name} (n={len(rs)}): foot barometer lines {lines}")
        for p in ("foot", "waist"):
            floors = dict(collections.Counter(tuple(r[p]["floors"]) for r in rs))
            print(f"   {p}: horizontal error m {stat(p, 'horiz_err_m')}; |altitude error| m {alt(p)}; "
                  f"distance error % {stat(p, 'dist_err_pct')}; floors up/down {floors}")


if __name__ == "__main__":
    main()
