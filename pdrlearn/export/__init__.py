"""Export trained per-user models as portable bundles (ONNX + JSON/NPZ + manifest) for the runtime.

:func:`export_model` (a model directory or ``model=UserModel`` -> bundle folder, as ``pdrlearn export``) is
the entry point; the others are its building blocks.
"""

from pdrlearn.export.bundle import base_manifest, bundle_size_bytes, write_bundle
from pdrlearn.export.from_model import export_model
from pdrlearn.export.onnx_convert import check_parity, sklearn_to_onnx, torch_to_onnx

__all__ = [
    "export_model",
    "base_manifest",
    "bundle_size_bytes",
    "write_bundle",
    "check_parity",
    "sklearn_to_onnx",
    "torch_to_onnx",
]
