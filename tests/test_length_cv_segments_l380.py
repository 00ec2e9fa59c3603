"""Decision L380 (session 33, trial T4 finding 4): a stride-length CV pooled over straight stretches of different
stride length (a 6MWT's slower laps) is named, with the CV about each stretch's own mean beside it."""
import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import clinical_summary, pooled_length_cv_warning, segment_length_cv, steady_rows
from pdrlearn.track.plasys import track_plasys


def _laps(short: bool) -> pd.DataFrame:
    tail = ":short" if short else ""
    route = (f"stand:3, straight:20, curve:180:0.5, straight:20, curve:180:0.5, straight:20{tail}, curve:180:0.5, "
             f"straight:20{tail}, stand:3")
    s = simulate_path(parse_route(route), UserProfile.from_seed(7281), rate_hz=20.0, seed=7281)
    return track_plasys(s).steps


def test_a_change_of_pace_between_laps_is_named_not_variability():
    c = clinical_summary(_laps(short=True))
    assert c["n_cv_segments"] == 4, c
    assert c["stride_length_cv_pct"] > 10.0  # two paces pooled
    assert c["stride_length_cv_within_segments_pct"] < 5.0  # the simulated walker's own variability is a few %
    line = pooled_length_cv_warning(c)
    assert line and "change of pace" in line and "L380" in line
    steady = clinical_summary(_laps(short=False))
    assert steady["stride_length_cv_within_segments_pct"] == pytest.approx(steady["stride_length_cv_pct"], rel=0.5)
    assert pooled_length_cv_warning(steady) is None


def test_segment_cv_by_hand():
    # 14 strides: two straight runs of 6 steady strides (1.5 m and 1.0 m, +-1 %) split by a turning stride
    length = np.r_[1.5, 1.5 * np.array([1.01, 0.99] * 3), 1.2, 1.0 * np.array([1.01, 0.99] * 3), 1.0]
    turn = np.zeros(len(length))
    turn[7] = np.radians(90.0)
    n = len(length)
    t = np.arange(n) * 1.2
    st = pd.DataFrame({"start_s": t, "end_s": t + 1.0, "length_m": length, "heading_rad": np.cumsum(turn),
                       "turn_angle_rad": turn, "stride_time_s": 1.2, "gap_s": 0.0, "unit": "foot", "dz_m": 0.0})
    st, steady = steady_rows(st)
    cv, n_seg = segment_length_cv(st, steady)
    runs = [length[steady][:5], length[steady][5:]]
    assert n_seg == 2 and steady.sum() == 10
    dev = np.concatenate([r / r.mean() - 1 for r in runs])
    assert cv == pytest.approx(100 * np.sqrt(np.sum(dev ** 2) / (10 - 2)))
