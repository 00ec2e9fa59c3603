"""Writing a model bundle atomically: ``manifest.json`` + ONNX + JSON/NPZ files, never pickle.

Layout (see docs/deploying.md)::

    BUNDLE_DIR/
      manifest.json            schema, versions, user, tasks/classes/methods, sensors, rate, frames,
                               displacement parameters, training summary, metrics, sha256 of every file
      models/<task>_<method>_<unit>.onnx
      params/<task>_<method>_<unit>.json | .npz   heuristic rules, DTW references

The folder is first written to a temporary sibling, checked, then renamed into place, so a reader never
sees a half-written bundle (decision E1).
"""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import onnx

from pdrlearn.atomic import atomic_directory
from pdrlearn.buildinfo import created_utc, git_stamp
from pdrlearn.classify.model_dir import _json_default  # numpy scalars/arrays, paths -> JSON
from pdrlearn.errors import ModelError
from pdrlearn.runtime.bundle import (
    MANIFEST,
    MANIFEST_SHA,
    REQUIRED_KEYS,
    SCHEMA_NAME,
    SCHEMA_VERSION,
    load_bundle,
    sha256_file,
)
from pdrlearn.textfile import read_json

log = logging.getLogger(__name__)


def base_manifest(**fields) -> dict:
    """A manifest skeleton with schema, versions and creation time; ``fields`` fill/override the rest."""
    import pdrlearn

    m = {
        "schema": SCHEMA_NAME,
        "schema_version": SCHEMA_VERSION,
        "package_version": pdrlearn.__version__,
        "created_utc": created_utc(),  # decision E159: SOURCE_DATE_EPOCH when set
        **git_stamp(),  # decision E158: the commit of the code that wrote the bundle
        "user": None,
        "tasks": {},
        "sampling": {},
        "sensors": {"required": [], "optional": []},
        "units": {},
        "frames": {},
        "displacement": {},
        "training": {},
        "metrics": {},
    }
    m.update(fields)
    return m


def _dump_json(obj, path: Path) -> None:
    path.write_text(json.dumps(obj, indent=1, default=_json_default, allow_nan=False, sort_keys=False))


def _check_rel(rel: str) -> None:
    p = Path(rel)
    if p.is_absolute() or ".." in p.parts or rel in (MANIFEST, MANIFEST_SHA):
        raise ModelError(f"bundle file name '{rel}' must be a relative path inside the bundle")


