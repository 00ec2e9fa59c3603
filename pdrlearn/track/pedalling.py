"""Decision L611's pedalling check shared by ``track`` (plasys, offline) and ``pdrlearn steps`` with a foot detector
(decision L625): the closed-loop strides of a foot displacement (:func:`pedal_loops`) and, for a detector's table,
the rows that are pedalling (:func:`pedalling_rows`)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.decision_refs import decision_ref
from pdrlearn.kernels.pedal import TRACK_REMOVED, closed_loop_strides, pedal_line, spans_of, unrested_strides


def pedal_verdict(fd, foot, g_rest: float, *, keep_travelling: bool = False,
                  stride_travel_m: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Decisions L611 / L799: ``(loop, going)``, (B,) bool over the strides of ``fd`` (a fitted
    :class:`~pdrlearn.displace.foot.FootDisplacement`): ``loop`` those that go round a closed loop (their raw heights
    reverse, or they are unrested; :func:`~pdrlearn.kernels.pedal.closed_loop_strides`) on the foot unit ``foot``
    (``g_rest``: its rest reading, L621); ``going`` those of L611's that travel ``stride_travel_m`` (m) or more (a
    running stride's unrested ends, not a crank's stroke, for the line). ``keep_travelling`` (L799's candidate, not
    adopted): ``loop`` leaves out the level ones (:func:`~pdrlearn.kernels.pedal.travelling_strides`: kept), and
    ``going`` is those."""
    dz, start, end = fd.disp_[:, 2], fd.start_s_, fd.end_s_
    unrested = unrested_strides(foot.t, foot.acc, start, end, g_rest)
    travel = np.hypot(fd.disp_[:, 0], fd.disp_[:, 1])
    loop = closed_loop_strides(dz, start, end, unrested, travel)
    if keep_travelling:
        kept = closed_loop_strides(dz, start, end, unrested, travel, stride_travel_m=stride_travel_m)
        return kept, loop & ~kept
    return loop, loop & (travel >= stride_travel_m)  # L799's line: a stride's travel, level or not (a crank's < 0.3 m)


def pedal_loops(fd, foot, g_rest: float) -> np.ndarray:
    """Decision L611: the closed-loop strides of :func:`pedal_verdict`."""
    return pedal_verdict(fd, foot, g_rest)[0]


def travelling_line(going: np.ndarray, fd, *, kept: bool = False, removed: str | None = None,
                    stride_travel_m: float = 1.0) -> str | None:
    """Decision L799: the line naming the travelling strides ``going`` of :func:`pedal_verdict` - removed by L611
    (``kept``: kept, L799's candidate; ``removed``: what was done with them, `pdrlearn steps`' L625 text, None: the
    track's) - as what they look like: a contact too short for the foot to rest (running), not cycling (None: none)."""
    if not np.any(going):
        return None
    travel = np.hypot(fd.disp_[going, 0], fd.disp_[going, 1])
    where = ", ".join(f"{a:.2f}-{b:.2f} s ({k})" for a, b, k in spans_of(going, fd.start_s_, fd.end_s_))
    done = "kept" if kept else f"not walking? {removed or TRACK_REMOVED}"
    undo = "" if kept or removed else "; --no-cycling keeps them"
    return (f"{int(np.sum(going))} stride(s) at {where} {done}: the foot did not rest at their ends, yet each "
            f"travelled {stride_travel_m:g} m or more (median {float(np.median(travel)):.2f} m) - not "
            "cycling (L611's pedal strokes travel under 0.3 m and rise and fall) but strides whose contact was too "
            f"short for the foot to rest, as in running, which the pipelines do not support{undo} "
            f"({decision_ref('L799')})")


#: decision L625: what ``pdrlearn steps`` does with the pedalling rows, for the line
STEPS_REMOVED = "left out of the count (pass --keep-pedalling to count them)"
STEPS_KEPT = "counted, as --keep-pedalling asks (--out's pedalling column marks them)"
#: L625's amendment (session 44, FM): the line when the foot's axis frame is not known (counting needs none, C142)
NO_FRAME = ("pedalling not checked (decision L625): the foot unit's axis frame is neither declared nor fixed by its "
            "data, and a stride's height needs it; every stride is counted (declare meta.json \"frames\" for the "
            "foot to leave a bike ride's strokes out)")


def pedalling_rows(session, table: pd.DataFrame, detections: pd.DataFrame | None = None,
                   kept: bool = False, force: bool = False) -> tuple[np.ndarray, int, str | None]:
    """Decision L625: ``(rows, n_rest, line)``: (R,) bool, the rows of a foot detector's table (``start_s`` /
    ``end_s``, one per pair of rests) that make only strides L611 calls pedalling or L639 a ride, the strides
    integrated by the default track's engine (M3's ZUPT Kalman strides) on the foot IMU's own rests (``force``: a
    detector reading the force sensors, on track's checked force stance, L365, as steps 34 cuts; review R1 F1);
    ``n_rest`` the rest-to-rest strides those rows make; the one line naming the strides (None: none); ``kept``: the
    line says they are counted (``--keep-pedalling``), else left out. Review R1 F1: the strides are judged as
    ``track`` judges them, made from the detector's whole table ``detections`` (before steps 34's one row per
    stride; None: ``table``), and a row is dropped when all of its strides are (L641's
    :func:`~pdrlearn.track.plasys.making_only`). L612's seated spans are the track's only (they need W418's chair
    transfers)."""
    from pdrlearn.displace.foot import FootDisplacement
    from pdrlearn.displace.force_check import checked_stance
    from pdrlearn.orient import unit_data
    from pdrlearn.track.foot_rest import foot_rest_gravity
    from pdrlearn.track.gaps import long_gaps
    from pdrlearn.track.plasys import METHODS, long_ride_strides, making_only

    rows = np.zeros(len(table), dtype=bool)
    detections = table if detections is None else detections
    if len(detections) < 3 or not len(table):  # L611 judges a stride on its neighbours
        return rows, 0, None
    if not session.has_frame("foot"):  # L625's amendment (session 44, FM): the strides' heights need the foot's axes
        return rows, 0, NO_FRAME
    foot = unit_data(session, "foot", purpose="the pedalling check (decision L611)")
    fd_kw = {k: METHODS["M3"][k] for k in ("integrator", "zupt_end", "gyro_bias", "attitude")}
    stance = checked_stance(session, foot, use_force=force)[0]  # steps 52: a force detector's is track's
    fd = FootDisplacement(**fd_kw).estimate(foot, detections.reset_index(drop=True), stance=stance)
    loop, going = pedal_verdict(fd, foot, foot_rest_gravity(session))  # decision L799: going, for the line
    ride, cap = long_ride_strides(fd, foot, long_gaps(session, ("fAccelerometer", "fGyroscope")))  # decision L639
    if not (loop | ride).any():
        return rows, 0, None
    table = table.reset_index(drop=True)
    rows[making_only(fd, fd_kw, foot, table, stance, loop | ride)] = True  # decision L641
    if not rows.any():
        return rows, 0, None
    made = FootDisplacement(**fd_kw).stride_bounds(foot, table, stance=stance)[2]
    removed = STEPS_KEPT if kept else STEPS_REMOVED
    lines = (pedal_line(loop & ~going, np.zeros(len(loop), dtype=bool), fd.start_s_, fd.end_s_, ride=ride, cap_s=cap,
                        removed=removed),
             travelling_line(going & ~ride, fd, removed=removed))  # decision L799: running's, not cycling's
    line = "; ".join(x for x in lines if x) or None
    return rows, int(np.isin(made, np.flatnonzero(rows)).sum()), line
