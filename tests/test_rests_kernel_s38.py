"""Session 38: the one kernel of the spans between a walk's rows (pdrlearn.kernels.rests), which the weather's
standstills (L464), the streamed rests (E205) and the clinical pauses (L110) share, each with its own rule."""

import numpy as np
import pandas as pd

from pdrlearn.kernels.rests import between_rows


def test_between_rows_spans_edges_and_carry():
    lo, hi = between_rows([1.0, 5.0, 6.0], [2.0, 9.0, 7.0])
    assert lo.tolist() == [2.0, 9.0] and hi.tolist() == [5.0, 6.0]  # row order, no carry: the overlap is negative
    lo, hi = between_rows([1.0, 5.0, 6.0], [2.0, 9.0, 7.0], edges=(0.0, 20.0), carry=True)
    assert lo.tolist() == [0.0, 2.0, 9.0, 9.0] and hi.tolist() == [1.0, 5.0, 6.0, 20.0]
    lo, hi = between_rows([], [], edges=(3.0, 8.0))  # a recording without rows is one span
    assert lo.tolist() == [3.0] and hi.tolist() == [8.0]
    t = np.array([0.0, 1.1, 2.3, 7.9])
    lo, hi = between_rows(t, t)  # start to start: numpy.diff's intervals, bit for bit
    assert np.array_equal(hi - lo, np.diff(t))
    assert between_rows([4.0], [5.0])[0].size == 0


def test_three_callers_keep_their_rules():
    from pdrlearn.kernels.weather_drift import standstills
    from pdrlearn.track.clinical import pause_spans
    from pdrlearn.track.position_sigma import streamed_rests

    # L464: the edges count, trimmed 5 s, at least 60 s, an overlapping step carries the walk
    assert standstills([10.0, 200.0, 150.0], [100.0, 210.0, 205.0], 0.0, 300.0) == [(215.0, 295.0)]  # 205 carries
    assert standstills([10.0, 200.0, 150.0], [100.0, 210.0, 205.0], 0.0, 400.0) == [(215.0, 395.0)]
    assert standstills([], [], 0.0, 100.0) == [(5.0, 95.0)]
    # E205: no edges, strictly longer than min_s, not next to a held foot-gap row
    steps = pd.DataFrame({"start_s": [0.0, 2.0, 10.0, 30.0], "end_s": [1.0, 3.0, 11.0, 31.0],
                          "gap_s": [0.0, 0.0, 0.0, 5.0]})
    assert streamed_rests(steps, 6.5) == [(3.0, 10.0)]  # 11 -> 30 is next to the held row
    assert streamed_rests(steps, 7.0) == []
    # L110: start-to-start intervals over the median, only between rows
    walk = pd.DataFrame({"start_s": [0.0, 1.0, 2.0, 3.0, 10.0, 11.0], "end_s": [1.0, 2.0, 3.0, 4.0, 11.0, 12.0]})
    assert pause_spans(walk, min_s=2.0).tolist() == [[4.0, 10.0]]
