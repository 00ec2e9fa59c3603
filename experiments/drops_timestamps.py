"""Decision L83: the offline foot integrated on the sample timestamps, on scattered dropped samples.

B64's protocol (``experiments/drops.py``): per user a 20 m straight walk and a 20 m curved route, at 20 and
100 Hz, copies with drop rate 0, 0.01, 0.03 (same walk and seed: only the drop mask differs), tracked with
``pdrlearn track`` (no model, bridging off) with the fixed sample interval (``--params {"timestamps": false}``)
and on the timestamps (``{"timestamps": true}``). The clean copies and the real recordings (datasets/real) are
compared between the two: steps.csv byte for byte, trajectory.csv positions to 1e-9 m.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/drops_timestamps.py --users 37-42 --out /tmp/dt

Writes experiments/results/drops_timestamps_<users>.md and .csv.
"""

# ruff: noqa: E501
from __future__ import annotations

import argparse
import json
import logging
import shutil
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from _results import add_users, user_range, write_result, write_table  # noqa: E402
from drops import REAL, by_drop, by_rate_route, cli_json, walks  # noqa: E402

TAGS = {"fixed": {"timestamps": False}, "ts": {"timestamps": True}}  # --params of each configuration


def track(d: Path, out: Path, params: Path) -> dict:
    shutil.rmtree(out, ignore_errors=True)
    return cli_json(["track", d, "--out", out, "--json", "--params", params])[0]


def compare(a: Path, b: Path) -> tuple[bool, float]:
    """steps.csv byte-identical, max |position difference| (m) in trajectory.csv."""
    same_steps = (a / "steps.csv").read_bytes() == (b / "steps.csv").read_bytes()
    ta, tb = pd.read_csv(a / "trajectory.csv"), pd.read_csv(b / "trajectory.csv")
    if ta.shape != tb.shape or list(ta.columns) != list(tb.columns):
        return same_steps, float("inf")
    num = [c for c in ta.columns if pd.api.types.is_numeric_dtype(ta[c])]
    diff = float(np.nanmax(np.abs(ta[num].to_numpy(float) - tb[num].to_numpy(float)))) if num else 0.0
    return same_steps, diff


def track_walks(users: str, root: Path, tags: dict[str, dict], pair: tuple[str, str],
                columns: Callable[[Path, Path], dict]) -> tuple[pd.DataFrame, dict[str, Path]]:
    """Every walk of ``users`` ("lo-hi", ``walks``) tracked in ``root`` with each tag's ``--params``: a row a walk
    (printed as it comes) with ``err_<tag>`` and ``f1_<tag>`` and the columns ``columns(a, b)`` gives for the
    outputs of the two tags of ``pair``; the rows and the params file of each tag."""
    root.mkdir(parents=True, exist_ok=True)
    logging.disable(logging.INFO)
    par = {}
    for tag, p in tags.items():
        par[tag] = root / f"params_{tag}.json"
        par[tag].write_text(json.dumps(p))
    rows = []
    for d, row in walks(user_range(users), root):
        for tag in tags:
            s = track(d, root / f"{d.name}_{tag}", par[tag])
            row[f"err_{tag}"] = s.get("distance_error_pct")
            row[f"f1_{tag}"] = s.get("step_f1")
        row.update(columns(*(root / f"{d.name}_{t}" for t in pair)))
        rows.append(row)
        print(json.dumps(row), flush=True)
    return pd.DataFrame(rows), par


def main() -> None:
    ap = argparse.ArgumentParser()
    add_users(ap, "37-42")
    ap.add_argument("--out", default="/tmp/drops_ts")
    a = ap.parse_args()
    root = Path(a.out)
    df, par = track_walks(a.users, root, TAGS, ("fixed", "ts"),
                          lambda x, y: dict(zip(("steps_same", "max_pos_diff_m"), compare(x, y), strict=True)))
    real = []
    for d in sorted(p for p in REAL.iterdir() if p.is_dir()):
        if not (d / "fAccelerometer.csv").exists():  # a waist recording: no foot integration, L83 does not apply
            real.append((d.name, "no foot unit", 0.0))
            print(real[-1], flush=True)
            continue
        for tag in TAGS:
            track(d, root / f"real_{d.name}_{tag}", par[tag])
        real.append((d.name, *compare(root / f"real_{d.name}_fixed", root / f"real_{d.name}_ts")))
        print(real[-1], flush=True)
    write_table(f"drops_timestamps_{a.users}", df)
    lines = [f"# Offline foot on the timestamps (decision L83), users {a.users}", "",
             "Distance error % of `pdrlearn track` (no model, bridging off) vs the simulated truth; fixed = "
             "`timestamps: false` (dt = 1 / rate), ts = `timestamps: true`. Median |error| over the walks.", "",
             "| drop | walks | median abs err fixed | median abs err ts | median ts - median ts of 0 % | worst (abs err - abs err of 0 % copy) fixed | worst ts | F1 ts != fixed | 0 % steps.csv identical | 0 % max position diff (m) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    m0 = df[df.drop_rate == 0].err_ts.abs().median()
    for drop, g, worse in by_drop(df, TAGS):
        lines.append(f"| {drop:g} | {len(g)} | {g.err_fixed.abs().median():.3f} | {g.err_ts.abs().median():.3f} | "
                     f"{g.err_ts.abs().median() - m0:+.3f} | {worse['fixed']:+.3f} | {worse['ts']:+.3f} | "
                     f"{int((g.f1_ts != g.f1_fixed).sum())} | "
                     + (f"{bool(g.steps_same.all())} | {g.max_pos_diff_m.max():.3g} |" if drop == 0 else "- | - |"))
    lines += ["", "Per rate and route (median distance error %, signed):", "",
              "| drop | rate | route | fixed | ts | worst ts - its 0 % copy (pp) |", "|---|---|---|---|---|---|"]
    for drop, rate, route, g, w in by_rate_route(df, ("ts",)):
        lines.append(f"| {drop:g} | {rate:g} | {route} | {g.err_fixed.median():+.3f} | {g.err_ts.median():+.3f} | {w['ts'].max():+.3f} |")
    lines += ["", "Real recordings (datasets/real), fixed vs ts: steps.csv identical, max trajectory.csv difference (m): "
              + ", ".join(f"{n} {ok}" + (f" {diff:.3g}" if ok != "no foot unit" else "") for n, ok, diff in real)]
    write_result(f"drops_timestamps_{a.users}", lines)


if __name__ == "__main__":
    main()
