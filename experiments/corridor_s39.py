"""Decisions L517 and L518 (session 39, fixer FC, trial T1 findings 1-2): the check of L517's short last lap and the
measurement of L518's `--corridor` agreement line, on fresh simulated users 10040-10059 (slow walkers, 15 / 20 / 30 m
halls, foot and uncalibrated lower-back tracks). A check, no tuning: the rule and criterion are in
docs/decisions/localization.md, written before this ran.

Each user walks 3-6 laps of its hall, then either stops 60 % into the next lap ("stop") or stops 70 % into it, stands
6 s, turns and walks 30 % back ("walk back"). Each track is scored by this checkout's `corridor_laps` and by the old
checkout's (OLD, e.g. /work/main) from the track's steps.csv / turns.csv / bouts.csv, with the true hall and with every
other hall of 10-50 m (L518's wrong corridors), and once more with `--walk-test-duration` 1 s past the stop.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/corridor_s39.py OLD_CHECKOUT [WORKDIR]
Output: experiments/results/corridor_s39.txt (the printed lines; corridor_s39_final.txt with FINAL as 3rd argument).
"""
import importlib.util
import subprocess
import sys
import tempfile
from pathlib import Path

import pandas as pd

from pdrlearn.track.corridor import corridor_laps

USERS = range(10040, 10060)
HALLS = (15.0, 20.0, 30.0)
WRONG = (10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0)
PDR = [sys.executable, "-m", "pdrlearn"]


def _run(args: list[str]) -> None:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{' '.join(args[:3])}: exit {done.returncode}: {done.stderr[-1500:]}")


def walk_of(u: int) -> dict:
    """User ``u``'s hall, walker and route (deterministic from the id)."""
    k = u - USERS.start
    hall = HALLS[k % 3]
    step_m, step_s = 0.35 + 0.25 * ((k * 7) % 10) / 9, 0.55 + 0.2 * ((k * 3) % 10) / 9  # 0.47-1.09 m/s
    laps = 3 + k % 4
    turn = "turn:180" if u % 2 == 0 else "curve:180:0.5"
    back = k % 2 == 1
    parts = ["stand:3"] + [f"straight:{hall:g}, {turn}"] * laps
    parts += ([f"straight:{0.7 * hall:g}, stand:6, {turn}, straight:{0.3 * hall:g}, stand:3"] if back
              else [f"straight:{0.6 * hall:g}, stand:3"])
    truth_m = laps * hall + (0.7 if back else 0.6) * hall
    return {"hall": hall, "step_m": round(step_m, 3), "step_s": round(step_s, 3), "laps": laps, "back": back,
            "route": ", ".join(parts), "truth_m": truth_m}


