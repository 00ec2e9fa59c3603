"""Decision B91: foot and waist files swapped, or one recording given as both units, told from the signals.

A foot unit swings forward at several hundred deg/s every stride; a waist unit turns with the pelvis and the
walking direction, a few tens of deg/s. The statistic is the 99th percentile of the gyroscope magnitude
(:func:`swing_rate`), the largest over the unit's consecutive 10 s blocks (decision B256: a whole night reads
still). The units are swapped when the foot unit's stays below
:data:`FOOT_NO_SWING` and the waist unit's exceeds :data:`WAIST_SWINGS`: a foot that never swings beside a
waist that does. A standing-only recording has both low and is never called swapped.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.io.sensors import UNIT_IMU
from pdrlearn.kernels.frozen_foot import block_swing_rate
from pdrlearn.kernels.units import (  # noqa: F401 - B91's rule, shared with the runtime (B119)
    FOOT_NO_SWING,
    SAME_RTOL,
    SWING_PERCENTILE,
    WAIST_SWINGS,
    swapped_units,
    swing_rate,
)


def _same(a, b) -> bool:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape or a.ndim != 2 or len(a) == 0:
        return False
    return bool(np.allclose(np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1), rtol=SAME_RTOL, atol=1e-9))


def _files(session, unit: str) -> str:
    """The CSV the unit was imported from (meta.json's import record), else its session files."""
    recs = session.meta.get("imported")
    recs = recs if isinstance(recs, list) else [recs] if isinstance(recs, dict) else []
    for r in recs:
        if isinstance(r, dict) and r.get("unit") == unit and r.get("file"):
            return str(r["file"])
    return " and ".join(f"{n}.csv" for n in UNIT_IMU[unit])


def unit_mixup(session) -> str | None:
    """Decision B91: why the session's foot and waist IMU files cannot be what they say (one line without the
    session's name), or None. Needs both units' accelerometer + gyroscope; otherwise None."""
    (fa, fg), (wa, wg) = UNIT_IMU["foot"], UNIT_IMU["waist"]
    if not session.has(fa, fg, wa, wg):
        return None
    s = session.streams
    foot, waist = _files(session, "foot"), _files(session, "waist")
    imported = isinstance(session.meta.get("imported"), (list, dict))
    if _same(s[fg].values, s[wg].values) and _same(s[fa].values, s[wa].values):
        fix = ("import the waist unit's own file with --unit waist --merge" if imported
               else "write the waist unit's own recording to wAccelerometer.csv and wGyroscope.csv")
        return (f"the foot unit ({foot}) and the waist unit ({waist}) hold the same data (one recording given as "
                f"both units; decision B91): {fix}, or remove the waist files to track the foot alone")
    # decision B256: each unit's largest swing of any 10 s block (B251's blocks): a night's whole-session 99th
    # percentile reads a foot that walked 1 % of the time as a waist that never swung, hiding the swap
    f99, w99 = block_swing_rate(s[fg].t, s[fg].values), block_swing_rate(s[wg].t, s[wg].values)
    if swapped_units(f99, w99):
        fix = (f"import {waist} as the foot unit (--unit foot) and {foot} with --unit waist --merge, into a new "
               "--out" if imported else "swap the f* and w* files (fAccelerometer.csv <-> wAccelerometer.csv, "
               "fGyroscope.csv <-> wGyroscope.csv) and their \"frames\" entries in meta.json")
        deg = np.degrees
        return (f"the foot and waist files look swapped: the foot unit ({foot}) turns at {deg(f99):.0f} deg/s "
                f"(99th percentile of |gyro|, largest 10 s block) while the waist unit ({waist}) swings at "
                f"{deg(w99):.0f} deg/s, as a foot does (decision B91); {fix}")
    return None


def no_swing_hint(t, gyr) -> str | None:
    """Decision B287: a hint (one clause) when a unit taken for the foot never swings as a foot does -- B91's swing
    statistic (largest 10 s block, B256) under :data:`FOOT_NO_SWING` -- so it looks like a lower-back unit; None
    when it swings or has no gyroscope samples."""
    gyr = np.asarray(gyr, dtype=float)
    if gyr.ndim != 2 or len(gyr) < 4:
        return None
    rate = block_swing_rate(np.asarray(t, dtype=float), gyr)
    if not np.isfinite(rate) or rate >= FOOT_NO_SWING:
        return None
    return (f"its gyroscope never swings as a foot's does ({np.degrees(rate):.0f} deg/s, 99th percentile of |gyro|, "
            f"largest 10 s block; a foot swings over {np.degrees(FOOT_NO_SWING):.0f}: B91), so it looks like a "
            "lower-back unit: import it with --unit waist")


def assumed_unit_note(session) -> str:
    """Decision B287: the line ``pdrlearn import`` prints when no ``--unit`` was given: the unit it assumed (the
    foot) and, when that unit's gyroscope never swings (:func:`no_swing_hint`), that it looks like a lower back."""
    acc_n, gyr_n = UNIT_IMU["foot"]
    line = f"no --unit given: imported as the foot unit ({acc_n}.csv, {gyr_n}.csv)"
    hint = (no_swing_hint(session.streams[gyr_n].t, session.streams[gyr_n].values)
            if session.has(acc_n, gyr_n) else None)
    return f"{line}; {hint} (B287)" if hint else f"{line}; pass --unit waist for a lower-back unit (B287)"
