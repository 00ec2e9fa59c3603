"""A waist-only bundle from a waist calibration (decision E57): ``pdrlearn export CAL.json --out BUNDLE``.

A belt-phone user calibrates (``pdrlearn calibrate``), never trains. The bundle holds what the live waist-pendulum
tracker reads: the calibration's parameters resolved as :class:`pdrlearn.waist.WaistTracker` resolves them (leg
length, K, F, gyro bias, turn mixture, motion gate, the W87 calibration rate), the live options and the waist unit's
axis frame, as plain JSON with sha256 checksums; :class:`pdrlearn.runtime.WaistTracker` runs it with numpy alone.
"""

from __future__ import annotations

from pathlib import Path

from pdrlearn.errors import DataError


def declared_frame(sessions, placement: str = "waist") -> dict | None:
    """Decision E367: the axis frame every session of ``sessions`` declares for ``placement`` (meta.json
    ``"frames"``), as a dict, when they all declare the same one; else None (what ``pdrlearn calibrate`` records)."""
    import json

    declared = {json.dumps(s.frames[placement].to_dict()) for s in sessions if placement in s.frames}
    if len(declared) != 1 or not all(placement in s.frames for s in sessions):
        return None
    return json.loads(declared.pop())


def calibration_frame(params_path: str | Path) -> tuple[str | None, str]:
    """Decision E367: the waist frame the calibration file ``params_path`` was fitted under, as ``--frame`` takes it
    (``x=left,y=up,z=forward``), and where it was found: the file's ``"frames"`` (``pdrlearn calibrate`` records the
    walks' declared frame since E367), else the ``meta.json`` of each walk its ``"fit"`` names (read from the current
    folder, else beside the file; one frame for all of them); ``(None, "")`` when neither says."""
    from pdrlearn.io.frames import AxisFrame
    from pdrlearn.textfile import read_json

    def axes(f) -> str | None:
        try:
            return ",".join(f"{k}={v}" for k, v in AxisFrame.from_dict(f).to_dict().items())
        except (DataError, TypeError, ValueError, AttributeError, KeyError):
            return None

    try:
        d = read_json(params_path)
    except (OSError, ValueError):
        return None, ""
    if not isinstance(d, dict):
        return None, ""
    own = axes(((d.get("frames") or {}) if isinstance(d.get("frames"), dict) else {}).get("waist"))
    if own is not None:
        return own, f"{params_path}'s \"frames\""
    walks = d.get("fit") if isinstance(d.get("fit"), list) and not d.get("paths_redacted") else []
    found = set()
    for walk in walks:
        metas = [Path(b) / str(walk) / "meta.json" for b in (Path.cwd(), Path(params_path).parent)]
        meta = next((m for m in metas if m.is_file()), None)
        if meta is None:
            return None, ""
        try:
            m = read_json(meta)
        except (OSError, ValueError):
            return None, ""
        found.add(axes(((m.get("frames") or {}) if isinstance(m, dict) else {}).get("waist")))
    if len(found) != 1 or None in found:
        return None, ""
    return found.pop(), f"the meta.json of the calibration walk {', '.join(map(str, walks))}"


def waist_manifest(params_path: str | Path, *, frame: str | None = None, user: str | None = None
                   ) -> tuple[dict, dict, list[str]]:
    """``(manifest fields, params dict, warnings)`` of the waist bundle for the calibration file ``params_path``
    (``frame``: the waist unit's axes as ``x=up,y=right,z=forward``; None: the calibration's, decision E367
    (:func:`calibration_frame`), else none recorded)."""
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
    quiet: list[str] = []  # decision E368: E107's line for the offline defaults, kept in the manifest, not warned
    options = live_options(p, warnings, quiet)
    frames = {"waist": None, "waist_matrix": None}
    origin = "--frame"
    if frame is None:  # decision E367: the frame the calibration walks declared, when known
        frame, origin = calibration_frame(params_path)
    if frame is not None:
        f = parse_frame(frame, "--frame")  # as `pdrlearn import --frames`
        frames = {"waist": f.to_dict(), "waist_matrix": np.asarray(f.matrix(), dtype=float).tolist()}
    pd = p.to_dict()
    rate = pd.get("rate_hz")
    m = base_manifest(schema=WAIST_SCHEMA_NAME, schema_version=WAIST_SCHEMA_VERSION, user=user,
                      pipeline="waist-pendulum", sampling={"rate_hz": rate, "tolerance": 0.10},
                      sensors={"required": ["wAccelerometer", "wGyroscope"], "optional": []}, units={"waist": 1.0},
                      frames=frames, params="params/waist.json", options=options, warnings=warnings,
                      not_applied_live=quiet[0] if quiet else None,
                      frame_from=origin if frame is not None else None,  # decision E367
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
