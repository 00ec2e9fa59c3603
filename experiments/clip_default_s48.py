"""Decision B470 (session 48, trial T1 finding F1): B454's ``clip_noise`` as the offline foot track's default when
the foot accelerometer clips, measured by the rule written in docs/decisions/bad-input.md before measuring.

Sessions: fresh simulated users 15860-15875 at B454's four walks (``--speed slow|normal|fast`` on T3's stair route,
a brisk level walk), the foot accelerometer / gyroscope clipped flat at +-4 g / 500 and +-8 g / 1000 deg/s
(``clip_range_s46.clipped``) and unclipped; users 15876-15899 at the simulator's own +-16 g on trial T1's half lap:
a race walk (step length / time drawn in T1's range) and a ``--speed fast`` walk. Each tracked offline without a
model with ``{"clip_noise": false}`` (before) and the default (the candidate). Run
``python experiments/clip_default_s48.py [WORKER NWORKERS]``, ``... real`` (the real foot recordings) and
``... report`` (the tables and B470's verdict).
"""
from __future__ import annotations

import logging
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.io.validate import clipped_samples
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

sys.path.insert(0, str(Path(__file__).resolve().parent))
from clip_range_s46 import BRISK, ROUTE, clipped  # noqa: E402 - B454's route and clipping, shared

STAIR_USERS = range(15860, 15876)
LAP_USERS = range(15876, 15900)
#: trial T1's half lap (mk.sh's lap: a straight, the bend, a straight): the end 73.6 m from the start
HALF_LAP = "stand:5, straight:84.39, curve:180:36.8, straight:84.39, stand:5"
STAIR_SPEEDS = ("slow", "normal", "fast", "brisk")
LAP_KINDS = ("racewalk", "lapfast")
RANGES = {"none": None, "4g": (4, 500), "8g": (8, 1000)}
WORK = Path(sys.argv[0]).resolve().parent / "results"
SIM = Path("/tmp/fe_s48/sim")
REAL = Path("/work/shared/data")
KEYS = ("distance_error_pct", "final_position_error_m", "final_altitude_error_m", "stride_length_mae_pct")


def race_step(user: int) -> tuple[float, float]:
    """The user's race-walking step length (m) and time (s), uniform in trial T1's range (0.93-1.00 m, 0.27-0.30 s)."""
    rng = np.random.default_rng(user)
    return round(float(rng.uniform(0.93, 1.00)), 2), round(float(rng.uniform(0.27, 0.30)), 2)


def simulate(user: int, kind: str) -> Path:
    from pdrlearn.cli import main

    d = SIM / f"u{user}_{kind}"
    if not (d / "meta.json").exists():
        if kind in STAIR_SPEEDS:
            args = (["--route", BRISK, "--step-length", "0.95", "--step-time", "0.42"] if kind == "brisk" else
                    ["--route", ROUTE, "--speed", kind])
        elif kind == "racewalk":
            length, time = race_step(user)
            args = ["--route", HALF_LAP, "--step-length", str(length), "--step-time", str(time)]
        else:  # "lapfast"
            args = ["--route", HALF_LAP, "--speed", "fast"]
        try:
            main(["simulate", *args, "--user-seed", str(user), "--seed", str(user), "--rate", "100", "--out", str(d),
                  "--force"])
        except SystemExit as e:
            if e.code:
                raise
    return d


def tracked(s, candidate: bool):
    """The offline track: the default (B470's candidate) or ``{"clip_noise": false}``."""
    return get_pipeline("auto")(s, **({} if candidate else {"params": {"clip_noise": False}}))


def identical(a, b) -> bool:
    """(e): steps' lengths and headings and the trajectory equal bit for bit."""
    return all(np.array_equal(x, y, equal_nan=True) for x, y in (
        (a.steps["length_m"].to_numpy(), b.steps["length_m"].to_numpy()),
        (a.steps["heading_rad"].to_numpy(), b.steps["heading_rad"].to_numpy()),
        (a.trajectory[["x", "y", "z"]].to_numpy(), b.trajectory[["x", "y", "z"]].to_numpy())))


def score(s) -> dict:
    n = clipped_samples(s.streams["fAccelerometer"].values, "accelerometer")[0]
    r = {"clipped_samples": n, "samples": len(s.streams["fAccelerometer"])}
    res = {c: tracked(s, c) for c in (False, True)}
    for c, tr in res.items():
        m = track_summary(tr, s)
        r.update({f"{k}_{'cand' if c else 'off'}": m.get(k) for k in KEYS})
    r["identical"] = identical(res[False], res[True])
    return r


