"""Decision L228: the strides of L219's side-stepping runs are no steady strides of the foot track's stride-time /
stride-length CVs (L104) and no straight strides of its ``median_speed_straight_mps``."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.clinical import clinical_summary
from pdrlearn.track.gait import gait_summary


def _foot_table(side: bool) -> pd.DataFrame:
    """24 strides of 1.0 s / 1.4 m; strides 8-14 are side steps (1.3 s, 0.42 m) marked ``sideways`` or not."""
    n = 24
    t = np.full(n, 1.0)
    length = np.full(n, 1.4)
    t[8:15], length[8:15] = 1.3, 0.42
    start = np.concatenate([[0.0], np.cumsum(t)[:-1]])
    flags = np.zeros(n, bool)
    flags[8:15] = side
    return pd.DataFrame({"start_s": start, "end_s": start + t, "event_s": start + 0.9 * t, "length_m": length,
                         "heading_rad": 0.0, "dz_m": 0.0, "stride_time_s": t, "cadence_spm": 120 / t,
                         "speed_mps": length / t, "turn_angle_rad": 0.0, "impossible": False,
                         "sideways": flags, "gap_s": 0.0, "unit": "foot"})


def test_sideways_strides_leave_the_cvs_and_the_straight_speed():
    with_side, without = clinical_summary(_foot_table(True)), clinical_summary(_foot_table(False))
    assert without["stride_length_cv_pct"] > 40  # before L228: the side steps pooled with the walk
    assert with_side["stride_length_cv_pct"] == 0.0 and with_side["stride_time_cv_pct"] == 0.0
    assert with_side["n_cv_strides"] == 24 - 7 - 2 - 2  # the run, its two neighbours, the first and last
    assert gait_summary(_foot_table(True))["median_speed_straight_mps"] == 1.4
    assert gait_summary(_foot_table(True))["n_straight_strides"] == 24 - 7


def test_plasys_marks_a_side_run_and_leaves_a_plain_walk_alone():
    logging.disable(logging.WARNING)
    try:
        def steps(route):
            s = simulate_path(parse_route(route), UserProfile.from_seed(4281), rate_hz=20.0, seed=1,
                              scenario="route")
            return get_pipeline("plasys")(s).steps
        side, plain = steps("straight:6, side:3, straight:6"), steps("straight:15")
    finally:
        logging.disable(logging.NOTSET)
    flags = side["sideways"].to_numpy(bool)
    assert 3 <= flags.sum() <= 9 and (np.abs(side["length_m"].to_numpy()[flags]) < 0.8).all()
    assert not plain["sideways"].to_numpy(bool).any()
