"""Decisions S121-S123 (session 51, FL): what `simulate --graded-slopes`, `--fatigue` and `--waist-reclip` simulate,
on fresh simulated users 18630-18649. Nothing is tuned here.

    PYTHONPATH=. python experiments/sim_options_s51_s121.py

S121: users 18630-18633, `stand:3, slope:40:0, slope:40:15, slope:40:-25, stand:3` at 100 Hz with and without
--graded-slopes: the truth strides' median length and time per grade (strides whose height / length is the grade
within 0.01) over the 0 % segment's, against Tobler's sqrt r and 1 / sqrt r; the plasys distance error and step F1.
S122: users 18640-18643, `stand:3, straight:300, stand:3` at 20 Hz, --fatigue 0 and 20: the truth speed of the last
10 % of the strides over the first 10 %, and the largest change of the stride time between consecutive strides.
S123: user 18645, `stand:20` (noise off) re-clipped at 10 s by y:20: gravity's turn and the gyroscope's integral."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.path import graded_step
from pdrlearn.sim.route import parse_route
from sim_options_s49_s115 import scores

logging.getLogger("pdrlearn").setLevel(logging.ERROR)


def _strides(d) -> pd.DataFrame:
    st = d.steps[d.steps["kind"] == "walk"].copy()
    st["time_s"] = st["end_s"] - st["start_s"]
    st["grade"] = st["height_m"] / st["length_m"]
    return st


def slope_rows() -> list[dict]:
    route = "stand:3, slope:40:0, slope:40:15, slope:40:-25, stand:3"
    rows = []
    for u in range(18630, 18634):
        for graded in (False, True):
            d = simulate_path(parse_route(route), UserProfile.from_seed(u), seed=1, rate_hz=100,
                              graded_slopes=graded)
            st = _strides(d)
            level = st[st["grade"].abs() < 0.01]
            row = {"user": u, "graded": graded}
            for g in (0.15, -0.25):
                on = st[(st["grade"] - g).abs() < 0.01]
                f_len, f_time = graded_step(g) if graded else (1.0, 1.0)
                row[f"len_{g:+.2f}"] = round(float(on["length_m"].median() / level["length_m"].median()), 4)
                row[f"len_want_{g:+.2f}"] = round(f_len, 4)
                row[f"time_{g:+.2f}"] = round(float(on["time_s"].median() / level["time_s"].median()), 4)
                row[f"time_want_{g:+.2f}"] = round(f_time, 4)
                row[f"n_{g:+.2f}"] = len(on)
            rows.append({**row, **scores(d, ["plasys"])})
    return rows


def fatigue_rows() -> list[dict]:
    route = "stand:3, straight:300, stand:3"
    rows = []
    for u in range(18640, 18644):
        for pct in (0.0, 20.0):
            d = simulate_path(parse_route(route), UserProfile.from_seed(u), seed=1, fatigue_pct=pct)
            st = _strides(d)
            st = st[st["steady"]]  # the bout's first and last strides out
            k = max(1, len(st) // 10)
            speed = st["length_m"].to_numpy() / st["time_s"].to_numpy()
            jump = np.abs(np.diff(st["time_s"].to_numpy())) / st["time_s"].to_numpy()[:-1]
            rows.append({"user": u, "fatigue_pct": pct, "n_strides": len(st),
                         "speed_last_over_first": round(float(speed[-k:].mean() / speed[:k].mean()), 4),
                         "max_consecutive_time_change": round(float(jump.max()), 4)})
    return rows


def reclip_row() -> dict:
    d = simulate_path(parse_route("stand:20"), UserProfile.from_seed(18645), seed=1, noise=False, stand_s=4.0,
                      waist_reclip=(10.0, (0.0, 20.0, 0.0)))
    acc, gyr = d.streams["wAccelerometer"], d.streams["wGyroscope"]
    a0, a1 = acc.values[acc.t < 9].mean(axis=0), acc.values[acc.t > 11].mean(axis=0)
    angle = np.degrees(np.arccos(a0 @ a1 / np.linalg.norm(a0) / np.linalg.norm(a1)))
    total = np.trapezoid(gyr.values, gyr.t, axis=0)
    plain = simulate_path(parse_route("stand:20"), UserProfile.from_seed(18645), seed=1, noise=False, stand_s=4.0)
    before = acc.t < 10.0
    same = bool(np.array_equal(acc.values[before], plain.streams["wAccelerometer"].values[before]))
    return {"gravity_turn_deg": round(float(angle), 4), "gyro_integral_deg": np.round(np.degrees(total), 4).tolist(),
            "samples_before_T_identical": same}


def main() -> None:
    pd.set_option("display.width", 250)
    pd.set_option("display.max_columns", 30)
    print("== S121 graded slopes (ratios over the 0 % segment)")
    print(pd.DataFrame(slope_rows()).to_string(index=False))
    print("== S122 fatigue")
    f = pd.DataFrame(fatigue_rows())
    print(f.to_string(index=False))
    print(f.groupby("fatigue_pct")[["speed_last_over_first", "max_consecutive_time_change"]].median().to_string())
    print("== S123 re-clip (user 18645, stand:20, noise off, y:20 at 10 s)")
    print(reclip_row())


if __name__ == "__main__":
    main()
