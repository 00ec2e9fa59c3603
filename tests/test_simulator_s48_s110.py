"""Decision S110: ``--gyro-bias-model gm:TAU``, the gyroscopes' bias drift a bounded first-order Gauss-Markov
process, opt-in (S12's random walk stays the default; docs/decisions/simulator.md)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli.simulate import parse_gyro_bias_model
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.sensors import FOOT_GYR, gauss_markov


def test_the_drift_is_the_walk_pulled_back_and_bounded_at_its_stationary_sd_s110():
    rng = np.random.default_rng(15542)
    q = FOOT_GYR.bias_walk
    steps = rng.normal(0.0, q, (40_000, 2))  # S12's increments at 1 s: 40000 s, two axes
    walk, gm = np.cumsum(steps, axis=0), gauss_markov(steps, 1.0, 288.0)
    assert np.allclose(gauss_markov(steps[:1000], 1.0, 1e12), walk[:1000], atol=1e-12)  # tau -> inf: S12's walk
    assert np.abs(gm[:10] - walk[:10]).max() < 0.2 * q  # the first seconds: the same steps
    late = gm[1000:]  # past 3 tau: stationary
    sd = FOOT_GYR.bias_walk * np.sqrt(288.0 / 2)  # 0.0024 rad/s: thesis Table 6's vertical (y) offset sd
    assert 0.6 * sd < late.std() < 1.4 * sd
    assert np.abs(walk[-1]).max() > 0 and np.abs(gm).max() < 5 * sd


def test_the_option_changes_only_the_gyroscopes_and_is_recorded_s110():
    route = parse_route("stand:2, straight:4, stand:2")
    user = UserProfile.from_seed(15543)
    a = simulate_path(route, user, seed=0)
    b = simulate_path(route, user, seed=0, gyro_bias_tau_s=60.0)
    assert "gyro_bias_tau_s" not in a.meta["knobs"] and b.meta["knobs"]["gyro_bias_tau_s"] == 60.0
    assert np.array_equal(a.streams["fAccelerometer"].values, b.streams["fAccelerometer"].values)
    assert np.array_equal(a.streams["wAccelerometer"].values, b.streams["wAccelerometer"].values)
    for name in ("fGyroscope", "wGyroscope"):
        d = np.abs(a.streams[name].values - b.streams[name].values)
        assert 0 < d.max() < 0.01  # the drift's difference only, over a ~12 s walk
    with pytest.raises(DataError, match="gyro_bias_tau_s"):
        simulate_path(route, user, seed=0, gyro_bias_tau_s=-1.0)


def test_the_cli_word_s110():
    assert parse_gyro_bias_model("walk") is None and parse_gyro_bias_model("gm:288") == 288.0
    for bad in ("gm", "gm:0", "gm:x", "ou:100"):
        with pytest.raises(DataError, match="--gyro-bias-model"):
            parse_gyro_bias_model(bad)
