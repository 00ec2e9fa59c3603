"""Offline vs streaming M3 with a trained model on the simulated scenarios (decisions L40 / E40).

For each simulated user (a model trained per user on the calibration exercises at three speeds, as
``experiments/localization.py`` does, with its model cache) and each scenario A-D at slow/normal/fast,
track with the offline M3 default (``track_plasys``) and with ``track --streaming`` (``streaming=True``,
its default rules), and print the mean |distance error| % and mean |altitude error| % (scenarios with a
height change) per scenario. ``--extra`` adds the streaming thesis rule (``rules="thesis",
min_confidence=0``) as a row, when the code accepts it.

    PYTHONPATH=$PWD python experiments/streaming_rules.py --users 3 --model-cache /tmp/x/loccache
"""

from __future__ import annotations

import argparse
import logging
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

from experiments.localization import train_model
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys


def run(users: int, scenarios: list[str], speeds: list[str], cache: Path | None, extra: bool) -> pd.DataFrame:
    from pdrlearn.sim import simulate

    simulate = partial(simulate, device_errors=True)  # decision S22 (experiments/localization.py default)
    rows = []
    for user in range(1, users + 1):
        model, _ = train_model(simulate, user, False, cache, ("slow", "normal", "fast"))
        runs = {"offline": {}, "streaming": {"streaming": True}}
        if extra:
            runs["streaming-thesis"] = {"streaming": True, "rules": "thesis", "min_confidence": 0.0}
        for scen in scenarios:
            for speed in speeds:
                s = simulate(scen, user_seed=user, speed=speed)
                for name, kw in runs.items():
                    res = track_plasys(s, method="M3", model=model, **kw)
                    ev = evaluate_track(res, s)
                    rows.append({"user": user, "scenario": scen, "speed": speed, "run": name,
                                 "distance_error_pct": ev.get("distance_error_pct", np.nan),
                                 "altitude_error_pct": ev.get("altitude_error_pct", np.nan),
                                 "n_steps": ev["n_steps"]})
    return pd.DataFrame(rows)


def table(df: pd.DataFrame) -> str:
    g = df.assign(d=df["distance_error_pct"].abs(), a=df["altitude_error_pct"].abs())
    g = g.groupby(["scenario", "run"])[["d", "a"]].mean().unstack("run")
    runs = list(dict.fromkeys(df["run"]))
    lines = ["| scenario | " + " | ".join(f"{r} dist % | {r} alt %" for r in runs) + " |",
             "|---|" + "---|---|" * len(runs)]
    for scen, row in g.iterrows():
        cells = []
        for r in runs:
            cells += [f"{row[('d', r)]:.2f}", "-" if not np.isfinite(row[("a", r)]) else f"{row[('a', r)]:.2f}"]
        lines.append(f"| {scen} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", type=int, default=3)
    p.add_argument("--scenarios", default="A,B,C,D")
    p.add_argument("--speeds", default="slow,normal,fast")
    p.add_argument("--model-cache", type=Path, default=None)
    p.add_argument("--extra", action="store_true", help="also streaming with the thesis rule, no gate")
    p.add_argument("--csv", type=Path, default=None)
    a = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    df = run(a.users, a.scenarios.split(","), a.speeds.split(","), a.model_cache, a.extra)
    if a.csv is not None:
        df.to_csv(a.csv, index=False)
    print(table(df))


if __name__ == "__main__":
    main()
