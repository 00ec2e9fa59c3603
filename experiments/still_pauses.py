"""Decisions L372 / L373 (session 33): is a still stretch between two rows standing (a pause), not a turn's time?
Pauses and walking time of foot and lower-back tracks with and without L372, measured once, no tuning. L373 adopted
L372; decision L594 removed its switch ``clinical.STILL_STANDING``: the "before" arm is :func:`before_l372` (the old
switch's off branch, ``still_before`` all 0), a stand-in for that arm only.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/still_pauses.py   # users 7172-7179
Output: experiments/results/still_pauses.txt (the printed lines).
"""
import logging
from contextlib import contextmanager
from unittest import mock

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import clinical
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.waist import track_waist

USERS = range(7172, 7180)
#: (route, true pauses: stands of 1 s or more between walking / turning, sit start / end) by user % 4
ROUTES = (("stand:3, turn:360, stand:3, turn:-360, stand:3", 1, 0.0),
          ("stand:3, straight:4, stand:3, turn:360, stand:4, turn:-360, stand:3", 2, 0.0),
          ("stand:3, straight:3, turn:180, straight:3, stand:3", 0, 5.0),  # L194's slow TUG: no pause
          ("stand:3, straight:6, stand:4, turn:180, straight:6, stand:3", 1, 0.0))


@contextmanager
def before_l372():
    """L119's turn time alone, as before L372: no row has a known still time (what ``STILL_STANDING = False`` did)."""
    with mock.patch.object(clinical, "still_before", lambda steps: np.zeros(len(steps))):
        yield


def main() -> None:
    err = {}
    for u in USERS:
        route, truth, sit = ROUTES[u % 4]
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed="slow", rate_hz=100.0, seed=u,
                          sit_start_s=sit, sit_end_s=sit)
        for name, track in (("foot", lambda s: track_plasys(s)),
                            ("waist", lambda s: track_waist(s, pipeline="waist-pendulum"))):
            res = track(s)
            line = []
            for on in (False, True):
                if on:
                    sm = evaluate_track(res, s)
                else:
                    with before_l372():
                        sm = evaluate_track(res, s)
                e = abs(sm["n_pauses"] - truth)
                err.setdefault((name, on), []).append(e)
                line.append(f"{'L372' if on else 'before'} pauses {sm['n_pauses']} bouts {sm['n_walking_bouts']} "
                            f"walking {sm['walking_time_s']:.2f} s")
            print(f"user {u} {name} [{route}] truth {truth} pauses: " + "; ".join(line), flush=True)
    for name in ("foot", "waist"):
        a, b = np.sum(err[(name, False)]), np.sum(err[(name, True)])
        print(f"{name}: summed |n_pauses - truth| before {a}, L372 {b}")


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    main()
