"""Decision E13 (runtime latency): the faster per-step kernels equal the formulas they replace."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels import rotation as KR
from pdrlearn.kernels import stats as KS
from pdrlearn.kernels import window as KW


def _attitude_reference(gyr, dt, k0, k1, r0, g_end):
    """The composed functions levelled_vectors stands for (the (n, 3, 3) attitude stack)."""
    return KS.correct_tilt_drift(KS.propagate_attitude(gyr, dt, k0, r0), g_end, k0, k1)


@pytest.mark.parametrize("n", [1, 2, 5, 24, 230])
def test_levelled_vectors_equal_the_attitude_stack(n):
    rng = np.random.default_rng(n)
    for trial in range(20):
        gyr = rng.normal(size=(n, 3)) * 3.0
        dt = rng.uniform(0.004, 0.06, size=n - 1)
        r0 = KR.gravity_rotation(rng.normal(size=3) + [0, 0, 9.0])
        k0 = int(rng.integers(0, max(1, n // 4)))
        k1 = int(rng.integers(k0, n)) if trial % 4 else k0  # k1 == k0: no tilt correction
        g_end = rng.normal(size=3) * 2 + [0.0, 0.0, 9.81]
        X = rng.normal(size=(n, 3, 3))  # rows: three vectors per sample
        want = X @ _attitude_reference(gyr, dt, k0, k1, r0, g_end).transpose(0, 2, 1)  # R_k x for each row x
        np.testing.assert_allclose(KS.levelled_vectors(gyr, dt, k0, k1, r0, g_end, X), want, rtol=0, atol=1e-12)


def test_levelled_vectors_level_and_upside_down_end_rest():
    rng = np.random.default_rng(7)
    n, dt = 12, np.full(11, 0.05)
    gyr, X = np.zeros((n, 3)), rng.normal(size=(n, 2, 3))
    r0 = np.eye(3)
    np.testing.assert_array_equal(KS.levelled_vectors(gyr, dt, 0, n - 1, r0, np.array([0, 0, 9.8]), X), X)
    rot = _attitude_reference(gyr, dt, 0, n - 1, r0, np.array([0, 0, -9.8]))  # 180 deg about x
    want = X @ rot.transpose(0, 2, 1)
    np.testing.assert_allclose(KS.levelled_vectors(gyr, dt, 0, n - 1, r0, np.array([0, 0, -9.8]), X), want,
                               atol=1e-12)
    with pytest.raises(DataError, match="gravity"):
        KS.levelled_vectors(gyr, dt, 0, n - 1, r0, np.zeros(3), X)


def test_rotvec_to_matrix_outer_product_form_equals_the_skew_form():
    rng = np.random.default_rng(3)
    w = np.vstack([rng.normal(size=(200, 3)) * s for s in (1e-3, 0.1, 1.0, 3.0)])
    K = np.zeros((len(w), 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 0] = -w[:, 2], w[:, 1], w[:, 2]
    K[:, 1, 2], K[:, 2, 0], K[:, 2, 1] = -w[:, 0], -w[:, 1], w[:, 0]
    th = np.linalg.norm(w, axis=1)[:, None, None]
    want = np.eye(3) + np.sin(th) / th * K + (1 - np.cos(th)) / th**2 * (K @ K)
    np.testing.assert_allclose(KR.rotvec_to_matrix(w), want, rtol=0, atol=1e-15)


def test_interp_is_np_interp_bit_for_bit():
    rng = np.random.default_rng(5)
    xp = np.sort(rng.uniform(0, 1, 23))
    fp = rng.normal(size=23)
    x = np.concatenate([np.linspace(-0.5, 1.5, 97), xp, [xp[0], xp[-1]]])
    assert np.array_equal(KW.interp(x, xp, fp), np.interp(x, xp, fp))
    assert KW.interp(0.37, xp, fp) == np.interp(0.37, xp, fp)


def _foot_levelled_reference(t, acc, gyr, forward_s, *, rest_search_s, heading):
    """foot_levelled as written before decision E13: the full attitude stack and one einsum per signal."""
    n = acc.shape[0]
    fs = (n - 1) / float(t[-1] - t[0])
    m = max(2, min(int(round(rest_search_s * fs)), n // 4 + 1))
    an = KS.row_norm(acc)
    h = max(0, int(round(0.02 * fs)))
    score = KS.rest_score(an, KS.row_norm(gyr), half_width=h)
    k0 = KS.rest_index(acc, gyr, 0, m, score=score)
    k1 = KS.rest_index(acc, gyr, n - m, n, score=score)
    g0 = acc[max(k0 - h, 0): k0 + h + 1].mean(axis=0)
    g1 = acc[max(k1 - h, 0): k1 + h + 1].mean(axis=0)
    r0 = KR.gravity_rotation(g0)
    rot = _attitude_reference(gyr, np.diff(t), k0, k1, r0, g1)
    a_lev = np.einsum("kij,kj->ki", rot, acc)
    a_lev[:, 2] -= np.linalg.norm(g0)
    ref = (rot[k0] @ forward_s)[:2]
    ref = ref / np.linalg.norm(ref)
    yaw = KS.heading_rotation(KS.principal_horizontal_axis(a_lev, ref) if heading == "pca" else ref)
    g_out = np.einsum("kij,kj->ki", rot, gyr) @ yaw.T
    dpsi = KW.twist_about_z(rot[-1] @ rot[0].T)  # decisions L30/L33: the turn about the vertical, first to last sample
    w = np.einsum("kij,kj->ki", rot, gyr)  # decision L35: + (5/24) sum dt^2 (w_k x w_k+1)_z of the levelled rate
    dpsi += 5.0 / 24.0 * float(np.sum(np.diff(t) ** 2 * np.cross(w[:-1], w[1:])[:, 2]))
    return a_lev @ yaw.T, g_out, an, dpsi


@pytest.mark.parametrize("rate", [20.0, 204.8])
@pytest.mark.parametrize("heading", ["pca", "declared"])
def test_foot_levelled_equals_the_attitude_stack_version(rate, heading):
    """A swinging foot between two rests, at 20 Hz and at 204.8 Hz (the +-20 ms rest mean is active)."""
    rng = np.random.default_rng(int(rate))
    t = np.arange(0.0, 1.1, 1.0 / rate)
    swing = np.clip(np.sin(np.pi * (t - 0.25) / 0.6), 0, None) * ((t > 0.25) & (t < 0.85))
    gyr = np.column_stack([0.3 * swing, 4.0 * swing * np.cos(6 * t), 0.5 * swing]) + rng.normal(0, 0.02, (len(t), 3))
    acc = np.column_stack([3.0 * swing, 0.4 * swing, 9.81 + 2.0 * swing]) + rng.normal(0, 0.05, (len(t), 3))
    fwd = np.array([1.0, 0.0, 0.0])
    got = KW.foot_levelled(t, acc, gyr, fwd, rest_search_s=0.3, heading=heading)
    want = _foot_levelled_reference(t, acc, gyr, fwd, rest_search_s=0.3, heading=heading)
    for g, w in zip(got[:3], want[:3], strict=True):
        np.testing.assert_allclose(g, w, rtol=0, atol=1e-12)
    assert got[3] == pytest.approx(want[3], abs=1e-13)


def test_stance_segmenter_norm_is_numpys_norm_bit_for_bit():
    """Decision E16: the segmenter's |w| without np.linalg.norm's wrapper is the same arithmetic."""
    rng = np.random.default_rng(7)
    for scale in (1e-6, 1.0, 30.0, 1e150):
        g = rng.normal(size=(500, 3)) * scale
        np.testing.assert_array_equal(np.sqrt(np.add.reduce(g * g, axis=1)), np.linalg.norm(g, axis=1))
    from pdrlearn.kernels.stride import StanceSegmenter

    t = np.arange(400) * 0.05
    g = np.where((np.arange(400) // 20 % 2 == 0)[:, None], 0.1, 3.0) * rng.normal(size=(400, 3))
    a, b = StanceSegmenter(), StanceSegmenter()
    assert a.update(t, g) == [s for i in range(400) for s in b.update(t[i:i + 1], g[i:i + 1])]
