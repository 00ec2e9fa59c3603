"""Decision E271 (session 43, implementer I3; docs/decisions/export.md): the live clock check says once, naming the
drift it read and the fix, when it loses its lock on a waist clock drifting beyond the 3000 ppm it follows (E258); it
had gone quiet. E245's synthetic step events (``_drifting_check``: no sample data, 6 min of events)."""

from __future__ import annotations

import re

import pytest

from tests.test_runtime_clocks_s41 import _drifting_check


@pytest.mark.parametrize("ppm", [5000.0, 8000.0])
def test_a_clock_drifting_beyond_the_followed_range_is_said_once_e271(ppm):
    lines, _ = _drifting_check(ppm, 6.0)
    said = [x for x in lines if "(decision E271)" in x]
    assert len(said) == 1, lines
    read = float(re.search(r"a drift of ([+-][0-9]+) ppm", said[0]).group(1))
    assert 0.8 * ppm < read < 1.2 * ppm, said[0]
    assert f"waist_clock_drift_ppm={read:.0f}" in said[0] and "--align-units" in said[0] and "\n" not in said[0]


@pytest.mark.parametrize("ppm", [0.0, 3000.0])
def test_a_clock_the_check_follows_is_not_said_lost_e271(ppm):
    lines, _ = _drifting_check(ppm, 6.0)
    assert not any("E271" in x for x in lines), lines
