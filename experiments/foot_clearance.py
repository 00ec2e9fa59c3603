"""Decision L421 (session 34, trial T5 finding 4): the foot track's per-stride sensor lift and sole angles against the
simulator's truth. Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/foot_clearance.py   # users 8100-8103
Output: experiments/results/foot_clearance.txt (the printed lines).

Truth: the session's ``foot_trajectory`` (the sensor's position and attitude per sample) over each tracked stride's own
bounds, with the same definitions (:func:`pdrlearn.kernels.clearance.max_lift`, ``sole_pitch_deg``); the true IC / TC
angles are read at the simulator's own ``ic_s`` / ``tc_s`` of the stride whose IC lies inside the tracked stride.
"""
import logging

import numpy as np

from pdrlearn.kernels.clearance import max_lift, sole_pitch_deg
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys

logging.disable(logging.WARNING)

USERS = range(8100, 8104)
ROUTE = "stand:3, straight:20, stand:3"


def truth_row(ft, a: float, b: float, ic: float, tc: float, ic_det: float) -> tuple[float, float, float, float]:
    """(lift m, IC angle deg, TC angle deg, the true angle at the detected IC ``ic_det``) over the stride a..b s."""
    t = ft["t_s"].to_numpy(float)
    sel = (t >= a) & (t <= b)
    pos = ft[["x", "y", "z"]].to_numpy(float)[sel][None]
    q = ft[["qw", "qx", "qy", "qz"]].to_numpy(float)[sel][None]
    pitch = sole_pitch_deg(q)[0]
    ts = t[sel]

    def at(x):
        return float(pitch[int(np.argmin(np.abs(ts - x)))]) if np.isfinite(x) and ts[0] <= x <= ts[-1] else np.nan

    return float(max_lift(pos, np.ones(pos.shape[:2], bool))[0]), at(ic), at(tc), at(ic_det)


def main() -> None:
    err = {"lift": [], "ic": [], "tc": [], "ic_at_detected_time": [], "ic_timing_s": []}
    for u in USERS:
        s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), rate_hz=100.0, seed=u)
        ft, truth = s.extras["foot_trajectory"], s.steps
        res = track_plasys(s, toe_off=True)
        st = res.steps
        for r in st.itertuples():
            if not np.isfinite(r.max_sensor_lift_m):
                continue
            k = np.flatnonzero((truth["ic_s"] > r.start_s) & (truth["ic_s"] < r.end_s))
            if len(k) != 1:
                continue
            tl, ti, tt, td = truth_row(ft, r.start_s, r.end_s, truth["ic_s"].iloc[k[0]], truth["tc_s"].iloc[k[0]],
                                       r.event_s)
            err["ic_at_detected_time"].append(r.ic_angle_deg - td)  # diagnostic: the attitude alone
            err["ic_timing_s"].append(r.event_s - truth["ic_s"].iloc[k[0]])
            err["lift"].append(r.max_sensor_lift_m - tl)
            err["ic"].append(r.ic_angle_deg - ti)
            err["tc"].append(r.tc_angle_deg - tt)
            print(f"user {u} stride {r.start_s:6.2f}-{r.end_s:6.2f} s: lift {r.max_sensor_lift_m:.3f} (truth {tl:.3f})"
                  f" m, IC {r.ic_angle_deg:+6.1f} (truth {ti:+6.1f}) deg, TC {r.tc_angle_deg:+6.1f} (truth {tt:+6.1f})"
                  " deg", flush=True)
    for k, unit in (("lift", "m"), ("ic", "deg"), ("tc", "deg"), ("ic_at_detected_time", "deg"),
                    ("ic_timing_s", "s")):
        e = np.asarray(err[k], float)
        e = e[np.isfinite(e)]
        print(f"{k}: {len(e)} strides, median error {np.median(e):+.4f} {unit}, median |error| "
              f"{np.median(np.abs(e)):.4f} {unit}, max |error| {np.max(np.abs(e)):.4f} {unit}")


if __name__ == "__main__":
    main()
