"""Decision W122's measurement: ``pause_steps="progression"`` (a step during which the unit stands still keeps
at most the trunk's horizontal travel over it) against the default (off), judged by the rule written before the
run (docs/decisions/waist.md W122):
(a) simulated daily activities (W111's route and protocol), fresh users 1350-1399: the median |bout error| falls by
    at least 0.5 point;
(b) real Test11 HA001 / HA002 / MS001 (calibrated, per bout as W112): each subject's median |bout error| vs
    ``Length`` and vs the bouts' strides rises by at most 1.0 point; Test5 pooled, calibrated and uncalibrated,
    rises by at most 1.0 point;
(c) Test11 pooled (15 bouts): the median vs the bouts' strides falls and the median vs ``Length`` does not rise.
For information: simulator A-D users 1-3 (experiments/waist.py).

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/waist_progression_steps.py [--external DIR]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import waist as W  # noqa: E402
import waist_pause_steps as P  # noqa: E402

USERS = range(1350, 1400)
CANDIDATE = "progression"


def measure(ext: Path, value: bool | str, sim_users: int, users=USERS) -> dict:
    """The numbers W122's rule (and W134's, the same rule) reads, for ``pause_steps=value`` on simulated ``users``."""
    d = P.sim_daily(value, users=users)
    b, pool = P.real(ext, value)
    t11 = b[b.test.str.startswith("Test11") & (b.params == "calibrated")].assign(
        a=lambda x: x.error_pct.abs(), s=lambda x: x.error_strides_pct.abs())
    t5 = pool[pool.test == "Test5"].set_index("params")["bout_err_median_pct"]
    t11p = pool[(pool.test == "Test11") & (pool.params == "calibrated")].iloc[0]
    sim = W.summarize_sim(W.simulated(list(range(1, sim_users + 1)),
                                      configs=[("waist-pendulum", "waist-pendulum", {"pause_steps": value})]))
    r = {"daily": d, "sim_daily": float(d.err_pct.abs().median()), "t11": t11.groupby("subject")[["a", "s"]].median(),
         "t5_cal": float(t5["calibrated"]), "t5_def": float(t5["defaults"]),
         "pooled_L": float(t11p.bout_err_median_pct), "pooled_s": float(t11p.bout_err_strides_median_pct),
         "ad": float(sim.dist_err_abs_median_pct.iloc[0])}
    print(f"pause_steps={value!r}: (a) simulated daily activities users {users.start}-{users.stop - 1}, {len(d)} "
          f"bouts: median |bout error| {r['sim_daily']:.3f} %; Test5 calibrated {r['t5_cal']:.3f} %, uncalibrated "
          f"{r['t5_def']:.3f} %; Test11 pooled vs Length / strides {r['pooled_L']:.3f} / {r['pooled_s']:.3f} %; "
          f"A-D users 1-{sim_users} {r['ad']:.3f} % (information)", flush=True)
    print("  (b) Test11 median per bout vs Length / vs strides: " + ", ".join(
        f"{k} {v.a:.3f} / {v.s:.3f} %" for k, v in r["t11"].iterrows()), flush=True)
    return r


def judge(off: dict, on: dict, decision: str) -> bool:
    """Print each part of W122's rule (W134 reuses it) for ``on`` against ``off`` and the verdict; True if adopted."""
    P.print_users_better(off["daily"], on["daily"])
    rules = {"(a) simulated daily activities falls >= 0.5 point": on["sim_daily"] <= off["sim_daily"] - 0.5,
             "(b) no Test11 subject's median (vs Length, vs strides) rises > 1.0 point": bool(
                 ((on["t11"] - off["t11"]) <= 1.0).to_numpy().all()),
             "(b) Test5 calibrated and uncalibrated rise <= 1.0 point": on["t5_cal"] <= off["t5_cal"] + 1.0
             and on["t5_def"] <= off["t5_def"] + 1.0,
             "(c) Test11 pooled falls vs strides, not higher vs Length": on["pooled_s"] < off["pooled_s"]
             and on["pooled_L"] <= off["pooled_L"]}
    for k, v in rules.items():
        print(f"{k}: {'holds' if v else 'FAILS'}")
    print(f"{decision}: " + ("ADOPTED (all hold)" if all(rules.values()) else "not adopted (a rule fails)"), flush=True)
    return all(rules.values())


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=P.ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    off, on = (measure(args.external, v, args.sim_users) for v in (False, CANDIDATE))
    judge(off, on, "W122")


if __name__ == "__main__":
    main()
