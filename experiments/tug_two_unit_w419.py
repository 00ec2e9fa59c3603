"""Decision W419's measurement (docs/decisions/waist.md): a TUG's step count and turn durations from the waist alone
(``track --units waist``) against the default two-unit track (W418 + W419), on fresh simulated slow TUGs.

Run: PYTHONPATH=. .venv/bin/python experiments/tug_two_unit_w419.py [--users 10060-10067] [--out /tmp/w419]
"""

from __future__ import annotations

import argparse
import dataclasses
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

#: trial T1's TUG (its mk_tug.py): 3 m out, a turn, 3 m back, a turn, seated 3 s at each end, 0.5 s standing
ROUTE = "straight:3, turn:180, straight:3, turn:180"
#: step length (m), step time (s) per user, walking speeds 0.6-1.0 m/s (an older adult's TUG pace)
GAITS = [(0.42, 0.70), (0.45, 0.65), (0.45, 0.60), (0.50, 0.62), (0.52, 0.58), (0.54, 0.60), (0.55, 0.58),
         (0.55, 0.55)]


def make(uid: int, gait: tuple[float, float], out: Path) -> dict:
    """One simulated TUG session written to ``out``; its truth (n_steps: ics.csv rows in the trial; the turns)."""
    from pdrlearn import write_session
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.tug_truth import true_tug_phases
    from pdrlearn.sim.user import SPEED_FACTORS, UserProfile

    fl, ft = SPEED_FACTORS["slow"]
    u = dataclasses.replace(UserProfile.from_seed(uid), step_length_m=gait[0] / fl, step_time_s=gait[1] / ft)
    s = simulate_path(parse_route(ROUTE), u, speed="slow", rate_hz=100, seed=0, scenario="route", sit_start_s=3,
                      sit_end_s=3, stand_s=0.5, bounce="pendulum")
    write_session(s, out, overwrite=True)
    tr = s.extras["transfers"]
    t0, t1 = float(tr.iloc[0]["rise_s"]), float(tr.iloc[-1]["seated_s"])
    ics = pd.read_csv(out / "ics.csv")["ic_ms"].to_numpy(float) / 1000.0
    ph = true_tug_phases(s, ROUTE)
    return {"n_steps": int(((ics >= t0) & (ics <= t1)).sum()), "turn": ph["turn"]["duration_s"],
            "turn_to_sit": ph["turn_to_sit"]["duration_s"], "tug": t1 - t0, "speed": gait[0] / gait[1]}


def tracked(folder: Path, out: Path, *extra: str) -> dict | None:
    """tug_trials.csv's one row of a track (None: no trial)."""
    from pdrlearn.cli import main

    assert main(["track", str(folder), "--out", str(out), "--force", *extra]) == 0
    path = out / "tug_trials.csv"
    if not path.is_file():
        return None
    return pd.read_csv(path).iloc[0].to_dict()


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="10060-10067")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    root = Path(a.out or tempfile.mkdtemp(prefix="w419_"))
    rows = []
    for k, uid in enumerate(range(lo, hi + 1)):
        truth = make(uid, GAITS[k % len(GAITS)], root / f"tug_{uid}")
        for arm, extra in (("before", ("--units", "waist")), ("after", ())):
            r = tracked(root / f"tug_{uid}", root / f"tug_{uid}_{arm}", *extra)
            rows.append({"user": uid, "arm": arm, "speed": truth["speed"], "true_steps": truth["n_steps"],
                         "true_turn": truth["turn"], "true_turn_to_sit": truth["turn_to_sit"], "true_tug": truth["tug"],
                         **({} if r is None else {"n_steps": r["n_steps"], "turn": r["tug_turn_s"],
                                                  "turn_to_sit": r["tug_turn_to_sit_s"], "tug": r["tug_time_s"],
                                                  "source": r.get("steps_source", "")})})
    t = pd.DataFrame(rows)
    pd.set_option("display.width", 200)
    print(t.round(2).to_string(index=False))
    for arm in ("before", "after"):
        d = t[t["arm"] == arm]
        steps = (d["n_steps"] - d["true_steps"]).abs()
        turns = np.concatenate([(d["turn"] - d["true_turn"]).abs(), (d["turn_to_sit"] - d["true_turn_to_sit"]).abs()])
        print(f"{arm}: users with a TUG {int(d['tug'].notna().sum())} of {len(d)}; median |n_steps error| "
              f"{steps.median():.1f}; median |turn error| {np.nanmedian(turns):.2f} s (max {np.nanmax(turns):.2f}); "
              f"median |TUG error| {(d['tug'] - d['true_tug']).abs().median():.2f} s")


if __name__ == "__main__":
    main()
