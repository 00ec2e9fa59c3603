"""Decision W301 (session 32 review item 2): ``lying_heading`` (true by default, W271) acts only on the offline gyro
heading with ``integrate_stops``. A ``--realtime`` or ``waist-pll`` track keeps W72's vertical rate through lying;
W193's line names the option there when the PARAMS.json gives it true, and says nothing when it is left at its
default (W271: not a line on every realtime track)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import OPTION_DEFAULTS, ignored_options_line, track_waist

FS = 20.0


def _w193(res) -> list[str]:
    return [w for w in res.info["warnings"] if "decision W193" in w]


@pytest.fixture(scope="module")
def lying():
    route = parse_route("stand:3, straight:8, lie:120:60, straight:8, stand:3")
    return simulate_path(route, UserProfile.from_seed(6700), rate_hz=FS, seed=1)


def _track(session, options, **kw):
    logging.disable(logging.WARNING)
    try:
        return track_waist(session, params=None if options is None else {"options": options}, **kw)
    finally:
        logging.disable(logging.NOTSET)


def test_given_true_where_it_does_nothing_is_named_w301(lying):
    for kw in ({"pipeline": "waist-pendulum", "realtime": True}, {"pipeline": "waist-pll"}):
        on = _track(lying, {"lying_heading": True}, **kw)
        off = _track(lying, {"lying_heading": False}, **kw)
        default = _track(lying, None, **kw)
        (line,) = _w193(on)
        assert "lying_heading=true applies to the offline gyro heading with integrate_stops" in line
        assert _w193(off) == [] and _w193(default) == []  # false and the default: no line (W199, W271)
        xy = on.trajectory[["x", "y"]].to_numpy(float)  # the old heading through lying, as the line says
        assert np.array_equal(xy, off.trajectory[["x", "y"]].to_numpy(float))


def test_given_true_where_it_acts_is_not_named_w301(lying):
    on = _track(lying, {"lying_heading": True}, pipeline="waist-pendulum")
    off = _track(lying, {"lying_heading": False}, pipeline="waist-pendulum")
    assert _w193(on) == []
    assert not np.array_equal(on.trajectory[["x", "y"]].to_numpy(float), off.trajectory[["x", "y"]].to_numpy(float))


def test_an_explicit_default_is_named_only_where_it_does_nothing_w301():
    o = dict(OPTION_DEFAULTS)
    assert ignored_options_line(o, "waist-pendulum", True, "gyro", False, True) is None
    line = ignored_options_line(o, "waist-pendulum", True, "gyro", False, True, explicit={"lying_heading"})
    assert line is not None and "lying_heading=true" in line and "--realtime" in line
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True, explicit={"lying_heading"}) is None
    o["lying_heading"] = False
    assert ignored_options_line(o, "waist-pll", False, "ahe", False, True, explicit={"lying_heading"}) is None
