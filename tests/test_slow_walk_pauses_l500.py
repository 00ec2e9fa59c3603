"""Decision L500: L482's stride-window rhythm leaves very slow continuous walks alone (review R1 finding 1): rows
that touch are one movement, and the window bounds the rhythm only when the intervals are mostly stands."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track import clinical
from pdrlearn.track.clinical import bout_rows, movement_windows, pauses
from tests.test_stopgo_pauses_l482 import WALKS, _stop_and_go


def _table(starts: list[float], ends: list[float]) -> pd.DataFrame:
    n = len(starts)
    return pd.DataFrame({"start_s": starts, "end_s": ends, "heading_rad": np.zeros(n), "turn_angle_rad": np.zeros(n),
                         "gap_s": 0.0, "unit": "foot"})


def _cut_slow_walk(n: int = 12) -> pd.DataFrame:
    """0.16 m/s as the tracker saw it (review R1): most strides cut in two touching rows (0.7 s + 0.9 s), then
    1.6 s of rest while the other foot swings; every fourth stride one row."""
    starts, ends, t = [], [], 0.0
    for k in range(n):
        starts += [t] if k % 4 == 3 else [t, t + 0.7]
        ends += [t + 1.6] if k % 4 == 3 else [t + 0.7, t + 1.6]
        t += 3.2
    return _table(starts, ends)


def test_very_slow_walk_cut_into_touching_rows_has_no_pause():
    st = _cut_slow_walk()
    assert np.allclose(movement_windows(st), 1.6)  # one movement per stride
    assert len(pauses(st)) == 0  # L482 alone: 11 pauses, each rest judged against a half stride; L104 none
    assert [b - a for a, b in bout_rows(st)] == [len(st)]


def test_slow_walk_with_a_longer_rest_is_judged_against_l104_median():
    t, starts, ends = 0.0, [], []
    for k in range(20):  # windows 2.33 s, rests 0.47 s, one rest of 1.44 s (review R1's 0.18 m/s walk)
        starts.append(t)
        ends.append(t + 2.33)
        t += 2.33 + (1.44 if k == 9 else 0.47)
    assert len(pauses(_table(starts, ends))) == 0  # L482 alone: 1 pause of 1.44 s


def test_stop_and_go_keeps_l482_and_no_module_switch_w413():
    """L482's case stays right; W413: L500 (adopted by L501) is the rule, no ``RHYTHM_MOVEMENTS`` to switch back to
    L482's row windows (11 pauses on the cut slow walk; commit d3ffb129 holds that switch)."""
    st = _stop_and_go()  # walks of 1-3 strides between 2 s stands: L482's case stays right
    assert len(pauses(st)) == len(WALKS) - 1
    assert not hasattr(clinical, "RHYTHM_MOVEMENTS") and not hasattr(clinical, "STRIDE_WINDOW_RHYTHM")
