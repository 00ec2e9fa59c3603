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
