"""Decision E15: the foot levelled at push time (``pdrlearn.runtime.stream``) against the shared kernel.

``Tracker(incremental=True)`` (the default) keeps per-sample attitude products as samples arrive and at
the step event runs only the whole-step part of the levelling; ``incremental=False`` runs the training
side's kernel alone. Windows must agree to rounding, steps/classes exactly, probabilities within 1e-5 and
positions within 1 mm, for sample-by-sample and chunked pushes, 20 Hz and 204.8 Hz, and across the
re-anchoring of the running product; a second foot clock falls back to the kernel.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.kernels.rotation import rotvec_to_matrix
from pdrlearn.kernels.window import _fill_channels, _unit_grid, levelled_units
from pdrlearn.runtime.stream import FootLevelling, Ring, _rotvec_matrix, fill_resampled
from pdrlearn.runtime.tracker import Tracker
from tests.benchmarks.test_bench_runtime import native_chunks
from tests.runtime_helpers import synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"] / "bundle"


def _stream(tr: Tracker, session, chunk_s: float | None, after_push=lambda tr: None) -> list:
    """Push ``session`` sample by sample (``chunk_s=None``: native_chunks) or in chunks of ``chunk_s``;
    ``after_push(tr)`` runs after every chunked push."""
    steps = []
    if chunk_s is None:
        for d in native_chunks(session):
            steps += tr.push(d)
    else:
        t_all = np.concatenate([st.t for st in session.streams.values()])
        edges = np.arange(t_all.min(), t_all.max() + 2 * chunk_s, chunk_s)
        for a, b in zip(edges[:-1], edges[1:], strict=True):
            d = {}
            for n, st in session.streams.items():
                i0, i1 = np.searchsorted(st.t, [a, b])
                d[n] = (st.t[i0:i1], st.values[i0:i1])
            steps += tr.push(d)
            after_push(tr)
    return steps + tr.flush()


def _assert_same_steps(got, want):
    assert len(got) == len(want) > 5
    for a, b in zip(got, want, strict=True):
        assert (a.start_s, a.end_s) == (b.start_s, b.end_s)
        assert a.classes == b.classes
        for task, p in a.proba.items():
            assert max(abs(p[c] - b.proba[task][c]) for c in p) <= 1e-5
        assert math.dist((a.x, a.y, a.z), (b.x, b.y, b.z)) < 1e-3
        assert abs(a.heading_rad - b.heading_rad) < 1e-9


def _assert_levelled_close(tr: Tracker, steps, atol=1e-12):
    """Every step's window (all channels) and levelled units against the shared kernel alone."""
    streams = {k: tr._stream(k) for k in tr._buf}
    for st in steps:
        W, lev = tr._window(st.start_s, st.end_s, channels=None)
        np.testing.assert_allclose(W, tr.window(st.start_s, st.end_s), rtol=0, atol=atol)
        ref = levelled_units(streams, st.start_s, st.end_s, available=tr._groups[1], forward=tr.forward,
                             rest_search_s=tr.rest_search_s, heading=tr.heading_mode)
        for unit, entry in ref.items():
            for x, y in zip(lev[unit], entry, strict=True):
                if isinstance(y, np.ndarray):
                    np.testing.assert_allclose(x, y, rtol=0, atol=atol)
                elif y is not None and y == y:
                    assert abs(x - y) <= atol


@pytest.mark.parametrize("chunk_s", [None, 0.05, 0.37])
def test_push_time_levelling_streams_the_same_steps(bundle, chunk_s):
    s = synthetic_session(40, seed=11, turn_rad_per_step=0.05)
    inc = Tracker(bundle, buffer_s=1e9)
    inc._trim = lambda *a: None  # keep the session to cut every window again afterwards
    got = _stream(inc, s, chunk_s)
    assert inc._foot is not None and inc._foot.ok
    _assert_same_steps(got, _stream(Tracker(bundle, incremental=False), s, chunk_s))
    _assert_levelled_close(inc, got)


