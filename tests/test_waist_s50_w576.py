"""Decision W576: a belt slide moves the quiet standing too, a walking trunk's lean does not - W565's line (and W566's
correction) with ``mount_drift`` "standing" needs the standing before the first and after the last walking bout to
follow the walking upright (pdrlearn.waist.mount_drift.standing_follows)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.waist import mount_drift as M
from pdrlearn.waist.ahrs import WaistIMU

FS = 50.0
BOUTS = ((5.0, 15.0), (45.0, 55.0), (85.0, 95.0))


def _recording(kind: str, end_s: float = 100.0):
    """A recording with three walking bouts (contacts every 0.5 s, the trunk moving 0.5 s either side of each) and
    still spans between them. ``kind`` "slide": every sample's up direction turns linearly about y by 20 deg over
    the recording (the unit on the belt); "lean": only the walking samples lean, by 0, 8 and 16 deg (the standing
    stays where it was)."""
    t = np.arange(0.0, end_s, 1.0 / FS)
    walking = np.zeros(t.size, bool)
    for a, b in BOUTS:
        walking |= (t >= a - 0.5) & (t <= b + 0.5)
    if kind == "slide":
        ang = np.radians(5.0 + 20.0 * t / 100.0)
    else:
        bout_no = np.searchsorted([a for a, _ in BOUTS], t, side="right") - 1
        ang = np.radians(5.0 + np.where(walking, 8.0 * np.clip(bout_no, 0, 2), 0.0))
    up = np.column_stack([np.sin(ang), np.zeros_like(t), np.cos(ang)])
    gyr = np.zeros((t.size, 3))
    gyr[walking, 2] = 1.0  # moving while walking, still (W277) elsewhere
    imu = WaistIMU(t=t, fs=FS, acc_nav=gyr * 0, gyr_nav=gyr, yaw=t * 0, acc_v=t * 0, acc_h=gyr[:, :2] * 0,
                   acc_ap=t * 0, acc_ml=t * 0, up_body=up)
    ev = np.concatenate([np.arange(a, b, 0.5) for a, b in BOUTS])
    has_next = np.concatenate([np.r_[np.ones(int((b - a) / 0.5) - 1, bool), False] for a, b in BOUTS])
    return imu, ev, has_next


def test_a_slide_moves_the_standing_and_is_said_a_lean_is_not_w576():
    slide = _recording("slide")
    out, line = M.drift_imu(*slide, standing=True)
    assert line is not None and "turned on the belt" in line and out is not slide[0]  # said and corrected (W566)
    lean = _recording("lean")
    assert M.drift_imu(*lean)[1] is not None  # W565 alone reads the lean as a 16 deg drift (HA002's case, W571)
    assert M.drift_imu(*lean, standing=True) == (lean[0], None)  # W576: the standing did not move
    walks = M.walking_bouts(lean[0].t, lean[0].up_body, lean[1], lean[2])
    assert [(a, b) for a, b, _ in walks] == [(5.0, 14.5), (45.0, 54.5), (85.0, 94.5)]
    assert M.drift_deg([(0.5 * (a + b), u) for a, b, u in walks]) == pytest.approx(16.0, abs=0.1)


def test_without_standing_after_the_last_bout_nothing_is_said_w576():
    cut = _recording("slide", end_s=96.0)  # the recording ends 1.5 s after the last contact, still walking
    assert M.drift_imu(*cut)[1] is not None and M.drift_imu(*cut, standing=True)[1] is None
    imu, ev, hn = _recording("slide")
    still = np.linalg.norm(imu.gyr_nav, axis=1) == 0
    walks = M.walking_bouts(imu.t, imu.up_body, ev, hn)
    assert M.standing_follows(imu.t, imu.up_body, still, walks)
    assert not M.standing_follows(imu.t, imu.up_body, still, walks, gap_s=0.4)  # the spans start 1 s from walking
    assert M.standing_around(imu.t, imu.up_body, still, 5.0, 94.5, 1.5) is not None


def test_the_option_takes_standing_and_refuses_other_words_w576(monkeypatch):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    s = simulate_path(parse_route("straight:4, stand:2, straight:4"), UserProfile.from_seed(17150), seed=1,
                      stand_s=2.0)
    seen = []
    monkeypatch.setattr(M, "drift_imu", lambda imu, ev, hn, **kw: (seen.append(kw), (imu, None))[1])
    p, _ = resolve_params(s, None)
    p.options = {"mount_drift": "standing"}
    track_waist(s, pipeline="waist-pendulum", params=p)
    assert seen == [{"standing": True}]  # W576's check reaches the kernel
    p.options = {"mount_drift": "sometimes"}
    with pytest.raises(DataError, match="W576"):
        track_waist(s, pipeline="waist-pendulum", params=p)
