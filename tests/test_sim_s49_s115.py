"""Decisions S115 (``simulate --swing-height``), S116 (``--pelvis-sway``) and S117 (``--waist-mount-drift``);
session 49, trials s49t1 / s49t3."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.cli.simulate import parse_mount, with_swing_and_sway
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.body import toe_off_pitch_for_apex, toe_tip_m
from pdrlearn.sim.route import parse_route
from tests.sim_helpers import session_digest as _digest

ROUTE = parse_route("stand:1, straight:5, stand:1")
USER = UserProfile.from_seed(16712)


def _walk(user=USER, **knobs):
    return simulate_path(ROUTE, user, seed=1, noise=False, stand_s=1.0, **knobs)


def _range(v):
    return float(np.max(v) - np.percentile(v, 5))


@pytest.fixture(scope="module")
def walks():
    return {"own": _walk(), "low": _walk(with_swing_and_sway(USER, 0.06, None)),
            "sway": _walk(with_swing_and_sway(USER, None, 0.10))}


def test_swing_height_lowers_the_foot_unit_and_meta_records_it_s115(walks):
    low = walks["low"]
    assert low.meta["user"]["swing_height_m"] == 0.06
    pitch = low.meta["user"]["toe_off_pitch_deg"]
    assert pitch == toe_off_pitch_for_apex(USER, 0.06) > -15.0  # a nearly flat toe-off (the user's: -50 to -58)
    # S23's heel height at the toe-off knot: toe clearance + toe tip x sin(plantarflexion) = the apex asked for
    assert USER.toe_clearance_m + toe_tip_m(USER) * np.sin(np.radians(-pitch)) == pytest.approx(0.06, abs=1e-4)
    own, lo = (_range(walks[k].extras["foot_trajectory"]["z"]) for k in ("own", "low"))
    assert own > 0.12 and lo < 0.6 * own, (own, lo)  # the swing_height_m field alone left it unchanged (S115)
    np.testing.assert_array_equal(low.steps["length_m"], walks["own"].steps["length_m"])  # the same footprints


def test_pelvis_sway_moves_the_waist_unit_sideways_s116(walks):
    assert walks["sway"].meta["user"]["pelvis_sway_m"] == 0.10
    y_own, y_sway = (_range(walks[k].trajectory["y"]) for k in ("own", "sway"))
    assert y_sway > y_own + 0.05, (y_own, y_sway)  # the walk is along x: the sway is the y excursion


@pytest.mark.parametrize("args, match", [
    ((0.5, None), "--swing-height 0.5: give the heel's highest point"),
    ((0.05, None), "0.06 to 0.3"),  # decision S118
    ((None, -0.1), "--pelvis-sway -0.1: give the pelvis's side-to-side sway amplitude in metres, 0 to 0.15"),
    ((None, float("nan")), "--pelvis-sway nan"),
])
def test_bad_swing_and_sway_are_one_line(args, match):
    with pytest.raises(DataError, match=match):
        with_swing_and_sway(USER, *args)
    with pytest.raises(DataError, match="--pelvis realistic draws its own"):
        with_swing_and_sway(USER, None, 0.05, "realistic")
    assert with_swing_and_sway(USER, None, None) is USER


def _stand(**knobs):
    return simulate_path(parse_route("stand:8"), USER, seed=1, noise=False, stand_s=4.0, **knobs)


def test_waist_mount_drift_turns_gravity_and_the_gyroscope_says_so_s117():
    s = _stand(waist_mount_deg=(0.0, 0.0, 90.0), waist_mount_end_deg=(0.0, 20.0, 0.0))
    acc, gyr = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    a0, a1 = acc.values[:3].mean(axis=0), acc.values[-3:].mean(axis=0)
    turned = Rotation.from_rotvec(np.radians([0.0, 20.0, 0.0])) * Rotation.from_rotvec(np.radians([0, 0, 90.0])).inv()
    # gravity in the unit turns by the angle between the start and the end mount
    angle = np.degrees(np.arccos(a0 @ a1 / np.linalg.norm(a0) / np.linalg.norm(a1)))
    assert angle == pytest.approx(np.degrees(np.arcsin(np.linalg.norm(  # the tilt part of the turn
        np.cross(turned.apply([0, 0, 1.0]), [0, 0, 1.0])))), abs=0.5)
    # standing still, the gyroscope is the turn's own rate: its integral rotates the start's gravity onto the end's
    total = np.trapezoid(gyr.values, gyr.t, axis=0) * (len(gyr.t) / (len(gyr.t) - 1))
    assert np.degrees(np.linalg.norm(total)) == pytest.approx(np.degrees(turned.magnitude()), abs=0.5)
    back = Rotation.from_rotvec(-total).apply(a0)
    assert np.degrees(np.arccos(back @ a1 / np.linalg.norm(back) / np.linalg.norm(a1))) < 0.5
    assert s.meta["knobs"]["waist_mount_end_deg"] == [0.0, 20.0, 0.0]
    fixed = _stand(waist_mount_deg=(0.0, 0.0, 90.0))
    assert "waist_mount_end_deg" not in fixed.meta["knobs"]
    np.testing.assert_allclose(fixed.streams["wAccelerometer"].values[0], acc.values[0], atol=0.02)  # same start
    np.testing.assert_array_equal(fixed.streams["fAccelerometer"].values, s.streams["fAccelerometer"].values)


def test_default_session_is_the_pinned_digest():
    """A default session (streams, truth, meta; noise on) is bit for bit the one before these options: its digest
    (test_sim's S27 digest) was computed with main at 3edc46c3, before S115-S117."""
    s = simulate_path(ROUTE, USER, seed=1, stand_s=1.0)
    assert _digest(s) == "8a3d75df7c02f465b08adc80849d3045d027534655dca021368aefe497119f30"
    assert _digest(simulate_path(ROUTE, USER, seed=1, stand_s=1.0, waist_mount_end_deg=None)) == _digest(s)


def test_cli_writes_the_three_options_to_meta_and_refuses_bad_ones(tmp_path, capsys):
    out = tmp_path / "s"
    main(["simulate", "--route", "stand:2", "--user-seed", "16713", "--swing-height", "0.06", "--pelvis-sway",
          "0.08", "--waist-mount-drift", "y:20", "--out", str(out)])
    meta = json.loads((out / "meta.json").read_text())
    assert meta["user"]["swing_height_m"] == 0.06 and meta["user"]["pelvis_sway_m"] == 0.08
    assert meta["knobs"]["waist_mount_end_deg"] == [0.0, 20.0, 0.0]
    with pytest.raises(DataError, match="--waist-mount-drift 'w:20': 'w:20' is not AXIS:DEG"):
        parse_mount("w:20", "--waist-mount-drift")
    assert main(["simulate", "--route", "stand:2", "--user-seed", "1", "--waist-mount-drift", "y:x", "--out",
                 str(tmp_path / "bad")]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["error: --waist-mount-drift 'y:x': 'y:x' is not AXIS:DEG; give x, y or z (forward, left, up) and "
                   "-360 to 360 degrees, e.g. 'z:90' or 'z:90,x:180'"] and not (tmp_path / "bad").exists()
