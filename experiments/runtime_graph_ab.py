"""Node count and run time of bundles' step graphs (decision E16), for before/after comparisons.

Usage (interleave the bundles to share the machine's load)::

    for i in 1 2 3; do .venv/bin/python experiments/runtime_graph_ab.py OLD_BUNDLE NEW_BUNDLE; done

For each bundle: the nodes of ``models/step.onnx`` in the file and after onnxruntime's load-time
optimisation, and the run time of one window (the compiled session's ``run``, as ``StepGraph`` calls it;
one thread): 20 batches of 200 runs, the median over the batches of each batch's 10th percentile (the
figure least moved by other processes). The window is random (positive force, increasing time grid);
the graph's cost does not depend on the values.
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort


def graph_cost(bundle: str, batches: int = 20, runs: int = 200) -> tuple[int, int, float]:
    path = Path(bundle) / "models" / "step.onnx"
    man = json.loads((Path(bundle) / "manifest.json").read_text())
    n_ch, m = len(man["features"]["channels"]), int(man["features"]["n_samples"])
    W = np.abs(np.random.default_rng(0).normal(size=(1, n_ch, m)))
    W[0, 0] = np.linspace(0.0, 1.1, m)
    with tempfile.TemporaryDirectory() as tmp:
        so = ort.SessionOptions()
        so.intra_op_num_threads = so.inter_op_num_threads = 1  # as pdrlearn.runtime.bundle
        so.optimized_model_filepath = str(Path(tmp) / "opt.onnx")
        so.log_severity_level = 3
        sess = ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])
        n_opt = len(onnx.load(so.optimized_model_filepath).graph.node)
    names = [o.name for o in sess.get_outputs()]
    run = sess._sess.run
    p10 = []
    for _ in range(batches):
        t = []
        for _ in range(runs):
            t0 = time.perf_counter()
            run(names, {"W": W}, None)
            t.append(time.perf_counter() - t0)
        p10.append(np.percentile(t, 10))
    return len(onnx.load(str(path)).graph.node), n_opt, float(np.median(p10)) * 1e6


if __name__ == "__main__":
    for b in sys.argv[1:]:
        n_file, n_opt, us = graph_cost(b)
        print(f"{b}: step graph {n_file} nodes ({n_opt} after load), run {us:.1f} us")
