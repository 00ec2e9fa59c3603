"""Decision L795 (session 51, trial s51t2 F6): the minimum toe clearance per side against the simulator's toe.

Users FIRST..LAST: the first 12 a one-side foot drop (``--prosthetic-side left|right`` alternating,
``--prosthetic-toe-off-pitch -20 --prosthetic-heel-strike-pitch 3``, the trial's), the rest symmetric walkers. Both
feet of one walk (``--foot left|right``, same user seed), ``gait LEFT RIGHT --out`` (each tracked --toe-off). Truth
per side: trial s51t2's truth_clear.py - the simulator's toe point ``[L (1 - x_frac), 0, -h]`` of foot_trajectory.csv,
the lowest toe height after its first peak between the toe-off and the contact, median over the walk strides.

    PYTHONPATH=. python experiments/toe_clearance_s51_l795.py OUTDIR 18680 18699
    PYTHONPATH=. python experiments/toe_clearance_s51_l795.py real     # gaitmap's level walks (check only)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

ROUTE = "stand:3, straight:20, turn:180, straight:20, stand:3"
N_DROP = 12
DROP = ["--prosthetic-toe-off-pitch", "-20", "--prosthetic-heel-strike-pitch", "3"]


def cli(*args: str) -> None:
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))
    subprocess.run(["nice", sys.executable, "-m", "pdrlearn", *args], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def truth_mtc(d: Path) -> float:
    """trial s51t2 truth_clear.py's median MTC of one simulated foot session."""
    m = json.loads((d / "meta.json").read_text())
    u = m["user"]
    ft = pd.read_csv(d / "foot_trajectory.csv")
    t = ft.t_ms.to_numpy() / 1000
    p, q = ft[["x", "y", "z"]].to_numpy(), ft[["qx", "qy", "qz", "qw"]].to_numpy()
    toe = p + Rotation.from_quat(q).apply([u["foot_length_m"] * (1 - u["foot_sensor_x_frac"]), 0,
                                           -u["foot_sensor_height_m"]])
    st = pd.read_csv(d / "steps.csv")
    out = []
    for _, r in st[st.kind == "walk"].iterrows():
        a = np.searchsorted(t, r.tc_ms / 1000)
        ic = np.searchsorted(t, r.ic_ms / 1000)
        tz = toe[a:ic, 2]
        if len(tz) > 5:
            k = int(np.argmax(tz[: len(tz) // 2 + 1]))
            out.append(tz[k:].min())
    return float(np.median(out))


def one(root: Path, uid: int) -> dict:
    drop = uid - FIRST < N_DROP
    side = ("left" if (uid - FIRST) % 2 == 0 else "right") if drop else None
    extra = ["--prosthetic-side", side, *DROP] if drop else []
    dirs = {}
    for f in ("left", "right"):
        d = root / f"u{uid}_{f}"
        if not (d / "meta.json").exists():
            cli("simulate", "--route", ROUTE, "--user-seed", str(uid), "--rate", "100", "--foot", f, *extra,
                "--out", str(d), "--force")
        dirs[f] = d
    g = root / f"u{uid}_gait"
    cli("gait", str(dirs["left"]), str(dirs["right"]), "--out", str(g), "--force")
    walk = json.loads((g / "gait_summary.json").read_text())["walk"]
    return {"user": uid, "drop": side, "lower": walk.get("toe_clearance_lower"),
            **{f"est_{s}": walk.get(f"min_toe_clearance_m_{s}") for s in ("left", "right")},
            **{f"true_{s}": truth_mtc(dirs[s]) for s in ("left", "right")}}


def real() -> None:
    top = Path(__file__).resolve().parents[1] / "datasets"
    for d in sorted([*top.glob("real/gaitmap_level_*"), *top.glob("external/gaitmap_ms_*")]):
        if not d.is_dir():
            continue
        out = Path("/tmp") / f"l795_real_{d.name}"
        try:
            cli("track", str(d), "--toe-off", "--out", str(out), "--force")
        except subprocess.CalledProcessError:
            print(f"{d.name}: track failed")
            continue
        v = pd.read_csv(out / "steps.csv")["min_toe_clearance_m"].to_numpy(float)
        v = v[np.isfinite(v)]
        print(f"{d.name}: {len(v)} strides, median min_toe_clearance_m {np.median(v):.4f} m, "
              f"p10 {np.percentile(v, 10):.4f} p90 {np.percentile(v, 90):.4f}")


if __name__ == "__main__":
    if sys.argv[1] == "real":
        real()
        sys.exit(0)
    ROOT, FIRST, LAST = Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
    ROOT.mkdir(parents=True, exist_ok=True)
    if "--summary" in sys.argv:  # the table written by an earlier run, printed again
        df = pd.read_csv(ROOT / "l795.csv")
    else:
        with ThreadPoolExecutor(2) as ex:
            rows = list(ex.map(lambda u: one(ROOT, u), range(FIRST, LAST + 1)))
        df = pd.DataFrame(rows)
        df.to_csv(ROOT / "l795.csv", index=False)
    pd.set_option("display.width", 200)
    print(df.round(4).to_string(index=False))
    d = df[df["drop"].notna()]
    print(f"(a) foot-drop side named lower {int((d.lower == d['drop']).sum())} of {len(d)}; other side named "
          f"{int((d.lower.notna() & (d.lower != d['drop'])).sum())}")
    err = np.concatenate([(df[f"est_{s}"] - df[f"true_{s}"]).to_numpy(float) for s in ("left", "right")])
    print(f"(b) per-side median vs truth: median |error| {np.nanmedian(np.abs(err)):.4f} m, median error "
          f"{np.nanmedian(err):+.4f} m, max |error| {np.nanmax(np.abs(err)):.4f} m over {int(np.isfinite(err).sum())} "
          "sides")
    t = np.where(df.true_left < df.true_right, "left", "right")
    print(f"truth's lower side = the foot-drop side on {int((t[df['drop'].notna()] == d['drop']).sum())} of {len(d)}; "
          f"named side = truth's lower side where named: {int((df.lower == t)[df.lower.notna()].sum())} of "
          f"{int(df.lower.notna().sum())}")
    s = df[df["drop"].isna()]
    print(f"(c) symmetric walkers flagged {int(s.lower.notna().sum())} of {len(s)}")
