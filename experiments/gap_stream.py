"""Decision L99 (docs/decisions/localization.md): the streamed paths' turn over a foot-gyroscope gap bridged by the
waist gyroscope from the foot's rest before the gap to its rest after it (L91's mechanism) as their default, against
L90 (the turn over the gap taken as 0), on fresh simulated walks.

Users 200-219 (fresh), 20 Hz, normal speed, seed 3; L91's routes and gaps (experiments/gap_heading.py, shared):
"straight" (1 s gap at the middle of "straight:40"), "curve" (1 s gap at the middle of TURNING's first 90 deg
curve), "turn" (1 s gap at the middle of its 180 deg turn) and "turn2s" (a 2 s gap centred there). `pdrlearn track
--streaming` defaults without a model (heading auto = the waist gyroscope), final position error (m,
`evaluate_track`); arms: ``waist_bridge=False`` (L90) and ``waist_bridge=True`` (the candidate). Also checks that
each walk's clean copy (no gap) gives identical steps and trajectory in both arms.

Run: PYTHONPATH=. .venv/bin/python experiments/gap_stream.py [--users 200-219]
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from gap_heading import GAP_S, STRAIGHT, TURNING, _crossing, with_gap
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

ARMS = {"L90": False, "L99": True}  # waist_bridge of the streamed paths
#: set -> (route, truth heading turned (deg) at the gap's centre, None = the walk's middle; gap length s)
SETS = {"straight": (STRAIGHT, None, GAP_S), "curve": (TURNING, 45.0, GAP_S), "turn": (TURNING, 180.0, GAP_S),
        "turn2s": (TURNING, 180.0, 2.0)}


def run(session, arm: str):
    return track_plasys(session, streaming=True, waist_bridge=ARMS[arm])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", default="200-219")
    a = p.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    lo, _, hi = a.users.partition("-")
    res: dict[str, list] = {}
    clean = [0, 0]
    for u in range(int(lo), int(hi or lo) + 1):
        user = UserProfile.from_seed(u)
        for route in (STRAIGHT, TURNING):
            ses = simulate_path(parse_route(route), user, speed="normal", rate_hz=20.0, seed=3,
                                name=f"gapstream_u{u}", scenario="route")
            st = ses.steps
            for name, (r, deg, length) in SETS.items():
                if r != route:
                    continue
                mid = (0.5 * (float(st["start_s"].iloc[0]) + float(st["end_s"].iloc[-1])) if deg is None
                       else _crossing(ses, deg))
                gs = with_gap(ses, mid - 0.5 * length, length)
                errs = [evaluate_track(run(gs, arm), gs)["final_position_error_m"] for arm in ARMS]
                res.setdefault(name, []).append(errs)
                print(f"u{u} {name:8s} gap {mid - 0.5 * length:6.2f}-{mid + 0.5 * length:6.2f} s: "
                      + " / ".join(f"{arm} {e:6.2f}" for arm, e in zip(ARMS, errs, strict=True)), flush=True)
            r0, r1 = (run(ses, arm) for arm in ARMS)
            clean[0] += int(r0.steps.equals(r1.steps) and r0.trajectory.equals(r1.trajectory))
            clean[1] += 1
    print()
    print("| set | walks | mean final position error m (L90 / L99) | change % | worst walk increase m |")
    print("|---|---|---|---|---|")
    for name, rows in res.items():
        e = np.array(rows)
        m0, m1 = e.mean(axis=0)
        print(f"| {name} | {len(e)} | {m0:.2f} / {m1:.2f} | {100 * (m1 / m0 - 1):+.1f} | "
              f"{float((e[:, 1] - e[:, 0]).max()):+.2f} |")
    print(f"\nclean copies (no gap) identical in both arms: {clean[0]} of {clean[1]}")


if __name__ == "__main__":
    main()
