"""Decisions W565 / W566 (session 49, FL): a lower-back unit turning on the belt during a recording.

Fresh users 16790-16819: a ~2 min route with two 20 s sits between walks, waist-pendulum, each user without and
with ``--waist-mount-drift`` (16790-16799 ``y:20``, 16800-16809 ``y:-20``, 16810-16819 ``x:15``); tracked with
W566's per-bout upright off and on. Truth: the simulator's transfers.csv. Real check: the three mobgap recordings
in /work/shared/data and the trial s49t3's rotated / slid files (not tuned to). Run:
``PYTHONPATH=. python experiments/mount_drift_s49_w565.py [N_USERS]``.
"""

from __future__ import annotations

import functools
import logging
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io.plasys import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import mount_drift

DRIFT_IMU = mount_drift.drift_imu  # the kernel; run() binds its W566 keyword

ROUTE = "stand:3, straight:15, sit:20, straight:15, turn:180, straight:15, sit:20, straight:15, stand:3"
SIM = Path("/tmp/fl_sim")
USERS = range(16790, 16820)
REAL = [Path("/work/shared/data") / n for n in ("mobgap_HA001_Test11_Trial1", "mobgap_HA001_Test5_Trial1",
                                                 "mobgap_HA001_Test5_Trial2")]
TRIAL = Path("/work/trial/s49t3/sess")


def drift_of(user: int) -> str:
    return "y:20" if user < 16800 else "y:-20" if user < 16810 else "x:15"


def simulate(user: int, drift: str | None) -> Path:
    out = SIM / f"u{user}_{'none' if drift is None else drift.replace(':', '')}"
    if not (out / "meta.json").exists():
        cmd = [sys.executable, "-m", "pdrlearn", "simulate", "--route", ROUTE, "--user-seed", str(user),
               "--bounce", "pendulum", "--rate", "100", "--out", str(out), "--force"]
        subprocess.run(cmd + ([] if drift is None else ["--waist-mount-drift", drift]), check=True,
                       capture_output=True)
    return out


def run(folder: Path, correct: bool, mode=True) -> tuple[list[dict], float, float, bool]:
    mount_drift.drift_imu = functools.partial(DRIFT_IMU, correct=correct)  # W566 on / off (a keyword, W413)
    from pdrlearn.waist.params import resolve_params

    session = read_session(folder)
    p, _ = resolve_params(session, None)
    p.options = {"mount_drift": mode}  # W571: an opt-in since the merge (PARAMS.json); W576: "standing"
    r = track_waist(session, pipeline="waist-pendulum", params=p)
    tr = [t for t in (r.info["transfers"] or []) if t["kind"] in ("sit-to-stand", "stand-to-sit")]
    post = r.info["postures"] or []
    sit = sum(b - a for a, b, k in post if k == "sitting")
    stand = sum(b - a for a, b, k in post if k == "standing")
    return tr, sit, stand, any("turned on the belt" in w for w in r.info["warnings"])


def truth(folder: Path) -> tuple[list[tuple[str, float, float]], float]:
    t = pd.read_csv(folder / "transfers.csv") / 1000.0
    rows, sit = [], 0.0
    for _, r in t.iterrows():
        if r.seated_ms > r.start_ms:
            rows.append(("stand-to-sit", r.start_ms, r.seated_ms))
        rows.append(("sit-to-stand", r.rise_ms, r.end_ms))
        sit += 0.5 * (r.rise_ms + r.end_ms) - 0.5 * (r.start_ms + r.seated_ms)
    return rows, sit


def errors(found: list[dict], true_rows) -> tuple[int, int]:
    used, hit = set(), 0
    for kind, a, b in true_rows:
        for i, f in enumerate(found):
            if i not in used and f["kind"] == kind and a - 1.0 <= f["peak_s"] <= b + 1.0:
                used.add(i)
                hit += 1
                break
    return len(true_rows) - hit, len(found) - len(used)


def _label(t: dict) -> str:
    return f"{t['kind']}@{t['peak_s']:.1f}{'*' if t['flag'] else ''}"  # * flagged (W278)


def real() -> None:
    for folder in [*REAL, *sorted(TRIAL.glob("HA001_*"))]:
        for correct in (False, True):
            tr, sit, stand, warned = run(folder, correct)
            print(f"REAL {folder.name} per_bout={correct!s:5s} transfers {len(tr)} "
                  f"({', '.join(_label(t) for t in tr)}) "
                  f"sitting {sit:.2f} standing {stand:.2f} warned {warned}", flush=True)


def main(n: int) -> None:
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    users = list(USERS)[:n]
    res = {}
    for cond in ("none", "drift"):
        for u in users:
            folder = simulate(u, None if cond == "none" else drift_of(u))
            rows, sit_true = truth(folder)
            for correct in (False, True):
                tr, sit, stand, warned = run(folder, correct)
                miss, false = errors(tr, rows)
                res[(cond, u, correct)] = (miss, false, abs(sit - sit_true), warned, len(tr), sit, stand)
                print(f"{cond:5s} {u} {drift_of(u) if cond == 'drift' else '-':6s} per_bout={correct!s:5s} "
                      f"transfers {len(tr)}/{len(rows)} miss {miss} false {false} sitting {sit:.2f} "
                      f"(true {sit_true:.2f}) standing {stand:.2f} warned {warned}", flush=True)
    for cond in ("none", "drift"):
        for correct in (False, True):
            v = [res[(cond, u, correct)] for u in users]
            print(f"SUMMARY {cond:5s} per_bout={correct!s:5s} n={len(v)} misses+false "
                  f"{sum(m + f for m, f, *_ in v)} median |sitting err| {np.median([e for _, _, e, *_ in v]):.2f} s "
                  f"max {max(e for _, _, e, *_ in v):.2f} s warned {sum(w for *_, w, _, _, _ in v)}")
    same = all(res[("none", u, False)][4:] == res[("none", u, True)][4:] for u in users)
    print(f"SUMMARY undrifted identical off/on: {same}")
    real()


if __name__ == "__main__":
    if sys.argv[1:] == ["real"]:  # the real check alone
        logging.getLogger("pdrlearn").setLevel(logging.ERROR)
        real()
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else len(USERS))
