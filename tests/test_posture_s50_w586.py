"""Decision W586: a foot + lower-back track splits the time that is not walking by posture with the lower-back
unit's own posture runs (W222's, read by W418 / W428's inner waist work, no second posture code), outside the foot's
walking; the waist-only track of the same unit has the same runs."""

from __future__ import annotations

import pytest

from pdrlearn.cli.common import posture_line
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.periods import time_accounting, track_postures
from pdrlearn.track.units import keep_units
from pdrlearn.warning_lines import isolated_warnings

#: a short ward day: lying in bed, a walk, a seat, a walk (both units, simulated)
ROUTE = "lie:20, straight:5, sit:15, straight:5"


@pytest.fixture(scope="module")
def tracks():
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(17729), rate_hz=50, seed=0, scenario="route",
                      sit_start_s=3, sit_end_s=3, bounce="pendulum")
    with isolated_warnings():
        foot = get_pipeline("plasys")(s)
        waist_session = keep_units(s, ("waist",))
        waist = get_pipeline("waist-pendulum")(waist_session)
    return s, foot, waist


def test_two_unit_track_reads_the_lower_backs_posture_runs_w586(tracks):
    s, foot, waist = tracks
    runs = foot.info["trunk_postures"]
    assert runs == waist.info["postures"]  # the waist-only track's runs, no copy of the posture code
    assert {p for *_, p in runs} >= {"lying", "sitting"}
    assert track_postures(foot.info) == runs and track_postures(waist.info) == waist.info["postures"]


def test_two_unit_summary_has_the_posture_split_w586(tracks):
    s, foot, waist = tracks
    got, ref = time_accounting(foot, s, "foot"), time_accounting(waist, keep_units(s, ("waist",)), "waist")
    assert got["lying_time_s"] > 15 and got["sitting_time_s"] > 10
    assert got["lying_time_s"] == pytest.approx(ref["lying_time_s"], abs=1.0)
    assert got["sitting_time_s"] == pytest.approx(ref["sitting_time_s"], abs=1.0)
    # W222's identity on the foot's own walking time: with it the four sum to the span
    total = got["time_walking_s"] + sum(got[k] for k in ("standing_time_s", "sitting_time_s", "lying_time_s",
                                                         "unknown_time_s"))
    assert total == pytest.approx(got["time_span_s"], abs=1e-6)
    line = posture_line(got, waist_unit=True)
    assert line.startswith("posture: standing") and "W586" in line
