"""Decisions W283 / W284 (session 32): does a lower-back track's "steps missed in turns" warning fire where its step
count is low? Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/turn_steps.py sim   # users 6590-6619
     ... experiments/turn_steps.py real  # the nine mobgap recordings (datasets/real, datasets/external)
Output: experiments/results/turn_steps_sim.txt, turn_steps_real.txt (the printed lines).

A session's count is "low" when the track's ``n_steps`` (steps.csv rows) is under the reference contacts (the
simulator's ics.csv; INDIP's contacts inside the track's first to last contact +- 1 s) by at least 2 and 10 %.
The warning is W283's :func:`pdrlearn.waist.turn_steps.turn_steps_warning`, called on the default track.
"""
import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.turn_steps import missed_turn_steps, turn_steps_warning

logging.disable(logging.WARNING)

USERS = range(6590, 6620)
#: (route, sit_start_s, sit_end_s) by user % 4; the last is the no-turn control
ROUTES = (("straight:3, turn:180, straight:3", 5.0, 5.0),
          ("straight:3, turn:180, straight:3, turn:180", 5.0, 5.0),
          ("stand:3, straight:8, pivot:180, straight:8, stand:3", 0.0, 0.0),
          ("stand:3, straight:10, stand:3", 0.0, 0.0))
REAL = [Path("datasets/real") / f"mobgap_HA001_{t}" for t in ("Test5_Trial1", "Test5_Trial2", "Test11_Trial1")]
REAL += [Path("datasets/external") / f"mobgap_{s}_{t}" for s in ("HA002", "MS001")
         for t in ("Test5_Trial1", "Test5_Trial2", "Test11_Trial1")]


def low(n: int, ref: int) -> bool:
    return ref - n >= 2 and ref - n >= 0.10 * ref


def judge(name: str, res, ref: int, control: bool = False) -> tuple[bool, bool, bool]:
    ev = res.steps["event_s"].to_numpy(float)
    n = len(res.steps)
    line = turn_steps_warning(ev, res.info["yaw_turns"], n)
    m = sum(t["missing"] for t in missed_turn_steps(ev, res.info["yaw_turns"]))
    is_low = low(n, ref)
    print(f"{name}: n_steps {n}, reference {ref} (shortfall {ref - n}), low {is_low}; estimated missing in turns "
          f"{m}; warned {line is not None}" + (" [control]" if control else ""), flush=True)
    return is_low, line is not None, control


def summarize(rows) -> None:
    a = np.array(rows, bool).reshape(-1, 3)
    low_, warn, ctrl = a[:, 0], a[:, 1], a[:, 2]
    tp = int((low_ & warn).sum())
    print(f"sessions {len(a)}: low {int(low_.sum())}, warned {int(warn.sum())}, warned and low {tp}; precision "
          f"{tp / warn.sum() if warn.any() else float('nan'):.3f}, recall "
          f"{tp / low_.sum() if low_.any() else float('nan'):.3f}; warned and not low {int((warn & ~low_).sum())}; "
          f"controls warned {int((warn & ctrl).sum())} of {int(ctrl.sum())}")


def sim() -> None:
    rows = []
    for u in USERS:
        route, s0, s1 = ROUTES[u % 4]
        speed = "slow" if (u // 4) % 2 else "normal"
        hz = 20.0 if (u // 8) % 2 == 0 else 100.0
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed=speed, rate_hz=hz, seed=u,
                          sit_start_s=s0, sit_end_s=s1)
        res = track_waist(s, pipeline="waist-pendulum")
        rows.append(judge(f"user {u} {speed} {hz:g} Hz [{route}]", res, len(s.extras["ics"]), u % 4 == 3))
    summarize(rows)


def real_tracks():
    """(folder, session, default waist-pendulum track) of each of the nine mobgap recordings (W284's; W332's too)."""
    for f in REAL:
        s = read_session(f)
        yield f, s, track_waist(s, pipeline="waist-pendulum")


def real() -> None:
    rows = []
    for f, s, res in real_tracks():
        ev = res.steps["event_s"].to_numpy(float)
        if "ics" not in s.extras:  # no INDIP contacts in this copy: not judged, the warning printed
            line = turn_steps_warning(ev, res.info["yaw_turns"], len(res.steps))
            print(f"{f.name}: n_steps {len(res.steps)}, no reference contacts (not judged); warned {line is not None}")
            continue
        ic = s.extras["ics"]["ic_s"].to_numpy(float)
        ref = int(((ic >= ev.min() - 1.0) & (ic <= ev.max() + 1.0)).sum()) if len(ev) else len(ic)
        rows.append(judge(f.name, res, ref))
    summarize(rows)


if __name__ == "__main__":
    {"sim": sim, "real": real}[sys.argv[1]]()
