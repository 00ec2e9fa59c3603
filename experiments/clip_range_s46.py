"""Decisions B453 / B454 (session 46, trial T3 findings F1 / F7): what a clipped foot IMU costs by range and speed,
and whether B454's candidate (``FootDisplacement(clip_noise=True)``: the ZUPT's velocity error put at the clipped
samples, ``pdrlearn.kernels.clip_noise``) recovers it.

Sessions: simulated users 14300-14305 at ``--speed slow|normal|fast`` on T3's route (47 m, a 12-step flight up and
down) and a brisk level walk (``--step-length 0.95 --step-time 0.42``), 100 Hz. The foot accelerometer / gyroscope
clipped flat at +-2 g / 250, +-4 g / 500, +-8 g / 1000 and +-16 g / 2000 deg/s; +-4 g and +-8 g tracked with the
candidate on and off (the ``declip`` column; the first candidate, a cubic declipping, was measured by this script at
commit 6f567ac6). Offline track without a model (``get_pipeline("auto")``), scored by ``track_summary`` against
steps.csv. Run ``python experiments/clip_range_s46.py [WORKER NWORKERS]`` (each worker writes its share of rows), then
``python experiments/clip_range_s46.py fused WORKER NWORKERS`` (the stair walks clipped at +-2 / 4 / 8 g tracked
with ``altitude="fused"``, decision L688), then ``python experiments/clip_range_s46.py report`` for the tables and
B454's verdict (its rule in docs/decisions/bad-input.md).
"""
from __future__ import annotations

import logging
import sys
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.io.session import Session, Stream
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

G0 = 9.80665
USERS = range(14300, 14306)
ROUTE = "stand:3, straight:20, turn:90, straight:10, up:12, turn:180, down:12, straight:10, stand:3"
BRISK = "stand:3, straight:40, turn:90, straight:20, stand:3"
SPEEDS = ("slow", "normal", "fast", "brisk")
RANGES = {"none": None, "2g": (2, 250), "4g": (4, 500), "8g": (8, 1000), "16g": (16, 2000)}
DECLIPPED = ("4g", "8g")
#: the rows' ``declip`` column -> B454's candidate (clip_noise) off / on
CANDIDATE = {False: False, True: True}
WORK = Path(sys.argv[0]).resolve().parent / "results"
SIM = Path("/tmp/lead_s46/scratch_FE/sim")


def simulate(user: int, speed: str) -> Path:
    from pdrlearn.cli import main

    d = SIM / f"u{user}_{speed}"
    if not (d / "meta.json").exists():
        args = (["--route", BRISK, "--step-length", "0.95", "--step-time", "0.42"] if speed == "brisk" else
                ["--route", ROUTE, "--speed", speed])
        try:
            main(["simulate", *args, "--user-seed", str(user), "--rate", "100", "--out", str(d), "--force"])
        except SystemExit as e:
            if e.code:
                raise
    return d


def clipped(s: Session, acc_g: float, gyro_dps: float) -> Session:
    """The session with its foot accelerometer / gyroscope clipped flat."""
    out = replace(s, streams=dict(s.streams))
    for name, lim in (("fAccelerometer", acc_g * G0), ("fGyroscope", np.deg2rad(gyro_dps))):
        st = s.streams[name]
        out.streams[name] = Stream(name, st.t, np.clip(np.asarray(st.values, float), -lim, lim))
    return out


def score(s: Session, candidate: bool | None, **options) -> dict:
    """The offline track's figures; ``candidate`` (B454's clip_noise) True / False given, None: the default;
    ``options`` the pipeline's (``altitude="fused"``)."""
    kw = {**options, **({} if candidate is None else {"params": {"clip_noise": candidate}})}
    m = track_summary(get_pipeline("auto")(s, **kw), s)
    return {k: m.get(k) for k in ("distance_error_pct", "final_position_error_m", "final_altitude_error_m",
                                  "altitude_change_m")}


