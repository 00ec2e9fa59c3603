"""Decision L645 (session 44, FF, trial T1 finding F10): a final partial lap that reaches the cone counts as a lap."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.track.corridor import corridor_laps
from tests.walk_test_s44_helpers import strides, turns_at


def test_a_last_lap_that_reaches_the_cone_is_a_lap_l645():
    """9 laps of 30 m; the test's span ends as the walker reaches the 9th cone (no turn after it)."""
    t = np.arange(270.0)
    laps, s, _ = corridor_laps(strides(t), turns_at([30.0 * k for k in range(1, 9)]), 30.0, span=(0.0, 270.0))
    assert s["n_laps"] == 9 and s["walk_test_distance_m"] == pytest.approx(270.0)  # main: 8 laps, 270 m
    assert laps["corridor_laps"].iloc[-1] == 1 and laps["distance_source"].iloc[-1] == "corridor"
    # 27 m of the last lap (90 %) is a partial lap, as before
    _, part, _ = corridor_laps(strides(t[:267]), turns_at([30.0 * k for k in range(1, 9)]), 30.0)
    assert part["n_laps"] == 8 and part["walk_test_distance_m"] == pytest.approx(267.0)
