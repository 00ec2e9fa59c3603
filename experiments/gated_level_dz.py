"""Decision L184's measurement: offline M3 with L39's level rule on the strides whose terrain class the 0.95 gate
(L18) dropped, against today's raw integrated height, on the same per-user models.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/gated_level_dz.py            # the rule's users (L184)
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/gated_level_dz.py --fresh 3070 3071 --thesis-users 1

Each user's model is trained as experiments/localization.py trains it (``train_model``); fresh users walk scenario
D, the thesis users (1-5 in localization.py) scenarios A-D, each at slow/normal/fast. Writes
experiments/results/gated_level_dz.csv and prints the rule's three figures.
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.track.plasys as plasys
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track

ROOT = Path(__file__).resolve().parents[1]
SPEEDS = ("slow", "normal", "fast")


def _localization():
    spec = importlib.util.spec_from_file_location("localization", ROOT / "experiments" / "localization.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def measure(user: int, scenarios: tuple[str, ...], group: str, loc) -> list[dict]:
    sim = partial(simulate, device_errors=True)  # as localization.run_sim
    model, _ = loc.train_model(sim, user, False)
    rows = []
    for scen in scenarios:
        for speed in SPEEDS:
            s = sim(scen, user_seed=user, speed=speed)
            for flag in (False, True):
                plasys.GATED_LEVEL_DZ = flag
                ev = evaluate_track(plasys.track_plasys(s, method="M3", model=model), s)
                rows.append({"group": group, "user": user, "scenario": scen, "speed": speed, "candidate": flag,
                             "distance_error_pct": ev["distance_error_pct"],
                             "altitude_error_pct": ev.get("altitude_error_pct", np.nan),
                             "altitude_change_m": ev["altitude_change_m"]})
    return rows


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fresh", type=int, nargs="*", default=list(range(3070, 3100)))
    ap.add_argument("--thesis-users", type=int, default=5)
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "gated_level_dz.csv")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    loc = _localization()
    rows = []
    for u in a.fresh:
        rows += measure(u, ("D",), "fresh", loc)
        print(f"user {u} done", flush=True)
    for u in range(1, a.thesis_users + 1):
        rows += measure(u, ("A", "B", "C", "D"), "thesis", loc)
        print(f"user {u} done", flush=True)
    df = pd.DataFrame(rows)
    df.to_csv(a.out, index=False)
    df["abs_dist"] = df["distance_error_pct"].abs()
    fr = df[df["group"] == "fresh"]
    for flag, tag in ((False, "today"), (True, "candidate")):
        d = fr[fr["candidate"] == flag]
        print(f"fresh D {tag}: runs {len(d)}, median altitude error {d['altitude_error_pct'].median():.2f} %, "
              f"mean {d['altitude_error_pct'].mean():.2f} %, mean |distance error| {d['abs_dist'].mean():.2f} %")
    th = df[df["group"] == "thesis"]
    if len(th):
        m = th.groupby(["scenario", "candidate"])["abs_dist"].mean().unstack()
        alt = th[th["scenario"] == "D"].groupby("candidate")["altitude_error_pct"].mean()
        print("thesis users A-D mean |distance error| % today -> candidate: " + ", ".join(
            f"{sc} {r[False]:.2f} -> {r[True]:.2f} ({r[True] - r[False]:+.3f})" for sc, r in m.iterrows()))
        print(f"thesis users D mean altitude error % today -> candidate: {alt[False]:.2f} -> {alt[True]:.2f}")


if __name__ == "__main__":
    main()
