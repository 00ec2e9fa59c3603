"""Decision L728 (session 48, fixer FK, trial T1 F3): which contact event makes `gait`'s double support read low,
at normal, fast and race-walking pace, with the force insoles and IMU-only, against the simulator's truth.

Usage:
    PYTHONPATH=. .venv/bin/python experiments/support_bias_s48_l728.py [FIRST_USER N_USERS]

Users 16000-16019 (fresh, session 48), route ``stand:3, straight:40, stand:3`` at 100 Hz, both feet of one walk
(``instrumented_foot`` left / right, the same user seed and walk seed). Paces: ``normal`` (the user's own),
``fast`` (``--speed fast``), ``race`` (T1's race walk: 0.97 m steps in 0.29 s, as ``simulate --step-length 0.97
--step-time 0.29``). Per walk and set-up (``force``: the insoles' contacts; ``imu``: ``--ignore-force``): the median
over both feet's tracked strides of (tracked IC - true IC) and (tracked toe-off - true toe-off) in ms (each tracked
event matched to the nearest labelled one within 0.15 s), and the walk's double support (%) tracked and true
(:func:`pdrlearn.track.bilateral.bilateral_gait` of the tracks and of the labels). Prints one row per walk and
set-up and the medians per pace; writes nothing.
"""

from __future__ import annotations

import dataclasses
import logging
import sys

import numpy as np

from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import SPEED_FACTORS, UserProfile
from pdrlearn.track.bilateral import bilateral_gait, label_steps
from pdrlearn.track.plasys import track_plasys

ROUTE = "stand:3, straight:40, stand:3"
RACE_STEP_M, RACE_STEP_S = 0.97, 0.29  # trial T1's cohort (mk2.sh: 0.93-1.0 m in 0.27-0.30 s)
MATCH_S = 0.15


def walker(u: int, pace: str) -> tuple[UserProfile, str]:
    user = UserProfile.from_seed(u)
    if pace != "race":
        return user, pace
    f_len, f_time = SPEED_FACTORS["normal"]
    return dataclasses.replace(user, step_length_m=RACE_STEP_M / f_len, step_time_s=RACE_STEP_S / f_time), "normal"


def errors_ms(tracked, labelled) -> np.ndarray:
    tr = np.asarray(tracked, float)
    tr = tr[np.isfinite(tr)]
    lab = np.sort(np.asarray(labelled, float)[np.isfinite(np.asarray(labelled, float))])
    if not len(tr) or not len(lab):
        return np.zeros(0)
    j = np.clip(np.searchsorted(lab, tr), 1, len(lab) - 1)
    near = np.where(np.abs(tr - lab[j - 1]) <= np.abs(tr - lab[j]), lab[j - 1], lab[j])
    d = tr - near
    return 1000.0 * d[np.abs(d) <= MATCH_S]


def main() -> None:
    logging.disable(logging.WARNING)
    first, n = (int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else (16000, 20)
    rows = []
    print("user | pace | set-up | cycle s | IC err ms | TO err ms | stance err ms | DS tracked % | DS true % | diff")
    for u in range(first, first + n):
        for pace in ("normal", "fast", "race"):
            user, speed = walker(u, pace)
            sessions = [simulate_path(parse_route(ROUTE), user, speed=speed, rate_hz=100.0, seed=u,
                                      instrumented_foot=f) for f in ("left", "right")]
            labels = [label_steps(s) for s in sessions]
            truth = bilateral_gait(*labels)["walk"]
            for setup in ("force", "imu"):
                tracks = [track_plasys(s, toe_off=True, ignore_force=setup == "imu", transfers=False)
                          for s in sessions]
                res = bilateral_gait(*(t.steps for t in tracks), contact_source=setup)["walk"]
                pairs = list(zip(tracks, labels, strict=True))
                ic = np.concatenate([errors_ms(t.steps["event_s"], lab["ic_s"]) for t, lab in pairs])
                to = np.concatenate([errors_ms(t.steps["tc_s"], lab["tc_s"]) for t, lab in pairs])
                ds, ds0 = res["double_support_pct"], truth["double_support_pct"]
                cyc = 0.5 * (truth["stride_time_s_left"] + truth["stride_time_s_right"])
                st = [res[f"stance_time_s_{s}"] - truth[f"stance_time_s_{s}"] for s in ("left", "right")
                      if res[f"stance_time_s_{s}"] is not None]
                row = (u, pace, setup, cyc, float(np.median(ic)) if len(ic) else np.nan,
                       float(np.median(to)) if len(to) else np.nan, 1000.0 * float(np.mean(st)) if st else np.nan,
                       np.nan if ds is None else ds, ds0, np.nan if ds is None else ds - ds0)
                rows.append(row)
                print(f"{u} | {pace} | {setup} | {cyc:.3f} | {row[4]:+.1f} | {row[5]:+.1f} | {row[6]:+.1f} | "
                      f"{row[7]:.1f} | {ds0:.1f} | {row[9]:+.1f}", flush=True)
    print("median per pace and set-up: cycle s | IC err ms | TO err ms | stance err ms | DS diff points (min..max)")
    for pace in ("normal", "fast", "race"):
        for setup in ("force", "imu"):
            r = np.array([x[3:] for x in rows if x[1] == pace and x[2] == setup], float)
            print(f"{pace} {setup}: {np.nanmedian(r[:, 0]):.3f} | {np.nanmedian(r[:, 1]):+.1f} | "
                  f"{np.nanmedian(r[:, 2]):+.1f} | {np.nanmedian(r[:, 3]):+.1f} | {np.nanmedian(r[:, 6]):+.1f} "
                  f"({np.nanmin(r[:, 6]):+.1f}..{np.nanmax(r[:, 6]):+.1f})")


if __name__ == "__main__":
    main()
