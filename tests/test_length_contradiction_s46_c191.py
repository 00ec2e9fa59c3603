"""Decision C191 (trial T2 finding F2): a stride of any turn whose measured length contradicts its length class by
more than 5 % of the class's nearest bound takes the measured class (C88's rule, which covered turning strides
only); and the calibration's stride-time range beside L474's speed range."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

#: trial T2's model bounds (manifest.json length_bounds_m [1.3077, 1.9405])
BOUNDS = {"short": (0.0, 1.3077), "normal": (1.3077, 1.9405), "long": (1.9405, 10.0)}


def test_a_straight_stride_far_outside_its_class_takes_the_measured_class():
    from pdrlearn.kernels.turn_length import contradicts_by_margin, turn_length_class_one

    proba = {"short": 0.1, "normal": 0.2, "long": 0.7}
    # the trial's waltz strides: 1.18-1.29 m called long (long starts at 1.9405 m): all far below it
    for length in (1.18, 1.22, 1.29):
        label, p = turn_length_class_one("long", proba, length, 0.0, BOUNDS)
        assert label == "short" and p == {"short": 1.0, "normal": 0.0, "long": 0.0}
    # within 5 % of normal's lower bound (1.3077 x 0.95 = 1.242 m): the measurement alone is no contradiction
    assert turn_length_class_one("normal", proba, 1.28, 0.0, BOUNDS) == ("normal", proba)
    assert turn_length_class_one("normal", proba, 1.20, 0.0, BOUNDS)[0] == "short"
    assert turn_length_class_one("short", proba, 1.36, 0.0, BOUNDS) == ("short", proba)  # 1.3077 x 1.05 = 1.373
    assert turn_length_class_one("short", proba, 1.40, 0.0, BOUNDS)[0] == "normal"
    # a backward stride's negative length is measured by its size; no class, NaN, above every bound: unchanged
    assert turn_length_class_one("long", None, -1.18, 0.0, BOUNDS) == ("short", None)
    assert not contradicts_by_margin(None, 1.18, BOUNDS) and not contradicts_by_margin("long", np.nan, BOUNDS)
    assert turn_length_class_one("normal", proba, 12.0, 0.0, BOUNDS) == ("normal", proba)


def _route_session(step_time: float, step_length: float):
    import dataclasses

    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS, UserProfile

    user = UserProfile.from_seed(8619)
    f_len, f_time = SPEED_FACTORS["normal"]
    walker = dataclasses.replace(user, step_length_m=step_length / f_len, class_step_length_m=user.step_length_m,
                                 step_time_s=step_time / f_time)  # decisions S30 / S81: classes stay the user's
    return simulate_path(parse_route("stand:3, straight:8, stand:3"), walker, seed=1)


@pytest.fixture(scope="module")
def waltz():
    return _route_session(0.68, 0.6)


def test_offline_track_gives_the_waltz_strides_their_measured_class(waltz):
    """Trial T2: the classifier called short straight strides long at a waltz tempo; C88's rule did not reach
    them. The stand-in model calls every stride long (C89's test's)."""
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.turn_classes import measured_length_class
    from tests.test_turning_length_classes_c89 import _FixedLength

    bounds = waltz.meta["length_class_bounds_m"]
    res = track_plasys(waltz, method="M3", model=_FixedLength("long", bounds))
    st = res.steps
    full = np.abs(st["raw_length_m"].to_numpy(float)) > 1.0  # the walk's strides, not its half first / last
    assert full.sum() >= 5
    lo, hi = bounds
    measured = measured_length_class(st["raw_length_m"].to_numpy(float), {"short": (0, lo), "normal": (lo, hi),
                                                                         "long": (hi, 10.0)})
    assert (measured[full] != "long").all() and (np.abs(st["raw_length_m"][full]) < 0.95 * hi).all()
    assert (st["length_class"].to_numpy(dtype=object)[full] == measured[full]).all()  # was long everywhere


def _walk(stride_time: float, n: int = 20) -> pd.DataFrame:
    start = stride_time * np.arange(n)
    return pd.DataFrame({"start_s": start, "end_s": start + stride_time, "raw_length_m": 1.2, "dz_m": 0.0,
                         "heading_rad": 0.0, "speed_mps": 1.2 / stride_time, "stride_time_s": stride_time})


class _Model:
    def __init__(self, **calibration):
        self.data_summary = {"distance_calibration": calibration}


def test_a_walk_at_another_tempo_than_the_calibration_is_flagged():
    from pdrlearn.track.speed_domain import flag_stride_times

    model = _Model(speed_range_mps=[0.5, 2.0], speed_range_strides="cruise", stride_time_range_s=[1.1, 1.25])
    lines: list[str] = []
    same = _walk(1.2)
    info = flag_stride_times(same, model, lines)
    assert not same["stride_time_out_of_range"].any() and lines == [] and info["n_strides"] == 18
    waltz = _walk(1.5)  # 0.75 s steps, 80 steps/min, inside the speed range (0.8 m/s)
    info = flag_stride_times(waltz, model, lines)
    assert waltz["stride_time_out_of_range"].sum() == 18 and info["n_out"] == 18 and info["range_s"] == [1.1, 1.25]
    assert len(lines) == 1 and "18 of 18 level straight strides at stride times" in lines[0]
    assert "96-109 steps/min" in lines[0] and "decision C191" in lines[0]


def test_a_model_trained_before_c191_says_once_that_the_tempo_is_not_checked():
    from pdrlearn.track.speed_domain import flag_stride_times

    lines: list[str] = []
    assert flag_stride_times(_walk(1.5), _Model(speed_range_mps=[0.5, 2.0]), lines) is None
    assert len(lines) == 1 and "no stride-time range" in lines[0]
    assert flag_stride_times(_walk(1.5), _Model(), lines) is None and len(lines) == 1  # no calibration: nothing


def test_the_calibration_records_the_stride_time_range_of_its_cruise_strides(monkeypatch):
    from pdrlearn.displace import calibration
    from pdrlearn.track.base import TrackResult

    st = _walk(1.2, 30)
    st.loc[[0, 29], "stride_time_s"] = 3.0  # a bout's first and last stride are no cruise strides (L480)
    st["length_m"] = st["raw_length_m"]

    class S:
        name, steps = "walk", st

        def has(self, *names):
            return True

    monkeypatch.setattr("pdrlearn.io.resample.recorded_rate", lambda s, name: (100.0, None))
    res = TrackResult(steps=st.copy(), trajectory=pd.DataFrame(), info={})
    out = calibration._estimate([S()], lambda s, p: res, None, {})
    assert out["stride_time_range_s"] == [1.2, 1.2]
