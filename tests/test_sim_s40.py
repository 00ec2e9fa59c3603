"""Decisions S92-S94 (session 40, fixer FF, trial T1 finding 5): the leading foot of step-to-step stairs, the
negative asymmetry's refusal pointing to --paretic-side, and the help saying the feet are anatomical."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import Stairs, UserProfile
from pdrlearn.sim.path import Stand, Straight, plan_footsteps
from pdrlearn.sim.route import parse_route


def test_route_takes_a_leading_foot_after_step_to_step():  # decision S92
    assert parse_route("up:5:0.17:0.28:step-to-step:left, down:5:step-to-step:RIGHT") == [
        Stairs(5, up=True, rise_m=0.17, run_m=0.28, step_to_step=True, lead="left"),
        Stairs(5, up=False, step_to_step=True, lead="right")]
    assert parse_route("up:5:step-to-step") == [Stairs(5, up=True, step_to_step=True)]


@pytest.mark.parametrize(("spec", "words"), [
    ("up:5:left", "a leading foot follows 'step-to-step'"),
    ("up:5:0.17:0.28:step-to-step:up", "'left' or 'right'"),
    ("up:5:0.17", "'up' takes N or N:RISE:RUN, then optionally ':step-to-step'"),
])
def test_bad_stair_options_name_the_forms(spec, words):  # decision S92: not "takes 1 or 3 value(s)"
    with pytest.raises(DataError, match="S92") as err:
        parse_route(spec)
    assert words in str(err.value)
    assert "1 or 3 value" not in str(err.value)


def _stair_feet(lead_up, lead_down) -> dict:
    segs = [Stand(2), Straight(3), Stairs(4, up=True, step_to_step=True, lead=lead_up), Straight(2),
            Stairs(4, up=False, step_to_step=True, lead=lead_down), Stand(2)]
    steps = plan_footsteps(segs, UserProfile.from_seed(10822), rng=np.random.default_rng(0))[0]
    return {k: "".join(s.foot[0] for s in steps if s.kind == k) for k in ("stairs_up", "stairs_down")}


@pytest.mark.parametrize(("up", "down"), [("left", "right"), ("right", "left"), ("left", "left")])
def test_the_chosen_foot_leads_every_stair(up, down):  # decision S92: "up with the good, down with the bad"
    feet = _stair_feet(up, down)
    assert feet["stairs_up"] == (up[0] + ("r" if up == "left" else "l")) * 4
    assert feet["stairs_down"] == (down[0] + ("r" if down == "left" else "l")) * 4


def test_a_lead_on_step_over_step_stairs_is_refused():  # decision S92
    with pytest.raises(DataError, match="step-to-step"):
        plan_footsteps([Stairs(3, lead="left")], UserProfile.from_seed(10823), rng=np.random.default_rng(0))


@pytest.mark.parametrize(("option", "side", "other"), [("--step-time-asymmetry", "left", "right"),
                                                       ("--step-length-asymmetry", "right", "left")])
def test_negative_asymmetry_points_to_paretic_side(tmp_path, capsys, option, side, other):  # decision S93
    assert main(["simulate", "--route", "stand:2, straight:2", "-u", "10824", option, "-0.2", "--paretic-side", side,
                 "--out", str(tmp_path / "s")]) != 0
    err = capsys.readouterr().err
    assert err.startswith("error:") and len(err.strip().splitlines()) == 1
    assert f"give --paretic-side {other} {option} 0.2 (decision S93)" in err
    assert not (tmp_path / "s").exists()


def test_help_says_the_feet_are_anatomical(capsys, monkeypatch):  # decision S94
    monkeypatch.setenv("COLUMNS", "250")
    try:
        main(["simulate", "--help"])
    except SystemExit:
        pass
    text = " ".join(w for w in capsys.readouterr().out.split() if w.strip("│╭╮╰╯─"))  # rich's box borders apart
    assert "S92" in text  # the route help names the leading foot
    # decision S119 (session 50): one foot of its own only with --prosthetic-side
    assert "the same anatomical foot's (decision S94) unless --prosthetic-side gives one foot its own (S119)" in text
    assert "--stance-time-asymmetry shortens the paretic side's (S94)" in text


def _stances(a: float) -> tuple[dict, np.ndarray]:
    from pdrlearn.sim.body import schedule

    user = UserProfile.from_seed(10826)
    steps = plan_footsteps([Stand(2), Straight(16), Stand(2)], user, rng=np.random.default_rng(1))[0]
    ev = schedule(steps, user, speed="normal", rng=np.random.default_rng(2), stand_s=2.0, rocker="smooth",
                  affected="right", stance_time_asymmetry=a)
    feet = np.array([s.foot for s in steps])
    out = {}
    for foot in ("left", "right"):
        k = np.flatnonzero(feet == foot)
        out[foot] = float(np.median(ev.to[k[2:]] - ev.ic[k[1:-1]]))  # a contact to the same foot's next toe-off
    return out, ev.ic


def test_stance_time_asymmetry_shortens_the_paretic_sides_stance_only():  # decision S94
    sym, ic0 = _stances(0.0)
    asym, ic1 = _stances(0.15)
    assert sym["left"] / sym["right"] == pytest.approx(1.0, abs=0.02)
    assert asym["left"] / asym["right"] == pytest.approx(1.15, abs=0.03)  # the other foot's about 1 + a times
    assert asym["left"] == pytest.approx(sym["left"], abs=1e-9)
    assert ic1 == pytest.approx(ic0, abs=1e-9)  # the contacts (step times) unchanged


def test_stance_time_asymmetry_range_is_one_line(tmp_path, capsys):  # decision S94
    from pdrlearn.cli.simulate import STANCE_TIME_ASYMMETRY_MAX as CLI_MAX
    from pdrlearn.sim.body import STANCE_TIME_ASYMMETRY_MAX

    assert CLI_MAX == STANCE_TIME_ASYMMETRY_MAX
    assert main(["simulate", "--route", "stand:2, straight:2", "-u", "10827", "--stance-time-asymmetry", "0.3",
                 "--out", str(tmp_path / "s")]) != 0
    err = capsys.readouterr().err
    assert err.startswith("error: --stance-time-asymmetry 0.3: give 0 (symmetric) to below 0.2")
    assert not (tmp_path / "s").exists()
