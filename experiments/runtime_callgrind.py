"""Deterministic per-step cost of the runtime: instructions counted by callgrind (decisions E13, E15).

Wall-clock latency moves by +-30 % on a shared machine; instruction counts do not. Run the loop with 0
and with 2 passes and divide the difference::

    for k in 0 2; do
        PYTHONHASHSEED=0 valgrind --tool=callgrind --callgrind-out-file=cg.k$k \\
            .venv/bin/python experiments/runtime_callgrind.py BUNDLE SESSION $k [MODE]
    done
    # MODE steps (default) / steps-noinc: per step =
    #   (I refs of cg.k2 - I refs of cg.k0) / (2 * number of labelled steps)
    # MODE push / push-noinc: per pass = (I refs of cg.k2 - I refs of cg.k0) / 2 = every push of the
    #   session in its native chunking (tests/benchmarks/test_bench_runtime.py native_chunks), with the
    #   foot levelled at push time (push) or at the step event only (push-noinc, Tracker(incremental=False))
    # by library: callgrind_annotate --inclusive=no cg.k2 (minus cg.k0)

``steps`` times ``Tracker.process_step`` on pre-filled buffers (decision E11); ``push`` streams the whole
session, so it includes every push's own work (decision E15): (push count - steps count x steps) / pushes
is the mean cost of a push. Put an older ``pdrlearn`` first on PYTHONPATH to count another version (as
experiments/runtime_latency_ab.py). Three warm-up steps (steps mode) or one warm-up pass (push modes).
"""

from __future__ import annotations

import logging
import sys

import _repo  # noqa: F401  (the repository root at the end of sys.path, for tests.*: E301)


def main(bundle: str, session_dir: str, passes: int, mode: str = "steps") -> None:
    logging.disable(logging.WARNING)
    from pdrlearn.io import read_session
    from tests.benchmarks.test_bench_runtime import _loaded_tracker, native_chunks

    s = read_session(session_dir)
    if mode.startswith("push"):
        import inspect

        from pdrlearn.runtime.tracker import Tracker

        kw = {}
        if "incremental" in inspect.signature(Tracker).parameters:
            kw["incremental"] = mode == "push"
        chunks = native_chunks(s)
        frames = {p: f.to_dict() for p, f in s.frames.items()}
        trackers = [Tracker(bundle, frames=frames, **kw) for _ in range(3)]  # the same setup for every k
        for tr in trackers[:1 + passes]:
            for d in chunks:
                tr.push(d)
        return
    tr = _loaded_tracker(bundle, s, **({"incremental": False} if mode == "steps-noinc" else {}))
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    for a, b in steps[:3]:
        tr.process_step(a, b)
    for _ in range(passes):
        for a, b in steps:
            tr.process_step(a, b)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), *sys.argv[4:5])
