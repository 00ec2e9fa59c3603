"""Decisions W562, W563, C217 (session 49, FC; docs/decisions/waist.md, cohort.md): the corridor's scale of the lower
back's gait speed and per-minute distances, and the rests inside a 6MWT, on fresh simulated users 16560-16599.

Each user walks a 6MWT on a 30 m corridor (16560-16579 stepping round cones, ``curve:180:0.5``; 16580-16599 turning
on the spot, ``turn:180``; every third user rests 15-30 s in one lap), tracked on the lower back (waist-pendulum)
uncalibrated and - the first 5 of each half - calibrated (``pdrlearn calibrate`` on a separate 30 m straight walk of
the same user and pace). Truth: the simulator's step lengths (``distance_ref_m``) and pelvis path per minute, its
heel strikes' gaps over 3 s inside the test (rests). Run: ``python experiments/corridor_scale_s49_w562.py [WORK]``
(with PYTHONPATH at the tree's root); ``--jobs 2`` runs two users at once.
"""

from __future__ import annotations

import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

USERS = range(16560, 16600)
CALIBRATED = set(range(16560, 16565)) | set(range(16580, 16585))
PY = [sys.executable, "-m", "pdrlearn"]


def route(uid: int, sl: float, st: float, total_s: float = 400.0) -> tuple[str, bool]:
    """gen.py's corridor route of the session-49 trial: laps of 30 m with a cone turn after each, a rest in one."""
    rng = np.random.default_rng(uid + 7)
    turn = "curve:180:0.5" if uid < 16580 else "turn:180"
    rest = (2 + uid % 4, float(rng.uniform(0.2, 0.8)), float(rng.uniform(15, 30))) if uid % 3 == 0 else None
    return laps_route(sl, st, turn, rest, total_s), rest is not None


def laps_route(sl: float, st: float, turn: str, rest: tuple[int, float, float] | None, total_s: float) -> str:
    """The route of 30 m laps, ``turn`` after each, ``rest`` (lap, fraction of it walked first, seconds) in one
    (shared with experiments/clinical_minutes_s49_c230.py)."""
    v, parts, t, lap = sl / st, [], 0.0, 0
    while t < total_s:
        if rest and lap == rest[0]:
            parts += [f"straight:{30 * rest[1]:.1f}", f"stand:{rest[2]:.1f}", f"straight:{30 * (1 - rest[1]):.1f}"]
            t += rest[2]
        else:
            parts.append("straight:30")
        t += 30 / v + 3
        lap += 1
        parts.append(turn)
    return ", ".join(parts)


def run(cmd: list[str]) -> None:
    got = subprocess.run(["nice", *cmd], capture_output=True, text=True)
    if got.returncode:
        raise RuntimeError(f"{' '.join(cmd[3:5])}: {got.stderr.strip()[-300:]}")


def truth(ses: Path, start: float, dur: float = 360.0) -> dict:
    tr = pd.read_csv(ses / "trajectory.csv")
    t = tr.timestamp.to_numpy() / 1000
    p = np.concatenate([[0], np.cumsum(np.hypot(np.diff(tr.x.to_numpy()), np.diff(tr.y.to_numpy())))])
    ic = np.sort(pd.read_csv(ses / "ics.csv").ic_ms.to_numpy() / 1000)
    gaps = [(a, b - a) for a, b in zip(ic[:-1], ic[1:], strict=True) if b - a > 3.0 and start <= a < start + dur]
    minutes = [float(np.interp(start + 60 * (k + 1), t, p) - np.interp(start + 60 * k, t, p)) for k in range(6)]
    return {"rests": len(gaps), "path_per_min": minutes}


def simulate_user(uid: int, work: Path, route=route) -> tuple[Path, float, float, bool]:
    """User ``uid``'s session (its step length and time drawn from the id) on ``route(uid, sl, st)``: ``(folder,
    sl, st, has_rest)`` (shared with experiments/clinical_minutes_s49_c230.py)."""
    rng = np.random.default_rng(uid)
    sl, st = round(float(rng.uniform(0.40, 0.65)), 3), round(float(rng.uniform(0.52, 0.66)), 3)
    r, has_rest = route(uid, sl, st)
    ses = work / f"u{uid}"
    if not (ses / "meta.json").is_file():
        run([*PY, "simulate", "--route", r, "--user-seed", str(uid), "--step-length", str(sl), "--step-time",
             str(st), "--bounce", "pendulum", "--rate", "100", "--out", str(ses), "--force"])
    return ses, sl, st, has_rest


