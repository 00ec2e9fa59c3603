"""Decision C54 (trial mlres, session 25): `make demo` printed only the accuracy on the labelled step boundaries
(100 %) while what `track --model` and the runtime get is the accuracy on the strides they detect (C49)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

DEMO = Path(__file__).resolve().parents[1] / "experiments" / "demo.py"


def _demo():
    spec = importlib.util.spec_from_file_location("pdrlearn_demo_c54", DEMO)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _task(acc, n, det):
    return {"chosen": {"method": "nn", "unit": "combined"}, "accuracy": acc, "n_steps": n, "detected": det}


def test_the_demo_prints_the_detected_figure_first_and_names_it():
    ev = {"tasks": {"terrain": _task(1.0, 224, {"accuracy": 0.955, "n_steps": 222}),
                    "length": _task(1.0, 224, None)}}  # no foot gyroscope: no detected figure
    rows = _demo().accuracy_rows(ev)
    assert rows[0] == ("terrain accuracy, held-out (nn/combined), on the strides track/run detect (what their "
                       "users get)", "95.5 % of 222 steps")
    assert rows[1] == ("terrain accuracy, held-out (nn/combined), on the labelled step boundaries",
                       "100.0 % of 224 steps")
    assert rows[2:] == [("length accuracy, held-out (nn/combined), on the labelled step boundaries",
                         "100.0 % of 224 steps")]
