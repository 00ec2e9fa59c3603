"""Decision E256 (session 42, implementer I3): ``add_fix`` refuses a bad fix in one :class:`DataError` line naming
the argument (a string, a bool, an array, a non-finite t / x / y, an accuracy or sigma <= 0 or NaN, a time more than
60 s before the first pushed sample), uses fixes given out of time order in time order (D14; late ones counted, D20),
and refuses a second thread with E231's guard. Simulated users 11780-11781 (a 30 m walk each, <= 40 s of data)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import ConcurrentUseError, DataError
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.sim import simulate
from pdrlearn.waist import WaistTracker as ParamsWaistTracker
from tests.test_runtime_threads_s41_e241 import _from_another_thread

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A foot walk as 1 s pushes, and a waist walk at 100 Hz with its calibration (E241's test's form)."""
    bundle = load_bundle(SHIPPED)
    s = simulate("walk", 11780, length_m=30)
    used = Tracker(bundle).used_sensors
    data = {n: (st.t, st.values) for n, st in s.streams.items() if n in used}
    end = max(t[-1] for t, _ in data.values())
    pushes = [{n: (t[(t >= a) & (t < a + 1.0)], v[(t >= a) & (t < a + 1.0)]) for n, (t, v) in data.items()}
              for a in np.arange(0.0, end + 1.0, 1.0)]
    w = simulate("walk", 11781, length_m=30, rate_hz=100.0)
    d = tmp_path_factory.mktemp("fixes_e256")
    (d / "cal.json").write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                                            "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    frame = ",".join(f"{k}={v}" for k, v in w.require_frame("waist").to_dict().items())
    a, g = w["wAccelerometer"], w["wGyroscope"]
    return {"bundle": bundle, "pushes": pushes, "cal": d / "cal.json", "frame": frame,
            "w": (a.t, a.values, g.values)}


def _foot(walks):
    return Tracker(walks["bundle"])


def _waist(walks):
    return ParamsWaistTracker(100.0, params=walks["cal"], frame=walks["frame"])


BAD = [  # (args, kwargs, the argument the line names)
    (("5", 1.0, 2.0), {"accuracy_m": 3.0}, "t='5' is a str"),  # float("5") accepted it before E256
    ((True, 1.0, 2.0), {"accuracy_m": 3.0}, "t=True is a bool"),
    ((1.0, None, 2.0), {"accuracy_m": 3.0}, "x=None is a NoneType"),
    ((1.0, 1.0, np.array([2.0])), {"accuracy_m": 3.0}, "y=array([2.]) is a ndarray"),
    ((float("inf"), 1.0, 2.0), {"accuracy_m": 3.0}, "t=inf is not finite"),
    ((1.0, float("nan"), 2.0), {"accuracy_m": 3.0}, "x=nan is not finite"),
    ((1.0, 1.0, -float("inf")), {"accuracy_m": 3.0}, "y=-inf is not finite"),
    ((1.0, 1.0, 2.0), {"accuracy_m": -1.0}, "accuracy_m=-1: t, x, y must be finite and the accuracy > 0 m"),
    ((1.0, 1.0, 2.0), {"accuracy_m": 0}, "accuracy_m=0: t, x, y must be finite and the accuracy > 0 m"),
    ((1.0, 1.0, 2.0), {"accuracy_m": float("nan")}, "accuracy_m=nan is not finite"),
    ((1.0, 1.0, 2.0), {"accuracy_m": "x"}, "accuracy_m='x' is a str"),  # a ValueError traceback before E256
    ((1.0, 1.0, 2.0), {"accuracy_m": [1.0, 2.0]}, "accuracy_m=[1.0, 2.0] is a list"),  # a numpy TypeError before
    ((1.0, 1.0, 2.0), {"sigma_m": -0.5}, "sigma_m=-0.5: t, x, y must be finite and the accuracy > 0 m"),
]


