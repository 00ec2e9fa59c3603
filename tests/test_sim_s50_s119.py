"""Decisions S119 (``simulate --prosthetic-side`` with one foot's own toe-off / heel-strike pitch and impact) and S120
(``--longer-stance-side``); session 50, trial T2 (prosthetics gait lab) finding F7."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.body import schedule
from pdrlearn.sim.path import plan_footsteps
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.user import side_foot
from pdrlearn.track.bilateral import check_clock

ROUTE = parse_route("stand:1, straight:5, stand:1")
USER = UserProfile.from_seed(17680)
STIFF = {"prosthetic_side": "left", "prosthetic_toe_off_pitch_deg": -15.0, "prosthetic_heel_strike_pitch_deg": 8.0,
         "prosthetic_impact_speed_mps": 0.3}


def _events(**kw):
    rng = np.random.default_rng(3)
    steps = plan_footsteps(ROUTE, USER, rng=rng)[0]
    return steps, schedule(steps, USER, speed="normal", rng=rng, stand_s=1.0, **kw)


def test_the_named_foot_takes_its_own_angles_and_impact_the_other_does_not_s119():
    steps, own = _events()
    _, stiff = _events(feet={"left": side_foot(USER, STIFF)})
    left = np.array([s.foot == "left" for s in steps])
    assert left.sum() >= 3 and (~left).sum() >= 3
    for k in ("ic", "to", "ho", "ff", "step_s", "clearance", "swing_roll"):  # every time and draw as before
        np.testing.assert_array_equal(getattr(stiff, k), getattr(own, k))
    for k in ("theta_to", "theta_ic", "impact"):  # the other foot to the bit
        np.testing.assert_array_equal(getattr(stiff, k)[~left], getattr(own, k)[~left])
    # the named foot: each step's value scaled by the set / the user's own (the same jitter)
    np.testing.assert_allclose(stiff.theta_to[left] / own.theta_to[left], -15.0 / USER.toe_off_pitch_deg)
    np.testing.assert_allclose(stiff.theta_ic[left] / own.theta_ic[left], 8.0 / USER.heel_strike_pitch_deg)
    np.testing.assert_allclose(stiff.impact[left] / own.impact[left], 0.3 / USER.impact_speed_mps)
    assert side_foot(USER, {"prosthetic_toe_off_pitch_deg": None}) is None


def test_longer_stance_side_shortens_the_other_foot_s120():
    steps, named = _events(stance_time_asymmetry=0.15, affected="right", short_stance="right")
    _, s94 = _events(stance_time_asymmetry=0.15, affected="right")  # S94's way: the other foot called paretic
    np.testing.assert_array_equal(named.to, s94.to)
    _, swapped = _events(stance_time_asymmetry=0.15, affected="left")
    left = np.array([s.foot == "left" for s in steps])
    swing = named.ic - named.to
    assert swing[~left].mean() > 1.05 * swing[left].mean()  # the right foot's swing longer: the left's stance longer
    assert (swapped.ic - swapped.to)[left].mean() > 1.05 * (swapped.ic - swapped.to)[~left].mean()


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    root = tmp_path_factory.mktemp("s119")
    args = ["simulate", "--route", "stand:1, straight:4, stand:1", "--user-seed", "17681", "--rate", "20",
            "--no-noise", "--stand", "1", "--paretic-side", "right", "--stance-time-asymmetry", "0.12",
            "--longer-stance-side", "left", "--prosthetic-side", "left", "--prosthetic-toe-off-pitch", "-15",
            "--prosthetic-heel-strike-pitch", "8"]
    for f in ("left", "right"):
        assert main([*args, "--foot", f, "--out", str(root / f)]) == 0
    assert main([*args[:-8], "--foot", "left", "--out", str(root / "anat")]) == 0
    return {k: root / k for k in ("left", "right", "anat")}


def test_both_feet_record_the_foot_and_gait_pairs_them_s119(pair):
    meta = {k: json.loads((d / "meta.json").read_text()) for k, d in pair.items()}
    assert meta["left"]["user"] == meta["right"]["user"] == meta["anat"]["user"]  # the user's own, both feet
    knobs = meta["left"]["knobs"]
    assert (knobs["prosthetic_side"], knobs["prosthetic_toe_off_pitch_deg"], knobs["longer_stance_side"]) == (
        "left", -15.0, "left")
    check_clock(pair["left"], pair["right"], meta["left"], meta["right"])  # one walk: no "two different walks"
    assert (pair["left"] / "ics.csv").read_bytes() == (pair["anat"] / "ics.csv").read_bytes()
    z = {k: np.loadtxt(pair[k] / "foot_trajectory.csv", delimiter=",", skiprows=1, usecols=3) for k in ("left", "anat")}
    assert z["left"].max() < 0.8 * z["anat"].max()  # the stiff toe-off lifts the heel less


@pytest.mark.parametrize("args, match", [
    (["--prosthetic-toe-off-pitch", "-15"], "--prosthetic-toe-off-pitch sets one foot's own value: give the foot "
                                           "with --prosthetic-side left or right"),
    (["--prosthetic-side", "left"], "--prosthetic-side left names a foot with no value of its own"),
    (["--prosthetic-side", "left", "--prosthetic-heel-strike-pitch", "50"], "--prosthetic-heel-strike-pitch 50.0: "
                                                                            "give a number from 0 to 40"),
    (["--longer-stance-side", "up"], "--longer-stance-side 'up': give left or right"),
])
def test_bad_prosthetic_options_are_one_line_s119(args, match, tmp_path, capsys):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", "stand:2", "--user-seed", "1", *args, "--out", str(out)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and match in err[0] and not out.exists()
    with pytest.raises(DataError, match="prosthetic_impact_speed_mps 0: give a number from 0.05 to 2"):
        simulate_path(ROUTE, USER, prosthetic_side="right", prosthetic_impact_speed_mps=0)


def test_the_help_gives_the_ranges_the_knobs_check_s119():
    """The CLI's help (numpy-free, C14) states PROSTHETIC_FOOT_FIELDS' ranges."""
    import typer

    from pdrlearn.cli import app
    from pdrlearn.sim.user import PROSTHETIC_FOOT_FIELDS

    params = {p.name: p for p in typer.main.get_command(app).commands["simulate"].params}
    for knob, (_, (lo, hi)) in PROSTHETIC_FOOT_FIELDS.items():
        name = knob.rsplit("_", 1)[0] if not knob.endswith("_mps") else "prosthetic_impact_speed"
        text = params[name].help
        assert f"{lo:g} to {hi:g}" in text or f"{lo:g}-{hi:g}" in text, (knob, text)