def old_module(old: str):
    """The old checkout's ``pdrlearn/track/corridor.py`` (its imports resolve in this checkout's package)."""
    spec = importlib.util.spec_from_file_location("old_corridor", Path(old) / "pdrlearn" / "track" / "corridor.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def stop_time(ses: Path, w: dict) -> tuple[float, float]:
    """The simulator's first step's start and the end of the last step before the stop (s)."""
    st = pd.read_csv(ses / "steps.csv")
    start, end = st["start_ms"].to_numpy() / 1000, st["end_ms"].to_numpy() / 1000
    gaps = start[1:] - end[:-1]
    stop = end[:-1][gaps > 3.0][-1] if w["back"] else end[-1]
    return float(start[0]), float(stop)


def main(old: str, work: Path) -> None:
    old_c = old_module(old)
    lines = []
    fired_true = {"foot": 0, "lower back": 0}
    n_true = {"foot": 0, "lower back": 0}
    wrong = {}  # (unit, ratio bucket) -> [fired, n]
    checks = {"a": 0, "b": 0, "c": 0}
    n_back = n_stop = 0
    for u in USERS:
        w = walk_of(u)
        ses = work / f"u{u}"
        if not (ses / "meta.json").exists():
            _run(["simulate", "--route", w["route"], "--step-length", str(w["step_m"]), "--step-time",
                  str(w["step_s"]), "--user-seed", str(u), "--rate", "100", "--out", str(ses), "--force"])
        t_first, t_stop = stop_time(ses, w)
        n_back += w["back"]
        n_stop += not w["back"]
        for unit, arg in (("foot", "foot"), ("lower back", "waist")):
            out = work / f"u{u}_{arg}"
            if not (out / "summary.json").exists():
                _run(["track", str(ses), "--units", arg, "--corridor", f"{w['hall']:g}", "--out", str(out), "--force"])
            steps = pd.read_csv(out / "steps.csv")
            turns = pd.read_csv(out / "turns.csv")
            bouts = pd.read_csv(out / "bouts.csv")
            _, s_new, w_new = corridor_laps(steps, turns, w["hall"], bouts)
            _, s_old, _ = old_c.corridor_laps(steps, turns, w["hall"], bouts)
            l517 = any("L517" in x for x in w_new)
            l518 = any("L518" in x for x in w_new)
            n_true[unit] += 1
            fired_true[unit] += l518
            same = s_new["n_laps"] == s_old["n_laps"] and abs(s_new["walk_test_distance_m"]
                                                             - s_old["walk_test_distance_m"]) < 1e-6
            dur = t_stop + 1.0 - t_first
            _, s_dur, w_dur = corridor_laps(steps, turns, w["hall"], bouts, duration_s=dur)
            if w["back"]:
                checks["b"] += l517 and s_new["n_laps"] == w["laps"]
                checks["c"] += s_dur["n_laps"] == w["laps"] and not any("L517" in x for x in w_dur)
            else:
                checks["a"] += (not l517) and same
            line = (f"user {u} {unit}: hall {w['hall']:g} m, {w['step_m']} m / {w['step_s']} s "
                    f"({w['step_m'] / w['step_s']:.2f} m/s), {w['laps']} laps + {'walk back' if w['back'] else 'stop'}"
                    f", truth {w['laps']} laps {w['truth_m']:.1f} m; old {s_old['n_laps']} laps "
                    f"{s_old['walk_test_distance_m']:.1f} m, new {s_new['n_laps']} laps "
                    f"{s_new['walk_test_distance_m']:.1f} m, L517 {'fired' if l517 else 'no'}, L518 "
                    f"{'fired' if l518 else 'no'}; --walk-test-duration {dur:.1f}: {s_dur['n_laps']} laps "
                    f"{s_dur['walk_test_distance_m']:.1f} m "
                    f"({100 * (s_dur['walk_test_distance_m'] / w['truth_m'] - 1):+.2f} %)")
            print(line, flush=True)
            lines.append(line)
            for c in WRONG:
                if c == w["hall"]:
                    continue
                _, _, w_c = corridor_laps(steps, turns, c, bouts)
                _, _, w_o = old_c.corridor_laps(steps, turns, c, bouts)
                key = (unit, f"{c / w['hall']:.2f}")
                hit = wrong.setdefault(key, [0, 0, 0])
                hit[0] += any("L518" in x for x in w_c)
                hit[1] += 1
                hit[2] += any("corridor length right" in x for x in w_o)  # the old code's L384 line
    lines.append(f"L518 on the true --corridor: foot {fired_true['foot']} of {n_true['foot']}, lower back "
                 f"{fired_true['lower back']} of {n_true['lower back']}")
    for (unit, ratio), (f, n, o) in sorted(wrong.items(), key=lambda kv: (kv[0][0], float(kv[0][1]))):
        lines.append(f"L518 on --corridor = {ratio} x the true hall, {unit}: fired {f} of {n} (the old L384 line {o})")
    lines.append(f"L517 check: (a) stop tracks silent and equal to the old code's {checks['a']} of {2 * n_stop}; "
                 f"(b) walk-back tracks named with the true laps {checks['b']} of {2 * n_back}; (c) walk-back tracks "
                 f"with --walk-test-duration: true laps and no L517 line {checks['c']} of {2 * n_back}")
    # the trial's --corridor 3 on a straight 10 m walk (user 10059's walker)
    ses = work / "straight10"
    if not (ses / "meta.json").exists():
        _run(["simulate", "--route", "stand:3, straight:10, stand:3", "--step-length", "0.5", "--step-time", "0.6",
              "--user-seed", "10059", "--rate", "100", "--out", str(ses), "--force"])
    for unit, arg in (("foot", "foot"), ("lower back", "waist")):
        out = work / f"straight10_{arg}"
        if not (out / "summary.json").exists():
            _run(["track", str(ses), "--units", arg, "--out", str(out), "--force"])
        steps, turns = pd.read_csv(out / "steps.csv"), pd.read_csv(out / "turns.csv")
        for c in (3.0, 10.0, 15.0):
            _, s_c, w_c = corridor_laps(steps, turns, c)
            lines.append(f"straight 10 m walk, {unit}, --corridor {c:g}: {s_c['walk_test_distance_m']:.1f} m, L518 "
                         f"{'fired' if any('L518' in x for x in w_c) else 'no'}")
    for line in lines[-(len(wrong) + 9):]:
        print(line)
    name = "corridor_s39_final.txt" if FINAL else "corridor_s39.txt"
    (Path(__file__).resolve().parent / "results" / name).write_text("\n".join(lines) + "\n")


FINAL = len(sys.argv) > 3 and sys.argv[3] == "FINAL"  # L518's outcome applied (the lower back at L384's 0.5-2 x)

if __name__ == "__main__":
    main(sys.argv[1], Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp()))
