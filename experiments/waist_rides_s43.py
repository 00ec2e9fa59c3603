"""Decisions W486 / W487 (docs/decisions/waist.md): rides counted as steps by a lower-back unit alone (trial T3, F3 /
F4), measured once, before (main's code) and after (this branch), rule committed first.

Sessions: fresh users 12030-12039 (20 Hz, seed = user) on ROUTE; T3's splicer's ride models (scratch_T3/splice.py:
5-20 Hz vibration averaged to 20 Hz as the firmware does, 1-3 Hz suspension, stop-and-go, 90 deg turns at 15 deg/s)
spliced into the first sit (a seated bus), the long stand (a standing tram, harsh for odd users) and the second sit
(a car); the simulator's own `vehicle:60:0.8` is the fourth ride. The foot files are deleted (waist only).

Run (each with its own code on PYTHONPATH):
  OMP_NUM_THREADS=1 PYTHONPATH=MAIN python experiments/waist_rides_s43.py run before.csv
  OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_rides_s43.py run after.csv
  python experiments/waist_rides_s43.py verdict before.csv after.csv   # W486's (a), (b)
"""

from __future__ import annotations

import contextlib
import io
import logging
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

USERS = range(12030, 12040)  # the lead's fresh users for session 43's fixer FB
ROUTE = ("stand:5, straight:20, vehicle:60:0.8, straight:20, sit:60, straight:20, stand:60, straight:20, sit:60, "
         "straight:20, stand:5")
PIPELINES = ("waist-pendulum", "waist-pll")
SESSIONS = Path(os.environ.get("WAIST_RIDES_DIR", Path(tempfile.gettempdir()) / "waist_rides_s43"))  # scratch
TOL_S = 0.25
RIDE_MODELS = {  # T3's splicer's parameters (vib / sus: F, L, U rms m/s^2; acc: stop-and-go m/s^2)
    "bus_seated": {},
    "tram_standing": {"vib": [0.3, 0.3, 0.6], "sus": [0.15, 0.15, 0.3]},
    "tram_harsh": {"vib": [0.6, 0.6, 1.2], "sus": [0.3, 0.3, 0.6], "acc": 1.5},
    "car": {"acc": 2.0},
}


def _bandnoise(rng, n: int, lo: float, hi: float, fs: float = 100.0) -> np.ndarray:
    f = np.fft.rfftfreq(n, 1 / fs)
    spec = np.fft.rfft(rng.normal(size=(n, 3)), axis=0)
    spec[(f < lo) | (f > hi)] = 0
    x = np.fft.irfft(spec, n=n, axis=0)
    return x / x.std(axis=0)


def _vehicle(rng, th: np.ndarray, t0: float, t1: float, p: dict) -> tuple[np.ndarray, np.ndarray]:
    """T3's splicer's `vehicle_motion`: FLU specific-force increments and yaw rate of a stop-and-go ride."""
    a, w = np.zeros((th.size, 3)), np.zeros((th.size, 3))
    e = np.clip(np.minimum(th - t0, t1 - th) / 1.5, 0, 1)[:, None]
    a += (_bandnoise(rng, th.size, 5, 20) * np.array(p.get("vib", [0.3, 0.3, 0.6]))
          + _bandnoise(rng, th.size, 1, 3) * np.array(p.get("sus", [0.15, 0.15, 0.3]))) * e
    cyc, acc = p.get("cycle", 25.0), p.get("acc", 1.2)
    for c0 in np.arange(t0 + 2, t1 - cyc + 1, cyc):
        a[(th >= c0) & (th < c0 + 5), 0] += acc
        a[(th >= c0 + cyc - 6) & (th < c0 + cyc - 2), 0] -= acc * 5 / 4
    for k, tt in enumerate(np.arange(t0 + 12, t1 - 8, 30.0)):
        m, sgn = (th >= tt) & (th < tt + 6), 1 if k % 2 == 0 else -1
        w[m, 2] += sgn * np.radians(15)
        a[m, 1] += sgn * 6.0 * np.radians(15)
    return a, w


def _down(th: np.ndarray, x: np.ndarray, tq: np.ndarray) -> np.ndarray:
    """The firmware's 20 Hz: the mean of the 100 Hz samples in the 50 ms before each sample time."""
    out = np.zeros((tq.size, 3))
    for i, t in enumerate(tq):
        m = (th > t - 0.05) & (th <= t)
        out[i] = x[m].mean(axis=0) if m.any() else 0
    return out


def _waist(v: np.ndarray) -> np.ndarray:  # FLU -> the simulator's waist frame (x left, y up, z forward)
    return np.c_[v[:, 1], v[:, 2], v[:, 0]]


