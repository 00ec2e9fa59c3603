"""Decision C213 (session 49, FB, trial s49t1 finding F1): the lower back's laps against ``--corridor`` by a 35 % band
(0.74-1.35 x, from its measured uncalibrated lap scale on fresh users 16520-16539), not L384's 0.5-2 x: the trial's
20 m corridor given 30 (laps 0.58 x) gets L518's line; its right corridors, tracked 0.85-1.03 x, none."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.track.corridor import CORRIDOR_SCALE_TOL, corridor_laps
from pdrlearn.warning_lines import warning_code
from tests.walk_test_s44_helpers import laps_after, strides, turns_at


def _l518(steps, turns, corridor_m):
    return [w for w in corridor_laps(steps, turns, corridor_m, duration_s=200.0)[2] if warning_code(w) == "L518"]


def _lower_back(lap_m: float):
    """4 laps + of 30 one-second contacts tracking ``lap_m`` metres a lap."""
    t, cones = laps_after(0.0, 4)
    return strides(t, step_m=lap_m / 30.0, unit="waist"), turns_at(cones)


def test_the_lower_backs_band_is_c213s_35_pct():
    assert CORRIDOR_SCALE_TOL["lower back"] == 0.35 and CORRIDOR_SCALE_TOL["foot"] == 0.15


@pytest.mark.parametrize("lap_m", [17.3, 41.0])
def test_a_lower_back_corridor_clearly_wrong_warns_c213(lap_m):
    """The trial's J_20m: laps tracked 17.3 m against --corridor 30 (0.58 x; main: silent inside 0.5-2 x); 41 m laps
    (1.37 x, a 40 m hall given 30) too. The count stays laps x --corridor (a line, no re-count)."""
    steps, turns = _lower_back(lap_m)
    line = _l518(steps, turns, 30.0)
    assert len(line) == 1 and "lower back" in line[0] and "0.74-1.35 x" in line[0] and "C213" in line[0]
    assert corridor_laps(steps, turns, 30.0, duration_s=200.0)[1]["n_laps"] == 4


@pytest.mark.parametrize("lap_m", [23.0, 25.5, 31.0, 39.5])
def test_a_lower_back_within_its_measured_scale_error_gets_no_line_c213(lap_m):
    """Laps 0.77-1.32 x the right 30 m (the trial's uncalibrated 25.5-31.0 m; fresh users' 0.86-1.20 x): no line."""
    assert _l518(*_lower_back(lap_m), 30.0) == []
    assert np.log(39.5 / 30.0) < np.log1p(CORRIDOR_SCALE_TOL["lower back"])
