"""Decision L304: L39's level threshold on the mean |dz| of a run of same-sign strides (``level_dz(run_mean=True)``),
judged by L304's adoption rule (docs/decisions/localization.md) on fresh simulated users and the real gaitmap walks.

Each session is tracked once (``track`` without a model, offline) with L39 off (``experiments/level_dz.raw_track``);
the current rule (L39 alone) and the candidate are applied to the same raw per-stride heights, and the floors counted
per climb (L127) on each.

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/run_mean_level_l304.py
    PYTHONPATH=. .venv/bin/python experiments/run_mean_level_l304.py --users 5780-5781 --no-real   # a quick look
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from level_dz import LEVEL, STAIRS, folder, raw_track  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.kernels.distance import level_dz  # noqa: E402
from pdrlearn.sim import UserProfile, simulate, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.evaluate import count_floors_by_climb  # noqa: E402

# trial s30 "ramp", route R12 (closed 1:12 loop, 3 x 9 m runs up and down; truth net 0, 2.25 m each way)
R12 = ("stand:3, straight:5, slope:9:8.33, straight:1.5, slope:9:8.33, straight:1.5, slope:9:8.33, straight:5, "
       "turn:180, straight:5, slope:9:-8.33, straight:1.5, slope:9:-8.33, straight:1.5, slope:9:-8.33, straight:5, "
       "stand:3")
UP = "stand:3, straight:5, up:17, straight:5, stand:3"
DOWN = "stand:3, straight:5, down:17, straight:5, stand:3"
HILL = "stand:3, straight:5, slope:60:{g}, straight:5, turn:180, slope:60:-{g}, straight:5, stand:3"  # L144 (a)


def variants(raw: np.ndarray) -> dict:
    out = {}
    for key, run_mean in (("now", False), ("cand", True)):
        dz = level_dz(raw, run_mean=run_mean)
        up, down, _ = count_floors_by_climb(dz)
        out[key] = {"net": float(dz.sum()), "floors": (up, down)}
    return out


def users(text: str) -> list[int]:
    a, _, b = text.partition("-")
    return list(range(int(a), int(b or a) + 1))


def sim(route: str, u: int) -> dict:
    s = simulate_path(parse_route(route), UserProfile.from_seed(u), seed=u)
    return variants(raw_track(s, {}).steps["dz_m"].to_numpy(float))


def line(tag: str, v: dict) -> None:
    print(f"{tag}: " + "; ".join(f"{k} net {r['net']:+.3f} floors {r['floors']}" for k, r in v.items()), flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="5780-5799")
    ap.add_argument("--no-real", action="store_true")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    us = users(a.users)
    res = {k: [] for k in ("r12", "up", "down", "level", "hill")}
    for u in us:
        g = 3 + (u - us[0]) % 13
        for key, route in (("r12", R12), ("up", UP), ("down", DOWN), ("hill", HILL.format(g=g))):
            v = sim(route, u)
            res[key].append(v)
            line(f"{key} u{u}" + (f" {g}%" if key == "hill" else ""), v)
        v = variants(raw_track(simulate("A", u, seed=u), {}).steps["dz_m"].to_numpy(float))
        res["level"].append(v)
        line(f"level A u{u}", v)
    for key in ("r12", "hill"):
        for k in ("now", "cand"):
            print(f"{key} {k}: median |net| {np.median([abs(v[k]['net']) for v in res[key]]):.3f} m, "
                  f"floors {[v[k]['floors'] for v in res[key]]}")
    for key in ("up", "down"):
        same = sum(v["cand"]["floors"] == v["now"]["floors"] for v in res[key])
        dnet = max(abs(v["cand"]["net"] - v["now"]["net"]) for v in res[key])
        print(f"stairs {key}: floors as now {same}/{len(res[key])}, largest |cand - now| net {dnet:.3f} m")
    fl = sum(v["cand"]["floors"] != (0, 0) for v in res["level"])
    worse = max(abs(v["cand"]["net"]) - abs(v["now"]["net"]) for v in res["level"])
    print(f"level A: tracks with a floor (cand) {fl}, largest |net| increase {worse:+.3f} m")
    if a.no_real:
        return
    for name in LEVEL + STAIRS:
        d = folder(name)
        if d is None:
            print(f"{name}: not found")
            continue
        line(f"real {name}", variants(raw_track(read_session(d), {}).steps["dz_m"].to_numpy(float)))


if __name__ == "__main__":
    main()
