"""Decision L87: 20 Hz foot upsampled run by run (between dropped samples) and integrated on the timestamps.

B64's protocol (``experiments/drops.py``): per user a 20 m straight walk and a 20 m curved route, at 20 and
100 Hz, copies with drop rate 0, 0.01, 0.03 (same walk and seed: only the drop mask differs), tracked with
``pdrlearn track`` (no model, bridging off): the default (``fixed``: dt = 1 / rate, one upsampling over the whole
clock), L83 (``ts``: ``{"timestamps": true}``) and the candidate (``runs``: ``{"timestamps": true,
"upsample_runs": true}``). The clean copies, the foot recordings of datasets/real and the gaitmap recordings of
datasets/external are compared between the default and the candidate: steps.csv and trajectory.csv byte for byte.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/drops_runs.py --users 43-54 --out /tmp/dr

Writes experiments/results/drops_runs_<users>.md and .csv.
"""

# ruff: noqa: E501
from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

import pandas as pd

from experiments.drops import DROPS, REAL, walks
from experiments.drops_timestamps import track

TAGS = {"fixed": {}, "ts": {"timestamps": True}, "runs": {"timestamps": True, "upsample_runs": True}}
EXTERNAL = REAL.parent / "external"


def same(a: Path, b: Path) -> bool:
    return all((a / f).read_bytes() == (b / f).read_bytes() for f in ("steps.csv", "trajectory.csv"))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="43-54")
    ap.add_argument("--out", default="/tmp/drops_runs")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    root = Path(a.out)
    root.mkdir(parents=True, exist_ok=True)
    logging.disable(logging.INFO)
    par = {}
    for tag, p in TAGS.items():
        par[tag] = root / f"params_{tag}.json"
        par[tag].write_text(json.dumps(p))
    rows = []
    for d, row in walks(lo, hi, root):
        for tag in TAGS:
            s = track(d, root / f"{d.name}_{tag}", par[tag])
            row[f"err_{tag}"] = s.get("distance_error_pct")
            row[f"f1_{tag}"] = s.get("step_f1")
        row["identical"] = same(root / f"{d.name}_fixed", root / f"{d.name}_runs")
        rows.append(row)
        print(json.dumps(row), flush=True)
    df = pd.DataFrame(rows)
    res = Path(__file__).resolve().parent / "results"
    df.to_csv(res / f"drops_runs_{a.users}.csv", index=False)
    real = []
    folders = sorted(p for p in REAL.iterdir() if p.is_dir()) + sorted(EXTERNAL.glob("gaitmap_*"))
    for d in folders:
        if not (d / "fAccelerometer.csv").exists():
            continue  # a waist recording: no foot integration
        for tag in ("fixed", "runs"):
            track(d, root / f"real_{d.parent.name}_{d.name}_{tag}", par[tag])
        real.append((f"{d.parent.name}/{d.name}", same(root / f"real_{d.parent.name}_{d.name}_fixed",
                                                       root / f"real_{d.parent.name}_{d.name}_runs")))
        print(real[-1], flush=True)
    base = df[df.drop_rate == 0].set_index(["user", "route", "rate_hz"])
    lines = [f"# Per-run 20 Hz upsampling on the timestamps (decision L87), users {a.users}", "",
             "Distance error % of `pdrlearn track` (no model, bridging off) vs the simulated truth; fixed = the default, "
             "ts = `timestamps: true` (L83), runs = `timestamps: true, upsample_runs: true` (the candidate). "
             "Worst = max over the walks of (|error| - |error| of the walk's 0 % copy), same configuration.", "",
             "| drop | walks | median abs err fixed | ts | runs | runs median - its 0 % median | worst fixed | worst ts | worst runs | F1 runs != fixed | 0 % copies identical fixed vs runs |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    m0 = base.err_runs.abs().median()
    for drop in DROPS:
        g = df[df.drop_rate == drop].set_index(["user", "route", "rate_hz"])
        worse = {t: (g[f"err_{t}"].abs() - base[f"err_{t}"].abs()).max() for t in TAGS}
        lines.append(f"| {drop:g} | {len(g)} | {g.err_fixed.abs().median():.3f} | {g.err_ts.abs().median():.3f} | "
                     f"{g.err_runs.abs().median():.3f} | {g.err_runs.abs().median() - m0:+.3f} | {worse['fixed']:+.3f} | "
                     f"{worse['ts']:+.3f} | {worse['runs']:+.3f} | {int((g.f1_runs != g.f1_fixed).sum())} | "
                     + (f"{bool(g.identical.all())} |" if drop == 0 else "- |"))
    lines += ["", "Per rate and route (median signed distance error %; worst = max (|error| - |error| of the 0 % copy), pp):", "",
              "| drop | rate | route | fixed | ts | runs | worst ts | worst runs | walk of the worst runs |", "|---|---|---|---|---|---|---|---|---|"]
    for (drop, rate, route), g in df.groupby(["drop_rate", "rate_hz", "route"]):
        gi = g.set_index(["user", "route", "rate_hz"])
        w = {t: gi[f"err_{t}"].abs() - base.loc[gi.index, f"err_{t}"].abs() for t in ("ts", "runs")}
        lines.append(f"| {drop:g} | {rate:g} | {route} | {g.err_fixed.median():+.3f} | {g.err_ts.median():+.3f} | "
                     f"{g.err_runs.median():+.3f} | {w['ts'].max():+.3f} | {w['runs'].max():+.3f} | user {w['runs'].idxmax()[0]} |")
    lines += ["", "Foot recordings, default vs candidate, steps.csv and trajectory.csv byte-identical: "
              + ", ".join(f"{n} {ok}" for n, ok in real)]
    (res / f"drops_runs_{a.users}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
