"""Lean streaming runtime: load a model bundle and classify/track steps as samples arrive.

Imports only numpy (and, lazily, onnxruntime — or OpenCV's dnn module for the network when onnxruntime
is absent). Never torch, scikit-learn, scipy or pandas: ``tests/test_runtime_imports.py`` checks it.
"""

try:
    import numpy as _numpy
except ModuleNotFoundError as _exc:  # decision E277: one line, not a traceback, in an install without numpy
    if _exc.name != "numpy":
        raise
    from pdrlearn.install import numpy_missing

    numpy_missing(_exc)
else:
    del _numpy  # the package's names stay its own

from pdrlearn.runtime.ble import CounterUnwrapper, Reorderer  # noqa: E402
from pdrlearn.runtime.bundle import SCHEMA_VERSION, Bundle, OnnxModel, load_bundle, read_manifest  # noqa: E402
from pdrlearn.runtime.pairing import SensorPair  # noqa: E402
from pdrlearn.runtime.tracker import Step, Tracker  # noqa: E402
from pdrlearn.runtime.waist import LiveStep, WaistBundle, WaistTracker, load_waist_bundle  # noqa: E402

__all__ = ["SCHEMA_VERSION", "Bundle", "OnnxModel", "load_bundle", "read_manifest", "Step", "Tracker", "LiveStep",
           "WaistBundle", "WaistTracker", "load_waist_bundle", "SensorPair",
           "CounterUnwrapper", "Reorderer"]
