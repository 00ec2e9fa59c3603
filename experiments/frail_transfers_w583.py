"""Decision W583's measurement: slow seated periods read as sit-and-rise pairs of W450's candidate C with no walk
needed (``chair_transfers_upright(slow_pairs=True)``) against today's, on fresh simulated users (trial s50 T3 finding
F4). Routes (20 Hz, 0.3 m steps in 0.8 s, pendulum bounce, walks seed 0): the trial's stand-pivot route shortened to
40 s sits (10 true transfers), a seated TUG, a walking-only route and W111's daily route (its sit:10), each at
``transfer_s`` 3:6 and the default 1.5:2.5; a row matches an overlapping true transfer of its kind
(frail_transfers_w450's matching). Prints found / true and false rows per route, transfer time and reading.

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/frail_transfers_w583.py FIRST LAST
    ... --real   (check (d), run from the repository root)
"""

from __future__ import annotations

import dataclasses
import functools
import sys

import pandas as pd

import frail_transfers_w450 as w450
import pdrlearn.track.waist as track_mod
import waist_backward
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.transfers import chair_transfers_upright

ROUTES = {"pivot": "sit:40, stand:3, sit:40, stand:3, sit:40, straight:3, sit:40, stand:3, sit:40",
          "tug": "sit:20, straight:3, turn:180, straight:3, sit:20",
          "walk": "stand:3, straight:10, turn:180, straight:10, stand:3",
          "daily": waist_backward.DAILY}


def rows_of(s, slow_pairs: bool) -> pd.DataFrame:
    """transfers.csv's rows of a waist-pendulum track with or without W583."""
    track_mod.chair_transfers_upright = functools.partial(chair_transfers_upright, slow_pairs=slow_pairs)
    return pd.DataFrame(track_mod.track_waist(s, pipeline="waist-pendulum").info["transfers"] or [])


def main(first: int, last: int) -> None:
    count: dict = {}
    for u in range(first, last + 1):
        p = UserProfile.from_seed(u)
        p = dataclasses.replace(p, step_length_m=0.3, step_time_s=0.8, class_step_length_m=p.step_length_m)
        for tx in ((3.0, 6.0), (1.5, 2.5)):
            for name, route in ROUTES.items():
                s = simulate_path(parse_route(route), p, seed=0, bounce="pendulum", transfer_s=tx, rate_hz=20.0)
                truth = w450.truth_of(s)
                for reading in (False, True):
                    f, x, _ = w450.match(truth, rows_of(s, reading))
                    c = count.setdefault((name, tx, reading), [0, 0, 0])
                    c[0], c[1], c[2] = c[0] + f, c[1] + len(truth), c[2] + x
        print(f"user {u} done", flush=True)
    for (name, tx, reading), (f, t, x) in count.items():
        print(f"{name:6s} transfer-time {tx[0]:g}:{tx[1]:g} {'W583' if reading else 'today':5s} users {first}-{last}: "
              f"found {f} of {t}, false {x}")


def real() -> None:
    """Check (d): the real lower-back recordings' transfers with and without W583."""
    from pathlib import Path

    from pdrlearn.io import read_session

    folders = sorted({p.resolve() for p in [*Path("datasets/external").glob("mobgap_*"),
                                            *Path("/work/shared/data").glob("mobgap_*")]})
    for f in folders:
        s = read_session(f)
        a, b = rows_of(s, False), rows_of(s, True)
        same = a.round(6).equals(b.round(6))
        print(f"{f.name}: today {len(a)} rows, W583 {len(b)} rows, {'unchanged' if same else 'CHANGED'}")


if __name__ == "__main__":
    if sys.argv[1] == "--real":
        real()
    else:
        main(int(sys.argv[1]), int(sys.argv[2]))
