"""Decision L96 (docs/decisions/localization.md): a detected window that ``pdrlearn track`` splits at the rests
inside it (missed steps; the accelerometer detector at running cadence) gives each piece its own landing, so
every piece has a stride time and the session a cadence (the running trial's no-force session: 0 of 37)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace import rest_to_rest
from pdrlearn.track.gait import stride_times
from pdrlearn.track.plasys import split_events


def test_each_piece_of_a_split_window_gets_the_landing_that_ends_it():
    t = np.arange(0.0, 8.0, 0.01)
    stance = np.zeros(len(t), bool)
    for a, b in [(0.0, 1.0), (2.0, 2.3), (3.0, 3.3), (4.0, 4.3), (6.0, 8.0)]:
        stance[(t >= a - 1e-9) & (t < b - 1e-9)] = True
    # row 0: one window over three strides (its contact 3.98 s, in the last piece); row 1: one stride (5.9 s)
    det = pd.DataFrame({"start_s": [0.6, 4.2], "end_s": [4.1, 6.2], "event_s": [3.98, 5.9]})
    i0, i1, rows = rest_to_rest(t, stance, det["start_s"].to_numpy(), det["end_s"].to_numpy())
    assert rows.tolist() == [0, 0, 0, 1]
    pieces = det.iloc[rows].reset_index(drop=True)
    pieces["start_s"], pieces["end_s"] = t[i0], t[i1]
    got = split_events(pieces, rows, t, stance)
    assert got == pytest.approx([2.0, 3.0, 4.0, 5.9])
    st = stride_times(pieces["start_s"], pieces["end_s"], got)
    assert np.isfinite(st[1:]).all() and st[1:] == pytest.approx([1.0, 1.0, 1.9])
    # before L96 every piece kept the window's contact: one piece had it inside, no stride time at all
    assert np.isnan(stride_times(pieces["start_s"], pieces["end_s"], pieces["event_s"])[1:3]).all()
