"""Decisions W490 / L614's adoption checks (docs/decisions/waist.md, docs/decisions/localization.md): a TUG trial turns
about once at its far end and walks at most 9 m each way. Prints, per track, the TUG trials and chair-to-chair walks
of ``pdrlearn track`` (summary.json ``n_tug_trials``, ``n_chair_walks``, tug_trials.csv's times).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/tug_shape_w490.py --out /tmp/w490 \
         [--t1 DIR ...] [--t3 DIR ...]

* rule (4): fresh seated TUGs, users 12040-12043 (W294's two-turn route, seated 5 s at both ends, 100 Hz; even users
  normal, odd slow), tracked with waist-pendulum, waist-pll and the default two-unit (foot) track: every one a TUG;
* rule (5): trial T1's daily-living route (fresh users 12044 normal, 12045 slow, and T1's own folders given with
  ``--t1``, ``--bout-rule mobgap``) and trial T3's sit-walk-sit folders (``--t3``, default track): no TUG.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pandas as pd

TUG = "straight:3, turn:180, straight:3, turn:180"  # W294's two-turn TUG
#: trial T1's daily-living route (its report, F3) with its sit ranges fixed per user
DAILY = ("sit:{a}, straight:1.2, stand:4, turn:90, straight:1.5, stand:5, straight:12, turn:180, straight:12, "
         "sit:{b}, straight:2, stand:3.5, straight:2, stand:2.5, straight:8, pivot:90, straight:6, stand:30, "
         "straight:1.0, sit:{c}")
PIPELINES = (("waist-pendulum", ("--pipeline", "waist-pendulum")), ("waist-pll", ("--pipeline", "waist-pll")),
             ("default", ()))


def simulate(route: str, uid: int, speed: str, out: Path, *sit: str) -> Path:
    from pdrlearn.cli import main

    assert main(["simulate", "--route", route, "--user-seed", str(uid), "--speed", speed, "--rate", "100",
                 *sit, "--out", str(out)]) == 0
    return out


def tracked(folder: Path, out: Path, *extra: str) -> str:
    """One line: the track's TUG trials and chair-to-chair walks."""
    from pdrlearn.cli import main

    assert main(["track", str(folder), "--out", str(out), "--force", *extra]) == 0
    s = json.loads((out / "summary.json").read_text())
    times = ""
    if (out / "tug_trials.csv").is_file():
        t = pd.read_csv(out / "tug_trials.csv")
        times = " (" + ", ".join(f"{v:.2f} s, n_turns {n}" for v, n in zip(t["tug_time_s"], t["n_turns"],
                                                                               strict=True)) + ")"
    return (f"n_tug_trials {s.get('n_tug_trials')}{times}, tug_time_s {s.get('tug_time_s')}, "
            f"n_chair_walks {s.get('n_chair_walks')}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--t1", nargs="*", default=[])
    ap.add_argument("--t3", nargs="*", default=[])
    a = ap.parse_args()
    root = Path(a.out)
    for uid in range(12040, 12044):
        speed = "slow" if uid % 2 else "normal"
        s = simulate(TUG, uid, speed, root / f"tug_{uid}", "--sit-start", "5", "--sit-end", "5")
        for name, extra in PIPELINES:
            print(f"(4) TUG user {uid} {speed} {name}: {tracked(s, root / f'tug_{uid}_{name}', *extra)}", flush=True)
    daily = [simulate(DAILY.format(a=75, b=50, c=35), 12044, "normal", root / "daily_12044"),
             simulate(DAILY.format(a=65, b=45, c=32), 12045, "slow", root / "daily_12045"),
             *(Path(p) for p in a.t1)]
    for s in daily:
        for name, extra in PIPELINES:
            line = tracked(s, root / f"{s.name}_{name}", *extra, "--bout-rule", "mobgap")
            print(f"(5) daily {s.name} {name}: {line}", flush=True)
    for p in a.t3:
        print(f"(5) T3 {Path(p).name} default: {tracked(Path(p), root / (Path(p).name + '_default'))}", flush=True)


if __name__ == "__main__":
    main()
