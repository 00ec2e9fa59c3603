"""Decision L379 (session 33, trial T4 finding 1): a 30 s rest right before a cone turn (``curve:180:0.5``) against
the same rest mid-corridor, and cone laps without a rest, on the foot track; pause_time_s with L119's assumed turn
time ("assumed") and L379's measured one ("measured"). Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/rest_at_cone.py   # users 7270-7279
Output: experiments/results/rest_at_cone.txt (the printed lines).
"""
import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import clinical
from pdrlearn.track.plasys import track_plasys

logging.disable(logging.WARNING)

USERS = range(7270, 7280)
REST_S = 30.0
ROUTES = {"cone": "stand:3, straight:15, stand:30, curve:180:0.5, straight:15, stand:3",
          "mid": "stand:3, straight:15, stand:30, straight:15, stand:3",
          "laps": "stand:3, straight:15, curve:180:0.5, straight:15, turn:180, straight:15, curve:180:0.5, "
                  "straight:15, turn:180, straight:15, curve:180:0.5, straight:15, stand:3"}


def summary(steps, mode: str) -> dict:
    old = clinical.PAUSE_TURN_TIME
    clinical.PAUSE_TURN_TIME = mode
    try:
        return clinical.clinical_summary(steps)
    finally:
        clinical.PAUSE_TURN_TIME = old


def main() -> None:
    got = {(r, m): [] for r in ROUTES for m in clinical.PAUSE_TURN_TIMES}
    for u in USERS:
        line = []
        for r, route in ROUTES.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(u), rate_hz=20.0, seed=u, bounce="pendulum")
            res = track_plasys(s)
            for m in clinical.PAUSE_TURN_TIMES:
                c = summary(res.steps, m)
                got[(r, m)].append((c["n_pauses"], c["pause_time_s"]))
                line.append(f"{r} [{m}] {c['n_pauses']} pause(s) {c['pause_time_s']:.2f} s")
        print(f"user {u}: " + "; ".join(line), flush=True)
    print()
    for m in clinical.PAUSE_TURN_TIMES:
        cone = np.array([p for _, p in got[("cone", m)]])
        mid = np.array([p for _, p in got[("mid", m)]])
        laps = [n for n, _ in got[("laps", m)]]
        print(f"[{m}] cone rest: median |pause_time_s - {REST_S:.0f}| {np.median(np.abs(cone - REST_S)):.2f} s "
              f"(min {cone.min():.2f}, max {cone.max():.2f}); mid-corridor median |error| "
              f"{np.median(np.abs(mid - REST_S)):.2f} s; laps without a rest: pauses {laps}")
    a = np.array([p for _, p in got[("mid", "assumed")]])
    b = np.array([p for _, p in got[("mid", "measured")]])
    print(f"mid-corridor: largest |measured - assumed| {np.max(np.abs(b - a)):.3f} s")


if __name__ == "__main__":
    main()
