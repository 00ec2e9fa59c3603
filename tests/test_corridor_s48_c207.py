"""Decision C207 (session 48, trial T4 finding F5; not adopted): the candidate - a foot track's laps measure the
corridor themselves (the median lap less the arc round the cone); one line when that differs from ``--corridor`` by
more than 3 %, none on the right corridor, none on a lower back - and that it is off (``corridor_laps``'
``lap_margin`` None): it failed its rule on fresh users 16160-16179, so no line is given."""
from __future__ import annotations

import inspect

import pytest

from pdrlearn.track.corridor import corridor_laps
from pdrlearn.warning_lines import warning_code
from tests.test_clinical_s45_c181 import _corridor  # C181's 12 m corridor, its cone turns 1.5 m arcs

CANDIDATE = 0.03  # decision C207's candidate margin


@pytest.fixture(scope="module")
def foot():
    """C181's table as a foot track: laps track 13.5 m (12 m + the arc) between the cone turns' middles."""
    steps, turns = _corridor(5)
    return steps.assign(unit="foot"), turns


def _c207(steps, turns, corridor_m, lap_margin=None):
    return [w for w in corridor_laps(steps, turns, corridor_m, lap_margin=lap_margin)[2] if warning_code(w) == "C207"]


def test_not_adopted_no_line(foot):
    """C207 failed its rule (3 and 2 of 20 right 30 m corridors got the line at 3 % and 4 %): off."""
    assert inspect.signature(corridor_laps).parameters["lap_margin"].default is None and _c207(*foot, 12.8) == []


@pytest.mark.parametrize("declared", [12.0, 12.0 * 1.025])
def test_no_line_on_a_corridor_within_the_margin_arc_left_out(foot, declared):
    """The laps track 12.5 % over 12 m, but the corridor they measure (less the arc) is 12 m."""
    assert _c207(*foot, declared, CANDIDATE) == []


def test_a_corridor_declared_7_pct_long_gets_one_line(foot):
    """12.8 m given (6.7 % long; L518's 15 % quiet): the line names both lengths."""
    lines = _c207(*foot, 12.8, CANDIDATE)
    assert len(lines) == 1 and "corridor 12.0 m" in lines[0] and "--corridor 12.8 m" in lines[0]


def test_a_lower_back_track_is_not_judged_by_it(foot):
    steps, turns = foot
    assert _c207(steps.assign(unit="waist"), turns, 12.8, CANDIDATE) == []
