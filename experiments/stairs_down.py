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

Decision L63 (walks whose descents do not retrace; ``--routes`` R1,R2,R3 of :data:`ROUTES`, simulated as the
``simulate`` command's ``--route`` option does; two modes compared walk by walk with medians and counts of walks
made worse; ``--runtime N``: ``pdrlearn run`` with a bundle exported per mode for the first N users)::

    PYTHONPATH=$PWD python experiments/stairs_down.py --first-user 21 --routes R1,R2,R3 \
        --down-mode norm3,projected --model-cache CACHE --sim-cache SIMS --runtime 3
    PYTHONPATH=$PWD python experiments/stairs_down.py --first-user 1 --users 5 --scenarios A,B,C,D \
        --down-mode norm3,projected --model-cache CACHE --sim-cache SIMS

Decision L178 (session 26; users 2940-2969, quick models; stair routes R1,R2,R3,D34,F2 and the level route LV)::

    PYTHONPATH=$PWD python experiments/stairs_down.py --first-user 2940 --users 30 --quick \
        --routes R1,R2,R3,D34,F2,LV --down-mode norm3,projected --model-cache CACHE --sim-cache SIMS --runtime 3
    PYTHONPATH=$PWD python experiments/stairs_down.py --first-user 1 --users 5 --quick --scenarios A,B,C,D \
        --down-mode norm3,projected --model-cache CACHE --sim-cache SIMS
"""

from __future__ import annotations

import argparse
import logging
import math
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

from localization import train_model
from pdrlearn.track.evaluate import evaluate_track, match_by_overlap
from pdrlearn.track.plasys import track_plasys


def descending_walk(user: int):
    """Level walk, 12 stairs down, a turn on the landing, 12 stairs down, level walk (seed 5)."""
    from pdrlearn.sim import Stairs, Straight, Turn, UserProfile, simulate_path

    path = [Straight(6.0), Stairs(12, up=False), Turn(math.pi), Stairs(12, up=False), Straight(6.0)]
    return simulate_path(path, UserProfile.from_seed(user), speed="normal", rate_hz=20, seed=5,
                         name=f"stairs_down_u{user}", device_errors=True)


#: decision L63: routes whose descents do not retrace (``pdrlearn simulate --route``, decision S28)
ROUTES = {
    "R1": "straight:5, down:17, straight:5, turn:90, down:17, straight:3",  # two flights at right angles
    "R2": "straight:4, down:12, straight:2, down:12, straight:4",  # two flights in one direction
    "R3": "straight:3, up:12, turn:90, straight:3, down:12, straight:3",  # up, then down at right angles
    # decision L178 (session 26 trial `building`, finding 1): the trial's descent and its two storeys up and down
    "D34": "straight:4, down:34, straight:4",
    "F2": "straight:10, up:17, turn:180, up:17, turn:180, straight:10, turn:180, down:17, turn:180, down:17, "
          "straight:5",
    # decision L178: a level walk (no stair), straight, a right-angle turn, a curve and a U-turn
    "LV": "straight:10, turn:90, straight:10, curve:-90:1, straight:10, turn:180, straight:10",
}
#: decision L178: the level routes, judged walk by walk and kept out of the stair walks' pooled medians
LEVEL_ROUTES = ("LV",)
#: decision L63: a walk is "worse" with a candidate when an error rises by more than this
WORSE_BY = {"final_position_error_m": 0.02, "final_position_error_3d_m": 0.02, "abs_distance_error_pct": 0.05}


def route_walk(route: str, user: int):
    """The walk ``simulate``'s ``--route`` option makes of ``ROUTES[route]`` for ``--user-seed`` ``user``
    (normal speed, seed 0, 20 Hz)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route(ROUTES[route]), UserProfile.from_seed(user), speed="normal", rate_hz=20.0,
                         seed=0, name=f"route_u{user}_normal_s0", scenario="route")


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


def _row(res, s, ev) -> dict:
    de, nd = down_error(res, s)
    last = res.trajectory.iloc[-1] if len(res.trajectory) else None
    return {"down_len_err_m": de, "n_down": nd,
            "distance_error_pct": ev.get("distance_error_pct", np.nan),
            "final_position_error_m": ev.get("final_position_error_m", np.nan),
            "final_position_error_3d_m": ev.get("final_position_error_3d_m", np.nan),
            "altitude_change_m": ev.get("altitude_change_m", np.nan),
            "altitude_change_ref_m": ev.get("altitude_change_ref_m", np.nan),
            "x": float(last["x"]) if last is not None else np.nan,
            "y": float(last["y"]) if last is not None else np.nan}


def runtime_run(model, session_dir: Path, bundle_dir: Path, down_mode: str) -> dict:
    """``pdrlearn run BUNDLE SESSION --json`` (in-process, the CLI's defaults) with a bundle exported with
    ``down_mode``."""
    import json

    from typer.testing import CliRunner

    from pdrlearn.cli import app
    from pdrlearn.export import export_model

    if not bundle_dir.exists():
        export_model(None, bundle_dir, model=model, displacement={"down_mode": down_mode})
    r = CliRunner().invoke(app, ["run", str(bundle_dir), str(session_dir), "--json"])
    if r.exit_code != 0:
        raise RuntimeError(f"pdrlearn run {bundle_dir} {session_dir}: exit {r.exit_code}: {r.output[-500:]}")
    out = r.stdout
    return json.loads(out[out.index("{"):])


