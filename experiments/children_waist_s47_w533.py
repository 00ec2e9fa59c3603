"""Decision W533 (docs/decisions/waist.md): uncalibrated lower-back distance error of simulated children at clinical
paediatric cadences, by the band of their tracked median step time (trial T1, session 47, finding F4).

Users 14970-14989: height uniform 1.15-1.45 m, leg 0.52 x height, step time uniform 0.34-0.45 s, step length uniform
0.30-0.50 m (numpy's default_rng(user)), `--bounce` constant for even users and pendulum for odd ones;
`stand:2, straight:30, stand:2` at 100 Hz through the CLI (`pdrlearn simulate`, then `pdrlearn track` on each
pipeline, no calibration); the error is summary.json's `distance_error_pct`, the step time its `median_step_time_s`.
Bands: under 0.38 s, 0.38-0.41 s, 0.41 s and over (W533's rule). Sessions are kept under --work and reused.

    python experiments/children_waist_s47_w533.py --users 14970-14989 --work /tmp/children_w533
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from _results import add_users, user_range, write_result, write_table

PIPELINES = ("waist-pll", "waist-pendulum")
BANDS = (0.0, 0.38, 0.41, np.inf)  # W533: thirds of 0.34-0.45 s rounded to 10 ms


def child(user: int) -> dict:
    r = np.random.default_rng(user)
    h = round(float(r.uniform(1.15, 1.45)), 2)
    step_time = round(float(r.uniform(0.34, 0.45)), 3)
    return {"user": user, "height": h, "leg": round(0.52 * h, 2), "step_time": step_time,
            "step_length": round(float(r.uniform(0.30, 0.50)), 3),
            "bounce": "constant" if user % 2 == 0 else "pendulum"}


def run(user: int, work: Path) -> dict:
    c, sim = child(user), work / f"u{user}"
    cli = [sys.executable, "-m", "pdrlearn"]
    if not (sim / "meta.json").exists():
        subprocess.run([*cli, "simulate", "--route", "stand:2, straight:30, stand:2", "--height", str(c["height"]),
                        "--leg-length", str(c["leg"]), "--step-length", str(c["step_length"]), "--step-time",
                        str(c["step_time"]), "--bounce", c["bounce"], "--user-seed", str(user), "--rate", "100",
                        "--out", str(sim)], check=True, capture_output=True, env=os.environ)
    for p in PIPELINES:
        out = Path(f"{sim}.{p}")
        if not (out / "summary.json").exists():
            subprocess.run([*cli, "track", str(sim), "--pipeline", p, "--out", str(out), "--force"], check=True,
                           capture_output=True, env=os.environ)
        s = json.loads((out / "summary.json").read_text())
        c[p] = round(s["distance_error_pct"], 1)
        c[p + "_step_s"] = round(s["median_step_time_s"], 3)
    return c


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_users(ap, "14970-14989")
    ap.add_argument("--work", type=Path, default=Path("/tmp/children_w533"))
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    t = pd.DataFrame([run(u, a.work) for u in user_range(a.users)])
    write_table("children_waist_s47_w533", t)
    t["band"] = pd.cut(t["waist-pll_step_s"], BANDS, right=False)
    lines = ["# W533: uncalibrated lower-back distance error (%) of simulated children by step-time band", "",
             t.drop(columns="band").to_string(index=False), "", "| band (s) | children | waist-pll | waist-pendulum |",
             "|---|---|---|---|"]
    for band, g in t.groupby("band", observed=True):
        lines.append(f"| {band} | {len(g)} | {g['waist-pll'].min():+.1f} to {g['waist-pll'].max():+.1f} | "
                     f"{g['waist-pendulum'].min():+.1f} to {g['waist-pendulum'].max():+.1f} |")
    lines.append(f"| all | {len(t)} | {t['waist-pll'].min():+.1f} to {t['waist-pll'].max():+.1f} | "
                 f"{t['waist-pendulum'].min():+.1f} to {t['waist-pendulum'].max():+.1f} |")
    write_result("children_waist_s47_w533", lines)


if __name__ == "__main__":
    main()
