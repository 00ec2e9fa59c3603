"""Decision E241 (session 41, implementer I3): the waist trackers refuse a second thread inside ``push`` /
``push_barometer`` / ``flush`` with E231's :class:`ConcurrentUseError`, one mechanism (``runtime.threads``) shared
with the foot ``Tracker``."""

from __future__ import annotations

import json
import threading

import numpy as np
import pytest

from pdrlearn.errors import ConcurrentUseError, DataError
from pdrlearn.export.waist import export_waist
from pdrlearn.runtime import Tracker, WaistTracker, threads
from pdrlearn.sim import simulate
from pdrlearn.waist import WaistTracker as ParamsWaistTracker


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("wthreads")
    s = simulate("B", 11100, rate_hz=100.0)
    (d / "cal.json").write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                                            "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(d / "cal.json", d / "wb", frame=frame)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    return {"bundle": d / "wb", "cal": d / "cal.json", "frame": frame, "t": a.t, "acc": a.values, "gyr": g.values}


def _from_another_thread(tr, calls):
    """What each of ``calls`` raised when run on a second thread while this one is inside the tracker."""
    got = []

    def other():
        for call in calls:
            try:
                call()
            except Exception as exc:  # noqa: BLE001 - the test looks at what came out
                got.append(exc)

    with tr._busy:  # "another thread is inside push"
        th = threading.Thread(target=other)
        th.start()
        th.join()
    return got


@pytest.mark.parametrize("kind", ["bundle", "params"])
def test_a_second_thread_inside_a_waist_tracker_is_refused_in_one_line_e241(walk, kind):
    """Before E241 the three calls ran inside the other thread's push (no error: the stream state interleaved)."""
    tr = (WaistTracker(walk["bundle"], fs=100.0) if kind == "bundle" else
          ParamsWaistTracker(100.0, params=walk["cal"], frame=walk["frame"]))
    t, acc, gyr = walk["t"], walk["acc"], walk["gyr"]
    n = len(t) // 2
    tr.push(t[:100], acc[:100], gyr[:100])
    got = _from_another_thread(tr, [lambda: tr.push(t[100:200], acc[100:200], gyr[100:200]),
                                    lambda: tr.push_barometer(t[100:200], np.full(100, 1000.0)), tr.flush])
    assert len(got) == 3 and all(isinstance(e, ConcurrentUseError) and not isinstance(e, DataError) for e in got)
    for e, name in zip(got, ("push", "push_barometer", "flush"), strict=True):
        assert str(e).startswith(f"WaistTracker.{name}: called from a second thread while another thread is inside "
                                 "push/push_barometer/flush/add_fix of the same tracker")  # E256: add_fix too
        assert "decision E231; the waist trackers: E241" in str(e) and "\n" not in str(e)
    # refused calls changed nothing: the same steps as a tracker fed one thread
    ref = (WaistTracker(walk["bundle"], fs=100.0) if kind == "bundle" else
           ParamsWaistTracker(100.0, params=walk["cal"], frame=walk["frame"]))
    steps = [*tr.push(t[100:n], acc[100:n], gyr[100:n]), *tr.push(t[n:], acc[n:], gyr[n:]), *tr.flush()]
    want = [*ref.push(t[:n], acc[:n], gyr[:n]), *ref.push(t[n:], acc[n:], gyr[n:]), *ref.flush()]
    assert len(steps) == len(want) > 10 and steps[-1].x == want[-1].x and steps[-1].y == want[-1].y


def test_the_foot_and_waist_trackers_share_one_guard_e241():
    """One mechanism (no copy): both trackers' guarded calls are ``runtime.threads.one_call_at_a_time``."""
    for cls, names in ((Tracker, ("push", "flush", "add_fix")),  # decision E256: add_fix guarded too
                       (WaistTracker, ("push", "push_barometer", "flush", "add_fix")),
                       (ParamsWaistTracker, ("push", "push_barometer", "flush", "add_fix"))):
        for name in names:
            assert getattr(cls, name).__code__ is threads.one_call_at_a_time(lambda self: None).__code__, name
            assert cls._one_at_a_time == "/".join(names)
