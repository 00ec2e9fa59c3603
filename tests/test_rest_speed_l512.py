"""Decisions L509/L512 (docs/decisions/localization.md): the opt-in speed of a stride after a rest, and the default
that stays IC to IC (not adopted)."""

import inspect

import numpy as np
import pandas as pd

from pdrlearn.track import gait


def _table():
    # two touching strides, a 1.5 s stand, then two touching strides (IC to IC 1.0 s while walking)
    return pd.DataFrame({"start_s": [0.0, 1.0, 3.5, 4.5], "end_s": [1.0, 2.0, 4.5, 5.5],
                         "event_s": [0.8, 1.8, 4.3, 5.3], "length_m": [1.0, 1.4, -1.2, -1.4]})


def test_rest_speed_opt_in_uses_the_shorter_of_own_and_next_stride_time_l512():
    t = gait.add_gait_columns(_table(), rest_speed=True)
    np.testing.assert_allclose(t["stride_time_s"], [np.nan, 1.0, 2.5, 1.0])  # IC to IC stays (cadence, L66)
    # the first stride and the first after the stand: over the next stride's 1.0 s, not the stand's 2.5 s
    np.testing.assert_allclose(t["speed_mps"], [1.0, 1.4, 1.2, 1.4])


def test_rest_speed_default_is_ic_to_ic_not_adopted_l512():
    # review R1 finding 7: the unadopted opt-in is the keyword only, no module global read as its default (W401)
    assert not hasattr(gait, "REST_SPEED")
    assert inspect.signature(gait.add_gait_columns).parameters["rest_speed"].default is False
    t = gait.add_gait_columns(_table())
    np.testing.assert_allclose(t["speed_mps"], [np.nan, 1.4, 1.2 / 2.5, 1.4])


def test_rest_speed_one_stride_burst_and_gap_rows_l512():
    # a lone stride between two stands keeps its shorter time; an invalid (gap) row is no stride
    t = pd.DataFrame({"start_s": [0.0, 2.0, 5.0, 6.0], "end_s": [1.0, 3.0, 6.0, 7.0],
                      "event_s": [0.8, 2.8, 5.8, 6.8], "length_m": [1.0, 1.0, 1.0, 1.0]})
    moving = gait.resumed_times(t["start_s"], t["end_s"], [np.nan, 2.0, 3.0, 1.0], [True, True, True, False])
    np.testing.assert_allclose(moving, [2.0, 2.0, 3.0, 1.0])  # an invalid row passes through (its own is NaN)