def run(users: list[int], scenarios: list[str] | None, cache: Path | None, sim_cache: Path | None,
        down_mode: str = "norm3", routes: list[str] | None = None, runtime_users: int = 0,
        quick: bool = False) -> pd.DataFrame:
    from pdrlearn.sim import simulate

    sim = partial(simulate, device_errors=True)  # decision S22, as experiments/localization.py
    modes = down_mode.split(",")
    rows = []
    for k, user in enumerate(users):
        model, _ = train_model(sim, user, quick, cache, ("slow", "normal", "fast"))
        if scenarios:
            walks = {s: _cached(sim_cache, f"{s}_u{user}", partial(sim, s, user_seed=user, speed="normal"))
                     for s in scenarios}
            runs = {"offline": dict(model=model)}
        else:
            if routes:
                walks = {r: _cached(sim_cache, f"{r}_u{user}", partial(route_walk, r, user)) for r in routes}
            else:
                walks = {"down": _cached(sim_cache, f"down_u{user}", partial(descending_walk, user))}
            runs = {"offline": dict(model=model), "streaming": dict(model=model, streaming=True),
                    "oracle": dict(model="oracle")}
        for scen, s in walks.items():
            for mode in modes:
                for name, kw in runs.items():
                    res = track_plasys(s, method="M3", down_mode=mode, **kw)
                    rows.append({"user": user, "scenario": scen, "run": name, "mode": mode,
                                 **_row(res, s, evaluate_track(res, s))})
                if k < runtime_users and sim_cache is not None and not scenarios:
                    summ = runtime_run(model, sim_cache / f"{scen}_u{user}", sim_cache / f"bundle_u{user}_{mode}", mode)
                    fp = summ["final_position"]
                    rows.append({"user": user, "scenario": scen, "run": "run", "mode": mode,
                                 "distance_error_pct": summ.get("distance_error_pct", np.nan),
                                 "final_position_error_m": summ.get("final_position_error_m", np.nan),
                                 "final_position_error_3d_m": summ.get("final_position_error_3d_m", np.nan),
                                 "x": fp["x"], "y": fp["y"]})
    return pd.DataFrame(rows)


def compare(df: pd.DataFrame, base: str, cand: str) -> str:
    """Decision L63: per run and error, the medians of both modes and how many walks the candidate made worse."""
    df = df.assign(abs_distance_error_pct=df["distance_error_pct"].abs())
    key = ["user", "scenario", "run"]
    a = df[df["mode"] == base].set_index(key)
    b = df[df["mode"] == cand].set_index(key)
    lines = [f"| run | error | median {base} | median {cand} | walks worse (> tolerance) | walks |",
             "|---|---|---|---|---|---|"]
    stairs = ~a.index.get_level_values("scenario").isin(LEVEL_ROUTES)  # decision L178: stair walks pooled
    if not stairs.all():
        lines.insert(0, f"stair walks (routes other than {', '.join(LEVEL_ROUTES)}):")
    for r in dict.fromkeys(df["run"]):
        ia = a[stairs].xs(r, level="run")
        ib = b.xs(r, level="run").loc[ia.index]
        for col, tol in WORSE_BY.items():
            worse = int(((ib[col] - ia[col]) > tol).sum())
            lines.append(f"| {r} | {col} | {ia[col].median():.4f} | {ib[col].median():.4f} | {worse} | {len(ia)} |")
    if (a.index.get_level_values("run") == "run").any():
        for mode, d in ((base, a), (cand, b)):
            rr = d.xs("run", level="run")
            st = d.xs("streaming", level="run").loc[rr.index]
            gap = float(np.hypot(rr["x"] - st["x"], rr["y"] - st["y"]).max())
            lines.append(f"{mode}: run vs streaming=True, largest final position difference {gap:.2e} m "
                         f"({len(rr)} walks)")
    if df["scenario"].nunique() > 1:  # decision L178: per route too
        lines += ["", "| route | run | error | median " + base + " | median " + cand + " | walks worse | walks |",
                  "|---|---|---|---|---|---|---|"]
        for (scen, r), ia in a.groupby(level=["scenario", "run"], sort=False):
            ib = b.loc[ia.index]
            for col, tol in WORSE_BY.items():
                worse = int(((ib[col] - ia[col]) > tol).sum())
                lines.append(f"| {scen} | {r} | {col} | {ia[col].median():.4f} | {ib[col].median():.4f} | {worse} "
                             f"| {len(ia)} |")
    return "\n".join(lines)


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
    p.add_argument("--down-mode", default="norm3", help="norm3 (default), projected (decision L51) or horizontal; "
                   "two, comma-separated, are compared walk by walk (decision L63)")
    p.add_argument("--routes", default="", help="routes of ROUTES instead of the descending walk, e.g. R1,R2,R3 (L63)")
    p.add_argument("--runtime", type=int, default=0, help="also `pdrlearn run` the first N users' walks (needs "
                   "--sim-cache; decision L63)")
    p.add_argument("--csv", type=Path, default=None)
    p.add_argument("--quick", action="store_true", help="train SVM only with 3-fold CV (experiments/localization.py's "
                   "--quick; decision L178)")
    a = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    users = list(range(a.first_user, a.first_user + a.users))
    df = run(users, [s for s in a.scenarios.split(",") if s], a.model_cache, a.sim_cache, a.down_mode,
             [r for r in a.routes.split(",") if r], a.runtime, a.quick)
    if a.csv is not None:
        df.to_csv(a.csv, index=False)
    for mode in a.down_mode.split(","):
        print(f"down_mode {mode}")
        print(table(df[df["mode"] == mode]))
    if len(a.down_mode.split(",")) == 2:
        print(compare(df, *a.down_mode.split(",")))


if __name__ == "__main__":
    main()
