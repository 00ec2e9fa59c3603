"""Decisions S115-S117 (session 49, FH): what `simulate --swing-height`, `--pelvis-sway` and `--waist-mount-drift`
simulate and what they do to the pipelines, on fresh simulated users. Nothing is tuned here.

    PYTHONPATH=. python experiments/sim_options_s49_s115.py

S115: users 16700-16703, a shuffler's gait (steps 0.35 m in 0.45 s, `stand:3, straight:30, stand:3`, 20 Hz) at the
user's own swing and at --swing-height 0.25 / 0.12 / 0.06 / 0.03 m: the foot unit's truth z range (max - 5th
percentile), the plasys pipeline's distance error and step F1. S116: users 16704-16707, their own gait
(`stand:3, straight:40, stand:3`), --pelvis-sway default / 0.01 / 0.03 / 0.06 / 0.10 m: the waist unit's truth
lateral excursion (the trajectory's y range, the walk is along x), waist-pll and waist-pendulum distance error and
step F1. S117: users 16708-16711, the same walk with no drift and --waist-mount-drift y:20 / z:20 / x:20."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.cli.simulate import _custom_gait, parse_mount, with_swing_and_sway
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline

logging.getLogger("pdrlearn").setLevel(logging.ERROR)


def scores(session, pipelines) -> dict:
    out = {}
    for p in pipelines:
        s = get_pipeline(p)(session).summary(session)
        out[f"{p}_dist_err_pct"] = s.get("distance_error_pct")
        out[f"{p}_step_f1"] = s.get("step_f1")
    return out


def swing_rows() -> list[dict]:
    route = "stand:3, straight:30, stand:3"
    rows = []
    for u in range(16700, 16704):
        base = _custom_gait(UserProfile.from_seed(u), "normal", 0.35, 0.45, route)
        for h in (None, 0.25, 0.12, 0.06, 0.03):
            user = with_swing_and_sway(base, h, None)
            d = simulate_path(parse_route(route), user, seed=1)
            z = d.extras["foot_trajectory"]["z"].to_numpy()
            rows.append({"user": u, "swing_height": "own" if h is None else h,
                         "toe_off_pitch_deg": user.toe_off_pitch_deg,
                         "foot_z_range_m": round(float(z.max() - np.percentile(z, 5)), 4), **scores(d, ["plasys"])})
    return rows


def waist_rows(users, option: str, values) -> list[dict]:
    route = "stand:3, straight:40, stand:3"
    rows = []
    for u in users:
        for v in values:
            user = UserProfile.from_seed(u)
            knobs = {}
            if option == "sway" and v is not None:
                user = with_swing_and_sway(user, None, v)
            if option == "drift" and v is not None:
                knobs["waist_mount_end_deg"] = parse_mount(v, "--waist-mount-drift")
            d = simulate_path(parse_route(route), user, seed=1, **knobs)
            y = d.trajectory["y"].to_numpy()
            rows.append({"user": u, option: "own" if v is None and option == "sway" else (v or "none"),
                         "waist_y_range_m": round(float(y.max() - y.min()), 4),
                         **scores(d, ["waist-pll", "waist-pendulum"])})
    return rows


def main() -> None:
    pd.set_option("display.width", 220)
    for title, rows, key in (
            ("S115 swing height (plasys, shuffler 0.35 m / 0.45 s)", swing_rows(), "swing_height"),
            ("S116 pelvis sway (own gait)", waist_rows(range(16704, 16708), "sway", (None, 0.01, 0.03, 0.06, 0.10)),
             "sway"),
            ("S117 waist mount drift (own gait)", waist_rows(range(16708, 16712), "drift",
                                                             (None, "y:20", "z:20", "x:20")), "drift")):
        table = pd.DataFrame(rows)
        print(f"== {title}")
        print(table.round(4).to_string(index=False))
        num = table.drop(columns=["user"]).groupby(key, sort=False).median(numeric_only=True)
        print("medians over users:")
        print(num.round(4).to_string())


if __name__ == "__main__":
    main()
