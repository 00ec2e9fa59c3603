"""Decision L766 (docs/decisions/localization.md): L687's lower-back stride guard at 0.75 (was 0.5), measured against
the rule written before measuring: `pdrlearn track` (foot + lower back) bouts of L765's slow shufflers (FRESH users
17590-17604, simulated by experiments/foot_freeze_walked_l765.py into its OUTDIR), old code vs this checkout. It was
run with this checkout at commit ff9eaadb (`MIN_STRIDE_SHARE` 0.75); not adopted, the constant is 0.5 again, so to
repeat it set the constant to 0.75 in the checkout measured.

Usage: python experiments/trunk_share_l766.py L765_OUTDIR OUTDIR --old /work/main [SESSION ...]
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pandas as pd

import rest_pauses_s46  # sibling: runs `python -m pdrlearn` with a given checkout


def bouts(code: str, session: Path, out: Path) -> tuple[int, list[float]]:
    if not (out / "summary.json").exists():
        rest_pauses_s46.run(code, ["track", str(session), "--out", str(out), "--force"])
    n = json.loads((out / "summary.json").read_text())["n_bouts"]
    return n, [round(float(d), 2) for d in pd.read_csv(out / "bouts.csv")["distance_m"]]


def main(sims: Path, out: Path, old: str, extra: list[Path]) -> None:
    one = {"old": 0, "new": 0}
    grew = 0
    for u in range(17590, 17605):
        got = {tag: bouts(code, sims / f"u{u}", out / f"u{u}_{tag}") for tag, code in
               (("old", old), ("new", rest_pauses_s46.HERE))}
        for tag in one:
            one[tag] += got[tag][0] == 1
        grew += got["new"][0] > got["old"][0]
        print(f"(a) user {u}: old n_bouts {got['old'][0]} {got['old'][1]}, new {got['new'][0]} {got['new'][1]}",
              flush=True)
    print(f"(a) sessions with n_bouts 1: old {one['old']} / 15, new {one['new']} / 15; sessions whose n_bouts grew: "
          f"{grew}")
    for s in extra:
        got = {tag: bouts(code, s, out / f"{s.name}_{tag}") for tag, code in
               (("old", old), ("new", rest_pauses_s46.HERE))}
        print(f"(check) {s.name}: old n_bouts {got['old'][0]} {got['old'][1]}, new {got['new'][0]} {got['new'][1]}")


if __name__ == "__main__":
    a = sys.argv[1:]
    i = a.index("--old")
    main(Path(a[0]), Path(a[1]), a[i + 1], [Path(p) for p in a[2:i] + a[i + 2:]])
