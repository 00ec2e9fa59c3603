"""Decision W558's measurement (session 49, I3): the lower back's stride-time CV raw and with the contacts' timing
jitter taken out (Var(S) + 2 Cov(S_k, S_k+2)), against ics.csv's truth, on fresh users 16330-16349 (new walks of
C208's persons): 16330-16339 a 60 m straight walk, 16340-16349 150 m; ``--variability`` 1 / 2.5 alternately; 100 Hz.

Run: PYTHONPATH=. nice python experiments/lower_back_cv_s49_w558.py OUTDIR [--rerun]
(``--rerun``: read the kept walks and tracks again, e.g. to print the library's ``lower_back_cv`` beside them.)
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from gait_variability_s49_w557 import _run, cv
from pdrlearn.track.clinical import jitter_free_cv, lower_back_cv


def bout_contacts(track: Path) -> list[np.ndarray]:
    """The lower back's contact times (steps.csv ``start_s``) of each bout of 8 or more."""
    st = pd.read_csv(track / "steps.csv").sort_values("start_s")
    out = []
    for _, b in pd.read_csv(track / "bouts.csv").iterrows():
        t = st[(st["start_s"] >= b["start_s"] - 1e-6) & (st["start_s"] <= b["end_s"] + 1e-6)]["start_s"]
        if len(t) >= 8:
            out.append(t.to_numpy(float))
    return out


def true_stride_cv(session: Path) -> float:
    ics = pd.read_csv(session / "ics.csv")
    t = ics[ics["kind"] == "walk"]["ic_ms"].to_numpy(float) / 1000.0
    return cv((t[2:] - t[:-2])[1:-1])


def main(out: Path, rerun: bool = False) -> None:
    """``rerun``: the walks and tracks already in ``out`` are read again (no simulate / track)."""
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for uid in range(16330, 16350):
        length = 60 if uid < 16340 else 150
        var = "1" if uid % 2 == 0 else "2.5"
        ses, tr = out / f"u{uid}", out / f"w{uid}"
        if not rerun:
            _run("simulate", "--route", f"stand:3, straight:{length}, stand:3", "--rate", "100", "--user-seed",
                 str(uid), "--variability", var, "--out", str(ses), "--force")
            _run("track", str(ses), "--units", "waist", "--out", str(tr), "--force")
        raw, corr, n = jitter_free_cv(bout_contacts(tr))
        lib = lower_back_cv(pd.read_csv(tr / "steps.csv"))  # the track's own bouts (bout_rows), as summary.json
        true = true_stride_cv(ses)
        rows.append({"user": uid, "length_m": length, "variability": float(var), "n_strides": n, "true_cv": true,
                     "raw_cv": raw, "corrected_cv": corr, "raw_err": raw - true, "corrected_err": corr - true,
                     "summary_cv": lib["jitter_free_cv_pct"], "summary_n": lib["n_jitter_free_strides"]})
        print(json.dumps(rows[-1]), flush=True)
    t = pd.DataFrame(rows)
    t.to_csv(out / "w558.csv", index=False)
    with pd.option_context("display.width", 200, "display.precision", 2):
        print(t.to_string(index=False))
        for length, g in t.groupby("length_m"):
            e = g["corrected_err"].abs()
            print(f"{length} m: corrected within 1.0 point {int((e <= 1.0).sum())} of {len(g)}, median |error| "
                  f"{e.median():.2f} points (raw median |error| {g['raw_err'].abs().median():.2f}); strides "
                  f"{g['n_strides'].min()}-{g['n_strides'].max()}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), rerun="--rerun" in sys.argv[2:])