def test_running_product_reanchors_without_drift(bundle):
    """A small buffer forces the running product to restart many times; windows stay within 1e-12."""
    s = synthetic_session(40, seed=3)
    tr = Tracker(bundle, buffer_s=1e9)
    tr._trim = lambda *a: None
    tr._foot = FootLevelling(tr.forward["foot"], capacity=8)  # grows to hold the session, re-anchoring each time
    got = _stream(tr, s, None)
    assert len(tr._foot) == len(s.streams["fAccelerometer"].t)
    q = tr._foot.a["Q"][tr._foot.i0]
    np.testing.assert_allclose(q, np.eye(3), atol=1e-15)  # the product restarts at the oldest kept sample
    _assert_levelled_close(tr, got)
    tr2 = Tracker(bundle)  # and with trimming on, a long walk keeps the state bounded
    _stream(tr2, s, None)
    assert len(tr2._foot) < len(s.streams["fAccelerometer"].t) // 2


def test_real_204hz_foot_windows_equal_the_shared_kernel(real_dir):
    """Real 204.8 Hz foot walk (box-filtered resampling, +-20 ms rest average): windows within 1e-9."""
    s = read_session(real_dir / "gaitmap_level_right")
    tr = Tracker.__new__(Tracker)  # a bundle-free tracker: only the buffers and the window code
    from pdrlearn.kernels.window import CHANNELS
    from pdrlearn.runtime.tracker import forward_vector

    tr.channels, tr.ci = list(CHANNELS), {c: i for i, c in enumerate(CHANNELS)}
    tr.n_samples, tr.heading_mode, tr.rest_search_s, tr.boundaries = 40, "pca", 0.3, "given"
    tr.forward = {"foot": forward_vector(s.frames["foot"].to_dict())}
    tr._buf, tr._groups, tr._waist_groups, tr._all_channels = {}, ((), ()), None, frozenset(CHANNELS)
    tr._foot = FootLevelling(tr.forward["foot"])
    for n in ("fAccelerometer", "fGyroscope"):
        st = s.streams[n]
        for a in range(0, len(st.t), 41):  # 0.2 s chunks
            tr._buf.setdefault(n, Ring(3)).append(st.t[a:a + 41], st.values[a:a + 41])
            tr._foot.feed(n, st.t[a:a + 41], st.values[a:a + 41])
    steps = list(zip(s.steps["start_s"], s.steps["end_s"], strict=True))
    assert tr._foot.ok and len(steps) > 20
    streams = {k: tr._stream(k) for k in tr._buf}
    worst = 0.0
    for a, b in steps:
        W, lev = tr._window(a, b, channels=None)
        ref = tr.window(a, b)
        assert np.array_equal(np.isnan(W), np.isnan(ref))
        worst = max(worst, float(np.nanmax(np.abs(W - ref))))
        lev0 = levelled_units(streams, a, b, available=tr._groups[1], forward=tr.forward, rest_search_s=0.3,
                              heading="pca")
        assert abs(lev["foot"][4] - lev0["foot"][4]) < 1e-12  # heading change
    assert worst < 1e-9


def test_second_foot_clock_falls_back_to_the_kernel(bundle):
    """Foot gyroscope on its own clock (shifted 10 ms): push-time levelling turns off, same steps as the kernel."""
    s = synthetic_session(20, seed=2)
    g = s.streams["fGyroscope"]
    g.t = g.t + 0.01
    inc, ref = Tracker(bundle), Tracker(bundle, incremental=False)
    got = _stream(inc, s, None)
    assert not inc._foot.ok
    want = _stream(ref, s, None)
    assert [(x.start_s, x.classes, x.x, x.y) for x in got] == [(x.start_s, x.classes, x.x, x.y) for x in want]


def test_one_sample_rotation_equals_the_array_kernel():
    rng = np.random.default_rng(0)
    for scale in (1e-12, 1e-9, 1e-6, 1e-3, 0.1, 1.0, 3.0):
        for w in rng.normal(size=(50, 3)) * scale:
            got = np.array(_rotvec_matrix(*w.tolist())).reshape(3, 3)
            np.testing.assert_allclose(got, rotvec_to_matrix(w[None])[0], rtol=0, atol=4e-16)
    np.testing.assert_array_equal(np.array(_rotvec_matrix(0.0, 0.0, 0.0)).reshape(3, 3), np.eye(3))


