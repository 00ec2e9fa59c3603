"""Decision B49: what a session built or changed in Python gave before the entry points checked it, and what
the check costs on the step-detection benchmark's 1 h session.

    PYTHONPATH=. .venv/bin/python experiments/api_validate.py

Part 1 runs the new-user trial's cases (session 13) on datasets/real (a DataError line, or the result).
Part 2 prints the CPU time (``time.process_time``) of ``detect`` per detector (best of 5) on the 1 h
two-unit 20 Hz session of tests/benchmarks/test_bench_steps.py, and of ``Session.validate`` first and again.
Run it on main and on a branch to compare (the numbers vary by tens of percent on a shared machine).
"""

from __future__ import annotations

import logging
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "benchmarks"))

from test_bench_steps import _hour  # noqa: E402

from pdrlearn import sim  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.steps import AccelStepDetector, get_detector  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402


def _run(label, fn) -> None:
    try:
        r = fn()
        out = f"{len(r.steps)} steps, {r.distance_m:,.2f} m" if hasattr(r, "distance_m") else f"{len(r)} rows"
    except Exception as e:  # noqa: BLE001 (printed, that is the point)
        out = f"{type(e).__name__}: {e}"
    print(f"{label}: {out}")


def _changed(s, name, t=1.0, v=1.0):
    s = s.copy()
    s.streams[name].t[:] *= t
    s.streams[name].values[:] *= v
    return s


def cases() -> None:
    logging.disable(logging.WARNING)
    f = read_session(ROOT / "datasets/real/gaitmap_level_left")
    w = read_session(ROOT / "datasets/real/mobgap_HA001_Test5_Trial1")

    def pl(s):
        return get_pipeline("plasys")(s, method="auto")

    _run("correct plasys", lambda: pl(f))
    _run("acc in g plasys", lambda: pl(_changed(f, "fAccelerometer", v=1 / 9.80665)))
    _run("gyro deg/s plasys", lambda: pl(_changed(f, "fGyroscope", v=180 / np.pi)))
    _run("t in ms plasys", lambda: pl(_changed(_changed(f, "fAccelerometer", t=1000), "fGyroscope", t=1000)))
    _run("waist acc in g waist-pendulum",
         lambda: get_pipeline("waist-pendulum")(_changed(w, "wAccelerometer", v=1 / 9.80665)))
    _run("acc in g detect", lambda: AccelStepDetector().detect(_changed(f, "fAccelerometer", v=1 / 9.80665)))
    _run("t in ms detect", lambda: AccelStepDetector().detect(_changed(f, "fAccelerometer", t=1000)))
    _run("dict detect", lambda: AccelStepDetector().detect(dict(f.streams)))
    logging.disable(logging.NOTSET)


def _cpu(fn) -> float:
    c = time.process_time()
    fn()
    return (time.process_time() - c) * 1e3


def cost() -> None:
    s = _hour(sim.simulate("B", 1, speed="normal"))
    parts = []
    for name in ("accel", "accel-force", "pelvic-gyro", "pll"):
        det = get_detector(name)
        parts.append(f"{name} {min(_cpu(lambda: det.detect(s)) for _ in range(5)):.1f}")  # noqa: B023
    print("detect, 1 h two-unit 20 Hz, best of 5, ms CPU: " + " | ".join(parts))
    if hasattr(s, "validate"):
        fresh = _hour(sim.simulate("B", 1, speed="normal"))
        first = _cpu(fresh.validate)
        again = min(_cpu(fresh.validate) for _ in range(5))
        print(f"Session.validate on it: first {first:.1f} ms, again {again:.2f} ms CPU")


if __name__ == "__main__":
    cases()
    cost()
