"""Decision L663 (session 45): L628's x5 foot grid made cheaper without changing what it computes.

The white-noise-jerk filter runs its strides longest first and touches only the strides still running at a sample;
``wnj_displacement`` keeps each stride's final state, not the (B, L, 3, 3) history. Its batch must give every stride
what the stride gets on its own, whatever the other strides' lengths, ZUPT samples, extra noise or intervals.
"""

from __future__ import annotations

import tracemalloc

import numpy as np

from pdrlearn.displace import _kernels as K
from pdrlearn.kernels.strapdown import cross, qrotate


def _ragged_batch(seed: int = 3, n: int = 9, L: int = 140):
    rng = np.random.default_rng(seed)
    lengths = rng.integers(20, L + 1, n)
    lengths[2] = L  # the longest stride is not the first row: the batch is reordered inside
    mask = np.arange(L)[None, :] < lengths[:, None]
    a = rng.normal(0.0, 3.0, (n, L, 3)) * mask[:, :, None]
    zupt = (rng.random((n, L)) < 0.15) & mask
    zupt[:, 0] = True
    zupt[np.arange(n), lengths - 1] = True
    q_vel = 1e-4 * rng.random((n, L))
    return a, mask, zupt, q_vel, lengths


def test_each_stride_of_a_ragged_batch_gets_what_it_gets_alone_l663():
    a, mask, zupt, q_vel, lengths = _ragged_batch()
    batch = K.wnj_displacement(a, mask, 0.01, zupt_at=zupt, q_vel=q_vel)
    alone = np.vstack([K.wnj_displacement(a[b:b + 1, :n], mask[b:b + 1, :n], 0.01, zupt_at=zupt[b:b + 1, :n],
                                          q_vel=q_vel[b:b + 1, :n]) for b, n in enumerate(lengths)])
    np.testing.assert_allclose(batch, alone, rtol=0, atol=1e-12)
    # the whole filtered history agrees at every valid sample too (smooth=False keeps it)
    full = K.wnj_kalman(a, mask, 0.01, zupt_at=zupt, q_vel=q_vel, smooth=False)
    for b, n in enumerate(lengths):
        one = K.wnj_kalman(a[b:b + 1, :n], mask[b:b + 1, :n], 0.01, zupt_at=zupt[b:b + 1, :n],
                           q_vel=q_vel[b:b + 1, :n], smooth=False)
        np.testing.assert_allclose(full[b, :n], one[0], rtol=0, atol=1e-12)


def test_per_step_intervals_and_padded_samples_inside_a_row_l663():
    a, mask, zupt, q_vel, lengths = _ragged_batch(seed=5)
    rng = np.random.default_rng(7)
    dt = np.where(mask[:, 1:], 0.01 * (1.0 + rng.random((len(a), a.shape[1] - 1))), 0.0)  # decision L83's steps
    got = K.wnj_displacement(a, mask, dt, zupt_at=zupt)
    alone = np.vstack([K.wnj_displacement(a[b:b + 1, :n], mask[b:b + 1, :n], dt[b:b + 1, :n - 1],
                                          zupt_at=zupt[b:b + 1, :n]) for b, n in enumerate(lengths)])
    np.testing.assert_allclose(got, alone, rtol=0, atol=1e-12)
    holed = mask.copy()
    holed[0, 5:8] = False  # a row with invalid samples before its end keeps its state there
    full = K.wnj_kalman(a, holed, 0.01, zupt_at=zupt, smooth=False)
    np.testing.assert_array_equal(full[0, 5:8], np.repeat(full[0, 4:5], 3, axis=0))


def test_the_displacement_keeps_no_filter_history_l663():
    a, mask, zupt, q_vel, _ = _ragged_batch(seed=11, n=120, L=400)
    K.wnj_displacement(a, mask, 0.01, zupt_at=zupt, q_vel=q_vel)  # warm-up
    tracemalloc.start()
    K.wnj_displacement(a, mask, 0.01, zupt_at=zupt, q_vel=q_vel)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    history = a.nbytes * 3  # the (B, L, 3 axes, 3 states) filtered states the former code kept
    assert peak < history, (peak, history)


def test_cross_and_rotation_are_the_former_formulas_l663():
    rng = np.random.default_rng(1)
    u, v = rng.normal(size=(4, 50, 3)), rng.normal(size=(4, 50, 3))
    np.testing.assert_array_equal(cross(u, v), np.cross(u, v))
    np.testing.assert_array_equal(cross(u, v[0, 0]), np.cross(u, v[0, 0]))  # broadcast
    q = rng.normal(size=(4, 50, 4))
    q /= np.linalg.norm(q, axis=2, keepdims=True)
    w, qv = q[..., :1], q[..., 1:]
    t = 2.0 * np.cross(qv, v)
    np.testing.assert_array_equal(qrotate(q, v), v + w * t + np.cross(qv, t))
    f = rng.normal(size=(4, 3))
    np.testing.assert_array_equal(qrotate(q, f[:, None, :]), qrotate(q, np.repeat(f[:, None, :], 50, axis=1)))
