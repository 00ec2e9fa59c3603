"""Decision L730: the insoles' support bias is a late contact (a share of the gait cycle) plus an early toe-off (ms),
so a race walker's short cycle states a larger share low than L703's single share did (trial T1 F3: 10 points)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.bilateral import bilateral_gait
from pdrlearn.track.support_bias import FORCE_IC_LAG_PCT, FORCE_TOE_OFF_MS, stance_bias_ms, support_note


def _foot(ic: np.ndarray, stance: float) -> pd.DataFrame:
    return pd.DataFrame({"event_s": ic, "tc_s": ic - (ic[1] - ic[0]) + stance})


def test_the_race_walkers_cycle_states_ten_points():
    """At T1's 0.58 s cycle: 29-32 ms short, -11.2 to -9.8 points of double support (L728 measured -10.1 to -11.0 on
    users 16010-16019 at race pace; L703's share stated -9.3 to -8.2)."""
    cyc = 0.58
    left, right = _foot(np.arange(8) * cyc, 0.37), _foot(0.5 * cyc + np.arange(8) * cyc, 0.37)
    reason = bilateral_gait(left, right, contact_source="force")["reason"]
    assert "29-32 ms short" in reason and "-11.2 to -9.8 of double support" in reason and "L730" in reason
    assert "toe-off the gyroscope's" in reason and "drop-off" not in reason  # gait's toe-off is L73's, not L388's


def test_the_two_terms_add_at_the_cycle():
    lo, hi = stance_bias_ms("force", 1.1)
    assert np.isclose(lo, FORCE_TOE_OFF_MS[0] - 10 * FORCE_IC_LAG_PCT[1] * 1.1)
    assert np.isclose(hi, FORCE_TOE_OFF_MS[1] - 10 * FORCE_IC_LAG_PCT[0] * 1.1)
    assert "13-16 ms plus 2.6-2.9 % of the gait cycle short" in support_note("force", None)
