"""Decision W598's measurement (session 51, FF): the lower back's stride-time CV (summary.json
``stride_time_cv_withheld.jitter_free_cv_pct``) before (the branch start's W558) and after (W598: steady straight
runs, jitter about each run's mean) against ics.csv's truth, on fresh users 18350-18389: a 30 m corridor walked 8
times (7 cone turns), 100 Hz, 18350-18369 ``--speed normal``, 18370-18389 ``--speed slow``, ``--variability`` 1 / 2.5
alternately, ``--step-time-asymmetry 0.2`` when uid % 4 == 3.

Run: PYTHONPATH=. nice python experiments/lower_back_cv_s51_w598.py OUTDIR BASE FIRST LAST [--after]
(BASE: a folder holding the branch start's ``pdrlearn``, for the "before" tracks;
``--after``: this tree's ``lower_back_cv`` of each "before" track's steps.csv - W598 changes no step, and on the
trial's five tracks it gave summary.json's values to 1e-12 - and print the table of both.)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.track.clinical import lower_back_cv

ROUTE = "stand:3, " + ", ".join(["straight:30, turn:180"] * 7) + ", straight:30, stand:3"


def _run(pythonpath: str, *args: str) -> None:
    """``python -m pdrlearn ARGS`` importing ``pdrlearn`` from ``pythonpath`` (run there: ``-m`` puts the working
    folder first on the path)."""
    env = dict(os.environ, PYTHONPATH=pythonpath)
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True, text=True, env=env,
                   cwd=pythonpath)


def options(uid: int) -> list[str]:
    out = ["--speed", "normal" if uid < 18370 else "slow", "--variability", "1" if uid % 2 == 0 else "2.5"]
    return out + (["--step-time-asymmetry", "0.2"] if uid % 4 == 3 else [])


def true_cv(session: Path) -> float:
    """ics.csv's strides t[k+2] - t[k] whose three contacts are of kind walk (turn and closing steps out)."""
    ics = pd.read_csv(session / "ics.csv").sort_values("ic_ms")
    t, k = ics["ic_ms"].to_numpy(float) / 1000.0, ics["kind"].to_numpy()
    s = t[2:] - t[:-2]
    ok = (k[2:] == "walk") & (k[1:-1] == "walk") & (k[:-2] == "walk")
    return float(100.0 * s[ok].std(ddof=1) / s[ok].mean())


def lb_cv(track: Path) -> float | None:
    w = json.loads((track / "summary.json").read_text()).get("stride_time_cv_withheld") or {}
    return w.get("jitter_free_cv_pct"), w.get("n_jitter_free_strides")


def main(out: Path, base: str, first: int, last: int, after: bool) -> None:
    out, base = out.resolve(), str(Path(base).resolve())
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for uid in range(first, last + 1):
        ses = out / f"u{uid}"
        if not after:
            _run(base, "simulate", "--route", ROUTE, "--rate", "100", "--user-seed", str(uid), "--out", str(ses),
                 "--force", *options(uid))
            _run(base, "track", str(ses), "--units", "waist", "--out", str(out / f"b{uid}"), "--force")
            print(uid, "before done", flush=True)
            continue
        if not (out / f"b{uid}" / "summary.json").exists():  # not tracked (yet)
            continue
        truth = true_cv(ses)
        b, nb = lb_cv(out / f"b{uid}")
        after = lower_back_cv(pd.read_csv(out / f"b{uid}" / "steps.csv"))  # the steps are W598's too
        a, na = after["jitter_free_cv_pct"], after["n_jitter_free_strides"]
        rows.append({"user": uid, "speed": "normal" if uid < 18370 else "slow", "true_cv": truth, "before": b,
                     "n_before": nb, "after": a, "n_after": na, "ratio_before": b / truth if b else np.nan,
                     "ratio_after": a / truth if a else np.nan})
        print(json.dumps(rows[-1]), flush=True)
    if not after:
        return
    t = pd.DataFrame(rows)
    t.to_csv(out / f"w598_{first}_{last}.csv", index=False)
    with pd.option_context("display.width", 200, "display.precision", 2):
        print(t.to_string(index=False))
    summarise(t)


def summarise(t: pd.DataFrame) -> None:
    for speed, g in t.groupby("speed", sort=False):
        ra, rb = g["ratio_after"], g["ratio_before"]
        within = int(((ra >= 0.67) & (ra <= 1.5)).sum())
        print(f"{speed}: median ratio before {rb.median():.2f} -> after {ra.median():.2f}; after within 0.67-1.5 on "
              f"{within} of {len(g)} (withheld {int(ra.isna().sum())}); true CV {g['true_cv'].min():.2f}-"
              f"{g['true_cv'].max():.2f} %")


if __name__ == "__main__":
    if sys.argv[2] == "--summarise":
        summarise(pd.concat([pd.read_csv(p) for p in sys.argv[3:]]))
    else:
        main(Path(sys.argv[1]), sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), "--after" in sys.argv[5:])
