"""Decision W193 (trial `tour` finding 4): an option that does nothing for the chosen lower-back pipeline / mode
(``integrate_end`` on ``waist-pll`` or ``--realtime``, ``stand_veto`` / ``vault_veto`` off the offline
``waist-pendulum``) gives one line naming it and where it applies; an applied option, or one left at its default,
none."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import OPTION_DEFAULTS, ignored_options_line, track_waist


def _lines(res) -> list[str]:
    return [w for w in res.info["warnings"] if "decision W193" in w]


@pytest.fixture(scope="module")
def session():
    return simulate_path(parse_route("straight:6, turn:90"), UserProfile.from_seed(4300), seed=0)


def test_integrate_end_and_stand_veto_on_waist_pll_are_named(session):
    logging.disable(logging.WARNING)
    try:
        pll = track_waist(session, pipeline="waist-pll", params={"options": {"integrate_end": True,
                                                                             "stand_veto": True}})
        rt = track_waist(session, pipeline="waist-pendulum", realtime=True, integrate_end=True)
        pend = track_waist(session, pipeline="waist-pendulum", integrate_end=True, stand_veto=True)
        plain = track_waist(session, pipeline="waist-pll")
    finally:
        logging.disable(logging.NOTSET)
    (line,) = _lines(pll)
    assert "integrate_end=true applies to the offline gyro heading" in line and "waist-pll" in line
    assert "stand_veto=true applies to the offline waist-pendulum" in line
    (line,) = _lines(rt)
    assert "--realtime" in line and "integrate_end" in line and "stand_veto" not in line
    assert _lines(pend) == [] and _lines(plain) == []


def test_the_line_follows_each_options_scope():
    o = dict(OPTION_DEFAULTS, vault_veto="turns")
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True) is None
    assert "vault_veto=\"turns\"" in ignored_options_line(o, "waist-pendulum", True, "gyro", False, True)
    o = dict(OPTION_DEFAULTS, integrate_end=True)
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True) is None
    assert "integrate_stops off" in ignored_options_line(o, "waist-pendulum", False, "gyro", False, False)
    assert "heading ahe" in ignored_options_line(o, "waist-pendulum", False, "ahe", False, True)
    assert ignored_options_line(dict(OPTION_DEFAULTS), "waist-pll", True, "ahe", True, False) is None
