"""Decision C207 (session 48, trial T4 finding F5): whether a foot track's own corridor length (its median lap less
the cone turn's arc) tells a --corridor 5-7 % wrong from a right one, at ``corridor_laps(lap_margin=0.03)``
(3 %). Fresh users 16160-16179, the rule in docs/decisions/cohort.md (C207), written before this ran. A check
of a margin, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/corridor_lap_length_c207.py [WORKDIR]
Output: experiments/results/corridor_lap_length_c207.txt (the printed lines). The rule's fallback margin (4 %) on the
same tracks: ``... corridor_lap_length_c207.py WORKDIR --rescore 0.04`` (no new simulation; output
corridor_lap_length_c207_rescore.txt), which also prints each track's own corridor length.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import pandas as pd

from pdrlearn.track.corridor import corridor_laps
from pdrlearn.warning_lines import warning_code

PDR = [sys.executable, "-m", "pdrlearn"]
#: (users, one lap's straight and turn, the right corridor, m)
ROUTES = [(range(16160, 16170), "straight:28, turn:180", 28.0),
          (range(16170, 16180), "straight:30, curve:180:0.5", 30.0)]
#: decision C207's candidate margin (``corridor_laps``' ``lap_margin`` is None by default: not adopted)
CANDIDATE = 0.03
FACTORS = (1.0, 1.05, 1.07, 1 / 1.05, 1 / 1.07)


def run(*args: str) -> str:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{args}: exit {done.returncode}: {done.stderr[-2000:]}")
    return done.stdout


def score(steps: pd.DataFrame, turns: pd.DataFrame, corridor: float, counts: list[int], margin: float) -> str:
    """Each of FACTORS x ``corridor`` judged on one track: its words; ``counts`` (right corridors, right ones with a
    line, wrong ones, wrong ones without a line) counted on."""
    got = []
    for f in FACTORS:
        fired = [w for w in corridor_laps(steps, turns, corridor * f, lap_margin=margin)[2]
                 if warning_code(w) in ("C207", "L518")]
        got.append(f"x{f:.3f}: {'line' if fired else 'none'}")
        right = f == 1.0
        counts[0 if right else 2] += 1
        counts[1 if right else 3] += bool(fired) if right else not fired
    return "; ".join(got)


def finish(lines: list[str], counts: list[int], name: str) -> None:
    """The summary line printed and every line written to experiments/results/``name``."""
    line = (f"right corridors with a line: {counts[1]} of {counts[0]}; wrong (5-7 %) corridors without one: "
            f"{counts[3]} of {counts[2]}")
    print(line)
    (Path(__file__).resolve().parent / "results" / name).write_text("\n".join([*lines, line]) + "\n")


def main(work: Path) -> None:
    lines, counts = [f"CORRIDOR_LAP_MARGIN {CANDIDATE}"], [0, 0, 0, 0]  # the first run's name for lap_margin
    for users, lap, corridor in ROUTES:
        straight = lap.split(",")[0]
        route = "stand:3, " + ", ".join([lap] * 5) + f", {straight}, stand:3"
        for k, u in enumerate(users):
            p = work / f"u{u}"
            speed = "normal" if k % 2 == 0 else "slow"
            run("simulate", "--route", route, "-u", str(u), "--speed", speed, "--rate", "100", "--out", str(p / "walk"))
            s = json.loads(run("track", str(p / "walk"), "--corridor", f"{corridor:g}", "--out", str(p / "res"),
                               "--force", "--json"))
            s = s.get("summary", s)
            steps, turns = pd.read_csv(p / "res" / "steps.csv"), pd.read_csv(p / "res" / "turns.csv")
            laps, _, _ = corridor_laps(steps, turns, corridor)
            line = (f"user {u} {speed} corridor {corridor:g} m: n_laps {s['n_laps']}, walk_test_distance_m "
                    f"{s['walk_test_distance_m']:.1f}, laps tracked {' '.join(f'{m:.2f}' for m in laps['tracked_m'])}; "
                    + score(steps, turns, corridor, counts, CANDIDATE))
            print(line, flush=True)
            lines.append(line)
    finish(lines, counts, "corridor_lap_length_c207.txt")


def rescore(work: Path, margin: float) -> None:
    """The tracks of :func:`main` under ``work`` scored again at ``margin``; each one's own corridor length."""
    lines, counts = [f"CORRIDOR_LAP_MARGIN {margin}"], [0, 0, 0, 0]
    for users, _, corridor in ROUTES:
        for u in users:
            steps, turns = (pd.read_csv(work / f"u{u}" / "res" / f) for f in ("steps.csv", "turns.csv"))
            own = [w for w in corridor_laps(steps, turns, corridor, lap_margin=0.0)[2]  # every track's own length
                   if warning_code(w) == "C207"]
            line = (f"user {u} corridor {corridor:g} m: {own[0].split('(')[0].split(': ')[1] if own else '-'}; "
                    + score(steps, turns, corridor, counts, margin))
            print(line, flush=True)
            lines.append(line)
    finish(lines, counts, "corridor_lap_length_c207_rescore.txt")


if __name__ == "__main__":
    if "--rescore" in sys.argv:
        rescore(Path(sys.argv[1]), float(sys.argv[sys.argv.index("--rescore") + 1]))
    else:
        main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp()))
