"""Session 48, fixer FC (trial T3 finding F1, decision L717): with the option ``foot_ramps`` (not the default: its
adoption rule failed, 16 of 20 users) a foot track without ``--altitude fused`` and without terrain classes reads its
ramps from its own L39 heights (a 1:12 ramp walked in strides of 1.2 m or more rises 0.10 m a stride, which L39
keeps): ramps.csv, ``n_ramps`` and L705's ``n_ramp_strides_up`` / ``_down`` are no longer 0 / empty; ``grade_pct`` /
``grade_source`` stay L300's; L574's "ramps need --altitude fused" line counts the ramps' rise as explained."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.altitude_check import integrated_altitude_check
from pdrlearn.track.evaluate import ramps_need_fused_warning
from pdrlearn.track.gait import stair_ramp_split
from pdrlearn.track.grade import add_grade, grade_summary, ramp_source, ramp_table, track_ramps

LINE = "ramps / grades need --altitude fused"
#: T3's course in strides: level, 6 ramp strides up (+0.12 m over 1.42 m, 8.5 %), level, 12 stair strides up
#: (0.34 m over 0.56 m), level, 7 ramp strides down, level (the heights as L39 leaves them)
DZ = np.r_[np.zeros(8), np.full(6, 0.12), np.zeros(8), np.full(12, 0.34), np.zeros(6), np.full(7, -0.118), np.zeros(5)]


def _foot(dz=DZ):
    n = len(dz)
    length = np.where(np.abs(dz) >= 0.25, 0.56, 1.42)
    return pd.DataFrame({"start_s": np.arange(n, dtype=float), "end_s": np.arange(n) + 1.0, "length_m": length,
                         "dz_m": dz, "gap_s": 0.0, "unit": "foot", "heading_rad": 0.0})


#: what L69's check records on a track without terrain classes (offline: L39 levelled its heights) - the default
DEFAULT = {"altitude_check": integrated_altitude_check(DZ)[1]}
#: ... with the option
OWN = {**DEFAULT, "foot_ramps": True}


def test_the_foot_reads_its_ramps_from_its_own_levelled_heights_l717():
    steps = _foot()
    assert OWN["altitude_check"]["levelled"] is True
    assert ramp_source(steps, OWN) == "foot"
    ramps = ramp_table(steps, OWN)
    assert ramps["direction"].tolist() == ["up", "down"] and ramps["n_steps"].tolist() == [6, 7]
    assert ramps["rise_m"].tolist() == pytest.approx([0.72, -0.826])  # the stair flight is no ramp
    s = grade_summary(steps, OWN)
    assert s["n_ramps"] == 2 and s["ramp_source"] == "foot"
    assert s["ramps_rise_m"] == pytest.approx(0.72) and s["ramps_drop_m"] == pytest.approx(0.826)
    assert s["grade_source"] is None and s["distance_along_slope_m"] is None  # L300: no grade of a levelled stride
    assert add_grade(steps, OWN) is None and steps["grade_pct"].isna().all()
    split = stair_ramp_split(steps, track_ramps(steps, OWN)[0])
    assert (split["n_ramp_strides_up"], split["n_ramp_strides_down"]) == (6, 7)  # L705: were 0 / 0 before L717
    assert (split["n_stair_strides_up"], split["n_stair_strides_down"]) == (12, 0)


@pytest.mark.parametrize("info", [DEFAULT,  # L717 not adopted: the default reads no ramp from the foot
                                  {"foot_ramps": True},  # a terrain model's classes set the heights: no L69 record
                                  {"foot_ramps": True,  # C17: a streamed model without terrain classes, unlevelled
                                   "altitude_check": integrated_altitude_check(DZ, levelled=False)[1]}])
def test_no_ramp_from_heights_l39_did_not_level_l717(info):
    steps = _foot()
    assert ramp_source(steps, info) is None and ramp_table(steps, info).empty
    s = grade_summary(steps, info)
    assert s["n_ramps"] is None and s["ramp_source"] is None and s["ramps_rise_m"] is None


def test_fused_and_lower_back_sources_are_unchanged_l717():
    steps = _foot()
    fused = {**OWN, "altitude_source": "fused"}
    assert ramp_source(steps, fused) == "fused" and grade_summary(steps, fused)["grade_source"] == "fused"
    waist = _foot().assign(unit="waist")
    assert ramp_source(waist, OWN) == "barometer"
    assert ramp_source(waist.assign(dz_m=0.0), OWN) is None  # a lower back without its barometer (W90)
    assert ramp_source(_foot(np.zeros(20)), OWN) == "foot" and grade_summary(_foot(np.zeros(20)), OWN)["n_ramps"] == 0


def test_the_fused_line_counts_the_foots_own_ramps_l717():
    # T3's P15702/A: the barometer's count less the two flights left 0.60 m / 0.39 m (over L146's 0.5 m band)
    s = {"barometer_unused": True, "grade_source": None, "barometer_ascent_m": 4.61, "barometer_descent_m": 4.51,
         "flights_rise_m": 4.01, "flights_drop_m": 4.12}
    assert "ramps.csv is empty" in ramps_need_fused_warning(s)  # L602 alone, as before
    foot = {**s, "ramp_source": "foot", "n_ramps": 2, "ramps_rise_m": 0.72, "ramps_drop_m": 0.83}
    assert ramps_need_fused_warning(foot) is None  # the ramps the foot found explain the rest
    line = ramps_need_fused_warning({**foot, "barometer_ascent_m": 5.61})  # a climb neither explains
    assert LINE in line and "0.88 m / 0.00 m more than stairs.csv's flights and ramps.csv's ramps, L602, L632, L717" \
        in line and "holds only the 2 ramp(s) of strides rising 0.10 m or more" in line


def test_the_option_is_a_track_params_key_l717(tmp_path):
    from pdrlearn.cli.track import _track_params
    from pdrlearn.errors import DataError
    from pdrlearn.track.base import TrackResult
    from pdrlearn.track.plasys import _foot_ramps_option

    assert _track_params({"foot_ramps": True}, tmp_path / "p.json", False) == ({}, {"foot_ramps": True})
    with pytest.raises(DataError, match='"foot_ramps" must be true or false'):
        _track_params({"foot_ramps": "yes"}, tmp_path / "p.json", False)
    res = TrackResult(steps=_foot(), trajectory=pd.DataFrame(), info=dict(DEFAULT))
    assert ramp_source(_foot(), _foot_ramps_option(res, False).info) is None
    assert ramp_source(_foot(), _foot_ramps_option(res, True).info) == "foot"


def test_a_simulated_ramp_is_read_with_the_option_only_l717():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    # T3's user 15700 (1.42 m strides) up 10 m of 1:12 (truth 0.83 m), 50 Hz to keep it short
    s = simulate_path(parse_route("stand:2, straight:3, slope:10:8.33, straight:3, stand:2"),
                      UserProfile.from_seed(15700), rate_hz=50, seed=1)
    off = evaluate_track(track_plasys(s), s)
    assert off["n_ramps"] is None and off["n_ramp_strides_up"] == 0  # the default, as before L717
    on = evaluate_track(track_plasys(s, foot_ramps=True), s)
    assert on["ramp_source"] == "foot" and on["n_ramps"] == 1 and on["n_ramp_strides_up"] >= 5
    assert 0.5 < on["ramps_rise_m"] < 0.9 and on["grade_source"] is None
