"""Decision W91's measurement: the stair-step length bound ``stairs_length`` (off / on) of ``waist-pendulum``.

Per fresh user (340-359, normal speed, 50 Hz, seed 3), waist-only sessions (the foot streams and the foot
strides dropped, as the session 19 trial's mk.py did), each user calibrated on a simulated ``straight:40`` (seed 11,
the same bounce) with its length:
1. the trial's two flights up and down, ``--bounce pendulum``; 2. the same, constant bounce; 3. a level walk;
4. the real lower-back mobgap recordings (uncalibrated). Prints the numbers W91's rule is judged on.

Run: PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_stairs.py [--users 340-359]
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.waist.calibration import calibrate

STAIRS = ("straight:5, up:17, turn:180, up:17, straight:5, turn:180, down:17, turn:180, down:17, straight:5")
LEVEL = "straight:30, turn:90, straight:20, turn:-90, straight:10"
CALIBRATION = "straight:40"


def waist_only(session):
    """The session as a belt unit records it: the waist streams, frame and reference trajectory only."""
    return dataclasses.replace(session, streams={k: v for k, v in session.streams.items() if k.startswith("w")},
                               steps=None, frames={k: v for k, v in session.frames.items() if k == "waist"})


def sim(route: str, user: int, seed: int, bounce: str):
    return waist_only(simulate_path(parse_route(route), UserProfile.from_seed(user), speed="normal", rate_hz=50.0,
                                    seed=seed, name=f"u{user}_{bounce}", scenario="route", bounce=bounce))


def arms(session, params) -> list[dict]:
    out = []
    for on in (False, True):
        res = get_pipeline("waist-pendulum")(session, params=params, stairs_length=on)
        ev = evaluate_track(res, session)
        ev["n_stairs"] = int(res.steps["stairs"].sum())
        out.append(ev)
    return out


def report(label: str, rows: list[list[dict]]) -> None:
    de = np.array([[abs(r[0]["distance_error_pct"]), abs(r[1]["distance_error_pct"])] for r in rows])
    fe = np.array([[r[0]["final_position_error_m"], r[1]["final_position_error_m"]] for r in rows])
    ns = [r[1]["n_stairs"] for r in rows]
    fl = sum((r[0]["floors_up"], r[0]["floors_down"]) == (r[0].get("floors_up_ref"), r[0].get("floors_down_ref"))
             for r in rows)
    print(f"{label}: users {len(rows)} | mean |distance error| off / on {de[:, 0].mean():.2f} / "
          f"{de[:, 1].mean():.2f} % "
          f"| mean final error off / on {fe[:, 0].mean():.3f} / {fe[:, 1].mean():.3f} m | steps called stairs "
          f"{sum(ns)} (per user min {min(ns)} max {max(ns)}) | floors = reference on {fl} users", flush=True)


def real(external: Path) -> None:
    for d in sorted(external.glob("mobgap_*_Test*")):
        s = read_session(d)
        off, on = arms(s, None)
        a, b = off.get("distance_error_pct"), on.get("distance_error_pct")
        print(f"{d.name:28s} steps called stairs {on['n_stairs']} | distance off / on {off['distance_m']:.2f} / "
              f"{on['distance_m']:.2f} m | distance error off / on "
              + (f"{a:+.3f} / {b:+.3f} %" if a is not None else "- / -")
              + f" | altitude change {off['altitude_change_m']:+.2f} m, floors {off['floors_up']}/{off['floors_down']}",
              flush=True)


def main() -> None:
    logging.disable(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", default="340-359")
    p.add_argument("--external", default="datasets/external")
    p.add_argument("--sets", default="sim,real")
    a = p.parse_args()
    lo, _, hi = a.users.partition("-")
    users = range(int(lo), int(hi or lo) + 1)
    if "sim" in a.sets.split(","):
        rows = {"stairs pendulum": [], "stairs constant": [], "level pendulum": []}
        for u in users:
            for bounce in ("pendulum", "constant"):
                params = calibrate([sim(CALIBRATION, u, 11, bounce)], "waist-pendulum", distances=[40.0])
                rows[f"stairs {bounce}"].append(arms(sim(STAIRS, u, 3, bounce), params))
                if bounce == "pendulum":
                    rows["level pendulum"].append(arms(sim(LEVEL, u, 3, bounce), params))
            r, c = rows["stairs pendulum"][-1], rows["stairs constant"][-1]
            print(f"user {u}: stairs pendulum dist err off / on {r[0]['distance_error_pct']:+.2f} / "
                  f"{r[1]['distance_error_pct']:+.2f} %, constant {c[0]['distance_error_pct']:+.2f}"
                  f" / {c[1]['distance_error_pct']:+.2f} %, level stairs steps "
                  f"{rows['level pendulum'][-1][1]['n_stairs']}", flush=True)
        for k, v in rows.items():
            report(k, v)
    if "real" in a.sets.split(","):
        real(Path(a.external))


if __name__ == "__main__":
    main()
