"""Decision W173: how often the backward-steps line fires. Fresh simulated users 3400-3429 on forward-only walks
(thesis scenarios A-D, W111's daily-activity route) must give none; backward routes (backward only, and forward /
backward / forward) must give one per backward stretch; the real lower-back recordings (mobgap, datasets/real and
datasets/external) none. Both waist pipelines; the simulated sessions also without their foot unit. Prints counts;
decision W173 records them. ``--seed N``: the walks' seed (default 1).
``--w174``: decision W174's check, the same users' seated-start / seated-end routes (the trial's TUG, the
daily-activity route) and stair routes (scenario D, one storey up), waist-pendulum with defaults: the summary's
altitude_change_m and ascent_m, and the same without W174 (its transfer_dz_m put back into z).

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_backward.py [--seed N | --w174]
"""

from __future__ import annotations

import dataclasses
import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track

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


def main(seed: int = 1) -> None:
    logging.disable(logging.WARNING)
    forward = {(p, u): [0, 0] for p in PIPELINES for u in ("both", "waist")}
    back = {(k, p, u): [0, 0] for k in BACKWARD for p in PIPELINES for u in ("both", "waist")}
    for user in USERS:
        sessions = [simulate(sc, user, rate_hz=20.0, seed=seed) for sc in "ABCD"]
        sessions.append(simulate_path(parse_route(DAILY), UserProfile.from_seed(user), rate_hz=20.0, seed=seed,
                                      scenario="route"))
        for s in sessions:
            for units, ss in (("both", s), ("waist", waist_only(s))):
                for p in PIPELINES:
                    c = forward[(p, units)]
                    c[0] += 1
                    c[1] += lines(ss, p) > 0
        for k, route in BACKWARD.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=seed,
                              scenario="route")
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


TUG = "straight:3, turn:180, straight:3"
STAIRS = "straight:5, up:17, straight:5"


def _altitudes(res) -> tuple[float, float, float, float]:
    """(altitude_change_m, ascent_m) of the track, and of the same track with W174's transfer_dz_m put back."""
    now = evaluate_track(res)
    tr = res.trajectory.copy()
    tr["z"] = tr["z"].to_numpy(float) + np.concatenate([[0.0], np.cumsum(res.steps["transfer_dz_m"].to_numpy(float))])
    off = evaluate_track(TrackResult(steps=res.steps, trajectory=tr, info=res.info))
    return now["altitude_change_m"], now["ascent_m"], off["altitude_change_m"], off["ascent_m"]


def w174() -> None:
    """Decision W174's check (printed; the criteria are in the decision text)."""
    logging.disable(logging.WARNING)
    seated = {"tug": (TUG, "slow"), "daily": (DAILY, "normal")}
    rows = {k: [] for k in ("tug", "daily", "D", "storey")}
    for user in USERS:
        prof = UserProfile.from_seed(user)
        for k, (route, speed) in seated.items():
            s = simulate_path(parse_route(route), prof, speed=speed, rate_hz=20.0, seed=1, scenario="route",
                              sit_start_s=5.0, sit_end_s=5.0)
            rows[k].append(_altitudes(get_pipeline("waist-pendulum")(s)))
        rows["D"].append(_altitudes(get_pipeline("waist-pendulum")(simulate("D", user, rate_hz=20.0, seed=1))))
        s = simulate_path(parse_route(STAIRS), prof, rate_hz=20.0, seed=1, scenario="route")
        rows["storey"].append(_altitudes(get_pipeline("waist-pendulum")(s)))
    for k, r in rows.items():
        a = np.array(r)
        print(f"{k}, users {USERS.start}-{USERS.stop - 1}: max |altitude_change_m| {np.abs(a[:, 0]).max():.3f} "
              f"(without W174 {np.abs(a[:, 2]).max():.3f}), max ascent_m {a[:, 1].max():.3f} (without "
              f"{a[:, 3].max():.3f}); median altitude_change_m {np.median(a[:, 0]):.3f} (without "
              f"{np.median(a[:, 2]):.3f}), median ascent_m {np.median(a[:, 1]):.3f} (without "
              f"{np.median(a[:, 3]):.3f}); "
              f"max |change - without| {np.abs(a[:, 0] - a[:, 2]).max():.3f}, max |ascent - without| "
              f"{np.abs(a[:, 1] - a[:, 3]).max():.3f}")


if __name__ == "__main__":
    if "--w174" in sys.argv[1:]:
        w174()
    else:  # --seed N: the walks' seed (1 by default; W173's check after its revision also ran seed 2)
        main(int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 1)
