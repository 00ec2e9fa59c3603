"""Decision L83: the offline foot integrates each stride step over its own sample interval."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.displace import _kernels as K
from pdrlearn.displace.foot import FootDisplacement
from pdrlearn.io import read_session
from pdrlearn.io.plasys import write_session
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.plasys import track_plasys


def _walk(tmp_path, drop_rate: float, name: str, rate_hz: float = 100.0):
    sim = simulate("walk", 2, rate_hz=rate_hz, seed=0, length_m=20.0, drop_rate=drop_rate)
    return read_session(write_session(sim, tmp_path / name)), float(sim.steps["length_m"].sum())


def _track(session, timestamps: bool):
    return track_plasys(session, params={"timestamps": timestamps})


def test_scattered_drops_track_within_the_bound_on_the_timestamps(tmp_path):
    clean, truth = _walk(tmp_path, 0.0, "clean")
    dropped, _ = _walk(tmp_path, 0.03, "dropped")
    d_clean = _track(clean, True).distance_m
    d_ts = _track(dropped, True).distance_m
    d_fixed = _track(dropped, False).distance_m
    assert abs(d_ts - d_clean) / truth < 0.015  # L83's bound per walk: 1.5 pp
    assert (d_clean - d_fixed) / truth > 0.03  # the fixed interval loses about one period per missing sample


def test_uniform_clock_is_bit_identical(tmp_path):
    clean, _ = _walk(tmp_path, 0.0, "clean", rate_hz=20.0)
    a, b = _track(clean, True), _track(clean, False)
    assert a.distance_m == b.distance_m
    assert a.trajectory.equals(b.trajectory)


def test_per_step_intervals_equal_the_scalar_on_a_uniform_grid():
    rng = np.random.default_rng(0)
    B, L = 4, 30
    a = rng.normal(size=(B, L, 3))
    mask = np.ones((B, L), dtype=bool)
    mask[1, 20:] = False
    dt = 0.01
    steps = np.where(mask[:, 1:], dt, 0.0)
    z = K.zupt_mask(np.zeros(B * L, dtype=bool), np.arange(B * L).reshape(B, L), mask)
    assert np.allclose(K.wnj_displacement(a, mask, steps, zupt_at=z), K.wnj_displacement(a, mask, dt, zupt_at=z),
                       atol=1e-12)
    assert np.allclose(K.double_integrate(a, mask, steps), K.double_integrate(a, mask, dt), atol=1e-12)
    gyr = rng.normal(size=(B * L, 3))
    idx, m2 = K.stride_index(np.arange(B) * L, np.arange(B) * L + L - 1)
    g = np.tile([0.0, 0.0, 9.81], (B, 1))
    assert np.allclose(K.stride_attitude(gyr, np.where(m2[:, 1:], dt, 0.0), idx, m2, g),
                       K.stride_attitude(gyr, dt, idx, m2, g), atol=1e-12)


def test_a_missing_sample_counts_its_time():
    # constant acceleration 1 m/s^2 from rest for 1 s at 100 Hz, sample 50 missing: 0.5 m on the timestamps
    t = np.delete(np.arange(101) * 0.01, 50)
    a = np.zeros((1, len(t), 3))
    a[0, :, 0] = 1.0
    mask = np.ones((1, len(t)), dtype=bool)
    steps = np.diff(t)[None, :]
    assert K.double_integrate(a, mask, steps, zupt_end=False)[0, 0] == pytest.approx(0.5, abs=1e-9)
    assert K.double_integrate(a, mask, 0.01, zupt_end=False)[0, 0] == pytest.approx(0.5 * 0.99 ** 2, abs=1e-9)


def test_smoother_refuses_per_step_intervals():
    with pytest.raises(ValueError, match="per-step"):
        K.wnj_kalman(np.zeros((1, 5)), np.ones((1, 5), dtype=bool), np.full((1, 4), 0.01), smooth=True)


def test_timestamps_is_a_foot_setting():
    assert "timestamps" in FootDisplacement().__dict__
