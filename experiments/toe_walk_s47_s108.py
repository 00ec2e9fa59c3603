"""Decision S108 (session 47, FD; trial T1 F6): the foot pipeline on fresh simulated toe walkers - IC, toe-off and
stride length errors against the simulator's truth. No detector is tuned here.

    PYTHONPATH=. python experiments/toe_walk_s47_s108.py OUTDIR FIRST LAST

For each user FIRST..LAST: T1's child (1.30 m, leg 0.68 m, steps 0.42 m in 0.40 s, 100 Hz, 20 m straight), the
smooth rocker and no insoles (fForce files removed: foot-only timing, T1's set-up), walked with ``--contact
forefoot`` and, as a control, ``--contact heel``; ``pdrlearn track DIR --toe-off``. IC error: each tracked stride's
``event_s`` minus the instrumented foot's nearest ics.csv contact; toe-off error: ``tc_s - ref_tc_s``; stride
length: the matched strides' summed ``length_m`` vs ``ref_length_m`` (%)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

CHILD = ["--route", "stand:3, straight:20, stand:3", "--height", "1.30", "--leg-length", "0.68", "--step-length",
         "0.42", "--step-time", "0.40", "--rocker", "smooth", "--rate", "100"]


def run(out: Path, user: int, contact: str) -> dict:
    sim, trk = out / f"u{user}_{contact}", out / f"u{user}_{contact}.t"
    py = [sys.executable, "-m", "pdrlearn"]
    subprocess.run([*py, "simulate", *CHILD, "--contact", contact, "--user-seed", str(user), "--out", str(sim)],
                   check=True, capture_output=True)
    for f in sim.glob("fForce*.csv"):
        f.unlink()
    subprocess.run([*py, "track", str(sim), "--toe-off", "--out", str(trk)], check=True, capture_output=True)
    steps = pd.read_csv(trk / "steps.csv")
    ics = pd.read_csv(sim / "ics.csv")
    ic = ics[ics["foot"] == "right"]["ic_ms"].to_numpy(float) / 1000.0
    ev = steps["event_s"].dropna().to_numpy(float)
    ic_err = np.array([e - ic[np.argmin(np.abs(ic - e))] for e in ev]) * 1000.0
    to_err = ((steps["tc_s"] - steps["ref_tc_s"]) * 1000.0).dropna().to_numpy(float)
    m = steps["ref_length_m"].notna() & steps["length_m"].notna()
    length = 100.0 * (steps.loc[m, "length_m"].sum() / steps.loc[m, "ref_length_m"].sum() - 1.0)
    return {"user": user, "contact": contact, "n_ic": len(ic_err), "ic_median_ms": np.median(ic_err),
            "ic_min_ms": ic_err.min(), "ic_max_ms": ic_err.max(), "ic_early_50ms": int((ic_err < -50).sum()),
            "n_to": len(to_err), "to_median_ms": np.median(to_err) if len(to_err) else np.nan,
            "to_min_ms": to_err.min() if len(to_err) else np.nan, "to_max_ms": to_err.max() if len(to_err) else np.nan,
            "stride_length_err_pct": length}


def main(argv: list[str]) -> None:
    out, first, last = Path(argv[0]), int(argv[1]), int(argv[2])
    out.mkdir(parents=True, exist_ok=True)
    rows = [run(out, u, c) for u in range(first, last + 1) for c in ("forefoot", "heel")]
    table = pd.DataFrame(rows)
    table.to_csv(out / "toe_walk_s108.csv", index=False)
    pd.set_option("display.width", 200)
    print(table.round(1).to_string(index=False))
    for c, g in table.groupby("contact"):
        print(f"{c}: {len(g)} walkers, IC median of medians {g['ic_median_ms'].median():+.1f} ms (range "
              f"{g['ic_min_ms'].min():+.1f}..{g['ic_max_ms'].max():+.1f}), ICs > 50 ms early "
              f"{g['ic_early_50ms'].sum()} of {g['n_ic'].sum()}; "
              f"toe-off median of medians {g['to_median_ms'].median():+.1f} ms (range "
              f"{g['to_min_ms'].min():+.1f}..{g['to_max_ms'].max():+.1f}); stride length "
              f"{g['stride_length_err_pct'].min():+.2f}..{g['stride_length_err_pct'].max():+.2f} %")


if __name__ == "__main__":
    main(sys.argv[1:])
