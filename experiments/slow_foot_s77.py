"""Decision S77 (session 35; trials T3 finding 1, T1 finding 2): is the slow foot's mid-swing "rest" and the force-free
foot's +100 ms contact the simulator's or the tracker's? Diagnosis only, nothing tuned.

(a) For each foot recording: the tracker's rest runs (``inertial_stance``, decision L27) per reference stride, and,
    where toe-off and contact are labelled, the lowest 0.1 s mean |gyro| inside the swing (toe-off + 0.05 s ..
    contact - 0.05 s). (b) After each labelled contact: the largest later peak (contact + 0.06 .. 0.25 s) of the
    8 Hz low-passed |acc| (the accel detector's event signal, steps decision 14) as a fraction of the swing's
    largest rise above gravity; the detector's last-impact rule takes a later peak at >= 0.3 (PEAK_FRAC).

Simulated: fresh users 8450-8456 (100 Hz; slow stairs at step time 1.2 s as trial T3, 0.9 s, level at 1.2 s and at the
user's own normal step, force-free level walks with the default Hermite and the S31 smooth rocker).
Real: the shared gaitmap foot recordings and datasets/external's gaitmap foot recordings (no step-time option).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/slow_foot_s77.py [--external datasets/external]
Output: experiments/results/slow_foot_s77.txt
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.ndimage import uniform_filter1d
from scipy.signal import argrelmax, butter, filtfilt

from pdrlearn.displace.foot import inertial_stance, stance_runs
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

STAIRS_UP = "stand:3, straight:2, up:12:0.17:0.29, straight:2, stand:3"
STAIRS_DOWN = "stand:3, straight:2, down:12:0.17:0.29, straight:2, stand:3"
LEVEL = "stand:3, straight:20, stand:3"
#: (name, route, user, speed, step time (None = the user's own), rocker, force files kept)
SIMS = (("up_1.2s", STAIRS_UP, 8450, "slow", 1.2, "hermite", True),
        ("up_0.9s", STAIRS_UP, 8451, "slow", 0.9, "hermite", True),
        ("level_1.2s", LEVEL, 8452, "slow", 1.2, "hermite", True),
        ("level_normal", LEVEL, 8453, "normal", None, "hermite", True),
        ("down_1.2s", STAIRS_DOWN, 8454, "slow", 1.2, "hermite", True),
        ("noforce_hermite", LEVEL, 8456, "normal", None, "hermite", False),
        ("noforce_smooth", LEVEL, 8456, "normal", None, "smooth", False))


def _load(d: Path):
    a = pd.read_csv(d / "fAccelerometer.csv")
    g = pd.read_csv(d / "fGyroscope.csv")
    t = a.timestamp.to_numpy(float) / 1000
    return t, a[["x", "y", "z"]].to_numpy(float), g[["x", "y", "z"]].to_numpy(float), 1 / np.median(np.diff(t))


def swing_rest(d: Path) -> str:
    t, acc, gyr, fs = _load(d)
    st = pd.read_csv(d / "steps.csv")
    rr = stance_runs(t, inertial_stance(acc, gyr, fs))
    mids = t[(rr[:, 0] + rr[:, 1] - 1) // 2]
    inside = int(((mids > st.start_ms.min() / 1000) & (mids < st.end_ms.max() / 1000)).sum())
    out = f"strides {len(st):3d} (median {np.median(st.end_ms - st.start_ms) / 1000:.2f} s), rest runs {inside:3d}"
    if "tc_ms" in st and st.tc_ms.notna().all():
        w = uniform_filter1d(np.linalg.norm(gyr, axis=1), max(1, int(round(0.1 * fs))), mode="nearest")
        mins = [w[(t > c + 0.05) & (t < i - 0.05)].min() for c, i in zip(st.tc_ms / 1000, st.ic_ms / 1000, strict=True)
                if ((t > c + 0.05) & (t < i - 0.05)).sum() >= 3]
        out += f"; in-swing min |w| median {np.median(mins):.2f}, lowest {np.min(mins):.2f} rad/s"
    return out


def later_peak(d: Path) -> str:
    t, acc, _, fs = _load(d)
    m = np.linalg.norm(acc, axis=1)
    b, a = butter(2, 8.0 / (fs / 2))
    e = filtfilt(b, a, m)
    ic = pd.read_csv(d / "steps.csv").ic_ms.dropna().to_numpy(float) / 1000
    pk = argrelmax(e)[0]
    r, lag = [], []
    for i, c in enumerate(ic):
        prev = ic[i - 1] if i and c - ic[i - 1] < 3 else c - 1.2
        big = e[(t > prev + 0.3 * (c - prev)) & (t < c + 0.3)].max() - 9.81
        late = pk[(t[pk] > c + 0.06) & (t[pk] < c + 0.25)]
        r.append((e[late].max() - 9.81) / big if len(late) else 0.0)
        lag.append(t[late[np.argmax(e[late])]] - c if len(late) else np.nan)
    r = np.array(r)
    lags = np.array(lag)[np.array(r) > 0.05]
    return (f"contacts {len(r):3d}, later |acc| peak / largest rise median {np.median(r):.2f}, p90 "
            f"{np.percentile(r, 90):.2f}, >= 0.3 in {(r >= 0.3).sum()}"
            + (f", lag median {1000 * np.median(lags):.0f} ms" if len(lags) else ""))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", default="datasets/external")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    real = sorted(Path("datasets/real").glob("gaitmap_*")) + sorted(Path(args.external).glob("gaitmap_*"))
    print("(a) rest runs of the tracker (L27) and in-swing rotation")
    for d in real:
        print(f"  real {d.name:28s} {swing_rest(d)}")
    with tempfile.TemporaryDirectory() as tmp:
        sims = {}
        for name, route, u, speed, step_s, rocker, force in SIMS:
            user = UserProfile.from_seed(u)
            if step_s is not None:
                user = dataclasses.replace(user, step_time_s=step_s / {"slow": 1.2, "normal": 1.0}[speed])
            s = simulate_path(parse_route(route), user, speed=speed, rate_hz=100.0, rocker=rocker)
            d = Path(tmp) / name
            write_session(s, d)
            if not force:
                for f in d.glob("fForce*.csv"):
                    f.unlink()
            sims[name] = d
        for name in ("level_normal", "up_0.9s", "level_1.2s", "up_1.2s", "down_1.2s"):
            print(f"  sim  {name:28s} {swing_rest(sims[name])}")
        print("(b) a later |acc| peak after the labelled contact (8 Hz low-pass)")
        for d in real:
            if "ic_ms" in pd.read_csv(d / "steps.csv"):
                print(f"  real {d.name:28s} {later_peak(d)}")
        for name in ("noforce_hermite", "noforce_smooth"):
            print(f"  sim  {name:28s} {later_peak(sims[name])}")


if __name__ == "__main__":
    main()
