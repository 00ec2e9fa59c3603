"""Decisions W137, W138 (docs/decisions/waist.md): the live lower-back tracker takes the pipelines' geodetic start
and gives each contact a causal side."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import simulate
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker
from tests.runtime_helpers import push_waist

_CACHE: dict = {}


def _sim():
    if "s" not in _CACHE:
        _CACHE["s"] = simulate("B", 1, speed="slow", rate_hz=100.0)
    return _CACHE["s"]


def _live(s, chunks=None, **kw):
    a = s["wAccelerometer"]
    tr = WaistTracker(a.rate_hz, meta=s.meta, frame=s.require_frame("waist"), **kw)
    return push_waist(tr, s, chunks or [len(a.t)]), tr


def test_live_start_takes_lat_lon_as_the_pipelines():
    s = _sim()
    start = (41.178, -8.608, 12.5)
    out, tr = _live(s, start=start)
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True, start=start).trajectory
    assert len(out) == len(ref) - 1 > 20
    lat = np.array([o.lat for o in out])
    lon = np.array([o.lon for o in out])
    np.testing.assert_allclose(lat, ref["lat"].to_numpy()[1:], atol=1e-11, rtol=0)  # ~1 micrometre
    np.testing.assert_allclose(lon, ref["lon"].to_numpy()[1:], atol=1e-11, rtol=0)
    assert tr.start_altitude_m == 12.5 and abs(lat[-1] - start[0]) > 1e-5  # it moved
    same, _ = _live(s, start="41.178,-8.608")  # the CLI's text form
    assert [o.lat for o in same] == list(lat)
    plain, _ = _live(s)
    assert {o.lat for o in plain} == {None} and [o.x for o in plain] == [o.x for o in out]


@pytest.mark.parametrize("start, match", [
    ((41.1, 200.0), r"^start=\(41.1, 200.0\): latitude must be in \[-90, 90\] and longitude in \[-180, 180\]"),
    ((41.1,), r"^start=\(41.1,\): pass \(lat, lon\) or \(lat, lon, alt\)"),
    ("41.1;x", r"^--start '41.1;x': expected LAT,LON\[,ALT\]"),
])
def test_a_bad_live_start_is_one_line(start, match):
    with pytest.raises(DataError, match=match):
        WaistTracker(100.0, frame="x=up,y=right,z=forward", start=start)


def test_live_sides_are_the_simulated_feet_and_do_not_depend_on_the_chunks():
    s = simulate("ABCD"[1906 % 4], 1906, rate_hz=100.0)  # W129's test user (W138 was measured on 2270-2289)
    assert {o.side for o in _live(s)[0]} == {None}  # not adopted (W138): an option
    out, _ = _live(s, sides=True)
    sides = np.array([o.side for o in out], dtype=object)
    assert set(sides) <= {"left", "right", ""} and (sides != "").mean() > 0.8
    ics = s.extras["ics"].dropna(subset=["ic_s"])
    from pdrlearn.steps.evaluate import match_events

    i_d, i_r = match_events(np.array([o.t for o in out]), ics["ic_s"].to_numpy(float), 0.25)
    got, ref = sides[i_d], ics["foot"].astype(str).str.lower().to_numpy()[i_r]
    assert (got[got != ""] == ref[got != ""]).mean() > 0.9  # 0.918 printed (the offline side: W129)
    off = track_waist(s, pipeline="waist-pendulum").steps  # where both decide, the offline side (W20's cue, W129)
    j_l, j_o = match_events(np.array([o.t for o in out]), off["event_s"].to_numpy(float), 0.25)
    a, b = sides[j_l], off["side"].to_numpy(object)[j_o]
    both = (a != "") & (b != "")
    assert both.sum() > 50 and (a[both] == b[both]).mean() > 0.97
    chunked, _ = _live(s, list(np.random.default_rng(5).integers(1, 300, 4000)), sides=True)
    assert [o.side for o in chunked] == list(sides)
