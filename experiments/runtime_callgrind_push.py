"""Instructions of the pushes that complete a step, each counted alone, with per-function inclusive costs
(decisions E18-E21 in docs/decisions/export.md).

The measured pushes run inside ``functools.reduce``, so callgrind counts only them::

    PYTHONHASHSEED=0 OPENBLAS_NUM_THREADS=1 valgrind --tool=callgrind --collect-atstart=no \\
        --toggle-collect=functools_reduce --callgrind-out-file=cg.out \\
        .venv/bin/python experiments/runtime_callgrind_push.py BUNDLE [MARKERS] [--other]
    # per push = PROGRAM TOTALS of `callgrind_annotate cg.out` / the number of steps printed
    # per function: callgrind_annotate --inclusive=yes --threshold=100 cg.out | grep _next
    #   (each marked function's inclusive cost is that of the C iterator it runs in; ~2 k per marker)

The session is simulated user 1, scenario C, pushed sample by sample (``native_chunks``; one warm-up pass
with another tracker first). ``MARKERS``: ``none`` (default), ``top`` (the step's stages), ``foot`` (the
foot levelling's kernels) or ``push`` (the push's own work). A marked function runs inside a C iterator
the runtime never calls (``itertools.starmap``, ``accumulate``, ``takewhile``, ``dropwhile``,
``filterfalse``, ``groupby``, ``list.sort(key=)``), so ``callgrind_annotate --inclusive=yes`` lists its
inclusive cost under that iterator's ``*_next`` (``list_sort_impl`` for the sort). ``--other`` counts the
pushes that complete no step instead. Put another ``pdrlearn`` first on PYTHONPATH to count it.
Since decision E24 the step is computed at the end of the push before it (``--other`` counts that work);
``--nospec`` counts the same code with ``Tracker(speculative=False)`` (every step in its own push).
"""

from __future__ import annotations

import functools
import itertools
import logging
import sys

import _repo  # noqa: F401  (the repository root at the end of sys.path, for tests.*: E301)


def _starmap(g):
    return next(itertools.starmap(g, ((),)))


def _accumulate(g):
    return list(itertools.accumulate((None, None), lambda x, y: g()))[1]


def _predicate(kind):
    def run(g):
        box = []
        list(kind(lambda x: box.append(g()) or True, (0,)))
        return box[0]
    return run


def _groupby(g):
    box = []
    list(itertools.groupby((0,), key=lambda x: box.append(g())))
    return box[0]


def _sorted(g):
    box = []
    sorted((0, 1), key=lambda x: (box.append(g()), 0)[1] if not box else 0)
    return box[0]


KINDS = [_starmap, _accumulate, _predicate(itertools.takewhile), _predicate(itertools.dropwhile),
         _predicate(itertools.filterfalse), _groupby, _sorted]
NAMES = ["starmap_next", "accumulate_next", "takewhile_next", "dropwhile_next", "filterfalse_next",
         "groupby_next", "list_sort_impl"]


def _wrap(owner, attr: str, k: int) -> None:
    f, run = getattr(owner, attr), KINDS[k]
    setattr(owner, attr, lambda *a, **kw: run(lambda: f(*a, **kw)))
    print(f"{NAMES[k]:17s} = {attr}", file=sys.stderr)


def main(bundle: str, markers: str = "none", other: bool = False, nospec: bool = False) -> None:
    logging.disable(logging.WARNING)
    import pdrlearn.runtime.stream as stm
    import pdrlearn.runtime.tracker as trm
    from pdrlearn.runtime.tracker import Tracker
    from pdrlearn.sim import simulate
    from tests.benchmarks.test_bench_runtime import native_chunks

    sets = {
        "none": [],
        "top": [(Tracker, "process_step"), (Tracker, "_window"), (trm, "foot_levelled"), (trm, "waist_entry"),
                (trm, "fill_resampled"), (Tracker, "_classify_step"), (trm, "stride_motion")],
        "foot": [(stm, "tilt_corrected"), (stm, "stride_headings"), (stm, "principal_horizontal_xy"),
                 (stm, "rest_score"), (stm, "gravity_rotation_xyz"), (stm, "step_direction"),
                 (trm, "foot_levelled")],
        "push": [(Tracker, "process_step"), (Tracker, "_detect"), (Tracker, "_process_ready"),
                 (trm.StanceSegmenter, "update_norms"), (stm.FootLevelling, "feed1")],
    }
    for k, (owner, attr) in enumerate(sets[markers]):
        _wrap(owner, attr, k)
    s = simulate("C", 1)
    chunks = native_chunks(s)
    frames = {p: f.to_dict() for p, f in s.frames.items()}
    kw = {"speculative": False} if nospec else {}
    warm, tr = Tracker(bundle, frames=frames, **kw), Tracker(bundle, frames=frames, **kw)
    hits = {i for i, d in enumerate(chunks) if warm.push(d)}
    measured = set(range(len(chunks))) - hits if other else hits
    for i, d in enumerate(chunks):
        if i in measured:
            functools.reduce(lambda t, x: t.push(x), (d,), tr)
        else:
            tr.push(d)
    print(f"measured pushes: {len(measured)} ({'without' if other else 'with'} a step)", file=sys.stderr)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a not in ("--other", "--nospec")]
    main(args[0], *(args[1:2]), other="--other" in sys.argv, nospec="--nospec" in sys.argv)
