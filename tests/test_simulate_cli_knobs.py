"""`simulate --heading0 / --mag-disturbance / --waist-mount` (decisions S32-S34): the Python simulator's initial
heading, indoor field disturbance and a waist unit turned on the belt, from the command line (session 19 trial
finding 15), each validated with one error line."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.cli.simulate import parse_mount
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:1, straight:4"


def _sim(tmp_path, name, *args):
    out = tmp_path / name
    assert main(["simulate", "--route", ROUTE, "--user-seed", "1", "--rate", "20", *args, "--out", str(out)]) == 0
    return read_session(out)


def test_heading0_turns_the_walk_and_the_magnetometer(tmp_path):
    east, north = _sim(tmp_path, "e"), _sim(tmp_path, "n", "--heading0", "90")
    d_e = east.trajectory[["x", "y"]].to_numpy()[-1] - east.trajectory[["x", "y"]].to_numpy()[0]
    d_n = north.trajectory[["x", "y"]].to_numpy()[-1] - north.trajectory[["x", "y"]].to_numpy()[0]
    assert abs(d_e[1]) < 0.3 < d_e[0] and abs(d_n[0]) < 0.3 < d_n[1]
    assert north.meta["knobs"]["heading0_deg"] == 90.0
    # standing still, the horizontal field turns by the heading in the unit's axes
    m_e, m_n = east["wMagneticField"].values[:10].mean(0), north["wMagneticField"].values[:10].mean(0)
    assert not np.allclose(m_e, m_n, atol=5.0)


def test_mag_disturbance_zero_is_the_clean_field(tmp_path):
    clean, dist = _sim(tmp_path, "c", "--mag-disturbance", "0"), _sim(tmp_path, "d", "--mag-disturbance", "30")
    spread = [np.ptp(np.linalg.norm(s["wMagneticField"].values, axis=1)) for s in (clean, dist)]
    assert clean.meta["knobs"]["mag_disturbance_ut"] == 0.0 and spread[1] > 3 * spread[0]


def test_waist_mount_is_the_python_knob_and_keeps_the_belt_frame(tmp_path):
    s = _sim(tmp_path, "m", "--waist-mount", "z:90", "--no-noise")
    py = simulate_path(parse_route(ROUTE), UserProfile.from_seed(1), rate_hz=20.0, seed=0, noise=False,
                       waist_mount_deg=(0.0, 0.0, 90.0), scenario="route")
    plain = simulate_path(parse_route(ROUTE), UserProfile.from_seed(1), rate_hz=20.0, seed=0, noise=False,
                          scenario="route")
    assert np.allclose(s["wAccelerometer"].values, py["wAccelerometer"].values, atol=1e-6)
    assert not np.allclose(s["wAccelerometer"].values, plain["wAccelerometer"].values, atol=0.5)
    assert s.meta["knobs"]["waist_mount_deg"] == [0.0, 0.0, 90.0]
    assert s.frames["waist"] == plain.frames["waist"]
    assert "waist_mount_deg" not in plain.meta["knobs"]  # default sessions' meta.json as before


def test_parse_mount_composes_rotations():
    assert parse_mount(None) == (0.0, 0.0, 0.0)
    assert parse_mount("z:90") == pytest.approx((0.0, 0.0, 90.0))
    want = Rotation.from_euler("ZX", [90, 180], degrees=True).as_rotvec(degrees=True)
    assert np.allclose(parse_mount("z:90,x:180"), want) or np.allclose(parse_mount("z:90,x:180"), -want)


@pytest.mark.parametrize("args, message", [
    (["--heading0", "400"], "--heading0 400: give the initial direction in degrees, -360 to 360"),
    (["--heading0", "nan"], "-360 to 360"),
    (["--mag-disturbance", "-1"], "--mag-disturbance -1: give 0-90 uT"),
    (["--mag-disturbance", "500"], "give 0-90 uT"),
    (["--waist-mount", "q:90"], "'q:90' is not AXIS:DEG"),
    (["--waist-mount", "z:ninety"], "is not AXIS:DEG"),
    (["--waist-mount", "z:90,y"], "'y' is not AXIS:DEG"),
    (["--variability", "-1"], "--variability -1: give a finite scale from 0 to 10"),  # decision S76
    (["--variability", "inf"], "give a finite scale from 0 to 10"),
    (["--variability", "100"], "--variability 100: give a finite scale from 0 to 10")])  # S76 amended (review R1)
def test_bad_values_are_one_line(tmp_path, capsys, args, message):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "1", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and not out.exists()


def test_help_names_the_options(capsys):
    main(["simulate", "--help"])
    text = capsys.readouterr().out
    assert "--heading0" in text and "--mag-disturbance" in text and "--waist-mount" in text
    assert "--variability" in text  # decision S76


def test_variability_is_the_python_knob(tmp_path):
    """Decision S76 (trial T1 finding F9): `--variability` is simulate_path's knob, recorded in meta.json."""
    route = "stand:2, straight:20, stand:2"
    steady, dual = (tmp_path / "v0", tmp_path / "v25")
    for out, v in ((steady, "0"), (dual, "2.5")):
        assert main(["simulate", "--route", route, "--user-seed", "7915", "--rate", "20", "--variability", v,
                     "--out", str(out)]) == 0
    py = simulate_path(parse_route(route), UserProfile.from_seed(7915), rate_hz=20.0, seed=0, variability=2.5,
                       scenario="route")
    s0, s25 = read_session(steady), read_session(dual)
    assert np.allclose(s25.steps["ic_s"].to_numpy(float), py.steps["ic_s"].to_numpy(float))
    assert s0.meta["knobs"]["variability"] == 0.0 and s25.meta["knobs"]["variability"] == 2.5
    cv = [np.std(np.diff(s.steps["ic_s"].to_numpy(float))[2:-2]) for s in (s0, s25)]
    assert cv[1] > 5 * cv[0] + 1e-3
