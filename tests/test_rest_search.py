"""Rest search of the foot step windows (pdrlearn.kernels.stats.rest_reference / rest_score / rest_index):
a stride with ~30 % rest, where a reference taken from the window's median |acc| picks a moving sample."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.features.batch import foot_levelled_batch
from pdrlearn.kernels.stats import STANDARD_GRAVITY, rest_index, rest_reference, rest_score, row_norm
from pdrlearn.kernels.window import foot_levelled

FS = 100.0  # Hz
N = 100  # one 1 s stride, mid-stance to mid-stance
REST = 15  # rest samples at each end: 30 % of the window
TILT = Rotation.from_euler("y", 20, degrees=True)  # sensor pitched 20 deg at rest


def stride(seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """t (N,), acc (N, 3) m/s^2, gyr (N, 3) rad/s of a hand-made stride: rest (tilted gravity, noise) for
    15 samples at each end; in between a loading / push-off phase (|acc| 14 m/s^2, |gyro| 0.2 rad/s) next
    to each rest, and a swing of large rates; most moving samples have |acc| ~ 14, so the window median
    |acc| is a moving value."""
    rng = np.random.default_rng(seed)
    t = np.arange(N) / FS
    g_s = TILT.inv().apply([0.0, 0.0, STANDARD_GRAVITY])  # specific force at rest, sensor frame
    acc = np.tile(g_s, (N, 1)) + rng.normal(0.0, 0.02, (N, 3))
    gyr = rng.normal(0.0, 0.005, (N, 3))
    move = np.arange(REST, N - REST)
    mag = np.full(len(move), 14.0) + rng.normal(0.0, 0.3, len(move))
    mag[20:30] = 30.0  # swing / impact peaks
    direction = Rotation.from_euler("y", np.linspace(-30, 40, len(move))[:, None], degrees=True).apply(
        g_s / STANDARD_GRAVITY)
    acc[move] = direction * mag[:, None]
    rate = np.full(len(move), 0.2)  # loading and push-off: slow rotation
    rate[6:-6] = 4.0  # swing
    gyr[move] = np.array([0.0, 1.0, 0.0]) * rate[:, None]
    return t, acc, gyr


def old_rest_index(acc: np.ndarray, gyr: np.ndarray, lo: int, hi: int) -> int:
    """The previous search: |acc| referenced to the WINDOW median |acc| (the defect)."""
    an = row_norm(acc)
    score = 0.1 * np.abs(an - np.median(an)) + row_norm(gyr)
    return lo + int(np.argmin(score[lo:hi]))


def test_old_window_median_search_picks_a_moving_sample_new_one_picks_rest():
    t, acc, gyr = stride()
    m = N // 4 + 1  # foot_levelled's search span at 100 Hz with rest_search_s=0.3
    assert np.median(row_norm(acc)) > 13.0  # less than half of the window is rest
    assert old_rest_index(acc, gyr, 0, m) >= REST  # the defect this test guards against
    assert old_rest_index(acc, gyr, N - m, N) < N - REST
    assert rest_reference(row_norm(acc), row_norm(gyr)) == pytest.approx(STANDARD_GRAVITY, abs=0.05)
    assert rest_index(acc, gyr, 0, m) < REST
    assert rest_index(acc, gyr, N - m, N) >= N - REST


def test_levelled_rest_is_level_after_the_fix():
    """Old search: the window is levelled on a push-off sample (|acc| 14): vertical acceleration at rest
    about 9.8 - 14 = -4 m/s^2; now ~0 at both rests, per-step and batch alike."""
    t, acc, gyr = stride()
    fwd = np.array([1.0, 0.0, 0.0])
    a, g, an, _ = foot_levelled(t, acc, gyr, fwd, rest_search_s=0.3, heading="pca")
    rest = np.r_[0:REST - 3, N - REST + 3:N]
    assert np.max(np.abs(a[rest, 2])) < 0.15
    ab, gb, anb = foot_levelled_batch(t[None], acc[None], gyr[None], fwd, rest_search_s=0.3, heading="pca",
                                      first_step=np.array([0]))
    np.testing.assert_allclose(ab[0], a, atol=1e-9)
    np.testing.assert_allclose(gb[0], g, atol=1e-9)


def test_neighbourhood_of_the_rest_sample_is_quiet():
    """The rest specific force is averaged over +-20 ms: a quiet sample next to motion is not chosen."""
    an = np.array([9.81, 9.81, 9.81, 9.81, 9.81, 14.0, 14.0, 14.0])
    gn = np.array([0.05, 0.05, 0.04, 0.03, 0.0, 0.2, 0.3, 0.4])
    acc = an[:, None] * np.array([0.0, 0.0, 1.0])
    assert int(np.argmin(rest_score(an, gn))) == 4
    s2 = rest_score(an, gn, half_width=2)
    assert rest_index(acc, None, 0, 8, score=s2) <= 2  # +-2 inside the quiet [0..4]
    np.testing.assert_allclose(s2[:3], [0.05, 0.05, 0.05])


def test_batch_rows_equal_single_windows():
    rng = np.random.default_rng(3)
    an = 9.8 + rng.normal(0, 3, (5, 37))
    gn = np.abs(rng.normal(0, 2, (5, 37)))
    ref = rest_reference(an, gn)
    sc = rest_score(an, gn, half_width=3)
    for b in range(5):
        assert ref[b] == rest_reference(an[b], gn[b])
        np.testing.assert_array_equal(sc[b], rest_score(an[b], gn[b], half_width=3))


def test_without_gyroscope_the_reference_is_standard_gravity():
    an = np.array([12.0, 9.6, 9.9, 13.0])
    assert rest_reference(an, None) == STANDARD_GRAVITY
    np.testing.assert_array_equal(rest_reference(np.vstack([an, an]), None), [STANDARD_GRAVITY] * 2)
    assert rest_index(an[:, None] * np.array([0.0, 0.0, 1.0]), None, 0, 4) == 2
