"""Decisions S108 (``--contact forefoot``: a toe walker's level forefoot-first contact) and S109
(``--foot-sensor-pos``: the foot unit moved along the foot, e.g. onto the forefoot dorsum); trial T1 F6."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:6, stand:2"


def _walk(**knobs):
    user = UserProfile.from_seed(15020).scaled(1.30, 0.68)
    return simulate_path(parse_route(ROUTE), user, seed=0, rate_hz=100, noise=False, name="tw", **knobs)


def _loads_at_contacts(session):
    """Heel (fForceA) and forefoot (fForceB) load 30 ms after each of the tracked foot's truth contacts."""
    ics = session.extras["ics"]
    t_ic = ics[(ics["foot"] == "right") & (ics["kind"] == "walk")]["ic_s"].to_numpy(float)
    heel, fore = session.streams["fForceA"], session.streams["fForceB"]
    at = t_ic + 0.03
    return np.interp(at, heel.t, heel.values[:, 0]), np.interp(at, fore.t, fore.values[:, 0]), t_ic


def test_forefoot_contact_loads_the_forefoot_first_at_the_truth_contact_s108():
    heel_h, fore_h, t_h = _loads_at_contacts(_walk())
    heel_f, fore_f, t_f = _loads_at_contacts(_walk(contact="forefoot"))
    assert len(t_f) >= 3 and np.allclose(t_f, t_h)  # the contact times are the truth's, unchanged
    # heel contact: the heel carries the load just after the contact; forefoot contact: the forefoot does
    assert (heel_h > fore_h).all(), (heel_h, fore_h)
    assert (fore_f > heel_f).all() and (fore_f > 0).all(), (heel_f, fore_f)


def _pitch_rate_after_contacts(session) -> np.ndarray:
    ics = session.extras["ics"]
    t_ic = ics[(ics["foot"] == "right") & (ics["kind"] == "walk")]["ic_s"].to_numpy(float)
    gyro = session.streams["fGyroscope"]  # the thesis foot frame's z axis (right): the pitch rate
    return np.array([np.interp(t + 0.04, gyro.t, gyro.values[:, 2]) for t in t_ic])


def test_forefoot_contact_lowers_the_heel_about_the_ball_s108():
    # after a heel contact the foot plantarflexes (toes come down), after a forefoot contact it dorsiflexes (the
    # heel comes down): the pitch rate 40 ms after every truth contact has the opposite sign
    heel, fore = _pitch_rate_after_contacts(_walk()), _pitch_rate_after_contacts(_walk(contact="forefoot"))
    assert len(heel) >= 3 and len(fore) == len(heel)
    assert (np.sign(heel) == np.sign(heel[0])).all() and (np.sign(fore) == -np.sign(heel[0])).all(), (heel, fore)
    assert _walk(contact="forefoot").meta["knobs"]["contact"] == "forefoot"
    assert "contact" not in _walk().meta["knobs"]  # a default session's meta.json as before (META_ONLY_WHEN_SET)


def test_foot_sensor_pos_moves_the_unit_and_meta_records_it_s109():
    s = _walk(foot_sensor_pos=0.70)
    assert s.meta["user"]["foot_sensor_x_frac"] == 0.70
    assert s.meta["knobs"]["foot_sensor_pos"] == 0.70
    # the unit nearer the toes rises less at a heel strike's heel rocker than one at the user's own 25-50 %: its
    # truth position differs
    own = _walk()
    assert own.meta["user"]["foot_sensor_x_frac"] != 0.70
    a = own.extras["foot_trajectory"][["x", "y"]].to_numpy()[0]
    b = s.extras["foot_trajectory"][["x", "y"]].to_numpy()[0]
    assert np.linalg.norm(b - a) > 0.03


@pytest.mark.parametrize("knobs, words", [({"contact": "toe"}, "contact='toe' must be one of heel, forefoot"),
                                          ({"foot_sensor_pos": 0.95}, "foot_sensor_pos=0.95 must be a share"),
                                          ({"foot_sensor_pos": True}, "foot_sensor_pos=True must be a share")])
def test_bad_knobs_are_one_line_s108_s109(knobs, words):
    with pytest.raises(DataError, match=words.replace("(", r"\(")):
        _walk(**knobs)


@pytest.mark.parametrize("args, words", [(["--contact", "toes"], "--contact 'toes': must be heel or forefoot"),
                                         (["--foot-sensor-pos", "0.9"], "--foot-sensor-pos 0.9: give the unit's"),
                                         (["--bounce-scale", "5"], "--bounce-scale 5: give a factor"),
                                         (["--pelvis-height", "0.1"], "pelvis_height_m=0.1 must be")])
def test_cli_errors_are_one_line_and_write_nothing_s108_s109(tmp_path, capsys, args, words):
    out = tmp_path / "sim"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "15022", "--out", str(out), *args]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err, err
    assert not out.exists()


def test_cli_writes_a_toe_walker_on_the_forefoot_dorsum_s108_s109(tmp_path):
    out = tmp_path / "sim"
    assert main(["simulate", "--route", ROUTE, "--height", "1.30", "--leg-length", "0.68", "--contact", "forefoot",
                 "--foot-sensor-pos", "0.7", "--user-seed", "15021", "--out", str(out)]) == 0
    meta = json.loads((out / "meta.json").read_text())
    assert meta["knobs"]["contact"] == "forefoot" and meta["user"]["foot_sensor_x_frac"] == 0.7


def test_pelvis_height_and_bounce_scale_lower_and_damp_the_waist_unit_s109():
    own, crouch = _walk(), _walk(pelvis_height_m=0.60, bounce_scale=0.5)
    assert crouch.meta["user"]["sensor_height_m"] == 0.60 and crouch.meta["sensor_height_m"] == 0.60
    assert crouch.meta["user"]["pelvis_bounce_m"] == pytest.approx(0.5 * own.meta["user"]["pelvis_bounce_m"], abs=1e-5)

    def z_range(s):  # the waist unit's truth height while walking (the middle of the straight)
        tr = s.trajectory
        mid = tr[(tr["t"] > tr["t"].iloc[-1] / 2 - 1.0) & (tr["t"] < tr["t"].iloc[-1] / 2 + 1.0)]
        return mid["z"].median(), mid["z"].max() - mid["z"].min()

    (z_own, b_own), (z_crouch, b_crouch) = z_range(own), z_range(crouch)
    assert z_crouch < z_own - 0.1, (z_own, z_crouch)
    assert b_crouch < 0.75 * b_own, (b_own, b_crouch)


@pytest.mark.parametrize("knobs, words", [({"pelvis_height_m": 0.2}, "pelvis_height_m=0.2 must be 0.34-0.82 m"),
                                          ({"pelvis_height_m": -1.0}, "must be a positive number of metres"),
                                          ({"bounce_scale": 4.0}, "bounce_scale=4.0 must be 0 to 3")])
def test_bad_pelvis_knobs_are_one_line_s109(knobs, words):
    with pytest.raises(DataError, match=words):
        _walk(**knobs)
