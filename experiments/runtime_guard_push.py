"""Per-push CPU cost of the live input checks (decisions B119/B120, E71): ``Tracker.push`` with one sample time per
push and with 100-sample chunks, p50/p95 (us) of each push's wall time, with the checks on and off
(``check_input``; the frozen-sensor watch runs in both); then the checks alone (``UnitGuard.check`` + ``take`` and
the ``FrozenWatch`` calls a tracker push makes) on the same pushes. Run it on two code versions to compare (the
"before": ``git archive <commit> pdrlearn | tar -x -C /tmp/old``, then ``PYTHONPATH=/tmp/old``)::

    python experiments/runtime_guard_push.py out/bundle/u1 out/sim/D_u1     # make demo writes both
"""

from __future__ import annotations

import logging
import sys
import time
from pathlib import Path

import numpy as np

import _repo  # noqa: F401  (the repository root at the end of sys.path, for tests.*: E301)


def chunks_of(streams: dict, n: int) -> list[dict]:
    """Pushes of ``n`` sample times each (``n = 1``: one push per distinct sample time, a live app's)."""
    times = np.unique(np.concatenate([t for t, _ in streams.values()]))
    out = []
    for a in range(0, len(times), n):
        lo, hi = times[a], times[min(a + n, len(times)) - 1]
        ch = {}
        for name, (t, v) in streams.items():
            i, j = np.searchsorted(t, lo), np.searchsorted(t, hi, side="right")
            if j > i:
                ch[name] = (t[i:j], v[i:j])
        out.append(ch)
    return out


def main(bundle_dir: str, session_dir: str, repeat: int = 3) -> None:
    logging.disable(logging.WARNING)
    import pdrlearn
    from pdrlearn.io import read_session
    from pdrlearn.runtime import Tracker, load_bundle

    print(f"code: {Path(pdrlearn.__file__).parent}")
    bundle = load_bundle(bundle_dir)
    s = read_session(session_dir)
    streams = {n: (st.t, st.values) for n, st in s.streams.items()}
    for n in (1, 100):
        pushes = chunks_of(streams, n)
        for check in (True, False):
            best = None
            for _ in range(repeat):
                tr = Tracker(bundle, check_input=check)
                us = np.empty(len(pushes))
                for k, c in enumerate(pushes):
                    c0 = time.perf_counter()
                    tr.push(c)
                    us[k] = (time.perf_counter() - c0) * 1e6
                tr.flush()
                best = us if best is None else np.minimum(best, us)  # each push's fastest pass (a loaded machine)
            print(f"{n:>3}-sample pushes ({len(pushes)}), check_input={check!s:5}: "
                  f"p50 {np.percentile(best, 50):7.1f} us  p95 {np.percentile(best, 95):7.1f} us  "
                  f"total {best.sum() / 1e3:7.0f} ms")

    checks_alone(streams)


def checks_alone(streams: dict, repeat: int = 5) -> None:
    """The input checks' share of a push: what ``Tracker.push`` calls of ``runtime.guard`` on each push."""
    from pdrlearn.runtime.guard import WATCHED, FrozenWatch, UnitGuard

    used = [n for n in streams if n in WATCHED]
    for n in (1, 100):
        pushes = [{k: tv for k, tv in c.items() if k in used} for c in chunks_of(streams, n)]
        fast = [{k: (float(t[0]), v[0].tolist()) for k, (t, v) in c.items()} for c in pushes] if n == 1 else None
        best = None
        for _ in range(repeat):
            guard, frozen = UnitGuard(used), FrozenWatch()
            us = np.empty(len(pushes))
            for k, c in enumerate(pushes):
                c0 = time.perf_counter()
                arrays = {m: c[m] for m in guard.wanted() if m in c}
                guard.take(arrays, guard.check(arrays))
                f = fast[k] if fast is not None else {}
                if hasattr(frozen, "push"):  # E71: one call
                    frozen.push({} if f else c, f)
                else:  # before E71: the tracker's two loops
                    for m in WATCHED:
                        if m in f:
                            frozen.note1(m, *f[m])
                        elif m in c:
                            frozen.note(m, *c[m])
                    for m in WATCHED:
                        if m in f:
                            frozen.feed1(m, *f[m])
                        elif m in c:
                            frozen.feed(m, *c[m])
                us[k] = (time.perf_counter() - c0) * 1e6
            best = us if best is None else np.minimum(best, us)
        print(f"checks alone, {n:>3}-sample pushes ({len(pushes)}): p50 {np.percentile(best, 50):7.1f} us  "
              f"p95 {np.percentile(best, 95):7.1f} us  total {best.sum() / 1e3:7.1f} ms")


if __name__ == "__main__":
    main(*sys.argv[1:3])
