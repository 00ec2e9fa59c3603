"""A declared foot frame whose forward the data find turned by more than 77 deg (decision D28) or that declares the
unit's vertical axis forward (decision D30) is refused as D23's reversal, with the frame the data give; a unit yawed
on the shoe with the nearest axes declared is not (trial T3, session 38, findings 3 and 4)."""

from __future__ import annotations

import logging
import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.io.frames import AxisFrame
from pdrlearn.track.frame_inference import MISDECLARED_DEG, remount

#: x/y swapped, then z negated back as D11's advice says: right-handed data, the old frame kept
SWAPPED_Z_FIXED = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, -1]])


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("walk", user_seed=9640, length_m=30.0, rate_hz=100.0)


def _kept(walk, M):
    """The walk with its foot unit's data turned by ``v_new = M v_old`` and meta.json's foot frame kept."""
    s = remount(walk, "foot", M)
    s.frames["foot"] = walk.frames["foot"]
    return s


def _yaw(deg: float) -> np.ndarray:
    return Rotation.from_euler("y", deg, degrees=True).as_matrix().T  # about the thesis foot frame's up (y)


def test_the_threshold_is_the_geometry_midway():
    assert MISDECLARED_DEG == pytest.approx((np.degrees(np.arctan(2.0)) + 90.0) / 2.0)


@pytest.mark.parametrize("deg", [90.0, -90.0])
def test_a_unit_strapped_across_the_foot_with_the_old_frame_is_refused_with_the_data_frame(walk, deg):
    s = _kept(walk, _yaw(deg))
    with pytest.raises(DataError) as exc:
        s.require_frame("foot")
    m = str(exc.value)
    assert re.search(r"tracked turned \(the declared forward is turned by (89|90|91) deg, decision D28\)", m)
    assert "decision D23" in m and '"force_frame": true' in m
    right = remount(walk, "foot", _yaw(deg)).frames["foot"]  # the truthful frame of that mount
    assert str(right.to_dict()).replace("'", '"') in m  # the frame the data give is the frame to write


@pytest.mark.parametrize("deg", [20.0, -30.0, 45.0])
def test_a_yawed_unit_with_the_nearest_axes_declared_is_not_refused(walk, deg):
    s = _kept(walk, _yaw(deg))
    assert s.require_frame("foot") == walk.frames["foot"]


def test_force_frame_keeps_a_turned_declaration(walk, caplog):
    s = _kept(walk, _yaw(90.0))
    s.meta["force_frame"] = ["foot"]
    with caplog.at_level(logging.WARNING):
        assert s.require_frame("foot") == walk.frames["foot"]
    assert any('("force_frame", decision D23) is still used' in r.getMessage() for r in caplog.records)


def test_a_declared_forward_that_is_the_vertical_axis_is_refused(walk):
    s = _kept(walk, SWAPPED_Z_FIXED)
    with pytest.raises(DataError) as exc:
        s.require_frame("foot")
    m = str(exc.value)
    assert "the declared forward is the unit's vertical axis, decision D30" in m and "decision D23" in m
    right = remount(walk, "foot", SWAPPED_Z_FIXED).frames["foot"]
    assert str(right.to_dict()).replace("'", '"') in m


def test_d11_advice_on_a_swapped_foot_gives_the_frame_to_write_after_the_fix(walk, caplog):
    """Trial T3 finding 4: D11's advice (negate z back) followed, the old frame kept, tracked backward 73.5 m off:
    the warning now gives the whole frame to write after the fix, and that frame is accepted."""
    swap = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, 1]])
    s = _kept(walk, swap)
    with caplog.at_level(logging.WARNING):
        assert s.handedness("foot").mirrored
    (m,) = [r.getMessage() for r in caplog.records if "left-handed (mirrored) pair" in r.getMessage()]
    want = '"frames": {"foot": {"x": "up", "y": "forward", "z": "left"}} (decision D30)'
    assert "negate the z axis back" in m and m.endswith(f"they give {want}")
    fixed = remount(walk, "foot", SWAPPED_Z_FIXED)  # the fix done, the frame written as the warning says
    fixed.frames["foot"] = AxisFrame(x="up", y="forward", z="left")
    assert fixed.require_frame("foot") == AxisFrame(x="up", y="forward", z="left")
