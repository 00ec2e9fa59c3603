"""Decision L379 (session 33, trial T4 finding 1): a rest taken right before a cone turn was ~9 s short on the foot
(L119 took 180 deg / 20 deg/s off it although the turn was measured in the next stride); now the turn takes the
span of the stride that measured it."""
import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import clinical
from pdrlearn.track.bouts import detected_bouts
from pdrlearn.track.plasys import track_plasys


def test_a_rest_at_a_cone_is_its_length_and_bouts_agree():
    route = "stand:3, straight:15, stand:30, curve:180:0.5, straight:15, stand:3"
    s = simulate_path(parse_route(route), UserProfile.from_seed(7280), rate_hz=20.0, seed=7280, bounce="pendulum")
    steps = track_plasys(s).steps
    c = clinical.clinical_summary(steps)
    assert c["n_pauses"] == 1 and c["pause_time_s"] == pytest.approx(30.0, abs=1.5), c  # was ~21 s
    b = detected_bouts(steps)
    assert len(b) == 2
    gap = float(b["start_s"].iloc[1] - b["end_s"].iloc[0])  # bouts.csv's standing between the two bouts
    assert abs(gap - c["pause_time_s"]) < 1.5, (gap, c["pause_time_s"])


def _streamed(pivot_deg: float, own_deg: float) -> pd.DataFrame:
    t = np.r_[np.arange(6) * 1.2, 6 * 1.2 + 10.0 + np.arange(6) * 1.2]
    own, pivot = np.zeros(len(t)), np.zeros(len(t))
    own[6], pivot[6] = np.radians(own_deg), np.radians(pivot_deg)
    return pd.DataFrame({"start_s": t, "end_s": t + 1.0, "heading_rad": np.cumsum(own + pivot),
                         "turn_angle_rad": own, "pivot_rad": pivot, "gap_s": 0.0, "unit": "foot"})


def test_turn_time_measured_on_the_stride_and_assumed_for_a_pivot():
    # the foot's own turn of 180 deg: its 1.0 s stride span, not 9 s; a streamed pivot (turned at rest): 9 s
    dh = np.array([180.0])
    two = pd.DataFrame({"start_s": [0.0, 20.0], "end_s": [1.0, 21.0], "heading_rad": [0.0, np.pi],
                        "turn_angle_rad": [0.0, np.pi], "gap_s": 0.0, "unit": "foot"})
    assert clinical.turn_allowance_s(two, dh) == pytest.approx([1.0])
    assert clinical.turn_allowance_s(two, dh, mode="assumed") == pytest.approx([9.0])
    assert clinical.turn_allowance_s(two.drop(columns=["turn_angle_rad", "unit"]), dh) == pytest.approx([9.0])
    with pytest.raises(ValueError):
        clinical.turn_allowance_s(two, dh, mode="fast")
    own = clinical.pauses(_streamed(0.0, 180.0))
    pivot = clinical.pauses(_streamed(180.0, 0.0))
    assert own == pytest.approx([10.0 - 1.0]) and pivot == pytest.approx([10.0 - 9.0])
