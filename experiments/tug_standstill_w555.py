"""Decision W555's measurement: a TUG's slow rise and sit with a standstill before walking off and before sitting
(trial T2 finding F6), on fresh simulated users.

T2's TUG (``simulate --route "straight:3, turn:180, straight:3, turn:180" --sit-start 5 --sit-end 5 --transfer-time
2:4``, the default ``--stand 5``), once at the user's own gait ("normal") and once patient-like (T2's ``--variability
5 --irregular-rate 0.3 --step-width 0.28 --pelvis realistic --speed slow --bounce pendulum``), 100 Hz, tracked with
``--units waist`` (waist-pendulum): per session the truth (the first rise to the last seated instant, simulator
transfers.csv) against ``tug_time_s`` today (L648 + W506: ``with_slow_edges(standstill=False)``) and with W555, and
the rows W555 adds that overlap no true transfer of their kind.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/tug_standstill_w555.py U0 U1 TMPDIR
     ... experiments/tug_standstill_w555.py l648 LO HI U0 U1 TMPDIR [old]   (L648's own measurement, --stand 0.5,
     through experiments/tug_slow_edges_l648.py; ``old``: with W555 off, to diff against)
"""
from __future__ import annotations

import functools
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.waist.transfers as T
from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

ROUTE = "straight:3, turn:180, straight:3, turn:180"
GAITS = {"normal": [], "patient": ["--variability", "5", "--irregular-rate", "0.3", "--step-width", "0.28",
                                    "--pelvis", "realistic", "--speed", "slow", "--bounce", "pendulum"]}
EDGES = T.with_slow_edges


def truth(folder: Path) -> tuple[float, list[tuple[str, float, float]]]:
    tr = pd.read_csv(folder / "transfers.csv")
    rise, seated = tr["rise_ms"].to_numpy(float) / 1000, tr["seated_ms"].to_numpy(float) / 1000
    start, end = tr["start_ms"].to_numpy(float) / 1000, tr["end_ms"].to_numpy(float) / 1000
    return float(seated[-1] - rise[0]), [("sit-to-stand", rise[0], end[0]), ("stand-to-sit", start[-1], seated[-1])]


def track(folder: Path, w555: bool) -> tuple[float | None, pd.DataFrame]:
    T.with_slow_edges = functools.partial(EDGES, standstill=w555)
    try:
        s = read_session(folder)
        r = get_pipeline("waist-pendulum")(s)
        return track_summary(r, s, pipeline="waist-pendulum").get("tug_time_s"), pd.DataFrame(
            r.info["transfers"] or [], columns=list(T.TRANSFER_COLUMNS))
    finally:
        T.with_slow_edges = EDGES


def run(users: range, tmp: Path) -> None:
    logging.disable(logging.WARNING)
    timed = {(g, k): 0 for g in GAITS for k in (False, True)}
    within = dict(timed)
    errs = {k: [] for k in timed}
    false_added = 0
    for u in users:
        for gait, opts in GAITS.items():
            d = tmp / f"tug_{gait}_{u}"
            if not d.is_dir():
                assert main(["simulate", "--route", ROUTE, "--sit-start", "5", "--sit-end", "5", "--transfer-time",
                             "2:4", *opts, "--rate", "100", "--user-seed", str(u), "--out", str(d)]) == 0
            true_s, kinds = truth(d)
            (t0, rows0), (t1, rows1) = track(d, False), track(d, True)
            for key, t in ((False, t0), (True, t1)):
                if t is not None:
                    timed[(gait, key)] += 1
                    errs[(gait, key)].append(t - true_s)
                    within[(gait, key)] += abs(t - true_s) <= 1.0
            old = {(r.kind, round(r.start_s, 3)) for r in rows0.itertuples()}
            for r in rows1.itertuples():
                if (r.kind, round(r.start_s, 3)) not in old and not any(
                        k == r.kind and r.start_s < b and r.end_s > a for k, a, b in kinds):
                    false_added += 1
            print(f"user {u} {gait}: truth {true_s:.2f} s, today {t0 if t0 is None else round(t0, 2)}, "
                  f"W555 {t1 if t1 is None else round(t1, 2)}", flush=True)
    n = len(users)
    for gait in GAITS:
        for key, name in ((False, "today"), (True, "W555")):
            e = np.asarray(errs[(gait, key)])
            print(f"{gait} users {users.start}-{users.stop - 1} {name}: timed {timed[(gait, key)]} of {n}, within "
                  f"1.0 s {within[(gait, key)]}, median error {np.median(e) if len(e) else float('nan'):+.2f} s")
    print(f"W555: rows added matching no true transfer {false_added}")


if __name__ == "__main__":
    if sys.argv[1] == "l648":
        if len(sys.argv) > 7 and sys.argv[7] == "old":
            T.with_slow_edges = functools.partial(EDGES, standstill=False)
        import tug_slow_edges_l648 as L  # noqa: E402 (after the switch: it keeps T.with_slow_edges as L648's)

        L.run(float(sys.argv[2]), float(sys.argv[3]), range(int(sys.argv[4]), int(sys.argv[5]) + 1),
              Path(sys.argv[6]))
    else:
        run(range(int(sys.argv[1]), int(sys.argv[2]) + 1), Path(sys.argv[3]))
