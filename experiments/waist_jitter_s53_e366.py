"""Decision E366's measurement (docs/decisions/export.md): the live waist tracker's distance on a jittered phone
stream against the same stream without jitter, and the offline track, before / after.

    PHONEIFY=/work/trial/s53t2/tools/phoneify.py LIVE=/work/trial/s53t2/tools/live.py \
    BASE=/tmp/base OUT=/tmp/e366 python experiments/waist_jitter_s53_e366.py sim|prep|run|report U0 U1

``sim``: the calibration walk and the walk per user at 50 and 100 Hz; ``prep``: the phone streams (the trial's
phoneify at 0, 2, 4, 6 ms jitter), a calibration on the 4 ms calibration walk and its bundle; ``run``: the live
tracker (the trial's live.py, 10-sample pushes) and offline ``track`` with BASE's code (before) and this tree's
(after), one JSON line per session; ``report``: the rule's numbers; ``all U0 U1 STEP``: sim, prep and run
of every STEP-th user (several workers).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

PY = sys.executable
HERE = str(Path(__file__).resolve().parents[1])
OUT = Path(os.environ.get("OUT", "/tmp/e366"))
BASE = os.environ.get("BASE", "")
PHONEIFY = os.environ.get("PHONEIFY", "/work/trial/s53t2/tools/phoneify.py")
LIVE = os.environ.get("LIVE", "/work/trial/s53t2/tools/live.py")
WALK = ("stand:5, straight:30, turn:90, straight:20, escalator:+5, straight:15, turn:-90, straight:25, stand:5")
CALIB = "stand:5, straight:40, stand:5"
RATES = (50, 100)
JITTERS = (0, 2, 4, 6)
#: the jitters offline ``track`` is run at (before and after; its path does not run ``Bridge``)
OFFLINE_JITTERS = tuple(int(j) for j in os.environ.get("OFFLINE_JITTERS", "0,2,4,6").split(","))


def sh(args: list[str], code: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": code, "OMP_NUM_THREADS": "1"}
    r = subprocess.run(args, env=env, capture_output=True, text=True, cwd=cwd)
    if r.returncode:
        print("FAIL", " ".join(args), r.stderr[-400:], flush=True)
    return r


def pdr(args: list[str], code: str = HERE) -> subprocess.CompletedProcess:
    return sh([PY, "-m", "pdrlearn", *args], code)


def folder(u: int, rate: int) -> Path:
    return OUT / f"r{rate}" / str(u)


def sim(u: int) -> None:
    for rate in RATES:
        d = folder(u, rate)
        for name, route in (("calib", CALIB), ("walk", WALK)):
            if not (d / name / "meta.json").exists():
                pdr(["simulate", "--route", route, "--user-seed", str(u), "--rate", str(rate), "--out", str(d / name)])


def prep(u: int) -> None:
    for rate in RATES:
        d = folder(u, rate)
        sh([PY, PHONEIFY, "calib", "pcalib", str(u), "0.3", "4"], HERE, cwd=d)
        for j in JITTERS:
            sh([PY, PHONEIFY, "walk", f"walk_j{j}", str(u), "0.3", str(j)], HERE, cwd=d)
        pdr(["calibrate", str(d / "pcalib"), "--pipeline", "waist-pendulum", "-d", "40", "--out", str(d / "cal.json")])
        axes = json.loads((d / "pcalib" / "meta.json").read_text())["frames"]["waist"]
        frame = ",".join(f"{k}={axes[k]}" for k in ("x", "y", "z"))
        pdr(["export", str(d / "cal.json"), "--frame", frame, "--out", str(d / "wb")])


def run(u: int) -> None:
    for rate in RATES:
        d = folder(u, rate)
        for tag, code in (("before", BASE), ("after", HERE)):
            for j in JITTERS:
                s = f"walk_j{j}"
                r = sh([PY, LIVE, "wb", s, "10", str(rate)], code, cwd=d)
                live = json.loads(r.stdout.strip().splitlines()[-1])["dist_est"] if r.stdout.strip() else None
                os.replace(d / f"{s}_live.csv", d / f"{s}_live_{tag}.csv")
                off = d / f"trk_{s}_{tag}"
                if j not in OFFLINE_JITTERS:
                    print(json.dumps({"u": u, "rate": rate, "jit": j, "tag": tag, "live_m": live, "offline_m": None}),
                          flush=True)
                    continue
                pdr(["track", str(d / s), "--pipeline", "waist-pendulum", "--params", str(d / "cal.json"),
                     "--out", str(off)], code)
                steps = off / "steps.csv"
                dist = float(pd.read_csv(steps)["length_m"].sum()) if steps.exists() else None
                print(json.dumps({"u": u, "rate": rate, "jit": j, "tag": tag, "live_m": live, "offline_m": dist}),
                      flush=True)


def report(rows: list[dict]) -> None:
    df = pd.DataFrame(rows)
    for rate in RATES:
        for tag in ("before", "after"):
            x = df[(df.rate == rate) & (df.tag == tag)].pivot(index="u", columns="jit", values="live_m")
            for j in JITTERS[1:]:
                r = 100 * (x[j] / x[0] - 1)
                print(f"{rate} Hz {tag:6s} live {j} ms / 0 ms - 1: mean {r.mean():+.3f} %, median |.| "
                      f"{r.abs().median():.3f} %, mean |.| {r.abs().mean():.3f} %, max |.| {r.abs().max():.3f} % "
                      f"(n={r.size})")
        o = df[(df.rate == rate) & df.offline_m.notna()]
        o = o.pivot_table(index=["u", "jit"], columns="tag", values="offline_m")
        print(f"{rate} Hz offline max |after - before| {float((o['after'] - o['before']).abs().max()):.3g} m "
              f"over {len(o)} sessions")
        for j in JITTERS:
            a = df[(df.rate == rate) & (df.tag == "after") & (df.jit == j)].set_index("u")
            r = 100 * (a.live_m / a.offline_m - 1)
            print(f"{rate} Hz after  {j} ms live / offline - 1: median {r.median():+.3f} %")
    worst = 0.0
    count_ok = True
    for p in sorted(OUT.glob("r*/*/walk_j0_live_after.csv")):
        a, b = pd.read_csv(p), pd.read_csv(p.with_name("walk_j0_live_before.csv"))
        count_ok &= len(a) == len(b)
        if len(a) == len(b):
            worst = max(worst, float(np.max(np.abs(a[["end_s", "x", "y"]].to_numpy() - b[["end_s", "x", "y"]]
                                                   .to_numpy()))))
    print(f"0 ms live before / after: same step counts {count_ok}, max |diff| end_s/x/y {worst:.3g}")


if __name__ == "__main__":
    phase = sys.argv[1]
    if phase == "report":
        report([json.loads(line) for line in open(sys.argv[2]) if line.startswith("{")])
    else:
        step = int(sys.argv[4]) if len(sys.argv) > 4 else 1
        for user in range(int(sys.argv[2]), int(sys.argv[3]), step):
            for ph in ("sim", "prep", "run") if phase == "all" else (phase,):
                if ph == "prep" and (folder(user, RATES[-1]) / "wb" / "manifest.json").exists():
                    continue
                {"sim": sim, "prep": prep, "run": run}[ph](user)
                print(ph, user, flush=True)