def write_bundle(
    out_dir: str | Path,
    manifest: dict,
    *,
    onnx_models: dict[str, onnx.ModelProto] | None = None,
    json_files: dict[str, dict] | None = None,
    npz_files: dict[str, dict[str, np.ndarray]] | None = None,
    overwrite: bool = False,
    verify: bool = True,
    required: tuple[str, ...] = REQUIRED_KEYS,
    loader=load_bundle,
) -> Path:
    """Write a bundle folder atomically and return its path.

    Parameters
    ----------
    out_dir : target folder; must not exist (or be empty) unless ``overwrite``.
    manifest : manifest fields (start from :func:`base_manifest`); ``files`` is filled here.
    onnx_models : relative path -> ONNX model (each must pass ``onnx.checker.check_model``).
    json_files : relative path -> JSON-serializable object (no NaN).
    npz_files : relative path -> arrays (numeric dtypes only, so loading never needs pickle).
    overwrite : replace an existing bundle.
    verify : re-open the written bundle with ``loader`` (:func:`pdrlearn.runtime.load_bundle`) before the rename.
    required : the manifest keys the bundle kind needs (a waist bundle's: ``WAIST_REQUIRED_KEYS``, decision E57).

    Raises
    ------
    ModelError : missing manifest keys, an invalid ONNX model, an object array, an existing target.
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ModelError(f"{out}: is a file; --out must be a folder for the bundle")
    if out.exists() and any(out.iterdir()) and not overwrite:
        raise ModelError(f"{out}: folder exists and is not empty; choose another --out or pass --overwrite")
    missing = [k for k in required if k != "files" and k not in manifest]
    if missing:
        raise ModelError(f"bundle manifest lacks {', '.join(missing)}; build it with base_manifest()")
    with atomic_directory(out) as tmp:
        files: dict[str, str] = {}
        for rel, model in (onnx_models or {}).items():
            _check_rel(rel)
            try:
                onnx.checker.check_model(model, full_check=True)
            except Exception as exc:
                raise ModelError(f"bundle file {rel}: ONNX checker failed ({exc})") from None
            (tmp / rel).parent.mkdir(parents=True, exist_ok=True)
            (tmp / rel).write_bytes(model.SerializeToString())
        for rel, obj in (json_files or {}).items():
            _check_rel(rel)
            (tmp / rel).parent.mkdir(parents=True, exist_ok=True)
            try:
                _dump_json(obj, tmp / rel)
            except ValueError as exc:
                raise ModelError(f"bundle file {rel}: not strict JSON ({exc})") from None
        for rel, arrays in (npz_files or {}).items():
            _check_rel(rel)
            arrs = {k: np.asarray(v) for k, v in arrays.items()}
            bad = [k for k, v in arrs.items() if v.dtype.hasobject]
            if bad:
                raise ModelError(f"bundle file {rel}: arrays {bad} have object dtype (would need pickle)")
            (tmp / rel).parent.mkdir(parents=True, exist_ok=True)
            with open(tmp / rel, "wb") as f:
                np.savez(f, **arrs)
        for f in sorted(tmp.rglob("*")):
            if f.is_file():
                files[f.relative_to(tmp).as_posix()] = sha256_file(f)
        full = dict(manifest)
        full["files"] = files
        _dump_json(full, tmp / MANIFEST)
        (tmp / MANIFEST_SHA).write_text(f"{sha256_file(tmp / MANIFEST)}  {MANIFEST}\n")
        if verify:
            loader(tmp, verify=True)
    log.info("wrote bundle %s (%d files)", out, len(files))
    return out


def bundle_size_bytes(path: str | Path) -> int:
    """Total size of a bundle folder in bytes."""
    return sum(f.stat().st_size for f in Path(path).rglob("*") if f.is_file())


def rebuild_step_graph(bundle_dir: str | Path, out_dir: str | Path | None = None) -> Path:
    """Re-build a bundle's step graph (``models/step.onnx``) with this version's graph builder.

    The bundle is verified and read (manifest, every ONNX/JSON/NPZ file), the step graph is built again
    from its own per-model graphs and feature table (:func:`pdrlearn.export.step_graph.build_step_graph`),
    and the bundle is written atomically with new checksums to ``out_dir`` (default: in place). The
    models, classes and numbers stay those of the bundle; a bundle without an ONNX task loses its
    step graph entry. Used to bring shipped bundles to the decision-E13 graph without retraining.
    """

    from pdrlearn.export.step_graph import build_step_graph

    src = Path(bundle_dir)
    b = load_bundle(src, verify=True)
    manifest = {k: v for k, v in b.manifest.items() if k not in ("files", "step_graph")}
    old_graph = (b.manifest.get("step_graph") or {}).get("file")
    onnx_models, json_files, npz_files = {}, {}, {}
    for rel in b.manifest["files"]:
        if rel == old_graph:
            continue
        if rel.endswith(".onnx"):
            onnx_models[rel] = onnx.load(str(src / rel))
        elif rel.endswith(".json"):
            json_files[rel] = read_json(src / rel)
        elif rel.endswith(".npz"):
            npz_files[rel] = b.npz(rel)  # numeric arrays only, one line otherwise (decision B125)
        else:
            raise ModelError(f"bundle {src.name}: file '{rel}' has no known type; re-export the bundle")
    step = build_step_graph(manifest["tasks"], onnx_models, manifest["features"])
    if step is not None:
        rel = old_graph or "models/step.onnx"
        onnx_models[rel] = step[0]
        manifest["step_graph"] = {"file": rel, **step[1]}
    return write_bundle(out_dir or src, manifest, onnx_models=onnx_models, json_files=json_files,
                        npz_files=npz_files, overwrite=True)
