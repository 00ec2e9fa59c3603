"""docs/deploying.md "Porting the runtime" is enough to port: a port written from its text alone (plain numpy and
math, no pdrlearn kernel) gives the runtime's strides and step windows (decision E70). A change of a kernel that the
text does not follow fails here: update the text with the kernel."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.io import write_session
from tests.runtime_helpers import synthetic_session

TIE = 1e-6
I3 = np.eye(3)


# -- the port, step by step as the text says -------------------------------------------------------------------
def port_strides(t, gyr, p):
    """Section 1 of the text: the stance segmenter."""
    win, floor_q, out = [], [], []
    s0 = s1 = None
    closed, open_s = False, None
    mean_rule = p["stance_mean_min_s"] > 0
    min_run = p["stance_mean_min_s"] if mean_rule else p["min_stance_s"]
    cap = max(p["stance_gyro_max_rad_s"], p["stance_gyro_rad_s"])

    def close(e):
        nonlocal closed, open_s
        closed = True
        if open_s is not None and p["min_step_s"] - TIE <= e - open_s <= p["max_step_s"] + TIE:
            out.append((open_s, e))
        open_s = None

    for tn, wn in zip(t.tolist(), np.sqrt((gyr ** 2).sum(axis=1)).tolist(), strict=True):
        win.append([tn, wn, p["stance_gyro_rad_s"]])
        win[:] = [x for x in win if x[0] > tn - p["min_stance_s"] + TIE]
        m = sum(x[1] for x in win) / len(win)
        floor_q.append((tn, m))
        floor_q[:] = [x for x in floor_q if x[0] > tn - p["stance_floor_window_s"] + TIE]
        floor = min(x[1] for x in floor_q)
        th = p["stance_gyro_rad_s"] if p["stance_floor_factor"] == 0 else min(
            max(p["stance_floor_factor"] * floor, p["stance_gyro_rad_s"]), cap)
        win[-1][2] = th
        if mean_rule:
            ti, wi, thi = win[(len(win) - 1) // 2]
            still = wi < thi or m < thi
        else:
            ti, still = tn, wn < th
        if still:
            if s0 is None:
                s0, closed = ti, False
            s1 = ti
            if not closed and ti - s0 >= max(2 * p["stance_half_s"], min_run) - TIE:
                close(s0 + p["stance_half_s"])
        elif s0 is not None and ti - s1 > p["stance_gap_s"] + TIE:
            if s1 - s0 >= min_run - TIE:
                mid = 0.5 * (s0 + s1)
                if not closed:
                    close(mid)
                open_s = max(mid, s1 - p["stance_half_s"])
            s0 = None
    return out


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]], dtype=float)


def rodrigues(axis, angle):
    K = skew(axis)
    return I3 + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def exp_so3(v):
    th = float(np.linalg.norm(v))
    return I3 + skew(v) if th < 1e-12 else rodrigues(v / th, th)


def to_z(g):
    """The shortest rotation taking g to +z."""
    n = g / np.linalg.norm(g)
    axis = np.cross(n, [0.0, 0.0, 1.0])
    s = float(np.linalg.norm(axis))
    if s < 1e-12:
        return I3.copy() if n[2] > 0 else np.diag([1.0, -1.0, -1.0])
    return rodrigues(axis / s, math.atan2(s, n[2]))


def cut(t, v, t0, t1):
    """The samples from the last one at or before t0 to the first at or after t1."""
    i0 = max(int(np.searchsorted(t, t0 + TIE, side="right")) - 1, 0)
    i1 = min(int(np.searchsorted(t, t1 - TIE, side="left")) + 1, len(t))
    return t[i0:i1], v[i0:i1]


def to_grid(tau, t, v):
    """Section 3, "Resampling": odd box width, moving mean with the ends repeated, linear interpolation."""
    width = round((tau[1] - tau[0]) * (len(t) - 1) / (t[-1] - t[0]))
    width = 2 * (width // 2) + 1
    if width > 1:
        h = width // 2
        padded = np.concatenate([np.repeat(v[:1], h, axis=0), v, np.repeat(v[-1:], h, axis=0)])
        v = np.array([padded[k:k + width].mean(axis=0) for k in range(len(v))])
    return np.array([np.interp(tau, t, v[:, j]) for j in range(v.shape[1])])


def port_foot(t, a, w, f, rest_search_s):
    """Section 3, "Foot": the levelled acc and rate in the step frame."""
    n = len(t)
    fs = (n - 1) / (t[-1] - t[0])
    m = max(2, min(round(rest_search_s * fs), n // 4 + 1))
    h = round(0.02 * fs)
    an, wn = np.linalg.norm(a, axis=1), np.linalg.norm(w, axis=1)
    rho = float(np.median(an[np.argsort(wn, kind="stable")[:max(1, n // 4)]]))
    s0 = 0.1 * np.abs(an - rho) + wn
    s = np.array([s0[max(0, k - h):k + h + 1].max() for k in range(n)])
    k0, k1 = int(np.argmin(s[:m])), n - m + int(np.argmin(s[n - m:]))
    g0, g1 = a[max(0, k0 - h):k0 + h + 1].mean(axis=0), a[max(0, k1 - h):k1 + h + 1].mean(axis=0)
    r0 = to_z(g0)
    P = [I3]
    for k in range(1, n):
        P.append(P[-1] @ exp_so3(0.5 * (w[k - 1] + w[k]) * (t[k] - t[k - 1])))
    R = [r0 @ P[k0].T @ P[k] for k in range(n)]
    gx, gy, gz = R[k1] @ g1
    hz = math.hypot(gx, gy)
    C = [I3] * n
    if k1 > k0 and hz > 1e-12 * np.linalg.norm([gx, gy, gz]):
        axis, theta = np.array([gy, -gx, 0.0]) / hz, math.atan2(hz, gz)
        C = [rodrigues(axis, min(max((k - k0) / (k1 - k0), 0.0), 1.0) * theta) for k in range(n)]
    at = np.array([C[k] @ R[k] @ a[k] for k in range(n)])
    wt = np.array([C[k] @ R[k] @ w[k] for k in range(n)])
    at[:, 2] -= np.linalg.norm(g0)
    ref = (r0 @ f)[:2]
    ref = ref / np.linalg.norm(ref)
    sxx, sxy, syy = (at[:, 0] ** 2).sum(), (at[:, 0] * at[:, 1]).sum(), (at[:, 1] ** 2).sum()
    phi = 0.5 * math.atan2(2 * sxy, sxx - syy)
    u = np.array([math.cos(phi), math.sin(phi)])
    if u @ ref < 0:
        u = -u
    yaw = np.array([[u[0], u[1], 0.0], [-u[1], u[0], 0.0], [0.0, 0.0, 1.0]])
    return at @ yaw.T, wt @ yaw.T, an


def port_waist(a, w, f):
    g = a.mean(axis=0)
    r = to_z(g)
    ref = (r @ f)[:2]
    ref = ref / np.linalg.norm(ref)
    R = np.array([[ref[0], ref[1], 0.0], [-ref[1], ref[0], 0.0], [0.0, 0.0, 1.0]]) @ r
    out = a @ R.T
    out[:, 2] -= np.linalg.norm(g)
    return out, w @ R.T


def port_window(streams, t0, t1, f_foot, f_waist, channels, n_samples=40, rest_search_s=0.3):
    W = np.full((len(channels), n_samples), np.nan)
    ci = {c: i for i, c in enumerate(channels)}
    tau = t0 + (t1 - t0) * np.arange(n_samples) / (n_samples - 1)
    W[ci["t_s"]] = tau - t0
    ta, a = cut(*streams["fAccelerometer"], t0, t1)
    w = to_grid(ta, *cut(*streams["fGyroscope"], t0, t1)).T
    fa, fw, an = port_foot(ta, a, w, f_foot, rest_search_s)
    rows = to_grid(tau, ta, np.column_stack([fa, an, fw]))
    for j, c in enumerate(["foot_acc_x", "foot_acc_y", "foot_acc_z", "foot_acc_norm", "foot_gyr_x", "foot_gyr_y",
                           "foot_gyr_z"]):
        W[ci[c]] = rows[j]
    if f_waist is None:
        return W
    tw, wa = cut(*streams["wAccelerometer"], t0, t1)
    ww = to_grid(tw, *cut(*streams["wGyroscope"], t0, t1)).T
    xa, xw = port_waist(wa, ww, f_waist)
    rows = to_grid(tau, tw, np.column_stack([xa, xw]))
    for j, c in enumerate(["waist_acc_x", "waist_acc_y", "waist_acc_z", "waist_gyr_x", "waist_gyr_y", "waist_gyr_z"]):
        W[ci[c]] = rows[j]
    return W


# -- the runtime's numbers ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import read_session

    root = tmp_path_factory.mktemp("port")
    write_session(synthetic_session(20, seed=9, name="walk"), root / "walk")
    return read_session(root / "walk")


def _params():
    from pdrlearn.kernels.stride import STANCE_L27_DEFAULTS
    from pdrlearn.runtime.tracker import DEFAULT_DISPLACEMENT

    return {**STANCE_L27_DEFAULTS, **DEFAULT_DISPLACEMENT}


def test_ported_segmenter_gives_the_runtimes_strides(walk):
    from pdrlearn.kernels.stride import stance_strides

    g = walk.streams["fGyroscope"]
    ref = stance_strides(g.t, g.values, _params())
    got = np.array(port_strides(g.t, g.values, _params()))
    assert len(ref) >= 15 and got.shape == ref.shape
    assert np.abs(got - ref).max() < 1e-12


def _compare_windows(session, f_foot, f_waist, rows):
    from pdrlearn.features import CHANNELS
    from pdrlearn.kernels.stride import stance_strides
    from pdrlearn.runtime.features import step_window

    streams = {n: (st.t, st.values) for n, st in session.streams.items() if n[1:] in ("Accelerometer", "Gyroscope")}
    forward = {"foot": f_foot} if f_waist is None else {"foot": f_foot, "waist": f_waist}
    g = session.streams["fGyroscope"]
    strides = stance_strides(g.t, g.values, _params())
    for t0, t1 in strides:
        ref = step_window(streams, t0, t1, channels=list(CHANNELS), forward=forward)
        got = port_window(streams, t0, t1, f_foot, f_waist, list(CHANNELS))
        filled = np.isfinite(ref).all(axis=1)
        assert filled.sum() == rows
        assert np.array_equal(np.isfinite(got).all(axis=1), filled)
        assert np.abs(got[filled] - ref[filled]).max() < 1e-9
    return len(strides)


@pytest.mark.parametrize("heading_sign", [1.0, -1.0])
def test_ported_window_gives_the_runtimes_window(walk, heading_sign):
    """Every foot and waist channel of every stride's window within 1e-9 (the port multiplies its attitude
    sample by sample, the kernel by a prefix scan); ``heading_sign`` -1 declares the foot's forward axis
    backwards (every stride then walks "backwards": the forward-sign rule is exercised both ways)."""
    from pdrlearn.runtime.tracker import forward_vector

    f_foot = heading_sign * forward_vector(walk.frames["foot"].to_dict())
    f_waist = forward_vector(walk.frames["waist"].to_dict())
    assert _compare_windows(walk, f_foot, f_waist, 14) >= 15  # t_s + 7 foot + 6 waist rows (no force, barometer)


def test_ported_window_at_204_hz():
    """The real 204.8 Hz foot recording: rest neighbourhoods of +-4 samples and the 7-sample box filter."""
    from pdrlearn.io import read_session
    from pdrlearn.runtime.tracker import forward_vector

    s = read_session(Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_level_left")
    assert _compare_windows(s, forward_vector(s.frames["foot"].to_dict()), None, 8) >= 25
