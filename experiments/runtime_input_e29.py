"""Decisions E29/E30 (docs/decisions/export.md): the runtime pushed one sample time per push, with gaps in every
stream, and the CPU time of such pushes. Prints the numbers of the E29 cost line and the E30 table (the
"before" column: the same script on the commit before E29).

    python experiments/runtime_input_e29.py out/bundle/u1 out/sim/D_u1     # make demo writes both
"""

from __future__ import annotations

import sys
import time

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.runtime import Tracker, load_bundle


def per_timestamp(streams: dict) -> list[dict]:
    """One push per distinct sample time: every sensor with a sample then (a live app's pushes)."""
    times = np.unique(np.concatenate([t for t, _ in streams.values()]))
    idx = {n: np.searchsorted(t, times) for n, (t, _) in streams.items()}
    out = []
    for k, T in enumerate(times):
        ch = {}
        for n, (t, v) in streams.items():
            i = idx[n][k]
            if i < len(t) and t[i] == T:
                ch[n] = (t[i:i + 1], v[i:i + 1])
        out.append(ch)
    return out


def main(bundle_dir: str, session_dir: str) -> None:
    bundle = load_bundle(bundle_dir)
    s = read_session(session_dir)
    streams = {n: (st.t, st.values) for n, st in s.streams.items()}
    chunks = per_timestamp(streams)
    best = np.inf
    for _ in range(5):
        tr = Tracker(bundle)
        c0 = time.process_time()
        for c in chunks:
            tr.push(c)
        tr.flush()
        best = min(best, time.process_time() - c0)
    print(f"{len(chunks)} pushes: best CPU time of 5 {best * 1e3:.0f} ms ({best / len(chunks) * 1e6:.1f} us/push)")
    for a, g in ((50.0, 0.0), (50.0, 0.5), (50.0, 1.5), (20.0, 2.0), (50.0, 10.0)):
        cut = {n: (t[~((t >= a) & (t < a + g))], v[~((t >= a) & (t < a + g))]) for n, (t, v) in streams.items()}
        tr = Tracker(bundle)
        steps = [st for c in per_timestamp(cut) for st in tr.push(c)] + tr.flush()
        dist = sum(abs(st.length_m) for st in steps)
        last = steps[-1]
        lines = sum("no samples for" in w for w in tr.warnings)
        print(f"gap {g:4.1f} s at {a:g} s: {len(steps)} steps, {dist:.2f} m, final ({last.x:.2f}, {last.y:.2f}, "
              f"{last.z:.2f}), gap lines {lines}")


if __name__ == "__main__":
    main(*sys.argv[1:3])
