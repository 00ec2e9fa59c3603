"""Decision C191 (docs/decisions/classifiers.md): a stride whose measured length contradicts its length class.

For each fresh simulated user (default 14420-14439): the calibration exercises terrain, direction and length (seed
0) train a model (``train_user`` defaults, seed 0); the trial T2 route is walked at the user's own gait ("normal"),
at 0.68 s steps with the user's step length ("slow") and at 0.68 s steps of 0.6 m ("waltz"), seed 1, and tracked
with ``track --method M3 --model`` with C191's margin rule off (``CONTRADICTION_MARGIN`` inf) and on. Per walk: the
length-class agreement (truth: ``ref_length_m`` against the session's ``length_class_bounds_m``) and the direction
agreement. Writes experiments/results/length_contradiction_c191.csv (one row per user, tempo and rule).

    PYTHONPATH=. .venv/bin/python experiments/length_contradiction_c191.py [--users 14420 ... 14439]
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.classify import train_user
from pdrlearn.kernels import turn_length
from pdrlearn.sim import simulate
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import SPEED_FACTORS, UserProfile
from pdrlearn.track import plasys
from pdrlearn.track.evaluate import with_reference_columns
from pdrlearn.track.turn_classes import measured_length_class

OUT = Path(__file__).parent / "results"
#: trial T2 finding F2's route (straight, backward, a turn, a side step)
ROUTE = ("stand:3, straight:3, backward:6, straight:3, backward:8, turn:180, backward:6, straight:3, side:1, "
         "backward:4, stand:3")
#: tempo -> (step time s, step length m or None for the user's own); None: the user's own gait
TEMPI = {"normal": (None, None), "slow": (0.68, None), "waltz": (0.68, 0.6)}


def walker(user: UserProfile, step_time, step_length) -> UserProfile:
    """The user walking ``step_time`` / ``step_length`` at normal speed, length classes the user's (S30, S81)."""
    f_len, f_time = SPEED_FACTORS["normal"]
    changes = {}
    if step_length is not None:
        changes.update(step_length_m=step_length / f_len, class_step_length_m=user.step_length_m)
    if step_time is not None:
        changes["step_time_s"] = step_time / f_time
    return dataclasses.replace(user, **changes) if changes else user


@contextmanager
def margin(value: float):
    before, turn_length.CONTRADICTION_MARGIN = turn_length.CONTRADICTION_MARGIN, value
    try:
        yield
    finally:
        turn_length.CONTRADICTION_MARGIN = before


def rows_of(u: int, model) -> list[dict]:
    rows = []
    user = UserProfile.from_seed(u)
    for tempo, (t, length) in TEMPI.items():
        s = simulate_path(parse_route(ROUTE), walker(user, t, length), seed=1)
        lo, hi = s.meta["length_class_bounds_m"]
        bounds = {"short": (0.0, lo), "normal": (lo, hi), "long": (hi, 10.0)}
        for on in (False, True):
            with margin(turn_length.CONTRADICTION_MARGIN if on else np.inf):
                res = plasys.track_plasys(s, method="M3", model=model)
            info = res.summary(s)
            st = with_reference_columns(res, s)
            ok = st["ref_length_m"].notna().to_numpy() if "ref_length_m" in st else np.zeros(len(st), bool)
            truth = measured_length_class(st["ref_length_m"].to_numpy(float), bounds)
            cls = st["length_class"].to_numpy(dtype=object)
            rows.append({"user": u, "tempo": tempo, "rule": on, "n": int(ok.sum()),
                         "agree": int(((cls == truth) & ok).sum()),
                         "direction_agreement": info.get("direction_agreement")})
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", type=int, nargs="+", default=list(range(14420, 14440)))
    ap.add_argument("--out", type=Path, default=OUT / "length_contradiction_c191.csv")
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    for u in a.users:
        model = train_user([simulate(ex, user_seed=u, seed=0) for ex in ("terrain", "direction", "length")], seed=0)
        df = pd.DataFrame(rows_of(u, model))
        df.to_csv(a.out, mode="a", header=not a.out.exists(), index=False)
        print(df.to_string(index=False), flush=True)
    df = pd.read_csv(a.out)
    g = df.groupby(["tempo", "rule"])
    print((g["agree"].sum() / g["n"].sum()).rename("length_agreement").to_string())
    print(g["direction_agreement"].mean().to_string())


if __name__ == "__main__":
    main()
