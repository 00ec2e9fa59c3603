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
from pathlib import Path

from _results import add_users, write_result, write_table  # noqa: E402
from drops import REAL, by_drop, by_rate_route, same  # noqa: E402
from drops_timestamps import track, track_walks  # noqa: E402

TAGS = {"fixed": {}, "ts": {"timestamps": True}, "runs": {"timestamps": True, "upsample_runs": True}}
EXTERNAL = REAL.parent / "external"


def main() -> None:
    ap = argparse.ArgumentParser()
    add_users(ap, "43-54")
    ap.add_argument("--out", default="/tmp/drops_runs")
    a = ap.parse_args()
    root = Path(a.out)
    df, par = track_walks(a.users, root, TAGS, ("fixed", "runs"), lambda x, y: {"identical": same(x, y)})
    write_table(f"drops_runs_{a.users}", df)
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
    lines = [f"# Per-run 20 Hz upsampling on the timestamps (decision L87), users {a.users}", "",
             "Distance error % of `pdrlearn track` (no model, bridging off) vs the simulated truth; fixed = the default, "
             "ts = `timestamps: true` (L83), runs = `timestamps: true, upsample_runs: true` (the candidate). "
             "Worst = max over the walks of (|error| - |error| of the walk's 0 % copy), same configuration.", "",
             "| drop | walks | median abs err fixed | ts | runs | runs median - its 0 % median | worst fixed | worst ts | worst runs | F1 runs != fixed | 0 % copies identical fixed vs runs |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    m0 = df[df.drop_rate == 0].err_runs.abs().median()
    for drop, g, worse in by_drop(df, TAGS):
        lines.append(f"| {drop:g} | {len(g)} | {g.err_fixed.abs().median():.3f} | {g.err_ts.abs().median():.3f} | "
                     f"{g.err_runs.abs().median():.3f} | {g.err_runs.abs().median() - m0:+.3f} | {worse['fixed']:+.3f} | "
                     f"{worse['ts']:+.3f} | {worse['runs']:+.3f} | {int((g.f1_runs != g.f1_fixed).sum())} | "
                     + (f"{bool(g.identical.all())} |" if drop == 0 else "- |"))
    lines += ["", "Per rate and route (median signed distance error %; worst = max (|error| - |error| of the 0 % copy), pp):", "",
              "| drop | rate | route | fixed | ts | runs | worst ts | worst runs | walk of the worst runs |", "|---|---|---|---|---|---|---|---|---|"]
    for drop, rate, route, g, w in by_rate_route(df, ("ts", "runs")):
        lines.append(f"| {drop:g} | {rate:g} | {route} | {g.err_fixed.median():+.3f} | {g.err_ts.median():+.3f} | "
                     f"{g.err_runs.median():+.3f} | {w['ts'].max():+.3f} | {w['runs'].max():+.3f} | user {w['runs'].idxmax()[0]} |")
    lines += ["", "Foot recordings, default vs candidate, steps.csv and trajectory.csv byte-identical: "
              + ", ".join(f"{n} {ok}" for n, ok in real)]
    write_result(f"drops_runs_{a.users}", lines)


if __name__ == "__main__":
    main()
