"""Decisions W224/W225: a lower-back summary's cadence and speeds from its strides vs W70's step medians.

Sessions and tracks (OUT = this folder; W224's rule names the users and commands):
  pdrlearn simulate ... --user-seed U --out sim/uU           users 5530-5555 (W224's four groups)
  pdrlearn track sim/uU --pipeline P --out o/uU_P            P in waist-pendulum, waist-pll
  pdrlearn track datasets/external/mobgap_X --pipeline waist-pendulum --out o/mobgap_X
Then: python experiments/w224_waist_strides.py (in OUT) -> experiments/results/w224_waist_strides.txt."""

from __future__ import annotations

import glob
import json
import os

import numpy as np
import pandas as pd

from pdrlearn.track.bouts import cadence_spm
from pdrlearn.track.gait import _judged, gait_range_warning, gait_summary

PIPELINES = ("waist-pendulum", "waist-pll")


def figures(out_dir: str, how: str) -> tuple[float, float | None, bool]:
    """(cadence, L95's judged speed, whether L95's slow line fires) of a track's steps.csv under ``how``."""
    st = pd.read_csv(f"{out_dir}/steps.csv")
    with open(f"{out_dir}/summary.json") as f:
        summary = json.load(f)
    summary.update(gait_summary(st, cadence_from=how))
    cad, speed, _ = _judged(summary)
    line = gait_range_warning(summary)
    return cad, speed, bool(line and "slower than the walking" in line)


def row(name: str, out_dir: str, truth: float, group: str, pipeline: str) -> dict | None:
    if not os.path.exists(f"{out_dir}/steps.csv"):
        return None
    old, new = figures(out_dir, "steps"), figures(out_dir, "strides")
    def r(v, k):
        return np.nan if v is None else round(v, k)

    return dict(session=name, group=group, pipeline=pipeline, truth=round(truth, 2), old=r(old[0], 2),
                new=r(new[0], 2), speed_old=r(old[1], 3), speed_new=r(new[1], 3),
                slow_old=old[2], slow_new=new[2])


def sim_truth(u) -> float:
    ic = np.sort(pd.read_csv(f"sim/u{u}/ics.csv")["ic_ms"].to_numpy(float)) / 1000
    return cadence_spm(len(ic) - 1, ic[-1] - ic[0])  # L164 on the true contacts (one bout)


def real_truth(d: str) -> float:
    ic = np.sort(pd.read_csv(f"{d}/ics.csv")["ic_ms"].to_numpy(float)) / 1000
    dt = np.diff(ic)
    return 60.0 / float(np.mean(dt[(dt > 0) & (dt <= 1.25)]))  # W224 (c): half of MAX_STRIDE_S


def main() -> None:
    rows = []
    for u in range(5530, 5556):
        group = "symmetric" if u < 5540 else ("A0.4" if u < 5550 else ("A0.75" if u < 5553 else "A0.95"))
        rows += [r for p in PIPELINES if (r := row(f"u{u}", f"o/u{u}_{p}", sim_truth(u), group, p)) is not None]
    for d in sorted(glob.glob("/work/main/datasets/external/mobgap_*")):
        n = os.path.basename(d)
        if not os.path.exists(f"{d}/ics.csv"):  # HA002 Test5 Trial1 has no INDIP reference: not judged
            print(f"{n}: no ics.csv, not judged")
            continue
        if (r := row(n, f"o/{n}", real_truth(d), "real", "waist-pendulum")) is not None:
            rows.append(r)
    d = pd.DataFrame(rows)
    d["err_old"], d["err_new"] = (d.old - d.truth).abs(), (d.new - d.truth).abs()
    d["speed_move_pct"] = 100 * (d.speed_new - d.speed_old).abs() / d.speed_old
    pd.set_option("display.width", 250)
    print(d.to_string(index=False))
    sym, asym, real = d[d.group == "symmetric"], d[d.group.str.startswith("A")], d[d.group == "real"]
    print("(a) symmetric: median |old-truth|, median |new-truth|, max |new-truth|, max speed move %")
    print(sym.groupby("pipeline").agg(med_old=("err_old", "median"), med_new=("err_new", "median"),
                                      max_new=("err_new", "max"), max_speed_move=("speed_move_pct", "max")))
    print("(b) asymmetric (A 0.4 / 0.75 / 0.95): median |old-truth|, median |new-truth|")
    print(asym.groupby("pipeline").agg(med_old=("err_old", "median"), med_new=("err_new", "median")))
    print("(c) real mobgap waist-pendulum: median |old-truth|, median |new-truth|:",
          round(real.err_old.median(), 3), round(real.err_new.median(), 3))
    a = all(g.err_new.median() <= g.err_old.median() + 0.5 and g.err_new.max() <= 3.0 and g.speed_move_pct.max() <= 5
            for _, g in sym.groupby("pipeline"))
    b = all(g.err_new.median() <= 2.0 and g.err_new.median() < g.err_old.median() for _, g in asym.groupby("pipeline"))
    c = real.err_new.median() <= real.err_old.median() + 0.5
    print(f"rule: (a) {'met' if a else 'NOT met'}, (b) {'met' if b else 'NOT met'}, (c) {'met' if c else 'NOT met'}")


if __name__ == "__main__":
    main()
