"""Waist contacts during simulated sit-to-stand transfers (decision S36's `sit:S`), per transfer, for the default
lower-back detectors `waist-pendulum` and `waist-pll` (session 22, issue 4: sit-to-stand counted as steps).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_sit.py count   # users 620-639
Output: experiments/results/waist_sit_count.txt
"""
import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist

logging.disable(logging.WARNING)

SIT_ROUTE = "straight:10, sit:20, straight:10, sit:15, straight:10"
PIPELINES = ("waist-pendulum", "waist-pll")


def in_transfers(events: np.ndarray, transfers) -> np.ndarray:
    """Number of ``events`` (s) inside each transfer [start_s, end_s]."""
    return np.array([int(((events >= a) & (events <= b)).sum())
                     for a, b in zip(transfers.start_s, transfers.end_s, strict=True)])


def true_matched(events: np.ndarray, truth: np.ndarray, tol_s: float = 0.25) -> int:
    """True contacts with a detected contact within ``tol_s`` (a loose count, not a one-to-one match)."""
    return int(sum(np.abs(events - t).min() <= tol_s for t in truth)) if events.size else 0


def count(users: range, **track_kw) -> None:
    per = {p: [] for p in PIPELINES}
    for u in users:
        s = simulate_path(parse_route(SIT_ROUTE), UserProfile.from_seed(u), rate_hz=100, seed=u)
        tr = s.extras["transfers"]
        truth = s.extras["ics"]["ic_s"].to_numpy(float)
        line = []
        for p in PIPELINES:
            res = track_waist(s, pipeline=p, **track_kw)
            ev = res.steps["event_s"].to_numpy(float)
            k = in_transfers(ev, tr)
            per[p].extend(k.tolist())
            line.append(f"{p}: {len(ev)} contacts, {true_matched(ev, truth)}/{truth.size} true matched, "
                        f"in transfers {k.tolist()}")
        print(f"user {u}: " + "; ".join(line), flush=True)
    for p in PIPELINES:
        k = np.array(per[p])
        print(f"{p}: {k.sum()} false contacts in {k.size} transfers (mean {k.mean():.2f}, max {k.max()}, "
              f"transfers with any {int((k > 0).sum())})")


if sys.argv[1:] == ["count"]:
    count(range(620, 640))