def make(user: int) -> tuple[Path, list[tuple[str, float, float]]]:
    out = SESSIONS / f"u{user}"
    if out.exists():
        shutil.rmtree(out)
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", ROUTE, "--user-seed", str(user),
                    "--out", str(out)], check=True, capture_output=True)
    tr = pd.read_csv(out / "transfers.csv")
    sits = [(r.seated_ms / 1000 + 3, r.rise_ms / 1000 - 3) for r in tr.itertuples()]
    ics = np.sort(pd.read_csv(out / "ics.csv")["ic_ms"].to_numpy(float) / 1000)
    ride = pd.read_csv(out / "rides.csv").iloc[0]
    gaps = [(a, b) for a, b in zip(ics[:-1], ics[1:], strict=True) if b - a > 40
            and not any(a <= s0 <= b for s0, _ in sits) and not a <= ride.start_ms / 1000 <= b]
    stand = (gaps[0][0] + 5, gaps[0][1] - 5)
    rides = [("bus_seated", *sits[0]), ("tram_harsh" if user % 2 else "tram_standing", *stand), ("car", *sits[1])]
    rng = np.random.default_rng(user)
    wa, wg = pd.read_csv(out / "wAccelerometer.csv"), pd.read_csv(out / "wGyroscope.csv")
    tq = wa["timestamp"].to_numpy(float) / 1000
    for kind, t0, t1 in rides:
        th = np.arange(t0, t1, 0.01)
        a, w = _vehicle(rng, th, t0, t1, RIDE_MODELS[kind])
        m = (tq >= t0) & (tq < t1)
        wa.loc[m, ["x", "y", "z"]] += _waist(_down(th, a, tq[m]))
        wg.loc[m, ["x", "y", "z"]] += _waist(_down(th, w, tq[m]))
    wa.to_csv(out / "wAccelerometer.csv", index=False)
    wg.to_csv(out / "wGyroscope.csv", index=False)
    for f in out.glob("f*.csv"):  # the lower-back unit alone
        f.unlink()
    rides.append(("vehicle", ride.start_ms / 1000, ride.end_ms / 1000))
    pd.DataFrame(rides, columns=["kind", "t0_s", "t1_s"]).to_csv(out / "spliced_rides.csv", index=False)
    return out, rides


def matched(ev: np.ndarray, truth: np.ndarray) -> int:
    """True contacts with a detected one within TOL_S (one-to-one, nearest first)."""
    used, seen = np.zeros(ev.size, bool), set()
    for _d, i, j in sorted((abs(e - t), i, j) for i, t in enumerate(truth) for j, e in enumerate(ev)
                           if abs(e - t) <= TOL_S):
        if i not in seen and not used[j]:
            seen.add(i)
            used[j] = True
    return len(seen)


def run(out_csv: str) -> None:
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist

    logging.disable(logging.WARNING)
    rows = []
    for u in USERS:
        folder = SESSIONS / f"u{u}"
        if not (folder / "spliced_rides.csv").exists():
            make(u)
        rides = pd.read_csv(folder / "spliced_rides.csv")
        truth = pd.read_csv(folder / "ics.csv")["ic_ms"].to_numpy(float) / 1000
        s = read_session(folder)
        for pl in PIPELINES:
            with contextlib.redirect_stderr(io.StringIO()):
                res = track_waist(s, pipeline=pl)
            ev = res.steps["event_s"].to_numpy(float)
            row = {"user": u, "pipeline": pl, "n_steps": ev.size, "n_true": truth.size,
                   "matched": matched(ev, truth), "distance_m": float(np.nansum(res.steps["length_m"]))}
            for r in rides.itertuples():
                row[r.kind.replace("tram_harsh", "tram_standing")] = int(((ev > r.t0_s) & (ev < r.t1_s)).sum())
            rows.append(row)
            print(row, flush=True)
    pd.DataFrame(rows).to_csv(out_csv, index=False)


def verdict(before_csv: str, after_csv: str) -> None:
    b, a = pd.read_csv(before_csv), pd.read_csv(after_csv)
    kinds = ["vehicle", "bus_seated", "tram_standing", "car"]
    ok = True
    for pl in PIPELINES:
        bb, aa = b[b.pipeline == pl], a[a.pipeline == pl]
        rb, ra = int(bb[kinds].to_numpy().sum()), int(aa[kinds].to_numpy().sum())
        drop = 1 - ra / rb if rb else float("nan")
        mb, ma = int(bb.matched.sum()), int(aa.matched.sum())
        ca = drop >= 0.80
        cb = ma >= 0.99 * mb
        ok &= ca and cb
        per = ", ".join(f"{k} {int(bb[k].sum())} -> {int(aa[k].sum())}" for k in kinds)
        print(f"{pl}: ride contacts {rb} -> {ra} ({100 * drop:.1f} % dropped; {per}): (a) "
              f"{'met' if ca else 'NOT met'}; true contacts matched {mb} -> {ma} of {int(bb.n_true.sum())}: (b) "
              f"{'met' if cb else 'NOT met'}; steps {int(bb.n_steps.sum())} -> {int(aa.n_steps.sum())}, distance "
              f"{bb.distance_m.sum():.1f} -> {aa.distance_m.sum():.1f} m")
    print(f"W486 (a), (b): {'met' if ok else 'NOT met'}")


if __name__ == "__main__":
    if sys.argv[1] == "run":
        run(sys.argv[2])
    else:
        verdict(sys.argv[2], sys.argv[3])
