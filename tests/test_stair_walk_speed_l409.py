"""Decision L409 (session 34, trial T3 finding 11): a session L179 reads as a walk of stairs (no speed judged) whose
gait speed lies above L95's speed range gets the session's "looks like running" line, not only a bout line that
says its cadence is inside the range."""

from __future__ import annotations

from pdrlearn.track.gait import bout_range_warning, gait_range_warning, session_range_side

#: trial T3's `run2` (a fast Python-API session read as stairs: +15.8 m on level ground)
RUN2 = dict(median_cadence_spm=129.79, median_speed_mps=4.23, median_speed_straight_mps=None, n_straight_strides=0,
            gait_speed_mps=4.06, n_stair_strides=13, leg_length_m=0.8465, pipeline="plasys", n_bouts=1,
            bouts_out_of_range=[{"bout": 1, "start_s": 7.78, "end_s": 20.09, "cadence_spm": 129.49,
                                 "speed_mps": 4.06}])


def test_a_stair_walk_at_a_running_speed_gets_the_session_line():
    assert session_range_side(RUN2) == "fast"
    line = gait_range_warning(RUN2)
    assert line is not None and "gait speed 4.06 m/s" in line and "looks like running" in line
    assert bout_range_warning(RUN2) is None  # the session line says it; no "cadence is inside it" bout line


def test_a_slow_stair_walk_stays_judged_by_its_cadence():
    stairs = dict(RUN2, gait_speed_mps=0.6, median_cadence_spm=100.0, bouts_out_of_range=[])
    assert session_range_side(stairs) is None and gait_range_warning(stairs) is None
