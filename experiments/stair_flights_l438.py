"""Decisions L438 / L439: a stair flight needs 2 consecutive stair strides of one sign; measured on the real gaitmap
walks and on T3-style simulated stair routes of fresh users (8630-8639).

Real: each gaitmap session of ``datasets/real`` is tracked (no model); its flights (signed strides) and its 10 m walk
test are printed with ``min_strides`` 1 (the rule before L438) and 2. Simulated: each user walks each route of
:data:`ROUTES` (R3's routes; ``simulate --route``, no model) and its flights (direction and n_stairs =
round(|height| / rise)) are compared with the route's own; printed per route and setting, the users whose flights
match exactly and the extra flights.

    PYTHONPATH=$PWD python experiments/stair_flights_l438.py --out /tmp/l438
"""

from __future__ import annotations

import argparse
import contextlib
import io
from pathlib import Path

import pandas as pd

import pdrlearn.track.stair_flights as sf
from pdrlearn.cli import main
from pdrlearn.track.clinical import bout_rows
from pdrlearn.track.gait import stair_rows, stride_rows
from pdrlearn.track.walk_test import ten_metre_walk
from stair_flights_l433 import tracked_steps

REAL = ("gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left")
#: name -> (route, rise m, true flights as signed stair counts): review R3's routes
ROUTES = {
    "landturn": ("straight:4, up:10, turn:180, up:10, straight:4", 0.17, [10, 10]),
    "pause": ("straight:4, up:12, stand:3, up:12, straight:4", 0.17, [12, 12]),
    "descent": ("straight:4, down:15, straight:2, down:15, straight:4", 0.17, [-15, -15]),
    "odd": ("straight:4, up:9, straight:4, down:9, straight:3", 0.17, [9, -9]),
    "tallrise": ("straight:4, up:10:0.20:0.25, turn:90, up:10:0.20:0.25, straight:4", 0.20, [10, 10]),
}
SETTINGS = (1, 2)


def quiet(argv: list[str]) -> int:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main(argv)


def flights(steps: pd.DataFrame, rise: float, min_strides: int) -> list[tuple[int, int]]:
    """(signed n_stairs, n_strides) of each flight."""
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    dz = pd.to_numeric(st["dz_m"], errors="coerce").to_numpy(float)
    runs = sf.flight_runs(dz, stair_rows(st) & stride_rows(st), bout_rows(st), min_strides=min_strides)
    return [(sign * round(abs(float(dz[a:b].sum())) / rise), b - a) for a, b, sign in runs]


def real(out: Path, data: Path) -> None:
    for name in REAL:
        trk = out / f"real_{name}"
        if not trk.exists():
            quiet(["track", str(data / name), "--out", str(trk)])
        steps = pd.read_csv(trk / "steps.csv")
        for m in SETTINGS:
            saved, sf.MIN_FLIGHT_STRIDES = sf.MIN_FLIGHT_STRIDES, m
            try:
                walk = ten_metre_walk(steps)
            finally:
                sf.MIN_FLIGHT_STRIDES = saved
            got = flights(steps, 0.17, m)
            time = walk["ten_m_walk_time_s"]
            print(f"{name:26s} min_strides {m}: flights (stairs@0.17, strides) {got}; 10 m walk "
                  f"{'not timed' if time is None else f'{time:.2f} s'}")


def simulated(out: Path, users: list[int]) -> None:
    for name, (route, rise, truth) in ROUTES.items():
        res = {m: [0, 0] for m in SETTINGS}
        for u in users:
            steps = tracked_steps(out, name, route, u)
            for m in SETTINGS:
                got = [s for s, _ in flights(steps, rise, m)]
                res[m][0] += got == truth
                res[m][1] += max(len(got) - len(truth), 0)
                if got != truth:
                    print(f"  {name} u{u} min_strides {m}: {got} (truth {truth})")
        for m, (ok, extra) in res.items():
            print(f"{name:9s} min_strides {m}: exact {ok}/{len(users)} users, extra flights {extra}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--data", type=Path, default=Path("datasets/real"))
    ap.add_argument("--first-user", type=int, default=8630)
    ap.add_argument("--users", type=int, default=10)
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    real(a.out, a.data)
    simulated(a.out, list(range(a.first_user, a.first_user + a.users)))