def run(worker: int, n: int) -> None:
    jobs = [(u, sp) for u in USERS for sp in SPEEDS][worker::n]
    rows = []
    for u, sp in jobs:
        s0 = read_session(simulate(u, sp))
        for rng, lim in RANGES.items():
            for dc in ((False, True) if rng in DECLIPPED else (False,)):
                s = s0 if lim is None else clipped(s0, *lim)
                r = {"user": u, "speed": sp, "range": rng, "declip": dc, **score(s, CANDIDATE[dc])}
                print(r, flush=True)
                rows.append(r)
        pd.DataFrame(rows).to_csv(WORK / f"clip_range_s46_part{worker}.csv", index=False)


def run_fused(worker: int, n: int) -> None:
    """Decision L688: the clipped copies tracked with ``altitude="fused"`` (L154: the waist barometer's height)."""
    jobs = [(u, sp) for u in USERS for sp in SPEEDS if sp != "brisk"][worker::n]
    rows = []
    for u, sp in jobs:
        s0 = read_session(simulate(u, sp))
        for rng in ("2g", "4g", "8g"):
            r = {"user": u, "speed": sp, "range": rng, **score(clipped(s0, *RANGES[rng]), None, altitude="fused")}
            print(r, flush=True)
            rows.append(r)
        pd.DataFrame(rows).to_csv(WORK / f"clip_range_s46_fused{worker}.csv", index=False)


def report() -> None:
    fused = sorted(WORK.glob("clip_range_s46_fused*.csv"))
    if fused:
        f = pd.concat([pd.read_csv(p) for p in fused])
        print("altitude fused (L154), median |final altitude error| m / median distance error %, by range x speed:")
        for rng, g in f.groupby("range", sort=False):
            print(f"  {rng}: " + "; ".join(f"{sp} {h.final_altitude_error_m.abs().median():.2f} / "
                                           f"{h.distance_error_pct.median():+.2f}" for sp, h in g.groupby("speed",
                                                                                                       sort=False)))
    df = pd.concat([pd.read_csv(p) for p in sorted(WORK.glob("clip_range_s46_part*.csv"))])
    df["abs_dist"] = df.distance_error_pct.abs()
    df["abs_alt"] = df.final_altitude_error_m.abs()
    print("median distance error % (min..max) / median |final altitude error| m, by range x speed:")
    for (rng, dc), g in df.groupby(["range", "declip"], sort=False):
        cells = []
        for sp in SPEEDS:
            h = g[g.speed == sp]
            cells.append(f"{sp} {h.distance_error_pct.median():+.2f} ({h.distance_error_pct.min():+.2f}.."
                         f"{h.distance_error_pct.max():+.2f}) / {h.abs_alt.median():.2f}")
        print(f"  {rng}{' candidate' if dc else ''}: " + "; ".join(cells))
    base = df[df.range == "none"]
    verdicts = {}
    for rng in DECLIPPED:
        c, d = df[(df.range == rng) & ~df.declip], df[(df.range == rng) & df.declip]
        loss = c.abs_dist.median() - base.abs_dist.median()
        need = c.abs_dist.median() - 0.3 * loss
        a = d.abs_dist.median() <= need
        b = (d.abs_alt.median() <= c.abs_alt.median()
             and d.final_position_error_m.median() <= c.final_position_error_m.median())
        verdicts[rng] = (a, b)
        print(f"B454 {rng}: median |distance error| unclipped {base.abs_dist.median():.2f} %, clipped "
              f"{c.abs_dist.median():.2f} %, candidate {d.abs_dist.median():.2f} % (needed <= {need:.2f}): (a) {a}; "
              f"median |final altitude error| {c.abs_alt.median():.2f} -> {d.abs_alt.median():.2f} m, median final "
              f"position error {c.final_position_error_m.median():.2f} -> {d.final_position_error_m.median():.2f} m:"
              f" (b) {b}")
    print("B454 (a) and (b) at both ranges:", all(a and b for a, b in verdicts.values()))


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    warnings.simplefilter("ignore")
    WORK.mkdir(parents=True, exist_ok=True)
    if sys.argv[1:2] == ["report"]:
        report()
    elif sys.argv[1:2] == ["fused"]:
        run_fused(int(sys.argv[2]), int(sys.argv[3]))
    else:
        run(int(sys.argv[1]) if len(sys.argv) > 1 else 0, int(sys.argv[2]) if len(sys.argv) > 2 else 1)
