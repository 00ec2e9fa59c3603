"""Decision L385 (session 33, trial T4 finding 7): the corridor walk test's distance (``track --corridor 30``, L383)
against the simulated truth on the trial's 6MWT route, fresh users 7290-7299. Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/corridor_walk_test.py [WORKDIR]
Output: experiments/results/corridor_walk_test.txt (the printed lines).

Route: 13 laps of 30 m with ``curve:180:0.5`` cone turns, laps 7-13 slowed (``:short``), a 30 s rest at the cone after
lap 10; pendulum bounce. Truth of ``walk_test_distance_m``: the route's straight metres, 390 m (what the ATS rule
counts; the turns' arcs are not); of the tracked ``distance_m``: the path's (``distance_error_pct``). Calibration
walk: ``stand:3, straight:20, stand:3`` (seed 1), ``calibrate -d 20``.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

USERS = range(7290, 7300)
LAPS = ["straight:30"] + ["curve:180:0.5, straight:30"] * 5 + ["curve:180:0.5, straight:30:short"] * 3 + [
    "curve:180:0.5, straight:30:short, stand:30"] + ["curve:180:0.5, straight:30:short"] * 3
ROUTE = ", ".join(LAPS)
TRUTH_M = 13 * 30.0
CAL = "stand:3, straight:20, stand:3"
CONFIGS = {"plasys": [], "waist-pendulum uncal": ["--pipeline", "waist-pendulum"],
           "waist-pendulum cal": ["--pipeline", "waist-pendulum", "--params", "{p}/cal_waist-pendulum.json"],
           "waist-pll cal": ["--pipeline", "waist-pll", "--params", "{p}/cal_waist-pll.json"]}
PDR = [sys.executable, "-m", "pdrlearn"]


def run(*args: str) -> str:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{args}: exit {done.returncode}: {done.stderr[-2000:]}")
    return done.stdout


def prepare_user(u: int, p: Path) -> None:
    """User ``u``'s 6MWT walk (``p/walk``), its calibration walk and both lower-back calibrations under ``p``."""
    run("simulate", "--route", ROUTE, "-u", str(u), "--bounce", "pendulum", "--out", str(p / "walk"))
    run("simulate", "--route", CAL, "-u", str(u), "--bounce", "pendulum", "--seed", "1", "--out", str(p / "cal"))
    for pipe in ("waist-pendulum", "waist-pll"):
        run("calibrate", str(p / "cal"), "-p", pipe, "-d", "20", "--out", str(p / f"cal_{pipe}.json"), "--force")


def main(work: Path) -> None:
    rows = {c: [] for c in CONFIGS}
    lines = [f"route: {ROUTE}", f"truth of walk_test_distance_m: {TRUTH_M:.0f} m"]
    for u in USERS:
        p = work / f"u{u}"
        prepare_user(u, p)
        for c, extra in CONFIGS.items():
            s = json.loads(run("track", str(p / "walk"), *[a.format(p=p) for a in extra], "--corridor", "30",
                               "--out", str(p / c.replace(" ", "_")), "--force", "--json"))
            s = s.get("summary", s)
            corr = 100 * (s["walk_test_distance_m"] / TRUTH_M - 1)
            rows[c].append((corr, s.get("distance_error_pct"), s["n_laps"], s.get("fatigue_index")))
            line = (f"user {u} {c}: walk_test_distance_m {s['walk_test_distance_m']:.1f} ({corr:+.2f} %), n_laps "
                    f"{s['n_laps']}, tracked distance_m {s['distance_m']:.1f} ({s.get('distance_error_pct'):+.2f} %), "
                    f"per minute {' / '.join(f'{v:.1f}' for v in s['walk_test_distance_per_minute_m'])}, "
                    f"fatigue {s['fatigue_index']:.2f}")
            print(line, flush=True)
            lines.append(line)
    for c, r in rows.items():
        a = np.array([[x[0], x[1]] for x in r], float)
        e = np.abs(a)
        line = (f"{c}: corridor |error| median {np.median(e[:, 0]):.2f} % worst {np.max(e[:, 0]):.2f} %;"
                f" tracked |error| median {np.median(e[:, 1]):.2f} % worst {np.max(e[:, 1]):.2f} %;"
                f" n_laps {sorted({x[2] for x in r})}")
        print(line)
        lines.append(line)
    out = Path(__file__).resolve().parent / "results" / "corridor_walk_test.txt"
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp()))
