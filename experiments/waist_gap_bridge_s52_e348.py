"""Decision E348 (session 52, FF): the streamed heading change across a dropout of both units, before / after.

    BASE=/tmp/ff_base python experiments/waist_gap_bridge_s52_e348.py sim U        # simulate user U (+ its gap copy)
    BASE=/tmp/ff_base python experiments/waist_gap_bridge_s52_e348.py run U        # track it (before / after / offline)
    python experiments/waist_gap_bridge_s52_e348.py report 19340 19370             # E348's numbers
    python experiments/waist_gap_bridge_s52_e348.py live U      # E354: the live Tracker (pdrlearn run's replay)

``BASE``: a directory holding the ``pdrlearn`` package before E348 (``git archive 49511d75 pdrlearn | tar -x``).
Users 19340-19354 walk straight (gap at 12 s), 19355-19369 walk into a 90 deg curve of 4 m radius (the gap opens
where the true heading has turned 20 deg); the gap lasts 1 + U % 5 s and is cut from every sensor file of the
gap-free simulation (as ``simulate --gap both:T:D``: no sample of either unit in [T, T + D) s). The heading change
across the gap: the mean heading of the 2 strides after the gap row less that of the 2 strides before it (steps.csv),
against the truth's heading averaged over the same strides."""

from __future__ import annotations

import csv
import filecmp
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(os.environ.get("OUT", "/tmp/ff_meas"))
#: E354 (session 52, FK): the first curve user and the two no-gap users (E348's by default)
SPLIT = int(os.environ.get("SPLIT", "19355"))
NOGAP = tuple(int(u) for u in os.environ.get("NOGAP", "19340,19355").split(","))
JOBS = os.environ.get("JOBS", "before,after,offline").split(",")
ROUTES = {"straight": "stand:3, straight:30, stand:2", "curve": "stand:3, straight:8, curve:90:4, straight:8, stand:2"}


def kind_of(u: int) -> str:
    return "straight" if u < SPLIT else "curve"


def cli(code: Path, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(code)}
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True, env=env, cwd=str(code))


def truth(sim: Path) -> tuple[np.ndarray, np.ndarray]:
    a = np.loadtxt(sim / "trajectory.csv", delimiter=",", skiprows=1)
    return a[:, 0] / 1000.0, np.unwrap(a[:, 4])


def gap_of(u: int, sim: Path) -> tuple[float, float]:
    if kind_of(u) == "straight":
        start = 12.0
    else:
        t, h = truth(sim)
        start = float(t[np.argmax(np.abs(h - h[0]) > math.radians(20))])
    return round(start, 2), float(1 + u % 5)


def cut(src: Path, dst: Path, a: float, b: float) -> None:
    shutil.copytree(src, dst)
    for f in dst.glob("[fw]*.csv"):
        if f.name in ("foot_trajectory.csv",):
            continue
        rows = list(csv.reader(open(f)))
        keep = [rows[0]] + [r for r in rows[1:] if not a <= float(r[0]) / 1000.0 < b]
        with open(f, "w", newline="") as fh:
            csv.writer(fh).writerows(keep)


def simulate(u: int) -> None:
    sim = OUT / f"u{u}"
    if not sim.exists():
        cli(ROOT, "simulate", "--route", ROUTES[kind_of(u)], "--rate", "100", "--user-seed", str(u), "--seed", str(u),
            "--out", str(sim))
    a, d = gap_of(u, sim)
    if not (OUT / f"gap_u{u}").exists():
        cut(sim, OUT / f"gap_u{u}", a, a + d)


def run(u: int) -> None:
    base = Path(os.environ["BASE"])
    jobs = [("before", base, ["--streaming"]), ("after", ROOT, ["--streaming"]), ("offline", ROOT, [])]
    for name, code, extra in jobs:
        if name not in JOBS:
            continue
        out = OUT / f"gap_u{u}_{name}"
        if not out.exists():
            cli(code, "track", str(OUT / f"gap_u{u}"), *extra, "--out", str(out))
    if u in NOGAP:  # E348 (d): without a gap, before / after byte-identical
        for name, code in [(n, c) for n, c in (("before", base), ("after", ROOT)) if n in JOBS]:
            out = OUT / f"u{u}_{name}"
            if not out.exists():
                cli(code, "track", str(OUT / f"u{u}"), "--streaming", "--out", str(out))


