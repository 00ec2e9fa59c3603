"""Offline vs streaming M3 with a trained model on the simulated scenarios (decisions L40 / L41).

For each simulated user (a model trained per user on the calibration exercises at three speeds, as
``experiments/localization.py`` does, with its model cache) and each scenario A-D at slow/normal/fast,
track with the offline M3 default (``track_plasys``) and streamed (``streaming=True``) with the thesis rule
on every class (``stream-thesis``, the streamed default) and with offline's rule (``stream-bayes``: bayes,
0.95 gate), and print the mean |distance error| %, the mean |altitude error| % (scenarios with a height
change) and the signed mean distance error % per scenario. Streamed runs apply the streamed stride kernel's
own distance gain (L41); ``--extra`` adds both streamed rules with the offline engine's gain (the record
without its ``streaming`` part: what a model calibrated before L41 streams with), suffix ``/offline-gain``;
``--weak`` adds L40's weak model (terrain + length SVM, normal-speed exercises) on D.
``--first-user`` picks held-out users (users ``first .. first + users - 1``). The printed tables are also
written, with the command, to experiments/results/streaming_rules_users<first>-<last>.md (``--out DIR``).

    PYTHONPATH=$PWD python experiments/streaming_rules.py --users 3 --model-cache /tmp/x/loccache
    PYTHONPATH=$PWD python experiments/streaming_rules.py --first-user 4 --users 7 --extra \
        --model-cache /tmp/x/loccache                                              # decision L41
"""

from __future__ import annotations

import argparse
import copy
import logging
import shlex
import sys
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

from localization import train_model
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

RESULTS = Path(__file__).resolve().parent / "results"


def _offline_gain(model):
    """``model`` with its distance calibration's streamed part removed (a record made before L41)."""
    m = copy.copy(model)
    m.data_summary = copy.deepcopy(model.data_summary)
    rec = m.data_summary.get("distance_calibration")
    if isinstance(rec, dict):
        rec.pop("streaming", None)
    return m


def weak_model(simulate, user: int):
    """L40's weak model: terrain + length, SVM only, trained on the normal-speed exercises (with their
    distance calibration)."""
    from pdrlearn.classify import train_user

    sessions = [simulate(ex, user_seed=user, speed="normal") for ex in ("terrain", "direction", "length")]
    model = train_user(sessions, tasks=["terrain", "length"], methods=["svm"], cv=3, user=f"sim{user}-weak")
    bounds = next((s.meta["length_class_bounds_m"] for s in sessions if s.meta.get("length_class_bounds_m")), None)
    if bounds is not None and getattr(model, "length_bounds_m", None) is None:
        model.length_bounds_m = bounds
    return model


def run(users: int, scenarios: list[str], speeds: list[str], cache: Path | None, extra: bool,
        first_user: int = 1, weak: bool = False) -> pd.DataFrame:
    from pdrlearn.sim import simulate

    simulate = partial(simulate, device_errors=True)  # decision S22 (experiments/localization.py default)
    rows = []
    for user in range(first_user, first_user + users):
        model, _ = train_model(simulate, user, False, cache, ("slow", "normal", "fast"))
        thesis = {"streaming": True, "rules": "thesis", "min_confidence": 0.0}
        bayes = {"streaming": True, "rules": "bayes", "min_confidence": 0.95}
        runs = {"offline": (model, {}), "stream-thesis": (model, thesis), "stream-bayes": (model, bayes)}
        if extra:
            old = _offline_gain(model)
            runs |= {"stream-thesis/offline-gain": (old, thesis), "stream-bayes/offline-gain": (old, bayes)}
        weak_runs = {}
        if weak and "D" in scenarios:
            wm = weak_model(simulate, user)
            weak_runs = {"weak offline": (wm, {}), "weak stream-thesis/offline-gain": (_offline_gain(wm), thesis),
                         "weak stream-bayes": (wm, bayes)}
        for scen in scenarios:
            for speed in speeds:
                s = simulate(scen, user_seed=user, speed=speed)
                for name, (m, kw) in (runs | weak_runs if scen == "D" else runs).items():
                    res = track_plasys(s, method="M3", model=m, **kw)
                    ev = evaluate_track(res, s)
                    rows.append({"user": user, "scenario": scen, "speed": speed, "run": name,
                                 "distance_error_pct": ev.get("distance_error_pct", np.nan),
                                 "altitude_error_pct": ev.get("altitude_error_pct", np.nan),
                                 "n_steps": ev["n_steps"], "distance_gain": res.info.get("distance_gain")})
    return pd.DataFrame(rows)


def table(df: pd.DataFrame) -> str:
    g = df.assign(d=df["distance_error_pct"].abs(), a=df["altitude_error_pct"].abs(), s=df["distance_error_pct"])
    g = g.groupby(["scenario", "run"])[["d", "a", "s"]].mean().unstack("run")
    runs = list(dict.fromkeys(df["run"]))
    lines = ["| scenario | " + " | ".join(f"{r} dist % | {r} alt %" for r in runs) + " |",
             "|---|" + "---|---|" * len(runs)]
    for scen, row in g.iterrows():
        cells = []
        for r in runs:
            cells += [f"{row[('d', r)]:.2f}", "-" if not np.isfinite(row[("a", r)]) else f"{row[('a', r)]:.2f}"]
        lines.append(f"| {scen} | " + " | ".join(cells) + " |")
    lines += ["", "signed mean distance error % (+ = too long)", "",
              "| scenario | " + " | ".join(runs) + " |", "|---|" + "---|" * len(runs)]
    for scen, row in g.iterrows():
        lines.append(f"| {scen} | " + " | ".join(f"{row[('s', r)]:+.2f}" for r in runs) + " |")
    n = df.groupby("run").size().iloc[0]
    lines += ["", f"users {sorted(df['user'].unique().tolist())}, {n} walks per run"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", type=int, default=3)
    p.add_argument("--first-user", type=int, default=1, help="first simulated user (held-out users: 4 or later)")
    p.add_argument("--scenarios", default="A,B,C,D")
    p.add_argument("--speeds", default="slow,normal,fast")
    p.add_argument("--model-cache", type=Path, default=None)
    p.add_argument("--extra", action="store_true", help="also both streamed rules with the offline engine's gain")
    p.add_argument("--weak", action="store_true",
                   help="also L40's weak model (terrain + length SVM, normal-speed exercises) on D")
    p.add_argument("--csv", type=Path, default=None)
    p.add_argument("--out", type=Path, default=RESULTS,
                   help="folder of the report streaming_rules_users<first>-<last>.md (the printed table and "
                        "the command)")
    argv = sys.argv[1:] if argv is None else list(argv)
    a = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    df = run(a.users, a.scenarios.split(","), a.speeds.split(","), a.model_cache, a.extra, a.first_user, a.weak)
    if a.csv is not None:
        df.to_csv(a.csv, index=False)
    text = table(df)
    print(text)
    # the numbers docs/localization.md quotes come from this output: keep it (one file per user range)
    a.out.mkdir(parents=True, exist_ok=True)
    report = a.out / f"streaming_rules_users{a.first_user}-{a.first_user + a.users - 1}.md"
    report.write_text("# Offline vs streaming M3 (generated by experiments/streaming_rules.py)\n\n"
                      f"Command: `{shlex.join(['.venv/bin/python', 'experiments/streaming_rules.py', *argv])}`\n\n"
                      "mean |distance error| % and mean |altitude error| % per scenario\n\n" + text + "\n")


if __name__ == "__main__":
    main()
