"""Decisions C38/C39: the length task chosen among the soft votes (foot/waist/fused) vs the default (C23, combined).

Fresh simulated users, each user's model trained as ``pdrlearn train`` does by default (``train_user``
defaults) on the three calibration exercises at normal speed (C38) or at the speeds of ``--cal-speeds``
(C39: slow,normal,fast, as experiments/localization.py's command line), then M3 (default rules) tracks
scenarios A-D at the speeds of ``--speeds`` (default normal). The candidate model is the default model with
its length task retrained with ``length_units=("foot", "waist", "fused")``; terrain and direction are the
same fit (same data, settings and seed) and are shared, not retrained. The held-out length exercise is
walked at every calibration speed (seed 1; training: seed 0). Prints the rule's three numbers.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/c38_length_vote.py --users 240 241 242 243   # C38
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/c38_length_vote.py --users 260 261 262 263 \
        --cal-speeds slow,normal,fast                                                          # C39
"""

from __future__ import annotations

import argparse
import copy
import logging

import numpy as np
import pandas as pd

from localization import stride_rows
from pdrlearn.classify import train_user
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

CLASSES = ("short", "normal", "long")


def models(user: int, cal_speeds: tuple[str, ...] = ("normal",), cv: int = 10):
    """(default model, candidate model) of ``user``, as experiments/localization.py's ``train_model``: the
    calibration exercises walked at every speed of ``cal_speeds``; ``cv`` = ``train_user``'s default."""
    sessions = [simulate(ex, user_seed=user, speed=sp) for sp in cal_speeds
                for ex in ("terrain", "direction", "length")]
    base = train_user(sessions, user=f"sim{user}", cv=cv)
    length = train_user(sessions, user=f"sim{user}", tasks=["length"], length_units=("foot", "waist", "fused"),
                        cv=cv)
    cand = copy.copy(base)
    cand.tasks = {**base.tasks, "length": length.tasks["length"]}
    bounds = next((s.meta.get("length_class_bounds_m") for s in sessions if s.meta.get("length_class_bounds_m")),
                  None)
    for m in (base, cand):
        if bounds is not None and getattr(m, "length_bounds_m", None) is None:
            m.length_bounds_m = bounds
    return base, cand


def main(argv=None) -> None:
    import torch

    torch.set_num_threads(1)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", type=int, nargs="+", default=[240, 241, 242, 243])
    p.add_argument("--cal-speeds", default="normal", help="speeds of the calibration exercises (C39: slow,normal,fast)")
    p.add_argument("--speeds", default="normal", help="speeds of the tracked scenarios A-D")
    p.add_argument("--cv", type=int, default=10, help="CV folds (train_user's and pdrlearn train's default: 10)")
    args = p.parse_args(argv)
    cal_speeds, speeds = tuple(args.cal_speeds.split(",")), args.speeds.split(",")
    logging.basicConfig(level=logging.WARNING)
    strides, dist, held = [], [], []
    for user in args.users:
        base, cand = models(user, cal_speeds, args.cv)
        for name, model in (("default", base), ("candidate", cand)):
            print(f"user {user} {name}: chosen length {model.tasks['length'].chosen}", flush=True)
        for sp in cal_speeds:
            test = simulate("length", user_seed=user, speed=sp, seed=1)  # held-out walk (training: seed 0)
            truth = test.steps["length_class"].to_numpy(object)
            for name, model in (("default", base), ("candidate", cand)):
                pred = model.predict_steps(test, tasks=["length"])["length_class"].to_numpy(object)
                ok = np.isin(truth, CLASSES)
                held.append({"user": user, "model": name, "n": int(ok.sum()),
                             "correct": int(np.sum(pred[ok] == truth[ok]))})
        for scen in ("A", "B", "C", "D"):
            for sp in speeds:
                s = simulate(scen, user_seed=user, speed=sp)
                for name, model in (("default", base), ("candidate", cand)):
                    res = track_plasys(s, method="M3", model=model)
                    ev = evaluate_track(res, s)
                    dist.append({"user": user, "scenario": scen, "speed": sp, "model": name,
                                 "distance_error_pct": ev["distance_error_pct"]})
                    strides += stride_rows(res, s, user=user, scenario=scen, speed=sp, model=name)
        print(f"user {user} done", flush=True)
    st = pd.DataFrame(strides)
    st = st[st["true_length_class"].isin(CLASSES)]
    st["ok"] = st["length_class"] == st["true_length_class"]
    d = pd.DataFrame(dist)
    h = pd.DataFrame(held).groupby("model")[["n", "correct"]].sum()
    print("\n| model | tracked strides B+C+D | length acc B+C+D | acc A | acc B | acc C | acc D | held-out length "
          "acc (steps) | M3 mean abs distance error A-D % | A | B | C | D |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in ("default", "candidate"):
        s = st[st["model"] == name]
        bcd = s[s["scenario"].isin(["B", "C", "D"])]
        acc = {sc: s[s["scenario"] == sc]["ok"].mean() for sc in "ABCD"}
        dd = d[d["model"] == name]
        per = {sc: dd[dd["scenario"] == sc]["distance_error_pct"].abs().mean() for sc in "ABCD"}
        print(f"| {name} | {len(bcd)} | {bcd['ok'].mean():.3f} | " + " | ".join(f"{acc[sc]:.3f}" for sc in "ABCD")
              + f" | {h.loc[name, 'correct'] / h.loc[name, 'n']:.3f} ({h.loc[name, 'n']}) | "
              f"{dd['distance_error_pct'].abs().mean():.3f} | " + " | ".join(f"{per[sc]:.2f}" for sc in "ABCD") + " |")
    print(d.pivot_table(index=["user", "scenario", "speed"], columns="model", values="distance_error_pct").round(3)
          .to_string())


if __name__ == "__main__":
    main()
