"""Decision C207 (session 48, trial T4 finding F5): whether a foot track's own corridor length (its median lap less
the cone turn's arc) tells a --corridor 5-7 % wrong from a right one, at CORRIDOR_LAP_MARGIN (3 %). Fresh users
16160-16179, the rule in docs/decisions/cohort.md (C207), written before this ran. A check of a margin, no tuning.

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

import pdrlearn.track.corridor as corridor_mod
from pdrlearn.track.corridor import corridor_laps
from pdrlearn.warning_lines import warning_code

PDR = [sys.executable, "-m", "pdrlearn"]
#: (users, one lap's straight and turn, the right corridor, m)
ROUTES = [(range(16160, 16170), "straight:28, turn:180", 28.0),
          (range(16170, 16180), "straight:30, curve:180:0.5", 30.0)]
#: decision C207's candidate margin (the module's CORRIDOR_LAP_MARGIN is None: not adopted)
CANDIDATE = 0.03
FACTORS = (1.0, 1.05, 1.07, 1 / 1.05, 1 / 1.07)


def run(*args: str) -> str:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{args}: exit {done.returncode}: {done.stderr[-2000:]}")
    return done.stdout


def main(work: Path) -> None:
    corridor_mod.CORRIDOR_LAP_MARGIN = CANDIDATE
    lines = [f"CORRIDOR_LAP_MARGIN {CANDIDATE}"]
    right_fired = wrong_missed = n_right = n_wrong = 0
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
            got = []
            for f in FACTORS:
                _, _, warn = corridor_laps(steps, turns, corridor * f)
                fired = [w for w in warn if warning_code(w) in ("C207", "L518")]
                got.append(f"x{f:.3f}: {'line' if fired else 'none'}")
                if f == 1.0:
                    n_right += 1
                    right_fired += bool(fired)
                else:
                    n_wrong += 1
                    wrong_missed += not fired
            line = (f"user {u} {speed} corridor {corridor:g} m: n_laps {s['n_laps']}, walk_test_distance_m "
                    f"{s['walk_test_distance_m']:.1f}, laps tracked {' '.join(f'{m:.2f}' for m in laps['tracked_m'])}; "
                    + "; ".join(got))
            print(line, flush=True)
            lines.append(line)
    line = (f"right corridors with a line: {right_fired} of {n_right}; wrong (5-7 %) corridors without one: "
            f"{wrong_missed} of {n_wrong}")
    print(line)
    lines.append(line)
    out = Path(__file__).resolve().parent / "results" / "corridor_lap_length_c207.txt"
    out.write_text("\n".join(lines) + "\n")


def rescore(work: Path, margin: float) -> None:
    """The tracks of :func:`main` under ``work`` scored again at ``margin``; each one's own corridor length."""
    corridor_mod.CORRIDOR_LAP_MARGIN = margin
    lines, right_fired, wrong_missed, n_right, n_wrong = [f"CORRIDOR_LAP_MARGIN {margin}"], 0, 0, 0, 0
    for users, _, corridor in ROUTES:
        for u in users:
            steps, turns = (pd.read_csv(work / f"u{u}" / "res" / f) for f in ("steps.csv", "turns.csv"))
            got = []
            for f in FACTORS:
                warn = corridor_laps(steps, turns, corridor * f)[2]
                fired = [w for w in warn if warning_code(w) in ("C207", "L518")]
                got.append(f"x{f:.3f}: {'line' if fired else 'none'}")
                n_right += f == 1.0
                n_wrong += f != 1.0
                right_fired += f == 1.0 and bool(fired)
                wrong_missed += f != 1.0 and not fired
            corridor_mod.CORRIDOR_LAP_MARGIN = 0.0  # every track's own length, from the line at margin 0
            own = [w for w in corridor_laps(steps, turns, corridor)[2] if warning_code(w) == "C207"]
            corridor_mod.CORRIDOR_LAP_MARGIN = margin
            line = f"user {u} corridor {corridor:g} m: {own[0].split('(')[0].split(': ')[1] if own else '-'}; " + (
                "; ".join(got))
            print(line, flush=True)
            lines.append(line)
    line = (f"right corridors with a line: {right_fired} of {n_right}; wrong (5-7 %) corridors without one: "
            f"{wrong_missed} of {n_wrong}")
    print(line)
    lines.append(line)
    out = Path(__file__).resolve().parent / "results" / "corridor_lap_length_c207_rescore.txt"
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    if "--rescore" in sys.argv:
        rescore(Path(sys.argv[1]), float(sys.argv[sys.argv.index("--rescore") + 1]))
    else:
        main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp()))
