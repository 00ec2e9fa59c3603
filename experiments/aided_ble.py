"""Beacon-grade fixes on offline foot tracks: the measurement of decisions D31 (innovation gate) and D32 (the default
stretched path's end points), docs/decisions/aided.md, adoption rules there.

    PYTHONPATH=<checkout> .venv/bin/python experiments/aided_ble.py --cache DIR [--users 9762-9779]

Each user walks ROUTE (simulator, ``--user-seed`` = user), tracked once by ``pdrlearn track`` (no model) into DIR;
fixes every U(10, 30) s from 20 s (the trial T5's mkfix.py) = the pelvis truth + N(0, s) per axis with ``accuracy_m``
= the 68 % radius of that noise (1.51 s), for s = 0.5, 2 and 5 m, and "wrong": s = 2 m with the third fix 10 m east
(accuracy 3 m); rng seed = user. Each variant is ``SporadicFixFusion(period_s=None)`` on the track's steps as
``aid_track`` runs it for an x, y fix file (start sigma 1 m); errors against the truth at each row.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd

from aided_streamed import _cli, truth_at  # noqa: E402

ROUTE = ("stand:3, straight:20, turn:90, straight:15, turn:-90, straight:20, turn:-90, straight:10, turn:90, "
         "straight:25, stand:3")
SCENARIOS = {"0.5m": (0.5, False), "2m": (2.0, False), "5m": (5.0, False), "wrong": (2.0, True)}
VARIANTS = {"today": (False, "fix"), "gate": (True, "fix"), "posterior": (False, "posterior"),
            "gate+posterior": (True, "posterior")}


def fixes_for(session: Path, t0: float, seed: int, sd: float, wrong: bool) -> pd.DataFrame:
    from pdrlearn.kernels.fixes import RADIUS68_PER_SIGMA

    t_end = float(pd.read_csv(session / "trajectory.csv")["timestamp"].iloc[-1]) / 1000.0
    rng = np.random.default_rng(seed)
    ts, T = [], 20.0
    while T < t_end - 5.0:
        ts.append(T)
        T += rng.uniform(10.0, 30.0)
    ts = np.array(ts)
    xy = truth_at(session, ts, t0) + rng.normal(0.0, sd, (len(ts), 2))
    if wrong and len(ts) > 2:
        xy[2, 0] += 10.0
    return pd.DataFrame({"t": ts, "x": xy[:, 0], "y": xy[:, 1], "accuracy_m": sd * RADIUS68_PER_SIGMA})


def user_rows(u: int, cache: Path) -> list[dict]:
    from pdrlearn.aid.sporadic import SporadicFixFusion

    d, trk = cache / f"u{u}", cache / f"u{u}.off"
    if not (d / "meta.json").is_file():
        _cli("simulate", "--route", ROUTE, "--user-seed", u, "--out", d)
    if not (trk / "summary.json").is_file():
        _cli("track", d, "--out", trk)
    traj, steps = pd.read_csv(trk / "trajectory.csv"), pd.read_csv(trk / "steps.csv")
    t0 = float(traj["t"].iloc[0])
    rows = []
    for scen, (sd, wrong) in SCENARIOS.items():
        fx = fixes_for(d, t0, u, sd, wrong)
        for var, (gate, to) in VARIANTS.items():
            f = SporadicFixFusion(period_s=None, initial_sigma_m=1.0, innovation_gate=gate, stretch_to=to)
            f.run(steps, fx, start_xy=(float(traj["x"].iloc[0]), float(traj["y"].iloc[0])), t_start=t0)
            ft = f.trajectory_
            g = truth_at(d, ft["t"].to_numpy(float), t0)
            row = {"user": u, "scenario": scen, "variant": var, "fixes": len(fx),
                   "rejected": f.stats_["fixes_rejected"],
                   "wrong_rejected": int(wrong and any(abs(r[0] - fx["t"].iloc[2]) < 1e-9 for r in f.rejected_))}
            for path, (cx, cy) in (("xy", ("x", "y")), ("rt", ("x_rt", "y_rt")), ("pdr", ("x_pdr", "y_pdr"))):
                e = np.hypot(ft[cx] - g[:, 0], ft[cy] - g[:, 1]).to_numpy()
                row[f"{path}_median_m"], row[f"{path}_max_m"] = float(np.median(e)), float(e.max())
            rows.append(row)
    return rows


def summarise(df: pd.DataFrame) -> None:
    print(f"{len(df.user.unique())} users; mean over users of each path's per-user median / max error (m)")
    for scen in SCENARIOS:
        s = df[df.scenario == scen]
        p = s[s.variant == "today"]
        print(f"{scen}: no fixes (x_pdr) {p.pdr_median_m.mean():.3f} / {p.pdr_max_m.mean():.3f}; fixes "
              f"{s.fixes.iloc[0]}-{s.fixes.max()} per user")
        for var in VARIANTS:
            v = s[s.variant == var]
            extra = f", wrong fix rejected {int(v.wrong_rejected.sum())} of {len(v)}" if scen == "wrong" else ""
            print(f"  {var:15s} x,y {v.xy_median_m.mean():.3f} / {v.xy_max_m.mean():.3f}   x_rt "
                  f"{v.rt_median_m.mean():.3f} / {v.rt_max_m.mean():.3f}   rejected {int(v.rejected.sum())} of "
                  f"{int(v.fixes.sum())}{extra}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="9762-9779", help="user range, e.g. 9762-9779")
    ap.add_argument("--cache", type=Path, required=True, help="folder for the sessions and the tracks (reused)")
    ap.add_argument("--out", type=Path, help="the per-user rows (CSV)")
    a = ap.parse_args(argv)
    lo, hi = (int(v) for v in a.users.split("-"))
    a.cache.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame([r for u in range(lo, hi + 1) for r in user_rows(u, a.cache)])
    if a.out is not None:
        df.to_csv(a.out, index=False)
    summarise(df)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