def test_fill_resampled_equals_the_kernel_bit_for_bit(bundle):
    s = synthetic_session(12, seed=4)
    tr = Tracker(bundle)
    for n, st in s.streams.items():
        tr._append(n, st.t, st.values)
    streams = {k: tr._stream(k) for k in tr._buf}
    tr._window(1.0, 2.0)
    checked = 0
    for a, b in zip(s.steps["start_s"], s.steps["end_s"], strict=True):
        lev = tr._levelled(streams, a, b, tr._groups[1])
        tg = a + (b - a) * _unit_grid(tr.n_samples)
        for need in (tr._all_channels, frozenset({"foot_acc_x", "force_b", "waist_gyr_z"})):
            W1 = np.full((len(tr.channels), tr.n_samples), np.nan)
            W2 = W1.copy()
            assert fill_resampled(W1, streams, a, b, tg, lev, tr.ci, tr._groups[1], need)
            _fill_channels(W2, streams, a, b, tg, lev, tr.ci, tr._groups[1], need)
            np.testing.assert_array_equal(W1, W2)
            checked += 1
    assert checked >= 20


def test_ring_drops_from_the_front_and_keeps_old_views_valid():
    r = Ring(2, capacity=4)
    r.append(np.array([0.0, 1.0, 2.0]), np.arange(6.0).reshape(3, 2))
    t_old, v_old = r.view()
    r.drop_before(1.5)  # keeps the last sample before 1.5 s (a window's left node across a gap, E23 amended)
    assert r.view()[0].tolist() == [1.0, 2.0]
    r.drop_before(1.5)
    assert r.view()[0].tolist() == [1.0, 2.0]
    r.drop_before(2.0)
    assert r.view()[0].tolist() == [1.0, 2.0]
    r.drop_before(2.5)
    assert r.view()[0].tolist() == [2.0]
    r.append1(3.0, [7.0, 8.0])
    r.append(np.array([4.0, 5.0]), np.ones((2, 2)))  # full: new arrays, the old views unchanged
    assert t_old.tolist() == [0.0, 1.0, 2.0] and v_old[2].tolist() == [4.0, 5.0]
    assert r.view()[0].tolist() == [2.0, 3.0, 4.0, 5.0] and r.last == 5.0
    r.drop_before(99.0)  # keeps the newest sample
    assert r.view()[0].tolist() == [5.0]


def test_foot_accelerometer_without_its_gyroscope_keeps_the_state_bounded(bundle):
    """Accelerometer samples held for a gyroscope that never comes are given up once the buffer passes them
    (with the lag check off; by default the missing gyroscope is a DataError after max_lag_s, decision E23:
    tests/test_runtime_resample.py)."""
    s = synthetic_session(12, seed=1)
    tr = Tracker(bundle, buffer_s=2.0, max_lag_s=float("inf"))
    acc = s.streams["fAccelerometer"]
    for k in range(len(acc.t)):
        tr.push({"fAccelerometer": (acc.t[k:k + 1], acc.values[k:k + 1])})
    assert not tr._foot.ok and tr._foot._pa is None
    assert len(tr._buf["fAccelerometer"]) <= 2.0 * 20 + 2


@pytest.mark.parametrize("chunk_s", [1.0, 2.0])
def test_chunked_pushes_keep_the_state_bounded(bundle, chunk_s):
    """Pushes of a stride or more return a step nearly every time; the buffers must still be trimmed."""
    tr = Tracker(bundle, buffer_s=8.0)
    held = []
    _stream(tr, synthetic_session(120, seed=5), chunk_s,  # (the first 1 s is held to learn the rate, E22)
            lambda tr: held.append(len(tr._buf["fAccelerometer"]) if "fAccelerometer" in tr._buf else 0))
    assert max(held) <= (2 * 8.0 + 2 * chunk_s) * 20 + 2  # 20 Hz foot; the whole 120 s would be 2400


