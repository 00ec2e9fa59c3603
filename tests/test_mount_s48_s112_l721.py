"""Decisions S112 (``--foot-sensor-height``), S113 (``--foot-mount-roll``) and L721 (``--reference-point heel``'s
``max_heel_lift_m``: the heel's lift, the same whatever the mount); trial T3 F3 / F7."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.displace.foot import heel_lift
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:8, stand:2"


def _walk(**knobs):
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(15841), seed=1, rate_hz=100, noise=False,
                         rocker="smooth", **knobs)


@pytest.fixture(scope="module")
def mounts():
    return _walk(foot_sensor_height_m=0.06), _walk(foot_sensor_height_m=0.10, foot_mount_pitch_deg=15.0)


def test_foot_sensor_height_raises_the_unit_and_meta_records_it_s112(mounts):
    a, b = mounts
    assert a.meta["user"]["foot_sensor_height_m"] == 0.06 and b.meta["knobs"]["foot_sensor_height_m"] == 0.10
    za, zb = (s.extras["foot_trajectory"]["z"].to_numpy()[0] for s in mounts)
    assert zb - za == pytest.approx(0.04, abs=1e-6)  # the foot flat at the first rest: the unit 4 cm higher
    default = _walk(stand_s=0.5)
    assert "foot_sensor_height_m" not in default.meta["knobs"] and "foot_mount_roll_deg" not in default.meta["knobs"]


def test_foot_mount_roll_tilts_the_unit_sideways_s113():
    def rest_lateral(s):  # the thesis foot frame: y along gravity at rest, z to the side
        acc = s.streams["fAccelerometer"]
        return abs(float(np.mean(acc.values[acc.t < 1.0, 2])))
    assert rest_lateral(_walk(foot_mount_roll_deg=30.0, stand_s=1.5)) > 4.0  # ~ g sin 30 deg
    assert rest_lateral(_walk(stand_s=1.5)) < 1.5  # the user's few-degree misalignment only


def test_heel_lift_kernel_adds_the_lever_arm_turned_by_the_attitude_l721():
    # the sensor stays put while the foot pitches about it up to 60 deg and back: the point 0.1 m behind and 0.05 m
    # below it rises to 0.1 sin 60 - 0.05 cos 60 + 0.05 above its rests; the sensor itself does not rise
    ang = np.radians(np.concatenate([np.linspace(0, 60, 31), np.linspace(60, 0, 31)]))
    q = np.stack([np.cos(ang / 2), np.zeros_like(ang), np.sin(ang / 2), np.zeros_like(ang)], axis=1)[None]
    pos, mask = np.zeros((1, len(ang), 3)), np.ones((1, len(ang)), dtype=bool)
    want = 0.1 * np.sin(np.radians(60)) - 0.05 * np.cos(np.radians(60)) + 0.05
    assert heel_lift(pos, q, mask, np.array([-0.1, 0.0, -0.05]))[0] == pytest.approx(want, abs=1e-9)
    assert heel_lift(pos, q, mask, np.zeros(3))[0] == pytest.approx(0.0, abs=1e-12)


def test_heel_lift_is_the_same_for_two_mounts_while_the_sensor_lift_is_not_l721(mounts):
    from pdrlearn.track.plasys import track_plasys

    heel = [track_plasys(s, params={"reference_point": "heel"}).steps for s in mounts]
    sensor_only = track_plasys(mounts[0]).steps
    assert "max_heel_lift_m" not in sensor_only  # the column comes with --reference-point heel only
    d_sensor = np.nanmedian(heel[1]["max_sensor_lift_m"]) - np.nanmedian(heel[0]["max_sensor_lift_m"])
    d_heel = np.nanmedian(heel[1]["max_heel_lift_m"]) - np.nanmedian(heel[0]["max_heel_lift_m"])
    assert abs(d_sensor) > 0.01 and abs(d_heel) < abs(d_sensor) / 3, (d_sensor, d_heel)


@pytest.mark.parametrize("knobs, words", [({"foot_sensor_height_m": 0.5}, "foot_sensor_height_m=0.5 must be the"),
                                          ({"foot_sensor_height_m": True}, "foot_sensor_height_m=True must be"),
                                          ({"foot_mount_roll_deg": 120.0}, "foot_mount_roll_deg=120.0 must be -90")])
def test_bad_knobs_are_one_line_s112_s113(knobs, words):
    with pytest.raises(DataError, match=words):
        _walk(**knobs)


@pytest.mark.parametrize("args, words", [(["--foot-sensor-height", "0.3"], "--foot-sensor-height 0.3: give the"),
                                         (["--foot-mount-roll", "100"], "--foot-mount-roll 100: give a sideways")])
def test_cli_errors_are_one_line_and_write_nothing_s112_s113(tmp_path, capsys, args, words):
    out = tmp_path / "sim"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "15841", "--out", str(out), *args]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


def test_cli_writes_the_mount_s112_s113(tmp_path):
    out = tmp_path / "sim"
    assert main(["simulate", "--route", "stand:1, straight:2, stand:1", "--user-seed", "15841", "--stand", "1",
                 "--foot-sensor-height", "0.09", "--foot-mount-roll", "10", "--out", str(out)]) == 0
    meta = json.loads((out / "meta.json").read_text())
    assert meta["user"]["foot_sensor_height_m"] == 0.09 and meta["knobs"]["foot_mount_roll_deg"] == 10.0
