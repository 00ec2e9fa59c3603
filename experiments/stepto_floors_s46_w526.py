"""Decision W526's measurement: a run of the lower back's climb rows that turns back by a climb (1.5 m) is two climbs.

Per track the floors are counted twice from one track result: the candidate (``climb_turn_pieces``) and main's
reading (the whole run of ``climb`` rows one piece, signed by its net height). Sets (W526's adoption rule):
1. users 14250-14269, trial T1's step-to return flight with the patient's limp, ``track --units waist``;
2. the same users and route step over step at their own gait;
3. the real lower-back recordings with a barometer (datasets/external mobgap_*), floors and ramps.
Also printed: tracks whose end floor (storeys_changed) differs from L64's floor of the altitude change.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/stepto_floors_s46_w526.py [--users 14250-14269]
     [--work DIR]   (simulated sessions are written to DIR, default a temporary folder)
"""

from __future__ import annotations

import argparse
import logging
import subprocess
import sys
import tempfile
from pathlib import Path
from unittest import mock

from pdrlearn.io import read_session
from pdrlearn.track.evaluate import STOREY_BAND, evaluate_track
from pdrlearn.track.units import keep_units

STEP_TO = ("stand:3, straight:4, up:12:0.17:0.28:step-to-step:left, stand:3, turn:180, "
           "down:12:0.17:0.28:step-to-step:right, straight:4, stand:3")
STEP_OVER = "stand:3, straight:4, up:12, stand:3, turn:180, down:12, straight:4, stand:3"
#: trial T1's patient (F3's command)
LIMP = ["--step-length", "0.42", "--step-time", "0.7", "--step-time-asymmetry", "0.25", "--step-length-asymmetry",
        "0.2", "--stance-time-asymmetry", "0.15", "--paretic-side", "right", "--bounce", "pendulum"]


def simulate(route: str, user: int, extra: list[str], out: Path) -> Path:
    if not (out / "meta.json").exists():
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, *extra, "--user-seed",
                        str(user), "--rate", "100", "--out", str(out)], check=True, capture_output=True)
    return out


def whole_run(dz):
    """Main's reading: the whole run of climb rows one piece."""
    return [(0, len(dz))] if len(dz) else []


def floors(session, res) -> tuple[dict, dict]:
    cand = evaluate_track(res, session)
    with mock.patch("pdrlearn.kernels.barometer.climb_turn_pieces", whole_run):
        main = evaluate_track(res, session)
    return main, cand


def l64_end(ev: dict) -> int:
    h = ev.get("storey_height_m") or 3.0
    x = float(ev.get("altitude_change_m") or 0.0) / h
    return int(round(x)) if abs(x - round(x)) <= STOREY_BAND else None


def main() -> None:
    logging.disable(logging.WARNING)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="14250-14269")
    ap.add_argument("--work", default=None)
    ap.add_argument("--external", default="datasets/external")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    work = Path(a.work or tempfile.mkdtemp(prefix="w526_"))
    from pdrlearn.track import get_pipeline

    waist = get_pipeline("waist-pendulum")
    exact = {k: [0, 0] for k in ("step-to", "step-over")}
    disagree = {k: [0, 0] for k in ("step-to", "step-over")}
    for u in range(lo, hi + 1):
        for label, route, extra in (("step-to", STEP_TO, LIMP), ("step-over", STEP_OVER, [])):
            d = simulate(route, u, extra, work / f"{label}_{u}")
            s = keep_units(read_session(d), ("waist",))  # track --units waist
            res = waist(s)
            m, c = floors(s, res)
            ref = (m["floors_up_ref"], m["floors_down_ref"])
            for i, ev in enumerate((m, c)):
                exact[label][i] += (ev["floors_up"], ev["floors_down"]) == ref
                disagree[label][i] += ev["storeys_changed"] != l64_end(ev)
            print(f"user {u} {label:9s} ref {ref[0]}/{ref[1]} | main {m['floors_up']}/{m['floors_down']} end "
                  f"{m['storeys_changed']:+d} | candidate {c['floors_up']}/{c['floors_down']} end "
                  f"{c['storeys_changed']:+d} | altitude {c['altitude_change_m']:+.2f} m", flush=True)
    for label in exact:
        print(f"{label}: floors = reference main {exact[label][0]}/{hi - lo + 1}, candidate {exact[label][1]}/"
              f"{hi - lo + 1}; end floor != L64's of the altitude change: main {disagree[label][0]}, candidate "
              f"{disagree[label][1]}")
    for d in sorted(Path(a.external).glob("mobgap_*_Test*")):
        s = read_session(d)
        res = waist(s)
        m, c = floors(s, res)
        keys = ("floors_up", "floors_down", "storeys_changed", "n_ramps")
        print(f"{d.name:28s} main {[m.get(k) for k in keys]} candidate {[c.get(k) for k in keys]}"
              f"{'' if all(m.get(k) == c.get(k) for k in keys) else '  CHANGED'}", flush=True)


if __name__ == "__main__":
    main()
