"""Decision L701 (session 47, I5): does a foot track's rest gap taking the lower back's missed turn recover S106's
stepless spins, and does it leave walks without a spin alone?

Sessions: ``pdrlearn simulate --rate 20`` (the firmware's rate), users 14700-14715 with a slow spin
(``stand:3, straight:8, spin:A:D, straight:8, stand:3``: A 90 / -120 / 150 / -180 deg in turn, D 2 / 5 / 10 / 20 s
in turn), 14716-14719 a fast one (A 180 / -90 / 120 / -180, D 1 / 1.5 / 1 / 2 s), 14720-14729 no spin (stepping
turns, a pivot, a curve, a 60 s stand and a sit). Each is tracked by ``pdrlearn track`` (defaults, no model) twice:
with main's code (``--main /work/main``: its checkout on PYTHONPATH) and with this worktree's. Run
``python experiments/gap_turn_s47_l701.py --main /work/main --work DIR [--first 14730]`` (L702: the spin users
14730-14749, the same design); it prints one row per user and L701's
adoption-rule numbers (docs/decisions/localization.md).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parents[1]
ROUTE = "stand:3, straight:8, spin:{a}:{d}, straight:8, stand:3"
SLOW = [(a, d) for a, d in zip([90, -120, 150, -180] * 4, [2] * 4 + [5] * 4 + [10] * 4 + [20] * 4, strict=True)]
FAST = [(180, 1), (-90, 1.5), (120, 1), (-180, 2)]
PLAIN = ["stand:3, straight:8, turn:180, straight:8, turn:90, straight:6, stand:3",
         "stand:3, straight:6, pivot:180, straight:6, curve:90:3, straight:4, stand:3",
         "stand:3, straight:8, stand:60, straight:8, sit:10, straight:5, stand:3"]


def plan(first: int = 14700) -> list[tuple[int, str, float | None, float | None]]:
    out = [(first + i, ROUTE.format(a=a, d=d), a, d) for i, (a, d) in enumerate(SLOW + FAST)]
    return out + [(14720 + i, PLAIN[i % len(PLAIN)], None, None) for i in range(10)]


def run(cmd: list[str], pythonpath: str, cwd: Path) -> None:
    """``python -m pdrlearn CMD`` with ``pythonpath``'s code, run in ``cwd`` (-m puts the working folder first)."""
    env = {**os.environ, "PYTHONPATH": pythonpath, "MPLBACKEND": "Agg"}
    r = subprocess.run([sys.executable, "-m", "pdrlearn", *cmd], env=env, capture_output=True, text=True, cwd=cwd)
    if r.returncode:
        raise SystemExit(f"{' '.join(cmd)}: {r.stderr.strip().splitlines()[-1:]}")


def wrap_deg(x: float) -> float:
    return (x + 180.0) % 360.0 - 180.0


def _seconds(df: pd.DataFrame) -> pd.DataFrame:
    """A simulator truth table's ``*_ms`` / ``timestamp`` columns (its files' clock, ms) in seconds, named ``*_s`` /
    ``t``."""
    for c in [c for c in df.columns if c.endswith("_ms")]:
        df[c[:-3] + "_s"] = df[c] / 1000.0
    if "timestamp" in df:
        df["t"] = df["timestamp"] / 1000.0
    return df


def spin_numbers(sim: Path, out: Path) -> dict:
    """Final position error, heading-change error across the spin and the turns.csv row near it."""
    summ = json.loads((out / "summary.json").read_text())
    row = {"final_m": summ.get("final_position_error_m"), "turn_count": summ.get("turn_count")}
    spins = sim / "spins.csv"
    if not spins.exists():
        return row
    sp = _seconds(pd.read_csv(spins)).iloc[0]
    st = pd.read_csv(out / "steps.csv")
    tr = _seconds(pd.read_csv(sim / "trajectory.csv"))
    before, after = st[st["end_s"] <= sp["start_s"]], st[st["start_s"] >= sp["end_s"]]
    if len(before) and len(after):
        t0, t1 = float(before["start_s"].iloc[-1]), float(after["start_s"].iloc[0])
        h = np.unwrap(tr["heading_rad"].to_numpy())
        true = math.degrees(np.interp(t1, tr["t"], h) - np.interp(t0, tr["t"], h))
        got = math.degrees(float(after["heading_rad"].iloc[0]) - float(before["heading_rad"].iloc[-1]))
        row["heading_err_deg"] = wrap_deg(got - true)
    turns = pd.read_csv(out / "turns.csv")
    near = turns[(turns["end_s"] >= sp["start_s"] - 2) & (turns["start_s"] <= sp["end_s"] + 2)]
    row["spin_found"] = bool((np.abs(near["angle_deg"] - sp["angle_deg"]) < 30).any())
    return row


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--main", required=True, help="main's checkout (its code on PYTHONPATH for the 'main' tracks)")
    ap.add_argument("--work", required=True, type=Path, help="scratch folder for the sessions and tracks")
    ap.add_argument("--first", type=int, default=14700, help="the first spin user (L702: 14730)")
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    a.work = a.work.resolve()
    rows = []
    for user, route, angle, secs in plan(a.first):
        sim = a.work / f"sim_u{user}"
        if not (sim / "meta.json").exists():
            run(["simulate", "--route", route, "--user-seed", str(user), "--rate", "20", "--out", str(sim),
                 "--force"], str(HERE), a.work)
        row = {"user": user, "angle": angle, "secs": secs}
        for code, path in (("main", a.main), ("l701", str(HERE))):
            out = a.work / f"{code}_u{user}"
            if not (out / "summary.json").exists():
                run(["track", str(sim), "--out", str(out), "--force"], path, a.work)
            row.update({f"{k}_{code}": v for k, v in spin_numbers(sim, out).items()})
        if angle is None:
            row["identical"] = all((a.work / f"main_u{user}" / f).read_bytes() == (a.work / f"l701_u{user}" / f)
                                   .read_bytes() for f in ("steps.csv", "trajectory.csv", "turns.csv"))
        rows.append(row)
        print(row, flush=True)
    df = pd.DataFrame(rows)
    pd.set_option("display.width", 200)
    print(df.to_string(index=False, float_format=lambda x: f"{x:.2f}"))
    spun = df[df["angle"].notna()]
    slow, fast = spun[spun["secs"] >= 2].iloc[:16], spun.iloc[16:]
    for name, part in (("slow", slow), ("fast", fast)):
        print(f"{name}: median final error main {part['final_m_main'].median():.2f} m, L701 "
              f"{part['final_m_l701'].median():.2f} m; median |heading error| main "
              f"{part['heading_err_deg_main'].abs().median():.1f} deg, L701 "
              f"{part['heading_err_deg_l701'].abs().median():.1f} deg; spin in turns.csv main "
              f"{int(part['spin_found_main'].sum())}/{len(part)}, "
              f"L701 {int(part['spin_found_l701'].sum())}/{len(part)}")
    print(f"largest rise of a final error: {(spun['final_m_l701'] - spun['final_m_main']).max():+.2f} m")
    plain = df[df["angle"].isna()]
    print(f"no spin: steps.csv, trajectory.csv, turns.csv identical on {int(plain['identical'].sum())}/{len(plain)}")


if __name__ == "__main__":
    main()
