"""Decision W108's measurement: stairs as a climb above the barometer's still-period noise, z only on stairs
(option ``stairs_climb``, off = W91's per-step test and W89's altitude as they were / on).

1. the real lower-back mobgap recordings (level lab walks, uncalibrated): steps called stairs and final z;
2. fresh users 880-899 (normal speed, 50 Hz, seed 3, waist-only, pendulum bounce), W91's two flights up and down:
   stair-step recall against the reference altitude and floors against the reference;
3. the same users, W91's level route: steps called stairs and final z. Prints the numbers W108's rule is judged on.

Run: PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_stairs_noise.py [--users 880-899]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.track.evaluate import evaluate_track  # noqa: E402
from waist_stairs import LEVEL, STAIRS, sim  # noqa: E402  (W91's routes and sessions, one definition)

#: a step is truly on stairs when the reference altitude changes by half a 0.17 m riser during it
HALF_RISER_M = 0.085


def run(session, on: bool):
    res = get_pipeline("waist-pendulum")(session, stairs_climb=on)
    return res, evaluate_track(res, session)


def true_stairs(session, steps) -> np.ndarray:
    tr = session.trajectory
    z0 = np.interp(steps["start_s"].to_numpy(float), tr["t"], tr["z"])
    z1 = np.interp(steps["end_s"].to_numpy(float), tr["t"], tr["z"])
    return np.abs(z1 - z0) >= HALF_RISER_M


def main() -> None:
    logging.disable(logging.WARNING)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="880-899")
    ap.add_argument("--external", default="datasets/external")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    for d in sorted(Path(a.external).glob("mobgap_*_Test*")):
        s = read_session(d)
        cells = []
        for on in (False, True):
            res, _ = run(s, on)
            z = float(res.trajectory["z"].iloc[-1])
            cells.append(f"stairs {int(res.steps['stairs'].sum())}/{len(res.steps)} z {z:+.3f}")
        print(f"{d.name:28s} off: {cells[0]} | on: {cells[1]}", flush=True)
    hits = {False: [0, 0], True: [0, 0]}
    floors = {False: 0, True: 0}
    level = {False: [0, 0.0], True: [0, 0.0]}
    for u in range(lo, hi + 1):
        st, lv = sim(STAIRS, u, 3, "pendulum"), sim(LEVEL, u, 3, "pendulum")
        line = [f"user {u}"]
        for on in (False, True):
            res, ev = run(st, on)
            truth = true_stairs(st, res.steps)
            called = res.steps["stairs"].to_numpy(bool)
            hits[on][0] += int((called & truth).sum())
            hits[on][1] += int(truth.sum())
            ok = (ev["floors_up"], ev["floors_down"]) == (ev["floors_up_ref"], ev["floors_down_ref"])
            floors[on] += ok
            rl, _ = run(lv, on)
            level[on][0] += int(rl.steps["stairs"].sum())
            level[on][1] = max(level[on][1], abs(float(rl.trajectory["z"].iloc[-1])))
            line.append(f"{'on' if on else 'off'}: recall {int((called & truth).sum())}/{int(truth.sum())} floors "
                        f"{ev['floors_up']}/{ev['floors_down']} (ref {ev['floors_up_ref']}/{ev['floors_down_ref']}) "
                        f"level stairs {int(rl.steps['stairs'].sum())} z {rl.trajectory['z'].iloc[-1]:+.3f}")
        print(" | ".join(line), flush=True)
    for on in (False, True):
        print(f"{'on ' if on else 'off'}: stair-step recall {hits[on][0]}/{hits[on][1]} = "
              f"{hits[on][0] / max(hits[on][1], 1):.3f} | floors = reference on {floors[on]} users | level route: "
              f"steps called stairs {level[on][0]}, max |final z| {level[on][1]:.3f} m")


if __name__ == "__main__":
    main()
