"""Decision W328 (lead's check, session 33): on the mobgap Test11 recordings, the lower back's turns.csv rows inside
INDIP's walking bouts (INDIP lists turns only inside its bouts) against INDIP's turns; today's table without the yaw
cut (``yaw_split=False, yaw_angle=False``) vs W328's.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/turns_w328_inside_bouts.py
Output: experiments/results/turns_w328_inside_bouts.txt (the printed lines).
A row is inside when its midpoint lies in a ``wb`` bout of bouts.csv; it is right when it overlaps an INDIP turn in
time; an INDIP turn is found when any row (inside or not) overlaps it.
"""
import logging
from pathlib import Path

import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.waist import track_waist

ROOT = Path("datasets/external")
SUBJECTS = ("HA001", "HA002", "MS001")
CONFIGS = {"today": {"yaw_split": False, "yaw_angle": False}, "W328": {"yaw_split": True, "yaw_angle": True}}


def overlaps(a0: float, a1: float, b0: float, b1: float) -> bool:
    return a0 < b1 and a1 > b0


def counts(rows: pd.DataFrame, bouts: pd.DataFrame, ref: pd.DataFrame) -> tuple[int, int, int, int, int]:
    """(rows, rows inside a bout, of those overlapping a reference turn, reference turns, reference turns hit)."""
    spans = [(b.start_ms / 1e3, b.end_ms / 1e3) for b in bouts.itertuples()]
    turns = [(t.start_ms / 1e3, t.end_ms / 1e3) for t in ref.itertuples()]
    inside = [r for r in rows.itertuples() if any(s0 <= (r.start_s + r.end_s) / 2 <= s1 for s0, s1 in spans)]
    right = sum(any(overlaps(r.start_s, r.end_s, t0, t1) for t0, t1 in turns) for r in inside)
    hit = sum(any(overlaps(r.start_s, r.end_s, t0, t1) for r in rows.itertuples()) for t0, t1 in turns)
    return len(rows), len(inside), right, len(turns), hit


def main() -> None:
    logging.disable(logging.WARNING)
    for pipeline in ("waist-pendulum", "waist-pll"):
        pooled = {c: [0] * 5 for c in CONFIGS}
        for subject in SUBJECTS:
            folder = ROOT / f"mobgap_{subject}_Test11_Trial1"
            result = track_waist(read_session(folder), pipeline=pipeline)
            bouts = pd.read_csv(folder / "bouts.csv")
            bouts = bouts[bouts.level == "wb"]
            ref = pd.read_csv(folder / "turns.csv")
            for config, knobs in CONFIGS.items():
                rows = turn_table(result.steps, yaw_turns=result.info.get("yaw_turns"), **knobs)
                c = counts(rows, bouts, ref)
                pooled[config] = [a + b for a, b in zip(pooled[config], c, strict=True)]
                print(f"{pipeline} {subject} {config}: rows {c[0]}, inside INDIP bouts {c[1]}, of those overlapping an "
                      f"INDIP turn {c[2]}; INDIP turns {c[3]}, found {c[4]}")
        for config, c in pooled.items():
            print(f"{pipeline} pooled {config}: rows {c[0]}, inside bouts {c[1]}, right inside bouts {c[2]}/{c[1]}, "
                  f"INDIP turns found {c[4]}/{c[3]}")


if __name__ == "__main__":
    main()
