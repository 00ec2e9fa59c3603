"""Decision L687's measurement (session 46): a foot + lower-back track's pauses and cadence on T1's step-to stairs
with a 1.5 s rest on every stair (users 14240-14249), and two controls (a walk without rests, a walk with three
5 s stops). Simulated and tracked through the CLI; ``--old PATH`` tracks with the pdrlearn checkout at PATH (main's
code) for the comparison.

Run: PYTHONPATH=. .venv/bin/python experiments/rest_pauses_s46.py [rests|plain|stops] OUT_DIR [--old /work/main]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd

USERS = range(14240, 14250)
GAIT = ["--step-length", "0.42", "--step-time", "0.7", "--step-time-asymmetry", "0.25", "--stance-time-asymmetry",
        "0.15", "--paretic-side", "right", "--bounce", "pendulum", "--rate", "100"]
TRUE_CADENCE = 120.0 / 1.4  # two 0.7 s steps per stride


def route(which: str) -> str:
    if which == "rests":  # T1's F5 route
        up = ", ".join(["up:1:0.17:0.28:step-to-step:left, stand:1.5"] * 8)
        down = ", ".join(["down:1:0.17:0.28:step-to-step:right, stand:1.5"] * 8)
        return f"stand:3, straight:4, {up}, turn:180, {down}, straight:4, stand:3"
    if which == "plain":
        return "stand:3, straight:20, turn:180, straight:20, stand:3"
    return ("stand:3, straight:10, stand:5, straight:10, stand:5, turn:180, straight:10, stand:5, straight:10, "
            "stand:3")


HERE = str(Path(__file__).resolve().parents[1])  # this checkout (the new code)


def run(code: str, args: list[str]) -> None:
    """``python -m pdrlearn ARGS`` with the checkout ``code`` (its folder first on the path: ``-m`` puts the working
    directory there, so it runs in ``code``)."""
    env = {**os.environ, "PYTHONPATH": code}
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], env=env, cwd=code, check=True, capture_output=True)


def one(uid: int, which: str, out: Path, code: str, tag: str) -> dict:
    sess = out / f"{which}_{uid}"
    if not sess.exists():
        run(HERE, ["simulate", "--route", route(which), *GAIT, "--user-seed", str(uid), "--out", str(sess)])
    tr = out / f"{which}_{uid}_{tag}"
    if tag != "old" or not (tr / "summary.json").exists():  # the old code's track, once
        run(code, ["track", str(sess), "--stair-rise", "0.17", "--out", str(tr), "--force"])
    s = json.loads((tr / "summary.json").read_text())
    flights = pd.read_csv(tr / "stairs.csv")
    return {"n_pauses": s["n_pauses"], "pause_time_s": s["pause_time_s"], "cadence": s["median_cadence_spm"],
            "flights": [(r.direction, int(r.n_stairs)) for r in flights.itertuples()] if "n_stairs" in flights
            else list(flights["direction"])}


def main(which: str, out: Path, old: str | None) -> None:
    out.mkdir(parents=True, exist_ok=True)
    ok = 0
    for uid in USERS:
        new = one(uid, which, out, HERE, "new")
        was = one(uid, which, out, old, "old") if old else None
        if which == "rests":
            good = (abs(new["n_pauses"] - 16) <= 2 and abs(new["cadence"] - TRUE_CADENCE) <= 0.1 * TRUE_CADENCE
                    and (was is None or was["flights"] == new["flights"]))
        elif which == "plain":
            good = new["n_pauses"] == 0 and (was is None or abs(new["cadence"] - was["cadence"]) <= 1.0)
        else:
            good = abs(new["n_pauses"] - 3) <= 1
        ok += good
        print(f"{which} user {uid}: new pauses {new['n_pauses']} ({new['pause_time_s']:.1f} s) cadence "
              f"{new['cadence']:.1f} flights {new['flights']}"
              + (f" | old pauses {was['n_pauses']} ({was['pause_time_s']:.1f} s) cadence {was['cadence']:.1f} "
                 f"flights {was['flights']}" if was else "") + f" -> {'ok' if good else 'not ok'}", flush=True)
    print(f"{which}: {ok} of {len(USERS)} walks meet the rule's criterion", flush=True)


if __name__ == "__main__":
    a = sys.argv[1:]
    main(a[0], Path(a[1]), a[a.index("--old") + 1] if "--old" in a else None)
