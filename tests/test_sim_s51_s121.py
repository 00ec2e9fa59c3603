"""Decisions S121 (``simulate --graded-slopes``, a slope's pace), S122 (``--fatigue``), S123 (``--waist-reclip``) and
S124 (``--bounce``'s help steers lower-back studies to ``population``); session 51, trials s51t1-s51t3."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.simulate import parse_reclip
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.body import schedule
from pdrlearn.sim.path import Slope, grade_speed_ratio, graded_step, plan_footsteps
from pdrlearn.sim.route import parse_route
from tests.sim_helpers import session_digest

USER = UserProfile.from_seed(18679)
SLOPES = "stand:1, slope:4:15, slope:3:-20, stand:1"
KW = {"speed": "normal", "stand_s": 1.0}


def test_default_slope_session_is_the_pinned_digest():
    """A default slope session (noise on) is bit for bit the one before S121-S123: the digest was computed with main
    at cb25186c, before them; the options at their defaults give the same."""
    s = simulate_path(parse_route(SLOPES), USER, seed=1, stand_s=1.0, rate_hz=100)
    assert session_digest(s) == "4a2b37e459df7487425391474e22b6f8fa544afdb5222c7b2daac8fe9aeb826e"
    same = simulate_path(parse_route(SLOPES), USER, seed=1, stand_s=1.0, rate_hz=100, graded_slopes=False,
                         fatigue_pct=0.0, waist_reclip=None)
    assert session_digest(same) == session_digest(s)


def test_tobler_ratio_and_its_even_split_s121():
    assert grade_speed_ratio(0.0) == 1.0
    assert grade_speed_ratio(-0.05) == pytest.approx(math.exp(0.175))  # the fastest, 5 % downhill
    assert grade_speed_ratio(0.25) == pytest.approx(math.exp(-0.875))
    assert grade_speed_ratio(-0.25) == pytest.approx(math.exp(-3.5 * 0.15))
    f_len, f_time = graded_step(0.15)
    assert f_len * f_len == pytest.approx(grade_speed_ratio(0.15)) and f_len * f_time == pytest.approx(1.0)


def _plan(route, graded):
    return plan_footsteps(parse_route(route), USER, rng=np.random.default_rng(3), variability=0.0,
                          graded_slopes=graded)[0]


def test_graded_slopes_shorten_and_slow_the_steps_and_a_slope_takes_a_pace_s121():
    level = _plan("slope:20:0, slope:20:15, slope:20:-25", False)
    graded = _plan("slope:20:0, slope:20:15, slope:20:-25", True)

    def lengths(steps, x0, x1):
        x = np.array([st.heel[0] for st in steps if st.foot == "right"])
        d = np.diff(x)
        mid = 0.5 * (x[1:] + x[:-1])
        return d[(mid > x0 + 1) & (mid < x1 - 1)]

    for (x0, x1), g in (((20, 40), 0.15), ((40, 60), -0.25)):
        ratio = np.median(lengths(graded, x0, x1)) / np.median(lengths(graded, 0, 20))
        assert ratio == pytest.approx(graded_step(g)[0], rel=0.06)  # whole steps per segment round the length
        assert np.median(lengths(level, x0, x1)) == pytest.approx(np.median(lengths(level, 0, 20)), rel=0.06)
    times = {round(st.time_factor, 9) for st in graded if st.kind == "walk"}
    assert times == {1.0, round(graded_step(0.15)[1], 9), round(graded_step(-0.25)[1], 9)}
    assert {st.time_factor for st in level} == {1.0}
    seg = parse_route("slope:50:20:slow")[0]  # the trial's refused item (S88's grammar, S121)
    assert seg == Slope(50.0, 0.2, gait="normal", pace="slow")
    assert parse_route("slope:50:20:short:fast")[0] == Slope(50.0, 0.2, gait="short", pace="fast")
    slow = plan_footsteps([seg], USER, rng=np.random.default_rng(3), variability=0.0)[0]
    assert {st.pace for st in slow if st.kind == "walk"} == {"slow"}
    ev_slow = schedule(slow, USER, rng=np.random.default_rng(1), variability=0.0, speed="normal", stand_s=1.0)
    normal = plan_footsteps([Slope(50.0, 0.2)], USER, rng=np.random.default_rng(3), variability=0.0)[0]
    ev_norm = schedule(normal, USER, rng=np.random.default_rng(1), variability=0.0, speed="normal", stand_s=1.0)
    assert np.median(ev_slow.step_s) > np.median(ev_norm.step_s)
    with pytest.raises(DataError, match="'run' must be a gait .* or a pace"):
        parse_route("slope:50:20:run")


def test_fatigue_slows_the_cadence_linearly_without_a_step_s122():
    steps = _plan("straight:30", False)
    base = schedule(steps, USER, rng=np.random.default_rng(1), variability=1.0, **KW)
    tired = schedule(steps, USER, rng=np.random.default_rng(1), variability=1.0, fatigue_pct=20.0, **KW)
    n = len(steps)
    expected = 1.0 / (1.0 - 0.2 * np.arange(n) / (n - 1))
    np.testing.assert_allclose(tired.step_s / base.step_s, expected, rtol=1e-12)
    assert tired.step_s[0] == base.step_s[0]
    same = schedule(steps, USER, rng=np.random.default_rng(1), variability=1.0, fatigue_pct=0.0, **KW)
    np.testing.assert_array_equal(same.ic, base.ic)
    with pytest.raises(DataError, match="fatigue_pct=60"):
        simulate_path(parse_route("straight:2"), USER, fatigue_pct=60)


def _stand(**knobs):
    return simulate_path(parse_route("stand:8"), USER, seed=1, noise=False, stand_s=4.0, **knobs)


def test_waist_reclip_turns_the_unit_at_once_and_meta_says_when_s123():
    s = _stand(waist_reclip=(8.0, (0.0, 20.0, 0.0)))
    plain = _stand()
    acc, gyr = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    before, after = acc.t < 7.9, acc.t > 8.6
    a0, a1 = acc.values[before].mean(axis=0), acc.values[after].mean(axis=0)
    assert np.degrees(np.arccos(a0 @ a1 / np.linalg.norm(a0) / np.linalg.norm(a1))) == pytest.approx(20.0, abs=0.5)
    turn = np.trapezoid(np.linalg.norm(gyr.values, axis=1), gyr.t)
    assert np.degrees(turn) == pytest.approx(20.0, abs=0.5)  # the gyroscope sees the re-clip, within 0.5 s
    moving = gyr.t[np.linalg.norm(gyr.values, axis=1) > 0.1]
    assert moving.min() >= 7.99 and moving.max() <= 8.51
    np.testing.assert_array_equal(acc.values[before], plain.streams["wAccelerometer"].values[before])
    np.testing.assert_array_equal(s.streams["fAccelerometer"].values, plain.streams["fAccelerometer"].values)
    assert json.loads(json.dumps(s.meta["knobs"]["waist_reclip"])) == [8.0, [0.0, 20.0, 0.0]]
    assert "waist_reclip" not in plain.meta["knobs"]
    with pytest.raises(DataError, match="cannot be combined"):
        _stand(waist_reclip=(8.0, (0.0, 20.0, 0.0)), waist_mount_end_deg=(0.0, 5.0, 0.0))
    with pytest.raises(DataError, match="does not lie inside the recording"):
        _stand(waist_reclip=(80.0, (0.0, 20.0, 0.0)))


def test_cli_parses_and_refuses_in_one_line_and_the_help_steers_to_population_s124(tmp_path, capsys):
    assert parse_reclip("1800:z:90") == (1800.0, (0.0, 0.0, 90.0))
    for args, match in ((["--waist-reclip", "soon:z:90"], "give T:AXIS:DEG"),
                        (["--waist-reclip", "10:q:90"], "is not AXIS:DEG"),
                        (["--waist-reclip", "10:z:9", "--waist-mount-drift", "y:5"], "cannot be combined"),
                        (["--fatigue", "60"], "0 to 50")):
        out = tmp_path / "x"
        code = main(["simulate", "--user-seed", "1", "--route", "straight:2", "--out", str(out), *args])
        err = capsys.readouterr().err
        assert code != 0 and match in err and "Traceback" not in err and not out.exists()
    main(["simulate", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "A lower-back (waist) study should use population" in text.replace("│ ", "").replace(" │", "")
