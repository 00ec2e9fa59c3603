"""Decision L247 (session 29): the foot track's distance and altitude on slow shuffling walks (0.2-0.5 m/s), measured
before L95's slow line changes what it says of the foot distance. Fresh users 4900-4919, route
``stand:3, straight:10, stand:3``, 100 Hz, the default foot track (``plasys``, no model), with the simulated force
sensors and without them (fForce removed). Nothing tuned.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/foot_slow.py [--users 4900-4919]
Output: the printed lines (experiments/results/foot_slow.txt)
"""
from __future__ import annotations

import argparse
import dataclasses
import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline

ROUTE = "stand:3, straight:10, stand:3"
#: (step length m, step time s): 0.2, 0.3, 0.4 (shuffle), 0.42 (v040) and 0.5 m/s
SLOW = ((0.15, 0.75), (0.2, 0.67), (0.2, 0.5), (0.25, 0.6), (0.25, 0.5))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="4900-4919")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    track = get_pipeline("plasys")
    errs: dict[str, list[float]] = {"force": [], "no force": []}
    alt: list[float] = []
    slow_line = 0
    n = 0
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        for sl, st in SLOW:
            s = simulate_path(parse_route(ROUTE), dataclasses.replace(user, step_length_m=sl, step_time_s=st),
                              speed="normal", rate_hz=100, seed=u, bounce="pendulum")
            for kind in ("force", "no force"):
                ss = s if kind == "force" else dataclasses.replace(
                    s, streams={k: v for k, v in s.streams.items() if not k.startswith("fForce")})
                r = track(ss)
                summ = r.summary(ss)
                e = float(summ["distance_error_pct"])
                errs[kind].append(e)
                line = any("slower than the walking" in w for w in summ["info"]["warnings"])
                if kind == "force":
                    n += 1
                    slow_line += line
                    alt.append(abs(float(summ.get("altitude_change_m") or 0.0)))
                print(f"user {u} {sl}/{st} ({sl / st:.2f} m/s) {kind}: distance error {e:+.2f} %, "
                      f"altitude change {summ.get('altitude_change_m')}, L95 slow line {line}", flush=True)
    print()
    for kind, v in errs.items():
        a = np.abs(v)
        print(f"{kind}: {len(v)} tracks, distance error {min(v):+.2f} to {max(v):+.2f} %, median |error| "
              f"{np.median(a):.2f} %, 95th percentile |error| {np.percentile(a, 95):.2f} %")
    print(f"|altitude change| on the flat route: max {max(alt):.2f} m; L95 slow line on {slow_line} of {n}")


if __name__ == "__main__":
    main()
