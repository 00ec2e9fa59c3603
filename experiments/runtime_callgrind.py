"""Deterministic per-step cost of ``Tracker.process_step``: instructions counted by callgrind (decision E13).

Wall-clock latency moves by +-30 % on a shared machine; instruction counts do not. Run the loop with 0
and with 2 passes over the session's labelled steps under valgrind and divide the difference::

    for k in 0 2; do
        PYTHONHASHSEED=0 valgrind --tool=callgrind --callgrind-out-file=cg.k$k \\
            .venv/bin/python experiments/runtime_callgrind.py BUNDLE SESSION $k
    done
    # per step = (I refs of cg.k2 - I refs of cg.k0) / (2 * number of labelled steps)
    # by library: callgrind_annotate --inclusive=no cg.k2 (minus cg.k0)

Put an older ``pdrlearn`` first on PYTHONPATH to count another version (as experiments/runtime_latency_ab.py).
Buffers are pre-filled without trimming, as tests/benchmarks/test_bench_runtime.py; three warm-up steps.
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path

sys.path.append(str(Path(__file__).resolve().parents[1]))  # after PYTHONPATH: an old pdrlearn there wins


def main(bundle: str, session_dir: str, passes: int) -> None:
    logging.disable(logging.WARNING)
    from pdrlearn.io import read_session
    from tests.benchmarks.test_bench_runtime import _loaded_tracker

    s = read_session(session_dir)
    tr = _loaded_tracker(bundle, s)
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    for a, b in steps[:3]:
        tr.process_step(a, b)
    for _ in range(passes):
        for a, b in steps:
            tr.process_step(a, b)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
