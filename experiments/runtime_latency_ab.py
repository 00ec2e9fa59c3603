"""Per-step runtime latency of one code version on one bundle and session (for before/after comparisons).

Usage (compare the current tree with an older commit, interleaving runs to share the machine's load)::

    git archive <old-commit> pdrlearn | tar -x -C /tmp/old
    for i in 1 2 3; do
        PYTHONPATH=/tmp/old .venv/bin/python experiments/runtime_latency_ab.py BUNDLE SESSION
        .venv/bin/python experiments/runtime_latency_ab.py BUNDLE SESSION
    done

Prints the code location, then p50/p99 (ms) of ``Tracker.process_step`` over the session's labelled
steps and the p50 of its CPU time (5 passes, buffers pre-filled without trimming, as
tests/benchmarks/test_bench_runtime.py), and the median over the steps of each step's fastest pass
("min-of-passes p50"): the figure least moved by other processes on a loaded machine (decision E13).
Then decision E15's latency: p50/p95/p99 of the push that completes a step with the session pushed sample
by sample (``native_chunks``), and the mean and p95 cost of the other pushes (E83: a step computed ahead moves
its cost to the push before).
"""

from __future__ import annotations

import logging
import sys

import numpy as np

import _repo  # noqa: F401  (the repository root at the end of sys.path, for tests.*: E301)


def main(bundle: str, session_dir: str, passes: int = 5) -> None:
    logging.disable(logging.WARNING)
    import pdrlearn
    from pdrlearn.io import read_session
    from tests.benchmarks.test_bench_runtime import _latencies, _loaded_tracker, push_latencies

    s = read_session(session_dir)
    tr = _loaded_tracker(bundle, s)
    cpu: list[float] = []
    ms = _latencies(tr, list(zip(s.steps["start_s"], s.steps["end_s"], strict=True)), repeat=passes, cpu=cpu)
    fastest = ms.reshape(passes, len(s.steps)).min(axis=0)  # each step's fastest pass
    print(f"{pdrlearn.__file__}: process_step p50 {np.percentile(ms, 50):.3f} ms, p99 {np.percentile(ms, 99):.3f} ms, "
          f"CPU time p50 {np.percentile(cpu, 50):.3f} ms, min-of-passes p50 {np.median(fastest):.3f} ms "
          f"({len(s.steps)} steps x {passes})")
    y, o, n = push_latencies(bundle, s, repeat=passes)
    print(f"{pdrlearn.__file__}: push yielding a step p50 {np.percentile(y, 50):.3f} ms, "
          f"p95 {np.percentile(y, 95):.3f} ms, p99 {np.percentile(y, 99):.3f} ms ({n} steps x {passes}); "
          f"other pushes mean {np.mean(o) * 1e3:.1f} us, "
          f"p95 {np.percentile(o, 95) * 1e3:.1f} us")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], *(int(a) for a in sys.argv[3:4]))
