"""Decision C146: subjects.csv's measures pooled from the strides of each subject's sessions (several short walkway
trials of one child: each alone has too few strides for a stride-time CV).

The strides are track-all's strides.csv rows (:mod:`pdrlearn.track.pooled`), each session's own: its stride times
run from one of its contacts to the next (L66), so no stride spans the time between two sessions. The stride-time CV
is taken within each session (:func:`pdrlearn.track.clinical.within_groups_cv_pct`, L196's within-bout CV): a
change of pace from one trial to the next is no stride-to-stride variability.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.clinical import CV_MIN_STRIDES, within_groups_cv_pct
from pdrlearn.track.evaluate import stride_lengths
from pdrlearn.track.flags import flag_values

#: decision C146: the columns added to subjects.csv, after its own
POOLED_COLUMNS = ("pooled_n_sessions", "pooled_n_strides", "pooled_median_stride_length_m", "pooled_n_cv_sessions",
                  "pooled_n_cv_strides", "pooled_stride_time_cv_pct", "pooled_stride_time_cv_reason")
#: decision C146: the pooled CV's fewest degrees of freedom (stride times less one per session's own mean): those of
#: L104's CV over CV_MIN_STRIDES strides of one session
POOLED_CV_MIN_DOF = CV_MIN_STRIDES - 1


def session_cv_strides(steps: pd.DataFrame) -> np.ndarray:
    """The stride times (s) a session's own stride-time CV is taken over: its steps.csv ``steady`` rows (L104 /
    L188 / L415, as written by the track) with a finite stride time; none for a lower-back table."""
    if "steady" not in steps or "stride_time_s" not in steps:
        return np.zeros(0)
    t = pd.to_numeric(steps["stride_time_s"], errors="coerce").to_numpy(float)[flag_values(steps["steady"])]
    return t[np.isfinite(t) & (t > 0)]


def pooled_stride_measures(sessions: list[pd.DataFrame]) -> dict:
    """Decision C146: :data:`POOLED_COLUMNS`' values of one subject (and visit) from its sessions' stride tables
    (each a session's steps.csv rows)."""
    lengths = [x for x in (stride_lengths(s) for s in sessions) if x is not None and len(x)]
    times = [t for t in (session_cv_strides(s) for s in sessions) if len(t) >= 2]  # one stride: no deviation
    n_len = int(sum(len(x) for x in lengths))
    n_cv = int(sum(len(t) for t in times))
    dof = n_cv - len(times)
    out = {"pooled_n_sessions": len(lengths), "pooled_n_strides": n_len,
           "pooled_median_stride_length_m": float(np.nanmedian(np.concatenate(lengths))) if n_len else np.nan,
           "pooled_n_cv_sessions": len(times), "pooled_n_cv_strides": n_cv,
           "pooled_stride_time_cv_pct": np.nan, "pooled_stride_time_cv_reason": None}
    if dof >= POOLED_CV_MIN_DOF:
        out["pooled_stride_time_cv_pct"] = within_groups_cv_pct(times)
    elif not n_len:
        out["pooled_stride_time_cv_reason"] = ("no foot strides: a lower-back track has no stride-time CV (its contact "
                                               "timing scatters too much, decision L104)")
    else:
        out["pooled_stride_time_cv_reason"] = (
            f"{n_cv} steady level forward strides in {len(times)} session(s) ({dof} degrees of freedom about each "
            f"session's own mean), {POOLED_CV_MIN_DOF} needed (those of one session's {CV_MIN_STRIDES}-stride CV, "
            "decisions L104, C146): record more or longer trials")
    return out


def add_pooled_columns(subjects: pd.DataFrame, strides: pd.DataFrame) -> pd.DataFrame:
    """Decision C146: ``subjects`` (subjects.csv) with :data:`POOLED_COLUMNS` added, each row's from the strides.csv
    rows (``strides``, track-all's, led by ``path``) of the sessions in its ``paths``."""
    by_path = dict(tuple(strides.groupby("path", sort=False))) if len(strides) and "path" in strides else {}
    rows = []
    for paths in subjects["paths"]:
        mine = [by_path[p] for p in str(paths).split("; ") if p in by_path]
        rows.append(pooled_stride_measures(mine))
    pooled = pd.DataFrame(rows, columns=list(POOLED_COLUMNS), index=subjects.index)
    for c in ("pooled_n_sessions", "pooled_n_strides", "pooled_n_cv_sessions", "pooled_n_cv_strides"):
        pooled[c] = pooled[c].astype("Int64")
    return pd.concat([subjects, pooled], axis=1)
