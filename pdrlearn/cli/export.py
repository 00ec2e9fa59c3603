"""``pdrlearn export`` (model directory -> bundle) and ``pdrlearn run`` (replay through the runtime)."""
# ruff: noqa: B008  (typer declares options as argument defaults)

from __future__ import annotations

import sys
import time
from pathlib import Path

import typer

from pdrlearn.cli.common import json_safe, print_json


def export(
    model_dir: Path = typer.Argument(..., help="Model directory written by 'pdrlearn train'."),
    out: Path = typer.Option(..., "--out", "-o", help="Bundle folder to create."),
    methods: str = typer.Option(None, help="Comma-separated methods to export for every task "
                                "(heuristic,fusion,dtw,svm,nn,ensemble); default: each task's chosen method."),
    length_bounds: str = typer.Option(None, "--length-bounds", help="Stride-length class edges (m) "
                                      "SHORT_NORMAL,NORMAL_LONG; default: model's, else 2x thesis ch.6.3."),
    overwrite: bool = typer.Option(False, "--overwrite", help="Replace an existing bundle."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object."),
) -> None:
    """Export a trained model as a portable bundle (manifest.json + ONNX + JSON/NPZ, no pickle).

    Examples:

        pdrlearn export out/models/u1 --out out/bundle_u1

        pdrlearn export out/models/u1 --out out/bundle_u1_all --methods svm,nn,dtw --json
    """
    from pdrlearn.errors import DataError
    from pdrlearn.export.bundle import bundle_size_bytes
    from pdrlearn.export.from_model import export_model
    from pdrlearn.runtime import load_bundle

    meths = [m.strip() for m in methods.split(",") if m.strip()] if methods else None
    bounds = None
    if length_bounds:
        try:
            bounds = [float(v) for v in length_bounds.split(",")]
        except ValueError:
            raise DataError(f"--length-bounds {length_bounds!r}: give two numbers, e.g. 0.6,0.9") from None
    path = export_model(model_dir, out, methods=meths, length_bounds=bounds, overwrite=overwrite)
    b = load_bundle(path)
    summary = {
        "bundle": str(path), "user": b.manifest["user"], "size_bytes": bundle_size_bytes(path),
        "files": sorted(b.manifest["files"]), "rate_hz": b.rate_hz,
        "boundaries": b.manifest["features"].get("boundaries", "given"),
        "tasks": {t: {"chosen": v["chosen"], "methods": {m: sorted(per) for m, per in v["methods"].items()}}
                  for t, v in b.tasks.items()},
        "skipped": b.manifest.get("export", {}).get("skipped", []),
    }
    if as_json:
        print_json(json_safe(summary))
        return
    typer.echo(f"bundle {path} ({summary['size_bytes'] / 1e3:.1f} kB, {len(summary['files'])} files, "
               f"{summary['boundaries']} step boundaries)")
    for t, v in summary["tasks"].items():
        typer.echo(f"  {t}: {v['chosen']['method']}/{v['chosen']['unit']}  (exported: "
                   + ", ".join(f"{m}/{u}" for m, us in v["methods"].items() for u in us) + ")")
    for s in summary["skipped"]:
        typer.echo(f"  skipped: {s}")


def _frames_of(session, bundle) -> dict:
    import logging

    frames = {p: f.to_dict() for p, f in session.frames.items()}
    for p, f in bundle.manifest["frames"].items():
        if p not in frames:
            logging.getLogger(__name__).warning("session '%s' declares no %s frame; using the bundle's %s",
                                                session.name, p, f)
            frames[p] = f
    return frames


def run(
    bundle_dir: Path = typer.Argument(..., help="Bundle folder written by 'pdrlearn export'."),
    session_dir: Path = typer.Argument(None, help="PLASYS session folder to replay (omit with --protocol)."),
    out: Path = typer.Option(None, "--out", "-o", help="Folder for steps.csv, trajectory.csv, summary.json."),
    protocol: str = typer.Option(None, "--protocol", help="Bluetooth text-protocol capture to read instead "
                                 "of a session ('-' = stdin)."),
    chunk_s: float = typer.Option(1.0, help="Replay chunk length (s)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON summary object."),
) -> None:
    """Replay a recorded session (or a Bluetooth capture) through the streaming runtime.

    Examples:

        pdrlearn run out/bundle/u1 out/sim/D_u1 --out out/run_D --json

        cat capture.txt | pdrlearn run out/bundle --protocol - --out out/live
    """
    import numpy as np

    from pdrlearn.errors import DataError
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.tracker import Tracker

    if protocol is not None and session_dir is not None:
        raise DataError(f"run: give a SESSION_DIR ({session_dir}) or --protocol {protocol}, not both")
    bundle = load_bundle(bundle_dir)  # verified before any output
    steps, lat, protocol_stats = [], [], None
    if protocol is not None:
        from pdrlearn.io import THESIS_FOOT_FRAME, BluetoothParser

        parser = BluetoothParser(rate_hz=bundle.rate_hz)
        tracker = Tracker(bundle, frames={**bundle.manifest["frames"], "foot": THESIS_FOOT_FRAME.to_dict()})
        if protocol == "-":
            stream = sys.stdin
        else:
            p = Path(protocol)
            if not p.is_file():
                raise DataError(f"{p}: protocol capture not found")
            stream = p.open()
        need = [s for s in bundle.manifest["sensors"]["required"] if not s.startswith("f")]
        if need:
            raise DataError(f"bundle {bundle.path} needs {', '.join(need)}, which the foot unit's "
                            "Bluetooth protocol does not carry; export a foot-only model")
        with stream:
            for line in stream:
                t0 = time.perf_counter()
                new = tracker.push(parser.feed(line))
                if new:
                    lat.append((time.perf_counter() - t0) / len(new))
                steps += new
            steps += tracker.push(parser.close())
            steps += tracker.flush()
        source = f"protocol {protocol}"
        protocol_stats = parser.stats.to_dict()
        if parser.stats.corrupted:
            typer.echo(f"warning: {protocol}: {parser.stats.corrupted} corrupted line(s) skipped (e.g. "
                       f"{parser.stats.examples[0]!r}) of {parser.stats.sets} set(s) read", err=True)
    else:
        if session_dir is None:
            raise DataError("run: give a SESSION_DIR or --protocol FILE")
        from pdrlearn.io import read_session

        s = read_session(session_dir)
        bundle.check_streams({n: st.rate_hz for n, st in s.streams.items()}, where=f"session '{s.name}'")
        tracker = Tracker(bundle, frames=_frames_of(s, bundle))
        t_all = np.concatenate([st.t for st in s.streams.values()])
        for a in np.arange(t_all.min(), t_all.max() + chunk_s, chunk_s):
            chunk = {}
            for n, st in s.streams.items():
                i0, i1 = np.searchsorted(st.t, [a, a + chunk_s])
                chunk[n] = (st.t[i0:i1], st.values[i0:i1])
            t0 = time.perf_counter()
            new = tracker.push(chunk)
            if new:
                lat.append((time.perf_counter() - t0) / len(new))
            steps += new
        steps += tracker.flush()
        source = f"session {s.name}"
    summary = _summary(steps, tracker, lat, source)
    if protocol_stats is not None:  # the README's "corrupted measurements are skipped and counted"
        summary["protocol"] = protocol_stats
    if out is not None:
        _write(out, steps, tracker, summary)
    if as_json:
        print_json(json_safe(summary))
    else:
        typer.echo(f"{source}: {summary['n_steps']} steps, {summary['distance_m']:.2f} m, final position "
                   f"{[round(v, 2) for v in summary['final_position']]}" + (f" -> {out}" if out else ""))


def _summary(steps, tracker, lat, source) -> dict:
    import numpy as np

    counts = {t: {} for t in tracker.classifiers}
    for st in steps:
        for t, c in st.classes.items():
            counts[t][c] = counts[t].get(c, 0) + 1
    return {
        "source": source, "n_steps": len(steps), "distance_m": float(sum(abs(s.length_m) for s in steps)),
        "final_position": [float(v) for v in tracker.position],
        "methods": {t: f"{c.method}/{c.unit}" for t, c in tracker.classifiers.items()},
        "classes": counts,
        "latency_ms_per_step": {"p50": float(np.percentile(lat, 50) * 1e3) if lat else None,
                                "p99": float(np.percentile(lat, 99) * 1e3) if lat else None},
    }


def _write(out: Path, steps, tracker, summary) -> None:
    import json

    import pandas as pd

    out.mkdir(parents=True, exist_ok=True)
    pd.DataFrame([s.to_dict() for s in steps]).to_csv(out / "steps.csv", index=False)
    traj = [{"t": steps[0].start_s if steps else 0.0, "x": 0.0, "y": 0.0, "z": 0.0}] if steps else []
    traj += [{"t": s.end_s, "x": s.x, "y": s.y, "z": s.z} for s in steps]
    pd.DataFrame(traj, columns=["t", "x", "y", "z"]).to_csv(out / "trajectory.csv", index=False)
    (out / "summary.json").write_text(json.dumps(json_safe(summary), indent=1))


def register(app: typer.Typer) -> None:
    app.command("export")(export)
    app.command("run")(run)
