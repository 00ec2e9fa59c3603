"""Decision W72 (docs/decisions/waist.md): `integrate_stops` (the waist's yaw turned between walking sequences, W58)
as the default of the waist gyro heading, measured against W72's adoption rule (written before this ran).

Uncalibrated `waist-pendulum` (meta.json defaults), offline and realtime, without / with `integrate_stops`;
initial heading = the truth's at the first step (as experiments/waist_gap_yaw.py, L61). Prints per set the mean
start-aligned final position error (m, `evaluate_track`) off / on, and the walks better / worse.

Sets: "turns" = fresh turn walks, users 61-70, normal, seed 7, 20 and 100 Hz, routes "tug" (a Timed-Up-and-Go,
the trial's route) and L61's "floors", "corridor", "stairwell"; "AD" = scenarios A-D, users 1-5 x 3 speeds, default
seed, 100 Hz; "real" = mobgap Test5 distance errors and Test11 final position / L42 turn metrics.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_turn_gaps.py [--sets turns,AD,real] [--external datasets/external]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track
from waist_gap_yaw import ROUTES as L61_ROUTES

ROUTES = {"tug": "stand:3, straight:3, turn:180, straight:3, turn:180, stand:3", **L61_ROUTES}
MODES = ("offline", "realtime")


def _truth_heading(session, t: float) -> float:
    g = session.trajectory
    return float(np.interp(t, g["t"].to_numpy(float), np.unwrap(g["heading_rad"].to_numpy(float))))


def run_arms(session) -> dict[str, tuple[float, float]]:
    """{mode: (final position error m off, on)}."""
    st = session.steps
    h0 = _truth_heading(session, float(st["start_s"].iloc[0])) if st is not None and len(st) else 0.0
    out = {}
    for mode in MODES:
        errs = []
        for integ in (False, True):
            res = get_pipeline("waist-pendulum")(session, realtime=mode == "realtime", integrate_stops=integ,
                                                 initial_heading=h0)
            errs.append(float(evaluate_track(res, session)["final_position_error_m"]))
        out[mode] = tuple(errs)
    return out


def _report(name: str, rows: list[dict]) -> dict[str, np.ndarray]:
    arr = {}
    for mode in MODES:
        a = np.array([r[mode] for r in rows])
        d = a[:, 1] - a[:, 0]
        print(f"{name:18s} {mode:8s} walks {len(a):2d} | mean final position error m off / on: {a[:, 0].mean():.3f} / "
              f"{a[:, 1].mean():.3f} | better {int((d < -1e-9).sum())}, worse {int((d > 1e-9).sum())} "
              f"(largest increase {max(d.max(), 0.0):.3f} m)", flush=True)
        arr[mode] = a
    return arr


def _users(spec: str) -> list[int]:
    lo, _, hi = spec.partition("-")
    return list(range(int(lo), int(hi or lo) + 1))


def real(external: Path) -> None:
    from pdrlearn.io import read_session

    for d in sorted(external.glob("mobgap_*_Test*")):
        s = read_session(d)
        line = []
        ends = []
        for integ in (False, True):
            res = get_pipeline("waist-pendulum")(s, integrate_stops=integ)
            ev = evaluate_track(res, s)
            tr = res.trajectory
            ends.append(np.array([tr["x"].iloc[-1], tr["y"].iloc[-1]]))
            de = ev.get("distance_error_pct")
            line.append(f"dist err {de:+.3f} %" if de is not None else "dist err -")
            if ev.get("n_turns"):
                line[-1] += (f", turns {ev['n_turns']} MAE {ev['turn_angle_mae_deg']:.1f} deg "
                             f"sign {ev['turn_sign_agreement']:.3f}")
        path = float(res.steps["length_m"].sum())
        print(f"{d.name:28s} off: {line[0]} | on: {line[1]} | final position moved "
              f"{np.linalg.norm(ends[1] - ends[0]):.2f} m (path {path:.1f} m)", flush=True)


def main() -> None:
    logging.disable(logging.WARNING)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sets", default="turns,AD,real")
    p.add_argument("--users-turns", default="61-70")
    p.add_argument("--users-ad", default="1-5")
    p.add_argument("--external", default="datasets/external")
    a = p.parse_args()
    sets = a.sets.split(",")
    if "turns" in sets:
        pooled = {m: [] for m in MODES}
        for rate in (20.0, 100.0):
            for name, route in ROUTES.items():
                rows = [run_arms(simulate_path(parse_route(route), UserProfile.from_seed(u), speed="normal",
                                               rate_hz=rate, seed=7, name=f"{name}_u{u}", scenario="route"))
                        for u in _users(a.users_turns)]
                arr = _report(f"{name} {rate:.0f} Hz", rows)
                for m in MODES:
                    pooled[m].append(arr[m])
        for m in MODES:
            a2 = np.concatenate(pooled[m])
            off, on = a2[:, 0].mean(), a2[:, 1].mean()
            print(f"ALL turn walks {m:8s} walks {len(a2)} | mean off / on {off:.3f} / {on:.3f} m "
                  f"({100 * (on - off) / off:+.1f} %)", flush=True)
    if "AD" in sets:
        for sc in "ABCD":
            rows = [run_arms(simulate(sc, u, sp, rate_hz=100.0)) for u in _users(a.users_ad)
                    for sp in ("slow", "normal", "fast")]
            _report(f"scenario {sc} 100 Hz", rows)
    if "real" in sets:
        real(Path(a.external))


if __name__ == "__main__":
    main()
