"""Decision L176: the summaries' median cadence from the step times (W70) vs 120 / the median stride time.

Sessions and tracks (users 2460-2469 symmetric, 2470-2479 with --step-time-asymmetry 0.4; OUT = this folder):
  pdrlearn simulate --route "stand:2, straight:25, stand:2" --user-seed U --seed U --rate 100 [ASYM] --out sim/uU
  pdrlearn track sim/uU --pipeline P --out o/uU_P      for P in plasys, waist-pendulum, waist-pll
Then: python experiments/l176_cadence.py (in OUT) -> experiments/results/l176_cadence.txt."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.bouts import cadence_spm
from pdrlearn.track.gait import gait_summary, waist_step_times

PIPELINES = ("plasys", "waist-pendulum", "waist-pll")


def row(u: int, p: str, truth: float) -> dict | None:
    try:
        st = pd.read_csv(f"o/u{u}_{p}/steps.csv")
    except FileNotFoundError:
        return None
    new = gait_summary(st, cadence_from="strides")["median_cadence_spm"]
    if p == "plasys":
        old = float(np.nanmedian(st["cadence_spm"].to_numpy(float)))
    else:
        old = float(np.nanmedian(60 / waist_step_times(st)[0]))
    return dict(user=u, asym=u >= 2470, pipeline=p, truth=round(truth, 2), old=round(old, 2), new=round(new, 2))


def main() -> None:
    rows = []
    for u in range(2460, 2480):
        ic = np.sort(pd.read_csv(f"sim/u{u}/ics.csv")["ic_ms"].to_numpy(float)) / 1000
        truth = cadence_spm(len(ic) - 1, ic[-1] - ic[0])  # L164 on the true contacts
        rows += [r for p in PIPELINES if (r := row(u, p, truth)) is not None]
    d = pd.DataFrame(rows)
    d["d_new_old"], d["err_old"], d["err_new"] = d.new - d.old, (d.old - d.truth).abs(), (d.new - d.truth).abs()
    pd.set_option("display.width", 200)
    print(d.to_string(index=False))
    print("symmetric max |new-old| per pipeline:")
    print(d[~d.asym].groupby("pipeline").d_new_old.apply(lambda x: x.abs().max()))
    print("asymmetric median |err| old / new:")
    print(d[d.asym].groupby("pipeline")[["err_old", "err_new"]].median())


if __name__ == "__main__":
    main()
