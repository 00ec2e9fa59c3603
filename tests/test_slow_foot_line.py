"""Session 29's Parkinson's trial (finding 7): every foot track under 0.5 m/s said "the distance ... not reliable"
although the foot distance was within 1.3 %; and bouts.csv's `gait_out_of_range` (fast side only) disagreed with the
summary's (either side). Decision L247: a slow offline foot track without classes says its distance stays usable,
with the measured range (users 4900-4919, 0.2-0.5 m/s: experiments/results/foot_slow.txt); decision L248: the
columns say which side each flag judges."""

from __future__ import annotations

import dataclasses

import pytest

from pdrlearn.columns import expanded
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.bouts import detected_bouts
from pdrlearn.track.gait import gait_range_warning

SLOW = {"median_cadence_spm": 100.0, "median_speed_mps": 0.42, "pipeline": "plasys"}


@pytest.mark.parametrize(("summary", "usable"), [
    ({**SLOW, "info": {"pipeline": "plasys", "classes_source": None}}, True),
    ({**SLOW, "info": {"pipeline": "plasys", "classes_source": None, "streaming": True}}, False),  # L120: +11 %
    ({**SLOW, "info": {"pipeline": "plasys", "classes_source": "model"}}, False),  # classes not validated slow
    ({**SLOW, "pipeline": "waist-pendulum", "info": {"pipeline": "waist-pendulum"}}, False),  # W207: reads long
    ({**SLOW, "pipeline": "runtime", "info": {"pipeline": "plasys"}}, False),  # `run`: streamed
])
def test_l247_the_slow_line_keeps_the_offline_foot_distance(summary, usable):
    line = gait_range_warning(summary)
    assert "slower than the walking" in line and "(decision L95)" in line
    assert ("decision L247" in line and "foot distance (ZUPT strides) stays usable" in line
            and "the distance, the terrain" not in line) is usable
    # decision L324: the direction class is named too (trial 31: slow backward steps read forward)
    assert ("the distance, the terrain / direction / length classes and the floors are not reliable"
            in line) is not usable


def test_l247_a_slow_shuffle_tracked_by_foot_and_l248_the_flags_sides():
    user = dataclasses.replace(UserProfile.from_seed(4803), step_length_m=0.25, step_time_s=0.6)
    s = simulate_path(parse_route("stand:3, straight:10, stand:3"), user, speed="normal", rate_hz=100, seed=4803,
                      bounce="pendulum")
    r = get_pipeline("plasys")(s)
    summ = r.summary(s)
    line, = [w for w in summ["info"]["warnings"] if "slower than the walking" in w]
    assert "decision L247" in line and abs(summ["distance_error_pct"]) < 3.1
    bouts = detected_bouts(r.steps)
    assert summ["gait_out_of_range"] is True and not bouts["gait_out_of_range"].any()  # L248: as documented
    assert summ["n_bouts_out_of_range"] == 0
    assert "ABOVE" in expanded("bouts.csv")["gait_out_of_range"][-1]
    assert "slow bout" in expanded("bouts.csv")["gait_out_of_range"][-1]
    assert "above OR below" in expanded("sessions.csv")["gait_out_of_range"][-1]
