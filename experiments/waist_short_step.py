"""Decisions W207 / W208 (session 29): do an uncalibrated lower-back track's short-step line (W207) and waist-pll's
missed-step / judged lines (W208) warn on slow shuffling walks read with |error| > 25 %, and stay silent on plain
normal walks and the real recordings? Run once after the rules in docs/decisions/waist.md were committed; nothing
tuned.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_short_step.py [--users 4900-4939]
Output: the printed lines (experiments/results/waist_short_step.txt)
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist

ROOT = Path(__file__).resolve().parents[1]
SLOW_ROUTE = "stand:3, straight:10, stand:3"
PLAIN_ROUTE = "stand:3, straight:14, stand:3"
#: (step length m, step time s): the trial's slow sweep (0.2, 0.3, 0.4 shuffle, 0.42 v040, 0.6, 0.8 m/s)
SLOW = ((0.15, 0.75), (0.2, 0.67), (0.2, 0.5), (0.25, 0.6), (0.3, 0.5), (0.4, 0.5))


def lines(warnings: list[str]) -> dict:
    return {"W207": any("decision W207" in w for w in warnings), "W100": any("decision W100" in w for w in warnings),
            "W208": any("decision W208" in w and "found" in w.split("(")[0] for w in warnings),
            "W139": any("decision W139" in w and "walk ratio" in w for w in warnings),
            "long": any(("W139" in w or "W208" in w) and ("reads long" in w or "longer than" in w) for w in warnings)}


def judge(session, true_m: float | None) -> dict:
    out = {}
    for pipe in ("waist-pendulum", "waist-pll"):
        r = track_waist(session, pipeline=pipe)
        d = float(r.steps["length_m"].abs().sum())
        out[pipe] = {"n": len(r.steps), "err": None if true_m is None else 100.0 * (d / true_m - 1.0),
                     **lines(r.info["warnings"])}
    return out


def show(tag: str, j: dict) -> str:
    p, q = j["waist-pendulum"], j["waist-pll"]

    def e(x):
        return "n/a" if x is None else f"{x:+.1f} %"

    def flags(x):
        return ",".join(k for k in ("W207", "W100", "W208", "W139", "long") if x[k]) or "-"
    return (f"{tag}: pendulum {e(p['err'])} n={p['n']} [{flags(p)}] | pll {e(q['err'])} n={q['n']} [{flags(q)}]")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="4900-4939")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    res: dict[str, list] = {"a": [], "b": [], "c": [], "slowhealthy": [], "const": []}
    for base in (ROOT / "datasets" / "external", Path("/work/shared/data")):
        for d in sorted(base.glob("mobgap_*")):
            j = judge(read_session(d), None)
            res["c"].append(j)
            print(show(f"c real {base.name}/{d.name}", j), flush=True)
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        for sl, st in SLOW:
            s = simulate_path(parse_route(SLOW_ROUTE), dataclasses.replace(user, step_length_m=sl, step_time_s=st),
                              speed="normal", rate_hz=100, seed=u, bounce="pendulum")
            j = judge(s, float(s.meta["distance_m"]))
            res["a"].append((f"{sl}/{st}", j))
            print(show(f"a user {u} {sl}/{st}", j), flush=True)
        bounce = "constant" if u % 2 == 0 else "pendulum"
        s = simulate_path(parse_route(PLAIN_ROUTE), user, speed="normal", rate_hz=100, seed=u, bounce=bounce)
        j = judge(s, float(s.meta["distance_m"]))
        res["b"].append(j)
        print(show(f"b user {u} normal {bounce}", j), flush=True)
    for u in range(lo, hi + 1):  # information
        user = UserProfile.from_seed(u)
        s = simulate_path(parse_route(PLAIN_ROUTE), user, speed="slow", rate_hz=100, seed=u, bounce="pendulum")
        j = judge(s, float(s.meta["distance_m"]))
        res["slowhealthy"].append(j)
        print(show(f"info user {u} slow pendulum", j), flush=True)
        s = simulate_path(parse_route(SLOW_ROUTE), dataclasses.replace(user, step_length_m=0.15, step_time_s=0.75),
                          speed="normal", rate_hz=100, seed=u, bounce="constant")
        j = judge(s, float(s.meta["distance_m"]))
        res["const"].append(j)
        print(show(f"info user {u} 0.15/0.75 constant", j), flush=True)
    print()
    for pipe, key in (("waist-pendulum", "W207"), ("waist-pll", "W208")):
        big = [j[pipe] for _, j in res["a"] if abs(j[pipe]["err"]) > 25.0]
        if pipe == "waist-pendulum":
            warned = sum(x["W207"] or x["W100"] for x in big)
            normal = sum(j[pipe]["W207"] for j in res["b"])
            real = sum(j[pipe]["W207"] for j in res["c"])
        else:
            warned = sum(x["W207"] or x["W208"] or x["W139"] for x in big)
            normal = sum(j[pipe]["W207"] or j[pipe]["W208"] or j[pipe]["W139"] for j in res["b"])
            real = sum(j[pipe]["W207"] or j[pipe]["W208"] for j in res["c"])
        print(f"{key} ({pipe}): (a) |error| > 25 %: {len(big)}; warned {warned} "
              f"({100.0 * warned / max(len(big), 1):.1f} %); (b) normal walks warned {normal} of {len(res['b'])}; "
              f"(c) real warned {real} of {len(res['c'])}")
        if pipe == "waist-pll":
            short_long = sum(1 for _, j in res["a"] if j[pipe]["err"] < 0 and j[pipe]["long"])
            print(f"W208 (d) slow walks read short whose line says long: {short_long}")
        for sl, st in SLOW:
            rows = [j[pipe] for name, j in res["a"] if name == f"{sl}/{st}"]
            errs = [x["err"] for x in rows]
            w = sum(x["W207"] or x["W100"] or x["W208"] or x["W139"] for x in rows)
            print(f"  {pipe} {sl}/{st}: warned {w} of {len(rows)}, error {min(errs):+.1f} to {max(errs):+.1f} %")
        for name in ("slowhealthy", "const"):
            rows = [j[pipe] for j in res[name]]
            w = sum(x["W207"] or x["W208"] or x["W139"] or x["W100"] for x in rows)
            errs = [x["err"] for x in rows]
            print(f"  info {pipe} {name}: warned {w} of {len(rows)}, error {min(errs):+.1f} to {max(errs):+.1f} %")


if __name__ == "__main__":
    main()
