"""Decision L804 (session 53, trial s53t3 F6): the error of the tracked toe clearance's side difference.

Per user both feet simulated (route of L795, 100 Hz), ``gait LEFT RIGHT --ignore-force``; truth per side: L795's
truth_mtc (the simulator's toe point from foot_trajectory.csv). ``derive``: symmetric walkers (first half --rocker
smooth, the rest hermite); T = the largest |E| rounded up to the mm, at least 0.005 m, E = (L - R tracked) - (L - R
truth). ``validate T``: the first 8 users a one-side foot drop (L795's options, side alternating, hermite), the rest
symmetric (first half smooth); the side named at T and at 0.005 m.

    PYTHONPATH=. python experiments/toe_clearance_s53_l804.py derive OUTDIR 20710 20719
    PYTHONPATH=. python experiments/toe_clearance_s53_l804.py validate OUTDIR 20720 20731 T
"""

from __future__ import annotations

import json
import math
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

import toe_clearance_s51_l795 as l795
from pdrlearn.track.bilateral import lower_clearance_side

SPEEDS = ("slow", "normal", "fast")
N_DROP = 8


def one(root: Path, uid: int, *, rocker: str, drop: str | None, speed: str) -> dict:
    extra = ["--prosthetic-side", drop, *l795.DROP] if drop else []
    dirs = {}
    for f in ("left", "right"):
        d = root / f"u{uid}_{f}"
        if not (d / "meta.json").exists():
            l795.cli("simulate", "--route", l795.ROUTE, "--user-seed", str(uid), "--rate", "100", "--foot", f,
                     "--speed", speed, "--rocker", rocker, *extra, "--out", str(d), "--force")
        dirs[f] = d
    g = root / f"u{uid}_gait"
    if not (g / "gait_summary.json").exists():  # a rerun (another T) reads the walks already measured
        l795.cli("gait", str(dirs["left"]), str(dirs["right"]), "--ignore-force", "--out", str(g), "--force")
    walk = json.loads((g / "gait_summary.json").read_text())["walk"]
    est = {s: walk.get(f"min_toe_clearance_m_{s}") for s in ("left", "right")}
    true = {s: l795.truth_mtc(dirs[s]) for s in ("left", "right")}
    return {"user": uid, "rocker": rocker, "speed": speed, "drop": drop,
            **{f"est_{s}": est[s] for s in est}, **{f"true_{s}": true[s] for s in true},
            "E": (est["left"] - est["right"]) - (true["left"] - true["right"])}


def run(root: Path, jobs: list[dict]) -> pd.DataFrame:
    root.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(2) as ex:
        return pd.DataFrame(list(ex.map(lambda k: one(root, **k), jobs)))


if __name__ == "__main__":
    mode, root, first, last = sys.argv[1], Path(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    users = range(first, last + 1)
    pd.set_option("display.width", 200)
    if mode == "derive":
        half = first + len(users) // 2
        df = run(root, [dict(uid=u, rocker="smooth" if u < half else "hermite", drop=None,
                             speed=SPEEDS[(u - first) % 3]) for u in users])
        df.to_csv(root / "l804_derive.csv", index=False)
        print(df.round(4).to_string(index=False))
        err = np.concatenate([(df[f"est_{s}"] - df[f"true_{s}"]).to_numpy(float) for s in ("left", "right")])
        big = float(np.nanmax(np.abs(df.E)))
        print(f"per-side median vs truth: median |error| {np.nanmedian(np.abs(err)):.4f} m, max |error| "
              f"{np.nanmax(np.abs(err)):.4f} m over {int(np.isfinite(err).sum())} sides; side difference E: median "
              f"|E| {np.nanmedian(np.abs(df.E)):.4f} m, max |E| {big:.4f} m")
        print(f"T = {max(0.005, math.ceil(big * 1000 - 1e-9) / 1000):.3f} m")
    else:
        t = float(sys.argv[5])
        sym = [u for u in users if u - first >= N_DROP]
        jobs = [dict(uid=u, rocker="hermite" if u - first < N_DROP or u >= sym[len(sym) // 2] else "smooth",
                     drop=("left" if (u - first) % 2 == 0 else "right") if u - first < N_DROP else None,
                     speed=SPEEDS[(u - first) % 3]) for u in users]
        df = run(root, jobs)
        for name, thr in (("T", t), ("L795", 0.005)):
            df[f"named_{name}"] = [lower_clearance_side({f"min_toe_clearance_m_{s}": r[f"est_{s}"]
                                                         for s in ("left", "right")}, min_diff_m=thr)
                                   for _, r in df.iterrows()]
        df.to_csv(root / "l804_validate.csv", index=False)
        print(df.round(4).to_string(index=False))
        d, s = df[df["drop"].notna()], df[df["drop"].isna()]
        for name, thr in (("T", t), ("L795", 0.005)):
            c = f"named_{name}"
            print(f"{name} {thr:.3f} m: (a) foot-drop side named {int((d[c] == d['drop']).sum())} of {len(d)}, other "
                  f"side {int((d[c].notna() & (d[c] != d['drop'])).sum())}; (c) symmetric named "
                  f"{int(s[c].notna().sum())} of {len(s)}")
