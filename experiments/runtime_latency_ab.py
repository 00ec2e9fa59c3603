"""Per-step runtime latency of one code version on one bundle and session (for before/after comparisons).

Usage (compare the current tree with an older commit, interleaving runs to share the machine's load)::

    git archive <old-commit> pdrlearn | tar -x -C /tmp/old
    for i in 1 2 3; do
        PYTHONPATH=/tmp/old .venv/bin/python experiments/runtime_latency_ab.py BUNDLE SESSION
        .venv/bin/python experiments/runtime_latency_ab.py BUNDLE SESSION
    done

Prints the code location, then p50/p99 (ms) of ``Tracker.process_step`` over the session's labelled
steps (5 passes, buffers pre-filled, as tests/benchmarks/test_bench_runtime.py).
"""

from __future__ import annotations

import logging
import sys
import time

import numpy as np


def main(bundle: str, session_dir: str, passes: int = 5) -> None:
    logging.disable(logging.WARNING)
    import pdrlearn
    from pdrlearn.io import read_session
    from pdrlearn.runtime.tracker import Tracker

    s = read_session(session_dir)
    tr = Tracker(bundle, frames={p: f.to_dict() for p, f in s.frames.items()}, buffer_s=1e9)
    tr.push({n: (st.t, st.values) for n, st in s.streams.items()})
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    lat = []
    for _ in range(passes):
        for a, b in steps:
            t0 = time.perf_counter()
            tr.process_step(a, b)
            lat.append(time.perf_counter() - t0)
    ms = np.array(lat) * 1e3
    print(f"{pdrlearn.__file__}: p50 {np.percentile(ms, 50):.3f} ms, p99 {np.percentile(ms, 99):.3f} ms "
          f"({len(steps)} steps x {passes})")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
