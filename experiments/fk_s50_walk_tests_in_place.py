"""Decisions L778, L779 (session 50, FK): print, for each track folder given, L95's gait-range line and the
automatic walk tests (10 m walk time, its trials, T25FW) computed from its steps.csv with the code on PYTHONPATH.
Run once with /work/main's code (before) and once with the branch (after), from a directory outside both trees.

    PYTHONPATH=TREE python experiments/fk_s50_walk_tests_in_place.py TRACK_DIR...
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pandas as pd

from pdrlearn.track.gait import gait_range_warning
from pdrlearn.track.walk_test import t25fw, ten_metre_walk


def row(folder: Path) -> str:
    summary = json.loads((folder / "summary.json").read_text())
    line = gait_range_warning(summary)
    steps = pd.read_csv(folder / "steps.csv")
    walk, t25 = ten_metre_walk(steps), t25fw(steps)

    def num(v):
        return "none" if v is None else f"{v:.2f}"

    said = "none" if line is None else repr(line[:70])
    return (f"{folder.name}: range line {said}; 10mw {num(walk['ten_m_walk_time_s'])} s "
            f"trials {walk['n_ten_m_walk_trials']}; t25fw {num(t25['t25fw_time_s'])} s")


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        print(row(Path(arg)))
