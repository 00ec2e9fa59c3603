"""Session 33, issue 8: W313 - an uncalibrated waist-pll track reading over 1.25 x the pendulum at a slow cadence
(the pendulum reading's median under 100 steps/min) says so; W289's speed judge beside it."""

from __future__ import annotations

import dataclasses

import pytest

from pdrlearn.cli import main
from pdrlearn.waist.plausibility import PLL_SLOW_CADENCE_SPM, pll_slow_excess_message


def test_w313_the_cadence_judge_separates_where_the_speed_judge_does_not():
    # long steps at a slow cadence, about 1.07 m/s: the speed judge says nothing, the cadence judge warns
    line = pll_slow_excess_message(1.37, 27.22, 19.83, 0.70, 92.0, 50, judge="cadence")
    assert line and "decision W313" in line and "92 steps/min" in line and "waist-pendulum" in line
    assert pll_slow_excess_message(1.37, 27.22, 19.83, 0.70, 92.0, 50) is None  # W289: 1.07 m/s is not slow
    # a normal cadence the uncalibrated pendulum reads slow (0.40 m at 105 steps/min, 0.70 m/s): W289 fired on these
    assert "decision W289" in pll_slow_excess_message(1.37, 27.22, 19.83, 0.40, 105.0, 50)
    assert pll_slow_excess_message(1.37, 27.22, 19.83, 0.40, 105.0, 50, judge="cadence") is None
    assert pll_slow_excess_message(1.37, 27.22, 19.83, 0.40, PLL_SLOW_CADENCE_SPM, 50, judge="cadence") is None
    assert pll_slow_excess_message(1.25, 25.0, 20.0, 0.40, 92.0, 50, judge="cadence") is None  # not over 1.25
    assert pll_slow_excess_message(1.5, 30.0, 20.0, 0.40, 92.0, 9, judge="cadence") is None  # under W99's 10 steps


def _track(tmp_path, user: int, extra: list[str], options: dict | None = None):
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    d = tmp_path / f"u{user}"
    assert main(["simulate", "--route", "stand:3, straight:16, stand:3", "--user-seed", str(user), "--out", str(d),
                 *extra]) == 0
    s = read_session(d)
    if options is None:
        return track_waist(s, pipeline="waist-pll")
    p, _ = resolve_params(s, None)  # uncalibrated: the options only
    return track_waist(s, pipeline="waist-pll", params=dataclasses.replace(p, options=options))


@pytest.mark.parametrize(("user", "extra", "fires"), [
    (6960, ["--step-length", "0.4", "--step-time", "0.65", "--bounce", "pendulum"], True),  # 0.62 m/s, 92 steps/min
    (6965, [], False),  # a healthy default walker: pll / pendulum 1.35 at 105 steps/min, the pendulum's 0.95 m/s
])
def test_w313_pll_slow_cadence_check_warns_a_slow_walker_not_a_normal_one(tmp_path, user, extra, fires):
    r = _track(tmp_path, user, extra, {"pll_slow_cadence_check": True})
    assert r.info["pll_pendulum_ratio"] > 1.25  # W289's ratio alone would judge both
    assert sum("decision W313" in w for w in r.info["warnings"]) == int(fires)
    assert not any("decision W289" in w for w in r.info["warnings"])
    # W289's speed judge warns both: the normal walker is one of the walks W290's rule (b) counted against it
    both = _track(tmp_path / "both", user, extra, {"pll_slow_check": True, "pll_slow_cadence_check": True})
    assert [("W289" in w, "W313" in w) for w in both.info["warnings"] if "pendulum model's" in w] == [(True, False)]


def test_w314_pll_slow_cadence_check_is_on_by_default(tmp_path):
    """W314: W313's rule was met (slow 32 of 32 warned, normal / fast 0 of 28, real 0), so an uncalibrated offline
    waist-pll track of a slow walker says so by default; the PARAMS.json option false turns it off."""
    from pdrlearn.track.waist import OPTION_DEFAULTS

    assert OPTION_DEFAULTS["pll_slow_cadence_check"] is True and OPTION_DEFAULTS["pll_slow_check"] is False
    slow = ["--step-length", "0.4", "--step-time", "0.65", "--bounce", "pendulum"]
    default = _track(tmp_path, 6960, slow)
    assert sum("decision W313" in w for w in default.info["warnings"]) == 1
    off = _track(tmp_path / "off", 6960, slow, {"pll_slow_cadence_check": False})
    assert not any("decision W313" in w for w in off.info["warnings"])
