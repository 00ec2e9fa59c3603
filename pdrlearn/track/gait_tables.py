"""Decision C109: ``pdrlearn gait``'s tables (gait_steps.csv, gait_cycles.csv, gait_bouts.csv) with the pair's
ids in front - both sessions' names, meta.json's subject and visit - and ``foot`` beside ``side`` (strides.csv's
name for it), so the tables of many pairs stack (``gait-all``, C110) and join with track-all's."""

from __future__ import annotations

import pandas as pd

#: decision C109: the id columns leading each gait table
GAIT_ID_COLUMNS = ("session_left", "session_right", "subject", "visit")


def pair_ids(left, right) -> dict:
    """Decision C109: the ids of a left / right pair of :class:`~pdrlearn.io.Session`: each one's name and meta.json's
    subject and visit (:func:`pdrlearn.track.bouts.session_key`); where the two feet's differ, both, ``; ``-joined
    (left first), never one of them silently."""
    from pdrlearn.track.bouts import session_key

    keys = session_key(left), session_key(right)
    ids = {"session_left": keys[0]["session"], "session_right": keys[1]["session"]}
    for name in ("subject", "visit"):
        values = [v for v in dict.fromkeys(k[name] for k in keys) if v is not None]
        ids[name] = "; ".join(values) or None
    return ids


def gait_tables(res: dict, ids: dict | None = None) -> dict[str, pd.DataFrame]:
    """Decision C109: {file name: table} of :func:`pdrlearn.track.bilateral.pair_sessions`'s ``res``, each led by
    ``ids`` (default ``res["ids"]``; track-all style callers put ``path`` first) and, in the steps and cycles,
    ``foot`` (= ``side``, kept for existing readers) after ``side``."""
    ids = res["ids"] if ids is None else ids
    tables = {"gait_steps.csv": res["steps"], "gait_cycles.csv": res["cycles"],
              "gait_bouts.csv": pd.DataFrame(res["bouts"])}
    out = {}
    for name, table in tables.items():
        table = table.copy()
        if "side" in table:
            table.insert(table.columns.get_loc("side") + 1, "foot", table["side"])
        for i, (key, value) in enumerate(ids.items()):
            table.insert(i, key, value)
        out[name] = table
    return out


#: decision C110: gait-all's tables of the pairs, gait's three stacked (each led by ``path``)
GAIT_TABLE_FILES = ("gait_steps.csv", "gait_cycles.csv", "gait_bouts.csv")
#: decision C110: gait-all's gait_pairs.csv, one row per visit folder
PAIR_COLUMNS = ("path", "status", "reason", *GAIT_ID_COLUMNS, "n_bouts", "n_steps", "clock_right_minus_left_s",
                "warnings")  # L461: warnings; L537: the absolute-clock alignment


def visit_pairs(found, root) -> list[dict]:
    """Decision C110: the session folders ``found`` under ``root`` (:func:`pdrlearn.cohort.find_sessions`'s order)
    grouped by the folder holding them (a visit folder) and paired by meta.json's foot
    (:func:`pdrlearn.track.bilateral.session_foot`): per visit folder ``{"path": relative to root, "left",
    "right": the two sessions or None, "reason": None for exactly one left and one right foot session, else why
    there is no pair}``, in order of first appearance."""
    from pathlib import Path

    from pdrlearn.errors import DataError
    from pdrlearn.runtime.replay import read_meta
    from pdrlearn.track.bilateral import session_foot

    root = Path(root)
    groups: dict[Path, list[Path]] = {}
    for p in found:
        groups.setdefault(Path(p).parent, []).append(Path(p))
    out = []
    for parent, sessions in groups.items():
        feet: dict[str | None, list[Path]] = {"left": [], "right": [], None: []}
        problems = []
        for s in sessions:
            try:
                feet[session_foot(read_meta(s))].append(s)
            except DataError as exc:
                problems.append(str(exc))
        rel = parent.relative_to(root).as_posix() if parent != root else "."
        pair = {"path": rel, "left": None, "right": None, "reason": None}
        if len(feet["left"]) == 1 and len(feet["right"]) == 1 and not problems:
            pair.update(left=feet["left"][0], right=feet["right"][0])
        else:
            names = ", ".join(s.name for s in feet[None])
            pair["reason"] = "; ".join(problems) or (
                f"no pair: {len(feet['left'])} left and {len(feet['right'])} right foot session(s)"
                + (f", {len(feet[None])} naming no foot ({names}; import --foot)" if feet[None] else "")
                + ": give each visit folder one left and one right foot session")
        out.append(pair)
    return out
