"""Decision L33 (docs/decisions/localization.md): a streamed stride's heading change runs from the stride's own
first sample to its last, so consecutive strides chain their turns without a hole. Before, it ran from the
start rest's quietest sample (the tilt reference, ~0.1 s into the stride on the gaitmap level walks) and the
turn of the foot in between was lost: 0.015 rad per stride of one sign, a heading drift of ~0.9 deg/s."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.io import read_session
from pdrlearn.kernels import window as KW
from pdrlearn.track.plasys import track_plasys
from tests.conftest import ROOT

FS = 100.0
G = 9.81


def _foot(t: np.ndarray, psi_rate: np.ndarray, pitch: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Body rate and specific force of a foot with attitude Rz(psi(t)) Ry(theta(t)) that does not translate."""
    dth = np.gradient(pitch, t)
    ry_t = Rotation.from_euler("y", pitch[:, None]).inv()  # Ry(theta)^T
    gyr = ry_t.apply(np.column_stack([0 * t, 0 * t, psi_rate])) + np.column_stack([0 * t, dth, 0 * t])
    acc = ry_t.apply(np.tile([0.0, 0.0, G], (len(t), 1)))
    return gyr, acc


def _stride(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """1-s strides from mid-stance: the foot finishes a turn on the ground in its first 0.1 s (0.3 rad/s
    decaying to 0: 0.015 rad per stride), rests, swings (pitch up to 0.6 rad) and rests again; body rate,
    specific force and the true turn from the first to the last sample (trapezoid, rad)."""
    u = np.round(t * FS) / FS % 1.0
    psi_rate = np.where(u < 0.1, 0.3 * (1.0 - u / 0.1), 0.0)
    pitch = np.where((u > 0.3) & (u < 0.8), 0.6 * np.sin(np.pi * (u - 0.3) / 0.5) ** 2, 0.0)
    turn = float(np.sum(0.5 * (psi_rate[1:] + psi_rate[:-1]) * np.diff(t)))
    return (*_foot(t, psi_rate, pitch), turn)


def test_the_turn_before_the_start_rests_quietest_sample_is_kept():
    t = np.arange(0.0, 1.0 + 0.5 / FS, 1.0 / FS)
    gyr, acc, turn = _stride(t)
    fwd = np.array([1.0, 0.0, 0.0])
    *_, dpsi = KW.foot_levelled(t, acc, gyr, fwd, rest_search_s=0.3, heading="declared", t0=0.0)
    assert turn > 0.015
    assert dpsi == pytest.approx(turn, abs=2e-4)  # was 0.0015: measured from the quietest sample (>= 0.1 s)


@pytest.mark.parametrize("split", [1.0, 1.004])  # on a sample, between two samples
def test_consecutive_strides_add_up_to_the_whole_turn(split):
    t = np.arange(0.0, 2.0 + 0.5 / FS, 1.0 / FS)
    gyr, acc, turn = _stride(t)
    streams = {"fAccelerometer": (t, acc), "fGyroscope": (t, gyr)}
    kw = {"available": ("foot_acc", "foot_gyr"), "forward": {"foot": np.array([1.0, 0.0, 0.0])},
          "rest_search_s": 0.3, "heading": "declared"}
    d1 = KW.levelled_units(streams, 0.0, split, **kw)["foot"][4]
    d2 = KW.levelled_units(streams, split, 2.0, **kw)["foot"][4]
    assert d1 + d2 == pytest.approx(turn, abs=4e-4)  # two strides, each 0.015 rad (was 0.0015 + 0.0015)


@pytest.mark.parametrize("side", ["left", "right"])
def test_streamed_level_walk_keeps_its_heading_and_turns_by_half_a_circle(side):
    """gaitmap 2 x 20 m: before L33 the streamed right foot drifted -15 mrad per stride on the first leg and
    turned 168 degrees (left: +186); offline turns 181 / 177 degrees."""
    d = ROOT / "datasets" / "real" / f"gaitmap_level_{side}"
    if not d.exists():
        pytest.skip(f"{d} not bundled")
    st = track_plasys(read_session(d), method="M3", model="oracle", heading="foot", streaming=True).steps
    h = np.unwrap(st["heading_rad"].to_numpy(float))
    leg1, leg2 = h[1:14], h[17:29]
    assert abs(np.polyfit(np.arange(len(leg1)), leg1, 1)[0]) < 0.012  # rad per stride
    assert abs(np.degrees(leg2.mean() - leg1.mean()) - 180.0) < 3.0


def test_a_foot_headed_stride_is_placed_along_the_heading_at_its_start():
    """Decision L34: heading after the stride less its own turn, plus the step frame's direction relative to the
    foot at the start and the displacement's direction in the step frame; a waist-headed stride: 0."""
    from pdrlearn.kernels.stride import placement_offset

    t = np.arange(3.0)
    foot = (t, np.zeros((3, 3)), np.zeros((3, 3)), np.ones(3), 1.2, 0.1)  # turned 1.2 rad, frame 0.1 rad left
    lev = {"foot": foot}
    assert placement_offset(lev, "foot", np.array([1.0, 0.2, 0.0])) == pytest.approx(0.1 + np.arctan(0.2) - 1.2)
    assert placement_offset(lev, "auto", np.array([-1.0, 0.2, 0.0])) == pytest.approx(0.1 - np.arctan(0.2) - 1.2)
    waist = (t, np.zeros((3, 3)), np.zeros((3, 3)), None, float("nan"))
    assert placement_offset({"foot": foot, "waist": waist}, "auto", np.array([1.0, 0.2, 0.0])) == 0.0
    assert placement_offset({"foot": foot, "waist": waist}, "waist-gyro", np.array([1.0, 0.2, 0.0])) == 0.0


@pytest.mark.parametrize(("side", "max_m"), [("left", 0.6), ("right", 0.9)])
def test_streamed_level_walk_ends_where_the_reference_does(side, max_m):
    """gaitmap 2 x 20 m, streamed (= pdrlearn run): final position error before L33 0.38 / 5.51 m (left / right),
    with L33 1.15 / 1.95 m (strides placed along the heading after them), with L34 0.29 / 0.53 m; offline 1.47 /
    0.22 m."""
    from pdrlearn.track.evaluate import evaluate_track

    d = ROOT / "datasets" / "real" / f"gaitmap_level_{side}"
    if not d.exists():
        pytest.skip(f"{d} not bundled")
    s = read_session(d)
    ev = evaluate_track(track_plasys(s, method="M3", model="oracle", streaming=True), s)
    assert ev["final_position_error_m"] < max_m
