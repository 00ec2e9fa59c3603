"""Decision W549 (docs/decisions/waist.md): L95's fast line on an uncalibrated lower-back track says the distance is
probably short at a fast long-stride walk (race walking), measured once after the rule was committed.

Fresh simulated users 15840-15859 (session 48), each at four gaits on one route (``ROUTE``, 100 Hz, seed = user):
race walking (steps drawn per user: 0.90-1.05 m in 0.27-0.33 s, as trial T1's coach's walkers), normal (the user's
own), brisk (speed "fast") and shuffling (0.25-0.35 m steps in 0.28-0.38 s). Each tracked uncalibrated by
``waist-pendulum`` and ``waist-pll``. Per gait and pipeline: tracks, how many print L95's fast line, how many W549's
clause, and the distance errors of those with the clause. Then the real recordings (datasets/real,
datasets/external, ``pdrlearn track DIR``): how many print the clause.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/race_walk_s48_w549.py [--users 15840-15859] [--no-real]``
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import io
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.sim import UserProfile  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.sim.simulate import simulate_path  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402

ROUTE = "stand:3, straight:80, curve:180:15, straight:80, stand:3"
PIPELINES = ("waist-pendulum", "waist-pll")
MARK_L95 = "(decision L95)"
MARK = "decision W549"


def gait_session(u: int, gait: str):
    rng = np.random.default_rng(u)
    race = (rng.uniform(0.90, 1.05), rng.uniform(0.27, 0.33))
    shuffle = (rng.uniform(0.25, 0.35), rng.uniform(0.28, 0.38))
    profile, speed = UserProfile.from_seed(u), "normal"
    if gait == "race":
        profile = dataclasses.replace(profile, step_length_m=race[0], step_time_s=race[1])
    elif gait == "shuffle":
        profile = dataclasses.replace(profile, step_length_m=shuffle[0], step_time_s=shuffle[1])
    elif gait == "brisk":
        speed = "fast"
    return simulate_path(parse_route(ROUTE), profile, speed=speed, rate_hz=100, seed=u)


def lines(summary: dict) -> list[str]:
    return list((summary.get("info") or {}).get("warnings") or [])


def simulated(users: range) -> bool:
    print("| gait | pipeline | tracks | L95 fast line | W549 clause | distance error % of the clause's tracks |")
    print("|---|---|---|---|---|---|")
    res = {}
    for gait in ("race", "normal", "brisk", "shuffle"):
        sessions = [gait_session(u, gait) for u in users]
        for pipe in PIPELINES:
            n_l95, errs, n = 0, [], 0
            for s in sessions:
                with contextlib.redirect_stderr(io.StringIO()):
                    summ = get_pipeline(pipe)(s).summary(s)
                ws = lines(summ)
                n += 1
                n_l95 += any(MARK_L95 in w and "above" not in w.split(":")[0] for w in ws)
                if any(MARK in w for w in ws):
                    errs.append(float(summ.get("distance_error_pct") or np.nan))
            res[gait, pipe] = (n, len(errs), errs)
            shown = ", ".join(f"{e:+.2f}" for e in errs)
            print(f"| {gait} | {pipe} | {n} | {n_l95} | {len(errs)} | {shown} |", flush=True)
    race_ok = (res["race", "waist-pendulum"][1] >= 0.8 * res["race", "waist-pendulum"][0]
               and all(e <= -10.0 for e in res["race", "waist-pendulum"][2]))
    none_else = (all(res[g, p][1] == 0 for g in ("normal", "brisk") for p in PIPELINES)
                 and all(res[g, "waist-pll"][1] == 0 for g in ("race", "shuffle")))
    shuffle_long = all(e >= 10.0 for e in res["shuffle", "waist-pendulum"][2])
    for g in ("race", "shuffle"):
        e = res[g, "waist-pendulum"][2]
        if e:
            print(f"\n{g}, waist-pendulum, with the clause: {min(e):+.2f} to {max(e):+.2f} % distance")
    print(f"\n(1) race (waist-pendulum): clause on >= 80 % of the tracks, each <= -10 %: {race_ok}; "
          f"(2) no clause on normal / brisk (both pipelines) nor waist-pll: {none_else}; "
          f"(3) shuffling tracks with the clause each >= +10 %: {shuffle_long}")
    race_ok = race_ok and shuffle_long
    return race_ok and none_else


def real() -> bool:
    n, hit = 0, []
    for base in (ROOT / "datasets" / "real", ROOT / "datasets" / "external"):
        for d in sorted(p for p in base.iterdir() if (p / "meta.json").exists()):
            with tempfile.TemporaryDirectory() as tmp, contextlib.redirect_stdout(io.StringIO()) as out, \
                    contextlib.redirect_stderr(io.StringIO()):
                code = cli(["track", str(d), "--out", str(Path(tmp) / "o"), "--json"])
            n += 1
            if code == 0 and any(MARK in w for w in lines(json.loads(out.getvalue()))):
                hit.append(d.name)
    print(f"\n(4) real recordings: the clause on {len(hit)} of {n} ({', '.join(hit) or 'none'})")
    return not hit


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="15840-15859")
    ap.add_argument("--no-real", action="store_true")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    ok = simulated(range(lo, hi + 1))
    ok = (real() if not a.no_real else True) and ok
    print(f"\nW549 rule met: {ok}")


if __name__ == "__main__":
    main()
