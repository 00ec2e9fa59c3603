"""Decision W625 (docs/decisions/waist.md): a waist gap of at most 5 s inside walking bridged at the pace either side.

``sim U`` simulates user U's control walk (no gap) and the gapped copy (``simulate --gap waist:T:D``) under $OUT;
``run U`` tracks both (waist-pendulum, ``--units waist``) with the option ``gap_bridge`` off (before) and on (after)
and writes OUT/res_U.json; ``report A B`` prints the rule's numbers over users A..B-1; ``real`` cuts an artificial gap
into the real lower-back recordings and prints the bridged distance against the cut part's distance in the uncut track.
Groups (by (U - 20900) % 40): 0-19 a gap inside straight walking at 15 s, 20-29 a gap centred on the 90 deg turn,
30-39 a gap inside a 12 s stand. D = 1 + U % 8 s (the stand group: at most the stand less 4 s).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pandas as pd

OUT = os.environ.get("OUT", "/tmp/fk_m/w625")
PY = sys.executable
ROUTES = {"walk": "stand:5, straight:40, turn:90, straight:30, stand:5",
          "stop": "stand:5, straight:25, stand:12, straight:25, stand:5"}


def group(u: int) -> str:
    k = (u - 20900) % 40
    return "straight" if k < 20 else "turn" if k < 30 else "stop"


def simulate(route: str, u: int, out: str, gap: str | None = None) -> None:
    cmd = [PY, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed", str(u), "--rate", "50", "--out", out]
    if gap:
        cmd += ["--gap", gap]
    subprocess.run(cmd, check=True, capture_output=True)


def gap_time(u: int, ctrl: str) -> tuple[float, float]:
    d = 1.0 + u % 8
    tr = pd.read_csv(f"{ctrl}/trajectory.csv")
    t = tr.iloc[:, 0].to_numpy(float) / 1000.0
    x, y = tr["x"].to_numpy(float), tr["y"].to_numpy(float)
    g = group(u)
    if g == "straight":
        return 15.0, d
    if g == "turn":
        h = np.unwrap(np.arctan2(np.gradient(y), np.gradient(x)))
        h = h - h[np.searchsorted(t, 10.0)]
        k = int(np.flatnonzero(np.abs(h) > np.radians(45))[0])
        return round(float(t[k]) - d / 2, 2), d
    v = np.hypot(np.gradient(x, t), np.gradient(y, t))
    mid = (t > 15) & (v < 0.02)
    a, b = float(t[mid][0]), float(t[mid][-1])
    d = min(d, b - a - 4.0)
    return round(a + 2.0, 2), d


def sim(u: int) -> None:
    route = ROUTES["stop" if group(u) == "stop" else "walk"]
    ctrl, gapped = f"{OUT}/c_{u}", f"{OUT}/g_{u}"
    simulate(route, u, ctrl)
    t, d = gap_time(u, ctrl)
    simulate(route, u, gapped, f"waist:{t}:{d}")
    json.dump({"t": t, "d": d, "group": group(u)}, open(f"{OUT}/gap_{u}.json", "w"))


def track(path: str, on: bool):
    from pdrlearn.io.plasys import read_session
    from pdrlearn.track.units import keep_units
    from pdrlearn.track.waist import track_waist

    s = keep_units(read_session(path), ("waist",))
    return track_waist(s, pipeline="waist-pendulum", params={"options": {"gap_bridge": on}})


def run(u: int) -> None:
    gp = json.load(open(f"{OUT}/gap_{u}.json"))
    res = dict(gp, user=u)
    for name in ("c", "g"):
        for on in (False, True):
            r = track(f"{OUT}/{name}_{u}", on)
            st = r.steps
            res[f"{name}_{int(on)}_dist"] = float(np.nansum(np.abs(st["length_m"].to_numpy(float))))
            res[f"{name}_{int(on)}_bridged"] = float(st["gap_bridged_m"].sum()) if "gap_bridged_m" in st else 0.0
            res[f"{name}_{int(on)}_csv"] = st.to_csv(index=False)
    res["c_identical"] = res.pop("c_0_csv") == res.pop("c_1_csv")
    res.pop("g_0_csv"), res.pop("g_1_csv")
    json.dump(res, open(f"{OUT}/res_{u}.json", "w"))
    print(json.dumps({k: v for k, v in res.items()}))


def report(a: int, b: int) -> None:
    rows = [json.load(open(f"{OUT}/res_{u}.json")) for u in range(a, b) if os.path.exists(f"{OUT}/res_{u}.json")]
    for g in ("straight", "turn", "stop"):
        rr = [r for r in rows if r["group"] == g]
        if not rr:
            continue
        e0 = np.array([r["g_0_dist"] - r["c_0_dist"] for r in rr])
        e1 = np.array([r["g_1_dist"] - r["c_0_dist"] for r in rr])
        br = np.array([r["g_1_bridged"] for r in rr])
        print(f"{g:8s} n={len(rr)} |distance error| vs no-gap track: before median {np.median(np.abs(e0)):.2f} m "
              f"max {np.max(np.abs(e0)):.2f}; after median {np.median(np.abs(e1)):.2f} m max {np.max(np.abs(e1)):.2f};"
              f" bridged m median {np.median(br):.2f} max {np.max(br):.2f}")
    walk = [r for r in rows if r["group"] != "stop"]
    e0 = np.median([abs(r["g_0_dist"] - r["c_0_dist"]) for r in walk])
    e1 = np.median([abs(r["g_1_dist"] - r["c_0_dist"]) for r in walk])
    stop = [r["g_1_dist"] - r["g_0_dist"] for r in rows if r["group"] == "stop"]
    print(f"gapped walks n={len(walk)}: median |error| before {e0:.2f} m, after {e1:.2f} m, ratio {e1 / e0:.3f}")
    print(f"stop gaps n={len(stop)}: added by the bridge max {max(stop, default=float('nan')):.3f} m")
    print(f"controls byte-identical off/on: {sum(r['c_identical'] for r in rows)} of {len(rows)}")


def real(root: str = "/work/main/datasets/external", cut_s: float = 3.0) -> None:
    import glob
    import shutil

    rel = []
    for src in sorted(glob.glob(f"{root}/mobgap_*")):
        name = os.path.basename(src)
        st = track(src, True).steps
        chained = st["has_next"].to_numpy(bool).copy()
        chained[:-1] &= np.isclose(st["end_s"].to_numpy(float)[:-1], st["start_s"].to_numpy(float)[1:])
        best, k = (0, 0), 0  # the longest run of chained steps
        for i in range(len(st) + 1):
            if i == len(st) or not chained[i]:
                best = max(best, (i - k, k))
                k = i + 1
        n, k0 = best
        t_mid = 0.5 * (st["start_s"].iloc[k0] + st["end_s"].iloc[k0 + n - 1])
        a = t_mid - cut_s / 2
        dst = f"{OUT}/real_{name}"
        shutil.rmtree(dst, ignore_errors=True)
        shutil.copytree(src, dst)
        for f in ("wAccelerometer.csv", "wGyroscope.csv"):
            df = pd.read_csv(f"{dst}/{f}")
            t = df["timestamp"].to_numpy(float) / 1000.0
            df[(t < a) | (t >= a + cut_s)].to_csv(f"{dst}/{f}", index=False)
        cut = track(dst, True).steps
        br = cut["gap_bridged_m"].to_numpy(float) if "gap_bridged_m" in cut else np.zeros(len(cut))
        if (br > 0).any():
            j = int(np.flatnonzero(br > 0)[0])
            s0, s1 = float(cut["start_s"].iloc[j]), float(cut["end_s"].iloc[j])
            ss = st["start_s"].to_numpy(float)
            uncut = float(np.abs(st["length_m"].to_numpy(float)[(ss >= s0 - 1e-6) & (ss < s1 - 1e-6)]).sum())
            e = abs(br[j] - uncut) / uncut
            print(f"{name}: longest sequence {n} steps, gap {a:.2f}-{a + cut_s:.2f} s: bridged {br[j]:.2f} m over "
                  f"{s0:.2f}-{s1:.2f} s, uncut track {uncut:.2f} m, |diff| {100 * e:.1f} %")
        else:
            e = 1.0
            print(f"{name}: longest sequence {n} steps, gap {a:.2f}-{a + cut_s:.2f} s: not bridged (counted 100 %)")
        rel.append(e)
    print(f"real n={len(rel)}: median |bridged - uncut| / uncut {100 * np.median(rel):.1f} %, "
          f"bridged {sum(e < 1.0 for e in rel)} of {len(rel)}")


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "sim":
        sim(int(sys.argv[2]))
    elif cmd == "run":
        run(int(sys.argv[2]))
    elif cmd == "report":
        report(int(sys.argv[2]), int(sys.argv[3]))
    elif cmd == "real":
        real()
