"""Decision L489: a foot track with many turns on the spot says that those strides' lengths depend on the point
tracked (``reference_point``, L22 / L72), and how much of its distance they hold.

A stride the foot turns through :data:`pdrlearn.kernels.backward.BACKWARD_MAX_TURN_DEG` or more between its rests
(L203's turn on the spot) moves the sensor and the heel by different chords (L22: heel = sensor + (R_end - R_start)
r); the simulated turn routes of L489 read 2.7-8.3 points of distance error apart between the two points, neither
consistently nearer the truth, but an ordinary walk's turnarounds only 0.14-0.17 points (L504), so the line states the
distance on turning strides, not a point figure. Pure function of the steps table.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L489: the line is given when at least this share of the measured strides turn on the spot (a choice, not
#: fitted to data: one stride in ten is a walk made of turns; a real corridor walk's turnarounds are one stride in
#: 4-8 as well, L504, so the episodes below decide)
TURN_SHARE = 0.10
#: decision L489: and at least this many of them (a short walk's single turnaround is no pattern)
MIN_TURN_STRIDES = 4
#: decision L504: and at least this many turn episodes (runs of consecutive turning strides; one turnaround spans 2-4
#: strides): a corridor walk's one to three turnarounds are not a walk made of turns (a choice, not fitted)
MIN_TURN_EPISODES = 4
#: decision L504: and at most this much measured distance (m) per turn episode: a walk made of turns turns often (L489's
#: route every 2-3 m; a corridor's legs are 10 m or more; a choice from the routes' geometry, not fitted)
MAX_M_PER_TURN = 5.0


def turn_reference_warning(steps: pd.DataFrame, reference_point: str, warnings: list[str]) -> None:
    """Decision L489: append one line to ``warnings`` when the foot table ``steps`` (``turn_angle_rad``,
    ``length_m``, optionally ``gap_s``) has :data:`MIN_TURN_STRIDES` or more strides, and :data:`TURN_SHARE` of its
    measured strides or more, that turn on the spot, in :data:`MIN_TURN_EPISODES` or more episodes (runs of turning
    strides) at most :data:`MAX_M_PER_TURN` m apart on average (L504); ``reference_point`` the point tracked."""
    from pdrlearn.kernels.backward import BACKWARD_MAX_TURN_DEG

    if "turn_angle_rad" not in steps or not len(steps):
        return
    turn = np.degrees(np.abs(pd.to_numeric(steps["turn_angle_rad"], errors="coerce").to_numpy(float)))
    measured = np.isfinite(turn)
    if "gap_s" in steps:
        measured &= ~(pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float) > 0)
    turning = measured & (turn >= BACKWARD_MAX_TURN_DEG)
    n = int(turning.sum())
    episodes = int(np.count_nonzero(np.diff(turning.astype(int), prepend=0) == 1))  # decision L504: runs of turns
    if n < MIN_TURN_STRIDES or n < TURN_SHARE * int(measured.sum()) or episodes < MIN_TURN_EPISODES:
        return
    length = np.abs(pd.to_numeric(steps["length_m"], errors="coerce").to_numpy(float))
    on_turns, total = float(np.nansum(length[turning])), float(np.nansum(length[measured]))
    if total > MAX_M_PER_TURN * episodes:  # decision L504: turns far apart (a corridor's turnarounds)
        return
    share = f" = {100 * on_turns / total:.0f} %" if total > 0 else ""
    other = "heel" if reference_point != "heel" else "sensor"
    warnings.append(f"{episodes} turns on the spot ({n} of {int(measured.sum())} strides turned "
                    f"{BACKWARD_MAX_TURN_DEG:g} deg or more; {on_turns:.1f} m{share} of the distance): those strides' "
                    f"lengths depend on the point tracked ({reference_point} here; --reference-point {other} tracks "
                    "the other: compare the two distances to see how much on this walk; on simulated routes made of "
                    "turns they read 2.7-8.3 points apart) (decisions L489, L504)")
