"""Lean streaming runtime: load a model bundle and classify/track steps as samples arrive.

Imports only numpy (and, lazily, onnxruntime — or OpenCV's dnn module for the network when onnxruntime
is absent). Never torch, scikit-learn, scipy or pandas: ``tests/test_runtime_imports.py`` checks it.
"""

from pdrlearn.runtime.bundle import SCHEMA_VERSION, Bundle, OnnxModel, load_bundle, read_manifest
from pdrlearn.runtime.pairing import SensorPair
from pdrlearn.runtime.tracker import Step, Tracker
from pdrlearn.runtime.waist import LiveStep, WaistBundle, WaistTracker, load_waist_bundle

__all__ = ["SCHEMA_VERSION", "Bundle", "OnnxModel", "load_bundle", "read_manifest", "Step", "Tracker", "LiveStep",
           "WaistBundle", "WaistTracker", "load_waist_bundle", "SensorPair"]
