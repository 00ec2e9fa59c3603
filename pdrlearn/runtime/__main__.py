"""``python -m pdrlearn.runtime BUNDLE SESSION``: replay a recorded session through the runtime with numpy (and
onnxruntime) alone, for a runtime-only install (decision E76; ``pdrlearn run`` is the full command).

Standard library argparse, no typer, pandas or matplotlib: reads the session's sensor files
(:func:`pdrlearn.runtime.replay.read_streams`), pushes them in ``--chunk-s`` slices (decision E28, as
``pdrlearn run``) through :class:`~pdrlearn.runtime.Tracker` and prints one line (or ``--json``); ``--out``
writes ``steps.csv`` (the columns of ``pdrlearn run``'s runtime fields), ``trajectory.csv`` and ``replay.json`` (the
``--json`` object). Bad input: one ``error: ...`` line, exit code 2 (as ``pdrlearn``). Decision E276: ``--out`` follows
``pdrlearn run``'s rules with the same standard-library modules (:func:`pdrlearn.outfolder.out_folder`,
:func:`pdrlearn.atomic.atomic_directory`): checked before the replay (a session, another command's output, a
read-only place are refused; a previous lean replay is replaced with ``--force``), written whole or not at all.
"""

from __future__ import annotations

import argparse
import csv
import json
import logging
import sys
from pathlib import Path

from pdrlearn.errors import PdrlearnError

PROG = "python -m pdrlearn.runtime"


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=PROG, description="Replay a PLASYS session folder through a model bundle with "
                                "the lean runtime (numpy + onnxruntime; decision E76). The full install's "
                                "`pdrlearn run` adds path.png, bouts, summary.json, gait values and data repair.")
    p.add_argument("bundle", type=Path, help="bundle folder written by 'pdrlearn export'")
    p.add_argument("session", type=Path, help="PLASYS session folder (<sensor>.csv files, optional meta.json)")
    p.add_argument("--out", "-o", type=Path, help="folder to write steps.csv and trajectory.csv into")
    p.add_argument("--chunk-s", type=float, default=1.0, help="replay chunk length (s), default 1 (decision E28)")
    p.add_argument("--units", help="body units to track: foot, or foot,waist (default: the bundle's; the foot "
                   "alone when the session has no waist unit)")
    p.add_argument("--method", metavar="[TASK=]METHOD[/UNIT],...", help="another exported model than the "
                   "bundle's chosen one (as pdrlearn run --method, decision E52)")
    p.add_argument("--gait", metavar="OTHER_FOOT_SESSION", type=Path, help="not in the lean install: gait's tables "
                   "need pandas and scipy; refused in one line naming `pdrlearn run BUNDLE SESSION --gait "
                   "OTHER_FOOT_SESSION` (decision E311)")
    p.add_argument("--altitude", default="foot", metavar="foot|fused", help="the altitude: the strides' own height "
                   "(foot, the default) or fused with the session's waist barometer as it streams (fused: as pdrlearn "
                   "run --altitude fused, L154's filter; decisions E339, E357)")
    p.add_argument("--json", action="store_true", help="print one JSON summary object")
    p.add_argument("--force", action="store_true", help="replace the --out folder of an earlier replay by this "
                   "command (nothing else: a session or another command's output is refused; decision E276)")
    return p