@pytest.mark.parametrize("kind", ["foot", "waist"])
def test_each_bad_fix_is_one_line_naming_its_argument_e256(walks, kind):
    tr = _foot(walks) if kind == "foot" else _waist(walks)
    for args, kwargs, named in BAD:
        with pytest.raises(DataError) as e:
            tr.add_fix(*args, **kwargs)
        assert str(e.value).startswith("add_fix") and named in str(e.value) and "\n" not in str(e.value), named
    assert tr.fix_stats()["fixes_read"] == 0  # nothing refused reached the filter
    tr.add_fix(np.float64(1.0), np.int64(2), 3, accuracy_m=np.float32(2.0))  # numpy and int numbers are numbers
    assert tr.fix_stats()["fixes_read"] == 1


def test_a_fix_far_before_the_first_pushed_sample_is_refused_as_another_clock_e256(walks):
    """E212's 60 s bound the other way: a fix in seconds since the app started, beside samples stamped in Unix
    time, was held and counted 'outside the tracked steps' only at flush."""
    tr = _foot(walks)
    t0 = 1.7e9
    for p in walks["pushes"][:2]:  # (the tracker holds its first push until the units' start clocks are read)
        tr.push({n: (t + t0, v) for n, (t, v) in p.items()})
    with pytest.raises(DataError, match=r"add_fix\(t=12, x=1, y=2\): t is 1699999988 s before the first pushed "
                                        r"sample \(1700000000\.0 s\): a fix on another clock\? give t in "
                                        r"seconds on the pushed samples' clock$"):
        tr.add_fix(12.0, 1.0, 2.0, accuracy_m=3.0)
    tr.add_fix(t0 - 30.0, 1.0, 2.0, accuracy_m=3.0)  # just before the track: held and counted outside (D17)
    assert tr.fix_stats()["fixes_read"] == 1
    w = _waist(walks)
    t, a, g = walks["w"]
    w.push(t[:100] + t0, a[:100], g[:100])
    with pytest.raises(DataError, match="before the first pushed sample"):
        w.add_fix(12.0, 1.0, 2.0, sigma_m=1.0)


def test_fixes_given_out_of_time_order_are_used_in_time_order_e256(walks):
    """A fix older than the last one given is not refused: while its step is not reported it is used in time order
    (the same steps as the fixes given in order, D14); once its step was reported it is counted late (D20)."""
    pushes = walks["pushes"]
    fixes = [(6.0, 3.0, 1.0, 2.0), (9.5, 6.0, 0.0, 2.0), (13.0, 9.0, -1.0, 2.0)]
    runs = []
    for order in (fixes, fixes[::-1]):
        tr = _foot(walks)
        for f in order:
            tr.add_fix(*f[:3], accuracy_m=f[3])
        runs.append([(s.x, s.y) for p in pushes for s in tr.push(p)] + [(s.x, s.y) for s in tr.flush()])
        assert tr.fix_stats()["fixes_used"] == 3
    assert runs[0] == runs[1] and len(runs[0]) > 10
    tr = _foot(walks)
    out = [s for p in pushes[:15] for s in tr.push(p)]
    tr.add_fix(out[-1].end_s + 5.0, 1.0, 1.0, accuracy_m=2.0)
    tr.add_fix(out[1].start_s + 0.01, 1.0, 1.0, accuracy_m=2.0)  # older than the last one, its step reported
    assert tr.fix_stats()["fixes_late"] == 1


@pytest.mark.parametrize("kind", ["foot", "waist"])
def test_a_second_thread_inside_add_fix_is_refused_e256(walks, kind):
    """``add_fix`` changes the fix filter's pending list that ``push`` reads and replaces: E231's guard. Before E256
    the second thread's fix went in while the other thread was inside ``push``."""
    tr = _foot(walks) if kind == "foot" else _waist(walks)
    got = _from_another_thread(tr, [lambda: tr.add_fix(1.0, 1.0, 2.0, accuracy_m=3.0)])
    assert len(got) == 1 and isinstance(got[0], ConcurrentUseError), got
    name = type(tr).__name__
    assert str(got[0]).startswith(f"{name}.add_fix: called from a second thread while another thread is inside "
                                  f"{tr._one_at_a_time} of the same tracker") and "add_fix" in tr._one_at_a_time
    assert tr.fix_stats()["fixes_read"] == 0
    tr.add_fix(1.0, 1.0, 2.0, accuracy_m=3.0)  # the same thread, nobody inside: taken
    assert tr.fix_stats()["fixes_read"] == 1
