"""Decision C230 (session 49, FJ; docs/decisions/cohort.md): the steps in each full minute of a 6MWT
(:func:`pdrlearn.track.corridor.steps_per_minute`, the clinical pace line's "steps per minute") against the
simulator's heel strikes, on fresh users 16740-16747.

Each user walks a 6MWT on a 30 m corridor (trial s49t1's gen.py route; every other user rests 15-30 s in one lap),
tracked on the foot (plasys) and on the lower back (waist-pendulum, uncalibrated) with ``--corridor 30
--walk-test-duration 360``. Truth: ics.csv's heel strikes counted in the same minutes from the track's
``walk_test_start_s``. Run: ``python experiments/clinical_minutes_s49_c230.py [WORK]`` (PYTHONPATH at the tree's
root); ``--jobs 2`` runs two users at once.
"""

from __future__ import annotations

import json
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from corridor_scale_s49_w562 import laps_route, run, simulate_user

USERS = range(16740, 16748)  # C230; C232: --users 16748-16755
PY = [sys.executable, "-m", "pdrlearn"]
UNITS = {"foot": [], "waist": ["--units", "waist", "--pipeline", "waist-pendulum"]}


def route(uid: int, sl: float, st: float, total_s: float = 400.0) -> tuple[str, bool]:
    """gen.py's corridor route of trial s49t1: laps of 30 m with a cone turn after each, a rest in one lap."""
    rng = np.random.default_rng(uid + 7)
    turn = "curve:180:0.5" if uid % 4 < 2 else "turn:180"
    rest = (1 + uid % 5, float(rng.uniform(0.2, 0.8)), float(rng.uniform(15, 30))) if uid % 2 == 0 else None
    return laps_route(sl, st, turn, rest, total_s), rest is not None


def one(uid: int, work: Path) -> list[dict]:
    from pdrlearn.track.corridor import steps_per_minute

    ses, _, _, has_rest = simulate_user(uid, work, route)
    ic = np.sort(pd.read_csv(ses / "ics.csv").ic_ms.to_numpy() / 1000)
    rows = []
    for unit, opts in UNITS.items():
        out = work / f"t{uid}_{unit}"
        if not (out / "summary.json").is_file():
            run([*PY, "track", str(ses), *opts, "--corridor", "30", "--walk-test-duration", "360", "--no-plot",
                 "--force", "--out", str(out)])
        s = json.loads((out / "summary.json").read_text())
        n = len(s.get("walk_test_distance_per_minute_m") or []) or 6
        got = steps_per_minute(pd.read_csv(out / "steps.csv"), s["walk_test_start_s"], n)
        edges = s["walk_test_start_s"] + 60.0 * np.arange(n + 1)
        true = np.histogram(ic, bins=edges)[0].tolist()
        rows.append({"user": uid, "unit": unit, "rest": has_rest, "got": got, "true": true,
                     "missed": s.get("turn_steps_missed") or 0})
    return rows


def main() -> None:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    jobs = int(sys.argv[sys.argv.index("--jobs") + 1]) if "--jobs" in sys.argv else 1
    users = USERS
    if "--users" in sys.argv:  # decision C232: a fresh range, FIRST-LAST
        first, last = sys.argv[sys.argv.index("--users") + 1].split("-")
        users = range(int(first), int(last) + 1)
    args = [a for a in args if not a.isdigit() and "-" not in a]
    work = Path(args[0] if args else "out/c230")
    work.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(jobs) as pool:
        rows = [r for rs in pool.map(lambda u: one(u, work), users) for r in rs]
    for r in rows:
        print(f"{r['user']} {r['unit']:5s} rest={r['rest']!s:5s} turn_steps_missed={r['missed']} got {r['got']} "
              f"true {r['true']}")
    summarise(rows, "C230")
    from pdrlearn.report.clinical import minute_steps_given

    summarise([r for r in rows if minute_steps_given(r["unit"] == "waist", r["missed"])], "C232 given")
    print(f"C232 withheld: {sum(not minute_steps_given(r['unit'] == 'waist', r['missed']) for r in rows)} sessions, "
          f"of them with turn_steps_missed > 0: {sum(r['missed'] > 0 and r['unit'] == 'waist' for r in rows)}")


def summarise(rows: list[dict], name: str) -> None:
    for unit in UNITS:
        sel = [r for r in rows if r["unit"] == unit]
        diffs = [abs(g - t) for r in sel for g, t in zip(r["got"], r["true"], strict=False)]
        n_minutes = sum(len(r["true"]) for r in sel)
        within = sum(d <= 3 for d in diffs)
        rest_ok = rest_n = 0
        for r in sel:
            if not r["rest"]:
                continue
            rest_n += 1
            true, got = np.array(r["true"]), np.array(r["got"])
            k = int(np.argmin(true))  # the rest's minute: the fewest true steps
            rest_ok += bool(len(got) == len(true) and got[k] <= np.median(got) - 10)
        pct = 100 * within / max(n_minutes, 1)
        print(f"{name} {unit} ({len(sel)} sessions): within 3 steps on {within} of {n_minutes} minutes ({pct:.1f} %), "
              f"max |diff| {max(diffs) if diffs else float('nan')}; rest minute >= 10 under the median on {rest_ok} "
              f"of {rest_n}; minute counts got {len(diffs)} of {n_minutes}")


if __name__ == "__main__":
    main()
