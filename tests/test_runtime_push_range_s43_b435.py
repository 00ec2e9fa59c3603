"""Decision B435 (session 43, implementer I3; docs/decisions/bad-input.md): ``Tracker.push`` refuses a value beyond any
sensor's range with B425's one line (the sample's time for its line), after B119's wrong-unit guard, so that a 1e308
pushed live is never a NaN track and a stream in another unit keeps its wrong-unit line."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime import Tracker, load_bundle
from tests.runtime_helpers import synthetic_session

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # the shipped bundle
SENSORS = ["fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"]


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


@pytest.fixture(scope="module")
def walk():
    s = synthetic_session(10, seed=5)
    return {n: (s.streams[n].t, s.streams[n].values) for n in SENSORS}


def _chunks(walk, chunk_s=1.0):
    t = walk["fAccelerometer"][0]
    for c in np.arange(t[0], t[-1] + chunk_s, chunk_s):
        yield {n: (tt[(tt >= c) & (tt < c + chunk_s)], v[(tt >= c) & (tt < c + chunk_s)])
               for n, (tt, v) in walk.items()}


def _bad(walk, name="fAccelerometer", i=140, value=1e308):
    w = {n: (t, v.copy()) for n, (t, v) in walk.items()}
    w[name][1][i, 0] = value
    return w


def test_an_absurd_chunked_sample_is_b425s_line_b435(bundle, walk):
    tr = Tracker(bundle, sensors=SENSORS)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy overflow warning on the way
        with pytest.raises(DataError) as e:
            for push in _chunks(_bad(walk)):
                tr.push(push)
    t = walk["fAccelerometer"][0][140]
    assert str(e.value) == (f"fAccelerometer (pushed to the Tracker): 1 sample(s) with a value beyond any "
                            f"accelerometer's range (first at t = {t:.3f} s: x = 1e+308; the limit is 2000 m/s^2, "
                            "decision B425): a corrupt sample; drop those samples before pushing")


def test_an_absurd_sample_pushed_alone_is_refused_and_changes_nothing_b435(bundle, walk):
    """The one-sample path (E16, E17), with a value whose sum stays finite (1e300): it had been appended unchecked."""
    tr = Tracker(bundle, sensors=SENSORS)
    events = sorted((float(t[i]), n, i) for n, (t, _) in walk.items() for i in range(len(t)))
    bad = _bad(walk, "fGyroscope", 150, -1e300)
    steps = []
    for _, n, i in events:
        t, v = bad[n]
        if n == "fGyroscope" and i == 150:
            with pytest.raises(DataError, match=r"^fGyroscope \(pushed to the Tracker\): 1 sample\(s\) with a "
                                                r"value beyond any gyroscope's range \(first at t = [0-9.]+ s: "
                                                r"x = -1e\+300;"):
                tr.push({n: (t[i:i + 1], v[i:i + 1])})
            v = walk[n][1]  # the push was refused whole (E29): the clean sample is taken after it
        steps += tr.push({n: (t[i:i + 1], v[i:i + 1])})
    steps += tr.flush()
    assert steps and all(np.isfinite([s.x, s.y]).all() for s in steps)


def test_an_infinite_sample_keeps_b9s_line_b435(bundle, walk):
    tr = Tracker(bundle, sensors=SENSORS)
    with pytest.raises(DataError, match=r"^fAccelerometer: pushed samples contain NaN/inf"):
        for push in _chunks(_bad(walk, value=np.inf)):
            tr.push(push)


def test_a_stream_in_counts_keeps_its_wrong_unit_line_b435(bundle, walk):
    """Counts at 2048 per g pushed as m/s^2 read ~2048 at rest, beyond the 2000 m/s^2 limit from the first sample:
    B119's unit line speaks first, though its 5 s window is not complete."""
    w = {**walk, "fAccelerometer": (walk["fAccelerometer"][0], walk["fAccelerometer"][1] * (2048 / 9.80665))}
    tr = Tracker(bundle, sensors=SENSORS)
    with pytest.raises(DataError, match=r"^fAccelerometer \(its first [0-9.]+ s pushed to the Tracker, decision "
                                        r"B119\): median \|acc\| is [0-9]+, which looks like raw counts"):
        for push in _chunks(w):
            tr.push(push)


def test_without_the_input_checks_the_range_is_still_refused_b435(bundle, walk):
    tr = Tracker(bundle, sensors=SENSORS, check_input=False)
    with pytest.raises(DataError, match=r"^fAccelerometer \(pushed to the Tracker\): 1 sample\(s\) with a value"):
        for push in _chunks(_bad(walk)):
            tr.push(push)
