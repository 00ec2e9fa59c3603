"""Decision L338's rule (docs/decisions/localization.md): L337's ramp climbs (``evaluate.RAMP_CLIMBS``) measured once.
Each fresh simulated session (users 6351-6366) is tracked by the CLI as ``track --altitude fused`` (foot) and ``track
--pipeline waist-pendulum`` (lower back), the real recordings with a waist barometer as the CLI chooses; the floors
are recomputed from the written steps.csv / summary.json with the flag off ("now", checked against the summary) and
on (the summary is checked against the recomputation with the module's default). One line per track, then the
rule's conditions. Measured once with the flag off by default; its output is experiments/results/ramp_floors_l338.txt.
L339 adopted it; decision L595 removed the switch: the "now" arm is :func:`l127_alone` (the old off branch,
``climb_slope_rows`` None), a stand-in for that arm only.

    PYTHONPATH=. OMP_NUM_THREADS=1 python experiments/ramp_floors_l338.py [--work DIR]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from contextlib import contextmanager, nullcontext
from pathlib import Path
from unittest import mock

import pandas as pd

from pdrlearn.track import evaluate as ev

ROUTES = {
    "RAMP": "stand:5, straight:60, slope:200:6, straight:30, up:20, straight:30, down:20, straight:30, "
            "slope:200:-6, straight:60, stand:5",
    "R12": "stand:3, straight:5, slope:9:8.33, straight:1.5, slope:9:8.33, straight:1.5, slope:9:8.33, "
           "straight:1.5, slope:9:8.33, straight:5, turn:180, straight:5, slope:36:-8.33, straight:5, stand:3",
    "STAIRWELL": "stand:3, straight:5, up:9, straight:1.5, turn:180, up:9, straight:5, turn:180, down:9, "
                 "straight:1.5, turn:180, down:9, straight:5, stand:3",
    "LEVEL": "stand:3, straight:150, turn:180, straight:150, stand:3",
    "LIFT": "stand:3, straight:10, lift:+9, straight:10, lift:-9, straight:10, stand:3",
}
USERS = {"RAMP": range(6351, 6361), "R12": range(6361, 6363), "STAIRWELL": range(6363, 6365), "LEVEL": [6365],
         "LIFT": [6366]}
KEYS = ("floors_up", "floors_down", *(f"floors_{d}_{k}" for d in ("up", "down") for k in ev.CLIMB_KINDS))
REAL = [Path(p) for p in ("/work/shared/data", "datasets/external")]


@contextmanager
def l127_alone():
    """L127's climbs alone, as before L337: no row is a climb row by its grade (what ``RAMP_CLIMBS = False`` did)."""
    with mock.patch.object(ev, "climb_slope_rows", lambda steps, info=None: None):
        yield


def cli(*args) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *map(str, args)], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


def floors(out: Path, on: bool) -> dict:
    """The floor keys of the track in ``out`` recomputed from its steps.csv and summary.json: L337's rule (``on``)
    or L127 alone."""
    steps = pd.read_csv(out / "steps.csv")
    sm = json.loads((out / "summary.json").read_text())
    info, h = sm.get("info") or {}, sm.get("storey_height_m", ev.STOREY_HEIGHT_M)
    with nullcontext() if on else l127_alone():
        dz, bridge = ev._climb_dz(steps)
        res = {}
        if dz is not None:
            up, down, _ = ev.count_floors_by_climb(dz, h, bridge=bridge, slope_rows=ev.climb_slope_rows(steps, info))
            res = {"floors_up": up, "floors_down": down, **ev.floors_by_kind(steps, h, info)}
    return res