def run(worker: int = 0, n: int = 1, kinds: tuple = (*STAIR_SPEEDS, *LAP_KINDS), part: str = "") -> None:
    """Worker ``worker`` of ``n``: its share of the sessions of ``kinds`` (rows: results/..._part{part}{worker}.csv)."""
    jobs = ([(u, k, rng) for u in STAIR_USERS for k in STAIR_SPEEDS if k in kinds for rng in RANGES]
            + [(u, k, "16g") for u in LAP_USERS for k in LAP_KINDS if k in kinds])[worker::n]
    rows = []
    for u, k, rng in jobs:
        s0 = read_session(simulate(u, k))
        s = s0 if RANGES.get(rng) is None else clipped(s0, *RANGES[rng])
        r = {"user": u, "kind": k, "range": rng, **score(s)}
        print(r, flush=True)
        rows.append(r)
        pd.DataFrame(rows).to_csv(WORK / f"clip_default_s48_part{part}{worker}.csv", index=False)


def real() -> None:
    """(e) on the real foot recordings of /work/shared/data."""
    for d in sorted(p for p in REAL.iterdir() if (p / "meta.json").exists()):
        s = read_session(d)
        if not s.has("fAccelerometer"):
            continue
        n = clipped_samples(s.streams["fAccelerometer"].values, "accelerometer")[0]
        print(f"{d.name}: {n} clipped foot accelerometer samples, identical "
              f"{identical(tracked(s, False), tracked(s, True))}", flush=True)


def report() -> None:
    df = pd.concat([pd.read_csv(p) for p in sorted(WORK.glob("clip_default_s48_part*.csv"))])
    for c in ("off", "cand"):
        df[f"abs_dist_{c}"] = df[f"distance_error_pct_{c}"].abs()
        df[f"abs_alt_{c}"] = df[f"final_altitude_error_m_{c}"].abs()
    print("median distance error % off -> candidate (min..max of the candidate) / median stride_length_mae_pct "
          "off -> candidate; clipped sessions / sessions, by range x kind:")
    for (rng, k), g in df.groupby(["range", "kind"], sort=False):
        print(f"  {rng} {k}: {g.distance_error_pct_off.median():+.2f} -> {g.distance_error_pct_cand.median():+.2f} "
              f"({g.distance_error_pct_cand.min():+.2f}..{g.distance_error_pct_cand.max():+.2f}) / "
              f"{g.stride_length_mae_pct_off.median():.2f} -> {g.stride_length_mae_pct_cand.median():.2f}; "
              f"{int((g.clipped_samples > 0).sum())} / {len(g)}")
    df["range"] = df["range"].replace("none", "16g")  # an unclipped copy that clips is at the simulator's +-16 g
    c = df[df.clipped_samples > 0]
    better = (c.abs_dist_cand <= c.abs_dist_off).mean()
    a = better >= 0.8
    print(f"B470 (a): |distance error| better or equal in {100 * better:.1f} % of {len(c)} clipped sessions: {a}")
    b = True
    for rng in ("4g", "8g", "16g"):
        g = c[c.range == rng]
        if not len(g):
            print(f"B470 (b) {rng}: no clipped session, left out")
            continue
        ok = g.abs_dist_cand.median() < g.abs_dist_off.median()
        b &= ok
        print(f"B470 (b) {rng}: median |distance error| {g.abs_dist_off.median():.2f} -> "
              f"{g.abs_dist_cand.median():.2f} % over {len(g)} clipped sessions: {ok}")
    worse = (c.final_position_error_m_cand - c.final_position_error_m_off > 0.2).mean()
    cc = worse <= 0.2
    print(f"B470 (c): final position error worse by more than 0.2 m in {100 * worse:.1f} % of the clipped sessions "
          f"(median {c.final_position_error_m_off.median():.2f} -> {c.final_position_error_m_cand.median():.2f} m): "
          f"{cc}")
    d = True
    for rng in ("4g", "8g"):
        g = c[c.range == rng]
        ok = g.abs_alt_cand.median() <= g.abs_alt_off.median()
        d &= ok
        print(f"B470 (d) {rng}: median |final altitude error| {g.abs_alt_off.median():.2f} -> "
              f"{g.abs_alt_cand.median():.2f} m: {ok}")
    u = df[df.clipped_samples == 0]
    e = bool(u.identical.all())
    print(f"B470 (e): {int(u.identical.sum())} of {len(u)} unclipped simulated sessions identical: {e} (the real "
          "recordings: `real`)")
    print("B470 (a)-(e), the real recordings aside:", bool(a and b and cc and d and e))


def main(argv: list[str]) -> None:
    """``report``, ``real``, ``lapfast W N`` (the half lap's fast walks alone: a first run simulated the stair
    route's) or ``[W N]``: the worker's share of every session."""
    modes = {"report": lambda: report(), "real": lambda: real(),
             "lapfast": lambda: run(int(argv[1]), int(argv[2]), ("lapfast",), "_lapfast")}
    mode = modes.get(argv[0] if argv else "")
    mode() if mode else run(*(int(a) for a in argv[:2]))


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    warnings.simplefilter("ignore")
    WORK.mkdir(parents=True, exist_ok=True)
    main(sys.argv[1:])
