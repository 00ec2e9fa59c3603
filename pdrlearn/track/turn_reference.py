"""Decision L489: a foot track with many turns on the spot says that those strides' lengths depend on the point
tracked (``reference_point``, L22 / L72), and how much of its distance they hold.

A stride the foot turns through :data:`pdrlearn.kernels.backward.BACKWARD_MAX_TURN_DEG` or more between its rests
(L203's turn on the spot) moves the sensor and the heel by different chords (L22: heel = sensor + (R_end - R_start)
r); the simulated turn routes of L489 read 2.7-8.3 points of distance error apart between the two points, neither
consistently nearer the truth. Pure function of the steps table.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L489: the line is given when at least this share of the measured strides turn on the spot (a choice, not
#: fitted to data: one stride in ten is a walk made of turns; a corridor walk's turnarounds are one in 10-20)
TURN_SHARE = 0.10
#: decision L489: and at least this many of them (a short walk's single turnaround is no pattern)
MIN_TURN_STRIDES = 4


def turn_reference_warning(steps: pd.DataFrame, reference_point: str, warnings: list[str]) -> None:
    """Decision L489: append one line to ``warnings`` when the foot table ``steps`` (``turn_angle_rad``,
    ``length_m``, optionally ``gap_s``) has :data:`MIN_TURN_STRIDES` or more strides, and :data:`TURN_SHARE` of its
    measured strides or more, that turn on the spot; ``reference_point`` the point tracked ("sensor" / "heel")."""
    from pdrlearn.kernels.backward import BACKWARD_MAX_TURN_DEG

    if "turn_angle_rad" not in steps or not len(steps):
        return
    turn = np.degrees(np.abs(pd.to_numeric(steps["turn_angle_rad"], errors="coerce").to_numpy(float)))
    measured = np.isfinite(turn)
    if "gap_s" in steps:
        measured &= ~(pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float) > 0)
    turning = measured & (turn >= BACKWARD_MAX_TURN_DEG)
    n = int(turning.sum())
    if n < MIN_TURN_STRIDES or n < TURN_SHARE * int(measured.sum()):
        return
    length = np.abs(pd.to_numeric(steps["length_m"], errors="coerce").to_numpy(float))
    other = "heel" if reference_point != "heel" else "sensor"
    warnings.append(f"{n} of {int(measured.sum())} strides turn on the spot (the foot turned "
                    f"{BACKWARD_MAX_TURN_DEG:g} deg or more; {np.nansum(length[turning]):.1f} m of the distance): "
                    f"their lengths depend on the point tracked ({reference_point} here; --reference-point {other} "
                    "tracks the other), and on simulated turn routes the two read 2.7-8.3 points of distance error "
                    "apart with neither nearer the truth, so the distance over turns is uncertain by that much "
                    "(decision L489)")
