"""Decision L179: stair strides are not slow straight walking in L95's gait-range guard (session 26 trial
`building`, finding 11: a spiral stair walk was told "straight-walking speed 0.26 m/s ... the floors are not
reliable" with its floors exact)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.gait import gait_range_warning, gait_summary

#: the trial's spiral: `simulate --route "straight:3, up:4, turn:90, ... (9 times) ..., straight:3" --user-seed 3`
SPIRAL = "straight:3, " + ", ".join(["up:4, turn:90"] * 9) + ", straight:3"


def _table(dz: np.ndarray, speed: np.ndarray) -> pd.DataFrame:
    n = len(dz)
    t = np.arange(n, dtype=float) * 1.1
    return pd.DataFrame({"start_s": t, "end_s": t + 1.1, "length_m": speed * 1.1, "dz_m": dz, "stride_time_s": 1.1,
                         "cadence_spm": 120 / 1.1, "speed_mps": speed, "turn_angle_rad": 0.0, "gap_s": 0.0,
                         "unit": "foot"})


def test_stair_strides_are_not_straight_walking():
    # 20 stair strides at 0.25 m/s horizontally, 3 level straight strides at 1.2 m/s: before L179 the 23 "straight"
    # strides' median (0.25 m/s) was judged slow
    steps = _table(np.r_[np.full(20, 0.34), np.zeros(3)], np.r_[np.full(20, 0.25), np.full(3, 1.2)])
    s = gait_summary(steps)
    assert s["n_stair_strides"] == 20 and s["n_straight_strides"] == 3
    assert s["median_speed_straight_mps"] == 1.2
    assert gait_range_warning(s) is None
    # a level slow walk still warns (L95): the guard is unchanged without stairs
    slow = gait_summary(_table(np.zeros(23), np.full(23, 0.25)))
    assert slow["n_stair_strides"] == 0
    assert "straight-walking speed 0.25 m/s" in gait_range_warning(slow)
    # enough level straight strides: their speed is judged on a stair walk too
    mixed = gait_summary(_table(np.r_[np.full(20, -0.34), np.zeros(6)], np.r_[np.full(20, 0.25), np.full(6, 0.3)]))
    assert "straight-walking speed 0.30 m/s" in gait_range_warning(mixed)


def test_the_trials_spiral_stair_walk_is_not_warned_slow():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track, summary_warnings
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route(SPIRAL), UserProfile.from_seed(3), speed="normal", rate_hz=20.0, seed=0,
                      name="spiral", scenario="route")
    res = track_plasys(s)  # as `pdrlearn track` without a model
    summ = evaluate_track(res, s)
    print({k: summ.get(k) for k in ("n_stair_strides", "n_straight_strides", "median_speed_mps", "floors_up",
                                    "floors_up_ref")})
    assert summ["floors_up"] == summ["floors_up_ref"] == 2
    assert summ["n_stair_strides"] >= 20 and summ["n_straight_strides"] < 5
    assert summ["median_speed_mps"] < 0.5  # all strides: the stairs and landings are slow horizontally
    assert not [w for w in summary_warnings(summ) if "validated on walking" in w]
