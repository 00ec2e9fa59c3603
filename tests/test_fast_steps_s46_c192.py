"""Decision C192 (trial T2 finding F8): L95's fast line at a walking speed states the cadence above the validated
range (a quickstep is neither running nor festination) and, on an offline foot track without classes, that the
ZUPT distance held on simulated fast stepping; every other fast track keeps "not reliable"."""

from __future__ import annotations

import pytest

from pdrlearn.track.gait import gait_range_warning

#: trial T2's quickstep: 200 steps/min, 0.5 m steps (1.67 m/s straight)
QUICK = {"median_cadence_spm": 200.0, "median_speed_straight_mps": 1.67, "n_straight_strides": 20,
         "pipeline": "plasys"}
FOOT = {"pipeline": "plasys", "classes_source": None}
NOT_RELIABLE = "the distance, the terrain / direction / length classes and the floors are not reliable"


@pytest.mark.parametrize(("summary", "held"), [
    ({**QUICK, "info": FOOT}, True),
    ({**QUICK, "median_speed_straight_mps": 0.33, "info": FOOT}, True),  # W144's short fast steps
    ({**QUICK, "info": {**FOOT, "streaming": True}}, False),  # a streamed track: not measured here
    ({**QUICK, "info": {**FOOT, "classes_source": "model"}}, False),  # the classes are not validated at 200
    ({**QUICK, "pipeline": "waist-pendulum", "info": {"pipeline": "waist-pendulum"}}, False),  # W178's lower back
    ({**QUICK, "median_speed_straight_mps": 3.3, "info": FOOT}, False),  # running: the simulator has none (S48)
])
def test_c192_the_fast_line_keeps_the_offline_foot_distance_of_fast_steps(summary, held):
    line = gait_range_warning(summary)
    assert line.startswith("median cadence 200 steps/min, straight-walking speed")
    assert ("held on simulated fast stepping" in line and "decision C192" in line and NOT_RELIABLE not in line) is held
    assert (NOT_RELIABLE in line) is not held
    if summary["median_speed_straight_mps"] < 2.5:  # a walking speed: the measured cadence against the range
        assert "a cadence above the walking range the pipelines were validated on (" in line
        assert "quick dance steps" in line and "70-160 steps/min" in line
    else:
        assert "this looks like running, and running is not supported" in line


def test_c192_the_trials_quickstep_tracked_offline_says_its_distance_held(tmp_path):
    import dataclasses

    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS, UserProfile
    from pdrlearn.track.base import get_pipeline

    user = UserProfile.from_seed(14441)
    f_len, f_time = SPEED_FACTORS["normal"]
    user = dataclasses.replace(user, step_length_m=0.5 / f_len, class_step_length_m=user.step_length_m,
                               step_time_s=0.3 / f_time)  # decisions S30 / S81: `simulate --step-time 0.3`
    s = simulate_path(parse_route("stand:3, straight:12, stand:3"), user, rate_hz=100, seed=4)
    summ = get_pipeline("plasys")(s).summary(s)
    line, = [w for w in summ["info"]["warnings"] if "(decision L95)" in w]
    assert "decision C192" in line and NOT_RELIABLE not in line and abs(summ["distance_error_pct"]) < 1.0
