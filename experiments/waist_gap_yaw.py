"""Decision L61 (docs/decisions/localization.md): the waist-gyro heading of `track --streaming` / `pdrlearn run`
with and without the waist's turn between strides (`waist_gap_yaw`), on fresh simulated walks.

Streamed PLASYS M3 with the oracle classes (only the heading differs between the arms; `pdrlearn run` equals
`track --streaming`, E6's parity tests), heading "auto" (= the waist gyroscope: the walks have both units),
initial heading = the truth's at the first stride. Prints, per set, the mean final position error (m, horizontal,
start-aligned, `evaluate_track`) without / with the candidate (L61: ungated) / with the 0.4 rad/s-gated variant
(information only), and the mean |error of the total turn| (deg).

Sets (L61's adoption rule): the turn-on-the-spot routes "floors", "corridor", "stairwell", users 21-30, normal,
20 Hz, seed 7; the scenarios A-D, users 1-5 x slow/normal/fast, default seed.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_gap_yaw.py [--sets turns,AD] [--users-turns 21-30]
"""

from __future__ import annotations

import argparse
import math
from unittest import mock

import numpy as np

from pdrlearn.kernels import stride as SK
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_streaming

ROUTES = {
    "floors": "straight:5, up:17, turn:180, down:17, backward:3",
    "corridor": "straight:6, turn:90, straight:4, stand:2, turn:-90, straight:6, turn:180, straight:6",
    "stairwell": ("straight:3, up:9, turn:180, up:9, turn:180, up:9, straight:4, turn:180, down:9, turn:180, "
                  "down:9, turn:180, down:9, straight:3"),
}
ARMS = ("off", "L61 ungated", "gated 0.4 (info)")


def _truth_heading(session, t: float) -> float:
    g = session.trajectory
    return float(np.interp(t, g["t"].to_numpy(float), np.unwrap(g["heading_rad"].to_numpy(float))))


def run_arms(session) -> list[tuple[float, float]]:
    """(final position error m, total-turn error deg) per arm."""
    out = []
    for arm in ARMS:
        gated = arm.startswith("gated")
        with mock.patch.object(SK, "WAIST_GAP_STILL_RAD_S", 0.4 if gated else SK.WAIST_GAP_STILL_RAD_S):
            st = session.steps
            h0 = _truth_heading(session, float(st["start_s"].iloc[0])) if st is not None and len(st) else 0.0
            res = track_streaming(session, method="M3", model="oracle", initial_heading=h0,
                                  waist_gap_yaw=arm != "off")  # explicit: independent of the default
        ev = evaluate_track(res, session)
        s = res.steps
        head = np.unwrap(s["heading_rad"].to_numpy(float))
        turn_est = head[-1] - head[0]
        turn_true = (_truth_heading(session, float(s["end_s"].iloc[-1]))
                     - _truth_heading(session, float(s["end_s"].iloc[0])))
        out.append((ev["final_position_error_m"], abs(math.degrees(turn_est - turn_true))))
    return out


def _report(name: str, rows: list[list[tuple[float, float]]]) -> None:
    a = np.array(rows)  # (runs, arms, 2)
    fin = " / ".join(f"{v:.2f}" for v in a[:, :, 0].mean(axis=0))
    turn = " / ".join(f"{v:.1f}" for v in a[:, :, 1].mean(axis=0))
    d = a[:, 1, 0] - a[:, 0, 0]
    better, worse = int((d < -1e-9).sum()), int((d > 1e-9).sum())
    print(f"{name:10s} runs {len(rows):2d} | mean final position error m ({' / '.join(ARMS)}): {fin} | "
          f"mean |total-turn error| deg: {turn} | L61 better on {better}, worse on {worse} of {len(rows)} "
          f"(largest increase {max(d.max(), 0.0):.2f} m)", flush=True)


def _users(spec: str) -> list[int]:
    lo, _, hi = spec.partition("-")
    return list(range(int(lo), int(hi or lo) + 1))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sets", default="turns,AD")
    p.add_argument("--users-turns", default="21-30")
    p.add_argument("--users-ad", default="1-5")
    a = p.parse_args()
    sets = a.sets.split(",")
    if "turns" in sets:
        for name, route in ROUTES.items():
            rows = [run_arms(simulate_path(parse_route(route), UserProfile.from_seed(u), speed="normal",
                                           rate_hz=20.0, seed=7, name=f"{name}_u{u}", scenario="route"))
                    for u in _users(a.users_turns)]
            _report(name, rows)
    if "AD" in sets:
        for sc in "ABCD":
            rows = [run_arms(simulate(sc, u, sp)) for u in _users(a.users_ad) for sp in ("slow", "normal", "fast")]
            _report(sc, rows)


if __name__ == "__main__":
    main()