def test_waist_entry_equals_the_shared_kernel_and_falls_back_on_degenerate_tilts():
    """Decision E16: the waist levelling on Python floats against ``levelled_units``' waist entry (1e-14),
    on random tilts, a level unit (no rotation), an upside-down unit and a second waist clock; a forward
    axis that is vertical at rest raises the kernel's DataError."""
    from pdrlearn.errors import DataError
    from pdrlearn.runtime.stream import waist_entry

    rng = np.random.default_rng(3)
    t = np.arange(40) * 0.05
    fwd = {"waist": np.array([0.0, 0.0, 1.0])}
    for k in range(30):
        g = rng.normal(size=3)
        g = 9.81 * g / np.linalg.norm(g) if k > 1 else np.array([0.0, 0.0, 9.81 if k == 0 else -9.81])
        acc = g + rng.normal(scale=2.0, size=(40, 3))
        gyr = rng.normal(size=(40, 3))
        tg = t if k % 3 else t + 0.013  # every third: the gyroscope on its own clock
        streams = {"wAccelerometer": (t, acc), "wGyroscope": (tg, gyr)}
        f = np.array([1.0, 0.0, 0.0]) if k > 1 else np.array([0.0, 1.0, 0.0])
        for gyro in (True, False):
            groups = ("waist_acc", "waist_gyr") if gyro else ("waist_acc",)
            want = levelled_units(streams, 0.3, 1.6, available=groups, forward={"waist": f}, rest_search_s=0.3,
                                  heading="pca")["waist"]
            got = waist_entry(streams, 0.3, 1.6, f, gyro)
            np.testing.assert_array_equal(got[0], want[0])
            np.testing.assert_allclose(got[1], want[1], rtol=0, atol=1e-13)
            assert (got[2] is None) == (want[2] is None) == (not gyro)
            if gyro:
                np.testing.assert_allclose(got[2], want[2], rtol=0, atol=1e-13)
    streams = {"wAccelerometer": (t, np.tile([0.0, 0.0, 9.81], (40, 1))), "wGyroscope": (t, np.zeros((40, 3)))}
    with pytest.raises(DataError, match="vertically"):
        waist_entry(streams, 0.3, 1.6, fwd["waist"], True)


def test_buffer_views_are_made_on_first_access(bundle):
    """Decision E16: the step reads its sensors through ``_Views``: membership and iteration are the
    buffers', a view is the buffer's, an unknown sensor is a KeyError."""
    from pdrlearn.runtime.tracker import _Views

    s = synthetic_session(6, seed=2)
    tr = Tracker(bundle)
    for n, st in s.streams.items():
        tr._append(n, st.t, st.values)
    v = _Views(tr._buf)
    assert tuple(v) == tuple(tr._buf) and len(v) == len(tr._buf) and "fGyroscope" in v and "nope" not in v
    assert dict.__len__(v) == 0  # nothing made yet
    t, x = v["fGyroscope"]
    np.testing.assert_array_equal(t, tr._buf["fGyroscope"].view()[0])
    assert np.shares_memory(x, tr._buf["fGyroscope"].v) and dict.__len__(v) == 1
    with pytest.raises(KeyError):
        v["nope"]


def test_lazy_buffer_views_answer_get_like_a_dict():
    """runtime.tracker._Views (E16) makes a sensor's view on first access; ``get`` must see every buffered
    sensor too (dict.get does not call __missing__)."""
    from pdrlearn.runtime.tracker import _Views

    r = Ring(3)
    r.append(np.array([0.0, 0.01]), np.zeros((2, 3)))
    v = _Views({"fGyroscope": r})
    t, g = v.get("fGyroscope")
    np.testing.assert_array_equal(t, [0.0, 0.01])
    assert g.shape == (2, 3)
    assert v.get("wGyroscope") is None and v.get("wGyroscope", 1) == 1
