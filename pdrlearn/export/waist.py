"""A waist-only bundle from a waist calibration (decision E57): ``pdrlearn export CAL.json --out BUNDLE``.

A belt-phone user calibrates (``pdrlearn calibrate``), never trains. The bundle holds what the live waist-pendulum
tracker reads: the calibration's parameters resolved as :class:`pdrlearn.waist.WaistTracker` resolves them (leg
length, K, F, gyro bias, turn mixture, motion gate, the W87 calibration rate), the live options and the waist unit's
axis frame, as plain JSON with sha256 checksums; :class:`pdrlearn.runtime.WaistTracker` runs it with numpy alone.
"""

from __future__ import annotations

from pathlib import Path

from pdrlearn.errors import DataError


def waist_manifest(params_path: str | Path, *, frame: str | None = None, user: str | None = None
                   ) -> tuple[dict, dict, list[str]]:
    """``(manifest fields, params dict, warnings)`` of the waist bundle for the calibration file ``params_path``
    (``frame``: the waist unit's axes as ``x=up,y=right,z=forward``, None: none recorded)."""
    import numpy as np

    from pdrlearn.export.bundle import base_manifest
    from pdrlearn.io.importer import parse_frame
    from pdrlearn.io.session import Session
    from pdrlearn.runtime.bundle import WAIST_SCHEMA_NAME, WAIST_SCHEMA_VERSION
    from pdrlearn.waist.events import WALK_THRESHOLD_MPS2
    from pdrlearn.waist.live import live_options
    from pdrlearn.waist.params import resolve_params

    p, warnings = resolve_params(Session(name="export", meta={}), str(params_path))
    if p.pipeline not in (None, "waist-pendulum"):
        raise DataError(f"{params_path}: calibrated for {p.pipeline}, but a waist bundle runs the live "
                        "waist-pendulum tracker; calibrate for it: pdrlearn calibrate WALK --pipeline waist-pendulum "
                        "--distance M --out CAL.json")
    options = live_options(p, warnings)
    frames = {"waist": None, "waist_matrix": None}
    if frame is not None:
        f = parse_frame(frame, "--frame")  # as `pdrlearn import --frames`
        frames = {"waist": f.to_dict(), "waist_matrix": np.asarray(f.matrix(), dtype=float).tolist()}
    pd = p.to_dict()
    rate = pd.get("rate_hz")
    m = base_manifest(schema=WAIST_SCHEMA_NAME, schema_version=WAIST_SCHEMA_VERSION, user=user,
                      pipeline="waist-pendulum", sampling={"rate_hz": rate, "tolerance": 0.10},
                      sensors={"required": ["wAccelerometer", "wGyroscope"], "optional": []}, units={"waist": 1.0},
                      frames=frames, params="params/waist.json", options=options, warnings=warnings,
                      walk_threshold=WALK_THRESHOLD_MPS2, source=str(params_path))
    for k in ("tasks", "displacement", "training", "metrics"):
        m.pop(k, None)
    return m, pd, warnings


def export_waist(params_path: str | Path, out: str | Path, *, frame: str | None = None, overwrite: bool = False,
                 user: str | None = None) -> Path:
    """Write the waist bundle of ``params_path`` to ``out`` atomically (verified by re-opening it)."""
    from pdrlearn.export.bundle import write_bundle
    from pdrlearn.runtime.bundle import WAIST_REQUIRED_KEYS
    from pdrlearn.runtime.waist import load_waist_bundle

    m, pd, _ = waist_manifest(params_path, frame=frame, user=user)
    return write_bundle(out, m, json_files={"params/waist.json": pd}, overwrite=overwrite,
                        required=WAIST_REQUIRED_KEYS, loader=load_waist_bundle)
