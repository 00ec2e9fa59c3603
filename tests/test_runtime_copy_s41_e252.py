"""Decision E252 (session 41, fixer FK, review R1 finding 6): a tracker copied mid-stream (``copy.deepcopy``: a
checkpoint, a "what if" branch) gets its own E231 / E241 guard (``runtime.threads.OwnGuard``) and goes on as the
original does; a shallow copy is not refused as "a second thread"."""

from __future__ import annotations

import copy
import json
import threading

import numpy as np
import pytest

from pdrlearn.runtime import Tracker, WaistTracker, threads
from pdrlearn.sim import simulate
from pdrlearn.waist import WaistTracker as ParamsWaistTracker
from tests.runtime_helpers import synthetic_session, time_chunks


def _xy(steps) -> np.ndarray:
    return np.array([(s.x, s.y) for s in steps])


def _branch(tr, chunks, push):
    """Feed half of ``chunks``, deep-copy, then feed the rest to the copy and to the original: both ends' steps."""
    n = len(chunks) // 2
    first = [s for c in chunks[:n] for s in push(tr, c)]
    tc = copy.deepcopy(tr)
    assert tc._busy is not tr._busy and type(tc._busy) is type(threads.new_guard())
    got = [s for c in chunks[n:] for s in push(tc, c)] + tc.flush()
    want = [s for c in chunks[n:] for s in push(tr, c)] + tr.flush()
    return first, got, want


def test_a_foot_tracker_deep_copied_mid_stream_goes_on_as_the_original_e252(synthetic_bundle):
    walk = synthetic_session(30, seed=3, name="walk", turn_rad_per_step=0.2)
    chunks = [c for _, c in time_chunks(walk, 0.5)]
    first, got, want = _branch(Tracker(synthetic_bundle), chunks, lambda tr, c: tr.push(c))
    assert len(first) > 5 and len(got) == len(want) > 5
    assert _xy(got) == pytest.approx(_xy(want), abs=0) and [s.classes for s in got] == [s.classes for s in want]


@pytest.fixture(scope="module")
def waist_walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("wcopy")
    s = simulate("B", 11600, rate_hz=100.0)
    (d / "cal.json").write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                                            "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    from pdrlearn.export.waist import export_waist

    export_waist(d / "cal.json", d / "wb", frame=frame)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    k = np.array_split(np.arange(len(a.t)), 8)
    return {"bundle": d / "wb", "cal": d / "cal.json", "frame": frame,
            "chunks": [(a.t[i], a.values[i], g.values[i]) for i in k]}


@pytest.mark.parametrize("kind", ["bundle", "params"])
def test_a_waist_tracker_deep_copied_mid_stream_goes_on_as_the_original_e252(waist_walk, kind):
    """R1: "deepcopy FAILED TypeError cannot pickle '_thread.lock' object" (E241's lock)."""
    tr = (WaistTracker(waist_walk["bundle"], fs=100.0) if kind == "bundle" else
          ParamsWaistTracker(100.0, params=waist_walk["cal"], frame=waist_walk["frame"]))
    first, got, want = _branch(tr, waist_walk["chunks"], lambda tr, c: tr.push(*c))
    assert len(first) > 5 and len(got) == len(want) > 5 and _xy(got) == pytest.approx(_xy(want), abs=0)


def test_a_shallow_copy_has_its_own_guard_e252(waist_walk):
    """A shallow copy on another thread while this thread is inside the original is not "a second thread"."""
    tr = ParamsWaistTracker(100.0, params=waist_walk["cal"], frame=waist_walk["frame"])
    tc = copy.copy(tr)
    assert tc._busy is not tr._busy
    got = []
    with tr._busy:  # "this thread is inside push"
        th = threading.Thread(target=lambda: got.append(tc.flush()))
        th.start()
        th.join()
    assert got == [[]]
