"""Decision W166: W131's ``contact_shift`` inside W31's decision window (``realtime_contact_shift``) -- measured, not
adopted, an option: off by default the realtime contacts are those before W166; with it the realtime replay drops
HA002 Test11's three weight shifts, the live tracker equals that replay whatever the push chunks, and a waist bundle
carries it to the lean runtime."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.export.waist import export_waist
from pdrlearn.io import read_session
from pdrlearn.runtime import WaistTracker as RuntimeWaistTracker
from pdrlearn.runtime import load_waist_bundle
from pdrlearn.sim import simulate
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.events import InitialContactDetector
from pdrlearn.waist.live import unapplied_options_line
from pdrlearn.waist.params import WaistParams
from tests.conftest import external_session
from tests.runtime_helpers import push_waist

_CACHE: dict = {}


def _ha002():
    if "s" not in _CACHE:
        _CACHE["s"] = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    return _CACHE["s"]


def _replay(**kw):
    key = repr(sorted(kw.items()))
    if key not in _CACHE:
        _CACHE[key] = track_waist(_ha002(), pipeline="waist-pendulum", realtime=True, **kw).steps
    return _CACHE[key]


def test_off_by_default_and_the_option_drops_ha002s_weight_shifts():
    """The default realtime detector is the one before W166; the option drops exactly the contacts printed after
    W166's measurement (13.61, 72.30, 154.32 s), no other."""
    assert OPTION_DEFAULTS["realtime_contact_shift"] is False and InitialContactDetector().realtime_shift is False
    assert InitialContactDetector(realtime=True).rule_settings()["contact_shift"] is False
    assert InitialContactDetector(realtime=True, realtime_shift=True).rule_settings()["contact_shift"] is True
    assert InitialContactDetector(realtime=True, realtime_shift=True, contact_shift=False).rule_settings()[
        "contact_shift"] is False
    off, on = _replay(), _replay(realtime_contact_shift=True)
    np.testing.assert_array_equal(off["event_s"], _replay(realtime_contact_shift=False)["event_s"])
    gone = sorted(set(np.round(off["event_s"], 2)) - set(np.round(on["event_s"], 2)))
    assert gone == [13.61, 72.3, 154.32] and len(off) - len(on) == 3


@pytest.mark.parametrize("how", ["all", "random"])
def test_the_live_tracker_with_the_option_equals_the_replay(how):
    s = _ha002()
    n = len(s["wAccelerometer"].t)
    chunks = [n] if how == "all" else list(np.random.default_rng(6).integers(1, 400, 4000))
    p = WaistParams(leg_m=0.9, options={"realtime_contact_shift": True})
    tr = WaistTracker(s["wAccelerometer"].rate_hz, params=p, meta=s.meta, frame=s.require_frame("waist"),
                      merge_fragments=False)
    out = push_waist(tr, s, chunks)
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True, params=p, merge_fragments=False).steps
    assert len(out) == len(ref) == len(_replay(realtime_contact_shift=True))
    np.testing.assert_array_equal([o.t for o in out], ref["event_s"])
    np.testing.assert_allclose([o.length_m for o in out], ref["length_m"], atol=1e-9, rtol=0)
    assert "contact_shift" not in (unapplied_options_line(p) or "")  # applied live: not named by E107's line


def test_an_exported_bundle_carries_the_option_to_the_runtime(tmp_path):
    s = _ha002()
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    cal = calibrate([simulate("A", 401, rate_hz=100.0)], "waist-pendulum", distances=[20.0])
    cal.save(tmp_path / "cal.json")
    d = json.loads((tmp_path / "cal.json").read_text())
    d["options"] = {**(d.get("options") or {}), "realtime_contact_shift": True}
    (tmp_path / "on.json").write_text(json.dumps(d))
    export_waist(tmp_path / "on.json", tmp_path / "wb", frame=frame)
    b = load_waist_bundle(tmp_path / "wb")
    assert b.options["realtime_contact_shift"] is True
    out = push_waist(RuntimeWaistTracker(b, fs=100.0), s, list(np.random.default_rng(8).integers(1, 300, 6000)))
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True, params=str(tmp_path / "on.json")).steps
    np.testing.assert_array_equal([o.t for o in out], ref["event_s"])
    assert len(out) == len(_replay(realtime_contact_shift=True))
    export_waist(tmp_path / "cal.json", tmp_path / "wb0", frame=frame)
    assert load_waist_bundle(tmp_path / "wb0").options["realtime_contact_shift"] is False
