"""Decision C277 (session 53, FJ, trial s53t1 finding F7): a chair transfer's seated side is dated where the trunk
starts / stops moving (``transfers.seated_side_bounds``), not where W182's 10 deg/s rate is passed - a slow rise
started 0.4 s late and a slow sit ended 0.6 s early, so the TUG read about 1 s short."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.transfer import Transfer, transfer_motion
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary
from pdrlearn.waist.transfers import (
    SIT_TO_STAND,
    STAND_TO_SIT,
    TRANSFER_COLUMNS,
    W450_CANDIDATE,
    movement_bounds,
    seated_side_bounds,
)

FS = 100.0


@pytest.fixture(scope="module")
def slow_chair():
    """The simulator's own trunk pitch of a 5 s sit-down, 10 s seated and a 5 s stand-up (seated 20 deg forward)."""
    t = np.arange(0.0, 30.0, 1.0 / FS)
    tr = Transfer(after=0, delay_s=0.0, down_s=5.0, seat_s=10.0, up_s=5.0, flexion_rad=math.radians(35.0),
                  drop_m=0.45, back_m=0.15, recline_rad=-math.radians(20.0))
    t0 = 5.0  # sits from 5 s, seated at 10 s, rises from 20 s, standing at 25 s
    tilt = np.degrees(transfer_motion(t, [tr], np.array([t0]))[2])
    rows = []
    for kind, lo, hi in ((STAND_TO_SIT, 5.0, 10.0), (SIT_TO_STAND, 20.0, 25.0)):
        m = (t >= lo) & (t <= hi)
        peak = int(np.flatnonzero(m)[np.argmax(tilt[m])])
        a, b = movement_bounds(t, tilt, peak, FS, top_s=W450_CANDIDATE["top_s"])  # L648's slow bounds
        rows.append({"transfer": len(rows) + 1, "kind": kind, "start_s": t[a], "end_s": t[b],
                     "duration_s": t[b] - t[a], "peak_s": t[peak], "peak_tilt_deg": tilt[peak],
                     "height_change_m": 0.45 if kind == SIT_TO_STAND else -0.45, "flag": ""})
    return t, tilt, pd.DataFrame(rows, columns=list(TRANSFER_COLUMNS))


def test_slow_transfer_seated_side_dated_at_the_movement(slow_chair):
    t, tilt, rows = slow_chair
    sit, rise = rows.iloc[0], rows.iloc[1]
    assert sit["end_s"] < 10.0 - 0.3 and rise["start_s"] > 20.0 + 0.3  # W182 alone: the finding
    out = seated_side_bounds(t, tilt, rows, FS)
    assert abs(out["end_s"].iloc[0] - 10.0) <= 0.15 and abs(out["start_s"].iloc[1] - 20.0) <= 0.15
    # the standing side, kind, peak and height stay; the duration follows
    assert out["start_s"].iloc[0] == sit["start_s"] and out["end_s"].iloc[1] == rise["end_s"]
    assert (out["kind"] == rows["kind"]).all() and (out["peak_s"] == rows["peak_s"]).all()
    assert np.allclose(out["duration_s"], out["end_s"] - out["start_s"])


def test_seated_side_moves_at_most_max_s_and_never_past_the_row_before(slow_chair):
    t, tilt, rows = slow_chair
    capped = seated_side_bounds(t, tilt, rows, FS, max_s=0.1)
    assert rows["end_s"].iloc[0] < capped["end_s"].iloc[0] <= rows["end_s"].iloc[0] + 0.1 + 1e-9
    assert rows["start_s"].iloc[1] - 0.1 - 1e-9 <= capped["start_s"].iloc[1] < rows["start_s"].iloc[1]
    near = rows.copy()
    near.loc[0, "end_s"] = rows["start_s"].iloc[1] - 0.05  # a sit ending just before the rise
    out = seated_side_bounds(t, tilt, near, FS)
    assert out["start_s"].iloc[1] >= out["end_s"].iloc[0]
    assert seated_side_bounds(t, tilt, rows.iloc[:0], FS).empty


def test_slow_tug_is_timed_from_the_rise_to_seated():
    """User 20840 (after C277's measured 20800-20839): a slow-transfer TUG, lower back tracked."""
    s = simulate_path(parse_route("straight:3, turn:180, straight:3, turn:180"), UserProfile.from_seed(20840),
                      seed=20840, rate_hz=100.0, sit_start_s=5.0, sit_end_s=5.0, stand_s=0.5, transfer_s=(4.0, 6.0))
    tr = s.extras["transfers"]
    true_s = float(tr["seated_s"].iloc[-1] - tr["rise_s"].iloc[0])
    got = track_summary(get_pipeline("waist-pendulum")(s), s, pipeline="waist-pendulum")["tug_time_s"]
    assert got is not None and abs(got - true_s) <= 0.4  # W182's bounds alone: about 1 s short
