"""Decision L332: ``pdrlearn evaluate`` says once when the evaluated sessions' gait lies outside the walking range
the pipelines are validated on (decision L95), as ``track`` and ``steps`` do.

Each session's gait is judged on its labelled strides (steps.csv: strides of the instrumented foot) by L95's own
test, :func:`pdrlearn.track.gait.session_range_side` (L148's leg scaling, L123's straight strides, L179's stairs):
the labels are turned into the foot track's stride table (``start_s``, ``end_s``, ``event_s`` = the labelled
initial contact, ``length_m``, ``dz_m``, ``turn_angle_rad``) and summarised by the track's own
:func:`~pdrlearn.track.gait.gait_summary`. Without a length label only the cadence is judged (as ``steps`` does,
decision steps 44).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: the summary keys that hold a speed (None when the labels give no stride length)
_SPEED_KEYS = ("median_speed_mps", "gait_speed_mps", "median_speed_straight_mps", "walking_speed_mps")


def labelled_strides(steps: pd.DataFrame) -> pd.DataFrame:
    """A session's labelled strides (``start_s``, ``end_s`` and, when labelled, ``ic_s``, ``length_m``,
    ``height_m``, ``heading_change_deg``) as a foot track's stride table with its gait columns
    (:func:`pdrlearn.track.gait.add_gait_columns`: stride time from initial contact to initial contact, L66),
    in time order; a missing label is NaN (no speed without a length, no straight stride without a heading).
    Labels of both feet (a ``foot`` column with two values, as a Mobilise-D import's) are timed foot by foot."""
    if "foot" in steps and steps["foot"].nunique(dropna=True) > 1:
        parts = [_one_foot(g) for _, g in steps.groupby(steps["foot"].astype(str), sort=True)]
        return pd.concat(parts, ignore_index=True).sort_values("start_s", kind="stable").reset_index(drop=True)
    return _one_foot(steps)


def _one_foot(steps: pd.DataFrame) -> pd.DataFrame:
    from pdrlearn.track.gait import add_gait_columns

    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)

    def col(name: str) -> np.ndarray:
        return pd.to_numeric(st[name], errors="coerce").to_numpy(float) if name in st else np.full(len(st), np.nan)

    start, end = col("start_s"), col("end_s")
    ic = col("ic_s")
    table = pd.DataFrame({"start_s": start, "end_s": end, "event_s": np.where(np.isfinite(ic), ic, start),
                          "length_m": col("length_m"), "dz_m": col("height_m"), "unit": "foot"})
    return add_gait_columns(table, turn_rad=np.deg2rad(col("heading_change_deg")))


def labelled_gait(session) -> dict:
    """L95's figures of ``session``'s labelled strides (:func:`pdrlearn.track.gait.gait_summary` of
    :func:`labelled_strides`) with the walker's leg length from meta.json (L148); the speeds None when no stride
    has a length label."""
    from pdrlearn.track.gait import gait_summary, leg_length

    table = labelled_strides(session.steps)
    out = gait_summary(table)
    if not np.isfinite(table["length_m"].to_numpy(float)).any():
        out.update({k: None for k in _SPEED_KEYS})
    return {**out, **leg_length(session.meta)}


def out_of_range_sessions(sessions) -> list[dict]:
    """Decision L332: the labelled ``sessions`` whose gait lies outside L95's walking range, one dict each:
    ``session``, ``side`` (``slow`` / ``fast``), ``median_cadence_spm``, the judged ``speed_mps`` and what it is
    (``speed_judged``), and ``figures`` (L95's text of them)."""
    from pdrlearn.track.gait import _judged, range_figures, session_range_side

    out = []
    for s in sessions:
        if s.steps is None or not len(s.steps) or "start_s" not in s.steps:
            continue
        summary = labelled_gait(s)
        side = session_range_side(summary)  # L95 / L148 / L123 / L179: track's own verdict
        if side is None:
            continue
        cad, speed, what = _judged(summary)
        out.append({"session": s.name, "side": side, "median_cadence_spm": cad, "speed_mps": speed,
                    "speed_judged": what if speed is not None else None, "figures": range_figures(summary),
                    "leg_length_m": summary.get("leg_length_m")})
    return out


def range_line(flagged: list[dict], total: int) -> str | None:
    """Decision L332: the one line for :func:`out_of_range_sessions`'s ``flagged`` of ``total`` sessions (the first
    three named with their figures); None when none is flagged."""
    from pdrlearn.cohort import first_names
    from pdrlearn.track.gait import CADENCE_RANGE_SPM, SPEED_RANGE_MPS

    if not flagged:
        return None
    sides = {f["side"] for f in flagged}
    what = ("slower than" if sides == {"slow"} else "faster than" if sides == {"fast"} else "outside")
    named = first_names([f"{f['session']} ({f['figures']}, {f['side']})" for f in flagged])
    leg = " (scaled to each walker's leg, decision L148)" if any(f.get("leg_length_m") for f in flagged) else ""
    return (f"{len(flagged)} of {total} evaluated sessions walk {what} the walking the pipelines are validated on "
            f"({CADENCE_RANGE_SPM[0]:.0f}-{CADENCE_RANGE_SPM[1]:.0f} steps/min and "
            f"{SPEED_RANGE_MPS[0]:g}-{SPEED_RANGE_MPS[1]:g} m/s{leg}, decision L95), by their labelled strides: "
            f"{named}; the terrain / direction / length classes are not validated at that gait, so these sessions' "
            "scores are no measure of walking inside the range (score them apart; decision L332)")
