"""Decision E17 (docs/decisions/export.md): fewer calls per streamed step with the same numbers.

Each rewritten kernel is pinned against the formula it replaces (copied here as the reference): bit for bit
where the arithmetic is the same, within 1e-12 relative where it is reordered (the ZUPT displacement).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels import distance as KD
from pdrlearn.kernels import rotation as KR
from pdrlearn.kernels import stats as KS
from pdrlearn.kernels import stride as SK
from pdrlearn.kernels import window as KW


def _zupt_cumsum(t, acc):
    """The pre-E17 ZUPT displacement: cumulative trapezoid velocity, linear drift removal, trapezoid."""
    if len(t) < 2 or not t[-1] > t[0]:
        return np.zeros(3)
    dt = np.diff(t)[:, None]
    v = np.zeros_like(acc)
    v[1:] = np.cumsum(0.5 * (acc[1:] + acc[:-1]) * dt, axis=0)
    v -= ((t - t[0]) / (t[-1] - t[0]))[:, None] * v[-1]
    return np.sum(0.5 * (v[1:] + v[:-1]) * dt, axis=0)


def _yaw_change_sum(t, rate, t0, t1):
    tt = np.clip(t, t0, t1)
    r = np.interp(tt, t, rate)
    return float(np.sum(0.5 * (r[1:] + r[:-1]) * np.diff(tt)))


def test_zupt_closed_form_equals_the_cumulative_sums():
    """The position weight of each interval, (t_c - m_k) dt_k, is the ZUPT double integral written out."""
    rng = np.random.default_rng(3)
    worst = 0.0
    for n in (2, 3, 5, 24, 230, 2000):
        for _ in range(50):
            t = 1e4 * rng.uniform() + np.cumsum(rng.uniform(0.001, 0.06, n))  # clock values up to 3 h
            acc = rng.normal(size=(n, 3)) * 8.0 + [0.3, -0.2, 0.1]
            got, want = SK.zupt_displacement(t, acc), _zupt_cumsum(t, acc)
            worst = max(worst, float(np.max(np.abs(got - want))) / max(float(np.max(np.abs(want))), 1e-3))
    assert worst < 1e-12
    assert np.array_equal(SK.zupt_displacement(np.array([1.0]), np.ones((1, 3))), np.zeros(3))
    assert np.array_equal(SK.zupt_displacement(np.array([1.0, 1.0]), np.ones((2, 3))), np.zeros(3))


def test_yaw_change_product_equals_the_sum():
    rng = np.random.default_rng(4)
    for n in (2, 3, 25, 300):
        t = np.cumsum(rng.uniform(0.005, 0.06, n))
        r = rng.normal(size=n)
        for t0, t1 in ((t[0], t[-1]), (t[0] + 0.3 * (t[-1] - t[0]), t[-1] - 0.1 * (t[-1] - t[0])), (t[1], t[1])):
            assert SK.yaw_change(t, r, t0, t1) == pytest.approx(_yaw_change_sum(t, r, t0, t1), rel=1e-13, abs=1e-15)


def test_one_stride_float_kernels_equal_the_array_paths():
    """apply_level_gain_one, stride_rules_one and advance_xyz: the array functions' bits for one stride."""
    rng = np.random.default_rng(5)
    bounds = {"short": (0.0, 0.6), "normal": (0.6, 0.9), "long": (0.92, 20.0)}
    for _ in range(300):
        d = rng.normal(size=3) * [1.0, 0.4, 0.3]
        gain = float(rng.uniform(0.9, 1.1))
        assert np.array_equal(np.array(KD.apply_level_gain_one(*d.tolist(), gain)), KD.apply_level_gain(d, gain))
        te, di, lc = (rng.choice(x) for x in (["flat", "up", "down", None], ["forward", "backward", None],
                                              ["short", "normal", "long", None]))
        for b in (None, bounds):
            for dm in ("norm3", "projected", "horizontal"):  # L51: "projected" too
                one = SK.stride_rules_one(*d.tolist(), te, di, lc, bounds=b, down_mode=dm)
                arr = SK.apply_stride_rules(np.vstack([d, d]), [te, te], [di, di], [lc, lc], bounds=b, down_mode=dm)
                assert one == (arr[0][0], arr[1][0])
        p, h = rng.normal(size=3) * 10, float(rng.uniform(-4, 4))
        assert np.array_equal(np.array(SK.advance_xyz(*p.tolist(), h, d[0], d[2])), SK.advance(p, h, d[0], d[2]))


