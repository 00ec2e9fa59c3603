"""Decision W165: W134's stand steps (``pause_steps="standing"``) in the realtime replay and the live trackers: the
live steps equal the replay's whatever the push chunks, the report waits one more contact (at most W16's 1.5 s),
and a waist bundle carries the option to the lean runtime."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.export.waist import export_waist
from pdrlearn.kernels.waist import DECISION_HOP_S
from pdrlearn.kernels.waist_stream import MAX_STEP_S
from pdrlearn.runtime import WaistTracker as RuntimeWaistTracker
from pdrlearn.runtime import load_waist_bundle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.live import unapplied_options_line
from pdrlearn.waist.params import WaistParams
from tests.runtime_helpers import push_waist

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "experiments"))
from waist_pause_steps import ROUTE  # noqa: E402  (W111's daily-activity route, with stands inside walks)

_CACHE: dict = {}


def _walk():
    """User 1351 (of W122's measurement, not of W165's 3260-3299) on W111's route: steps holding a stand."""
    if "s" not in _CACHE:
        _CACHE["s"] = simulate_path(parse_route(ROUTE), UserProfile.from_seed(1351), rate_hz=100, seed=1351)
    return _CACHE["s"]


def _replay(pause):
    if pause not in _CACHE:
        _CACHE[pause] = track_waist(_walk(), pipeline="waist-pendulum", realtime=True, pause_steps=pause)
    return _CACHE[pause]


def _live(chunks, **kw):
    s = _walk()
    tr = WaistTracker(100.0, meta=s.meta, frame=s.require_frame("waist"), **kw)
    return push_waist(tr, s, chunks)


@pytest.mark.parametrize("how", ["all", "random", "one"])
def test_live_stand_steps_equal_the_realtime_replay_whatever_the_chunks(how):
    """The default (``"standing"``) shortens the steps holding a stand, live as in the replay, to rounding; off, the
    steps are the realtime track before W165."""
    s = _walk()
    n = len(s["wAccelerometer"].t)
    chunks = {"all": [n], "random": list(np.random.default_rng(4).integers(1, 300, 4000)), "one": [1] * n}[how]
    out = _live(chunks)
    st = _replay("standing").steps
    assert len(out) == len(st) > 40
    np.testing.assert_allclose([o.t for o in out], st["event_s"], atol=1e-9, rtol=0)
    np.testing.assert_allclose([o.length_m for o in out], st["length_m"], atol=1e-9, rtol=0)
    np.testing.assert_allclose([o.x for o in out], _replay("standing").trajectory["x"].to_numpy()[1:], atol=1e-9)
    shortened = st["pause_factor"].to_numpy() < 1
    assert shortened.sum() >= 3  # the route's stands inside walks
    off = _replay(False).steps
    assert "pause_factor" not in off
    L, L0 = st["length_m"].to_numpy(), off["length_m"].to_numpy()
    assert (L[shortened] < L0[shortened] - 0.05).all() and np.array_equal(L[~shortened], L0[~shortened])
    if how == "all":
        np.testing.assert_allclose([o.length_m for o in _live(chunks, pause_steps=False)], L0, atol=1e-9, rtol=0)


def _report_times(pause):
    """Each step's report time: the last sample pushed when it came out (pushes of 5 samples)."""
    s = _walk()
    a, g = s["wAccelerometer"], s["wGyroscope"]
    tr = WaistTracker(100.0, meta=s.meta, frame=s.require_frame("waist"), pause_steps=pause)
    rep = {}
    for i in range(0, len(a.t), 5):
        for o in tr.push(a.t[i:i + 5], a.values[i:i + 5], g.values[i:i + 5]):
            rep[o.t] = float(a.t[min(i + 4, len(a.t) - 1)])
    for o in tr.flush():
        rep[o.t] = float(a.t[-1])
    return rep


def test_the_added_latency_is_one_contact_at_most_max_step_s():
    """W165: with the stand test a step waits for one more contact of its sequence: never earlier than without it and
    never more than W16's 1.5 s plus W31's 0.25 s decision hop later (a contact is decided on the hop after it is
    old enough), about one step period while walking."""
    on, off = _report_times("standing"), _report_times(False)
    assert on.keys() == off.keys()
    added = np.array([on[k] - off[k] for k in on])
    assert added.min() >= 0 and added.max() <= MAX_STEP_S + DECISION_HOP_S + 1e-9
    walking = added[added > 0]
    assert walking.size > len(added) / 2 and 0.3 < np.median(walking) < 0.9


def test_an_exported_bundle_carries_the_stand_steps_to_the_runtime(tmp_path):
    """E57's bundle options carry ``pause_steps``; the lean runtime's tracker then equals the live one and the replay
    with the calibration; a calibration with ``pause_steps: false`` exports it off."""
    s = _walk()
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    cal = calibrate([simulate_path(parse_route("straight:20"), UserProfile.from_seed(1351), rate_hz=100,
                                   seed=6351)], "waist-pendulum", distances=[20.0])
    cal.save(tmp_path / "cal.json")
    export_waist(tmp_path / "cal.json", tmp_path / "wb", frame=frame)
    b = load_waist_bundle(tmp_path / "wb")
    assert b.options["pause_steps"] == "standing"
    out = push_waist(RuntimeWaistTracker(b, fs=100.0), s, list(np.random.default_rng(2).integers(1, 200, 5000)))
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True, params=str(tmp_path / "cal.json")).steps
    assert (ref["pause_factor"] < 1).sum() >= 3
    np.testing.assert_allclose([o.length_m for o in out], ref["length_m"], atol=1e-9, rtol=0)
    off = json.loads((tmp_path / "cal.json").read_text())
    off["options"] = {"pause_steps": False}
    (tmp_path / "off.json").write_text(json.dumps(off))
    export_waist(tmp_path / "off.json", tmp_path / "wb0", frame=frame)
    assert load_waist_bundle(tmp_path / "wb0").options["pause_steps"] is False


def test_the_look_ahead_values_stay_named_as_not_applied_live():
    """E107's line names ``pause_steps`` true / "progression" (W111 / W122, not applied live), not false or
    "standing" (applied, W165); a model spec with "progression" is refused in realtime, "standing" is not."""
    p = WaistParams(leg_m=0.9)
    for v, named in ((True, True), ("progression", True), (False, False), ("standing", False)):
        p.options = {"pause_steps": v}
        line = unapplied_options_line(p)
        assert (line is not None and "pause_steps" in line) is named
    with pytest.raises(DataError, match="W165"):
        track_waist(_walk(), pipeline="waist-pendulum", realtime=True, length_model="pendulum:pause_steps=progression")
    st = track_waist(_walk(), pipeline="waist-pendulum", realtime=True,
                     length_model="pendulum:pause_steps=standing").steps
    np.testing.assert_allclose(st["length_m"], _replay("standing").steps["length_m"], atol=1e-12, rtol=0)
