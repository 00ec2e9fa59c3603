"""Decision W126's measurement: the default two-unit track (method auto, fused heading) with and without the
waist gyroscope bias read at rest removed, on clean and BLE-biased simulated 400 m walks (IMU only, as the
session-24 BLE trial).

    PYTHONPATH=. python experiments/waist_rest_bias_w126.py --users 1790-1809
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from pdrlearn.io.session import Stream
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

#: the BLE trial's IMU-only pods: no force, magnetometer or barometer
DROPPED = ("fForceA", "fForceB", "wMagneticField", "wBarometer")


def imu_only(session):
    s = session.copy()
    for n in DROPPED:
        s.streams.pop(n, None)
    return s


def biased(session, seed: int):
    """Both units' gyroscopes plus a per-axis bias drifting linearly from b0 to b1 over the session, |b0|, |b1|
    uniform 0.5-2 deg/s with the same sign per axis (the trial's `bias` kind)."""
    rng = np.random.default_rng(seed)
    s = session.copy()
    for n in ("fGyroscope", "wGyroscope"):
        st = s.streams[n]
        b0 = rng.uniform(0.5, 2, 3) * rng.choice([-1, 1], 3)
        b1 = rng.uniform(0.5, 2, 3) * np.sign(b0)
        frac = (st.t - st.t[0]) / (st.t[-1] - st.t[0])
        s.streams[n] = Stream(n, st.t, st.values + np.deg2rad(b0 + (b1 - b0) * frac[:, None]))
    return s


def final_error(session, waist_bias: bool) -> float:
    r = track_plasys(session, method="auto", waist_bias=waist_bias)
    return float(evaluate_track(r, session)["final_position_error_m"])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--users", default="1790-1809", help="first-last simulated user seeds")
    ap.add_argument("--length-m", type=float, default=400.0)
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    logging.disable(logging.WARNING)
    clean_d, before, after = [], [], []
    for u in range(lo, hi + 1):
        s = imu_only(simulate("walk", u, length_m=a.length_m, rate_hz=100.0))
        c0, c1 = final_error(s, False), final_error(s, True)
        b = biased(s, u)
        b0, b1 = final_error(b, False), final_error(b, True)
        clean_d.append(abs(c1 - c0))
        before.append(b0)
        after.append(b1)
        print(f"user {u}: clean {c0:.2f} -> {c1:.2f} m | biased {b0:.2f} -> {b1:.2f} m", flush=True)
    before, after = np.array(before), np.array(after)
    n_better = int((after < before).sum())
    print(f"clean: largest change {max(clean_d):.3f} m; biased: improved {n_better}/{len(before)}, median "
          f"{np.median(before):.2f} -> {np.median(after):.2f} m")
    adopted = max(clean_d) <= 0.1 and n_better >= 15 * len(before) / 20 and np.median(after) < np.median(before)
    print("W126 rule:", "ADOPTED" if adopted else "NOT adopted")


if __name__ == "__main__":
    main()
