"""Decision L770 (session 50, FH): the waist compass's direction sinusoid taken off before the fused heading's window
(candidate A), measured by the rule written in docs/decisions/localization.md before measuring.

Fresh users 17650-17669 on trial s50t1's route1 (6 min, two storeys, back to the door), ``--waist-mount y:20
--gyro-bias-model gm:288``, at 100 and 50 Hz (simulated into ``SIM`` if missing); offline ``track_plasys`` defaults:
the foot alone, the fused heading as it is, and ``compass_sinusoid=True``; the oracle amplitude from the waist
heading (``heading="waist"``) against the simulated walking direction on the straight strides.
``PYTHONPATH=. python experiments/compass_sinusoid_s50_l770.py [sim|real]``.
"""

from __future__ import annotations

import logging
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROUTE = Path("/work/trial/s50t1/route1.txt")
SIM = Path("/tmp/fh/sim")
USERS = range(17650, 17670)
RATES = (100, 50)
REAL = sorted([*Path("/work/shared/data").glob("*_*"), *Path("/work/main/datasets/external").glob("*_*")])


def simulate(user: int, rate: int) -> Path:
    out = SIM / f"m1_r{rate}_u{user}"
    if not (out / "meta.json").exists():
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", ROUTE.read_text().strip(),
                        "--user-seed", str(user), "--rate", str(rate), "--waist-mount", "y:20",
                        "--gyro-bias-model", "gm:288", "--out", str(out)], check=True, capture_output=True)
    return out


def wrap(a):
    return (np.asarray(a, float) + np.pi) % (2 * np.pi) - np.pi


def oracle_deg(folder: Path, steps: pd.DataFrame) -> float:
    """The waist heading's error against the simulated foot's walking direction over each straight stride (over
    0.5 m, no turn over 15 deg), fitted by const + a cos(theta) + b sin(theta) of the true direction: hypot(a, b)."""
    tr = pd.read_csv(folder / "foot_trajectory.csv")
    t = tr["t_ms"].to_numpy(float) / 1000
    st, en = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    dx = np.interp(en, t, tr["x"]) - np.interp(st, t, tr["x"])
    dy = np.interp(en, t, tr["y"]) - np.interp(st, t, tr["y"])
    theta = np.arctan2(dy, dx)
    turn = np.abs(steps["turn_angle_rad"].to_numpy(float)) if "turn_angle_rad" in steps else np.zeros(len(st))
    ok = (np.hypot(dx, dy) > 0.5) & (steps["length_m"].to_numpy(float) > 0) & ~(turn > np.radians(15))
    err = wrap(steps["heading_rad"].to_numpy(float)[ok] - theta[ok])
    err = wrap(err - np.angle(np.mean(np.exp(1j * err))))
    X = np.column_stack([np.ones(ok.sum()), np.cos(theta[ok]), np.sin(theta[ok])])
    c = np.linalg.lstsq(X, err, rcond=None)[0]
    return float(np.degrees(np.hypot(c[1], c[2])))


def errors(folder: Path) -> dict:
    from pdrlearn.io.plasys import read_session
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    ses = read_session(folder)
    out = {}
    for name, kw in (("foot", {"heading": "foot"}), ("fused", {}), ("A", {"compass_sinusoid": True})):
        res = track_plasys(ses, **kw)
        out[name] = evaluate_track(res, ses).get("final_position_error_m")
        if name == "A":
            out["fit_deg"] = res.info.get("compass_sinusoid_deg")
        out.setdefault("final_" + name, res.trajectory[["x", "y"]].iloc[-1].to_numpy(float))
    if (folder / "foot_trajectory.csv").exists():
        out["oracle_deg"] = oracle_deg(folder, track_plasys(ses, heading="waist").steps)
    return out


def main_sim() -> None:
    rows = []
    for rate in RATES:
        for u in USERS:
            r = errors(simulate(u, rate))
            rows.append(r)
            fit = "None" if r["fit_deg"] is None else f"{r['fit_deg']:.2f}"
            print(f"{rate} Hz u{u}: foot {r['foot']:.2f} fused {r['fused']:.2f} A {r['A']:.2f} m; "
                  f"fit {fit} oracle {r['oracle_deg']:.2f} deg", flush=True)
    n = len(rows)
    a1 = sum(r["A"] <= r["foot"] + 0.10 for r in rows)
    fused_ok = sum(r["fused"] <= r["foot"] + 0.10 for r in rows)
    med = {k: float(np.median([r[k] for r in rows])) for k in ("foot", "fused", "A")}
    print(f"(a1) A <= foot + 0.10 m on {a1} of {n} (fused as it is: {fused_ok}); medians foot {med['foot']:.2f} "
          f"fused {med['fused']:.2f} A {med['A']:.2f} m; (a2) A median below fused: {med['A'] < med['fused']}")
    fits = [(r["fit_deg"], r["oracle_deg"]) for r in rows]
    b1 = sum(f is not None and abs(f - o) <= 2 for f, o in fits)
    b2 = sum(f is not None and f >= 5 and o < 4 for f, o in fits)
    b3 = sum((f is None or f < 5) and o > 6 for f, o in fits)
    print(f"(b1) fit within 2 deg of the oracle on {b1} of {n}; (b2) lines with the oracle under 4 deg: {b2}; "
          f"(b3) no line with the oracle over 6 deg: {b3}")


def main_real() -> None:
    for folder in REAL:
        if not (folder / "meta.json").exists():
            continue
        try:
            r = errors(folder)
        except Exception as exc:  # a lower-back-only or foot-only recording: say why, go on
            print(f"{folder.name}: not tracked by plasys ({type(exc).__name__}: {str(exc)[:90]})")
            continue
        moved = float(np.hypot(*(r["final_A"] - r["final_fused"])))
        print(f"{folder.name}: fused {r['fused']} A {r['A']} m; final position moved {moved:.3f} m; fit "
              f"{r['fit_deg']}")


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    (main_real if sys.argv[1:] == ["real"] else main_sim)()
