"""Decision L379 (session 33, trial T4 finding 1): a 30 s rest right before a cone turn (``curve:180:0.5``) against
the same rest mid-corridor, and cone laps without a rest, on the foot and both lower-back pipelines; pause_time_s
with L119's turn time alone and with L372's still time (the rule since L373; decision L594 removed its switch
``clinical.STILL_STANDING``: the L119 arm is :func:`experiments.still_pauses.before_l372`). A check, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/rest_at_cone.py   # users 7270-7279
Output: experiments/results/rest_at_cone.txt (the printed lines).
"""
import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import clinical
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.waist import track_waist
from still_pauses import before_l372

logging.disable(logging.WARNING)

USERS = range(7270, 7280)
REST_S = 30.0
ROUTES = {"cone": "stand:3, straight:15, stand:30, curve:180:0.5, straight:15, stand:3",
          "mid": "stand:3, straight:15, stand:30, straight:15, stand:3",
          "laps": "stand:3, straight:15, curve:180:0.5, straight:15, turn:180, straight:15, curve:180:0.5, "
                  "straight:15, turn:180, straight:15, curve:180:0.5, straight:15, stand:3"}
TRACKS = {"plasys": track_plasys, "waist-pendulum": lambda s: track_waist(s, pipeline="waist-pendulum"),
          "waist-pll": lambda s: track_waist(s, pipeline="waist-pll")}
RULES = {"L119": False, "L372": True}


def summary(steps, still: bool) -> dict:
    if still:
        return clinical.clinical_summary(steps)
    with before_l372():
        return clinical.clinical_summary(steps)


def main() -> None:
    got = {(n, r, k): [] for n in TRACKS for r in ROUTES for k in RULES}
    for u in USERS:
        sessions = {r: simulate_path(parse_route(route), UserProfile.from_seed(u), rate_hz=20.0, seed=u,
                                     bounce="pendulum") for r, route in ROUTES.items()}
        for n, track in TRACKS.items():
            line = []
            for r, s in sessions.items():
                steps = track(s).steps
                for k, still in RULES.items():
                    c = summary(steps, still)
                    got[(n, r, k)].append((c["n_pauses"], c["pause_time_s"]))
                    line.append(f"{r} [{k}] {c['n_pauses']} / {c['pause_time_s']:.2f} s")
            print(f"user {u} {n}: " + "; ".join(line), flush=True)
    print()
    for n in TRACKS:
        for k in RULES:
            cone = np.array([p for _, p in got[(n, "cone", k)]])
            mid = np.array([p for _, p in got[(n, "mid", k)]])
            laps = [c for c, _ in got[(n, "laps", k)]]
            print(f"{n} [{k}]: cone rest median |pause_time_s - {REST_S:.0f}| {np.median(np.abs(cone - REST_S)):.2f} s "
                  f"({cone.min():.2f}-{cone.max():.2f}); mid-corridor median |error| "
                  f"{np.median(np.abs(mid - REST_S)):.2f} s; laps without a rest: pauses {laps}")


if __name__ == "__main__":
    main()
