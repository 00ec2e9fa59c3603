"""Decision E328 (session 51, I3): the live Tracker's memory over a stop over 600 s (E324 keeps the waist's
accelerometer and gyroscope rings for up to 600 s of it).

    python experiments/runtime_ring_memory_s51_e328.py 17930 100     # user 17930's walk at 100 Hz
    python experiments/runtime_ring_memory_s51_e328.py 17930 1000    # the same walk interpolated to 1000 Hz

The walk (`simulate --route "stand:5, straight:10, stand:620, spin:90:4, straight:10, stand:5" --waist-mount y:20`)
is pushed in 1 s chunks through `Tracker(models/plasys-sim-default)` (foot + waist, the defaults); printed: the
largest bytes held by the rings (their arrays' nbytes, all rings and the two carried ones) and samples held, over the
pushes, and the traced peak of the whole push loop (tracemalloc)."""

import logging
import os
import sys
import tracemalloc
from pathlib import Path

import numpy as np

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.runtime import Tracker, load_bundle

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
CARRIED = ("wAccelerometer", "wGyroscope")  # E324 / E305's carried rings


def chunks(session, chunk_s: float):
    t = session.streams["fAccelerometer"].t
    edges = t[0] + chunk_s * np.arange(int((t[-1] - t[0]) / chunk_s) + 2)
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        yield {n: (st.t[(st.t >= a) & (st.t < b)], st.values[(st.t >= a) & (st.t < b)])
               for n, st in session.streams.items()}


def ring_bytes(tr, names=None) -> tuple[int, int]:
    rings = {n: r for n, r in tr._buf.items() if names is None or n in names}
    return (sum(r.t.nbytes + r.v.nbytes for r in rings.values()), sum(len(r) for r in rings.values()))


def run(user: int, rate: int) -> None:
    logging.disable(logging.WARNING)
    root = Path(os.environ.get("OUT", "/tmp/e328"))
    d = root / f"mem_u{user}_100"
    if not d.exists():
        assert main(["simulate", "--route", "stand:5, straight:10, stand:620, spin:90:4, straight:10, stand:5",
                     "--user-seed", str(user), "--rate", "100", "--waist-mount", "y:20", "--out", str(d)]) == 0
    s = read_session(d, streamed=True)
    if rate != 100:  # the simulator gives 100 Hz / n only: a faster unit is the 100 Hz walk interpolated (memory only)
        for st in s.streams.values():
            t = np.arange(st.t[0], st.t[-1], 1.0 / rate)
            st.values = np.column_stack([np.interp(t, st.t, st.values[:, k]) for k in range(st.values.shape[1])])
            st.t = t
    tr = Tracker(load_bundle(BUNDLE), sensors=list(s.streams), input_rates_hz={n: float(rate) for n in s.streams})
    peak_all = peak_carried = peak_n = 0
    tracemalloc.start()
    steps = []
    for c in chunks(s, 1.0):
        steps += tr.push(c)
        b_all, _ = ring_bytes(tr)
        b_c, n_c = ring_bytes(tr, CARRIED)
        peak_all, peak_carried, peak_n = max(peak_all, b_all), max(peak_carried, b_c), max(peak_n, n_c)
    steps += tr.flush()
    _, traced = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"user {user} {rate} Hz: {len(steps)} steps; rings max bytes all {peak_all}, carried (wAccelerometer + "
          f"wGyroscope) {peak_carried} holding {peak_n} samples; traced peak {traced} bytes; final heading "
          f"{steps[-1].heading_rad:.6f} rad, position ({steps[-1].x:.4f}, {steps[-1].y:.4f}) m", flush=True)


if __name__ == "__main__":
    run(int(sys.argv[1]), int(sys.argv[2]))
