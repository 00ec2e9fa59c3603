"""Session 41, implementer I4: decisions L558 / L559 (L545's drift-aware compass windows, with a walk of one window
fitted as L182's one fit so a recording too short for two windows is judged exactly as before; adopted)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.orient._kernels import compass_disagreement
from pdrlearn.track.plasys import COMPASS_CHECK_WINDOW_S, check_angle, compass_windows, windowed_disagreement
from tests.test_march_s40 import _straight_march


def test_a_walk_of_one_window_is_fitted_as_l182s_one_fit_with_drift_l558():
    """L558: under two of L264's windows the drift-aware fit is not used: the angles are L182's one fit's."""
    mf, ml, psi, t = _straight_march(drift_dps=1.0, disturb_deg=0.0)
    keep = t < 0.9 * COMPASS_CHECK_WINDOW_S  # one window
    mf, ml, psi, t = mf[keep], ml[keep], psi[keep], t[keep]
    assert len(compass_windows(t, COMPASS_CHECK_WINDOW_S, 8)) == 1
    one = compass_disagreement(mf, ml, psi)[0]
    assert windowed_disagreement(mf, ml, psi, t) == pytest.approx(one, abs=1e-12)
    assert check_angle(mf, ml, psi, t, windowed=True)[0] == pytest.approx(
        check_angle(mf, ml, psi, t, windowed=False)[0], abs=1e-12)


def test_two_windows_or_more_still_take_the_drift_aware_fit_l558():
    """L558: from two windows on, each window is fitted with L544's model (a drifting foot heading agrees)."""
    mf, ml, psi, t = _straight_march(drift_dps=1.0, disturb_deg=0.0)
    keep = t < 2.5 * COMPASS_CHECK_WINDOW_S
    mf, ml, psi, t = mf[keep], ml[keep], psi[keep], t[keep]
    assert len(compass_windows(t, COMPASS_CHECK_WINDOW_S, 8)) == 3
    drift = np.degrees(np.median(np.abs(windowed_disagreement(mf, ml, psi, t))))
    plain = np.degrees(np.median(np.abs(np.concatenate([compass_disagreement(mf[g], ml[g], psi[g])[0]
                                                        for g in compass_windows(t, COMPASS_CHECK_WINDOW_S, 8)]))))
    assert drift < 5.0 < plain
