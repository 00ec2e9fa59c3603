"""Runtime benchmarks (issue 7 targets, measured, not asserted; run with `make bench` or
``pytest tests/benchmarks/test_bench_runtime.py --benchmark-enable -m bench -s``).

Targets: per-step latency (step window + features + 3 task classifiers + displacement) p50 <= 0.3 ms,
p99 <= 2 ms, measured as the push that completes a step with the session pushed sample by sample
(decision E15; ``process_step`` on pre-filled buffers is decision E11's figure, kept for comparison);
runtime import + bundle load < 0.5 s; bundle size < 5 MB for the default methods.
The bundle is trained on the simulator's calibration exercises of one user (default export = each
task's chosen method, usually a foot+waist fused model = 2 ONNX runs per task).
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

import numpy as np
import pytest

pytestmark = pytest.mark.bench


@pytest.fixture(scope="module")
def bundles(tmp_path_factory):
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.sim import simulate

    root = tmp_path_factory.mktemp("bench_runtime")
    cal = [simulate(sc, 1) for sc in ("terrain", "direction", "length")]
    train_user(cal, cv=3, seed=0).save(root / "model")
    export_model(root / "model", root / "bundle")
    export_model(root / "model", root / "bundle_all", methods=["heuristic", "fusion", "dtw", "svm", "nn"])
    return {"root": root, "session": simulate("C", 1)}


def _loaded_tracker(bundle, session, **kw):
    from pdrlearn.runtime.tracker import Tracker

    tr = Tracker(bundle, frames={p: f.to_dict() for p, f in session.frames.items()}, buffer_s=1e9, **kw)
    # fill the buffers with the whole session, without detecting, processing and trimming (push would
    # process every step and then keep only the last second before the last stance: the labelled steps
    # timed afterwards would see one-sample windows)
    for n, st in session.streams.items():
        tr._append(n, st.t, st.values)
    return tr


def native_chunks(session) -> list[dict]:
    """The session's samples as a device streams them (decision E15): one push per timestamp, holding
    each sensor's sample at that time (all sensors of a 20 Hz PLASYS tick together; units on their own
    clocks in separate pushes), in time order."""
    names = list(session.streams)
    ts = [session.streams[n].t for n in names]
    allt = np.unique(np.concatenate(ts))
    idx = [np.searchsorted(allt, t) for t in ts]  # each sample's tick
    per_tick: list[dict] = [{} for _ in range(len(allt))]
    for n, t, ix in zip(names, ts, idx, strict=True):
        v = session.streams[n].values
        for k, j in enumerate(ix.tolist()):
            per_tick[j][n] = (t[k:k + 1], v[k:k + 1])
    return per_tick


def push_latencies(bundle, session, repeat=3, **kw) -> tuple[np.ndarray, np.ndarray, int]:
    """Decision E15's latency: ``Tracker.push`` timed on every push of :func:`native_chunks` (a new tracker
    per pass). Returns (ms of the pushes that returned a step, ms of the other pushes, steps per pass)."""
    from pdrlearn.runtime.tracker import Tracker

    chunks = native_chunks(session)
    frames = {p: f.to_dict() for p, f in session.frames.items()}
    yielding, other, n = [], [], 0
    for _ in range(repeat):
        tr = Tracker(bundle, frames=frames, **kw)
        n = 0
        for d in chunks:
            t0 = time.perf_counter()
            out = tr.push(d)
            dt = time.perf_counter() - t0
            if out:
                yielding.append(dt / len(out))
                n += len(out)
            else:
                other.append(dt)
    return np.array(yielding) * 1e3, np.array(other) * 1e3, n


def _latencies(tr, steps, repeat=3, cpu: list | None = None) -> np.ndarray:
    """Wall-clock ms per ``process_step``; ``cpu`` (a list) also gets each step's CPU time of this thread
    (ms), which other processes on the machine inflate less than the wall clock."""
    out = []
    for _ in range(repeat):
        for a, b in steps:
            c0, t0 = time.thread_time(), time.perf_counter()
            tr.process_step(a, b)
            out.append(time.perf_counter() - t0)
            if cpu is not None:
                cpu.append((time.thread_time() - c0) * 1e3)
    return np.array(out) * 1e3


def test_bench_runtime_per_step_default_bundle(benchmark, bundles):
    s = bundles["session"]
    tr = _loaded_tracker(bundles["root"] / "bundle", s)
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    cpu: list[float] = []
    lat = _latencies(tr, steps, cpu=cpu)
    benchmark.extra_info.update(p50_ms=float(np.percentile(lat, 50)), p99_ms=float(np.percentile(lat, 99)),
                                cpu_p50_ms=float(np.percentile(cpu, 50)),
                                methods={t: f"{c.method}/{c.unit}" for t, c in tr.classifiers.items()})
    print(f"\nper step (default bundle {benchmark.extra_info['methods']}): p50 {np.percentile(lat, 50):.2f} ms, "
          f"p99 {np.percentile(lat, 99):.2f} ms over {len(lat)} steps; CPU time p50 {np.percentile(cpu, 50):.2f} ms, "
          f"p99 {np.percentile(cpu, 99):.2f} ms")
    a, b = steps[len(steps) // 2]
    benchmark(tr.process_step, a, b)


def test_bench_runtime_push_latency_default_bundle(benchmark, bundles):
    """Decision E15: the latency of the push that completes a step (that sample's own work, the step's
    window, classification and displacement, or with E24 only its heading and position when the push before
    computed the step), with the session pushed sample by sample (native_chunks), and the mean cost of every
    other push (where the push-time share of the work now is; with E24 the step computed ahead too)."""
    s = bundles["session"]
    out = {}
    # decision E24: the default computes the likely next step at the end of the push before it; without it
    # (speculative=False) the step is computed in its own push, and incremental=False levels the foot there too
    for inc, label in ((True, "incremental=True"), ("nospec", "incremental=True, speculative=False"),
                       (False, "incremental=False, speculative=False")):
        kw = {"incremental": inc is True} | ({} if inc is True else {"speculative": False})
        y, o, n = push_latencies(bundles["root"] / "bundle", s, repeat=3, **kw)
        out[inc] = (y, o)
        print(f"\npush that yields a step ({label}): p50 {np.percentile(y, 50):.3f} ms, "
              f"p99 {np.percentile(y, 99):.3f} ms over {len(y)} steps ({n} per pass); other pushes: mean "
              f"{np.mean(o) * 1e3:.1f} us, p50 {np.percentile(o, 50) * 1e3:.1f} us, "
              f"p99 {np.percentile(o, 99) * 1e3:.1f} us ({len(o)} pushes)")
    y, o = out[True]
    benchmark.extra_info.update(push_step_p50_ms=float(np.percentile(y, 50)),
                                push_step_p99_ms=float(np.percentile(y, 99)),
                                other_push_mean_us=float(np.mean(o) * 1e3))
    chunks = native_chunks(s)
    benchmark.pedantic(lambda: push_latencies(bundles["root"] / "bundle", s, repeat=1), rounds=1, iterations=1)
    assert len(chunks) > 100


def test_bench_runtime_stage_breakdown(benchmark, bundles):
    """Where a step's time goes: step window, classification (of which ONNX runs), stride kernel."""
    import pdrlearn.runtime.bundle as rb
    from pdrlearn.kernels.stride import apply_stride_rules, stride_motion

    s = bundles["session"]
    tr = _loaded_tracker(bundles["root"] / "bundle", s)
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    onnx = [0.0]
    run = rb.OnnxModel.run

    def timed(self, X):
        t0 = time.perf_counter()
        out = run(self, X)
        onnx[0] += time.perf_counter() - t0
        return out

    stages: dict[str, list[float]] = {"window": [], "classify": [], "onnx": [], "stride": []}
    rb.OnnxModel.run = timed
    g = tr.step_graph
    if g is not None and g._run is not None:  # the step graph's session run (decision E13)
        graph_run = g._run

        def timed_graph(*args):
            t0 = time.perf_counter()
            out = graph_run(*args)
            onnx[0] += time.perf_counter() - t0
            return out

        g._run = timed_graph
    try:
        for _ in range(3):
            for a, b in steps:
                t0 = time.perf_counter()
                W, lev = tr._window(a, b)
                t1 = time.perf_counter()
                onnx[0] = 0.0
                classes, _ = tr._classify_step(W)  # what process_step runs
                t2 = time.perf_counter()
                d, _ = stride_motion(lev, tr.heading_source, t0=a, t1=b)
                apply_stride_rules(d, *([classes[k]] if k in classes else None
                                        for k in ("terrain", "direction", "length")), bounds=tr.bounds)
                t3 = time.perf_counter()
                for k, v in zip(stages, (t1 - t0, t2 - t1, onnx[0], t3 - t2), strict=True):
                    stages[k].append(v * 1e3)
    finally:
        rb.OnnxModel.run = run
    med = {k: float(np.median(v)) for k, v in stages.items()}
    print("\nper step, median ms: " + ", ".join(f"{k} {v:.3f}" for k, v in med.items()))
    benchmark.extra_info.update(median_ms=med)
    a, b = steps[len(steps) // 2]
    benchmark(tr._window, a, b)


@pytest.mark.parametrize("method", ["heuristic/foot", "fusion/fused", "dtw/foot", "svm/foot", "nn/foot",
                                    "svm/fused", "nn/fused"])
def test_bench_runtime_per_step_by_method(benchmark, bundles, method):
    from pdrlearn.runtime import load_bundle

    s = bundles["session"]
    b = load_bundle(bundles["root"] / "bundle_all")
    m, u = method.split("/")
    tasks = [t for t, spec in b.tasks.items() if u in spec["methods"].get(m, {})]
    if not tasks:
        pytest.skip(f"no task has a {method} model")
    tr = _loaded_tracker(b, s, tasks=tasks, methods={t: method for t in tasks})
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    lat = _latencies(tr, steps, repeat=1)
    print(f"\n{method} ({len(tasks)} tasks): p50 {np.percentile(lat, 50):.2f} ms, p99 {np.percentile(lat, 99):.2f} ms")
    a, b = steps[len(steps) // 2]
    benchmark(tr.process_step, a, b)


def test_bench_runtime_import_and_bundle_load(benchmark, bundles):
    script = ("import time; t=time.perf_counter(); import pdrlearn.runtime as r; "  # noqa: UP031
              "from pdrlearn.runtime.tracker import Tracker; tr=Tracker(r.load_bundle(%r)); "
              "import json; print(json.dumps(time.perf_counter()-t))") % str(bundles["root"] / "bundle")

    def once():
        out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
        return json.loads(out.stdout)

    times = [once() for _ in range(5)]
    print(f"\nimport + bundle load (incl. ONNX sessions): median {np.median(times) * 1e3:.0f} ms")
    benchmark.extra_info["median_s"] = float(np.median(times))
    benchmark.pedantic(once, rounds=3, iterations=1)


def test_bench_bundle_size(benchmark, bundles):
    from pdrlearn.export.bundle import bundle_size_bytes

    size = bundle_size_bytes(bundles["root"] / "bundle")
    size_all = bundle_size_bytes(bundles["root"] / "bundle_all")
    print(f"\nbundle size: default {size / 1e3:.0f} kB, all methods {size_all / 1e3:.0f} kB")
    benchmark.extra_info.update(default_bytes=size, all_methods_bytes=size_all)
    benchmark(bundle_size_bytes, bundles["root"] / "bundle")
