"""Decision C193's measurement (session 47): `pdrlearn track --ten-m-walk 2,6,2` on simulated 10 m walkways walked end
to end (users 14960-14969, T1's child gait and each user's own, 100 Hz) and on controls stopping 0.4 m short
(`straight:9.6`, the child gait). Per walk: the tracked verdict (timed or not; "old" = L349's, which refuses every
walk tracked short: a note naming C193 is a walk L349 refused), the speed against the truth (the simulator's pelvis
path, trajectory.csv, passing 2 m and 8 m from its start).

Run: PYTHONPATH=. python experiments/walkway_short_s47_c193.py OUTDIR [FIRST_USER LAST_USER]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

USERS = range(14960, 14970)
CHILD = ["--height", "1.30", "--leg-length", "0.68", "--step-length", "0.42", "--step-time", "0.40"]  # trial T1's
WALKS = (("child", "stand:3, straight:10, stand:3", CHILD), ("own", "stand:3, straight:10, stand:3", []),
         ("control", "stand:3, straight:9.6, stand:3", CHILD))


def _cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True,
                   env={**os.environ, "OMP_NUM_THREADS": "1"})


def truth_speed(folder: Path, a: float = 2.0, b: float = 8.0) -> float:
    """The pelvis path's speed between ``a`` and ``b`` m from its start (trajectory.csv, ms)."""
    tr = pd.read_csv(folder / "trajectory.csv")
    d = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(tr["x"]), np.diff(tr["y"])))])
    ta, tb = np.interp([a, b], d, tr["timestamp"].to_numpy(float) / 1000.0)
    return (b - a) / (tb - ta)


def main(out: Path, users) -> None:
    out.mkdir(parents=True, exist_ok=True)
    counts = {k: [0, 0, 0, 0] for k, _, _ in WALKS}  # walks, timed new, timed old, speed within 5 %
    for uid in users:
        for kind, route, gait in WALKS:
            sim, trk = out / f"{kind}_{uid}", out / f"{kind}_{uid}.t"
            if not sim.exists():
                _cli("simulate", "--route", route, "--user-seed", str(uid), "--rate", "100", *gait, "--out", str(sim))
            if not trk.exists():
                _cli("track", str(sim), "--ten-m-walk", "2,6,2", "--out", str(trk))
            s = json.loads((trk / "summary.json").read_text())
            t, note = s.get("ten_m_walk_speed_mps"), s.get("ten_m_walk_note") or ""
            true = truth_speed(sim)
            timed_old = t is not None and "C193" not in note
            err = np.nan if t is None else 100.0 * (t / true - 1.0)
            c = counts[kind]
            c[0] += 1
            c[1] += t is not None
            c[2] += timed_old
            c[3] += t is not None and abs(err) <= 5.0
            print(f"{kind} user {uid}: distance {s.get('distance_m', float('nan')):.2f} m, "
                  f"{'timed' if t is not None else 'not timed'} (old {'timed' if timed_old else 'not timed'}) "
                  f"speed {'-' if t is None else f'{t:.3f}'} m/s, truth {true:.3f} m/s, error {err:+.2f} %"
                  f"{'; note: ' + note[:90] if note else ''}", flush=True)
    for kind, (n, new, old, within) in counts.items():
        print(f"{kind}: {n} walks, timed new {new} old {old}, speed within 5 % of the truth {within} of {new}",
              flush=True)


if __name__ == "__main__":
    a = sys.argv[1:]
    main(Path(a[0]), range(int(a[1]), int(a[2]) + 1) if len(a) == 3 else USERS)