def replay(bundle_dir: Path, session_dir: Path, *, chunk_s: float = 1.0, units: str | None = None,
           method: str | None = None, fallback_line: bool = True, domain_line: bool = True,
           block_rows: int | None = None, clip_lines: bool = True, contacts: bool = False, gait: bool = False,
           altitude: str = "foot"):
    """The tracker after replaying ``session_dir`` through ``bundle_dir`` and its steps, as ``pdrlearn run`` pushes
    a session (same input rates, stream ends, frames when the session declares them; decision E76).
    ``fallback_line=False``: no E26 line about the foot unit only (``evaluate`` says it its own way, E196);
    ``domain_line=False``: the strides are still checked against the training ranges (``tracker.domain_report()``)
    but the C61 line is not said (``evaluate`` pools the sessions and warns only when asked, E198).
    ``clip_lines=False``: no live clipping / stuck-axis lines (decision E303: ``evaluate`` read the session, which
    said them).
    ``block_rows``: the sensor files are read this many data rows at a time (default ``chunked.BLOCK_ROWS``;
    decision E274: bounded memory, the same pushes as the whole files'; a file the block reader finds unusual is
    read whole, as before).
    ``contacts``, ``gait``: the :class:`~pdrlearn.runtime.tracker.Tracker`'s (decisions E49, E320: with both, the
    tracker's :meth:`~pdrlearn.runtime.tracker.Tracker.gait_strides` / ``gait_summary`` after the replay).
    ``altitude``: ``"foot"`` or ``"fused"`` (decision E357: ``pdrlearn run --altitude``'s check and units rule,
    :func:`~pdrlearn.runtime.baro_fusion.replay_altitude`; the Tracker's E339 fusion)."""
    from pdrlearn.errors import DataError
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.runtime import chunked as _chunked
    from pdrlearn.runtime.baro_fusion import check_altitude, replay_altitude
    from pdrlearn.runtime.replay import read_streams, replay_chunks, session_frames
    from pdrlearn.runtime.tracker import tracked_units

    check_altitude(altitude, PROG)  # decision E357: run's check, before the session is read

    if not (chunk_s > 0 and chunk_s < float("inf")):
        raise DataError(f"--chunk-s {chunk_s}: give the replay chunk length in seconds (> 0, e.g. 1)")
    bundle = load_bundle(bundle_dir)
    methods = bundle.choose_methods(method) if method is not None else None
    rows = _chunked.BLOCK_ROWS if block_rows is None else block_rows
    chunked, meta = _chunked.open_session(session_dir, bundle, rows=rows)  # decision E274: bounded memory
    if chunked is not None:
        periods, ends, pushes = chunked.periods, chunked.ends, chunked.chunks(chunk_s)
    else:  # a file the whole-file reader judges: its line, or the replay as before E274
        streams, meta = read_streams(session_dir, bundle)
        periods = {n: _period(t) for n, (t, _) in streams.items()}
        ends = {n: float(t[-1]) for n, (t, _) in streams.items() if len(t)}
        pushes = replay_chunks(streams, chunk_s)
    asked = None if units is None else [u for u in units.split(",") if u.strip()]
    if altitude != "foot":  # decision E357: run's rule on the units the tracker will follow
        altitude = replay_altitude(altitude, tracked_units(bundle, asked, list(ends)), units, PROG, str(session_dir))
    tracker = Tracker(bundle, frames=session_frames(meta, bundle, asked or bundle.body_units, f"session {session_dir}"),
                      units=asked, sensors=list(ends), methods=methods,
                      input_rates_hz={n: 1.0 / p if p > 0 else float("nan") for n, p in periods.items()},
                      stream_ends_s=ends, check_domain=True,  # decision E105: C61's out-of-domain line, as pdrlearn run
                      full_scale=(meta or {}).get("full_scale"),  # decision B456: the session's declared ranges
                      contacts=contacts, gait=gait, altitude=altitude)  # decisions E49, E320, E357
    if not domain_line:  # decision E198: checked, never said
        tracker.quiet_domain()
    if not clip_lines:  # decision E303: said when the caller read the session
        tracker.quiet_clipping()
    if fallback_line and asked is None and tracker.units != bundle.body_units:  # decision E26, as run says it
        logging.getLogger("pdrlearn.runtime").warning(
            "session %s has no waist unit the bundle also uses: the foot unit only (--units foot chooses this "
            "without the warning)", session_dir)
    steps = []
    try:
        for chunk in pushes:
            steps += tracker.push(chunk)
        steps += tracker.flush()
    except DataError as exc:  # the Tracker names the stream; the line names the session's file too
        raise DataError(f"{Path(session_dir)}: {exc}") from None
    return tracker, steps


def _period(t) -> float:
    """The period behind the rate ``pdrlearn run`` gives the Tracker (``Stream.rate_hz``: D7, B33; NaN without)."""
    from pdrlearn.kernels.clock import nominal_period_s

    return nominal_period_s(t)


def _rows(steps) -> list[dict]:
    """The Step rows (``Step.to_dict``, B142) with ``heading_rad`` wrapped to [-pi, pi), as ``pdrlearn run`` writes
    it (E43)."""
    from pdrlearn.kernels.fixes import wrap_angle

    return [{**d, "heading_rad": float(wrap_angle(d["heading_rad"]))} for d in (st.to_dict() for st in steps)]


def _write(out: Path, steps, start_s: float | None) -> None:
    """steps.csv and trajectory.csv into the folder ``out`` (the temporary folder of the atomic write, E276)."""
    from pdrlearn.runtime.replay import STEP_COLUMNS, travel_table

    rows = travel_table(_rows(steps))  # a foot replay: decisions L224, E317's columns, as pdrlearn run's
    have = list(dict.fromkeys(k for r in rows for k in r))
    cols = [c for c in STEP_COLUMNS if c in have] + [c for c in have if c not in STEP_COLUMNS]
    cols = cols or ["start_s", "end_s", "length_m", "heading_rad"]
    with (out / "steps.csv").open("w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows({k: (_num(v) if isinstance(v, float) else v) for k, v in r.items()} for r in rows)
    with (out / "trajectory.csv").open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["t", "x", "y", "z"])
        if steps:
            w.writerow([_num(start_s), 0, 0, 0])
        w.writerows([_num(v) for v in (st.end_s, st.x, st.y, st.z)] for st in steps)


