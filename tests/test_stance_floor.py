"""Decision L27 (docs/decisions/localization.md): the foot stance threshold follows the walker's own stance
rotation (rolling instep mounts, short foot-flats), offline (``inertial_stance``) and streaming
(``StanceSegmenter``, the runtime's and ``track --streaming``'s shared kernel)."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace.foot import inertial_stance, stance_runs
from pdrlearn.errors import DataError
from pdrlearn.kernels.stride import StanceSegmenter, stance_strides
from tests.conftest import external_session

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
E7 = {"stance_floor_factor": 0.0, "stance_gap_s": 0.0, "stance_mean_min_s": 0.0}  # the fixed rule before L27, L29


def _walk(stance_level: float, *, fs: float = 100.0, n_strides: int = 12, stance_s: float = 0.35,
          swing_s: float = 0.75, spike: float | None = None, seed: int = 0):
    """Foot gyro/acc of a walk: 2 s standing, strides (stance rolling at ``stance_level`` rad/s about the
    lateral axis, half-sine swing peaking at 6 rad/s), 1 s standing. ``spike``: one sample of that |w| in
    the middle of every stance."""
    rng = np.random.default_rng(seed)
    dt = 1.0 / fs
    parts_g, parts_a, stances = [np.zeros((int(2 * fs), 3))], [np.tile([0, 0, 9.81], (int(2 * fs), 1))], []
    t0 = 2.0
    for _ in range(n_strides):
        ns, nw = int(round(stance_s * fs)), int(round(swing_s * fs))
        g = np.zeros((ns, 3))
        g[:, 1] = stance_level
        if spike is not None:
            g[ns // 2, 1] = spike
        stances.append(t0 + 0.5 * stance_s)
        sw = np.zeros((nw, 3))
        ph = np.sin(np.pi * (np.arange(nw) + 0.5) / nw)
        sw[:, 1] = 6.0 * ph * np.sign(np.sin(2 * np.pi * (np.arange(nw) + 0.5) / nw))
        parts_g += [g, sw]
        parts_a += [np.tile([0, 0, 9.81], (ns, 1)), np.column_stack([5 * ph, 0 * ph, 9.81 + 8 * ph])]
        t0 += stance_s + swing_s
    parts_g.append(np.zeros((int(fs), 3)))
    parts_a.append(np.tile([0, 0, 9.81], (int(fs), 1)))
    gyr = np.vstack(parts_g) + rng.normal(0, 0.02, (sum(len(p) for p in parts_g), 3))
    acc = np.vstack(parts_a) + rng.normal(0, 0.05, gyr.shape)
    t = np.arange(len(gyr)) * dt
    return t, gyr, acc, np.array(stances)


def test_rolling_stance_is_found_streaming_and_offline():
    t, gyr, acc, stances = _walk(1.1)  # the instep mount of the 4x10 m walk rolls at ~1 rad/s in stance
    old = stance_strides(t, gyr, E7)
    new = stance_strides(t, gyr)
    assert len(old) == 0  # |w| never below the fixed 0.8 rad/s: no stride (the failure L27 fixes)
    assert len(new) >= len(stances) - 2
    # boundaries in the stances (middles within half a stance; the last stride ends in the final standstill)
    assert np.abs(new[:-1, 1, None] - stances[None, :]).min(axis=1).max() < 0.2
    fs = 1.0 / (t[1] - t[0])
    assert len(stance_runs(t, inertial_stance(acc, gyr, fs, floor_factor=0.0))) == 2  # the standstills only
    runs = stance_runs(t, inertial_stance(acc, gyr, fs))
    # every stance but the first after standing (its floor window still holds the standstill: fixed threshold)
    assert len(runs) >= len(stances) + 1


def test_short_foot_flat_with_a_spike_is_one_stance():
    # 0.13 s foot-flats (MS patient: 0.12-0.19 s) with one 1.5 rad/s sample (heel impact ringing)
    t, gyr, _, stances = _walk(0.3, stance_s=0.13, swing_s=0.8, spike=1.5)
    assert len(stance_strides(t, gyr, E7)) == 0
    assert len(stance_strides(t, gyr)) >= len(stances) - 1


def test_calm_stance_keeps_the_fixed_threshold():
    t, gyr, _, _ = _walk(0.05)
    seg = StanceSegmenter()
    thr = np.array(seg._thresholds(t.tolist(), np.linalg.norm(gyr, axis=1).tolist()))
    assert np.all(thr == 0.8)  # floor x 2 stays below 0.8: decision E7's threshold
    np.testing.assert_array_equal(stance_strides(t, gyr, {"stance_mean_min_s": 0.0}), stance_strides(t, gyr, E7))
    # decision L29's window-mean test only widens a stance by less than half its 0.1 s window
    new, e7 = stance_strides(t, gyr), stance_strides(t, gyr, E7)
    assert new.shape == e7.shape and np.abs(new - e7).max() <= 0.05


def test_threshold_is_capped_and_chunk_invariant():
    t, gyr, _, _ = _walk(1.6, seed=3)  # floor 1.6 x 2 = 3.2 -> capped at 2 rad/s
    seg = StanceSegmenter()
    thr = np.array(seg._thresholds(t.tolist(), np.linalg.norm(gyr, axis=1).tolist()))
    assert thr.max() == 2.0 and thr.min() == 0.8
    whole = stance_strides(t, gyr)
    seg, parts = StanceSegmenter(), []
    rng = np.random.default_rng(1)
    i = 0
    while i < len(t):
        j = i + int(rng.integers(1, 60))
        parts += seg.update(t[i:j], gyr[i:j])
        i = j
    np.testing.assert_array_equal(np.array(parts).reshape(-1, 2), whole)


def test_bad_floor_parameters_are_one_line_errors():
    with pytest.raises(DataError, match="L27"):
        StanceSegmenter(stance_floor_factor=-1)


def _matched(session, strides: np.ndarray) -> tuple[int, int]:
    import pdrlearn.steps as S
    from pdrlearn.track.evaluate import match_by_overlap

    det = S.AccelStepDetector().detect(session)
    got = pd.DataFrame(np.asarray(strides).reshape(-1, 2), columns=["start_s", "end_s"])
    return len(match_by_overlap(got, det[["start_s", "end_s"]], min_iou=0.5)), len(det)


def _streamed_and_offline(d: Path) -> tuple[tuple[int, int], tuple[int, int]]:
    from pdrlearn.io import read_session
    from pdrlearn.orient import unit_data
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        s = read_session(d)
        f = unit_data(s, "foot")
        streamed = _matched(s, stance_strides(f.t, f.gyr))
        off = track_plasys(s, method="M3", model="oracle", steps="detector")
        offline = _matched(s, off.steps[["start_s", "end_s"]].to_numpy(float))
    finally:
        logging.disable(logging.NOTSET)
    return streamed, offline


@pytest.mark.parametrize("name", ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_down_left",
                                  "gaitmap_stairs_up_left"])
def test_bundled_foot_recordings_keep_every_detected_stride(name):
    for found, det in _streamed_and_offline(REAL / name):
        assert found >= det - 1, (name, found, det)


@pytest.mark.parametrize("name,min_frac", [("gaitmap_walk4x10_left", 0.93), ("gaitmap_walk4x10_right", 0.93),
                                           ("gaitmap_stairs_down_right", 0.99), ("gaitmap_stairs_up_right", 0.99),
                                           ("gaitmap_ms_left", 0.9), ("gaitmap_ms_right", 0.9)])
def test_external_foot_recordings_find_the_detected_strides(name, min_frac):
    d = external_session(name)
    for found, det in _streamed_and_offline(d):
        assert found >= min_frac * det, (name, found, det)


def test_bundle_parameters_reach_the_segmenter():
    seg = StanceSegmenter.from_params({"stance_gyro_rad_s": 0.8, "stance_floor_factor": 0.0, "stance_gap_s": 0.0,
                                       "stance_floor_window_s": 2.0, "stance_gyro_max_rad_s": 3.0, "unit": "x"})
    assert (seg.factor, seg.gap, seg.floor_window_s, seg.cap) == (0.0, 0.0, 2.0, 3.0)
    from pdrlearn.export.from_model import _displacement
    from pdrlearn.kernels.stride import STANCE_L27_DEFAULTS

    disp = _displacement(None, None, None)
    assert all(disp[k] == v for k, v in STANCE_L27_DEFAULTS.items())


def test_a_foot_pivoting_between_strides_turns_the_heading():
    """Decision L28: between two strides that do not touch, the turn about gravity of a pivoting foot is
    kept; a still foot (|w| below the ZARU threshold) does not turn."""
    from pdrlearn.displace import FootDisplacement

    fs, n = 100.0, 300
    acc = np.tile([0.0, 0.0, 9.81], (n, 1))
    gyr = np.zeros((n, 3))
    gyr[100:200, 2] = 1.0  # 1 s pivot at 1 rad/s about the vertical, between stride 0 (ends 90) and 1 (starts 210)
    fd = FootDisplacement()
    i0, i1 = np.array([0, 210]), np.array([90, 290])
    gy = fd._gap_yaw(acc, gyr, 1 / fs, i0, i1, None)
    assert gy[0] == 0 and gy[1] == pytest.approx(1.0, abs=0.02)
    gyr[100:200, 2] = 0.2  # below the 0.4 rad/s ZARU threshold: a still foot
    assert fd._gap_yaw(acc, gyr, 1 / fs, i0, i1, None)[1] == 0
    fd.yaw_change_, fd.gap_yaw_ = np.array([0.1, 0.2]), np.array([0.0, 1.0])
    np.testing.assert_allclose(fd.foot_heading(0.5), [0.5, 1.6])


def test_l_walk_turns_are_right_angles_and_turnarounds():
    """Real L-walk (400 Hz, 250 s): every turn between straight legs is a 90-degree corner or a 180-degree
    turnaround within 20 deg (before L28 one turnaround measured +62 deg: its pivot fell between strides)."""
    d = external_session("gaitmap_lwalk")
    from pdrlearn.io import read_session
    from pdrlearn.track.evaluate import straight_legs
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        r = track_plasys(read_session(d), method="M3", model="oracle", steps="detector", heading="foot")
    finally:
        logging.disable(logging.NOTSET)
    h = np.degrees(np.unwrap(r.steps["heading_rad"].to_numpy(float)))
    legs = straight_legs(h)
    turns = np.diff([np.mean(h[g[1:-1]]) for g in legs])
    assert len(turns) >= 10
    err = np.minimum(np.abs(np.abs(turns) - 90), np.abs(np.abs(turns) - 180))
    assert err.max() < 20, np.round(turns)
