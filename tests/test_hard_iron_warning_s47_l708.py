"""Decision L708 (trace L707): a fused foot track warns when its walk's turns show a waist hard-iron offset that
turns the heading by more than 5 deg; a straight walk cannot show it and stays quiet."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track import get_pipeline
from pdrlearn.track.hard_iron_check import HARD_IRON_WARN_DEG, hard_iron_amplitude_deg

LOOP = "straight:8, curve:90:1.5, straight:8, curve:90:1.5, straight:8, curve:90:1.5, straight:8"


def _walk(route: str, offset_sensor) -> object:
    s = simulate_path(parse_route(route), UserProfile.from_seed(3), seed=1, noise=False)
    m = s.streams["wMagneticField"]
    m.values = m.values + np.asarray(offset_sensor, float)  # waist sensor axes: x left, y up, z forward
    return s


def _lines(result) -> list[str]:
    return [w for w in result.info.get("warnings", []) if "decision L708" in w]


def test_amplitude_kernel_l708():
    # L707: T2's user 5020, |b_h| 4.92 uT (left 2.72, forward -4.10) on a 25.81 uT horizontal field: 10.98 deg
    assert hard_iron_amplitude_deg([-4.0964, 2.7166], 25.8109) == pytest.approx(10.98, abs=0.01)
    assert hard_iron_amplitude_deg([30.0, 0.0], 25.8) == 90.0


def test_turning_walk_with_an_offset_warns_l708():
    plasys = get_pipeline("plasys")
    res = plasys(_walk(LOOP, [0.3, 0.0, -4.7]))  # FLU (-4.7, 0.3): asin(4.71 / 25.8) = 10.5 deg
    cc = res.info["compass_check"]
    assert cc["hard_iron_deg"] == pytest.approx(10.5, abs=2.0)
    assert len(_lines(res)) == 1 and "hard_iron_fit" in _lines(res)[0]
    clean = plasys(_walk(LOOP, [0.0, 0.0, 0.0]))
    assert clean.info["compass_check"]["hard_iron_deg"] < HARD_IRON_WARN_DEG and not _lines(clean)
    # with the fit subtracted (L636) the line has nothing to say
    assert not _lines(plasys(_walk(LOOP, [0.3, 0.0, -4.7]), hard_iron_fit=True))


def test_straight_walk_cannot_show_the_offset_l708():
    res = get_pipeline("plasys")(_walk("straight:20", [0.3, 0.0, -4.7]))
    assert res.info["compass_check"]["hard_iron_deg"] is None and not _lines(res)
