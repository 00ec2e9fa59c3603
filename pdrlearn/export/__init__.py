"""Export trained per-user models as portable bundles (ONNX + JSON/NPZ + manifest) for the runtime."""

from pdrlearn.export.bundle import base_manifest, bundle_size_bytes, write_bundle
from pdrlearn.export.onnx_convert import check_parity, sklearn_to_onnx, torch_to_onnx

__all__ = [
    "base_manifest",
    "bundle_size_bytes",
    "write_bundle",
    "check_parity",
    "sklearn_to_onnx",
    "torch_to_onnx",
]
