"""Decision L84: the waist magnetometer's horizontal hard-iron offset fitted on a walk that turns."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.orient import WaistHeading, wrap_angle
from pdrlearn.orient._kernels import fit_horizontal_hard_iron, level_axes, tilt_compensated_heading
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track import get_pipeline

G = 9.81
M_NAV = np.array([0.0, 45.0 * np.cos(np.radians(55.0)), -45.0 * np.sin(np.radians(55.0))])  # ENU, uT


def _bodies(yaw: np.ndarray, rng: np.random.Generator) -> Rotation:
    n = len(yaw)
    return Rotation.from_euler("ZYX", np.column_stack([yaw, rng.uniform(-0.05, 0.05, n),
                                                       rng.uniform(-0.05, 0.05, n)]))


def test_fit_recovers_the_offset_only_when_the_walk_turns():
    rng = np.random.default_rng(3)
    b = np.array([-4.7, 0.3, 0.0])  # uT, body FLU (scenario A user 8's forward-axis offset)
    c = 0.4  # unknown absolute offset of the relative heading
    psi = np.linspace(0.0, 2 * np.pi, 60, endpoint=False)
    R = _bodies(psi + c, rng)
    acc = R.inv().apply([0.0, 0.0, G])
    mag = R.inv().apply(M_NAV) + b
    _, fwd, left = level_axes(acc)
    est, field, resultant = fit_horizontal_hard_iron(np.sum(mag * fwd, 1), np.sum(mag * left, 1), psi)
    assert resultant < 0.01
    np.testing.assert_allclose(est, b[:2], atol=0.1)
    assert field == pytest.approx(45.0 * np.cos(np.radians(55.0)), abs=0.2)
    # a straight walk: one heading, nothing separates the offset from the heading
    psi0 = np.zeros(30)
    R0 = _bodies(psi0 + c, rng)
    mag0 = R0.inv().apply(M_NAV) + b
    _, f0, l0 = level_axes(R0.inv().apply([0.0, 0.0, G]))
    assert fit_horizontal_hard_iron(np.sum(mag0 * f0, 1), np.sum(mag0 * l0, 1), psi0)[2] > 0.999


def test_waist_heading_subtracts_the_given_offset():
    yaw = np.full(40, 0.3)
    R = Rotation.from_euler("Z", yaw[:, None])
    acc = R.inv().apply([0.0, 0.0, G])
    b = np.array([-4.7, 0.3, 1.0])
    mag = R.inv().apply(M_NAV) + b
    t = np.arange(40) / 20.0
    biased = WaistHeading().estimate(t, acc, np.zeros((40, 3)), mag)
    assert abs(wrap_angle(biased.compass_[0] - 0.3)) > 0.1  # atan(4.7 / 25.8) ~ 0.18 rad
    fixed = WaistHeading(hard_iron_ut=b).estimate(t, acc, np.zeros((40, 3)), mag)
    np.testing.assert_allclose(fixed.compass_, tilt_compensated_heading(acc, R.inv().apply(M_NAV)), atol=1e-9)


def _walk(route: str, offset_sensor: np.ndarray):
    s = simulate_path(parse_route(route), UserProfile.from_seed(3), seed=1, noise=False)
    m = s.streams["wMagneticField"]
    m.values = m.values + offset_sensor  # a hard-iron offset in the waist's sensor axes (x left, y up, z fwd)
    return s


def test_track_fits_the_hard_iron_on_a_turning_walk_not_on_a_straight_one():
    plasys = get_pipeline("plasys")
    offset = np.array([0.3, 0.0, -4.7])  # sensor x = left, z = forward: FLU (-4.7, 0.3, 0)
    route = "straight:5, curve:90:1.5, straight:5, curve:90:1.5, straight:5, curve:90:1.5, straight:5"
    loop, clean = _walk(route, offset), _walk(route, np.zeros(3))
    hi = plasys(loop, hard_iron_fit=True).info["hard_iron"]
    assert hi["applied"] and hi["resultant"] < 0.5
    # the exact physics alone fits about 1 uT (the curves' centripetal tilt, L84): the injected offset adds itself
    base = plasys(clean, hard_iron_fit=True).info["hard_iron"]["offset_ut"]
    np.testing.assert_allclose(np.subtract(hi["offset_ut"], base), [-4.7, 0.3], atol=0.2)
    assert plasys(loop).info["hard_iron"] is None  # off by default (L84 not adopted)
    straight = _walk("straight:15", offset)
    hs = plasys(straight, hard_iron_fit=True).info["hard_iron"]
    assert not hs["applied"] and "turns too little" in hs["reason"]
