"""Decision B442 (session 43, fixer FJ; docs/decisions/bad-input.md): the lean live ``WaistTracker.push`` refuses a
value beyond any sensor's range with B425's line, the foot Tracker's B435 check shared (review R1 finding 2: one
1e300 in wAccelerometer silently ended lower-back tracking, 19 of 26 steps lost with numpy overflow warnings only)."""

from __future__ import annotations

import json
import logging
import warnings

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.export.waist import export_waist
from pdrlearn.runtime.waist import WaistTracker
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """R1's reproducer: user 12116, 20 m at 100 Hz, a calibrated waist bundle (as tests/test_live_fixes.py exports)."""
    d = tmp_path_factory.mktemp("b442")
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:2, straight:20, stand:2"), UserProfile.from_seed(12116), seed=12116,
                          scenario="route", rate_hz=100.0)
    finally:
        logging.disable(logging.NOTSET)
    (d / "cal.json").write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                                            "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(d / "cal.json", d / "wb", frame=frame)
    return d / "wb", s["wAccelerometer"], s["wGyroscope"]


def _push_all(bundle, t, acc, gyr):
    tr, out = WaistTracker(bundle, fs=100.0), []
    for j in range(0, len(t), 10):
        out += tr.push(t[j:j + 10], acc[j:j + 10], gyr[j:j + 10])
    return out + tr.flush()


@pytest.mark.parametrize("sensor, axis, value", [("wAccelerometer", 2, 1e300), ("wGyroscope", 0, -1e300)])
def test_an_absurd_pushed_sample_is_b425s_line_on_the_waist_tracker_b442(walk, sensor, axis, value):
    bundle, a, g = walk
    acc, gyr = a.values.copy(), g.values.copy()
    i = int(np.searchsorted(a.t, 8.0))
    (acc if sensor == "wAccelerometer" else gyr)[i, axis] = value
    kind, lim, ax = ("accelerometer", "2000 m/s^2", "z") if axis == 2 else ("gyroscope", "100 rad/s", "x")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy overflow warning on the way
        with pytest.raises(DataError) as e:
            _push_all(bundle, a.t, acc, gyr)
    assert str(e.value) == (f"{sensor} (pushed to the WaistTracker): 1 sample(s) with a value beyond any {kind}'s "
                            f"range (first at t = {a.t[i]:.3f} s: {ax} = {value:g}; the limit is {lim}, decision "
                            "B425): a corrupt sample; drop those samples before pushing")


def test_the_clean_push_still_tracks_b442(walk):
    bundle, a, g = walk
    assert len(_push_all(bundle, a.t, a.values, g.values)) > 20
