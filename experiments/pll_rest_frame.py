"""`waist-pll`'s harmonic heading across a rest over a minute, W285's `rest_frame` off (the default) and on: decision
W286's rule. Users 6504-6519 and 6560-6589 (session 32; 6500-6503 were looked at while writing W285). Run from the
repo root:

    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/pll_rest_frame.py > experiments/results/pll_rest_frame.md

Per simulated session: the final position error (m, the track's last position against trajectory.csv's last) and
the last walking step's heading error (deg, against trajectory.csv's last heading) of uncalibrated `waist-pll` (the
`ahe` heading) with the option off and on, and whether the two tracks are identical. Uncalibrated tracks (meta.json
defaults), the simulator's default rate."""

from __future__ import annotations

import contextlib
import io
import logging
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from lying_heading import errors  # noqa: E402 -- W270's end / heading errors (experiments/lying_heading.py)
from pdrlearn.cli import main as cli
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline

# W286's groups: (key, route, users, has a rest over 60 s)
GROUPS = [
    ("a", "stand:5, straight:10, sit:600, straight:10, stand:5", range(6504, 6512), True),  # sit, walk on
    ("b", "stand:5, straight:10, sit:600, turn:180, straight:10, stand:5", range(6512, 6520), True),  # sit, walk back
    ("c", "stand:5, straight:10, lie:600:30, turn:180, straight:10, stand:5", range(6560, 6570), True),  # lying
    ("d", "stand:5, straight:10, sit:1800, straight:10, stand:5", range(6570, 6575), True),  # half an hour seated
    ("e", "stand:120, straight:10, turn:90, straight:10, stand:5", range(6575, 6580), True),  # a long lead-in stand
    ("f", "stand:5, straight:10, turn:90, straight:10, stand:30, turn:180, straight:20, stand:5", range(6580, 6590),
     False),  # plain walks, no rest over 60 s
]


def session(user: int, route: str, root: Path) -> dict:
    sim = root / f"s{user}"
    with contextlib.redirect_stdout(io.StringIO()):
        assert cli(["simulate", "--route", route, "--user-seed", str(user), "--out", str(sim)]) == 0
    s, truth = read_session(sim), pd.read_csv(sim / "trajectory.csv")
    row = {"user": user}
    off = get_pipeline("waist-pll")(s, params={"options": {"rest_frame": False}})
    on = get_pipeline("waist-pll")(s, params={"options": {"rest_frame": True}})
    row["off_m"], row["off_deg"], xy_off = errors(off, truth)
    row["on_m"], row["on_deg"], xy_on = errors(on, truth)
    row["identical"] = xy_off.shape == xy_on.shape and bool(np.array_equal(xy_off, xy_on))
    return row


def summary(t: pd.DataFrame) -> str:
    worse = int((t["on_deg"].abs() - t["off_deg"].abs() > 5.0).sum())
    return (f"median end error off {t['off_m'].median():.2f} m, on {t['on_m'].median():.2f} m; median |heading error| "
            f"off {t['off_deg'].abs().median():.1f} deg, on {t['on_deg'].abs().median():.1f} deg; sessions whose "
            f"|heading error| rises by more than 5 deg: {worse}; tracks identical: {int(t['identical'].sum())} of "
            f"{len(t)}")


def main() -> int:
    logging.disable(logging.WARNING)
    print("# W285's `rest_frame` measured by W286's rule (`experiments/pll_rest_frame.py`)\n")
    rest_rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for key, route, users, rest in GROUPS:
            print(f"## ({key}) `{route}`, users {users.start}-{users.stop - 1}\n")
            print("| user | waist-pll off: end error m / heading deg | on: m / deg | track identical |")
            print("|---|---|---|---|")
            rows = []
            for u in users:
                r = session(u, route, Path(tmp))
                rows.append(r)
                print(f"| {u} | {r['off_m']:.2f} / {r['off_deg']:+.1f} | {r['on_m']:.2f} / {r['on_deg']:+.1f} | "
                      f"{'yes' if r['identical'] else 'no'} |", flush=True)
            t = pd.DataFrame(rows)
            if rest:
                rest_rows.append(t)
            print(f"\n{summary(t)}\n", flush=True)
    print(f"## pooled (a)-(e), the sessions with a rest over 60 s\n\n{summary(pd.concat(rest_rows))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
