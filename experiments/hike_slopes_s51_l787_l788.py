"""Decisions L787 / L788 (session 51, FD): score the hike and stair tracks of /tmp-style output folders.

Usage: python experiments/hike_slopes_s51_l787_l788.py OUT_BEFORE OUT_AFTER
Each folder holds h20_<user> / h30_<user> (hike, default / --stair-grade 30) and s20_<user> (stairs, default) tracks
of the route written in docs/decisions/localization.md (L787, L788). Prints, per rule part, the counts before and
after as the decisions define them.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pandas as pd


def _csv(path: Path) -> pd.DataFrame:
    return pd.read_csv(path) if path.exists() else pd.DataFrame()


def _near(ramps: pd.DataFrame, grade: float, tol: float) -> bool:
    if not len(ramps):
        return False
    return bool(((ramps["max_run_grade_pct"] - grade).abs() <= tol).any())


def _across_stop(track: Path) -> bool:
    """Whether a ramp holds rows on both sides of a standstill of >= 40 s (the route's 60 s and 45 s stops)."""
    steps, ramps = _csv(track / "steps.csv"), _csv(track / "ramps.csv")
    if not len(steps) or not len(ramps):
        return False
    gap = steps["start_s"].to_numpy()[1:] - steps["end_s"].to_numpy()[:-1]
    at = steps["start_s"].to_numpy()[1:][gap >= 40.0]
    return any(((ramps["start_s"] < t) & (ramps["end_s"] > t)).any() for t in at)


def hike_scores(out: Path, users) -> dict:
    s = {"l787_both": 0, "l787_across": 0, "l788_noflight": 0, "l788_ramp22": 0, "l788_pass": 0, "n": 0}
    for u in users:
        h30, h20 = out / f"h30_{u}", out / f"h20_{u}"
        if not (h30 / "ramps.csv").exists() or not (h20 / "stairs.csv").exists():
            continue
        s["n"] += 1
        r30 = _csv(h30 / "ramps.csv")
        s["l787_both"] += _near(r30, 22.0, 4.0) and _near(r30, -15.0, 4.0)
        s["l787_across"] += _across_stop(h30)
        st20, r20 = _csv(h20 / "stairs.csv"), _csv(h20 / "ramps.csv")
        noflight = not len(st20) or not (st20["n_strides"] > 24).any()
        ramp22 = _near(r20, 22.0, 5.0)
        s["l788_noflight"] += noflight
        s["l788_ramp22"] += ramp22
        s["l788_pass"] += noflight and ramp22
    return s


def stair_rows(out: Path, users) -> dict:
    rows = {}
    for u in users:
        d = out / f"s20_{u}"
        if not (d / "summary.json").exists():
            continue
        st = _csv(d / "stairs.csv")
        summ = json.loads((d / "summary.json").read_text())
        rows[u] = (tuple(st["direction"]) if len(st) else (), tuple(st["n_strides"]) if len(st) else (),
                   tuple(round(float(h), 3) for h in st["height_m"]) if len(st) else (),
                   summ.get("floors_up_stairs"), summ.get("floors_down_stairs"))
    return rows


def main(before: str, after: str) -> None:
    hikes, stairs = range(18250, 18265), range(18270, 18285)
    for tag, out in (("before", Path(before)), ("after", Path(after))):
        print(tag, "hikes", hike_scores(out, hikes))
    b, a = stair_rows(Path(before), stairs), stair_rows(Path(after), stairs)
    same = sum(1 for u in b if u in a and a[u] == b[u])
    print(f"stair users identical (flights, strides, heights, floors_*_stairs): {same} of {len(set(a) & set(b))}")
    for u in sorted(set(a) & set(b)):
        print(u, "before", b[u][:2], b[u][3:], "after", a[u][:2], a[u][3:])


if __name__ == "__main__":
    main(*sys.argv[1:3])
