"""Decision B91 measurement: the swapped / duplicated foot-waist detector (pdrlearn.io.unit_check) on fresh
simulated users 260-262 (every scenario, 20 and 100 Hz) and on the real recordings of datasets/external, each
real foot recording paired with each real waist one. Run after the rule was committed:

    PYTHONPATH=. OMP_NUM_THREADS=1 python experiments/unit_mixup_b91.py
"""

from __future__ import annotations

import glob
import logging
import types

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.io.unit_check import swing_rate, unit_mixup
from pdrlearn.sim import SCENARIOS, simulate

SWAP = {"fAccelerometer": "wAccelerometer", "fGyroscope": "wGyroscope",
        "wAccelerometer": "fAccelerometer", "wGyroscope": "fGyroscope"}


def fake(streams: dict):
    """What unit_mixup reads of a session: its streams, meta.json and has()."""
    return types.SimpleNamespace(streams=streams, meta={}, has=lambda *n: all(x in streams for x in n))


def swapped(streams: dict) -> dict:
    return {SWAP.get(k, k): v for k, v in streams.items()}


def copied(streams: dict) -> dict:
    return {**streams, "wAccelerometer": streams["fAccelerometer"], "wGyroscope": streams["fGyroscope"]}


def deg(gyro) -> float:
    return float(np.degrees(swing_rate(gyro.values)))


def main() -> None:
    logging.disable(logging.WARNING)
    alarms = called = refused = n = n_walk = 0
    for rate in (20, 100):
        for sc in SCENARIOS:
            for u in (260, 261, 262):
                st = simulate(sc, u, "normal", rate_hz=rate, seed=u, length_m=200.0).streams
                ok, sw, cp = unit_mixup(fake(st)), unit_mixup(fake(swapped(st))), unit_mixup(fake(copied(st)))
                n += 1
                alarms += ok is not None
                refused += cp is not None and "same data" in cp
                if sc != "standstill":
                    n_walk += 1
                    called += sw is not None and "swapped" in sw
                print(f"{rate:3d} Hz {sc:10s} u{u}: foot p99 {deg(st['fGyroscope']):6.1f} deg/s waist p99 "
                      f"{deg(st['wGyroscope']):6.1f} | correct: {'ALARM' if ok else 'clear'} | swapped: "
                      f"{'called' if sw else 'missed'} | copy: {'refused' if cp else 'missed'}")
    feet, waists = [], []
    for d in sorted(glob.glob("datasets/external/*")):
        s = read_session(d)
        for p, found in (("f", feet), ("w", waists)):
            if p + "Gyroscope" in s.streams:
                found.append({f"{p}{k}": s.streams[p + k] for k in ("Accelerometer", "Gyroscope")})
                print(f"real {d.split('/')[-1]} {p}: p99 {deg(s.streams[p + 'Gyroscope']):.1f} deg/s")
    pairs = [{**f, **w} for f in feet for w in waists]
    real_alarms = sum(unit_mixup(fake(st)) is not None for st in pairs)
    real_called = sum(unit_mixup(fake(swapped(st))) is not None for st in pairs)
    print(f"simulated: false alarms {alarms}/{n}; swapped walking sessions called {called}/{n_walk}; "
          f"copies refused {refused}/{n}")
    print(f"real pairs: false alarms {real_alarms}/{len(pairs)}; swapped pairs called {real_called}/{len(pairs)}")


if __name__ == "__main__":
    main()