def one(uid: int, work: Path) -> list[dict]:
    ses, sl, st, has_rest = simulate_user(uid, work)
    variants = [("uncal", [])]
    if uid in CALIBRATED:
        cal = work / f"cal{uid}"
        if not (cal / "meta.json").is_file():
            run([*PY, "simulate", "--route", "straight:30", "--user-seed", str(uid), "--step-length", str(sl),
                 "--step-time", str(st), "--bounce", "pendulum", "--rate", "100", "--out", str(cal), "--force"])
        tr = pd.read_csv(cal / "trajectory.csv")
        ic = np.sort(pd.read_csv(cal / "ics.csv").ic_ms.to_numpy() / 1000)
        x = np.interp(ic[[0, -1]], tr.timestamp.to_numpy() / 1000, tr.x.to_numpy())
        params = work / f"p{uid}.json"
        run([*PY, "calibrate", str(cal), "-p", "waist-pendulum", "-d", f"{abs(x[1] - x[0]):.3f}", "--force", "--out",
             str(params)])
        variants.append(("cal", ["--params", str(params)]))
    rows = []
    for name, extra in variants:
        out = work / f"t{uid}_{name}"
        run([*PY, "track", str(ses), "--units", "waist", "--pipeline", "waist-pendulum", "--corridor", "30",
             "--walk-test-duration", "360", "--per", "1min", "--no-plot", "--force", "--out", str(out), *extra])
        s = json.loads((out / "summary.json").read_text())
        laps = pd.read_csv(out / "laps.csv")
        single = laps.iloc[:-1]
        single = single[(single.corridor_laps == 1) & (single.distance_source == "corridor")]
        noarc = 30.0 / float(np.median(single.tracked_m)) if len(single) >= 2 else float("nan")
        per = pd.read_csv(out / "periods.csv")
        T = truth(ses, float(s["per_start_s"]))
        ref = float(s["distance_ref_m"])
        six = per[per.period <= 6]
        scale = s.get("walk_test_scale")
        rows.append({
            "user": uid, "arcs": uid < 16580, "variant": name, "rest": has_rest, "speed": round(sl / st, 2),
            "err_unscaled_pct": 100 * (s["distance_m"] / ref - 1),
            "err_arc_pct": 100 * (s["distance_m"] * scale / ref - 1) if scale else float("nan"),
            "err_noarc_pct": 100 * (s["distance_m"] * noarc / ref - 1),
            "min_err_unscaled_pct": float(np.median(np.abs(six.distance_m.to_numpy() / T["path_per_min"] - 1))) * 100,
            "min_err_scaled_pct": float(np.median(np.abs(six.distance_corridor_m.to_numpy() / T["path_per_min"] - 1)))
            * 100 if "distance_corridor_m" in six else float("nan"),
            "rests_truth": T["rests"], "rests_tracked": s.get("walk_test_n_rests"),
            "n_pauses": s.get("n_pauses"),
            "gait_speed": s.get("gait_speed_mps"), "gait_speed_corridor": s.get("gait_speed_corridor_mps"),
        })
    print(uid, "done", flush=True)
    return rows


def safe(uid: int, work: Path) -> list[dict]:
    try:
        return one(uid, work)
    except RuntimeError as err:  # one user's failure is printed, not the run's end
        print(uid, "failed:", err, flush=True)
        return []


def main() -> None:
    args = [a for a in sys.argv[1:] if not a.startswith("--jobs")]
    jobs = 2 if "--jobs" in " ".join(sys.argv) else 1
    work = Path(args[0] if args else "/tmp/corridor_scale_w562")
    work.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(jobs) as ex:
        rows = [r for got in ex.map(lambda u: safe(u, work), USERS) for r in got]
    df = pd.DataFrame(rows)
    pd.set_option("display.width", 250)
    print(df.round(2).to_string())
    for (name, arcs), g in df.groupby(["variant", "arcs"]):
        print(f"\n{name} {'cone arcs' if arcs else 'on the spot'} (n={len(g)}): |error| median / max, %")
        for col in ("err_unscaled_pct", "err_arc_pct", "err_noarc_pct", "min_err_unscaled_pct", "min_err_scaled_pct"):
            v = g[col].abs()
            print(f"  {col}: {v.median():.2f} / {v.max():.2f}")
    u = df[df.variant == "uncal"]
    print(f"\nC217 rests (uncal): count right on {(u.rests_truth == u.rests_tracked).sum()} of {len(u)}; "
          f"a rest read without one on {((u.rests_truth == 0) & (u.rests_tracked > 0)).sum()}; "
          f"n_pauses right on {(u.rests_truth == u.n_pauses).sum()}")


if __name__ == "__main__":
    main()
