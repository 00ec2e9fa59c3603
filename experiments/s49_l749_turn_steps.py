"""Decision L749: steps per turn on a foot track against the simulator's truth (users 16720-16739).

Usage: python experiments/s49_l749_turn_steps.py OUT_DIR [FIRST LAST]
Simulates each user's 360 / 180 / spin route, tracks it with foot + waist (default) and --units foot, and scores
turns.csv's turn_steps per true turn (ics.csv contacts grouped by the standing gaps)."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROUTE = "stand:3, turn:360, stand:3, turn:-180, stand:3, spin:360:4, stand:3"
KINDS = ("turn360", "turn180", "spin360")
PY = [sys.executable, "-m", "pdrlearn"]


def true_turns(sim: Path) -> list[tuple[float, float, int]]:
    ic = np.sort(pd.read_csv(sim / "ics.csv")["ic_ms"].to_numpy(float) / 1000)
    groups = np.split(ic, np.flatnonzero(np.diff(ic) > 1.5) + 1)
    return [(g[0], g[-1], len(g)) for g in groups if len(g)]


def score(turns: pd.DataFrame, truth) -> list[dict]:
    """The two walked turns (their contacts' groups) and the stepless spin after them (S106: no contact, truth 0;
    any turns.csv row starting after the last group is the spin's)."""
    truth = list(truth)[:2] + [(truth[-1][1] + 1.5, np.inf, 0)]
    out = []
    for kind, (a, b, n) in zip(KINDS, truth, strict=True):
        hit = turns[(turns["end_s"] >= a - 1) & (turns["start_s"] <= b + 1)]
        est = hit["turn_steps"].iloc[0] if len(hit) else None
        out.append({"kind": kind, "truth": n, "est": None if est is None or pd.isna(est) else int(est),
                    "n_rows": int(hit["n_rows"].iloc[0]) if len(hit) else None,
                    "source": hit["turn_steps_source"].iloc[0] if len(hit) else None})
    return out


def main(out: Path, first: int, last: int) -> None:
    rows = []
    for user in range(first, last + 1):
        sim = out / f"u{user}"
        if not (sim / "ics.csv").exists():
            subprocess.run([*PY, "simulate", "--route", ROUTE, "--user-seed", str(user), "--seed", "49",
                            "--rate", "100", "--out", str(sim)], check=True, capture_output=True)
        truth = true_turns(sim)
        for units in ("foot,waist", "foot"):
            tr = out / f"tr_{units.replace(',', '_')}_{user}"
            if not (tr / "turns.csv").exists():
                subprocess.run([*PY, "track", str(sim), "--units", units, "--out", str(tr)], check=True,
                               capture_output=True)
            for r in score(pd.read_csv(tr / "turns.csv", keep_default_na=True), truth):
                rows.append({"user": user, "units": units, **r})
    t = pd.DataFrame(rows)
    t.to_csv(out / "scores.csv", index=False)
    t["err"] = t["est"] - t["truth"]
    print(t.to_string())
    for units, g in t.groupby("units"):
        m = g.dropna(subset=["est"])
        print(f"{units}: turns {len(g)}, scored {len(m)}, missed {len(g) - len(m)}, mean |err| "
              f"{m['err'].abs().mean():.2f}, within +-1 {100 * (m['err'].abs() <= 1).mean():.1f} %")
        for kind, k in m.groupby("kind"):
            print(f"  {kind}: n {len(k)}, truth median {k['truth'].median():.0f}, est median {k['est'].median():.0f},"
                  f" mean |err| {k['err'].abs().mean():.2f}, mean err {k['err'].mean():+.2f}, within +-1 "
                  f"{100 * (k['err'].abs() <= 1).mean():.1f} %, 2 x n_rows mean |err| "
                  f"{(2 * k['n_rows'] - k['truth']).abs().mean():.2f}")


if __name__ == "__main__":
    a = sys.argv[1:]
    main(Path(a[0]), int(a[1]) if len(a) > 1 else 16720, int(a[2]) if len(a) > 2 else 16739)
