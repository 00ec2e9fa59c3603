"""The runtime's import boundary: numpy + onnxruntime only (never torch, scikit-learn, scipy, pandas).

A fresh interpreter imports :mod:`pdrlearn.runtime`, loads a bundle holding every method (heuristic,
heuristic fusion, DTW, SVM, NN; foot, waist, fused), streams a session through :class:`Tracker` with
each of them, and reports which heavy modules got imported.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import numpy as np

from tests.runtime_helpers import synthetic_session, trained_dirs

HEAVY = ("torch", "sklearn", "scipy", "pandas", "skl2onnx", "onnx", "dtaidistance", "cv2", "matplotlib")

SCRIPT = textwrap.dedent("""
    import json, sys
    import numpy as np
    import pdrlearn.runtime
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.tracker import Tracker

    bundle = load_bundle(sys.argv[1])
    z = np.load(sys.argv[2])
    names = sorted({k.rsplit("_", 1)[0] for k in z.files})
    n_steps, n_ic, n_ood, n_gait = {}, 0, 0, 0
    for task, spec in bundle.tasks.items():
        for method, per in spec["methods"].items():
            for unit in per:
                tr = Tracker(bundle, tasks=[task], methods={task: method + "/" + unit}, contacts=True,  # E49-E51
                             check_domain=True,  # decision E105: the out-of-domain scores, numpy only too
                             gait=unit == "foot")  # decision E320: the gait values, numpy only too
                steps = tr.push({n: (z[n + "_t"], z[n + "_v"]) for n in names})
                steps += tr.flush()  # decision E280: the strides held for L611's verdict (numpy only too)
                n_ood += tr.domain_report() is not None
                n_steps[f"{task} {method}/{unit}"] = len(steps)
                n_ic += sum(st.event_s == st.event_s for st in steps)  # the contacts ran (decision E49)
                if unit == "foot":  # decision E320
                    n_gait += tr.gait_summary(tr)["left"]["n_stride_times"]
    heavy = sys.argv[3].split(",")
    loaded = sorted(m for m in heavy if m in sys.modules)
    print(json.dumps({"loaded": loaded, "n_steps": n_steps, "n_ic": n_ic, "n_ood": n_ood, "n_gait": n_gait}))
""")


def test_runtime_imports_only_numpy_and_onnxruntime(tmp_path, tmp_path_factory):
    root = trained_dirs(tmp_path_factory)["root"]
    s = synthetic_session(12, seed=7)
    np.savez(tmp_path / "streams.npz", **{f"{n}_t": st.t for n, st in s.streams.items()},
             **{f"{n}_v": st.values for n, st in s.streams.items()})
    r = subprocess.run([sys.executable, "-c", SCRIPT, str(root / "bundle_all"), str(tmp_path / "streams.npz"),
                        ",".join(HEAVY)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["loaded"] == []
    assert len(out["n_steps"]) >= 27  # every task x method x unit was exercised
    assert all(n >= 10 for n in out["n_steps"].values()), out["n_steps"]
    assert out["n_ic"] >= 27 * 5  # decisions E49-E51: the streamed contacts computed with numpy alone
    assert out["n_ood"] >= 27  # decision E105: every model's strides scored against its training ranges
    assert out["n_gait"] >= 5 * sum(k.endswith("/foot") for k in out["n_steps"])  # decision E320: numpy only
