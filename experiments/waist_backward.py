"""Decision W173: how often the backward-steps line fires. Fresh simulated users 3400-3429 on forward-only walks
(thesis scenarios A-D, W111's daily-activity route) must give none; backward routes (backward only, and forward /
backward / forward) must give one per backward stretch; the real lower-back recordings (mobgap, datasets/real and
datasets/external) none. Both waist pipelines; the simulated sessions also without their foot unit (the trunk cue
alone). Prints counts; decision W173 records them.

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_backward.py
"""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline

USERS = range(3400, 3430)
#: W111's daily-activity route (experiments/waist_pause_steps.py)
DAILY = ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, straight:4, "
         "turn:-135, straight:4, stand:3")
BACKWARD = {"backward": "stand:3, backward:10, stand:3", "mixed": "straight:10, backward:10, straight:6"}
PIPELINES = ("waist-pendulum", "waist-pll")
REAL = sorted({p.resolve(): p for p in [*Path("datasets/real").glob("mobgap_*"),
                                        *Path("datasets/external").glob("mobgap_*")]}.values())


def waist_only(session):
    """The session without its foot unit (streams and frame)."""
    return dataclasses.replace(session, streams={k: v for k, v in session.streams.items() if k.startswith("w")},
                               frames={k: v for k, v in session.frames.items() if k == "waist"})


def lines(session, pipeline: str) -> int:
    return sum("decision W173" in w for w in get_pipeline(pipeline)(session).info["warnings"])


def main() -> None:
    logging.disable(logging.WARNING)
    forward = {(p, u): [0, 0] for p in PIPELINES for u in ("both", "waist")}
    back = {(k, p, u): [0, 0] for k in BACKWARD for p in PIPELINES for u in ("both", "waist")}
    for user in USERS:
        sessions = [simulate(sc, user, rate_hz=20.0, seed=1) for sc in "ABCD"]
        sessions.append(simulate_path(parse_route(DAILY), UserProfile.from_seed(user), rate_hz=20.0, seed=1,
                                      scenario="route"))
        for s in sessions:
            for units, ss in (("both", s), ("waist", waist_only(s))):
                for p in PIPELINES:
                    c = forward[(p, units)]
                    c[0] += 1
                    c[1] += lines(ss, p) > 0
        for k, route in BACKWARD.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=1, scenario="route")
            for units, ss in (("both", s), ("waist", waist_only(s))):
                for p in PIPELINES:
                    c = back[(k, p, units)]
                    c[0] += 1
                    c[1] += lines(ss, p) == 1
    for (p, units), (n, w) in forward.items():
        print(f"forward-only (A-D, daily), users {USERS.start}-{USERS.stop - 1}, {p}, units {units}: {w} of {n} "
              "tracks warn")
    for (k, p, units), (n, w) in back.items():
        print(f"{k} route, users {USERS.start}-{USERS.stop - 1}, {p}, units {units}: {w} of {n} tracks give one line")
    for d in REAL:
        s = read_session(d)
        print(f"{d}: " + ", ".join(f"{p} {lines(s, p)} line(s)" for p in PIPELINES))


if __name__ == "__main__":
    main()
