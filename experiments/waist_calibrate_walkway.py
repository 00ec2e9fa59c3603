"""Decision W212: what `calibrate --distance` means on a start-to-stop walkway. Fresh users 4960-4969, the trial's
1.0 m/s walkway (stand 2 s, straight 20 m, stand 2 s; step 0.54 m / 0.54 s; 100 Hz, pendulum bounce), waist-pendulum
calibrated on the walk with seed = user, given either the walkway's length (20 m) or the pelvis's true distance from
the first to the last initial contact (ics.csv, trajectory); each calibration tracks the walk with seed user + 1000,
scored against the same two distances.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_calibrate_walkway.py [--users 4960-4969]
"""

from __future__ import annotations

import argparse
import dataclasses
import logging

import numpy as np

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate

ROUTE = [Stand(2), Straight(20), Stand(2)]


def walk(user: UserProfile, seed: int):
    return simulate_path(ROUTE, dataclasses.replace(user, step_length_m=0.54, step_time_s=0.54), speed="normal",
                         rate_hz=100, seed=seed, bounce="pendulum")


def ic_to_ic_m(s) -> float:
    """The pelvis's true horizontal distance from the first to the last initial contact (either foot)."""
    ic = np.sort(s.extras["ics"]["ic_s"].dropna().to_numpy(float))
    tr = s.trajectory
    x, y = (np.interp(ic[[0, -1]], tr["t"].to_numpy(float), tr[c].to_numpy(float)) for c in ("x", "y"))
    return float(np.hypot(x[1] - x[0], y[1] - y[0]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="4960-4969")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    rows = []
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        cal, test = walk(user, u), walk(user, u + 1000)
        ref = {"walkway": 20.0, "ic_to_ic": ic_to_ic_m(cal)}
        test_ref = {"walkway": 20.0, "ic_to_ic": ic_to_ic_m(test)}
        row = {"user": u, "cal_ic_to_ic_m": round(ref["ic_to_ic"], 3)}
        for how, d in ref.items():
            p = calibrate([cal], "waist-pendulum", distances=[d])
            got = float(track_waist(test, pipeline="waist-pendulum", params=p).steps["length_m"].abs().sum())
            for what, true in test_ref.items():
                row[f"d={how} vs {what} %"] = round(100.0 * (got / true - 1.0), 2)
        rows.append(row)
        print(row, flush=True)
    for k in [k for k in rows[0] if k.endswith("%")]:
        v = np.array([r[k] for r in rows])
        print(f"{k}: mean {v.mean():+.2f}, range {v.min():+.2f} to {v.max():+.2f}")
    print(f"first-to-last IC distance of the calibration walks: {min(r['cal_ic_to_ic_m'] for r in rows)}-"
          f"{max(r['cal_ic_to_ic_m'] for r in rows)} m")


if __name__ == "__main__":
    main()
