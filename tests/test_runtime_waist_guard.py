"""The waist trackers check their input as the foot Tracker does (review 2 of session 20):

- B119: ``runtime.WaistTracker`` and ``pdrlearn.waist.WaistTracker`` refuse acceleration in g or mg and a gyroscope
  in deg/s (before: 0 steps in g, 93.3 m for 25.5 m in mg, 1.3 m in deg/s, all without a word); a refused push
  changes nothing; ``check_input=False`` turns the check off;
- B120: a frozen waist gyroscope while walking is warned about;
- W95: ``frame=`` must be a rotation (before: a sheared matrix gave 18.7 m for 25.5 m; a mirrored one is warned
  about, as D10 does) and the axes string of ``export --frame`` is accepted (before: a bare ValueError).
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.export.waist import export_waist
from pdrlearn.runtime import WaistTracker
from pdrlearn.sim import simulate
from pdrlearn.waist import WaistTracker as ParamsWaistTracker


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("wguard")
    s = simulate("B", 406, rate_hz=100.0)
    (d / "cal.json").write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                                            "pipeline": "waist-pendulum", "rate_hz": 100.0,
                                            # E126 / E130 (W199): as live, so E107's line does not name them
                                            "options": {"sit_veto": False, "contact_shift": False,
                                                        "parity_fill": False, "stand_veto": False,
                                                        "pause_ride": False, "rest_bias": False,  # E145
                                                        "turn_bridge": False}}))  # W385: live tracks without it
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(d / "cal.json", d / "wb", frame=frame)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    return {"bundle": d / "wb", "cal": d / "cal.json", "frame": frame, "t": a.t, "acc": a.values, "gyr": g.values,
            "R": s.require_frame("waist").matrix()}


def _run(tr, t, acc, gyr, chunk=50):
    out = []
    for i in range(0, len(t), chunk):
        out += tr.push(t[i:i + chunk], acc[i:i + chunk], gyr[i:i + chunk])
    return out + tr.flush()


SCALINGS = [("acc in g", 1 / 9.80665, 1.0, r"^wAccelerometer \(its first 5\.0 s pushed to the WaistTracker, decision "
                                           r"B119\): median \|acc\| is 1\.0\d, which looks like units of g"),
            ("acc in mg", 1000 / 9.80665, 1.0, r"^wAccelerometer .*looks like raw counts or mm/s\^2"),
            ("gyro in deg/s", 1.0, 180 / math.pi, r"^wGyroscope .*beyond a 2000 deg/s gyroscope in rad/s")]


@pytest.mark.parametrize(("what", "ka", "kg", "match"), SCALINGS, ids=[s[0] for s in SCALINGS])
def test_the_waist_bundle_tracker_refuses_the_wrong_units_unless_check_input_is_off(walk, what, ka, kg,
                                                                                  match):
    t, acc, gyr = walk["t"], walk["acc"] * ka, walk["gyr"] * kg
    tr = WaistTracker(walk["bundle"], fs=100.0)
    with pytest.raises(DataError, match=match):
        _run(tr, t, acc, gyr)
    tr2 = WaistTracker(walk["bundle"], fs=100.0, check_input=False)  # the check off: the old silent result
    _run(tr2, t, acc, gyr)  # no DataError


def test_a_refused_waist_push_takes_nothing(walk):
    t, acc, gyr = walk["t"], walk["acc"], walk["gyr"]
    tr = WaistTracker(walk["bundle"], fs=100.0)
    tr.push(t[:100], acc[:100], gyr[:100])
    last, size = tr._last_t, tr.state_size()
    with pytest.raises(DataError, match="B119"):
        tr.push(t[100:600], acc[100:600] / 9.80665, gyr[100:600])  # the first 5 s complete, mostly in g
    assert (tr._last_t, tr.state_size()) == (last, size)
    ref = WaistTracker(walk["bundle"], fs=100.0)
    assert [s.length_m for s in _run(tr, t[100:], acc[100:], gyr[100:])] == \
        [s.length_m for s in _run(ref, t, acc, gyr)]  # the good samples go on as if nothing was pushed


def test_the_params_waist_tracker_checks_units_too(walk):
    tr = ParamsWaistTracker(100.0, params=str(walk["cal"]), frame=walk["frame"])
    with pytest.raises(DataError, match=r"^wAccelerometer .*decision B119.*units of g"):
        _run(tr, walk["t"], walk["acc"] / 9.80665, walk["gyr"])


def test_si_units_pass_without_warnings(walk):
    tr = WaistTracker(walk["bundle"], fs=100.0)
    out = _run(tr, walk["t"], walk["acc"], walk["gyr"])
    assert len(out) > 20 and not tr.warnings


def test_a_frozen_waist_gyroscope_while_walking_is_warned(walk):
    t, gyr = walk["t"], walk["gyr"].copy()
    i = int(np.searchsorted(t, 10.0))
    gyr[i:i + 300] = gyr[i]  # 3 s of one sample while the unit walks
    tr = WaistTracker(walk["bundle"], fs=100.0)
    _run(tr, t, walk["acc"], gyr)
    assert sum("wGyroscope" in w and "identical consecutive samples" in w for w in tr.warnings) == 1, tr.warnings


def test_the_frame_must_be_a_rotation_and_takes_the_axes_string(walk):
    R = walk["R"]
    ref = _run(WaistTracker(walk["bundle"], fs=100.0), walk["t"], walk["acc"], walk["gyr"])
    by_text = _run(WaistTracker(walk["bundle"], fs=100.0, frame=walk["frame"]), walk["t"], walk["acc"], walk["gyr"])
    assert [s.length_m for s in by_text] == [s.length_m for s in ref]
    with pytest.raises(DataError, match=r"^WaistTracker: frame=: the matrix is not a rotation"):
        WaistTracker(walk["bundle"], fs=100.0, frame=R @ np.diag([2.0, 0.5, 1.0]))
    mirrored = WaistTracker(walk["bundle"], fs=100.0, frame=R @ np.diag([1.0, 1.0, -1.0]))  # used, warned (D10)
    assert re.match(r"^WaistTracker: frame=: the frame is mirrored \(left-handed, det -1\)", mirrored.warnings[-1])
    assert not WaistTracker(walk["bundle"], fs=100.0, frame=R).warnings
    with pytest.raises(DataError, match=r"^WaistTracker: frame=: x=sideways is not an axis"):
        WaistTracker(walk["bundle"], fs=100.0, frame="x=sideways,y=right,z=forward")
    assert any(w.startswith("WaistTracker: frame=: the frame is mirrored") for w in
               ParamsWaistTracker(100.0, params=str(walk["cal"]), frame=R @ np.diag([1.0, 1.0, -1.0])).warnings)
