"""Decision W187 (session 28): the gyro heading integrated through the final stop (option ``integrate_end``), off and
on, uncalibrated waist-pendulum. Run once after W187's rule was committed; nothing tuned.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_final_turn.py sim   # users 3640-3679
     ... experiments/waist_final_turn.py real   # datasets/external and /work/shared/data mobgap_*
Output: experiments/results/waist_final_turn_sim.txt, waist_final_turn_real.txt (the printed lines)
"""
import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.sim import UserProfile, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.clinical import turn_table  # noqa: E402
from pdrlearn.track.waist import track_waist  # noqa: E402
from turns_transfers import true_turn  # noqa: E402  the truth's turn (the waist unit's true heading change)

logging.disable(logging.WARNING)

USERS = range(3640, 3680)
END_TURN = "straight:10, turn:180, stand:3"
PLAIN = "stand:3, straight:20, stand:3"


def tracks(session):
    return [track_waist(session, pipeline="waist-pendulum", integrate_end=on, sit_veto=False)
            for on in (False, True)]  # as measured, before W185


def final(res) -> tuple[float, float, float]:
    tr = res.trajectory
    return float(tr["x"].iloc[-1]), float(tr["y"].iloc[-1]), float(np.degrees(res.steps["heading_rad"].iloc[-1]))


def sim() -> None:
    found = {False: 0, True: 0}
    err = {False: [], True: []}
    for u in USERS:
        speed = "slow" if u % 2 else "normal"
        s = simulate_path(parse_route(END_TURN), UserProfile.from_seed(u), speed=speed, seed=u, rate_hz=100.0)
        ang = true_turn(s)[2]
        parts = []
        for on, res in zip((False, True), tracks(s), strict=True):
            tt = turn_table(res.steps)
            ok = len(tt) == 1 and abs(float(tt["angle_deg"].iloc[0]) - ang) <= 30.0
            found[on] += ok
            e = abs((final(res)[2] - ang + 180.0) % 360.0 - 180.0)
            err[on].append(e)
            parts.append(f"{'on' if on else 'off'}: {len(tt)} turn(s) "
                         f"{', '.join(f'{a:+.1f}' for a in tt['angle_deg'])} deg, final heading error {e:.1f} deg")
        print(f"end-turn user {u} {speed}: truth {ang:+.1f} deg; " + "; ".join(parts), flush=True)
    moved = same_turns = small = n = 0
    largest = 0.0
    for u in USERS:
        for speed in ("slow", "normal", "fast"):
            s = simulate_path(parse_route(PLAIN), UserProfile.from_seed(u), speed=speed, seed=u, rate_hz=100.0)
            off, on = tracks(s)
            (x0, y0, h0), (x1, y1, h1) = final(off), final(on)
            dpos = float(np.hypot(x1 - x0, y1 - y0))
            dh = abs((h1 - h0 + 180.0) % 360.0 - 180.0)
            n0, n1 = len(turn_table(off.steps)), len(turn_table(on.steps))
            n += 1
            moved += dpos > 1e-9
            same_turns += n0 == n1
            small += dh <= 5.0
            largest = max(largest, dh)
            print(f"plain user {u} {speed}: final position moved {dpos:.2e} m, final heading moved {dh:.2f} deg, "
                  f"turns {n0} -> {n1}", flush=True)
    print(f"\n(a) end-turn tracks with one turn within 30 deg of the truth: off {found[False]} of {len(USERS)}, "
          f"on {found[True]} of {len(USERS)}; median |final heading error| off {np.median(err[False]):.1f} deg, "
          f"on {np.median(err[True]):.1f} deg")
    print(f"(b) plain walks: final position moved on {moved} of {n}; turns.csv row count unchanged on {same_turns} "
          f"of {n}; final heading moved <= 5 deg on {small} of {n} (largest {largest:.2f} deg)")


def real() -> None:
    for base in (Path("datasets/external"), Path("/work/shared/data")):
        for d in sorted(base.glob("mobgap_*")):
            off, on = tracks(read_session(d))
            (x0, y0, h0), (x1, y1, h1) = final(off), final(on)
            dist = (float(off.steps["length_m"].abs().sum()), float(on.steps["length_m"].abs().sum()))
            print(f"{base.name}/{d.name}: distance {dist[0]:.3f} -> {dist[1]:.3f} m, final position moved "
                  f"{np.hypot(x1 - x0, y1 - y0):.2e} m, final heading {h0:+.1f} -> {h1:+.1f} deg, turns "
                  f"{len(turn_table(off.steps))} -> {len(turn_table(on.steps))}", flush=True)


if __name__ == "__main__":
    {"sim": sim, "real": real}[sys.argv[1]]()
