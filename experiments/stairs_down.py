"""Descending stairs: horizontal length of the down strides and whole-walk errors (decision L51).

For held-out simulated users (default 11-20; each user's classifiers trained on their own calibration
exercises at three speeds, as ``experiments/streaming_rules.py`` does, with its model cache) a walk with two
flights of 12 stairs down (a landing turn between, level walks before and after) is tracked with M3 and the
user's model offline and ``streaming=True``, and with the session's labels (oracle). Printed per run: the
mean |horizontal length error| of the strides labelled down (tracked strides matched to the labelled ones by
time overlap), the mean |whole-walk distance error| % and the mean final position error (m, horizontal).
``--scenarios A,B,C,D`` instead tracks those README scenarios (M3 offline with the model) and prints the
mean |distance error| % and final position error per scenario.

    PYTHONPATH=$PWD python experiments/stairs_down.py --model-cache /tmp/x/loccache            # L51
    PYTHONPATH=$PWD python experiments/stairs_down.py --model-cache /tmp/x/loccache --down-mode projected
    PYTHONPATH=$PWD python experiments/stairs_down.py --model-cache /tmp/x/loccache --users 3 --scenarios A,B,C,D

``--down-mode projected`` applies decision L51's option (default: the thesis norm); ``--sim-cache`` keeps the
simulated walks so both runs track the same data.
"""

from __future__ import annotations

import argparse
import logging
import math
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

from experiments.localization import train_model
from pdrlearn.track.evaluate import evaluate_track, match_by_overlap
from pdrlearn.track.plasys import track_plasys


def descending_walk(user: int):
    """Level walk, 12 stairs down, a turn on the landing, 12 stairs down, level walk (seed 5)."""
    from pdrlearn.sim import Stairs, Straight, Turn, UserProfile, simulate_path

    path = [Straight(6.0), Stairs(12, up=False), Turn(math.pi), Stairs(12, up=False), Straight(6.0)]
    return simulate_path(path, UserProfile.from_seed(user), speed="normal", rate_hz=20, seed=5,
                         name=f"stairs_down_u{user}", device_errors=True)


def _cached(cache: Path | None, name: str, make):
    from pdrlearn.io import read_session, write_session

    if cache is None:
        return make()
    d = cache / name
    if not d.exists():
        write_session(make(), d)
    return read_session(d)


def down_error(res, session) -> tuple[float, int]:
    """Mean |horizontal length error| (m) of the tracked strides matched to strides labelled down."""
    lab = session.steps.reset_index(drop=True)
    st = res.steps
    err = [abs(abs(float(st["length_m"].iloc[i])) - abs(float(lab["length_m"].iloc[j])))
           for i, j in match_by_overlap(st, lab, min_iou=0.3) if lab["terrain"].iloc[j] == "down"]
    return (float(np.mean(err)) if err else float("nan")), len(err)


def run(users: list[int], scenarios: list[str] | None, cache: Path | None, sim_cache: Path | None,
        down_mode: str = "norm3") -> pd.DataFrame:
    from pdrlearn.sim import simulate

    sim = partial(simulate, device_errors=True)  # decision S22, as experiments/localization.py
    rows = []
    for user in users:
        model, _ = train_model(sim, user, False, cache, ("slow", "normal", "fast"))
        if scenarios:
            walks = {s: _cached(sim_cache, f"{s}_u{user}", partial(sim, s, user_seed=user, speed="normal"))
                     for s in scenarios}
            runs = {"offline": dict(model=model)}
        else:
            walks = {"down": _cached(sim_cache, f"down_u{user}", partial(descending_walk, user))}
            runs = {"offline": dict(model=model), "streaming": dict(model=model, streaming=True),
                    "oracle": dict(model="oracle")}
        for scen, s in walks.items():
            for name, kw in runs.items():
                res = track_plasys(s, method="M3", down_mode=down_mode, **kw)
                ev = evaluate_track(res, s)
                de, nd = down_error(res, s)
                rows.append({"user": user, "scenario": scen, "run": name, "down_len_err_m": de, "n_down": nd,
                             "distance_error_pct": ev.get("distance_error_pct", np.nan),
                             "final_position_error_m": ev.get("final_position_error_m", np.nan),
                             "altitude_change_m": ev.get("altitude_change_m", np.nan),
                             "altitude_change_ref_m": ev.get("altitude_change_ref_m", np.nan)})
    return pd.DataFrame(rows)


def table(df: pd.DataFrame) -> str:
    g = df.assign(d=df["distance_error_pct"].abs(), s=df["distance_error_pct"])
    g = g.groupby(["scenario", "run"], sort=False).agg(
        down=("down_len_err_m", "mean"), n_down=("n_down", "sum"), d=("d", "mean"), s=("s", "mean"),
        f=("final_position_error_m", "mean"), walks=("user", "size"))
    lines = ["| walk | run | down strides | mean abs down-stride horizontal error m | mean abs distance error % | "
             "signed % | mean final position error m | walks |", "|---|---|---|---|---|---|---|---|"]
    for (scen, r), row in g.iterrows():
        lines.append(f"| {scen} | {r} | {int(row['n_down'])} | {row['down']:.4f} | {row['d']:.2f} | {row['s']:+.2f} "
                     f"| {row['f']:.3f} | {int(row['walks'])} |")
    lines += ["", f"users {sorted(df['user'].unique().tolist())}"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--first-user", type=int, default=11, help="first simulated user (held out: 11-20)")
    p.add_argument("--users", type=int, default=10)
    p.add_argument("--scenarios", default="", help="README scenarios instead of the descending walk, e.g. A,B,C,D")
    p.add_argument("--model-cache", type=Path, default=None)
    p.add_argument("--sim-cache", type=Path, default=None, help="folder caching the simulated sessions")
    p.add_argument("--down-mode", default="norm3", help="norm3 (default), projected (decision L51) or horizontal")
    p.add_argument("--csv", type=Path, default=None)
    a = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    users = list(range(a.first_user, a.first_user + a.users))
    df = run(users, [s for s in a.scenarios.split(",") if s], a.model_cache, a.sim_cache, a.down_mode)
    print(f"down_mode {a.down_mode}")
    if a.csv is not None:
        df.to_csv(a.csv, index=False)
    print(table(df))


if __name__ == "__main__":
    main()
