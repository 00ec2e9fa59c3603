"""Decision L35 (docs/decisions/localization.md): the streamed foot heading chain adds the second-order (coning)
term that the attitude from the mean rate of each sample interval misses, (5/24) sum dt^2 (w_k x w_k+1)_z of
the levelled rate. At 20 Hz (the PLASYS firmware's 5-sample means) the simulated foot's streamed heading drifted
+0.023 rad per stride without it; the levelled step windows (training features) do not take it."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.kernels import window as KW

G = 9.81
FINE_HZ = 2000.0
FWD = np.array([1.0, 0.0, 0.0])


def _coning_foot(rate_hz: float, *, tilt: float = 0.4, yaw_rate: float = 0.0, dur_s: float = 1.5):
    """A foot at rest 0.5 s, then 0.5 s whose tilt (``tilt`` sin^2, rad) is about a horizontal axis that turns
    once around the vertical (a cone: pitch and roll rates a quarter period apart), then at rest; the whole
    time turning about the vertical at ``yaw_rate`` (rad/s). Simulated at 2 kHz and averaged over each output
    sample interval (as the PLASYS firmware's 20 Hz samples, thesis ch.4.2.3). Returns the sample times (block
    centres), specific force, body rate and the true heading change from the first to the last sample."""
    k = int(round(FINE_HZ / rate_hz))
    nf = int(round(dur_s * FINE_HZ)) // k * k + k
    tf = np.arange(nf + 1) / FINE_HZ
    u = np.clip((tf - 0.5) / 0.5, 0.0, 1.0)
    axis = np.column_stack([np.cos(2 * np.pi * u), np.sin(2 * np.pi * u), 0 * u])
    R = Rotation.from_euler("z", yaw_rate * tf[:, None]) * Rotation.from_rotvec(
        axis * (tilt * np.sin(np.pi * u) ** 2)[:, None])
    w = (R[:-1].inv() * R[1:]).as_rotvec() * FINE_HZ
    f = 0.5 * (R[:-1].inv().apply([0.0, 0.0, G]) + R[1:].inv().apply([0.0, 0.0, G]))
    tm = 0.5 * (tf[:-1] + tf[1:])
    nb = len(w) // k

    def blocks(x):
        return x[: nb * k].reshape(nb, k, -1).mean(axis=1)

    t = blocks(tm[:, None])[:, 0]
    i0, i1 = (int(round(v * FINE_HZ)) for v in (t[0], t[-1]))
    truth = KW.twist_about_z((R[i1] * R[i0].inv()).as_matrix())
    return t, blocks(f), blocks(w), truth


def _dpsi(t, acc, gyr):
    return KW.foot_levelled(t, acc, gyr, FWD, rest_search_s=0.3, heading="declared", t0=float(t[0]))[3]


@pytest.mark.parametrize("yaw_rate", [0.0, 0.3])
def test_coning_swing_at_20hz_keeps_its_net_yaw(yaw_rate, monkeypatch):
    t, acc, gyr, truth = _coning_foot(20.0, yaw_rate=yaw_rate)
    assert truth == pytest.approx(yaw_rate * (t[-1] - t[0]), abs=1e-9)
    assert abs(_dpsi(t, acc, gyr) - truth) < 0.008  # rad; the mean-rate attitude alone: -0.050
    monkeypatch.setattr(KW, "CONING_COEF", 1.0 / 12.0)  # the linear-rate term alone (L33's note): -0.032
    assert abs(_dpsi(t, acc, gyr) - truth) > 0.02
    monkeypatch.setattr(KW, "CONING_COEF", 0.0)
    assert abs(_dpsi(t, acc, gyr) - truth) > 0.04


def test_coning_term_scales_with_the_sample_interval_squared():
    """Formulas in seconds: the same motion at 100 Hz needs a term 25x smaller, and is then exact to 0.5 mrad."""
    terms = {}
    for rate in (20.0, 100.0):
        t, acc, gyr, truth = _coning_foot(rate)
        d = _dpsi(t, acc, gyr)
        Y = _levelled_rows(t, acc, gyr)
        terms[rate] = KW.coning_yaw(t, Y, 0)
        assert d - terms[rate] == pytest.approx(KW.stride_dpsi(FWD, acc, Y, 0), abs=1e-12)
        if rate == 100.0:
            assert abs(d - truth) < 5e-4
    assert abs(terms[100.0]) * 10 < abs(terms[20.0])


def _levelled_rows(t, acc, gyr):
    """The rows (acc, gyro, forward axis) of foot_levelled's attitude, before gravity is removed."""
    from pdrlearn.kernels.rotation import gravity_rotation
    from pdrlearn.kernels.stats import levelled_vectors, rest_index, rest_score, row_norm

    n = len(t)
    fs = (n - 1) / float(t[-1] - t[0])
    m = max(2, min(int(round(0.3 * fs)), n // 4 + 1))
    h = max(0, int(round(0.02 * fs)))
    score = rest_score(row_norm(acc), row_norm(gyr), half_width=h)
    k0, k1 = rest_index(acc, gyr, 0, m, score=score), rest_index(acc, gyr, n - m, n, score=score)
    g0, g1 = acc[max(k0 - h, 0): k0 + h + 1].mean(axis=0), acc[max(k1 - h, 0): k1 + h + 1].mean(axis=0)
    X = np.empty((n, 3, 3))
    X[:, 0], X[:, 1], X[:, 2] = acc, gyr, FWD
    return levelled_vectors(gyr, np.diff(t), k0, k1, gravity_rotation(g0), g1, X)


def test_levelled_windows_do_not_take_the_coning_term(monkeypatch):
    """Only the heading change moves: the levelled acc / gyro (the step window's channels) and the step
    frame's direction are the same bit for bit with the term switched off, so no model is retrained."""
    t, acc, gyr, _ = _coning_foot(20.0, yaw_rate=0.3)
    streams = {"fAccelerometer": (t, acc), "fGyroscope": (t, gyr)}
    kw = {"available": ("foot_acc", "foot_gyr"), "forward": {"foot": FWD}, "rest_search_s": 0.3, "heading": "pca"}
    W1 = np.full((len(KW.CHANNELS), 40), np.nan)
    on = KW.fill_step_window(W1, streams, float(t[0]), float(t[-1]), channel_index=KW.CHANNEL_INDEX, **kw)["foot"]
    monkeypatch.setattr(KW, "CONING_COEF", 0.0)
    W0 = np.full((len(KW.CHANNELS), 40), np.nan)
    off = KW.fill_step_window(W0, streams, float(t[0]), float(t[-1]), channel_index=KW.CHANNEL_INDEX, **kw)["foot"]
    np.testing.assert_array_equal(W1, W0)
    for a, b in zip(on[:4], off[:4], strict=True):
        np.testing.assert_array_equal(a, b)
    assert on[5] == off[5]  # decision L34's step direction
    assert abs(on[4] - off[4]) > 0.04


def test_runtime_push_time_levelling_takes_the_same_term():
    """runtime.stream.foot_levelled (the push-time state) gives the shared kernel's heading change."""
    from pdrlearn.runtime.stream import FootLevelling, foot_levelled

    t, acc, gyr, truth = _coning_foot(20.0, yaw_rate=0.3, dur_s=2.0)
    t1 = float(t[-8])  # the stride ends in the rest; later samples arrive before it is measured
    state = FootLevelling(FWD)
    state.feed("fAccelerometer", t, acc)
    state.feed("fGyroscope", t, gyr)
    rt = foot_levelled(state, float(t[0]), t1, rest_search_s=0.3, heading="pca")
    streams = {"fAccelerometer": (t, acc), "fGyroscope": (t, gyr)}
    ref = KW.levelled_units(streams, float(t[0]), t1, available=("foot_acc", "foot_gyr"), forward={"foot": FWD},
                            rest_search_s=0.3, heading="pca")["foot"]
    assert rt[4] == pytest.approx(ref[4], abs=1e-12)
    assert rt[4] == pytest.approx(0.3 * (float(rt[0][-1]) - float(t[0])), abs=0.008)


def test_simulated_20hz_streamed_foot_heading_does_not_drift():
    """Simulated scenario D, user 1, normal speed, 20 Hz: the streamed strides' heading change against the
    simulator's foot attitude (mean error +23 mrad per stride over A-D x 5 users x 3 speeds without the term,
    +2.8 with it) and the foot-headed streamed track's final position error (6.85 m without, 0.69 m with)."""
    from pdrlearn.features.windows import _declared_forward
    from pdrlearn.kernels import stride as SK
    from pdrlearn.sim import simulate
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_streaming

    s = simulate("D", user_seed=1, speed="normal")
    streams = {n: (x.t, x.values) for n, x in s.streams.items()}
    ft = s.extras["foot_trajectory"]
    tt, q = ft["t_s"].to_numpy(), Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy())
    kw = {"available": ("foot_acc", "foot_gyr"), "forward": {"foot": _declared_forward(s, "foot")},
          "rest_search_s": 0.3, "heading": "pca"}
    err = []
    for t0, t1 in SK.stance_strides(*streams["fGyroscope"], {}):
        foot = KW.levelled_units(streams, float(t0), float(t1), **kw)["foot"]
        ta = foot[0]
        i, j = (int(np.argmin(np.abs(tt - v))) for v in (ta[KW.start_index(ta, float(t0))], ta[-1]))
        err.append(np.remainder(foot[4] - KW.twist_about_z((q[j] * q[i].inv()).as_matrix()) + np.pi, 2 * np.pi)
                   - np.pi)
    assert abs(np.mean(err)) < 0.008
    ev = evaluate_track(track_streaming(s, method="M3", model="oracle", heading="foot"), s)
    assert ev["final_position_error_m"] < 2.0
