"""Decision W550's measurement: `trunk_rhythm_veto` (lower-back runs of contacts without a step rhythm) off vs on.

`python experiments/trunk_rhythm_w550.py simulate DIR`: S114's sessions of the fresh users 15900-15939 (the rule's
groups; waist streams only: the foot files removed). `... measure DIR`: one uncalibrated `waist-pendulum` track per
session with the veto off and on (count, distance vs meta.json's `distance_m`, whole-recording step F1 0.25 s), the
rule's group means, and how often W550's line fires (veto off). `... real`: (D), experiments/waist.py's real runs
(`waist-pendulum`) with the option's default patched off / on.
"""

from __future__ import annotations

import logging
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
HD = ["--variability", "5", "--irregular-rate", "0.3", "--step-width", "0.28", "--pelvis", "realistic",
      "--speed", "slow", "--bounce", "pendulum"]  # the trial's patient-like walker (T2 gen.sh)
W10 = ["--route", "stand:3, straight:10, stand:3"]
TUG = ["--route", "straight:3, turn:180, straight:3, turn:180", "--sit-start", "5", "--sit-end", "5",
       "--transfer-time", "2:4"]
JERKS = ["--trunk-jerks", "1"]
GROUPS = [  # (name, users, options): decision W550's (A)-(C)
    ("stand", range(15900, 15908), ["--route", "stand:40", "--pelvis", "realistic", *JERKS]),
    ("w10j", range(15908, 15916), [*W10, *HD, *JERKS]),
    ("tugj", range(15916, 15920), [*TUG, *HD, *JERKS]),
    ("w10n", range(15920, 15925), W10),
    ("w10s", range(15925, 15930), [*W10, "--speed", "slow"]),
    ("w10p", range(15930, 15935), [*W10, *HD]),
    ("tugp", range(15935, 15940), [*TUG, *HD]),
]


def simulate(out: Path) -> None:
    for name, users, opts in GROUPS:
        for u in users:
            d = out / f"{name}_u{u}"
            subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", *opts, "--rate", "100", "--user-seed", str(u),
                            "--out", str(d), "--force"], check=True, stdout=subprocess.DEVNULL)
            for f in d.glob("f*.csv"):
                f.unlink()  # the lower back alone


def _track(session, veto: bool):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    p, _ = resolve_params(session, None)
    p.options = {"trunk_rhythm_veto": veto}
    return track_waist(session, pipeline="waist-pendulum", params=p).steps


def measure(out: Path) -> None:
    from pdrlearn.io import read_session
    from pdrlearn.waist.evaluate import step_metrics
    from pdrlearn.waist.trunk_rhythm import LINE_MIN_CONTACTS, rhythm_keep_mask

    rows = []
    for d in sorted(out.iterdir()):
        s = read_session(d)
        n_ref = len(s.extras["ics"]) if "ics" in s.extras else 0
        dist_ref = float(s.meta.get("distance_m", 0.0))
        for on in (False, True):
            st = _track(s, on)
            dist = float(np.abs(st["length_m"]).sum()) if len(st) else 0.0
            k = rhythm_keep_mask(st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool))
            rows.append(dict(session=d.name, group=d.name.split("_")[0], veto=on, n=len(st), n_ref=n_ref,
                             count_err_pct=(len(st) - n_ref) / n_ref * 100 if n_ref else np.nan,
                             dist=dist, dist_ref=dist_ref,
                             dist_err_pct=(dist - dist_ref) / dist_ref * 100 if dist_ref else np.nan,
                             f1=step_metrics(st, s).get("step_f1_all", np.nan),
                             line=(not on) and int((~k).sum()) >= LINE_MIN_CONTACTS))
    df = pd.DataFrame(rows)
    print(df.to_string(index=False, float_format="%.3f"))
    g = df.assign(abs_count=df.count_err_pct.abs(), abs_dist=df.dist_err_pct.abs()).groupby(["group", "veto"])
    print(g.agg(n=("n", "sum"), median_n=("n", "median"), n_ref=("n_ref", "sum"), mean_abs_count=("abs_count", "mean"),
                mean_abs_dist=("abs_dist", "mean"), mean_f1=("f1", "mean"), line=("line", "sum"))
          .to_string(float_format="%.3f"))


def real() -> None:
    sys.path.insert(0, str(ROOT / "experiments"))
    import pdrlearn.track.waist as TW
    import waist as W

    cfg = [c for c in W.CONFIGS if c[0] == "waist-pendulum"]
    out = []
    for on in (False, True):
        TW.OPTION_DEFAULTS["trunk_rhythm_veto"] = on
        out.append(W.real(ROOT / "datasets" / "real", configs=cfg).assign(veto=on))
    print(pd.concat(out)[["test", "calibrated_on", "params", "veto", "step_f1", "step_f1_all", "bout_err_median_pct",
                          "n_detected", "n_reference"]].to_string(index=False, float_format="%.4f"))


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "simulate":
        simulate(Path(sys.argv[2]))
    elif cmd == "measure":
        measure(Path(sys.argv[2]))
    elif cmd == "real":
        real()
    else:
        sys.exit(__doc__)
