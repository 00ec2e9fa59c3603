"""Decisions W331 / W332 (session 33): does a lower-back track's "turns on the spot hold no detected step" warning
fire exactly where a turn's steps were lost? Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/stepless_turns.py sim   # users 7160-7171
     ... experiments/stepless_turns.py real  # the nine mobgap recordings (W284's list)
Output: experiments/results/stepless_turns_sim.txt, stepless_turns_real.txt (the printed lines).

A flagged turn is "right" when its 5-95 % span holds at least 2 reference contacts (the simulator's ics.csv;
INDIP's contacts) - the track lost steps that were there. A session "lost a turn" when one of its turns of at least
80 deg holds at least 2 reference contacts and no track contact.
"""
import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.turn_steps import missed_turn_steps, stepless_turns
from turn_steps import real_tracks

logging.disable(logging.WARNING)

USERS = range(7160, 7172)
#: by user % 3: the trial's turns on the spot after a walk (T3 finding F3), a walking 180 deg turn, a plain walk
ROUTES = ("stand:3, straight:4, stand:3, turn:360, stand:4, turn:-360, stand:3",
          "stand:3, straight:6, turn:180, straight:6, stand:3",
          "stand:3, straight:10, stand:3")


def judge(name: str, res, ref_ic: np.ndarray, control: bool = False) -> tuple[int, int, int, bool]:
    """(flagged turns, flagged turns holding >= 2 reference contacts, lost turns, control) of one track."""
    ev = res.steps["event_s"].to_numpy(float)
    flagged = stepless_turns(ev, res.info["yaw_turns"])
    right = sum(int(((ref_ic >= t["start_s"]) & (ref_ic <= t["end_s"])).sum()) >= 2 for t in flagged)
    lost = sum(t["counted"] == 0 and int(((ref_ic >= t["start_s"]) & (ref_ic <= t["end_s"])).sum()) >= 2
               for t in missed_turn_steps(ev, res.info["yaw_turns"]))
    spans = "; ".join(f"{t['start_s']:.1f}-{t['end_s']:.1f} s: {round(t['expected'])} implied, "
                      f"{int(((ref_ic >= t['start_s']) & (ref_ic <= t['end_s'])).sum())} reference" for t in flagged)
    print(f"{name}: n_steps {len(ev)}, reference {len(ref_ic)}; flagged {len(flagged)} ({spans}), right {right}, "
          f"lost turns {lost}" + (" [control]" if control else ""), flush=True)
    return len(flagged), right, lost, control


def summarize(rows) -> None:
    a = np.array(rows, float).reshape(-1, 4)
    flagged, right, lost, ctrl = a[:, 0], a[:, 1], a[:, 2], a[:, 3] > 0
    print(f"sessions {len(a)}: flagged turns {int(flagged.sum())}, right {int(right.sum())}; lost turns "
          f"{int(lost.sum())}; recall {right.sum() / lost.sum() if lost.sum() else float('nan'):.3f}; "
          f"controls flagged {int((flagged[ctrl] > 0).sum())} of {int(ctrl.sum())}")


def sim() -> None:
    rows = []
    for u in USERS:
        route = ROUTES[u % 3]
        bounce = "pendulum" if u % 2 else "constant"
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed="slow", rate_hz=100.0, seed=u,
                          bounce=bounce)
        res = track_waist(s, pipeline="waist-pendulum")
        ic = s.extras["ics"]["ic_s"].to_numpy(float)
        rows.append(judge(f"user {u} {bounce} [{route}]", res, ic, u % 3 == 2))
    summarize(rows)


def real() -> None:
    rows = []
    for f, s, res in real_tracks():
        if "ics" not in s.extras:  # no INDIP contacts in this copy: printed, not judged
            n = len(stepless_turns(res.steps["event_s"].to_numpy(float), res.info["yaw_turns"]))
            print(f"{f.name}: no reference contacts (not judged); flagged {n}")
            continue
        rows.append(judge(f.name, res, s.extras["ics"]["ic_s"].to_numpy(float)))
    summarize(rows)


if __name__ == "__main__":
    {"sim": sim, "real": real}[sys.argv[1]]()
