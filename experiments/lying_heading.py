"""The lower-back heading across lying in bed, W269's `lying_heading` off (the default) and on: decision W270's rule.
Users 6450-6479 (session 32; 6440-6449 were looked at while writing W269). Run from the repo root:

    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/lying_heading.py > experiments/results/lying_heading.md

Per simulated session: the final position error (m, the track's last position against trajectory.csv's last) and
the last walking step's heading error (deg, against trajectory.csv's last heading) of `waist-pendulum` (its gyro
heading, the one W269 acts on) with the option off and on; `waist-pll` (the `ahe` heading, which W269 does not
touch) once, for reference. Uncalibrated tracks (meta.json defaults), 20 Hz."""

from __future__ import annotations

import contextlib
import io
import logging
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main as cli
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline

ROLLS = "stand:5, straight:10, lie:600:30, turn:180, straight:10, stand:5"  # W270 (a): a walk, 10 min, a walk back
NIGHT = "stand:5, straight:10, lie:3600:8, straight:10, stand:5"  # W270 (c): an hour, walking on the same way
SEATED = "stand:5, straight:10, sit:600, turn:180, straight:10, stand:5"  # W270 (d): no lying
GROUPS = [("a", ROLLS, range(6450, 6470)), ("c", NIGHT, range(6470, 6475)), ("d", SEATED, range(6475, 6480))]


def errors(result, truth: pd.DataFrame) -> tuple[float, float, np.ndarray]:
    """(final position error m, last walking step's heading error deg, the track's x / y)."""
    xy = result.trajectory[["x", "y"]].to_numpy(float)
    end = truth[["x", "y"]].to_numpy(float)[-1]
    walking = result.steps[result.steps["has_next"].to_numpy(bool)]
    diff = float(walking["heading_rad"].iloc[-1]) - float(truth["heading_rad"].iloc[-1])
    dh = np.degrees(np.angle(np.exp(1j * diff)))
    return float(np.hypot(*(xy[-1] - end))), float(dh), xy


def session(user: int, route: str, root: Path) -> dict:
    sim = root / f"s{user}"
    with contextlib.redirect_stdout(io.StringIO()):
        assert cli(["simulate", "--route", route, "--user-seed", str(user), "--out", str(sim)]) == 0
    s, truth = read_session(sim), pd.read_csv(sim / "trajectory.csv")
    rolls = pd.read_csv(sim / "rolls.csv") if (sim / "rolls.csv").exists() else pd.DataFrame()
    row = {"user": user, "rolls": len(rolls)}
    off = get_pipeline("waist-pendulum")(s, params={"options": {"lying_heading": False}})
    on = get_pipeline("waist-pendulum")(s, params={"options": {"lying_heading": True}})
    pll = get_pipeline("waist-pll")(s)
    row["off_m"], row["off_deg"], xy_off = errors(off, truth)
    row["on_m"], row["on_deg"], xy_on = errors(on, truth)
    row["pll_m"], row["pll_deg"], _ = errors(pll, truth)
    row["identical"] = xy_off.shape == xy_on.shape and bool(np.array_equal(xy_off, xy_on))
    return row


def main() -> int:
    logging.disable(logging.WARNING)
    print("# W269's `lying_heading` measured by W270's rule (`experiments/lying_heading.py`)\n")
    with tempfile.TemporaryDirectory() as tmp:
        for key, route, users in GROUPS:
            print(f"## ({key}) `{route}`, users {users.start}-{users.stop - 1}\n")
            print("| user | rolls | pendulum off: end error m / heading deg | pendulum on: m / deg | track identical | "
                  "waist-pll: m / deg |")
            print("|---|---|---|---|---|---|")
            rows = []
            for u in users:
                r = session(u, route, Path(tmp))
                rows.append(r)
                print(f"| {u} | {r['rolls']} | {r['off_m']:.2f} / {r['off_deg']:+.1f} | {r['on_m']:.2f} / "
                      f"{r['on_deg']:+.1f} | {'yes' if r['identical'] else 'no'} | {r['pll_m']:.2f} / "
                      f"{r['pll_deg']:+.1f} |", flush=True)
            t = pd.DataFrame(rows)
            worse = int((t["on_deg"].abs() - t["off_deg"].abs() > 5.0).sum())
            print(f"\nmedian end error off {t['off_m'].median():.2f} m, on {t['on_m'].median():.2f} m; median |heading "
                  f"error| off {t['off_deg'].abs().median():.1f} deg, on {t['on_deg'].abs().median():.1f} deg; "
                  f"sessions whose |heading error| rises by more than 5 deg: {worse}; tracks identical: "
                  f"{int(t['identical'].sum())} of {len(t)}; waist-pll median end error {t['pll_m'].median():.2f} m, "
                  f"median |heading error| {t['pll_deg'].abs().median():.1f} deg\n", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
