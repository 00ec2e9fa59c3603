"""Decisions L368 / L369 (session 33, trial T3 findings F1 / F2): turns on the spot done from standing, one after the
other in opposite directions, in turns.csv of the foot and the lower back. Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/turns_in_place.py   # users 7140-7159
     ... experiments/turns_in_place.py l370   # decision L370's rule: the same users, other sessions
     ... experiments/turns_in_place.py l371   # decisions L371 / W328: the same users, a third set of sessions
Output: experiments/results/turns_in_place.txt, turns_in_place_l370.txt, turns_in_place_l371.txt (printed lines).

Truth: L255's ``true_turns`` (the waist's true heading, 1 s mean, 5 % / 95 % of each route turn's angle). A truth
turn is found when the turns.csv row of largest |angle| overlapping it (not taken by an earlier truth turn) has its
sign and |angle error| < 90 deg; extra rows: the rows no truth turn took. Each track is made once and its turn table
computed with each candidate (``turn_table``'s ``reversal`` / ``first_own``), the lower back with its yaw-rate turns
as ``pdrlearn track`` does.
"""
import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.bouts import detected_bouts  # noqa: E402
from pdrlearn.track.clinical import turn_table  # noqa: E402
from pdrlearn.track.plasys import track_plasys  # noqa: E402
from pdrlearn.track.waist import track_waist  # noqa: E402
from turns_transfers import match_truth_rows, med, true_turns  # noqa: E402

logging.disable(logging.WARNING)

USERS = range(7140, 7160)
#: by user % 4: (route, speed): the trial's two turn-in-place routes, a TUG and two opposite corners
ROUTES = (("stand:3, turn:360, stand:3, turn:-360, stand:3", "normal"),
          ("stand:3, straight:4, stand:3, turn:360, stand:4, turn:-360, stand:3", "slow"),
          ("stand:2, straight:3, turn:180, straight:3, stand:2", "normal"),
          ("stand:2, straight:4, turn:90, straight:4, turn:-90, straight:4, stand:2", "normal"))
CONFIGS = {"today": {"reversal": False, "first_own": False}, "L368": {"reversal": True, "first_own": False},
           "L368+L369": {"reversal": True, "first_own": True}}
#: decision L370's sessions: each route's turns the other way, pendulum bounce
ROUTES370 = (("stand:3, turn:-360, stand:3, turn:360, stand:3", "normal"),
             ("stand:3, straight:4, stand:3, turn:-360, stand:4, turn:360, stand:3", "slow"),
             ("stand:2, straight:3, turn:-180, straight:3, stand:2", "normal"),
             ("stand:2, straight:4, turn:-90, straight:4, turn:90, straight:4, stand:2", "normal"))
CONFIGS370 = {"today": {"reversal": False, "first_own": False, "foot_split": False, "yaw_split": False},
              "L370+L369": {"reversal": False, "first_own": True, "foot_split": True, "yaw_split": True}}
#: decisions L371 / W328's tables (the third sessions: 20 Hz, constant bounce, :data:`ROUTES`)
CONFIGS371 = {"today": {"reversal": False, "first_own": False, "foot_split": False, "yaw_split": False,
                        "yaw_angle": False},
              "L371 / W328": {"reversal": False, "first_own": True, "foot_split": True, "yaw_split": True,
                              "yaw_angle": True}}
TRACKS = {"plasys": track_plasys, "waist-pendulum": lambda s: track_waist(s, pipeline="waist-pendulum"),
          "waist-pll": lambda s: track_waist(s, pipeline="waist-pll")}


def main(routes=ROUTES, configs=CONFIGS, knobs=None, rate_hz: float = 100.0) -> None:
    knobs = knobs or {}
    err = {(n, c): [] for n in TRACKS for c in configs}  # per truth turn: (route kind, route angle, found, errors)
    extra = {(n, c, k): 0 for n in TRACKS for c in configs for k in range(4)}
    for u in USERS:
        route, speed = routes[u % 4]
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed=speed, rate_hz=rate_hz, seed=u, **knobs)
        truth = true_turns(s, route)
        print(f"user {u} [{route}]: truth " + ", ".join(f"{a:.2f}-{b:.2f} s {g:+.1f} deg" for a, b, g in truth))
        for n, track in TRACKS.items():
            res = track(s)
            for c, kw in configs.items():
                tt = turn_table(res.steps, detected_bouts(res.steps), yaw_turns=res.info.get("yaw_turns"), **kw)
                got = []
                matched, n_extra = match_truth_rows(tt, truth)
                for (ta, tb, g), (r, ok) in zip(truth, matched, strict=True):
                    if r is None:
                        err[(n, c)].append((u % 4, round(g, -1), 0.0, np.nan, np.nan))
                        got.append("-")
                        continue
                    err[(n, c)].append((u % 4, round(g, -1), ok, r.angle_deg - g, r.duration_s - (tb - ta)))
                    got.append(f"{r.start_s:.2f}-{r.end_s:.2f} s {r.angle_deg:+.1f}")
                extra[(n, c, u % 4)] += n_extra
                print(f"  {n} [{c}]: {len(tt)} row(s), {n_extra} extra; " + "; ".join(got), flush=True)
    print("\nTURNS (found: sign and |angle error| < 90 deg; median |angle error| (signed) and duration error of "
          "the found)")
    for (n, c), e in err.items():
        a = np.array(e, float)
        ok = a[:, 2] == 1
        full = np.abs(a[:, 1]) >= 300
        reg = a[:, 0] >= 2
        print(f"{n} [{c}]: 360 deg turns found {int((ok & full).sum())}/{int(full.sum())} (duration error "
              f"{med(a[ok & full, 4])} s, |angle error| {med(np.abs(a[ok & full, 3]))} deg); TUG / corners found "
              f"{int((ok & reg).sum())}/{int(reg.sum())} (|angle error| {med(np.abs(a[ok & reg, 3]))} deg); extra "
              f"rows 360 routes {sum(extra[(n, c, k)] for k in (0, 1))}, TUG / corners "
              f"{sum(extra[(n, c, k)] for k in (2, 3))}")
    for n in TRACKS:  # the rule's "loses a turn found today"
        base = np.array(err[(n, "today")], float)[:, 2]
        for c in list(configs)[1:]:
            b = np.array(err[(n, c)], float)[:, 2]
            print(f"{n} [{c}] against today: turns lost {int(((base == 1) & (b == 0)).sum())}, gained "
                  f"{int(((base == 0) & (b == 1)).sum())}")


if __name__ == "__main__":
    if sys.argv[1:] == ["l370"]:
        main(ROUTES370, CONFIGS370, {"bounce": "pendulum"})
    elif sys.argv[1:] == ["l371"]:
        main(ROUTES, CONFIGS371, {"bounce": "constant"}, rate_hz=20.0)
    else:
        main()