def _num(v: float) -> str:
    """A float as the CSV files hold it: 10 significant digits, but an epoch time in seconds (|v| >= 1e6) with its
    microseconds (decision E164): the package's ``wide_float_text`` (C103), as ``write_table_csv`` writes it."""
    from pdrlearn.table_csv import wide_float_text

    return wide_float_text(v) if v == v else "nan"  # decisions E164, C103: the package's own, no exponent


def _summary(args, tracker, steps, warnings=None) -> dict:
    """The ``--json`` object, also ``replay.json`` in ``--out`` (decision E276); ``distance_m`` walked as
    ``pdrlearn run``'s (decision E316), ``warnings`` the lines said (E317; default the tracker's)."""
    from pdrlearn.kernels.travel import walked_distance

    return {"session": str(args.session), "n_steps": len(steps),
            "distance_m": walked_distance([st.length_m for st in steps]),  # decision E316: not netted
            "final_position": dict(zip("xyz", (float(v) for v in tracker.position), strict=True)),
            "methods": {t: f"{c.method}/{c.unit}" for t, c in tracker.classifiers.items()},
            "warnings": list(tracker.warnings) if warnings is None else list(warnings),
            "out": None if args.out is None else str(args.out),
            # decision E357: as run's summary (E339), the altitude's source when the barometer was fused
            **({} if tracker.foot_altitude_change_m is None else {
                "altitude_source": "fused", "foot_altitude_change_m": tracker.foot_altitude_change_m})}


def _replay_and_write(args) -> dict:
    """Decision E276: check ``--out`` as ``pdrlearn run`` does (before the replay), replay, and write the folder
    whole under a temporary name renamed into place."""
    from pdrlearn.atomic import atomic_directory
    from pdrlearn.outfolder import out_folder

    if args.gait is not None:  # decision E311: gait's functions are the full install's (pandas, scipy)
        from pdrlearn.decision_refs import decision_ref
        from pdrlearn.errors import DataError

        raise DataError(f"--gait {args.gait}: gait's tables of two feet need the full install (pandas, scipy); "
                        f"replay both feet with `pdrlearn run {args.bundle} {args.session} --gait {args.gait}` "
                        f"({decision_ref('E311')})")
    if args.out is not None:
        out_folder(args.out, "lean", force=args.force, inputs=(args.bundle, args.session))
    from pdrlearn.runtime.replay import travel_table, travel_warnings
    from pdrlearn.warning_lines import captured_warnings, merged_warnings

    with captured_warnings(echo=True) as logged:  # decision E317: the lines said, in replay.json as run's (E154)
        tracker, steps = replay(args.bundle, args.session, chunk_s=args.chunk_s, units=args.units, method=args.method,
                                altitude=args.altitude)  # decision E357
        travel_warnings(travel_table(_rows(steps)), tracker.bundle, str(args.session))  # run's C137 / L578 / L652
    summary = _summary(args, tracker, steps, merged_warnings(tracker.warnings, logged, str(args.session)))
    if args.out is not None:
        with atomic_directory(args.out) as tmp:
            _write(tmp, steps, steps[0].start_s if steps else None)
            (tmp / "replay.json").write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")
    return summary


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    from pdrlearn.atomic import checked_outputs
    from pdrlearn.errors import OUT_OF_MEMORY_EXIT, os_error_line, out_of_memory, out_of_memory_line

    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("warning: %(message)s"))
    handler.setLevel(logging.WARNING)
    logging.getLogger("pdrlearn").addHandler(handler)
    try:
        with checked_outputs():  # decision B20: the replacement deletes only what out_folder checked
            summary = _replay_and_write(args)
    except PdrlearnError as exc:
        print(f"error: {' '.join(str(exc).split())}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:  # decision E279: Ctrl-C as pdrlearn's (B96): one line, 130; --out is atomic (E276)
        print("error: interrupted (Ctrl-C); nothing written", file=sys.stderr)
        return 130
    except (OSError, MemoryError) as exc:  # decision E276: an output the system refuses (disk full ...): one line
        if out_of_memory(exc):  # decision B440, as pdrlearn's
            print(f"error: {out_of_memory_line(PROG, blocks=True)}", file=sys.stderr)
            return OUT_OF_MEMORY_EXIT
        line = os_error_line(exc, args.out)
        if line is None:
            raise
        print(f"error: {line}", file=sys.stderr)
        return 2
    finally:
        logging.getLogger("pdrlearn").removeHandler(handler)
    if args.json:
        print(json.dumps(summary))
    else:
        position = list(summary["final_position"].values())
        print(f"session {args.session}: {summary['n_steps']} strides, {summary['distance_m']:.2f} m, final position "
              f"{[round(v, 2) for v in position]}" + (f" -> {args.out}" if args.out else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
