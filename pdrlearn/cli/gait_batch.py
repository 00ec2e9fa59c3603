"""Decisions C110, C115, C116: ``pdrlearn gait-all``'s work. Every visit folder's pair goes through
:func:`pdrlearn.track.bilateral.pair_sessions` as a job of :func:`pdrlearn.cohort.run_cohort` - in this process, or
(``--jobs N``, C115) on the Dask LocalCluster of N single-threaded worker processes that ``track-all --jobs`` uses.
Each paired visit folder's result is recorded in OUT's hidden :data:`pdrlearn.cli.resume.PAIR_RECORDS` folder (its
tables as written, the two sessions' input hashes, the code); ``--resume`` (C116) reuses the records that still
match, from OUT or from an interrupted run's temporary folder, as ``track-all --resume`` (C41) does. The pooled tables
are always built from the records' tables, so a serial, a parallel and a resumed run write the same bytes."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from pdrlearn.decision_refs import decision_ref

#: the numeric libraries of a pair's tracking, loaded before each job's one-thread limit (as track-all's)
PAIR_LIBRARIES = ("scipy.linalg", "scipy.signal")


def _pair_job(args: dict) -> dict:
    """One visit folder (cohort C115): a pair tracked by ``pair_sessions`` and its record written (C116) into the
    batch's temporary folder; a folder without a pair is its ``no_pair`` row (no record). Returns ``{"row",
    "tables"}`` as read back from the record, so that a fresh and a reused pair are the same objects."""
    from pdrlearn.cli.gait import summary_json
    from pdrlearn.cli.resume import write_record
    from pdrlearn.cohort import attach_to_error
    from pdrlearn.io.plasys import json_safe
    from pdrlearn.table_csv import table_text
    from pdrlearn.track.bilateral import pair_sessions
    from pdrlearn.track.gait_tables import GAIT_TABLE_FILES, gait_tables
    from pdrlearn.warning_lines import captured_warnings

    if args["reason"] is not None:
        return {"row": {"path": args["path"], "status": "no_pair", "reason": args["reason"]}, "tables": {},
                "warnings": []}
    # cohort C129 (C15's mechanism): the pair's warnings go into its record, said once by the batch
    with captured_warnings() as warned:
        try:
            res = pair_sessions(Path(args["left"]), Path(args["right"]))
            got = gait_tables(res, {"path": args["path"], **res["ids"]})
        except Exception as exc:  # cohort C15: the warnings raised before the failure stay with its error
            attach_to_error(exc, warnings=list(warned))
            raise
    value = {"row": {"path": args["path"], "status": "ok", "reason": None, **res["ids"], "n_bouts": len(res["bouts"]),
                     "n_steps": len(res["steps"]),
                     "clock_right_minus_left_s": res["clock_alignment"]["right_minus_left_s"],  # decision L537
                     "warnings": " | ".join(res["warnings"])},  # decision L461
             "tables": {name: table_text(got[name]) for name in GAIT_TABLE_FILES},
             "summary": _portable(json_safe(summary_json(res)), args),  # decision W437: as gait's, paths below ROOT
             "warnings": list(dict.fromkeys(warned))}
    return write_record(Path(args["record"]), args["key"], args["input_sha256"], value)


def _portable(summary: dict, args: dict) -> dict:
    """Decision W437 (cohort C116's rule for records): the pair's gait_summary.json object with each session's path
    relative to ROOT (``args["root"]``), so a record reused after the study moved holds no stale folder."""
    for side in ("left", "right"):
        entry = (summary.get("sessions") or {}).get(side)
        if isinstance(entry, dict) and entry.get("session"):
            entry["session"] = Path(entry["session"]).relative_to(args["root"]).as_posix()
    return summary


def _placed(summary: dict, root: Path, affected_side: str | None = None) -> dict:
    """Decision W437: a record's gait_summary.json object with its sessions' paths under this run's ROOT again (the
    file names each foot's session folder as `gait --out`'s does). Decision W457: under the resolved ROOT, so a relative
    ROOT gives the same absolute folders as track-all's summary.json (C13) and `report --clinical` reads the same from
    any working directory. Cohort C245: ``affected_side`` (gait-all --affected-side) is written at placing, not
    recorded, so a resumed run with another side words its summaries by the new one."""
    import copy

    summary = copy.deepcopy(summary)
    summary["affected_side"] = affected_side
    root = Path(root).resolve()
    for side in ("left", "right"):
        entry = (summary.get("sessions") or {}).get(side)
        if isinstance(entry, dict) and entry.get("session"):
            entry["session"] = str(root / entry["session"])
    return summary


def _write_changes(tmp: Path, values: list) -> list[str]:
    """Cohort C242: gait_changes.csv and gait_changes_summary.csv of the paired visit folders' walks into ``tmp``
    (:func:`pdrlearn.track.gait_changes.gait_change_tables`); the names written, none under two visits."""
    from pdrlearn.table_csv import write_table_csv
    from pdrlearn.track.gait_changes import gait_change_tables

    walks = [{**v["row"], "walk": (v.get("summary") or {}).get("walk")} for v in values
             if v is not None and v["row"]["status"] == "ok"]
    changes, summary = gait_change_tables(walks)
    if changes is None:
        return []
    write_table_csv(changes, tmp / "gait_changes.csv")
    write_table_csv(summary, tmp / "gait_changes_summary.csv")
    return ["gait_changes.csv", "gait_changes_summary.csv"]


def _progress_text(value: dict | None, error: str | None, reused: bool) -> str:
    """A visit folder's progress line after ``[i/n] path: `` (C110's wording; C116: ``reused``)."""
    if value is None:
        return f"failed: {error}"
    row = value["row"]
    if row["status"] == "no_pair":
        return row["reason"]
    return f"{'reused' if reused else 'ok'}, {row['n_steps']} steps in {row['n_bouts']} bout(s)"


def gait_all(root: Path, out: Path, force: bool = False, jobs: int = 1, resume: bool = False,
             affected_side: str | None = None) -> int:
    """Decisions C110, C115, C116: ``pdrlearn gait-all``'s work; the exit code (1 when a pair failed, as track-all).
    Cohort C242: with two or more visits of a subject, gait_changes.csv and gait_changes_summary.csv too; C245:
    ``affected_side`` ("left" / "right") names the affected side in each pair's gait_summary.json."""
    import shutil

    import pandas as pd

    from pdrlearn.atomic import adopt_leftovers, atomic_directory
    from pdrlearn.cli.cohort import resumable, said_once
    from pdrlearn.cli.common import existed, out_folder, progress, refused_output, replaced
    from pdrlearn.cli.gait import GAIT_ALL_FILES
    from pdrlearn.cli.resume import (
        PAIR_KEY_CHANGED,
        PAIR_RECORDS,
        code_record,
        pair_key,
        pair_record_name,
        recomputed,
        reusable,
        write_record,
    )
    from pdrlearn.cohort import JobResult, find_sessions, folder_bytes, run_cohort
    from pdrlearn.columns import TABLES
    from pdrlearn.errors import DataError
    from pdrlearn.provenance import input_hashes
    from pdrlearn.table_csv import table_from_text, write_table_csv
    from pdrlearn.track.gait_tables import GAIT_TABLE_FILES, PAIR_COLUMNS, visit_pairs

    # cohort C116: --resume replaces a previous output as --force does (its unchanged pairs reused), as track-all's C41
    out_folder(out, "gait-all", force=force or resume, inputs=(root,))
    pairs = visit_pairs(find_sessions(root), root)
    if all(p["reason"] is not None for p in pairs):  # decision B372: nothing to pair, nothing written
        raise DataError(f"gait-all: {root}: no visit folder holds one left and one right foot session "
                        f"({pairs[0]['path']}: {pairs[0]['reason']}); give each visit folder both feet's sessions "
                        "with meta.json \"foot\" (pdrlearn import --foot), or use `pdrlearn gait LEFT RIGHT`")
    names = [pair_record_name(p["path"]) for p in pairs]
    code = code_record()  # cohort C130: once per batch (it hashes pdrlearn's sources in a dirty checkout)
    keys = [None if p["reason"] else pair_key(*(Path(p[s]).relative_to(root).as_posix() for s in ("left", "right")),
                                              code) for p in pairs]
    hashes = [None if p["reason"] else {"left": input_hashes(p["left"]), "right": input_hashes(p["right"])}
              for p in pairs]
    adopted = adopt_leftovers(out) if resume else []
    sources = [*adopted, *([out] if resume and out.is_dir() else [])]
    reuse, changed = {}, {}
    for i, p in enumerate(pairs):
        if resume and p["reason"] is None:
            _, reuse[i], changed[i] = reusable([Path(src) / PAIR_RECORDS / names[i] for src in sources], keys[i],
                                               hashes[i], key_changed=PAIR_KEY_CHANGED)
    reuse = {i: v for i, v in reuse.items() if v is not None}
    was = existed(out)
    done, kept = [0], [0]  # cohort C116: kept = the pairs with a record (not the failed and no_pair folders)
    with refused_output(out), resumable(kept, command="gait-all", noun="pair", decision="C116"), \
            atomic_directory(out, keep_on_interrupt=True) as tmp, progress("gait-all", len(pairs), eta=True) as advance:

        def progress_line(r: JobResult) -> None:
            i = int(r.name)
            done[0] += 1
            kept[0] += bool(r.ok and r.value["row"]["status"] == "ok")
            line = _progress_text(r.value if r.ok else None, r.error, i in reuse)
            why = recomputed(changed.get(i))
            typer.echo(f"[{done[0]}/{len(pairs)}] {pairs[i]['path']}: {line} ({r.seconds:.1f} s{why})", err=True)
            advance()

        for i, value in reuse.items():  # cohort C116: the record put into the new OUT as it was
            write_record(tmp / PAIR_RECORDS / names[i], keys[i], hashes[i], value)
            progress_line(JobResult(str(i), ok=True, value=value))
        items = [(str(i), {"path": p["path"], "reason": p["reason"], "root": str(root),
                           "left": p["left"] and str(p["left"]),
                           "right": p["right"] and str(p["right"]), "record": str(tmp / PAIR_RECORDS / names[i]),
                           "key": keys[i], "input_sha256": hashes[i]})
                 for i, p in enumerate(pairs) if i not in reuse]
        costs = [sum(folder_bytes(a[s]) for s in ("left", "right") if a[s]) for _, a in items]
        ran = {int(r.name): r for r in run_cohort(_pair_job, items, serial=jobs == 1, n_workers=jobs, costs=costs,
                                                  preload=PAIR_LIBRARIES, on_done=progress_line)}
        values = [reuse[i] if i in reuse else (ran[i].value if ran[i].ok else None) for i in range(len(pairs))]
        rows = [v["row"] if v is not None else {"path": p["path"], "status": "failed", "reason": ran[i].error}
                for i, (p, v) in enumerate(zip(pairs, values, strict=True))]
        write_table_csv(pd.DataFrame(rows, columns=list(PAIR_COLUMNS)).astype({"n_bouts": "Int64",
                                                                              "n_steps": "Int64"}),
                        tmp / "gait_pairs.csv")
        for name in GAIT_TABLE_FILES:
            frames = [table_from_text(v["tables"][name]) for v in values if v is not None and v["tables"]]
            header = pd.DataFrame(columns=[c[0] for c in TABLES[name]])
            write_table_csv(pd.concat(frames, ignore_index=True) if frames else header, tmp / name)
        for p, v in zip(pairs, values, strict=True):  # decision W437: each pair's summary, for `report` (clinical)
            if v is not None and isinstance(v.get("summary"), dict):
                (tmp / p["path"]).mkdir(parents=True, exist_ok=True)
                (tmp / p["path"] / "gait_summary.json").write_text(json.dumps(
                    _placed(v["summary"], root, affected_side), indent=2, allow_nan=False) + "\n")
        changed_files = _write_changes(tmp, values)  # cohort C242: visit against visit
    replaced(out, was)
    # cohort C129: each pair's warnings (fresh, reused or failed), each distinct one said once, as track-all's C12
    said_once([(p["path"], (v or {}).get("warnings") or (ran[i].extra.get("warnings", []) if i in ran else []))
               for i, (p, v) in enumerate(zip(pairs, values, strict=True))], len(pairs), "pairs")
    for folder in adopted:  # cohort C116 (as C41): the interrupted runs' folders, now in OUT
        shutil.rmtree(folder, ignore_errors=True)
    n_ok = sum(r["status"] == "ok" for r in rows)
    typer.echo(f"{n_ok} of {len(pairs)} visit folder(s) paired"
               + (f" ({len(reuse)} reused from an earlier run, --resume)" if resume else "")
               + f"; wrote {out}/" + ", ".join(GAIT_ALL_FILES)
               + f" and each pair's PATH/gait_summary.json ({decision_ref('W437')})"  # decision D49
               + "".join(f", {name}" for name in changed_files)
               + (f" (visit against visit, {decision_ref('C242', topic='cohort')})" if changed_files else ""))
    return 0 if all(r["status"] != "failed" for r in rows) else 1
