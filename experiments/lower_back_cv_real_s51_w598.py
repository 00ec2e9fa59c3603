"""Decision W598's check on the real lower-back recordings (session 51, FF; never tuned to): each
datasets/external/mobgap_* recording tracked with ``--units waist``; the lower back's jitter-free stride-time CV
without W558's 181-interval minimum (the recordings hold 3-90 contacts), against the INDIP reference's stride
durations (steps.csv ``duration_s``, strides that are no turn). Run once with each tree: the one whose
``pdrlearn.track.clinical`` has ``steady_runs`` prints W598's runs ("after"), else W558's bouts ("before").

Run: cd TREE && PYTHONPATH=TREE nice python /path/to/experiments/lower_back_cv_real_s51_w598.py DATASETS OUTDIR
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.track import clinical


def runs(steps: pd.DataFrame) -> tuple[str, list[np.ndarray]]:
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    t = st["start_s"].to_numpy(float)
    ranges = [(a, b) for a, b in clinical.bout_rows(st) if b - a >= clinical.JITTER_FREE_MIN_CONTACTS]
    if not hasattr(clinical, "steady_runs"):
        return "before", [t[a:b] for a, b in ranges]
    turning = st["turning"].to_numpy(float) != 0 if "turning" in st else np.zeros(len(st), bool)
    return "after", [r for a, b in ranges for r in clinical.steady_runs(t[a:b], turning[a:b])]


def main(data: Path, out: Path) -> None:
    for rec in sorted(data.glob("mobgap_*")):
        if not (rec / "steps.csv").exists():  # no INDIP strides in this test
            continue
        ref = pd.read_csv(rec / "steps.csv")
        ref = ref[~ref["turn"].astype(bool)] if "turn" in ref else ref
        d = ref["duration_s"].to_numpy(float)
        d = d[np.isfinite(d)]
        ref_cv = 100 * d.std(ddof=1) / d.mean() if len(d) > 2 else float("nan")
        tr = out / rec.name
        if not (tr / "steps.csv").exists():
            subprocess.run([sys.executable, "-m", "pdrlearn", "track", str(rec), "--units", "waist", "--out", str(tr),
                            "--force"], check=True, capture_output=True, text=True)
        which, r = runs(pd.read_csv(tr / "steps.csv"))
        raw, jf, n = clinical.jitter_free_cv(r)
        print(f"{rec.name} {which}: raw {raw:.1f} % jitter-free {jf:.1f} % over {n} stride intervals; INDIP "
              f"reference {ref_cv:.1f} % over {len(d)} straight strides", flush=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]))
