"""Decision W527's measurement: the lower back's n_stair_strides_up / _down as main counted them (L179: rows whose
dz_m reaches 0.10 m, by their own sign) and as W527 counts them (W108's climb rows by their climb's sign, W526's
pieces), on one track each, against the simulator's stair steps (ics.csv kind stairs_up / stairs_down).

Sessions: W526's (``experiments/stepto_floors_s46_w526.py --work DIR`` writes them), users 14250-14269 step-to and
step over step; then the nine real mobgap recordings.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/stair_counts_s46_w527.py --work DIR
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd

import pdrlearn.track.evaluate as E
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.units import keep_units

K = ("n_stair_strides", "n_stair_strides_up", "n_stair_strides_down")


def both(s, res):
    """(main's, the candidate's) summary of one track: main's reading has no climb signs (L179 alone)."""
    c = evaluate_track(res, s)
    real = E._climb_parts
    with mock.patch.object(E, "_climb_parts", lambda st: (*real(st)[:2], None)):
        m = evaluate_track(res, s)
    return m, c


def main() -> None:
    logging.disable(logging.WARNING)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", required=True)
    ap.add_argument("--users", default="14250-14269")
    ap.add_argument("--external", default="datasets/external")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    w = get_pipeline("waist-pendulum")
    for label in ("step-to", "step-over"):
        err = [[], []]
        for u in range(lo, hi + 1):
            d = Path(a.work) / f"{label}_{u}"
            s = keep_units(read_session(d), ("waist",))
            res = w(s)
            m, c = both(s, res)
            ics = pd.read_csv(d / "ics.csv")
            tu, td = int((ics.kind == "stairs_up").sum()), int((ics.kind == "stairs_down").sum())
            for i, ev in enumerate((m, c)):
                err[i].append(abs(ev["n_stair_strides_up"] - tu) + abs(ev["n_stair_strides_down"] - td))
            print(f"{label} {u} true {tu}/{td} main {m['n_stair_strides_up']}/{m['n_stair_strides_down']} "
                  f"candidate {c['n_stair_strides_up']}/{c['n_stair_strides_down']} floors "
                  f"{c['floors_up']}/{c['floors_down']}", flush=True)
        print(f"{label}: mean |up error| + |down error| main {np.mean(err[0]):.2f}, candidate "
              f"{np.mean(err[1]):.2f} steps")
    for d in sorted(Path(a.external).glob("mobgap_*_Test*")):
        s = read_session(d)
        res = w(s)
        m, c = both(s, res)
        n = int(res.steps["climb"].astype(str).str.lower().eq("true").sum()) if "climb" in res.steps else 0
        print(f"{d.name:28s} climb rows {n} main {[m[k] for k in K]} candidate {[c[k] for k in K]}"
              f"{'' if all(m[k] == c[k] for k in K) else '  CHANGED'}", flush=True)


if __name__ == "__main__":
    main()
