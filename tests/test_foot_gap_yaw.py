"""Decision L31 (docs/decisions/localization.md): the streamed form of L28's gap yaw (a foot pivoting between
two strides keeps its turn), numpy only, shared with the offline foot heading."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.stride import gap_yaw, pivot_yaw


def _gap(rate_z: float, fs: float = 100.0, dur: float = 3.0, tilt_deg: float = 0.0):
    t = np.arange(int(dur * fs)) / fs
    gyr = np.zeros((len(t), 3))
    gyr[:, 2] = rate_z
    a = np.radians(tilt_deg)  # the unit tilted on the loaded foot: gravity and the pivot axis tilt together
    rot = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
    acc = np.tile([0.0, 0.0, 9.81], (len(t), 1)) @ rot.T
    return t, gyr @ rot.T, acc


@pytest.mark.parametrize("tilt", [0.0, 40.0])
def test_a_pivoting_foot_turns_by_its_rate_about_gravity(tilt):
    t, gyr, acc = _gap(0.8, tilt_deg=tilt)
    assert gap_yaw(t, gyr, t, acc, 1.0, 1.5) == pytest.approx(0.4, abs=1e-9)  # 0.5 s at 0.8 rad/s
    # the look-back stops one second before the next stride (what the runtime still holds)
    assert gap_yaw(t, gyr, t, acc, 0.0, 2.5) == pytest.approx(0.8, abs=1e-9)
    assert gap_yaw(t, gyr, t, acc, 0.0, 2.5, max_s=2.5) == pytest.approx(2.0, abs=1e-9)


def test_gap_between_samples_chains_with_the_next_strides_first_sample():
    # t1 between two samples: the next stride's turn starts at its first sample at or after t1 (L33), so
    # the gap runs to that sample; before, the interval holding t1 was counted by neither (review, s6)
    t, gyr, acc = _gap(0.8)
    assert gap_yaw(t, gyr, t, acc, 1.005, 1.505) == pytest.approx(0.8 * (1.51 - 1.01), abs=1e-9)
    assert gap_yaw(t, gyr, t, acc, 1.0, 2.995) == pytest.approx(0.8 * (2.99 - 2.0), abs=1e-9)  # data end


def test_a_still_foot_and_touching_strides_do_not_turn():
    t, gyr, acc = _gap(0.3)  # below the 0.4 rad/s ZARU threshold: still
    assert gap_yaw(t, gyr, t, acc, 0.5, 1.5) == 0.0
    t, gyr, acc = _gap(1.0)
    assert gap_yaw(t, gyr, t, acc, 1.5, 1.5) == 0.0  # strides touch
    assert pivot_yaw(t[:1], gyr[:1], acc[0]) == 0.0  # one sample: no interval
    assert pivot_yaw(t, gyr, np.zeros(3)) == 0.0  # no gravity estimate


def test_streaming_gap_yaw_changes_only_the_heading():
    sim = pytest.importorskip("pdrlearn.sim")
    from pdrlearn.track.plasys import track_streaming

    s = sim.simulate("A", user_seed=1, speed="normal")
    a = track_streaming(s, method="M2", heading="foot", gap_yaw=False)
    b = track_streaming(s, method="M2", heading="foot")  # on by default since 9fd85b4 (L31 in the runtime)
    np.testing.assert_array_equal(a.steps["length_m"], b.steps["length_m"])
    assert len(a.steps) == len(b.steps)


def test_track_plasys_forwards_gap_yaw_to_streaming(monkeypatch):
    sim = pytest.importorskip("pdrlearn.sim")
    import pdrlearn.track.plasys as P

    seen = []
    real = P.track_streaming
    monkeypatch.setattr(P, "track_streaming", lambda s, **kw: seen.append(kw.get("gap_yaw")) or real(s, **kw))
    s = sim.simulate("A", user_seed=1, speed="normal")
    P.track_plasys(s, method="M2", streaming=True, heading="foot", gap_yaw=True)
    P.track_plasys(s, method="M2", streaming=True, heading="foot")
    assert seen == [True, None]  # None: track_streaming's own default