def test_segmenter_fed_norms_equals_the_segmenter_fed_rates():
    """The runtime feeds |w| computed on Python floats (update_norms): the same |w| bits as update's ufuncs,
    hence the same strides, sample by sample and in chunks."""
    rng = np.random.default_rng(6)
    g = rng.normal(size=(2000, 3)) * np.where((np.arange(2000) // 23 % 2 == 0)[:, None], 0.1, 3.0)
    norms = [math.sqrt(x * x + y * y + z * z) for x, y, z in g.tolist()]
    assert norms == np.sqrt(np.add.reduce(g * g, axis=1)).tolist()
    t = np.arange(2000) * 0.05
    a, b = SK.StanceSegmenter(), SK.StanceSegmenter()
    want = a.update(t, g)
    got = [s for i in range(2000) for s in b.update_norms([float(t[i])], [norms[i]])]
    assert len(want) > 20 and got == want


def _tilt_corrected_before(Y, g_lev, k0, k1):
    """kernels.stats.tilt_corrected before E17 (its arithmetic, more calls)."""
    if k1 <= k0:
        return Y
    n, shape = Y.shape[0], Y.shape
    gx, gy, gz = g_lev.tolist()
    nrm = math.sqrt(gx * gx + gy * gy + gz * gz)
    s = math.sqrt(gx * gx + gy * gy) / nrm
    if s < 1e-12:
        if gz > 0:
            return Y
        kx, ky, th = 1.0, 0.0, math.pi
    else:
        kx, ky, th = gy / nrm / s, -gx / nrm / s, math.atan2(s, gz / nrm)
    frac = np.minimum(np.maximum((np.arange(n) - k0) / float(k1 - k0), 0.0), 1.0)
    ang = frac * th
    KT = np.array([[0.0, 0.0, -ky], [0.0, 0.0, kx], [ky, -kx, 0.0]])
    KY = Y.reshape(-1, 3) @ KT
    K2Y = (KY @ KT).reshape(shape)
    return Y + np.sin(ang)[:, None, None] * KY.reshape(shape) + (1.0 - np.cos(ang))[:, None, None] * K2Y


def _stride_dpsi_before(forward_s, acc, Y, s=0):
    """kernels.window.stride_dpsi as introduced by L33 (sum() of generator products)."""
    if s == 0 and len(Y) == 1:
        return 0.0

    def att(e1, e2, f1, f2):
        S = KW._frame3(np.asarray(e1, float).tolist(), np.asarray(e2, float).tolist())
        V = KW._frame3(np.asarray(f1, float).tolist(), np.asarray(f2, float).tolist())
        if S is None or V is None:
            return None
        (s1, s2, s3), (v1, v2, v3) = S, V
        return [[v1[i] * s1[j] + v2[i] * s2[j] + v3[i] * s3[j] for j in range(3)] for i in range(3)]

    Rs, Re = att(forward_s, acc[s], Y[s, 2], Y[s, 0]), att(forward_s, acc[-1], Y[-1, 2], Y[-1, 0])
    if Rs is None or Re is None:
        f, g = Y[s, 2].tolist(), Y[-1, 2].tolist()
        return math.atan2(f[0] * g[1] - f[1] * g[0], f[0] * g[0] + f[1] * g[1])
    return KW.twist_about_z([[sum(Re[i][k] * Rs[j][k] for k in range(3)) for j in range(3)] for i in range(3)])


def _random_stride(rng, max_n: int, *, zero_last: bool = False, zero_any: bool = False):
    """A random stride for the kernel comparisons: levelled rows Y (n, 3, 3), specific force (n, 3), the
    forward axis and the start sample s (0 or 1); optionally one zeroed (degenerate) sample."""
    n = int(rng.integers(1, max_n))
    Y = rng.normal(size=(n, 3, 3))
    acc = rng.normal(size=(n, 3)) * 5.0
    if zero_last:
        acc[-1] = 0.0
    if zero_any:
        acc[rng.integers(0, n)] = 0.0
    fwd = rng.normal(size=3)
    s = int(rng.integers(0, 2)) if n > 1 else 0
    return Y, acc, fwd, s, n


def test_rewritten_window_kernels_are_bit_identical():
    """tilt_corrected (cached index column, no [:, None, None]), stride_dpsi (rows fetched once, products
    written out), rest_reference (argsort method), gravity_rotation_xyz and principal_horizontal_xy."""
    rng = np.random.default_rng(8)
    for it in range(1500):
        Y, acc, fwd, s, n = _random_stride(rng, 70, zero_last=it % 9 == 0)  # degenerate: pre-L30 fallback
        a, b = _stride_dpsi_before(fwd, acc, Y, s), KW.stride_dpsi(fwd, acc, Y, s)
        assert a == b or (math.isnan(a) and math.isnan(b))
        k0, k1 = int(rng.integers(0, n)), int(rng.integers(0, n))
        g = rng.normal(size=3) + [0.0, 0.0, 9.8] if it % 13 else np.array([0.0, 0.0, -9.8])
        assert np.array_equal(KS.tilt_corrected(Y.copy(), g, k0, k1), _tilt_corrected_before(Y.copy(), g, k0, k1))
        an, gn = rng.normal(size=n) + 9.8, np.abs(rng.normal(size=n))
        k = max(1, int(KS.REST_QUIET_FRACTION * n))
        q = np.sort(an[np.argsort(gn, kind="stable")[:k]])
        assert KS.rest_reference(an, gn) == float(0.5 * (q[(k - 1) // 2] + q[k // 2]))
        assert np.array_equal(KR.gravity_rotation_xyz(*g.tolist()), KR.gravity_rotation(g))
        ref = rng.normal(size=2)
        assert np.array_equal(np.array(KS.principal_horizontal_xy(Y[:, 0], *ref.tolist())),
                              KS.principal_horizontal_axis(Y[:, 0], ref))


def test_waist_entry_without_acceleration_keeps_the_rate_and_the_fallback_resamples_without_it():
    """need_acc=False: the waist's rate is the same array and its acceleration is None; the shared kernel's
    channel filling (the fallback for box-filtered windows) then leaves the waist acceleration rows alone."""
    from pdrlearn.runtime.stream import waist_entry

    rng = np.random.default_rng(9)
    t = np.arange(60) * 0.05
    acc = rng.normal(size=(60, 3)) * 0.5 + [0.3, -0.2, 9.8]
    gyr = rng.normal(size=(60, 3))
    streams = {"wAccelerometer": (t, acc), "wGyroscope": (t, gyr)}
    fwd = np.array([1.0, 0.0, 0.0])
    full = waist_entry(streams, 0.7, 2.1, fwd, True)
    part = waist_entry(streams, 0.7, 2.1, fwd, True, need_acc=False)
    assert part[1] is None and full[1] is not None
    assert np.array_equal(part[0], full[0]) and np.array_equal(part[2], full[2])
    W = np.full((len(KW.CHANNELS), 40), np.nan)
    tg = 0.7 + 1.4 * KW._unit_grid(40)
    need = {"waist_gyr_z"}
    KW._fill_channels(W, streams, 0.7, 2.1, tg, {"waist": part}, KW.CHANNEL_INDEX, ("waist_acc", "waist_gyr"), need)
    assert np.isfinite(W[KW.CHANNEL_INDEX["waist_gyr_z"]]).all()
    assert np.isnan(W[KW.CHANNEL_INDEX["waist_acc_x"]]).all()


def test_nan_window_template_copies_are_writable_nan():
    from pdrlearn.runtime.tracker import _nan_template

    a = _nan_template(17, 40).copy()
    b = _nan_template(17, 40).copy()
    assert a.shape == (17, 40) and np.isnan(a).all() and a.flags.writeable
    a[0] = 1.0
    assert np.isnan(b).all() and np.isnan(_nan_template(17, 40)).all()


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    from tests.runtime_helpers import trained_dirs

    return trained_dirs(tmp_path_factory)["root"] / "bundle"


def test_one_sample_push_fast_path_checks_like_append(bundle):
    """After a sensor's rate check, one-sample float64 pushes skip _append (decision E17) but are refused
    exactly as before: NaN, timestamps that do not increase, another number of values; other dtypes and
    chunks still go through _append; the buffers and foot state equal those of chunked pushes."""
    from pdrlearn.errors import DataError
    from pdrlearn.runtime.tracker import Tracker

    rng = np.random.default_rng(10)
    t = np.arange(40) * 0.05
    acc, gyr = rng.normal(size=(40, 3)) + [0, 9.8, 0], rng.normal(size=(40, 3))
    # foot samples only (the waist never comes): the lag check (decision E23) off
    one, chunked = Tracker(bundle, max_lag_s=np.inf), Tracker(bundle, max_lag_s=np.inf)
    for i in range(40):
        one.push({"fAccelerometer": (t[i:i + 1], acc[i:i + 1]), "fGyroscope": (t[i:i + 1], gyr[i:i + 1])})
    chunked.push({"fAccelerometer": (t, acc), "fGyroscope": (t, gyr)})
    assert {"fAccelerometer", "fGyroscope"} <= one.inputs.passed  # their rates judged by the input stage (E22)
    for name in ("fAccelerometer", "fGyroscope"):
        for a, b in zip(one._buf[name].view(), chunked._buf[name].view(), strict=True):
            np.testing.assert_array_equal(a, b)
    for k in ("t", "acc", "gyr", "an", "gn"):  # the norms: Python floats sample by sample, einsum in chunks
        np.testing.assert_allclose(one._foot.a[k][one._foot.i0:one._foot.i1],
                                   chunked._foot.a[k][chunked._foot.i0:chunked._foot.i1], rtol=1e-15, atol=0)
    assert one._latest == chunked._latest == t[-1]
    with pytest.raises(DataError, match="NaN"):
        one.push({"fAccelerometer": (np.array([2.0]), np.array([[np.nan, 0.0, 9.8]]))})
    with pytest.raises(DataError, match="NaN"):
        one.push({"fAccelerometer": (np.array([np.inf]), np.array([[0.0, 0.0, 9.8]]))})
    with pytest.raises(DataError, match="not increasing"):
        one.push({"fGyroscope": (np.array([t[-1]]), np.zeros((1, 3)))})
    with pytest.raises(DataError, match=r"shape \(1, 4\).*push an array of shape \(1, 3\)"):
        one.push({"fGyroscope": (np.array([5.0]), np.zeros((1, 4)))})
    n = len(one._buf["fAccelerometer"])
    one.push({"fAccelerometer": (np.array([2.5], dtype=np.float32), np.ones((1, 3), dtype=np.float32))})
    assert len(one._buf["fAccelerometer"]) == n + 1 and one._buf["fAccelerometer"].last == 2.5


def test_ring_segment_equals_the_kernel_segment_of_its_view():
    from pdrlearn.runtime.stream import Ring

    rng = np.random.default_rng(11)
    r = Ring(3, capacity=16)  # small: reallocations and trimming on the way
    t = np.cumsum(rng.uniform(0.01, 0.1, 150))
    v = rng.normal(size=(150, 3))
    for i in range(150):
        r.append(t[i:i + 1], v[i:i + 1])
        if i % 7 == 0:
            r.drop_before(t[max(0, i - 10)])
        for _ in range(4):
            a, b = np.sort(rng.uniform(t[0] - 0.5, t[i] + 0.5, 2)).tolist()
            for x, y in zip(r.segment(a, b), KW.segment(*r.view(), a, b), strict=True):
                np.testing.assert_array_equal(x, y)


def test_stride_headings_equal_stride_dpsi_and_start_heading():
    """The runtime computes the start attitude once for L33's turn and L34's start heading."""
    rng = np.random.default_rng(12)
    for it in range(1500):
        # a degenerate frame at the start or the end
        Y, acc, fwd, s, n = _random_stride(rng, 40, zero_any=it % 9 == 0)
        dpsi, psi0 = KW.stride_headings(fwd, acc, Y, s)
        want = KW.stride_dpsi(fwd, acc, Y, s), KW.start_heading(fwd, acc[s], Y[s])
        assert (dpsi, psi0) == want
