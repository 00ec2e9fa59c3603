"""Decisions L277-L279: periods.csv of a tracked simulated session against its summary and its simulated truth.

    pdrlearn track SESSION_DIR --per 10min --out TRACK_OUT
    python experiments/period_totals.py SESSION_DIR TRACK_OUT

Prints the table (time columns in s), the periods' totals next to summary.json's, and per period the truth:
distance and strides of the reference strides (steps.csv, by their middle, L105's rule), the true walking time
(L79's rule, :func:`pdrlearn.track.gait.walking_pieces`, on the reference strides), the true seated time
(transfers.csv: seated to rise) and lift time (rides.csv), and the true storeys (L127's climbs on the reference
strides' height_m).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.track.evaluate import floor_climbs
from pdrlearn.track.gait import walking_pieces
from pdrlearn.track.periods import TIME_KEYS, _measure, _union


def main(session_dir: Path, out: Path) -> None:
    per = pd.read_csv(out / "periods.csv")
    summ = json.loads((out / "summary.json").read_text())
    cols = ["period", "start_s", "end_s", "partial", "distance_m", "n_steps", *TIME_KEYS, "floors_up", "floors_down",
            "n_bouts", "n_turns", "data_gap", "position_sigma_end_m"]
    print(per[cols].round(2).to_string(index=False))
    pairs = [("distance_m", "distance_m"), ("n_steps", "n_steps"), ("time_walking_s", "walking_time_s"),
             ("time_no_data_s", "time_no_data_s"), ("floors_up", "floors_up"), ("floors_down", "floors_down"),
             ("n_bouts", "n_bouts"), ("n_turns", "turn_count")]
    print("\nperiods summed vs summary.json:")
    for col, key in pairs:
        print(f"  {col:22s} {per[col].sum():10.2f}   summary {key} {summ[key]:.2f}")
    stop = per["time_between_steps_s"].sum() + per["time_no_steps_s"].sum()
    both = summ["time_between_steps_s"] + summ["time_no_steps_s"]
    print(f"  between + no steps     {stop:10.2f}   summary {both:.2f}")
    print(f"  all four times         {per[list(TIME_KEYS)].to_numpy().sum():10.2f}   summary time_span_s "
          f"{summ['time_span_s']:.2f}")
    ref = pd.read_csv(session_dir / "steps.csv")
    a, b = ref["start_ms"].to_numpy(float) / 1e3, ref["end_ms"].to_numpy(float) / 1e3
    mid = 0.5 * (a + b)
    walk = _union(walking_pieces(a, b))
    seated = _union(pd.read_csv(session_dir / "transfers.csv")[["seated_ms", "rise_ms"]].to_numpy(float) / 1e3) \
        if (session_dir / "transfers.csv").is_file() else np.zeros((0, 2))
    lift = _union(pd.read_csv(session_dir / "rides.csv")[["start_ms", "end_ms"]].to_numpy(float) / 1e3) \
        if (session_dir / "rides.csv").is_file() else np.zeros((0, 2))
    climbs = floor_climbs(ref["height_m"].to_numpy(float))
    print("\ntruth per period (reference strides of the tracked foot):")
    rows = []
    for k, r in per.iterrows():
        last = k == len(per) - 1
        m = (mid >= r.start_s) & ((mid <= r.end_s) if last else (mid < r.end_s))
        up = sum(n for i, n in climbs if n > 0 and m[i])
        down = -sum(n for i, n in climbs if n < 0 and m[i])
        rows.append({"period": int(r.period), "distance_m": float(np.abs(ref["length_m"].to_numpy(float))[m].sum()),
                     "n_strides": int(m.sum()), "walking_s": _measure(walk, r.start_s, r.end_s),
                     "seated_s": _measure(seated, r.start_s, r.end_s), "lift_s": _measure(lift, r.start_s, r.end_s),
                     "floors_up": up, "floors_down": down,
                     "tracked_distance_error_pct": 100 * (r.distance_m / float(np.abs(ref["length_m"])[m].sum()) - 1)
                     if m.any() else np.nan})
    truth = pd.DataFrame(rows)
    print(truth.round(2).to_string(index=False))
    print(f"  totals: distance {truth['distance_m'].sum():.2f} m, strides {truth['n_strides'].sum()}, walking "
          f"{truth['walking_s'].sum():.2f} s, seated {truth['seated_s'].sum():.2f} s, "
          f"lift {truth['lift_s'].sum():.2f} s, "
          f"floors {truth['floors_up'].sum()} up / {truth['floors_down'].sum()} down (stairs)")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]))