def measure(session: Path, out: Path, *args) -> tuple[dict, dict, dict]:
    if not (out / "summary.json").exists():
        cli("track", session, "--out", out, *args)
    sm = json.loads((out / "summary.json").read_text())
    now, cand = floors(out, False), floors(out, True)
    mine = cand  # the summary was written with the rule (L339: adopted)
    mismatch = {k: (mine.get(k), sm.get(k)) for k in mine if mine.get(k) != sm.get(k)}
    if mismatch:
        print(f"  !! recomputed 'now' differs from the summary: {mismatch}")
    return sm, now, cand


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", default="/tmp/ramp_floors_l338")
    work = Path(ap.parse_args().work)
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    for route, users in USERS.items():
        for u in users:
            sess = work / f"{route}_u{u}"
            if not (sess / "meta.json").exists():
                cli("simulate", "--route", ROUTES[route], "--user-seed", u, "--seed", u, "--out", sess)
            for pipe, args in (("fused", ("--altitude", "fused")), ("waist", ("--pipeline", "waist-pendulum"))):
                sm, now, cand = measure(sess, work / f"t_{route}_u{u}_{pipe}", *args)
                rows.append({"route": route, "user": u, "pipe": pipe, "ref_up": sm.get("floors_up_ref"),
                             "ref_down": sm.get("floors_down_ref"), "ascent_m": sm.get("ascent_m"),
                             **{f"now_{k}": now.get(k) for k in KEYS}, **{f"new_{k}": cand.get(k) for k in KEYS}})
                print(f"{route:9s} {u} {pipe:5s} ref {sm.get('floors_up_ref')}/{sm.get('floors_down_ref')} "
                      f"ascent {sm.get('ascent_m'):.2f} now {now['floors_up']}/{now['floors_down']} "
                      f"(ramps {now['floors_up_ramps']}/{now['floors_down_ramps']}) new {cand['floors_up']}/"
                      f"{cand['floors_down']} (ramps {cand['floors_up_ramps']}/{cand['floors_down_ramps']}, stairs "
                      f"{cand['floors_up_stairs']}/{cand['floors_down_stairs']})", flush=True)
    for root in REAL:
        for sess in sorted(root.glob("mobgap_*")):
            if not (sess / "wBarometer.csv").exists():
                continue
            sm, now, cand = measure(sess, work / f"t_real_{sess.name}")
            rows.append({"route": "REAL", "user": sess.name, "pipe": sm.get("pipeline"),
                         **{f"now_{k}": now.get(k) for k in KEYS}, **{f"new_{k}": cand.get(k) for k in KEYS}})
            print(f"REAL {sess.name} {sm.get('pipeline')} now {now.get('floors_up')}/{now.get('floors_down')} "
                  f"new {cand.get('floors_up')}/{cand.get('floors_down')}", flush=True)
    t = pd.DataFrame(rows)
    t.to_csv(work / "l338.csv", index=False)
    ramp = t[t.route == "RAMP"]
    a1 = bool(((ramp.new_floors_up - 5).abs() <= 1).all() and ((ramp.new_floors_down - 5).abs() <= 1).all())
    spread = {p: int(g.new_floors_up.max() - g.new_floors_up.min()) for p, g in ramp.groupby("pipe")}
    spread_now = {p: int(g.now_floors_up.max() - g.now_floors_up.min()) for p, g in ramp.groupby("pipe")}
    a = a1 and all(v <= 1 for v in spread.values())
    r12 = t[t.route == "R12"]
    b = bool(((r12.new_floors_up - r12.ref_up).abs() <= 1).all()
             and ((r12.new_floors_down - r12.ref_down).abs() <= 1).all())
    ctl = t[t.route.isin(["STAIRWELL", "LEVEL", "LIFT"])]
    ck = [k for k in KEYS if "ramps" not in k]
    c = bool(all((ctl[f"now_{k}"] == ctl[f"new_{k}"]).all() for k in ck))
    real = t[t.route == "REAL"]
    d = bool(all((real[f"now_{k}"] == real[f"new_{k}"]).all() for k in ("floors_up", "floors_down")))
    print(f"(a) RAMP: all within 1 of 5/5 {a1}; floors_up spread now {spread_now} new {spread}: {a}")
    print(f"(b) R12 within 1 of ref: {b}")
    print(f"(c) STAIRWELL/LEVEL/LIFT floors, _stairs, _rides unchanged: {c}")
    print(f"(d) real floors unchanged on {len(real)} recordings: {d}")
    print(f"ADOPT: {a and b and c and d}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
