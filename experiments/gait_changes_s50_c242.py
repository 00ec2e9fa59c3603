"""Cohort C242 check (session 50, FC; not a rule): a gait-all output's gait_changes.csv against the same visit pairing
of the labels' reference walks (each pair's gait_summary.json ``reference``: the simulator's labelled contacts and
ics.csv step lengths). Prints, per subject, each symmetry index's baseline and change, tracked and reference.

    python experiments/gait_changes_s50_c242.py GAIT_ALL_OUT
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pandas as pd

from pdrlearn.track.gait_changes import gait_change_tables

MEASURES = ("step_time_s_si_pct", "stance_time_s_si_pct", "swing_time_s_si_pct", "step_length_m_si_pct")


def main(out: Path) -> None:
    pairs = pd.read_csv(out / "gait_pairs.csv", dtype=str)
    walks = {"tracked": [], "reference": []}
    for _, p in pairs[pairs["status"] == "ok"].iterrows():
        summary = json.loads((out / p["path"] / "gait_summary.json").read_text())
        for kind, walk in (("tracked", summary["walk"]), ("reference", (summary.get("reference") or {}).get("walk"))):
            walks[kind].append({"path": p["path"], "subject": p["subject"], "visit": p["visit"], "walk": walk})
    tables = {kind: gait_change_tables(w)[0] for kind, w in walks.items()}
    rows = []
    for i, row in tables["tracked"].iterrows():
        ref = tables["reference"].iloc[i]
        assert ref["subject"] == row["subject"]
        rows.append({"subject": row["subject"], "visits": f"{row['baseline_visit']}->{row['visit']}",
                     **{f"{m[:-7]} {k}": f"{row[f'{m}_{k}']:.2f} / {ref[f'{m}_{k}']:.2f}"
                        for m in MEASURES for k in ("baseline", "change")}})
    print("tracked / reference (labels)")
    print(pd.DataFrame(rows).to_string(index=False))
    for m in MEASURES:
        d = (tables["tracked"][f"{m}_change"] - tables["reference"][f"{m}_change"]).abs()
        print(f"{m}: |tracked - reference change| median {d.median():.2f}, max {d.max():.2f} points "
              f"(n {d.notna().sum()})")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
