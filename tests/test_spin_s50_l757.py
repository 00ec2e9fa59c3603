"""Decision L757: L742's two statistics are public (``kernels.spin.turn_rates``), the numbers L757 measured with and
``turn_in_place`` judges by."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.spin import SPIN_ACC_DEV_MAX, SPIN_TILT_MAX_RAD_S, turn_in_place, turn_rates


def test_turn_rates_are_the_statistics_turn_in_place_judges_l757():
    t = np.arange(0, 2, 0.02)
    up = np.array([0.0, 0.6, 0.8])  # a tilted mount: gravity off z
    acc = np.tile(9.80665 * up, (t.size, 1))
    w = np.outer(3.0 * np.ones_like(t), up)  # 3 rad/s about gravity only
    w[50] += [0.45, 0.0, 0.0]  # one sample tilts the foot at 0.45 rad/s (across gravity)
    tilt, dev = turn_rates(t, acc, t, w, 0.0, 2.0)
    assert tilt == pytest.approx(0.45, abs=1e-9) and dev == pytest.approx(0.0, abs=1e-9)
    assert turn_in_place(t, acc, t, w, 0.0, 2.0) == (tilt < SPIN_TILT_MAX_RAD_S and dev < SPIN_ACC_DEV_MAX)
    w[50] += [0.4, 0.0, 0.0]  # 0.85 rad/s: over the limit, a swing
    assert turn_rates(t, acc, t, w, 0.0, 2.0)[0] == pytest.approx(0.85) and not turn_in_place(t, acc, t, w, 0.0, 2.0)
    assert all(np.isnan(turn_rates(t, acc, t, w, 5.0, 6.0)))  # no samples: not judged
