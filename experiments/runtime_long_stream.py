"""Decision E27: the default (incremental) ``Tracker`` against ``incremental=False`` over an hour of walking.

Simulates a 5 km walk (``pdrlearn.sim``, scenario ``walk``, user 1) at 20 Hz and at 100 Hz, keeps its first
hour, and streams it into the shipped bundle ``models/plasys-sim-default`` (a 20 Hz bundle: the 100 Hz walk is
tracked at its own rate, decision E22) twice, with the push-time foot levelling state (decision E15, the
default) and without it (``incremental=False``, the shared kernel alone), pushed one sample at a time and in
1 s chunks. Prints per case the step counts, the first stride whose length or position differs by more than
1e-9 m / 1e-6 m / 1 cm / 1 m, the largest difference and the CPU seconds of each run. Before E27 the default
tracker crashed (``gravity vector [..e+205..] is zero or not finite``) after 6-8 minutes at 20 Hz.

Usage::

    .venv/bin/python experiments/runtime_long_stream.py [--minutes 60] [--rates 20,100] [--chunks 0,1]

(``--chunks 0`` = one sample per push). Takes ~5 minutes (the 100 Hz simulation ~1 minute).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


def pushes(streams: dict, chunk_s: float):
    """The streams as pushes: one sample per push (``chunk_s == 0``; the simulator's units share one clock)
    or chunks on integer chunk indices (as ``pdrlearn run``'s, decision E28)."""
    if chunk_s > 0:  # (written out rather than imported, so that the script runs on versions before E28 too)
        t0 = min(float(t[0]) for t, _ in streams.values() if len(t))
        idx = {k: np.floor((t - t0) / chunk_s + 1e-9).astype(int) for k, (t, _) in streams.items()}
        n = max(int(i[-1]) for i in idx.values() if len(i)) + 1
        cut = {k: np.searchsorted(i, np.arange(n + 1)) for k, i in idx.items()}
        for j in range(n):
            yield {k: (t[cut[k][j]:cut[k][j + 1]], v[cut[k][j]:cut[k][j + 1]]) for k, (t, v) in streams.items()}
        return
    n = len(streams["fGyroscope"][0])
    for i in range(n):
        yield {k: (t[i:i + 1], v[i:i + 1]) for k, (t, v) in streams.items() if i < len(t)}


def stream(streams: dict, chunk_s: float, **kw):
    from pdrlearn.runtime import Tracker

    tr = Tracker(BUNDLE, **kw)
    out, err, c0 = [], None, time.process_time()
    try:
        for d in pushes(streams, chunk_s):
            out += tr.push(d)
        out += tr.flush()
    except Exception as exc:  # noqa: BLE001 - the failure is the result (before E27)
        err = f"{type(exc).__name__} at {out[-1].end_s if out else 0:.0f} s: {str(exc)[:80]}"
    return out, err, time.process_time() - c0


def compare(streams: dict, chunk_s: float, label: str) -> None:
    A, ea, ca = stream(streams, chunk_s)
    B, eb, cb = stream(streams, chunk_s, incremental=False)
    first, worst = {}, 0.0
    for a, b in zip(A, B, strict=False):
        e = max(abs(a.length_m - b.length_m), abs(a.x - b.x), abs(a.y - b.y), abs(a.z - b.z))
        worst = max(worst, e)
        for th in (1e-9, 1e-6, 0.01, 1.0):
            if e > th and th not in first:
                first[th] = f"{a.end_s:.0f} s ({a.length_m:.4g} vs {b.length_m:.4g} m)"
    same = [(a.start_s, a.end_s) for a in A] == [(b.start_s, b.end_s) for b in B]
    print(f"{label}, {'one sample' if chunk_s == 0 else f'{chunk_s:g} s'} per push: default {len(A)} steps"
          f"{' ' + ea if ea else ''} ({ca:.1f} s CPU), incremental=False {len(B)} steps{' ' + eb if eb else ''} "
          f"({cb:.1f} s CPU); same step times {same}; max |diff| {worst:.2e} m; first > 1e-9 / 1e-6 / 1 cm / 1 m: "
          + " / ".join(first.get(th, "none") for th in (1e-9, 1e-6, 0.01, 1.0)), flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--minutes", type=float, default=60.0)
    ap.add_argument("--rates", default="20,100")
    ap.add_argument("--chunks", default="0,1")
    args = ap.parse_args()
    from pdrlearn.sim import simulate

    for rate in [float(r) for r in args.rates.split(",")]:
        s = simulate("walk", 1, rate_hz=rate, length_m=5000.0)
        end = args.minutes * 60.0
        streams = {n: (st.t[st.t <= end], np.asarray(st.values)[st.t <= end]) for n, st in s.streams.items()}
        dur = max(float(t[-1]) for t, _ in streams.values() if len(t))
        for chunk_s in [float(c) for c in args.chunks.split(",")]:
            compare(streams, chunk_s, f"walk {rate:g} Hz, {dur:.0f} s")


if __name__ == "__main__":
    main()
