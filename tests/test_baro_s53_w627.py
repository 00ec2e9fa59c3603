"""Decision W627: W621's noise window is at most 12 s: a barometer sampled every 5 s (0.26 m a sample) read a 17.5 s
window whose median flattened a lift ride (tests/test_floors_rides_l375.py's user 7222 at its sparsest rate: 3
floors down read as 2; that test fails without the cap)."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.barometer import altitude_m, noise_window_s


def _sparse(sigma_m: float, dt: float, n: int = 200) -> tuple[np.ndarray, np.ndarray]:
    t = np.arange(n) * dt
    h = np.random.default_rng(627).normal(0.0, sigma_m, n)
    p = np.linspace(900.0, 1100.0, 20001)  # altitude_m's inverse by interpolation (pressure falls with height)
    hp = altitude_m(p)
    return t, np.interp(h, hp[::-1], p[::-1])


def test_the_noise_window_is_capped_at_12_s_w627():
    t, p = _sparse(0.26, 5.0)
    assert noise_window_s(t, p, max_s=1e9) > 15.0  # W621's bound alone: ~17 s
    assert noise_window_s(t, p) == 12.0
    t, p = _sparse(0.27, 1.0)  # a phone's 1 Hz: W621's own window, under the cap
    assert 4.0 < noise_window_s(t, p) < 12.0
