"""Decision L680 (session 46, I5): L602's "ramps / grades need --altitude fused" band in each direction is the larger
of L146's 0.5 m and 10 % of the stair flights' height that way, so a long stair loop whose flights and barometer
disagree by their proportional errors stays quiet, while a climb the flights do not explain is still said."""

from __future__ import annotations

from pdrlearn.track.evaluate import FLIGHT_BAND_FRACTION, ramps_need_fused_warning

LINE = "ramps / grades need --altitude fused"
BASE = {"barometer_unused": True, "grade_source": None}


def test_a_long_stair_loops_disagreement_is_within_the_relative_band_l680():
    # session 45's stair loop, streamed: the flights missed 0.58 m of the barometer's 17 m descent
    s = {**BASE, "barometer_ascent_m": 17.30, "barometer_descent_m": 17.40, "flights_rise_m": 17.20,
         "flights_drop_m": 16.82}
    assert ramps_need_fused_warning(s) is None  # L602 alone (0.5 m): said
    line = ramps_need_fused_warning({**s, "flights_drop_m": 15.0})  # 2.40 m unexplained: over 1.50 m
    assert LINE in line and "0.10 m / 2.40 m more than stairs.csv's flights" in line
    assert "over 1.50 m: 10 % of the flights' climb, L680" in line
    assert FLIGHT_BAND_FRACTION == 0.10


def test_l602s_band_is_kept_under_5_m_of_flights_l680():
    s = {**BASE, "barometer_ascent_m": 3.78, "barometer_descent_m": 0.0, "flights_drop_m": 0.0}
    assert ramps_need_fused_warning({**s, "flights_rise_m": 3.30}) is None  # 0.48 m: L602's band
    line = ramps_need_fused_warning({**s, "flights_rise_m": 3.19})
    assert "0.59 m / 0.00 m more than stairs.csv's flights, L602, L632)" in line  # no L680 words: the 0.5 m band
    # the band is per direction: 17 m of flights up do not widen the descent's band
    s2 = {**BASE, "barometer_ascent_m": 17.3, "barometer_descent_m": 2.0, "flights_rise_m": 17.3,
          "flights_drop_m": 1.4}
    assert "0.00 m / 0.60 m more" in ramps_need_fused_warning(s2)