def across(steps: Path, t: np.ndarray, h: np.ndarray) -> tuple[float, float]:
    rows = list(csv.DictReader(open(steps)))
    g = next(i for i, r in enumerate(rows) if float(r.get("gap_s") or 0) > 0)
    walk = [i for i, r in enumerate(rows) if float(r.get("gap_s") or 0) == 0 and float(r["length_m"]) > 0]
    sides = [[i for i in walk if i < g][-2:], [i for i in walk if i > g][:2]]
    est, tru = [], []
    for side in sides:
        hd = np.unwrap([float(rows[i]["heading_rad"]) for i in side])
        est.append(float(np.mean(hd)))
        tru.append(float(np.mean([np.mean(h[(t >= float(rows[i]["start_s"])) & (t <= float(rows[i]["end_s"]))])
                                  for i in side])))
    err = (est[1] - est[0]) - (tru[1] - tru[0])
    return math.degrees(math.remainder(err, 2 * math.pi)), math.degrees(tru[1] - tru[0])


def report(a: int, b: int, *more: int) -> None:
    """E348's numbers over users ``a`` to ``b - 1`` (E354: and any further ranges ``c d ...``)."""
    errs: dict[tuple[str, str], list] = {}
    bounds = (a, b, *more)
    for u in [u for k in range(0, len(bounds), 2) for u in range(bounds[k], bounds[k + 1])]:
        sim = OUT / f"u{u}"
        t, h = truth(sim)
        g0, d = gap_of(u, sim)
        line = [f"u{u} {kind_of(u):8s} gap {g0:6.2f}+{d:.0f}s"]
        for name in [n for n in ("before", "after", "offline") if n in JOBS]:  # E364: JOBS=before,after
            e, tr = across(OUT / f"gap_u{u}_{name}" / "steps.csv", t, h)
            errs.setdefault((kind_of(u), name), []).append(e)
            line.append(f"{name} {e:+7.2f}")
        print(" ".join(line) + f"  (true change {tr:+7.2f} deg)")
    for (kind, name), v in errs.items():
        v = np.abs(v)
        print(f"{kind:8s} {name:8s} n={len(v)} median |err| {np.median(v):.2f} deg, max {np.max(v):.2f} deg")
    for u in NOGAP:
        x, y = OUT / f"u{u}_before" / "steps.csv", OUT / f"u{u}_after" / "steps.csv"
        if x.exists() and y.exists():
            print(f"no gap u{u}: steps.csv byte-identical before / after: {filecmp.cmp(x, y, shallow=False)}")


def live(u: int) -> None:
    """Decision E354: the live ``Tracker`` (``pdrlearn run``'s replay of the sim bundle, 1 s chunks) on user U's gap
    session, this tree: its heading change across the gap against the truth, and ``track --streaming``'s (after)."""
    from pdrlearn.runtime.__main__ import replay

    _, steps = replay(ROOT / "models" / "plasys-sim-default", OUT / f"gap_u{u}")
    out = OUT / f"gap_u{u}_live"
    out.mkdir(exist_ok=True)
    keys = ("start_s", "end_s", "length_m", "heading_rad", "gap_s")
    with open(out / "steps.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(keys)
        w.writerows([[getattr(st, k) for k in keys] for st in steps])
    t, h = truth(OUT / f"u{u}")
    for name in ("live", "after"):
        e, tr = across(OUT / f"gap_u{u}_{name}" / "steps.csv", t, h)
        print(f"u{u} {name:6s} heading change error {e:+7.2f} deg (true change {tr:+7.2f} deg)")


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "sim":
        simulate(int(sys.argv[2]))
    elif cmd == "run":
        run(int(sys.argv[2]))
    elif cmd == "live":
        live(int(sys.argv[2]))
    else:
        report(*(int(x) for x in sys.argv[2:]))
