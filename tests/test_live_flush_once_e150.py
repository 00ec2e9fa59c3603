"""Decision E150 (session 31 review, F5): the live waist tracker's W231 drift line (E146) is said once per stream: a
second ``flush()`` adds no second line."""

from __future__ import annotations

from pdrlearn.kernels.barometer import pressure_hpa
from tests.test_live_night_e146_l308 import _live
from tests.test_night_rest_w231_l296 import _edit, _sim


def test_a_second_flush_does_not_repeat_the_drift_line():
    s = _sim("straight:10, stand:200, straight:10", 6246)  # the reviewer's user; 4 m of drift over the pause
    drift = pressure_hpa(0.0, 1013.25) - pressure_hpa(4.0, 1013.25)
    s = _edit(s, "wBarometer", lambda t, v: v + drift * ((t - t[0]) / (t[-1] - t[0]))[:, None])
    out, tr = _live(s, {"pause_ride": True})
    assert len(out) > 0
    assert sum("W231" in w for w in tr.warnings) == 1
    assert tr.flush() == []
    assert sum("W231" in w for w in tr.warnings) == 1  # was 2 before E150
