"""Decision L600 (session 42, trial T2 finding F7): `gait` calls a walk backward only when most strides are."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.bilateral import BACKWARD_WALK_MIN_FRAC, backward_note


def _foot(n: int, n_back: int) -> pd.DataFrame:
    """A foot track's steps.csv of ``n`` straight strides, the first ``n_back`` travelling backward (L203)."""
    ic = np.arange(n) * 1.4
    raw = np.where(np.arange(n) < n_back, -0.6, 0.6)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - 0.45,
                         "length_m": np.abs(raw), "raw_length_m": raw, "turn_angle_rad": 0.0, "gap_s": 0.0,
                         "unit": "foot"})


def test_one_stray_backward_stride_does_not_make_the_walk_backward_l600():
    """Trial T2's hemiparetic pair: 0 of 15 / 1 of 16 strides backward was called a backward walk."""
    assert backward_note([_foot(15, 0), _foot(16, 1)]) is None


def test_most_strides_backward_is_a_backward_walk_l600():
    """A pair with more than half its strides backward keeps L329's line; exactly half does not."""
    line = backward_note([_foot(10, 6), _foot(10, 5)])
    assert line is not None and "6 of 10 / 5 of 10" in line
    assert BACKWARD_WALK_MIN_FRAC == 0.5
    assert backward_note([_foot(10, 5), _foot(10, 5)]) is None
