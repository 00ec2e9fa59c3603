"""Decision L353 (L350's candidate): ``gait_speed_warning`` names a reported gait speed below L95's range while L95's
judged figures are inside it; adopted by L353's rule (a default line of ``summary_warnings``)."""

from __future__ import annotations

from pdrlearn.track.evaluate import summary_warnings
from pdrlearn.track.gait import gait_range_warning, gait_speed_warning

#: MS001 Test11's summary figures as `track` printed them (L350): gait 0.43 m/s, 8 straight strides at 0.89 m/s
MS001 = {"gait_speed_mps": 0.4276, "median_speed_straight_mps": 0.8882, "n_straight_strides": 8,
         "median_speed_mps": 0.6231, "median_cadence_spm": 101.69, "leg_length_m": 0.975,
         "leg_length_source": "meta.json subject.sensor_height_m"}


def test_gait_speed_line_fires_only_where_l95_is_quiet():
    assert gait_range_warning(MS001) is None  # L95 judges the straight strides (L123): quiet
    line = gait_speed_warning(MS001)
    assert line is not None and line.startswith("the reported gait speed 0.43 m/s")
    assert "0.52-2.60 m/s" in line and "straight-walking speed 0.89 m/s" in line and line.endswith("(decision L353)")
    # inside the leg-scaled range (0.52 m/s for this leg; L148): no line
    assert gait_speed_warning({**MS001, "gait_speed_mps": 0.53}) is None
    # the adult range without a leg: 0.49 m/s is below 0.5
    adult = {k: v for k, v in MS001.items() if not k.startswith("leg_length")}
    assert gait_speed_warning({**adult, "gait_speed_mps": 0.49}) is not None
    assert gait_speed_warning({**adult, "gait_speed_mps": 0.51}) is None
    # L95 already fires (straight strides slow too): its own line, no second one
    slow = {**MS001, "median_speed_straight_mps": 0.40}
    assert gait_range_warning(slow) is not None and gait_speed_warning(slow) is None
    # L179's walk of stairs (too few straight strides, 5 or more stair strides): slow horizontally by nature
    stairs = {**MS001, "n_straight_strides": 4, "n_stair_strides": 27}
    assert gait_range_warning(stairs) is None and gait_speed_warning(stairs) is None
    assert gait_speed_warning({**stairs, "n_stair_strides": 4}) is not None  # neither: L95 judges all strides
    # no gait speed: nothing to say
    assert gait_speed_warning({**MS001, "gait_speed_mps": None}) is None


def test_gait_speed_line_is_a_default_summary_warning():
    assert gait_speed_warning(MS001) in summary_warnings(MS001)  # `track`, `track-all` and `run` print it
    assert not any("L353" in w for w in summary_warnings({**MS001, "gait_speed_mps": 0.80}))
