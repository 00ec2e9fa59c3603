"""Trial T2 (session 47) F6, decision W539: L566's ascent line needs a climb over L172's 0.5 m band and says "counts
none of" for a zero count (adopted); a ramp's whole horizontal run of at least W517's 4 m window is the kernel's
``min_ramp_m`` option (measured, not adopted: it also drops a slow walker's ramp read in short pieces)."""

from __future__ import annotations

import numpy as np

from pdrlearn.track.evaluate import climb_total_warning
from pdrlearn.track.grade import WAIST_SLOPE_WINDOW_M, ramp_runs


def test_the_ascent_line_needs_a_climb_over_the_band_and_says_counts_none_of_w539():
    # T2 F6's line: "ascent_m 0.00 m is 0.27 m below the 0.27 m" - under the 0.5 m band nothing is counted by L172
    assert climb_total_warning({"ascent_m": 0.0, "descent_m": 0.0, "ramps_stairs_ascent_m": 0.27,
                                "ramps_stairs_descent_m": 0.0}) is None
    line = climb_total_warning({"ascent_m": 0.0, "descent_m": 0.0, "ramps_stairs_ascent_m": 0.8,
                                "ramps_stairs_descent_m": 0.0})
    assert line is not None and line.startswith("ascent_m 0.00 m counts none of the 0.80 m its ramps"), line
    line = climb_total_warning({"ascent_m": 0.59, "descent_m": 0.0, "ramps_stairs_ascent_m": 1.08,
                                "ramps_stairs_descent_m": 0.0})
    assert line is not None and "ascent_m 0.59 m is 0.49 m below the 1.08 m" in line  # L566's own case


def test_min_ramp_m_drops_a_lone_two_metre_ramp_and_keeps_a_long_one_w539():
    length = np.full(60, 0.5)
    dz = np.zeros(60)
    dz[10:15] = 0.025  # 2.5 m at 5 %: one run, a ramp under L301's 2 m run
    dz[30:50] = 0.025  # 10 m at 5 %
    got = ramp_runs(length, dz)
    assert [round(r["horizontal_run_m"], 2) for r in got] == [2.5, 10.0]
    kept = ramp_runs(length, dz, min_ramp_m=WAIST_SLOPE_WINDOW_M)
    assert [round(r["horizontal_run_m"], 2) for r in kept] == [10.0]
