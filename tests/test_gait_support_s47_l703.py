"""Decision L703 (session 47, trial T1 F3): the support caveat of `pdrlearn gait` and --toe-off's short-contact line
state the known stance bias of the set-up that timed the contacts (force insoles or the IMU alone), in ms and in
percentage points of this walk's own gait cycle, instead of one fixed adult walk's -7.2 / +3.6 points."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.bilateral import bilateral_gait
from pdrlearn.track.support_bias import STANCE_BIAS, setup_of, stance_bias_ms, support_note
from pdrlearn.track.toeoff import stance_range_warning


def _foot(ic, swing=0.30) -> pd.DataFrame:
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.4, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - swing,
                         "length_m": 0.84, "gap_s": 0.0, "unit": "foot"})


def test_setups_and_their_bias_in_ms():
    assert setup_of("force") == "force" and setup_of("inertial") == "imu"
    assert setup_of({"left": "imu", "right": "imu"}) == "imu" and setup_of({"left": "imu", "right": "force"}) is None
    assert stance_bias_ms("imu", None) == (-40.1, -36.9)  # L73's real gaitmap walks, whatever the cycle
    lo, hi = stance_bias_ms("force", 0.8)  # the simulated insoles: ms plus a share of the cycle (L730)
    assert np.isclose(lo, -15.9 - 2.86 * 8.0) and np.isclose(hi, -13.4 - 2.61 * 8.0)
    assert stance_bias_ms("force", None) is None


def test_a_childs_gait_states_its_own_points_per_setup():
    """A 0.80 s cycle: IMU-only 36.9-40.1 ms = -9.2 to -10.0 points of double support, but at a child's short cycle
    some IMU contacts fired early (steps 87) and are re-dated (steps 91, 92), so no sign is claimed; insoles
    13.4-15.9 ms plus 2.61-2.86 % of the cycle (L730) = -8.6 to -9.7; the old fixed adult numbers are gone."""
    left, right = _foot(np.arange(6) * 0.8), _foot(0.4 + np.arange(6) * 0.8)
    imu = bilateral_gait(left, right, contact_source={"left": "imu", "right": "imu"})["reason"]
    force = bilateral_gait(left, right, contact_source="force")["reason"]
    assert "0.80 s gait cycle" in imu and "-10.0 to -9.2 of double support" in imu and "37-40 ms short" in imu
    assert "-9.7 to -8.6 of double support" in force  # L730 (L703's: -9.3 to -8.2)
    assert "insole" in force and "IMU-only" not in force
    assert "re-dated at the stride's rhythm (steps 91" in imu and "not known" in imu and "fire" not in force
    assert "stance read -30 to -4 ms (steps 92)" in imu  # steps decision 92
    assert force.startswith("double support reads low")
    adult = bilateral_gait(_foot(np.arange(6) * 1.1), _foot(0.55 + np.arange(6) * 1.1), contact_source="imu")["reason"]
    assert adult.startswith("double support reads low") and "1.10 s gait cycle" in adult
    assert "-7.3 to -6.7 of double support" in adult
    for r in (imu, force, adult):
        assert "-7.2 / +3.6" not in r and "L703" in r
    both = bilateral_gait(left, right)["reason"]  # set-up unknown: both ranges
    assert "IMU-only" in both and "insole" in both
    assert set(STANCE_BIAS) == {"imu", "force"}


def test_the_short_contact_line_gives_this_walks_bias():
    line = stance_range_warning({"median_stance_time_s": 0.478, "median_stride_time_s": 0.805,
                                 "info": {"stance_source": "force"}})
    assert "0.478 s is below 0.69 s" in line and "0.81 s gait cycle" in line and "insole" in line
    assert "% of this walk's 0.478 s stance" in line and line.endswith("(decision L414)")
    imu = stance_range_warning({"median_stance_time_s": 0.504, "median_stride_time_s": 0.8,
                                "info": {"stance_source": "inertial"}})
    assert "37-40 ms short" in imu and "insole" not in imu and "were not checked" not in imu
    assert support_note("imu", None).count("ms short") == 1
