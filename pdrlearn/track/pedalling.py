"""Decision L611's pedalling check shared by ``track`` (plasys, offline) and ``pdrlearn steps`` with a foot detector
(decision L625): the closed-loop strides of a foot displacement (:func:`pedal_loops`) and, for a detector's table,
the rows that are pedalling (:func:`pedalling_rows`)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.pedal import closed_loop_strides, pedal_line, unrested_strides


def pedal_loops(fd, foot, g_rest: float) -> np.ndarray:
    """Decision L611: (B,) bool over the strides of ``fd`` (a fitted
    :class:`~pdrlearn.displace.foot.FootDisplacement`) that go round a closed loop: their raw heights reverse, or
    they are unrested (:func:`~pdrlearn.kernels.pedal.closed_loop_strides`), on the foot unit ``foot``; ``g_rest``:
    the foot's rest reading (L621)."""
    return closed_loop_strides(fd.disp_[:, 2], fd.start_s_, fd.end_s_,
                               unrested_strides(foot.t, foot.acc, fd.start_s_, fd.end_s_, g_rest),
                               np.hypot(fd.disp_[:, 0], fd.disp_[:, 1]))


#: decision L625: what ``pdrlearn steps`` does with the pedalling rows, for the line
STEPS_REMOVED = "left out of the count (pass --keep-pedalling to count them)"
STEPS_KEPT = "counted, as --keep-pedalling asks (--out's pedalling column marks them)"


def pedalling_rows(session, table: pd.DataFrame, kept: bool = False) -> tuple[np.ndarray, int, str | None]:
    """Decision L625: ``(rows, n_rest, line)``: (R,) bool, the rows of a foot detector's table (``start_s`` /
    ``end_s``, one per pair of rests) whose stride L611 calls pedalling, each integrated by the default track's engine
    (M3's ZUPT Kalman strides) on the foot IMU's own rests (a row spanning several rests is cut there, as track cuts
    it: ``n_rest`` those rest-to-rest strides), and the one line naming the rows (None: none); ``kept``: the line
    says they are counted (``--keep-pedalling``), else left out. L612's seated spans are the track's only (they need
    W418's chair transfers)."""
    from pdrlearn.displace import inertial_stance
    from pdrlearn.displace.foot import FootDisplacement
    from pdrlearn.orient import unit_data
    from pdrlearn.track.foot_rest import foot_rest_gravity
    from pdrlearn.track.plasys import METHODS

    rows = np.zeros(len(table), dtype=bool)
    if len(table) < 3:  # L611 judges a stride on its neighbours
        return rows, 0, None
    foot = unit_data(session, "foot", purpose="the pedalling check (decision L611)")
    fd = FootDisplacement(**{k: METHODS["M3"][k] for k in ("integrator", "zupt_end", "gyro_bias", "attitude")}
                          ).estimate(foot, table.reset_index(drop=True),
                                     stance=inertial_stance(foot.acc, foot.gyr, foot.fs))
    loop = pedal_loops(fd, foot, foot_rest_gravity(session))
    if not loop.any():
        return rows, 0, None
    rows[np.unique(np.asarray(fd.rows_)[loop])] = True
    line = pedal_line(rows, np.zeros(len(rows), dtype=bool), table["start_s"].to_numpy(float),
                      table["end_s"].to_numpy(float), removed=STEPS_KEPT if kept else STEPS_REMOVED)
    return rows, int(loop.sum()), line
