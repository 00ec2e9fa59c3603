"""Decision E20 (docs/decisions/export.md): fewer instructions in the per-step kernels, the same numbers.

Each rewritten piece is pinned against the code it replaces (copied here as the reference), bit for bit.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.kernels import rotation as KR
from pdrlearn.kernels import stride as SK
from pdrlearn.kernels import window as KW


def _twist_e19(R):
    """kernels.window.twist_about_z before E20 (max over a key function)."""
    (a, b, c), (d, e, f), (g, h, i) = R.tolist() if isinstance(R, np.ndarray) else R
    sq = (1.0 + a + e + i, 1.0 + a - e - i, 1.0 - a + e - i, 1.0 - a - e + i)
    k = max(range(4), key=sq.__getitem__)
    m = 2.0 * math.sqrt(sq[k])
    if k == 0:
        qw, qz = 0.25 * m, (d - b) / m
    elif k == 1:
        qw, qz = (h - f) / m, (c + g) / m
    elif k == 2:
        qw, qz = (c - g) / m, (f + h) / m
    else:
        qw, qz = (d - b) / m, 0.25 * m
    return 2.0 * math.atan2(qz if qw >= 0 else -qz, abs(qw))


def _rotations(rng, n):
    w = rng.normal(size=(n, 3)) * rng.uniform(0.0, math.pi, size=(n, 1))
    return KR.rotvec_to_matrix(w)


def test_twist_about_z_picks_the_same_square_as_max():
    rng = np.random.default_rng(20)
    Rs = list(_rotations(rng, 3000))
    # ties and half-turns: identity, 180 deg about x / y / z, 90 deg about z, and permutation-like matrices
    Rs += [np.eye(3), np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0]),
           np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), np.zeros((3, 3)),
           np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
           np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])]  # 180 deg about (1, 1, 0): a tie
    for R in Rs:
        for arg in (R, R.tolist()):
            got, want = KW.twist_about_z(arg), _twist_e19(arg)
            assert got == want or (math.isnan(got) and math.isnan(want))


def _coning_e19(t, Y, s=0):
    w = Y[s:, 1]
    if w.shape[0] < 2:
        return 0.0
    ts = t[s:]
    dt = ts[1:] - ts[:-1]
    dt *= dt
    p, q = (dt @ (w[:-1, :2] * w[1:, 1::-1])).tolist()
    return KW.CONING_COEF * (p - q)


def _stride_headings_e19(forward_s, acc, Y, s=0, t=None):
    fwd = np.asarray(forward_s, dtype=float).tolist()
    ys = np.asarray(Y[s], dtype=float).tolist()
    Rs = KW._attitude(fwd, np.asarray(acc[s], dtype=float).tolist(), ys[2], ys[0])
    psi0 = math.atan2(ys[2][1], ys[2][0]) if Rs is None else _twist_e19(Rs)
    if s == 0 and len(Y) == 1:
        return 0.0, psi0
    ye = np.asarray(Y[-1], dtype=float).tolist()
    Re = KW._attitude(fwd, np.asarray(acc[-1], dtype=float).tolist(), ye[2], ye[0])
    if Rs is None or Re is None:
        f, g = ys[2], ye[2]
        d = math.atan2(f[0] * g[1] - f[1] * g[0], f[0] * g[0] + f[1] * g[1])
    else:
        R = [[sum(Re[i][k] * Rs[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
        d = _twist_e19(R)
    # decision L690 (session 46): the twist on the branch of the levelled vertical rate's integral, as the kernel's
    return (d if t is None else KW._unwrapped(d + _coning_e19(t, Y, s), t, Y, s)), psi0


def test_stride_headings_and_coning_unchanged_with_the_axis_as_array_or_list():
    rng = np.random.default_rng(5)
    fwd = np.array([0.9, 0.1, -0.42])
    for n in (1, 2, 3, 21, 40):
        for _ in range(30):
            acc = rng.normal(size=(n, 3)) + [0.0, 0.0, 9.8]
            Y = rng.normal(size=(n, 3, 3))
            t = np.cumsum(rng.uniform(0.04, 0.06, size=n))
            for s in ((0, 1) if n > 2 else (0,)):
                want = _stride_headings_e19(fwd, acc, Y, s, t)
                assert KW.stride_headings(fwd, acc, Y, s, t) == want
                assert KW.stride_headings(fwd.tolist(), acc, Y, s, t) == want
                assert KW.coning_yaw(t, Y, s) == _coning_e19(t, Y, s)
    # a degenerate attitude (a zeroed sample) takes the forward axis's heading, as before
    acc = rng.normal(size=(5, 3))
    acc[0] = 0.0
    Y = rng.normal(size=(5, 3, 3))
    assert KW.stride_headings(fwd, acc, Y, 0) == _stride_headings_e19(fwd, acc, Y, 0)


def test_gravity_rotation_xyz_flat_construction_is_unchanged():
    rng = np.random.default_rng(3)
    for g in rng.normal(size=(500, 3)) * [1.0, 1.0, 5.0]:
        gx, gy, gz = g.tolist()
        n = math.sqrt(gx * gx + gy * gy + gz * gz)
        a0, a1, c = gx / n, gy / n, gz / n
        s = math.sqrt(a1 * a1 + a0 * a0)
        k0, k1 = a1 / s, -a0 / s
        b = 1.0 - c
        want = np.array([[1.0 - b * k1 * k1, b * k0 * k1, s * k1],
                         [b * k0 * k1, 1.0 - b * k0 * k0, -s * k0],
                         [-s * k1, s * k0, 1.0 - b * (k0 * k0 + k1 * k1)]])
        got = KR.gravity_rotation_xyz(gx, gy, gz)
        assert got.shape == (3, 3) and got.flags.c_contiguous
        assert np.array_equal(got, want)


def test_dot_products_equal_matmul_in_the_stride_kernel():
    rng = np.random.default_rng(11)
    for n in (2, 3, 22, 40, 300):
        t = np.cumsum(rng.uniform(0.004, 0.06, size=n)) + 1e4
        acc = rng.normal(size=(n, 3))
        tr = t - t[0]
        lo, hi = tr[:-1], tr[1:]
        w = (0.5 * tr[-1].item() - 0.5 * (lo + hi)) * (hi - lo)
        assert np.array_equal(SK.zupt_displacement(t, acc), (0.5 * w) @ (acc[1:] + acc[:-1]))
        rate = rng.normal(size=n)
        tt = np.minimum(np.maximum(t, t[1]), t[-2])
        r = KW.interp(tt, t, rate)
        assert SK.yaw_change(t, rate, float(t[1]), float(t[-2])) == 0.5 * float((r[1:] + r[:-1]) @ (tt[1:] - tt[:-1]))


def test_rest_reference_median_on_floats_is_unchanged():
    from pdrlearn.kernels import stats as KS

    rng = np.random.default_rng(8)
    for n in (1, 2, 3, 8, 21, 40, 79):
        for _ in range(40):
            a = rng.normal(9.8, 0.5, size=n)
            g = np.abs(rng.normal(size=n))
            g[-1] = g[0]  # a tie in the quiet order
            k = max(1, int(KS.REST_QUIET_FRACTION * n))
            q = a[g.argsort(kind="stable")[:k]]
            q.sort()
            want = float(0.5 * (q[(k - 1) // 2] + q[k // 2]))
            got = KS.rest_reference(a, g)
            assert type(got) is float and got == want
