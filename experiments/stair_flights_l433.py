"""Decision L433: stair flights split at landing strides, measured on fresh simulated users (8470-8479).

Each user walks each route of :data:`ROUTES` (``simulate --route``, its default 20 Hz, no model); the track's steps are
cut into flights (:func:`pdrlearn.track.stair_flights.flight_runs`) with L433's landing split and without it, and
the flights (direction and n_stairs = round(|height| / 0.17 m)) are compared with the route's own flights. Printed:
per route and mode, the users whose flights match exactly (count, directions, stairs), and the flights found where
the truth has none (false splits) over all users.

    PYTHONPATH=$PWD python experiments/stair_flights_l433.py --out /tmp/l433
"""

from __future__ import annotations

import argparse
import contextlib
import io
from pathlib import Path

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.clinical import bout_rows
from pdrlearn.track.gait import stair_rows, stride_rows
from pdrlearn.track.stair_flights import flight_runs

RISE = 0.17
#: decision L433's landing cut as measured (not adopted: the module's LANDING_GRADE_RATIO is None)
LANDING_GRADE_RATIO = 0.5
#: name -> (route, true flights as signed stair counts)
ROUTES = {
    "landing1.5": ("straight:3, up:10, straight:1.5, up:7, turn:180, down:7, straight:1.5, down:10, straight:3",
                   [10, 7, -7, -10]),
    "landing1.0": ("straight:3, up:9, straight:1.0, up:9, turn:180, down:9, straight:1.0, down:9, straight:3",
                   [9, 9, -9, -9]),
    "landing_turn": ("straight:3, up:12, turn:180, up:12, straight:2, turn:180, down:12, turn:180, down:12, "
                     "straight:3", [12, 12, -12, -12]),
    "no_landing": ("straight:3, up:14, turn:180, down:14, straight:3", [14, -14]),
    # the skipped stair is two rises in one step: 5 + 2 + 5 = 12 stairs of 0.17 m (the first run's table said 13, a
    # slip in writing the truth: every user read 12 with either mode)
    "skip": ("straight:3, up:5, up:1:0.34:0.58, up:5, turn:180, down:12, straight:3", [12, -12]),
}


def flights(steps: pd.DataFrame, ratio) -> list[int]:
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    dz = pd.to_numeric(st["dz_m"], errors="coerce").to_numpy(float)
    runs = flight_runs(dz, stair_rows(st) & stride_rows(st), bout_rows(st), st["length_m"].to_numpy(float), ratio)
    return [sign * round(abs(float(dz[a:b].sum())) / RISE) for a, b, sign in runs]


def tracked_steps(out: Path, name: str, route: str, u: int) -> pd.DataFrame:
    """User ``u`` walking ``route`` (simulated into ``out``, then tracked with no model; both kept for a rerun):
    the track's steps.csv (also :mod:`experiments.stair_flights_l438`'s)."""
    sim, trk = out / f"{name}_u{u}", out / f"{name}_u{u}_track"
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        if not sim.exists():
            assert main(["simulate", "--route", route, "-u", str(u), "-o", str(sim)]) == 0
        if not trk.exists():
            main(["track", str(sim), "--out", str(trk)])
    return pd.read_csv(trk / "steps.csv")


def run(out: Path, users: list[int]) -> None:
    for name, (route, truth) in ROUTES.items():
        res = {"L433": [0, 0], "off": [0, 0]}
        for u in users:
            steps = tracked_steps(out, name, route, u)
            for mode, ratio in (("L433", LANDING_GRADE_RATIO), ("off", None)):
                got = flights(steps, ratio)
                res[mode][0] += got == truth
                res[mode][1] += max(len(got) - len(truth), 0)
                if got != truth:
                    print(f"  {name} u{u} {mode}: {got} (truth {truth})")
        for mode, (ok, extra) in res.items():
            print(f"{name:13s} {mode:4s}: exact {ok}/{len(users)} users, extra flights {extra}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--first-user", type=int, default=8470)
    ap.add_argument("--users", type=int, default=10)
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    run(a.out, list(range(a.first_user, a.first_user + a.users)))
