"""One row per rest-to-rest stride: the foot steps ``pdrlearn steps``, ``pdrlearn score-steps`` and ``pdrlearn
track`` count (decision steps 34; public since decision steps 39)."""

from __future__ import annotations

import pandas as pd

from pdrlearn.io.session import Session


def one_per_stride(table: pd.DataFrame, session: Session) -> tuple[pd.DataFrame, int]:
    """A foot detector's steps ``table`` reduced to the rows ``pdrlearn track`` integrates, one per rest-to-rest
    stride of ``session``'s foot unit (:func:`pdrlearn.displace.foot.one_per_rest_stride`; the rests of
    ``track``'s default M3 stance: the force sensors' when recorded, else the accelerometer/gyroscope one), and
    how many rows were dropped. ``pdrlearn steps`` and ``pdrlearn score-steps`` apply it to foot tables before
    :func:`pdrlearn.steps.score_steps` (decision steps 34); a Python caller who scores a foot detector's raw
    table gets a lower precision when the detector fires more than once per stride."""
    kept, dropped, _ = one_per_stride_counted(table, session)
    return kept, dropped


def one_per_stride_counted(table: pd.DataFrame, session: Session) -> tuple[pd.DataFrame, int, int]:
    """:func:`one_per_stride`, plus how many more rest-to-rest strides the kept rows cover (a detection
    spanning several strides: strides merged, decision steps 38)."""
    from pdrlearn.displace.foot import force_stance, inertial_stance, one_per_rest_stride
    from pdrlearn.orient import unit_data

    foot = unit_data(session, "foot", purpose="the rests between strides")
    stance = force_stance(session, foot.t, foot.gyr)
    if stance is None:
        stance = inertial_stance(foot.acc, foot.gyr, foot.fs)
    ev = table["event_s"] if "event_s" in table else table["end_s"]
    rows, n_strides = one_per_rest_stride(foot.t, stance, table["start_s"], table["end_s"], ev, count_strides=True)
    return table.iloc[rows].reset_index(drop=True), int(len(table) - len(rows)), int(n_strides - len(rows))
