"""Decision L154: where a foot track's altitude comes from - the foot's strides alone (``"foot"``, the default:
L39's level rule or the terrain classes) or the strides fused with the session's waist barometer (``"fused"``,
:func:`pdrlearn.kernels.barometer.fuse_altitude`, an option: L154's adoption rule was not met)."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.barometer import ALTITUDES, FUSED_WITHOUT_BAROMETER

log = logging.getLogger("pdrlearn.track")

#: decision L154: the default altitude source of the foot pipeline (not adopted: the foot's own); the sources are
#: :data:`pdrlearn.kernels.barometer.ALTITUDES` (decision E339: shared with the runtime)
DEFAULT_ALTITUDE = "foot"


def check_altitude(altitude: str | None) -> str:
    """``altitude`` (None = :data:`DEFAULT_ALTITUDE`) checked: an unknown value is one line naming the valid ones."""
    value = DEFAULT_ALTITUDE if altitude is None else altitude
    if value not in ALTITUDES:
        raise DataError(f"plasys: altitude '{altitude}' is not one of {', '.join(ALTITUDES)} (foot: the strides' "
                        "own height; fused: with the waist barometer, decision L154)")
    return value


def set_strides_dz(result, dz: np.ndarray) -> None:
    """The strides' ``dz_m`` replaced by ``dz`` and the trajectory's height re-accumulated from its first row (one
    trajectory row per stride after the start row; a trajectory of another length keeps its z)."""
    result.steps["dz_m"] = dz
    if len(result.trajectory) == len(dz) + 1:
        z0 = float(result.trajectory["z"].iloc[0])
        result.trajectory["z"] = z0 + np.concatenate([[0.0], np.cumsum(dz)])


def apply_altitude(result, session, altitude: str, raw_dz: np.ndarray | None = None, *,
                   stairs_level: bool = False) -> None:
    """Decision L154: with ``altitude="fused"`` and a waist barometer in ``session`` (wBarometer with samples), the
    strides' heights become the fused ones and ``info["altitude_source"]`` says so, with the foot's own altitude
    change in ``info["foot_altitude_change_m"]``; without a barometer one warning says the foot's altitude is
    kept. ``"foot"``: ``info["altitude_source"] = "foot"``. ``raw_dz`` (decision L564; the strides' heights before
    L39's level rule, one per row, or None where no level rule ran, e.g. a terrain model): inside a barometric climb
    (:func:`pdrlearn.kernels.barometer.barometric_climb`) a stride is fused with its own un-levelled height.
    ``stairs_level`` (decision L591's candidate): but not inside a climb that holds a stair stride
    (:func:`pdrlearn.kernels.barometer.without_stair_climbs`, L301's stair grade)."""
    result.info["altitude_source"] = "foot"
    steps = result.steps
    if altitude != "fused" or not len(steps):
        return
    if not (session.has("wBarometer") and len(session["wBarometer"])):
        msg = FUSED_WITHOUT_BAROMETER  # decision E339: run's too
        result.info.setdefault("warnings", []).append(msg)
        log.warning("%s: %s", session.where, msg)
        return
    from pdrlearn.kernels.barometer import barometric_climb, fuse_altitude
    from pdrlearn.track.barometer import FUSED_EFFECT, usable_barometer

    lines: list[str] = []
    b = usable_barometer(session, lines, FUSED_EFFECT)  # decision B188: an impossible pressure is not fused
    if b is None:
        result.info.setdefault("warnings", []).extend(lines)
        for line in lines:
            log.warning("%s: %s", session.where, line)
        return
    foot = np.nan_to_num(steps["dz_m"].to_numpy(float))
    t0, t1 = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    climbing, into = None, foot
    if raw_dz is not None and len(raw_dz) == len(foot):  # decision L564: one height source inside a climb
        climbing = barometric_climb(t0, t1, steps["length_m"].to_numpy(float), b.t, b.values[:, 0])
        if stairs_level:  # decision L591's candidate: a stair climb keeps L39's level heights
            from pdrlearn.kernels.barometer import without_stair_climbs
            from pdrlearn.track.grade import STAIR_MIN_GRADE_PCT

            climbing = without_stair_climbs(climbing, raw_dz, steps["length_m"].to_numpy(float), STAIR_MIN_GRADE_PCT)
        into = np.where(climbing, np.nan_to_num(np.asarray(raw_dz, dtype=float)), foot)
    fused = fuse_altitude(into, t0, t1, b.t, b.values[:, 0], climbing=climbing)
    set_strides_dz(result, fused)
    result.info["altitude_source"] = "fused"
    result.info["foot_altitude_change_m"] = float(foot.sum())
    from pdrlearn.kernels.altitude_check import fused_altitude_line

    warnings = result.info.get("warnings") or []  # decision L292: L69's line quotes the reported altitude
    warnings[:] = [fused_altitude_line(w, float(np.sum(fused))) for w in warnings]
