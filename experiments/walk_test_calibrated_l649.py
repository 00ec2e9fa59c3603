"""Decision L649's measurement: the 10 m walk and the timed 25-foot walk on a calibrated lower back (waist-pendulum
with ``calibrate -d 30``'s parameters) against the simulator's truth, on fresh users 12462-12470.

Per user (step length 0.25-0.65 m, step time 0.5-0.8 s, 100 Hz, pendulum bounce): a 30 m calibration walk
(``stand:3, straight:30, stand:3``, --seed 9) -> ``calibrate -d 30``; the 10 m walk ``stand:3, straight:16, stand:3``
(the middle 10 m of L312's 14 m; truth: the body's crossing of 2 m and 12 m, trajectory.csv) and the T25FW from
standing ``stand:3, straight:12, stand:3`` (truth: the body's first movement, 1 cm from its start, to its crossing of
7.62 m). The kernel is read without L313's refusal (the steps' unit relabelled, as experiments/step_length_l310.py),
calibrated and uncalibrated.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/walk_test_calibrated_l649.py TMPDIR [--flying]
(--flying, after a first run in TMPDIR: trial T1's walkway 1,7.62,3.38 on the 16 m walks, calibrated; truth the body's
crossing of 1 m and 8.62 m)
"""
from __future__ import annotations

import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.track.walk_test import T25FW_M, t25fw, ten_metre_walk

USERS = range(12462, 12471)


def gait(i: int) -> tuple[float, float]:
    """User i's step length (m) and step time (s): 0.25-0.65 m, 0.5-0.8 s."""
    return 0.25 + 0.05 * i, 0.5 + 0.075 * (i % 5)


def crossing(traj: pd.DataFrame, metres: float) -> float:
    t, x = traj["timestamp"].to_numpy(float) / 1000, traj["x"].to_numpy(float)
    return float(t[np.argmax(x - x[0] >= metres)])


def sim(d: Path, route: str, u: int, sl: float, st: float, seed: str = "0") -> None:
    if not d.is_dir():
        assert main(["simulate", "--route", route, "--user-seed", str(u), "--rate", "100", "--bounce", "pendulum",
                     "--step-length", f"{sl:.3f}", "--step-time", f"{st:.3f}", "--seed", seed, "--out", str(d)]) == 0


def unrefused(session, params) -> pd.DataFrame:
    return track_waist(session, pipeline="waist-pendulum", params=params).steps.assign(unit="waist-unrefused")


def run(tmp: Path) -> None:
    logging.disable(logging.WARNING)
    err = {(k, c): [] for k in ("10mw", "t25fw") for c in ("calibrated", "uncalibrated")}
    for i, u in enumerate(USERS):
        sl, st = gait(i)
        cal, walk, t25 = tmp / f"cal_{u}", tmp / f"w16_{u}", tmp / f"t25_{u}"
        sim(cal, "stand:3, straight:30, stand:3", u, sl, st, seed="9")
        params = tmp / f"p_{u}.json"
        if not params.is_file():
            assert main(["calibrate", str(cal), "-d", "30", "--out", str(params)]) == 0
        sim(walk, "stand:3, straight:16, stand:3", u, sl, st)
        sim(t25, "stand:3, straight:12, stand:3", u, sl, st)
        tr = pd.read_csv(walk / "trajectory.csv")
        true10 = crossing(tr, 12.0) - crossing(tr, 2.0)
        tr = pd.read_csv(t25 / "trajectory.csv")
        true25 = crossing(tr, T25FW_M) - crossing(tr, 0.01)
        line = (f"u{u} {sl:.2f} m / {st:.3f} s (~{sl / st:.2f} m/s): 10 m walk true {true10:.2f} s, T25FW true "
                f"{true25:.2f} s;")
        for c, p in (("calibrated", str(params)), ("uncalibrated", None)):
            r10 = ten_metre_walk(unrefused(read_session(walk), p))
            r25 = t25fw(unrefused(read_session(t25), p))
            for key, r, tk, truth in (("10mw", r10, "ten_m_walk_time_s", true10),
                                      ("t25fw", r25, "t25fw_time_s", true25)):
                if r[tk] is None:
                    line += f" {c} {key} not timed;"
                    continue
                e = 100.0 * (truth / r[tk] - 1.0)  # speed error: (m / t) / (m / truth) - 1
                err[(key, c)].append(e)
                line += f" {c} {key} {r[tk]:.2f} s ({e:+.1f} %);"
        print(line, flush=True)
    for (key, c), e in err.items():
        a = np.asarray(e)
        print(f"{key} {c}: n={len(a)}, speed error median {np.median(a):+.2f} %, median |.| "
              f"{np.median(np.abs(a)):.2f} %, max |.| {np.abs(a).max():.2f} %")


def flying(tmp: Path) -> None:
    logging.disable(logging.WARNING)
    errs = []
    for u in USERS:
        tr = pd.read_csv(tmp / f"w16_{u}" / "trajectory.csv")
        truth = crossing(tr, 8.62) - crossing(tr, 1.0)
        r = ten_metre_walk(unrefused(read_session(tmp / f"w16_{u}"), str(tmp / f"p_{u}.json")), (1.0, 7.62, 3.38))
        if r["ten_m_walk_time_s"] is None:
            print(f"u{u}: not timed ({r['ten_m_walk_note'][:80]})")
            continue
        errs.append(100.0 * (truth / r["ten_m_walk_time_s"] - 1.0))
        print(f"u{u}: 1,7.62,3.38 true {truth:.2f} s, calibrated {r['ten_m_walk_time_s']:.2f} s ({errs[-1]:+.1f} %)")
    a = np.asarray(errs)
    print(f"1,7.62,3.38 calibrated: n={len(a)}, speed error median {np.median(a):+.2f} %, median |.| "
          f"{np.median(np.abs(a)):.2f} %, max |.| {np.abs(a).max():.2f} %")


if __name__ == "__main__":
    flying(Path(sys.argv[1])) if "--flying" in sys.argv else run(Path(sys.argv[1]))
