"""Decision E371's measurement (docs/decisions/export.md): the live waist tracker with W59's fill (the default,
"before") and with ``uniform_clock="nearest"`` ("after") on a jittered phone stream against the same stream without
jitter. Sim and prep are E366's (``waist_jitter_s53_e366``, its phoneify and bundle); the live loop runs in-process
(the trial's ``live.py``: 10-sample pushes, the barometer pushed up to each chunk's last sample).

    PHONEIFY=/tmp/fm_m/phoneify.py OUT=/tmp/fm_m/e371 python experiments/waist_jitter_s53_e371.py all U0 U1 > LOG
    python experiments/waist_jitter_s53_e371.py report LOG
"""

from __future__ import annotations

import json
import os
import sys
import time

import numpy as np
import pandas as pd

import waist_jitter_s53_e366 as e366

e366.WALK = ("stand:5, straight:35, turn:90, straight:25, turn:90, straight:20, turn:-90, straight:25, stand:5")
e366.JITTERS = JITTERS = (0, 2, 4, 6)
#: the arms ``tag:clock`` (``ARMS=e372:nearest-phase`` for E372's); "0" is W59's fill, the default
ARMS = {a.split(":")[0]: {"0": False}.get(a.split(":")[1], a.split(":")[1])
        for a in os.environ.get("ARMS", "before:0,after:nearest").split(",")}


def _read(path):
    a = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return a[:, 0] / 1000.0, a[:, 1:]


def live(folder, rate: int, clock) -> list[tuple[float, float, float, float]]:
    """The steps ``(end_s, x, y, length_m)`` of the live tracker on the session ``folder``."""
    from pdrlearn.runtime import WaistTracker, load_waist_bundle

    ta, acc = _read(folder / "wAccelerometer.csv")
    _, gyr = _read(folder / "wGyroscope.csv")
    tb, baro = _read(folder / "wBarometer.csv")
    tr = WaistTracker(load_waist_bundle(str(folder.parent / "wb")), fs=float(rate), drop_duplicate_timestamps=True,
                      uniform_clock=clock)
    steps, bi = [], 0
    for i in range(0, ta.size, 10):
        j = min(i + 10, ta.size)
        while bi < tb.size and tb[bi] <= ta[j - 1]:
            tr.push_barometer(tb[bi:bi + 1], baro[bi:bi + 1, 0])
            bi += 1
        steps += tr.push(ta[i:j], acc[i:j], gyr[i:j])
    steps += tr.flush()
    return [(s.end_s, s.x, s.y, s.length_m) for s in steps]


def run(u: int) -> None:
    while not (e366.folder(u, e366.RATES[-1]) / "wb" / "manifest.json").exists():  # another worker's prep
        time.sleep(10)
    for rate in e366.RATES:
        d = e366.folder(u, rate)
        for j in JITTERS:
            for tag, clock in ARMS.items():
                st = live(d / f"walk_j{j}", rate, clock)
                np.save(d / f"live_j{j}_{tag}.npy", np.array(st))
                print(json.dumps({"u": u, "rate": rate, "jit": j, "tag": tag, "live_m": sum(s[3] for s in st)}),
                      flush=True)


def report(rows: list[dict]) -> None:
    df = pd.DataFrame(rows)
    for rate in e366.RATES:
        for j in JITTERS[1:]:
            for tag in sorted(set(df.tag)):
                x = df[(df.rate == rate) & (df.tag == tag)].pivot(index="u", columns="jit", values="live_m").dropna()
                r = 100 * (x[j] / x[0] - 1)
                print(f"{rate} Hz {tag:6s} live {j} ms / 0 ms - 1: mean {r.mean():+.3f} %, median |.| "
                      f"{r.abs().median():.3f} %, mean |.| {r.abs().mean():.3f} %, max |.| {r.abs().max():.3f} % "
                      f"(n={r.size})")
    for tag in sorted(set(df.tag) - {"before"}):
        worst, same = 0.0, True
        for p in sorted(e366.OUT.glob(f"r*/*/live_j0_{tag}.npy")):
            if not p.with_name("live_j0_before.npy").exists():
                continue
            a, b = np.load(p), np.load(p.with_name("live_j0_before.npy"))
            same &= a.shape == b.shape
            if a.shape == b.shape:
                worst = max(worst, float(np.max(np.abs(a[:, :3] - b[:, :3]))))
        print(f"0 ms live before / {tag}: same step counts {same}, max |diff| end_s/x/y {worst:.3g}")


if __name__ == "__main__":
    if sys.argv[1] == "report":
        report([json.loads(line) for line in open(sys.argv[2]) if line.startswith("{")])
    else:
        for user in range(int(sys.argv[2]), int(sys.argv[3])):
            for ph in ("sim", "prep", "run") if sys.argv[1] == "all" else (sys.argv[1],):
                if ph == "prep" and (e366.folder(user, e366.RATES[-1]) / "wb" / "manifest.json").exists():
                    continue
                {"sim": e366.sim, "prep": e366.prep, "run": run}[ph](user)
                print(ph, user, flush=True)
