"""One row per rest-to-rest stride: the foot steps ``pdrlearn steps``, ``pdrlearn score-steps`` and ``pdrlearn
track`` count (decision steps 34; public since decision steps 39)."""

from __future__ import annotations

import pandas as pd

from pdrlearn.io.session import Session


def one_per_stride(table: pd.DataFrame, session: Session, *, force: bool = True) -> tuple[pd.DataFrame, int]:
    """A foot detector's steps ``table`` reduced to the rows ``pdrlearn track`` integrates, one per rest-to-rest
    stride of ``session``'s foot unit (:func:`pdrlearn.displace.foot.one_per_rest_stride`; the rests of
    ``track``'s default M3 stance: the force sensors' when recorded, else the accelerometer/gyroscope one), and
    how many rows were dropped. ``pdrlearn steps`` and ``pdrlearn score-steps`` apply it to foot tables before
    :func:`pdrlearn.steps.score_steps` (decision steps 34); a Python caller who scores a foot detector's raw
    table gets a lower precision when the detector fires more than once per stride. ``force`` False: the rests of
    the foot IMU alone (decision steps 52: what ``pdrlearn steps`` uses for a detector that reads no force)."""
    kept, dropped, _ = one_per_stride_counted(table, session, force=force)
    return kept, dropped


def _foot_rests(session: Session, force: bool = True):
    """The foot unit's data and ``track``'s default M3 stance (the force sensors' when recorded, checked against the
    IMU's, decision L365; else, or with ``force`` False, decision steps 52, the accelerometer/gyroscope one)."""
    from pdrlearn.displace.force_check import checked_stance
    from pdrlearn.orient import unit_data

    # decision C142 (trial T3 finding 6): the rests read |acc| and |gyro| only (signal.conditioning.standstill_mask,
    # force_stance), so the unit's own axes do: counting needs no frame (a yawed foot was refused by `steps`)
    foot = unit_data(session, "foot", purpose="the rests between strides", sensor_axes=True)
    return foot, checked_stance(session, foot, use_force=force)[0]


def one_per_stride_counted(table: pd.DataFrame, session: Session, *,
                           force: bool = True) -> tuple[pd.DataFrame, int, int]:
    """:func:`one_per_stride`, plus how many more rest-to-rest strides the kept rows cover (a detection
    spanning several strides: strides merged, decision steps 38)."""
    from pdrlearn.displace.foot import one_per_rest_stride

    foot, stance = _foot_rests(session, force)
    ev = table["event_s"] if "event_s" in table else table["end_s"]
    rows, n_strides = one_per_rest_stride(foot.t, stance, table["start_s"], table["end_s"], ev, count_strides=True)
    return table.iloc[rows].reset_index(drop=True), int(len(table) - len(rows)), int(n_strides - len(rows))


def swinging_rest_strides(session: Session, *, force: bool = True) -> int:
    """Decision steps 47: the foot's own stride count, without a detector: the rest-to-rest strides of ``track``'s
    stance (:func:`pdrlearn.displace.foot.rest_to_rest` on one window over the whole session, as ``track`` splits a
    detection at the rests, L96) whose foot swings - its largest |gyro| between the two rests reaches B91's
    :data:`~pdrlearn.kernels.units.FOOT_NO_SWING` (a walking foot swings at several hundred deg/s; a shuffle or a
    weight shift between two rests does not)."""
    import numpy as np

    from pdrlearn.displace.foot import rest_to_rest
    from pdrlearn.kernels.units import FOOT_NO_SWING

    foot, stance = _foot_rests(session, force)
    t = np.asarray(foot.t, dtype=float)
    if len(t) < 4:
        return 0
    i0, i1, _ = rest_to_rest(t, stance, np.array([t[0]]), np.array([t[-1]]))
    gyr = np.linalg.norm(np.asarray(foot.gyr, dtype=float), axis=1)
    peak = np.array([np.nanmax(gyr[a:b + 1]) if b > a else 0.0 for a, b in zip(i0, i1, strict=True)])
    return int(np.count_nonzero(peak >= FOOT_NO_SWING))
